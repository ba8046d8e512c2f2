/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The array forms against the scalar forms, element by element, bit for bit, with the
 * library sharing the arrays among threads (OpenMP, when it is built with it): every
 * array form of the C interface and the FORTRAN 77 array routines, at sizes above the
 * thresholds at which they go parallel (src/hcimpact/parallel.f90) and below them, on
 * inputs drawn over whole domains with failures at random places (NaN, out of domain);
 * the status of an array call must be that of its lowest failing index, each element's
 * status that of the scalar call, outputs in place too.
 *
 * Usage: arrays EXPECTED_THREADS. hcimpact_array_threads() must equal it (the CTest
 * tests set OMP_NUM_THREADS and pass the number, or 1 for a library without OpenMP),
 * so that a build that silently stayed serial fails. Exit status 0 on success.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hcimpact.h"

/* the FORTRAN 77 array routines (gfortran's names: lower case and an underscore) */
void hcresa_(const int *n, const double *beta, double *rk, int *info);
void hcrsia_(const int *n, const double *e, double *beta, int *info);
void hcimpa_(const int *ni, const double *m, const double *c, const double *en,
             const double *b, const double *v, double *out, int *istat, int *info);
void hcfrca_(const int *n, const double *c, const double *en, const double *b,
             const double *x, const double *xdot, double *f, int *istat, int *info);

static int failures = 0;

static void check(int ok, const char *what) {
  if (!ok) {
    ++failures;
    fprintf(stderr, "FAIL: %s\n", what);
  }
}

/* xorshift64*: reproducible inputs */
static uint64_t state = 0x9e3779b97f4a7c15ULL;
static double uniform(void) {
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return (double)((state * 0x2545f4914f6cdd1dULL) >> 11) * 0x1.0p-53;
}
/* a double spread over the decades [10^lo, 10^hi] */
static double decades(double lo, double hi) { return pow(10.0, lo + (hi - lo) * uniform()); }

/* same bits (NaNs of any payload count as equal: the libraries' NaN is one quiet NaN,
   but the test asks for the same value, not the same payload) */
static int same(double a, double b) {
  if (isnan(a) && isnan(b)) return 1;
  return memcmp(&a, &b, sizeof a) == 0;
}
static int same_array(const double *a, const double *b, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!same(a[i], b[i])) return 0;
  return 1;
}

typedef double (*scalar_fn)(double);
typedef int (*array_fn)(int, const double *, double *);

/* one function of one argument: array form vs scalar form, out of place and in place */
static void cheap(const char *name, scalar_fn f, array_fn fa, int n, double lo, double hi,
                  int signed_inputs) {
  double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *z = malloc(n * sizeof *z);
  char what[160];
  if (!x || !y || !z) {
    check(0, "out of memory in the test");
    free(x), free(y), free(z);
    return;
  }
  for (int i = 0; i < n; ++i) {
    x[i] = decades(lo, hi);
    if (signed_inputs && uniform() < 0.5) x[i] = -x[i];
    if (uniform() < 1e-3) x[i] = NAN;
  }
  int status = fa(n, x, y);
  snprintf(what, sizeof what, "%s_array(%d): status %d", name, n, status);
  check(status == HCIMPACT_OK, what);
  for (int i = 0; i < n; ++i) z[i] = f(x[i]);
  snprintf(what, sizeof what, "%s_array(%d) equals the scalar form bit for bit", name, n);
  check(same_array(y, z, n), what);
  status = fa(n, x, x); /* in place */
  snprintf(what, sizeof what, "%s_array(%d) in place", name, n);
  check(status == HCIMPACT_OK && same_array(x, z, n), what);
  free(x), free(y), free(z);
}

static hcimpact_contact random_contact(void) {
  hcimpact_contact c;
  c.mass = decades(-6, 4);
  c.stiffness = decades(3, 12);
  c.exponent = 0.5 + 2.0 * uniform();
  c.damping = uniform() < 0.2 ? 0.0 : decades(-4, 1);
  c.velocity = decades(-3, 2);
  return c;
}

/* a contact broken in one of its fields, in turn */
static void spoil(hcimpact_contact *c, int how) {
  switch (how % 5) {
  case 0: c->mass = -1.0; break;
  case 1: c->stiffness = NAN; break;
  case 2: c->exponent = 0.0; break;
  case 3: c->damping = -1.0; break;
  default: c->velocity = INFINITY; break;
  }
}

