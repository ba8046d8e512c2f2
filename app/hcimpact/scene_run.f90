! SPDX-License-Identifier: Apache-2.0
!> Running a scene: the plan (which components the requested outputs need, and only
!> those), the computations, the console tables, the CSV files and the log of what
!> each output cost.
!>
!> Methods, by output (the library module behind each in brackets):
!> - summary, sweep: the closed forms of one impact; the times by tanh-sinh quadrature
!>   [hcimpact_impact_model: impact];
!> - phase, loops: the closed-form velocity at a depth, V(x) through Lambert W, on a grid
!>   of x up to the closed-form x_max; no quadrature [velocity_at_depth]; the loops also
!>   compare their area with the energy lost (1 - k^2) m V^2/2 [restitution law];
!> - histories: the time law, the quadrature t(x) inverted by Newton's method
!>   [time_law_samples];
!> - restitution: k(beta), 1 - k^2 [hcimpact_restitution_law];
!> - lambertw: W0 and W-1 at a grid of z, and V = -(1 + W)/b from the offset t with
!>   z = -exp(-1 - t) [hcimpact_lambertw];
!> - legacy: the damping rules of multibody codes against the exact beta(e)
!>   [restitution_inverse, restitution];
!> - cvode: SUNDIALS CVODE at each tolerance against the closed forms [hcimpact::cvode,
!>   through hcimpact_scene_ode].
module hcimpact_scene_run
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, status_message
   use hcimpact_version_info, only : hcimpact_version_string
   use hcimpact_impact_model, only : contact_type, outcome_type, impact, velocity_at_depth, &
      & time_law, compression_branch, restitution_branch
   use hcimpact_hertz, only : two_body_velocities
   use hcimpact_restitution_law, only : restitution, energy_loss_ratio, &
      & one_minus_restitution, restitution_inverse, u_minus_log1p
   use hcimpact_lambertw, only : lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1
   use hcimpact_scene_model, only : scene_type, n_outputs, output_names, output_files, &
      & out_summary, out_sweep, out_histories, out_phase, out_loops, out_restitution, &
      & out_lambertw, out_legacy, out_cvode, out_contacts, out_final, out_motion, &
      & out_system_sweep, out_impact_sweep, system_outputs, nan
   use hcimpact_scene_chain, only : system_method, system_needs_ode, describe_system, &
      & write_system_parameters, run_system
   use hcimpact_scene_output, only : results_type, csv_type, open_results, commit_results, &
      & abandon_results, csv_open, csv_row, csv_line, csv_close, checkpoint_path, manifest_line
   use hcimpact_scene_ode, only : ode_available, ode_description, ode_missing, ode_run_type, &
      & ode_chain_description, &
      & ode_impact
   use hcimpact_legacy_damping, only : n_rules => n_damping_rules, &
      & rule_names => damping_rule_names, legacy_chi => legacy_damping
   use hcimpact_scene_system, only : wall_clock
   use hcimpact_chain_types, only : method_exact, method_integrated
   use hcimpact_scene_sweep, only : sweep_impacts, sweep_description
   use hcimpact_scene_systems, only : system_sweep_method, run_system_sweep
   use hcimpact_scene_impacts, only : impact_sweep_method, run_impact_sweep
   use hcimpact_scene_console, only : console_begin, console_log, console_failed, &
      & console_reason, say, emit, say_wrapped, say_text, shout, files_note, pad, str_int64, &
      & progress_begin, progress_step, progress_clear, progress_end
   use hcimpact_scene_numbers, only : power_product, quotient_of
   use hcimpact_scene_text, only : str, real_str, duration_str, join, count_str, csv_real, &
      & csv_text
   implicit none
   private

   public :: run_options, run_scene
   public :: exit_ok, exit_failure, exit_usage, exit_unavailable

   !> Exit codes of the program
   integer, parameter :: exit_ok = 0, exit_failure = 1, exit_usage = 2, exit_unavailable = 3

   !> How to run
   type :: run_options
      !> Only the tables and errors on the console
      logical :: quiet = .false.
      !> Show progress of long work on standard error (a terminal)
      logical :: progress = .false.
      !> Print the plan and stop
      logical :: plan_only = .false.
      !> Write the results directory
      logical :: write_files = .true.
      !> The results directory
      character(len=:), allocatable :: output_dir
   end type run_options

   !> The components an output can need
   integer, parameter :: c_impact = 1, c_velocity = 2, c_timelaw = 3, c_klaw = 4, &
      & c_lambertw = 5, c_ode = 6, c_system = 7, n_components = 7
   character(len=*), parameter :: component_names(n_components) = [character(len=44) :: &
      & "closed forms + quadrature of the times", "closed-form V(x) (Lambert W)", &
      & "time law (quadrature inverted by Newton)", "restitution law k(beta)", &
      & "Lambert W curves", "ODE solver (CVODE)", "a system of bodies on a line"]

