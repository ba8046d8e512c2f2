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
!> Every result that is a double is returned as the double nearest to the exact value
!> at the given doubles (within 0.5 ulp and a few 1e-15 ulp; test/unit/test_hertz.f90
!> against the mpmath references of test/reference/hertz.csv), over the whole range of
!> doubles, subnormal arguments and results included: the formulas are evaluated in
!> double-double arithmetic (hcimpact_double_double) on significands kept near 1, with
!> the binary exponents carried apart as integers, and rounded once at the end. So no
!> intermediate overflows or underflows where the result does not (1/R of a subnormal
!> radius, m1/m2 of very different masses, v1 - v2 of opposite velocities near the
!> largest double), and 1 - nu^2, which cancels for nu near -1, is formed as
!> (1 - nu)(1 + nu) from two exact sums. A result beyond the largest double is +-inf,
!> formed without raising the overflow exception. None of these procedures raises an
!> IEEE exception that the Debug build traps (invalid, division by zero, overflow).
!>
!> The functions return NaN for arguments outside their domain (as the elementary
!> functions do); the subroutine returns a status.
module hcimpact_hertz
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_positive_inf, ieee_negative_inf
   use hcimpact_kinds, only : wp, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_velocity, hcimpact_err_restitution
   use hcimpact_double_double, only : dd_real, dd, two_sum, dd_sqrt, dd_scale, &
      & operator(+), operator(-), operator(*), operator(/)
   implicit none
   private

   public :: hertz_constant, effective_mass, two_body_velocities


   !> The number significand 2^exponent: a double-double significand near 1 with the
   !> binary exponent apart, so that products and quotients neither overflow nor
   !> underflow before the one rounding at the end
   type :: scaled_dd
      type(dd_real) :: significand
      integer :: exponent = 0
   end type scaled_dd

