/* SPDX-License-Identifier: Apache-2.0 */
/* The out-of-memory tests' one helper (test/cvode/memory_test.c,
 * test/cvode/chain_memory_test.c, test/lapack/memory_test.c): the virtual memory this
 * process holds now, from which each test caps a child's address space
 * (setrlimit(RLIMIT_AS)) at that plus a headroom. Linux only (/proc/self/statm). */
#ifndef HCIMPACT_TEST_MEMORY_LIMIT_H
#define HCIMPACT_TEST_MEMORY_LIMIT_H

#include <stddef.h>
#include <stdio.h>
#include <unistd.h>

/* virtual memory of this process, bytes (0 when /proc cannot tell) */
static inline size_t address_space(void)
{
  unsigned long pages = 0;
  FILE *statm = fopen("/proc/self/statm", "r");
  if (statm == NULL) return 0;
  if (fscanf(statm, "%lu", &pages) != 1) pages = 0;
  fclose(statm);
  return (size_t)pages * (size_t)sysconf(_SC_PAGESIZE);
}

#endif
