/* SPDX-License-Identifier: Apache-2.0 */
/*
 * A Newton's cradle of five steel balls computed by the library through the C
 * interface, hcimpact_chain_simulate (include/hcimpact_cvode.h, doc/c-api.md): the first
 * ball strikes the other four at 1 m/s, once with the four touching and once with gaps
 * of 0.1 mm between all five. With gaps every contact is isolated and computed by the
 * closed forms of one impact; with the balls touching the contacts overlap and the
 * cluster is integrated by CVODE. The program prints the velocities after the last
 * contact and the list of contacts, and checks the balances: momentum to rounding,
 * energy (no damping) to the solver's tolerance, and that the touching balls do not end
 * at (0, 0, 0, 0, V) as instantaneous binary collisions would have them.
 *
 * Memory is the caller's: the arrays below are all there is (doc/c-api.md).
 * Build against an installed hcimpact with the CVODE component:
 *   cc $(pkg-config --cflags hcimpact-cvode) main.c $(pkg-config --libs hcimpact-cvode) -o cradle
 */
#include <math.h>
#include <stdio.h>

#include "hcimpact_cvode.h"

#define N 5
#define CAPACITY 64

/* two steel balls of 14.52 mm radius: the ball-on-plate constant over sqrt(2) */
static const double ball_mass = 0.1, pair_stiffness = 1.7135e10 / 1.4142135623730951;

static int run(const char *title, double gap)
{
  double masses[N], velocities[N], gaps[N - 1], positions[N], after[N];
  hcimpact_chain_law laws[N - 1];
  hcimpact_chain_options options = {0}; /* zeros: the defaults */
  hcimpact_chain_result result;
  hcimpact_chain_contact contacts[CAPACITY];
  char message[256];
  double p0 = 0.0, p1 = 0.0;
  int i, status, failed = 0;

  for (i = 0; i < N; ++i) {
    masses[i] = ball_mass;
    velocities[i] = i == 0 ? 1.0 : 0.0;
  }
  for (i = 0; i < N - 1; ++i) {
    gaps[i] = gap;
    laws[i].stiffness = pair_stiffness;
    laws[i].exponent = 1.5;
    laws[i].damping = 0.0;
  }
  options.rtol = 1e-10;
  status = hcimpact_chain_simulate(N, masses, velocities, gaps, laws, NULL, NULL, 0.0, &options,
                                   &result, positions, after, CAPACITY, contacts, NULL, message,
                                   sizeof message);
  if (status != HCIMPACT_OK) {
    fprintf(stderr, "%s: %s (%s)\n", title, hcimpact_status_message(status), message);
    return 1;
  }
  printf("%s\n  velocities after (m/s):", title);
  for (i = 0; i < N; ++i) printf(" %.6f", after[i]);
  printf("\n  %lld contacts (%lld by the closed forms, %lld integrated in %lld CVODE steps),"
         " until t = %.6e s\n",
         (long long)result.n_contacts, (long long)result.closed_form_contacts,
         (long long)result.integrated_contacts, (long long)result.steps, result.time);
  printf("  pair      start (s)        end (s)  approach  separation  peak force (N)  method\n");
  for (i = 0; i < (int)result.contacts_recorded; ++i) {
    printf("  %4d  %.6e  %.6e  %8.5f  %10.5f  %14.2f  %s\n", contacts[i].pair,
           contacts[i].t_start, contacts[i].t_end, contacts[i].approach_speed,
           contacts[i].separation_speed, contacts[i].peak_force,
           contacts[i].method == HCIMPACT_CHAIN_BY_CLOSED_FORMS ? "closed forms" : "CVODE");
  }
  printf("  energy error %.2e, momentum error %.2e\n\n", result.energy_error,
         result.momentum_error);
  for (i = 0; i < N; ++i) {
    p0 += masses[i] * velocities[i];
    p1 += masses[i] * after[i];
  }
  if (!(fabs(p1 - p0) <= 1e-14 * fabs(p0))) {
    fprintf(stderr, "%s: momentum not conserved (%.17g, %.17g)\n", title, p0, p1);
    failed = 1;
  }
  if (!(result.energy_error <= 1e-7)) {
    fprintf(stderr, "%s: energy error %.3g\n", title, result.energy_error);
    failed = 1;
  }
  return failed;
}

int main(void)
{
  int failed = run("Five balls, 0.1 mm apart (isolated contacts: the closed forms)", 1e-4);
  double v[N];
  failed |= run("Five touching balls (overlapping contacts: CVODE)", 0.0);
  /* the touching cradle's first ball rebounds: the classical (0, 0, 0, 0, V) is wrong */
  {
    double masses[N] = {0.1, 0.1, 0.1, 0.1, 0.1}, v0[N] = {1.0, 0.0, 0.0, 0.0, 0.0};
    double gaps[N - 1] = {0.0, 0.0, 0.0, 0.0};
    hcimpact_chain_law laws[N - 1] = {{pair_stiffness, 1.5, 0.0}, {pair_stiffness, 1.5, 0.0},
                                      {pair_stiffness, 1.5, 0.0}, {pair_stiffness, 1.5, 0.0}};
    hcimpact_chain_result result;
    if (hcimpact_chain_simulate(N, masses, v0, gaps, laws, NULL, NULL, 0.0, NULL, &result, NULL,
                                v, 0, NULL, NULL, NULL, 0) != HCIMPACT_OK
        || !(fabs(v[0]) > 1e-3 && v[4] < 0.999)) {
      fprintf(stderr, "the touching cradle ended at (0, 0, 0, 0, V)\n");
      failed = 1;
    }
  }
  return failed;
}
