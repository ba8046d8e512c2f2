! SPDX-License-Identifier: Apache-2.0
!> Benchmarks of systems of bodies on a line (issue 15, "Speed and scale";
!> doc/chains-bench.md). Calls `chain_simulate` of the shared libhcimpact_cvode through
!> its Fortran API, as a user's program does. Time is the CPU time of the thread
!> (descheduled time does not count). The systems: bench/chain/chain_cases.f90.
!>
!>   bench_chain struck --n N --t-end T --rtols R1,R2,... [--integrator bdf|adams]
!>       [--method auto|integrated] [--min-seconds S] [--states DIR]
!>     The struck chain of N touching beads until T, once per rtol: a CSV row per rtol
!>     on standard output (time per call: calls repeated until S seconds have passed),
!>     and with --states the final positions and velocities in DIR/hc_<integrator>_
!>     <rtol>.csv (with the system's parameters in its header, for the SciPy script).
!>   bench_chain scaling OUT.csv --sizes N1,N2,... --rounds R --t-end T --rtol R
!>       [--min-seconds S] [--gap G] [--method auto|integrated]
!>     Per-step cost against N: in every round each size once, in an order reversed
!>     every other round; a row per round and size (with --gap, the chain has the gap G
!>     in m between all its beads instead of touching; method auto by default).
!>   bench_chain memory --n N --t-end T --rtol R [--method auto|integrated]
!>     One run; the peak resident set size (getrusage) before the chain is built and
!>     after the run, in KiB: one CSV row.
!>   bench_chain dilute TIMES.csv ACCURACY.csv --rounds R [--rtol R] [--rtols LIST]
!>       [--min-seconds S] [--closed-forms-only]
!>     The dilute systems: methods auto and exact (closed forms) against integrated
!>     (CVODE BDF and Adams at rtol), timed one after the other in every round, in an
!>     order reversed every other round; the integrated answers' errors against the
!>     exact one, at rtol and (one run each) at every rtol of LIST. With
!>     --closed-forms-only, methods auto and exact alone (for a profiler).
!>   bench_chain row OUT.csv --sizes N1,N2,... --rounds R --t-end T --rtol R
!>       [--integrated-up-to N]
!>     The dilute row of beads with random speeds (bench_chain_cases) of each size to T:
!>     method auto (closed forms, a region for each cluster) and, for the sizes up to N
!>     (default 1000), the whole row integrated by CVODE (BDF), one after the other in
!>     every round (the order reversed every other round); a CSV row per run with the
!>     work done, the energy error and, for the integrated run, the largest difference
!>     of its final velocities from method auto's.
program bench_chain
   use, intrinsic :: iso_c_binding, only : c_int, c_long
   use, intrinsic :: iso_fortran_env, only : error_unit, output_unit, int64
   use hcimpact, only : wp, chain_type, chain_options, chain_result
   use hcimpact_chain_types, only : method_auto, method_exact, method_integrated, &
      & integrator_bdf, integrator_adams
   use hcimpact_cvode, only : chain_simulate
   use bench_cvode_common, only : cpu_seconds, median, fail_run
   use bench_chain_cases, only : struck_chain, dilute_case, n_dilute, dilute_names, &
      & dilute_t_end, bead_mass, bead_stiffness, striker_speed, dilute_row
   implicit none

   !> struct rusage of Linux: two struct timeval, then ru_maxrss and 13 more longs
   type, bind(C) :: rusage
      integer(c_long) :: utime(2), stime(2), fields(14)
   end type rusage
   interface
      function getrusage(who, usage) result(stat) bind(C, name="getrusage")
         import :: c_int, rusage
         integer(c_int), value :: who
         type(rusage), intent(out) :: usage
         integer(c_int) :: stat
      end function getrusage
   end interface

   character(len=4096) :: mode, arg, out_path, out_path2, states_dir
   character(len=4096) :: list_text
   integer :: ia, n, rounds, method, integrator, integrated_up_to
   logical :: closed_forms_only
   real(wp) :: t_end, rtol, min_seconds, gap
   real(wp), allocatable :: rtols(:), sizes(:)

   if (command_argument_count() < 1) call usage()
   call get_command_argument(1, mode)
   n = 100
   rounds = 5
   method = method_auto
   integrator = integrator_bdf
   t_end = 1.0e-3_wp
   rtol = 1.0e-10_wp
   min_seconds = 0.05_wp
   gap = 0.0_wp
   closed_forms_only = .false.
   integrated_up_to = 1000
   states_dir = ""
   out_path = ""
   out_path2 = ""
   allocate(rtols(0), sizes(0))
   ia = 2
   do while (ia <= command_argument_count())
      call get_command_argument(ia, arg)
      select case (trim(arg))
      case ("--n")
         n = nint(next_real())
      case ("--rounds")
         rounds = nint(next_real())
      case ("--t-end")
         t_end = next_real()
      case ("--rtol")
         rtol = next_real()
      case ("--min-seconds")
         min_seconds = next_real()
      case ("--gap")
         gap = next_real()
      case ("--closed-forms-only")
         closed_forms_only = .true.
      case ("--integrated-up-to")
         integrated_up_to = nint(next_real())
      case ("--rtols")
         rtols = next_list()
      case ("--sizes")
         sizes = next_list()
      case ("--states")
         ia = ia + 1
         call get_command_argument(ia, states_dir)
      case ("--integrator")
         ia = ia + 1
         call get_command_argument(ia, arg)
         if (trim(arg) == "adams") then
            integrator = integrator_adams
         else if (trim(arg) == "bdf") then
            integrator = integrator_bdf
         else
            call usage()
         end if
      case ("--method")
         ia = ia + 1
         call get_command_argument(ia, arg)
         if (trim(arg) == "integrated") then
            method = method_integrated
         else if (trim(arg) == "auto") then
            method = method_auto
         else
            call usage()
         end if
      case default
         if (arg(1:2) == "--") call usage()
         if (len_trim(out_path) == 0) then
            out_path = arg
         else
            out_path2 = arg
         end if
      end select
      ia = ia + 1
   end do

   select case (trim(mode))
   case ("struck")
      if (size(rtols) == 0) rtols = [rtol]
      call run_struck()
   case ("scaling")
      if (len_trim(out_path) == 0 .or. size(sizes) == 0) call usage()
      call run_scaling()
   case ("memory")
      call run_memory()
   case ("dilute")
      if (len_trim(out_path2) == 0) call usage()
      call run_dilute()
   case ("row")
      if (len_trim(out_path) == 0 .or. size(sizes) == 0) call usage()
      call run_row()
   case default
      call usage()
   end select

contains

   subroutine usage()
      write(error_unit, '(a)') "usage: bench_chain struck|scaling|memory|dilute|row ... " // &
         & "(see the header of bench/chain/bench_chain.f90)"
      stop 2, quiet=.true.
   end subroutine usage

   !> The value after the current option
   real(wp) function next_real()
      integer :: ios
      ia = ia + 1
      call get_command_argument(ia, arg)
      read(arg, *, iostat=ios) next_real
      if (ios /= 0) call usage()
   end function next_real

   !> The comma-separated list after the current option
   function next_list() result(values)
      real(wp), allocatable :: values(:)
      integer :: count, k, ios
      ia = ia + 1
      call get_command_argument(ia, list_text)
      count = 1
      do k = 1, len_trim(list_text)
         if (list_text(k:k) == ",") count = count + 1
      end do
      allocate(values(count))
      read(list_text, *, iostat=ios) values
      if (ios /= 0) call usage()
   end function next_list

   !> Options of a run until t_end
   function options_for(t_stop, tolerance, how, integ) result(options)
      real(wp), intent(in) :: t_stop, tolerance
      integer, intent(in) :: how, integ
      type(chain_options) :: options
      options%t_end = t_stop
      options%rtol = tolerance
      options%method = how
      options%integrator = integ
   end function options_for

   !> CPU seconds per call of chain_simulate (calls repeated until min_s has passed;
   !> at least one), the last call's result and status.
   function time_runs(chain, options, min_s, result, stat, calls) result(seconds)
      type(chain_type), intent(in) :: chain
      type(chain_options), intent(in) :: options
      real(wp), intent(in) :: min_s
      type(chain_result), intent(out) :: result
      integer, intent(out) :: stat, calls
      real(wp) :: seconds, t0, t1
      calls = 0
      t0 = cpu_seconds()
      do
         call chain_simulate(chain, result, stat, options)
         calls = calls + 1
         t1 = cpu_seconds()
         if (t1 - t0 >= min_s .or. stat /= 0) exit
      end do
      seconds = (t1 - t0) / calls
   end function time_runs

   !> The bead where the wave is: the fastest one
   pure integer function wave_front(result)
      type(chain_result), intent(in) :: result
      wave_front = maxloc(result%velocities, dim=1)
   end function wave_front

   !> Bodies in the last integrated region (from the log of switches; 0: none)
   pure integer function region_size(result)
      type(chain_result), intent(in) :: result
      integer :: k
      region_size = 0
      do k = size(result%switches), 1, -1
         if (result%switches(k)%first > 0) then
            region_size = result%switches(k)%last - result%switches(k)%first + 1
            return
         end if
      end do
   end function region_size

   character(len=5) function integrator_name(integ)
      integer, intent(in) :: integ
      integrator_name = merge("bdf  ", "adams", integ == integrator_bdf)
   end function integrator_name

   subroutine run_struck()
      type(chain_type) :: chain
      type(chain_result) :: result
      integer :: k, stat, calls
      real(wp) :: seconds
      character(len=4096) :: state_path
      call struck_chain(n, chain)
      write(output_unit, '(a)') "n,t_end,rtol,integrator,method,status,seconds,calls,steps," // &
         & "rhs_evals,jacobian_evals,contacts,energy_error,front,state_file"
      do k = 1, size(rtols)
         seconds = time_runs(chain, options_for(t_end, rtols(k), method, integrator), &
            & min_seconds, result, stat, calls)
         state_path = ""
         if (len_trim(states_dir) > 0) then
            write(state_path, '(a, "/hc_", a, "_", es7.1e2, ".csv")') trim(states_dir), &
               & trim(integrator_name(integrator)), rtols(k)
            call write_state(trim(state_path), result, rtols(k), seconds)
         end if
         write(output_unit, '(i0, 2(",", es10.3e2), ",", a, ",", i0, ",", i0, ",", &
            & es12.5e2, 5(",", i0), ",", es10.3e3, ",", i0, ",", a)') n, t_end, rtols(k), &
            & trim(integrator_name(integrator)), method, stat, seconds, calls, &
            & result%counters%steps, result%counters%rhs_evals, &
            & result%counters%jacobian_evals, result%n_contacts, result%energy_error, &
            & wave_front(result), trim(state_path)
         if (stat /= 0) write(error_unit, '(a, es8.1, 2a)') "struck: rtol ", rtols(k), &
            & ": ", trim(result%message)
         flush(output_unit)
      end do
   end subroutine run_struck

   !> The final state of the struck chain with the system's parameters in the header
   subroutine write_state(path, result, tolerance, seconds)
      character(len=*), intent(in) :: path
      type(chain_result), intent(in) :: result
      real(wp), intent(in) :: tolerance, seconds
      integer :: unit, i, ios
      open(newunit=unit, file=path, status="replace", action="write", iostat=ios)
      if (ios /= 0) call fail_run("bench_chain: cannot write " // path)
      write(unit, '(a, i0)', iostat=ios) "# n=", n
      write(unit, '(a, es24.16e3)', iostat=ios) "# mass=", bead_mass()
      write(unit, '(a, es24.16e3)', iostat=ios) "# stiffness=", bead_stiffness()
      write(unit, '(a)', iostat=ios) "# exponent=1.5"
      write(unit, '(a, es24.16e3)', iostat=ios) "# striker_speed=", striker_speed
      write(unit, '(a, es24.16e3)', iostat=ios) "# t_end=", t_end
      write(unit, '(a, es10.3e2)', iostat=ios) "# rtol=", tolerance
      write(unit, '(a, es12.5e2)', iostat=ios) "# seconds=", seconds
      write(unit, '(a, i0)', iostat=ios) "# steps=", result%counters%steps
      write(unit, '(a)', iostat=ios) "bead,position,velocity"
      do i = 1, size(result%velocities)
         write(unit, '(i0, 2(",", es24.16e3))', iostat=ios) i, result%positions(i), &
            & result%velocities(i)
         if (ios /= 0) exit
      end do
      if (ios == 0) close(unit, iostat=ios)
      if (ios /= 0) call fail_run("bench_chain: write failed: " // path)
   end subroutine write_state

   subroutine run_scaling()
      type(chain_type) :: chain
      type(chain_result) :: result
      integer :: unit, r, k, kk, stat, calls, ios
      real(wp) :: seconds
      open(newunit=unit, file=trim(out_path), status="replace", action="write", iostat=ios)
      if (ios /= 0) call fail_run("bench_chain: cannot write the scaling CSV")
      write(unit, '(a)') "round,n,t_end,rtol,status,seconds,calls,steps,rhs_evals," // &
         & "jacobian_evals,front,energy_error,gap,clusters,switches,region"
      do r = 1, rounds
         do kk = 1, size(sizes)
            k = kk
            if (mod(r, 2) == 0) k = size(sizes) + 1 - kk
            call struck_chain(nint(sizes(k)), chain, gap)
            seconds = time_runs(chain, options_for(t_end, rtol, method, integrator), &
               & min_seconds, result, stat, calls)
            write(unit, '(i0, ",", i0, 2(",", es10.3e2), ",", i0, ",", es12.5e2, 5(",", i0), &
               & ",", es10.3e3, ",", es10.3e2, 3(",", i0))') r, nint(sizes(k)), t_end, rtol, &
               & stat, seconds, calls, result%counters%steps, result%counters%rhs_evals, &
               & result%counters%jacobian_evals, wave_front(result), result%energy_error, &
               & gap, result%counters%clusters, size(result%switches), region_size(result)
            flush(unit)
            write(error_unit, '(a, i0, a, i0, a, i0, a, f9.3, a)') "scaling: round ", r, &
               & " n = ", nint(sizes(k)), " steps ", result%counters%steps, " ", seconds, " s"
         end do
      end do
      close(unit)
   end subroutine run_scaling

   !> Peak resident set size of the process so far, KiB (Linux: ru_maxrss in KiB)
   integer(int64) function peak_rss_kib()
      type(rusage) :: usage
      peak_rss_kib = -1
      if (getrusage(0_c_int, usage) == 0) peak_rss_kib = usage%fields(1)
   end function peak_rss_kib

   subroutine run_memory()
      type(chain_type) :: chain
      type(chain_result) :: result
      integer :: stat
      integer(int64) :: baseline
      baseline = peak_rss_kib()
      call struck_chain(n, chain)
      call chain_simulate(chain, result, stat, options_for(t_end, rtol, method, &
         & integrator))
      write(output_unit, '(a)') "n,t_end,rtol,status,baseline_kib,peak_kib,steps"
      write(output_unit, '(i0, 2(",", es10.3e2), 3(",", i0), ",", i0)') n, t_end, rtol, &
         & stat, baseline, peak_rss_kib(), result%counters%steps
   end subroutine run_memory

   subroutine run_dilute()
      integer, parameter :: n_methods = 4
      character(len=10), parameter :: names(n_methods) = [character(len=10) :: "auto", &
         & "exact", "bdf", "adams"]
      type(chain_type) :: chain
      type(chain_result) :: results(n_methods)
      type(chain_options) :: options(n_methods), sweep
      type(chain_result) :: swept
      integer :: times_unit, acc_unit, k, r, j, jj, i, stat(n_methods), stat_sweep, calls, ios
      integer :: timed
      real(wp) :: seconds, round_seconds(rounds, n_methods)
      open(newunit=times_unit, file=trim(out_path), status="replace", action="write", &
         & iostat=ios)
      if (ios /= 0) call fail_run("bench_chain: cannot write the dilute times")
      open(newunit=acc_unit, file=trim(out_path2), status="replace", action="write", &
         & iostat=ios)
      if (ios /= 0) call fail_run("bench_chain: cannot write the dilute accuracy")
      write(times_unit, '(a)') "case,round,method,seconds,calls,status"
      write(acc_unit, '(a)') "case,method,rtol,status,seconds,contacts," // &
         & "closed_form_contacts,integrated_contacts,clusters,steps,energy_error," // &
         & "err_velocity,err_position,err_separation,contacts_compared,final_time"
      do k = 1, n_dilute
         call dilute_case(k, chain)
         options(1) = options_for(dilute_t_end(k), rtol, method_auto, integrator_bdf)
         options(2) = options_for(dilute_t_end(k), rtol, method_exact, integrator_bdf)
         options(3) = options_for(dilute_t_end(k), rtol, method_integrated, integrator_bdf)
         options(4) = options_for(dilute_t_end(k), rtol, method_integrated, integrator_adams)
         timed = n_methods
         if (closed_forms_only) timed = 2
         do r = 1, rounds
            do jj = 1, timed
               j = jj
               if (mod(r, 2) == 0) j = timed + 1 - jj
               seconds = time_runs(chain, options(j), merge(min_seconds, 0.0_wp, j <= 2), &
                  & results(j), stat(j), calls)
               round_seconds(r, j) = seconds
               write(times_unit, '(a, ",", i0, ",", a, ",", es12.5e2, ",", i0, ",", i0)') &
                  & trim(dilute_names(k)), r, trim(names(j)), seconds, calls, stat(j)
            end do
            flush(times_unit)
         end do
         do j = 1, timed
            call write_accuracy(acc_unit, trim(dilute_names(k)), trim(names(j)), &
               & rtol, stat(j), median(round_seconds(:, j)), results(j), results(1))
         end do
         if (closed_forms_only) cycle
         ! CVODE's error against the exact answer as the tolerance tightens
         do i = 1, size(rtols)
            do j = 3, n_methods
               sweep = options(j)
               sweep%rtol = rtols(i)
               seconds = time_runs(chain, sweep, 0.0_wp, swept, stat_sweep, calls)
               call write_accuracy(acc_unit, trim(dilute_names(k)), trim(names(j)), &
                  & rtols(i), stat_sweep, seconds, swept, results(1))
            end do
         end do
         flush(acc_unit)
         write(error_unit, '(a, i0, a, i0, 2a)') "dilute: case ", k, " of ", n_dilute, &
            & " ", trim(dilute_names(k))
      end do
      close(times_unit)
      close(acc_unit)
   end subroutine run_dilute

   subroutine run_row()
      type(chain_type), allocatable :: rows(:)
      type(chain_result) :: auto, integrated
      integer :: unit, ios, r, kk, k, j, stat, calls, methods
      real(wp) :: seconds, dv
      open(newunit=unit, file=trim(out_path), status="replace", action="write", iostat=ios)
      if (ios /= 0) call fail_run("bench_chain: cannot write the row times")
      write(unit, '(a)') "n,round,method,seconds,status,contacts,closed_form_contacts," // &
         & "integrated_contacts,clusters,steps,energy_error,dv_from_auto,t_end,rtol"
      allocate(rows(size(sizes)))
      do k = 1, size(sizes)
         call dilute_row(nint(sizes(k)), 20261126_int64, rows(k))
      end do
      do r = 1, rounds
         do kk = 1, size(sizes)
            k = kk
            if (mod(r, 2) == 0) k = size(sizes) + 1 - kk
            methods = 1
            if (nint(sizes(k)) <= integrated_up_to) methods = 2
            do j = 1, methods
               if (j == 1) then
                  seconds = time_runs(rows(k), options_for(t_end, rtol, method_auto, &
                     & integrator_bdf), 0.0_wp, auto, stat, calls)
                  call write_row(unit, nint(sizes(k)), r, "auto", seconds, stat, auto, -1.0_wp)
               else
                  seconds = time_runs(rows(k), options_for(t_end, rtol, method_integrated, &
                     & integrator_bdf), 0.0_wp, integrated, stat, calls)
                  dv = -1.0_wp
                  if (stat == 0 .and. allocated(auto%velocities)) &
                     & dv = maxval(abs(integrated%velocities - auto%velocities))
                  call write_row(unit, nint(sizes(k)), r, "integrated", seconds, stat, &
                     & integrated, dv)
               end if
            end do
            write(error_unit, '(a, i0, a, i0, a, i0)') "row: round ", r, ", n = ", &
               & nint(sizes(k)), ", methods ", methods
         end do
      end do
      close(unit, iostat=ios)
      if (ios /= 0) call fail_run("bench_chain: cannot close the row times")
   end subroutine run_row

   !> One CSV row of the dilute row's runs (t_end and rtol: the program's)
   subroutine write_row(unit, size_n, round, name, seconds, stat, result, dv_auto)
      integer, intent(in) :: unit, size_n, round, stat
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: seconds, dv_auto
      type(chain_result), intent(in) :: result
      integer :: ios
      write(unit, '(i0, ",", i0, ",", a, ",", es12.5e2, ",", i0, 5(",", i0), &
         & 2(",", es13.5e3), 2(",", es10.3e2))', iostat=ios) size_n, round, name, &
         & seconds, stat, result%n_contacts, result%counters%closed_form_contacts, &
         & result%counters%integrated_contacts, result%counters%clusters, &
         & result%counters%steps, result%energy_error, dv_auto, t_end, rtol
      if (ios /= 0) call fail_run("bench_chain: cannot write the row times")
      flush(unit)
   end subroutine write_row

   !> One row of the dilute accuracy table: result against the exact one (method auto;
   !> the closed forms). Errors: largest |v - v_exact| (m/s) and |q - q_exact| (m) at the
   !> end, and the largest relative error of the separation speeds of the contacts,
   !> compared in the order they ended while their pairs agree.
   subroutine write_accuracy(unit, case_name, method_name, tolerance, stat, seconds, result, &
         & exact)
      integer, intent(in) :: unit, stat
      character(len=*), intent(in) :: case_name, method_name
      !> rtol, and the CPU seconds of one run
      real(wp), intent(in) :: tolerance, seconds
      type(chain_result), intent(in) :: result, exact
      real(wp) :: err_v, err_q, err_s
      integer :: i, compared
      err_v = -1.0_wp
      err_q = -1.0_wp
      err_s = -1.0_wp
      compared = 0
      if (stat == 0) then
         err_v = maxval(abs(result%velocities - exact%velocities))
         err_q = maxval(abs(result%positions - exact%positions))
         err_s = 0.0_wp
         do i = 1, min(size(result%contacts), size(exact%contacts))
            if (result%contacts(i)%pair /= exact%contacts(i)%pair) exit
            err_s = max(err_s, abs(result%contacts(i)%separation_speed &
               & - exact%contacts(i)%separation_speed) / exact%contacts(i)%separation_speed)
            compared = i
         end do
      end if
      write(unit, '(a, ",", a, ",", es10.3e2, ",", i0, ",", es12.5e2, 5(",", i0), &
         & 4(",", es12.5e3), ",", i0, ",", es12.5e2)') case_name, method_name, tolerance, &
         & stat, seconds, result%n_contacts, &
         & result%counters%closed_form_contacts, result%counters%integrated_contacts, &
         & result%counters%clusters, result%counters%steps, result%energy_error, err_v, &
         & err_q, err_s, compared, result%time
   end subroutine write_accuracy

end program bench_chain
