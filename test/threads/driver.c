/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Thread safety of the libraries: every work item is computed once serially and then
 * again by several POSIX threads at once, in several rounds (reversed order every
 * other round, so that threads run different kinds of work at the same time); every
 * result must be bit-identical to the serial one (memcmp of the whole record). The
 * libraries keep no state, so a difference is a data race (a static variable, such as
 * gfortran's hidden length of a deferred-length character result, or a local array
 * moved to static storage) or uninitialised memory.
 *
 * The work mixes successes and failures (different statuses and messages, of
 * different lengths):
 *  - core, C: the Lambert W functions, restitution and its relatives, status texts,
 *    hcimpact_impact, the velocity at a depth, the time law (some contacts invalid),
 *    hcimpact_impact_law with a law given as C callbacks (some failing: NaN force);
 *  - core, Fortran (cases_core.f90): status_message and quadrature_status_message;
 *  - CVODE component (HCIMPACT_THREADS_CVODE): hcimpact_simulate from C, good and bad
 *    input and CVODE failures; `simulate` from Fortran (cases_cvode.f90) with the power
 *    law and with user laws, compared with its messages; systems of bodies through
 *    hcimpact_chain_simulate_monitored (cradles by CVODE and by the closed forms, a
 *    ball pair on a floor, samples; each run with its own monitor, whose calls are
 *    part of the result) and its failures (a cluster for the method exact, a negative
 *    gap, NaN, too few steps, rtol out of range, a monitor that stops the run), with
 *    their messages;
 *  - LAPACK component (HCIMPACT_THREADS_LAPACK): the calibration fits from C, on good
 *    data and on data that fail (NaN, non-positive, NULL, underdetermined).
 * Threads are POSIX threads, not OpenMP, so that ThreadSanitizer sees every
 * synchronisation (.ci/tsan runs this program in a -fsanitize=thread build).
 *
 * Usage: threads [threads=4] [rounds=3]. Exit status 0 on success, 1 on a mismatch.
 */
#define _POSIX_C_SOURCE 200112L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hcimpact.h"
#ifdef HCIMPACT_THREADS_CVODE
#include "hcimpact_cvode.h"
#endif
#ifdef HCIMPACT_THREADS_LAPACK
#include "hcimpact_lapack.h"
#endif

#define N_ITEMS 4000    /* every item: the scalar functions and the texts */
#define N_IMPACT 400    /* items below: closed-form impacts, velocity, time law */
#define N_LAW 200       /* items below: an impact with a C callback law */
#define N_CVODE 96      /* items below: hcimpact_simulate and Fortran simulate */
#define N_FITS 72       /* items below: a calibration fit */
#define N_CHAIN 48      /* items below: a system of bodies */
#define N_BODIES 5
#define N_CHAIN_CONTACTS 8
#define N_CHAIN_SAMPLES 3
#define N_TIMES 4
#define N_DATA 8        /* points of a fit */
#define TEXT 512

/* everything one item produces */
typedef struct {
  double scalar[9];
  const char *status_text;
  char fortran_text[TEXT];
  int impact_status, depth_status, time_law_status;
  hcimpact_outcome impact;
  double depth_velocity, x[N_TIMES], v[N_TIMES], f[N_TIMES];
  int law_status;
  hcimpact_outcome law;
  int simulate_status;
  hcimpact_outcome simulate;
  int fortran_simulate_status;
  double fortran_simulate[10];
  char fortran_simulate_message[TEXT];
  int fit_status;
  double fit[4 + 3 * N_DATA];
#ifdef HCIMPACT_THREADS_CVODE
  int chain_status, chain_polls;
  hcimpact_chain_result chain;
  double chain_positions[N_BODIES], chain_velocities[N_BODIES];
  hcimpact_chain_contact chain_contacts[N_CHAIN_CONTACTS];
  double chain_sampled[N_CHAIN_SAMPLES * (3 * N_BODIES + 1)];
  char chain_message[TEXT];
#endif
} result_t;

/* the Fortran cases (cases_core.f90, cases_cvode.f90) */
void thread_core_texts(int i, char *text, int capacity);
void thread_cvode_case(int i, int *status, double values[10], char *message, int capacity);

