/* SPDX-License-Identifier: Apache-2.0 */
/*
 * libFuzzer target over the C interface of hcimpact (include/hcimpact.h): the input
 * bytes choose an entry point and supply its arguments, as raw IEEE doubles (NaN,
 * infinities, subnormals, huge values, signed zeros) or as "physical" doubles
 * (2^e * [1, 2) with |e| <= 64, so that valid contacts and deep code paths are common),
 * plus sizes, branches and NULL pointers. Every entry point of the core library is
 * reached, hcimpact_impact_law with laws given as C callbacks among them; with
 * HCIMPACT_FUZZ_CVODE / HCIMPACT_FUZZ_LAPACK also hcimpact_simulate,
 * hcimpact_simulate_message, hcimpact_chain_simulate and the calibration fits.
 *
 * Besides crashes and sanitizer reports, the target checks the contract of the header
 * and aborts (a crash for libFuzzer) when it is broken:
 *  - every status is HCIMPACT_OK or a documented code (1 .. 15);
 *  - NULL pointers give HCIMPACT_ERR_NULL and write nothing; bad sizes give
 *    HCIMPACT_ERR_SIZE and write nothing;
 *  - on an error every output is NaN;
 *  - on success the results make sense (check_outcome and the fuzz_* functions): an
 *    impact's fields finite, 0 < k <= 1, 0 <= 1 - k^2 <= 1, rebound -k V, the peak
 *    force's compression at most x_max and its time at most the contact time, the
 *    compression time inside the contact; the power law through callbacks
 *    (hcimpact_impact_law) agreeing with hcimpact_impact where both are well inside
 *    the double range; velocities at a depth finite, of the branch's sign and at
 *    most V; the time law within [0, x_max] and at most the peak force, exactly
 *    x = F = 0 at both ends; the effective mass within [min/2, min] of the masses;
 *    the contact-force element's force, potential and dissipation >= 0 (all 0 without
 *    contact) and its array form equal to the scalar one; a chain's energies finite
 *    and its recorded contacts min(count, capacity);
 *  - hcimpact_status_message never returns NULL.
 *
 * With HCIMPACT_FUZZ_FPE the floating-point exceptions invalid, divide-by-zero and
 * overflow trap (SIGFPE), as in a gfortran program built with -ffpe-trap; the contract
 * checks themselves use only quiet comparisons (isnan first).
 *
 * Built and run by bench/fuzz/run.sh; results in doc/robustness.md.
 */
#ifdef HCIMPACT_FUZZ_FPE
#define _GNU_SOURCE /* feenableexcept */
#include <fenv.h>
#endif
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hcimpact.h"
#include "hcimpact_cvode.h"
#include "hcimpact_lapack.h"

#define MAX_N 16
/* the doubles of an hcimpact_outcome (every field is one) */
#define OUTCOME_FIELDS ((int)(sizeof(hcimpact_outcome) / sizeof(double)))

typedef struct {
  const uint8_t *data;
  size_t size;
} stream;

static uint8_t next_byte(stream *s)
{
  uint8_t b = 0;
  if (s->size > 0) {
    b = s->data[0];
    ++s->data;
    --s->size;
  }
  return b;
}

/* a double: raw bits (1 in 4) or 2^e * (1 + f) with a random sign, |e| <= 64 */
static double next_double(stream *s)
{
  uint8_t mode = next_byte(s);
  if ((mode & 3) == 0) {
    uint64_t bits = 0;
    double x;
    int i;
    for (i = 0; i < OUTCOME_FIELDS; ++i) bits = (bits << 8) | next_byte(s);
    memcpy(&x, &bits, sizeof x);
    return x;
  } else {
    int e = (int)(next_byte(s) % 129) - 64;
    double f = (double)((next_byte(s) << 8) | next_byte(s)) / 65536.0;
    double x = ldexp(1.0 + f, e);
    if ((mode & 0x1c) == 0) x = 0.0;         /* zeros now and then */
    return (mode & 0x80) ? -x : x;
  }
}

/* n in [-1, MAX_N], mostly positive */
static int next_size(stream *s)
{
  int n = (int)(next_byte(s) % (MAX_N + 3)) - 2;
  return n < -1 ? 1 : n;
}

/* HCIMPACT_FUZZ_VERBOSE set: print every contact decoded (to reproduce a finding) */
static int verbose = -1;

/* How hcimpact_chain_simulate is fuzzed (HCIMPACT_FUZZ_CHAIN; doc/robustness.md):
   unset (the default, CTest's run): with bounded work per input. NULL options mean the
   library's defaults (max_steps 1e8, until no contact can happen again), hours of
   integration for some extreme systems: a 12-minute run on 26 November found 7 inputs
   over 20 s, every one with NULL options and a long CVODE integration, none a defect.
   So NULL options go only with a call that fails before any work (n < 1 or masses
   NULL), and otherwise the options with at most 2000 steps and 200 contacts.
   "1" (run.sh --with-chain, the replay of bench/fuzz/findings): NULL options with any
   call, as the findings were made. "0" (run.sh --without-chain): no chain. */
enum { chain_off = 0, chain_bounded = 1, chain_full = 2 };
static int chain_mode = -1;

/* the last contact decoded, printed with a broken contract */
static hcimpact_contact last_contact;
static int have_contact = 0;

static void contract(int ok, const char *what)
{
  if (!ok) {
    fprintf(stderr, "hcimpact contract broken: %s\n", what);
    if (have_contact) {
      fprintf(stderr, "  last contact: mass %.17g, stiffness %.17g, exponent %.17g, "
              "damping %.17g, velocity %.17g\n", last_contact.mass, last_contact.stiffness,
              last_contact.exponent, last_contact.damping, last_contact.velocity);
    }
    abort();
  }
}

