! SPDX-License-Identifier: Apache-2.0
!> Tanh-sinh (double exponential) quadrature on a finite interval.
!>
!> The rule of Takahasi and Mori (1974): with x = c + r tanh((pi/2) sinh t),
!> c = (a+b)/2 and r = (b-a)/2,
!>
!>     int_a^b f(x) dx = r int_-inf^inf f(x(t)) w(t) dt,
!>     w(t) = (pi/2) cosh t / cosh^2((pi/2) sinh t),
!>
!> and the trapezoidal rule in t with step h converges like exp(-c/h) for
!> integrands analytic inside the interval, even when they are singular at its
!> ends, because w(t) decays double exponentially.
!>
!> The scheme of levels follows Bailey, Jeyabalan and Li (Experimental
!> Mathematics 14, 2005, 317-329): level k uses h = 2**(-k) and only adds the
!> nodes at odd multiples of h, so every evaluation is kept. The nodes and
!> weights are constants computed by the compiler (in quadruple precision when
!> it has one) and rounded once to working precision.
!>
!> Each node is handed to the integrand with its distances to both ends, and
!> the distance to the nearer end is formed without cancellation:
!> b - x = r (1 - tanh u) = 2 r / (1 + exp(2u)), u = (pi/2) sinh t, from a
!> table of 1 - tanh u. A node never lies on an end (its distance is at least
!> the smallest normal number), although x itself may round to a or b: an
!> integrand singular at an end must be written in terms of the distance.
!>
!> Method, error estimate, limits and measured costs: doc/quadrature.md.
module hcimpact_quadrature
   use, intrinsic :: iso_fortran_env, only : real128
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_quiet_nan, ieee_positive_inf
   use hcimpact_kinds, only : wp, ik
   implicit none
   private

   public :: integrand_type, integrand_eval, quadrature_function, quadrature_result
   public :: tanh_sinh, quadrature_status_message
   public :: quadrature_success, quadrature_not_converged, quadrature_nonfinite, &
      & quadrature_invalid_interval, quadrature_invalid_tolerance, quadrature_invalid_levels
   public :: tanh_sinh_max_levels, tanh_sinh_default_levels

   !> The integral met the tolerance
   integer(ik), parameter :: quadrature_success = 0_ik
   !> The last level allowed did not meet the tolerance; the result is the best
   !> estimate and its error estimate is still reported
   integer(ik), parameter :: quadrature_not_converged = 1_ik
   !> The integrand returned NaN or an infinity, or the sum overflowed;
   !> the integral is NaN and the error estimate +Inf
   integer(ik), parameter :: quadrature_nonfinite = 2_ik
   !> An end of the interval is NaN or infinite, a > b, or b - a overflows
   integer(ik), parameter :: quadrature_invalid_interval = 3_ik
   !> rtol is NaN or not positive, or atol is NaN or negative
   integer(ik), parameter :: quadrature_invalid_tolerance = 4_ik
   !> max_levels is outside 2 .. tanh_sinh_max_levels
   integer(ik), parameter :: quadrature_invalid_levels = 5_ik

   !> Texts of the status codes 0 .. 5 (blank-padded), then the one for unknown codes
   character(len=60), parameter :: quadrature_texts(0:6) = [character(len=60) :: &
      & "converged to the requested tolerance", &
      & "tolerance not met at the last level allowed", &
      & "the integrand returned NaN or an infinity", &
      & "interval ends must be finite with a <= b and b - a finite", &
      & "rtol must be positive and atol non-negative", &
      & "max_levels outside the range of the node tables", &
      & "unknown status"]

   !> Deepest level of the node tables: the finest step is 2**(-tanh_sinh_max_levels)
   integer(ik), parameter :: tanh_sinh_max_levels = 10_ik
   !> Number of levels tried when the caller does not say (finest step 1/256)
   integer(ik), parameter :: tanh_sinh_default_levels = 8_ik

   !> The tables run over 0 <= t <= table_end; at t = 6 the distance of a node
   !> to its end is 2 exp(-pi sinh 6) = 1.7e-275 times r, still a normal number.
   integer, parameter :: table_end = 6
   !> Index of the last node in the tables
   integer, parameter :: table_size = table_end * 2**tanh_sinh_max_levels

   !> Kind in which the compiler evaluates the tables: quadruple when available
   integer, parameter :: xp = merge(real128, wp, real128 > 0)

   !> Sides of the centre that the walks take: t > 0 (nodes near b), t < 0 (near a)
   integer, parameter :: toward_b = 1, toward_a = 2

   !> Integrand with whatever state it needs; extend it and implement `eval`.
   type, abstract :: integrand_type
   contains
      !> Value of the integrand at a node
      procedure(integrand_eval), deferred :: eval
   end type integrand_type

   abstract interface
      !> Value of the integrand at the node x of [a, b]. The distances are the
      !> accurate ones: near an end, write a singular factor in terms of dxa or
      !> dxb rather than x (x - a and b - x would cancel).
      pure function integrand_eval(self, x, dxa, dxb) result(fx)
         import :: integrand_type, wp
         !> The integrand and its parameters
         class(integrand_type), intent(in) :: self
         !> Node, a < x < b up to rounding (x may round onto an end)
         real(wp), intent(in) :: x
         !> Distance x - a, always > 0
         real(wp), intent(in) :: dxa
         !> Distance b - x, always > 0
         real(wp), intent(in) :: dxb
         !> Integrand at the node
         real(wp) :: fx
      end function integrand_eval

      !> A stateless integrand given as a plain pure function, same arguments
      !> as `integrand_eval`.
      pure function quadrature_function(x, dxa, dxb) result(fx)
         import :: wp
         !> Node, a < x < b up to rounding (x may round onto an end)
         real(wp), intent(in) :: x
         !> Distance x - a, always > 0
         real(wp), intent(in) :: dxa
         !> Distance b - x, always > 0
         real(wp), intent(in) :: dxb
         !> Integrand at the node
         real(wp) :: fx
      end function quadrature_function
   end interface

   !> Outcome of one integration
   type :: quadrature_result
      !> Estimate of the integral
      real(wp) :: integral = 0.0_wp
      !> Estimate of its absolute error (see doc/quadrature.md for what it includes)
      real(wp) :: error = 0.0_wp
      !> Number of calls of the integrand
      integer(ik) :: evaluations = 0_ik
      !> Levels completed: the finest step used was 2**(-levels) (0 if none)
      integer(ik) :: levels = 0_ik
      !> One of the quadrature_* status codes
      integer(ik) :: status = quadrature_success
   end type quadrature_result

   !> Adapter that lets a plain function go through the same integrator
   type, extends(integrand_type) :: function_integrand
      procedure(quadrature_function), pointer, nopass :: fun => null()
   contains
      procedure :: eval => function_integrand_eval
   end type function_integrand

   !> Integrate over a finite interval [a, b] by tanh-sinh quadrature.
   interface tanh_sinh
      module procedure :: tanh_sinh_integrand
      module procedure :: tanh_sinh_function
   end interface tanh_sinh

