! SPDX-License-Identifier: Apache-2.0
!> Driver of the tests of the CVODE component: `tester_cvode` runs every suite,
!> `tester_cvode SUITE` one suite, `tester_cvode SUITE TEST` one test of it.
!>
!> A new suite is a file test_<name>.f90 with module test_cvode_<name> exporting
!> collect_<name>: add it below; CMake derives the CTest entries
!> (hcimpact/cvode/<name>) from the file names.
program tester_cvode
   use, intrinsic :: iso_fortran_env, only : error_unit
   use testdrive, only : run_testsuite, new_testsuite, testsuite_type, &
      & select_suite, run_selected, get_argument
   use test_cvode_power, only : collect_power
   use test_cvode_input, only : collect_input
   use test_cvode_law, only : collect_law
   use test_cvode_stability, only : collect_stability
   use test_cvode_threads, only : collect_threads
   implicit none
   integer :: stat, is
   character(len=:), allocatable :: suite_name, test_name
   type(testsuite_type), allocatable :: testsuites(:)
   character(len=*), parameter :: fmt = '("#", *(1x, a))'

   stat = 0
   testsuites = [ &
      new_testsuite("power", collect_power), &
      new_testsuite("input", collect_input), &
      new_testsuite("law", collect_law), &
      new_testsuite("stability", collect_stability), &
      new_testsuite("threads", collect_threads) &
      ]

   call get_argument(1, suite_name)
   call get_argument(2, test_name)

   if (allocated(suite_name)) then
      is = select_suite(testsuites, suite_name)
      if (is > 0 .and. is <= size(testsuites)) then
         if (allocated(test_name)) then
            write(error_unit, fmt) "Suite:", testsuites(is)%name
            call run_selected(testsuites(is)%collect, test_name, error_unit, stat)
            if (stat < 0) then
               error stop 1
            end if
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

end program tester_cvode