static void check_status(int status)
{
  contract(status >= HCIMPACT_OK && status <= HCIMPACT_ERR_OUT_OF_MEMORY, "unknown status");
  contract(hcimpact_status_message(status) != NULL, "status message NULL");
}

static int all_nan(const double *x, int n)
{
  int i;
  for (i = 0; i < n; ++i) {
    if (!isnan(x[i])) return 0;
  }
  return 1;
}

static void check_outcome(int status, const hcimpact_outcome *o)
{
  double fields[OUTCOME_FIELDS];
  check_status(status);
  memcpy(fields, o, sizeof fields);
  if (status == HCIMPACT_OK) {
    int i;
    if (verbose) {
      fprintf(stderr, "outcome: k %.17g, loss %.17g, rebound %.17g, x_max %.17g, peak %.17g "
              "at x %.17g, t %.17g, compression time %.17g, contact time %.17g\n",
              o->restitution, o->energy_loss_ratio, o->rebound_velocity, o->max_compression,
              o->peak_force, o->compression_at_peak_force, o->time_at_peak_force,
              o->compression_time, o->contact_time);
    }
    for (i = 0; i < OUTCOME_FIELDS; ++i) {
      if (isnan(fields[i])) fprintf(stderr, "outcome field %d is NaN\n", i);
      contract(!isnan(fields[i]), "NaN in a successful outcome");
    }
    contract(o->restitution > 0.0 && o->restitution <= 1.0, "k outside (0, 1]");
    for (i = 0; i < OUTCOME_FIELDS; ++i) contract(isfinite(fields[i]), "infinite field in an outcome");
    contract(o->energy_loss_ratio >= 0.0 && o->energy_loss_ratio <= 1.0,
             "energy loss outside [0, 1]");
    contract(o->rebound_velocity < 0.0, "rebound velocity not negative");
    contract(o->max_compression > 0.0 && o->peak_force > 0.0, "x_max or peak force <= 0");
    contract(o->compression_at_peak_force > 0.0
             && o->compression_at_peak_force <= o->max_compression,
             "compression at the peak force outside (0, x_max]");
    contract(o->compression_time > 0.0 && o->compression_time < o->contact_time,
             "compression time outside the contact");
    contract(o->time_at_peak_force >= 0.0 && o->time_at_peak_force <= o->compression_time,
             "time of the peak force after the compression");
  } else {
    contract(status != HCIMPACT_ERR_NULL, "NULL status without a NULL pointer");
    contract(all_nan(fields, OUTCOME_FIELDS), "outcome not NaN on error");
  }
}

static hcimpact_contact next_contact(stream *s)
{
  hcimpact_contact c;
  c.mass = next_double(s);
  c.stiffness = next_double(s);
  c.exponent = next_double(s);
  c.damping = next_double(s);
  c.velocity = next_double(s);
  /* exponents are mostly moderate (x^n with n = 2^60 is legal but slow to reach) */
  if (next_byte(s) & 1) c.exponent = 0.25 + fmod(fabs(c.exponent), 4.0);
  last_contact = c;
  have_contact = 1;
  if (verbose) {
    fprintf(stderr, "contact: mass %.17g, stiffness %.17g, exponent %.17g, damping %.17g, "
            "velocity %.17g\n", c.mass, c.stiffness, c.exponent, c.damping, c.velocity);
  }
  return c;
}

typedef double (*scalar_fn)(double);
typedef int (*array_fn)(int, const double *, double *);

static const scalar_fn scalars[] = {
    hcimpact_lambert_w0, hcimpact_lambert_wm1, hcimpact_lambert_w0p1, hcimpact_lambert_wm1p1,
    hcimpact_restitution, hcimpact_restitution_inverse, hcimpact_one_minus_restitution,
    hcimpact_energy_loss_ratio, hcimpact_restitution_derivative, hcimpact_u_minus_log1p};
static const array_fn arrays[] = {
    hcimpact_lambert_w0_array, hcimpact_lambert_wm1_array, hcimpact_lambert_w0p1_array,
    hcimpact_lambert_wm1p1_array, hcimpact_restitution_array,
    hcimpact_restitution_inverse_array, hcimpact_one_minus_restitution_array,
    hcimpact_energy_loss_ratio_array, hcimpact_restitution_derivative_array};

static void fuzz_scalars(stream *s)
{
  unsigned which = next_byte(s) % (sizeof scalars / sizeof scalars[0]);
  volatile double y = scalars[which](next_double(s));
  (void)y;
}

static void fuzz_arrays(stream *s)
{
  unsigned which = next_byte(s) % (sizeof arrays / sizeof arrays[0]);
  int n = next_size(s), i, status;
  double in[MAX_N], out[MAX_N];
  uint8_t nulls = next_byte(s);
  for (i = 0; i < MAX_N; ++i) {
    in[i] = next_double(s);
    out[i] = 42.0;
  }
  status = arrays[which](n, (nulls & 1) ? NULL : in, (nulls & 2) ? NULL : out);
  check_status(status);
  if (nulls & 3) {
    contract(status == HCIMPACT_ERR_NULL, "array form: NULL not detected");
  } else if (n < 1) {
    contract(status == HCIMPACT_ERR_SIZE, "array form: size not detected");
  } else {
    contract(status == HCIMPACT_OK, "array form failed");
    for (i = 0; i < n; ++i) {
      double y = scalars[which](in[i]);
      contract((isnan(y) && isnan(out[i])) || y == out[i], "array form differs from scalar");
    }
  }
  if (status != HCIMPACT_OK) {
    for (i = 0; i < MAX_N; ++i) contract(out[i] == 42.0, "written on NULL/size error");
  }
}

