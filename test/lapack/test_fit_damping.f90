! SPDX-License-Identifier: Apache-2.0
!> Tests of fit_damping (the exact law e = k(b V)) and fit_damping_linear (e = 1 - alpha V)
!> on restitution data generated from the model, with and without noise.
module test_fit_damping
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_restitution_law, only : restitution, restitution_derivative
   use hcimpact_calibration, only : fit_type, fit_damping, fit_damping_linear
   use hcimpact_check, only : check_close
   use calibration_cases, only : seed_damping, speeds, restitution_data
   use calibration_coverage, only : coverage_type, add_estimate, check_coverage
   implicit none
   private

   public :: collect_fit_damping

   !> Seeds of the noisy tests: 1 ... seeds
   integer, parameter :: seeds = 200
   !> Noise of the restitution (absolute)
   real(wp), parameter :: sigma_e = 0.01_wp

contains

   !> Collect all exported unit tests
   subroutine collect_fit_damping(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         new_unittest("noise-free", test_noise_free), &
         new_unittest("elastic-data", test_elastic), &
         new_unittest("one-speed", test_one_speed), &
         new_unittest("noisy-coverage", test_noisy), &
         new_unittest("absolute-sigma", test_absolute_sigma), &
         new_unittest("residuals", test_residuals), &
         new_unittest("linear-law-exact-data", test_linear_law_bias), &
         new_unittest("linear-law-linear-data", test_linear_law_own_data) &
         ]
   end subroutine collect_fit_damping

   !> Exact data give b back to the precision of the data: rounding e_i to a double
   !> moves the least-squares b by up to sum |V_i k'_i| ulp(e_i) / sum (V_i k'_i)^2
   !> (about 1e-16 b for beta near 1, but 1e-13 b at beta = 1e-4 where 1 - e is
   !> tiny). Checked over beta from 5e-5 to 50, within 4 times that plus 4 ulps.
   subroutine test_noise_free(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: dampings(*) = [1.0e-4_wp, 0.1_wp, 1.0_wp, 10.0_wp]
      real(wp) :: v(10), e(10), slope(10), bound
      type(fit_type) :: fit
      integer :: stat, i
      v = speeds(10, 0.5_wp, 5.0_wp)
      do i = 1, size(dampings)
         e = restitution_data(dampings(i), v, 0.0_wp, 0)
         call fit_damping(v, e, fit, stat)
         call check(error, stat, hcimpact_ok, "fit_damping status")
         if (allocated(error)) return
         slope = v * restitution_derivative(dampings(i) * v)
         bound = sum(abs(slope) * spacing(e)) / sum(slope**2)
         call check_close(error, fit%parameters(1), dampings(i), &
            & abs=4 * bound + 4 * epsilon(1.0_wp) * dampings(i), message="b from exact data")
         if (allocated(error)) return
         if (.not. fit%standard_errors(1) <= 1.0e-13_wp * dampings(i)) then
            call test_failed(error, "standard error of exact data not ~0")
            return
         end if
      end do
   end subroutine test_noise_free

   !> e = 1 at every speed: b = 0 exactly (the bound), without an error.
   subroutine test_elastic(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v(5)
      type(fit_type) :: fit
      integer :: stat
      v = speeds(5, 1.0_wp, 3.0_wp)
      call fit_damping(v, [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], fit, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call check_close(error, fit%parameters(1), 0.0_wp, message="b")
      if (allocated(error)) return
      ! e slightly above 1 (noise): still b = 0
      call fit_damping(v, [1.001_wp, 0.999_wp, 1.002_wp, 1.0_wp, 1.001_wp], fit, stat)
      call check(error, stat, hcimpact_ok, "status, e > 1")
      if (allocated(error)) return
      call check_close(error, fit%parameters(1), 0.0_wp, message="b, e > 1")
   end subroutine test_elastic

   !> Repeated drops at one speed determine b (one parameter).
   subroutine test_one_speed(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v(4), e(4)
      type(fit_type) :: fit
      integer :: stat
      v = 2.0_wp
      e = restitution(0.3_wp * v) + [0.01_wp, -0.01_wp, 0.005_wp, -0.005_wp]
      call fit_damping(v, e, fit, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      ! the mean e is k(0.6): b = 0.3 to the curvature of k over +-0.01
      call check_close(error, fit%parameters(1), 0.3_wp, rel=1.0e-3_wp, message="b")
   end subroutine test_one_speed

   !> Noisy data: the reported 1 and 2 sigma intervals hold the truth about as often as
   !> they should (seeds 1 ... 200; measured 64.0 % and 93.0 %).
   subroutine test_noisy(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v(10), e(10)
      type(fit_type) :: fit
      type(coverage_type) :: coverage
      integer :: stat, seed
      v = speeds(10, 0.5_wp, 5.0_wp)
      do seed = 1, seeds
         e = restitution_data(seed_damping, v, sigma_e, seed)
         call fit_damping(v, e, fit, stat)
         call check(error, stat, hcimpact_ok, "fit_damping status")
         if (allocated(error)) return
         call add_estimate(coverage, fit%parameters(1), fit%standard_errors(1), seed_damping)
      end do
      call check_coverage(error, "fit_damping b", coverage, 0.55_wp, 0.80_wp, 0.88_wp)
   end subroutine test_noisy

   !> Known sigmas: the standard error is the textbook one at the fitted b,
   !> (sum (V k'(b V)/sigma)^2)^(-1/2), and it covers the truth.
   subroutine test_absolute_sigma(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v(10), e(10), sigma(10), expected
      type(fit_type) :: fit
      type(coverage_type) :: coverage
      integer :: stat, seed
      v = speeds(10, 0.5_wp, 5.0_wp)
      sigma = sigma_e
      do seed = 1, seeds
         e = restitution_data(seed_damping, v, sigma_e, seed)
         call fit_damping(v, e, fit, stat, sigma=sigma, absolute_sigma=.true.)
         call check(error, stat, hcimpact_ok, "fit_damping status")
         if (allocated(error)) return
         expected = 1.0_wp / sqrt(sum((v * restitution_derivative(fit%parameters(1) * v) &
            & / sigma)**2))
         call check_close(error, fit%standard_errors(1), expected, rel=1.0e-6_wp, &
            & message="standard error with absolute sigma")
         if (allocated(error)) return
         call add_estimate(coverage, fit%parameters(1), fit%standard_errors(1), seed_damping)
      end do
      call check_coverage(error, "fit_damping b, absolute sigma", coverage, 0.58_wp, &
         & 0.80_wp, 0.90_wp)
   end subroutine test_absolute_sigma

   !> The residuals are e - k(b V) at the fitted b, and chi^2 their sum of squares.
   subroutine test_residuals(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v(10), e(10), jac(10)
      type(fit_type) :: fit
      integer :: stat, i
      v = speeds(10, 0.5_wp, 5.0_wp)
      e = restitution_data(seed_damping, v, sigma_e, 7)
      call fit_damping(v, e, fit, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call check(error, size(fit%residuals), 10, "number of residuals")
      if (allocated(error)) return
      do i = 1, 10
         call check_close(error, fit%residuals(i), e(i) - restitution(fit%parameters(1) * v(i)), &
            & abs=1.0e-15_wp, message="residual")
         if (allocated(error)) return
      end do
      call check(error, fit%degrees_of_freedom, 9, "degrees of freedom")
      if (allocated(error)) return
      ! at the minimum the residuals are orthogonal to the Jacobian column
      jac = v * restitution_derivative(fit%parameters(1) * v)
      if (.not. abs(sum(fit%residuals * jac)) <= 1.0e-9_wp * norm2(fit%residuals) &
         & * norm2(jac)) call test_failed(error, "gradient not zero at the fit")
   end subroutine test_residuals

   !> On exact-law data the linear law's b is biased low: by 20.2 % for the seed's ball
   !> (b = 0.1 s/m, V = 0.5 ... 5 m/s; independent value from mpmath:
   !> b_linear = 0.07982680592763838 s/m).
   subroutine test_linear_law_bias(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v(10), e(10)
      type(fit_type) :: fit
      integer :: stat
      v = speeds(10, 0.5_wp, 5.0_wp)
      e = restitution_data(seed_damping, v, 0.0_wp, 0)
      call fit_damping_linear(v, e, fit, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call check_close(error, fit%parameters(1), 0.07982680592763838_wp, rel=1.0e-13_wp, &
         & message="b of the linear law")
   end subroutine test_linear_law_bias

   !> Data on the linear law itself give its alpha back: b = 3 alpha/2.
   subroutine test_linear_law_own_data(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v(6)
      type(fit_type) :: fit
      integer :: stat
      v = speeds(6, 0.5_wp, 3.0_wp)
      call fit_damping_linear(v, 1.0_wp - 0.08_wp * v, fit, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call check_close(error, fit%parameters(1), 0.12_wp, rel=1.0e-14_wp, message="b")
   end subroutine test_linear_law_own_data

end module test_fit_damping
