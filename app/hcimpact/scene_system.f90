! SPDX-License-Identifier: Apache-2.0
!> What the scene runner needs from the operating system and Fortran does not give:
!> whether a stream is a terminal, directories, renaming and removing files (POSIX, from
!> the C library through `bind(C)`), and a wall clock.
!>
!> The C names bound here (isatty, mkdir, rename, remove, getpid) are not module names
!> of this program (gfortran miscompiles a binding label equal to a module name).
module hcimpact_scene_system
   use, intrinsic :: iso_c_binding, only : c_int, c_char, c_null_char
   use, intrinsic :: iso_fortran_env, only : int64
   implicit none
   private

   public :: is_terminal, make_directory, rename_path, remove_path, process_id
   public :: directory_exists, file_exists, wall_clock

   interface
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
      function c_remove(path) bind(C, name="remove") result(r)
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: r
      end function c_remove
      function c_getpid() bind(C, name="getpid") result(r)
         import :: c_int
         integer(c_int) :: r
      end function c_getpid
   end interface

contains

   !> Whether the file descriptor fd (1: standard output, 2: standard error) is a terminal.
   function is_terminal(fd) result(yes)
      integer, intent(in) :: fd
      logical :: yes
      yes = c_isatty(int(fd, c_int)) == 1_c_int
   end function is_terminal

   !> Create the directory `path` and any missing parents (like mkdir -p); ok is
   !> .true. when the directory exists afterwards.
   subroutine make_directory(path, ok)
      character(len=*), intent(in) :: path
      logical, intent(out) :: ok
      integer :: i
      integer(c_int) :: r
      ok = .false.
      if (len_trim(path) == 0) return
      ! every parent, from the top; errors (e.g. "exists") are judged at the end
      do i = 2, len_trim(path)
         if (path(i:i) == "/" .and. path(i - 1:i - 1) /= "/") then
            if (.not. directory_exists(path(1:i - 1))) r = c_mkdir(c_string(path(1:i - 1)), &
               & int(o'777', c_int))
         end if
      end do
      if (.not. directory_exists(path)) r = c_mkdir(c_string(trim(path)), int(o'777', c_int))
      ok = directory_exists(path)
   end subroutine make_directory

   !> Whether `path` names an existing directory.
   function directory_exists(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      ! "dir/." exists only for a directory
      inquire(file=trim(path) // "/.", exist=yes)
   end function directory_exists

   !> Whether `path` names an existing file (or directory).
   function file_exists(path) result(yes)
      character(len=*), intent(in) :: path
      logical :: yes
      inquire(file=trim(path), exist=yes)
   end function file_exists

   !> Rename `from` to `to` (replacing a file `to`), atomically on one file system.
   subroutine rename_path(from, to, ok)
      character(len=*), intent(in) :: from, to
      logical, intent(out) :: ok
      ok = c_rename(c_string(from), c_string(to)) == 0_c_int
   end subroutine rename_path

   !> Remove the file (or empty directory) `path`; nothing happens if it does not exist.
   subroutine remove_path(path)
      character(len=*), intent(in) :: path
      integer(c_int) :: r
      if (file_exists(path) .or. directory_exists(path)) r = c_remove(c_string(path))
   end subroutine remove_path

   !> The id of this process.
   function process_id() result(pid)
      integer :: pid
      pid = int(c_getpid())
   end function process_id

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
      integer :: i
      do i = 1, len(text)
         c(i) = text(i:i)
      end do
      c(len(text) + 1) = c_null_char
   end function c_string

end module hcimpact_scene_system