static double scalar_input(int i)
{
  /* spread over many regions of every function: tiny, near the branch point, huge */
  double u = (double)i / N_ITEMS;
  return pow(10.0, -20.0 + 40.0 * u) * (i % 3 == 0 ? 1.0 : 0.37) - (i % 7 == 0 ? 0.36 : 0.0);
}

static hcimpact_contact valid_contact(int i)
{
  hcimpact_contact c;
  c.mass = 0.01 + 0.1 * (i % 5);
  c.stiffness = 1.7135e10 * (1.0 + (i % 3));
  c.exponent = 1.0 + 0.25 * (i % 4);
  c.damping = (i % 6 == 0) ? 0.0 : 0.05 * (i % 11);
  c.velocity = 0.1 + 0.5 * (i % 13);
  return c;
}

/* a valid contact or, for some i, one with a bad field */
static hcimpact_contact contact_input(int i)
{
  hcimpact_contact c = valid_contact(i);
  if (i % 19 == 18) c.exponent = NAN;
  else if (i % 17 == 16) c.mass = -1.0;
  return c;
}

/* A power law f = k x^p given to the library as C callbacks; the force turns NaN
   beyond `limit` (a law that fails in the middle of the quadratures). */
typedef struct {
  double k, p, limit;
} power_callbacks;

static double law_force(double x, void *data)
{
  const power_callbacks *law = data;
  return x > law->limit ? NAN : law->k * pow(x, law->p);
}

static double law_potential(double x, void *data)
{
  const power_callbacks *law = data;
  return law->k * pow(x, law->p + 1.0) / (law->p + 1.0);
}

static double law_derivative(double x, void *data)
{
  const power_callbacks *law = data;
  return x > law->limit ? NAN : law->k * law->p * pow(x, law->p - 1.0);
}

#ifdef HCIMPACT_THREADS_CVODE
static void simulate_item(int i, result_t *r)
{
  hcimpact_contact c = valid_contact(i);
  double rtol = 1e-5;
  switch (i % 7) {
  case 1: rtol = 0.0; break;           /* HCIMPACT_ERR_DOMAIN */
  case 2: rtol = 1e-20; break;         /* CVODE gives up: HCIMPACT_ERR_SOLVER */
  case 3: c.damping = 1e300; break;    /* b V too large: HCIMPACT_ERR_DOMAIN */
  case 4: c.velocity = -1.0; break;    /* HCIMPACT_ERR_VELOCITY */
  case 5: c.mass = NAN; break;         /* HCIMPACT_ERR_NOT_FINITE */
  default: break;
  }
  r->simulate_status = hcimpact_simulate(&c, rtol, &r->simulate);
  thread_cvode_case(i, &r->fortran_simulate_status, r->fortran_simulate,
                    r->fortran_simulate_message, TEXT);
}
#endif

#ifdef HCIMPACT_THREADS_CVODE
/* A system of five steel balls (0.1 kg, Hertz), case by case (i % 8): a touching
   cradle (a cluster: CVODE, BDF), the same with gaps and damping (the closed forms),
   a pair falling onto a floor (Adams, samples), and failures, each with its message:
   the method exact meeting a cluster, a negative gap, a NaN mass, too few steps, an
   rtol out of range. */
/* a chain's monitor: counts its calls, stops at call `stop_at` (0: never) */
typedef struct {
  int calls, stop_at;
} chain_watch;

static int chain_poll(void *data, double time, int64_t steps, int64_t events)
{
  chain_watch *w = (chain_watch *)data;
  (void)time;
  (void)steps;
  (void)events;
  ++w->calls;
  return w->stop_at > 0 && w->calls >= w->stop_at;
}

/* item i of the systems: case 0 of every second round of eight is stopped by its
   monitor at its second call */
static int chain_stopped(int i)
{
  return i % 8 == 0 && (i / 8) % 2 == 1;
}