static void impacts(int n) {
  hcimpact_contact *c = malloc(n * sizeof *c);
  hcimpact_outcome *out = malloc(n * sizeof *out), one;
  int *st = malloc(n * sizeof *st), first = -1, first_status = HCIMPACT_OK;
  double *m = malloc(5 * n * sizeof *m), *out77 = malloc(8 * n * sizeof *out77);
  int *st77 = malloc(n * sizeof *st77), info;
  char what[160];
  if (!c || !out || !st || !m || !out77 || !st77) {
    check(0, "out of memory in the test");
    goto done;
  }
  for (int i = 0; i < n; ++i) {
    c[i] = random_contact();
    if (uniform() < 0.05) spoil(&c[i], i);
  }
  int status = hcimpact_impact_array(n, c, out, st);
  int ok = 1;
  for (int i = 0; i < n; ++i) {
    int s = hcimpact_impact(&c[i], &one);
    if (s != HCIMPACT_OK && first < 0) first = i, first_status = s;
    ok = ok && s == st[i] && same_array((const double *)&one, (const double *)&out[i], 9);
  }
  snprintf(what, sizeof what, "impact_array(%d) equals hcimpact_impact bit for bit", n);
  check(ok, what);
  snprintf(what, sizeof what, "impact_array(%d): status %d, of the first failure %d", n,
           status, first_status);
  check(status == first_status, what);
  /* without statuses: the same status */
  check(hcimpact_impact_array(n, c, out, NULL) == first_status, "impact_array without statuses");

  /* HCIMPA: the same impacts, INFO the first failing index (1-based) */
  for (int i = 0; i < n; ++i) {
    m[i] = c[i].mass, m[n + i] = c[i].stiffness, m[2 * n + i] = c[i].exponent;
    m[3 * n + i] = c[i].damping, m[4 * n + i] = c[i].velocity;
  }
  hcimpa_(&n, m, m + n, m + 2 * n, m + 3 * n, m + 4 * n, out77, st77, &info);
  ok = info == first + 1;
  for (int i = 0; i < n; ++i) {
    ok = ok && st77[i] == st[i];
    /* OUT(1:8, I): the outcome without the time of the peak (HCIMPN's OUT(9)) */
    const double *o = (const double *)&out[i];
    if (st[i] == HCIMPACT_OK)
      ok = ok && same_array(out77 + 8 * i, o, 6) && same_array(out77 + 8 * i + 6, o + 7, 2);
  }
  snprintf(what, sizeof what, "HCIMPA(%d) equals the scalar impacts, INFO %d", n, info);
  check(ok, what);
done:
  free(c), free(out), free(st), free(m), free(out77), free(st77);
}

static void forces(int n) {
  double *p = malloc(5 * n * sizeof *p), *f77 = malloc(5 * n * sizeof *f77);
  hcimpact_force *f = malloc(n * sizeof *f), one;
  int *st = malloc(n * sizeof *st), *st77 = malloc(n * sizeof *st77);
  int first = -1, first_status = HCIMPACT_OK, info;
  char what[160];
  if (!p || !f77 || !f || !st || !st77) {
    check(0, "out of memory in the test");
    goto done;
  }
  double *c = p, *en = p + n, *b = p + 2 * n, *x = p + 3 * n, *v = p + 4 * n;
  for (int i = 0; i < n; ++i) {
    c[i] = decades(3, 12);
    en[i] = 0.5 + 2.0 * uniform();
    b[i] = decades(-4, 1);
    x[i] = (uniform() < 0.1 ? -1.0 : 1.0) * decades(-9, -2);
    v[i] = (uniform() < 0.5 ? -1.0 : 1.0) * decades(-3, 3); /* clamped where b v < -1 */
    if (uniform() < 2e-3) b[i] = -b[i];
    if (uniform() < 2e-3) x[i] = NAN;
  }
  int status = hcimpact_contact_force_array(n, c, en, b, x, v, f, st);
  int ok = 1;
  for (int i = 0; i < n; ++i) {
    int s = hcimpact_contact_force(c[i], en[i], b[i], x[i], v[i], &one);
    if (s != HCIMPACT_OK && first < 0) first = i, first_status = s;
    ok = ok && s == st[i] && same_array((const double *)&one, (const double *)&f[i], 5);
  }
  snprintf(what, sizeof what, "contact_force_array(%d) equals the scalar form bit for bit", n);
  check(ok, what);
  snprintf(what, sizeof what, "contact_force_array(%d): status %d, of the first failure %d",
           n, status, first_status);
  check(status == first_status, what);
  hcfrca_(&n, c, en, b, x, v, f77, st77, &info);
  ok = info == first + 1;
  for (int i = 0; i < n; ++i)
    ok = ok && st77[i] == st[i] && same_array(f77 + 5 * i, (const double *)&f[i], 5);
  snprintf(what, sizeof what, "HCFRCA(%d) equals the scalar form, INFO %d", n, info);
  check(ok, what);
done:
  free(p), free(f77), free(f), free(st), free(st77);
}

