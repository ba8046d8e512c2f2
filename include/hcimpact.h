/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file hcimpact.h
 * @brief C interface of hcimpact, the Hunt-Crossley model of a collinear impact.
 *
 * All quantities are in SI units. Functions that return a double answer NaN
 * for an argument outside their domain or for NaN; they never abort.
 */
#ifndef HCIMPACT_H
#define HCIMPACT_H

#define HCIMPACT_VERSION_MAJOR 0
#define HCIMPACT_VERSION_MINOR 1
#define HCIMPACT_VERSION_PATCH 0
/** Version as one integer: 10000*major + 100*minor + patch */
#define HCIMPACT_VERSION 100

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------
 * Lambert W, real branches
 * ------------------------------------------------------------------------ */

/** Principal branch W0(z), z >= -1/e. Returns W0 in [-1, inf).
 *  The double nearest to -1/e lies just below -1/e (by 1.2e-17): it and every
 *  z down to -1/e - 2^-54 return -1 exactly (the branch point, which is what a
 *  rounded -1/e stands for); z further below, and NaN, return NaN. */
double hcimpact_lambert_w0(double z);

/** Lower branch W-1(z), -1/e <= z < 0. Returns W-1 in (-inf, -1].
 *  Same treatment of the doubles just below -1/e as hcimpact_lambert_w0;
 *  z >= 0, z below the branch point, and NaN return NaN. z = -0.0 returns -inf. */
double hcimpact_lambert_wm1(double z);

/** 1 + W0(-exp(-1 - t)) for t >= 0, computed from t (no loss near t = 0).
 *  Lies in [0, 1); equals sqrt(2t) - 2t/3 + ... for small t. t < 0 or NaN: NaN;
 *  t = +inf: 1. */
double hcimpact_lambert_w0p1(double t);

/** 1 + W-1(-exp(-1 - t)) for t >= 0, computed from t (no loss near t = 0).
 *  Lies in (-inf, 0]; equals -sqrt(2t) - 2t/3 - ... for small t. t < 0 or NaN:
 *  NaN; t = +inf: -inf. */
double hcimpact_lambert_wm1p1(double t);

/* ------------------------------------------------------------------------
 * Restitution of the Hunt-Crossley impact (depends on beta = b V only)
 * ------------------------------------------------------------------------ */

/** Coefficient of restitution k(beta) = -V+/V- for beta = b V- >= 0
 *  (damping b in s/m times approach speed V- in m/s). k(0) = 1, k ~ 1/beta for
 *  large beta, k(+inf) = 0. Within 2 ulp of the exact value. beta < 0 or NaN: NaN. */
double hcimpact_restitution(double beta);

/** The exact inverse: beta >= 0 with k(beta) = e, for 0 < e <= 1 (then b = beta/V-).
 *  beta(1) = 0; within 4 ulp. e outside (0, 1] or NaN: NaN; e below 1/DBL_MAX
 *  (where beta would exceed DBL_MAX): +inf. */
double hcimpact_restitution_inverse(double e);

#ifdef __cplusplus
}
#endif

#endif /* HCIMPACT_H */
