! SPDX-License-Identifier: Apache-2.0
!> Status codes shared by the Fortran and C interfaces, and their messages.
!>
!> Every procedure that can reject its input returns one of these codes; 0 means
!> success. The same numbers are the `HCIMPACT_*` macros of include/hcimpact.h.
!>
!> The texts live in one table, `status_texts` (a named constant, so that a constant
!> table of another interface can be initialised from it). `status_message` returns
!> a text without trailing blanks; its length is a specification expression, not a
!> deferred length: gfortran keeps the length of a deferred-length function result
!> in a hidden static variable of every caller (even with -frecursive), which two
!> threads calling at once would share.
module hcimpact_status
   implicit none
   private

   public :: status_message, status_texts, max_status_code
   public :: hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_stiffness, hcimpact_err_exponent, hcimpact_err_velocity, &
      & hcimpact_err_damping, hcimpact_err_restitution, hcimpact_err_domain, &
      & hcimpact_err_no_convergence, hcimpact_err_null, hcimpact_err_solver, &
      & hcimpact_err_unavailable, hcimpact_err_elastic_law, hcimpact_err_size, &
      & hcimpact_err_underdetermined, hcimpact_err_out_of_memory

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
   !> The memory available cannot hold what the input needs (an allocation failed):
   !> the arguments are valid, the machine is too small for them
   integer, parameter :: hcimpact_err_out_of_memory = 16

   !> Largest status code with a text of its own
   integer, parameter :: max_status_code = hcimpact_err_out_of_memory
   !> Length of every entry of `status_texts` (blank-padded)
   integer, parameter :: status_text_length = 79

   !> The text of each status code 0 .. max_status_code, then (at max_status_code + 1)
   !> the one for codes without a text, blank-padded to status_text_length. The only
   !> copy of the messages: status_message reads it, and the C layer's constant table
   !> must say the same (test/api/status_table.f90).
   character(len=status_text_length), parameter :: status_texts(0:max_status_code + 1) = [ &
      & character(len=status_text_length) :: &
      & "success", &
      & "an argument is NaN or infinite", &
      & "mass must be positive", &
      & "stiffness must be positive", &
      & "exponent of the power law must be at least 1e-6", &
      & "approach velocity must be positive", &
      & "damping must not be negative", &
      & "target restitution must lie in (0, 1]", &
      & "argument outside the domain of the function", &
      & "iteration or quadrature did not converge within its bound", &
      & "a required pointer argument is NULL", &
      & "the ODE solver failed", &
      & "the requested component is not part of this build", &
      & "the elastic law returned an invalid value", &
      & "an array argument has the wrong size", &
      & "the data cannot determine the parameters (too few or too similar points)", &
      & "out of memory: the input needs more memory than is available", &
      & "unknown status code"]

contains

   !> Row of status_texts for a status code: the code itself, or the last row.
   pure function status_index(stat) result(row)
      !> Status code
      integer, intent(in) :: stat
      !> Index into status_texts
      integer :: row

      row = max_status_code + 1
      if (stat >= 0 .and. stat <= max_status_code) row = stat
   end function status_index

   !> Length of status_message(stat) (a specification function of its result).
   pure function status_message_length(stat) result(length)
      !> Status code
      integer, intent(in) :: stat
      !> Number of characters
      integer :: length

      length = len_trim(status_texts(status_index(stat)))
   end function status_message_length

   !> Text for a status code (never empty; unknown codes say so), without trailing
   !> blanks. Thread-safe: nothing static, in the callee or in the caller.
   pure function status_message(stat) result(message)
      !> Status code
      integer, intent(in) :: stat
      !> Human-readable description
      character(len=status_message_length(stat)) :: message

      message = status_texts(status_index(stat))
   end function status_message

end module hcimpact_status
