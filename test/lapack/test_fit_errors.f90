! SPDX-License-Identifier: Apache-2.0
!> Degenerate and invalid data give a status, never a wrong answer: too few points,
!> data that cannot separate the parameters (one speed, one deflection), non-positive
!> or non-finite values, arrays of different sizes.
module test_fit_errors
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_velocity, hcimpact_err_damping, hcimpact_err_restitution, &
      & hcimpact_err_domain, hcimpact_err_size, hcimpact_err_underdetermined, &
      & status_message
   use hcimpact_calibration, only : fit_type, fit_damping, fit_damping_linear, &
      & fit_static, fit_elastic, fit_impact
   use calibration_cases, only : seed_mass, seed_damping, speeds, deflections, &
      & static_data, impact_data
   implicit none
   private

   public :: collect_fit_errors

contains

   !> Collect all exported unit tests
   subroutine collect_fit_errors(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         new_unittest("damping", test_damping), &
         new_unittest("static", test_static), &
         new_unittest("elastic", test_elastic), &
         new_unittest("impact", test_impact), &
         new_unittest("status-message", test_message) &
         ]
   end subroutine collect_fit_errors

   !> The status and an empty result.
   subroutine expect(error, stat, expected, fit, what)
      type(error_type), allocatable, intent(out) :: error
      integer, intent(in) :: stat, expected
      type(fit_type), intent(in) :: fit
      character(len=*), intent(in) :: what
      call check(error, stat, expected, what)
      if (allocated(error)) return
      if (allocated(fit%parameters)) call test_failed(error, what // ": parameters returned")
   end subroutine expect

   subroutine test_damping(error)
      type(error_type), allocatable, intent(out) :: error
      type(fit_type) :: fit
      integer :: stat
      real(wp) :: nan
      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      call fit_damping([1.0_wp], [0.9_wp], fit, stat)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "one point")
      if (allocated(error)) return
      call fit_damping([real(wp) ::], [real(wp) ::], fit, stat)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "no point")
      if (allocated(error)) return
      call fit_damping([1.0_wp, 2.0_wp], [0.9_wp], fit, stat)
      call expect(error, stat, hcimpact_err_size, fit, "sizes")
      if (allocated(error)) return
      call fit_damping([1.0_wp, 2.0_wp], [0.9_wp, 0.8_wp], fit, stat, sigma=[0.01_wp])
      call expect(error, stat, hcimpact_err_size, fit, "sigma size")
      if (allocated(error)) return
      call fit_damping([1.0_wp, 0.0_wp], [0.9_wp, 0.8_wp], fit, stat)
      call expect(error, stat, hcimpact_err_velocity, fit, "zero speed")
      if (allocated(error)) return
      call fit_damping([1.0_wp, 2.0_wp], [0.9_wp, -0.1_wp], fit, stat)
      call expect(error, stat, hcimpact_err_restitution, fit, "negative e")
      if (allocated(error)) return
      call fit_damping([1.0_wp, 2.0_wp], [0.9_wp, nan], fit, stat)
      call expect(error, stat, hcimpact_err_not_finite, fit, "NaN e")
      if (allocated(error)) return
      call fit_damping([1.0_wp, 2.0_wp], [0.9_wp, 0.8_wp], fit, stat, sigma=[0.01_wp, 0.0_wp])
      call expect(error, stat, hcimpact_err_domain, fit, "zero sigma")
      if (allocated(error)) return
      ! sizes that would overflow the sums of squares: no restitution, absurd sigmas
      call fit_damping([1.0_wp, 2.0_wp], [0.9_wp, 2.5_wp], fit, stat)
      call expect(error, stat, hcimpact_err_restitution, fit, "e > 2")
      if (allocated(error)) return
      call fit_damping([1.0_wp, 2.0_wp], [0.9_wp, 0.8_wp], fit, stat, &
         & sigma=[0.01_wp, 1.0e-200_wp])
      call expect(error, stat, hcimpact_err_domain, fit, "sigma 1e-200")
      if (allocated(error)) return
      call fit_static([1.0_wp, 2.0_wp, 3.0_wp], [1.0e-300_wp, 2.0_wp, 3.0_wp], fit, stat, &
         & sigma=[1.0_wp, 1.0_wp, 1.0_wp])
      call expect(error, stat, hcimpact_err_domain, fit, "sigma 1e300 times the force")
      if (allocated(error)) return
      call fit_damping_linear([1.0_wp], [0.9_wp], fit, stat)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "linear, one point")
      if (allocated(error)) return
      call fit_damping_linear([-1.0_wp, 1.0_wp], [0.9_wp, 0.9_wp], fit, stat)
      call expect(error, stat, hcimpact_err_velocity, fit, "linear, negative speed")
   end subroutine test_damping

   subroutine test_static(error)
      type(error_type), allocatable, intent(out) :: error
      type(fit_type) :: fit
      real(wp) :: x(6), f(6)
      integer :: stat
      x = 3.0e-5_wp
      f = static_data(x, 0.02_wp, 1)
      call fit_static(x, f, fit, stat)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "one deflection")
      if (allocated(error)) return
      x = deflections(6)
      f = static_data(x, 0.0_wp, 0)
      call fit_static(x(1:2), f(1:2), fit, stat)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "two points")
      if (allocated(error)) return
      call fit_static([0.0_wp, x(2:)], f, fit, stat)
      call expect(error, stat, hcimpact_err_domain, fit, "zero deflection")
      if (allocated(error)) return
      call fit_static(x, [f(1:5), -1.0_wp], fit, stat)
      call expect(error, stat, hcimpact_err_domain, fit, "negative force")
      if (allocated(error)) return
      call fit_static(x, f(1:5), fit, stat)
      call expect(error, stat, hcimpact_err_size, fit, "sizes")
      if (allocated(error)) return
      ! finiteness before sign (issue 13: a NaN deflection gave hcimpact_err_domain)
      call fit_static([x(1:5), ieee_value(1.0_wp, ieee_quiet_nan)], f, fit, stat)
      call expect(error, stat, hcimpact_err_not_finite, fit, "NaN deflection")
      if (allocated(error)) return
      call fit_static([ieee_value(1.0_wp, ieee_quiet_nan), x(2:)], f, fit, stat)
      call expect(error, stat, hcimpact_err_not_finite, fit, "NaN first deflection")
   end subroutine test_static

   subroutine test_elastic(error)
      type(error_type), allocatable, intent(out) :: error
      type(fit_type) :: fit
      real(wp) :: v(6), t(6), f(6), e(6)
      integer :: stat
      ! every measurement at one speed: one series cannot separate c from n
      v = 2.0_wp
      call impact_data(seed_damping, v, 0.01_wp, 0.01_wp, 0.0_wp, 1, t, f, e)
      call fit_elastic(seed_mass, seed_damping, v, fit, stat, contact_time=t)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "times at one speed")
      if (allocated(error)) return
      call fit_elastic(seed_mass, seed_damping, v, fit, stat, peak_force=f)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "forces at one speed")
      if (allocated(error)) return
      v = speeds(6, 0.5_wp, 3.0_wp)
      call impact_data(seed_damping, v, 0.0_wp, 0.0_wp, 0.0_wp, 0, t, f, e)
      call fit_elastic(seed_mass, seed_damping, v, fit, stat)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "no series")
      if (allocated(error)) return
      call fit_elastic(seed_mass, seed_damping, v(1:2), fit, stat, contact_time=t(1:2))
      call expect(error, stat, hcimpact_err_underdetermined, fit, "two points, two parameters")
      if (allocated(error)) return
      call fit_elastic(0.0_wp, seed_damping, v, fit, stat, contact_time=t)
      call expect(error, stat, hcimpact_err_mass, fit, "zero mass")
      if (allocated(error)) return
      call fit_elastic(seed_mass, -0.1_wp, v, fit, stat, contact_time=t)
      call expect(error, stat, hcimpact_err_damping, fit, "negative damping")
      if (allocated(error)) return
      call fit_elastic(seed_mass, seed_damping, v, fit, stat, contact_time=[t(1:5), 0.0_wp])
      call expect(error, stat, hcimpact_err_domain, fit, "zero time")
      if (allocated(error)) return
      call fit_elastic(seed_mass, seed_damping, v, fit, stat, contact_time=t, &
         & peak_force=f(1:5))
      call expect(error, stat, hcimpact_err_size, fit, "sizes")
      if (allocated(error)) return
      call fit_elastic(seed_mass, seed_damping, v, fit, stat, contact_time=t, guess=[1.0e10_wp])
      call expect(error, stat, hcimpact_err_size, fit, "guess size")
      if (allocated(error)) return
      call fit_elastic(seed_mass, seed_damping, v, fit, stat, contact_time=t, &
         & guess=[-1.0e10_wp, 1.5_wp])
      call expect(error, stat, hcimpact_err_domain, fit, "negative guess")
   end subroutine test_elastic

   subroutine test_impact(error)
      type(error_type), allocatable, intent(out) :: error
      type(fit_type) :: fit
      real(wp) :: v(6), t(6), f(6), e(6)
      integer :: stat
      v = speeds(6, 0.5_wp, 3.0_wp)
      call impact_data(seed_damping, v, 0.0_wp, 0.0_wp, 0.0_wp, 0, t, f, e)
      ! restitution determines b, nothing about c and n
      call fit_impact(seed_mass, v, fit, stat, restitution=e)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "restitution only")
      if (allocated(error)) return
      ! one speed, contact time and restitution: rank 2 of 3
      v = 2.0_wp
      call impact_data(seed_damping, v, 0.01_wp, 0.01_wp, 0.01_wp, 2, t, f, e)
      call fit_impact(seed_mass, v, fit, stat, contact_time=t, restitution=e)
      call expect(error, stat, hcimpact_err_underdetermined, fit, "time and e at one speed")
      if (allocated(error)) return
      v = speeds(6, 0.5_wp, 3.0_wp)
      call fit_impact(seed_mass, v, fit, stat, contact_time=t, restitution=[e(1:5), 0.0_wp])
      call expect(error, stat, hcimpact_err_restitution, fit, "zero restitution")
      if (allocated(error)) return
      call fit_impact(seed_mass, [v(1:5), -1.0_wp], fit, stat, contact_time=t)
      call expect(error, stat, hcimpact_err_velocity, fit, "negative speed")
      if (allocated(error)) return
      call fit_impact(seed_mass, v, fit, stat, contact_time=t, &
         & guess=[1.0e10_wp, 1.5_wp, -1.0_wp])
      call expect(error, stat, hcimpact_err_damping, fit, "negative damping guess")
   end subroutine test_impact

   subroutine test_message(error)
      type(error_type), allocatable, intent(out) :: error
      if (index(status_message(hcimpact_err_underdetermined), "cannot determine") == 0) &
         & call test_failed(error, "message of hcimpact_err_underdetermined", &
         & status_message(hcimpact_err_underdetermined))
   end subroutine test_message

end module test_fit_errors
