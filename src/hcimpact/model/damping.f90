! SPDX-License-Identifier: Apache-2.0
!> The damping constant b that gives a target coefficient of restitution.
module hcimpact_damping
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, &
      & hcimpact_err_restitution, hcimpact_err_velocity, hcimpact_err_domain
   use hcimpact_restitution_law, only : restitution_inverse
   implicit none
   private

   public :: damping_for_restitution, default_min_velocity

   !> Default of `damping_for_restitution`'s min_velocity, in m/s: below this approach
   !> speed the damping for a target restitution is computed at this speed
   real(wp), parameter :: default_min_velocity = 1.0e-3_wp

contains

   !> Damping constant b (s/m) that gives the restitution e at the approach speed V:
   !> b = beta(e)/V with beta(e) the exact inverse of k(beta) (hcimpact_restitution).
   !>
   !> Resting contact: as V -> 0 the exact b grows without bound. Below `min_velocity`
   !> (default `default_min_velocity` = 1e-3 m/s) b is computed at min_velocity instead,
   !> so that b stays finite and so does every force; impacts slower than that then
   !> restitute with k(b V) > e (less dissipation), tending to 1 as V -> 0. V = 0 is
   !> allowed and gives b = beta(e)/min_velocity.
   !>
   !> b is formed from the significands and binary exponents of beta(e) and of the speed,
   !> so that neither beta(e) (about 1/e, beyond the largest double for e below
   !> 5.6e-309) nor a quotient by a subnormal speed overflows on the way: every b that
   !> is a double is returned (subnormal b rounded to its precision).
   !>
   !> Errors: hcimpact_err_not_finite (NaN or infinite argument), hcimpact_err_restitution
   !> (e outside (0, 1]), hcimpact_err_velocity (V < 0, or min_velocity not positive),
   !> hcimpact_err_domain (the exact b exceeds the largest double, e.g. e = 1e-310 at
   !> V = 1 m/s, or e = 0.5 with min_velocity = 1e-320 at V = 0).
   elemental subroutine damping_for_restitution(e, velocity, damping, stat, min_velocity)
      !> Target coefficient of restitution, 0 < e <= 1
      real(wp), intent(in) :: e
      !> Approach speed V in m/s, >= 0
      real(wp), intent(in) :: velocity
      !> Damping b in s/m (0 for e = 1); NaN on error
      real(wp), intent(out) :: damping
      !> Status
      integer, intent(out) :: stat
      !> Speed below which b is computed at this speed, in m/s (> 0)
      real(wp), intent(in), optional :: min_velocity
      real(wp) :: vmin, speed, beta, significand
      integer :: scale_exponent

      damping = nan
      vmin = default_min_velocity
      if (present(min_velocity)) vmin = min_velocity
      if (.not. (ieee_is_finite(e) .and. ieee_is_finite(velocity) .and. ieee_is_finite(vmin))) then
         stat = hcimpact_err_not_finite
         return
      end if
      if (.not. (e > 0.0_wp .and. e <= 1.0_wp)) then
         stat = hcimpact_err_restitution
         return
      end if
      if (velocity < 0.0_wp .or. .not. vmin > 0.0_wp) then
         stat = hcimpact_err_velocity
         return
      end if
      speed = max(velocity, vmin)
      beta = restitution_inverse(e)
      if (beta <= huge(1.0_wp)) then
         ! b = beta/speed = (its significands' quotient, in (1/2, 2)) 2^(e_beta - e_speed)
         significand = fraction(beta) / fraction(speed)
         scale_exponent = exponent(beta) - exponent(speed)
      else
         ! e below 1/DBL_MAX: beta = 1/e to far below an ulp (k = 1/beta above 2^60,
         ! hcimpact_restitution_law), so b = 1/(e speed), significand in (1, 4]
         significand = 1.0_wp / (fraction(e) * fraction(speed))
         scale_exponent = -(exponent(e) + exponent(speed))
      end if
      if (exponent(significand) + scale_exponent > maxexponent(1.0_wp)) then
         stat = hcimpact_err_domain
         return
      end if
      stat = hcimpact_ok
      damping = scale(significand, scale_exponent)
   end subroutine damping_for_restitution

end module hcimpact_damping
