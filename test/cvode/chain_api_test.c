/* SPDX-License-Identifier: Apache-2.0 */
/* hcimpact_chain_simulate (libhcimpact_cvode, hcimpact_cvode.h) from C: the structures
 * as the header declares them (two bodies against the closed forms of one impact, field
 * by field, so that a field out of place fails), a cradle of touching balls (momentum,
 * energy, not the (0, 0, V) of instantaneous collisions), the samples' layout, options of
 * zeros, the caller's contact array and message buffer, the statuses for bad input, and
 * the monitor of hcimpact_chain_simulate_monitored.
 * The bit-for-bit comparison with the Fortran API is test/cvode/test_chain_api.f90.
 * Exit code 0 when every check passes. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hcimpact_cvode.h"

static int failures = 0;

static void check(const char *what, int ok)
{
  if (!ok) {
    printf("FAIL %s\n", what);
    ++failures;
  }
}

static void check_close(const char *what, double actual, double expected, double rel)
{
  if (!(fabs(actual - expected) <= rel * fabs(expected))) {
    printf("FAIL %s: %.17g, expected %.17g (rel %.1e)\n", what, actual, expected, rel);
    ++failures;
  }
}

static void check_status(const char *what, int actual, int expected, const char *message)
{
  if (actual != expected) {
    printf("FAIL %s: status %d, expected %d (%s)\n", what, actual, expected, message);
    ++failures;
  }
}

#define STEEL_PLATE 1.7135e10
#define STEEL_PAIR (STEEL_PLATE / 1.4142135623730951)

/* Two balls of different masses, the first striking the second: one contact, computed
 * by the closed forms, equal to hcimpact_impact's outcome at the effective mass and the
 * relative speed, and to hcimpact_two_body_velocities' velocities after it. */
static void two_bodies(void)
{
  const double m[2] = {0.1, 0.3}, v[2] = {2.0, -0.5}, gap[1] = {1e-4};
  const hcimpact_chain_law law[1] = {{STEEL_PAIR, 1.5, 0.2}};
  hcimpact_chain_result r;
  hcimpact_chain_contact c[4];
  hcimpact_contact contact;
  hcimpact_outcome out;
  double x[2], vf[2], v1, v2;
  char message[256];
  int stat;

  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, x, vf, 4, c,
                                 NULL, message, sizeof message);
  check_status("two bodies", stat, HCIMPACT_OK, message);
  check("two bodies: message", strcmp(message, "success") == 0);
  check("two bodies: one contact by the closed forms",
        r.n_contacts == 1 && r.contacts_recorded == 1 && c[0].pair == 1
            && c[0].method == HCIMPACT_CHAIN_BY_CLOSED_FORMS
            && r.method_used == HCIMPACT_CHAIN_BY_CLOSED_FORMS && r.closed_form_contacts == 1
            && r.integrated_contacts == 0 && r.steps == 0 && r.rested == 0);
  contact.mass = hcimpact_effective_mass(m[0], m[1]);
  contact.stiffness = law[0].stiffness;
  contact.exponent = law[0].exponent;
  contact.damping = law[0].damping;
  contact.velocity = v[0] - v[1];
  check_status("hcimpact_impact", hcimpact_impact(&contact, &out), HCIMPACT_OK, "");
  check_status("hcimpact_two_body_velocities",
               hcimpact_two_body_velocities(m[0], m[1], v[0], v[1], out.restitution, &v1, &v2),
               HCIMPACT_OK, "");
  /* the contact starts when the gap has closed at the relative speed */
  check_close("t_start", c[0].t_start, gap[0] / contact.velocity, 1e-15);
  check_close("contact time", c[0].t_end - c[0].t_start, out.contact_time, 1e-11);
  check_close("approach speed", c[0].approach_speed, contact.velocity, 1e-15);
  check_close("separation speed", c[0].separation_speed, -out.rebound_velocity, 1e-14);
  check_close("peak force", c[0].peak_force, out.peak_force, 1e-14);
  check_close("max deformation", c[0].max_deformation, out.max_compression, 1e-14);
  check_close("dissipated", c[0].dissipated,
              0.5 * contact.mass * contact.velocity * contact.velocity * out.energy_loss_ratio,
              1e-13);
  check_close("dissipated (result)", r.dissipated, c[0].dissipated, 1e-15);
  check_close("velocity 1 after", vf[0], v1, 1e-14);
  check_close("velocity 2 after", vf[1], v2, 1e-14);
  check("energy balance", r.energy_error < 1e-14);
  check("momentum balance", r.momentum_error < 1e-15);
  check("no walls: no walls' impulses", r.wall_impulse_left == 0.0 && r.wall_impulse_right == 0.0);
  check_close("initial energy", r.initial_energy, 0.5 * (m[0] * v[0] * v[0] + m[1] * v[1] * v[1]),
              1e-15);
  /* the centre of mass moves uniformly; the bodies part from touching at t_end */
  check_close("centre of mass", (m[0] * x[0] + m[1] * x[1]) / (m[0] + m[1]),
              (m[1] * gap[0] + (m[0] * v[0] + m[1] * v[1]) * r.time) / (m[0] + m[1]), 1e-12);
  check("gap after the contact", fabs((x[1] - x[0]) - (vf[1] - vf[0]) * (r.time - c[0].t_end))
                                     <= 1e-12 * fabs(x[1]) + 1e-18);
}