contains

   !> Integral of an integrand object over [a, b] (Takahasi-Mori rule, levels of
   !> Bailey et al.). Stops at the first level whose error estimate is at most
   !> max(rtol, epsilon) |integral| + atol.
   pure subroutine tanh_sinh_integrand(integrand, a, b, res, rtol, atol, max_levels, analytic)
      !> Integrand; its `eval` receives the node and its distances to a and b
      class(integrand_type), intent(in) :: integrand
      !> Lower end, finite
      real(wp), intent(in) :: a
      !> Upper end, finite, b >= a (b = a gives 0), b - a finite
      real(wp), intent(in) :: b
      !> Integral, error estimate, evaluations, levels and status
      type(quadrature_result), intent(out) :: res
      !> Relative tolerance, > 0; values below epsilon(1._wp) act as epsilon
      !> (default: epsilon, i.e. full working precision)
      real(wp), intent(in), optional :: rtol
      !> Absolute tolerance, >= 0 (default 0)
      real(wp), intent(in), optional :: atol
      !> Most levels to compute, 2 .. tanh_sinh_max_levels (default tanh_sinh_default_levels)
      integer(ik), intent(in), optional :: max_levels
      !> The caller vouches that the transformed integrand is analytic in a strip around
      !> the real t axis with no singularity near the interval, so that the rule doubles
      !> its digits per level (Takahasi-Mori): the error estimate then predicts the next
      !> level as d_k**2/d_(k-1) (Bailey's estimate) and saves the level that would only
      !> confirm convergence. Default false (the cautious estimate below).
      logical, intent(in), optional :: analytic

      call integrate(integrand, a, b, res, rtol, atol, max_levels, analytic)
   end subroutine tanh_sinh_integrand

   !> Integral of a plain pure function over [a, b]; see `tanh_sinh_integrand`.
   pure subroutine tanh_sinh_function(fun, a, b, res, rtol, atol, max_levels, analytic)
      !> Integrand f(x, x - a, b - x)
      procedure(quadrature_function) :: fun
      !> Lower end, finite
      real(wp), intent(in) :: a
      !> Upper end, finite, b >= a (b = a gives 0), b - a finite
      real(wp), intent(in) :: b
      !> Integral, error estimate, evaluations, levels and status
      type(quadrature_result), intent(out) :: res
      !> Relative tolerance, > 0; values below epsilon(1._wp) act as epsilon
      !> (default: epsilon)
      real(wp), intent(in), optional :: rtol
      !> Absolute tolerance, >= 0 (default 0)
      real(wp), intent(in), optional :: atol
      !> Most levels to compute, 2 .. tanh_sinh_max_levels (default tanh_sinh_default_levels)
      integer(ik), intent(in), optional :: max_levels
      !> Digits double per level (see tanh_sinh_integrand); default false
      logical, intent(in), optional :: analytic

      type(function_integrand) :: wrapped

      wrapped%fun => fun
      call integrate(wrapped, a, b, res, rtol, atol, max_levels, analytic)
   end subroutine tanh_sinh_function

   !> Forward a node to the wrapped plain function.
   pure function function_integrand_eval(self, x, dxa, dxb) result(fx)
      !> The adapter
      class(function_integrand), intent(in) :: self
      !> Node
      real(wp), intent(in) :: x
      !> Distance x - a
      real(wp), intent(in) :: dxa
      !> Distance b - x
      real(wp), intent(in) :: dxb
      !> Integrand at the node
      real(wp) :: fx

      fx = self%fun(x, dxa, dxb)
   end function function_integrand_eval

   !> Row of quadrature_texts for a status code (the last row for unknown codes).
   pure function quadrature_message_row(status) result(row)
      !> One of the quadrature_* codes
      integer(ik), intent(in) :: status
      !> Index into quadrature_texts
      integer :: row

      row = ubound(quadrature_texts, 1)
      if (status >= 0_ik .and. status < ubound(quadrature_texts, 1)) row = int(status)
   end function quadrature_message_row

   !> Length of quadrature_status_message(status).
   pure function quadrature_message_length(status) result(length)
      !> One of the quadrature_* codes
      integer(ik), intent(in) :: status
      !> Number of characters
      integer :: length

      length = len_trim(quadrature_texts(quadrature_message_row(status)))
   end function quadrature_message_length

   !> Short English description of a status code. Its length is a specification
   !> expression, not a deferred length (gfortran would keep that in a hidden static
   !> variable of every caller, shared by threads).
   pure function quadrature_status_message(status) result(message)
      !> One of the quadrature_* codes
      integer(ik), intent(in) :: status
      !> Description
      character(len=quadrature_message_length(status)) :: message

      message = quadrature_texts(quadrature_message_row(status))
   end function quadrature_status_message

   !> The integrator behind both entry points.
   !>
   !> Level 0 (h = 1) walks outwards from t = 0 on both sides at once and stops a
   !> side after two consecutive terms |w f| below `small` (a 2**-10 share of the
   !> tolerance applied to the sum of |w f| so far); that fixes how far the finer
   !> levels go. A finer level also stops a side at its first small term past the
   !> last large term of level 0: the tails of w f decay double exponentially.
   !>
   !> Error estimate after level k, with d_k = |I_k - I_(k-1)| and L the
   !> integral of |f| (as summed by the rule):
   !>   d_k (d_k / d_(k-1))**(1/2)  when the levels converge: d_k < d_(k-1) <= L/10,
   !>                               and d_k/L >= (d_(k-1)/L)**3 unless d_k is at
   !>                               rounding level (more than tripling the digits
   !>                               in one level is a coincidence, not convergence);
   !>   max(d_k, d_(k-1))           when d_(k-1) > L/10 (level k-1 had no digit
   !>                               right, so d_k may be small by coincidence);
   !>   d_k                         otherwise.
   !> Level 1 is never accepted: one difference proves nothing.
   !> The first form assumes the next level gains at least half as many digits as
   !> the last one did. The asymptotic rate of the rule doubles the digits per
   !> level (Bailey's estimate uses that and takes the power 1); half is what stays
   !> honest when a singularity near the interval takes over the convergence late
   !> (see doc/quadrature.md). Added to it: half an ulp of L (rounding), the
   !> tails dropped by the truncation, and the integrand beyond the tables.
   pure subroutine integrate(integrand, a, b, res, rtol, atol, max_levels, analytic)
      !> Integrand
      class(integrand_type), intent(in) :: integrand
      !> Lower end
      real(wp), intent(in) :: a
      !> Upper end
      real(wp), intent(in) :: b
      !> Integral, error estimate, evaluations, levels and status
      type(quadrature_result), intent(out) :: res
      !> Relative tolerance (default epsilon)
      real(wp), intent(in), optional :: rtol
      !> Absolute tolerance (default 0)
      real(wp), intent(in), optional :: atol
      !> Most levels (default tanh_sinh_default_levels)
      integer(ik), intent(in), optional :: max_levels
      !> Digits double per level (see tanh_sinh_integrand); default false
      logical, intent(in), optional :: analytic

      ! Node tables, folded by the compiler in the kind xp and rounded once:
      ! for t_i = i 2**(-tanh_sinh_max_levels) and u_i = (pi/2) sinh t_i,
      !   complement_i = 1 - tanh u_i = 2 / (1 + exp(2 u_i))
      !   weight_i     = (pi/2) cosh t_i / cosh^2 u_i.
      ! No overflow up to t = 6 (exp(2 u) = 1e275). The expressions sit inside
      ! the array constructors: gfortran folds an elemental intrinsic applied to
      ! a whole parameter array in quadratic time.
      integer :: i
      real(xp), parameter :: pi_xp = acos(-1.0_xp)
      real(xp), parameter :: step_xp = 2.0_xp**(-tanh_sinh_max_levels)
      real(wp), parameter :: complement(0:table_size) = &
         & [(real(2 / (1 + exp(pi_xp * sinh(i * step_xp))), wp), i = 0, table_size)]
      real(wp), parameter :: weight(0:table_size) = &
         & [(real(pi_xp / 2 * cosh(i * step_xp) / cosh(pi_xp / 2 * sinh(i * step_xp))**2, wp), &
         & i = 0, table_size)]

      real(wp), parameter :: share = 2.0_wp**(-10)

      real(wp) :: rtol_eff, atol_eff, r, small
      real(wp) :: total, comp, l1, g
      real(wp) :: integral, previous, delta, delta_prev, l1_int, estimate
      logical :: doubling
      real(wp) :: tail, truncation, h
      integer :: levels, level, stride, j, side, last_index
      integer :: cut(2), last_large(2), small_run(2)
      real(wp) :: g_last(2)
      logical :: walking(2)

      res = quadrature_result()

      ! Arguments. NaN is tested first: an ordered comparison with NaN would
      ! raise the invalid flag.
      if (ieee_is_nan(a) .or. ieee_is_nan(b)) then
         res%status = quadrature_invalid_interval
         return
      end if
      if (.not. (ieee_is_finite(a) .and. ieee_is_finite(b))) then
         res%status = quadrature_invalid_interval
         return
      end if
      if (a > b) then
         res%status = quadrature_invalid_interval
         return
      end if
      rtol_eff = epsilon(1.0_wp)
      if (present(rtol)) then
         if (ieee_is_nan(rtol)) then
            res%status = quadrature_invalid_tolerance
            return
         end if
         if (.not. rtol > 0.0_wp) then
            res%status = quadrature_invalid_tolerance
            return
         end if
         rtol_eff = max(rtol, epsilon(1.0_wp))
      end if
      atol_eff = 0.0_wp
      if (present(atol)) then
         if (ieee_is_nan(atol)) then
            res%status = quadrature_invalid_tolerance
            return
         end if
         if (atol < 0.0_wp) then
            res%status = quadrature_invalid_tolerance
            return
         end if
         atol_eff = atol
      end if
      doubling = .false.
      if (present(analytic)) doubling = analytic
      levels = tanh_sinh_default_levels
      if (present(max_levels)) then
         if (max_levels < 2 .or. max_levels > tanh_sinh_max_levels) then
            res%status = quadrature_invalid_levels
            return
         end if
         levels = max_levels
      end if

      ! Half-width, without overflow for ends beyond huge/2 (halving first
      ! would lose the last bit of a subnormal end, so only there). The width
      ! itself must be a finite number: the distances handed to the integrand
      ! reach it.
      if (max(abs(a), abs(b)) <= 0.5_wp * huge(1.0_wp)) then
         r = 0.5_wp * (b - a)
      else
         r = 0.5_wp * b - 0.5_wp * a
         if (r > 0.5_wp * huge(1.0_wp)) then
            res%status = quadrature_invalid_interval
            return
         end if
      end if
      ! a = b, or b - a the smallest subnormal number: nothing to integrate.
      if (.not. r > 0.0_wp) return

      ! Last node whose distance to its end, r complement_i, is a normal number.
      last_index = last_normal_node(r, complement)

      total = 0.0_wp
      comp = 0.0_wp
      tail = 0.0_wp

      ! Level 0, h = 1: the centre, then outwards on both sides.
      call add_node(integrand, a, b, r, complement(0), weight(0), toward_a, g, total, comp, res)
      if (res%status /= quadrature_success) return
      l1 = abs(g)
      g_last(:) = g
      walking(:) = .true.
      small_run(:) = 0
      last_large(:) = 0
      cut(:) = last_index + 1
      stride = 2**tanh_sinh_max_levels
      j = 0
      do while (any(walking))
         j = j + 1
         i = j * stride
         do side = 1, 2
            if (.not. walking(side)) cycle
            if (i > last_index) then
               ! Out of table (or the distance would underflow): whatever lies
               ! beyond is at most about |w f| at the last node times a unit of t.
               walking(side) = .false.
               if (small_run(side) == 0) tail = tail + r * abs(g_last(side))
               cycle
            end if
            call add_node(integrand, a, b, r, complement(i), weight(i), side, g, total, comp, res)
            if (res%status /= quadrature_success) return
            l1 = l1 + abs(g)
            g_last(side) = g
            small = share * (rtol_eff * r * l1 + atol_eff)
            if (r * abs(g) <= small) then
               small_run(side) = small_run(side) + 1
               if (small_run(side) >= 2) then
                  walking(side) = .false.
                  cut(side) = i - stride
               end if
            else
               small_run(side) = 0
               last_large(side) = i
            end if
         end do
      end do
      integral = r * (total + comp)
      l1_int = r * l1
      res%levels = 0

      delta_prev = 0.0_wp
      do level = 1, levels
         stride = 2**(tanh_sinh_max_levels - level)
         h = 2.0_wp**(-level)
         ! Terms beyond `small` are dropped: small is a density in t, and the
         ! tail past the first small term of a double-exponential decay
         ! integrates to less than that density.
         small = share * (rtol_eff * l1_int + atol_eff)
         truncation = 2 * small
         do side = 1, 2
            i = stride
            do while (i < cut(side))
               call add_node(integrand, a, b, r, complement(i), weight(i), side, g, total, &
                  & comp, res)
               if (res%status /= quadrature_success) return
               l1 = l1 + abs(g)
               if (i > last_large(side) .and. r * abs(g) <= small) exit
               i = i + 2 * stride
            end do
         end do
         previous = integral
         integral = r * h * (total + comp)
         l1_int = r * h * l1
         res%levels = int(level, ik)
         if (.not. ieee_is_finite(integral)) then
            call set_nonfinite(res)
            return
         end if

         delta = abs(integral - previous)
         if (level == 1) then
            ! one difference proves nothing: levels 0 and 1 can agree by
            ! coincidence (a peak between their nodes)
            delta_prev = delta
            cycle
         end if
         if (.not. l1_int > 0.0_wp) then
            ! the integrand vanished at every node
            estimate = 0.0_wp
         else if (converging(delta, delta_prev, l1_int)) then
            if (doubling) then
               estimate = delta * (delta / delta_prev)
            else
               estimate = delta * sqrt(delta / delta_prev)
            end if
         else if (delta_prev > 0.1_wp * l1_int) then
            ! the level before had not a single digit right: d_k may be small
            ! by coincidence
            estimate = max(delta, delta_prev)
         else
            estimate = delta
         end if
         estimate = max(estimate, 0.5_wp * epsilon(1.0_wp) * l1_int) + tail + truncation
         res%integral = integral
         res%error = estimate
         if (estimate <= rtol_eff * abs(integral) + atol_eff) then
            res%status = quadrature_success
            return
         end if
         delta_prev = delta
      end do
      res%status = quadrature_not_converged

   end subroutine integrate

   !> Whether successive levels converge (see `integrate`): d_k < d_(k-1) <= L/10,
   !> and no more than tripled digits unless d_k is at rounding level.
   pure function converging(delta, delta_prev, l1) result(yes)
      !> |I_k - I_(k-1)|, |I_(k-1) - I_(k-2)| and the integral of |f|, > 0
      real(wp), intent(in) :: delta, delta_prev, l1
      !> True when the last two differences show convergence
      logical :: yes

      yes = delta < delta_prev .and. delta_prev <= 0.1_wp * l1
      if (yes) yes = delta / l1 >= (delta_prev / l1)**3 &
         & .or. delta <= 100 * epsilon(1.0_wp) * l1
   end function converging

   !> Evaluate the integrand at one node, add w f to the compensated sum
   !> (Neumaier's variant of Kahan summation) and return w f.
   pure subroutine add_node(integrand, a, b, r, complement, weight, towards, term, &
         & total, comp, res)
      !> Integrand
      class(integrand_type), intent(in) :: integrand
      !> Ends of the interval and half its width
      real(wp), intent(in) :: a, b, r
      !> 1 - tanh u and the weight at the node, from the tables
      real(wp), intent(in) :: complement, weight
      !> toward_b or toward_a
      integer, intent(in) :: towards
      !> w f at the node (0 when f is not finite)
      real(wp), intent(out) :: term
      !> Running sum and its compensation
      real(wp), intent(inout) :: total, comp
      !> Evaluations counted here; status set on a non-finite value
      type(quadrature_result), intent(inout) :: res
      real(wp) :: near, far, fx, sum_new

      near = r * complement
      far = r * (2.0_wp - complement)
      if (towards == toward_b) then
         fx = integrand%eval(b - near, far, near)
      else
         fx = integrand%eval(a + near, near, far)
      end if
      res%evaluations = res%evaluations + 1_ik
      if (.not. ieee_is_finite(fx)) then
         call set_nonfinite(res)
         term = 0.0_wp
         return
      end if
      term = weight * fx
      sum_new = total + term
      if (abs(total) >= abs(term)) then
         comp = comp + ((total - sum_new) + term)
      else
         comp = comp + ((term - sum_new) + total)
      end if
      total = sum_new
   end subroutine add_node

   !> Record a non-finite integrand value or sum: no sensible integral exists.
   pure subroutine set_nonfinite(res)
      !> Result to mark
      type(quadrature_result), intent(inout) :: res
      res%status = quadrature_nonfinite
      res%integral = ieee_value(1.0_wp, ieee_quiet_nan)
      res%error = ieee_value(1.0_wp, ieee_positive_inf)
   end subroutine set_nonfinite

   !> Largest table index whose node distance r complement_i is a normal number
   !> (complement decreases with the index; bisection).
   pure function last_normal_node(r, complement) result(last)
      !> Half-width of the interval
      real(wp), intent(in) :: r
      !> Table of 1 - tanh u, decreasing
      real(wp), intent(in) :: complement(0:)
      !> Largest usable index
      integer :: last
      integer :: lo, hi, mid

      hi = ubound(complement, 1)
      if (r * complement(hi) >= tiny(1.0_wp)) then
         last = hi
         return
      end if
      lo = 0
      do while (hi - lo > 1)
         mid = (lo + hi) / 2
         if (r * complement(mid) >= tiny(1.0_wp)) then
            lo = mid
         else
            hi = mid
         end if
      end do
      last = lo
   end function last_normal_node

end module hcimpact_quadrature
