! SPDX-License-Identifier: Apache-2.0
!> Driver of the tests of the CVODE component: `tester_cvode` runs every suite,
!> `tester_cvode SUITE` one suite, `tester_cvode SUITE TEST` one test of it.
!>
!> A new suite is a file test_<name>.f90 with module test_cvode_<name> exporting
!> collect_<name>: add it below; CMake derives the CTest entries
!> (hcimpact/cvode/<name>) from the file names.
program tester_cvode
   use testdrive, only : new_testsuite, testsuite_type
   use hcimpact_tester, only : run_tester
   use test_cvode_power, only : collect_power
   use test_cvode_input, only : collect_input
   use test_cvode_law, only : collect_law
   use test_cvode_stability, only : collect_stability
   use test_cvode_threads, only : collect_threads
   use test_cvode_chain, only : collect_chain
   use test_cvode_chain_api, only : collect_chain_api
   use test_cvode_chain_newton, only : collect_chain_newton
   use test_cvode_chain_monitor, only : collect_chain_monitor
   implicit none
   type(testsuite_type), allocatable :: testsuites(:)

   testsuites = [ &
      new_testsuite("power", collect_power), &
      new_testsuite("input", collect_input), &
      new_testsuite("law", collect_law), &
      new_testsuite("stability", collect_stability), &
      new_testsuite("threads", collect_threads), &
      new_testsuite("chain", collect_chain), &
      new_testsuite("chain_api", collect_chain_api), &
      new_testsuite("chain_newton", collect_chain_newton), &
      new_testsuite("chain_monitor", collect_chain_monitor) &
      ]

   call run_tester(testsuites)

end program tester_cvode
