! SPDX-License-Identifier: Apache-2.0
!> The namelist group `&bodies` of a scene file: a system of bodies on a line, one
!> value per body or per neighbouring pair in lists (doc/scenes.md).
!>
!> Its names (mass, radius, young, ...) are lists here, while the same names are
!> single values in `&body1` and `&contact`: a namelist object is a variable of the
!> scoping unit that declares the group, so `&bodies` has a module of its own. The
!> scene reader (hcimpact_scene_reader) scans the file, reads the group through
!> `read_bodies` and checks the values.
module hcimpact_scene_bodies
   use, intrinsic :: ieee_exceptions, only : ieee_get_halting_mode, ieee_set_halting_mode, &
      & ieee_set_flag, ieee_usual
   use hcimpact_kinds, only : wp
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_scene_model, only : unset_bits, max_bodies
   implicit none
   private

   public :: read_bodies, bodies_text_length
   public :: mass, radius, density, young, poisson, velocity, gap, stiffness, exponent, b, &
      & restitution, at_speed, gravity, t_end, rtol, method, integrator

   !> The mark of a real not given (hcimpact_scene_model's unset_bits)
   real(wp), parameter :: unset = transfer(unset_bits, 1.0_wp)

   !> Length of the text values (method, integrator); one that fills it is refused
   integer, parameter :: bodies_text_length = 64

   !> One value per body
   real(wp) :: mass(max_bodies), radius(max_bodies), density(max_bodies), &
      & young(max_bodies), poisson(max_bodies), velocity(max_bodies)
   !> One value per neighbouring pair (or one for all)
   real(wp) :: gap(max_bodies), stiffness(max_bodies), exponent(max_bodies), &
      & b(max_bodies), restitution(max_bodies), at_speed(max_bodies)
   !> The whole system
   real(wp) :: gravity, t_end, rtol
   character(len=bodies_text_length) :: method, integrator

   namelist /bodies/ mass, radius, density, young, poisson, velocity, gap, stiffness, &
      & exponent, b, restitution, at_speed, gravity, t_end, rtol, method, integrator

contains

   !> Read `&bodies` from the records `rec` with the compiler's namelist reader, every
   !> variable first set to "not given". As for the other groups, the floating-point
   !> traps are held off while the reader converts numbers (1e999 raises overflow in
   !> strtod and reads as inf, which the checks refuse) and its flags are cleared.
   subroutine read_bodies(rec, ios, msg)
      character(len=*), intent(in) :: rec(:)
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      logical :: halting(size(ieee_usual))
      mass = unset
      radius = unset
      density = unset
      young = unset
      poisson = unset
      velocity = unset
      gap = unset
      stiffness = unset
      exponent = unset
      b = unset
      restitution = unset
      at_speed = unset
      gravity = unset
      t_end = unset
      rtol = unset
      method = ""
      integrator = ""
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      read(rec, nml=bodies, iostat=ios, iomsg=msg)
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
   end subroutine read_bodies

end module hcimpact_scene_bodies
