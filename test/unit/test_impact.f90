! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_impact (STUB: to be filled).
module test_impact
   use testdrive, only : new_unittest, unittest_type, error_type, check
   implicit none
   private

   public :: collect_impact

contains

   !> Collect all exported unit tests
   subroutine collect_impact(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      allocate(testsuite(0))
   end subroutine collect_impact

end module test_impact