/* Three touching equal Hertz balls, one striking from a gap: a cluster integrated by
 * CVODE, sampled; zero options are the defaults. */
static void cradle(void)
{
  enum { n = 3, ns = 4 };
  const double m[n] = {0.1, 0.1, 0.1}, v[n] = {1.0, 0.0, 0.0}, gap[n - 1] = {1e-5, 0.0};
  const hcimpact_chain_law law[n - 1] = {{STEEL_PAIR, 1.5, 0.0}, {STEEL_PAIR, 1.5, 0.0}};
  const double times[ns] = {0.0, 5e-6, 1e-4, 1e-3};
  double sx[ns * n], sv[ns * n], sf[ns * (n + 1)], x[n], vf[n], x0[n], v0[n];
  hcimpact_chain_samples samples;
  hcimpact_chain_options options = {0};
  hcimpact_chain_result r;
  hcimpact_chain_contact c[16];
  char message[256];
  int stat, i, j;

  samples.count = ns;
  samples.times = times;
  samples.positions = sx;
  samples.velocities = sv;
  samples.forces = sf;
  options.rtol = 1e-10;
  stat = hcimpact_chain_simulate(n, m, v, gap, law, NULL, NULL, 0.0, &options, &r, x, vf, 16,
                                 c, &samples, message, sizeof message);
  check_status("cradle", stat, HCIMPACT_OK, message);
  check("cradle: integrated", r.integrated_contacts >= 1 && r.steps > 0 && r.clusters >= 1
                                  && (r.method_used == HCIMPACT_CHAIN_BY_INTEGRATION
                                      || r.method_used == HCIMPACT_CHAIN_BY_BOTH));
  check("cradle: momentum to rounding", r.momentum_error < 1e-14);
  check("cradle: elastic energy to the tolerance", r.energy_error < 1e-7);
  check("cradle: not (0, 0, V)", fabs(vf[0]) > 1e-3 || fabs(vf[1]) > 1e-3);
  check("cradle: all separating", vf[0] <= vf[1] && vf[1] <= vf[2]);
  /* the first sample is the initial state: q = 0, gap, gap; forces 0 */
  x0[0] = 0.0;
  x0[1] = gap[0];
  x0[2] = gap[0] + gap[1];
  v0[0] = 1.0;
  v0[1] = v0[2] = 0.0;
  for (i = 0; i < n; ++i) {
    check("sample 0: positions", sx[i] == x0[i]);
    check("sample 0: velocities", sv[i] == v0[i]);
  }
  for (i = 0; i <= n; ++i) check("sample 0: forces", sf[i] == 0.0);
  /* at 5 us the first ball flies freely: 5e-6 m, the others at rest; walls: force 0 */
  check_close("sample 1: ball 1", sx[n + 0], 5e-6, 1e-14);
  check("sample 1: balls 2 and 3", sx[n + 1] == x0[1] && sx[n + 2] == x0[2]);
  /* the last sample is after every contact: the final velocities */
  for (i = 0; i < n; ++i) check_close("last sample: velocity", sv[3 * n + i], vf[i], 1e-12);
  for (j = 0; j < ns; ++j) {
    check("no wall: no wall force", sf[j * (n + 1)] == 0.0 && sf[j * (n + 1) + n] == 0.0);
  }
  check("some force during the contacts", sf[2 * (n + 1) + 1] >= 0.0);
}

