! SPDX-License-Identifier: Apache-2.0
!> The C layer's table of status messages (hcimpact_api, constant storage so that
!> hcimpact_status_message is thread-safe and allocates nothing) must say what
!> hcimpact_status's status_message says, for every code; and the C function must
!> return the table's entries. Exit status 1 on a mismatch.
program status_table
   use, intrinsic :: iso_c_binding, only : c_ptr, c_char, c_null_char, c_f_pointer, c_int
   use hcimpact_status, only : status_message
   use hcimpact_api, only : c_status_message, message_length, last_status
   implicit none
   integer :: code, failures
   character(len=:), allocatable :: expected, actual

   failures = 0
   do code = -3, last_status + 5
      expected = status_message(code)
      actual = c_string(c_status_message(int(code, c_int)))
      if (actual /= expected) then
         failures = failures + 1
         write (*, '(a, i0, 5a)') "FAIL status ", code, ": C '", actual, "', Fortran '", &
            & expected, "'"
      end if
   end do
   ! a code beyond the table must be unknown to the Fortran side as well: otherwise a
   ! status was added to status.f90 but not to the C table (and include/hcimpact.h)
   if (status_message(last_status + 1) /= "unknown status code") then
      failures = failures + 1
      write (*, '(a, i0, a)') "FAIL status ", last_status + 1, &
         & " has a message in status.f90: add it to hcimpact_api and hcimpact.h"
   end if
   if (failures > 0) error stop 1
   write (*, '(a, i0, a)') "status messages agree for codes -3 .. ", last_status + 5, &
      & " (C table and Fortran status_message)"

contains

   !> The NUL-terminated C string at p, as a Fortran string
   function c_string(p) result(s)
      type(c_ptr), intent(in) :: p
      character(len=:), allocatable :: s
      character(kind=c_char), pointer :: chars(:)
      integer :: n
      call c_f_pointer(p, chars, [message_length])
      n = 0
      do while (n < message_length)
         if (chars(n + 1) == c_null_char) exit
         n = n + 1
      end do
      allocate(character(len=n) :: s)
      s = transfer(chars(1:n), s)
   end function c_string

end program status_table
