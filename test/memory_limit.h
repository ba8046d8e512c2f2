/* SPDX-License-Identifier: Apache-2.0 */
/* The out-of-memory tests' one helper (test/cvode/memory_test.c,
 * test/cvode/chain_memory_test.c, test/lapack/memory_test.c): cap this process's
 * address space (setrlimit(RLIMIT_AS)) at the virtual memory it holds now plus a
 * headroom, in the child each test forks per call. Linux only (/proc/self/statm). */
#ifndef HCIMPACT_TEST_MEMORY_LIMIT_H
#define HCIMPACT_TEST_MEMORY_LIMIT_H

#include <stddef.h>
#include <stdio.h>
#include <sys/resource.h>
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

/* cap the address space at what is used now plus headroom bytes: 0, or -1 when the
 * use cannot be read or the limit not set */
static inline int cap_address_space(size_t headroom)
{
  struct rlimit cap;
  size_t used = address_space();
  if (used == 0) return -1;
  cap.rlim_cur = cap.rlim_max = (rlim_t)(used + headroom);
  return setrlimit(RLIMIT_AS, &cap) == 0 ? 0 : -1;
}

#endif
