! SPDX-License-Identifier: Apache-2.0
!> The namelist group `&system_sweep` of a scene file: the variations of a system of
!> bodies that the output `system_sweep` runs, each a whole run of the system
!> (doc/scenes.md). Its names `gap` and `b` are lists here and single values in the
!> walls' groups: a namelist object is a variable of the scoping unit that declares
!> the group, so the group has a module of its own, like `&bodies`
!> (hcimpact_scene_bodies). The scene reader reads it through `read_variations` and
!> checks the values.
module hcimpact_scene_variations
   use, intrinsic :: ieee_exceptions, only : ieee_get_halting_mode, ieee_set_halting_mode, &
      & ieee_set_flag, ieee_usual
   use hcimpact_kinds, only : wp
   use hcimpact_scene_model, only : unset_bits
   implicit none
   private

   public :: read_variations, max_variations, variations_text_length
   public :: striker_speed, gap, b, combine

   !> Most values of one list
   integer, parameter :: max_variations = 1000
   !> Length of the text value (combine); one that fills it is refused
   integer, parameter :: variations_text_length = 64
   !> The mark of a real not given (hcimpact_scene_model's unset_bits)
   real(wp), parameter :: unset = transfer(unset_bits, 1.0_wp)

   !> The speeds of body 1 (m/s), the gaps of every pair (m), the damping of every
   !> pair (s/m)
   real(wp) :: striker_speed(max_variations), gap(max_variations), b(max_variations)
   !> "product" (every combination) or "list" (the lists side by side)
   character(len=variations_text_length) :: combine

   namelist /system_sweep/ striker_speed, gap, b, combine

contains

   !> Read `&system_sweep` from the records `rec` with the compiler's namelist reader,
   !> every variable first set to "not given"; the floating-point traps held off while
   !> it converts numbers, as for the other groups.
   subroutine read_variations(rec, ios, msg)
      character(len=*), intent(in) :: rec(:)
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      logical :: halting(size(ieee_usual))
      striker_speed = unset
      gap = unset
      b = unset
      combine = ""
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      read(rec, nml=system_sweep, iostat=ios, iomsg=msg)
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
   end subroutine read_variations

end module hcimpact_scene_variations
