/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Out of memory, hcimpact_chain_simulate returns HCIMPACT_ERR_OUT_OF_MEMORY (the
 * system is too large for the memory) with a message that says so, never a crash or an abort
 * of the Fortran runtime. Three systems of n bodies (default 100 000), each with
 * four sample times and a contact array of n records:
 *   - a row of balls with gaps, neighbours approaching in pairs (method auto: n / 2
 *     contacts by the closed forms, the list of contacts growing),
 *   - a row of touching balls, the first struck (method auto: a cluster that grows),
 *   - the same, n / 10 bodies, with method integrated (CVODE for the whole system
 *     from the start).
 * Each call runs in a child process (fork) whose address space is capped (setrlimit
 * RLIMIT_AS) at what it already uses plus a headroom growing from 256 KiB in steps
 * of a quarter of an input array (2 n bytes) until the call succeeds, so that the
 * allocations fail one after the other at every depth (the copies of the input, the
 * engine's arrays, the regions, CVODE's vectors and band matrix, the samples, the
 * result). A child that dies from a signal (an unchecked automatic array or
 * temporary: NULL dereferenced), exits with the Fortran runtime's error (1 or 2:
 * "Error allocating ... bytes") or returns anything but HCIMPACT_OK or
 * HCIMPACT_ERR_OUT_OF_MEMORY with "out of memory" in the message fails the test.
 *
 * Linux (fork, setrlimit, /proc/self/statm). Usage: chain_memory_test [n >= 1000
 * [case 0 to 2 [headroom in KiB]]]: a case alone runs in this process, without a cap or
 * with that headroom (e.g. under a debugger).
 * Exit status 0 on success.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../memory_limit.h"

#include "hcimpact_cvode.h"

enum { ROW_WITH_GAPS, TOUCHING_AUTO, TOUCHING_INTEGRATED, N_CASES };
static const char *case_names[N_CASES] = {"row with gaps, auto", "touching, auto",
                                          "touching, integrated"};

/* what a child reports (its exit status minus 40) besides a status */
enum { WRONG_MESSAGE = 50 };

typedef struct {
  int n;
  double *m, *v, *gap, *x, *vf, *sx, *sv, *sf;
  hcimpact_chain_law *law;
  hcimpact_chain_contact *contacts;
} data_t;

static void *array(size_t count, size_t size)
{
  void *a = calloc(count, size);
  if (a == NULL) {
    fprintf(stderr, "cannot allocate the test data\n");
    exit(2);
  }
  return a;
}

/* steel balls of 10 mm (Hertz), lightly damped */
static void make_data(data_t *d, int n)
{
  int i;
  d->n = n;
  d->m = array((size_t)n, sizeof(double));
  d->v = array((size_t)n, sizeof(double));
  d->gap = array((size_t)n, sizeof(double));
  d->law = array((size_t)n, sizeof(hcimpact_chain_law));
  d->x = array((size_t)n, sizeof(double));
  d->vf = array((size_t)n, sizeof(double));
  d->sx = array((size_t)n * 4, sizeof(double));
  d->sv = array((size_t)n * 4, sizeof(double));
  d->sf = array((size_t)(n + 1) * 4, sizeof(double));
  d->contacts = array((size_t)n, sizeof(hcimpact_chain_contact));
  for (i = 0; i < n; ++i) {
    d->m[i] = 4.1e-3;
    d->law[i].stiffness = 8.6e9;
    d->law[i].exponent = 1.5;
    d->law[i].damping = 0.01;
  }
}

/* Touch a few MiB of stack, so that the children's stack need not grow: a stack
   growing into the cap is SIGSEGV from the kernel, whatever the library does (the
   heap alone is the library's to check) */
static void grow_stack(void)
{
  volatile char block[(size_t)4 << 20];
  size_t i;
  for (i = 0; i < sizeof block; i += 4096) block[i] = 0;
}

/* bodies of a case */
static int bodies(const data_t *d, int which)
{
  return which == TOUCHING_INTEGRATED ? d->n / 10 : d->n;
}

/* one call; its status, or WRONG_MESSAGE for HCIMPACT_ERR_OUT_OF_MEMORY without "out of
 * memory" */
