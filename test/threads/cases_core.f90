! SPDX-License-Identifier: Apache-2.0
!> Work of the thread test (test/threads/driver.c) done in Fortran, core library:
!> the texts that Fortran callers receive from functions with a character result
!> (status_message, quadrature_status_message), copied into a C buffer. A text whose
!> length came from a variable shared by threads would be cut, padded or read past
!> its end when another thread asks for a text of another length at the same time.
module thread_cases_core
   use, intrinsic :: iso_c_binding, only : c_int, c_char, c_null_char
   use hcimpact_kinds, only : ik
   use hcimpact_status, only : status_message
   use hcimpact_quadrature, only : quadrature_status_message
   implicit none
   private

   public :: thread_core_texts, copy_text

contains

   !> void thread_core_texts(int i, char *text, int capacity): the status text of
   !> code i mod 20 - 2 (unknown codes too), " | ", the quadrature status text of
   !> i mod 9 - 1, NUL-terminated and cut to capacity.
   subroutine thread_core_texts(i, text, capacity) bind(C, name="thread_core_texts")
      !> Index of the work item
      integer(c_int), value, intent(in) :: i
      !> Output buffer
      character(kind=c_char), intent(out) :: text(*)
      !> Its size in bytes (the NUL included)
      integer(c_int), value, intent(in) :: capacity

      call copy_text(status_message(mod(i, 20) - 2) // " | " &
         & // quadrature_status_message(int(mod(i, 9) - 1, ik)), text, capacity)
   end subroutine thread_core_texts

   !> Copy a Fortran string into a C buffer of `capacity` bytes, NUL-terminated.
   subroutine copy_text(source, text, capacity)
      !> The string
      character(len=*), intent(in) :: source
      !> The buffer
      character(kind=c_char), intent(out) :: text(*)
      !> Its size in bytes
      integer(c_int), intent(in) :: capacity
      integer :: k, n

      if (capacity < 1) return
      n = min(len(source), capacity - 1)
      do k = 1, n
         text(k) = source(k:k)
      end do
      text(n + 1) = c_null_char
   end subroutine copy_text

end module thread_cases_core
