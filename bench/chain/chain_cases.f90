! SPDX-License-Identifier: Apache-2.0
!> The systems of the chain benchmarks (doc/chains-bench.md), in one place: the struck
!> chain of touching Hertz beads, the dilute systems with gaps between two walls, and
!> the dilute row of beads with random speeds.
!> The SciPy script reads the struck chain's parameters from the state files that
!> bench_chain writes, so they are defined here only.
module bench_chain_cases
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact, only : wp, hertz_constant, contact_law, chain_type
   implicit none
   private

   public :: bead_mass, bead_stiffness, wall_stiffness, striker_speed
   public :: struck_chain, dilute_case, n_dilute, dilute_names, dilute_t_end, dilute_row

   !> Steel beads: radius 5 mm, E = 200 GPa, nu = 0.3, density 7800 kg/m^3
   real(wp), parameter :: bead_radius = 5.0e-3_wp, young = 2.0e11_wp, poisson = 0.3_wp, &
      & density = 7800.0_wp
   !> Speed of the striker (the first bead) in m/s
   real(wp), parameter :: striker_speed = 1.0_wp
   !> Gaps of the dilute systems (between balls, and to the walls), m
   real(wp), parameter :: dilute_gap = 1.0e-3_wp
   !> Damping of the dissipative dilute systems, s/m (restitution 0.987 at 1 m/s)
   real(wp), parameter :: dilute_damping = 0.02_wp

   !> The dilute systems: one ball between two walls (dissipative); a horizontal
   !> Newton's cradle of five balls with gaps between two walls, dissipative and elastic
   integer, parameter :: n_dilute = 3
   character(len=*), parameter :: dilute_names(n_dilute) = [character(len=16) :: &
      & "ball_walls", "cradle_gaps", "cradle_elastic"]
   !> Their end times, s
   real(wp), parameter :: dilute_t_end(n_dilute) = [0.5_wp, 0.5_wp, 0.5_wp]

contains

   !> Mass of a bead, kg
   pure real(wp) function bead_mass()
      bead_mass = density * (4.0_wp / 3.0_wp) * acos(-1.0_wp) * bead_radius**3
   end function bead_mass

   !> Hertz constant of two beads, N/m^1.5
   elemental real(wp) function bead_stiffness()
      bead_stiffness = hertz_constant(young, poisson, bead_radius, young, poisson, &
         & bead_radius)
   end function bead_stiffness

   !> Hertz constant of a bead on a flat steel wall, N/m^1.5
   elemental real(wp) function wall_stiffness()
      wall_stiffness = hertz_constant(young, poisson, bead_radius, young, poisson, &
         & ieee_value(1.0_wp, ieee_positive_inf))
   end function wall_stiffness

   !> A chain of n touching beads (gaps 0, no preload; or the gap given between every
   !> pair, m), elastic (b = 0), no walls; the first bead moves at striker_speed
   !> towards the others, which are at rest.
   subroutine struck_chain(n, chain, gap)
      integer, intent(in) :: n
      type(chain_type), intent(out) :: chain
      real(wp), intent(in), optional :: gap
      allocate(chain%mass(n), chain%velocity(n), chain%gap(n - 1), chain%law(n - 1))
      chain%mass = bead_mass()
      chain%velocity = 0.0_wp
      chain%velocity(1) = striker_speed
      chain%gap = 0.0_wp
      if (present(gap)) chain%gap = gap
      chain%law = contact_law(stiffness=bead_stiffness(), exponent=1.5_wp, damping=0.0_wp)
   end subroutine struck_chain

   !> Dilute system k (dilute_names): balls with gaps dilute_gap between them and to
   !> both walls, the first ball moving at striker_speed to the right, g = 0.
   subroutine dilute_case(k, chain)
      integer, intent(in) :: k
      type(chain_type), intent(out) :: chain
      integer :: n
      real(wp) :: damping
      n = 5
      if (k == 1) n = 1
      damping = dilute_damping
      if (k == 3) damping = 0.0_wp
      allocate(chain%mass(n), chain%velocity(n), chain%gap(n - 1), chain%law(n - 1))
      chain%mass = bead_mass()
      chain%velocity = 0.0_wp
      chain%velocity(1) = striker_speed
      chain%gap = dilute_gap
      chain%law = contact_law(stiffness=bead_stiffness(), exponent=1.5_wp, damping=damping)
      chain%left_wall = .true.
      chain%right_wall = .true.
      chain%left_law = contact_law(stiffness=wall_stiffness(), exponent=1.5_wp, &
         & damping=damping)
      chain%right_law = chain%left_law
      chain%left_gap = dilute_gap
      chain%right_gap = dilute_gap
   end subroutine dilute_case

   !> The dilute row: n beads, their speeds uniform in [-1, 1] m/s, the gaps between
   !> them log-uniform in [1, 10] mm, dissipative (dilute_damping), no walls, g = 0;
   !> drawn by a fixed generator (xorshift64 from `seed`, not 0), the same on every
   !> machine.
   subroutine dilute_row(n, seed, chain)
      integer, intent(in) :: n
      integer(int64), intent(in) :: seed
      type(chain_type), intent(out) :: chain
      integer(int64) :: state
      integer :: i
      real(wp) :: dummy
      allocate(chain%mass(n), chain%velocity(n), chain%gap(n - 1), chain%law(n - 1))
      state = seed
      do i = 1, 8
         ! (nearby seeds give nearby first numbers)
         dummy = uniform(state)
      end do
      chain%mass = bead_mass()
      do i = 1, n
         chain%velocity(i) = 2.0_wp * uniform(state) - 1.0_wp
      end do
      do i = 1, n - 1
         chain%gap(i) = 1.0e-3_wp * 10.0_wp**uniform(state)
      end do
      chain%law = contact_law(stiffness=bead_stiffness(), exponent=1.5_wp, &
         & damping=dilute_damping)
   end subroutine dilute_row

   !> A number uniform in [0, 1) from a xorshift64 generator's state (shifts and
   !> exclusive ors only: no integer overflow)
   real(wp) function uniform(state)
      integer(int64), intent(inout) :: state
      state = ieor(state, shiftl(state, 13))
      state = ieor(state, shiftr(state, 7))
      state = ieor(state, shiftl(state, 17))
      uniform = real(shiftr(state, 11), wp) * 2.0_wp**(-53)
   end function uniform

end module bench_chain_cases