static int run_case(const data_t *d, int which)
{
  const double times[4] = {1e-6, 5e-6, 1e-5, 5.5e-4};
  hcimpact_chain_options options;
  hcimpact_chain_samples samples;
  hcimpact_chain_result result;
  char message[256];
  int i, n, stat;

  memset(&options, 0, sizeof options);
  for (i = 0; i < d->n; ++i) {
    if (which == ROW_WITH_GAPS)
      d->v[i] = i % 2 == 0 ? 1.0 : -1.0;
    else
      d->v[i] = i == 0 ? 1.0 : 0.0;
    d->gap[i] = which == ROW_WITH_GAPS ? 1e-3 : 0.0;
  }
  if (which == ROW_WITH_GAPS) {
    /* the n / 2 pairs meet at 0.5 ms, each contact isolated */
    options.t_end = 6e-4;
  } else {
    options.t_end = 2e-5;
    if (which == TOUCHING_INTEGRATED) options.method = HCIMPACT_CHAIN_INTEGRATED;
  }
  samples.count = 4;
  samples.times = times;
  samples.positions = d->sx;
  samples.velocities = d->sv;
  samples.forces = d->sf;
  n = bodies(d, which);
  stat = hcimpact_chain_simulate(n, d->m, d->v, d->gap, d->law, NULL, NULL, 0.0, &options,
                                 &result, d->x, d->vf, n, d->contacts, &samples, message,
                                 sizeof message);
  if (stat == HCIMPACT_ERR_OUT_OF_MEMORY && strstr(message, "out of memory") == NULL) {
    fprintf(stderr, "%s: %s\n", case_names[which], message);
    return WRONG_MESSAGE;
  }
  if (stat != HCIMPACT_OK && stat != HCIMPACT_ERR_OUT_OF_MEMORY)
    fprintf(stderr, "%s: status %d: %s\n", case_names[which], stat, message);
  return stat;
}

/* the headrooms of one case until it succeeds; 0 when every child passed */
static int try_case(const data_t *d, int which)
{
  size_t step = (size_t)bodies(d, which) * 2, start = (size_t)1 << 18;
  size_t limit = (size_t)bodies(d, which) * 4000 + ((size_t)64 << 20);
  size_t headroom;
  int stopped = 0;

  for (headroom = start; headroom < limit; headroom += step) {
    int wstatus = 0, outcome;
    pid_t pid;
    fflush(stdout);
    fflush(stderr);
    pid = fork();
    if (pid < 0) return 2;
    if (pid == 0) {
      if (cap_address_space(headroom) != 0) _exit(100);
      /* (40 + outcome: the Fortran runtime's own abort exits with 1 or 2) */
      _exit(40 + run_case(d, which));
    }
    if (waitpid(pid, &wstatus, 0) != pid) return 2;
    if (WIFSIGNALED(wstatus)) {
      printf("FAIL %s, headroom %.2f MiB: killed by signal %d\n", case_names[which],
             headroom / 1048576.0, WTERMSIG(wstatus));
      return 1;
    }
    outcome = WEXITSTATUS(wstatus) - 40;
    if (outcome == HCIMPACT_OK) {
      printf("%s, %d bodies: HCIMPACT_ERR_OUT_OF_MEMORY at %d headrooms from %.2f MiB, "
             "success at %.2f MiB\n", case_names[which], bodies(d, which), stopped,
             start / 1048576.0, headroom / 1048576.0);
      return stopped > 0 ? 0 : 1;
    }
    if (outcome != HCIMPACT_ERR_OUT_OF_MEMORY) {
      printf("FAIL %s, headroom %.2f MiB: exit status %d (%s)\n", case_names[which],
             headroom / 1048576.0, WEXITSTATUS(wstatus),
             outcome == WRONG_MESSAGE ? "HCIMPACT_ERR_OUT_OF_MEMORY without \"out of memory\""
                                      : "not a status of the library");
      return 1;
    }
    ++stopped;
  }
  printf("FAIL %s: no success within %.0f MiB\n", case_names[which], limit / 1048576.0);
  return 1;
}

int main(int argc, char **argv)
{
  int n = argc > 1 ? atoi(argv[1]) : 100000;
  int which, failed = 0;
  data_t d;

  if (n < 1000) {
    fprintf(stderr, "usage: chain_memory_test [n >= 1000]\n");
    return 2;
  }
  make_data(&d, n);
  grow_stack();
  if (argc > 2) {
    /* one case in this process, without a cap (timing) or with a headroom in KiB (to
       run under a debugger) */
    which = atoi(argv[2]);
    if (which < 0 || which >= N_CASES) return 2;
    if (argc > 3 && cap_address_space((size_t)atol(argv[3]) * 1024) != 0) return 2;
    return run_case(&d, which);
  }
  /* (no call without a cap first: the heap it leaves would serve the children) */
  for (which = 0; which < N_CASES; ++which)
    if (try_case(&d, which) != 0) failed = 1;
  return failed;
}
