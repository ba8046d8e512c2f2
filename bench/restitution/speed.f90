! SPDX-License-Identifier: Apache-2.0
!> Speed of the restitution k(beta) against one `log` on the same inputs (issue #3 goal:
!> k at most 3x the time of log, and the batch (array) form as fast per element).
!>
!> For each range of beta: N inputs log-uniform in the range; each measurement times a
!> loop over all of them, repeated until it lasts at least 20 ms; measurements alternate
!> between the candidates and are repeated; the median ns/call is reported, with the
!> ratio to log. Timings are never asserted anywhere.
!>
!> Usage: bench_restitution_speed [--quick]
program bench_restitution_speed
   use, intrinsic :: iso_fortran_env, only : int64, output_unit
   use hcimpact, only : wp, restitution, restitution_inverse
   implicit none
   integer, parameter :: n = 4096
   integer :: repeats, nrange, ir, ic, irep
   real(wp) :: beta(n), out(n), lo(4), hi(4), u(n), sink
   real(wp), allocatable :: times(:, :)
   character(len=32) :: arg
   character(len=*), parameter :: names(4) = [character(len=24) :: "log(beta)", &
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
   allocate(times(repeats, size(names)))

   write(output_unit, '(a)') "| beta range | function | ns/call (median) | min | max | ratio to log |"
   write(output_unit, '(a)') "|---|---|---:|---:|---:|---:|"
   do ir = 1, nrange
      call fill_log_uniform(u, lo(ir), hi(ir), beta)
      do irep = 1, repeats
         do ic = 1, size(names)
            times(irep, ic) = time_candidate(ic)
         end do
      end do
      do ic = 1, size(names)
         write(output_unit, '("| [", es8.1, ", ", es8.1, "] | ", a, " | ", f8.2, " | ", f8.2, &
            & " | ", f8.2, " | ", f6.2, " |")') lo(ir), hi(ir), trim(names(ic)), &
            & median(times(:, ic)), minval(times(:, ic)), maxval(times(:, ic)), &
            & median(times(:, ic)) / median(times(:, 1))
      end do
   end do
   ! Keep the results alive
   if (sink == 1.2345_wp) write(output_unit, *) sink

contains

   !> ns per element of one candidate, over a loop lasting at least min_seconds
   function time_candidate(ic) result(ns)
      integer, intent(in) :: ic
      real(wp) :: ns
      integer(int64) :: t0, t1, rate, loops, i, j
      real(wp) :: e(n)

      if (ic == 4) e = restitution(beta)
      loops = 0
      call system_clock(t0, rate)
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
         call system_clock(t1)
         if (real(t1 - t0, wp) / real(rate, wp) >= min_seconds) exit
      end do
      i = loops * n
      ns = 1.0e9_wp * real(t1 - t0, wp) / real(rate, wp) / real(i, wp)
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
