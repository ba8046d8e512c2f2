! SPDX-License-Identifier: Apache-2.0
!> The module `testdrive`, built on mctc-lib's `mctc_env_testing`.
!>
!> Debian ships mctc-lib (libmctc-lib-dev) but not test-drive. The testing
!> module of mctc-lib is the framework test-drive grew out of: the same types
!> and the same procedures under another module name. This adapter re-exports
!> it as `testdrive` and adds what test-drive has and mctc-lib 0.3 lacks
!> (get_argument, get_variable, to_string, skip_test, the `and_more` line of
!> test_failed, the NaN check `check(error, actual)`), so that the unit tests
!> compile unchanged against either.
!>
!> It is compiled only when the tests use the mctc-lib backend (CMake falls back
!> to it when no test-drive is installed; fpm always uses it). Differences that
!> remain: mctc-lib has no "skipped" state, so skip_test reports the skip on
!> standard error and the test counts as passed; and mctc-lib's real-valued
!> `check` lets NaN pass and divides by the signed expected value in relative
!> mode -- compare reals with the helpers of `hcimpact_check` instead.
module testdrive
   use, intrinsic :: iso_fortran_env, only : error_unit, int32, int64, real64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use mctc_env_testing, only : run_testsuite, run_selected, new_unittest, new_testsuite, &
      & select_test, select_suite, unittest_type, testsuite_type, error_type, check, &
      & test_interface, collect_interface, mctc_test_failed => test_failed
   use mctc_env_system, only : get_argument, get_variable
   implicit none
   private

   public :: run_testsuite, run_selected, new_unittest, new_testsuite
   public :: select_test, select_suite
   public :: unittest_type, testsuite_type, error_type
   public :: check, test_failed, skip_test
   public :: test_interface, collect_interface
   public :: get_argument, get_variable, to_string

   !> test-drive's check of a single real: fails if it is NaN
   interface check
      module procedure :: check_float_exceptional_dp
   end interface check

   !> Text form of a number, as test-drive's to_string
   interface to_string
      module procedure :: int32_to_string
      module procedure :: int64_to_string
      module procedure :: real64_to_string
   end interface to_string

contains

   !> Mark a test as failed; up to three lines of message.
   subroutine test_failed(error, message, more, and_more)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> A detailed message describing the error
      character(len=*), intent(in) :: message
      !> Another line of error message
      character(len=*), intent(in), optional :: more
      !> Another line of error message
      character(len=*), intent(in), optional :: and_more

      if (present(more) .and. present(and_more)) then
         call mctc_test_failed(error, message, more // new_line("a") // and_more)
      else if (present(and_more)) then
         call mctc_test_failed(error, message, and_more)
      else
         call mctc_test_failed(error, message, more)
      end if
   end subroutine test_failed

   !> Skip a test whose requirements are not met.
   !>
   !> mctc-lib's runner knows only "passed" and "failed": the skip is reported
   !> on standard error and the test is left to pass.
   subroutine skip_test(error, message, more, and_more)
      !> Error handling (left unallocated)
      type(error_type), allocatable, intent(out) :: error
      !> Why the test is skipped
      character(len=*), intent(in) :: message
      !> Another line of message
      character(len=*), intent(in), optional :: more
      !> Another line of message
      character(len=*), intent(in), optional :: and_more

      write(error_unit, '(2x, a, 1x, a)') "[SKIPPED]", message
      if (present(more)) write(error_unit, '(12x, a)') more
      if (present(and_more)) write(error_unit, '(12x, a)') and_more
      if (allocated(error)) deallocate(error)
   end subroutine skip_test

   !> Fail if a real value is NaN.
   subroutine check_float_exceptional_dp(error, actual, message, more)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Value to inspect
      real(real64), intent(in) :: actual
      !> A detailed message describing the error
      character(len=*), intent(in), optional :: message
      !> Another line of error message
      character(len=*), intent(in), optional :: more

      if (ieee_is_nan(actual)) then
         if (present(message)) then
            call test_failed(error, message, more)
         else
            call test_failed(error, "Exceptional value 'not a number' found", more)
         end if
      end if
   end subroutine check_float_exceptional_dp

   !> Decimal text of a default-kind integer
   pure function int32_to_string(val) result(string)
      !> Integer to format
      integer(int32), intent(in) :: val
      !> Its decimal representation
      character(len=:), allocatable :: string
      character(len=12) :: buffer

      write(buffer, '(i0)') val
      string = trim(buffer)
   end function int32_to_string

   !> Decimal text of a 64-bit integer
   pure function int64_to_string(val) result(string)
      !> Integer to format
      integer(int64), intent(in) :: val
      !> Its decimal representation
      character(len=:), allocatable :: string
      character(len=21) :: buffer

      write(buffer, '(i0)') val
      string = trim(buffer)
   end function int64_to_string

   !> Shortest processor-chosen text of a double (g0 edit descriptor)
   pure function real64_to_string(val) result(string)
      !> Real to format
      real(real64), intent(in) :: val
      !> Its representation
      character(len=:), allocatable :: string
      character(len=40) :: buffer

      write(buffer, '(g0)') val
      string = trim(adjustl(buffer))
   end function real64_to_string

end module testdrive
