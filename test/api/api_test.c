/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Test of the C interface of hcimpact from a plain C program: every function
 * declared in hcimpact.h is called with good arguments (values checked against
 * MODEL.md and mpmath references, loosely: accuracy is the business of the Fortran
 * unit tests), with arguments outside its domain (NaN or a documented status), and
 * with NULL pointers and bad sizes (HCIMPACT_ERR_NULL / HCIMPACT_ERR_SIZE, nothing
 * written). Also: the version macros, the status messages.
 *
 * Exit status 0 on success, 1 if any check failed. Run under valgrind by CTest
 * (hcimpact/valgrind/c-api) as well.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hcimpact.h"

static int failures = 0;
static int checks = 0;

static void fail(const char *what)
{
  ++failures;
  printf("FAIL %s\n", what);
}

/* |actual - expected| <= rel * |expected|; NaN never passes */
static void check_close(const char *what, double actual, double expected, double rel)
{
  ++checks;
  if (isnan(actual) || !(fabs(actual - expected) <= rel * fabs(expected))) {
    printf("FAIL %-44s got %.17g, expected %.17g\n", what, actual, expected);
    ++failures;
  }
}

static void check_nan(const char *what, double actual)
{
  ++checks;
  if (!isnan(actual)) {
    printf("FAIL %-44s got %.17g, expected NaN\n", what, actual);
    ++failures;
  }
}

static void check_status(const char *what, int actual, int expected)
{
  ++checks;
  if (actual != expected) {
    printf("FAIL %-44s status %d (%s), expected %d (%s)\n", what, actual,
           hcimpact_status_message(actual), expected, hcimpact_status_message(expected));
    ++failures;
  }
}

static void check_true(const char *what, int condition)
{
  ++checks;
  if (!condition) fail(what);
}

/* MODEL.md: the seed's steel ball */
static const double seed_v[6] = {0.5, 1.0, 2.0, 3.0, 4.0, 5.0};
static const double seed_k[6] = {0.9677385785309325, 0.93747557994990506, 0.88218998624730638,
                                 0.83286979226560167, 0.78853912590706515, 0.74843493159743416};
static const double seed_xmax[6] = {1.9893579643308693e-5, 3.4204625278143626e-5,
                                    5.8156728355576902e-5, 7.8679668816420547e-5,
                                    9.7008052543829528e-5, 1.1372585556115339e-4};
static const double seed_fmax[6] = {1521.9160892838993, 3441.1122331638547, 7709.8673680931372,
                                    12322.929545918441, 17199.324205797322, 22315.267380743067};
static const double seed_tc[6] = {1.1904584326151915e-4, 1.0399469349496538e-4,
                                  9.1181013535146273e-5, 8.4701327451018694e-5,
                                  8.0573545729318647e-5, 7.7655384043269703e-5};
static const double seed_tcomp[6] = {5.8859751374268991e-5, 5.0856853135224197e-5,
                                     4.3649774771233254e-5, 3.9721750506275539e-5,
                                     3.7040161639485758e-5, 3.5014163526885175e-5};

static hcimpact_contact steel_ball(double velocity)
{
  hcimpact_contact c;
  c.mass = 0.1;
  c.stiffness = 1.7135e10;
  c.exponent = 1.5;
  c.damping = 0.1;
  c.velocity = velocity;
  return c;
}

static int outcome_all_nan(const hcimpact_outcome *o)
{
  return isnan(o->restitution) && isnan(o->energy_loss_ratio) && isnan(o->rebound_velocity)
         && isnan(o->max_compression) && isnan(o->peak_force)
         && isnan(o->compression_at_peak_force) && isnan(o->time_at_peak_force)
         && isnan(o->compression_time)
         && isnan(o->contact_time);
}

static void test_version(void)
{
  char expected[32];
  snprintf(expected, sizeof expected, "%d.%d.%d", HCIMPACT_VERSION_MAJOR,
           HCIMPACT_VERSION_MINOR, HCIMPACT_VERSION_PATCH);
  check_true("HCIMPACT_VERSION = 10000 major + 100 minor + patch",
             HCIMPACT_VERSION == 10000 * HCIMPACT_VERSION_MAJOR + 100 * HCIMPACT_VERSION_MINOR
                                   + HCIMPACT_VERSION_PATCH);
  check_true("hcimpact_version() == header version",
             hcimpact_version() != NULL && strcmp(hcimpact_version(), expected) == 0);
  check_true("hcimpact_version_number() == HCIMPACT_VERSION",
             hcimpact_version_number() == HCIMPACT_VERSION);
  printf("hcimpact %s (%d)\n", hcimpact_version(), hcimpact_version_number());
}

static void test_status_messages(void)
{
  int i, j;
  const char *unknown = hcimpact_status_message(-1);
  check_true("message(-1) is 'unknown status code'",
             unknown != NULL && strcmp(unknown, "unknown status code") == 0);
  check_true("message(17) is unknown", strcmp(hcimpact_status_message(17), unknown) == 0);
  check_true("message(INT_MAX-ish) is unknown",
             strcmp(hcimpact_status_message(2147483647), unknown) == 0);
  check_true("message(INT_MIN-ish) is unknown",
             strcmp(hcimpact_status_message(-2147483647 - 1), unknown) == 0);
  check_true("message(0) is 'success'", strcmp(hcimpact_status_message(HCIMPACT_OK), "success") == 0);
  check_true("message(NULL) mentions NULL",
             strstr(hcimpact_status_message(HCIMPACT_ERR_NULL), "NULL") != NULL);
  check_true("message(OUT_OF_MEMORY) begins 'out of memory'",
             strncmp(hcimpact_status_message(HCIMPACT_ERR_OUT_OF_MEMORY), "out of memory", 13) == 0);
  for (i = HCIMPACT_OK; i <= HCIMPACT_ERR_OUT_OF_MEMORY; ++i) {
    const char *m = hcimpact_status_message(i);
    check_true("message is non-empty and known", m != NULL && m[0] != '\0' && strcmp(m, unknown) != 0);
    check_true("message is static (same pointer twice)", m == hcimpact_status_message(i));
    for (j = 0; j < i; ++j) {
      check_true("messages differ", strcmp(m, hcimpact_status_message(j)) != 0);
    }
  }
}

