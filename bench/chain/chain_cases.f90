! SPDX-License-Identifier: Apache-2.0
!> The systems of the chain benchmarks (doc/chains-bench.md), in one place: the struck
!> chain of touching Hertz beads and the dilute systems with gaps between two walls.
!> The SciPy script reads the struck chain's parameters from the state files that
!> bench_chain writes, so they are defined here only.
module bench_chain_cases
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf
   use hcimpact, only : wp, hertz_constant, contact_law, chain_type
   implicit none
   private

   public :: bead_mass, bead_stiffness, wall_stiffness, striker_speed
   public :: struck_chain, dilute_case, n_dilute, dilute_names, dilute_t_end

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

end module bench_chain_cases