static void fuzz_two_bodies(stream *s)
{
  double a[6], v1 = 42.0, v2 = 42.0, damping = 42.0;
  int i, status;
  uint8_t nulls = next_byte(s);
  for (i = 0; i < 6; ++i) a[i] = next_double(s);
  if (nulls & 4) a[2] = INFINITY;
  if (nulls & 8) a[5] = INFINITY;
  {
    double c = hcimpact_hertz_constant(a[0], a[1], a[2], a[3], a[4], a[5]);
    double m = hcimpact_effective_mass(a[0], a[1]);
    int young_ok = isfinite(a[0]) && a[0] > 0.0 && isfinite(a[3]) && a[3] > 0.0;
    int poisson_ok = a[1] > -1.0 && a[1] <= 0.5 && a[4] > -1.0 && a[4] <= 0.5;
    int radius_ok = a[2] > 0.0 && a[5] > 0.0 && !(isinf(a[2]) && isinf(a[5]));
    /* in its domain the Hertz constant is a number >= 0 (0 or +inf only where the
       exact value is beyond the double range); outside it NaN */
    if (young_ok && poisson_ok && radius_ok) {
      contract(c >= 0.0, "hertz_constant: NaN or negative in its domain");
    } else {
      contract(isnan(c), "hertz_constant: not NaN outside its domain");
    }
    /* m1 m2/(m1 + m2) lies in [min/2, min]: always a positive double */
    if (isfinite(a[0]) && a[0] > 0.0 && a[1] > 0.0) {
      double smaller = a[0] < a[1] ? a[0] : a[1];
      contract(m >= 0.5 * smaller && m <= smaller, "effective_mass outside [min/2, min]");
    } else {
      contract(isnan(m), "effective_mass: not NaN outside its domain");
    }
  }
  status = hcimpact_two_body_velocities(a[0], a[1], a[2], a[3], a[4], (nulls & 1) ? NULL : &v1,
                                        (nulls & 2) ? NULL : &v2);
  check_status(status);
  if (nulls & 3) {
    contract(status == HCIMPACT_ERR_NULL && v1 == 42.0 && v2 == 42.0, "two bodies: NULL");
  } else if (status != HCIMPACT_OK) {
    contract(isnan(v1) && isnan(v2), "two bodies: not NaN on error");
  } else {
    /* a velocity beyond the largest double is +-inf (documented), never NaN; body 2
       is pushed on (v2' >= v2) and body 1 held back (v1' <= v1), the relative
       velocity becomes -k (v1 - v2) <= 0 */
    contract(!isnan(v1) && !isnan(v2), "two bodies: NaN with status OK");
    contract(v1 <= a[2] && v2 >= a[3] && v1 <= v2, "two bodies: velocities out of order");
  }
  status = hcimpact_damping_for_restitution(a[0], a[1], a[2], (nulls & 16) ? NULL : &damping);
  check_status(status);
  if (nulls & 16) {
    contract(status == HCIMPACT_ERR_NULL && damping == 42.0, "damping: NULL");
  } else if (status != HCIMPACT_OK) {
    contract(isnan(damping), "damping: not NaN on error");
  } else {
    contract(damping >= 0.0 && isfinite(damping), "damping negative or not finite");
  }
}

static void fuzz_impact(stream *s)
{
  hcimpact_contact c = next_contact(s);
  hcimpact_outcome o;
  uint8_t nulls = next_byte(s);
  int status;
  memset(&o, 0x2a, sizeof o);
  status = hcimpact_impact((nulls & 1) ? NULL : &c, (nulls & 2) ? NULL : &o);
  if (nulls & 3) {
    hcimpact_outcome untouched;
    memset(&untouched, 0x2a, sizeof untouched);
    contract(status == HCIMPACT_ERR_NULL && memcmp(&o, &untouched, sizeof o) == 0,
             "impact: NULL");
    return;
  }
  check_outcome(status, &o);
}

static void fuzz_impact_array(stream *s)
{
  hcimpact_contact c[4];
  hcimpact_outcome o[4];
  int statuses[4], n = (int)(next_byte(s) % 6) - 1, i, status, first = HCIMPACT_OK;
  uint8_t nulls = next_byte(s);
  for (i = 0; i < 4; ++i) c[i] = next_contact(s);
  if (n > 4) n = 4;
  status = hcimpact_impact_array(n, (nulls & 1) ? NULL : c, (nulls & 2) ? NULL : o,
                                 (nulls & 4) ? NULL : statuses);
  check_status(status);
  if (nulls & 3) {
    contract(status == HCIMPACT_ERR_NULL, "impact_array: NULL");
  } else if (n < 1) {
    contract(status == HCIMPACT_ERR_SIZE, "impact_array: size");
  } else {
    for (i = 0; i < n; ++i) {
      hcimpact_outcome one;
      int one_status;
      last_contact = c[i];
      one_status = hcimpact_impact(&c[i], &one);
      check_outcome(one_status, &o[i]);
      if (!(nulls & 4)) contract(statuses[i] == one_status, "impact_array: status differs");
      if (first == HCIMPACT_OK) first = one_status;
      contract(memcmp(&one, &o[i], sizeof one) == 0, "impact_array differs from impact");
    }
    contract(status == first, "impact_array: not the first error");
  }
}

