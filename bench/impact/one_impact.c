/* SPDX-License-Identifier: Apache-2.0 */
/* The cost of one impact as a user meets it (issue 17): hcimpact_impact of a shared
 * library called through the C API, contacts drawn at random and visited in a fresh
 * random order every pass, thread CPU time, rounds in which every library is timed once
 * (in an order alternating between rounds), the median of the per-round times and of
 * the per-round ratios to the first library.
 *
 * Usage: bench_one_impact [options] LIB [LIB ...]
 *   LIB            path of a libhcimpact.so (the first is the reference of the ratios;
 *                  bench/impact/run.sh passes the current build and a baseline revision)
 *   --rounds R     rounds (default 15)
 *   --count N      contacts per group (default 65536)
 *   --seed S       random seed (default 20261125)
 *   --group G      only one group: "low" (beta <= 100) or "high" (100 < beta <= 1e8)
 *   --beta LO HI   one group instead, beta log-uniform in [LO, HI] (to count the work of
 *                  one regime, e.g. with callgrind)
 *   --lambertw     time hcimpact_lambert_w0 and hcimpact_lambert_wm1 instead, on four
 *                  groups of arguments (W0 on (-1/e, 0) and on [e, 1e300], W-1 on
 *                  (-1/e, 0), both next to the branch point, z + 1/e in [1e-15, 1e-2]):
 *                  the same protocol, to compare two builds of the library
 *
 * The contacts of a group: n log-uniform in [0.5, 3] with a quarter exactly 1.5 (Hertz),
 * beta = b V log-uniform in [1e-3, 100] (low) or (100, 1e8] (high), m, c, V
 * log-uniform over three decades each (the outcome scales with them; the work does
 * not). Every library computes the same contacts; their outcomes are compared bit for
 * bit and differences are counted (a faster library must give the same answers). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct {
    double mass, stiffness, exponent, damping, velocity;
} contact;
typedef struct {
    double v[9];
} outcome;
typedef int (*impact_fn)(const contact *, outcome *);
typedef double (*lambert_fn)(double);

enum { max_libs = 4 };

static uint64_t rng_state;

static double uniform(void)
{
    /* splitmix64: a fixed stream for a given seed */
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

static double log_uniform(double lo, double hi)
{
    return lo * pow(hi / lo, uniform());
}

static double thread_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void shuffle(size_t *order, size_t count)
{
    for (size_t i = count - 1; i > 0; --i) {
        size_t j = (size_t)(uniform() * (double)(i + 1));
        size_t t = order[i];
        order[i] = order[j];
        order[j] = t;
    }
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *values, size_t count)
{
    qsort(values, count, sizeof *values, compare_doubles);
    return count % 2 ? values[count / 2] : 0.5 * (values[count / 2 - 1] + values[count / 2]);
}

/* What is timed: the impacts of the libraries on `contacts`, or one Lambert W function
 * of each library on `z`; each library's results in its own buffer */
typedef struct {
    int nlibs;
    impact_fn impact[max_libs];
    lambert_fn w[max_libs];
    const contact *contacts; /* the impacts, or NULL: the Lambert W function on z */
    const double *z;
    void *results[max_libs];
    size_t failures[max_libs];
} workload;

/* One pass of library l over all inputs in the given order: nanoseconds per call; the
 * number of failed impacts in failures[l] */
static double time_pass(workload *work, int l, const size_t *order, size_t count)
{
    size_t failed = 0;
    double t0 = thread_seconds();
    if (work->contacts) {
        outcome *out = work->results[l];
        for (size_t i = 0; i < count; ++i) {
            size_t k = order[i];
            failed += work->impact[l](&work->contacts[k], &out[k]) != 0;
        }
    } else {
        double *out = work->results[l];
        for (size_t i = 0; i < count; ++i) {
            size_t k = order[i];
            out[k] = work->w[l](work->z[k]);
        }
    }
    double t1 = thread_seconds();
    work->failures[l] = failed;
    return 1e9 * (t1 - t0) / (double)count;
}

/* One untimed pass per library (page in code and data), then the rounds: in each, every
 * library one pass in a fresh order (the libraries' order alternating between rounds).
 * Per library l: the sorted times per call in per_round[l * rounds ...], the sorted
 * per-round ratios to library 0 in ratios[l * rounds ...], and their medians */