contains

   !> Hertz's contact constant c (N/m^(3/2)) of two elastic spheres; a radius of +inf
   !> (ieee_value(x, ieee_positive_inf)) makes that body a half-space (a plate).
   !>
   !> Domain: E > 0 finite, -1 < nu <= 1/2, R > 0 (finite or +inf, not both infinite).
   !> Anything else, or NaN, gives NaN. Example (the seed's): steel, E = 2e11 Pa,
   !> nu = 0.25, a ball of R = 1.452 cm on a plate: c = 1.7138e10 N/m^(3/2).
   !>
   !> Evaluated as c = 4 sqrt(R) / (3 sqrt(1 + rho) S) with R the smaller radius,
   !> rho = R/R' <= 1 the ratio of the radii (so that 1/R1 + 1/R2 = (1 + rho)/R) and
   !> S = (1 - nu1)(1 + nu1)/E1 + (1 - nu2)(1 + nu2)/E2, each on significands with the
   !> exponents apart: correctly rounded (see the module) for every representable c,
   !> +inf beyond the largest double.
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
      real(wp) :: r_small, r_large
      type(dd_real) :: root, one_plus_rho, term1, term2, compliance
      integer :: e_root, e_compliance

      c = nan
      if (.not. (valid_material(young1, poisson1) .and. valid_material(young2, poisson2))) &
         & return
      if (.not. (valid_radius(radius1) .and. valid_radius(radius2))) return
      r_small = min(radius1, radius2)
      r_large = max(radius1, radius2)
      ! two plates have no Hertz contact
      if (.not. ieee_is_finite(r_small)) return

      ! sqrt(r_small) = root 2^(e_root/2), from a significand in [1/4, 1) (e_root even)
      e_root = exponent(r_small)
      if (modulo(e_root, 2) /= 0) e_root = e_root + 1
      root = dd_sqrt(dd(scale(r_small, -e_root)))
      ! 1 + rho, rho = r_small/r_large in [0, 1] (0 for a plate; a rho below 2^-1074
      ! underflows to 0, far below the precision of 1 + rho)
      one_plus_rho = dd(1.0_wp)
      if (ieee_is_finite(r_large)) one_plus_rho = 1.0_wp + unscaled(ratio_of(r_small, r_large))

      ! S = term1 2^-exponent(E1) + term2 2^-exponent(E2) = compliance 2^e_compliance
      term1 = elastic_term(young1, poisson1)
      term2 = elastic_term(young2, poisson2)
      e_compliance = -min(exponent(young1), exponent(young2))
      compliance = dd_scale(term1, -exponent(young1) - e_compliance) &
         & + dd_scale(term2, -exponent(young2) - e_compliance)

      c = round_scaled(4.0_wp * root / (3.0_wp * dd_sqrt(one_plus_rho) * compliance), &
         & e_root / 2 - e_compliance)
   end function hertz_constant

   !> (1 - nu)(1 + nu)/f with f the significand of E in [1/2, 1): the body's share of
   !> the compliance S, times 2^exponent(E). Both factors are exact sums, so no
   !> cancellation for nu near -1 (where 1 - nu^2 would lose up to 53 bits).
   elemental function elastic_term(young, poisson) result(term)
      real(wp), intent(in) :: young, poisson
      type(dd_real) :: term
      term = two_sum(1.0_wp, -poisson) * two_sum(1.0_wp, poisson) / fraction(young)
   end function elastic_term

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
   !>
   !> Evaluated as m/(1 + m/M) with m the smaller mass and M the larger, the ratio from
   !> the significands and the exponents apart: correctly rounded for every pair of
   !> masses (see the module), also when m1/m2 or m2/m1 is beyond the range of doubles.
   elemental function effective_mass(mass1, mass2) result(m)
      !> Mass of body 1 in kg, > 0 and finite
      real(wp), intent(in) :: mass1
      !> Mass of body 2 in kg, > 0 (+inf allowed)
      real(wp), intent(in) :: mass2
      !> Effective mass in kg
      real(wp) :: m
      type(scaled_dd) :: ratio
      m = nan
      if (.not. ieee_is_finite(mass1) .or. ieee_is_nan(mass2)) return
      if (.not. (mass1 > 0.0_wp .and. mass2 > 0.0_wp)) return
      if (.not. ieee_is_finite(mass2)) then
         m = mass1
         return
      end if
      ratio = ratio_of(min(mass1, mass2), max(mass1, mass2))
      m = round_scaled(fraction(min(mass1, mass2)) / (1.0_wp + unscaled(ratio)), &
         & exponent(min(mass1, mass2)))
   end function effective_mass

   !> small/large for 0 < small <= large < inf (masses or radii): the quotient of the
   !> significands, in (1/2, 2), and the difference of the exponents (so that the
   !> quotient neither underflows nor overflows).
   elemental function ratio_of(small, large) result(ratio)
      real(wp), intent(in) :: small, large
      type(scaled_dd) :: ratio
      ratio = scaled_dd(dd(fraction(small)) / fraction(large), exponent(small) - exponent(large))
   end function ratio_of

   !> Velocities of both bodies after a collinear impact with the coefficient of
   !> restitution k (from `impact`): the relative velocity v1 - v2 = V > 0 becomes -k V
   !> and the momentum m1 v1 + m2 v2 is conserved:
   !>
   !>     v1' = v1 - (1 + k) V m2/(m1 + m2),   v2' = v2 + (1 + k) V m1/(m1 + m2).
   !>
   !> Body 1 moves towards body 2 along the positive direction of the line. m2 = +inf
   !> is an immovable obstacle (v2' = v2).
   !>
   !> Evaluated as the velocity of the centre of mass, u = v1 s1 + v2 s2 with the shares
   !> s1 = m1/(m1 + m2) and s2 = m2/(m1 + m2), and the rebound about it:
   !> v1' = u - k V s2, v2' = u + k V s1. (The form v1 - (1 + k) V s2 cancels when
   !> m2 >> m1: then v1 and (1 + k) V s2 agree in hundreds of digits.) Each velocity is
   !> the double nearest to the exact value (see the module) unless the three terms
   !> cancel to below 2^-45 of the largest, which needs a restitution tuned to the
   !> last bit; a velocity beyond the largest double is +-inf (still hcimpact_ok).
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
      type(scaled_dd) :: share1, share2, momentum1, momentum2, rebound
      integer :: e_velocity

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

      call shares(mass1, mass2, share1, share2)
      ! v1 s1 and v2 s2, whose sum is the velocity of the centre of mass
      momentum1 = times(scaled_dd(dd(fraction(velocity1)), exponent(velocity1)), share1)
      momentum2 = times(scaled_dd(dd(fraction(velocity2)), exponent(velocity2)), share2)
      ! k (v1 - v2): the velocities scaled below 1 first, so that v1 - v2 cannot
      ! overflow; two_sum keeps it exact (a velocity that underflows in the scaling is
      ! below 2^-1074 of the other, and of v1 - v2)
      e_velocity = exponent(max(abs(velocity1), abs(velocity2)))
      rebound = scaled_dd(restitution * two_sum(scale(velocity1, -e_velocity), &
         & -scale(velocity2, -e_velocity)), e_velocity)
      velocity1_after = round_sum([momentum1, momentum2, negative(times(rebound, share2))])
      velocity2_after = round_sum([momentum1, momentum2, times(rebound, share1)])
   end subroutine two_body_velocities

   !> The shares m1/(m1 + m2) and m2/(m1 + m2): the larger mass's is 1/(1 + r), the
   !> smaller's r/(1 + r) with r = small/large (`ratio_of`), both with the exponent
   !> apart. m2 = +inf gives 0 and 1.
   elemental subroutine shares(mass1, mass2, share1, share2)
      real(wp), intent(in) :: mass1, mass2
      type(scaled_dd), intent(out) :: share1, share2
      type(scaled_dd) :: ratio, large_share, small_share
      if (.not. ieee_is_finite(mass2)) then
         share1 = scaled_dd(dd(0.0_wp), 0)
         share2 = scaled_dd(dd(1.0_wp), 0)
         return
      end if
      ratio = ratio_of(min(mass1, mass2), max(mass1, mass2))
      large_share = scaled_dd(1.0_wp / (1.0_wp + unscaled(ratio)), 0)
      small_share = scaled_dd(ratio%significand * large_share%significand, ratio%exponent)
      if (mass1 <= mass2) then
         share1 = small_share
         share2 = large_share
      else
         share1 = large_share
         share2 = small_share
      end if
   end subroutine shares

   !> The value of a scaled double-double number (underflows gracefully: used only
   !> where it is added to 1).
   elemental function unscaled(a) result(b)
      type(scaled_dd), intent(in) :: a
      type(dd_real) :: b
      b = dd_scale(a%significand, a%exponent)
   end function unscaled

   !> a b
   elemental function times(a, b) result(c)
      type(scaled_dd), intent(in) :: a, b
      type(scaled_dd) :: c
      c = scaled_dd(a%significand * b%significand, a%exponent + b%exponent)
   end function times

   !> -a
   elemental function negative(a) result(b)
      type(scaled_dd), intent(in) :: a
      type(scaled_dd) :: b
      b = scaled_dd(-a%significand, a%exponent)
   end function negative

   !> The sum of scaled double-double numbers, rounded once: each is scaled to the
   !> binary exponent of the largest and they are added in double-double (a term more
   !> than 2^1074 times smaller than the largest underflows there, which moves the sum
   !> by less than its last bit).
   pure function round_sum(terms) result(y)
      type(scaled_dd), intent(in) :: terms(:)
      real(wp) :: y
      type(dd_real) :: total
      integer :: i, top
      logical :: nonzero(size(terms))
      nonzero = terms%significand%hi /= 0.0_wp
      y = 0.0_wp
      if (.not. any(nonzero)) return
      top = maxval(exponent(terms%significand%hi) + terms%exponent, mask=nonzero)
      total = dd(0.0_wp)
      do i = 1, size(terms)
         if (nonzero(i)) total = total + dd_scale(terms(i)%significand, terms(i)%exponent - top)
      end do
      y = round_scaled(total, top)
   end function round_sum

   !> The double nearest to (a%hi + a%lo) 2^e (a normalised, |a%lo| <= ulp(a%hi)/2):
   !> exact scaling in the normal range; in the subnormal range scale() rounds a%hi
   !> once more, which can go the wrong way only when a%hi lies exactly halfway
   !> between two subnormals, and then a%lo decides. +-inf beyond the largest double,
   !> without an overflow exception.
   elemental function round_scaled(a, e) result(y)
      type(dd_real), intent(in) :: a
      integer, intent(in) :: e
      real(wp) :: y
      integer, parameter :: e_subnormal = minexponent(1.0_wp) - digits(1.0_wp)   ! -1074
      real(wp) :: back, gap, half
      integer :: e_result
      if (a%hi == 0.0_wp) then
         y = a%hi
         return
      end if
      ! |a 2^e| lies in [2^(e_result - 1), 2^e_result)
      e_result = exponent(a%hi) + e
      if (e_result > maxexponent(1.0_wp)) then
         if (a%hi > 0.0_wp) then
            y = ieee_value(1.0_wp, ieee_positive_inf)
         else
            y = ieee_value(1.0_wp, ieee_negative_inf)
         end if
         return
      end if
      if (e_result < e_subnormal) then
         ! below half the smallest subnormal: rounds to zero
         y = sign(0.0_wp, a%hi)
         return
      end if
      y = scale(a%hi, e)
      if (e_result >= minexponent(1.0_wp)) return
      ! subnormal: was a%hi exactly halfway between two neighbours of the coarser grid?
      back = scale(y, -e)
      gap = a%hi - back
      half = scale(1.0_wp, e_subnormal - 1 - e)
      if (abs(gap) /= half .or. a%lo == 0.0_wp) return
      if ((a%lo > 0.0_wp) .eqv. (gap > 0.0_wp)) then
         ! beyond the halfway point: away from back
         y = scale(back + sign(2.0_wp * half, gap), e)
      else
         y = scale(back, e)
      end if
   end function round_scaled

end module hcimpact_hertz
