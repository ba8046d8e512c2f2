! SPDX-License-Identifier: Apache-2.0
!> Driver of the tests of the LAPACK component (calibration): `lapack_tester` runs
!> every suite, `lapack_tester SUITE` one suite, `lapack_tester SUITE TEST` one test.
!>
!> Built by test/lapack/CMakeLists.txt only when hcimpact::lapack is; CTest has one
!> entry hcimpact/lapack/<suite> per suite listed there and below.
program lapack_tester
   use testdrive, only : new_testsuite, testsuite_type
   use hcimpact_tester, only : run_tester
   use test_least_squares, only : collect_least_squares
   use test_fit_damping, only : collect_fit_damping
   use test_fit_static, only : collect_fit_static
   use test_fit_impact, only : collect_fit_impact
   use test_fit_errors, only : collect_fit_errors
   use test_order_statistics, only : collect_order_statistics
   implicit none
   type(testsuite_type), allocatable :: testsuites(:)

   testsuites = [ &
      new_testsuite("least_squares", collect_least_squares), &
      new_testsuite("fit_damping", collect_fit_damping), &
      new_testsuite("fit_static", collect_fit_static), &
      new_testsuite("fit_impact", collect_fit_impact), &
      new_testsuite("fit_errors", collect_fit_errors), &
      new_testsuite("order_statistics", collect_order_statistics) &
      ]

   call run_tester(testsuites)

end program lapack_tester
