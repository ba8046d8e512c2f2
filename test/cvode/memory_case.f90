! SPDX-License-Identifier: Apache-2.0
!> The Fortran side of test/cvode/memory_test.c: a long recorded integration whose
!> trajectory grows to several MiB (an oscillating force keeps the body in contact
!> until max_steps), run by the C driver under a capped address space.
module cvode_memory_case
   use, intrinsic :: iso_c_binding, only : c_int
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_err_solver
   use hcimpact_elastic, only : power_law
   use hcimpact_cvode, only : simulate, simulation_type, cvode_options, external_force
   implicit none
   private

   public :: recorded_run

   !> g(t) = g0 (1 + sin(omega t)) N, pressing the body into the obstacle
   type, extends(external_force) :: pulsating_force
      real(wp) :: g0 = 1.0e3_wp, omega = 1.0e3_wp
   contains
      procedure :: force => pulsating_value
   end type pulsating_force

contains

   !> int recorded_run(int max_steps): 0 when the run reached max_steps with every
   !> step recorded; 1 when it stopped with the out-of-memory status and message and a
   !> trajectory of consistent sizes (or none); 2 otherwise.
   function recorded_run(max_steps) result(outcome) bind(C, name="recorded_run")
      !> Steps to take
      integer(c_int), value, intent(in) :: max_steps
      !> 0, 1 or 2
      integer(c_int) :: outcome
      type(simulation_type) :: sim
      integer :: stat, n

      call simulate(power_law(stiffness=1.0e4_wp, exponent=1.0_wp), 1.0_wp, 0.5_wp, 1.0_wp, &
         & sim, stat, cvode_options(rtol=1.0e-6_wp, max_steps=int(max_steps), &
         & max_time=huge(1.0_wp), record_trajectory=.true.), external=pulsating_force())
      outcome = 2
      if (stat /= hcimpact_err_solver) return
      if (index(sim%message, "out of memory") > 0) then
         if (.not. allocated(sim%time)) then
            outcome = 1
         else
            n = size(sim%time)
            if (size(sim%compression) == n .and. size(sim%velocity) == n .and. &
               & size(sim%force) == n) outcome = 1
         end if
      else if (index(sim%message, "CV_TOO_MUCH_WORK") > 0) then
         if (allocated(sim%time)) then
            if (size(sim%time) > max_steps) outcome = 0
         end if
      end if
   end function recorded_run

   pure function pulsating_value(self, t, x, v) result(g)
      class(pulsating_force), intent(in) :: self
      real(wp), intent(in) :: t, x, v
      real(wp) :: g
      g = self%g0 * (1.0_wp + sin(self%omega * t)) + 0.0_wp * (x + v)
   end function pulsating_value

end module cvode_memory_case
