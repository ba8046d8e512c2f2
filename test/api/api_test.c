/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Test of the C interface of hcimpact from a plain C program: the header
 * compiles as C99, the version macros agree, and every exported function is
 * reachable and returns the right value (checked loosely here; accuracy is the
 * business of the Fortran unit tests) or NaN outside its domain.
 *
 * Exit status 0 on success, 1 if any check failed.
 */
#include <math.h>
#include <stdio.h>

#include "hcimpact.h"

static int failures = 0;

/* |actual - expected| <= rel * |expected|; NaN never passes */
static void check_close(const char *what, double actual, double expected, double rel)
{
  if (isnan(actual) || !(fabs(actual - expected) <= rel * fabs(expected))) {
    printf("FAIL %-28s got %.17g, expected %.17g\n", what, actual, expected);
    ++failures;
  } else {
    printf("ok   %-28s %.17g\n", what, actual);
  }
}

static void check_nan(const char *what, double actual)
{
  if (!isnan(actual)) {
    printf("FAIL %-28s got %.17g, expected NaN\n", what, actual);
    ++failures;
  } else {
    printf("ok   %-28s NaN\n", what);
  }
}

int main(void)
{
  const double rel = 1.0e-13;

  if (HCIMPACT_VERSION != 10000 * HCIMPACT_VERSION_MAJOR + 100 * HCIMPACT_VERSION_MINOR
        + HCIMPACT_VERSION_PATCH) {
    printf("FAIL HCIMPACT_VERSION %d does not match %d.%d.%d\n", HCIMPACT_VERSION,
           HCIMPACT_VERSION_MAJOR, HCIMPACT_VERSION_MINOR, HCIMPACT_VERSION_PATCH);
    ++failures;
  }

  /* Reference values from mpmath at 30 digits. */
  check_close("lambert_w0(1)", hcimpact_lambert_w0(1.0), 0.56714329040978387, rel);
  check_close("lambert_w0(10)", hcimpact_lambert_w0(10.0), 1.7455280027406994, rel);
  check_close("lambert_wm1(-0.1)", hcimpact_lambert_wm1(-0.1), -3.5771520639572971, rel);
  check_close("lambert_w0p1(1)", hcimpact_lambert_w0p1(1.0), 0.84140566043696064, rel);
  check_close("lambert_wm1p1(1)", hcimpact_lambert_wm1p1(1.0), -2.1461932206205826, rel);

  check_nan("lambert_w0(-1)", hcimpact_lambert_w0(-1.0));
  check_nan("lambert_w0(NaN)", hcimpact_lambert_w0(NAN));
  check_nan("lambert_wm1(0.5)", hcimpact_lambert_wm1(0.5));
  check_nan("lambert_w0p1(-1)", hcimpact_lambert_w0p1(-1.0));
  check_nan("lambert_wm1p1(NaN)", hcimpact_lambert_wm1p1(NAN));

  /* Restitution (MODEL.md: the seed's steel ball at V = 5 m/s has beta = 0.5) */
  check_close("restitution(0.5)", hcimpact_restitution(0.5), 0.74843493159743416, rel);
  check_close("restitution(0)", hcimpact_restitution(0.0), 1.0, 0.0);
  check_close("restitution_inverse(0.5)", hcimpact_restitution_inverse(0.5), 1.4327505332713750,
              rel);
  check_close("restitution_inverse(1)", hcimpact_restitution_inverse(1.0) + 1.0, 1.0, 0.0);
  check_nan("restitution(-1)", hcimpact_restitution(-1.0));
  check_nan("restitution(NaN)", hcimpact_restitution(NAN));
  check_nan("restitution_inverse(0)", hcimpact_restitution_inverse(0.0));
  check_nan("restitution_inverse(1.5)", hcimpact_restitution_inverse(1.5));

  if (failures > 0) {
    printf("%d check(s) failed\n", failures);
    return 1;
  }
  printf("all checks passed\n");
  return 0;
}
