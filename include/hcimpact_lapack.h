/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file hcimpact_lapack.h
 * @brief C interface of the LAPACK component of hcimpact: calibration of the model.
 *
 * Fit the model to measured data. Part of the optional component libhcimpact_lapack:
 * link it (CMake: hcimpact::lapack, which brings LAPACK; pkg-config: hcimpact-lapack)
 * as well as libhcimpact. The conventions (units, statuses, thread safety) are those
 * of hcimpact.h, which this header includes. Fortran:
 * components/lapack/calibration.f90 (module hcimpact_calibration), C wrappers
 * components/lapack/calibration_api.f90; doc/calibration.md.
 *
 * Common rules:
 * - Arrays hold npoints doubles unless said otherwise. An array marked
 *   "or NULL" is optional; any other NULL pointer gives HCIMPACT_ERR_NULL.
 * - sigma arrays are standard deviations in the units of the data (s, N, or
 *   dimensionless for restitution). NULL: the series' scatter is estimated
 *   from its residuals (for a fit of several series, each its own).
 * - absolute_sigma != 0: the sigmas are the true ones and the covariance is
 *   (J^T W J)^-1; 0: it is rescaled by chi^2/(N - p).
 * - covariance is p x p (symmetric, so row- or column-major alike).
 * - Residuals are ln(observed/model) for times and forces, observed - model
 *   for restitution, unweighted; several series are stored one after the
 *   other in the order time, force, restitution (only those given).
 * - Returns 0 (HCIMPACT_OK) or a status. HCIMPACT_ERR_NULL and
 *   HCIMPACT_ERR_SIZE write nothing (the rule of the whole interface); on any
 *   other error every output that is not NULL is set to NaN:
 *   HCIMPACT_ERR_NOT_FINITE (1)     a NaN or infinite value,
 *   HCIMPACT_ERR_MASS (2)           mass <= 0,
 *   HCIMPACT_ERR_VELOCITY (5)       a speed <= 0,
 *   HCIMPACT_ERR_DAMPING (6)        a given damping < 0,
 *   HCIMPACT_ERR_RESTITUTION (7)    a restitution <= 0 or > 2 (values in
 *                                   (1, 2], noise, are allowed),
 *   HCIMPACT_ERR_DOMAIN (8)         another value <= 0 (deflection, force,
 *                                   time, sigma, guess), or a sigma beyond
 *                                   1e100 times its value (1 for restitution),
 *   HCIMPACT_ERR_NO_CONVERGENCE (9) the iteration did not converge,
 *   HCIMPACT_ERR_NULL (10)          a required pointer is NULL,
 *   HCIMPACT_ERR_SIZE (14)          npoints < 0, npoints above INT_MAX/2
 *                                   (fit_elastic) or INT_MAX/3 (fit_impact),
 *   HCIMPACT_ERR_UNDERDETERMINED (15) the data cannot determine the
 *                                   parameters: fewer observations than
 *                                   parameters + 1, or too little variation
 *                                   (e.g. contact times at a single speed),
 *   HCIMPACT_ERR_OUT_OF_MEMORY (16) too many points for the memory the fit
 *                                   needs (its copies and work arrays; the
 *                                   outputs NaN).
 */
#ifndef HCIMPACT_LAPACK_H
#define HCIMPACT_LAPACK_H

#include "hcimpact.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Damping b (s/m) from restitution e_i measured at approach speeds V_i,
 *  with the exact law e = k(b V) (nonlinear least squares). npoints >= 2;
 *  the speeds may all be equal. b >= 0 (e = 1 everywhere gives 0).
 *  standard_error and residuals (e_i - k(b V_i)) may be NULL. */
HCIMPACT_API int hcimpact_fit_damping(int npoints, const double *velocity,
                                      const double *restitution, const double *sigma,
                                      int absolute_sigma, double *damping,
                                      double *standard_error, double *residuals);

/** The common linear law e = 1 - alpha V, returned as b = 3 alpha / 2 (s/m),
 *  the small-beta slope of the exact law, for comparison: on data following
 *  the exact law it is biased low (20 % for the seed's steel ball at
 *  0.5...5 m/s). Residuals e_i - (1 - alpha V_i). Same arguments as
 *  hcimpact_fit_damping. */
HCIMPACT_API int hcimpact_fit_damping_linear(int npoints, const double *velocity,
                                             const double *restitution, const double *sigma,
                                             int absolute_sigma, double *damping,
                                             double *standard_error, double *residuals);

/** Elastic law F = c x^n from a static force-deflection curve: weighted
 *  linear least squares on ln F = ln c + n ln x. npoints >= 3 at two or more
 *  different deflections. sigma (N) or NULL (equal relative errors).
 *  parameters[2] = {c in N/m^n, n}; covariance[4] or NULL; residuals
 *  (ln F_i - ln(c x_i^n)) or NULL. */
HCIMPACT_API int hcimpact_fit_static(int npoints, const double *deflection,
                                     const double *force, const double *sigma,
                                     int absolute_sigma, double parameters[2],
                                     double covariance[4], double *residuals);

/** Elastic law (c, n) from impact data, the damping b (s/m, >= 0) known:
 *  contact times (s) and/or peak forces (N) measured at approach speeds V_i
 *  (m/s) on a body of mass `mass` (kg). Either series may be NULL, not both;
 *  one series needs two or more different speeds, both together determine
 *  (c, n) even at one speed. guess[2] = {c, n} or NULL (from the data).
 *  parameters[2] = {c in N/m^n, n}; covariance[4] or NULL; residuals
 *  (npoints per series given) or NULL. */
HCIMPACT_API int hcimpact_fit_elastic(int npoints, double mass, double damping,
                                      const double *velocity, const double *contact_time,
                                      const double *peak_force, const double *sigma_time,
                                      const double *sigma_force, int absolute_sigma,
                                      const double guess[2], double parameters[2],
                                      double covariance[4], double *residuals);

/** Joint fit of (c, n, b) to impact data: contact times (s), peak forces (N)
 *  and restitution measured at approach speeds V_i (m/s), mass in kg. Any
 *  series may be NULL if the others still determine the three parameters.
 *  guess[3] = {c, n, b} or NULL. parameters[3] = {c in N/m^n, n, b in s/m};
 *  covariance[9] or NULL; residuals (npoints per series given) or NULL. */
HCIMPACT_API int hcimpact_fit_impact(int npoints, double mass, const double *velocity,
                                     const double *contact_time, const double *peak_force,
                                     const double *restitution, const double *sigma_time,
                                     const double *sigma_force,
                                     const double *sigma_restitution, int absolute_sigma,
                                     const double guess[3], double parameters[3],
                                     double covariance[9], double *residuals);

#ifdef __cplusplus
}
#endif

#endif /* HCIMPACT_LAPACK_H */