static void chain_item(int i, result_t *r)
{
  double m[N_BODIES], v[N_BODIES], gaps[N_BODIES - 1];
  hcimpact_chain_law laws[N_BODIES - 1];
  hcimpact_chain_wall floor = {1.7135e10, 1.5, 0.05, 1e-3};
  hcimpact_chain_options o;
  double times[N_CHAIN_SAMPLES] = {1e-4, 2e-3, 8e-3};
  hcimpact_chain_samples samples;
  const hcimpact_chain_wall *left = NULL;
  double gravity = 0.0;
  chain_watch watch = {0, 0};
  hcimpact_chain_monitor monitor = {chain_poll, NULL};
  int n = N_BODIES, j;
  memset(&o, 0, sizeof o);
  monitor.data = &watch;
  if (chain_stopped(i)) watch.stop_at = 2;
  for (j = 0; j < N_BODIES; ++j) {
    m[j] = 0.1;
    v[j] = 0.0;
  }
  v[0] = 0.2 + 0.1 * (i % 5);
  for (j = 0; j < N_BODIES - 1; ++j) {
    gaps[j] = 0.0;
    laws[j].stiffness = 1.7135e10 / sqrt(2.0);
    laws[j].exponent = 1.5;
    laws[j].damping = 0.0;
  }
  o.rtol = 1e-8;
  samples.count = 0;
  samples.times = times;
  samples.positions = r->chain_sampled;
  samples.velocities = r->chain_sampled + N_CHAIN_SAMPLES * N_BODIES;
  samples.forces = r->chain_sampled + 2 * N_CHAIN_SAMPLES * N_BODIES;
  switch (i % 8) {
  case 1: /* isolated contacts, damped */
    for (j = 0; j < N_BODIES - 1; ++j) {
      gaps[j] = 1e-4 * (j + 1);
      laws[j].damping = 0.05;
    }
    break;
  case 2: /* a pair dropped onto a floor, Adams, sampled */
    n = 2;
    v[0] = v[1] = -0.5;
    left = &floor;
    gravity = -9.81;
    o.t_end = 1e-2;
    o.integrator = HCIMPACT_CHAIN_ADAMS;
    samples.count = N_CHAIN_SAMPLES;
    samples.forces = NULL;
    break;
  case 3: /* a cluster for the method exact: HCIMPACT_ERR_DOMAIN, its time */
    o.method = HCIMPACT_CHAIN_EXACT;
    gaps[0] = 1e-3 * (1 + i % 3);
    break;
  case 4: /* HCIMPACT_ERR_DOMAIN: a negative gap */
    gaps[i % (N_BODIES - 1)] = -1e-6;
    break;
  case 5: /* HCIMPACT_ERR_NOT_FINITE */
    m[i % N_BODIES] = NAN;
    break;
  case 6: /* HCIMPACT_ERR_NO_CONVERGENCE: too few steps */
    o.max_steps = 3 + i % 5;
    break;
  case 7: /* HCIMPACT_ERR_DOMAIN: rtol out of range */
    o.rtol = 0.5;
    break;
  default:
    break;
  }
  r->chain_status = hcimpact_chain_simulate_monitored(
      n, m, v, gaps, laws, left, NULL, gravity, &o, &r->chain, r->chain_positions,
      r->chain_velocities, N_CHAIN_CONTACTS, r->chain_contacts, &samples, &monitor,
      r->chain_message, TEXT);
  r->chain_polls = watch.calls;
}
#endif

