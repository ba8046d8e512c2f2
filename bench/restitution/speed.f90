! SPDX-License-Identifier: Apache-2.0
!> Speed of the restitution k(beta) against one `log` on the same inputs (issue #3 goal:
!> k at most 3x the time of log, and the batch (array) form as fast per element).
!>
!> For each range of beta: N = 65536 inputs log-uniform in the range, so many that the
!> branch predictor cannot learn their sequence (the protocol of issue 17); each
!> measurement times a loop over all of them with the processor time, repeated until it
!> lasts at least 20 ms. In each round every candidate is measured once, in an order
!> reversed every other round; the table gives the median ns/call over the rounds and the
!> median of the per-round ratios to log (with their smallest and largest), so that a
!> slow phase of a shared machine cancels. k is called through the library's Fortran
!> module procedures (`use hcimpact`); bench/restitution/run.sh builds the library shared,
!> so that the calls cross into it as a user's program does. Timings are never asserted.
!>
!> Usage: bench_restitution_speed [--quick]
program bench_restitution_speed
   use, intrinsic :: iso_fortran_env, only : int64, output_unit
   use hcimpact, only : wp, restitution, restitution_inverse
   implicit none
   integer, parameter :: n = 65536
   integer :: repeats, nrange, ir, ic, irep, k
   real(wp) :: lo(4), hi(4), sink
   real(wp), allocatable :: beta(:), out(:), u(:), e(:), times(:, :), ratios(:, :)
   character(len=32) :: arg
   character(len=*), parameter :: names(4) = [character(len=25) :: "log(beta)", &
      & "k(beta) scalar loop", "k(beta) array (elemental)", "beta(e), e = k(beta)"]
   real(wp) :: min_seconds

   repeats = 11
   min_seconds = 0.02_wp
   if (command_argument_count() > 0) then
      call get_command_argument(1, arg)
      if (arg == "--quick") then
         repeats = 3
         min_seconds = 0.005_wp
      end if
   end if

   lo = [1.0e-6_wp, 1.0_wp, 40.0_wp, 1.0e-300_wp]
   hi = [1.0_wp, 40.0_wp, 1.0e300_wp, 1.0e300_wp]
   nrange = size(lo)
   sink = 0.0_wp
   allocate(beta(n), out(n), u(n), e(n), times(repeats, size(names)), &
      & ratios(repeats, size(names)))

   write(output_unit, '(a)') "| beta range | function | ns/call (median) | min | max | " // &
      & "ratio to log (median of the rounds') | smallest | largest |"
   write(output_unit, '(a)') "|---|---|---:|---:|---:|---:|---:|---:|"
   do ir = 1, nrange
      call fill_log_uniform(u, lo(ir), hi(ir), beta)
      e = restitution(beta)
      do irep = 1, repeats
         do k = 1, size(names)
            ! every other round the other way round, so that no candidate always
            ! follows the same one
            ic = merge(k, size(names) + 1 - k, mod(irep, 2) == 1)
            times(irep, ic) = time_candidate(ic)
         end do
         ratios(irep, :) = times(irep, :) / times(irep, 1)
      end do
      do ic = 1, size(names)
         write(output_unit, '("| [", es8.1, ", ", es8.1, "] | ", a, " | ", f8.2, " | ", f8.2, &
            & " | ", f8.2, " | ", f6.2, " | ", f6.2, " | ", f6.2, " |")') lo(ir), hi(ir), &
            & trim(names(ic)), median(times(:, ic)), minval(times(:, ic)), &
            & maxval(times(:, ic)), median(ratios(:, ic)), minval(ratios(:, ic)), &
            & maxval(ratios(:, ic))
      end do
   end do
   ! Keep the results alive
   if (sink == 1.2345_wp) write(output_unit, *) sink

contains

   !> ns per element of one candidate, over loops lasting at least min_seconds of
   !> processor time (a single-threaded program: time spent descheduled does not count)
   function time_candidate(ic) result(ns)
      integer, intent(in) :: ic
      real(wp) :: ns
      integer(int64) :: loops, i, j
      real(wp) :: t0, t1

      loops = 0
      call cpu_time(t0)
      do
         select case (ic)
         case (1)
            do j = 1, n
               out(j) = log(beta(j))
            end do
         case (2)
            do j = 1, n
               out(j) = restitution(beta(j))
            end do
         case (3)
            out = restitution(beta)
         case (4)
            out = restitution_inverse(e)
         end select
         sink = sink + out(1 + mod(loops, int(n, int64)))
         loops = loops + 1
         call cpu_time(t1)
         if (t1 - t0 >= min_seconds) exit
      end do
      i = loops * n
      ns = 1.0e9_wp * (t1 - t0) / real(i, wp)
   end function time_candidate

   !> Deterministic log-uniform inputs in [a, b] (a simple LCG: no system seeding)
   subroutine fill_log_uniform(r, a, b, x)
      real(wp), intent(out) :: r(:)
      real(wp), intent(in) :: a, b
      real(wp), intent(out) :: x(:)
      integer(int64) :: state
      integer :: j
      state = 20240603_int64
      do j = 1, size(r)
         state = mod(6364136223846793005_int64 * state + 1442695040888963407_int64, huge(state))
         r(j) = real(abs(shiftr(state, 11)), wp) / 2.0_wp**52
         r(j) = r(j) - int(r(j))
         x(j) = exp(log(a) + r(j) * (log(b) - log(a)))
      end do
   end subroutine fill_log_uniform

   pure function median(x) result(m)
      real(wp), intent(in) :: x(:)
      real(wp) :: m, y(size(x)), t
      integer :: i, j
      y = x
      do i = 2, size(y)
         t = y(i)
         j = i - 1
         do while (j >= 1)
            if (y(j) <= t) exit
            y(j + 1) = y(j)
            j = j - 1
         end do
         y(j + 1) = t
      end do
      if (mod(size(y), 2) == 1) then
         m = y((size(y) + 1) / 2)
      else
         m = 0.5_wp * (y(size(y) / 2) + y(size(y) / 2 + 1))
      end if
   end function median

end program bench_restitution_speed
