! SPDX-License-Identifier: Apache-2.0
!> Working precision of the library, the one quiet NaN every failed output holds, and
!> the one test of finiteness that raises no floating-point flag.
module hcimpact_kinds
   use, intrinsic :: iso_fortran_env, only : real64, int32, int64
   implicit none
   private

   public :: wp, ik, nan, finite_value, bit_exponent, exponent_from_bits

   !> Real kind of every computation and interface (IEEE binary64)
   integer, parameter :: wp = real64
   !> Integer kind of statuses and counters in the public interfaces
   integer, parameter :: ik = int32
   !> The quiet NaN of every output that could not be computed (IEEE binary64, all
   !> payload bits clear but the quiet bit). A constant rather than
   !> `ieee_value(x, ieee_quiet_nan)`, which is a library call on hot paths.
   real(wp), parameter :: nan = transfer(9221120237041090560_int64, 1.0_wp)

contains

   !> Whether x is finite, from its bits: no floating-point operation, so that a
   !> signalling NaN given as input raises nothing (a comparison, or ieee_is_finite,
   !> raises invalid on it, which the Debug build traps).
   elemental function finite_value(x) result(finite)
      !> Any double
      real(wp), intent(in) :: x
      !> False for NaN (quiet or signalling) and +-Inf
      logical :: finite
      finite = ibits(transfer(x, 0_int64), 52, 11) /= 2047_int64
   end function finite_value

   !> The binary exponent e of x = 1.f 2^e read from its bits (one shift, no library
   !> call as `exponent` makes): -1023 for zero and subnormals, 1024 for Inf and NaN.
   !> `exponent(x)` is bit_exponent(x) + 1 for normal x.
   elemental function bit_exponent(x) result(e)
      !> Any double
      real(wp), intent(in) :: x
      !> Unbiased exponent
      integer :: e
      e = int(ibits(transfer(x, 0_int64), 52, 11)) - 1023
   end function bit_exponent

   !> exponent(x), the e of x = f 2^e with f in [1/2, 1), the same integer for every x:
   !> read from the bits when x is normal (gfortran's intrinsic is a call of frexp,
   !> seven of them in the set-up of one impact), the intrinsic for zero, subnormals,
   !> Inf and NaN.
   elemental function exponent_from_bits(x) result(e)
      !> Any double
      real(wp), intent(in) :: x
      !> exponent(x)
      integer :: e
      e = int(ibits(transfer(x, 0_int64), 52, 11))
      if (e == 0 .or. e == 2047) then
         e = exponent(x)
      else
         e = e - 1022
      end if
   end function exponent_from_bits

end module hcimpact_kinds
