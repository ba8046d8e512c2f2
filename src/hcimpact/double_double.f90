! SPDX-License-Identifier: Apache-2.0
!> Double-double arithmetic: a number is the unevaluated sum hi + lo of two doubles
!> with |lo| <= ulp(hi)/2, carrying about 106 bits.
!>
!> The closed forms of the impact (maximum compression, peak force, the time unit)
!> are products of fractional powers such as [(n+1) m h(beta) / (c b^2)]^(1/(n+1)).
!> In plain double precision the rounding of the exponent 1/(n+1) alone costs
!> |ln x| 2^-53 relatively, tens of ulps for x = 1e-10. Done here in double-double and
!> rounded once, they are correct to half an ulp plus about 1e-30.
!>
!> The error-free transformations are those of Dekker (Numer. Math. 18, 1971, 224) and
!> Knuth (TAOCP vol. 2, 4.2.2): two_sum, and two_prod by Veltkamp's splitting. The
!> elementary functions follow the usual double-double scheme (e.g. Hida, Li and Bailey,
!> "Library for double-double and quad-double arithmetic", 2007): exp by reduction
!> modulo ln 2, a further division by 2^9, a Taylor series and nine squarings; log by
!> one Newton step on exp from the double logarithm.
!>
!> All procedures are elemental. None of them raises an IEEE flag that the library
!> traps, for arguments in the ranges stated at each procedure.
module hcimpact_double_double
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: dd_real, dd, two_sum, two_prod
   public :: operator(+), operator(-), operator(*), operator(/)
   public :: dd_exp, dd_log, dd_sqrt, dd_scale

   !> A double-double number hi + lo
   type :: dd_real
      !> Leading part, the double nearest to the value
      real(wp) :: hi = 0.0_wp
      !> Trailing part
      real(wp) :: lo = 0.0_wp
   end type dd_real

   !> Sum of double-double numbers and doubles
   interface operator(+)
      module procedure :: add_dd_dd, add_dd_r, add_r_dd
   end interface operator(+)

   !> Difference and negation of double-double numbers and doubles
   interface operator(-)
      module procedure :: sub_dd_dd, sub_dd_r, sub_r_dd, neg_dd
   end interface operator(-)

   !> Product of double-double numbers and doubles
   interface operator(*)
      module procedure :: mul_dd_dd, mul_dd_r, mul_r_dd
   end interface operator(*)

   !> Quotient of double-double numbers and doubles
   interface operator(/)
      module procedure :: div_dd_dd, div_dd_r, div_r_dd
   end interface operator(/)

   !> ln 2 as a double-double number
   type(dd_real), parameter :: ln2 = dd_real(0.6931471805599453_wp, 2.3190468138462996e-17_wp)
   !> Veltkamp's splitting constant 2^27 + 1
   real(wp), parameter :: splitter = 134217729.0_wp
   !> Beyond this magnitude the splitting could overflow and is done at a smaller scale
   real(wp), parameter :: split_max = 2.0_wp**996
   !> exp overflows above this argument
   real(wp), parameter :: exp_max = 709.782712893384_wp
   !> exp underflows to zero below this argument
   real(wp), parameter :: exp_min = -745.1332191019411_wp

