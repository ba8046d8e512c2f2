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
 * components/cvode/solver.f90; doc/cvode.md. Systems of bodies on a line
 * (hcimpact_chain_simulate): components/cvode/chain_api.f90, the structures'
 * conversions in components/cvode/chain_capi_types.f90; doc/chains.md, doc/c-api.md.
 */
#ifndef HCIMPACT_CVODE_H
#define HCIMPACT_CVODE_H

#include <stddef.h>
#include <stdint.h>

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

/* ------------------------------------------------------------------------
 * Systems of bodies on a line (doc/chains.md)
 * ------------------------------------------------------------------------ */

/** Methods of hcimpact_chain_options.method: decide per contact (the closed forms of
 *  one impact where contacts are isolated, CVODE for clusters of overlapping ones;
 *  the default, 0), the closed forms only (a cluster is HCIMPACT_ERR_DOMAIN),
 *  or CVODE for the whole system from the start. */
#define HCIMPACT_CHAIN_AUTO 0
#define HCIMPACT_CHAIN_EXACT 1      /**< see HCIMPACT_CHAIN_AUTO */
#define HCIMPACT_CHAIN_INTEGRATED 2 /**< see HCIMPACT_CHAIN_AUTO */

/** CVODE's multistep method (hcimpact_chain_options.integrator; 0: BDF). */
#define HCIMPACT_CHAIN_BDF 1
#define HCIMPACT_CHAIN_ADAMS 2 /**< see HCIMPACT_CHAIN_BDF */

/** How a contact was computed (hcimpact_chain_contact.method), and which ways a run
 *  used (hcimpact_chain_result.method_used: BY_BOTH when some contacts were computed
 *  each way; BY_CLOSED_FORMS also when there was no contact at all). */
#define HCIMPACT_CHAIN_BY_CLOSED_FORMS 1
#define HCIMPACT_CHAIN_BY_INTEGRATION 2 /**< see HCIMPACT_CHAIN_BY_CLOSED_FORMS */
#define HCIMPACT_CHAIN_BY_BOTH 3        /**< see HCIMPACT_CHAIN_BY_CLOSED_FORMS */

/** The contact law of one pair of neighbours, f = c x^n (1 + b x'): stiffness c in
 *  N/m^n (> 0), exponent n (>= 1e-6; 1.5: Hertz), damping b in s/m (>= 0); the rules
 *  of hcimpact_impact. */
typedef struct {
  double stiffness; /**< c in N/m^n, > 0 */
  double exponent;  /**< n, >= 1e-6 (1.5: Hertz) */
  double damping;   /**< b in s/m, >= 0 */
} hcimpact_chain_law;

/** A fixed wall at one end: its contact law with the end body, as
 *  hcimpact_chain_law, and the gap between them in m (>= 0; 0: touching). */
typedef struct {
  double stiffness; /**< c in N/m^n, > 0 */
  double exponent;  /**< n, >= 1e-6 */
  double damping;   /**< b in s/m, >= 0 */
  double gap;       /**< gap to the end body in m, >= 0 */
} hcimpact_chain_wall;

/** How to compute a system. A structure of zeros (hcimpact_chain_options o = {0};)
 *  or a NULL pointer means every default. */
typedef struct {
  double t_end;       /**< end time in s; <= 0: until no contact can happen again */
  double rtol;        /**< CVODE's relative tolerance in (0, 0.01]; 0: 1e-10 */
  int64_t max_steps;  /**< most integration steps, all clusters together; 0: 1e8 */
  int64_t max_events; /**< most contacts computed before giving up; 0: 1e8 */
  int method;         /**< HCIMPACT_CHAIN_AUTO (0), _EXACT or _INTEGRATED */
  int integrator;     /**< HCIMPACT_CHAIN_BDF (or 0) or HCIMPACT_CHAIN_ADAMS */
} hcimpact_chain_options;

/** What a run computed besides the arrays. Energies in J, times in s. */
typedef struct {
  double time;                  /**< time reached: t_end, the time after which no
                                     contact can happen, or when the system came to rest */
  double rest_time;             /**< when it came to rest on a wall (NaN if not) */
  double initial_energy;        /**< initial kinetic energy */
  double energy_error;          /**< |kinetic + elastic + gravitational + dissipated -
                                     initial| relative to the initial energy */
  double dissipated;            /**< energy dissipated in the contacts up to time (also
                                     by those still in progress) */
  double momentum_error;        /**< relative error of the momentum against the
                                     initial one plus the outside impulses: gravity's
                                     M g t and the walls' */
  double wall_impulse_left;     /**< impulse the left wall gave the system up to
                                     time, N s along the line (>= 0; 0 without it) */
  double wall_impulse_right;    /**< the right wall's (<= 0; 0 without it) */
  int64_t n_contacts;           /**< every contact that ended, also beyond
                                     contact_capacity */
  int64_t contacts_recorded;    /**< contacts written: min(n_contacts, capacity) */
  int64_t closed_form_contacts; /**< contacts computed by the closed forms, also one
                                     still in progress at t_end (so it can exceed
                                     n_contacts, which counts those that ended) */
  int64_t integrated_contacts;  /**< contacts computed (in part) by CVODE */
  int64_t steps;                /**< CVODE's steps, all clusters together */
  int64_t rhs_evals;            /**< right-hand side evaluations */
  int64_t jacobian_evals;       /**< band Jacobians */
  int64_t roots;                /**< contact starts and ends located in steps */
  int64_t clusters;             /**< clusters integrated */
  int method_used;              /**< HCIMPACT_CHAIN_BY_* */
  int rested;                   /**< 1: came to rest on a wall under gravity */
} hcimpact_chain_result;