contains

   ! ------------------------------------------------------------------------------
   ! Plan and driver
   ! ------------------------------------------------------------------------------

   !> The components output k needs.
   pure function needs(k) result(uses)
      integer, intent(in) :: k
      logical :: uses(n_components)
      uses = .false.
      select case (k)
      case (out_summary, out_sweep, out_impact_sweep)
         uses(c_impact) = .true.
      case (out_phase)
         uses(c_velocity) = .true.
      case (out_loops)
         uses([c_velocity, c_klaw]) = .true.
      case (out_histories)
         uses(c_timelaw) = .true.
      case (out_restitution, out_legacy)
         uses(c_klaw) = .true.
      case (out_lambertw)
         uses(c_lambertw) = .true.
      case (out_cvode)
         uses([c_impact, c_ode]) = .true.
      case (out_contacts, out_final, out_motion, out_system_sweep)
         uses(c_system) = .true.
      end select
   end function needs

   !> How output k is computed, for the plan.
   function method(sc, k) result(text)
      type(scene_type), intent(in) :: sc
      integer, intent(in) :: k
      character(len=:), allocatable :: text
      integer :: ns
      ns = size(sc%speeds)
      select case (k)
      case (out_summary)
         text = "closed forms (Lambert W, double-double) and tanh-sinh quadrature for the" &
            & // " times: " // count_str(ns, "impact")
      case (out_sweep)
         text = "the same closed forms at " // count_str(size(sc%sweep), "speed") // " from " &
            & // real_str(sc%sweep(1), 4) // " to " // real_str(sc%sweep(size(sc%sweep)), 4) &
            & // " m/s"
      case (out_histories)
         text = "time law: quadrature of t(x) inverted by Newton's method, " // str(ns) &
            & // " x " // str(sc%samples) // " times (half in the compression)"
      case (out_phase)
         text = "closed-form V(x) through Lambert W on both branches, " // str(ns) // " x 2 x " &
            & // str(sc%samples) // " points; no quadrature"
      case (out_loops)
         text = "F = c x^n (1 + b V(x)) from the closed-form V(x), " // str(ns) // " x 2 x " &
            & // str(sc%samples) // " points; area checked against (1 - k^2) m V^2/2"
      case (out_restitution)
         text = "k(beta) and 1 - k^2 (Taylor tables / Lambert W), " // str(sc%samples) &
            & // " points, beta from 0 to " // real_str(sc%beta_max, 4)
      case (out_lambertw)
         text = "W0 and W-1 on a grid of z; V = -(1 + W)/b from the offset t, z = -exp(-1-t)"
      case (out_legacy)
         text = str(n_rules) // " damping rules of multibody codes against the exact" &
            & // " beta(e), at each speed's restitution"
      case (out_cvode)
         text = "CVODE at " // count_str(size(sc%tolerances), "tolerance") // " x " &
            & // count_str(ns, "speed") // ", against the closed forms"
      case (out_contacts, out_final, out_motion)
         text = system_method(sc, k)
      case (out_system_sweep)
         text = system_sweep_method(sc)
      case (out_impact_sweep)
         text = impact_sweep_method(sc)
      case default
         text = ""
      end select
   end function method

   !> Run a scene: plan, compute, write. Returns the program's exit code.
   subroutine run_scene(sc, scene_text, opts, code)
      !> The scene
      type(scene_type), intent(in) :: sc
      !> The text of the scene file (copied to scene.nml in the results)
      character(len=*), intent(in) :: scene_text(:)
      !> How to run
      type(run_options), intent(in) :: opts
      !> Exit code
      integer, intent(out) :: code
      type(results_type) :: res
      type(csv_type) :: csv
      character(len=:), allocatable :: error, log_text
      logical :: used(n_components), unavailable, system_done
      integer :: k, i
      real(wp) :: t0

      call console_begin(opts%quiet, opts%progress)
      code = exit_ok
      t0 = wall_clock()
      if (sc%is_system) then
         call describe_system(sc)
      else
         call describe_scene(sc)
      end if

      ! the plan
      used = .false.
      call say("Plan (only what the outputs need):")
      do k = 1, n_outputs
         if (.not. sc%wanted(k)) cycle
         used = used .or. needs(k)
         call say_text("  " // pad(output_names(k), 12), method(sc, k))
      end do
      ! a system's isolated contacts come from the closed forms of one impact and its
      ! time law, but with the method integrated; its clusters from CVODE, but with the
      ! method exact; the restitution law always
      if (sc%is_system) then
         ! (k(b V) is the contacts' column beside each restitution, and beta(e) gives b
         ! where a restitution is given)
         used(c_klaw) = .true.
         used([c_impact, c_timelaw]) = sc%system%method /= method_integrated
         used(c_ode) = sc%system%method /= method_exact
      end if
      if (.not. all(used)) call say_wrapped("  not needed: ", pack(component_names, .not. used))
      if (sc%wanted(out_summary) .or. sc%wanted(out_sweep) .or. sc%wanted(out_impact_sweep)) &
         & call say_text("  impacts: ", &
         & sweep_description())
      if (sc%wanted(out_system_sweep)) call say_text("  runs: ", sweep_description(.true.))
      if (sc%wanted(out_cvode)) then
         if (.not. ode_available) then
            call shout("error: the output 'cvode' needs the CVODE component: " // ode_missing)
            code = exit_unavailable
            return
         end if
         call say_text("  ODE solver: ", ode_description)
      end if
      if (sc%is_system) then
         if (system_needs_ode(sc) .and. .not. ode_available) then
            call shout("error: the method 'integrated' needs the CVODE component: " &
               & // ode_missing)
            code = exit_unavailable
            return
         end if
         if (sc%system%method /= method_exact) call say_text("  ODE solver: ", &
            & ode_chain_description)
      end if
      if (opts%plan_only) then
         if (console_failed()) then
            call shout("error: the standard output: writing failed: " // console_reason())
            code = exit_failure
         end if
         return
      end if

      if (opts%write_files) then
         call open_results(opts%output_dir, res, error)
         if (allocated(error)) then
            call shout("error: " // error)
            code = exit_failure
            return
         end if
      end if

      if (sc%is_system) then
         call write_system_parameters(sc, res, error)
      else
         call write_parameters(sc, res, error)
      end if
      system_done = .false.
      unavailable = .false.
      do k = 1, n_outputs
         if (allocated(error)) exit
         if (.not. sc%wanted(k)) cycle
         ! one run of a system gives all its outputs (the sweep of systems is its own)
         if (system_outputs(k) .and. system_done .and. k /= out_system_sweep) cycle
         select case (k)
         case (out_summary)
            call run_summary(sc, sc%speeds, "summary", res, .true., error)
         case (out_sweep)
            call run_summary(sc, sc%sweep, "sweep", res, .false., error)
         case (out_histories)
            call run_histories(sc, res, error)
         case (out_phase)
            call run_phase(sc, res, .false., error)
         case (out_loops)
            call run_phase(sc, res, .true., error)
         case (out_restitution)
            call run_restitution(sc, res, error)
         case (out_lambertw)
            call run_lambertw(sc, res, error)
         case (out_legacy)
            call run_legacy(sc, res, error)
         case (out_cvode)
            call run_cvode(sc, res, error)
         case (out_contacts, out_final, out_motion)
            call run_system(sc, res, error, unavailable)
            system_done = .true.
         case (out_system_sweep)
            call run_system_sweep(sc, res, error)
         case (out_impact_sweep)
            call run_impact_sweep(sc, res, error)
         end select
         if (allocated(error)) then
            call shout("error: " // trim(output_names(k)) // ": " // error)
            call abandon_results(res)
            if (res%active) call shout("nothing written: the partial results were removed")
            code = exit_failure
            if (unavailable) code = exit_unavailable
            return
         end if
      end do

      call say("Total: " // duration_str(wall_clock() - t0))
      if (res%active) then
         call csv_open(res, "scene.nml", [character(len=1) ::], csv, error)
         do i = 1, size(scene_text)
            call csv_line(csv, trim(scene_text(i)))
         end do
         call csv_close(csv, error)
         if (.not. allocated(error)) then
            call say_text("Results: ", res%path // "/ (" // join(res%files(1:res%n_files), ", ") &
               & // ", log.txt)")
            call csv_open(res, "log.txt", [character(len=1) ::], csv, error)
         end if
         if (.not. allocated(error)) then
            log_text = console_log()
            if (len(log_text) > 0) call csv_line(csv, log_text(1:len(log_text) - 1))
            ! the last line lists the files of this run (log.txt among them): those the
            ! next run into the directory removes when it does not write them itself
            call csv_line(csv, manifest_line(res))
            call csv_close(csv, error)
         end if
      end if
      ! the console is part of the results: a table that did not reach it fails the run
      if (console_failed() .and. .not. allocated(error)) error = "the standard output:" &
         & // " writing failed: " // console_reason()
      if (.not. allocated(error)) call commit_results(res, error)
      if (allocated(error)) then
         call shout("error: " // error)
         call abandon_results(res)
         if (res%active) call shout("nothing written: the partial results were removed")
         code = exit_failure
         return
      end if
   end subroutine run_scene

   !> parameters.csv: the scene's resolved parameters, as name, value, unit.
   subroutine write_parameters(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      call csv_open(res, "parameters.csv", [character(len=8) :: "name", "value", "unit"], &
         & csv, error)
      if (allocated(error) .or. .not. csv%opened) return
      call csv_line(csv, "title," // csv_text(sc%title) // ",-")
      call csv_line(csv, "hcimpact_version," // hcimpact_version_string // ",-")
      call item("mass", sc%mass, "kg")
      call item("stiffness", sc%stiffness, "N/m^n")
      call item("exponent", sc%exponent, "-")
      call item("damping", sc%damping, "s/m")
      call item("mass1", sc%body1%mass, "kg")
      if (sc%two_bodies) then
         call item("mass2", sc%body2%mass, "kg")
      else
         call csv_line(csv, "mass2,inf,kg")
      end if
      call item("target_restitution", sc%target_restitution, "-")
      call item("reference_speed", sc%reference_speed, "m/s")
      call csv_close(csv, error)
   contains
      subroutine item(name, value, unit)
         character(len=*), intent(in) :: name, unit
         real(wp), intent(in) :: value
         call csv_line(csv, name // "," // csv_real(value) // "," // unit)
      end subroutine item
   end subroutine write_parameters

   !> The scene's bodies, contact and damping, for the log.
   subroutine describe_scene(sc)
      type(scene_type), intent(in) :: sc
      character(len=:), allocatable :: text
      call say("hcimpact " // hcimpact_version_string // ": " // sc%title)
      call say("Scene: " // sc%source)
      text = "  body 1: m = " // real_str(sc%body1%mass, 8) // " kg"
      if (sc%body1%mass_from_density) text = text // " (sphere of R = " &
         & // real_str(sc%body1%radius, 6) // " m, rho = " // real_str(sc%body1%density, 6) &
         & // " kg/m^3)"
      if (sc%two_bodies) then
         call say_text("  body 1: ", text(11:))
         text = "  body 2: m = " // real_str(sc%body2%mass, 8) // " kg"
         if (sc%body2%mass_from_density) text = text // " (sphere of R = " &
            & // real_str(sc%body2%radius, 6) // " m, rho = " // real_str(sc%body2%density, 6) &
            & // " kg/m^3)"
         call say_text("  body 2: ", text(11:) // "; effective mass m = " &
            & // real_str(sc%mass, 8) // " kg")
         call say("  body 2 is at rest; the speeds are the approach speeds of body 1")
      else
         call say_text("  body 1: ", text(11:) // "; it strikes a massive flat wall at rest")
      end if
      if (sc%exponent == 1.0_wp) then
         text = " N/m"
      else
         text = " N/m^" // real_str(sc%exponent, 6)
      end if
      call say_text("  contact: ", "f = c x^n, c = " // real_str(sc%stiffness, 8) // text &
         & // ", n = " // real_str(sc%exponent, 6) // " (" // sc%stiffness_origin // ")")
      call say_text("  damping: ", "b = " // real_str(sc%damping, 10) // " s/m (" &
         & // sc%damping_origin // ")")
      if (size(sc%speeds) > 0) then
         if (size(sc%speeds) <= 12) then
            call say("  speeds: " // speeds_list(sc%speeds) // " m/s")
         else
            call say("  speeds: " // count_str(size(sc%speeds), "speed") // " from " &
               & // real_str(minval(sc%speeds), 6) // " to " // real_str(maxval(sc%speeds), 6) &
               & // " m/s")
         end if
      end if
   end subroutine describe_scene

   !> "0.5, 1, 2"
   function speeds_list(v) result(text)
      real(wp), intent(in) :: v(:)
      character(len=:), allocatable :: text
      integer :: i
      text = ""
      do i = 1, size(v)
         if (i > 1) text = text // ", "
         text = text // real_str(v(i), 8)
      end do
   end function speeds_list

   !> The contact at speed v.
   pure function contact_at(sc, v) result(contact)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: v
      type(contact_type) :: contact
      contact = contact_type(mass=sc%mass, stiffness=sc%stiffness, exponent=sc%exponent, &
         & damping=sc%damping, velocity=v)
   end function contact_at

   ! ------------------------------------------------------------------------------
   ! Outputs
   ! ------------------------------------------------------------------------------

   !> The summary (or the sweep): the closed forms at each speed; table and CSV.
   subroutine run_summary(sc, speeds, name, res, table, error)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: speeds(:)
      character(len=*), intent(in) :: name
      type(results_type), intent(inout) :: res
      logical, intent(in) :: table
      character(len=:), allocatable, intent(out) :: error
      type(outcome_type), allocatable :: out(:)
      type(csv_type) :: csv
      real(wp), allocatable :: after(:, :)
      real(wp) :: t0, elapsed, row(15)
      integer(int64) :: evaluations
      integer :: i, stat, ncol, resumed
      integer, allocatable :: stats(:)
      character(len=40), allocatable :: header(:)

      allocate(out(size(speeds)), after(2, size(speeds)), stats(size(speeds)))
      after = nan
      evaluations = 0
      t0 = wall_clock()
      call sweep_impacts([(contact_at(sc, speeds(i)), i = 1, size(speeds))], name, &
         & checkpoint_path(res, name), out, stats, resumed, error)
      if (allocated(error)) return
      do i = 1, size(speeds)
         if (stats(i) /= hcimpact_ok) then
            error = "the impact at V = " // real_str(speeds(i), 8) // " m/s: " &
               & // status_message(stats(i))
            return
         end if
         evaluations = evaluations + sum(int(out(i)%evaluations, int64))
         if (sc%two_bodies) then
            call two_body_velocities(sc%body1%mass, sc%body2%mass, speeds(i), 0.0_wp, &
               & out(i)%restitution, after(1, i), after(2, i), stat)
         end if
      end do
      elapsed = wall_clock() - t0

      header = [character(len=40) :: "speed [m/s]", "beta [-]", "restitution [-]", &
         & "energy_loss_ratio [-]", "energy_lost [J]", "rebound_velocity [m/s]", &
         & "max_compression [m]", "peak_force [N]", "compression_at_peak_force [m]", &
         & "time_at_peak_force [s]", "compression_time [s]", "contact_time [s]", &
         & "evaluations [-]"]
      if (sc%two_bodies) header = [character(len=40) :: header, "velocity1_after [m/s]", &
         & "velocity2_after [m/s]"]
      ncol = size(header)
      call csv_open(res, name // ".csv", header, csv, error)
      if (allocated(error)) return
      do i = 1, size(speeds)
         row = [speeds(i), damping_number(sc, speeds(i)), out(i)%restitution, &
            & out(i)%energy_loss_ratio, energy_lost(sc, speeds(i), out(i)%energy_loss_ratio), &
            & out(i)%rebound_velocity, out(i)%max_compression, out(i)%peak_force, &
            & out(i)%compression_at_peak_force, out(i)%time_at_peak_force, &
            & out(i)%compression_time, out(i)%contact_time, &
            & real(sum(out(i)%evaluations), wp), after(1, i), after(2, i)]
         call csv_row(csv, row(1:ncol))
      end do
      call csv_close(csv, error)
      if (allocated(error)) return
      if (table) call print_summary(sc, speeds, out, after)
      if (resumed > 0) then
         call say_text(pad(name, 12), count_str(size(speeds), "impact") // " (" &
            & // str(resumed) // " from the checkpoint of an earlier run): " &
            & // duration_str(elapsed) // ", " // str_int64(evaluations) &
            & // " integrand evaluations (quadrature)" // files_note(res, name // ".csv"))
      else
         call say_text(pad(name, 12), count_str(size(speeds), "impact") // ": " &
            & // duration_str(elapsed) // ", " // str_int64(evaluations) &
            & // " integrand evaluations (quadrature)" // files_note(res, name // ".csv"))
      end if
   end subroutine run_summary

   !> The console table of the summary (12 significant digits).
   subroutine print_summary(sc, speeds, out, after)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: speeds(:)
      type(outcome_type), intent(in) :: out(:)
      real(wp), intent(in) :: after(:, :)
      character(len=160) :: line
      integer :: i

      call emit("")
      call emit(sc%title)
      write(line, '(a9, 2a16, 3a19)') "V (m/s)", "k", "dT/T-", "dT (J)", "V+ (m/s)", &
         & "beta = bV"
      if (sc%two_bodies) write(line(len_trim(line) + 1:), '(2a19)') "v1 after (m/s)", &
         & "v2 after (m/s)"
      call emit(trim(line))
      do i = 1, size(speeds)
         write(line, '(f9.3, 2f16.12, 3es19.11e2)') speeds(i), out(i)%restitution, &
            & out(i)%energy_loss_ratio, energy_lost(sc, speeds(i), out(i)%energy_loss_ratio), &
            & out(i)%rebound_velocity, damping_number(sc, speeds(i))
         if (sc%two_bodies) write(line(len_trim(line) + 1:), '(2es19.11e2)') after(:, i)
         call emit(trim(line))
      end do
      call emit("")
      write(line, '(a9, 5a19)') "V (m/s)", "x_max (m)", "F_max (N)", "t(F_max) (s)", &
         & "t_compr. (s)", "t_contact (s)"
      call emit(trim(line))
      do i = 1, size(speeds)
         write(line, '(f9.3, 5es19.11e2)') speeds(i), out(i)%max_compression, &
            & out(i)%peak_force, out(i)%time_at_peak_force, out(i)%compression_time, &
            & out(i)%contact_time
         call emit(trim(line))
      end do
      call emit("")
   end subroutine print_summary

   !> The kinetic energy lost in the impact at speed v, (1 - k^2) m v^2/2 (+inf, without
   !> an overflow exception, where it exceeds the largest double).
   function energy_lost(sc, v, loss_ratio) result(energy)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: v
      !> 1 - k^2
      real(wp), intent(in) :: loss_ratio
      real(wp) :: energy
      energy = 0.0_wp
      if (loss_ratio > 0.0_wp) energy = power_product([loss_ratio, 0.5_wp, sc%mass, v], &
         & [1.0_wp, 1.0_wp, 1.0_wp, 2.0_wp])
   end function energy_lost

   !> beta = b v (finite: the scene reader refuses a b V beyond the largest double).
   function damping_number(sc, v) result(beta)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: v
      real(wp) :: beta
      beta = 0.0_wp
      if (sc%damping > 0.0_wp) beta = power_product([sc%damping, v], [1.0_wp, 1.0_wp])
   end function damping_number

   !> Time histories x(t), V(t), F(t).
   subroutine run_histories(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      type(outcome_type) :: out
      real(wp), allocatable :: t(:), x(:), v(:), f(:)
      real(wp) :: t0, elapsed
      integer :: i, j, stat, m, n1

      m = sc%samples
      n1 = (m + 1) / 2
      allocate(t(m), x(m), v(m), f(m))
      call csv_open(res, "histories.csv", [character(len=24) :: "speed [m/s]", "time [s]", &
         & "compression [m]", "velocity [m/s]", "force [N]"], csv, error)
      if (allocated(error)) return
      t0 = wall_clock()
      call progress_begin("histories", size(sc%speeds))
      do i = 1, size(sc%speeds)
         ! half the times in the compression, half in the restitution (which can last
         ! much longer: for large beta the body creeps back at nearly -1/b)
         call impact(contact_at(sc, sc%speeds(i)), out, stat)
         if (stat == hcimpact_ok) then
            do j = 1, n1
               t(j) = out%compression_time * (real(j - 1, wp) / real(n1 - 1, wp))
            end do
            do j = n1 + 1, m
               t(j) = out%compression_time + (out%contact_time - out%compression_time) &
                  & * (real(j - n1, wp) / real(m - n1, wp))
            end do
            t(n1) = out%compression_time
            t(m) = out%contact_time
            call time_law(contact_at(sc, sc%speeds(i)), t, x, v, f, stat)
         end if
         if (stat /= hcimpact_ok) then
            call progress_end()
            call csv_close(csv, error)
            error = "the time law at V = " // real_str(sc%speeds(i), 8) // " m/s: " &
               & // status_message(stat)
            return
         end if
         do j = 1, size(t)
            call csv_row(csv, [sc%speeds(i), t(j), x(j), v(j), f(j)])
         end do
         call progress_step(i)
      end do
      call progress_end()
      call csv_close(csv, error)
      if (allocated(error)) return
      elapsed = wall_clock() - t0
      call say_text(pad("histories", 12), str(size(sc%speeds)) // " x " // str(sc%samples) &
         & // " times: " // duration_str(elapsed) // files_note(res, "histories.csv"))
   end subroutine run_histories

   !> Closed-form x_max = [(n+1) m V^2 H/c]^(1/(n+1)), H = h(beta)/beta^2 (MODEL.md);
   !> +inf where it exceeds the largest double.
   function max_compression(sc, v) result(x)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: v
      real(wp) :: x, beta, h, a
      beta = damping_number(sc, v)
      if (beta < 1.0e-4_wp) then
         ! h(u)/u^2 = 1/2 - u/3 + u^2/4 - u^3/5 + ...
         h = 0.5_wp - beta * (1.0_wp / 3.0_wp - beta * (0.25_wp - beta / 5.0_wp))
      else
         ! (h/beta)/beta: beta^2 overflows above 1e154
         h = (u_minus_log1p(beta) / beta) / beta
      end if
      a = 1.0_wp / (sc%exponent + 1.0_wp)
      x = power_product([sc%exponent + 1.0_wp, sc%mass, v, h, sc%stiffness], &
         & [a, a, 2.0_wp * a, a, -a])
   end function max_compression

   !> The contact force F = c x^n (1 + b V) at compression x and velocity V (+inf where
   !> it exceeds the largest double).
   function contact_force(sc, x, v) result(force)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: x, v
      real(wp) :: force, factor
      ! 1 + b V > 0 on both branches (V > -1/b), but may round to 0 next to -1/b
      factor = 1.0_wp + sc%damping * v
      force = 0.0_wp
      if (x > 0.0_wp .and. factor > 0.0_wp) force = power_product([sc%stiffness, x, factor], &
         & [1.0_wp, sc%exponent, 1.0_wp])
   end function contact_force

   !> Phase trajectories V(x) (phase.csv) or force-deformation loops F(x) (loops.csv),
   !> both from the closed-form V(x) on a grid clustered at x_max.
   subroutine run_phase(sc, res, loops, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      logical, intent(in) :: loops
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      real(wp), allocatable :: x(:), vc(:), vr(:), fc(:), fr(:)
      real(wp) :: t0, elapsed, xmax, s, area, lost, worst, fmax
      integer :: i, j, m, stat
      character(len=:), allocatable :: name

      m = sc%samples
      allocate(x(m), vc(m), vr(m), fc(m), fr(m))
      if (loops) then
         name = "loops"
         call csv_open(res, "loops.csv", [character(len=24) :: "phase [-]", "speed [m/s]", &
            & "compression [m]", "force [N]"], csv, error)
      else
         name = "phase"
         call csv_open(res, "phase.csv", [character(len=24) :: "phase [-]", "speed [m/s]", &
            & "compression [m]", "velocity [m/s]"], csv, error)
      end if
      if (allocated(error)) return
      t0 = wall_clock()
      worst = 0.0_wp
      do i = 1, size(sc%speeds)
         xmax = max_compression(sc, sc%speeds(i))
         if (.not. xmax <= huge(xmax)) then
            call csv_close(csv, error)
            error = "the maximum compression at V = " // real_str(sc%speeds(i), 8) &
               & // " m/s exceeds the largest double"
            return
         end if
         do j = 1, m
            s = real(j - 1, wp) / real(m - 1, wp)
            x(j) = xmax * (s * (2.0_wp - s))
         end do
         x(m) = xmax
         do j = 1, m - 1
            call velocity_at_depth(contact_at(sc, sc%speeds(i)), x(j), compression_branch, &
               & vc(j), stat)
            if (stat == hcimpact_ok) call velocity_at_depth(contact_at(sc, sc%speeds(i)), &
               & x(j), restitution_branch, vr(j), stat)
            if (stat /= hcimpact_ok) then
               call csv_close(csv, error)
               error = "V(x) at V = " // real_str(sc%speeds(i), 8) // " m/s, x = " &
                  & // real_str(x(j), 8) // " m: " // status_message(stat)
               return
            end if
         end do
         ! the turning point
         vc(m) = 0.0_wp
         vr(m) = 0.0_wp
         if (loops) then
            do j = 1, m
               fc(j) = contact_force(sc, x(j), vc(j))
               fr(j) = contact_force(sc, x(j), vr(j))
            end do
            do j = 1, m
               call csv_row(csv, [sc%speeds(i), x(j), fc(j)], "compression")
            end do
            do j = m, 1, -1
               call csv_row(csv, [sc%speeds(i), x(j), fr(j)], "restitution")
            end do
            ! the area of the loop is the energy lost; compared on the scale of x_max F_max
            ! (both may lie beyond the range of doubles when multiplied, the ratio not)
            fmax = maxval(fc)
            lost = energy_lost(sc, sc%speeds(i), energy_loss_ratio(damping_number(sc, &
               & sc%speeds(i))))
            if (fmax > 0.0_wp .and. fmax <= huge(fmax) .and. lost > 0.0_wp &
               & .and. lost <= huge(lost)) then
               area = 0.5_wp * sum(((x(2:m) - x(1:m - 1)) / xmax) * ((fc(2:m) - fr(2:m)) / fmax &
                  & + (fc(1:m - 1) - fr(1:m - 1)) / fmax))
               lost = power_product([lost, xmax, fmax], [1.0_wp, -1.0_wp, -1.0_wp])
               if (lost > 0.0_wp .and. lost <= huge(lost)) worst = max(worst, &
                  & abs(area / lost - 1.0_wp))
            end if
         else
            do j = 1, m
               call csv_row(csv, [sc%speeds(i), x(j), vc(j)], "compression")
            end do
            do j = m, 1, -1
               call csv_row(csv, [sc%speeds(i), x(j), vr(j)], "restitution")
            end do
         end if
      end do
      call csv_close(csv, error)
      if (allocated(error)) return
      elapsed = wall_clock() - t0
      if (loops) then
         call say_text(pad(name, 12), str(size(sc%speeds)) // " x 2 x " // str(m) // " points: " &
            & // duration_str(elapsed) // "; loop area (trapezoids) within " &
            & // real_str(100.0_wp * worst, 2) // " % of (1 - k^2) m V^2/2" &
            & // files_note(res, "loops.csv"))
      else
         call say_text(pad(name, 12), str(size(sc%speeds)) // " x 2 x " // str(m) // " points: " &
            & // duration_str(elapsed) // files_note(res, "phase.csv"))
      end if
   end subroutine run_phase

   !> k(beta) and 1 - k^2 on beta in [0, beta_max].
   subroutine run_restitution(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      real(wp) :: beta, t0
      integer :: j, m

      m = sc%samples
      call csv_open(res, "restitution.csv", [character(len=24) :: "beta [-]", &
         & "restitution [-]", "one_minus_k [-]", "energy_loss_ratio [-]"], csv, error)
      if (allocated(error)) return
      t0 = wall_clock()
      do j = 1, m
         beta = sc%beta_max * real(j - 1, wp) / real(m - 1, wp)
         call csv_row(csv, [beta, restitution(beta), one_minus_restitution(beta), &
            & energy_loss_ratio(beta)])
      end do
      call csv_close(csv, error)
      if (allocated(error)) return
      call say_text(pad("restitution", 12), str(m) // " values of beta: " &
         & // duration_str(wall_clock() - t0) // files_note(res, "restitution.csv"))
   end subroutine run_restitution

   !> The real branches of W (lambertw.csv) and, for b > 0, V(z) on both branches
   !> (velocity_z.csv) with the arcs each impact runs through (motion_z.csv).
   subroutine run_lambertw(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      real(wp), parameter :: e_inv = exp(-1.0_wp), z_max = 3.0_wp, t_max = 8.0_wp
      real(wp) :: s, z, t, t0, hb
      integer :: i, j, m

      m = sc%samples
      t0 = wall_clock()
      call csv_open(res, "lambertw.csv", [character(len=16) :: "branch [-]", "z [-]", &
         & "w [-]"], csv, error)
      if (allocated(error)) return
      ! clustered at the branch point, where W ~ -1 +- sqrt(2 e (z + 1/e))
      do j = 1, m
         s = real(j - 1, wp) / real(m - 1, wp)
         z = -e_inv + (z_max + e_inv) * s * s
         if (j == 1) z = -e_inv
         call csv_row(csv, [z, lambert_w0(z)], "0")
      end do
      do j = 1, m
         s = real(j - 1, wp) / real(m - 1, wp)
         t = t_max * s * s
         z = -exp(-1.0_wp - t)
         if (j == 1) z = -e_inv
         call csv_row(csv, [z, lambert_wm1(z)], "-1")
      end do
      call csv_close(csv, error)
      if (allocated(error)) return
      if (.not. sc%damping > 0.0_wp) then
         call say_text(pad("lambertw", 12), "both branches of W, " // str(m) // " points each: " &
            & // duration_str(wall_clock() - t0) // "; V(z) skipped: it needs b > 0" &
            & // files_note(res, "lambertw.csv"))
         return
      end if
      ! V(z) = -(1 + W(z))/b with z = -exp(-1 - t): 1 + W from the offset t, exactly
      call csv_open(res, "velocity_z.csv", [character(len=16) :: "phase [-]", "z [-]", &
         & "velocity [m/s]"], csv, error)
      if (allocated(error)) return
      do j = 1, m
         s = real(j - 1, wp) / real(m - 1, wp)
         t = t_max * s * s
         call csv_row(csv, [-exp(-1.0_wp - t), quotient_of(-lambert_wm1p1(t), sc%damping)], &
            & "compression")
      end do
      do j = 1, m
         s = real(j - 1, wp) / real(m - 1, wp)
         t = t_max * s * s
         call csv_row(csv, [-exp(-1.0_wp - t), quotient_of(-lambert_w0p1(t), sc%damping)], &
            & "restitution")
      end do
      call csv_close(csv, error)
      if (allocated(error)) return
      ! the arcs: t runs from h(beta) (contact) to 0 (x_max) and back
      call csv_open(res, "motion_z.csv", [character(len=16) :: "phase [-]", "speed [m/s]", &
         & "z [-]", "velocity [m/s]"], csv, error)
      if (allocated(error)) return
      do i = 1, size(sc%speeds)
         hb = u_minus_log1p(damping_number(sc, sc%speeds(i)))
         do j = 1, m
            s = real(j - 1, wp) / real(m - 1, wp)
            t = hb * (1.0_wp - s * s)
            call csv_row(csv, [sc%speeds(i), -exp(-1.0_wp - t), &
               & quotient_of(-lambert_wm1p1(t), sc%damping)], "compression")
         end do
         do j = m, 1, -1
            s = real(j - 1, wp) / real(m - 1, wp)
            t = hb * (1.0_wp - s * s)
            call csv_row(csv, [sc%speeds(i), -exp(-1.0_wp - t), &
               & quotient_of(-lambert_w0p1(t), sc%damping)], "restitution")
         end do
      end do
      call csv_close(csv, error)
      if (allocated(error)) return
      call say_text(pad("lambertw", 12), "both branches of W and V(z), " // str(m) &
         & // " points each: " // duration_str(wall_clock() - t0) &
         & // files_note(res, "lambertw.csv, velocity_z.csv, motion_z.csv"))
   end subroutine run_lambertw

   !> The damping rules of multibody codes at each speed's exact restitution.
   subroutine run_legacy(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      real(wp), allocatable :: e(:), beta(:), kr(:, :), chi(:, :)
      real(wp) :: t0
      integer :: i, j, ns
      character(len=:), allocatable :: line

      ns = size(sc%speeds)
      t0 = wall_clock()
      allocate(e(ns), beta(ns), kr(n_rules, ns), chi(n_rules, ns))
      do i = 1, ns
         beta(i) = damping_number(sc, sc%speeds(i))
         e(i) = restitution(beta(i))
         do j = 1, n_rules
            chi(j, i) = legacy_chi(j, e(i))
            kr(j, i) = restitution(chi(j, i))
         end do
      end do
      call csv_open(res, "legacy.csv", [character(len=28) :: "rule [-]", "speed [m/s]", &
         & "restitution [-]", "beta [-]", "chi [-]", "chi_relative_error [-]", &
         & "k_of_chi [-]", "k_relative_error [-]"], csv, error)
      if (allocated(error)) return
      do i = 1, ns
         do j = 1, n_rules
            call csv_row(csv, [sc%speeds(i), e(i), beta(i), chi(j, i), &
               & signed_rel(chi(j, i), beta(i)), kr(j, i), signed_rel(kr(j, i), e(i))], &
               & '"' // trim(rule_names(j)) // '"')
         end do
      end do
      call csv_close(csv, error)
      if (allocated(error)) return

      call emit("")
      call emit("Damping rules of multibody codes, asked for each speed's exact restitution" &
         & // " e: the restitution k(chi) they give, error (k - e)/e in %")
      allocate(character(len=24 + 10 * ns) :: line)
      write(line, '(a24, *(f10.3))') "V (m/s)", sc%speeds
      call emit(trim(line))
      write(line, '(a24, *(f10.5))') "e (exact)", e
      call emit(trim(line))
      do j = 1, n_rules
         write(line, '(a24)') rule_names(j)
         do i = 1, ns
            if (e(i) < 1.0_wp) then
               write(line(25 + 10 * (i - 1):), '(f10.3)') 100.0_wp * signed_rel(kr(j, i), e(i))
            else
               write(line(25 + 10 * (i - 1):), '(a10)') "-"
            end if
         end do
         call emit(trim(line))
      end do
      call emit("")
      call say_text(pad("legacy", 12), str(n_rules) // " rules x " // count_str(ns, "speed") &
         & // ": " // duration_str(wall_clock() - t0) // files_note(res, "legacy.csv"))
   end subroutine run_legacy

   !> CVODE at each tolerance against the closed forms.
   subroutine run_cvode(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      type(outcome_type) :: exact
      type(ode_run_type) :: run
      real(wp) :: t0, t_exact, t_ode, err(5), total_ode, total_exact, t1
      integer(int64) :: steps, rhs
      integer :: i, j, rep, stat, done
      character(len=160) :: line

      call csv_open(res, "cvode.csv", [character(len=32) :: "speed [m/s]", "rtol [-]", &
         & "error_restitution [-]", "error_max_compression [-]", "error_peak_force [-]", &
         & "error_contact_time [-]", "error_compression_time [-]", "max_error [-]", &
         & "seconds [s]", "steps [-]", "rhs_evaluations [-]", "jacobian_evaluations [-]", &
         & "root_evaluations [-]", "closed_form_seconds [s]", "closed_form_evaluations [-]"], &
         & csv, error)
      if (allocated(error)) return
      call emit("")
      call emit("CVODE against the closed forms (relative errors; time per impact, the best" &
         & // " of 3 runs)")
      write(line, '(a9, a9, 5a11, a12, 2a8)') "V (m/s)", "rtol", "k", "x_max", "F_max", &
         & "t_contact", "max", "time", "steps", "rhs"
      call emit(trim(line))
      total_ode = 0.0_wp
      total_exact = 0.0_wp
      steps = 0
      rhs = 0
      done = 0
      t0 = wall_clock()
      call progress_begin("cvode", size(sc%speeds) * size(sc%tolerances))
      do i = 1, size(sc%speeds)
         ! the closed forms, timed as the best of 3
         t_exact = huge(1.0_wp)
         do rep = 1, 3
            t1 = wall_clock()
            call impact(contact_at(sc, sc%speeds(i)), exact, stat)
            t_exact = min(t_exact, wall_clock() - t1)
         end do
         if (stat /= hcimpact_ok) then
            call progress_end()
            call csv_close(csv, error)
            error = "the closed forms at V = " // real_str(sc%speeds(i), 8) // " m/s: " &
               & // status_message(stat)
            return
         end if
         total_exact = total_exact + t_exact
         do j = 1, size(sc%tolerances)
            ! timed as the best of 3 (the first run also pays for warming the caches)
            t_ode = huge(1.0_wp)
            do rep = 1, 3
               t1 = wall_clock()
               call ode_impact(contact_at(sc, sc%speeds(i)), sc%tolerances(j), run, stat)
               t_ode = min(t_ode, wall_clock() - t1)
               if (stat /= hcimpact_ok) exit
            end do
            if (stat /= hcimpact_ok) then
               call progress_end()
               call csv_close(csv, error)
               error = "CVODE at V = " // real_str(sc%speeds(i), 8) // " m/s, rtol = " &
                  & // real_str(sc%tolerances(j), 3) // ": " // status_message(stat) // ": " &
                  & // run%message
               return
            end if
            total_ode = total_ode + 3.0_wp * t_ode
            steps = steps + run%steps
            rhs = rhs + run%rhs_evals
            err = [rel(run%outcome%restitution, exact%restitution), &
               & rel(run%outcome%max_compression, exact%max_compression), &
               & rel(run%outcome%peak_force, exact%peak_force), &
               & rel(run%outcome%contact_time, exact%contact_time), &
               & rel(run%outcome%compression_time, exact%compression_time)]
            call csv_row(csv, [sc%speeds(i), sc%tolerances(j), err, maxval(err), t_ode, &
               & real(run%steps, wp), real(run%rhs_evals, wp), real(run%jacobian_evals, wp), &
               & real(run%root_evals, wp), t_exact, real(sum(exact%evaluations), wp)])
            call progress_clear()
            write(line, '(f9.3, es9.1, 5es11.2, a12, 2i8)') sc%speeds(i), &
               & sc%tolerances(j), err(1:4), maxval(err), duration_str(t_ode), run%steps, &
               & run%rhs_evals
            call emit(trim(line))
            done = done + 1
            call progress_step(done)
         end do
         write(line, '(f9.3, a9, a55, a12, i8, a)') sc%speeds(i), "closed", &
            & "(the reference)", duration_str(t_exact), sum(exact%evaluations), &
            & " quadrature evaluations"
         call emit(trim(line))
      end do
      call progress_end()
      call csv_close(csv, error)
      if (allocated(error)) return
      call emit("")
      call say_text(pad("cvode", 12), str(size(sc%speeds) * size(sc%tolerances)) &
         & // " integrations: " // duration_str(wall_clock() - t0) // " (CVODE " &
         & // duration_str(total_ode) // ", " // str_int64(steps) // " steps, " &
         & // str_int64(rhs) // " right-hand sides; closed forms " // duration_str(total_exact) &
         & // ")" // files_note(res, "cvode.csv"))
   end subroutine run_cvode

   !> |a - b|/|b|, NaN if either is NaN.
   elemental function rel(a, b) result(r)
      real(wp), intent(in) :: a, b
      real(wp) :: r
      if (ieee_is_nan(a) .or. ieee_is_nan(b)) then
         r = nan
      else if (b == 0.0_wp) then
         r = abs(a)
      else
         r = quotient_of(abs(a - b), abs(b))
      end if
   end function rel

   !> (a - b)/b, NaN if b is 0 or either is NaN.
   elemental function signed_rel(a, b) result(r)
      real(wp), intent(in) :: a, b
      real(wp) :: r
      r = nan
      if (ieee_is_nan(a) .or. ieee_is_nan(b)) return
      if (b /= 0.0_wp) r = quotient_of(a - b, b)
   end function signed_rel

end module hcimpact_scene_run
