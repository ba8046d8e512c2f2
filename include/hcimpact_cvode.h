/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file hcimpact_cvode.h
 * @brief C interface of the CVODE component of hcimpact: the impact integrated as an ODE.
 *
 * Part of the optional component libhcimpact_cvode: link it (CMake: hcimpact::cvode,
 * which brings the SUNDIALS libraries; pkg-config: hcimpact-cvode) as well as
 * libhcimpact. A program linked with the core alone gets an undefined reference to
 * hcimpact_simulate at link time; there is no stub in the core. The conventions (units,
 * statuses, thread safety) are those of hcimpact.h, which this header includes.
 * Fortran: components/cvode/api.f90 (module hcimpact_cvode_api), physics in
 * components/cvode/solver.f90; doc/cvode.md.
 */
#ifndef HCIMPACT_CVODE_H
#define HCIMPACT_CVODE_H

#include <stddef.h>

#include "hcimpact.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The impact of hcimpact_impact integrated by SUNDIALS CVODE (BDF, dense Newton
 *  with the analytic Jacobian, root finding for x' = 0, dF/dt = 0 and x = 0) in
 *  the scaled variables x/X, t V/X, with the relative tolerance rtol and absolute
 *  tolerances rtol times the natural scale of each variable. Measured on the
 *  benchmark contacts (doc/cvode.md): the contact time within 50 rtol, the other
 *  fields within about 250 rtol, for rtol from 1e-4 to 1e-11; far below 1e-13
 *  CVODE gives up (HCIMPACT_ERR_SOLVER, CV_TOO_MUCH_ACC). On success, as for the
 *  exact model, 0 < restitution <= 1 and 0 <= energy_loss_ratio <= 1: where the
 *  solver's k comes out above 1 (b V small against rtol; b = 0 gives k - 1 of
 *  some rtol either side), k = 1, no energy lost and rebound -V are reported,
 *  never further from the exact values than the solver's (the Fortran interface
 *  keeps the solver's k: solver_restitution, restitution_clamped). Thread-safe.
 *  Returns 0 (HCIMPACT_OK) on success; otherwise a status and, except for
 *  HCIMPACT_ERR_NULL, every field of *outcome is NaN:
 *  the input errors of hcimpact_impact (1 to 6),
 *  HCIMPACT_ERR_NOT_FINITE (1)   rtol is NaN or infinite,
 *  HCIMPACT_ERR_DOMAIN (8)       rtol outside (0, 1); b V above about 1e140 (the
 *                                absolute tolerance of x' would fall below
 *                                1e-150); exponent above 100; scales outside
 *                                the double range,
 *  HCIMPACT_ERR_NO_CONVERGENCE (9) the contact did not end in time (not seen),
 *  HCIMPACT_ERR_NULL (10)        contact or outcome is NULL (nothing written),
 *  HCIMPACT_ERR_SOLVER (11)      CVODE failed (hcimpact_simulate_message below
 *                                says how: its flag name, e.g. CV_TOO_MUCH_WORK). */
HCIMPACT_API int hcimpact_simulate(const hcimpact_contact *contact, double rtol,
                                   hcimpact_outcome *outcome);

/** hcimpact_simulate with the reason of a failure in words: the same integration,
 *  outcome and statuses, and in `message` (message_size bytes, always
 *  NUL-terminated when message_size >= 1, cut to fit) "success" or what went wrong:
 *  for HCIMPACT_ERR_SOLVER CVODE's flag name, the time it failed at and CVODE's own
 *  message, e.g. "CVODE failed at t = ... s: CV_TOO_MUCH_ACC (...)"; for the other
 *  statuses the reason, as far as the solver knows it, else hcimpact_status_message.
 *  message may be NULL (with any message_size): nothing is written to it. The buffer
 *  is the caller's, so this stays thread-safe (no "last error" state). 256 bytes
 *  hold every message the library writes today. */
HCIMPACT_API int hcimpact_simulate_message(const hcimpact_contact *contact, double rtol,
                                           hcimpact_outcome *outcome, char *message,
                                           size_t message_size);

#ifdef __cplusplus
}
#endif

#endif /* HCIMPACT_CVODE_H */
