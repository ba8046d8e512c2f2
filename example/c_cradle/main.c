/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Three equal steel balls on a line (a Newton's cradle), the first striking the other
 * two, which touch, stepped by the caller's own integrator (the classical fourth-order
 * Runge-Kutta method at a fixed step) with each contact force from the library's
 * contact-force element, hcimpact_contact_force_pair (doc/contact-force.md). The same
 * program as example/legacy_f77/cradle.f, in C.
 *
 * It checks one ball against a wall (hcimpact_contact_force_wall) against the closed
 * forms of one impact (hcimpact_impact), then the cradle's energy and momentum
 * balance, and that the three touching balls do not end at (0, 0, V) as instantaneous
 * collisions would have them. Exit status 1 when a check fails.
 *
 * Build against an installed hcimpact:
 *   cc $(pkg-config --cflags hcimpact) main.c $(pkg-config --libs hcimpact) -lm -o cradle
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hcimpact.h"

#define NB 3           /* balls */
#define NS (2 * NB + 1) /* positions, velocities, dissipated energy */

static const double mass = 0.1, radius = 1.452e-2, exponent = 1.5, damping = 0.1;
static const double plate_stiffness = 1.7135e10;
/* two equal steel spheres: the sphere-on-plate constant over sqrt(2) */
#define BALL_STIFFNESS (plate_stiffness / 1.4142135623730951)

typedef void (*rate_fn)(const double *y, double *dy);

static void check(int status)
{
  if (status != HCIMPACT_OK) {
    fprintf(stderr, "hcimpact: %s\n", hcimpact_status_message(status));
    exit(2);
  }
}

/* one classical Runge-Kutta step of y' = f(y); y0 keeps the state before it */
static void rk4(rate_fn f, int n, double *y, double h, double *y0)
{
  double k1[NS], k2[NS], k3[NS], k4[NS], tmp[NS];
  int i;
  for (i = 0; i < n; ++i) y0[i] = y[i];
  f(y0, k1);
  for (i = 0; i < n; ++i) tmp[i] = y0[i] + 0.5 * h * k1[i];
  f(tmp, k2);
  for (i = 0; i < n; ++i) tmp[i] = y0[i] + 0.5 * h * k2[i];
  f(tmp, k3);
  for (i = 0; i < n; ++i) tmp[i] = y0[i] + h * k3[i];
  f(tmp, k4);
  for (i = 0; i < n; ++i) y[i] = y0[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

/* the cradle: +F on the right ball of a pair, -F on the left one */
static void cradle_rate(const double *y, double *dy)
{
  hcimpact_force f;
  int i;
  for (i = 0; i < NB; ++i) {
    dy[i] = y[NB + i];
    dy[NB + i] = 0.0;
  }
  dy[2 * NB] = 0.0;
  for (i = 0; i < NB - 1; ++i) {
    check(hcimpact_contact_force_pair(BALL_STIFFNESS, exponent, damping, 2.0 * radius, y[i],
                                      y[NB + i], y[i + 1], y[NB + i + 1], &f));
    dy[NB + i] -= f.force / mass;
    dy[NB + i + 1] += f.force / mass;
    dy[2 * NB] += f.dissipation;
  }
}

/* one ball (its surface at y[0]) against a wall at 0 on its right */
static void wall_rate(const double *y, double *dy)
{
  hcimpact_force f;
  check(hcimpact_contact_force_wall(plate_stiffness, exponent, damping, 0.0, y[0], y[1], 0.0,
                                    1, &f));
  dy[0] = y[1];
  dy[1] = -f.force / mass; /* the force on the body is -side F */
  dy[2] = f.dissipation;
}

static double cradle_energy(const double *y)
{
  hcimpact_force f;
  double e = y[2 * NB];
  int i;
  for (i = 0; i < NB; ++i) e += 0.5 * mass * y[NB + i] * y[NB + i];
  for (i = 0; i < NB - 1; ++i) {
    check(hcimpact_contact_force_pair(BALL_STIFFNESS, exponent, damping, 2.0 * radius, y[i],
                                      y[NB + i], y[i + 1], y[NB + i + 1], &f));
    e += f.potential;
  }
  return e;
}

int main(void)
{
  const double v0 = 1.0;
  hcimpact_contact contact = {mass, plate_stiffness, exponent, damping, v0};
  hcimpact_outcome outcome;
  double y[NS], y0[NS], h, t, e0, p0, p, worst = 0.0;
  int i, j, step, failures = 0, apart;

  /* 1. one ball on a wall against the closed forms */
  check(hcimpact_impact(&contact, &outcome));
  h = outcome.contact_time / 4000.0;
  y[0] = 0.0;
  y[1] = v0;
  y[2] = 0.0;
  t = 0.0;
  for (step = 0; step < 8000; ++step) {
    rk4(wall_rate, 3, y, h, y0);
    t += h;
    if (y[0] <= 0.0) break;
  }
  t -= h * y[0] / (y[0] - y0[0]);
  printf("one ball on a wall:  rebound/V = %.8f  closed form k = %.8f\n", -y[1] / v0,
         outcome.restitution);
  printf("                     contact time = %.6e  closed form = %.6e\n", t,
         outcome.contact_time);
  if (fabs(-y[1] / v0 - outcome.restitution) > 1e-6) ++failures;
  if (fabs(t - outcome.contact_time) > 1e-3 * outcome.contact_time) ++failures;

  /* 2. the cradle: centres 2R apart (touching), ball 1 moving */
  for (i = 0; i < NB; ++i) {
    y[i] = 2.0 * radius * i;
    y[NB + i] = 0.0;
  }
  y[NB] = v0;
  y[2 * NB] = 0.0;
  e0 = cradle_energy(y);
  p0 = mass * v0;
  for (step = 0; step < 200000; ++step) {
    rk4(cradle_rate, NS, y, h, y0);
    worst = fmax(worst, fabs(cradle_energy(y) - e0) / e0);
    apart = 1;
    for (j = 0; j < NB - 1; ++j)
      if (y[j + 1] - y[j] < 2.0 * radius || y[NB + j] > y[NB + j + 1]) apart = 0;
    if (apart) break;
  }
  p = 0.0;
  for (i = 0; i < NB; ++i) p += mass * y[NB + i];
  printf("three touching balls, final velocities / V: %.6f %.6f %.6f\n", y[NB] / v0,
         y[NB + 1] / v0, y[NB + 2] / v0);
  printf("energy balance error %.2e, momentum error %.2e, share of energy dissipated %.5f\n",
         worst, fabs(p - p0) / p0, y[2 * NB] / e0);
  if (worst > 1e-9) ++failures;
  if (fabs(p - p0) > 1e-12 * p0) ++failures;
  if (fabs(y[NB + 1]) < 1e-3 * v0) ++failures; /* not the instantaneous (0, 0, V) */
  if (failures) {
    printf("FAILED: %d check(s)\n", failures);
    return 1;
  }
  printf("all checks passed\n");
  return 0;
}