/** One contact from its start to its end. Pairs are numbered 0 to n: pair 0 is the
 *  left wall and the first body (masses[0]), pair p (1 <= p <= n - 1) the bodies
 *  masses[p - 1] and masses[p] (gap gaps[p - 1], law laws[p - 1]), pair n the last
 *  body and the right wall: pair p is the contact on the left of body p counted
 *  from 0. */
typedef struct {
  double t_start;          /**< start, s */
  double t_end;            /**< end, s */
  double approach_speed;   /**< relative speed at the start, m/s (>= 0) */
  double separation_speed; /**< relative speed at the end, m/s (>= 0) */
  double peak_force;       /**< largest force, N */
  double max_deformation;  /**< largest deformation, m */
  double dissipated;       /**< energy dissipated in the contact, J */
  int pair;                /**< 0 .. n, as above */
  int method;              /**< HCIMPACT_CHAIN_BY_CLOSED_FORMS or _BY_INTEGRATION */
} hcimpact_chain_contact;

/** Samples of the motion at given times. The arrays are the caller's, stored sample
 *  after sample: positions[j * n + i] is body i at times[j]; forces[j * (n + 1) + p]
 *  is the force of pair p (0 for a missing wall). Each output may be NULL (not
 *  written). */
typedef struct {
  int count;                 /**< number of times, >= 0 */
  const double *times;       /**< [count], s, not decreasing, >= 0 */
  double *positions;         /**< [count * n], m */
  double *velocities;        /**< [count * n], m/s */
  double *forces;            /**< [count * (n + 1)], N */
} hcimpact_chain_samples;

/** A caller's watch over a long run (hcimpact_chain_simulate_monitored): the poll is
 *  called from the run's loop every 64 passes (a pass is one integration step of a
 *  cluster, one event of the closed forms or switch of method, or the samples due)
 *  with `data`, the time the run has reached (s), the integration steps and the
 *  events so far (what max_events bounds: the starts and ends of the contacts the
 *  closed forms compute and the switches of method; the contacts inside an
 *  integrated cluster are not events); a nonzero return stops the run there with HCIMPACT_ERR_NO_CONVERGENCE
 *  (the message begins "stopped by the caller's monitor"). Use it to show progress,
 *  to keep a deadline, or to stop a run from another thread through a flag that data
 *  points to. poll runs in the calling thread, must not call back into this run, and
 *  must be safe to call from every thread that runs a simulation with it. */
typedef int (*hcimpact_chain_poll)(void *data, double time, int64_t steps, int64_t events);

/** The monitor of hcimpact_chain_simulate_monitored: its poll and the caller's data. */
typedef struct {
  hcimpact_chain_poll poll; /**< the caller's function (required) */
  void *data;               /**< handed back to every call of poll */
} hcimpact_chain_monitor;

