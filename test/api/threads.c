/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Thread safety of the C interface: the same inputs are evaluated once serially and
 * then by several OpenMP threads at once (each input by whichever thread gets it, in
 * several rounds, with threads calling different functions at the same time); every
 * result must be bit-identical to the serial one. The library keeps no state, so
 * any difference would be a data race (e.g. a local array that gfortran moved to
 * static storage) or uninitialised memory.
 *
 * Usage: threads [threads=4] [rounds=3]. Exit status 0 on success, 1 on a mismatch.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "hcimpact.h"

#define N_SCALAR 4000
#define N_IMPACT 400
#define N_TIMES 4

/* everything one input produces */
typedef struct {
  double w0, wm1, w0p1, wm1p1, k, beta, dk, one_minus_k, h;
  int impact_status, depth_status, law_status;
  hcimpact_outcome outcome;
  double depth_velocity;
  double x[N_TIMES], v[N_TIMES], f[N_TIMES];
  const char *message;
} result_t;

static double scalar_input(int i)
{
  /* spread over many regions of every function: tiny, near the branch point, huge */
  double u = (double)i / N_SCALAR;
  return pow(10.0, -20.0 + 40.0 * u) * (i % 3 == 0 ? 1.0 : 0.37) - (i % 7 == 0 ? 0.36 : 0.0);
}

static hcimpact_contact contact_input(int i)
{
  hcimpact_contact c;
  c.mass = 0.01 + 0.1 * (i % 5);
  c.stiffness = 1.7135e10 * (1.0 + (i % 3));
  c.exponent = 1.0 + 0.25 * (i % 4);
  c.damping = (i % 6 == 0) ? 0.0 : 0.05 * (i % 11);
  c.velocity = 0.1 + 0.5 * (i % 13);
  if (i % 17 == 16) c.mass = -1.0; /* some errors too */
  return c;
}

static void compute(int i, result_t *r)
{
  double z = scalar_input(i);
  memset(r, 0, sizeof *r);
  r->w0 = hcimpact_lambert_w0(z);
  r->wm1 = hcimpact_lambert_wm1(-fabs(z) * 1e-3);
  r->w0p1 = hcimpact_lambert_w0p1(z);
  r->wm1p1 = hcimpact_lambert_wm1p1(z);
  r->k = hcimpact_restitution(z);
  r->beta = hcimpact_restitution_inverse(1.0 / (1.0 + fabs(z)));
  r->dk = hcimpact_restitution_derivative(z);
  r->one_minus_k = hcimpact_one_minus_restitution(z);
  r->h = hcimpact_u_minus_log1p(z);
  r->message = hcimpact_status_message(i % 20);
  if (i < N_IMPACT) {
    hcimpact_contact c = contact_input(i);
    double t[N_TIMES];
    int j;
    r->impact_status = hcimpact_impact(&c, &r->outcome);
    r->depth_status = hcimpact_velocity_at_depth(&c, 0.5 * r->outcome.max_compression,
                                                 1 + i % 2, &r->depth_velocity);
    for (j = 0; j < N_TIMES; ++j) t[j] = r->outcome.contact_time * (j + 0.5) / N_TIMES;
    if (r->impact_status != HCIMPACT_OK) t[0] = t[1] = t[2] = t[3] = 0.0;
    r->law_status = hcimpact_time_law(&c, N_TIMES, t, r->x, r->v, r->f);
  }
}

int main(int argc, char **argv)
{
  int threads = argc > 1 ? atoi(argv[1]) : 4;
  int rounds = argc > 2 ? atoi(argv[2]) : 3;
  result_t *serial = calloc(N_SCALAR, sizeof *serial);
  result_t *parallel = calloc(N_SCALAR, sizeof *parallel);
  int i, round, mismatches = 0;
  double t0, t_serial, t_parallel = 0.0;

  if (serial == NULL || parallel == NULL) return 1;
  t0 = omp_get_wtime();
  for (i = 0; i < N_SCALAR; ++i) compute(i, &serial[i]);
  t_serial = omp_get_wtime() - t0;

  omp_set_num_threads(threads);
  for (round = 0; round < rounds; ++round) {
    memset(parallel, 0xff, N_SCALAR * sizeof *parallel);
    t0 = omp_get_wtime();
    /* dynamic schedule, reversed in odd rounds: the impacts (slow) and the scalar
       functions (fast) run at the same time on different threads */
#pragma omp parallel for schedule(dynamic, 7)
    for (i = 0; i < N_SCALAR; ++i) {
      int j = (round % 2) ? N_SCALAR - 1 - i : i;
      compute(j, &parallel[j]);
    }
    t_parallel += omp_get_wtime() - t0;
    for (i = 0; i < N_SCALAR; ++i) {
      if (memcmp(&serial[i], &parallel[i], sizeof serial[i]) != 0) {
        if (mismatches < 10) printf("MISMATCH round %d, input %d\n", round, i);
        ++mismatches;
      }
    }
  }
  printf("%d inputs (%d impacts with velocity at a depth and a %d-point time law), "
         "%d threads x %d rounds: %d mismatches against the serial results\n",
         N_SCALAR, N_IMPACT, N_TIMES, threads, rounds, mismatches);
  printf("serial %.3f s, parallel %.3f s per round (max threads available: %d)\n", t_serial,
         t_parallel / rounds, omp_get_num_procs());
  free(serial);
  free(parallel);
  return mismatches == 0 ? 0 : 1;
}
