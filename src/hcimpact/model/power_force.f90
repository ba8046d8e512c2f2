! SPDX-License-Identifier: Apache-2.0
!> The power law f = c x^n, its potential and its derivative, evaluated once for the
!> whole library: products of correctly rounded factors that never overflow or underflow
!> on the way (a representable result is returned as such).
!>
!> hcimpact_elastic's `power_law` and the contact-force element (hcimpact_force_element)
!> both evaluate the law here.
module hcimpact_power_force
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf
   use hcimpact_kinds, only : wp
   use hcimpact_double_double, only : dd_real, dd, two_sum, operator(+), operator(-), &
      & operator(*), dd_exp, dd_log
   implicit none
   private

   public :: power_law_force, power_law_potential, power_law_derivative
   public :: power_product, product_of, signed_product, safe_power

contains

   !> f(x) = c x^n in N for x > 0 (0 for x <= 0); within about 1.5 ulp.
   elemental function power_law_force(c, n, x) result(f)
      !> Contact constant c in N/m^n (> 0) and exponent n (> 0)
      real(wp), intent(in) :: c, n
      !> Deformation in m
      real(wp), intent(in) :: x
      !> Force in N
      real(wp) :: f
      f = 0.0_wp
      if (x > 0.0_wp) f = power_product(safe_power(x, n), x, n, [c], 1.0_wp)
   end function power_law_force

   !> Pi(x) = c x^(n+1)/(n+1) in J for x > 0 (0 for x <= 0); within a few ulps.
   elemental function power_law_potential(c, n, x) result(p)
      !> Contact constant c in N/m^n (> 0) and exponent n (> 0)
      real(wp), intent(in) :: c, n
      !> Deformation in m
      real(wp), intent(in) :: x
      !> Potential energy in J
      real(wp) :: p
      type(dd_real) :: np1
      p = 0.0_wp
      if (.not. x > 0.0_wp) return
      np1 = two_sum(n, 1.0_wp)
      p = power_product(safe_power(x, n), x, n, [c, x], np1%hi)
   end function power_law_potential

   !> f'(x) = n c x^(n-1) in N/m for x > 0, formed as n f(x)/x (no rounding of n - 1
   !> in the exponent); within a few ulps, +Inf only where it overflows. At x <= 0 the
   !> limit from the right: 0 for n > 1, c for n = 1, and for n < 1 (where it is
   !> infinite) the largest double.
   elemental function power_law_derivative(c, n, x) result(d)
      !> Contact constant c in N/m^n (> 0) and exponent n (> 0)
      real(wp), intent(in) :: c, n
      !> Deformation in m
      real(wp), intent(in) :: x
      !> Derivative in N/m
      real(wp) :: d
      if (x > 0.0_wp) then
         d = power_product(safe_power(x, n), x, n, [c, n], x)
      else if (n > 1.0_wp) then
         d = 0.0_wp
      else if (n == 1.0_wp) then
         d = c
      else
         d = huge(1.0_wp)
      end if
   end function power_law_derivative

   !> factors(1) * ... * factors(k) * x^p / divisor for positive finite factors (none
   !> zero), x > 0 and a positive finite divisor, with xp = x**p already formed (0 when
   !> it is not a normal double: safe_power). Multiplied directly when x^p and the
   !> partial products stay normal (each rounding then relative); otherwise from
   !> double-double logarithms (`log_product`).
   pure function power_product(xp, x, p, factors, divisor) result(y)
      real(wp), intent(in) :: xp, x, p
      real(wp), intent(in) :: factors(:)
      real(wp), intent(in) :: divisor
      real(wp) :: y
      integer :: i

      ! each product is formed only when the exponents say it stays normal (within a
      ! factor 2 of the estimate), so that no overflow is ever raised (the Debug build
      ! traps on it) and no digit is lost to underflow on the way
      if (xp >= tiny(1.0_wp) .and. xp <= huge(1.0_wp)) then
         y = xp
         do i = 1, size(factors)
            if (.not. normal_product(exponent(y) + exponent(factors(i)))) exit
            y = y * factors(i)
         end do
         if (i > size(factors)) then
            if (normal_product(exponent(y) - exponent(divisor))) then
               y = y / divisor
               return
            end if
         end if
      end if
      y = log_product(x, p, factors, divisor)
   end function power_product

   !> Whether a product (or quotient) whose binary exponents add up to e is surely a
   !> normal double (the result's exponent is e or e - 1)
   elemental logical function normal_product(e)
      integer, intent(in) :: e
      normal_product = e <= maxexponent(1.0_wp) - 1 .and. e >= minexponent(1.0_wp) + 1
   end function normal_product

   !> x^p for x > 0, or 0 when it would overflow or leave the normal range (then the
   !> callers take the logarithms: power_product); no overflow is raised.
   elemental function safe_power(x, p) result(y)
      real(wp), intent(in) :: x, p
      real(wp) :: y
      real(wp) :: estimate
      y = 0.0_wp
      ! the test below needs |p| < maxexponent - 4: a larger p fails it without forming
      ! p e(x), which overflows for p near the largest double (a trap in Debug builds)
      if (.not. abs(p) < real(maxexponent(1.0_wp) - 4, wp)) return
      ! log2(x^p) = p log2(x), log2(x) within 1 of exponent(x)
      estimate = p * real(exponent(x), wp)
      if (abs(estimate) + abs(p) < real(maxexponent(1.0_wp) - 4, wp)) y = x**p
   end function safe_power

   !> factors(1) * ... * factors(k) * x^p / divisor from the sum of their logarithms in
   !> double-double (each ln(2^e f) = e ln 2 + ln f to about 2^-100 relative), then one
   !> exponential: a result above the largest double is +Inf, below the smallest
   !> subnormal 0, and a subnormal result is rounded once more to its precision.
   !> Where |p ln x| alone exceeds what the other logarithms (each within 745 of 0)
   !> could bring back into the range, the result is 0 or +Inf without forming p ln x,
   !> which overflows for p near the largest double (the fuzzer's n = 2.5e307 at
   !> x = 3.8e-10 gave NaN: -inf plus the NaN of its trailing part).
   pure function log_product(x, p, factors, divisor) result(y)
      real(wp), intent(in) :: x, p
      real(wp), intent(in) :: factors(:)
      real(wp), intent(in) :: divisor
      real(wp) :: y
      type(dd_real) :: l, r
      real(wp) :: log_x, bound
      logical :: beyond
      integer :: i
      ! beyond what a product of doubles can bring back: about 2 ln(huge) per factor
      real(wp), parameter :: beyond_range = 1500.0_wp

      log_x = log(x)
      bound = beyond_range * real(size(factors) + 2, wp)
      ! |p ln x| > bound, tested without forming a product or quotient that could
      ! overflow (separate branches: Fortran's .and. may evaluate both operands)
      if (p >= 1.0_wp) then
         beyond = abs(log_x) > bound / p
      else
         beyond = abs(log_x) * abs(p) > bound
      end if
      if (beyond) then
         y = 0.0_wp
         if (log_x > 0.0_wp) y = ieee_value(1.0_wp, ieee_positive_inf)
         return
      end if
      ! below a quarter of the smallest subnormal whatever the fractions: 0, as the
      ! logarithms would give, without them (the beads ahead of a wave, pressed by
      ! 1e-250 m, went this way: 11 % of a struck chain's time). Not with a subnormal
      ! divisor, nor a subnormal x with p < 0, whose binary exponents the standard
      ! leaves to the compiler (gfortran's are those of the value; one clamped to
      ! minexponent would make the bound too low)
      if (divisor >= tiny(1.0_wp) .and. (p >= 0.0_wp .or. x >= tiny(1.0_wp))) then
         if (log2_bound(x, p, factors, divisor) < real(minexponent(1.0_wp) &
            & - digits(1.0_wp) - 2, wp)) then
            y = 0.0_wp
            return
         end if
      end if
      l = p * dd_log(dd(x)) - dd_log(dd(divisor))
      do i = 1, size(factors)
         l = l + dd_log(dd(factors(i)))
      end do
      r = dd_exp(l)
      y = r%hi
   end function log_product

   !> An upper bound of log2(factors(1) * ... * factors(k) * x^p / divisor) from the
   !> binary exponents alone (a double 2^e f has f in [1/2, 1), so log2 lies in
   !> [e - 1, e)), for |p ln x| within log_product's bound (p e(x) is then finite)
   pure real(wp) function log2_bound(x, p, factors, divisor) result(bound)
      real(wp), intent(in) :: x, p
      real(wp), intent(in) :: factors(:)
      real(wp), intent(in) :: divisor
      bound = p * real(exponent(x), wp) + max(0.0_wp, -p) &
         & + real(sum(exponent(factors)) - exponent(divisor) + 1, wp)
   end function log2_bound

   !> The product of positive finite doubles without overflow or underflow on the way:
   !> direct when the partial products stay normal, else from logarithms.
   pure function product_of(factors) result(y)
      real(wp), intent(in) :: factors(:)
      real(wp) :: y
      if (any(factors == 0.0_wp)) then
         y = 0.0_wp
         return
      end if
      y = power_product(1.0_wp, 1.0_wp, 0.0_wp, factors, 1.0_wp)
   end function product_of

   !> a times the product of positive finite factors, a of either sign.
   pure function signed_product(a, factors) result(y)
      real(wp), intent(in) :: a
      real(wp), intent(in) :: factors(:)
      real(wp) :: y
      y = sign(product_of([abs(a), factors]), a)
   end function signed_product

end module hcimpact_power_force
