! SPDX-License-Identifier: Apache-2.0
!> The ODE path of the scene runner in a build without the CVODE component (fpm, or
!> CMake without SUNDIALS): it says so. CMake builds with the component compile
!> app/cvode/scene_ode.f90 instead, a module of the same name and interface.
module hcimpact_scene_ode
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_err_unavailable
   use hcimpact_impact_model, only : contact_type, outcome_type
   use hcimpact_chain, only : chain_exact, chain_type, chain_options, chain_result, &
      & method_integrated
   use hcimpact_scene_text, only : real_str
   implicit none
   private

   public :: ode_available, ode_description, ode_missing, ode_run_type, ode_impact, ode_chain
   public :: ode_chain_description

   !> Whether this build can integrate the impact with CVODE
   logical, parameter :: ode_available = .false.
   !> The solver, for the log
   character(len=*), parameter :: ode_description = "none (built without the CVODE component)"
   !> The integrator of a system's clusters, for the log
   character(len=*), parameter :: ode_chain_description = ode_description
   !> Why it is missing and how to get it
   character(len=*), parameter :: ode_missing = &
      & "this hcimpact was built without the CVODE component (SUNDIALS): fpm builds never " &
      & // "have it, CMake builds have it when SUNDIALS with its Fortran modules is found " &
      & // "(Debian: libsundials-dev libsundials-fortran-dev; bash .ci/install) and " &
      & // "HCIMPACT_WITH_CVODE is not OFF. Build with CMake, or leave 'cvode' out of the outputs"

   !> One integration: the outcome and the solver's counters
   type :: ode_run_type
      type(outcome_type) :: outcome
      integer(int64) :: steps = 0, rhs_evals = 0, jacobian_evals = 0, root_evals = 0
      character(len=:), allocatable :: message
   end type ode_run_type

contains

   !> Not available in this build: hcimpact_err_unavailable.
   subroutine ode_impact(contact, rtol, run, stat)
      type(contact_type), intent(in) :: contact
      real(wp), intent(in) :: rtol
      type(ode_run_type), intent(out) :: run
      integer, intent(out) :: stat
      run%message = "no ODE solver for the impact at V = " // real_str(contact%velocity, 6) &
         & // " m/s with rtol = " // real_str(rtol, 3) // ": " // ode_missing
      stat = hcimpact_err_unavailable
   end subroutine ode_impact

   !> A system of bodies with the core alone: the closed forms of one impact for every
   !> contact (chain_exact). A cluster of overlapping contacts, a wall contact under
   !> gravity, or the method 'integrated' needs CVODE: hcimpact_err_unavailable, and the
   !> message says why.
   subroutine ode_chain(chain, options, result, stat)
      type(chain_type), intent(in) :: chain
      type(chain_options), intent(in) :: options
      type(chain_result), intent(out) :: result
      integer, intent(out) :: stat
      if (options%method == method_integrated) then
         stat = hcimpact_err_unavailable
         result%message = "the method 'integrated' needs the CVODE component"
         return
      end if
      call chain_exact(chain, result, stat, options)
   end subroutine ode_chain

end module hcimpact_scene_ode
