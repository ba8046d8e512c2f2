! SPDX-License-Identifier: Apache-2.0
!> The Fortran API of the MPI component (hcimpact_mpi_sweep), run under mpirun with
!> any number of ranks: every sweep's outcomes and statuses, on rank 0, bit for bit
!> those of `impact` called for each contact on one process, with failing contacts
!> among good ones (each gets its status, the call the first one's), n = 0, fewer
!> items than ranks, the items `known` left alone, the listener told of every item
!> once, and arrays of the wrong size (hcimpact_err_size on every rank). Exit status 1
!> on any failure (rank 0 prints what failed).
!> The test's listener: how often each item is reported.
module mpi_sweep_test_tally
   use hcimpact_impact_model, only : outcome_type
   use hcimpact_mpi_sweep, only : sweep_listener
   implicit none
   private

   public :: tally

   !> Counts how often each item is reported
   type, extends(sweep_listener) :: tally
      integer, allocatable :: seen(:)
   contains
      procedure :: chunk_done => count_chunk
   end type tally

contains

   !> The listener: count each item reported.
   subroutine count_chunk(self, first, out, stats)
      class(tally), intent(inout) :: self
      integer, intent(in) :: first
      type(outcome_type), intent(in) :: out(:)
      integer, intent(in) :: stats(:)
      self%seen(first:first + size(out) - 1) = self%seen(first:first + size(out) - 1) + 1
      if (size(stats) /= size(out)) self%seen(first) = -100
   end subroutine count_chunk

end module mpi_sweep_test_tally

program mpi_sweep_test
   use, intrinsic :: iso_fortran_env, only : int64, error_unit
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
   use mpi_f08, only : MPI_Init, MPI_Finalize, MPI_Comm_rank, MPI_Comm_size, MPI_Allreduce, &
      & MPI_COMM_WORLD, MPI_INTEGER, MPI_MAX
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_size, hcimpact_err_mass, &
      & hcimpact_err_not_finite, hcimpact_err_damping, hcimpact_err_no_convergence
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_mpi_sweep, only : mpi_impact_sweep
   use mpi_sweep_test_tally, only : tally
   implicit none

   integer :: rank, ranks, failures, worst
   call MPI_Init()
   call MPI_Comm_rank(MPI_COMM_WORLD, rank)
   call MPI_Comm_size(MPI_COMM_WORLD, ranks)
   failures = 0

   call check_sweep("many items with failures among them", mixed(5000))
   call check_sweep("n = 0", mixed(0))
   call check_sweep("one item", mixed(1))
   call check_sweep("two items (fewer than ranks with 3)", mixed(2))
   call check_sweep("every item fails", [contact_type(mass=-1.0_wp, stiffness=1.0e7_wp, &
      & velocity=1.0_wp), contact_type(mass=1.0_wp, stiffness=1.0e7_wp, velocity=0.0_wp)])
   call check_known()
   call check_wrong_sizes()

   call MPI_Allreduce(failures, worst, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD)
   if (rank == 0) write(*, '(a, i0, a, i0, a)') "mpi_sweep_test: ", ranks, " ranks, ", &
      & worst, " failures"
   call MPI_Finalize()
   if (worst /= 0) stop 1

contains

   !> n contacts of many costs: speeds over six decades, the exponent and the damping
   !> varied, and every 97th one bad in one of four ways (negative mass, NaN stiffness,
   !> negative damping, an exponent beyond the quadrature's bound).
   function mixed(n) result(contacts)
      integer, intent(in) :: n
      type(contact_type) :: contacts(n)
      integer :: i
      do i = 1, n
         contacts(i) = contact_type(mass=0.05_wp, stiffness=2.0e7_wp, &
            & exponent=1.0_wp + real(modulo(i, 7), wp) / 4.0_wp, &
            & damping=0.1_wp * real(modulo(i, 5), wp), &
            & velocity=10.0_wp**(-3.0_wp + 6.0_wp * real(i, wp) / real(max(n, 1), wp)))
         if (modulo(i, 97) /= 0) cycle
         select case (modulo(i / 97, 4))
         case (0)
            contacts(i)%mass = -1.0_wp
         case (1)
            contacts(i)%stiffness = ieee_value(1.0_wp, ieee_quiet_nan)
         case (2)
            contacts(i)%damping = -0.5_wp
         case default
            contacts(i)%exponent = 150.0_wp
         end select
      end do
   end function mixed

   !> A sweep of `contacts` (given on rank 0; the other ranks pass none) against
   !> `impact` on rank 0, bit for bit; every item reported once to the listener.
   subroutine check_sweep(what, contacts)
      character(len=*), intent(in) :: what
      type(contact_type), intent(in) :: contacts(:)
      type(contact_type), allocatable :: given(:)
      type(outcome_type), allocatable :: out(:), expected(:)
      integer, allocatable :: stats(:), expected_stats(:)
      type(tally) :: listener
      integer :: status, expected_status, i, n
      n = 0
      if (rank == 0) n = size(contacts)
      given = contacts(1:n)
      allocate(out(n), stats(n), expected(n), expected_stats(n), listener%seen(n))
      listener%seen = 0
      stats = -1
      call mpi_impact_sweep(MPI_COMM_WORLD, given, out, stats, status, listener=listener)
      if (rank /= 0) return
      expected_status = hcimpact_ok
      do i = 1, n
         call impact(given(i), expected(i), expected_stats(i))
         if (expected_stats(i) /= hcimpact_ok .and. expected_status == hcimpact_ok) &
            & expected_status = expected_stats(i)
      end do
      call expect(what // ": the statuses", all(stats == expected_stats))
      call expect(what // ": the outcomes bit for bit", all([(same(out(i), expected(i)), &
         & i = 1, n)]))
      call expect(what // ": the call's status is the first failure's", &
         & status == expected_status)
      call expect(what // ": every item reported once", all(listener%seen == 1))
      if (n >= 5000) call expect(what // ": all four kinds of failure met", &
         & any(stats == hcimpact_err_mass) .and. any(stats == hcimpact_err_not_finite) &
         & .and. any(stats == hcimpact_err_damping) &
         & .and. any(stats == hcimpact_err_no_convergence))
   end subroutine check_sweep

   !> Items marked known keep what they hold when their chunk needs no computing: all
   !> known leaves every item and reports none; one unknown item is computed.
   subroutine check_known()
      type(contact_type), allocatable :: contacts(:)
      type(outcome_type), allocatable :: out(:)
      type(outcome_type) :: expected
      integer, allocatable :: stats(:)
      logical, allocatable :: known(:)
      type(tally) :: listener
      integer :: status, n, expected_stat
      n = 0
      if (rank == 0) n = 300
      contacts = mixed(n)
      allocate(out(n), stats(n), known(n), listener%seen(n))
      out%restitution = 0.25_wp
      stats = 77
      known = .true.
      listener%seen = 0
      call mpi_impact_sweep(MPI_COMM_WORLD, contacts, out, stats, status, known, listener)
      if (rank == 0) then
         call expect("all known: nothing computed", all(out%restitution == 0.25_wp) &
            & .and. all(stats == 77) .and. all(listener%seen == 0))
         ! the status is formed from the statuses held
         call expect("all known: the call's status from the statuses held", status == 77)
      end if
      if (rank == 0) known(n) = .false.
      listener%seen = 0
      call mpi_impact_sweep(MPI_COMM_WORLD, contacts, out, stats, status, known, listener)
      if (rank /= 0) return
      call impact(contacts(n), expected, expected_stat)
      call expect("one unknown: computed", same(out(n), expected) &
         & .and. stats(n) == expected_stat .and. listener%seen(n) == 1)
      call expect("one unknown: the first item left alone", out(1)%restitution == 0.25_wp &
         & .and. stats(1) == 77)
   end subroutine check_known

   !> Outcomes or statuses not of the contacts' size on rank 0: hcimpact_err_size on
   !> every rank, nothing computed.
   subroutine check_wrong_sizes()
      type(contact_type), allocatable :: contacts(:)
      type(outcome_type), allocatable :: out(:)
      integer, allocatable :: stats(:)
      logical, allocatable :: known(:)
      integer :: status, n
      n = 0
      if (rank == 0) n = 10
      contacts = mixed(n)
      allocate(out(max(n - 1, 0)), stats(n))
      stats = 77
      call mpi_impact_sweep(MPI_COMM_WORLD, contacts, out, stats, status)
      call expect("outcomes of the wrong size: hcimpact_err_size on every rank", &
         & status == hcimpact_err_size)
      if (rank == 0) call expect("outcomes of the wrong size: nothing written", &
         & all(stats == 77))
      deallocate(out)
      allocate(out(n), known(max(n - 2, 0)))
      known = .false.
      call mpi_impact_sweep(MPI_COMM_WORLD, contacts, out, stats, status, known)
      call expect("known of the wrong size: hcimpact_err_size on every rank", &
         & status == hcimpact_err_size)
   end subroutine check_wrong_sizes

   !> Whether two outcomes are the same bits, field by field (NaN included).
   logical function same(a, b)
      type(outcome_type), intent(in) :: a, b
      real(wp) :: x(9), y(9)
      x = [a%restitution, a%energy_loss_ratio, a%rebound_velocity, a%max_compression, &
         & a%peak_force, a%compression_at_peak_force, a%time_at_peak_force, &
         & a%compression_time, a%contact_time]
      y = [b%restitution, b%energy_loss_ratio, b%rebound_velocity, b%max_compression, &
         & b%peak_force, b%compression_at_peak_force, b%time_at_peak_force, &
         & b%compression_time, b%contact_time]
      same = all(transfer(x, 0_int64, 9) == transfer(y, 0_int64, 9)) &
         & .and. all(a%evaluations == b%evaluations)
   end function same

   subroutine expect(what, ok)
      character(len=*), intent(in) :: what
      logical, intent(in) :: ok
      if (ok) return
      failures = failures + 1
      write(error_unit, '(a, i0, a, a)') "FAIL (rank ", rank, "): ", what
   end subroutine expect

end program mpi_sweep_test
