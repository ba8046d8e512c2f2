! SPDX-License-Identifier: Apache-2.0
!> Two bodies in a collinear impact: the Hertz contact constant, the effective mass,
!> and the velocities after the impact.
!>
!> Two spheres (or a sphere and a plate, radius +inf) pressed together by x obey
!> Hertz's law f = c x^(3/2) with (MODEL.md, seed eq. before the example)
!>
!>     1/c = (3/4) ((1 - nu1^2)/E1 + (1 - nu2^2)/E2) sqrt(1/R1 + 1/R2),
!>
!> and the relative motion of the two bodies is that of one body of the effective mass
!> m = m1 m2/(m1 + m2) striking a fixed obstacle (seed, introduction). The impact gives
!> the relative rebound velocity -k V; momentum conservation then gives the velocities
!> of both bodies.
!>
!> The functions return NaN for arguments outside their domain (as the elementary
!> functions do); the subroutine returns a status.
module hcimpact_hertz
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_velocity, hcimpact_err_restitution
   implicit none
   private

   public :: hertz_constant, effective_mass, two_body_velocities

   !> Quiet NaN
   real(wp), parameter :: nan = transfer(9221120237041090560_int64, 1.0_wp)

contains

   !> Hertz's contact constant c (N/m^(3/2)) of two elastic spheres; a radius of +inf
   !> (ieee_value(x, ieee_positive_inf)) makes that body a half-space (a plate).
   !>
   !> Domain: E > 0 finite, -1 < nu <= 1/2, R > 0 (finite or +inf, not both infinite).
   !> Anything else, or NaN, gives NaN. Example (the seed's): steel, E = 2e11 Pa,
   !> nu = 0.25, a ball of R = 1.452 cm on a plate: c = 1.7138e10 N/m^(3/2).
   elemental function hertz_constant(young1, poisson1, radius1, young2, poisson2, radius2) &
         & result(c)
      !> Young's modulus of body 1 in Pa
      real(wp), intent(in) :: young1
      !> Poisson's ratio of body 1
      real(wp), intent(in) :: poisson1
      !> Radius of curvature of body 1 at the contact in m (+inf: flat)
      real(wp), intent(in) :: radius1
      !> Young's modulus of body 2 in Pa
      real(wp), intent(in) :: young2
      !> Poisson's ratio of body 2
      real(wp), intent(in) :: poisson2
      !> Radius of curvature of body 2 at the contact in m (+inf: flat)
      real(wp), intent(in) :: radius2
      !> c in N/m^(3/2), or NaN
      real(wp) :: c
      real(wp) :: compliance, curvature

      c = nan
      if (.not. (valid_material(young1, poisson1) .and. valid_material(young2, poisson2))) &
         & return
      if (.not. (valid_radius(radius1) .and. valid_radius(radius2))) return
      ! 1/R of a plate is 0; two plates have no Hertz contact
      curvature = 1.0_wp / radius1 + 1.0_wp / radius2
      if (.not. curvature > 0.0_wp) return
      compliance = (1.0_wp - poisson1**2) / young1 + (1.0_wp - poisson2**2) / young2
      c = (4.0_wp / 3.0_wp) / (compliance * sqrt(curvature))
   end function hertz_constant

   !> E > 0 finite and -1 < nu <= 1/2
   elemental function valid_material(young, poisson) result(ok)
      real(wp), intent(in) :: young, poisson
      logical :: ok
      ok = ieee_is_finite(young) .and. ieee_is_finite(poisson)
      if (ok) ok = young > 0.0_wp .and. poisson > -1.0_wp .and. poisson <= 0.5_wp
   end function valid_material

   !> R > 0, +inf allowed
   elemental function valid_radius(radius) result(ok)
      real(wp), intent(in) :: radius
      logical :: ok
      ok = .not. ieee_is_nan(radius)
      if (ok) ok = radius > 0.0_wp
   end function valid_radius

   !> Effective mass m1 m2/(m1 + m2) in kg. m2 = +inf (an immovable obstacle) gives m1.
   !> Masses must be positive (m1 finite); otherwise NaN.
   elemental function effective_mass(mass1, mass2) result(m)
      !> Mass of body 1 in kg, > 0 and finite
      real(wp), intent(in) :: mass1
      !> Mass of body 2 in kg, > 0 (+inf allowed)
      real(wp), intent(in) :: mass2
      !> Effective mass in kg
      real(wp) :: m
      m = nan
      if (.not. ieee_is_finite(mass1) .or. ieee_is_nan(mass2)) return
      if (.not. (mass1 > 0.0_wp .and. mass2 > 0.0_wp)) return
      ! m1/(1 + m1/m2): no overflow, and exact for m2 = +inf
      m = mass1 / (1.0_wp + mass1 / mass2)
   end function effective_mass

   !> Velocities of both bodies after a collinear impact with the coefficient of
   !> restitution k (from `impact`): the relative velocity v1 - v2 = V > 0 becomes -k V
   !> and the momentum m1 v1 + m2 v2 is conserved:
   !>
   !>     v1' = v1 - (1 + k) V m2/(m1 + m2),   v2' = v2 + (1 + k) V m1/(m1 + m2).
   !>
   !> Body 1 moves towards body 2 along the positive direction of the line. m2 = +inf
   !> is an immovable obstacle (v2' = v2).
   !>
   !> Errors: hcimpact_err_not_finite (NaN or infinite input other than m2 = +inf),
   !> hcimpact_err_mass (a mass not positive), hcimpact_err_velocity (v1 <= v2: the
   !> bodies do not approach), hcimpact_err_restitution (k outside [0, 1]). Outputs NaN.
   elemental subroutine two_body_velocities(mass1, mass2, velocity1, velocity2, &
         & restitution, velocity1_after, velocity2_after, stat)
      !> Mass of body 1 in kg
      real(wp), intent(in) :: mass1
      !> Mass of body 2 in kg (+inf allowed)
      real(wp), intent(in) :: mass2
      !> Velocity of body 1 before the impact in m/s
      real(wp), intent(in) :: velocity1
      !> Velocity of body 2 before the impact in m/s (< velocity1)
      real(wp), intent(in) :: velocity2
      !> Coefficient of restitution k in [0, 1]
      real(wp), intent(in) :: restitution
      !> Velocity of body 1 after the impact in m/s
      real(wp), intent(out) :: velocity1_after
      !> Velocity of body 2 after the impact in m/s
      real(wp), intent(out) :: velocity2_after
      !> Status
      integer, intent(out) :: stat
      real(wp) :: approach, share1, share2, exchange

      velocity1_after = nan
      velocity2_after = nan
      if (.not. (ieee_is_finite(mass1) .and. ieee_is_finite(velocity1) &
         & .and. ieee_is_finite(velocity2) .and. ieee_is_finite(restitution)) &
         & .or. ieee_is_nan(mass2)) then
         stat = hcimpact_err_not_finite
         return
      end if
      if (.not. (mass1 > 0.0_wp .and. mass2 > 0.0_wp)) then
         stat = hcimpact_err_mass
         return
      end if
      if (.not. velocity1 > velocity2) then
         stat = hcimpact_err_velocity
         return
      end if
      if (.not. (restitution >= 0.0_wp .and. restitution <= 1.0_wp)) then
         stat = hcimpact_err_restitution
         return
      end if
      stat = hcimpact_ok
      approach = velocity1 - velocity2
      ! m2/(m1 + m2) and m1/(m1 + m2), also for m2 = +inf
      share2 = 1.0_wp / (1.0_wp + mass1 / mass2)
      share1 = (mass1 / mass2) * share2
      exchange = (1.0_wp + restitution) * approach
      velocity1_after = velocity1 - exchange * share2
      velocity2_after = velocity2 + exchange * share1
   end subroutine two_body_velocities

end module hcimpact_hertz