static void fuzz_trajectory(stream *s)
{
  hcimpact_contact c = next_contact(s);
  uint8_t nulls = next_byte(s);
  int branch = (int)(next_byte(s) % 4);
  int n = next_size(s), i, status;
  double x[MAX_N], v[MAX_N], f[MAX_N], t[MAX_N], vel = 42.0;
  hcimpact_outcome o;
  int impact_status = hcimpact_impact(&c, &o);

  for (i = 0; i < MAX_N; ++i) {
    /* depths and times: raw, or a fraction of the impact's own scales */
    double u = next_double(s);
    if (impact_status == HCIMPACT_OK && (next_byte(s) & 1)) {
      double share = fmod(fabs(u), 1.5);
      x[i] = share * o.max_compression;
      t[i] = share * o.contact_time;
    } else {
      x[i] = u;
      t[i] = u;
    }
  }
  status = hcimpact_velocity_at_depth((nulls & 1) ? NULL : &c, x[0], branch,
                                      (nulls & 2) ? NULL : &vel);
  check_status(status);
  if (nulls & 3) {
    contract(status == HCIMPACT_ERR_NULL && vel == 42.0, "velocity_at_depth: NULL");
  } else if (status != HCIMPACT_OK) {
    contract(isnan(vel), "velocity_at_depth: not NaN on error");
  } else {
    contract(isfinite(vel), "velocity_at_depth: not finite on success");
    contract(branch == HCIMPACT_COMPRESSION_BRANCH || branch == HCIMPACT_RESTITUTION_BRANCH,
             "velocity_at_depth: success on another branch");
    contract(fabs(vel) <= c.velocity, "velocity_at_depth: |x'| above V");
    contract(branch == HCIMPACT_COMPRESSION_BRANCH ? vel >= 0.0 : vel <= 0.0,
             "velocity_at_depth: sign differs from the branch");
    if (impact_status == HCIMPACT_OK && x[0] == 0.0) {
      contract(vel == (branch == HCIMPACT_COMPRESSION_BRANCH ? c.velocity : o.rebound_velocity),
               "velocity_at_depth: not V or -k V at x = 0");
    }
  }

  status = hcimpact_velocity_at_depth_array(&c, n, (nulls & 4) ? NULL : x, branch, v);
  check_status(status);
  if (nulls & 4) {
    contract(status == HCIMPACT_ERR_NULL, "velocity_at_depth_array: NULL");
  } else if (n < 1) {
    contract(status == HCIMPACT_ERR_SIZE, "velocity_at_depth_array: size");
  } else if (status != HCIMPACT_OK) {
    contract(all_nan(v, n), "velocity_at_depth_array: not NaN on error");
  }

  /* time law: at most 4 times (each costs a few quadratures) */
  if (n > 4) n = 4;
  status = hcimpact_time_law(&c, n, t, (nulls & 8) ? NULL : x, v, f);
  check_status(status);
  if (nulls & 8) {
    contract(status == HCIMPACT_ERR_NULL, "time_law: NULL");
  } else if (n < 1) {
    contract(status == HCIMPACT_ERR_SIZE, "time_law: size");
  } else if (status != HCIMPACT_OK) {
    contract(all_nan(x, n) && all_nan(v, n) && all_nan(f, n), "time_law: not NaN on error");
  } else {
    /* a time whose state is representable is answered where the impact's outcome is
       not (its peak force beyond DBL_MAX): then only the sign and range checks */
    contract(impact_status == HCIMPACT_OK || impact_status == HCIMPACT_ERR_DOMAIN,
             "time_law: success where impact failed");
    for (i = 0; i < n && impact_status != HCIMPACT_OK; ++i) {
      contract(x[i] >= 0.0 && f[i] >= 0.0 && isfinite(x[i]) && isfinite(f[i])
               && fabs(v[i]) <= c.velocity, "time_law: x, x' or F out of range");
    }
    for (i = 0; i < n && impact_status == HCIMPACT_OK; ++i) {
      /* within [0, x_max], |x'| <= V and at most the peak force (a few ulps allowed: the
         time law is accurate to a few ulps, x' = V (1 + 1 ulp) was seen early on); before
         the contact x = 0, x' = V, from the contact time on x = 0, x' = -k V, F = 0 */
      int inside = x[i] >= 0.0 && f[i] >= 0.0 && isfinite(v[i])
                   && x[i] <= o.max_compression * (1.0 + 16 * DBL_EPSILON)
                   && f[i] <= o.peak_force * (1.0 + 64 * DBL_EPSILON)
                   && fabs(v[i]) <= c.velocity * (1.0 + 4 * DBL_EPSILON);
      int ends = t[i] <= 0.0 ? (x[i] == 0.0 && v[i] == c.velocity && f[i] == 0.0)
                 : t[i] >= o.contact_time
                   ? (x[i] == 0.0 && v[i] == o.rebound_velocity && f[i] == 0.0) : 1;
      if (!(inside && ends)) {
        fprintf(stderr, "time_law at t = %.17g: x = %.17g, v = %.17g, F = %.17g "
                "(x_max %.17g, peak %.17g, contact time %.17g)\n", t[i], x[i], v[i], f[i],
                o.max_compression, o.peak_force, o.contact_time);
      }
      contract(inside, "time_law: x, x' or F outside the impact's bounds");
      contract(ends, "time_law: not the resting values before or after the contact");
    }
  }
  status = hcimpact_time_law_samples(&c, n, t, x, v, (nulls & 16) ? NULL : f);
  check_status(status);
  if (nulls & 16) {
    contract(status == HCIMPACT_ERR_NULL, "time_law_samples: NULL");
  } else if (n < 2) {
    contract(status == HCIMPACT_ERR_SIZE, "time_law_samples: size");
  } else if (status != HCIMPACT_OK) {
    contract(all_nan(t, n) && all_nan(x, n), "time_law_samples: not NaN on error");
  } else {
    contract(t[0] == 0.0 && t[n - 1] == o.contact_time, "time_law_samples: not 0 ... T");
    contract(x[0] == 0.0 && x[n - 1] == 0.0 && f[0] == 0.0 && f[n - 1] == 0.0,
             "time_law_samples: x or F not 0 at the ends");
  }
}