static void test_lambertw(void)
{
  const double rel = 1.0e-14;
  double z[4] = {1.0, 10.0, -0.1, -1.0};
  double w[4];
  double big = 1.0e300;

  /* mpmath at 30 digits */
  check_close("lambert_w0(1)", hcimpact_lambert_w0(1.0), 0.56714329040978387, rel);
  check_close("lambert_w0(10)", hcimpact_lambert_w0(10.0), 1.7455280027406994, rel);
  check_close("lambert_w0(-1/e)", hcimpact_lambert_w0(-0.36787944117144233), -1.0, 0.0);
  check_close("lambert_wm1(-0.1)", hcimpact_lambert_wm1(-0.1), -3.5771520639572971, rel);
  check_close("lambert_w0p1(1)", hcimpact_lambert_w0p1(1.0), 0.84140566043696064, rel);
  check_close("lambert_wm1p1(1)", hcimpact_lambert_wm1p1(1.0), -2.1461932206205826, rel);
  check_close("lambert_w0p1(1e-20)", hcimpact_lambert_w0p1(1.0e-20), 1.4142135623064284e-10, rel);
  check_true("lambert_w0p1(0) = 0", hcimpact_lambert_w0p1(0.0) == 0.0);
  check_true("lambert_w0p1(+inf) = 1", hcimpact_lambert_w0p1(INFINITY) == 1.0);
  check_true("lambert_wm1p1(+inf) = -inf", hcimpact_lambert_wm1p1(INFINITY) == -INFINITY);
  /* z = 0 of either sign is the end of the domain, W-1 -> -inf (include/hcimpact.h) */
  check_true("lambert_wm1(-0.0) = -inf", hcimpact_lambert_wm1(-0.0) == -INFINITY);
  check_true("lambert_wm1(+0.0) = -inf", hcimpact_lambert_wm1(0.0) == -INFINITY);
  check_nan("lambert_wm1(smallest subnormal > 0)", hcimpact_lambert_wm1(4.9406564584124654e-324));
  check_true("lambert_w0(huge) finite", isfinite(hcimpact_lambert_w0(big)));

  check_nan("lambert_w0(-1)", hcimpact_lambert_w0(-1.0));
  check_nan("lambert_w0(NaN)", hcimpact_lambert_w0(NAN));
  check_nan("lambert_w0(-inf)", hcimpact_lambert_w0(-INFINITY));
  check_nan("lambert_wm1(0.5)", hcimpact_lambert_wm1(0.5));
  check_nan("lambert_wm1(-1)", hcimpact_lambert_wm1(-1.0));
  check_nan("lambert_wm1(NaN)", hcimpact_lambert_wm1(NAN));
  check_nan("lambert_w0p1(-1)", hcimpact_lambert_w0p1(-1.0));
  check_nan("lambert_w0p1(NaN)", hcimpact_lambert_w0p1(NAN));
  check_nan("lambert_wm1p1(-1e-300)", hcimpact_lambert_wm1p1(-1.0e-300));
  check_nan("lambert_wm1p1(NaN)", hcimpact_lambert_wm1p1(NAN));

  /* array forms */
  check_status("lambert_w0_array", hcimpact_lambert_w0_array(4, z, w), HCIMPACT_OK);
  check_close("lambert_w0_array[0]", w[0], hcimpact_lambert_w0(1.0), 0.0);
  check_close("lambert_w0_array[2]", w[2], hcimpact_lambert_w0(-0.1), 0.0);
  check_nan("lambert_w0_array[3] (-1)", w[3]);
  check_status("lambert_wm1_array", hcimpact_lambert_wm1_array(4, z, w), HCIMPACT_OK);
  check_close("lambert_wm1_array[2]", w[2], -3.5771520639572971, rel);
  check_nan("lambert_wm1_array[0] (1)", w[0]);
  check_status("lambert_w0p1_array", hcimpact_lambert_w0p1_array(2, z, w), HCIMPACT_OK);
  check_close("lambert_w0p1_array[0]", w[0], 0.84140566043696064, rel);
  check_status("lambert_wm1p1_array", hcimpact_lambert_wm1p1_array(2, z, w), HCIMPACT_OK);
  check_close("lambert_wm1p1_array[0]", w[0], -2.1461932206205826, rel);

  w[0] = 42.0;
  check_status("lambert_w0_array(n = 0)", hcimpact_lambert_w0_array(0, z, w), HCIMPACT_ERR_SIZE);
  check_status("lambert_w0_array(n = -5)", hcimpact_lambert_w0_array(-5, z, w), HCIMPACT_ERR_SIZE);
  check_status("lambert_w0_array(z = NULL)", hcimpact_lambert_w0_array(4, NULL, w), HCIMPACT_ERR_NULL);
  check_status("lambert_w0_array(w = NULL)", hcimpact_lambert_w0_array(4, z, NULL), HCIMPACT_ERR_NULL);
  check_status("lambert_wm1_array(NULL)", hcimpact_lambert_wm1_array(1, NULL, NULL), HCIMPACT_ERR_NULL);
  check_status("lambert_w0p1_array(NULL)", hcimpact_lambert_w0p1_array(1, z, NULL), HCIMPACT_ERR_NULL);
  check_status("lambert_wm1p1_array(NULL)", hcimpact_lambert_wm1p1_array(1, NULL, w), HCIMPACT_ERR_NULL);
  check_true("nothing written on error", w[0] == 42.0);

  /* in place */
  z[0] = 1.0;
  check_status("lambert_w0_array in place", hcimpact_lambert_w0_array(1, z, z), HCIMPACT_OK);
  check_close("lambert_w0_array in place", z[0], 0.56714329040978387, rel);
}

