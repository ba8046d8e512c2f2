/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Out of memory, the calibration fits return a status: HCIMPACT_ERR_OUT_OF_MEMORY (the
 * data are too large for the memory the fit needs; not HCIMPACT_ERR_SIZE, a wrong
 * size), every output NaN, never a crash or an abort of the Fortran runtime. Each fit runs in a child process (fork) whose
 * address space is capped (setrlimit RLIMIT_AS) at what it already uses plus a
 * headroom; the headroom grows in steps of half an input array until the fit
 * succeeds, so that the allocations fail one after the other at every depth of
 * the fit (the copies of the inputs, the model's arrays, the Jacobian, LAPACK's
 * workspace, the singular value decomposition, the residuals). A child that dies
 * from a signal (an unchecked automatic array: NULL dereferenced) or exits with
 * anything but HCIMPACT_OK or HCIMPACT_ERR_OUT_OF_MEMORY fails the test.
 *
 * Linux (fork, setrlimit, /proc/self/statm). Usage: memory_test [log2 of the points
 * of the linear fits, default 20].
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../memory_limit.h"

#include "hcimpact_lapack.h"

enum { FIT_DAMPING, FIT_DAMPING_LINEAR, FIT_STATIC, FIT_ELASTIC, FIT_IMPACT, N_FITS };
static const char *fit_names[N_FITS] = {"fit_damping", "fit_damping_linear", "fit_static",
                                         "fit_elastic", "fit_impact"};

typedef struct {
  int n;
  double *v, *e, *sigma, *x, *f, *t, *fm, *out;
} data_t;

static double *array(int n)
{
  double *a = malloc((size_t)n * sizeof *a);
  if (a == NULL) {
    fprintf(stderr, "cannot allocate the test data\n");
    exit(2);
  }
  return a;
}

/* the seed's steel ball: restitution at b = 0.1 s/m, a static curve, Hertz impacts */
static void make_data(data_t *d, int n)
{
  const double mass = 0.1, c = 1.7135e10, nexp = 1.5, b = 0.1;
  const double hertz_time = 2.9432751843247047; /* t_c V / x_max at b = 0, n = 3/2 */
  int i;
  d->n = n;
  d->v = array(n);
  d->e = array(n);
  d->sigma = array(n);
  d->x = array(n);
  d->f = array(n);
  d->t = array(n);
  d->fm = array(n);
  d->out = array(3 * n + 16);
  for (i = 0; i < n; ++i) {
    double u = (double)i / n, x_max;
    d->v[i] = 0.5 + 4.5 * u;
    d->e[i] = hcimpact_restitution(b * d->v[i]) * (1.0 + 1e-3 * sin(7.0 * i));
    d->sigma[i] = 0.01;
    d->x[i] = 2.0e-6 * pow(50.0, u);
    d->f[i] = c * pow(d->x[i], nexp) * (1.0 + 1e-3 * cos(3.0 * i));
    x_max = pow((nexp + 1.0) * mass * d->v[i] * d->v[i] / (2.0 * c), 1.0 / (nexp + 1.0));
    d->t[i] = hertz_time * x_max / d->v[i] * (1.0 + 1e-4 * sin(5.0 * i));
    d->fm[i] = c * pow(x_max, nexp) * (1.0 + 1e-4 * cos(2.0 * i));
  }
}

static int run_fit(int which, const data_t *d)
{
  double *o = d->out;
  switch (which) {
  case FIT_DAMPING:
    return hcimpact_fit_damping(d->n, d->v, d->e, d->sigma, 0, &o[0], &o[1], &o[2]);
  case FIT_DAMPING_LINEAR:
    return hcimpact_fit_damping_linear(d->n, d->v, d->e, d->sigma, 0, &o[0], &o[1], &o[2]);
  case FIT_STATIC:
    return hcimpact_fit_static(d->n, d->x, d->f, NULL, 0, &o[0], &o[2], &o[6]);
  case FIT_ELASTIC:
    return hcimpact_fit_elastic(d->n, 0.1, 0.0, d->v, d->t, d->fm, NULL, NULL, 0, NULL, &o[0],
                                &o[2], &o[6]);
  default:
    return hcimpact_fit_impact(d->n, 0.1, d->v, d->t, d->fm, d->e, NULL, NULL, NULL, 0, NULL,
                               &o[0], &o[3], &o[12]);
  }
}