/* Bad input: statuses, nothing written (NULL, sizes) or NaN (values). */
static void bad_input(void)
{
  const double m[2] = {0.1, 0.1}, v[2] = {1.0, 0.0}, gap[1] = {0.0}, bad_gap[1] = {-1e-9};
  const double nan_mass[2] = {0.1, NAN}, zero_mass[2] = {0.1, 0.0};
  const hcimpact_chain_law law[1] = {{STEEL_PAIR, 1.5, 0.0}};
  const hcimpact_chain_wall wall = {STEEL_PLATE, 1.5, 0.1, -1.0};
  hcimpact_chain_options options = {0};
  hcimpact_chain_result r;
  double x[2] = {-7.0, -7.0};
  char message[256];
  int stat;

  r.time = -7.0;
  stat = hcimpact_chain_simulate(2, NULL, v, gap, law, NULL, NULL, 0.0, NULL, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("masses NULL", stat, HCIMPACT_ERR_NULL, message);
  check("masses NULL: nothing written", r.time == -7.0 && x[0] == -7.0);
  check("masses NULL: a message", strlen(message) > 0);
  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, NULL, NULL, x, NULL, 0,
                                 NULL, NULL, NULL, 0);
  check_status("result NULL", stat, HCIMPACT_ERR_NULL, "");
  stat = hcimpact_chain_simulate(2, m, v, NULL, law, NULL, NULL, 0.0, NULL, &r, x, NULL, 0,
                                 NULL, NULL, NULL, 0);
  check_status("gaps NULL", stat, HCIMPACT_ERR_NULL, "");
  stat = hcimpact_chain_simulate(0, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, x, NULL, 0, NULL,
                                 NULL, message, sizeof message);
  check_status("n = 0", stat, HCIMPACT_ERR_SIZE, message);
  check("n = 0: nothing written", r.time == -7.0 && x[0] == -7.0);
  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, x, NULL, -1,
                                 NULL, NULL, NULL, 0);
  check_status("capacity -1", stat, HCIMPACT_ERR_SIZE, "");

  stat = hcimpact_chain_simulate(2, nan_mass, v, gap, law, NULL, NULL, 0.0, NULL, &r, x, NULL,
                                 0, NULL, NULL, message, sizeof message);
  check_status("mass NaN", stat, HCIMPACT_ERR_NOT_FINITE, message);
  check("mass NaN: NaN outputs", isnan(r.time) && isnan(r.energy_error) && r.n_contacts == 0
                                     && isnan(r.wall_impulse_left) && isnan(r.wall_impulse_right)
                                     && isnan(x[0]) && isnan(x[1]));
  stat = hcimpact_chain_simulate(2, zero_mass, v, gap, law, NULL, NULL, 0.0, NULL, &r, x, NULL,
                                 0, NULL, NULL, message, sizeof message);
  check_status("mass 0", stat, HCIMPACT_ERR_MASS, message);
  stat = hcimpact_chain_simulate(2, m, v, bad_gap, law, NULL, NULL, 0.0, NULL, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("negative gap", stat, HCIMPACT_ERR_DOMAIN, message);
  check("negative gap: the message names the gap", strstr(message, "gap 1") != NULL);
  stat = hcimpact_chain_simulate(2, m, v, gap, law, &wall, NULL, 0.0, NULL, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("wall overlapping", stat, HCIMPACT_ERR_DOMAIN, message);
  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, INFINITY, NULL, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("gravity infinite", stat, HCIMPACT_ERR_NOT_FINITE, message);
  options.rtol = -1e-8;
  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, &options, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("rtol < 0", stat, HCIMPACT_ERR_DOMAIN, message);
  options.rtol = 0.0;
  options.method = 9;
  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, &options, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("method 9", stat, HCIMPACT_ERR_DOMAIN, message);
  /* the touching pair struck from one side is isolated here (two bodies): exact works */
  options.method = HCIMPACT_CHAIN_EXACT;
  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, &options, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("two touching bodies, exact", stat, HCIMPACT_OK, message);
  check("contacts counted without an array", r.n_contacts == 1 && r.contacts_recorded == 0);
}

/* Found by the fuzzer (bench/fuzz, doc/robustness.md): a region that cannot begin
   (forces below the normal range of doubles) freed nothing of what it had set up (a
   leak under valgrind, which runs this test); a wall contact integrated at 1e-4 rtol
   reported -2e-26 J dissipated with success. */
static void fuzz_findings(void)
{
  const double m[2] = {1.0, 1.0}, v[2] = {1e-300, 0.0}, gap[1] = {0.0};
  const hcimpact_chain_law law[1] = {{1e9, 1.5, 0.0}};
  const double m2[2] = {0.00032758712768554688, 2947514368.0};
  const double v2[2] = {-9.2120426690421719e+18, 3954147328.0}, gap2[1] = {0.00058975815773010254};
  const hcimpact_chain_law law2[1] = {{1.3101787786857928e-51, 0.25, 0.00048828125}};
  const hcimpact_chain_wall wall2 = {4.0591795293901135e-66, 0.25, 7.0179812610149384e-05,
                                     180334592.0};
  hcimpact_chain_options options = {0};
  hcimpact_chain_result r;
  hcimpact_chain_contact c[4];
  double x[2];
  char message[256];
  int stat, i;

  options.method = HCIMPACT_CHAIN_INTEGRATED;
  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, &options, &r, x, NULL, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("forces below the doubles' range", stat, HCIMPACT_ERR_DOMAIN, message);
  check("forces below the doubles' range: the message says so",
        strstr(message, "below the normal range") != NULL);

  options.method = HCIMPACT_CHAIN_AUTO;
  options.rtol = 1e-4;
  stat = hcimpact_chain_simulate(2, m2, v2, gap2, law2, &wall2, NULL, 2.0638712862657741e+17,
                                 &options, &r, x, NULL, 4, c, NULL, message, sizeof message);
  check_status("a faint wall contact", stat, HCIMPACT_OK, message);
  check("a faint wall contact: integrated", r.contacts_recorded >= 1 && r.integrated_contacts >= 1);
  check("a faint wall contact: dissipated >= 0", r.dissipated >= 0.0);
  for (i = 0; i < r.contacts_recorded && i < 4; ++i) {
    check("a faint wall contact: each contact's dissipated >= 0", c[i].dissipated >= 0.0);
  }
}

/* A contact whose b V is above 1e40 (HCIMPACT_MAX_BETA) is outside the model's domain,
   as for one impact: HCIMPACT_ERR_DOMAIN naming the pair, by the closed forms' path, the
   integrated method and a cluster alike (CVODE's corrector failed on them, status 11). */
static void beyond_max_beta(void)
{
  const double m1[1] = {1.0}, v1[1] = {-1.0};
  const hcimpact_chain_wall wall = {1e9, 1.5, 1e41, 1.0};
  const double m3[3] = {1.0, 1.0, 1.0}, v3[3] = {1.0, 0.0, 0.0}, gap3[2] = {0.0, 0.0};
  const hcimpact_chain_law law3[2] = {{1e9, 1.5, 1e41}, {1e9, 1.5, 1e41}};
  const hcimpact_chain_wall wall_below = {1e9, 1.5, 0.99e40, 1.0};
  hcimpact_chain_options options = {0};
  hcimpact_chain_result r;
  double vf[3];
  char message[256];
  int stat, method;

  for (method = HCIMPACT_CHAIN_AUTO; method <= HCIMPACT_CHAIN_INTEGRATED; ++method) {
    options.method = method;
    stat = hcimpact_chain_simulate(1, m1, v1, NULL, NULL, &wall, NULL, 0.0, &options, &r, NULL,
                                   vf, 0, NULL, NULL, message, sizeof message);
    check_status("b V = 1e41 on a wall", stat, HCIMPACT_ERR_DOMAIN, message);
    check("b V = 1e41 on a wall: the message names pair 0 and the domain",
          strstr(message, "pair 0 ") != NULL && strstr(message, "outside the model's domain"));
  }
  options.method = HCIMPACT_CHAIN_AUTO;
  stat = hcimpact_chain_simulate(3, m3, v3, gap3, law3, NULL, NULL, 0.0, &options, &r, NULL, vf,
                                 0, NULL, NULL, message, sizeof message);
  check_status("b V = 1e41 in a cluster", stat, HCIMPACT_ERR_DOMAIN, message);
  check("b V = 1e41 in a cluster: the message names pair 1", strstr(message, "pair 1 ") != NULL);
  /* just below: a contact of the closed forms, the rebound about 1 / b */
  stat = hcimpact_chain_simulate(1, m1, v1, NULL, NULL, &wall_below, NULL, 0.0, &options, &r,
                                 NULL, vf, 0, NULL, NULL, message, sizeof message);
  check_status("b V = 0.99e40 on a wall", stat, HCIMPACT_OK, message);
  check("b V = 0.99e40 on a wall: rebound", vf[0] > 0.0 && vf[0] < 1e-30);
}

/* The next free contact under gravity where the speeds pass huge / 16 (1.1e307 m/s): its
   equation is solved divided by 32 (unscaled, q overflows from huge / 2 on; found by the
   fuzzer, whose input bench/fuzz/findings/chain-fixed-exponent-18d8635 takes this branch
   with an infinite gap). Here the division's roots themselves are checked (a speed left
   undivided put the contact at 1/32 of its time): a body of 1e-307 kg at 1.5e307 m/s
   toward a wall 1e300 m away, gravity 1 m/s^2 away from the wall, meets the wall at
   1e300 / 1.5e307 s (gravity's share is 1e-315 of the gap) and rebounds elastically. */
static void fast_body_under_gravity(void)
{
  const double m[1] = {1e-307}, v[1] = {-1.5e307};
  const hcimpact_chain_wall wall = {1e9, 1.5, 0.0, 1e300};
  hcimpact_chain_result r;
  hcimpact_chain_contact c[2];
  double vf[1];
  char message[256];
  int stat;

  stat = hcimpact_chain_simulate(1, m, v, NULL, NULL, &wall, NULL, 1.0, NULL, &r, NULL, vf, 2,
                                 c, NULL, message, sizeof message);
  check_status("1.5e307 m/s under gravity", stat, HCIMPACT_OK, message);
  check("1.5e307 m/s under gravity: one contact", r.n_contacts == 1 && r.contacts_recorded == 1);
  if (r.contacts_recorded == 1) {
    check_close("1.5e307 m/s under gravity: the contact's start", c[0].t_start, 1e300 / 1.5e307,
                4.0 * 2.220446049250313e-16);
    check_close("1.5e307 m/s under gravity: approach", c[0].approach_speed, 1.5e307, 1e-15);
  }
  check_close("1.5e307 m/s under gravity: rebound", vf[0], 1.5e307, 1e-12);
}

/* Found by a cross-check of the chain against hcimpact_impact (27 November): an elastic
   pair of 1e-150 kg bodies at 3e-174 m/s, whose momentum 3e-324 kg m/s is subnormal
   (one digit), ended with both velocities 1e-174 m/s off, and bodies of 1e-260 kg
   ended half their gap (5e-71 m) away from where they met, both with success (the
   centre of mass was formed from products of masses and speeds). */
static void small_momenta(void)
{
  const double m[2] = {1e-150, 1e-150}, v[2] = {3.0000000000000002e-174, 0.0}, gap[1] = {0.0};
  const double m2[2] = {9.9999999999999996e-261, 9.9999999999999996e-261};
  const double v2[2] = {0.0, -9.9999999999999998e-46}, gap2[1] = {1e-70};
  const hcimpact_chain_law law[1] = {{1.0, 1.0, 0.0}};
  hcimpact_chain_result r;
  double x[2], vf[2];
  char message[256];
  int stat;

  stat = hcimpact_chain_simulate(2, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, NULL, vf, 0, NULL,
                                 NULL, message, sizeof message);
  check_status("momenta of 3e-324", stat, HCIMPACT_OK, message);
  check("momenta of 3e-324: the striker stops", fabs(vf[0]) <= 1e-16 * v[0]);
  check_close("momenta of 3e-324: the other takes the speed", vf[1], v[0], 4.5e-16);
  stat = hcimpact_chain_simulate(2, m2, v2, gap2, law, NULL, NULL, 0.0, NULL, &r, x, vf, 0, NULL,
                                 NULL, message, sizeof message);
  check_status("masses of 1e-260", stat, HCIMPACT_OK, message);
  /* they meet at 0 at t = 1e-25 s and part within 1e-129 s at 1e-45 m/s */
  check("masses of 1e-260: both end where they met", x[0] <= 0.0 && x[0] > -1e-150 &&
        x[1] >= 0.0 && x[1] < 1e-150);
  check_close("masses of 1e-260: the speeds exchanged", vf[0], v2[1], 4.5e-16);
}

/* Scales the closed forms refuse (the same cross-check): a body of 1e-300 kg on a wall of
   c = 1e300 N/m (a contact of pi 1e-300 s, as the unit impact scaled) was integrated at
   steps of 1e-300 s for hours; with c = 1e-300 N/m^2 at 1e-20 m/s (a peak force of 1e-327
   N, below the doubles' normal range) CVODE returned a rebound 17 % short, with success. */
static void scales_apart(void)
{
  const double m[1] = {1e-300}, v[1] = {-1.0}, v_slow[1] = {-9.9999999999999995e-21};
  const hcimpact_chain_wall stiff = {1e300, 1.0, 0.0, 0.0}, damped = {1e300, 1.0, 1e20, 0.0};
  const hcimpact_chain_wall faint = {1e-300, 2.0, 0.0, 0.0};
  const hcimpact_contact unit = {1.0, 1.0, 1.0, 1e20, 1.0};
  hcimpact_chain_options options = {0};
  hcimpact_chain_result r;
  hcimpact_chain_contact c[2];
  hcimpact_outcome out;
  double vf[1];
  char message[256];
  int stat;

  stat = hcimpact_chain_simulate(1, m, v, NULL, NULL, &stiff, NULL, 0.0, NULL, &r, NULL, vf, 2,
                                 c, NULL, message, sizeof message);
  check_status("1e-300 kg on 1e300 N/m", stat, HCIMPACT_OK, message);
  check("1e-300 kg on 1e300 N/m: closed forms", r.closed_form_contacts == 1 && r.steps == 0);
  check_close("1e-300 kg on 1e300 N/m: rebound", vf[0], 1.0, 2.3e-16);
  check_close("1e-300 kg on 1e300 N/m: duration", c[0].t_end, 3.141592653589793e-300, 1e-12);
  check_close("1e-300 kg on 1e300 N/m: peak force", c[0].peak_force, 1.0, 1e-12);
  stat = hcimpact_impact(&unit, &out);
  check_status("the unit impact at b V = 1e20", stat, HCIMPACT_OK, "");
  stat = hcimpact_chain_simulate(1, m, v, NULL, NULL, &damped, NULL, 0.0, NULL, &r, NULL, vf, 2,
                                 c, NULL, message, sizeof message);
  check_status("1e-300 kg on 1e300 N/m, b V = 1e20", stat, HCIMPACT_OK, message);
  check_close("b V = 1e20: rebound", vf[0], -out.rebound_velocity, 2.3e-16);
  check_close("b V = 1e20: duration", c[0].t_end, out.contact_time * 1e-300, 1e-12);
  /* two bodies that meet 1e195 m away end one ulp of their positions (1e179 m) into each
     other: no deformation (its elastic energy at 1 N/m, 1e358 J, failed the run) */
  {
    const double m2[2] = {9.9999999999999998e-201, 2.9999999999999999e-200};
    const double v2[2] = {9.9999999999999997e+199, 0.0}, gap2[1] = {1e195};
    const hcimpact_chain_law law2[1] = {{1.0, 1.0, 0.0}};
    double vf2[2];
    stat = hcimpact_chain_simulate(2, m2, v2, gap2, law2, NULL, NULL, 0.0, NULL, &r, NULL, vf2,
                                   0, NULL, NULL, message, sizeof message);
    check_status("an overlap of one ulp at 1e195 m", stat, HCIMPACT_OK, message);
    check_close("an overlap of one ulp: velocity", vf2[1], 0.5 * v2[0], 4.5e-16);
    check("an overlap of one ulp: energy kept", r.energy_error <= 1e-15);
  }
  /* the same where one body rests at 0 and the other, 4.3e-26 m away, strikes it: the
     overlap is within the rounding of the striker's initial position, not of the final
     positions (near 0); mirrored, the same speeds */
  {
    const double m4[2] = {2.3100573870691286e-289, 3.3367871291592019e-293};
    const double m4r[2] = {3.3367871291592019e-293, 2.3100573870691286e-289};
    const double v4[2] = {0.0, -51.403765492995504}, v4r[2] = {51.403765492995504, 0.0};
    const double gap4[1] = {4.2709192487976837e-26};
    const hcimpact_chain_law law4[1] = {{1.22628440837845e+245, 1.0, 0.0}};
    double vf4[2], vf4r[2];
    stat = hcimpact_chain_simulate(2, m4, v4, gap4, law4, NULL, NULL, 0.0, NULL, &r, NULL, vf4,
                                   0, NULL, NULL, message, sizeof message);
    check_status("an overlap within the initial positions' rounding", stat, HCIMPACT_OK, message);
    stat = hcimpact_chain_simulate(2, m4r, v4r, gap4, law4, NULL, NULL, 0.0, NULL, &r, NULL,
                                   vf4r, 0, NULL, NULL, message, sizeof message);
    check_status("an overlap within the initial positions' rounding, mirrored", stat,
                 HCIMPACT_OK, message);
    check_close("mirrored: the light body", vf4[1], -vf4r[0], 4.5e-16);
    check_close("mirrored: the heavy body", vf4[0], -vf4r[1], 4.5e-16);
  }
  /* 1e300 kg on a wall of 1e100 N/m at 1e-300 m/s: exact by the closed forms; CVODE does
     not resolve it (it ended with 5e18 times the energy, and success) */
  {
    const double m3[1] = {1e300}, v3[1] = {-1e-300};
    const hcimpact_chain_wall heavy = {1e100, 1.0, 0.0, 0.0};
    stat = hcimpact_chain_simulate(1, m3, v3, NULL, NULL, &heavy, NULL, 0.0, NULL, &r, NULL, vf,
                                   0, NULL, NULL, message, sizeof message);
    check_status("1e300 kg at 1e-300 m/s", stat, HCIMPACT_OK, message);
    check_close("1e300 kg at 1e-300 m/s: rebound", vf[0], 1e-300, 2.3e-16);
    options.method = HCIMPACT_CHAIN_INTEGRATED;
    stat = hcimpact_chain_simulate(1, m3, v3, NULL, NULL, &heavy, NULL, 0.0, &options, &r, NULL,
                                   vf, 0, NULL, NULL, message, sizeof message);
    if (stat == HCIMPACT_OK) {
      check_close("1e300 kg at 1e-300 m/s, integrated: rebound", vf[0], 1e-300, 1e-6);
    } else {
      check_status("1e300 kg at 1e-300 m/s, integrated", stat, HCIMPACT_ERR_SOLVER, message);
      check("1e300 kg at 1e-300 m/s, integrated: said",
            strstr(message, "did not resolve the contacts") != NULL);
    }
    options.method = HCIMPACT_CHAIN_AUTO;
  }
  /* a compression of 1.2e300 m whose scale in the unit impact's units is e^767: refused
     (it came out +Inf with success) */
  {
    const double m5[1] = {1.0}, v5[1] = {-1e150};
    const hcimpact_chain_wall soft = {1e-100, 0.2, 1e-110, 0.0};
    stat = hcimpact_chain_simulate(1, m5, v5, NULL, NULL, &soft, NULL, 0.0, NULL, &r, NULL, vf,
                                   0, NULL, NULL, message, sizeof message);
    check_status("a compression scale of e^767", stat, HCIMPACT_ERR_DOMAIN, message);
    check("a compression scale of e^767: said",
          strstr(message, "leaves the range of doubles") != NULL);
  }
  /* 1 kg at 1e-200 m/s on c = 1e-300 N/m^0.2: the powers of V underflow (V^(2/1.2) =
     1e-333), the compression 3e-84 m came out 0; elastic, x_max = ((n + 1) m V^2 /
     (2 c))^(1 / (n + 1)), formed here in long double */
  {
    const double m6[1] = {1.0}, v6[1] = {-1e-200};
    const hcimpact_chain_wall loose = {1e-300, 0.2, 0.0, 0.0};
    const double x_max = (double)expl((logl(1.2L) + 2.0L * logl(1e-200L) - logl(2e-300L)) / 1.2L);
    stat = hcimpact_chain_simulate(1, m6, v6, NULL, NULL, &loose, NULL, 0.0, NULL, &r, NULL, vf,
                                   2, c, NULL, message, sizeof message);
    check_status("V^(2p) below the doubles", stat, HCIMPACT_OK, message);
    if (stat == HCIMPACT_OK && r.contacts_recorded == 1) {
      check_close("V^(2p) below the doubles: compression", c[0].max_deformation, x_max, 1e-12);
    }
  }
  /* the closed forms, scaled, rebound it elastically; CVODE cannot resolve such forces */
  stat = hcimpact_chain_simulate(1, m, v_slow, NULL, NULL, &faint, NULL, 0.0, NULL, &r, NULL,
                                 vf, 0, NULL, NULL, message, sizeof message);
  check_status("a peak force of 1e-327 N", stat, HCIMPACT_OK, message);
  check_close("a peak force of 1e-327 N: rebound", vf[0], -v_slow[0], 2.3e-16);
  options.method = HCIMPACT_CHAIN_INTEGRATED;
  stat = hcimpact_chain_simulate(1, m, v_slow, NULL, NULL, &faint, NULL, 0.0, &options, &r, NULL,
                                 vf, 0, NULL, NULL, message, sizeof message);
  check_status("a peak force of 1e-327 N, integrated", stat, HCIMPACT_ERR_DOMAIN, message);
  check("a peak force of 1e-327 N, integrated: said",
        strstr(message, "below the normal range") != NULL);
}

/* The monitor of hcimpact_chain_simulate_monitored: what its poll is given, a monitor
   that never stops leaves the run as it is (bit for bit), one that stops at its third
   call ends the run there with HCIMPACT_ERR_NO_CONVERGENCE and NaN outputs, and a monitor
   without a poll is refused. The run: a row of eight touching steel beads struck at one
   end, until they all separate (some hundred steps). */
typedef struct {
  int calls;
  int stop_at;          /* stop at this call (0: never) */
  int ordered;          /* time, steps and events never decreased */
  double time;
  int64_t steps, events;
} watch;

static int poll(void *data, double time, int64_t steps, int64_t events)
{
  watch *w = (watch *)data;
  if (w->calls > 0 && (time < w->time || steps < w->steps || events < w->events))
    w->ordered = 0;
  w->time = time;
  w->steps = steps;
  w->events = events;
  ++w->calls;
  return w->stop_at > 0 && w->calls >= w->stop_at;
}

static void monitored(void)
{
  enum { n = 8 };
  const double m[n] = {0.0163, 0.0163, 0.0163, 0.0163, 0.0163, 0.0163, 0.0163, 0.0163};
  const double v[n] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const double gap[n - 1] = {0.0};
  const hcimpact_chain_law steel = {STEEL_PAIR, 1.5, 0.0};
  hcimpact_chain_law law[n - 1];
  hcimpact_chain_result plain, r;
  double x0[n], v0[n], x[n], vf[n];
  char message[256];
  watch w = {0, 0, 1, 0.0, 0, 0};
  hcimpact_chain_monitor monitor = {poll, &w}, no_poll = {NULL, &w};
  int stat, i;

  for (i = 0; i < n - 1; ++i) law[i] = steel;

  stat = hcimpact_chain_simulate(n, m, v, gap, law, NULL, NULL, 0.0, NULL, &plain, x0, v0, 0,
                                 NULL, NULL, message, sizeof message);
  check_status("struck row", stat, HCIMPACT_OK, message);
  check("struck row: some steps", plain.steps > 64 * 4);
  stat = hcimpact_chain_simulate_monitored(n, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, x,
                                           vf, 0, NULL, NULL, &monitor, message, sizeof message);
  check_status("a monitor that never stops", stat, HCIMPACT_OK, message);
  check("a monitor that never stops: the same run", memcmp(x, x0, sizeof x) == 0
        && memcmp(vf, v0, sizeof vf) == 0 && r.time == plain.time && r.steps == plain.steps
        && r.n_contacts == plain.n_contacts && r.energy_error == plain.energy_error);
  check("a monitor that never stops: called every 64 passes at least",
        w.calls >= (int)(plain.steps / 64) && w.calls > 0);
  check("a monitor that never stops: time, steps and events in order", w.ordered);
  check("a monitor that never stops: it saw the work", w.steps > 0 && w.time > 0.0
        && w.time <= plain.time && w.steps <= plain.steps);
  w.calls = 0;
  w.stop_at = 3;
  stat = hcimpact_chain_simulate_monitored(n, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, x,
                                           vf, 0, NULL, NULL, &monitor, message, sizeof message);
  check_status("a monitor that stops", stat, HCIMPACT_ERR_NO_CONVERGENCE, message);
  check("a monitor that stops: at its third call", w.calls == 3);
  check("a monitor that stops: the message says so",
        strncmp(message, "stopped by the caller's monitor", 31) == 0);
  check("a monitor that stops: NaN outputs", isnan(r.time) && isnan(x[0]) && isnan(vf[1])
        && r.steps == 0 && r.n_contacts == 0);
  r.time = -7.0;
  x[0] = -7.0;
  stat = hcimpact_chain_simulate_monitored(n, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, x,
                                           vf, 0, NULL, NULL, &no_poll, message, sizeof message);
  check_status("a monitor without a poll", stat, HCIMPACT_ERR_NULL, message);
  check("a monitor without a poll: nothing written", r.time == -7.0 && x[0] == -7.0
        && strstr(message, "poll") != NULL);
  stat = hcimpact_chain_simulate_monitored(n, m, v, gap, law, NULL, NULL, 0.0, NULL, &r, x,
                                           vf, 0, NULL, NULL, NULL, message, sizeof message);
  check_status("no monitor", stat, HCIMPACT_OK, message);
  check("no monitor: the same run", memcmp(x, x0, sizeof x) == 0 && r.steps == plain.steps);
}

int main(void)
{
  two_bodies();
  cradle();
  bad_input();
  fuzz_findings();
  beyond_max_beta();
  fast_body_under_gravity();
  small_momenta();
  scales_apart();
  monitored();
  if (failures) {
    printf("%d checks failed\n", failures);
    return 1;
  }
  printf("hcimpact_chain_simulate: all checks passed\n");
  return 0;
}