static void test_restitution(void)
{
  const double rel = 1.0e-14;
  double beta[5] = {0.0, 0.5, 1.4327505332713750, -1.0, NAN};
  double out[5];
  double e[4] = {0.5, 1.0, 0.0, 2.0};
  double damping = 0.0;

  check_close("restitution(0.5)", hcimpact_restitution(0.5), 0.74843493159743416, rel);
  check_close("restitution(0)", hcimpact_restitution(0.0), 1.0, 0.0);
  check_true("restitution(+inf) = 0", hcimpact_restitution(INFINITY) == 0.0);
  check_close("restitution_inverse(0.5)", hcimpact_restitution_inverse(0.5), 1.4327505332713750, rel);
  check_close("restitution_inverse(0.9)", hcimpact_restitution_inverse(0.9), 0.16648195068530810, 1e-13);
  check_close("restitution_inverse(0.01)", hcimpact_restitution_inverse(0.01), 100.0, 1e-13);
  check_true("restitution_inverse(1) = 0", hcimpact_restitution_inverse(1.0) == 0.0);
  check_true("restitution_inverse(1e-310) = +inf", hcimpact_restitution_inverse(1.0e-310) == INFINITY);
  check_nan("restitution(-1)", hcimpact_restitution(-1.0));
  check_nan("restitution(NaN)", hcimpact_restitution(NAN));
  check_nan("restitution(-inf)", hcimpact_restitution(-INFINITY));
  check_nan("restitution_inverse(0)", hcimpact_restitution_inverse(0.0));
  check_nan("restitution_inverse(1.5)", hcimpact_restitution_inverse(1.5));
  check_nan("restitution_inverse(NaN)", hcimpact_restitution_inverse(NAN));

  /* 1 - k, 1 - k^2, dk/dbeta, h(u) */
  check_close("one_minus_restitution(0.5)", hcimpact_one_minus_restitution(0.5),
              1.0 - 0.74843493159743416, 1e-14);
  check_close("one_minus_restitution(1e-10)", hcimpact_one_minus_restitution(1e-10),
              2.0e-10 / 3.0, 1e-9);
  check_close("energy_loss_ratio(0.5)", hcimpact_energy_loss_ratio(0.5),
              1.0 - 0.74843493159743416 * 0.74843493159743416, 1e-14);
  check_close("restitution_derivative(0)", hcimpact_restitution_derivative(0.0), -2.0 / 3.0, 1e-15);
  {
    /* against a central difference of k */
    const double h = 1e-5;
    double fd = (hcimpact_restitution(0.5 + h) - hcimpact_restitution(0.5 - h)) / (2 * h);
    check_close("restitution_derivative(0.5) ~ finite difference",
                hcimpact_restitution_derivative(0.5), fd, 1e-8);
  }
  check_close("u_minus_log1p(1)", hcimpact_u_minus_log1p(1.0), 1.0 - log(2.0), 1e-15);
  check_close("u_minus_log1p(1e-8)", hcimpact_u_minus_log1p(1e-8), 0.5e-16, 1e-7);
  check_true("u_minus_log1p(-1) = +inf", hcimpact_u_minus_log1p(-1.0) == INFINITY);
  check_nan("u_minus_log1p(-2)", hcimpact_u_minus_log1p(-2.0));
  check_nan("one_minus_restitution(-1)", hcimpact_one_minus_restitution(-1.0));
  check_nan("energy_loss_ratio(NaN)", hcimpact_energy_loss_ratio(NAN));
  check_nan("restitution_derivative(-1)", hcimpact_restitution_derivative(-1.0));

  /* array forms */
  check_status("restitution_array", hcimpact_restitution_array(5, beta, out), HCIMPACT_OK);
  check_close("restitution_array[1]", out[1], 0.74843493159743416, rel);
  check_close("restitution_array[2]", out[2], 0.5, 1e-15);
  check_nan("restitution_array[3] (-1)", out[3]);
  check_nan("restitution_array[4] (NaN)", out[4]);
  check_status("restitution_inverse_array", hcimpact_restitution_inverse_array(4, e, out), HCIMPACT_OK);
  check_close("restitution_inverse_array[0]", out[0], 1.4327505332713750, rel);
  check_true("restitution_inverse_array[1] = 0", out[1] == 0.0);
  check_nan("restitution_inverse_array[2] (0)", out[2]);
  check_nan("restitution_inverse_array[3] (2)", out[3]);
  check_status("one_minus_restitution_array", hcimpact_one_minus_restitution_array(2, beta, out), HCIMPACT_OK);
  check_close("one_minus_restitution_array[1]", out[1], hcimpact_one_minus_restitution(0.5), 0.0);
  check_status("energy_loss_ratio_array", hcimpact_energy_loss_ratio_array(2, beta, out), HCIMPACT_OK);
  check_close("energy_loss_ratio_array[1]", out[1], hcimpact_energy_loss_ratio(0.5), 0.0);
  check_status("restitution_derivative_array", hcimpact_restitution_derivative_array(2, beta, out), HCIMPACT_OK);
  check_close("restitution_derivative_array[1]", out[1], hcimpact_restitution_derivative(0.5), 0.0);

  check_status("restitution_array(n = 0)", hcimpact_restitution_array(0, beta, out), HCIMPACT_ERR_SIZE);
  check_status("restitution_array(NULL)", hcimpact_restitution_array(5, NULL, out), HCIMPACT_ERR_NULL);
  check_status("restitution_inverse_array(NULL)", hcimpact_restitution_inverse_array(1, e, NULL), HCIMPACT_ERR_NULL);
  check_status("restitution_inverse_array(n = -1)", hcimpact_restitution_inverse_array(-1, e, out), HCIMPACT_ERR_SIZE);
  check_status("one_minus_restitution_array(NULL)", hcimpact_one_minus_restitution_array(1, NULL, out), HCIMPACT_ERR_NULL);
  check_status("energy_loss_ratio_array(NULL)", hcimpact_energy_loss_ratio_array(1, beta, NULL), HCIMPACT_ERR_NULL);
  check_status("restitution_derivative_array(NULL)", hcimpact_restitution_derivative_array(1, NULL, NULL), HCIMPACT_ERR_NULL);
  check_status("restitution_derivative_array(n = 0)", hcimpact_restitution_derivative_array(0, beta, out), HCIMPACT_ERR_SIZE);

  /* damping for a target restitution */
  check_status("damping_for_restitution(0.5, 5 m/s)",
               hcimpact_damping_for_restitution(0.5, 5.0, HCIMPACT_DEFAULT_MIN_VELOCITY, &damping),
               HCIMPACT_OK);
  check_close("damping_for_restitution(0.5, 5 m/s)", damping, 1.4327505332713750 / 5.0, rel);
  check_status("damping_for_restitution(0.5, 0 m/s)",
               hcimpact_damping_for_restitution(0.5, 0.0, 0.01, &damping), HCIMPACT_OK);
  check_close("damping_for_restitution at min_velocity", damping, 1.4327505332713750 / 0.01, rel);
  check_status("damping_for_restitution(e = 0)",
               hcimpact_damping_for_restitution(0.0, 5.0, 1e-3, &damping), HCIMPACT_ERR_RESTITUTION);
  check_nan("damping_for_restitution(e = 0) output", damping);
  check_status("damping_for_restitution(V = -1)",
               hcimpact_damping_for_restitution(0.5, -1.0, 1e-3, &damping), HCIMPACT_ERR_VELOCITY);
  check_status("damping_for_restitution(min_velocity = 0)",
               hcimpact_damping_for_restitution(0.5, 1.0, 0.0, &damping), HCIMPACT_ERR_VELOCITY);
  check_status("damping_for_restitution(NaN)",
               hcimpact_damping_for_restitution(NAN, 1.0, 1e-3, &damping), HCIMPACT_ERR_NOT_FINITE);
  check_status("damping_for_restitution(NULL)",
               hcimpact_damping_for_restitution(0.5, 1.0, 1e-3, NULL), HCIMPACT_ERR_NULL);
  /* issue 13: b beyond DBL_MAX is a status, b = 1/(e V) = 1e300 a double */
  check_status("damping_for_restitution(1e-310, 1, 1e-3)",
               hcimpact_damping_for_restitution(1e-310, 1.0, 1e-3, &damping), HCIMPACT_ERR_DOMAIN);
  check_nan("damping_for_restitution(1e-310, 1, 1e-3) output", damping);
  check_status("damping_for_restitution(0.5, 0, 1e-320)",
               hcimpact_damping_for_restitution(0.5, 0.0, 1e-320, &damping), HCIMPACT_ERR_DOMAIN);
  check_status("damping_for_restitution(1e-310, 1e10, 1e-3)",
               hcimpact_damping_for_restitution(1e-310, 1e10, 1e-3, &damping), HCIMPACT_OK);
  /* (1e-310 is a subnormal, 1e-310 * 1e10 a normal double: b = 1/(e V) as one quotient) */
  check_close("damping_for_restitution(1e-310, 1e10) = 1/(e V)", damping,
              1.0 / (1e-310 * 1e10), 4e-16);
}