#ifdef HCIMPACT_THREADS_LAPACK
static void fit_item(int i, result_t *r)
{
  double v[N_DATA], e[N_DATA], x[N_DATA], force[N_DATA], t[N_DATA], fm[N_DATA];
  const double mass = 0.1, c = 1.7135e10, n = 1.5, b = 0.05 + 0.001 * i;
  const double hertz_time = 2.9432751843247047; /* t_c V / x_max at b = 0, n = 3/2 */
  double *out = r->fit;
  int j;
  for (j = 0; j < N_DATA; ++j) {
    double x_max;
    v[j] = 0.5 + 0.5 * j;
    e[j] = hcimpact_restitution(b * v[j]) * (1.0 + 1e-3 * sin(i + j));
    x[j] = 2.0e-6 * pow(50.0, j / (N_DATA - 1.0));
    force[j] = c * pow(x[j], n) * (1.0 + 1e-2 * cos(i * j));
    x_max = pow((n + 1.0) * mass * v[j] * v[j] / (2.0 * c), 1.0 / (n + 1.0));
    t[j] = hertz_time * x_max / v[j] * (1.0 + 1e-3 * sin(i - j));
    fm[j] = c * pow(x_max, n) * (1.0 + 1e-3 * cos(i + 2 * j));
  }
  switch (i % 8) {
  case 0:
    r->fit_status = hcimpact_fit_damping(N_DATA, v, e, NULL, 0, &out[0], &out[1], &out[4]);
    break;
  case 1:
    e[i % N_DATA] = NAN;  /* HCIMPACT_ERR_NOT_FINITE */
    r->fit_status = hcimpact_fit_damping(N_DATA, v, e, NULL, 0, &out[0], &out[1], &out[4]);
    break;
  case 2:
    r->fit_status = hcimpact_fit_static(N_DATA, x, force, NULL, 0, &out[0], NULL, &out[4]);
    break;
  case 3:
    force[i % N_DATA] = -1.0;  /* HCIMPACT_ERR_DOMAIN */
    r->fit_status = hcimpact_fit_static(N_DATA, x, force, NULL, 0, &out[0], NULL, &out[4]);
    break;
  case 4:
    r->fit_status = hcimpact_fit_damping_linear(N_DATA, v, e, NULL, 0, &out[0], &out[1],
                                                &out[4]);
    break;
  case 5:
    r->fit_status = hcimpact_fit_damping(N_DATA, NULL, e, NULL, 0, &out[0], NULL, NULL);
    break;
  case 6:
    /* contact times at one speed: HCIMPACT_ERR_UNDERDETERMINED */
    for (j = 0; j < N_DATA; ++j) v[j] = 2.0;
    r->fit_status = hcimpact_fit_elastic(N_DATA, mass, 0.0, v, t, NULL, NULL, NULL, 0, NULL,
                                         &out[0], NULL, &out[4]);
    break;
  default:
    /* the nonlinear impact fit (quadratures at every step): a few only */
    if (i < 24) {
      r->fit_status = hcimpact_fit_elastic(N_DATA, mass, 0.0, v, t, fm, NULL, NULL, 0, NULL,
                                           &out[0], NULL, &out[4]);
    } else {
      r->fit_status = hcimpact_fit_damping(1, v, e, NULL, 0, &out[0], NULL, NULL);
    }
    break;
  }
}
#endif

static void compute(int i, result_t *r)
{
  double z = scalar_input(i);
  memset(r, 0, sizeof *r);
  r->scalar[0] = hcimpact_lambert_w0(z);
  r->scalar[1] = hcimpact_lambert_wm1(-fabs(z) * 1e-3);
  r->scalar[2] = hcimpact_lambert_w0p1(z);
  r->scalar[3] = hcimpact_lambert_wm1p1(z);
  r->scalar[4] = hcimpact_restitution(z);
  r->scalar[5] = hcimpact_restitution_inverse(1.0 / (1.0 + fabs(z)));
  r->scalar[6] = hcimpact_restitution_derivative(z);
  r->scalar[7] = hcimpact_one_minus_restitution(z);
  r->scalar[8] = hcimpact_u_minus_log1p(z);
  r->status_text = hcimpact_status_message(i % 20 - 2);
  thread_core_texts(i, r->fortran_text, TEXT);
  if (i < N_IMPACT) {
    hcimpact_contact c = contact_input(i);
    double t[N_TIMES];
    int j;
    r->impact_status = hcimpact_impact(&c, &r->impact);
    r->depth_status = hcimpact_velocity_at_depth(&c, 0.5 * r->impact.max_compression,
                                                 1 + i % 2, &r->depth_velocity);
    for (j = 0; j < N_TIMES; ++j) t[j] = r->impact.contact_time * (j + 0.5) / N_TIMES;
    if (r->impact_status != HCIMPACT_OK) t[0] = t[1] = t[2] = t[3] = 0.0;
    r->time_law_status = hcimpact_time_law(&c, N_TIMES, t, r->x, r->v, r->f);
  }
  if (i < N_LAW) {
    /* limits: far beyond the maximum compression (success) or inside it (failure) */
    power_callbacks p = {1.0e9 * (1 + i % 3), 1.0 + 0.5 * (i % 3), i % 4 == 3 ? 1e-6 : 1.0};
    hcimpact_elastic_law law = {law_force, law_potential, law_derivative, NULL};
    law.data = &p;
    r->law_status = hcimpact_impact_law(&law, 0.05 + 0.01 * (i % 7), 0.02 * (i % 5),
                                        0.2 + 0.3 * (i % 11), &r->law);
  }
#ifdef HCIMPACT_THREADS_CVODE
  if (i < N_CVODE) simulate_item(i, r);
  if (i < N_CHAIN) chain_item(i, r);
#endif
#ifdef HCIMPACT_THREADS_LAPACK
  if (i < N_FITS) fit_item(i, r);
#endif
}

