! SPDX-License-Identifier: Apache-2.0
!> Helpers of the FORTRAN 77 entry points (src/hcimpact/f77/f77.f90): the LAPACK-style
!> INFO of a contact's arguments and the flat result array of one impact.
module hcimpact_f77_support
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : outcome_type
   use hcimpact_elastic, only : elastic_law
   implicit none
   private

   public :: nan, contact_info, outcome_array, f77_law, f77_law_fn

   abstract interface
      !> A function of a FORTRAN 77 law: DOUBLE PRECISION FUNCTION F(X), X the compression
      !> in m. Taken as free of side effects, as a law of the Fortran interface must be.
      pure function f77_law_fn(x) result(y)
         import :: wp
         real(wp), intent(in) :: x
         real(wp) :: y
      end function f77_law_fn
   end interface

   !> A law given as three EXTERNAL functions (HCIMPL)
   type, extends(elastic_law) :: f77_law
      procedure(f77_law_fn), pointer, nopass :: f => null(), p => null(), d => null()
   contains
      procedure :: force => f77_force
      procedure :: potential => f77_potential
      procedure :: force_derivative => f77_force_derivative
   end type f77_law

   !> Quiet NaN, the value of every real output on error
   real(wp), parameter :: nan = transfer(9221120237041090560_int64, 1.0_wp)

contains

   !> INFO for the contact arguments (M, C, EN, B, V) in this order: -i for the first
   !> that is NaN, infinite or outside its domain (M, C, EN, V > 0; B >= 0), else 0.
   pure function contact_info(m, c, en, b, v) result(info)
      !> Mass in kg
      real(wp), intent(in) :: m
      !> Contact constant in N/m**EN
      real(wp), intent(in) :: c
      !> Exponent of the elastic law
      real(wp), intent(in) :: en
      !> Damping in s/m
      real(wp), intent(in) :: b
      !> Approach speed in m/s
      real(wp), intent(in) :: v
      !> 0 or -1 .. -5
      integer :: info
      if (.not. positive(m)) then
         info = -1
      else if (.not. positive(c)) then
         info = -2
      else if (.not. positive(en)) then
         info = -3
      else if (.not. (positive(b) .or. b == 0.0_wp)) then
         info = -4
      else if (.not. positive(v)) then
         info = -5
      else
         info = 0
      end if
   end function contact_info

   !> x finite and > 0 (no ordered comparison with NaN: -ffpe-trap=invalid)
   elemental function positive(x) result(ok)
      real(wp), intent(in) :: x
      logical :: ok
      ok = ieee_is_finite(x)
      if (ok) ok = x > 0.0_wp
   end function positive

   !> The eight results of HCIMP in their order: k, 1 - k**2, rebound velocity,
   !> x_max, peak force, compression at the peak force, compression time, contact time.
   pure function outcome_array(outcome) result(out)
      !> Outcome of `impact`
      type(outcome_type), intent(in) :: outcome
      !> OUT(8)
      real(wp) :: out(8)
      out = [outcome%restitution, outcome%energy_loss_ratio, outcome%rebound_velocity, &
         & outcome%max_compression, outcome%peak_force, outcome%compression_at_peak_force, &
         & outcome%compression_time, outcome%contact_time]
   end function outcome_array

   pure function f77_force(self, x) result(y)
      class(f77_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%f(x)
   end function f77_force

   pure function f77_potential(self, x) result(y)
      class(f77_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%p(x)
   end function f77_potential

   pure function f77_force_derivative(self, x) result(y)
      class(f77_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%d(x)
   end function f77_force_derivative

end module hcimpact_f77_support
