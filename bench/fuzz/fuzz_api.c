/* SPDX-License-Identifier: Apache-2.0 */
/*
 * libFuzzer target over the C interface of hcimpact (include/hcimpact.h): the input
 * bytes choose an entry point and supply its arguments, as raw IEEE doubles (NaN,
 * infinities, subnormals, huge values, signed zeros) or as "physical" doubles
 * (2^e * [1, 2) with |e| <= 64, so that valid contacts and deep code paths are common),
 * plus sizes, branches and NULL pointers. Every entry point of the core library is
 * reached; with HCIMPACT_FUZZ_CVODE / HCIMPACT_FUZZ_LAPACK also hcimpact_simulate and
 * the calibration fits.
 *
 * Besides crashes and sanitizer reports, the target checks the contract of the header
 * and aborts (a crash for libFuzzer) when it is broken:
 *  - every status is HCIMPACT_OK or a documented code (1 .. 15);
 *  - NULL pointers give HCIMPACT_ERR_NULL and write nothing; bad sizes give
 *    HCIMPACT_ERR_SIZE and write nothing;
 *  - on an error every output is NaN; on success an impact's outputs are not NaN and
 *    0 < k <= 1;
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
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hcimpact.h"
#include "hcimpact_cvode.h"
#include "hcimpact_lapack.h"

#define MAX_N 16

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
    for (i = 0; i < 8; ++i) bits = (bits << 8) | next_byte(s);
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
  contract(status >= HCIMPACT_OK && status <= HCIMPACT_ERR_UNDERDETERMINED, "unknown status");
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
  double fields[8];
  check_status(status);
  memcpy(fields, o, sizeof fields);
  if (status == HCIMPACT_OK) {
    int i;
    for (i = 0; i < 8; ++i) {
      if (isnan(fields[i])) fprintf(stderr, "outcome field %d is NaN\n", i);
      contract(!isnan(fields[i]), "NaN in a successful outcome");
    }
    contract(o->restitution > 0.0 && o->restitution <= 1.0, "k outside (0, 1]");
  } else {
    contract(status != HCIMPACT_ERR_NULL, "NULL status without a NULL pointer");
    contract(all_nan(fields, 8), "outcome not NaN on error");
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
    volatile double c = hcimpact_hertz_constant(a[0], a[1], a[2], a[3], a[4], a[5]);
    volatile double m = hcimpact_effective_mass(a[0], a[1]);
    (void)c;
    (void)m;
  }
  status = hcimpact_two_body_velocities(a[0], a[1], a[2], a[3], a[4], (nulls & 1) ? NULL : &v1,
                                        (nulls & 2) ? NULL : &v2);
  check_status(status);
  if (nulls & 3) {
    contract(status == HCIMPACT_ERR_NULL && v1 == 42.0 && v2 == 42.0, "two bodies: NULL");
  } else if (status != HCIMPACT_OK) {
    contract(isnan(v1) && isnan(v2), "two bodies: not NaN on error");
  }
  status = hcimpact_damping_for_restitution(a[0], a[1], a[2], (nulls & 16) ? NULL : &damping);
  check_status(status);
  if (nulls & 16) {
    contract(status == HCIMPACT_ERR_NULL && damping == 42.0, "damping: NULL");
  } else if (status != HCIMPACT_OK) {
    contract(isnan(damping), "damping: not NaN on error");
  } else {
    contract(damping >= 0.0, "damping negative");
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
    contract(!isnan(vel), "velocity_at_depth: NaN on success");
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
    for (i = 0; i < n; ++i) {
      if (!(x[i] >= 0.0 && f[i] >= 0.0)) {
        fprintf(stderr, "time_law at t = %.17g: x = %.17g, v = %.17g, F = %.17g\n", t[i], x[i],
                v[i], f[i]);
      }
      contract(x[i] >= 0.0 && f[i] >= 0.0, "time_law: x or F < 0");
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
    double fields[8];
    memcpy(fields, &o, sizeof fields);
    contract(all_nan(fields, 8), "simulate: not NaN on error");
  } else {
    contract(o.restitution > 0.0 && o.restitution <= 1.0 && o.energy_loss_ratio >= 0.0
             && o.energy_loss_ratio <= 1.0, "simulate: k outside (0, 1] with status OK");
  }
  contract(hcimpact_simulate(NULL, rtol, &o) == HCIMPACT_ERR_NULL, "simulate: NULL");
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
  switch (next_byte(&s) % 10) {
  case 0:
  case 1: fuzz_scalars(&s); break;
  case 2: fuzz_arrays(&s); break;
  case 3: fuzz_two_bodies(&s); break;
  case 4:
  case 5: fuzz_impact(&s); break;
  case 6: fuzz_impact_array(&s); break;
  case 7: fuzz_trajectory(&s); break;
#ifdef HCIMPACT_FUZZ_CVODE
  case 8: fuzz_simulate(&s); break;
#endif
#ifdef HCIMPACT_FUZZ_LAPACK
  case 9: fuzz_fits(&s); break;
#endif
  default: fuzz_misc(&s); break;
  }
  return 0;
}
