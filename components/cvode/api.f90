! SPDX-License-Identifier: Apache-2.0
!> C interface of the CVODE component: `hcimpact_simulate` and
!> `hcimpact_simulate_message`.
!>
!> It lives in libhcimpact_cvode (hcimpact::cvode), not in the core library: a C
!> program that calls it must link the component, and one that links only the core
!> gets an undefined reference at link time rather than a status at run time. The
!> declarations are in include/hcimpact_cvode.h; the structures are those of
!> hcimpact_impact (hcimpact_capi_types).
module hcimpact_cvode_api
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_ptr, c_size_t, c_char, &
      & c_null_char, c_associated, c_f_pointer
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_null, hcimpact_err_not_finite, &
      & hcimpact_err_domain, status_message
   use hcimpact_impact_model, only : outcome_type
   use hcimpact_capi_types, only : hcimpact_contact, hcimpact_outcome, to_contact, from_outcome
   use hcimpact_cvode_system, only : finite_value
   use hcimpact_cvode_solver, only : cvode_options, simulation_type, simulate_power, &
      & cvode_bdf
   implicit none
   private

   public :: c_simulate, c_simulate_message, copy_message

contains

   !> int hcimpact_simulate(const hcimpact_contact *contact, double rtol,
   !>                       hcimpact_outcome *outcome);
   !>
   !> The impact integrated by CVODE (BDF, analytic Jacobian, relative tolerance rtol
   !> and the absolute tolerances rtol * natural scale, hcimpact_cvode_solver); on
   !> success 0 < k <= 1 (the solver's k above 1 is reported as 1, see
   !> hcimpact_cvode_solver). Returns 0 on success; HCIMPACT_ERR_NULL (10) if a pointer is NULL (nothing is
   !> written); otherwise a status and NaN in every field of *outcome: the input
   !> errors of hcimpact_impact, HCIMPACT_ERR_NOT_FINITE (1) for a NaN or infinite
   !> rtol, HCIMPACT_ERR_DOMAIN (8) for rtol outside (0, 1), b V above about 1e140 or
   !> an exponent above 100,
   !> HCIMPACT_ERR_SOLVER (11) when CVODE fails, HCIMPACT_ERR_NO_CONVERGENCE (9)
   !> when the contact does not end.
   function c_simulate(contact, rtol, outcome) result(stat) bind(C, name="hcimpact_simulate")
      !> const hcimpact_contact *
      type(c_ptr), value :: contact
      !> Relative tolerance of CVODE, 0 < rtol < 1
      real(c_double), value :: rtol
      !> hcimpact_outcome *
      type(c_ptr), value :: outcome
      !> Status
      integer(c_int) :: stat
      character(len=:), allocatable :: message

      stat = simulate_to_c(contact, rtol, outcome, message)
   end function c_simulate

   !> int hcimpact_simulate_message(const hcimpact_contact *contact, double rtol,
   !>                               hcimpact_outcome *outcome, char *message,
   !>                               size_t message_size);
   !>
   !> hcimpact_simulate, and the solver's account of the run ("success", or CVODE's
   !> flag name and message) in the caller's buffer: message_size bytes, cut to fit
   !> and NUL-terminated when message_size >= 1; nothing is written to a NULL buffer.
   !> The buffer belongs to the caller, so no state is kept between calls.
   function c_simulate_message(contact, rtol, outcome, message, message_size) result(stat) &
         & bind(C, name="hcimpact_simulate_message")
      !> const hcimpact_contact *
      type(c_ptr), value :: contact
      !> Relative tolerance of CVODE, 0 < rtol < 1
      real(c_double), value :: rtol
      !> hcimpact_outcome *
      type(c_ptr), value :: outcome
      !> char *: the caller's buffer, or NULL
      type(c_ptr), value :: message
      !> Size of the buffer in bytes
      integer(c_size_t), value :: message_size
      !> Status
      integer(c_int) :: stat
      character(len=:), allocatable :: text

      stat = simulate_to_c(contact, rtol, outcome, text)
      call copy_message(text, message, message_size)
   end function c_simulate_message

   !> The common body: checks, the integration and the copy to *outcome; `message`
   !> receives the solver's account (or the status text when the solver did not run).
   function simulate_to_c(contact, rtol, outcome, message) result(stat)
      !> const hcimpact_contact *
      type(c_ptr), intent(in) :: contact
      !> Relative tolerance of CVODE, 0 < rtol < 1
      real(c_double), intent(in) :: rtol
      !> hcimpact_outcome *
      type(c_ptr), intent(in) :: outcome
      !> What happened, in words
      character(len=:), allocatable, intent(out) :: message
      !> Status
      integer(c_int) :: stat
      type(hcimpact_contact), pointer :: c_in
      type(hcimpact_outcome), pointer :: c_out
      type(simulation_type) :: simulation
      type(outcome_type) :: result
      integer :: status

      if (.not. (c_associated(contact) .and. c_associated(outcome))) then
         stat = int(hcimpact_err_null, c_int)
         message = status_message(hcimpact_err_null)
         return
      end if
      call c_f_pointer(contact, c_in)
      call c_f_pointer(outcome, c_out)
      ! (finiteness from the bits: a signalling NaN must not raise invalid)
      if (.not. finite_value(rtol)) then
         status = hcimpact_err_not_finite
         result = outcome_type()
         message = "rtol is NaN or infinite"
      else if (.not. (rtol > 0.0_c_double .and. rtol < 1.0_c_double)) then
         status = hcimpact_err_domain
         result = outcome_type()
         message = "rtol must lie in (0, 1)"
      else
         call simulate_power(to_contact(c_in), &
            & simulation, status, cvode_options(method=cvode_bdf, rtol=real(rtol, wp)))
         result = simulation%outcome
         if (allocated(simulation%message)) then
            message = simulation%message
         else if (status == hcimpact_ok) then
            message = "success"
         else
            message = status_message(status)
         end if
      end if
      c_out = from_outcome(result)
      stat = int(status, c_int)
   end function simulate_to_c

   !> A text into the caller's buffer of message_size bytes: cut to fit and
   !> NUL-terminated when message_size >= 1; nothing is written to a NULL buffer. (The
   !> buffer belongs to the caller: no state is kept between calls.)
   subroutine copy_message(text, message, message_size)
      !> The text
      character(len=*), intent(in) :: text
      !> char *: the caller's buffer, or NULL
      type(c_ptr), intent(in) :: message
      !> Size of the buffer in bytes
      integer(c_size_t), intent(in) :: message_size
      character(kind=c_char), pointer :: buffer(:)
      integer(c_size_t) :: i, count
      if (.not. c_associated(message) .or. message_size < 1_c_size_t) return
      call c_f_pointer(message, buffer, [message_size])
      count = min(int(len(text), c_size_t), message_size - 1_c_size_t)
      do i = 1_c_size_t, count
         buffer(i) = text(i:i)
      end do
      buffer(count + 1_c_size_t) = c_null_char
   end subroutine copy_message

end module hcimpact_cvode_api
