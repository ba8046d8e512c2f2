! SPDX-License-Identifier: Apache-2.0
!> C interface of one impact: `hcimpact_impact` and the structures it exchanges.
!>
!> Declared in include/hcimpact.h (text in doc/impact-c-api.h.txt); the physics is in
!> hcimpact_impact_model. The structures mirror the C ones field by field (bind(C)).
module hcimpact_api_impact
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_ptr, c_associated, c_f_pointer
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_err_null
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   implicit none
   private

   public :: hcimpact_contact, hcimpact_outcome, c_impact

   !> typedef struct { double mass, stiffness, exponent, damping, velocity; } hcimpact_contact;
   type, bind(C) :: hcimpact_contact
      !> Mass in kg (effective mass for two bodies), > 0
      real(c_double) :: mass
      !> Contact constant c in N/m^n, > 0
      real(c_double) :: stiffness
      !> Exponent n of the elastic law f = c x^n, > 0
      real(c_double) :: exponent
      !> Damping constant b in s/m, >= 0
      real(c_double) :: damping
      !> Approach speed V in m/s, > 0
      real(c_double) :: velocity
   end type hcimpact_contact

   !> typedef struct { double restitution, energy_loss_ratio, rebound_velocity,
   !> max_compression, peak_force, compression_at_peak_force, compression_time,
   !> contact_time; } hcimpact_outcome;
   type, bind(C) :: hcimpact_outcome
      !> Coefficient of restitution k
      real(c_double) :: restitution
      !> 1 - k^2
      real(c_double) :: energy_loss_ratio
      !> -k V in m/s (negative)
      real(c_double) :: rebound_velocity
      !> Maximum compression in m
      real(c_double) :: max_compression
      !> Peak contact force in N
      real(c_double) :: peak_force
      !> Compression at the peak force in m
      real(c_double) :: compression_at_peak_force
      !> Time from impact to maximum compression in s
      real(c_double) :: compression_time
      !> Duration of the contact in s
      real(c_double) :: contact_time
   end type hcimpact_outcome

contains

   !> int hcimpact_impact(const hcimpact_contact *contact, hcimpact_outcome *outcome);
   !>
   !> Returns 0 on success, HCIMPACT_ERR_NULL (10) if a pointer is NULL (nothing is
   !> written), or another status of hcimpact_status; on any error but NULL the
   !> outcome holds NaN in every field.
   function c_impact(contact, outcome) result(stat) bind(C, name="hcimpact_impact")
      !> const hcimpact_contact *
      type(c_ptr), value :: contact
      !> hcimpact_outcome *
      type(c_ptr), value :: outcome
      !> Status
      integer(c_int) :: stat
      type(hcimpact_contact), pointer :: c_in
      type(hcimpact_outcome), pointer :: c_out
      type(outcome_type) :: result
      integer :: status

      if (.not. (c_associated(contact) .and. c_associated(outcome))) then
         stat = int(hcimpact_err_null, c_int)
         return
      end if
      call c_f_pointer(contact, c_in)
      call c_f_pointer(outcome, c_out)
      call impact(contact_type(mass=real(c_in%mass, wp), stiffness=real(c_in%stiffness, wp), &
         & exponent=real(c_in%exponent, wp), damping=real(c_in%damping, wp), &
         & velocity=real(c_in%velocity, wp)), result, status)
      c_out%restitution = result%restitution
      c_out%energy_loss_ratio = result%energy_loss_ratio
      c_out%rebound_velocity = result%rebound_velocity
      c_out%max_compression = result%max_compression
      c_out%peak_force = result%peak_force
      c_out%compression_at_peak_force = result%compression_at_peak_force
      c_out%compression_time = result%compression_time
      c_out%contact_time = result%contact_time
      stat = int(status, c_int)
   end function c_impact

end module hcimpact_api_impact