/* the fit in a child capped at its present address space + headroom: the child's
   exit status is the fit's status (-1 for a signal, -2 when fork fails) */
static int capped_fit(int which, const data_t *d, size_t headroom, int *signal_number)
{
  pid_t pid;
  int wstatus = 0;
  *signal_number = 0;
  fflush(stdout);
  pid = fork();
  if (pid < 0) return -2;
  if (pid == 0) {
    if (cap_address_space(headroom) != 0) _exit(100);
    /* the outputs must be NaN on HCIMPACT_ERR_OUT_OF_MEMORY (the rule of any error but
       a NULL pointer or a wrong size) */
    d->out[0] = 42.0;
    {
      int status = run_fit(which, d);
      if (status == HCIMPACT_ERR_OUT_OF_MEMORY && !isnan(d->out[0])) _exit(101);
      _exit(status);
    }
  }
  if (waitpid(pid, &wstatus, 0) != pid) return -2;
  if (WIFSIGNALED(wstatus)) {
    *signal_number = WTERMSIG(wstatus);
    return -1;
  }
  return WEXITSTATUS(wstatus);
}

int main(int argc, char **argv)
{
  int log2_points = argc > 1 ? atoi(argv[1]) : 20;
  data_t large, small;
  int which, failures = 0;

  if (log2_points < 10 || log2_points > 26) {
    fprintf(stderr, "usage: memory_test [log2 of the points, 10 ... 26]\n");
    return 2;
  }
  make_data(&large, 1 << log2_points);
  /* the nonlinear impact fits cost a closed-form impact per point and step */
  make_data(&small, 1 << (log2_points - 8));

  for (which = 0; which < N_FITS; ++which) {
    const data_t *d = which >= FIT_ELASTIC ? &small : &large;
    size_t step = (size_t)d->n * sizeof(double) / 2, headroom = step;
    size_t limit = 200 * (size_t)d->n * sizeof(double) + ((size_t)64 << 20);
    int status = HCIMPACT_ERR_OUT_OF_MEMORY, signal_number = 0, tries = 0, clean_failures = 0;
    while (headroom < limit) {
      status = capped_fit(which, d, headroom, &signal_number);
      ++tries;
      if (status == HCIMPACT_OK) break;
      if (status == HCIMPACT_ERR_OUT_OF_MEMORY) {
        ++clean_failures;
      } else {
        if (status == -1) {
          printf("FAIL %s, %d points, headroom %.1f MiB: killed by signal %d\n",
                 fit_names[which], d->n, headroom / 1048576.0, signal_number);
        } else if (status == 101) {
          printf("FAIL %s, %d points, headroom %.1f MiB: HCIMPACT_ERR_OUT_OF_MEMORY left an "
                 "output not NaN\n",
                 fit_names[which], d->n, headroom / 1048576.0);
        } else {
          printf("FAIL %s, %d points, headroom %.1f MiB: exit status %d\n", fit_names[which],
                 d->n, headroom / 1048576.0, status);
        }
        ++failures;
        break;
      }
      headroom += step;
    }
    if (status == HCIMPACT_OK) {
      printf("%-18s %8d points: HCIMPACT_ERR_OUT_OF_MEMORY at %d headrooms from %.0f KiB, "
             "success at %.1f MiB\n", fit_names[which], d->n, clean_failures, step / 1024.0,
             headroom / 1048576.0);
    } else if (status == HCIMPACT_ERR_OUT_OF_MEMORY) {
      printf("FAIL %s: no success up to a headroom of %.1f MiB\n", fit_names[which],
             limit / 1048576.0);
      ++failures;
    }
    (void)tries;
  }
  if (failures > 0) {
    printf("%d fit(s) failed out of memory\n", failures);
    return 1;
  }
  printf("out of memory: every fit returned HCIMPACT_ERR_OUT_OF_MEMORY with NaN outputs, or "
         "succeeded\n");
  return 0;
}
