! SPDX-License-Identifier: Apache-2.0
!> A contact and an impact's outcome as columns of doubles, and back: the one layout of
!> them that the sweeps hand to other MPI ranks (component hcimpact::mpi) and write to
!> their checkpoints (the scene runner). Every field travels as the double it is; the
!> evaluation counts and the status, integers far below 2^53, as exact doubles, so
!> that the round trip gives back the same bits.
module hcimpact_impact_values
   use hcimpact_kinds, only : wp, ik
   use hcimpact_contact, only : contact_type, outcome_type
   implicit none
   private

   public :: contact_values_size, outcome_values_size
   public :: contact_values, values_contact, outcome_values, values_outcome

   !> Doubles of a contact: mass, stiffness, exponent, damping, velocity
   integer, parameter :: contact_values_size = 5
   !> Doubles of an outcome and its status: the nine outputs in the order of
   !> outcome_type, the three evaluation counts, the status
   integer, parameter :: outcome_values_size = 13

contains

   !> The doubles of a contact
   pure function contact_values(contact) result(values)
      type(contact_type), intent(in) :: contact
      real(wp) :: values(contact_values_size)
      values = [contact%mass, contact%stiffness, contact%exponent, contact%damping, &
         & contact%velocity]
   end function contact_values

   !> The contact of its doubles (contact_values)
   pure function values_contact(values) result(contact)
      real(wp), intent(in) :: values(:)
      type(contact_type) :: contact
      contact = contact_type(mass=values(1), stiffness=values(2), exponent=values(3), &
         & damping=values(4), velocity=values(5))
   end function values_contact

   !> The doubles of an outcome and its status
   pure function outcome_values(out, stat) result(values)
      type(outcome_type), intent(in) :: out
      integer, intent(in) :: stat
      real(wp) :: values(outcome_values_size)
      values = [out%restitution, out%energy_loss_ratio, out%rebound_velocity, &
         & out%max_compression, out%peak_force, out%compression_at_peak_force, &
         & out%time_at_peak_force, out%compression_time, out%contact_time, &
         & real(out%evaluations, wp), real(stat, wp)]
   end function outcome_values

   !> The outcome and status of their doubles (outcome_values)
   pure subroutine values_outcome(values, out, stat)
      real(wp), intent(in) :: values(:)
      type(outcome_type), intent(out) :: out
      integer, intent(out) :: stat
      out%restitution = values(1)
      out%energy_loss_ratio = values(2)
      out%rebound_velocity = values(3)
      out%max_compression = values(4)
      out%peak_force = values(5)
      out%compression_at_peak_force = values(6)
      out%time_at_peak_force = values(7)
      out%compression_time = values(8)
      out%contact_time = values(9)
      out%evaluations = int(values(10:12), ik)
      stat = nint(values(13))
   end subroutine values_outcome

end module hcimpact_impact_values
