! SPDX-License-Identifier: Apache-2.0
!> The command line of the test drivers (test/unit, test/cvode, test/lapack):
!> `PROGRAM` runs every suite, `PROGRAM SUITE` one suite, `PROGRAM SUITE TEST` one
!> test of it; an unknown suite lists the available ones. Stops with a non-zero code
!> when a test failed, so that CTest sees it.
module hcimpact_tester
   use, intrinsic :: iso_fortran_env, only : error_unit
   use testdrive, only : run_testsuite, testsuite_type, select_suite, run_selected, &
      & get_argument
   implicit none
   private

   public :: run_tester

contains

   !> Run the suites the command line selects, then stop with code 1 on failure.
   subroutine run_tester(testsuites)
      !> The driver's suites
      type(testsuite_type), intent(in) :: testsuites(:)
      character(len=*), parameter :: fmt = '("#", *(1x, a))'
      character(len=:), allocatable :: suite_name, test_name
      integer :: stat, is

      stat = 0
      call get_argument(1, suite_name)
      call get_argument(2, test_name)

      if (allocated(suite_name)) then
         is = select_suite(testsuites, suite_name)
         if (is > 0 .and. is <= size(testsuites)) then
            if (allocated(test_name)) then
               write(error_unit, fmt) "Suite:", testsuites(is)%name
               call run_selected(testsuites(is)%collect, test_name, error_unit, stat)
               if (stat < 0) error stop 1
            else
               write(error_unit, fmt) "Testing:", testsuites(is)%name
               call run_testsuite(testsuites(is)%collect, error_unit, stat)
            end if
         else
            write(error_unit, fmt) "Available testsuites"
            do is = 1, size(testsuites)
               write(error_unit, fmt) "-", testsuites(is)%name
            end do
            error stop 1
         end if
      else
         do is = 1, size(testsuites)
            write(error_unit, fmt) "Testing:", testsuites(is)%name
            call run_testsuite(testsuites(is)%collect, error_unit, stat)
         end do
      end if

      if (stat > 0) then
         write(error_unit, '(i0, 1x, a)') stat, "test(s) failed!"
         error stop 1
      end if
   end subroutine run_tester

end module hcimpact_tester
