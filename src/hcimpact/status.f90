! SPDX-License-Identifier: Apache-2.0
!> Status codes shared by the Fortran and C interfaces, and their messages.
!>
!> Every procedure that can reject its input returns one of these codes; 0 means
!> success. The same numbers are the `HCIMPACT_*` macros of include/hcimpact.h.
module hcimpact_status
   implicit none
   private

   public :: status_message
   public :: hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_stiffness, hcimpact_err_exponent, hcimpact_err_velocity, &
      & hcimpact_err_damping, hcimpact_err_restitution, hcimpact_err_domain, &
      & hcimpact_err_no_convergence, hcimpact_err_null, hcimpact_err_solver, &
      & hcimpact_err_unavailable, hcimpact_err_elastic_law, hcimpact_err_size, &
      & hcimpact_err_underdetermined

   !> Success
   integer, parameter :: hcimpact_ok = 0
   !> An argument is NaN or infinite
   integer, parameter :: hcimpact_err_not_finite = 1
   !> Mass is zero or negative
   integer, parameter :: hcimpact_err_mass = 2
   !> Stiffness (contact constant c) is zero or negative
   integer, parameter :: hcimpact_err_stiffness = 3
   !> Exponent n of the elastic law is below its minimum (1e-6 for the power law; 0 elsewhere)
   integer, parameter :: hcimpact_err_exponent = 4
   !> Approach velocity is zero or negative
   integer, parameter :: hcimpact_err_velocity = 5
   !> Damping b is negative
   integer, parameter :: hcimpact_err_damping = 6
   !> Target restitution outside (0, 1]
   integer, parameter :: hcimpact_err_restitution = 7
   !> Another argument outside the function's domain
   integer, parameter :: hcimpact_err_domain = 8
   !> An iteration or quadrature did not reach its tolerance within its bound
   integer, parameter :: hcimpact_err_no_convergence = 9
   !> A required pointer argument of the C interface is NULL
   integer, parameter :: hcimpact_err_null = 10
   !> The ODE solver failed (the message names the solver's flag)
   integer, parameter :: hcimpact_err_solver = 11
   !> The requested component is not part of this build
   integer, parameter :: hcimpact_err_unavailable = 12
   !> A user-supplied elastic law returned an invalid value
   integer, parameter :: hcimpact_err_elastic_law = 13
   !> An array argument has the wrong size
   integer, parameter :: hcimpact_err_size = 14
   !> The data cannot determine the parameters of a fit (too few points, or points
   !> that do not vary enough, e.g. all at one speed)
   integer, parameter :: hcimpact_err_underdetermined = 15

contains

   !> Text for a status code (never empty; unknown codes say so).
   pure function status_message(stat) result(message)
      !> Status code
      integer, intent(in) :: stat
      !> Human-readable description
      character(len=:), allocatable :: message

      select case (stat)
      case (hcimpact_ok)
         message = "success"
      case (hcimpact_err_not_finite)
         message = "an argument is NaN or infinite"
      case (hcimpact_err_mass)
         message = "mass must be positive"
      case (hcimpact_err_stiffness)
         message = "stiffness must be positive"
      case (hcimpact_err_exponent)
         message = "exponent of the power law must be at least 1e-6"
      case (hcimpact_err_velocity)
         message = "approach velocity must be positive"
      case (hcimpact_err_damping)
         message = "damping must not be negative"
      case (hcimpact_err_restitution)
         message = "target restitution must lie in (0, 1]"
      case (hcimpact_err_domain)
         message = "argument outside the domain of the function"
      case (hcimpact_err_no_convergence)
         message = "iteration or quadrature did not converge within its bound"
      case (hcimpact_err_null)
         message = "a required pointer argument is NULL"
      case (hcimpact_err_solver)
         message = "the ODE solver failed"
      case (hcimpact_err_unavailable)
         message = "the requested component is not part of this build"
      case (hcimpact_err_elastic_law)
         message = "the elastic law returned an invalid value"
      case (hcimpact_err_size)
         message = "an array argument has the wrong size"
      case (hcimpact_err_underdetermined)
         message = "the data cannot determine the parameters (too few or too similar points)"
      case default
         message = "unknown status code"
      end select
   end function status_message

end module hcimpact_status