static void test_two_bodies(void)
{
  double v1 = 0.0, v2 = 0.0;
  double c = hcimpact_hertz_constant(2e11, 0.25, 0.01452, 2e11, 0.25, INFINITY);

  check_close("hertz_constant(steel ball on plate)", c, 1.7138e10, 1e-4);
  check_close("hertz_constant symmetric",
              hcimpact_hertz_constant(2e11, 0.25, INFINITY, 2e11, 0.25, 0.01452), c, 1e-15);
  check_nan("hertz_constant(E = 0)", hcimpact_hertz_constant(0.0, 0.25, 0.01, 2e11, 0.25, 0.01));
  check_nan("hertz_constant(nu = 0.6)", hcimpact_hertz_constant(2e11, 0.6, 0.01, 2e11, 0.25, 0.01));
  check_nan("hertz_constant(two plates)",
            hcimpact_hertz_constant(2e11, 0.25, INFINITY, 2e11, 0.25, INFINITY));
  check_nan("hertz_constant(R = -1)", hcimpact_hertz_constant(2e11, 0.25, -1.0, 2e11, 0.25, 0.01));
  check_nan("hertz_constant(NaN)", hcimpact_hertz_constant(NAN, 0.25, 0.01, 2e11, 0.25, 0.01));

  /* issue 13, item 13: a subnormal radius made 1/R overflow and c come out as 0 */
  check_close("hertz_constant(R2 = 5e-324)",
              hcimpact_hertz_constant(2e11, 0.25, 0.01452, 2e11, 0.25, 5e-324),
              3.161256888156555e-151, 1e-15);
  /* item 27: nu near -1 (auxetic): 1 - nu^2 cancelled (6.2e3 ulp) */
  check_close("hertz_constant(nu near -1)",
              hcimpact_hertz_constant(2e11, -0.9999999, 0.01452, 2e11, -0.9999999999, INFINITY),
              1.6050478684445405e+17, 1e-15);

  check_close("effective_mass(1, 1)", hcimpact_effective_mass(1.0, 1.0), 0.5, 1e-15);
  /* item 8: m1/m2 overflowed and the effective mass came out as 0 */
  check_close("effective_mass(1e300, 1e-20)", hcimpact_effective_mass(1e300, 1e-20), 1e-20, 1e-15);
  check_close("effective_mass(DBL_MAX, 0.5)", hcimpact_effective_mass(DBL_MAX, 0.5), 0.5, 1e-15);
  check_close("effective_mass(1, 1e-310)", hcimpact_effective_mass(1.0, 1e-310), 1e-310, 1e-15);
  check_close("effective_mass(0.1, inf)", hcimpact_effective_mass(0.1, INFINITY), 0.1, 0.0);
  check_nan("effective_mass(0, 1)", hcimpact_effective_mass(0.0, 1.0));
  check_nan("effective_mass(1, NaN)", hcimpact_effective_mass(1.0, NAN));

  check_status("two_body_velocities", hcimpact_two_body_velocities(1.0, 1.0, 1.0, -1.0, 0.5, &v1, &v2),
               HCIMPACT_OK);
  /* equal masses, V = 2, k = 0.5: exchange (1 + k) V/2 = 1.5 */
  check_close("two_body_velocities v1'", v1, -0.5, 1e-15);
  check_close("two_body_velocities v2'", v2, 0.5, 1e-15);
  check_status("two_body_velocities(m2 = inf)",
               hcimpact_two_body_velocities(0.1, INFINITY, 5.0, 0.0, 0.75, &v1, &v2), HCIMPACT_OK);
  check_close("two_body_velocities wall v1'", v1, -3.75, 1e-15);
  check_true("two_body_velocities wall v2' = 0", v2 == 0.0);
  /* item 7: m1/m2 or v1 - v2 overflowed, and the velocities came out NaN or inf */
  check_status("two_body_velocities(1e300, 1e-300)",
               hcimpact_two_body_velocities(1e300, 1e-300, 1.0, 0.0, 1.0, &v1, &v2), HCIMPACT_OK);
  check_close("two_body_velocities(1e300, 1e-300) v1'", v1, 1.0, 1e-15);
  check_close("two_body_velocities(1e300, 1e-300) v2'", v2, 2.0, 1e-15);
  check_status("two_body_velocities(1, 5e-324)",
               hcimpact_two_body_velocities(1.0, 5e-324, 1.0, 0.0, 0.5, &v1, &v2), HCIMPACT_OK);
  check_close("two_body_velocities(1, 5e-324) v1'", v1, 1.0, 1e-15);
  check_close("two_body_velocities(1, 5e-324) v2'", v2, 1.5, 1e-15);
  check_status("two_body_velocities(DBL_MAX, -DBL_MAX)",
               hcimpact_two_body_velocities(1.0, 1.0, DBL_MAX, -DBL_MAX, 0.5, &v1, &v2), HCIMPACT_OK);
  check_close("two_body_velocities(DBL_MAX, -DBL_MAX) v1'", v1, -0.5 * DBL_MAX, 1e-15);
  check_close("two_body_velocities(DBL_MAX, -DBL_MAX) v2'", v2, 0.5 * DBL_MAX, 1e-15);
  check_status("two_body_velocities(no approach)",
               hcimpact_two_body_velocities(1.0, 1.0, -1.0, 1.0, 0.5, &v1, &v2), HCIMPACT_ERR_VELOCITY);
  check_nan("two_body_velocities(no approach) v1'", v1);
  check_status("two_body_velocities(m1 = 0)",
               hcimpact_two_body_velocities(0.0, 1.0, 1.0, -1.0, 0.5, &v1, &v2), HCIMPACT_ERR_MASS);
  check_status("two_body_velocities(k = 2)",
               hcimpact_two_body_velocities(1.0, 1.0, 1.0, -1.0, 2.0, &v1, &v2), HCIMPACT_ERR_RESTITUTION);
  check_status("two_body_velocities(NaN)",
               hcimpact_two_body_velocities(1.0, 1.0, NAN, -1.0, 0.5, &v1, &v2), HCIMPACT_ERR_NOT_FINITE);
  check_status("two_body_velocities(NULL)",
               hcimpact_two_body_velocities(1.0, 1.0, 1.0, -1.0, 0.5, NULL, &v2), HCIMPACT_ERR_NULL);
  check_status("two_body_velocities(NULL 2)",
               hcimpact_two_body_velocities(1.0, 1.0, 1.0, -1.0, 0.5, &v1, NULL), HCIMPACT_ERR_NULL);
}

