! SPDX-License-Identifier: Apache-2.0
!> C interface of the library: thin bind(C) wrappers that convert and check.
!>
!> Every name here is declared in include/hcimpact.h; the physics lives in the
!> Fortran modules this one calls.
module hcimpact_api
   use, intrinsic :: iso_c_binding, only : c_double, c_int
   use hcimpact_lambertw, only : lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1
   use hcimpact_restitution_law, only : restitution, restitution_inverse
   implicit none
   private

   public :: c_lambert_w0, c_lambert_wm1, c_lambert_w0p1, c_lambert_wm1p1
   public :: c_restitution, c_restitution_inverse

contains

   !> W0(z) for z >= -1/e; NaN outside the domain or for NaN.
   function c_lambert_w0(z) result(w) bind(C, name="hcimpact_lambert_w0")
      real(c_double), value, intent(in) :: z
      real(c_double) :: w
      w = lambert_w0(z)
   end function c_lambert_w0

   !> W-1(z) for -1/e <= z < 0; NaN outside the domain or for NaN.
   function c_lambert_wm1(z) result(w) bind(C, name="hcimpact_lambert_wm1")
      real(c_double), value, intent(in) :: z
      real(c_double) :: w
      w = lambert_wm1(z)
   end function c_lambert_wm1

   !> 1 + W0(-exp(-1-t)) for t >= 0, from t directly; NaN for t < 0 or NaN.
   function c_lambert_w0p1(t) result(v) bind(C, name="hcimpact_lambert_w0p1")
      real(c_double), value, intent(in) :: t
      real(c_double) :: v
      v = lambert_w0p1(t)
   end function c_lambert_w0p1

   !> 1 + W-1(-exp(-1-t)) for t >= 0, from t directly; NaN for t < 0 or NaN.
   function c_lambert_wm1p1(t) result(v) bind(C, name="hcimpact_lambert_wm1p1")
      real(c_double), value, intent(in) :: t
      real(c_double) :: v
      v = lambert_wm1p1(t)
   end function c_lambert_wm1p1

   !> Coefficient of restitution k(beta), beta = b V >= 0; NaN for beta < 0 or NaN.
   function c_restitution(beta) result(k) bind(C, name="hcimpact_restitution")
      real(c_double), value, intent(in) :: beta
      real(c_double) :: k
      k = restitution(beta)
   end function c_restitution

   !> beta with k(beta) = e for 0 < e <= 1; NaN outside, +inf for e below 1/DBL_MAX.
   function c_restitution_inverse(e) result(beta) bind(C, name="hcimpact_restitution_inverse")
      real(c_double), value, intent(in) :: e
      real(c_double) :: beta
      beta = restitution_inverse(e)
   end function c_restitution_inverse

end module hcimpact_api