static void depths(int n) {
  double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v), one;
  char what[160];
  hcimpact_outcome out;
  hcimpact_contact c = {0.1, 1e9, 1.5, 0.3, 2.0};
  if (!x || !v || hcimpact_impact(&c, &out) != HCIMPACT_OK) {
    check(0, "set-up of velocity_at_depth_array");
    free(x), free(v);
    return;
  }
  for (int branch = HCIMPACT_COMPRESSION_BRANCH; branch <= HCIMPACT_RESTITUTION_BRANCH; ++branch) {
    for (int i = 0; i < n; ++i) x[i] = out.max_compression * uniform();
    int status = hcimpact_velocity_at_depth_array(&c, n, x, branch, v);
    int ok = status == HCIMPACT_OK;
    for (int i = 0; ok && i < n; ++i) {
      int s = hcimpact_velocity_at_depth(&c, x[i], branch, &one);
      ok = s == HCIMPACT_OK && same(one, v[i]);
    }
    snprintf(what, sizeof what, "velocity_at_depth_array(%d, branch %d) equals the scalar form",
             n, branch);
    check(ok, what);
  }
  /* two bad depths: the status of the lower one, every velocity NaN (in place too) */
  int lo = n / 3, hi = (2 * n) / 3;
  x[hi] = -1.0;
  x[lo] = 2.0 * out.max_compression;
  int expect = hcimpact_velocity_at_depth(&c, x[lo], HCIMPACT_COMPRESSION_BRANCH, &one);
  int status = hcimpact_velocity_at_depth_array(&c, n, x, HCIMPACT_COMPRESSION_BRANCH, x);
  int ok = expect != HCIMPACT_OK && status == expect;
  for (int i = 0; ok && i < n; ++i) ok = isnan(x[i]);
  snprintf(what, sizeof what, "velocity_at_depth_array(%d) with bad depths: status %d (%d)",
           n, status, expect);
  check(ok, what);
  free(x), free(v);
}

/* HCRESA and HCRSIA against the scalar C functions; INFO -2 when some element is NaN */
static void f77_restitution(int n) {
  double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
  int info, ok = 1;
  char what[160];
  if (!x || !y) {
    check(0, "out of memory in the test");
    free(x), free(y);
    return;
  }
  for (int i = 0; i < n; ++i) x[i] = decades(-6, 6);
  hcresa_(&n, x, y, &info);
  for (int i = 0; i < n; ++i) ok = ok && same(y[i], hcimpact_restitution(x[i]));
  snprintf(what, sizeof what, "HCRESA(%d) equals hcimpact_restitution, INFO %d", n, info);
  check(ok && info == 0, what);
  for (int i = 0; i < n; ++i) x[i] = uniform();
  x[n - 1] = -0.5; /* out of (0, 1]: INFO -2 from the last element */
  hcrsia_(&n, x, y, &info);
  ok = 1;
  for (int i = 0; i < n; ++i) ok = ok && same(y[i], hcimpact_restitution_inverse(x[i]));
  snprintf(what, sizeof what, "HCRSIA(%d) equals hcimpact_restitution_inverse, INFO %d", n, info);
  check(ok && info == -2, what);
  free(x), free(y);
}

int main(int argc, char **argv) {
  int expected = argc > 1 ? atoi(argv[1]) : 1;
  int threads = hcimpact_array_threads();
  printf("hcimpact_array_threads() = %d (expected %d)\n", threads, expected);
  check(threads == expected, "hcimpact_array_threads() is the number of threads asked for");

  /* sizes below and above the thresholds of src/hcimpact/parallel.f90 */
  const int cheap_sizes[] = {1, 1000, 3 * 32768 + 17};
  for (int k = 0; k < 3; ++k) {
    int n = cheap_sizes[k];
    cheap("lambert_w0", hcimpact_lambert_w0, hcimpact_lambert_w0_array, n, -300, 300, 0);
    cheap("lambert_wm1", hcimpact_lambert_wm1, hcimpact_lambert_wm1_array, n, -300, -0.4343, 1);
    cheap("lambert_w0p1", hcimpact_lambert_w0p1, hcimpact_lambert_w0p1_array, n, -300, 300, 0);
    cheap("lambert_wm1p1", hcimpact_lambert_wm1p1, hcimpact_lambert_wm1p1_array, n, -300, 300, 0);
    cheap("restitution", hcimpact_restitution, hcimpact_restitution_array, n, -20, 40, 1);
    cheap("restitution_inverse", hcimpact_restitution_inverse, hcimpact_restitution_inverse_array,
          n, -300, 0.1, 0);
    cheap("one_minus_restitution", hcimpact_one_minus_restitution,
          hcimpact_one_minus_restitution_array, n, -20, 40, 1);
    cheap("energy_loss_ratio", hcimpact_energy_loss_ratio, hcimpact_energy_loss_ratio_array, n,
          -20, 40, 1);
    cheap("restitution_derivative", hcimpact_restitution_derivative,
          hcimpact_restitution_derivative_array, n, -20, 40, 1);
    depths(n < 2 ? 3 : n);
    f77_restitution(n);
  }
  const int force_sizes[] = {1, 100, 3 * 4096 + 5};
  for (int k = 0; k < 3; ++k) forces(force_sizes[k]);
  const int impact_sizes[] = {1, 15, 400};
  for (int k = 0; k < 3; ++k) impacts(impact_sizes[k]);

  if (failures) {
    fprintf(stderr, "%d check(s) failed\n", failures);
    return 1;
  }
  printf("array forms: bit-identical to the scalar forms\n");
  return 0;
}
