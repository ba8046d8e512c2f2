! SPDX-License-Identifier: Apache-2.0
!> C interface for an elastic law supplied by the caller as C functions.
!>
!> The C caller passes the law as three callbacks double f(double x, void *data) for the
!> force f(x), its potential Pi(x) = integral of f from 0 to x, and its derivative f'(x),
!> with one data pointer handed back to them. They are converted once to procedure
!> pointers with a pure interface, so the law extends `elastic_law` and runs through the
!> same closed forms as any Fortran law (`impact_law`). The library takes the callbacks
!> to be free of side effects on what it reads (as the Fortran interface requires of a
!> law): they may be called many times, in any order, and from several threads when
!> the caller runs impacts in parallel.
module hcimpact_api_law
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_ptr, c_funptr, c_null_ptr, &
      & c_associated, c_f_pointer, c_f_procpointer
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_err_null
   use hcimpact_elastic, only : elastic_law
   use hcimpact_impact_model, only : outcome_type, impact_law
   use hcimpact_capi_types, only : hcimpact_outcome, from_outcome
   implicit none
   private

   public :: hcimpact_elastic_law, c_impact_law

   !> C view of a law: struct hcimpact_elastic_law in include/hcimpact.h
   type, bind(C) :: hcimpact_elastic_law
      !> double force(double x, void *data): f(x) in N
      type(c_funptr) :: force
      !> double potential(double x, void *data): Pi(x) in J
      type(c_funptr) :: potential
      !> double force_derivative(double x, void *data): f'(x) in N/m
      type(c_funptr) :: force_derivative
      !> Passed back to every callback
      type(c_ptr) :: data
   end type hcimpact_elastic_law

   abstract interface
      !> A callback of the law: a value at the compression x (m)
      pure function law_callback(x, data) result(y) bind(C)
         import :: c_double, c_ptr
         real(c_double), value, intent(in) :: x
         type(c_ptr), value, intent(in) :: data
         real(c_double) :: y
      end function law_callback
   end interface

   !> The law as the closed forms see it
   type, extends(elastic_law) :: callback_law
      procedure(law_callback), pointer, nopass :: f => null(), p => null(), d => null()
      type(c_ptr) :: data = c_null_ptr
   contains
      procedure :: force => callback_force
      procedure :: potential => callback_potential
      procedure :: force_derivative => callback_force_derivative
   end type callback_law

contains

   !> hcimpact_impact for the caller's elastic law (mass, damping b in s/m, approach
   !> speed V in m/s). NULL law, outcome or callback: HCIMPACT_ERR_NULL (nothing
   !> written); otherwise the statuses of `impact_law`, among them
   !> HCIMPACT_ERR_ELASTIC_LAW when a callback returns a non-finite or inconsistent value.
   function c_impact_law(law, mass, damping, velocity, outcome) result(stat) &
         & bind(C, name="hcimpact_impact_law")
      type(c_ptr), value, intent(in) :: law
      real(c_double), value, intent(in) :: mass, damping, velocity
      type(c_ptr), value, intent(in) :: outcome
      integer(c_int) :: stat
      type(hcimpact_elastic_law), pointer :: c_law
      type(hcimpact_outcome), pointer :: out
      type(callback_law) :: f_law
      type(outcome_type) :: result
      integer :: fstat

      stat = int(hcimpact_err_null, c_int)
      if (.not. (c_associated(law) .and. c_associated(outcome))) return
      call c_f_pointer(law, c_law)
      call c_f_pointer(outcome, out)
      if (.not. (c_associated(c_law%force) .and. c_associated(c_law%potential) &
         & .and. c_associated(c_law%force_derivative))) return
      call c_f_procpointer(c_law%force, f_law%f)
      call c_f_procpointer(c_law%potential, f_law%p)
      call c_f_procpointer(c_law%force_derivative, f_law%d)
      f_law%data = c_law%data

      call impact_law(f_law, mass, damping, velocity, result, fstat)
      out = from_outcome(result)
      stat = int(fstat, c_int)
   end function c_impact_law

   pure function callback_force(self, x) result(y)
      class(callback_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%f(x, self%data)
   end function callback_force

   pure function callback_potential(self, x) result(y)
      class(callback_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%p(x, self%data)
   end function callback_potential

   pure function callback_force_derivative(self, x) result(y)
      class(callback_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%d(x, self%data)
   end function callback_force_derivative

end module hcimpact_api_law
