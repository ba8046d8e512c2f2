! SPDX-License-Identifier: Apache-2.0
!> The C structures of the C interface (include/hcimpact.h) and their one pair of
!> conversions to and from the Fortran types.
!>
!> Every C entry point that takes a `hcimpact_contact` or fills a `hcimpact_outcome`
!> (the core's, the CVODE component's) converts through `to_contact` and
!> `from_outcome`, so a field added to the outcome is a change here and in the header.
!> The layout must match the header's field by field: test/api checks it from C, and
!> the Python package checks its own view against the header.
module hcimpact_capi_types
   use, intrinsic :: iso_c_binding, only : c_double
   use hcimpact_kinds, only : wp
   use hcimpact_contact, only : contact_type, outcome_type
   use hcimpact_force_element, only : contact_force_type
   implicit none
   private

   public :: hcimpact_contact, hcimpact_outcome, to_contact, from_outcome
   public :: hcimpact_force, from_force

   !> typedef struct { double mass, stiffness, exponent, damping, velocity; } hcimpact_contact;
   type, bind(C) :: hcimpact_contact
      !> Mass in kg (effective mass for two bodies), > 0
      real(c_double) :: mass
      !> Contact constant c in N/m^n, > 0
      real(c_double) :: stiffness
      !> Exponent n of the elastic law f = c x^n, >= 1e-6
      real(c_double) :: exponent
      !> Damping constant b in s/m, >= 0
      real(c_double) :: damping
      !> Approach speed V in m/s, > 0
      real(c_double) :: velocity
   end type hcimpact_contact

   !> typedef struct { double restitution, energy_loss_ratio, rebound_velocity,
   !> max_compression, peak_force, compression_at_peak_force, time_at_peak_force,
   !> compression_time, contact_time; } hcimpact_outcome;
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
      !> Time from the start of contact to the peak force in s
      real(c_double) :: time_at_peak_force
      !> Time from impact to maximum compression in s
      real(c_double) :: compression_time
      !> Duration of the contact in s
      real(c_double) :: contact_time
   end type hcimpact_outcome

   !> typedef struct { double force, dforce_dx, dforce_dv, potential, dissipation; }
   !> hcimpact_force;
   type, bind(C) :: hcimpact_force
      !> Contact force F in N (>= 0)
      real(c_double) :: force
      !> dF/dx in N/m
      real(c_double) :: dforce_dx
      !> dF/dv in N s/m
      real(c_double) :: dforce_dv
      !> Elastic potential energy in J
      real(c_double) :: potential
      !> Dissipated power in W (>= 0)
      real(c_double) :: dissipation
   end type hcimpact_force

contains

   !> The Fortran contact of a C one.
   elemental function to_contact(c) result(contact)
      !> C structure
      type(hcimpact_contact), intent(in) :: c
      !> Fortran type
      type(contact_type) :: contact
      contact = contact_type(mass=real(c%mass, wp), stiffness=real(c%stiffness, wp), &
         & exponent=real(c%exponent, wp), damping=real(c%damping, wp), &
         & velocity=real(c%velocity, wp))
   end function to_contact

   !> The C outcome of a Fortran one (every field but the evaluation counts).
   elemental function from_outcome(outcome) result(c)
      !> Fortran type
      type(outcome_type), intent(in) :: outcome
      !> C structure
      type(hcimpact_outcome) :: c
      c%restitution = outcome%restitution
      c%energy_loss_ratio = outcome%energy_loss_ratio
      c%rebound_velocity = outcome%rebound_velocity
      c%max_compression = outcome%max_compression
      c%peak_force = outcome%peak_force
      c%compression_at_peak_force = outcome%compression_at_peak_force
      c%time_at_peak_force = outcome%time_at_peak_force
      c%compression_time = outcome%compression_time
      c%contact_time = outcome%contact_time
   end function from_outcome

   !> The C element of a Fortran one.
   elemental function from_force(element) result(c)
      !> Fortran type
      type(contact_force_type), intent(in) :: element
      !> C structure
      type(hcimpact_force) :: c
      c%force = element%force
      c%dforce_dx = element%dforce_dx
      c%dforce_dv = element%dforce_dv
      c%potential = element%potential
      c%dissipation = element%dissipation
   end function from_force

end module hcimpact_capi_types
