! SPDX-License-Identifier: Apache-2.0
!> fpm consumer of hcimpact's components: `use hcimpact_cvode` and
!> `use hcimpact_calibration` from a project that depends on them through fpm. The ODE
!> path must agree with the closed form, and the damping fit must give back the b of
!> exact restitution data. Stops with a non-zero code on a failure.
program components
   use hcimpact, only : wp, contact_type, outcome_type, impact, restitution, hcimpact_ok
   use hcimpact_cvode, only : simulation_type, simulate_power, cvode_options, cvode_bdf
   use hcimpact_calibration, only : fit_type, fit_damping
   implicit none

   !> the steel ball of doc/model.md at V = 1 m/s
   type(contact_type), parameter :: ball = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, &
      & exponent=1.5_wp, damping=0.1_wp, velocity=1.0_wp)
   real(wp), parameter :: rtol = 1.0e-8_wp
   real(wp), parameter :: speeds(5) = [0.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 5.0_wp]
   type(outcome_type) :: exact
   type(simulation_type) :: simulation
   type(fit_type) :: fit
   integer :: stat, failures

   failures = 0
   call impact(ball, exact, stat)
   if (stat /= hcimpact_ok) call fail("impact: status")
   call simulate_power(ball, simulation, stat, cvode_options(method=cvode_bdf, rtol=rtol))
   write(*, '(a, i0, 2a)') "hcimpact_cvode: status ", stat, ", ", simulation%message
   if (stat /= hcimpact_ok) call fail("simulate_power: status")
   write(*, '(a, 2es24.16)') "contact time (ODE, closed form): ", &
      & simulation%outcome%contact_time, exact%contact_time
   if (.not. (abs(simulation%outcome%contact_time - exact%contact_time) &
      & <= 100 * rtol * exact%contact_time)) call fail("contact time")

   call fit_damping(speeds, restitution(ball%damping * speeds), fit, stat)
   write(*, '(a, i0, a, es24.16)') "hcimpact_calibration: status ", stat, ", b = ", &
      & fit%parameters(1)
   if (stat /= hcimpact_ok) call fail("fit_damping: status")
   if (.not. (abs(fit%parameters(1) - ball%damping) <= 1.0e-12_wp)) call fail("fitted b")

   if (failures > 0) error stop 1
   write(*, '(a)') "components: all checks passed"

contains

   subroutine fail(what)
      character(len=*), intent(in) :: what
      write(*, '(2a)') "FAIL: ", what
      failures = failures + 1
   end subroutine fail

end program components
