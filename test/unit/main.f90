! SPDX-License-Identifier: Apache-2.0
!> Driver of the unit tests: `tester` runs every suite, `tester SUITE` one suite,
!> `tester SUITE TEST` one test of it.
!>
!> A new suite is a file test_<name>.f90 with module test_<name> exporting
!> collect_<name>: add its `use` line and its new_testsuite entry below. CMake
!> derives the CTest entries (hcimpact/<name>) from the file names; fpm
!> compiles every file of this directory.
program tester
   use testdrive, only : new_testsuite, testsuite_type
   use hcimpact_tester, only : run_tester
   use test_check, only : collect_check
   use test_lambertw, only : collect_lambertw
   use test_quadrature, only : collect_quadrature
   use test_restitution, only : collect_restitution
   use test_impact, only : collect_impact
   use test_double_double, only : collect_double_double
   use test_modified_cc, only : collect_modified_cc
   use test_contact_force, only : collect_contact_force
   implicit none
   type(testsuite_type), allocatable :: testsuites(:)

   testsuites = [ &
      new_testsuite("check", collect_check), &
      new_testsuite("lambertw", collect_lambertw), &
      new_testsuite("quadrature", collect_quadrature), &
      new_testsuite("restitution", collect_restitution), &
      new_testsuite("impact", collect_impact), &
      new_testsuite("double_double", collect_double_double), &
      new_testsuite("modified_cc", collect_modified_cc), &
      new_testsuite("contact_force", collect_contact_force) &
      ]

   call run_tester(testsuites)

end program tester