static void run_rounds(workload *work, int rounds, size_t *order, size_t count,
                       double *per_round, double *ratios, double *time_median,
                       double *ratio_median)
{
    for (size_t i = 0; i < count; ++i) order[i] = i;
    for (int l = 0; l < work->nlibs; ++l) time_pass(work, l, order, count);
    for (int r = 0; r < rounds; ++r) {
        double t[max_libs];
        for (int s = 0; s < work->nlibs; ++s) {
            int l = (r % 2) ? work->nlibs - 1 - s : s;
            shuffle(order, count);
            t[l] = time_pass(work, l, order, count);
        }
        for (int l = 0; l < work->nlibs; ++l) {
            per_round[l * rounds + r] = t[l];
            ratios[l * rounds + r] = t[l] / t[0];
        }
    }
    for (int l = 0; l < work->nlibs; ++l) {
        time_median[l] = median(&per_round[l * rounds], (size_t)rounds);
        ratio_median[l] = median(&ratios[l * rounds], (size_t)rounds);
    }
}

/* How many of library l's results are not bit-identical to library 0's */
static size_t count_differing(const workload *work, int l, size_t count, size_t size)
{
    const unsigned char *a = work->results[l], *b = work->results[0];
    size_t differing = 0;
    for (size_t i = 0; i < count; ++i)
        differing += memcmp(a + i * size, b + i * size, size) != 0;
    return differing;
}

static void make_group(contact *contacts, size_t count, double beta_lo, double beta_hi)
{
    for (size_t i = 0; i < count; ++i) {
        contact *c = &contacts[i];
        c->mass = log_uniform(1e-3, 1.0);
        c->stiffness = log_uniform(1e8, 1e11);
        c->exponent = (i % 4 == 0) ? 1.5 : log_uniform(0.5, 3.0);
        c->velocity = log_uniform(0.1, 100.0);
        c->damping = log_uniform(beta_lo, beta_hi) / c->velocity;
    }
}

/* The Lambert W groups: the same rounds, ratios and bit-identity counts as the impacts */
static void run_lambertw(workload *work, lambert_fn *w0, lambert_fn *wm1, const char **paths,
                         int rounds, size_t count, double *z, size_t *order,
                         double *per_round, double *ratios)
{
    const char *group_text[4] = {"W0, z in (-1/e, 0)", "W0, z in [e, 1e300]",
                                 "W-1, z in (-1/e, 0)", "W-1, z + 1/e in [1e-15, 1e-2]"};
    const double inv_e = 0.36787944117144233;
    double tmed[max_libs], rmed[max_libs];
    printf("| arguments | library | ns per call (median of %d rounds) | min | max |"
           " ratio to the first (median, min, max) | results differing |\n", rounds);
    printf("|---|---|---:|---:|---:|---|---:|\n");
    work->contacts = NULL;
    work->z = z;
    for (int g = 0; g < 4; ++g) {
        for (size_t i = 0; i < count; ++i) {
            switch (g) {
            case 0: case 2: z[i] = -inv_e * uniform(); break;
            case 1: z[i] = log_uniform(2.718281828459045, 1e300); break;
            default: z[i] = -inv_e + log_uniform(1e-15, 1e-2); break;
            }
        }
        for (int l = 0; l < work->nlibs; ++l) work->w[l] = (g < 2) ? w0[l] : wm1[l];
        run_rounds(work, rounds, order, count, per_round, ratios, tmed, rmed);
        for (int l = 0; l < work->nlibs; ++l) {
            double *tl = &per_round[l * rounds], *rl = &ratios[l * rounds];
            printf("| %s | %s | %.1f | %.1f | %.1f | %.3f (%.3f, %.3f) | %zu |\n",
                   group_text[g], paths[l], tmed[l], tl[0], tl[rounds - 1], rmed[l], rl[0],
                   rl[rounds - 1], count_differing(work, l, count, sizeof(double)));
        }
    }
}

