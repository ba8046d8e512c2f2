! SPDX-License-Identifier: Apache-2.0
!> A caller's monitor of a run (`chain_options%monitor`, doc/chains.md "Watching a long
!> run"): what its poll is given, that a monitor which never stops leaves the run as
!> it is to the bit, that one which stops ends the run at that call with
!> hcimpact_err_no_convergence and no results but the time reached, on the exact and
!> the integrated paths, and in OpenMP threads at once (each run its own monitor,
!> stopping at its own call, when the tester is built with OpenMP).
module test_cvode_chain_monitor
   use, intrinsic :: iso_fortran_env, only : int64
   use testdrive, only : new_unittest, unittest_type, error_type, check
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_no_convergence
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, chain_result, &
      & chain_monitor, monitor_interval, method_integrated, integrator_adams
   use hcimpact_cvode_chain, only : chain_simulate
   implicit none
   private

   public :: collect_chain_monitor

   !> Counts its calls, checks that what it is given never goes back, and stops at
   !> call `stop_at` (0: never)
   type, extends(chain_monitor) :: counting_monitor
      integer :: calls = 0
      integer :: stop_at = 0
      logical :: ordered = .true.
      real(wp) :: time = 0.0_wp
      integer(int64) :: steps = 0, events = 0
   contains
      procedure :: poll => counting_poll
   end type counting_monitor

   !> Steel beads of 16.3 g and Hertz's constant of two of them (N/m^1.5)
   real(wp), parameter :: bead_mass = 0.0163_wp, bead_pair = 1.7135e10_wp / sqrt(2.0_wp)

