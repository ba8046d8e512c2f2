! SPDX-License-Identifier: Apache-2.0
!> The seed's steel ball (MODEL.md: m = 0.1 kg, c = 1.7135e10 N/m^1.5, n = 3/2,
!> b = 0.1 s/m, V = 1 m/s) integrated by CVODE (component hcimpact::cvode), next to the
!> closed forms; then the same ball against a contact law without a closed form (a
!> Hertz law stiffening like x^3 beyond 10 micrometres) pressed by its weight.
!>
!> Stops with an error if CVODE's outcome is further from the closed forms than
!> 100 rtol, so that it also serves as a test.
program simulate
   use, intrinsic :: iso_fortran_env, only : error_unit
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, status_message
   use hcimpact_elastic, only : elastic_law
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate_power, simulate_law, &
      & cvode_bdf, cvode_adams, external_force
   use example_laws, only : stiffening_law, weight
   implicit none

   type(contact_type), parameter :: ball = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, &
      & exponent=1.5_wp, damping=0.1_wp, velocity=1.0_wp)
   real(wp), parameter :: rtol = 1.0e-8_wp
   character(len=*), parameter :: names(8) = [character(len=26) :: "restitution k", &
      & "max. compression (m)", "peak force (N)", "compression at peak (m)", &
      & "time of peak force (s)", "compression time (s)", "contact time (s)", &
      & "rebound velocity (m/s)"]
   type(outcome_type) :: closed
   type(simulation_type) :: bdf, adams, law_run
   real(wp) :: exact(8), ode(8, 2), worst
   integer :: stat, i, m

   write(*, '(a)') "Steel ball on a steel plate, V = 1 m/s (MODEL.md), CVODE at rtol = 1e-8"
   call impact(ball, closed, stat)
   if (stat /= hcimpact_ok) call fail("closed forms failed: " // status_message(stat))
   call simulate_power(ball, bdf, stat, cvode_options(method=cvode_bdf, rtol=rtol, &
      & record_trajectory=.true.))
   if (stat /= hcimpact_ok) call fail("CVODE (BDF) failed: " // bdf%message)
   call simulate_power(ball, adams, stat, cvode_options(method=cvode_adams, rtol=rtol))
   if (stat /= hcimpact_ok) call fail("CVODE (Adams) failed: " // adams%message)

   exact = values(closed)
   ode(:, 1) = values(bdf%outcome)
   ode(:, 2) = values(adams%outcome)
   write(*, '(/, a26, 3a24, 2a11)') "", "closed forms", "CVODE BDF", "CVODE Adams", &
      & "rel. BDF", "rel. Adams"
   worst = 0.0_wp
   do i = 1, 8
      write(*, '(a26, 3es24.16, 2es11.2)') names(i), exact(i), ode(i, :), &
         & (abs(ode(i, m) - exact(i)) / abs(exact(i)), m = 1, 2)
      worst = max(worst, maxval(abs(ode(i, :) - exact(i))) / abs(exact(i)))
   end do
   write(*, '(/, a)') "CVODE's counters            BDF      Adams"
   write(*, '(a, 2i11)') "steps                ", bdf%counters%steps, adams%counters%steps
   write(*, '(a, 2i11)') "RHS evaluations      ", bdf%counters%rhs_evals, &
      & adams%counters%rhs_evals
   write(*, '(a, 2i11)') "Jacobian evaluations ", bdf%counters%jacobian_evals, &
      & adams%counters%jacobian_evals
   write(*, '(a, 2i11)') "root evaluations     ", bdf%counters%root_evals, &
      & adams%counters%root_evals
   write(*, '(a, 2i11)') "error test failures  ", bdf%counters%error_test_failures, &
      & adams%counters%error_test_failures
   write(*, '(a, 2i11)') "Newton iterations    ", bdf%counters%nonlinear_iterations, &
      & adams%counters%nonlinear_iterations
   write(*, '(a, es11.3)') "stiffness ratio max|lambda| t_c: ", bdf%stiffness_ratio
   write(*, '(a, i0, a)') "trajectory (BDF): ", size(bdf%time), " samples; every 8th:"
   write(*, '(4a16)') "t (s)", "x (m)", "x' (m/s)", "F (N)"
   do i = 1, size(bdf%time), 8
      write(*, '(4es16.7)') bdf%time(i), bdf%compression(i), bdf%velocity(i), bdf%force(i)
   end do
   if (worst > 100.0_wp * rtol) call fail("CVODE is further than 100 rtol from the closed forms")

   write(*, '(/, a)') "The same ball, a law that stiffens like x^3 beyond 10 um, and its weight:"
   call simulate_law(stiffening_law(stiffness=1.7135e10_wp, knee=1.0e-5_wp), &
      & ball%mass, ball%damping, ball%velocity, law_run, stat, &
      & cvode_options(rtol=rtol), external=weight(force=0.1_wp * 9.81_wp))
   if (stat /= hcimpact_ok) call fail("CVODE (user law) failed: " // law_run%message)
   write(*, '(a, es16.8)') "restitution          ", law_run%outcome%restitution
   write(*, '(a, es16.8, a)') "max. compression     ", law_run%outcome%max_compression, " m"
   write(*, '(a, es16.8, a)') "peak force           ", law_run%outcome%peak_force, " N"
   write(*, '(a, es16.8, a)') "contact time         ", law_run%outcome%contact_time, " s"
   write(*, '(a, i0, a, i0, a)') "(", law_run%counters%steps, " steps, ", &
      & law_run%counters%rhs_evals, " RHS evaluations)"

contains

   !> The outputs compared, in the order of `names`.
   pure function values(o) result(v)
      type(outcome_type), intent(in) :: o
      real(wp) :: v(8)
      v = [o%restitution, o%max_compression, o%peak_force, o%compression_at_peak_force, &
         & o%time_at_peak_force, o%compression_time, o%contact_time, o%rebound_velocity]
   end function values

   !> The message on standard error, exit status 1
   subroutine fail(message)
      character(len=*), intent(in) :: message
      write(error_unit, '(a)') message
      stop 1, quiet=.true.
   end subroutine fail

end program simulate