/* The power law f = c x^1.5 of the steel ball, given as callbacks; data points at c */
static double cb_force(double x, void *data) { return *(const double *)data * pow(x, 1.5); }
static double cb_potential(double x, void *data)
{
  return *(const double *)data * pow(x, 2.5) / 2.5;
}
static double cb_derivative(double x, void *data)
{
  return 1.5 * *(const double *)data * sqrt(x);
}
static double cb_nan(double x, void *data)
{
  (void)x;
  (void)data;
  return NAN;
}

static void test_impact_law(void)
{
  double c = 1.7135e10;
  hcimpact_elastic_law law;
  hcimpact_outcome outcome, reference;
  hcimpact_contact contact = steel_ball(2.0);

  law.force = cb_force;
  law.potential = cb_potential;
  law.force_derivative = cb_derivative;
  law.data = &c;
  check_status("impact(steel ball, V = 2)", hcimpact_impact(&contact, &reference), HCIMPACT_OK);
  check_status("impact_law(power law)", hcimpact_impact_law(&law, 0.1, 0.1, 2.0, &outcome),
               HCIMPACT_OK);
  check_close("impact_law k", outcome.restitution, reference.restitution, 1e-14);
  check_close("impact_law x_max", outcome.max_compression, reference.max_compression, 1e-12);
  check_close("impact_law F_max", outcome.peak_force, reference.peak_force, 1e-12);
  check_close("impact_law t_contact", outcome.contact_time, reference.contact_time, 1e-12);
  check_status("impact_law(NULL law)", hcimpact_impact_law(NULL, 0.1, 0.1, 2.0, &outcome),
               HCIMPACT_ERR_NULL);
  check_status("impact_law(NULL outcome)", hcimpact_impact_law(&law, 0.1, 0.1, 2.0, NULL),
               HCIMPACT_ERR_NULL);
  law.potential = NULL;
  check_status("impact_law(NULL callback)", hcimpact_impact_law(&law, 0.1, 0.1, 2.0, &outcome),
               HCIMPACT_ERR_NULL);
  law.potential = cb_potential;
  check_status("impact_law(mass < 0)", hcimpact_impact_law(&law, -0.1, 0.1, 2.0, &outcome),
               HCIMPACT_ERR_MASS);
  check_nan("impact_law(mass < 0) k", outcome.restitution);
  law.force = cb_nan;
  check_status("impact_law(NaN force)", hcimpact_impact_law(&law, 0.1, 0.1, 2.0, &outcome),
               HCIMPACT_ERR_ELASTIC_LAW);
  /* issue 13: the peak of a law through callbacks at large and tiny scales (m = 1e300 gave
     2.0e155 N, b = 1e-300 gave 4.3e-87 N) agrees with the power law */
  law.force = cb_force;
  contact.mass = 1e300;
  contact.velocity = 5.0;
  check_status("impact(m = 1e300)", hcimpact_impact(&contact, &reference), HCIMPACT_OK);
  check_status("impact_law(m = 1e300)", hcimpact_impact_law(&law, 1e300, 0.1, 5.0, &outcome),
               HCIMPACT_OK);
  check_close("impact_law(m = 1e300) F_max", outcome.peak_force, reference.peak_force, 1e-14);
  contact.mass = 0.1;
  contact.damping = 1e-300;
  check_status("impact(b = 1e-300)", hcimpact_impact(&contact, &reference), HCIMPACT_OK);
  check_status("impact_law(b = 1e-300)", hcimpact_impact_law(&law, 0.1, 1e-300, 5.0, &outcome),
               HCIMPACT_OK);
  check_close("impact_law(b = 1e-300) F_max", outcome.peak_force, reference.peak_force, 1e-14);
  check_close("impact_law(b = 1e-300) time of the peak", outcome.time_at_peak_force,
              reference.time_at_peak_force, 1e-14);
}