/* A law given as C callbacks: the power law c x^n (kind 0), the same law returning NaN
   beyond a compression (1), or a law that decreases (2) */
typedef struct {
  double stiffness, exponent, nan_beyond;
  int kind;
} callback_law;

static double law_value(const callback_law *l, double x, double value)
{
  if (l->kind == 1 && x > l->nan_beyond) return NAN;
  return l->kind == 2 ? -value : value;
}
static double law_force(double x, void *data)
{
  const callback_law *l = data;
  return law_value(l, x, l->stiffness * pow(x, l->exponent));
}
static double law_potential(double x, void *data)
{
  const callback_law *l = data;
  return law_value(l, x, l->stiffness * pow(x, l->exponent + 1.0) / (l->exponent + 1.0));
}
static double law_derivative(double x, void *data)
{
  const callback_law *l = data;
  return law_value(l, x, l->stiffness * l->exponent * pow(x, l->exponent - 1.0));
}

/* |a - b| <= tol |b| */
static int close_to(double a, double b, double tol) { return fabs(a - b) <= tol * fabs(b); }

/* a value well inside the double range (the power law's callbacks, x^n and x^(n+1)
   formed by pow, lose no digits there) */
static int moderate(double x) { return fabs(x) >= 1e-100 && fabs(x) <= 1e100; }

static void fuzz_impact_law(stream *s)
{
  hcimpact_contact c = next_contact(s);
  callback_law data;
  hcimpact_elastic_law law;
  hcimpact_outcome o, exact;
  uint8_t nulls = next_byte(s);
  int status, exact_status;
  data.stiffness = fabs(c.stiffness); /* a negative one would turn kind 2 around */
  data.exponent = c.exponent;
  data.kind = (int)(next_byte(s) % 3);
  data.nan_beyond = fabs(next_double(s));
  law.force = (nulls & 4) ? NULL : law_force;
  law.potential = (nulls & 8) ? NULL : law_potential;
  law.force_derivative = (nulls & 16) ? NULL : law_derivative;
  law.data = &data;
  memset(&o, 0x2a, sizeof o);
  status = hcimpact_impact_law((nulls & 1) ? NULL : &law, c.mass, c.damping, c.velocity,
                               (nulls & 2) ? NULL : &o);
  check_status(status);
  if (nulls & 31) {
    hcimpact_outcome untouched;
    memset(&untouched, 0x2a, sizeof untouched);
    contract(status == HCIMPACT_ERR_NULL && memcmp(&o, &untouched, sizeof o) == 0,
             "impact_law: NULL");
    return;
  }
  check_outcome(status, &o);
  if (data.kind == 2) {
    contract(status != HCIMPACT_OK, "impact_law: success with a decreasing law");
  }
  if (data.kind != 0) return;
  /* the power law both ways: where the contact and its results are well inside the
     range, the callbacks are as exact as the closed forms' power law (pow within an
     ulp), and both paths give the same impact to a few ulps of its conditioning */
  exact_status = hcimpact_impact(&c, &exact);
  if (exact_status == HCIMPACT_OK && c.exponent >= 0.25 && c.exponent <= 4.0
      && c.damping * c.velocity <= 1e6 && moderate(c.mass) && moderate(c.stiffness)
      && moderate(c.velocity) && (c.damping == 0.0 || moderate(c.damping))
      && moderate(exact.max_compression) && moderate(exact.peak_force)
      && moderate(exact.contact_time) && moderate(c.mass * c.velocity * c.velocity)
      && moderate(exact.compression_at_peak_force)) {
    if (status != HCIMPACT_OK
        || !(close_to(o.restitution, exact.restitution, 1e-12)
             && close_to(o.max_compression, exact.max_compression, 1e-12)
             && close_to(o.peak_force, exact.peak_force, 1e-10)
             && close_to(o.compression_time, exact.compression_time, 1e-10)
             && close_to(o.contact_time, exact.contact_time, 1e-10))) {
      fprintf(stderr, "impact_law (status %d): k %.17g, x_max %.17g, F %.17g, t_c %.17g, "
              "T %.17g\nimpact: k %.17g, x_max %.17g, F %.17g, t_c %.17g, T %.17g\n", status,
              o.restitution, o.max_compression, o.peak_force, o.compression_time,
              o.contact_time, exact.restitution, exact.max_compression, exact.peak_force,
              exact.compression_time, exact.contact_time);
      contract(0, "impact_law with the power law differs from impact");
    }
  }
}

static void check_force(int status, const hcimpact_force *f, double x, const char *where)
{
  double fields[5];
  check_status(status);
  memcpy(fields, f, sizeof fields);
  if (verbose) {
    fprintf(stderr, "%s: status %d, x %.17g: F %.17g, dF/dx %.17g, dF/dv %.17g, potential "
            "%.17g, dissipation %.17g\n", where, status, x, f->force, f->dforce_dx,
            f->dforce_dv, f->potential, f->dissipation);
  }
  if (status != HCIMPACT_OK) {
    contract(status != HCIMPACT_ERR_NULL, where);
    contract(all_nan(fields, 5), where);
    return;
  }
  contract(!isnan(f->force) && !isnan(f->dforce_dx) && !isnan(f->dforce_dv)
           && !isnan(f->potential) && !isnan(f->dissipation), where);
  contract(f->force >= 0.0 && f->potential >= 0.0 && f->dissipation >= 0.0, where);
  if (!isnan(x) && x <= 0.0) {
    contract(f->force == 0.0 && f->dforce_dx == 0.0 && f->dforce_dv == 0.0
             && f->potential == 0.0 && f->dissipation == 0.0, where);
  }
}

