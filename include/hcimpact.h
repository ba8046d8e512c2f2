/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file hcimpact.h
 * @brief C interface of hcimpact, the Hunt-Crossley model of a collinear impact.
 *
 * The model: m x'' = -c x^n (1 + b x'), x(0) = 0, x'(0) = V > 0 (a body of mass m
 * strikes a fixed obstacle with the speed V; x is the compression). Everything is in
 * SI units: kg, m, s, N, Pa. See doc/c-api.md for a tour and the link lines.
 *
 * Conventions (the same for every function below):
 *  - A function that returns a double answers NaN for an argument outside its domain
 *    or for NaN; it has no other way to fail and never aborts.
 *  - Every other function returns an int status: HCIMPACT_OK (0) or one of the
 *    HCIMPACT_ERR_* codes below (hcimpact_status_message() gives its text).
 *    A NULL pointer for a required argument gives HCIMPACT_ERR_NULL, a size out of
 *    range HCIMPACT_ERR_SIZE (below 1 unless a function says otherwise); then
 *    nothing is written. On any other error every output is NaN.
 *  - A function that allocates memory sized by its arguments (the time law, the fits,
 *    a system of bodies, a sweep) returns HCIMPACT_ERR_OUT_OF_MEMORY when the memory
 *    available cannot hold it: valid arguments, too large for this machine (never an
 *    abort). Its outputs are then NaN unless the function says otherwise.
 *  - Array ("_array") forms take the number of elements n and plain arrays of n
 *    elements; an output array may be the input array itself (computed in place),
 *    other overlaps are not allowed. In a library built with OpenMP, large arrays
 *    are shared among OMP_NUM_THREADS threads (hcimpact_array_threads()); the
 *    results and the status (that of the lowest failing index) are those of a
 *    serial run, bit for bit.
 *  - The library keeps no state: every function may be called from several threads
 *    at once, and no function allocates memory that the caller must free.
 *
 * Link: -lhcimpact (pkg-config --libs hcimpact). The optional components are
 * declared in hcimpact_cvode.h (the ODE path, -lhcimpact_cvode) and
 * hcimpact_lapack.h (calibration, -lhcimpact_lapack).
 */
#ifndef HCIMPACT_H
#define HCIMPACT_H

#define HCIMPACT_VERSION_MAJOR 0 /**< major version of this header */
#define HCIMPACT_VERSION_MINOR 2 /**< minor version of this header */
#define HCIMPACT_VERSION_PATCH 0 /**< patch level of this header */
/** Version as one integer: 10000*major + 100*minor + patch
 *  (hcimpact_version_number() returns that of the library at run time) */
#define HCIMPACT_VERSION 200

/** HCIMPACT_API marks every function of the library (and of its components): the
 *  default symbol visibility with GCC and Clang, __declspec(dllimport) on Windows
 *  when the library is a DLL (define HCIMPACT_SHARED there; the CMake package does).
 *  Define HCIMPACT_API yourself before including the header to override it. */
#ifndef HCIMPACT_API
#if defined(_WIN32) && defined(HCIMPACT_SHARED)
#define HCIMPACT_API __declspec(dllimport)
#elif defined(__GNUC__) && __GNUC__ >= 4
#define HCIMPACT_API __attribute__((visibility("default")))
#else
#define HCIMPACT_API
#endif
#endif

/* ------------------------------------------------------------------------
 * Status codes (src/hcimpact/status.f90)
 * ------------------------------------------------------------------------ */

#define HCIMPACT_OK 0                   /**< success */
#define HCIMPACT_ERR_NOT_FINITE 1       /**< an argument is NaN or infinite */
#define HCIMPACT_ERR_MASS 2             /**< mass is zero or negative */
#define HCIMPACT_ERR_STIFFNESS 3        /**< stiffness (contact constant c) is not positive */
#define HCIMPACT_ERR_EXPONENT 4         /**< exponent n of the elastic law is out of range */
#define HCIMPACT_ERR_VELOCITY 5         /**< approach velocity is zero or negative */
#define HCIMPACT_ERR_DAMPING 6          /**< damping b is negative */
#define HCIMPACT_ERR_RESTITUTION 7      /**< target restitution outside (0, 1] */
#define HCIMPACT_ERR_DOMAIN 8           /**< another argument outside the domain, or a
                                             result would leave the double range */
#define HCIMPACT_ERR_NO_CONVERGENCE 9   /**< an iteration or quadrature did not converge */
#define HCIMPACT_ERR_NULL 10            /**< a required pointer argument is NULL */
#define HCIMPACT_ERR_SOLVER 11          /**< the ODE solver (CVODE) failed */
#define HCIMPACT_ERR_UNAVAILABLE 12     /**< the component is not part of this build */
#define HCIMPACT_ERR_ELASTIC_LAW 13     /**< an elastic law returned an invalid value */
#define HCIMPACT_ERR_SIZE 14            /**< an array size is wrong (below 1, ...) */
#define HCIMPACT_ERR_UNDERDETERMINED 15 /**< the data cannot determine a fit's parameters */
#define HCIMPACT_ERR_OUT_OF_MEMORY 16   /**< the memory available cannot hold what valid
                                             arguments need (an allocation failed) */

/** Branches of hcimpact_velocity_at_depth: compression (x' >= 0) and restitution
 *  (x' <= 0). */
#define HCIMPACT_COMPRESSION_BRANCH 1
#define HCIMPACT_RESTITUTION_BRANCH 2 /**< see HCIMPACT_COMPRESSION_BRANCH */

/** Smallest exponent n of the power law that hcimpact_impact accepts (as n -> 0 the
 *  law tends to a step and the peak force degenerates). */
#define HCIMPACT_MIN_EXPONENT 1.0e-6
/** Largest beta = b V the closed forms (hcimpact_impact and the time law) accept */
#define HCIMPACT_MAX_BETA 1.0e40

/** Default min_velocity of hcimpact_damping_for_restitution, in m/s. */
#define HCIMPACT_DEFAULT_MIN_VELOCITY 1.0e-3

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------
 * Library, status messages
 * ------------------------------------------------------------------------ */

/** Text of a status code, e.g. "mass must be positive". A pointer to constant
 *  storage: never NULL, never to be freed or written, valid for the life of the
 *  program; unknown codes give "unknown status code". Thread-safe. */
HCIMPACT_API const char *hcimpact_status_message(int status);

/** Version of the library as "major.minor.patch" (constant storage, do not free). */
HCIMPACT_API const char *hcimpact_version(void);

/** Version of the library as 10000*major + 100*minor + patch; compare it with the
 *  header's HCIMPACT_VERSION to detect a mismatch between header and library. */
HCIMPACT_API int hcimpact_version_number(void);

/** Number of threads the array forms share a large array among when called here and
 *  now: OpenMP's (OMP_NUM_THREADS; 1 inside a parallel region of the caller's unless
 *  nesting is enabled), 1 in a library built without OpenMP. */
HCIMPACT_API int hcimpact_array_threads(void);

/* ------------------------------------------------------------------------
 * Lambert W, real branches
 * ------------------------------------------------------------------------ */

/** Principal branch W0(z), z >= -1/e. Returns W0 in [-1, inf).
 *  The double nearest to -1/e lies just below -1/e (by 1.2e-17): it and every
 *  z down to -1/e - 2^-54 return -1 exactly (the branch point, which is what a
 *  rounded -1/e stands for); z further below, and NaN, return NaN. */
HCIMPACT_API double hcimpact_lambert_w0(double z);

/** Lower branch W-1(z), -1/e <= z < 0. Returns W-1 in (-inf, -1].
 *  Same treatment of the doubles just below -1/e as hcimpact_lambert_w0.
 *  z = 0, either +0.0 or -0.0, returns -inf: the limit of W-1 as z rises to 0
 *  (as log(+0.0) = log(-0.0) = -inf; the sign of a zero is not a side of the
 *  domain). z > 0, z below the branch point, and NaN return NaN. */
HCIMPACT_API double hcimpact_lambert_wm1(double z);

/** 1 + W0(-exp(-1 - t)) for t >= 0, computed from t (no loss near t = 0).
 *  Lies in [0, 1); equals sqrt(2t) - 2t/3 + ... for small t. t < 0 or NaN: NaN;
 *  t = +inf: 1. */
HCIMPACT_API double hcimpact_lambert_w0p1(double t);

/** 1 + W-1(-exp(-1 - t)) for t >= 0, computed from t (no loss near t = 0).
 *  Lies in (-inf, 0]; equals -sqrt(2t) - 2t/3 - ... for small t. t < 0 or NaN:
 *  NaN; t = +inf: -inf. */
HCIMPACT_API double hcimpact_lambert_wm1p1(double t);

/** Array forms: w[i] = hcimpact_lambert_w0(z[i]) etc. for i < n (n >= 1).
 *  Returns HCIMPACT_OK, HCIMPACT_ERR_NULL or HCIMPACT_ERR_SIZE; an argument outside
 *  the domain gives NaN in its element only. */
HCIMPACT_API int hcimpact_lambert_w0_array(int n, const double *z, double *w);
HCIMPACT_API int hcimpact_lambert_wm1_array(int n, const double *z, double *w);
/**< w[i] = hcimpact_lambert_wm1(z[i]), as hcimpact_lambert_w0_array */
HCIMPACT_API int hcimpact_lambert_w0p1_array(int n, const double *t, double *v);
/**< v[i] = hcimpact_lambert_w0p1(t[i]), as hcimpact_lambert_w0_array */
HCIMPACT_API int hcimpact_lambert_wm1p1_array(int n, const double *t, double *v);
/**< v[i] = hcimpact_lambert_wm1p1(t[i]), as hcimpact_lambert_w0_array */

/* ------------------------------------------------------------------------
 * Restitution of the Hunt-Crossley impact (depends on beta = b V only)
 * ------------------------------------------------------------------------ */

/** Coefficient of restitution k(beta) = -V+/V- for beta = b V- >= 0
 *  (damping b in s/m times approach speed V- in m/s). k(0) = 1, k ~ 1/beta for
 *  large beta, k(+inf) = 0. Within 2 ulp of the exact value. beta < 0 or NaN: NaN. */
HCIMPACT_API double hcimpact_restitution(double beta);

/** The exact inverse: beta >= 0 with k(beta) = e, for 0 < e <= 1 (then b = beta/V-).
 *  beta(1) = 0; within 4 ulp. e outside (0, 1] or NaN: NaN; e below 1/DBL_MAX
 *  (where beta would exceed DBL_MAX): +inf. */
HCIMPACT_API double hcimpact_restitution_inverse(double e);

/** 1 - k(beta), accurate also where k is close to 1 (small beta). Domain as
 *  hcimpact_restitution. */
HCIMPACT_API double hcimpact_one_minus_restitution(double beta);

/** Share of the kinetic energy lost in the impact, 1 - k(beta)^2 (dimensionless).
 *  Domain as hcimpact_restitution. */
HCIMPACT_API double hcimpact_energy_loss_ratio(double beta);

/** Sensitivity dk/dbeta of the restitution (negative; -2/3 at beta = 0, -0 at
 *  beta = +inf). dk/db = V dk/dbeta, dk/dV = b dk/dbeta. Domain as
 *  hcimpact_restitution. */
HCIMPACT_API double hcimpact_restitution_derivative(double beta);

/** h(u) = u - ln(1 + u) >= 0 for u > -1 (the first integral of the motion,
 *  MODEL.md), accurate near u = 0 where it is u^2/2. u = -1 and u = +inf: +inf;
 *  u < -1, NaN: NaN. */
HCIMPACT_API double hcimpact_u_minus_log1p(double u);

/** Array forms of the five functions above (not h): out[i] = f(in[i]) for i < n
 *  (n >= 1). Returns HCIMPACT_OK, HCIMPACT_ERR_NULL or HCIMPACT_ERR_SIZE; an argument
 *  outside the domain gives NaN in its element only. */
HCIMPACT_API int hcimpact_restitution_array(int n, const double *beta, double *k);
HCIMPACT_API int hcimpact_restitution_inverse_array(int n, const double *e, double *beta);
/**< beta[i] = hcimpact_restitution_inverse(e[i]), as hcimpact_restitution_array */
HCIMPACT_API int hcimpact_one_minus_restitution_array(int n, const double *beta, double *d);
/**< d[i] = hcimpact_one_minus_restitution(beta[i]), as hcimpact_restitution_array */
HCIMPACT_API int hcimpact_energy_loss_ratio_array(int n, const double *beta, double *r);
/**< r[i] = hcimpact_energy_loss_ratio(beta[i]), as hcimpact_restitution_array */
HCIMPACT_API int hcimpact_restitution_derivative_array(int n, const double *beta, double *dk);
/**< dk[i] = hcimpact_restitution_derivative(beta[i]), as hcimpact_restitution_array */

/** Damping constant b (s/m) that gives the restitution e (0 < e <= 1) at the
 *  approach speed velocity (m/s, >= 0): b = beta(e)/max(velocity, min_velocity).
 *  Below min_velocity (m/s, > 0; HCIMPACT_DEFAULT_MIN_VELOCITY is 1e-3) b is that of
 *  min_velocity, so that it stays finite as the speed tends to 0.
 *  Every b that is a double is returned (b = 1/(e V) for tiny e, formed without
 *  overflow on the way).
 *  Returns HCIMPACT_OK; HCIMPACT_ERR_NOT_FINITE (NaN or infinite argument),
 *  HCIMPACT_ERR_RESTITUTION (e outside (0, 1]), HCIMPACT_ERR_VELOCITY (velocity < 0
 *  or min_velocity <= 0), HCIMPACT_ERR_DOMAIN (the exact b exceeds the largest
 *  double, e.g. e = 1e-310 at 1 m/s): *damping = NaN; HCIMPACT_ERR_NULL (damping is
 *  NULL). */
HCIMPACT_API int hcimpact_damping_for_restitution(double e, double velocity, double min_velocity,
                                                  double *damping);

/* ------------------------------------------------------------------------
 * Two bodies: Hertz constant, effective mass, velocities after the impact
 * ------------------------------------------------------------------------ */

/** Hertz's contact constant c in N/m^(3/2) of two elastic spheres:
 *  1/c = (3/4) ((1 - nu1^2)/E1 + (1 - nu2^2)/E2) sqrt(1/R1 + 1/R2).
 *  young (Pa) > 0 finite, -1 < poisson <= 1/2, radius (m) > 0 or INFINITY for a
 *  flat body (a plate; not both). Otherwise NaN. Steel ball R = 1.452 cm on a steel
 *  plate (E = 2e11 Pa, nu = 0.25): 1.7138e10. */
HCIMPACT_API double hcimpact_hertz_constant(double young1, double poisson1, double radius1,
                                            double young2, double poisson2, double radius2);

/** Effective mass m1 m2/(m1 + m2) in kg, the mass of the equivalent one-body impact.
 *  mass1 > 0 finite, mass2 > 0 (INFINITY: an immovable obstacle, gives mass1).
 *  Otherwise NaN. */
HCIMPACT_API double hcimpact_effective_mass(double mass1, double mass2);

/** Velocities (m/s) of two bodies after a collinear impact with the coefficient of
 *  restitution k (e.g. from hcimpact_impact with the effective mass and the relative
 *  speed velocity1 - velocity2 > 0): momentum is conserved and the relative velocity
 *  becomes -k (velocity1 - velocity2). Body 1 moves along +x towards body 2.
 *  mass2 = INFINITY is an immovable obstacle.
 *  Returns HCIMPACT_OK; HCIMPACT_ERR_NOT_FINITE, HCIMPACT_ERR_MASS (a mass <= 0),
 *  HCIMPACT_ERR_VELOCITY (velocity1 <= velocity2: no approach),
 *  HCIMPACT_ERR_RESTITUTION (k outside [0, 1]): outputs NaN; HCIMPACT_ERR_NULL. */
HCIMPACT_API int hcimpact_two_body_velocities(double mass1, double mass2, double velocity1,
                                              double velocity2, double restitution,
                                              double *velocity1_after, double *velocity2_after);

/* ------------------------------------------------------------------------
 * One impact (issue #3): m x'' = -c x^n (1 + b x'), x(0) = 0, x'(0) = V.
 * Fortran: src/hcimpact/capi/api_impact.f90 (module hcimpact_api_impact; the structs
 * are mirrored in src/hcimpact/capi/capi_types.f90), physics in
 * hcimpact_impact_model; doc/impact.md.
 * ------------------------------------------------------------------------ */

/** The contact of one collinear impact (SI units). For two bodies use the
 *  effective mass m1 m2/(m1 + m2) and the relative approach speed. */
typedef struct {
    double mass;      /**< mass m in kg (effective mass for two bodies), > 0 */
    double stiffness; /**< contact constant c in N/m^n, > 0 (Hertz: see doc/impact.md) */
    double exponent;  /**< exponent n of the elastic law f = c x^n, >= 1e-6 (3/2: Hertz) */
    double damping;   /**< Hunt-Crossley damping b in s/m, >= 0 (0: elastic) */
    double velocity;  /**< approach speed V in m/s, > 0 */
} hcimpact_contact;

/** What hcimpact_impact computes. */
typedef struct {
    double restitution;               /**< coefficient of restitution k in (0, 1] */
    double energy_loss_ratio;         /**< share of kinetic energy lost, 1 - k^2 */
    double rebound_velocity;          /**< -k V in m/s (negative) */
    double max_compression;           /**< maximum compression x_max in m */
    double peak_force;                /**< largest contact force c x^n (1 + b x') in N */
    double compression_at_peak_force; /**< compression at which it acts, in m */
    double time_at_peak_force;        /**< time from impact to the peak force in s */
    double compression_time;          /**< time from impact to x_max in s */
    double contact_time;              /**< duration of the contact in s */
} hcimpact_outcome;

/** One impact with the power law f = c x^n. Every output is the value at the
 *  doubles given (b V formed exactly); measured errors are within about 1.2 ulp
 *  (x_max and k within 0.5 ulp) over the reference data, see doc/impact.md.
 *  Returns 0 (HCIMPACT_OK) on success; otherwise a status and, except for
 *  HCIMPACT_ERR_NULL, every field of *outcome is NaN:
 *  HCIMPACT_ERR_NOT_FINITE (1)   a field of *contact is NaN or infinite,
 *  HCIMPACT_ERR_MASS (2)         mass <= 0,
 *  HCIMPACT_ERR_STIFFNESS (3)    stiffness <= 0,
 *  HCIMPACT_ERR_EXPONENT (4)     exponent < 1e-6 (HCIMPACT_MIN_EXPONENT),
 *  HCIMPACT_ERR_VELOCITY (5)     velocity <= 0,
 *  HCIMPACT_ERR_DAMPING (6)      damping < 0,
 *  HCIMPACT_ERR_DOMAIN (8)       b V above 1e40 (HCIMPACT_MAX_BETA), or a result
 *                                would leave the double range,
 *  HCIMPACT_ERR_NO_CONVERGENCE (9) exponent above 100 (the times are not
 *                                integrated beyond), or a quadrature did not
 *                                converge (not seen for b V up to 1e40),
 *  HCIMPACT_ERR_NULL (10)        contact or outcome is NULL (nothing written). */
HCIMPACT_API int hcimpact_impact(const hcimpact_contact *contact, hcimpact_outcome *outcome);

/** A callback of an elastic law: a value at the compression x >= 0 (m); `data` is the
 *  pointer given in hcimpact_elastic_law. */
typedef double (*hcimpact_law_fn)(double x, void *data);

/** An elastic law supplied by the caller: an increasing force f with f(0) = 0,
 *  its potential Pi(x) = integral of f from 0 to x, and its derivative f'(x).
 *  The callbacks must have no side effects on what the library reads: they are
 *  called many times, in any order, and from several threads if the caller runs
 *  impacts in parallel. */
typedef struct {
  hcimpact_law_fn force;             /**< f(x) in N */
  hcimpact_law_fn potential;         /**< Pi(x) in J */
  hcimpact_law_fn force_derivative;  /**< f'(x) in N/m */
  void *data;                        /**< handed back to every callback */
} hcimpact_elastic_law;

/** hcimpact_impact for a caller's elastic law: mass in kg (the effective mass for two
 *  bodies), damping b in s/m, approach speed in m/s. Same outcome and statuses as
 *  hcimpact_impact (mass, damping, velocity checked alike); a NULL law, outcome or
 *  callback gives HCIMPACT_ERR_NULL (nothing written), and a callback returning a
 *  value that is not finite, or a law that is not increasing, HCIMPACT_ERR_ELASTIC_LAW.
 *  HCIMPACT_ERR_DOMAIN where the law's values the method needs leave the double range
 *  (energies m V^2 h(bV)/(bV)^2 near the bottom of the range, f or f' infinite or
 *  subnormal where the peak's sign is decided; a peak force closer to the impact than
 *  the smallest double, as for a law that jumps at 0 like c x^n with n near 0), rather
 *  than a wrong number. */
HCIMPACT_API int hcimpact_impact_law(const hcimpact_elastic_law *law, double mass, double damping,
                                     double velocity, hcimpact_outcome *outcome);

/** hcimpact_impact for each of n >= 1 contacts: outcomes[i] from contacts[i].
 *  statuses (may be NULL) receives the status of each; an impact that fails has NaN
 *  in its outcome and does not stop the others. Returns HCIMPACT_OK when all
 *  succeeded, otherwise the status of the first that failed; HCIMPACT_ERR_NULL
 *  (contacts or outcomes NULL) and HCIMPACT_ERR_SIZE (n < 1) write nothing. */
HCIMPACT_API int hcimpact_impact_array(int n, const hcimpact_contact *contacts,
                                       hcimpact_outcome *outcomes, int *statuses);

/* ------------------------------------------------------------------------
 * Trajectory: velocity at a depth (phase curves), time law x(t), x'(t), F(t)
 * ------------------------------------------------------------------------ */

/** Velocity x' in m/s at the compression x (m, 0 <= x <= x_max) on the branch
 *  HCIMPACT_COMPRESSION_BRANCH (x' >= 0) or HCIMPACT_RESTITUTION_BRANCH (x' <= 0):
 *  V(x) = u(h(b V) (1 - (x/x_max)^(n+1)))/b through Lambert W (MODEL.md), smooth as
 *  b -> 0. At x = 0 it is exactly V resp. the rebound velocity -k V of
 *  hcimpact_impact, at x = x_max 0. No quadrature: any exponent up to about 6e299.
 *  Returns HCIMPACT_OK; the statuses of hcimpact_impact for the contact (not those
 *  of its times and force);
 *  HCIMPACT_ERR_NOT_FINITE (x NaN or infinite), HCIMPACT_ERR_DOMAIN (x < 0,
 *  x > x_max by more than 4 ulp, or another branch): *velocity = NaN;
 *  HCIMPACT_ERR_NULL. */
HCIMPACT_API int hcimpact_velocity_at_depth(const hcimpact_contact *contact, double x, int branch,
                                            double *velocity);

/** velocity[i] = the velocity at the compression x[i], for i < n (n >= 1), on one
 *  branch. On an error every velocity is NaN and the status is that of the first x
 *  that failed (or of the contact). */
HCIMPACT_API int hcimpact_velocity_at_depth_array(const hcimpact_contact *contact, int n,
                                                  const double *x, int branch, double *velocity);

/** The time law at n >= 1 times t[i] (s from the start of contact, any order):
 *  compression x[i] (m), velocity v[i] = x' (m/s) and contact force
 *  f[i] = c x^n (1 + b x') (N). Before the contact (t <= 0): x = 0, x' = V, F = 0;
 *  from the contact time of hcimpact_impact on: x = 0, x' = -k V, F = 0 exactly.
 *  Each time costs a few quadratures. A time whose state is within the range of
 *  doubles is answered even where hcimpact_impact fails only because another of its
 *  outputs is not (a peak force beyond DBL_MAX); a state beyond it is
 *  HCIMPACT_ERR_DOMAIN. HCIMPACT_ERR_NO_CONVERGENCE where the point cannot be located
 *  to double accuracy (large exponents with heavy damping, n = 80 and b V = 6600:
 *  the restitution creeps within 1e-16 of its end, in the trajectory's parameter).
 *  Returns HCIMPACT_OK; the statuses of hcimpact_impact; HCIMPACT_ERR_NOT_FINITE (a
 *  t is NaN or infinite): all outputs NaN; HCIMPACT_ERR_NULL, HCIMPACT_ERR_SIZE;
 *  HCIMPACT_ERR_OUT_OF_MEMORY when the library cannot allocate its copies of the n
 *  values (outputs NaN). */
HCIMPACT_API int hcimpact_time_law(const hcimpact_contact *contact, int n, const double *t,
                                   double *x, double *v, double *f);

/** The time law on n >= 2 equally spaced times t[i] = contact_time i/(n - 1), written
 *  to t, with x, v and f as in hcimpact_time_law (x[0] = x[n-1] = 0 and
 *  f[0] = f[n-1] = 0 exactly, t[n-1] the contact time of hcimpact_impact).
 *  Returns as hcimpact_time_law; n < 2 gives HCIMPACT_ERR_SIZE (nothing written), n
 *  samples beyond the memory available HCIMPACT_ERR_OUT_OF_MEMORY (every output NaN). */
HCIMPACT_API int hcimpact_time_law_samples(const hcimpact_contact *contact, int n, double *t,
                                           double *x, double *v, double *f);

/* ------------------------------------------------------------------------
 * The contact-force element: the force of one contact inside the caller's own
 * integrator. Fortran: src/hcimpact/model/force_element.f90 (module
 * hcimpact_force_element); C wrappers src/hcimpact/capi/api_force.f90;
 * doc/contact-force.md.
 * ------------------------------------------------------------------------ */

/** The contact force and what an integrator needs with it, at one state. */
typedef struct {
    double force;       /**< F = f(x) max(0, 1 + b v) in N, >= 0 (pushes the bodies apart) */
    double dforce_dx;   /**< dF/dx in N/m (0 where the force is clamped) */
    double dforce_dv;   /**< dF/dv in N s/m (0 where the force is clamped) */
    double potential;   /**< elastic potential energy Pi(x) = c x^(n+1)/(n+1) in J */
    double dissipation; /**< dissipated power (F - f(x)) v in W, >= 0 */
} hcimpact_force;

/** The element of one power-law contact f = c x^n at the deformation x (m; x <= 0:
 *  no contact, every field 0) and the deformation rate v = dx/dt (m/s; > 0 while the
 *  bodies approach). The force never pulls: where 1 + b v < 0 it is clamped at 0, and
 *  so are both derivatives (also at 1 + b v = 0 exactly). 1 + b v is formed from the
 *  exact product b v, so every field is within a few ulps of its exact value, also
 *  next to the clamp; a result beyond the double range is +inf (dF/dx for n < 1 as
 *  x -> 0+), never a finite representable value lost on the way.
 *  Returns HCIMPACT_OK; HCIMPACT_ERR_NOT_FINITE (an argument NaN or infinite),
 *  HCIMPACT_ERR_STIFFNESS (c <= 0), HCIMPACT_ERR_EXPONENT (n < 1e-6),
 *  HCIMPACT_ERR_DAMPING (b < 0): every field NaN; HCIMPACT_ERR_NULL (f NULL). */
HCIMPACT_API int hcimpact_contact_force(double stiffness, double exponent, double damping, double x,
                                        double v, hcimpact_force *f);

/** The element of n >= 1 contacts at once: f[i] from stiffness[i], exponent[i],
 *  damping[i], x[i], v[i]. statuses (may be NULL) receives each status; the result is
 *  HCIMPACT_OK when all succeeded, else the status of the first that failed (its
 *  fields NaN; the others are computed regardless). HCIMPACT_ERR_NULL and
 *  HCIMPACT_ERR_SIZE (n < 1) write nothing. */
HCIMPACT_API int hcimpact_contact_force_array(int n, const double *stiffness, const double *exponent,
                                              const double *damping, const double *x, const double *v,
                                              hcimpact_force *f, int *statuses);

/** The element of two bodies on a line, body 1 left of body 2, from their positions
 *  (m) and velocities (m/s): x = distance - (q2 - q1), v = v1 - v2, both formed without
 *  rounding error (the result is that of the exact x and v of these doubles).
 *  distance = q2 - q1 at first touch (the sum of the radii for centres). The force on
 *  body 2 is +F, on body 1 -F; dF/dq1 = dF/dx = -dF/dq2, dF/dv1 = dF/dv = -dF/dv2.
 *  Statuses as hcimpact_contact_force; bodies apart by more than DBL_MAX have no
 *  contact; an overlap or relative speed beyond DBL_MAX: HCIMPACT_ERR_DOMAIN. */
HCIMPACT_API int hcimpact_contact_force_pair(double stiffness, double exponent, double damping,
                                             double distance, double q1, double v1, double q2,
                                             double v2, hcimpact_force *f);

/** The element of a body (position q, velocity v) against a fixed wall at `wall`:
 *  side = +1 when the wall is on the body's right (x = distance - (wall - q)), -1 on
 *  its left (x = distance - (q - wall)); distance = |wall - q| at first touch. The
 *  force on the body is -side F, and its derivatives with respect to q and v are
 *  -dF/dx and -dF/dv. Another side: HCIMPACT_ERR_DOMAIN. */
HCIMPACT_API int hcimpact_contact_force_wall(double stiffness, double exponent, double damping,
                                             double distance, double q, double v, double wall, int side,
                                             hcimpact_force *f);

/* ------------------------------------------------------------------------
 * The optional components have headers of their own: hcimpact_cvode.h
 * (hcimpact_simulate, the ODE path; link libhcimpact_cvode) and hcimpact_lapack.h
 * (hcimpact_fit_*, calibration; link libhcimpact_lapack). Each includes this one.
 * ------------------------------------------------------------------------ */

#ifdef __cplusplus
}
#endif

#endif /* HCIMPACT_H */