static void test_impact(void)
{
  const double rel = 1.0e-13;
  int i;
  hcimpact_contact contact, contacts[8];
  hcimpact_outcome outcome, outcomes[8];
  int statuses[8];

  for (i = 0; i < 6; ++i) {
    contact = steel_ball(seed_v[i]);
    check_status("impact(steel ball)", hcimpact_impact(&contact, &outcome), HCIMPACT_OK);
    check_close("impact k", outcome.restitution, seed_k[i], rel);
    check_close("impact 1 - k^2", outcome.energy_loss_ratio, 1.0 - seed_k[i] * seed_k[i], 1e-12);
    check_close("impact rebound velocity", outcome.rebound_velocity, -seed_k[i] * seed_v[i], rel);
    check_close("impact x_max", outcome.max_compression, seed_xmax[i], rel);
    check_close("impact F_max", outcome.peak_force, seed_fmax[i], rel);
    check_true("impact x at F_max in (0, x_max)",
               outcome.compression_at_peak_force > 0.0
                   && outcome.compression_at_peak_force < outcome.max_compression);
    check_true("impact t at F_max in (0, t_compression)",
               outcome.time_at_peak_force > 0.0
                   && outcome.time_at_peak_force < outcome.compression_time);
    check_close("impact t_compression", outcome.compression_time, seed_tcomp[i], rel);
    check_close("impact t_contact", outcome.contact_time, seed_tc[i], rel);
  }
  /* b = 0 at V = 1 (MODEL.md) */
  contact = steel_ball(1.0);
  contact.damping = 0.0;
  check_status("impact(b = 0)", hcimpact_impact(&contact, &outcome), HCIMPACT_OK);
  {
    /* issue 13: the steel ball at V = 1e40 (beta = 1e39) had a compression time of 0 */
    hcimpact_contact fast = steel_ball(1e40);
    hcimpact_outcome o;
    check_status("impact(V = 1e40)", hcimpact_impact(&fast, &o), HCIMPACT_OK);
    check_close("impact(V = 1e40) compression time", o.compression_time, 4.270256913017152e-27,
                1e-15);
    check_close("impact(V = 1e40) time of the peak", o.time_at_peak_force, 8.95173406821078e-29,
                1e-15);
  }
  check_close("impact(b = 0) k", outcome.restitution, 1.0, 0.0);
  check_close("impact(b = 0) x_max", outcome.max_compression, 3.5092181079293274e-5, rel);
  check_close("impact(b = 0) t_contact", outcome.contact_time, 1.0328594573451282e-4, rel);
  check_close("impact(b = 0) F_max", outcome.peak_force, 3562.0470473908028, rel);

  /* every invalid field */
  {
    struct {
      const char *what;
      int field;
      double value;
      int status;
    } bad[] = {
        {"mass = 0", 0, 0.0, HCIMPACT_ERR_MASS},
        {"mass = -1", 0, -1.0, HCIMPACT_ERR_MASS},
        {"mass = NaN", 0, NAN, HCIMPACT_ERR_NOT_FINITE},
        {"stiffness = 0", 1, 0.0, HCIMPACT_ERR_STIFFNESS},
        {"stiffness = inf", 1, INFINITY, HCIMPACT_ERR_NOT_FINITE},
        {"exponent = 0", 2, 0.0, HCIMPACT_ERR_EXPONENT},
        {"exponent = -1.5", 2, -1.5, HCIMPACT_ERR_EXPONENT},
        {"exponent below HCIMPACT_MIN_EXPONENT", 2, 0.5 * HCIMPACT_MIN_EXPONENT,
         HCIMPACT_ERR_EXPONENT},
        {"damping = -0.1", 3, -0.1, HCIMPACT_ERR_DAMPING},
        {"damping = NaN", 3, NAN, HCIMPACT_ERR_NOT_FINITE},
        {"velocity = 0", 4, 0.0, HCIMPACT_ERR_VELOCITY},
        {"velocity = -1", 4, -1.0, HCIMPACT_ERR_VELOCITY},
        {"velocity = -inf", 4, -INFINITY, HCIMPACT_ERR_NOT_FINITE},
        {"damping = 1e300, velocity 1e300", 3, 1e300, HCIMPACT_ERR_DOMAIN},
    };
    for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); ++i) {
      char what[96];
      contact = steel_ball(1.0);
      if (bad[i].status == HCIMPACT_ERR_DOMAIN) contact.velocity = 1e300;
      switch (bad[i].field) {
      case 0: contact.mass = bad[i].value; break;
      case 1: contact.stiffness = bad[i].value; break;
      case 2: contact.exponent = bad[i].value; break;
      case 3: contact.damping = bad[i].value; break;
      default: contact.velocity = bad[i].value; break;
      }
      snprintf(what, sizeof what, "impact(%s)", bad[i].what);
      check_status(what, hcimpact_impact(&contact, &outcome), bad[i].status);
      check_true("impact error: outcome all NaN", outcome_all_nan(&outcome));
    }
  }
  check_true("hcimpact_contact is five doubles", sizeof(hcimpact_contact) == 5 * sizeof(double));
  check_true("hcimpact_outcome is nine doubles", sizeof(hcimpact_outcome) == 9 * sizeof(double));

  contact = steel_ball(1.0);
  outcome.restitution = 42.0;
  check_status("impact(NULL, outcome)", hcimpact_impact(NULL, &outcome), HCIMPACT_ERR_NULL);
  check_status("impact(contact, NULL)", hcimpact_impact(&contact, NULL), HCIMPACT_ERR_NULL);
  check_true("impact(NULL): outcome untouched", outcome.restitution == 42.0);

  /* array form: the seed table plus two bad contacts */
  for (i = 0; i < 6; ++i) contacts[i] = steel_ball(seed_v[i]);
  contacts[6] = steel_ball(1.0);
  contacts[6].mass = -1.0;
  contacts[7] = steel_ball(1.0);
  contacts[7].damping = -1.0;
  check_status("impact_array (two bad)", hcimpact_impact_array(8, contacts, outcomes, statuses),
               HCIMPACT_ERR_MASS);
  for (i = 0; i < 6; ++i) {
    check_status("impact_array status", statuses[i], HCIMPACT_OK);
    check_close("impact_array k", outcomes[i].restitution, seed_k[i], rel);
    check_close("impact_array t_contact", outcomes[i].contact_time, seed_tc[i], rel);
  }
  check_status("impact_array status[6]", statuses[6], HCIMPACT_ERR_MASS);
  check_status("impact_array status[7]", statuses[7], HCIMPACT_ERR_DAMPING);
  check_true("impact_array failed outcome NaN", outcome_all_nan(&outcomes[7]));
  check_status("impact_array (statuses NULL)", hcimpact_impact_array(6, contacts, outcomes, NULL),
               HCIMPACT_OK);
  check_close("impact_array (statuses NULL) x_max", outcomes[5].max_compression, seed_xmax[5], rel);
  check_status("impact_array(n = 0)", hcimpact_impact_array(0, contacts, outcomes, statuses),
               HCIMPACT_ERR_SIZE);
  check_status("impact_array(contacts NULL)", hcimpact_impact_array(1, NULL, outcomes, statuses),
               HCIMPACT_ERR_NULL);
  check_status("impact_array(outcomes NULL)", hcimpact_impact_array(1, contacts, NULL, statuses),
               HCIMPACT_ERR_NULL);
}

