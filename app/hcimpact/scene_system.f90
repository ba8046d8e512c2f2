! SPDX-License-Identifier: Apache-2.0
!> What the scene runner needs from the operating system and Fortran does not give, or
!> gives without telling of failures: whether a stream is a terminal, directories,
!> renaming and removing files, writing files and the standard output with every
!> failure seen (POSIX and the C library through `bind(C)`), a wall clock, and a pause.
!>
!> Results are written through the C library, not through Fortran units: gfortran 12
!> reports no error of a buffered write, flush or close (a file on a full disk, or
!> /dev/full, is "written" with iostat = 0 and cut at the last block that fitted).
!> fwrite, fflush, fsync and fclose each return a status, and every one is checked.
!> A file is created with fopen mode "wx" (C11): exclusive creation, which fails on an
!> existing name and follows no symbolic link (O_CREAT | O_EXCL).
!>
!> What bind(C) cannot reach (C macros, errno) is in scene_system.c: the text of the
!> last error of a C call, and ignoring SIGXFSZ and SIGPIPE so that a file size limit
!> or a closed pipe fails a write (EFBIG, EPIPE) instead of killing the program.
!>
!> The C names bound here are not module names of this program (gfortran miscompiles a
!> binding label equal to a module name).
module hcimpact_scene_system
   use, intrinsic :: iso_c_binding, only : c_int, c_char, c_null_char, c_ptr, c_null_ptr, &
      & c_associated, c_size_t, c_intptr_t
   use, intrinsic :: iso_fortran_env, only : int64
   implicit none
   private

   public :: is_terminal, make_directory, rename_path, remove_path
   public :: directory_exists, file_exists, wall_clock
   public :: output_file, create_file, write_file, flush_file, close_file, write_standard_output
   public :: last_system_error, ignore_output_signals, pause_microseconds, read_file_tail

   !> A file being written (a C stream)
   type :: output_file
      type(c_ptr) :: stream = c_null_ptr
   end type output_file

   interface
      function c_usleep(microseconds) bind(C, name="usleep") result(r)
         import :: c_int
         integer(c_int), value :: microseconds
         integer(c_int) :: r
      end function c_usleep
      function c_isatty(fd) bind(C, name="isatty") result(r)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: r
      end function c_isatty
      function c_mkdir(path, mode) bind(C, name="mkdir") result(r)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         ! mode_t is an unsigned int on Linux and the BSDs
         integer(c_int), value :: mode
         integer(c_int) :: r
      end function c_mkdir
      function c_rename(from, to) bind(C, name="rename") result(r)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: from(*), to(*)
         integer(c_int) :: r
      end function c_rename
      function c_read_tail(path, buffer, size) bind(C, name="hcimpact_scene_read_tail") &
            & result(n)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         character(kind=c_char), intent(out) :: buffer(*)
         integer(c_int), value :: size
         integer(c_int) :: n
      end function c_read_tail
      function c_remove(path) bind(C, name="remove") result(r)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: r
      end function c_remove
      function c_fopen(path, mode) bind(C, name="fopen") result(stream)
         import :: c_char, c_ptr
         character(kind=c_char), intent(in) :: path(*), mode(*)
         type(c_ptr) :: stream
      end function c_fopen
      function c_fwrite(buffer, size, count, stream) bind(C, name="fwrite") result(written)
         import :: c_char, c_size_t, c_ptr
         character(kind=c_char), intent(in) :: buffer(*)
         integer(c_size_t), value :: size, count
         type(c_ptr), value :: stream
         integer(c_size_t) :: written
      end function c_fwrite
      function c_fflush(stream) bind(C, name="fflush") result(r)
         import :: c_int, c_ptr
         type(c_ptr), value :: stream
         integer(c_int) :: r
      end function c_fflush
      function c_fileno(stream) bind(C, name="fileno") result(fd)
         import :: c_int, c_ptr
         type(c_ptr), value :: stream
         integer(c_int) :: fd
      end function c_fileno
      function c_fsync(fd) bind(C, name="fsync") result(r)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: r
      end function c_fsync
      function c_fclose(stream) bind(C, name="fclose") result(r)
         import :: c_int, c_ptr
         type(c_ptr), value :: stream
         integer(c_int) :: r
      end function c_fclose
      !> POSIX write(2); ssize_t has the width of a pointer on the POSIX ABIs
      function c_write(fd, buffer, count) bind(C, name="write") result(written)
         import :: c_int, c_char, c_size_t, c_intptr_t
         integer(c_int), value :: fd
         character(kind=c_char), intent(in) :: buffer(*)
         integer(c_size_t), value :: count
         integer(c_intptr_t) :: written
      end function c_write
      subroutine ignore_output_signals() bind(C, name="hcimpact_scene_ignore_output_signals")
      end subroutine ignore_output_signals
      function c_error_text(buffer, size) bind(C, name="hcimpact_scene_error_text") &
            & result(length)
         import :: c_char, c_size_t
         character(kind=c_char), intent(out) :: buffer(*)
         integer(c_size_t), value :: size
         integer(c_size_t) :: length
      end function c_error_text
   end interface

