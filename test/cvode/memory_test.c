/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Out of memory while CVODE records a trajectory (options%record_trajectory): the
 * run stops with HCIMPACT_ERR_SOLVER and "out of memory recording the trajectory",
 * never a crash or an abort of the Fortran runtime. A long recorded integration
 * (memory_case.f90; 200 000 steps by default: arrays of 6 MiB, 12 MiB while they
 * double) runs in child processes (fork) whose address space is capped (setrlimit
 * RLIMIT_AS) at what they use plus a headroom growing from 1 MiB (enough for
 * CVODE's setup) in steps of a sixteenth of the trajectory until the run completes;
 * the growth of the arrays then fails at every size in between.
 *
 * Linux (fork, setrlimit, /proc/self/statm). Usage: memory_test [steps >= 10000].
 * Exit status 0 on success.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../memory_limit.h"

int recorded_run(int max_steps);

int main(int argc, char **argv)
{
  int steps = argc > 1 ? atoi(argv[1]) : 200000;
  /* a trajectory sample: four doubles */
  size_t step = (size_t)steps * 32 / 16, limit = (size_t)steps * 32 * 4 + ((size_t)16 << 20);
  size_t headroom;
  int stopped = 0;

  if (steps < 10000) {
    fprintf(stderr, "usage: memory_test [steps >= 10000]\n");
    return 2;
  }
  for (headroom = (size_t)1 << 20; headroom < limit; headroom += step) {
    int wstatus = 0, outcome;
    pid_t pid;
    fflush(stdout);
    pid = fork();
    if (pid < 0) return 2;
    if (pid == 0) {
      if (cap_address_space(headroom) != 0) _exit(100);
      /* (40 + outcome: the Fortran runtime's own abort exits with 1 or 2) */
      _exit(40 + recorded_run(steps));
    }
    if (waitpid(pid, &wstatus, 0) != pid) return 2;
    if (WIFSIGNALED(wstatus)) {
      printf("FAIL headroom %.1f MiB: killed by signal %d\n", headroom / 1048576.0,
             WTERMSIG(wstatus));
      return 1;
    }
    outcome = WEXITSTATUS(wstatus) - 40;
    if (outcome == 0) {
      printf("recorded run of %d steps: out-of-memory status at %d headrooms from 1 MiB, "
             "complete at %.1f MiB\n", steps, stopped, headroom / 1048576.0);
      return stopped > 0 ? 0 : 1;
    }
    if (outcome != 1) {
      printf("FAIL headroom %.1f MiB: exit status %d\n", headroom / 1048576.0,
             WEXITSTATUS(wstatus));
      return 1;
    }
    ++stopped;
  }
  printf("FAIL: the recorded run did not complete within %.0f MiB\n", limit / 1048576.0);
  return 1;
}
