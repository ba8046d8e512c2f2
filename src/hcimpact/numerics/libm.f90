! SPDX-License-Identifier: Apache-2.0
!> Functions of the C math library that Fortran lacks as intrinsics.
!>
!> log1p and expm1 are what keep ln(1+x) and exp(x)-1 accurate for small x; the
!> C library's versions are pure (no side effects beyond errno, which we never read).
module hcimpact_libm
   use, intrinsic :: iso_c_binding, only : c_double
   implicit none
   private

   public :: log1p, expm1

   interface
      !> ln(1 + x), accurate for small |x|
      pure function log1p(x) result(y) bind(C, name="log1p")
         import :: c_double
         real(c_double), value, intent(in) :: x
         real(c_double) :: y
      end function log1p

      !> exp(x) - 1, accurate for small |x|
      pure function expm1(x) result(y) bind(C, name="expm1")
         import :: c_double
         real(c_double), value, intent(in) :: x
         real(c_double) :: y
      end function expm1
   end interface

end module hcimpact_libm
