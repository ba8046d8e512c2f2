! SPDX-License-Identifier: Apache-2.0
!> Working precision of the library, and the one quiet NaN every failed output holds.
module hcimpact_kinds
   use, intrinsic :: iso_fortran_env, only : real64, int32, int64
   implicit none
   private

   public :: wp, ik, nan

   !> Real kind of every computation and interface (IEEE binary64)
   integer, parameter :: wp = real64
   !> Integer kind of statuses and counters in the public interfaces
   integer, parameter :: ik = int32
   !> The quiet NaN of every output that could not be computed (IEEE binary64, all
   !> payload bits clear but the quiet bit). A constant rather than
   !> `ieee_value(x, ieee_quiet_nan)`, which is a library call on hot paths.
   real(wp), parameter :: nan = transfer(9221120237041090560_int64, 1.0_wp)

end module hcimpact_kinds
