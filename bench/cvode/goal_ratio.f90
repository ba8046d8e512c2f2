! SPDX-License-Identifier: Apache-2.0
!> The speed ratio of issue #4's goal (CVODE at rtol = 1e-10 against the closed forms)
!> under issue 17's protocol, on the contacts of bench/cvode/reference.csv.
!>
!>   bench_cvode_goal_ratio REFERENCE.csv OUT.csv [--quick] [--rounds R]
!>
!> Both sides are called as a user calls them: `impact` of the public module `hcimpact`
!> and `simulate_power` of `hcimpact_cvode`, from the shared libraries this program is
!> linked with (bench/cvode/run.sh builds them shared). Each call is timed on its own
!> with the thread's CPU clock; the cost of reading the clock (an interval with no call
!> in it, timed at a random place of every pass) is subtracted.
!>
!> Why every call is timed alone: a closed-form impact takes a few microseconds and its
!> branches depend on the contact (n, beta); repeating one contact in a batch lets the
!> branch predictor learn its path. Here a pass calls all contacts once each, in a fresh
!> random order, so the contacts before a call change every pass and nothing can be
!> learnt across calls; a per-contact time then needs a clock read around each call.
!>
!> One round: `cvode_passes` CVODE passes (every contact with Adams and with BDF, the
!> 2 x 21 solves in a fresh random order) interleaved with `closed_passes` passes of the
!> closed forms (split evenly between the CVODE passes). Per round and contact: the
!> median of the closed forms' calls, the median of each CVODE method's solves, and
!> their ratios. Over the rounds: the median, smallest and largest of the per-round
!> ratios, and the medians of the times. The same rounds also time the old protocol's
!> batches (the same contact `batch` times in a row through the closed forms,
!> `cvode_batch` times through each CVODE method, the clock read once a batch), the
!> columns that show how much the repetition changed the figures, and passes of the
!> closed forms timed whole (the clock read once per pass): the mean time per call of
!> those over the mean of the calls timed alone, clock subtracted, checks the
!> subtraction (printed on standard output, median and range over the rounds).
!>
!> OUT.csv: case, n, beta, V, the median times (s) of the closed forms in random order,
!> in a batch, of Adams and BDF one solve at a time and in batches, the per-round ratios
!> (median, min, max) of Adams and BDF against the closed forms in random order, of the
!> closed forms' batch against random order, the old protocol's per-round ratios (the
!> batches of Adams and BDF against the closed forms' batch; median) and the clock cost
!> subtracted (s).
program bench_cvode_goal_ratio
   use, intrinsic :: iso_fortran_env, only : error_unit
   use hcimpact, only : wp, outcome_type, impact
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate_power, cvode_bdf, &
      & cvode_adams
   use bench_cvode_common, only : cpu_seconds, reference_case, read_reference, median, &
      & fail_run
   implicit none

   !> CVODE's tolerance of the goal
   real(wp), parameter :: goal_rtol = 1.0e-10_wp
   !> calls of the same contact in one batch of the old protocol
   integer, parameter :: batch = 64
   !> solves of the same contact and method in one batch of the old protocol
   integer, parameter :: cvode_batch = 4
   type(reference_case), allocatable :: cases(:)
   character(len=1024) :: ref_path, out_path, arg
   integer :: rounds, closed_passes, cvode_passes, ia, n_cases, ios
   logical :: quick

   if (command_argument_count() < 2) then
      call fail_run("usage: bench_cvode_goal_ratio REFERENCE.csv OUT.csv " // &
         & "[--quick] [--rounds R]")
   end if
   call get_command_argument(1, ref_path)
   call get_command_argument(2, out_path)
   quick = .false.
   rounds = 0
   ia = 3
   do while (ia <= command_argument_count())
      call get_command_argument(ia, arg)
      if (trim(arg) == "--quick") then
         quick = .true.
      else if (trim(arg) == "--rounds" .and. ia < command_argument_count()) then
         ia = ia + 1
         call get_command_argument(ia, arg)
         read(arg, *, iostat=ios) rounds
         if (ios /= 0 .or. rounds < 1) then
            call fail_run("bench_cvode_goal_ratio: --rounds needs a positive integer")
         end if
      else
         call fail_run("bench_cvode_goal_ratio: unknown option " // trim(arg))
      end if
      ia = ia + 1
   end do
   if (quick) then
      if (rounds == 0) rounds = 5
      closed_passes = 60
      cvode_passes = 2
   else
      if (rounds == 0) rounds = 31
      closed_passes = 400
      cvode_passes = 4
   end if
   call read_reference(trim(ref_path), cases)
   n_cases = size(cases)
   call random_seed()
   call measure()

contains

   subroutine measure()
      ! per round and contact: closed forms (random order), closed forms (batch), Adams, BDF
      real(wp) :: t_closed(n_cases, rounds), t_batch(n_cases, rounds)
      real(wp) :: t_adams_batch(n_cases, rounds), t_bdf_batch(n_cases, rounds)
      real(wp) :: t_adams(n_cases, rounds), t_bdf(n_cases, rounds), t_clock(rounds)
      real(wp) :: whole_over_split(rounds), t0, t1
      integer :: orders(0:n_cases, closed_passes / 4)
      real(wp) :: calls(n_cases, closed_passes), solves(n_cases, 2, cvode_passes)
      real(wp) :: empty(closed_passes + cvode_passes)
      integer :: r, q, p, done, n_empty, unit, ic, stat

      do r = 1, rounds
         done = 0
         n_empty = 0
         do q = 1, cvode_passes
            call cvode_pass(solves(:, :, q), empty, n_empty)
            do p = done + 1, (q * closed_passes) / cvode_passes
               call closed_pass(calls(:, p), empty, n_empty)
            end do
            done = (q * closed_passes) / cvode_passes
         end do
         call batch_pass(t_batch(:, r), t_adams_batch(:, r), t_bdf_batch(:, r))
         t_clock(r) = median(empty(1:n_empty))
         do p = 1, size(orders, 2)
            call shuffle(orders(:, p))
         end do
         t0 = cpu_seconds()
         do p = 1, size(orders, 2)
            call whole_pass(orders(:, p))
         end do
         t1 = cpu_seconds()
         whole_over_split(r) = ((t1 - t0) / ((closed_passes / 4) * n_cases)) / &
            & (sum(calls) / size(calls) - sum(empty(1:n_empty)) / n_empty)
         do ic = 1, n_cases
            t_closed(ic, r) = median(calls(ic, :)) - t_clock(r)
            t_adams(ic, r) = median(solves(ic, 1, :)) - t_clock(r)
            t_bdf(ic, r) = median(solves(ic, 2, :)) - t_clock(r)
         end do
         write(error_unit, '(a, i0, a, i0, a, f6.3, a)') "round ", r, " of ", rounds, &
            & ": clock read ", 1.0e6_wp * t_clock(r), " us"
      end do

      write(*, '(a, 3(f5.3, a))') "closed forms timed by whole passes over timed alone: ", &
         & median(whole_over_split), " (", minval(whole_over_split), " to ", &
         & maxval(whole_over_split), " over the rounds)"
      open(newunit=unit, file=trim(out_path), status="replace", action="write", iostat=stat)
      if (stat /= 0) call fail("cannot open " // trim(out_path))
      write(unit, '(a)', iostat=stat) "case,n,beta,V,closed_seconds,batch_seconds," // &
         & "adams_seconds,bdf_seconds,ratio_adams,ratio_adams_min,ratio_adams_max," // &
         & "ratio_bdf,ratio_bdf_min,ratio_bdf_max,ratio_batch,ratio_batch_min," // &
         & "ratio_batch_max,adams_batch_seconds,bdf_batch_seconds,old_ratio_adams," // &
         & "old_ratio_bdf,clock_seconds"
      if (stat /= 0) call fail("cannot write " // trim(out_path))
      do ic = 1, n_cases
         write(unit, '(i0, 21(",", es12.5e3))', iostat=stat) ic, &
            & cases(ic)%contact%exponent, &
            & cases(ic)%contact%damping * cases(ic)%contact%velocity, &
            & cases(ic)%contact%velocity, median(t_closed(ic, :)), median(t_batch(ic, :)), &
            & median(t_adams(ic, :)), median(t_bdf(ic, :)), &
            & spread3(t_adams(ic, :) / t_closed(ic, :)), &
            & spread3(t_bdf(ic, :) / t_closed(ic, :)), &
            & spread3(t_batch(ic, :) / t_closed(ic, :)), median(t_adams_batch(ic, :)), &
            & median(t_bdf_batch(ic, :)), median(t_adams_batch(ic, :) / t_batch(ic, :)), &
            & median(t_bdf_batch(ic, :) / t_batch(ic, :)), median(t_clock)
         if (stat /= 0) call fail("cannot write " // trim(out_path))
      end do
      close(unit, iostat=stat)
      if (stat /= 0) call fail("cannot close " // trim(out_path))
   end subroutine measure

   !> Median, smallest and largest of per-round values.
   pure function spread3(x) result(s)
      real(wp), intent(in) :: x(:)
      real(wp) :: s(3)
      s = [median(x), minval(x), maxval(x)]
   end function spread3

   !> Every contact once through the closed forms, in a fresh random order, each call
   !> timed alone; one empty interval at a random place (the clock's own cost).
   subroutine closed_pass(seconds, empty, n_empty)
      real(wp), intent(out) :: seconds(:)
      real(wp), intent(inout) :: empty(:)
      integer, intent(inout) :: n_empty
      integer :: order(0:n_cases), k, stat
      real(wp) :: t0, t1
      type(outcome_type) :: outcome
      call shuffle(order)
      do k = 0, n_cases
         if (order(k) == 0) then
            t0 = cpu_seconds()
            t1 = cpu_seconds()
            n_empty = n_empty + 1
            empty(n_empty) = t1 - t0
         else
            t0 = cpu_seconds()
            call impact(cases(order(k))%contact, outcome, stat)
            t1 = cpu_seconds()
            seconds(order(k)) = t1 - t0
            if (stat /= 0) call fail("closed forms failed")
         end if
      end do
   end subroutine closed_pass

   !> Every contact with Adams and with BDF at rtol = 1e-10, the 2 n_cases solves in a
   !> fresh random order, each timed alone; one empty interval at a random place.
   subroutine cvode_pass(seconds, empty, n_empty)
      real(wp), intent(out) :: seconds(:, :)
      real(wp), intent(inout) :: empty(:)
      integer, intent(inout) :: n_empty
      integer :: order(0:2 * n_cases), k, ic, method, stat
      real(wp) :: t0, t1
      type(simulation_type) :: sim
      call shuffle(order)
      do k = 0, 2 * n_cases
         if (order(k) == 0) then
            t0 = cpu_seconds()
            t1 = cpu_seconds()
            n_empty = n_empty + 1
            empty(n_empty) = t1 - t0
            cycle
         end if
         ic = 1 + mod(order(k) - 1, n_cases)
         method = 1 + (order(k) - 1) / n_cases
         t0 = cpu_seconds()
         call simulate_power(cases(ic)%contact, sim, stat, &
            & cvode_options(method=merge(cvode_adams, cvode_bdf, method == 1), rtol=goal_rtol))
         t1 = cpu_seconds()
         seconds(ic, method) = t1 - t0
         if (stat /= 0) call fail("CVODE failed: " // trim(sim%message))
      end do
   end subroutine cvode_pass

   !> Every contact once through the closed forms in the given order (a permutation of
   !> 0 ... n_cases, 0 skipped), untimed: the caller times a series of such passes.
   subroutine whole_pass(order)
      integer, intent(in) :: order(0:)
      integer :: k, stat
      type(outcome_type) :: outcome
      do k = 0, n_cases
         if (order(k) == 0) cycle
         call impact(cases(order(k))%contact, outcome, stat)
         if (stat /= 0) call fail("closed forms failed")
      end do
   end subroutine whole_pass

   !> The old protocol, for comparison: each contact through the closed forms (in a
   !> fresh random order) `batch` times in a row, then each contact and CVODE method (in
   !> a fresh random order) `cvode_batch` times in a row, the clock read once a batch.
   subroutine batch_pass(closed, adams, bdf)
      real(wp), intent(out) :: closed(:), adams(:), bdf(:)
      integer :: order(0:n_cases), cvode_order(0:2 * n_cases), k, i, ic, stat
      real(wp) :: t0, t1
      type(outcome_type) :: outcome
      type(simulation_type) :: sim
      call shuffle(order)
      do k = 0, n_cases
         if (order(k) == 0) cycle
         t0 = cpu_seconds()
         do i = 1, batch
            call impact(cases(order(k))%contact, outcome, stat)
         end do
         t1 = cpu_seconds()
         closed(order(k)) = (t1 - t0) / batch
      end do
      call shuffle(cvode_order)
      do k = 0, 2 * n_cases
         if (cvode_order(k) == 0) cycle
         ic = 1 + mod(cvode_order(k) - 1, n_cases)
         t0 = cpu_seconds()
         do i = 1, cvode_batch
            call simulate_power(cases(ic)%contact, sim, stat, cvode_options(rtol=goal_rtol, &
               & method=merge(cvode_adams, cvode_bdf, cvode_order(k) <= n_cases)))
         end do
         t1 = cpu_seconds()
         if (cvode_order(k) <= n_cases) then
            adams(ic) = (t1 - t0) / cvode_batch
         else
            bdf(ic) = (t1 - t0) / cvode_batch
         end if
      end do
   end subroutine batch_pass

   !> A fresh random permutation of lbound(order) ... ubound(order) (Fisher-Yates).
   subroutine shuffle(order)
      integer, intent(out) :: order(0:)
      integer :: i, j, t
      real(wp) :: u
      order = [(i, i = 0, ubound(order, 1))]
      do i = ubound(order, 1), 1, -1
         call random_number(u)
         j = min(int(u * (i + 1)), i)
         t = order(i)
         order(i) = order(j)
         order(j) = t
      end do
   end subroutine shuffle

   subroutine fail(message)
      character(len=*), intent(in) :: message
      call fail_run("bench_cvode_goal_ratio: " // message)
   end subroutine fail

end program bench_cvode_goal_ratio