contains

   !> The text of the error of the C library call that failed last (errno), e.g. "No
   !> space left on device": to be asked right after the failure.
   function last_system_error() result(text)
      character(len=:), allocatable :: text
      character(kind=c_char) :: buffer(200)
      integer :: length, i
      length = int(c_error_text(buffer, int(size(buffer), c_size_t)))
      allocate(character(len=length) :: text)
      do i = 1, length
         text(i:i) = buffer(i)
      end do
   end function last_system_error

   !> Whether the file descriptor fd (1: standard output, 2: standard error) is a terminal.
   !> Sleep for about `microseconds` (less than a second; an interruption by a signal
   !> only shortens the pause).
   subroutine pause_microseconds(microseconds)
      integer, intent(in) :: microseconds
      integer(c_int) :: r
      r = c_usleep(int(min(max(microseconds, 0), 999999), c_int))
   end subroutine pause_microseconds

   function is_terminal(fd) result(yes)
      integer, intent(in) :: fd
      logical :: yes
      yes = c_isatty(int(fd, c_int)) == 1_c_int
   end function is_terminal

   !> Create the directory `path` and any missing parents (like mkdir -p); ok is
   !> .true. when the directory exists afterwards. `created` lists the lengths of the
   !> prefixes of `path` (parents, then `path` itself) this call created, in the order
   !> of creation, so that a failed run can remove them again, deepest first.
   subroutine make_directory(path, ok, created)
      character(len=*), intent(in) :: path
      logical, intent(out) :: ok
      integer, allocatable, intent(out) :: created(:)
      integer :: i, n
      allocate(created(0))
      ok = .false.
      n = len_trim(path)
      if (n == 0) return
      ! every parent, from the top, then the directory itself
      do i = 2, n + 1
         if (i <= n) then
            if (path(i:i) /= "/" .or. path(i - 1:i - 1) == "/") cycle
         end if
         if (directory_exists(path(1:i - 1))) cycle
         if (c_mkdir(c_string(path(1:i - 1)), int(o'777', c_int)) == 0_c_int) then
            created = [created, i - 1]
         else
            exit
         end if
      end do
      ok = directory_exists(path(1:n))
   end subroutine make_directory

   !> Whether `path` names an existing directory.
   function directory_exists(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      ! "dir/." exists only for a directory
      inquire(file=trim(path) // "/.", exist=yes)
   end function directory_exists

   !> Whether `path` names an existing file (or directory); a dangling symbolic link
   !> does not count.
   function file_exists(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      inquire(file=trim(path), exist=yes)
   end function file_exists

   !> The last `size` bytes (at most) of the regular file `path`, in `text`; `ok` is
   !> .false. (and `text` empty) when `path` is not a regular file or cannot be read: a
   !> symbolic link is not followed, a FIFO or a device not read (hcimpact_scene_read_tail).
   subroutine read_file_tail(path, size, text, ok)
      character(len=*), intent(in) :: path
      integer, intent(in) :: size
      character(len=:), allocatable, intent(out) :: text
      logical, intent(out) :: ok
      character(kind=c_char) :: buffer(max(size, 1))
      integer(c_int) :: n
      integer :: i
      n = c_read_tail(c_string(path), buffer, int(max(size, 0), c_int))
      ok = n >= 0_c_int
      allocate(character(len=max(int(n), 0)) :: text)
      do i = 1, len(text)
         text(i:i) = buffer(i)
      end do
   end subroutine read_file_tail

   !> Rename `from` to `to` (replacing a file, or a symbolic link itself, named `to`),
   !> atomically on one file system.
   subroutine rename_path(from, to, ok)
      character(len=*), intent(in) :: from, to
      logical, intent(out) :: ok
      ok = c_rename(c_string(from), c_string(to)) == 0_c_int
   end subroutine rename_path

   !> Remove the file, symbolic link (not its target) or empty directory `path`; ok
   !> (optional) says whether it was removed. Nothing happens if it does not exist.
   subroutine remove_path(path, ok)
      character(len=*), intent(in) :: path
      logical, intent(out), optional :: ok
      integer(c_int) :: r
      r = c_remove(c_string(path))
      if (present(ok)) ok = r == 0_c_int
   end subroutine remove_path

   !> Create the file `path` for writing: only if no file, directory or link of that
   !> name exists (exclusive creation, no link followed). ok is .false. otherwise, and
   !> `reason` says why.
   subroutine create_file(path, file, ok, reason)
      character(len=*), intent(in) :: path
      type(output_file), intent(out) :: file
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: reason
      file%stream = c_fopen(c_string(path), c_string("wx"))
      ok = c_associated(file%stream)
      if (.not. ok) reason = last_system_error()
   end subroutine create_file

   !> Write `text` to the file; ok is .false. if not all of it was written, and
   !> `reason` says why.
   subroutine write_file(file, text, ok, reason)
      type(output_file), intent(in) :: file
      character(len=*), intent(in) :: text
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: reason
      ok = c_associated(file%stream)
      if (.not. ok .or. len(text) == 0) return
      ok = c_fwrite(c_chars(text), 1_c_size_t, int(len(text), c_size_t), file%stream) &
         & == int(len(text), c_size_t)
      if (.not. ok) reason = last_system_error()
   end subroutine write_file

   !> Flush the file to the device (fflush, then fsync: a network file system may
   !> report a failed write only then) and close it; ok is .false. if any step
   !> failed, and `reason` says why. The stream is closed whatever happened before.
   !> Hand what was written so far to the operating system (fflush): it survives the
   !> program being killed. ok is .false. if that failed, and `reason` says why.
   subroutine flush_file(file, ok, reason)
      type(output_file), intent(in) :: file
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: reason
      ok = .false.
      if (.not. c_associated(file%stream)) return
      ok = c_fflush(file%stream) == 0_c_int
      if (.not. ok) reason = last_system_error()
   end subroutine flush_file

   subroutine close_file(file, ok, reason)
      type(output_file), intent(inout) :: file
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: reason
      ok = .false.
      if (.not. c_associated(file%stream)) return
      ok = c_fflush(file%stream) == 0_c_int
      if (ok) ok = c_fsync(c_fileno(file%stream)) == 0_c_int
      if (.not. ok) reason = last_system_error()
      if (c_fclose(file%stream) /= 0_c_int .and. ok) then
         ok = .false.
         reason = last_system_error()
      end if
      file%stream = c_null_ptr
   end subroutine close_file

   !> Write `text` to the standard output (file descriptor 1, unbuffered); ok is
   !> .false. if not all of it was written (a full disk, a closed pipe).
   subroutine write_standard_output(text, ok)
      character(len=*), intent(in) :: text
      logical, intent(out) :: ok
      integer(c_intptr_t) :: written
      integer :: start
      ok = .true.
      start = 1
      ! write(2) may write less than asked (a pipe): go on from there
      do while (start <= len(text))
         written = c_write(1_c_int, c_chars(text(start:)), int(len(text) - start + 1, c_size_t))
         if (written <= 0) then
            ok = .false.
            return
         end if
         start = start + int(written)
      end do
   end subroutine write_standard_output

   !> Wall-clock time in seconds from an arbitrary origin.
   function wall_clock() result(seconds)
      real(kind(1.0d0)) :: seconds
      integer(int64) :: count, rate
      call system_clock(count, rate)
      seconds = real(count, kind(1.0d0)) / real(rate, kind(1.0d0))
   end function wall_clock

   !> A Fortran string as a NUL-terminated C string.
   pure function c_string(text) result(c)
      character(len=*), intent(in) :: text
      character(kind=c_char) :: c(len(text) + 1)
      c(1:len(text)) = c_chars(text)
      c(len(text) + 1) = c_null_char
   end function c_string

   !> A Fortran string as an array of C characters (no terminator).
   pure function c_chars(text) result(c)
      character(len=*), intent(in) :: text
      character(kind=c_char) :: c(len(text))
      integer :: i
      do i = 1, len(text)
         c(i) = text(i:i)
      end do
   end function c_chars

end module hcimpact_scene_system
