! SPDX-License-Identifier: Apache-2.0
!> Work of the thread test (test/threads/driver.c) done in Fortran, CVODE component:
!> integrations through `simulate` with the power law and with user laws, most of them
!> failing on purpose, each with its own message (different texts, different lengths:
!> the input checks, CVODE's flag names, times formatted into the text, CVODE's own
!> message from its error handler). The driver compares the status, the outcome and
!> the message of every case, run by several threads at once, with a serial run.
module thread_cases_cvode
   use, intrinsic :: iso_c_binding, only : c_int, c_double, c_char
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
   use hcimpact_kinds, only : wp
   use hcimpact_elastic, only : elastic_law, power_law
   use hcimpact_impact_model, only : contact_type
   use hcimpact_cvode, only : simulate, simulation_type, cvode_options, cvode_bdf, &
      & cvode_adams
   use thread_cases_core, only : copy_text
   implicit none
   private

   public :: thread_cvode_case, n_cvode_kinds

   !> Number of different cases (case i is kind mod(i, n_cvode_kinds))
   integer, parameter :: n_cvode_kinds = 12

   !> A power law that breaks down (NaN) beyond a compression: a user's law failing
   !> in the middle of an integration
   type, extends(elastic_law) :: breaking_law
      real(wp) :: stiffness = 1.0e9_wp
      real(wp) :: limit = 1.0_wp
   contains
      procedure :: force => breaking_force
      procedure :: potential => breaking_potential
      procedure :: force_derivative => breaking_derivative
   end type breaking_law

contains

   !> void thread_cvode_case(int i, int *status, double values[10], char *message,
   !> int capacity): case i; values = the outcome's nine fields and the number of
   !> steps; message NUL-terminated, cut to capacity.
   subroutine thread_cvode_case(i, status, values, message, capacity) &
         & bind(C, name="thread_cvode_case")
      !> Index of the case
      integer(c_int), value, intent(in) :: i
      !> Status of simulate
      integer(c_int), intent(out) :: status
      !> Outcome and steps
      real(c_double), intent(out) :: values(10)
      !> simulation%message
      character(kind=c_char), intent(out) :: message(*)
      !> Size of message in bytes
      integer(c_int), value, intent(in) :: capacity
      type(simulation_type) :: sim
      type(contact_type) :: ball
      integer :: stat
      real(wp) :: v

      v = 0.5_wp + 0.125_wp * real(mod(i, 29), wp)
      ball = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=v)
      select case (mod(i, n_cvode_kinds))
      case (0)
         call simulate(ball, sim, stat, cvode_options(rtol=1.0e-6_wp))
      case (1)
         call simulate(power_law(stiffness=1.0e9_wp, exponent=2.0_wp), 0.3_wp, 0.05_wp, v, &
            & sim, stat, cvode_options(rtol=1.0e-6_wp, method=cvode_adams))
      case (2)
         ball%mass = ieee_value(1.0_wp, ieee_quiet_nan)
         call simulate(ball, sim, stat)
      case (3)
         ball%mass = -1.0_wp
         call simulate(ball, sim, stat)
      case (4)
         ball%velocity = 0.0_wp
         call simulate(ball, sim, stat)
      case (5)
         ball%damping = -1.0_wp
         call simulate(ball, sim, stat)
      case (6)
         call simulate(ball, sim, stat, cvode_options(rtol=2.0_wp))
      case (7)
         ! CV_TOO_MUCH_WORK with the step count in the message
         call simulate(ball, sim, stat, cvode_options(max_steps=3 + mod(i, 5)))
      case (8)
         ! the law fails: CVODE's own message reaches ours through its error handler
         call simulate(breaking_law(limit=1.0e-6_wp * v), 0.1_wp, 0.1_wp, v, sim, stat, &
            & cvode_options(rtol=1.0e-6_wp, method=cvode_bdf))
      case (9)
         ball%damping = 1.0e300_wp
         call simulate(ball, sim, stat)
      case (10)
         ! the contact has not ended at max_time: a time in the message
         call simulate(ball, sim, stat, cvode_options(rtol=1.0e-5_wp, &
            & max_time=1.0e-6_wp * v))
      case default
         ball%exponent = 0.0_wp
         call simulate(ball, sim, stat)
      end select
      status = int(stat, c_int)
      values = [sim%outcome%restitution, sim%outcome%energy_loss_ratio, &
         & sim%outcome%rebound_velocity, sim%outcome%max_compression, &
         & sim%outcome%peak_force, sim%outcome%compression_at_peak_force, &
         & sim%outcome%time_at_peak_force, sim%outcome%compression_time, &
         & sim%outcome%contact_time, real(sim%counters%steps, wp)]
      call copy_text(sim%message, message, capacity)
   end subroutine thread_cvode_case

   pure function breaking_force(self, x) result(y)
      class(breaking_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%stiffness * x**1.5_wp
      if (x > self%limit) y = ieee_value(y, ieee_quiet_nan)
   end function breaking_force

   pure function breaking_potential(self, x) result(y)
      class(breaking_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%stiffness * x**2.5_wp / 2.5_wp
   end function breaking_potential

   pure function breaking_derivative(self, x) result(y)
      class(breaking_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = 1.5_wp * self%stiffness * sqrt(x)
      if (x > self%limit) y = ieee_value(y, ieee_quiet_nan)
   end function breaking_derivative

end module thread_cases_cvode
