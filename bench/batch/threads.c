/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bench_batch_threads: throughput of the array forms against the number of threads
 * (issue 17). The library shares a large array among OpenMP's threads; this program
 * sets that number with omp_set_num_threads (the same OpenMP runtime as the library's)
 * and times, round after round, every array form at every thread count, the counts in
 * a fresh random order each round. Each pass gets the inputs in a fresh random order
 * (shuffled outside the timed region), so that no branch predictor learns them.
 *
 * Reported per form and thread count: the median throughput (elements per second of
 * wall time) and the median over rounds of the per-round speed-up T(1)/T(k), with the
 * parallel efficiency speed-up / k. Wall time, since the point of threads is to cut it.
 *
 * Forms: hcimpact_impact_array (random contacts, beta = b V over [1e-3, 1e2] and a
 * quarter beyond, to 1e4), hcimpact_contact_force_array, hcimpact_lambert_w0_array,
 * hcimpact_restitution_array, hcimpact_velocity_at_depth_array.
 *
 * Usage: bench_batch_threads [--threads 1,2,4] [--rounds R] [--min-ms MS] [--quick]
 */
#define _POSIX_C_SOURCE 200112L
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hcimpact.h"

#define MAX_THREADS 16
#define MAX_ROUNDS 101

static uint64_t state = 0x243f6a8885a308d3ULL;
static uint64_t next64(void) {
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return state * 0x2545f4914f6cdd1dULL;
}
static double uniform(void) { return (double)(next64() >> 11) * 0x1.0p-53; }
static double decades(double lo, double hi) { return pow(10.0, lo + (hi - lo) * uniform()); }

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}
static double median(double *v, int n) {
  qsort(v, n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Fisher-Yates on records of `size` bytes */
static void shuffle(void *base, size_t n, size_t size, void *tmp) {
  char *b = base;
  for (size_t i = n - 1; i > 0; --i) {
    size_t j = (size_t)(next64() % (i + 1));
    memcpy(tmp, b + i * size, size);
    memcpy(b + i * size, b + j * size, size);
    memcpy(b + j * size, tmp, size);
  }
}

/* one form: its inputs, outputs, and a pass over them */
typedef struct {
  const char *name;
  int n;
  double *in;          /* n records of `fields` doubles (shuffled together) */
  int fields;
  void *out;
  hcimpact_contact contact; /* velocity_at_depth's contact */
  int (*pass)(void *self);
} form;

static int pass_impact(void *p) {
  form *f = p;
  return hcimpact_impact_array(f->n, (const hcimpact_contact *)f->in, f->out, NULL);
}
static int pass_force(void *p) {
  form *f = p;
  /* the records are (c, n, b, x, v): strided views are not what the API takes, so the
     five columns live after the records, rebuilt by prepare() */
  const double *col = f->in + (size_t)5 * f->n;
  int n = f->n;
  return hcimpact_contact_force_array(n, col, col + n, col + 2 * n, col + 3 * n,
                                      col + 4 * n, f->out, NULL);
}
static int pass_w0(void *p) {
  form *f = p;
  return hcimpact_lambert_w0_array(f->n, f->in, f->out);
}
static int pass_restitution(void *p) {
  form *f = p;
  return hcimpact_restitution_array(f->n, f->in, f->out);
}
static int pass_depth(void *p) {
  form *f = p;
  return hcimpact_velocity_at_depth_array(&f->contact, f->n, f->in,
                                          HCIMPACT_RESTITUTION_BRANCH, f->out);
}

/* a fresh order of the inputs before each pass */
static void prepare(form *f, void *tmp) {
  shuffle(f->in, (size_t)f->n, (size_t)f->fields * sizeof(double), tmp);
  if (f->pass == pass_force) {
    double *col = f->in + (size_t)5 * f->n;
    for (int i = 0; i < f->n; ++i)
      for (int k = 0; k < 5; ++k) col[(size_t)k * f->n + i] = f->in[(size_t)5 * i + k];
  }
}

static int parse_threads(const char *s, int *t) {
  int k = 0;
  while (*s && k < MAX_THREADS) {
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || v < 1 || v > 256) return -1;
    t[k++] = (int)v;
    s = *end == ',' ? end + 1 : end;
    if (*end && *end != ',') return -1;
  }
  return k;
}

int main(int argc, char **argv) {
  int threads[MAX_THREADS] = {1, 2, 4}, nthreads = 3, rounds = 15;
  double min_ms = 200.0;
  int quick = 0;
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
      nthreads = parse_threads(argv[++i], threads);
      if (nthreads < 1 || threads[0] != 1) {
        fprintf(stderr, "--threads: a list of counts from 1 to 256, the first 1\n");
        return 2;
      }
    } else if (!strcmp(argv[i], "--rounds") && i + 1 < argc) {
      rounds = atoi(argv[++i]);
      if (rounds < 1 || rounds > MAX_ROUNDS) {
        fprintf(stderr, "--rounds: 1 to %d\n", MAX_ROUNDS);
        return 2;
      }
    } else if (!strcmp(argv[i], "--min-ms") && i + 1 < argc) {
      min_ms = atof(argv[++i]);
    } else if (!strcmp(argv[i], "--quick")) {
      quick = 1;
    } else {
      fprintf(stderr, "usage: %s [--threads 1,2,4] [--rounds R] [--min-ms MS] [--quick]\n",
              argv[0]);
      return 2;
    }
  }
  if (quick) rounds = 3, min_ms = 20.0;
  int library_threads = hcimpact_array_threads(); /* before this program sets any */

  int n_impact = quick ? 1024 : 8192, n_big = quick ? 1 << 16 : 1 << 18;
  form forms[5];
  memset(forms, 0, sizeof forms);
  forms[0] = (form){"impact_array", n_impact, NULL, 5, NULL, {0}, pass_impact};
  forms[1] = (form){"contact_force_array", n_big, NULL, 5, NULL, {0}, pass_force};
  forms[2] = (form){"lambert_w0_array", n_big, NULL, 1, NULL, {0}, pass_w0};
  forms[3] = (form){"restitution_array", n_big, NULL, 1, NULL, {0}, pass_restitution};
  forms[4] = (form){"velocity_at_depth_array", n_big, NULL, 1, NULL, {0}, pass_depth};
  const int nforms = 5;
  double *tmp = malloc(5 * sizeof(double));
  for (int k = 0; k < nforms; ++k) {
    form *f = &forms[k];
    size_t doubles = (size_t)f->n * f->fields * (k == 1 ? 2 : 1);
    f->in = malloc(doubles * sizeof(double));
    f->out = malloc((size_t)f->n * (k == 0 ? sizeof(hcimpact_outcome)
                                           : k == 1 ? sizeof(hcimpact_force) : sizeof(double)));
    if (!f->in || !f->out || !tmp) {
      fprintf(stderr, "out of memory\n");
      return 1;
    }
  }
  for (int i = 0; i < n_impact; ++i) {
    hcimpact_contact *c = (hcimpact_contact *)forms[0].in + i;
    c->mass = decades(-3, 1);
    c->stiffness = decades(7, 11);
    c->exponent = 1.0 + uniform();
    c->velocity = decades(-2, 1);
    double beta = uniform() < 0.75 ? decades(-3, 2) : decades(2, 4);
    c->damping = beta / c->velocity;
  }
  for (int i = 0; i < n_big; ++i) {
    double *r = forms[1].in + (size_t)5 * i;
    r[0] = decades(7, 11), r[1] = 1.0 + uniform(), r[2] = decades(-3, 0);
    r[3] = decades(-8, -3), r[4] = (uniform() < 0.5 ? -1 : 1) * decades(-2, 1);
    forms[2].in[i] = uniform() < 0.2 ? -exp(-1.0) * uniform() : decades(-3, 30);
    forms[3].in[i] = decades(-4, 4);
  }
  hcimpact_contact steel = {0.1, 1.7135e10, 1.5, 0.1, 2.0};
  hcimpact_outcome o;
  if (hcimpact_impact(&steel, &o) != HCIMPACT_OK) return 1;
  forms[4].contact = steel;
  for (int i = 0; i < n_big; ++i) forms[4].in[i] = o.max_compression * uniform();

  /* every form at every thread count: check the status once, calibrate the passes per
     measurement so that one measurement at one thread lasts min_ms */
  int passes[5];
  for (int k = 0; k < nforms; ++k) {
    omp_set_num_threads(1);
    prepare(&forms[k], tmp);
    double t0 = now();
    int status = forms[k].pass(&forms[k]);
    double t1 = now() - t0;
    if (status != HCIMPACT_OK) {
      fprintf(stderr, "%s: status %d\n", forms[k].name, status);
      return 1;
    }
    passes[k] = (int)fmax(1.0, ceil(min_ms * 1e-3 / fmax(t1, 1e-7)));
  }

  static double seconds[5][MAX_THREADS][MAX_ROUNDS];
  int order[MAX_THREADS];
  for (int r = 0; r < rounds; ++r) {
    for (int j = 0; j < nthreads; ++j) order[j] = j;
    for (int j = nthreads - 1; j > 0; --j) {
      int s = (int)(next64() % (uint64_t)(j + 1)), t = order[j];
      order[j] = order[s], order[s] = t;
    }
    for (int k = 0; k < nforms; ++k)
      for (int jj = 0; jj < nthreads; ++jj) {
        int j = order[jj];
        omp_set_num_threads(threads[j]);
        double total = 0.0;
        for (int p = 0; p < passes[k]; ++p) {
          prepare(&forms[k], tmp);
          double t0 = now();
          forms[k].pass(&forms[k]);
          total += now() - t0;
        }
        seconds[k][j][r] = total / passes[k];
      }
  }

  printf("# bench_batch_threads: %d rounds; thread counts in a fresh random order each round\n",
         rounds);
  printf("# library %s; hcimpact_array_threads() at start: %d (1: built without OpenMP); "
         "omp_get_num_procs(): %d\n", hcimpact_version(), library_threads, omp_get_num_procs());
  printf("| form | n | threads | throughput (1e6 elements/s) | speed-up T(1)/T(k) | efficiency |\n");
  printf("|---|---|---|---|---|---|\n");
  for (int k = 0; k < nforms; ++k)
    for (int j = 0; j < nthreads; ++j) {
      double rate[MAX_ROUNDS], speedup[MAX_ROUNDS];
      for (int r = 0; r < rounds; ++r) {
        rate[r] = forms[k].n / seconds[k][j][r] * 1e-6;
        speedup[r] = seconds[k][0][r] / seconds[k][j][r];
      }
      double s = median(speedup, rounds);
      printf("| %s | %d | %d | %.3g | %.2f | %.2f |\n", forms[k].name, forms[k].n, threads[j],
             median(rate, rounds), s, s / threads[j]);
    }
  for (int k = 0; k < nforms; ++k) free(forms[k].in), free(forms[k].out);
  free(tmp);
  return 0;
}
