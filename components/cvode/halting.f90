! SPDX-License-Identifier: Apache-2.0
!> Floating-point halting around CVODE, for every integrator of the component.
!>
!> CVODE's C code is not written for trapping floating-point exceptions: a diverging
!> Newton iterate may overflow its weighted norms, which it treats as a convergence
!> failure (a smaller step). A caller that traps exceptions (a Debug build with
!> -ffpe-trap) would be killed there, so halting is off while CVODE runs
!> (`halting_suspend` ... `halting_resume`), and each callback switches the caller's
!> halting back on for our own code (`callback_enter` ... `callback_leave`), so traps
!> still catch our own bugs.
module hcimpact_cvode_halting
   use, intrinsic :: ieee_exceptions, only : ieee_flag_type, ieee_overflow, ieee_invalid, &
      & ieee_divide_by_zero, ieee_get_halting_mode, ieee_set_halting_mode, ieee_get_flag, &
      & ieee_set_flag, ieee_support_halting
   implicit none
   private

   public :: halting_suspend, halting_resume, callback_enter, callback_leave

   !> The exceptions a caller may trap
   type(ieee_flag_type), parameter :: trapped(3) = [ieee_overflow, ieee_invalid, &
      & ieee_divide_by_zero]

contains

   !> Before CVODE runs: the caller's halting modes into `halting`, halting off.
   subroutine halting_suspend(halting)
      logical, intent(out) :: halting(3)
      halting = .false.
      if (ieee_support_halting(ieee_overflow) .and. ieee_support_halting(ieee_invalid) &
         & .and. ieee_support_halting(ieee_divide_by_zero)) then
         call ieee_get_halting_mode(trapped, halting)
         call ieee_set_halting_mode(trapped, .false.)
      end if
   end subroutine halting_suspend

   !> After CVODE: the flags it raised cleared and the caller's halting modes back.
   subroutine halting_resume(halting)
      logical, intent(in) :: halting(3)
      if (any(halting)) then
         call ieee_set_flag(trapped, .false.)
         call ieee_set_halting_mode(trapped, halting)
      end if
   end subroutine halting_resume

   !> In a callback: the caller's halting modes back on, with the flags CVODE may have
   !> raised set aside in `flags` (unmasking a raised flag could trap at once).
   subroutine callback_enter(halting, flags)
      logical, intent(in) :: halting(3)
      logical, intent(out) :: flags(3)
      flags = .false.
      if (.not. any(halting)) return
      call ieee_get_flag(trapped, flags)
      call ieee_set_flag(trapped, .false.)
      call ieee_set_halting_mode(trapped, halting)
   end subroutine callback_enter

   !> Leaving a callback: halting off again for CVODE, its flags restored.
   subroutine callback_leave(halting, flags)
      logical, intent(in) :: halting(3), flags(3)
      if (.not. any(halting)) return
      call ieee_set_halting_mode(trapped, .false.)
      call ieee_set_flag(trapped, flags)
   end subroutine callback_leave

end module hcimpact_cvode_halting
