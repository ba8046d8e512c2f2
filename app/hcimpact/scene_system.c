/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The part of the scene runner's operating-system layer (scene_system.f90) that Fortran
 * cannot reach through bind(C): C macros (SIGXFSZ, SIG_IGN) and errno.
 */
#include <errno.h>
#include <signal.h>
#include <stddef.h>
#include <string.h>

/*
 * Ignore SIGXFSZ and SIGPIPE, so that a write beyond a file size limit (ulimit -f) fails
 * with EFBIG, and a write to a pipe whose reader has gone with EPIPE, and each is
 * reported like a full disk, instead of killing the program halfway and leaving its
 * .partial files and new directories behind (the gfortran run-time library would
 * catch SIGXFSZ, print a backtrace and end the process).
 */
void hcimpact_scene_ignore_output_signals(void)
{
#ifdef SIGXFSZ
  signal(SIGXFSZ, SIG_IGN);
#endif
#ifdef SIGPIPE
  signal(SIGPIPE, SIG_IGN);
#endif
}

/*
 * The text of errno (the error of the C library call that failed last), copied into
 * buffer without a terminator; returns its length (at most size).
 */
size_t hcimpact_scene_error_text(char *buffer, size_t size)
{
  const char *text = strerror(errno);
  size_t length = strlen(text);
  if (length > size) length = size;
  memcpy(buffer, text, length);
  return length;
}
