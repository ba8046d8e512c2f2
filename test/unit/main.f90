! SPDX-License-Identifier: Apache-2.0
!> Driver of the unit tests: `tester` runs every suite, `tester SUITE` one suite,
!> `tester SUITE TEST` one test of it.
!>
!> A new suite is a file test_<name>.f90 with module test_<name> exporting
!> collect_<name>: add its `use` line and its new_testsuite entry below. CMake
!> derives the CTest entries (hcimpact/<name>) from the file names; fpm
!> compiles every file of this directory.
program tester
   use, intrinsic :: iso_fortran_env, only : error_unit
   use testdrive, only : run_testsuite, new_testsuite, testsuite_type, &
      & select_suite, run_selected, get_argument
   use test_check, only : collect_check
   use test_lambertw, only : collect_lambertw
   use test_quadrature, only : collect_quadrature
   use test_restitution, only : collect_restitution
   use test_impact, only : collect_impact
   implicit none
   integer :: stat, is
   character(len=:), allocatable :: suite_name, test_name
   type(testsuite_type), allocatable :: testsuites(:)
   character(len=*), parameter :: fmt = '("#", *(1x, a))'

   stat = 0

   testsuites = [ &
      new_testsuite("check", collect_check), &
      new_testsuite("lambertw", collect_lambertw), &
      new_testsuite("quadrature", collect_quadrature), &
      new_testsuite("restitution", collect_restitution), &
      new_testsuite("impact", collect_impact) &
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

end program tester