int main(int argc, char **argv)
{
    int rounds = 15;
    size_t count = 65536;
    const char *only = NULL;
    double beta_range[2] = {0.0, 0.0};
    int lambertw = 0;
    const char *paths[max_libs];
    int nlibs = 0;
    rng_state = 20261125u;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--rounds") && i + 1 < argc) rounds = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--count") && i + 1 < argc) count = (size_t)atol(argv[++i]);
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc) rng_state = (uint64_t)atoll(argv[++i]);
        else if (!strcmp(argv[i], "--group") && i + 1 < argc) only = argv[++i];
        else if (!strcmp(argv[i], "--beta") && i + 2 < argc) {
            beta_range[0] = atof(argv[++i]);
            beta_range[1] = atof(argv[++i]);
            if (!(beta_range[0] > 0.0 && beta_range[1] >= beta_range[0])) {
                fprintf(stderr, "bench_one_impact: --beta needs 0 < LO <= HI\n");
                return 2;
            }
        } else if (!strcmp(argv[i], "--lambertw")) lambertw = 1;
        else if (argv[i][0] == '-') {
            fprintf(stderr, "bench_one_impact: unknown option %s\n", argv[i]);
            return 2;
        } else if (nlibs < max_libs) paths[nlibs++] = argv[i];
        else {
            fprintf(stderr, "bench_one_impact: at most %d libraries\n", max_libs);
            return 2;
        }
    }
    if (nlibs == 0 || rounds < 1 || count < 2) {
        fprintf(stderr, "usage: bench_one_impact [--rounds R] [--count N] [--seed S] "
                        "[--group low|high] [--beta LO HI] [--lambertw] LIB [LIB ...]\n");
        return 2;
    }
    workload work = {.nlibs = nlibs};
    lambert_fn w0[max_libs], wm1[max_libs];
    for (int l = 0; l < nlibs; ++l) {
        /* RTLD_LOCAL|RTLD_DEEPBIND: each copy keeps its own symbols */
        void *handle = dlopen(paths[l], RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
        if (!handle) {
            fprintf(stderr, "bench_one_impact: %s\n", dlerror());
            return 1;
        }
        work.impact[l] = (impact_fn)dlsym(handle, "hcimpact_impact");
        w0[l] = (lambert_fn)dlsym(handle, "hcimpact_lambert_w0");
        wm1[l] = (lambert_fn)dlsym(handle, "hcimpact_lambert_wm1");
        if (!work.impact[l] || !w0[l] || !wm1[l]) {
            fprintf(stderr, "bench_one_impact: %s: not an hcimpact library\n", paths[l]);
            return 1;
        }
    }

    contact *contacts = malloc(count * sizeof *contacts);
    double *z = malloc(count * sizeof *z);
    size_t *order = malloc(count * sizeof *order);
    double *per_round = malloc((size_t)rounds * max_libs * sizeof *per_round);
    double *ratios = malloc((size_t)rounds * max_libs * sizeof *ratios);
    int ok = contacts && z && order && per_round && ratios;
    for (int l = 0; l < nlibs; ++l) {
        work.results[l] = malloc(count * sizeof(outcome)); /* room for a double too */
        ok = ok && work.results[l];
    }
    if (!ok) {
        fprintf(stderr, "bench_one_impact: out of memory\n");
        return 1;
    }
    if (lambertw) {
        run_lambertw(&work, w0, wm1, paths, rounds, count, z, order, per_round, ratios);
        return 0;
    }

    const char *group_name[2] = {"low", "high"};
    const char *group_text[2] = {"beta <= 100", "100 < beta <= 1e8"};
    double beta_lo[2] = {1e-3, 100.0}, beta_hi[2] = {100.0, 1e8};
    char beta_text[64];
    if (beta_range[0] > 0.0) {
        /* one group of the given range, in the place of "low" */
        snprintf(beta_text, sizeof beta_text, "%g <= beta <= %g", beta_range[0], beta_range[1]);
        group_text[0] = beta_text;
        beta_lo[0] = beta_range[0];
        beta_hi[0] = beta_range[1];
        only = group_name[0];
    }
    double tmed[max_libs], rmed[max_libs];
    printf("| contacts | library | ns per impact (median of %d rounds) | min | max |"
           " ratio to the first (median, min, max) | failures | outcomes differing |\n",
           rounds);
    printf("|---|---|---:|---:|---:|---|---:|---:|\n");
    work.contacts = contacts;
    for (int g = 0; g < 2; ++g) {
        if (only && strcmp(only, group_name[g])) continue;
        make_group(contacts, count, beta_lo[g], beta_hi[g]);
        run_rounds(&work, rounds, order, count, per_round, ratios, tmed, rmed);
        for (int l = 0; l < nlibs; ++l) {
            double *tl = &per_round[l * rounds], *rl = &ratios[l * rounds];
            printf("| %s | %s | %.0f | %.0f | %.0f | %.3f (%.3f, %.3f) | %zu | %zu |\n",
                   group_text[g], paths[l], tmed[l], tl[0], tl[rounds - 1], rmed[l], rl[0],
                   rl[rounds - 1], work.failures[l],
                   count_differing(&work, l, count, sizeof(outcome)));
        }
    }
    return 0;
}