contains

   !> Collect all exported unit tests
   subroutine collect_chain_monitor(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("never-stops", test_never_stops), &
         & new_unittest("stops", test_stops), &
         & new_unittest("threads", test_threads) &
         & ]
   end subroutine collect_chain_monitor

   logical function counting_poll(self, time, steps, events) result(stop)
      class(counting_monitor), intent(inout) :: self
      real(wp), intent(in) :: time
      integer(int64), intent(in) :: steps, events
      if (self%calls > 0 .and. (time < self%time .or. steps < self%steps .or. &
         & events < self%events)) self%ordered = .false.
      self%time = time
      self%steps = steps
      self%events = events
      self%calls = self%calls + 1
      stop = self%stop_at > 0 .and. self%calls >= self%stop_at
   end function counting_poll

   !> n touching steel beads, the first struck at 1 m/s; with `walls` one bead between
   !> two steel walls 1 mm away instead, at 1 m/s to 10 s (some 5000 isolated contacts:
   !> the closed forms alone)
   subroutine struck_row(n, walls, chain, options)
      integer, intent(in) :: n
      logical, intent(in) :: walls
      type(chain_type), intent(out) :: chain
      type(chain_options), intent(inout) :: options
      integer :: m
      m = merge(1, n, walls)
      allocate(chain%mass(m), chain%velocity(m), chain%gap(m - 1), chain%law(m - 1))
      chain%mass = bead_mass
      chain%velocity = 0.0_wp
      chain%velocity(1) = 1.0_wp
      chain%gap = 0.0_wp
      chain%law = contact_law(bead_pair, 1.5_wp, 0.0_wp)
      if (walls) then
         chain%left_wall = .true.
         chain%right_wall = .true.
         chain%left_law = contact_law(bead_pair, 1.5_wp, 0.0_wp)
         chain%right_law = chain%left_law
         chain%left_gap = 1.0e-3_wp
         chain%right_gap = 1.0e-3_wp
         options%t_end = 10.0_wp
      end if
   end subroutine struck_row

   !> The same run with and without a monitor that never stops: the same bits, and the
   !> monitor called every monitor_interval passes with the time and work in order
   subroutine test_never_stops(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_options) :: options
      type(chain_type) :: chain
      type(chain_result) :: plain, watched
      type(counting_monitor), target :: watch
      integer :: stat, k

      do k = 1, 3
         ! touching beads (auto: a cluster), the same integrated, a bead between walls
         ! (exact)
         options = chain_options()
         if (k == 2) options%method = method_integrated
         options%integrator = integrator_adams
         call struck_row(12, k == 3, chain, options)
         call chain_simulate(chain, plain, stat, options)
         call check(error, stat, hcimpact_ok, "without a monitor: " // trim(plain%message))
         if (allocated(error)) return
         watch = counting_monitor()
         options%monitor => watch
         call chain_simulate(chain, watched, stat, options)
         call check(error, stat, hcimpact_ok, "with a monitor: " // trim(watched%message))
         if (allocated(error)) return
         call check(error, all(watched%velocities == plain%velocities) .and. &
            & all(watched%positions == plain%positions) .and. &
            & watched%time == plain%time .and. watched%n_contacts == plain%n_contacts &
            & .and. watched%counters%steps == plain%counters%steps .and. &
            & watched%energy_error == plain%energy_error, &
            & "a monitor that never stops changed the run")
         if (allocated(error)) return
         ! every step or contact is a pass of the loop
         call check(error, int(watch%calls, int64) >= (plain%counters%steps + &
            & plain%counters%closed_form_contacts) / monitor_interval .and. watch%calls > 0, &
            & "the monitor was called too seldom")
         if (allocated(error)) return
         call check(error, watch%ordered .and. watch%time <= plain%time .and. &
            & watch%steps <= plain%counters%steps, "time or work went back, or too far")
         if (allocated(error)) return
      end do
   end subroutine test_never_stops

   !> A monitor that stops at its k-th call: the run ends there, failed, with the
   !> message naming the monitor and NaN in the result
   subroutine test_stops(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_options) :: options
      type(chain_type) :: chain
      type(chain_result) :: result
      type(counting_monitor), target :: watch
      integer :: stat, k

      do k = 1, 4
         options = chain_options()
         if (k == 3) options%method = method_integrated
         watch = counting_monitor(stop_at=k)
         options%monitor => watch
         call struck_row(12, k == 4, chain, options)
         call chain_simulate(chain, result, stat, options)
         call check(error, stat, hcimpact_err_no_convergence, "stopped by the monitor")
         if (allocated(error)) return
         call check(error, watch%calls, k, "the run went on after the monitor stopped it")
         if (allocated(error)) return
         call check(error, index(result%message, "stopped by the caller's monitor") == 1, &
            & "the message: " // trim(result%message))
         if (allocated(error)) return
         ! (the Fortran API's failed result: the message and the time reached)
         call check(error, result%time == watch%time .and. result%counters%steps == 0 .and. &
            & .not. allocated(result%contacts), "a stopped run reported results")
         if (allocated(error)) return
      end do
   end subroutine test_stops

   !> Runs in OpenMP threads at once, each with its own monitor stopping at its own
   !> call (or never): each stops where its monitor said, and those that never stop
   !> equal the run without a monitor
   subroutine test_threads(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: runs = 8
      type(chain_options) :: options(runs)
      type(chain_type) :: chain
      type(chain_result) :: plain, results(runs)
      type(counting_monitor), target :: watches(runs)
      integer :: stats(runs), stat, i

      call struck_row(12, .false., chain, options(1))
      call chain_simulate(chain, plain, stat)
      call check(error, stat, hcimpact_ok, "without a monitor: " // trim(plain%message))
      if (allocated(error)) return
      do i = 1, runs
         watches(i) = counting_monitor(stop_at=merge(0, i, mod(i, 2) == 0))
      end do
      !$omp parallel do schedule(static, 1)
      do i = 1, runs
         options(i)%monitor => watches(i)
         call chain_simulate(chain, results(i), stats(i), options(i))
      end do
      !$omp end parallel do
      do i = 1, runs
         if (mod(i, 2) == 0) then
            call check(error, stats(i) == hcimpact_ok .and. &
               & all(results(i)%velocities == plain%velocities), "a run that went on")
         else
            call check(error, stats(i) == hcimpact_err_no_convergence .and. &
               & watches(i)%calls == i, "a run stopped by its monitor")
         end if
         if (allocated(error)) return
      end do
   end subroutine test_threads

end module test_cvode_chain_monitor
