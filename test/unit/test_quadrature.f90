! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_quadrature: tanh-sinh quadrature (issue #3).
!>
!> Reference integrals come from test/reference/make_quadrature.py (closed
!> forms at 50 digits, cross-checked with mpmath.quad); run it to see where
!> every constant below comes from. Parameters that the integrands hold as
!> doubles (0.9, 1e-3, ...) enter the references as the same doubles.
!>
!> Besides accuracy, the tests hold the integrator to its word: an estimate of
!> the error that is at least a tenth of the actual error, a status that says
!> when the tolerance was not met, an evaluation count that is positive and
!> bounded, and a status instead of a crash for every bad input.
module test_quadrature
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_is_nan
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_check, only : check_ulps, check_close, format_real
   use hcimpact_kinds, only : wp, ik
   use hcimpact_quadrature, only : integrand_type, quadrature_result, tanh_sinh, &
      & quadrature_status_message, quadrature_success, quadrature_not_converged, &
      & quadrature_nonfinite, quadrature_invalid_interval, quadrature_invalid_tolerance, &
      & quadrature_invalid_levels, tanh_sinh_max_levels, tanh_sinh_default_levels
   implicit none
   private

   public :: collect_quadrature

   ! References from test/reference/make_quadrature.py
   !> int_-1^2 (3x^7 - 2x^4 + x - 5) dx = 2757/40
   real(wp), parameter :: ref_poly7 = 68.925_wp
   !> int_0^1 exp(x) dx = e - 1
   real(wp), parameter :: ref_exp = 1.71828182845904523536_wp
   !> int_0^1 (1-x)^(-1/2) dx = 2
   real(wp), parameter :: ref_inv_sqrt = 2.0_wp
   !> int_0^1 sqrt(x) ln x dx = -4/9
   real(wp), parameter :: ref_sqrt_log = -4.444444444444444444444e-1_wp
   !> int_0^1 ln x ln(1-x) dx = 2 - pi^2/6
   real(wp), parameter :: ref_log_log = 3.550659331517735635276e-1_wp
   !> int_-1^1 (1-x^2)^(-1/2) dx = pi
   real(wp), parameter :: ref_chebyshev = 3.141592653589793238463_wp
   !> int_0^1 x^(-p) dx = 1/(1-p), p the double nearest 0.9
   real(wp), parameter :: ref_pow_m0p9 = 1.000000000000000222045e+1_wp
   !> int_0^1 x^(-p) dx = 1/(1-p), p the double nearest 0.99
   real(wp), parameter :: ref_pow_m0p99 = 9.999999999999991118216e+1_wp
   !> int_0^1 dx / (x + c) = ln((1+c)/c), c the double nearest 1e-3
   real(wp), parameter :: ref_near_pole = 6.908754779315220564425_wp
   !> int_0^1 dx / ((x - 0.3)^2 + 0.01^2), the doubles nearest 0.3 and 0.01
   real(wp), parameter :: ref_interior_peak = 3.093986915124149344467e+2_wp
   !> int_0^1 exp(-50 x^2) dx
   real(wp), parameter :: ref_gauss50 = 1.253314137315500251208e-1_wp
   !> int_0^1 sqrt(1 - x + c) dx, c the double nearest 1e-6
   real(wp), parameter :: ref_late_singularity = 6.666676660002499999583e-1_wp
   !> int_-1^1 (1 + 100 exp(-((x - 0.35)/0.02)^2)) dx
   real(wp), parameter :: ref_hidden_bump = 5.54490770181103212839_wp
   !> int_0^b (b-x)^(-1/2) dx = 2 sqrt(b), b the double nearest 1e-30
   real(wp), parameter :: ref_small_interval = 2.000000000000000083336e-15_wp
   !> int_0^b (b-x)^(-1/2) dx = 2 sqrt(b), b the double nearest 1e-300
   real(wp), parameter :: ref_tiny_interval = 2.000000000000000025059e-150_wp
   !> int_-B^B c dx = 2 B c, B and c the doubles nearest 1e300 and 1e-300
   real(wp), parameter :: ref_huge_interval = 2.000000000000000155128_wp

   !> Most integrand calls a smooth or endpoint-singular test may take at full
   !> precision (they need 55 to 121; a regression in efficiency fails here)
   integer(ik), parameter :: budget_smooth = 150_ik

   !> exp(-k x^2): an integrand whose parameter lives in the object
   type, extends(integrand_type) :: gaussian_integrand
      real(wp) :: k = 1.0_wp
   contains
      procedure :: eval => gaussian_eval
   end type gaussian_integrand

   !> x^(-p), singular at a = 0, written through the distance to a
   type, extends(integrand_type) :: power_integrand
      real(wp) :: p = 0.0_wp
   contains
      procedure :: eval => power_eval
   end type power_integrand

   !> 1/(x - a + c): a pole at distance c outside the interval, next to a
   type, extends(integrand_type) :: pole_integrand
      real(wp) :: c = 1.0_wp
   contains
      procedure :: eval => pole_eval
   end type pole_integrand

   !> The constant 1 where the node and its distances obey the documented
   !> convention, NaN where they do not (which the integrator reports)
   type, extends(integrand_type) :: convention_integrand
      real(wp) :: a = 0.0_wp
      real(wp) :: b = 1.0_wp
   contains
      procedure :: eval => convention_eval
   end type convention_integrand

   !> The constant c (for intervals at the edges of the double range)
   type, extends(integrand_type) :: constant_integrand
      real(wp) :: c = 1.0_wp
   contains
      procedure :: eval => constant_eval
   end type constant_integrand

contains

   !> Collect all exported unit tests
   subroutine collect_quadrature(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("polynomial", test_polynomial), &
         & new_unittest("exp", test_exp), &
         & new_unittest("exp-analytic", test_exp_analytic), &
         & new_unittest("inverse-sqrt-endpoint", test_inverse_sqrt), &
         & new_unittest("sqrt-log", test_sqrt_log), &
         & new_unittest("log-both-ends", test_log_log), &
         & new_unittest("chebyshev-weight", test_chebyshev), &
         & new_unittest("power-0.9", test_power_09), &
         & new_unittest("power-0.99-truncated", test_power_099), &
         & new_unittest("near-pole", test_near_pole), &
         & new_unittest("near-pole-few-levels", test_near_pole_few_levels), &
         & new_unittest("interior-peak", test_interior_peak), &
         & new_unittest("late-singularity", test_late_singularity), &
         & new_unittest("hidden-bump", test_hidden_bump), &
         & new_unittest("object-state", test_object_state), &
         & new_unittest("function-equals-object", test_function_equals_object), &
         & new_unittest("loose-tolerance", test_loose_tolerance), &
         & new_unittest("node-distances", test_node_distances), &
         & new_unittest("tiny-interval", test_tiny_interval), &
         & new_unittest("huge-interval", test_huge_interval), &
         & new_unittest("zero-integral", test_zero_integral), &
         & new_unittest("empty-interval", test_empty_interval), &
         & new_unittest("invalid-interval", test_invalid_interval), &
         & new_unittest("invalid-tolerance", test_invalid_tolerance), &
         & new_unittest("invalid-levels", test_invalid_levels), &
         & new_unittest("nan-integrand", test_nan_integrand), &
         & new_unittest("x-form-hits-endpoint", test_x_form_endpoint), &
         & new_unittest("evaluation-bound", test_evaluation_bound), &
         & new_unittest("pure-caller", test_pure_caller), &
         & new_unittest("status-messages", test_status_messages) &
         & ]
   end subroutine collect_quadrature

   ! ------------------------------------------------------------------------
   ! Integrands

   pure function gaussian_eval(self, x, dxa, dxb) result(fx)
      class(gaussian_integrand), intent(in) :: self
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = exp(-self%k * x * x)
   end function gaussian_eval

   pure function power_eval(self, x, dxa, dxb) result(fx)
      class(power_integrand), intent(in) :: self
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = dxa**(-self%p)
   end function power_eval

   pure function pole_eval(self, x, dxa, dxb) result(fx)
      class(pole_integrand), intent(in) :: self
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = 1.0_wp / (dxa + self%c)
   end function pole_eval

   pure function convention_eval(self, x, dxa, dxb) result(fx)
      class(convention_integrand), intent(in) :: self
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      real(wp) :: scale, width
      logical :: ok

      scale = max(abs(self%a), abs(self%b))
      width = self%b - self%a
      ! never on an end, and the distances are normal numbers
      ok = dxa >= tiny(1.0_wp) .and. dxb >= tiny(1.0_wp)
      ! inside the interval, and x agrees with either distance to rounding
      ok = ok .and. x >= self%a .and. x <= self%b
      ok = ok .and. abs((self%a + dxa) - x) <= 4 * spacing(scale)
      ok = ok .and. abs((self%b - dxb) - x) <= 4 * spacing(scale)
      ! the two distances add up to the width
      ok = ok .and. abs((dxa + dxb) - width) <= 4 * spacing(width)
      if (ok) then
         fx = 1.0_wp
      else
         fx = ieee_value(1.0_wp, ieee_quiet_nan)
      end if
   end function convention_eval

   pure function constant_eval(self, x, dxa, dxb) result(fx)
      class(constant_integrand), intent(in) :: self
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = self%c
   end function constant_eval

   pure function poly7(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = 3 * x**7 - 2 * x**4 + x - 5
   end function poly7

   pure function exp_x(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = exp(x)
   end function exp_x

   !> (1-x)^(-1/2) on [0, 1], through the distance to b
   pure function inv_sqrt_to_b(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = 1.0_wp / sqrt(dxb)
   end function inv_sqrt_to_b

   !> sqrt(x) ln x on [0, 1]
   pure function sqrt_log(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = sqrt(dxa) * log(dxa)
   end function sqrt_log

   !> ln x ln(1-x) on [0, 1]
   pure function log_log(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = log(dxa) * log(dxb)
   end function log_log

   !> (1-x^2)^(-1/2) = ((x+1)(1-x))^(-1/2) on [-1, 1]
   pure function chebyshev(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = 1.0_wp / sqrt(dxa * dxb)
   end function chebyshev

   !> A peak of height 1e4 and width 0.01 at 0.3 (poles at 0.3 +- 0.01 i)
   pure function interior_peak(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = 1.0_wp / ((x - 0.3_wp)**2 + 0.01_wp**2)
   end function interior_peak

   !> sqrt(1 - x + 1e-6): a branch point 1e-6 beyond b
   pure function sqrt_beyond_b(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = sqrt(dxb + 1.0e-6_wp)
   end function sqrt_beyond_b

   !> 1 plus a bump of height 100 and width 0.02 at 0.35, between the nodes
   !> of levels 0 and 1
   pure function hidden_bump(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = 1.0_wp + 100.0_wp * exp(-((x - 0.35_wp) / 0.02_wp)**2)
   end function hidden_bump

   !> x^3 on a symmetric interval: the integral is 0
   pure function odd_cubic(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = x**3
   end function odd_cubic

   !> NaN from x > 0.5 on
   pure function nan_right_half(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      if (x > 0.5_wp) then
         fx = ieee_value(1.0_wp, ieee_quiet_nan)
      else
         fx = 1.0_wp
      end if
   end function nan_right_half

   !> (1-x)^(-1/2) written through x: once a node rounds onto x = 1 it is
   !> infinite (1/sqrt(0); the division is spelled out so that the test also
   !> runs with division-by-zero traps)
   pure function inv_sqrt_in_x(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      if (x >= 1.0_wp) then
         fx = ieee_value(1.0_wp, ieee_positive_inf)
      else
         fx = 1.0_wp / sqrt(1.0_wp - x)
      end if
   end function inv_sqrt_in_x

   ! ------------------------------------------------------------------------
   ! Helpers

   !> Check a converged integral: status, accuracy in ulps, an honest error
   !> estimate (actual error at most ten times the estimate), and evaluations
   !> in 1 .. budget.
   subroutine check_integral(error, res, expected, max_ulps, budget, name)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result), intent(in) :: res
      real(wp), intent(in) :: expected, max_ulps
      integer(ik), intent(in) :: budget
      character(len=*), intent(in) :: name

      character(len=8) :: text

      call check(error, res%status, quadrature_success, name // ": status " // &
         & quadrature_status_message(res%status))
      if (allocated(error)) return
      call check_ulps(error, res%integral, expected, max_ulps, name // ": integral")
      if (allocated(error)) return
      call check_honest(error, res, expected, name)
      if (allocated(error)) return
      write(text, '(i0)') res%evaluations
      call check(error, res%evaluations > 0 .and. res%evaluations <= budget, &
         & name // ": evaluations " // trim(text) // " not in 1 .. budget")
      if (allocated(error)) return
      call check(error, res%levels >= 1 .and. res%levels <= tanh_sinh_default_levels, &
         & name // ": levels out of range")
   end subroutine check_integral

   !> |integral - expected| <= 10 * error estimate
   subroutine check_honest(error, res, expected, name)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result), intent(in) :: res
      real(wp), intent(in) :: expected
      character(len=*), intent(in) :: name

      if (ieee_is_nan(res%integral) .or. ieee_is_nan(res%error)) then
         call test_failed(error, name // ": NaN integral or error estimate")
         return
      end if
      if (abs(res%integral - expected) > 10 * res%error) then
         call test_failed(error, name // ": error estimate not honest", &
            & "actual error " // format_real(abs(res%integral - expected)) // &
            & " > 10 x estimate " // format_real(res%error))
      end if
   end subroutine check_honest

   ! ------------------------------------------------------------------------
   ! Accuracy at full precision (the default tolerance)

   subroutine test_polynomial(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(poly7, -1.0_wp, 2.0_wp, res)
      call check_integral(error, res, ref_poly7, 4.0_wp, budget_smooth, "3x^7-2x^4+x-5")
   end subroutine test_polynomial

   subroutine test_exp(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_exp, 4.0_wp, budget_smooth, "exp")
   end subroutine test_exp

   !> The analytic option: same accuracy on an entire integrand, with fewer evaluations
   !> (the level that only confirms convergence is saved)
   subroutine test_exp_analytic(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res, cautious
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, cautious)
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, analytic=.true.)
      call check_integral(error, res, ref_exp, 4.0_wp, budget_smooth, "exp, analytic")
      if (allocated(error)) return
      call check(error, res%evaluations < cautious%evaluations, &
         & "the analytic estimate must save evaluations on exp")
   end subroutine test_exp_analytic

   subroutine test_inverse_sqrt(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(inv_sqrt_to_b, 0.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_inv_sqrt, 4.0_wp, budget_smooth, "(1-x)^(-1/2)")
   end subroutine test_inverse_sqrt

   subroutine test_sqrt_log(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(sqrt_log, 0.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_sqrt_log, 4.0_wp, budget_smooth, "sqrt(x) ln x")
   end subroutine test_sqrt_log

   subroutine test_log_log(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(log_log, 0.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_log_log, 4.0_wp, budget_smooth, "ln x ln(1-x)")
   end subroutine test_log_log

   subroutine test_chebyshev(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(chebyshev, -1.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_chebyshev, 4.0_wp, budget_smooth, "(1-x^2)^(-1/2)")
   end subroutine test_chebyshev

   !> x^(-0.9): a tenth of the integral lies within 1e-10 of 0, where x
   !> itself could not tell the nodes apart, and a 3e-28 share below the
   !> smallest node distance (1.7e-275). Through dxa it converges like a
   !> smooth integrand.
   subroutine test_power_09(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(power_integrand(p=0.9_wp), 0.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_pow_m0p9, 4.0_wp, budget_smooth, "x^(-0.9)")
   end subroutine test_power_09

   !> x^(-0.99): the part of the integral below the smallest node distance
   !> (1.7e-275, where x^0.01 is still 2e-3) is out of reach. The integrator
   !> must say so: status not converged, with an estimate covering the
   !> error. With a tolerance looser than that part it converges.
   subroutine test_power_099(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res

      call tanh_sinh(power_integrand(p=0.99_wp), 0.0_wp, 1.0_wp, res, max_levels=5_ik)
      call check(error, res%status, quadrature_not_converged, &
         & "x^(-0.99) at full precision: status " // quadrature_status_message(res%status))
      if (allocated(error)) return
      call check(error, res%levels, 5_ik, "x^(-0.99): levels")
      if (allocated(error)) return
      call check_honest(error, res, ref_pow_m0p99, "x^(-0.99) at full precision")
      if (allocated(error)) return
      ! the error is really there: the tail is about 2e-3 of the integral
      call check(error, abs(res%integral - ref_pow_m0p99) > 1.0e-4_wp * ref_pow_m0p99, &
         & "x^(-0.99): the truncated tail should be visible")
      if (allocated(error)) return

      call tanh_sinh(power_integrand(p=0.99_wp), 0.0_wp, 1.0_wp, res, rtol=0.05_wp)
      call check(error, res%status, quadrature_success, "x^(-0.99) at rtol 0.05: status " // &
         & quadrature_status_message(res%status))
      if (allocated(error)) return
      call check_close(error, res%integral, ref_pow_m0p99, rel=0.05_wp, &
         & message="x^(-0.99) at rtol 0.05")
      if (allocated(error)) return
      call check_honest(error, res, ref_pow_m0p99, "x^(-0.99) at rtol 0.05")
   end subroutine test_power_099

   ! ------------------------------------------------------------------------
   ! Near singularities: accuracy or an honest status, at every tolerance

   !> 1/(x + 1e-3) on [0, 1]: a pole 1e-3 outside the interval, the kind of
   !> nearly real singularity the contact-time integrands have for large beta.
   subroutine test_near_pole(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      real(wp), parameter :: rtols(5) = [1.0e-3_wp, 1.0e-6_wp, 1.0e-10_wp, 1.0e-13_wp, 0.0_wp]
      real(wp) :: rtol, tol
      integer :: i
      character(len=:), allocatable :: name

      do i = 1, size(rtols)
         rtol = max(rtols(i), epsilon(1.0_wp))
         name = "1/(x+1e-3), rtol " // format_real(rtol)
         call tanh_sinh(pole_integrand(c=1.0e-3_wp), 0.0_wp, 1.0_wp, res, rtol=rtol)
         call check(error, res%status, quadrature_success, name // ": status " // &
            & quadrature_status_message(res%status))
         if (allocated(error)) return
         ! never more than 10x the tolerance off when claiming convergence
         tol = rtol * ref_near_pole
         if (abs(res%integral - ref_near_pole) > 10 * tol) then
            call test_failed(error, name // ": converged to a wrong answer", &
               & "error " // format_real(abs(res%integral - ref_near_pole)) // " > 10 x " // &
               & format_real(tol))
            return
         end if
         call check_honest(error, res, ref_near_pole, name)
         if (allocated(error)) return
      end do
      ! full precision costs five levels here (level 4 is already exact, level
      ! 5 confirms it)
      call check_ulps(error, res%integral, ref_near_pole, 4.0_wp, "1/(x+1e-3) at full precision")
      if (allocated(error)) return
      call check(error, res%evaluations <= 250_ik, "1/(x+1e-3): more than 250 evaluations")
   end subroutine test_near_pole

   !> The same pole with too few levels allowed: not converged, and the
   !> estimate still covers the error.
   subroutine test_near_pole_few_levels(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      integer(ik) :: levels

      do levels = 2_ik, 3_ik
         call tanh_sinh(pole_integrand(c=1.0e-3_wp), 0.0_wp, 1.0_wp, res, max_levels=levels)
         call check(error, res%status, quadrature_not_converged, &
            & "1/(x+1e-3) with few levels: status " // quadrature_status_message(res%status))
         if (allocated(error)) return
         call check(error, res%levels, levels, "1/(x+1e-3) with few levels: levels")
         if (allocated(error)) return
         call check_honest(error, res, ref_near_pole, "1/(x+1e-3) with few levels")
         if (allocated(error)) return
      end do
   end subroutine test_near_pole_few_levels

   !> A sharp interior peak (poles 0.01 off the real axis at x = 0.3): hard
   !> for tanh-sinh, which refines near the ends, not in the middle. Whatever
   !> the tolerance and level limit, the answer is within 10x the tolerance
   !> or the status says it is not converged, and the estimate is honest.
   !> (Levels 0 and 1 agree to 1% here while both are 92% off: a rule that
   !> trusted the first difference would converge to a wrong answer at rtol
   !> 1e-2.)
   subroutine test_interior_peak(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      real(wp), parameter :: rtols(5) = [1.0e-2_wp, 1.0e-4_wp, 1.0e-8_wp, 1.0e-12_wp, 0.0_wp]
      integer(ik), parameter :: levels(5) = [2_ik, 3_ik, 4_ik, 6_ik, 8_ik]
      real(wp) :: rtol
      integer :: i, j
      logical :: any_converged
      character(len=:), allocatable :: name

      any_converged = .false.
      do i = 1, size(rtols)
         rtol = max(rtols(i), epsilon(1.0_wp))
         do j = 1, size(levels)
            name = "interior peak, rtol " // format_real(rtol)
            call tanh_sinh(interior_peak, 0.0_wp, 1.0_wp, res, rtol=rtol, max_levels=levels(j))
            if (res%status == quadrature_success) then
               any_converged = .true.
               if (abs(res%integral - ref_interior_peak) > 10 * rtol * ref_interior_peak) then
                  call test_failed(error, name // ": converged to a wrong answer", &
                     & format_real(res%integral) // " against " // format_real(ref_interior_peak))
                  return
               end if
            else
               call check(error, res%status, quadrature_not_converged, name // ": status " // &
                  & quadrature_status_message(res%status))
               if (allocated(error)) return
            end if
            call check_honest(error, res, ref_interior_peak, name)
            if (allocated(error)) return
         end do
      end do
      call check(error, any_converged, "interior peak: never converged")
   end subroutine test_interior_peak

   !> sqrt(1 - x + 1e-6): the branch point 1e-6 beyond b governs the
   !> convergence only from level 3 on; before, the levels converge fast and
   !> look asymptotic. An estimate that assumes the digits double from there
   !> (Bailey's, power 1 in `integrate`) converges at level 3 with an error of
   !> about 80 ulp; the estimate used here takes two more levels and is right.
   subroutine test_late_singularity(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(sqrt_beyond_b, 0.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_late_singularity, 4.0_wp, 250_ik, "sqrt(1-x+1e-6)")
   end subroutine test_late_singularity

   !> A bump that the nodes of levels 0 and 1 miss: those two levels agree to
   !> 2% while both are 64% off. The first difference is therefore
   !> never trusted; at a loose tolerance the answer is right or not claimed.
   subroutine test_hidden_bump(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      real(wp), parameter :: rtols(3) = [1.0e-1_wp, 3.0e-2_wp, 1.0e-2_wp]
      integer :: i

      do i = 1, size(rtols)
         call tanh_sinh(hidden_bump, -1.0_wp, 1.0_wp, res, rtol=rtols(i))
         if (res%status == quadrature_success) then
            call check_close(error, res%integral, ref_hidden_bump, rel=10 * rtols(i), &
               & message="hidden bump, rtol " // format_real(rtols(i)) // &
               & ": converged to a wrong answer")
            if (allocated(error)) return
         end if
         call check_honest(error, res, ref_hidden_bump, "hidden bump")
         if (allocated(error)) return
      end do
      ! at full precision it converges too, if slowly (an interior peak of
      ! width 0.02: 1747 evaluations, level 8)
      call tanh_sinh(hidden_bump, -1.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_hidden_bump, 4.0_wp, &
         & 12_ik * 2_ik**tanh_sinh_default_levels + 1_ik, "hidden bump")
   end subroutine test_hidden_bump

   ! ------------------------------------------------------------------------
   ! Interfaces and tolerances

   !> exp(-50 x^2): the parameter lives in the integrand object
   subroutine test_object_state(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      ! narrower than the others (width 0.14 on [0, 1]): one level more
      call tanh_sinh(gaussian_integrand(k=50.0_wp), 0.0_wp, 1.0_wp, res)
      call check_integral(error, res, ref_gauss50, 4.0_wp, 2 * budget_smooth, "exp(-50 x^2)")
   end subroutine test_object_state

   !> A plain function and an object holding the same integrand give the same
   !> bits, evaluations and levels.
   subroutine test_function_equals_object(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: by_function, by_object

      call tanh_sinh(pole_integrand(c=1.0_wp), 0.0_wp, 1.0_wp, by_object)
      call tanh_sinh(one_over_one_plus_x, 0.0_wp, 1.0_wp, by_function)
      call check(error, transfer(by_function%integral, 0_int64), &
         & transfer(by_object%integral, 0_int64), "function and object: integrals differ")
      if (allocated(error)) return
      call check(error, by_function%evaluations, by_object%evaluations, &
         & "function and object: evaluations differ")
      if (allocated(error)) return
      call check(error, by_function%levels, by_object%levels, "function and object: levels differ")
      if (allocated(error)) return
      call check_ulps(error, by_object%integral, log(2.0_wp), 4.0_wp, "int_0^1 dx/(1+x)")
   end subroutine test_function_equals_object

   !> 1/(1 + x) through the distance to 0, as pole_integrand(c=1) computes it
   pure function one_over_one_plus_x(x, dxa, dxb) result(fx)
      real(wp), intent(in) :: x, dxa, dxb
      real(wp) :: fx
      fx = 1.0_wp / (dxa + 1.0_wp)
   end function one_over_one_plus_x

   !> A loose tolerance is met with fewer evaluations than full precision,
   !> and an absolute tolerance is honoured.
   subroutine test_loose_tolerance(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: loose, full, absolute

      call tanh_sinh(log_log, 0.0_wp, 1.0_wp, full)
      call tanh_sinh(log_log, 0.0_wp, 1.0_wp, loose, rtol=1.0e-6_wp)
      call check(error, loose%status, quadrature_success, "rtol 1e-6: status")
      if (allocated(error)) return
      call check_close(error, loose%integral, ref_log_log, rel=1.0e-6_wp, message="rtol 1e-6")
      if (allocated(error)) return
      call check(error, loose%evaluations < full%evaluations, &
         & "rtol 1e-6 should cost fewer evaluations than full precision")
      if (allocated(error)) return
      call check(error, loose%error <= 1.0e-6_wp * abs(loose%integral), &
         & "rtol 1e-6: estimate above the tolerance with status success")
      if (allocated(error)) return

      call tanh_sinh(log_log, 0.0_wp, 1.0_wp, absolute, rtol=1.0e-300_wp, atol=1.0e-9_wp)
      call check(error, absolute%status, quadrature_success, "atol 1e-9: status")
      if (allocated(error)) return
      call check_close(error, absolute%integral, ref_log_log, abs=1.0e-9_wp, message="atol 1e-9")
   end subroutine test_loose_tolerance

   !> Every node lies strictly inside, its distances are normal numbers that
   !> agree with x, on a wide interval, a narrow one far from 0, and one whose
   !> ends are negative.
   subroutine test_node_distances(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      real(wp) :: a(3), b(3)
      integer :: i

      a = [-3.0_wp, 1.0_wp, -1.0e10_wp]
      b = [7.0_wp, 1.0_wp + 2.0_wp**(-20), -1.0e10_wp + 1.0e-3_wp]
      do i = 1, size(a)
         call tanh_sinh(convention_integrand(a=a(i), b=b(i)), a(i), b(i), res)
         call check(error, res%status, quadrature_success, "node convention on [" // &
            & format_real(a(i)) // ", " // format_real(b(i)) // "]: " // &
            & quadrature_status_message(res%status))
         if (allocated(error)) return
         call check_ulps(error, res%integral, b(i) - a(i), 4.0_wp, "int of 1 = b - a")
         if (allocated(error)) return
      end do
   end subroutine test_node_distances

   !> Narrow intervals. On [0, 1e-30] the node distances, down to 1.7e-275
   !> times the half-width, are all normal numbers: full precision. On
   !> [0, 1e-300] only the nodes up to |t| = 1.9 are (the others would be
   !> subnormal or 0), so the tail of an endpoint singularity is out of reach;
   !> the status and the error estimate must say so.
   subroutine test_tiny_interval(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res

      call tanh_sinh(inv_sqrt_to_b, 0.0_wp, 1.0e-30_wp, res)
      call check_integral(error, res, ref_small_interval, 4.0_wp, budget_smooth, &
         & "(b-x)^(-1/2) on [0, 1e-30]")
      if (allocated(error)) return

      call tanh_sinh(inv_sqrt_to_b, 0.0_wp, 1.0e-300_wp, res)
      call check(error, res%status, quadrature_not_converged, &
         & "(b-x)^(-1/2) on [0, 1e-300]: status " // quadrature_status_message(res%status))
      if (allocated(error)) return
      call check_honest(error, res, ref_tiny_interval, "(b-x)^(-1/2) on [0, 1e-300]")
      if (allocated(error)) return
      call check_close(error, res%integral, ref_tiny_interval, rel=1.0e-2_wp, &
         & message="(b-x)^(-1/2) on [0, 1e-300]")
   end subroutine test_tiny_interval

   !> [-1e300, 1e300] and [-huge/2, huge/2]: nothing overflows on the way to
   !> the half-width; [-huge, huge] has no finite width and is refused
   subroutine test_huge_interval(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      call tanh_sinh(constant_integrand(c=1.0e-300_wp), -1.0e300_wp, 1.0e300_wp, res)
      call check_integral(error, res, ref_huge_interval, 4.0_wp, budget_smooth, &
         & "1e-300 on [-1e300, 1e300]")
      if (allocated(error)) return
      ! the widest interval whose width is finite
      call tanh_sinh(constant_integrand(c=1.0e-300_wp), -0.5_wp * huge(1.0_wp), &
         & 0.5_wp * huge(1.0_wp), res)
      call check(error, res%status, quadrature_success, "[-huge/2, huge/2]: status " // &
         & quadrature_status_message(res%status))
      if (allocated(error)) return
      call check_ulps(error, res%integral, huge(1.0_wp) * 1.0e-300_wp, 4.0_wp, &
         & "1e-300 on [-huge/2, huge/2]")
      if (allocated(error)) return
      ! finite ends, but b - a overflows: refused (the distances would too)
      call tanh_sinh(constant_integrand(c=1.0e-300_wp), -huge(1.0_wp), huge(1.0_wp), res)
      call check(error, res%status, quadrature_invalid_interval, "[-huge, huge]: status " // &
         & quadrature_status_message(res%status))
   end subroutine test_huge_interval

   !> A vanishing integral cannot meet a relative tolerance: with rtol alone
   !> the status says so; an absolute tolerance makes it converge. An
   !> integrand that vanishes at every node converges at once, to 0.
   subroutine test_zero_integral(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res

      call tanh_sinh(constant_integrand(c=0.0_wp), -1.0_wp, 1.0_wp, res)
      call check(error, res%status, quadrature_success, "0 on [-1,1]: status")
      if (allocated(error)) return
      call check_close(error, res%integral, 0.0_wp, message="0 on [-1,1]")
      if (allocated(error)) return

      call tanh_sinh(odd_cubic, -1.0_wp, 1.0_wp, res, max_levels=4_ik)
      call check(error, res%status, quadrature_not_converged, "x^3 on [-1,1], rtol only: status")
      if (allocated(error)) return
      call check_close(error, res%integral, 0.0_wp, abs=1.0e-15_wp, message="x^3 on [-1,1]")
      if (allocated(error)) return
      call tanh_sinh(odd_cubic, -1.0_wp, 1.0_wp, res, atol=1.0e-15_wp)
      call check(error, res%status, quadrature_success, "x^3 on [-1,1], atol: status")
      if (allocated(error)) return
      call check_close(error, res%integral, 0.0_wp, abs=1.0e-15_wp, message="x^3 on [-1,1], atol")
   end subroutine test_zero_integral

   ! ------------------------------------------------------------------------
   ! Bad input: a status, never a crash

   !> a = b: 0 with status success and no evaluation
   subroutine test_empty_interval(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res

      call tanh_sinh(inv_sqrt_to_b, 0.25_wp, 0.25_wp, res)
      call check(error, res%status, quadrature_success, "a = b: status")
      if (allocated(error)) return
      call check_close(error, res%integral, 0.0_wp, message="a = b: integral")
      if (allocated(error)) return
      call check_close(error, res%error, 0.0_wp, message="a = b: error estimate")
      if (allocated(error)) return
      call check(error, res%evaluations, 0_ik, "a = b: evaluations")
   end subroutine test_empty_interval

   subroutine test_invalid_interval(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      real(wp) :: nan, inf

      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      inf = ieee_value(1.0_wp, ieee_positive_inf)

      call tanh_sinh(exp_x, nan, 1.0_wp, res)
      call check(error, res%status, quadrature_invalid_interval, "a = NaN")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, nan, res)
      call check(error, res%status, quadrature_invalid_interval, "b = NaN")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, inf, res)
      call check(error, res%status, quadrature_invalid_interval, "b = +Inf")
      if (allocated(error)) return
      call tanh_sinh(exp_x, -inf, 0.0_wp, res)
      call check(error, res%status, quadrature_invalid_interval, "a = -Inf")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 1.0_wp, 0.0_wp, res)
      call check(error, res%status, quadrature_invalid_interval, "a > b")
      if (allocated(error)) return
      call check(error, res%evaluations, 0_ik, "a > b: evaluations")
   end subroutine test_invalid_interval

   subroutine test_invalid_tolerance(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      real(wp) :: nan

      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, rtol=0.0_wp)
      call check(error, res%status, quadrature_invalid_tolerance, "rtol = 0")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, rtol=-1.0e-8_wp)
      call check(error, res%status, quadrature_invalid_tolerance, "rtol < 0")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, rtol=nan)
      call check(error, res%status, quadrature_invalid_tolerance, "rtol = NaN")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, atol=-1.0_wp)
      call check(error, res%status, quadrature_invalid_tolerance, "atol < 0")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, atol=nan)
      call check(error, res%status, quadrature_invalid_tolerance, "atol = NaN")
      if (allocated(error)) return
      call check(error, res%evaluations, 0_ik, "bad tolerance: evaluations")
      if (allocated(error)) return
      ! a positive rtol below epsilon is allowed and acts as epsilon
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, rtol=1.0e-300_wp)
      call check_integral(error, res, ref_exp, 4.0_wp, budget_smooth, "exp, rtol 1e-300")
   end subroutine test_invalid_tolerance

   subroutine test_invalid_levels(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res

      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, max_levels=0_ik)
      call check(error, res%status, quadrature_invalid_levels, "max_levels = 0")
      if (allocated(error)) return
      ! one level gives one difference, not enough to judge convergence
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, max_levels=1_ik)
      call check(error, res%status, quadrature_invalid_levels, "max_levels = 1")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, max_levels=tanh_sinh_max_levels + 1_ik)
      call check(error, res%status, quadrature_invalid_levels, "max_levels too large")
      if (allocated(error)) return
      call tanh_sinh(exp_x, 0.0_wp, 1.0_wp, res, max_levels=tanh_sinh_max_levels)
      call check(error, res%status, quadrature_success, "max_levels = tanh_sinh_max_levels")
   end subroutine test_invalid_levels

   !> NaN from the integrand: status, NaN integral, evaluations counted up to
   !> the offending node
   subroutine test_nan_integrand(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res

      call tanh_sinh(nan_right_half, 0.0_wp, 1.0_wp, res)
      call check(error, res%status, quadrature_nonfinite, "NaN integrand: status " // &
         & quadrature_status_message(res%status))
      if (allocated(error)) return
      call check(error, ieee_is_nan(res%integral), "NaN integrand: integral should be NaN")
      if (allocated(error)) return
      call check(error, res%evaluations >= 1_ik, "NaN integrand: evaluations")
   end subroutine test_nan_integrand

   !> An endpoint singularity written in x: the nodes near b round onto b and
   !> the integrand is infinite there; the integrator reports it (the cure is
   !> to write the integrand through dxb, as in test_inverse_sqrt).
   subroutine test_x_form_endpoint(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res

      call tanh_sinh(inv_sqrt_in_x, 0.0_wp, 1.0_wp, res)
      call check(error, res%status, quadrature_nonfinite, "(1-x)^(-1/2) in x: status " // &
         & quadrature_status_message(res%status))
   end subroutine test_x_form_endpoint

   !> The evaluation count never exceeds the nodes of the levels allowed,
   !> 2 * 6 * 2**max_levels + 1 (t runs over [-6, 6]), even when the
   !> tolerance cannot be met; levels never exceed max_levels.
   subroutine test_evaluation_bound(error)
      type(error_type), allocatable, intent(out) :: error
      type(quadrature_result) :: res
      integer(ik) :: levels

      do levels = 2_ik, tanh_sinh_max_levels
         call tanh_sinh(power_integrand(p=0.99_wp), 0.0_wp, 1.0_wp, res, max_levels=levels)
         call check(error, res%evaluations > 0 .and. &
            & res%evaluations <= 12_ik * 2_ik**levels + 1_ik, "evaluation count out of bounds")
         if (allocated(error)) return
         call check(error, res%levels, levels, "x^(-0.99) runs to max_levels")
         if (allocated(error)) return
         call tanh_sinh(interior_peak, 0.0_wp, 1.0_wp, res, max_levels=levels)
         call check(error, res%evaluations > 0 .and. &
            & res%evaluations <= 12_ik * 2_ik**levels + 1_ik, "evaluation count out of bounds")
         if (allocated(error)) return
         call check(error, res%levels >= 1 .and. res%levels <= levels, "levels out of bounds")
         if (allocated(error)) return
      end do
   end subroutine test_evaluation_bound

   !> The integrator can be called from pure and elemental code (this test
   !> compiles only if it is pure): int_0^1 x^(-p) dx = 1/(1-p) for several p.
   subroutine test_pure_caller(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: p(4) = [-2.0_wp, -0.5_wp, 0.25_wp, 0.75_wp]
      real(wp) :: values(4)
      integer :: i

      values = power_integral(p)
      do i = 1, size(p)
         call check_ulps(error, values(i), 1.0_wp / (1.0_wp - p(i)), 4.0_wp, &
            & "int_0^1 x^(-p), p = " // format_real(p(i)))
         if (allocated(error)) return
      end do
   end subroutine test_pure_caller

   elemental function power_integral(p) result(integral)
      real(wp), intent(in) :: p
      real(wp) :: integral
      type(quadrature_result) :: res
      call tanh_sinh(power_integrand(p=p), 0.0_wp, 1.0_wp, res)
      integral = res%integral
   end function power_integral

   subroutine test_status_messages(error)
      type(error_type), allocatable, intent(out) :: error
      integer(ik) :: status
      character(len=:), allocatable :: first, other

      do status = quadrature_success, quadrature_invalid_levels
         first = quadrature_status_message(status)
         call check(error, len(first) > 0 .and. first /= "unknown status", "status message missing")
         if (allocated(error)) return
         other = quadrature_status_message(status + 1_ik)
         call check(error, first /= other, "two statuses share a message")
         if (allocated(error)) return
      end do
      call check(error, quadrature_status_message(-1_ik), "unknown status")
   end subroutine test_status_messages

end module test_quadrature
