/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The part of the scene runner's operating-system layer (scene_system.f90) that Fortran
 * cannot reach through bind(C): C macros (SIGXFSZ, SIG_IGN, O_NOFOLLOW, S_ISREG) and
 * errno.
 */
#if !defined(_XOPEN_SOURCE) && !defined(_GNU_SOURCE)
#define _XOPEN_SOURCE 700 /* O_NOFOLLOW (POSIX.1-2008), SIGXFSZ (XSI) */
#endif
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stddef.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

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

/*
 * The last bytes of the file path, at most size of them, into buffer: their number, or
 * -1 when path is not a regular file or cannot be read. A symbolic link is not followed
 * and a FIFO or a device is not read (opened without blocking, then refused), so that
 * nothing planted at path can make the program wait, read without end, or read what a
 * link points to.
 */
int hcimpact_scene_read_tail(const char *path, char *buffer, int size)
{
  struct stat info;
  off_t start = 0;
  int total = 0;
  int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return -1;
  if (size < 0 || fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd);
    return -1;
  }
  if (info.st_size > (off_t)size) start = info.st_size - (off_t)size;
  if (lseek(fd, start, SEEK_SET) == (off_t)-1) {
    close(fd);
    return -1;
  }
  while (total < size) {
    ssize_t got = read(fd, buffer + total, (size_t)(size - total));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      close(fd);
      return -1;
    }
    if (got == 0) break;
    total += (int)got;
  }
  close(fd);
  return total;
}
