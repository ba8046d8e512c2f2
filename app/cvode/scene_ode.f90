! SPDX-License-Identifier: Apache-2.0
!> The ODE path of the scene runner with the CVODE component (hcimpact::cvode):
!> replaces app/hcimpact/scene_ode.f90 in CMake builds that have the component.
module hcimpact_scene_ode
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type
   use hcimpact_cvode, only : simulate, simulation_type, cvode_options, cvode_bdf, &
      & chain_simulate
   use hcimpact_chain, only : chain_type, chain_options, chain_result
   implicit none
   private

   public :: ode_available, ode_description, ode_missing, ode_run_type, ode_impact, ode_chain
   public :: ode_chain_description

   !> Whether this build can integrate the impact with CVODE
   logical, parameter :: ode_available = .true.
   !> The solver, for the log
   character(len=*), parameter :: ode_description = "SUNDIALS CVODE (BDF, dense Newton " &
      & // "with the analytic Jacobian, root finding for the events), scaled equation"
   !> The integrator of a system's clusters, for the log
   character(len=*), parameter :: ode_chain_description = "SUNDIALS CVODE (BDF or Adams," &
      & // " as &bodies' integrator says; Newton with the banded Jacobian of the contact" &
      & // " forces, solved by eliminating the displacements and a tridiagonal solve for" &
      & // " the velocities; contacts followed on its interpolant), for clusters of" &
      & // " overlapping contacts"
   !> Why it would be missing (it is not)
   character(len=*), parameter :: ode_missing = ""

   !> One integration: the outcome and the solver's counters
   type :: ode_run_type
      type(outcome_type) :: outcome
      integer(int64) :: steps = 0, rhs_evals = 0, jacobian_evals = 0, root_evals = 0
      character(len=:), allocatable :: message
   end type ode_run_type

contains

   !> The impact integrated by CVODE with the relative tolerance rtol (and the same
   !> relative absolute tolerance).
   subroutine ode_impact(contact, rtol, run, stat)
      type(contact_type), intent(in) :: contact
      real(wp), intent(in) :: rtol
      type(ode_run_type), intent(out) :: run
      integer, intent(out) :: stat
      type(simulation_type) :: sim
      type(cvode_options) :: options
      options = cvode_options(method=cvode_bdf, rtol=rtol)
      call simulate(contact, sim, stat, options)
      run%outcome = sim%outcome
      run%steps = sim%counters%steps
      run%rhs_evals = sim%counters%rhs_evals + sim%counters%jacobian_rhs_evals
      run%jacobian_evals = sim%counters%jacobian_evals
      run%root_evals = sim%counters%root_evals
      run%message = sim%message
   end subroutine ode_impact

   !> A system of bodies: the closed forms where contacts are isolated, CVODE for the
   !> clusters (chain_simulate).
   subroutine ode_chain(chain, options, result, stat)
      type(chain_type), intent(in) :: chain
      type(chain_options), intent(in) :: options
      type(chain_result), intent(out) :: result
      integer, intent(out) :: stat
      call chain_simulate(chain, result, stat, options)
   end subroutine ode_chain

end module hcimpact_scene_ode