static void test_trajectory(void)
{
  const double rel = 1.0e-12;
  hcimpact_contact contact = steel_ball(5.0), bad = steel_ball(5.0);
  hcimpact_outcome outcome;
  double v = 0.0, xs[3], vs[3], t[5], x[5], xd[5], f[5];
  int i;

  bad.exponent = 0.0;
  check_status("impact(V = 5)", hcimpact_impact(&contact, &outcome), HCIMPACT_OK);

  /* velocity at a depth */
  check_status("velocity_at_depth(0, compression)",
               hcimpact_velocity_at_depth(&contact, 0.0, HCIMPACT_COMPRESSION_BRANCH, &v), HCIMPACT_OK);
  check_true("velocity_at_depth(0, compression) = V exactly", v == 5.0);
  check_status("velocity_at_depth(0, restitution)",
               hcimpact_velocity_at_depth(&contact, 0.0, HCIMPACT_RESTITUTION_BRANCH, &v), HCIMPACT_OK);
  check_true("velocity_at_depth(0, restitution) = -k V exactly", v == outcome.rebound_velocity);
  /* issue 13: n = DBL_MAX gave HCIMPACT_OK with NaN */
  bad.exponent = DBL_MAX;
  i = hcimpact_velocity_at_depth(&bad, 1e-5, HCIMPACT_COMPRESSION_BRANCH, &v);
  check_true("velocity_at_depth(n = DBL_MAX): a status or a finite velocity",
             (i != HCIMPACT_OK && isnan(v)) || (i == HCIMPACT_OK && isfinite(v)));
  bad.exponent = 0.0;
  check_status("velocity_at_depth(x_max)",
               hcimpact_velocity_at_depth(&contact, outcome.max_compression,
                                          HCIMPACT_COMPRESSION_BRANCH, &v), HCIMPACT_OK);
  check_true("velocity_at_depth(x_max) ~ 0", fabs(v) < 1e-6);
  check_status("velocity_at_depth(2 x_max)",
               hcimpact_velocity_at_depth(&contact, 2.0 * outcome.max_compression,
                                          HCIMPACT_COMPRESSION_BRANCH, &v), HCIMPACT_ERR_DOMAIN);
  check_nan("velocity_at_depth(2 x_max) output", v);
  check_status("velocity_at_depth(x = -1e-9)",
               hcimpact_velocity_at_depth(&contact, -1e-9, HCIMPACT_COMPRESSION_BRANCH, &v), HCIMPACT_ERR_DOMAIN);
  check_status("velocity_at_depth(x = NaN)",
               hcimpact_velocity_at_depth(&contact, NAN, HCIMPACT_COMPRESSION_BRANCH, &v), HCIMPACT_ERR_NOT_FINITE);
  check_status("velocity_at_depth(branch = 3)",
               hcimpact_velocity_at_depth(&contact, 0.0, 3, &v), HCIMPACT_ERR_DOMAIN);
  check_status("velocity_at_depth(bad contact)",
               hcimpact_velocity_at_depth(&bad, 0.0, HCIMPACT_COMPRESSION_BRANCH, &v), HCIMPACT_ERR_EXPONENT);
  check_status("velocity_at_depth(NULL contact)",
               hcimpact_velocity_at_depth(NULL, 0.0, HCIMPACT_COMPRESSION_BRANCH, &v), HCIMPACT_ERR_NULL);
  check_status("velocity_at_depth(NULL velocity)",
               hcimpact_velocity_at_depth(&contact, 0.0, HCIMPACT_COMPRESSION_BRANCH, NULL), HCIMPACT_ERR_NULL);

  xs[0] = 0.0;
  xs[1] = 0.5 * outcome.max_compression;
  xs[2] = outcome.max_compression;
  check_status("velocity_at_depth_array",
               hcimpact_velocity_at_depth_array(&contact, 3, xs, HCIMPACT_RESTITUTION_BRANCH, vs), HCIMPACT_OK);
  check_close("velocity_at_depth_array[0]", vs[0], outcome.rebound_velocity, rel);
  check_true("velocity_at_depth_array[1] in (-kV, 0)", vs[1] < 0.0 && vs[1] > outcome.rebound_velocity);
  xs[2] = -1.0;
  check_status("velocity_at_depth_array (x < 0)",
               hcimpact_velocity_at_depth_array(&contact, 3, xs, HCIMPACT_RESTITUTION_BRANCH, vs), HCIMPACT_ERR_DOMAIN);
  check_true("velocity_at_depth_array error: all NaN", isnan(vs[0]) && isnan(vs[1]) && isnan(vs[2]));
  check_status("velocity_at_depth_array(n = 0)",
               hcimpact_velocity_at_depth_array(&contact, 0, xs, 1, vs), HCIMPACT_ERR_SIZE);
  check_status("velocity_at_depth_array(NULL x)",
               hcimpact_velocity_at_depth_array(&contact, 3, NULL, 1, vs), HCIMPACT_ERR_NULL);
  check_status("velocity_at_depth_array(NULL v)",
               hcimpact_velocity_at_depth_array(&contact, 3, xs, 1, NULL), HCIMPACT_ERR_NULL);
  check_status("velocity_at_depth_array(NULL contact)",
               hcimpact_velocity_at_depth_array(NULL, 3, xs, 1, vs), HCIMPACT_ERR_NULL);

  /* time law */
  t[0] = -1.0;
  t[1] = outcome.compression_time;
  t[2] = 0.5 * outcome.contact_time;
  t[3] = 2.0 * outcome.contact_time;
  t[4] = 0.0;
  check_status("time_law", hcimpact_time_law(&contact, 5, t, x, xd, f), HCIMPACT_OK);
  check_true("time_law before contact: x = 0, x' = V, F = 0", x[0] == 0.0 && xd[0] == 5.0 && f[0] == 0.0);
  check_close("time_law at t_compression: x = x_max", x[1], outcome.max_compression, 1e-10);
  check_true("time_law at t_compression: x' ~ 0", fabs(xd[1]) < 1e-5);
  check_true("time_law mid-contact: 0 < x < x_max", x[2] > 0.0 && x[2] < outcome.max_compression);
  check_true("time_law mid-contact: 0 < F <= F_max", f[2] > 0.0 && f[2] <= outcome.peak_force);
  check_true("time_law after contact: x = 0, F = 0", x[3] == 0.0 && f[3] == 0.0);
  check_close("time_law after contact: x' = -k V", xd[3], outcome.rebound_velocity, rel);
  check_true("time_law at t = 0: x = 0", x[4] == 0.0);
  t[2] = NAN;
  check_status("time_law (t NaN)", hcimpact_time_law(&contact, 5, t, x, xd, f), HCIMPACT_ERR_NOT_FINITE);
  check_true("time_law (t NaN): outputs NaN", isnan(x[0]) && isnan(xd[4]) && isnan(f[1]));
  check_status("time_law (bad contact)", hcimpact_time_law(&bad, 2, t, x, xd, f), HCIMPACT_ERR_EXPONENT);
  check_status("time_law (n = 0)", hcimpact_time_law(&contact, 0, t, x, xd, f), HCIMPACT_ERR_SIZE);
  check_status("time_law (NULL t)", hcimpact_time_law(&contact, 1, NULL, x, xd, f), HCIMPACT_ERR_NULL);
  check_status("time_law (NULL x)", hcimpact_time_law(&contact, 1, t, NULL, xd, f), HCIMPACT_ERR_NULL);
  check_status("time_law (NULL v)", hcimpact_time_law(&contact, 1, t, x, NULL, f), HCIMPACT_ERR_NULL);
  check_status("time_law (NULL f)", hcimpact_time_law(&contact, 1, t, x, xd, NULL), HCIMPACT_ERR_NULL);
  check_status("time_law (NULL contact)", hcimpact_time_law(NULL, 1, t, x, xd, f), HCIMPACT_ERR_NULL);
  /* in place: the times array doubles as the compressions */
  t[0] = outcome.compression_time;
  check_status("time_law in place", hcimpact_time_law(&contact, 1, t, t, xd, f), HCIMPACT_OK);
  check_close("time_law in place: x = x_max", t[0], outcome.max_compression, 1e-10);

  check_status("time_law_samples", hcimpact_time_law_samples(&contact, 5, t, x, xd, f), HCIMPACT_OK);
  check_true("time_law_samples t[0] = 0", t[0] == 0.0);
  check_close("time_law_samples t[4] = contact time", t[4], outcome.contact_time, 0.0);
  for (i = 1; i < 5; ++i) check_true("time_law_samples increasing", t[i] > t[i - 1]);
  check_true("time_law_samples x[0] = 0", x[0] == 0.0);
  check_close("time_law_samples v[0] = V", xd[0], 5.0, rel);
  /* issue 13: the contact is over at the contact time of hcimpact_impact */
  check_true("time_law_samples x[4] = F[4] = 0, v[4] = -k V",
             x[4] == 0.0 && f[4] == 0.0 && xd[4] == outcome.rebound_velocity);
  t[0] = outcome.contact_time;
  check_status("time_law(contact time)", hcimpact_time_law(&contact, 1, t, x, xd, f), HCIMPACT_OK);
  check_true("time_law(contact time): x = F = 0", x[0] == 0.0 && f[0] == 0.0);
  check_status("time_law_samples (n = 1)", hcimpact_time_law_samples(&contact, 1, t, x, xd, f), HCIMPACT_ERR_SIZE);
  check_status("time_law_samples (bad contact)", hcimpact_time_law_samples(&bad, 5, t, x, xd, f), HCIMPACT_ERR_EXPONENT);
  check_true("time_law_samples (bad contact): NaN", isnan(t[0]) && isnan(x[4]) && isnan(f[2]));
  check_status("time_law_samples (NULL t)", hcimpact_time_law_samples(&contact, 2, NULL, x, xd, f), HCIMPACT_ERR_NULL);
  check_status("time_law_samples (NULL f)", hcimpact_time_law_samples(&contact, 2, t, x, xd, NULL), HCIMPACT_ERR_NULL);
  check_status("time_law_samples (NULL contact)", hcimpact_time_law_samples(NULL, 2, t, x, xd, f), HCIMPACT_ERR_NULL);
}