static void fuzz_force(stream *s)
{
  double c[4], n[4], b[4], x[4], v[4], q1, q2, distance, wall;
  hcimpact_force f[4], one;
  int statuses[4], i, status, first = HCIMPACT_OK, count = (int)(next_byte(s) % 6) - 1;
  uint8_t nulls = next_byte(s);
  for (i = 0; i < 4; ++i) {
    c[i] = next_double(s);
    n[i] = next_double(s);
    if (next_byte(s) & 1) n[i] = 0.25 + fmod(fabs(n[i]), 4.0);
    b[i] = next_double(s);
    x[i] = next_double(s);
    v[i] = next_double(s);
  }
  if (count > 4) count = 4;
  memset(&one, 0x2a, sizeof one);
  if (verbose) {
    fprintf(stderr, "contact_force(c %.17g, n %.17g, b %.17g, x %.17g, v %.17g)\n", c[0], n[0],
            b[0], x[0], v[0]);
  }
  status = hcimpact_contact_force(c[0], n[0], b[0], x[0], v[0], (nulls & 1) ? NULL : &one);
  if (nulls & 1) {
    contract(status == HCIMPACT_ERR_NULL, "contact_force: NULL");
  } else {
    check_force(status, &one, x[0], "contact_force: outputs");
  }
  memset(f, 0x2a, sizeof f);
  status = hcimpact_contact_force_array(count, c, n, b, (nulls & 2) ? NULL : x, v,
                                        (nulls & 4) ? NULL : f, (nulls & 8) ? NULL : statuses);
  check_status(status);
  if (nulls & 6) {
    contract(status == HCIMPACT_ERR_NULL, "contact_force_array: NULL");
  } else if (count < 1) {
    contract(status == HCIMPACT_ERR_SIZE, "contact_force_array: size");
  } else {
    for (i = 0; i < count; ++i) {
      int one_status = hcimpact_contact_force(c[i], n[i], b[i], x[i], v[i], &one);
      if (!(nulls & 8)) contract(statuses[i] == one_status, "contact_force_array: status");
      if (first == HCIMPACT_OK) first = one_status;
      contract(memcmp(&one, &f[i], sizeof one) == 0, "contact_force_array differs");
    }
    contract(status == first, "contact_force_array: not the first error");
  }
  /* pair and wall: positions near each other or raw */
  distance = fabs(next_double(s));
  q1 = next_double(s);
  q2 = (next_byte(s) & 1) ? q1 + distance - fabs(x[1]) : next_double(s);
  status = hcimpact_contact_force_pair(c[1], n[1], b[1], distance, q1, v[1], q2, v[2],
                                       (nulls & 16) ? NULL : &one);
  if (nulls & 16) {
    contract(status == HCIMPACT_ERR_NULL, "contact_force_pair: NULL");
  } else {
    check_force(status, &one, NAN, "contact_force_pair: outputs");
  }
  wall = (next_byte(s) & 1) ? q1 + distance - fabs(x[2]) : next_double(s);
  status = hcimpact_contact_force_wall(c[2], n[2], b[2], distance, q1, v[3], wall,
                                       (int)(next_byte(s) % 4) - 1, (nulls & 32) ? NULL : &one);
  if (nulls & 32) {
    contract(status == HCIMPACT_ERR_NULL, "contact_force_wall: NULL");
  } else {
    check_force(status, &one, NAN, "contact_force_wall: outputs");
  }
}

#ifdef HCIMPACT_FUZZ_CVODE
static void fuzz_simulate(stream *s)
{
  hcimpact_contact c = next_contact(s);
  hcimpact_outcome o;
  double rtol = next_double(s);
  int status;
  /* the ODE is slow at tight tolerances: mostly loose ones */
  if (next_byte(s) & 1) rtol = 1e-3 + fmod(fabs(rtol), 0.1);
  status = hcimpact_simulate(&c, rtol, &o);
  check_status(status);
  if (status != HCIMPACT_OK) {
    double fields[OUTCOME_FIELDS];
    memcpy(fields, &o, sizeof fields);
    contract(all_nan(fields, OUTCOME_FIELDS), "simulate: not NaN on error");
  } else {
    contract(o.restitution > 0.0 && o.restitution <= 1.0 && o.energy_loss_ratio >= 0.0
             && o.energy_loss_ratio <= 1.0, "simulate: k outside (0, 1] with status OK");
  }
  contract(hcimpact_simulate(NULL, rtol, &o) == HCIMPACT_ERR_NULL, "simulate: NULL");
}

/* hcimpact_simulate_message: the same status, a message cut to the buffer, always
   terminated */
static void fuzz_simulate_message(stream *s)
{
  hcimpact_contact c = next_contact(s);
  hcimpact_outcome o, plain;
  char message[80];
  size_t size = next_byte(s) % (sizeof message + 1);
  double rtol = 1e-3 + fmod(fabs(next_double(s)), 0.1);
  uint8_t nulls = next_byte(s);
  int status, plain_status;
  memset(message, 'x', sizeof message);
  status = hcimpact_simulate_message(&c, rtol, &o, (nulls & 1) ? NULL : message, size);
  check_status(status);
  plain_status = hcimpact_simulate(&c, rtol, &plain);
  contract(status == plain_status, "simulate_message: status differs from simulate");
  contract(memcmp(&o, &plain, sizeof o) == 0, "simulate_message: outcome differs");
  if ((nulls & 1) || size == 0) {
    size_t i;
    for (i = 0; i < sizeof message; ++i) contract(message[i] == 'x', "simulate_message: wrote");
  } else {
    contract(memchr(message, '\0', size) != NULL, "simulate_message: not terminated");
    if (size > 1) contract(message[0] != '\0', "simulate_message: empty");
  }
}

