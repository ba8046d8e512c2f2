! SPDX-License-Identifier: Apache-2.0
!> Arithmetic of the scene runner on the doubles a user may write into a scene (any
!> value up to the largest double, subnormals included), without the floating-point
!> exceptions the Debug build traps (invalid, division by zero, overflow): a product or
!> quotient beyond the largest double comes out as +-inf, formed by ieee_value, and
!> the caller decides whether that is a result (an energy too large to print) or an
!> error (a mass that does not fit in a double).
module hcimpact_scene_numbers
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: power_product, quotient_of, decimal_exponent

   !> Binary exponent within which a product is formed directly
   integer, parameter :: safe_exponent = 1000

contains

   !> x(1)**p(1) * x(2)**p(2) * ... for finite x >= 0: +inf where the product
   !> exceeds the largest double, 0 or a subnormal where it falls below the smallest
   !> normal one. Formed directly (the same roundings as the expression) when the
   !> powers cannot leave the range of doubles, else as 2^(sum p log2 x) (relative
   !> error below 2^-42: only for values beyond 2^+-1000 / size(x) in some factor).
   !> A base 0 gives 0 (with a positive power; +inf with a negative one, 1 with 0).
   pure recursive function power_product(x, p) result(y)
      !> The bases, >= 0 and finite
      real(wp), intent(in) :: x(:)
      !> The powers
      real(wp), intent(in) :: p(size(x))
      !> The product
      real(wp) :: y
      real(wp) :: total
      integer :: i, e
      y = 1.0_wp
      if (size(x) == 0) return
      if (any(x == 0.0_wp .and. p < 0.0_wp)) then
         y = ieee_value(1.0_wp, ieee_positive_inf)
         return
      end if
      if (any(x == 0.0_wp .and. p > 0.0_wp)) then
         y = 0.0_wp
         return
      end if
      if (any(x == 0.0_wp)) then
         y = power_product(pack(x, x /= 0.0_wp), pack(p, x /= 0.0_wp))
         return
      end if
      if (all(abs(p * exponent(x)) <= real(safe_exponent / size(x), wp))) then
         y = 1.0_wp
         do i = 1, size(x)
            if (p(i) == 1.0_wp) then
               y = y * x(i)
            else
               y = y * x(i)**p(i)
            end if
         end do
         return
      end if
      total = sum(p * log(x)) / log(2.0_wp)
      if (total >= real(maxexponent(1.0_wp), wp)) then
         y = ieee_value(1.0_wp, ieee_positive_inf)
      else if (total < real(minexponent(1.0_wp) - digits(1.0_wp) - 1, wp)) then
         y = 0.0_wp
      else
         e = floor(total)
         y = scale(2.0_wp**(total - real(e, wp)), e)
      end if
   end function power_product

   !> a/b for finite a and b /= 0; +-inf where the quotient exceeds the largest double.
   pure function quotient_of(a, b) result(q)
      !> Dividend, finite
      real(wp), intent(in) :: a
      !> Divisor, finite and not 0
      real(wp), intent(in) :: b
      !> a/b
      real(wp) :: q
      q = 0.0_wp
      if (a == 0.0_wp) return
      if (abs(exponent(a)) <= safe_exponent / 2 .and. abs(exponent(b)) <= safe_exponent / 2) then
         q = a / b
      else
         q = sign(power_product([abs(a), abs(b)], [1.0_wp, -1.0_wp]), a) * sign(1.0_wp, b)
      end if
   end function quotient_of

   !> The power of ten of x(1)**p(1) * x(2)**p(2) * ... for positive finite x (also
   !> far beyond the range of doubles), for messages: floor(sum p log10 x).
   pure function decimal_exponent(x, p) result(n)
      !> The bases, > 0 and finite
      real(wp), intent(in) :: x(:)
      !> The powers
      real(wp), intent(in) :: p(size(x))
      integer :: n
      n = floor(sum(p * log10(x)))
   end function decimal_exponent

end module hcimpact_scene_numbers
