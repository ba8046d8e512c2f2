! SPDX-License-Identifier: Apache-2.0
!> One rank's block of the distributed chain (doc/mpi.md): a contiguous run of beads,
!> the exchange of its boundary beads with the neighbouring ranks, and its part of the
!> right-hand side.
!>
!> The beads 1 .. n are cut into blocks of consecutive beads, one per rank in rank
!> order, the sizes differing by at most one. A rank's state is that of its m beads in
!> the layout of the serial chain's regions (hcimpact_cvode_chain_system): per bead k,
!> its displacement u_k, velocity v_k and e_k, the energy dissipated so far in the pair
!> on its left; 3 m values. The pair between two blocks is thus owned by the block on
!> its right, and every pair by exactly one rank.
!>
!> The force on a boundary bead needs the displacement and velocity of the first bead
!> of the block on the right and of the last bead of the block on the left: before
!> each evaluation of the right-hand side, `exchange_halo` trades these (2 doubles
!> each way per neighbour, MPI_Sendrecv). The right-hand side itself is that of the
!> serial chain (`region_rhs`) on a region made of the block and the one or two
!> neighbouring beads (halo beads): the same contact-force element and the same
!> arithmetic, whose rows for the halo beads are dropped.
!>
!> Walls: the first rank's region has the left wall in its slot 0, the last rank's the
!> right wall in its last slot (`part_region`). The right wall's dissipated energy is
!> the one value of the serial region's layout after the beads' (e_(m+1)): the last
!> rank's block then holds 3 m + 1 values of that layout (`n_motion`). After them comes
!> the impulse each wall the block holds has given the chain so far (J_left on the
!> first rank, then J_right on the last; J_left' = F_0, J_right' = -F_n, the rows of
!> the serial region's `impulse_index`), so that the walls' impulses are results of
!> the integration and the momentum's balance can be formed (doc/mpi.md).
module hcimpact_mpi_chain_block
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_value, ieee_quiet_nan
   use mpi_f08, only : MPI_Comm, MPI_Sendrecv, MPI_DOUBLE_PRECISION, MPI_PROC_NULL, &
      & MPI_STATUS_IGNORE, MPI_Comm_rank, MPI_Comm_size
   use hcimpact_kinds, only : wp
   use hcimpact_chain_types, only : chain_type, kinetic_energy
   use hcimpact_force_element, only : contact_force_type
   use hcimpact_cvode_chain_system, only : chain_region, region_size, region_rhs, &
      & slot_state, slot_none, slot_pair, slot_left_wall, slot_right_wall, impulse_index
   implicit none
   private

   public :: chain_block, block_partition, block_setup, exchange_halo, block_rhs
   public :: part_region, region_energy
   public :: halo_doubles

   !> Doubles sent to each neighbour per exchange: the displacement and velocity of one
   !> boundary bead
   integer, parameter :: halo_doubles = 2

   !> Message tags of the two directions
   integer, parameter :: tag_to_left = 11, tag_to_right = 12

   !> A rank's block and what its callbacks need
   type :: chain_block
      !> The communicator, this rank and the number of ranks
      type(MPI_Comm) :: comm
      integer :: rank = 0, n_ranks = 1
      !> The global number of beads, the first bead of the block and its size m; the
      !> number of values of the block's state (3 m, 3 m + 1 with the right wall) and
      !> of the whole chain's
      integer :: n = 0, first = 1, m = 0, n_local = 0, n_global = 0
      !> The values of the serial region's layout in the block's state (3 m, 3 m + 1
      !> with the right wall), and where the block's state holds the impulse of the
      !> left (1) and right (2) wall (0: not in this block)
      integer :: n_motion = 0, impulse(2) = 0
      !> The neighbouring ranks (MPI_PROC_NULL at an end of the chain)
      integer :: left = MPI_PROC_NULL, right = MPI_PROC_NULL
      !> Halo beads in the region: 1 if there is a neighbour on that side, else 0
      integer :: n_left = 0, n_right = 0
      !> The region: halo beads, the block's beads (hcimpact_cvode_chain_system)
      type(chain_region) :: region
      !> The region's state and its derivative (halo beads: exchanged values, e = 0)
      real(wp), allocatable :: y_region(:), dy_region(:)
      !> Displacement and velocity of the halo beads, from the last exchange
      real(wp) :: halo_left(halo_doubles) = 0.0_wp, halo_right(halo_doubles) = 0.0_wp
      !> Exchanges done (each: one MPI_Sendrecv per direction)
      integer(int64) :: exchanges = 0
   end type chain_block

contains

   !> The block of `rank` among n_ranks for n beads: its first bead and size m
   !> (n / n_ranks beads, one more for the first mod(n, n_ranks) ranks)
   pure subroutine block_partition(n, n_ranks, rank, first, m)
      integer, intent(in) :: n, n_ranks, rank
      integer, intent(out) :: first, m
      integer :: base, extra
      base = n / n_ranks
      extra = mod(n, n_ranks)
      first = rank * base + min(rank, extra) + 1
      m = base
      if (rank < extra) m = m + 1
   end subroutine block_partition

   !> The block of this rank of `comm` for the chain (at least as many beads as
   !> ranks: hcimpact_mpi_chain_scene checks it)
   subroutine block_setup(chain, comm, block)
      type(chain_type), intent(in) :: chain
      type(MPI_Comm), intent(in) :: comm
      type(chain_block), intent(out) :: block
      integer :: mr

      block%comm = comm
      call MPI_Comm_rank(comm, block%rank)
      call MPI_Comm_size(comm, block%n_ranks)
      block%n = size(chain%mass)
      call block_partition(block%n, block%n_ranks, block%rank, block%first, block%m)
      if (block%rank > 0) then
         block%left = block%rank - 1
         block%n_left = 1
      end if
      if (block%rank < block%n_ranks - 1) then
         block%right = block%rank + 1
         block%n_right = 1
      end if
      ! the region: beads first - n_left .. first + m - 1 + n_right, its slots j between
      ! its beads j and j + 1 are the chain's pairs; the slots at its two ends are the
      ! walls on the first and last rank, else none
      mr = block%n_left + block%m + block%n_right
      block%region = part_region(chain, block%first - block%n_left, &
         & block%first + block%m - 1 + block%n_right)
      block%n_motion = 3 * block%m
      block%n_global = 3 * block%n
      if (chain%right_wall) then
         block%n_global = block%n_global + 2
         if (block%rank == block%n_ranks - 1) block%n_motion = block%n_motion + 1
      end if
      block%n_local = block%n_motion
      if (chain%left_wall) then
         block%n_global = block%n_global + 1
         if (block%rank == 0) then
            block%n_local = block%n_local + 1
            block%impulse(1) = block%n_local
         end if
      end if
      if (chain%right_wall .and. block%rank == block%n_ranks - 1) then
         block%n_local = block%n_local + 1
         block%impulse(2) = block%n_local
      end if
      allocate(block%y_region(region_size(mr)), block%dy_region(region_size(mr)))
      block%y_region = 0.0_wp
      block%dy_region = 0.0_wp
   end subroutine block_setup

   !> Trade the boundary beads with the neighbours: this block's first bead (u, v) to
   !> the left and its last to the right, the halo beads back. y is the block's state.
   subroutine exchange_halo(block, y)
      type(chain_block), intent(inout) :: block
      real(wp), intent(in) :: y(:)
      real(wp) :: first_bead(halo_doubles), last_bead(halo_doubles)
      integer :: m
      m = block%m
      first_bead = y(1:2)
      last_bead = y(3 * m - 2:3 * m - 1)
      ! to the left, from the right: the right neighbour's first bead
      call MPI_Sendrecv(first_bead, halo_doubles, MPI_DOUBLE_PRECISION, block%left, &
         & tag_to_left, block%halo_right, halo_doubles, MPI_DOUBLE_PRECISION, block%right, &
         & tag_to_left, block%comm, MPI_STATUS_IGNORE)
      ! to the right, from the left: the left neighbour's last bead
      call MPI_Sendrecv(last_bead, halo_doubles, MPI_DOUBLE_PRECISION, block%right, &
         & tag_to_right, block%halo_left, halo_doubles, MPI_DOUBLE_PRECISION, block%left, &
         & tag_to_right, block%comm, MPI_STATUS_IGNORE)
      block%exchanges = block%exchanges + 1
   end subroutine exchange_halo

   !> The block's right-hand side dy at the time t from its state y and the halo beads
   !> of the last exchange (the walls' impulses: the walls' forces on the chain); ok
   !> false if a force is not finite.
   subroutine block_rhs(block, t, y, dy, ok)
      type(chain_block), intent(inout) :: block
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: dy(:)
      logical, intent(out) :: ok
      integer :: nl, lo, mr, side
      nl = block%n_motion
      mr = block%region%m
      lo = 3 * block%n_left
      if (block%n_left == 1) block%y_region(1:2) = block%halo_left
      block%y_region(lo + 1:lo + nl) = y(1:nl)
      if (block%n_right == 1) block%y_region(3 * mr - 2:3 * mr - 1) = block%halo_right
      ! a state CVODE tried that is not finite (its norms then reject the step): NaN
      ! without comparing it (the Debug build traps a comparison with NaN; beads of
      ! 1e-200 kg met one)
      if (.not. all(ieee_is_finite(block%y_region))) then
         dy = ieee_value(1.0_wp, ieee_quiet_nan)
         ok = .false.
         return
      end if
      call region_rhs(block%region, t, block%y_region, block%dy_region, ok)
      dy(1:nl) = block%dy_region(lo + 1:lo + nl)
      do side = 1, 2
         if (block%impulse(side) > 0) dy(block%impulse(side)) = &
            & block%dy_region(impulse_index(mr, side))
      end do
   end subroutine block_rhs

   !> The region (hcimpact_cvode_chain_system) of the beads g_first .. g_last of the
   !> chain: their masses, the pairs between them, and in its end slots the left wall
   !> when g_first is bead 1, the right wall when g_last is bead n (else nothing).
   !> part_region(chain, 1, n) is the whole chain, the serial chain's one region.
   pure function part_region(chain, g_first, g_last) result(region)
      type(chain_type), intent(in) :: chain
      integer, intent(in) :: g_first, g_last
      type(chain_region) :: region
      integer :: mr, j
      mr = g_last - g_first + 1
      region%m = mr
      region%gravity = chain%gravity
      allocate(region%mass(mr), region%kind(0:mr), region%law(0:mr), region%gap0(0:mr))
      region%mass = chain%mass(g_first:g_last)
      region%kind = slot_none
      region%gap0 = 0.0_wp
      do j = 1, mr - 1
         region%kind(j) = slot_pair
         region%law(j) = chain%law(g_first + j - 1)
         region%gap0(j) = chain%gap(g_first + j - 1)
      end do
      if (g_first == 1 .and. chain%left_wall) then
         region%kind(0) = slot_left_wall
         region%law(0) = chain%left_law
         region%gap0(0) = chain%left_gap
      end if
      if (g_last == size(chain%mass) .and. chain%right_wall) then
         region%kind(mr) = slot_right_wall
         region%law(mr) = chain%right_law
         region%gap0(mr) = chain%right_gap
      end if
   end function part_region

   !> Kinetic + elastic + gravitational energy (J) of a region in the state y (region
   !> layout; the gravitational energy from the initial positions, -m g u)
   pure function region_energy(region, y) result(energy)
      type(chain_region), intent(in) :: region
      real(wp), intent(in) :: y(:)
      real(wp) :: energy
      type(contact_force_type) :: element
      real(wp) :: x, w
      integer :: k, j
      energy = 0.0_wp
      do k = 1, region%m
         energy = energy + kinetic_energy(region%mass(k), y(3 * k - 1)) &
            & - region%mass(k) * region%gravity * y(3 * k - 2)
      end do
      do j = 0, region%m
         if (region%kind(j) == slot_none) cycle
         call slot_state(region, j, 0.0_wp, y, x, w, element)
         energy = energy + element%potential
      end do
   end function region_energy

end module hcimpact_mpi_chain_block