/* a small system of bodies (1 to 3, walls or not) with bounded work */
static void fuzz_chain(stream *s)
{
  double masses[3], velocities[3], gaps[2], positions[3], finals[3];
  double times[4], spos[12], svel[12], sforce[16];
  hcimpact_chain_law laws[2];
  hcimpact_chain_wall walls[2];
  hcimpact_chain_options options;
  hcimpact_chain_result result;
  hcimpact_chain_contact contacts[4];
  hcimpact_chain_samples samples;
  char message[128];
  int n = (int)(next_byte(s) % 5) - 1, capacity = (int)(next_byte(s) % 6) - 1, i, status;
  int bad_size, null_options;
  uint8_t nulls = next_byte(s), opt = next_byte(s);
  double gravity = (opt & 1) ? next_double(s) : 0.0;
  if (n > 3) n = 3;
  if (capacity > 4) capacity = 4;
  for (i = 0; i < 3; ++i) {
    masses[i] = next_double(s);
    velocities[i] = next_double(s);
  }
  for (i = 0; i < 2; ++i) {
    gaps[i] = (opt & 2) ? next_double(s) : fabs(next_double(s));
    laws[i].stiffness = next_double(s);
    laws[i].exponent = 0.25 + fmod(fabs(next_double(s)), 4.0);
    laws[i].damping = fabs(next_double(s));
    walls[i].stiffness = next_double(s);
    walls[i].exponent = 0.25 + fmod(fabs(next_double(s)), 4.0);
    walls[i].damping = fabs(next_double(s));
    walls[i].gap = fabs(next_double(s));
  }
  memset(&options, 0, sizeof options);
  options.t_end = (opt & 4) ? next_double(s) : 0.0;
  options.rtol = (opt & 8) ? next_double(s) : 1e-4;
  options.max_steps = 2000;   /* bounded work per input */
  options.max_events = 200;
  options.method = (int)(next_byte(s) % 4);
  options.integrator = (int)(next_byte(s) % 3);
  samples.count = (int)(next_byte(s) % 6) - 1;
  if (samples.count > 4) samples.count = 4;
  for (i = 0; i < 4; ++i) times[i] = fabs(next_double(s));
  if (opt & 16) {
    for (i = 1; i < 4; ++i) {
      if (times[i] < times[i - 1]) times[i] = times[i - 1];
    }
  }
  samples.times = times;
  samples.positions = spos;
  samples.velocities = svel;
  samples.forces = sforce;
  memset(&result, 0x2a, sizeof result);
  null_options = (nulls & 2) && (chain_mode == chain_full || n < 1 || (nulls & 1));
  status = hcimpact_chain_simulate(n, (nulls & 1) ? NULL : masses, velocities, gaps, laws,
                                   (opt & 32) ? &walls[0] : NULL, (opt & 64) ? &walls[1] : NULL,
                                   gravity, null_options ? NULL : &options,
                                   (nulls & 4) ? NULL : &result, positions, finals, capacity,
                                   (nulls & 8) ? NULL : contacts, (opt & 128) ? &samples : NULL,
                                   message, sizeof message);
  check_status(status);
  contract(memchr(message, '\0', sizeof message) != NULL, "chain: message not terminated");
  if (nulls & 4) {
    contract(status == HCIMPACT_ERR_NULL, "chain: NULL result");
    return;
  }
  bad_size = n < 1 || capacity < 0 || ((opt & 128) && samples.count < 0);
  if (bad_size && !(nulls & 3) && !((nulls & 8) && capacity > 0)) {
    contract(status == HCIMPACT_ERR_SIZE, "chain: size not detected");
  }
  if (status == HCIMPACT_ERR_NULL || status == HCIMPACT_ERR_SIZE) {
    hcimpact_chain_result untouched;
    memset(&untouched, 0x2a, sizeof untouched);
    if (status == HCIMPACT_ERR_NULL || bad_size) {
      contract(memcmp(&result, &untouched, sizeof result) == 0, "chain: wrote on NULL/size");
    } else {
      /* the other size error: sample times that decrease */
      contract(opt & 128, "chain: size error with good sizes");
    }
    return;
  }
  if (verbose) {
    fprintf(stderr, "chain: n %d, status %d (%s), time %.17g, initial energy %.17g, "
            "dissipated %.17g, energy error %.17g, contacts %lld\n", n, status, message,
            result.time, result.initial_energy, result.dissipated, result.energy_error,
            (long long)result.n_contacts);
    for (i = 0; i < n; ++i) {
      fprintf(stderr, "  body %d: mass %.17g, velocity %.17g\n", i, masses[i], velocities[i]);
    }
    for (i = 0; i + 1 < n; ++i) {
      fprintf(stderr, "  pair %d: gap %.17g, law %.17g %.17g %.17g\n", i, gaps[i],
              laws[i].stiffness, laws[i].exponent, laws[i].damping);
    }
    for (i = 0; i < 2; ++i) {
      if (opt & (32 << i)) {
        fprintf(stderr, "  wall %s: gap %.17g, law %.17g %.17g %.17g\n", i ? "right" : "left",
                walls[i].gap, walls[i].stiffness, walls[i].exponent, walls[i].damping);
      }
    }
    fprintf(stderr, "  gravity %.17g, t_end %.17g, rtol %.17g, method %d, integrator %d, "
            "options %s\n", gravity, options.t_end, options.rtol, options.method,
            options.integrator, null_options ? "NULL" : "given");
  }
  if (status == HCIMPACT_OK) {
    contract(isfinite(result.time) && result.time >= 0.0 && isfinite(result.initial_energy)
             && result.initial_energy >= 0.0 && isfinite(result.dissipated)
             && result.dissipated >= 0.0 && !isnan(result.energy_error),
             "chain: result not finite or negative");
    contract(result.n_contacts >= 0
             && result.contacts_recorded
                  == (result.n_contacts < capacity ? result.n_contacts : capacity),
             "chain: contacts recorded not min(count, capacity)");
    for (i = 0; i < n; ++i) {
      contract(!isnan(positions[i]) && !isnan(finals[i]), "chain: NaN position or velocity");
    }
  } else {
    contract(isnan(result.time) && isnan(result.initial_energy) && isnan(result.dissipated)
             && result.n_contacts == 0 && result.contacts_recorded == 0,
             "chain: result not NaN/0 on error");
    for (i = 0; i < n; ++i) {
      contract(isnan(positions[i]) && isnan(finals[i]), "chain: outputs not NaN on error");
    }
  }
}
#endif