/* The contact-force element through C: the formula of the header at ordinary states,
 * the clamp, no contact, the array, pair and wall forms, bad input and NULL. */
static void test_contact_force(void)
{
  const double c = 1.7135e10, n = 1.5, b = 0.1;
  double x = 5.0e-5, v = 2.0, f0 = c * pow(x, n);
  double cs[3] = {c, c, -1.0}, ns[3] = {n, n, n}, bs[3] = {b, b, b};
  double xs[3] = {x, -1.0e-6, x}, vs[3] = {v, v, v};
  hcimpact_force f, many[3], pair, wall;
  int statuses[3];

  check_true("hcimpact_force is five doubles", sizeof(hcimpact_force) == 5 * sizeof(double));
  check_status("contact_force", hcimpact_contact_force(c, n, b, x, v, &f), HCIMPACT_OK);
  check_close("contact_force F", f.force, f0 * (1.0 + b * v), 1e-14);
  check_close("contact_force dF/dx", f.dforce_dx, n * f0 / x * (1.0 + b * v), 1e-14);
  check_close("contact_force dF/dv", f.dforce_dv, b * f0, 1e-14);
  check_close("contact_force potential", f.potential, f0 * x / (n + 1.0), 1e-14);
  check_close("contact_force dissipation", f.dissipation, b * f0 * v * v, 1e-14);
  /* separating faster than 1/b: clamped, the dissipation -f(x) v */
  check_status("contact_force clamped", hcimpact_contact_force(c, n, b, x, -20.0, &f),
               HCIMPACT_OK);
  check_true("clamped: no force", f.force == 0.0 && f.dforce_dx == 0.0 && f.dforce_dv == 0.0);
  check_close("clamped dissipation", f.dissipation, 20.0 * f0, 1e-14);
  check_status("contact_force apart", hcimpact_contact_force(c, n, b, -x, v, &f), HCIMPACT_OK);
  check_true("apart: all zero", f.force == 0.0 && f.potential == 0.0 && f.dissipation == 0.0);
  check_status("contact_force(n < 1e-6)", hcimpact_contact_force(c, 1e-7, b, x, v, &f),
               HCIMPACT_ERR_EXPONENT);
  check_true("bad exponent: NaN", isnan(f.force) && isnan(f.dissipation));
  check_status("contact_force(v NaN)", hcimpact_contact_force(c, n, b, x, NAN, &f),
               HCIMPACT_ERR_NOT_FINITE);
  check_status("contact_force(NULL)", hcimpact_contact_force(c, n, b, x, v, NULL),
               HCIMPACT_ERR_NULL);
  check_status("contact_force_array", hcimpact_contact_force_array(3, cs, ns, bs, xs, vs,
               many, statuses), HCIMPACT_ERR_STIFFNESS);
  check_true("array statuses", statuses[0] == HCIMPACT_OK && statuses[1] == HCIMPACT_OK
             && statuses[2] == HCIMPACT_ERR_STIFFNESS);
  check_close("array F", many[0].force, f0 * (1.0 + b * v), 1e-14);
  check_true("array: apart, bad", many[1].force == 0.0 && isnan(many[2].force));
  check_status("contact_force_array(n = 0)", hcimpact_contact_force_array(0, cs, ns, bs, xs,
               vs, many, NULL), HCIMPACT_ERR_SIZE);
  check_status("contact_force_array(NULL)", hcimpact_contact_force_array(3, cs, ns, NULL,
               xs, vs, many, NULL), HCIMPACT_ERR_NULL);
  /* two balls of radius 1 cm at 1 m from the origin, overlapping by x */
  check_status("contact_force_pair", hcimpact_contact_force_pair(c, n, b, 0.02, 1.0, 1.5,
               1.02 - x, -0.5, &pair), HCIMPACT_OK);
  check_close("pair F", pair.force, f0 * (1.0 + b * v), 1e-9);
  check_status("contact_force_wall", hcimpact_contact_force_wall(c, n, b, 0.01, 1.0 + x,
               v, 1.01, 1, &wall), HCIMPACT_OK);
  check_close("wall F", wall.force, f0 * (1.0 + b * v), 1e-9);
  check_status("contact_force_wall(side 0)", hcimpact_contact_force_wall(c, n, b, 0.01,
               1.0, v, 1.01, 0, &wall), HCIMPACT_ERR_DOMAIN);
}

int main(void)
{
  test_version();
  test_status_messages();
  test_lambertw();
  test_restitution();
  test_two_bodies();
  test_impact();
  test_impact_law();
  test_trajectory();
  test_contact_force();

  if (failures > 0) {
    printf("%d of %d checks failed\n", failures, checks);
    return 1;
  }
  printf("all %d checks passed\n", checks);
  return 0;
}
