! SPDX-License-Identifier: Apache-2.0
!> A small deterministic random number generator for the calibration tests.
!>
!> L'Ecuyer's combined multiplicative congruential generator (P. L'Ecuyer, "Efficient
!> and portable combined random number generators", Comm. ACM 31, 742-751, 1988):
!> period about 2.3e18, every product below 2^47, so plain 64-bit integer arithmetic
!> never overflows. The same seed gives the same numbers on every machine and
!> compiler, unlike `random_number` with its processor-dependent seeding. Normal
!> deviates by the Box-Muller transform.
module hcimpact_rng
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: rng_type, new_rng, uniform, normal

   !> State of the generator
   type :: rng_type
      !> The two component generators' states
      integer(int64) :: s1 = 1_int64, s2 = 1_int64
   end type rng_type

   integer(int64), parameter :: m1 = 2147483563_int64, a1 = 40014_int64
   integer(int64), parameter :: m2 = 2147483399_int64, a2 = 40692_int64

contains

   !> A generator started from `seed` (any integer; different seeds give different
   !> streams).
   function new_rng(seed) result(rng)
      !> Seed
      integer, intent(in) :: seed
      !> The generator
      type(rng_type) :: rng
      integer :: i
      real(wp) :: discard
      rng%s1 = 1_int64 + modulo(int(seed, int64) * 7919_int64 + 12345_int64, m1 - 1_int64)
      rng%s2 = 1_int64 + modulo(int(seed, int64) * 104729_int64 + 54321_int64, m2 - 1_int64)
      ! move away from the correlated start of nearby seeds
      do i = 1, 10
         discard = uniform(rng)
      end do
   end function new_rng

   !> A uniform deviate in (0, 1).
   function uniform(rng) result(u)
      !> The generator
      type(rng_type), intent(inout) :: rng
      !> The deviate
      real(wp) :: u
      integer(int64) :: z
      rng%s1 = modulo(a1 * rng%s1, m1)
      rng%s2 = modulo(a2 * rng%s2, m2)
      z = rng%s1 - rng%s2
      if (z < 1_int64) z = z + (m1 - 1_int64)
      u = real(z, wp) / real(m1, wp)
   end function uniform

   !> A standard normal deviate (Box-Muller).
   function normal(rng) result(z)
      !> The generator
      type(rng_type), intent(inout) :: rng
      !> The deviate
      real(wp) :: z
      real(wp), parameter :: two_pi = 6.283185307179586476925286766559_wp
      real(wp) :: u1, u2
      u1 = uniform(rng)
      u2 = uniform(rng)
      z = sqrt(-2.0_wp * log(u1)) * cos(two_pi * u2)
   end function normal

end module hcimpact_rng
