! SPDX-License-Identifier: Apache-2.0
!> Driver of the tests of the LAPACK component (calibration): `lapack_tester` runs
!> every suite, `lapack_tester SUITE` one suite, `lapack_tester SUITE TEST` one test.
!>
!> Built by test/lapack/CMakeLists.txt only when hcimpact::lapack is; CTest has one
!> entry hcimpact/lapack/<suite> per suite listed there and below.
program lapack_tester
   use, intrinsic :: iso_fortran_env, only : error_unit
   use testdrive, only : run_testsuite, new_testsuite, testsuite_type, &
      & select_suite, run_selected, get_argument
   use test_least_squares, only : collect_least_squares
   use test_fit_damping, only : collect_fit_damping
   use test_fit_static, only : collect_fit_static
   use test_fit_impact, only : collect_fit_impact
   use test_fit_errors, only : collect_fit_errors
   implicit none
   integer :: stat, is
   character(len=:), allocatable :: suite_name, test_name
   type(testsuite_type), allocatable :: testsuites(:)
   character(len=*), parameter :: fmt = '("#", *(1x, a))'

   stat = 0

   testsuites = [ &
      new_testsuite("least_squares", collect_least_squares), &
      new_testsuite("fit_damping", collect_fit_damping), &
      new_testsuite("fit_static", collect_fit_static), &
      new_testsuite("fit_impact", collect_fit_impact), &
      new_testsuite("fit_errors", collect_fit_errors) &
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

end program lapack_tester
