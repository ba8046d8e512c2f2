! SPDX-License-Identifier: Apache-2.0
!> Working precision of the library.
module hcimpact_kinds
   use, intrinsic :: iso_fortran_env, only : real64, int32
   implicit none
   private

   public :: wp, ik

   !> Real kind of every computation and interface (IEEE binary64)
   integer, parameter :: wp = real64
   !> Integer kind of statuses and counters in the public interfaces
   integer, parameter :: ik = int32

end module hcimpact_kinds
