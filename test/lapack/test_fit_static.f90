! SPDX-License-Identifier: Apache-2.0
!> Tests of fit_static: F = c x^n from a static force-deflection curve generated from
!> the seed's ball (c = 1.7135e10 N/m^1.5, n = 3/2), with and without noise.
module test_fit_static
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_calibration, only : fit_type, fit_static
   use hcimpact_check, only : check_close
   use calibration_cases, only : seed_stiffness, seed_exponent, deflections, static_data
   use calibration_coverage, only : coverage_type, add_estimate, check_coverage
   implicit none
   private

   public :: collect_fit_static

   !> Seeds of the noisy tests: 1 ... seeds
   integer, parameter :: seeds = 200
   !> Relative noise of the forces
   real(wp), parameter :: sigma_f = 0.02_wp

contains

   !> Collect all exported unit tests
   subroutine collect_fit_static(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         new_unittest("noise-free", test_noise_free), &
         new_unittest("noisy-coverage", test_noisy), &
         new_unittest("weights", test_weights), &
         new_unittest("residuals", test_residuals) &
         ]
   end subroutine collect_fit_static

   !> Exact data: n to a few ulps, c to the rounding of ln c (|ln c| = 23.6).
   subroutine test_noise_free(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: x(10), f(10)
      type(fit_type) :: fit
      integer :: stat
      x = deflections(10)
      f = static_data(x, 0.0_wp, 0)
      call fit_static(x, f, fit, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call check_close(error, fit%parameters(1), seed_stiffness, rel=1.0e-13_wp, message="c")
      if (allocated(error)) return
      call check_close(error, fit%parameters(2), seed_exponent, abs=1.0e-14_wp, message="n")
      if (allocated(error)) return
      call check(error, fit%iterations, 0, "a linear fit takes no iterations")
   end subroutine test_noise_free

   !> 2 % noise: coverage of the reported intervals (seeds 1 ... 200; measured
   !> c: 65.0 % and 91.0 %, n: 64.5 % and 92.0 %).
   subroutine test_noisy(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: x(10), f(10)
      type(fit_type) :: fit
      type(coverage_type) :: cover_c, cover_n
      integer :: stat, seed
      x = deflections(10)
      do seed = 1, seeds
         f = static_data(x, sigma_f, seed)
         call fit_static(x, f, fit, stat)
         call check(error, stat, hcimpact_ok, "status")
         if (allocated(error)) return
         call add_estimate(cover_c, fit%parameters(1), fit%standard_errors(1), seed_stiffness)
         call add_estimate(cover_n, fit%parameters(2), fit%standard_errors(2), seed_exponent)
      end do
      call check_coverage(error, "fit_static c", cover_c, 0.55_wp, 0.80_wp, 0.86_wp)
      if (allocated(error)) return
      call check_coverage(error, "fit_static n", cover_n, 0.55_wp, 0.80_wp, 0.86_wp)
   end subroutine test_noisy

   !> Sigmas proportional to F are the default weighting: the same fit; with absolute
   !> sigmas the standard error of n is the textbook sigma_rel / sqrt(sum (ln x - mean)^2).
   !> Uneven sigmas move the fit towards the precise points.
   subroutine test_weights(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: x(10), f(10), lx(10)
      type(fit_type) :: plain, weighted
      integer :: stat
      x = deflections(10)
      f = static_data(x, sigma_f, 3)
      call fit_static(x, f, plain, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call fit_static(x, f, weighted, stat, sigma=sigma_f * f, absolute_sigma=.true.)
      call check(error, stat, hcimpact_ok, "status, sigma")
      if (allocated(error)) return
      call check_close(error, weighted%parameters(1), plain%parameters(1), rel=1.0e-13_wp, &
         & message="c, proportional sigma")
      if (allocated(error)) return
      call check_close(error, weighted%parameters(2), plain%parameters(2), rel=1.0e-14_wp, &
         & message="n, proportional sigma")
      if (allocated(error)) return
      lx = log(x)
      call check_close(error, weighted%standard_errors(2), &
         & sigma_f / sqrt(sum((lx - sum(lx) / 10)**2)), rel=1.0e-12_wp, &
         & message="standard error of n, absolute sigma")
      if (allocated(error)) return
      ! one point 1000 times more precise: the fitted curve passes (almost) through it
      f(4) = seed_stiffness * x(4)**seed_exponent * 1.05_wp
      call fit_static(x, f, weighted, stat, sigma=[sigma_f * f(1:3), 1.0e-3_wp * sigma_f * &
         & f(4), sigma_f * f(5:10)])
      call check(error, stat, hcimpact_ok, "status, uneven sigma")
      if (allocated(error)) return
      if (.not. abs(weighted%residuals(4)) < 1.0e-3_wp * maxval(abs(weighted%residuals))) &
         & call test_failed(error, "the precise point does not pull the fit")
   end subroutine test_weights

   !> Residuals are ln F - ln(c x^n); they sum to zero (the fit has an intercept).
   subroutine test_residuals(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: x(10), f(10)
      type(fit_type) :: fit
      integer :: stat, i
      x = deflections(10)
      f = static_data(x, sigma_f, 11)
      call fit_static(x, f, fit, stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      do i = 1, 10
         call check_close(error, fit%residuals(i), log(f(i)) - log(fit%parameters(1)) - &
            & fit%parameters(2) * log(x(i)), abs=1.0e-13_wp, message="residual")
         if (allocated(error)) return
      end do
      call check_close(error, sum(fit%residuals), 0.0_wp, abs=1.0e-14_wp, &
         & message="sum of the residuals")
      if (allocated(error)) return
      call check(error, fit%degrees_of_freedom, 8, "degrees of freedom")
   end subroutine test_residuals

end module test_fit_static
