! SPDX-License-Identifier: Apache-2.0
!> Helpers of the FORTRAN 77 entry points (src/hcimpact/f77/f77.f90): the LAPACK-style
!> INFO of a contact's arguments and the flat result array of one impact.
module hcimpact_f77_support
   use hcimpact_kinds, only : wp, nan
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_contact, only : outcome_type, check_parameters
   use hcimpact_force_element, only : contact_force_type
   use hcimpact_elastic, only : elastic_law
   implicit none
   private

   public :: nan, n_outputs, contact_info, outcome_array, f77_law, f77_law_fn
   public :: law_info, force_array, first_failure

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

   !> Number of results of an impact in the FORTRAN 77 arrays (HCIMPN's largest NOUT)
   integer, parameter :: n_outputs = 9

contains

   !> INFO of an array routine from its ISTAT(N): the index of the first element whose
   !> status is not success, else 0.
   pure function first_failure(n, istat) result(info)
      !> Number of elements
      integer, intent(in) :: n
      !> The library status of each element
      integer, intent(in) :: istat(*)
      !> 0 or the first failing index
      integer :: info
      integer :: i
      info = 0
      do i = 1, n
         if (istat(i) /= hcimpact_ok) then
            info = i
            return
         end if
      end do
   end function first_failure

   !> INFO for the contact arguments (M, C, EN, B, V) in this order: -i for the first
   !> that breaks the library's rules for it (hcimpact_contact's `check_parameters`:
   !> NaN or infinite; M, C, V > 0; EN >= 1e-6; B >= 0), else 0.
   elemental function contact_info(m, c, en, b, v) result(info)
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
      if (check_parameters(mass=m) /= hcimpact_ok) then
         info = -1
      else if (check_parameters(stiffness=c) /= hcimpact_ok) then
         info = -2
      else if (check_parameters(exponent=en) /= hcimpact_ok) then
         info = -3
      else if (check_parameters(damping=b) /= hcimpact_ok) then
         info = -4
      else if (check_parameters(velocity=v) /= hcimpact_ok) then
         info = -5
      else
         info = 0
      end if
   end function contact_info

   !> INFO for the law arguments (C, EN, B) of the contact-force routines, in this
   !> order: -i for the first that breaks the library's rules for it, else 0.
   elemental function law_info(c, en, b) result(info)
      !> Contact constant in N/m**EN
      real(wp), intent(in) :: c
      !> Exponent of the elastic law
      real(wp), intent(in) :: en
      !> Damping in s/m
      real(wp), intent(in) :: b
      !> 0 or -1 .. -3
      integer :: info
      if (check_parameters(stiffness=c) /= hcimpact_ok) then
         info = -1
      else if (check_parameters(exponent=en) /= hcimpact_ok) then
         info = -2
      else if (check_parameters(damping=b) /= hcimpact_ok) then
         info = -3
      else
         info = 0
      end if
   end function law_info

   !> The element as the array F(5) of the contact-force routines: force, dF/dx, dF/dv,
   !> potential, dissipation.
   pure function force_array(element) result(f)
      !> The element
      type(contact_force_type), intent(in) :: element
      !> F(5)
      real(wp) :: f(5)
      f = [element%force, element%dforce_dx, element%dforce_dv, element%potential, &
         & element%dissipation]
   end function force_array

   !> The results of an impact in the order of the FORTRAN 77 arrays: k, 1 - k**2,
   !> rebound velocity, x_max, peak force, compression at the peak force, compression
   !> time, contact time (the eight of HCIMP), then the time of the peak force (HCIMPN).
   !> New results are appended, so that OUT(1..8) keeps its meaning.
   pure function outcome_array(outcome, count) result(out)
      !> Outcome of `impact`
      type(outcome_type), intent(in) :: outcome
      !> How many of the results, 1 .. n_outputs
      integer, intent(in) :: count
      !> The first `count` results
      real(wp) :: out(count)
      real(wp) :: all(n_outputs)
      all = [outcome%restitution, outcome%energy_loss_ratio, outcome%rebound_velocity, &
         & outcome%max_compression, outcome%peak_force, outcome%compression_at_peak_force, &
         & outcome%compression_time, outcome%contact_time, outcome%time_at_peak_force]
      out = all(1:count)
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
