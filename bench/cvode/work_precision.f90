! SPDX-License-Identifier: Apache-2.0
!> Error against run time of CVODE (BDF and Adams, rtol 1e-3 ... 1e-13) and of the
!> closed forms, on the contacts of bench/cvode/reference.csv (doc/cvode.md).
!>
!>   bench_cvode_work_precision REFERENCE.csv OUT.csv [--quick]
!>
!> For every contact and setting: the relative errors of the contact time, the
!> restitution, the maximum compression and the peak force against the mpmath
!> reference, the CPU time of one call (median of the measurements; one measurement
!> repeats the call until 20 ms have passed, reading the clock once per batch of
!> calls), and CVODE's counters. The closed forms (hcimpact_impact_model's `impact`)
!> get one row per contact (method "closed"). These times repeat one contact and so
!> flatter the closed forms (the branch predictor learns the call); the speed ratio of
!> the goal is measured under issue 17's protocol by bench_cvode_goal_ratio.
program bench_cvode_work_precision
   use, intrinsic :: iso_fortran_env, only : error_unit
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : outcome_type, impact
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate_power, cvode_bdf, &
      & cvode_adams
   use bench_cvode_common, only : cpu_seconds, reference_case, read_reference, rel_error, &
      & ulp_error, n_outputs, outcome_values, median, fail_run
   implicit none

   integer, parameter :: n_rtol = 11
   type(reference_case), allocatable :: cases(:)
   character(len=1024) :: ref_path, out_path, arg
   integer :: unit, ic, im, ir, stat, repeats, ia
   real(wp) :: rtol, seconds, values(n_outputs)
   real(wp) :: min_seconds
   type(simulation_type) :: sim
   type(outcome_type) :: closed
   character(len=5) :: method_name
   logical :: quick

   if (command_argument_count() < 2) then
      call fail_run("usage: bench_cvode_work_precision REFERENCE.csv OUT.csv [--quick]")
   end if
   call get_command_argument(1, ref_path)
   call get_command_argument(2, out_path)
   quick = .false.
   ia = 3
   do while (ia <= command_argument_count())
      call get_command_argument(ia, arg)
      if (trim(arg) == "--quick") then
         quick = .true.
      else
         call fail_run("bench_cvode_work_precision: unknown option " // trim(arg))
      end if
      ia = ia + 1
   end do
   repeats = 5
   min_seconds = 0.02_wp
   if (quick) then
      repeats = 1
      min_seconds = 0.002_wp
   end if
   call read_reference(trim(ref_path), cases)

   open(newunit=unit, file=trim(out_path), status="replace", action="write")
   write(unit, '(a)') "method,case,n,beta,V,rtol,status,seconds," // &
      & "err_contact,err_restitution,err_x_max,err_peak_force," // &
      & "ulps_contact,ulps_restitution,ulps_x_max,ulps_peak_force," // &
      & "steps,rhs_evals,jacobian_evals,root_evals,error_test_failures,stiffness_ratio"
   do ic = 1, size(cases)
      ! the closed forms
      seconds = time_closed(cases(ic), repeats, min_seconds, closed, stat)
      values = outcome_values(closed)
      call write_row("closed", ic, 0.0_wp, stat, seconds, values, [0, 0, 0, 0, 0], &
         & 0.0_wp)
      do im = 1, 2
         method_name = merge("bdf  ", "adams", im == 1)
         do ir = 1, n_rtol
            rtol = 10.0_wp**(-2 - ir)
            seconds = time_cvode(cases(ic), merge(cvode_bdf, cvode_adams, im == 1), rtol, &
               & repeats, min_seconds, sim, stat)
            values = outcome_values(sim%outcome)
            call write_row(trim(method_name), ic, rtol, stat, seconds, values, &
               & [int(sim%counters%steps), int(sim%counters%rhs_evals), &
               & int(sim%counters%jacobian_evals), int(sim%counters%root_evals), &
               & int(sim%counters%error_test_failures)], sim%stiffness_ratio)
            if (stat /= 0) write(error_unit, '(a, i0, 3a, es8.1, 2a)') "case ", ic, " ", &
               & trim(method_name), " rtol ", rtol, ": ", sim%message
         end do
      end do
      write(error_unit, '(a, i0, a, i0)') "case ", ic, " of ", size(cases)
   end do
   close(unit)

contains

   subroutine write_row(method, ic, rtol, stat, seconds, values, counters, stiffness)
      character(len=*), intent(in) :: method
      integer, intent(in) :: ic, stat, counters(5)
      real(wp), intent(in) :: rtol, seconds, values(n_outputs), stiffness
      real(wp) :: err(n_outputs), ulps(n_outputs)
      integer :: k
      err = rel_error(values, cases(ic)%hi, cases(ic)%lo)
      ulps = ulp_error(values, cases(ic)%hi, cases(ic)%lo)
      if (stat /= 0) then
         err = -1.0_wp
         ulps = -1.0_wp
      end if
      write(unit, '(a, ",", i0, 4(",", es12.5e3), ",", i0, ",", es12.5e3, 8(",", es12.5e3), &
         & 5(",", i0), ",", es12.5e3)') method, ic, cases(ic)%contact%exponent, &
         & cases(ic)%contact%damping * cases(ic)%contact%velocity, &
         & cases(ic)%contact%velocity, rtol, stat, seconds, (err(k), k = 1, n_outputs), &
         & (ulps(k), k = 1, n_outputs), counters, stiffness
   end subroutine write_row

   !> CPU seconds per call of the closed forms (median over `repeats` measurements).
   function time_closed(case, repeats, min_seconds, outcome, stat) result(seconds)
      type(reference_case), intent(in) :: case
      integer, intent(in) :: repeats
      real(wp), intent(in) :: min_seconds
      type(outcome_type), intent(out) :: outcome
      integer, intent(out) :: stat
      real(wp) :: seconds, samples(repeats), t0, t1, t_batch
      integer :: r, calls, batch, i
      batch = 1
      do r = 1, repeats
         calls = 0
         t0 = cpu_seconds()
         do
            t_batch = cpu_seconds()
            do i = 1, batch
               call impact(case%contact, outcome, stat)
            end do
            calls = calls + batch
            t1 = cpu_seconds()
            if (t1 - t0 >= min_seconds) exit
            batch = next_batch(batch, t1 - t_batch)
         end do
         samples(r) = (t1 - t0) / calls
      end do
      seconds = median(samples)
   end function time_closed

   !> The clock is read once per batch of calls: reading the thread's CPU time is a
   !> system call (about 0.5 us here), as long as a closed-form impact itself. The batch
   !> doubles until it lasts at least 200 us, which puts the clock below 0.3 %.
   pure function next_batch(batch, seconds) result(next)
      integer, intent(in) :: batch
      real(wp), intent(in) :: seconds
      integer :: next
      next = batch
      if (seconds < 2.0e-4_wp .and. batch < 2**20) next = 2 * batch
   end function next_batch

   !> CPU seconds per call of CVODE (median over `repeats` measurements).
   function time_cvode(case, method, rtol, repeats, min_seconds, sim, stat) result(seconds)
      type(reference_case), intent(in) :: case
      integer, intent(in) :: method, repeats
      real(wp), intent(in) :: rtol, min_seconds
      type(simulation_type), intent(out) :: sim
      integer, intent(out) :: stat
      real(wp) :: seconds, samples(repeats), t0, t1, t_batch
      integer :: r, calls, batch, i
      batch = 1
      do r = 1, repeats
         calls = 0
         t0 = cpu_seconds()
         do
            t_batch = cpu_seconds()
            do i = 1, batch
               call simulate_power(case%contact, sim, stat, cvode_options(method=method, &
                  & rtol=rtol))
            end do
            calls = calls + batch
            t1 = cpu_seconds()
            if (t1 - t0 >= min_seconds) exit
            batch = next_batch(batch, t1 - t_batch)
         end do
         samples(r) = (t1 - t0) / calls
      end do
      seconds = median(samples)
   end function time_cvode

end program bench_cvode_work_precision
