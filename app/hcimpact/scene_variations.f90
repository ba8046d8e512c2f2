! SPDX-License-Identifier: Apache-2.0
!> The namelist groups `&system_sweep` and `&impact_sweep` of a scene file: the
!> variations of a system of bodies that the output `system_sweep` runs, each a whole
!> run of the system, and the parameter sets of one impact that the output
!> `impact_sweep` computes (doc/scenes.md). Their names (`gap`, `b`, `mass`, ...) are
!> lists here and single values in the other groups: a namelist object is a variable
!> of the scoping unit that declares the group, so the groups have a module of their
!> own, like `&bodies` (hcimpact_scene_bodies). The scene reader reads them through
!> `read_variations` and checks the values; `variation_index` says which value of each
!> list a variation takes, for both.
module hcimpact_scene_variations
   use, intrinsic :: ieee_exceptions, only : ieee_get_halting_mode, ieee_set_halting_mode, &
      & ieee_set_flag, ieee_usual
   use hcimpact_kinds, only : wp
   use hcimpact_scene_model, only : unset_bits, max_bodies
   implicit none
   private

   public :: read_variations, max_variations, variations_text_length, variation_index, &
      & variation_count
   public :: striker_speed, gap, b, combine, mass, stiffness, exponent, speed, restitution, &
      & gravity, at_speed, mass_body, left_gap, right_gap, left_b, right_b, &
      & left_stiffness, right_stiffness, left_exponent, right_exponent, t_end, striker_body

   !> Most values of one list
   integer, parameter :: max_variations = 1000
   !> Length of the text value (combine); one that fills it is refused
   integer, parameter :: variations_text_length = 64
   !> The mark of a real not given (hcimpact_scene_model's unset_bits)
   real(wp), parameter :: unset = transfer(unset_bits, 1.0_wp)

   !> A system's sweep: the speeds of body 1 (m/s), the gaps of every pair (m), the
   !> damping of every pair (s/m), the restitutions of every pair at the speed at_speed
   !> (m/s), gravity (m/s^2), the gaps of the left and the right wall to their end body
   !> (m), their damping (s/m), contact constants (N/m^n) and exponents, the end times
   !> (s), and
   !> (with stiffness and exponent
   !> below, every pair's) the masses of the bodies mass_body (kg, `mass` below); the
   !> speeds are those of the bodies striker_body (lists of indices, 0 alone: every
   !> body; default body 1; read as reals, so that "not given" is a mark no file can
   !> write, and checked to be whole numbers by the reader)
   real(wp) :: striker_speed(max_variations), gap(max_variations), b(max_variations), &
      & restitution(max_variations), gravity(max_variations), at_speed, &
      & left_gap(max_variations), right_gap(max_variations), left_b(max_variations), &
      & right_b(max_variations), left_stiffness(max_variations), &
      & right_stiffness(max_variations), left_exponent(max_variations), &
      & right_exponent(max_variations), t_end(max_variations)
   real(wp) :: mass_body(max_bodies), striker_body(max_bodies)
   !> "product" (every combination) or "list" (the lists side by side)
   character(len=variations_text_length) :: combine

   !> The effective masses (kg), stiffnesses (N/m^n), exponents and approach speeds
   !> (m/s) of one impact (its damping is `b`); of a system, the masses of one body and
   !> every pair's stiffness and exponent
   real(wp) :: mass(max_variations), stiffness(max_variations), exponent(max_variations), &
      & speed(max_variations)

   namelist /system_sweep/ striker_speed, striker_body, mass, mass_body, gap, stiffness, &
      & exponent, b, restitution, at_speed, gravity, left_gap, right_gap, left_b, right_b, &
      & left_stiffness, right_stiffness, left_exponent, right_exponent, t_end, combine
   namelist /impact_sweep/ mass, stiffness, exponent, b, speed, combine

contains

   !> Read `&system_sweep` (or `&impact_sweep` when `impacts`) from the records `rec`
   !> with the compiler's namelist reader, every variable first set to "not given"; the
   !> floating-point traps held off while it converts numbers, as for the other groups.
   subroutine read_variations(rec, impacts, ios, msg)
      character(len=*), intent(in) :: rec(:)
      logical, intent(in) :: impacts
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      logical :: halting(size(ieee_usual))
      striker_speed = unset
      gap = unset
      b = unset
      mass = unset
      stiffness = unset
      exponent = unset
      speed = unset
      restitution = unset
      gravity = unset
      left_gap = unset
      right_gap = unset
      left_b = unset
      right_b = unset
      left_stiffness = unset
      right_stiffness = unset
      left_exponent = unset
      right_exponent = unset
      t_end = unset
      at_speed = unset
      mass_body = unset
      striker_body = unset
      combine = ""
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      if (impacts) then
         read(rec, nml=impact_sweep, iostat=ios, iomsg=msg)
      else
         read(rec, nml=system_sweep, iostat=ios, iomsg=msg)
      end if
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
   end subroutine read_variations

   !> How many variations lists `lengths` long give (0: not varied): their product, or
   !> the longest side by side (1 with none).
   pure integer function variation_count(lengths, every_combination) result(items)
      integer, intent(in) :: lengths(:)
      !> A product of the lists (else side by side)
      logical, intent(in) :: every_combination
      if (every_combination) then
         items = product(max(lengths, 1))
      else
         items = max(maxval(lengths, 1), 1)
      end if
   end function variation_count

   !> Which value of each list variation `k` takes, the lists `lengths` long (0: not
   !> varied, index 1): every combination in a product (the first list varies slowest),
   !> the k-th of each in a list.
   pure function variation_index(lengths, every_combination, k) result(index)
      integer, intent(in) :: lengths(:)
      !> A product of the lists (else side by side)
      logical, intent(in) :: every_combination
      integer, intent(in) :: k
      integer :: index(size(lengths))
      integer :: rest, j
      if (.not. every_combination) then
         index = k
         where (lengths == 0) index = 1
         return
      end if
      rest = k - 1
      do j = size(lengths), 1, -1
         index(j) = modulo(rest, max(lengths(j), 1)) + 1
         rest = rest / max(lengths(j), 1)
      end do
   end function variation_index

end module hcimpact_scene_variations
