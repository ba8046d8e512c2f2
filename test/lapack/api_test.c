/* SPDX-License-Identifier: Apache-2.0 */
/* The C entry points of the calibration component (include/hcimpact_lapack.h),
 * called from plain C. Data: the seed's steel ball (doc/model.md), from the core's hcimpact_restitution and from Hertz's
 * closed forms (b = 0). */
#include <math.h>
#include <stdio.h>
#include <stddef.h>

#include "hcimpact_lapack.h"

#define NPOINTS 10

static int failures = 0;

static void check_status(const char *what, int actual, int expected)
{
  if (actual != expected) {
    printf("FAIL %s: status %d, expected %d\n", what, actual, expected);
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

static void check_nan(const char *what, double actual)
{
  if (!isnan(actual)) {
    printf("FAIL %s: %.17g, expected NaN\n", what, actual);
    ++failures;
  }
}

int main(void)
{
  const double mass = 0.1, c = 1.7135e10, n = 1.5, b = 0.1;
  /* t_c = const x_max / V for b = 0, n = 3/2 (MODEL.md) */
  const double hertz_time = 2.9432751843247047;
  double v[NPOINTS], e[NPOINTS], x[NPOINTS], f[NPOINTS], t[NPOINTS], fm[NPOINTS];
  double one[NPOINTS], residuals[3 * NPOINTS], parameters[3], covariance[9];
  double damping, standard_error;
  int i;

  for (i = 0; i < NPOINTS; ++i) {
    double xmax;
    v[i] = 0.5 + 0.5 * i;
    e[i] = hcimpact_restitution(b * v[i]);
    one[i] = 1.0;
    x[i] = 2.0e-6 * pow(50.0, i / (NPOINTS - 1.0));
    f[i] = c * pow(x[i], n);
    xmax = pow((n + 1.0) * mass * v[i] * v[i] / (2.0 * c), 1.0 / (n + 1.0));
    t[i] = hertz_time * xmax / v[i];
    fm[i] = c * pow(xmax, n);
  }

  /* damping, exact and linear law */
  check_status("fit_damping", hcimpact_fit_damping(NPOINTS, v, e, NULL, 0, &damping,
                                                   &standard_error, residuals), HCIMPACT_OK);
  check_close("fit_damping b", damping, b, 1e-14);
  check_close("fit_damping residual", residuals[3] + 1.0, 1.0, 1e-15);
  check_status("fit_damping, optional outputs NULL",
               hcimpact_fit_damping(NPOINTS, v, e, NULL, 0, &damping, NULL, NULL), HCIMPACT_OK);
  check_status("fit_damping_linear", hcimpact_fit_damping_linear(NPOINTS, v, e, NULL, 0,
                                                                 &damping, NULL, NULL),
               HCIMPACT_OK);
  check_close("fit_damping_linear b", damping, 0.07982680592763838, 1e-12);

  /* static curve */
  check_status("fit_static", hcimpact_fit_static(NPOINTS, x, f, NULL, 0, parameters,
                                                 covariance, residuals), HCIMPACT_OK);
  check_close("fit_static c", parameters[0], c, 1e-12);
  check_close("fit_static n", parameters[1], n, 1e-13);
  check_close("fit_static covariance symmetric", covariance[1], covariance[2], 1e-12);

  /* elastic law from Hertz's impacts, b = 0 */
  check_status("fit_elastic", hcimpact_fit_elastic(NPOINTS, mass, 0.0, v, t, fm, NULL, NULL,
                                                   0, NULL, parameters, covariance, residuals),
               HCIMPACT_OK);
  check_close("fit_elastic c", parameters[0], c, 1e-11);
  check_close("fit_elastic n", parameters[1], n, 1e-12);

  /* joint fit: the same impacts with e = 1 give b = 0 */
  check_status("fit_impact", hcimpact_fit_impact(NPOINTS, mass, v, t, fm, one, NULL, NULL, NULL,
                                                 0, NULL, parameters, covariance, residuals),
               HCIMPACT_OK);
  check_close("fit_impact c", parameters[0], c, 1e-11);
  check_close("fit_impact n", parameters[1], n, 1e-12);
  check_close("fit_impact b", parameters[2] + 1.0, 1.0, 1e-12);

  /* errors, the header's rule: a NULL or a size error writes nothing; any other
     error sets every output given to NaN */
  damping = standard_error = 42.0;
  parameters[0] = parameters[1] = covariance[0] = residuals[0] = 42.0;
  check_status("fit_damping, velocity NULL",
               hcimpact_fit_damping(NPOINTS, NULL, e, NULL, 0, &damping, &standard_error,
                                    residuals), HCIMPACT_ERR_NULL);
  check_status("fit_damping_linear, npoints -1",
               hcimpact_fit_damping_linear(-1, v, e, NULL, 0, &damping, &standard_error,
                                           residuals), HCIMPACT_ERR_SIZE);
  check_status("fit_static, force NULL",
               hcimpact_fit_static(NPOINTS, x, NULL, NULL, 0, parameters, covariance, residuals),
               HCIMPACT_ERR_NULL);
  check_status("fit_elastic, npoints -1",
               hcimpact_fit_elastic(-1, mass, 0.0, v, t, fm, NULL, NULL, 0, NULL, parameters,
                                    covariance, residuals), HCIMPACT_ERR_SIZE);
  check_status("fit_impact, velocity NULL",
               hcimpact_fit_impact(NPOINTS, mass, NULL, t, fm, one, NULL, NULL, NULL, 0, NULL,
                                   parameters, covariance, residuals), HCIMPACT_ERR_NULL);
  check_status("fit_impact, npoints too large for the residual count",
               hcimpact_fit_impact(2147483647, mass, v, t, fm, one, NULL, NULL, NULL, 0, NULL,
                                   parameters, covariance, residuals), HCIMPACT_ERR_SIZE);
  if (!(damping == 42.0 && standard_error == 42.0 && parameters[0] == 42.0
        && parameters[1] == 42.0 && covariance[0] == 42.0 && residuals[0] == 42.0)) {
    printf("FAIL NULL and size errors wrote an output\n");
    ++failures;
  }
  /* a NaN deflection: HCIMPACT_ERR_NOT_FINITE (not HCIMPACT_ERR_DOMAIN), outputs NaN */
  {
    double bad = x[3];
    x[3] = NAN;
    check_status("fit_static, NaN deflection",
                 hcimpact_fit_static(NPOINTS, x, f, NULL, 0, parameters, covariance, residuals),
                 HCIMPACT_ERR_NOT_FINITE);
    x[3] = bad;
    check_nan("fit_static c after NaN", parameters[0]);
    check_nan("fit_static covariance after NaN", covariance[3]);
    check_nan("fit_static residual after NaN", residuals[NPOINTS - 1]);
  }
  e[2] = NAN;
  check_status("fit_damping, NaN restitution",
               hcimpact_fit_damping(NPOINTS, v, e, NULL, 0, &damping, &standard_error, NULL),
               HCIMPACT_ERR_NOT_FINITE);
  e[2] = hcimpact_restitution(b * v[2]);
  check_nan("fit_damping b after NaN", damping);
  check_nan("fit_damping standard error after NaN", standard_error);
  for (i = 0; i < NPOINTS; ++i) v[i] = 2.0;
  check_status("fit_elastic, times at one speed",
               hcimpact_fit_elastic(NPOINTS, mass, 0.0, v, t, NULL, NULL, NULL, 0, NULL,
                                    parameters, covariance, residuals),
               HCIMPACT_ERR_UNDERDETERMINED);
  check_nan("fit_elastic c after error", parameters[0]);
  check_nan("fit_elastic covariance after error", covariance[3]);
  check_nan("fit_elastic residual after error", residuals[NPOINTS - 1]);

  if (failures > 0) {
    printf("%d check(s) failed\n", failures);
    return 1;
  }
  printf("calibration C API: all checks passed\n");
  return 0;
}
