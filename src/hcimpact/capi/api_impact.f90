! SPDX-License-Identifier: Apache-2.0
!> C interface of one impact: `hcimpact_impact`.
!>
!> Declared in include/hcimpact.h (text in doc/impact-c-api.h.txt); the physics is in
!> hcimpact_impact_model, the structures and their conversions in hcimpact_capi_types.
module hcimpact_api_impact
   use, intrinsic :: iso_c_binding, only : c_int, c_ptr, c_associated, c_f_pointer
   use hcimpact_status, only : hcimpact_err_null
   use hcimpact_impact_model, only : outcome_type, impact
   use hcimpact_capi_types, only : hcimpact_contact, hcimpact_outcome, to_contact, from_outcome
   implicit none
   private

   public :: c_impact

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
      call impact(to_contact(c_in), result, status)
      c_out = from_outcome(result)
      stat = int(status, c_int)
   end function c_impact

end module hcimpact_api_impact