/** A system of n bodies on a line, bodies numbered left to right (masses[0] the
 *  leftmost), velocities positive to the right: the closed forms of one impact
 *  wherever a contact is isolated, CVODE (band Jacobian, O(n) per step) for the
 *  clusters where contacts overlap (doc/chains.md for the model, the decision and
 *  the accuracy).
 *
 *  Positions: the bodies are points whose distance is the surface gap; initially
 *  the first is at 0 and body i + 1 at body i's position + gaps[i] (0: touching
 *  without preload). The left wall stands at -left_wall->gap, the right one at the
 *  last body's position + right_wall->gap. gravity is the constant acceleration of
 *  every body along the line in m/s^2 (negative: to the left, e.g. -9.81 for a
 *  stack standing on a left wall as its floor).
 *
 *  Memory: every array is the caller's; the library allocates nothing that
 *  outlives the call and keeps no state, so calls may run in several threads at
 *  once. Inputs: masses[n] (kg, > 0), velocities[n] (m/s), gaps[n - 1] (m, >= 0)
 *  and laws[n - 1] (both may be NULL when n = 1); left_wall, right_wall: NULL for
 *  none; options: NULL for the defaults. Outputs: *result (required);
 *  positions[n] and final_velocities[n] at result->time (each may be NULL);
 *  contacts[contact_capacity]: the first contact_capacity contacts in the order
 *  they ended (result->contacts_recorded of them; one still in progress at t_end is
 *  not listed); result->n_contacts counts them all, so a caller who needs every contact and gave too small an array calls again
 *  with contact_capacity = n_contacts (the run is deterministic: the same input
 *  gives the same contacts); contact_capacity 0 and contacts NULL record none.
 *  samples: NULL for none. message: "success" or what went wrong (e.g. "gap 3 is
 *  negative ...", "CVODE failed at t = ...: CV_TOO_MUCH_WORK"), cut to message_size
 *  bytes and NUL-terminated (NULL or 0: nothing written; 256 bytes hold every
 *  message).
 *
 *  Returns HCIMPACT_OK (0), or:
 *  HCIMPACT_ERR_NULL (10)   result, masses or velocities NULL; gaps or laws NULL
 *                           with n > 1; contacts NULL with a capacity above 0;
 *                           samples->times NULL with count > 0 (nothing written
 *                           but the message),
 *  HCIMPACT_ERR_SIZE (14)   n < 1, contact_capacity < 0, samples->count < 0
 *                           (nothing written but the message); sample times that
 *                           decrease,
 *  HCIMPACT_ERR_OUT_OF_MEMORY (16) the system is too large for the memory available
 *                           (the message, "out of memory (...): ...", names what did
 *                           not fit: the library's copies, the engine's arrays, a
 *                           cluster's arrays or CVODE's; the outputs as after the
 *                           errors below),
 *  HCIMPACT_ERR_NOT_FINITE (1), _MASS (2), _STIFFNESS (3), _EXPONENT (4),
 *  _DAMPING (6)             a NaN or infinite value, a mass or a law out of range,
 *  HCIMPACT_ERR_DOMAIN (8)  a negative gap (bodies may touch, not overlap), gaps
 *                           or masses that add up beyond a quarter of the range,
 *                           method HCIMPACT_CHAIN_EXACT meeting a cluster, a
 *                           position or velocity beyond the range at the end, a
 *                           contact whose damping times approach speed is above
 *                           1e40 (HCIMPACT_MAX_BETA, as for one impact), a contact
 *                           whose compression, duration or force leaves the range
 *                           of doubles, rtol
 *                           outside (0, 0.01], an unknown method or integrator,
 *                           negative limits, negative sample times, t_end
 *                           unset (<= 0) for a system that never ends (bodies
 *                           between two walls without gravity, or an undamped
 *                           system falling onto a wall),
 *  HCIMPACT_ERR_SOLVER (11) CVODE failed (the message names its flag), or an
 *                           integration ended with its energy or momentum balance
 *                           off by more than max(1/2, 1e4 rtol) of its scale
 *                           (scales that CVODE does not resolve; "did not resolve"),
 *  HCIMPACT_ERR_NO_CONVERGENCE (9) more than max_events contacts or max_steps
 *                           steps (a ball that would bounce for ever: give t_end).
 *  After an error other than NULL and SIZE for a size every real of *result is NaN,
 *  its counts 0, and every output array NaN (the contacts are not written). */
HCIMPACT_API int hcimpact_chain_simulate(int n, const double *masses, const double *velocities,
                                         const double *gaps, const hcimpact_chain_law *laws,
                                         const hcimpact_chain_wall *left_wall,
                                         const hcimpact_chain_wall *right_wall, double gravity,
                                         const hcimpact_chain_options *options,
                                         hcimpact_chain_result *result, double *positions,
                                         double *final_velocities, int contact_capacity,
                                         hcimpact_chain_contact *contacts,
                                         hcimpact_chain_samples *samples, char *message,
                                         size_t message_size);

/** hcimpact_chain_simulate with a monitor: the same arguments, statuses and outputs,
 *  and `monitor` (NULL: none, the same run as hcimpact_chain_simulate) whose poll may
 *  stop the run (HCIMPACT_ERR_NO_CONVERGENCE, the outputs as after any error). A
 *  monitor whose poll is NULL gives HCIMPACT_ERR_NULL (nothing written but the
 *  message). A monitor that never stops the run does not change its results. */
HCIMPACT_API int hcimpact_chain_simulate_monitored(
    int n, const double *masses, const double *velocities, const double *gaps,
    const hcimpact_chain_law *laws, const hcimpact_chain_wall *left_wall,
    const hcimpact_chain_wall *right_wall, double gravity, const hcimpact_chain_options *options,
    hcimpact_chain_result *result, double *positions, double *final_velocities,
    int contact_capacity, hcimpact_chain_contact *contacts, hcimpact_chain_samples *samples,
    const hcimpact_chain_monitor *monitor, char *message, size_t message_size);

#ifdef __cplusplus
}
#endif

#endif /* HCIMPACT_CVODE_H */