/* the work queue of one round: items handed out under a mutex, in chunks */
typedef struct {
  pthread_mutex_t lock;
  int next, reversed;
  result_t *results;
} queue_t;

#define CHUNK 7

static void *worker(void *arg)
{
  queue_t *q = arg;
  for (;;) {
    int first, i;
    pthread_mutex_lock(&q->lock);
    first = q->next;
    q->next += CHUNK;
    pthread_mutex_unlock(&q->lock);
    if (first >= N_ITEMS) break;
    for (i = first; i < first + CHUNK && i < N_ITEMS; ++i) {
      int j = q->reversed ? N_ITEMS - 1 - i : i;
      compute(j, &q->results[j]);
    }
  }
  return NULL;
}

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int main(int argc, char **argv)
{
  int threads = argc > 1 ? atoi(argv[1]) : 4;
  int rounds = argc > 2 ? atoi(argv[2]) : 3;
  result_t *serial = calloc(N_ITEMS, sizeof *serial);
  result_t *parallel = calloc(N_ITEMS, sizeof *parallel);
  pthread_t *ids = calloc(threads > 0 ? threads : 1, sizeof *ids);
  int i, round, mismatches = 0, failures = 0;
  double t0, t_serial, t_parallel = 0.0;

  if (serial == NULL || parallel == NULL || ids == NULL || threads < 1 || rounds < 1) {
    fprintf(stderr, "usage: threads [threads >= 1] [rounds >= 1]\n");
    return 2;
  }
  t0 = now();
  for (i = 0; i < N_ITEMS; ++i) compute(i, &serial[i]);
  t_serial = now() - t0;

  for (round = 0; round < rounds; ++round) {
    queue_t q;
    memset(parallel, 0xff, N_ITEMS * sizeof *parallel);
    pthread_mutex_init(&q.lock, NULL);
    q.next = 0;
    q.reversed = round % 2;
    q.results = parallel;
    t0 = now();
    for (i = 0; i < threads; ++i) {
      if (pthread_create(&ids[i], NULL, worker, &q) != 0) {
        fprintf(stderr, "pthread_create failed\n");
        return 2;
      }
    }
    for (i = 0; i < threads; ++i) pthread_join(ids[i], NULL);
    t_parallel += now() - t0;
    pthread_mutex_destroy(&q.lock);
    for (i = 0; i < N_ITEMS; ++i) {
      if (memcmp(&serial[i], &parallel[i], sizeof serial[i]) != 0) {
        if (mismatches < 10) {
          printf("MISMATCH round %d, item %d\n", round, i);
          if (strcmp(serial[i].fortran_simulate_message,
                     parallel[i].fortran_simulate_message) != 0) {
            printf("  serial message:   '%s'\n  parallel message: '%s'\n",
                   serial[i].fortran_simulate_message, parallel[i].fortran_simulate_message);
          }
#ifdef HCIMPACT_THREADS_CVODE
          if (strcmp(serial[i].chain_message, parallel[i].chain_message) != 0) {
            printf("  serial chain message:   '%s'\n  parallel chain message: '%s'\n",
                   serial[i].chain_message, parallel[i].chain_message);
          }
#endif
        }
        ++mismatches;
      }
    }
  }

  /* the serial run did what the mix promises: successes and failures of each kind */
  for (i = 0; i < N_ITEMS; ++i) {
    int ok = 1;
    if (i < N_IMPACT && i % 19 != 18 && i % 17 == 16 && serial[i].impact_status != HCIMPACT_ERR_MASS)
      ok = 0;
    if (i < N_IMPACT && i % 19 == 18 && serial[i].impact_status != HCIMPACT_ERR_NOT_FINITE) ok = 0;
    if (i < N_LAW && i % 4 == 3 && serial[i].law_status != HCIMPACT_ERR_ELASTIC_LAW) ok = 0;
    if (i < N_LAW && i % 4 != 3 && serial[i].law_status != HCIMPACT_OK) ok = 0;
#ifdef HCIMPACT_THREADS_CVODE
    if (i < N_CVODE && i % 7 == 0 && serial[i].simulate_status != HCIMPACT_OK) ok = 0;
    if (i < N_CVODE && i % 7 == 4 && serial[i].simulate_status != HCIMPACT_ERR_VELOCITY) ok = 0;
    if (i < N_CVODE && i % 7 == 2 && serial[i].simulate_status != HCIMPACT_ERR_SOLVER) ok = 0;
    if (i < N_CVODE && serial[i].fortran_simulate_message[0] == '\0') ok = 0;
    if (i < N_CHAIN) {
      static const int expected[8] = {HCIMPACT_OK, HCIMPACT_OK, HCIMPACT_OK,
                                      HCIMPACT_ERR_DOMAIN, HCIMPACT_ERR_DOMAIN,
                                      HCIMPACT_ERR_NOT_FINITE, HCIMPACT_ERR_NO_CONVERGENCE,
                                      HCIMPACT_ERR_DOMAIN};
      if (serial[i].chain_status
          != (chain_stopped(i) ? HCIMPACT_ERR_NO_CONVERGENCE : expected[i % 8]))
        ok = 0;
      if (chain_stopped(i) && serial[i].chain_polls != 2) ok = 0;
      if (i % 8 == 0 && !chain_stopped(i) && serial[i].chain.integrated_contacts == 0) ok = 0;
      if (i % 8 == 1 && serial[i].chain.closed_form_contacts == 0) ok = 0;
      if (serial[i].chain_message[0] == '\0') ok = 0;
    }
#endif
#ifdef HCIMPACT_THREADS_LAPACK
    if (i < N_FITS && i % 8 == 0 && serial[i].fit_status != HCIMPACT_OK) ok = 0;
    if (i < N_FITS && i % 8 == 1 && serial[i].fit_status != HCIMPACT_ERR_NOT_FINITE) ok = 0;
    if (i < N_FITS && i % 8 == 5 && serial[i].fit_status != HCIMPACT_ERR_NULL) ok = 0;
#endif
    if (!ok) {
      if (failures < 10) printf("UNEXPECTED serial result, item %d\n", i);
#ifdef HCIMPACT_THREADS_CVODE
      if (failures < 10 && i < N_CHAIN)
        printf("  system: status %d, %s\n", serial[i].chain_status, serial[i].chain_message);
#endif
      ++failures;
    }
  }

  printf("%d items (%d impacts, %d callback laws", N_ITEMS, N_IMPACT, N_LAW);
#ifdef HCIMPACT_THREADS_CVODE
  printf(", %d CVODE runs from C and %d from Fortran, %d systems", N_CVODE, N_CVODE,
         N_CHAIN);
#endif
#ifdef HCIMPACT_THREADS_LAPACK
  printf(", %d fits", N_FITS);
#endif
  printf("), %d threads x %d rounds: %d mismatches against the serial results\n", threads,
         rounds, mismatches);
  printf("serial %.3f s, parallel %.3f s per round\n", t_serial, t_parallel / rounds);
  free(serial);
  free(parallel);
  free(ids);
  return (mismatches == 0 && failures == 0) ? 0 : 1;
}