contains

   !> The double x as a double-double number.
   elemental function dd(x) result(a)
      !> Value
      real(wp), intent(in) :: x
      !> x + 0
      type(dd_real) :: a
      a = dd_real(x, 0.0_wp)
   end function dd

   !> Exact sum: a + b = s%hi + s%lo with s%hi = fl(a + b) (Knuth).
   elemental function two_sum(a, b) result(s)
      !> Summand
      real(wp), intent(in) :: a
      !> Summand
      real(wp), intent(in) :: b
      !> The sum, exactly
      type(dd_real) :: s
      real(wp) :: bv
      s%hi = a + b
      bv = s%hi - a
      s%lo = (a - (s%hi - bv)) + (b - bv)
   end function two_sum

   !> Exact sum when |a| >= |b| or a = 0 (Dekker).
   elemental function quick_two_sum(a, b) result(s)
      real(wp), intent(in) :: a, b
      type(dd_real) :: s
      s%hi = a + b
      s%lo = b - (s%hi - a)
   end function quick_two_sum

   !> Veltkamp's splitting of a into two halves of 26 bits each, a = ah + al.
   elemental subroutine split(a, ah, al)
      real(wp), intent(in) :: a
      real(wp), intent(out) :: ah, al
      real(wp) :: t
      if (abs(a) > split_max) then
         t = splitter * (a * 2.0_wp**(-28))
         ah = (t - (t - a * 2.0_wp**(-28))) * 2.0_wp**28
      else
         t = splitter * a
         ah = t - (t - a)
      end if
      al = a - ah
   end subroutine split

   !> Exact product: a b = p%hi + p%lo with p%hi = fl(a b) (Dekker), as long as the
   !> product neither overflows nor falls into the subnormal range.
   elemental function two_prod(a, b) result(p)
      !> Factor
      real(wp), intent(in) :: a
      !> Factor
      real(wp), intent(in) :: b
      !> The product, exactly
      type(dd_real) :: p
      real(wp) :: ah, al, bh, bl
      p%hi = a * b
      call split(a, ah, al)
      call split(b, bh, bl)
      if (abs(p%hi) > split_max) then
         ! the error term is below the precision of anything this large
         p%lo = 0.0_wp
      else
         p%lo = ((ah * bh - p%hi) + ah * bl + al * bh) + al * bl
      end if
   end function two_prod

   !> a 2^k, exact unless the result leaves the normal range.
   elemental function dd_scale(a, k) result(c)
      !> Value
      type(dd_real), intent(in) :: a
      !> Power of two
      integer, intent(in) :: k
      !> a 2^k
      type(dd_real) :: c
      c%hi = scale(a%hi, k)
      c%lo = scale(a%lo, k)
   end function dd_scale

   elemental function add_dd_dd(a, b) result(c)
      type(dd_real), intent(in) :: a, b
      type(dd_real) :: c
      type(dd_real) :: s, t
      s = two_sum(a%hi, b%hi)
      t = two_sum(a%lo, b%lo)
      s%lo = s%lo + t%hi
      s = quick_two_sum(s%hi, s%lo)
      s%lo = s%lo + t%lo
      c = quick_two_sum(s%hi, s%lo)
   end function add_dd_dd

   elemental function add_dd_r(a, b) result(c)
      type(dd_real), intent(in) :: a
      real(wp), intent(in) :: b
      type(dd_real) :: c
      type(dd_real) :: s
      s = two_sum(a%hi, b)
      s%lo = s%lo + a%lo
      c = quick_two_sum(s%hi, s%lo)
   end function add_dd_r

   elemental function add_r_dd(a, b) result(c)
      real(wp), intent(in) :: a
      type(dd_real), intent(in) :: b
      type(dd_real) :: c
      c = add_dd_r(b, a)
   end function add_r_dd

   elemental function neg_dd(a) result(c)
      type(dd_real), intent(in) :: a
      type(dd_real) :: c
      c = dd_real(-a%hi, -a%lo)
   end function neg_dd

   elemental function sub_dd_dd(a, b) result(c)
      type(dd_real), intent(in) :: a, b
      type(dd_real) :: c
      c = add_dd_dd(a, neg_dd(b))
   end function sub_dd_dd

   elemental function sub_dd_r(a, b) result(c)
      type(dd_real), intent(in) :: a
      real(wp), intent(in) :: b
      type(dd_real) :: c
      c = add_dd_r(a, -b)
   end function sub_dd_r

   elemental function sub_r_dd(a, b) result(c)
      real(wp), intent(in) :: a
      type(dd_real), intent(in) :: b
      type(dd_real) :: c
      c = add_dd_r(neg_dd(b), a)
   end function sub_r_dd

   elemental function mul_dd_dd(a, b) result(c)
      type(dd_real), intent(in) :: a, b
      type(dd_real) :: c
      type(dd_real) :: p
      p = two_prod(a%hi, b%hi)
      p%lo = p%lo + (a%hi * b%lo + a%lo * b%hi)
      c = quick_two_sum(p%hi, p%lo)
   end function mul_dd_dd

   elemental function mul_dd_r(a, b) result(c)
      type(dd_real), intent(in) :: a
      real(wp), intent(in) :: b
      type(dd_real) :: c
      type(dd_real) :: p
      p = two_prod(a%hi, b)
      p%lo = p%lo + a%lo * b
      c = quick_two_sum(p%hi, p%lo)
   end function mul_dd_r

   elemental function mul_r_dd(a, b) result(c)
      real(wp), intent(in) :: a
      type(dd_real), intent(in) :: b
      type(dd_real) :: c
      c = mul_dd_r(b, a)
   end function mul_r_dd

   !> a / b by long division: three partial quotients.
   elemental function div_dd_dd(a, b) result(c)
      type(dd_real), intent(in) :: a, b
      type(dd_real) :: c
      real(wp) :: q1, q2, q3
      type(dd_real) :: r
      q1 = a%hi / b%hi
      r = a - b * q1
      q2 = r%hi / b%hi
      r = r - b * q2
      q3 = r%hi / b%hi
      c = quick_two_sum(q1, q2)
      c = c + q3
   end function div_dd_dd

   elemental function div_dd_r(a, b) result(c)
      type(dd_real), intent(in) :: a
      real(wp), intent(in) :: b
      type(dd_real) :: c
      real(wp) :: q1, q2
      type(dd_real) :: r
      q1 = a%hi / b
      r = a - two_prod(q1, b)
      q2 = r%hi / b
      r = r - two_prod(q2, b)
      c = quick_two_sum(q1, q2)
      c = c + r%hi / b
   end function div_dd_r

   elemental function div_r_dd(a, b) result(c)
      real(wp), intent(in) :: a
      type(dd_real), intent(in) :: b
      type(dd_real) :: c
      c = div_dd_dd(dd(a), b)
   end function div_r_dd

   !> Square root of a >= 0 (one Newton correction of the double root).
   elemental function dd_sqrt(a) result(c)
      !> Radicand, >= 0
      type(dd_real), intent(in) :: a
      !> sqrt(a)
      type(dd_real) :: c
      real(wp) :: s
      type(dd_real) :: r
      if (.not. a%hi > 0.0_wp) then
         c = dd(0.0_wp)
         return
      end if
      s = sqrt(a%hi)
      r = a - two_prod(s, s)
      c = quick_two_sum(s, r%hi / (2.0_wp * s))
   end function dd_sqrt

   !> exp(a). Overflow (a%hi > 709.78) gives +Inf without arithmetic on it; a%hi below
   !> -745.13 gives 0; results in the subnormal range keep only the leading part.
   elemental function dd_exp(a) result(c)
      !> Argument
      type(dd_real), intent(in) :: a
      !> exp(a)
      type(dd_real) :: c
      ! Taylor terms kept for |r| <= ln(2)/2^10: the first omitted, r^10/10!, is 6e-39 r
      integer, parameter :: terms = 10
      ! the reduced argument is divided by 2^squarings, the result squared as often
      integer, parameter :: squarings = 9
      ! 1/(j+1)! as two doubles, folded at compile time in quadruple precision
      integer, parameter :: qp = selected_real_kind(30)
      integer :: j
      real(wp), parameter :: fact_hi(0:terms - 1) = real(1.0_qp / gamma(real([(j, &
         & j = 2, terms + 1)], qp)), wp)
      real(wp), parameter :: fact_lo(0:terms - 1) = real(1.0_qp / gamma(real([(j, &
         & j = 2, terms + 1)], qp)) - real(fact_hi, qp), wp)
      type(dd_real) :: r, p
      integer :: k

      if (a%hi > exp_max) then
         c = dd(ieee_value(1.0_wp, ieee_positive_inf))
         return
      end if
      if (a%hi < exp_min) then
         c = dd(0.0_wp)
         return
      end if
      k = nint(a%hi / ln2%hi)
      r = dd_scale(a - ln2 * real(k, wp), -squarings)
      ! expm1(r) = r sum_j r^j/(j+1)! by Horner's rule with double-double coefficients
      p = dd_real(fact_hi(terms - 1), fact_lo(terms - 1))
      do j = terms - 2, 0, -1
         p = dd_real(fact_hi(j), fact_lo(j)) + r * p
      end do
      p = r * p
      ! (1 + p)^2 - 1 = p (2 + p), kept in this form so that no digit of p is lost
      do j = 1, squarings
         p = p * (p + 2.0_wp)
      end do
      p = p + 1.0_wp
      if (k > 1021) then
         ! 2^k itself would overflow: scale in two steps
         c = dd_scale(dd_scale(p, k - 2), 2)
      else
         c = dd_scale(p, k)
      end if
   end function dd_exp

   !> Natural logarithm of a > 0 (finite): a = 2^e f with f in [1/2, 1), then one
   !> Newton step y + f exp(-y) - 1 from the double logarithm y of f, plus e ln 2.
   !> The absolute error is about 1e-32.
   elemental function dd_log(a) result(c)
      !> Argument, a%hi > 0 and finite
      type(dd_real), intent(in) :: a
      !> ln(a)
      type(dd_real) :: c
      type(dd_real) :: f
      real(wp) :: y
      integer :: e
      e = exponent(a%hi)
      f = dd_scale(a, -e)
      y = log(f%hi)
      c = ((f * dd_exp(dd(-y)) - 1.0_wp) + y) + ln2 * real(e, wp)
   end function dd_log

end module hcimpact_double_double