#ifdef HCIMPACT_FUZZ_LAPACK
static void fuzz_fits(stream *s)
{
  double a[MAX_N], b[MAX_N], c[MAX_N], d[MAX_N], res[3 * MAX_N], p[3], cov[9], guess[3];
  double damping, error;
  int n = next_size(s), i;
  uint8_t which = next_byte(s), opt = next_byte(s);
  for (i = 0; i < MAX_N; ++i) {
    a[i] = next_double(s);
    b[i] = next_double(s);
    c[i] = next_double(s);
    d[i] = fabs(next_double(s));
  }
  for (i = 0; i < 3; ++i) guess[i] = next_double(s);
  switch (which % 5) {
  case 0:
    check_status(hcimpact_fit_damping(n, a, b, (opt & 1) ? d : NULL, opt & 2, &damping,
                                      (opt & 4) ? &error : NULL, (opt & 8) ? res : NULL));
    break;
  case 1:
    check_status(hcimpact_fit_damping_linear(n, a, b, (opt & 1) ? d : NULL, opt & 2, &damping,
                                             (opt & 4) ? &error : NULL,
                                             (opt & 8) ? res : NULL));
    break;
  case 2:
    check_status(hcimpact_fit_static(n, a, b, (opt & 1) ? d : NULL, opt & 2, p,
                                     (opt & 4) ? cov : NULL, (opt & 8) ? res : NULL));
    break;
  case 3:
    check_status(hcimpact_fit_elastic(n, fabs(guess[0]), fabs(guess[1]), a,
                                      (opt & 16) ? b : NULL, (opt & 32) ? c : NULL,
                                      (opt & 1) ? d : NULL, (opt & 64) ? d : NULL, opt & 2,
                                      (opt & 128) ? guess : NULL, p, (opt & 4) ? cov : NULL,
                                      (opt & 8) ? res : NULL));
    break;
  default:
    check_status(hcimpact_fit_impact(n, fabs(guess[0]), a, (opt & 16) ? b : NULL,
                                     (opt & 32) ? c : NULL, (opt & 64) ? d : NULL,
                                     (opt & 1) ? d : NULL, NULL, NULL, opt & 2,
                                     (opt & 128) ? guess : NULL, p, (opt & 4) ? cov : NULL,
                                     (opt & 8) ? res : NULL));
    break;
  }
}
#endif

static void fuzz_misc(stream *s)
{
  int code = (int)((next_byte(s) << 8) | next_byte(s)) - 32768;
  const char *m = hcimpact_status_message(code);
  contract(m != NULL && m[0] != '\0', "status message empty");
  contract(hcimpact_version() != NULL, "version NULL");
  contract(hcimpact_version_number() == HCIMPACT_VERSION, "version number");
  contract(hcimpact_array_threads() >= 1, "array threads below 1");
}

/* gfortran -fsanitize-coverage=trace-cmp calls these at floating-point comparisons;
   libFuzzer has hooks for the integer ones only (__sanitizer_cov_trace_cmp1..8,
   _const_cmp*, _switch), so these two take the calls and do nothing */
void __sanitizer_cov_trace_cmpf(float a, float b);
void __sanitizer_cov_trace_cmpd(double a, double b);
void __sanitizer_cov_trace_cmpf(float a, float b)
{
  (void)a;
  (void)b;
}
void __sanitizer_cov_trace_cmpd(double a, double b)
{
  (void)a;
  (void)b;
}

#ifdef HCIMPACT_FUZZ_FPE
/* trap invalid operations, divisions by zero and overflows like -ffpe-trap (SIGFPE) */
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  return 0;
}
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  stream s;
  s.data = data;
  s.size = size;
  have_contact = 0;
  if (verbose < 0) verbose = getenv("HCIMPACT_FUZZ_VERBOSE") != NULL;
  if (chain_mode < 0) {
    const char *mode = getenv("HCIMPACT_FUZZ_CHAIN");
    chain_mode = mode == NULL ? chain_bounded : strcmp(mode, "0") == 0 ? chain_off : chain_full;
  }
  switch (next_byte(&s) % 14) {
  case 0:
  case 1: fuzz_scalars(&s); break;
  case 2: fuzz_arrays(&s); break;
  case 3: fuzz_two_bodies(&s); break;
  case 4:
  case 5: fuzz_impact(&s); break;
  case 6: fuzz_impact_array(&s); break;
  case 7: fuzz_trajectory(&s); break;
  case 8: fuzz_impact_law(&s); break;
  case 9: fuzz_force(&s); break;
#ifdef HCIMPACT_FUZZ_CVODE
  case 10: fuzz_simulate(&s); break;
  case 11:
    if ((next_byte(&s) & 1) && chain_mode != chain_off) {
      fuzz_chain(&s);
    } else {
      fuzz_simulate_message(&s);
    }
    break;
#endif
#ifdef HCIMPACT_FUZZ_LAPACK
  case 12: fuzz_fits(&s); break;
#endif
  default: fuzz_misc(&s); break;
  }
  return 0;
}
