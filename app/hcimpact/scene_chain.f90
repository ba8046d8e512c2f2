! SPDX-License-Identifier: Apache-2.0
!> Running a system of bodies on a line (a scene with `&bodies`): the description and
!> the plan, one computation for every output of the system (the closed forms where
!> contacts are isolated, CVODE for clusters: hcimpact_scene_ode's `ode_chain`), the
!> console tables and the CSV files:
!> - `contacts` -> contacts.csv: every contact in the order they ended;
!> - `final` -> final.csv: every body's state at the start and at the end;
!> - `motion` -> motion.csv (positions and velocities) and forces.csv (the pairs'
!>   forces) at `samples` times from 0 to the end. Without an end time the end is
!>   known only after a run: a first run finds it, a second samples [0, 1.1 end].
!> Every system also writes pairs.csv (the laws and gaps of the pairs) next to
!> parameters.csv. doc/scenes.md.
module hcimpact_scene_chain
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_unavailable, status_message
   use hcimpact_version_info, only : hcimpact_version_string
   use hcimpact_restitution_law, only : restitution
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, chain_result, &
      & contact_record, by_closed_forms, by_integration, method_integrated, method_exact, &
      & integrator_adams
   use hcimpact_scene_model, only : scene_type, system_type, wall_type, out_contacts, &
      & out_final, out_motion, nan
   use hcimpact_scene_output, only : results_type, csv_type, csv_open, csv_row, csv_line, &
      & csv_close
   use hcimpact_scene_ode, only : ode_available, ode_missing, ode_chain
   use hcimpact_scene_console, only : say, emit, say_text, files_note, pad, str_int64
   use hcimpact_scene_system, only : wall_clock
   use hcimpact_scene_text, only : str, real_str, duration_str, count_str, csv_real, csv_text
   implicit none
   private

   public :: system_method, system_needs_ode, describe_system, write_system_parameters, &
      & run_system

   !> Rows of the console tables before "... more in the file"
   integer, parameter :: table_rows = 20

contains

   !> How output k of a system is computed, for the plan.
   function system_method(sc, k) result(text)
      type(scene_type), intent(in) :: sc
      integer, intent(in) :: k
      character(len=:), allocatable :: text
      character(len=:), allocatable :: how
      select case (sc%system%method)
      case (method_integrated)
         how = "CVODE for the whole system (method 'integrated')"
      case (method_exact)
         how = "the closed forms of one impact for every contact (method 'exact')"
      case default
         how = "the closed forms where contacts are isolated, CVODE for clusters"
      end select
      select case (k)
      case (out_contacts)
         text = "every contact of the " // bodies_text(sc%system%n) // ": " // how
      case (out_final)
         text = "each body's state at the end: the same run"
      case (out_motion)
         text = "positions, velocities, pair forces at " // str(sc%samples) // " times: the" &
            & // " same run"
         if (.not. sc%system%t_end > 0.0_wp) text = text // " (a first run finds the end)"
      case default
         text = ""
      end select
   end function system_method

   !> Whether the system surely needs CVODE (method 'integrated'); a cluster met on the
   !> way is known only when it forms.
   pure logical function system_needs_ode(sc)
      type(scene_type), intent(in) :: sc
      system_needs_ode = sc%system%method == method_integrated
   end function system_needs_ode

   !> The system, for the log.
   subroutine describe_system(sc)
      type(scene_type), intent(in) :: sc
      type(system_type) :: s
      character(len=:), allocatable :: text
      real(wp), allocatable :: c(:), n(:), b(:)
      s = sc%system
      call say("hcimpact " // hcimpact_version_string // ": " // sc%title)
      call say("Scene: " // sc%source)
      text = bodies_text(s%n) // " on a line, numbered from the left: m = " &
         & // range_text(s%mass, "kg")
      if (s%mass_from_density) text = text // " (spheres: radius " // range_text(s%radius, &
         & "m") // ", density " // range_text(s%density, "kg/m^3") // ")"
      call say_text("  bodies: ", text)
      call say_text("  velocities: ", range_text(s%velocity, "m/s") // " (positive to the" &
         & // " right)")
      if (s%n > 1) then
         call say_text("  gaps: ", range_text(s%gap, "m") // " (0: touching)")
         ! (the laws' parts as arrays of their own: passed as parts of the laws, each
         ! would be copied into a temporary, which the Debug build reports)
         c = s%law%stiffness
         n = s%law%exponent
         b = s%law%damping
         call say_text("  pairs: ", "f = c x^n (1 + b x'), c = " // range_text(c, "N/m^n") &
            & // " (" // s%law_origin // "), n = " // range_text(n, "") // ", b = " &
            & // range_text(b, "s/m") // " (" // s%damping_origin // ")")
      end if
      call say_text("  left wall: ", wall_text(s%left))
      call say_text("  right wall: ", wall_text(s%right))
      call say("  gravity: " // real_str(s%gravity, 6) // " m/s^2 along the line")
      if (s%t_end > 0.0_wp) then
         text = "until t = " // real_str(s%t_end, 6) // " s"
      else
         text = "until no contact can happen again (or the system rests on a wall)"
      end if
      text = text // "; CVODE: " // merge("Adams", "BDF  ", s%integrator == integrator_adams)
      text = trim(text) // ", rtol = " // real_str(s%rtol, 3)
      call say_text("  run: ", text)
   end subroutine describe_system

   !> A wall, for the log.
   function wall_text(w) result(text)
      type(wall_type), intent(in) :: w
      character(len=:), allocatable :: text
      if (.not. w%present) then
         text = "none"
         return
      end if
      text = "gap " // real_str(w%gap, 6) // " m; c = " // real_str(w%law%stiffness, 8) &
         & // " N/m^n (" // w%law_origin // "), n = " // real_str(w%law%exponent, 6) &
         & // ", b = " // real_str(w%law%damping, 8) // " s/m (" // w%damping_origin // ")"
   end function wall_text

   !> "1 body", "5 bodies"
   pure function bodies_text(n) result(text)
      integer, intent(in) :: n
      character(len=:), allocatable :: text
      if (n == 1) then
         text = "1 body"
      else
         text = str(n) // " bodies"
      end if
   end function bodies_text

   !> "0.1 kg" when all values are equal, else "0.1 .. 0.3 kg".
   function range_text(values, unit) result(text)
      real(wp), intent(in) :: values(:)
      character(len=*), intent(in) :: unit
      character(len=:), allocatable :: text
      if (size(values) == 0) then
         text = "none"
      else if (all(values == values(1))) then
         text = real_str(values(1), 8)
      else
         text = real_str(minval(values), 8) // " .. " // real_str(maxval(values), 8)
      end if
      if (len(unit) > 0) text = text // " " // unit
   end function range_text

   !> parameters.csv (name, value, unit) and pairs.csv (the pairs' laws and gaps) of a
   !> system.
   subroutine write_system_parameters(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      type(system_type) :: s
      integer :: p
      s = sc%system
      call csv_open(res, "parameters.csv", [character(len=8) :: "name", "value", "unit"], &
         & csv, error)
      if (allocated(error)) return
      call csv_line(csv, "title," // csv_text(sc%title) // ",-")
      call csv_line(csv, "hcimpact_version," // hcimpact_version_string // ",-")
      call csv_line(csv, "kind,system,-")
      call item("bodies", real(s%n, wp), "-")
      call item("total_mass", sum(s%mass), "kg")
      call item("gravity", s%gravity, "m/s^2")
      call item("t_end", merge(s%t_end, nan, s%t_end > 0.0_wp), "s")
      call item("rtol", s%rtol, "-")
      call item("left_wall", merge(1.0_wp, 0.0_wp, s%left%present), "-")
      call item("left_wall_gap", merge(s%left%gap, nan, s%left%present), "m")
      call item("right_wall", merge(1.0_wp, 0.0_wp, s%right%present), "-")
      call item("right_wall_gap", merge(s%right%gap, nan, s%right%present), "m")
      call item("target_restitution", s%target_restitution, "-")
      call item("reference_speed", s%reference_speed, "m/s")
      call csv_close(csv, error)
      if (allocated(error)) return
      call csv_open(res, "pairs.csv", [character(len=20) :: "pair [-]", &
         & "stiffness [N/m^n]", "exponent [-]", "damping [s/m]", "gap [m]"], csv, error)
      if (allocated(error)) return
      if (s%left%present) call csv_row(csv, [0.0_wp, law_row(s%left%law), s%left%gap])
      do p = 1, s%n - 1
         call csv_row(csv, [real(p, wp), law_row(s%law(p)), s%gap(p)])
      end do
      if (s%right%present) call csv_row(csv, [real(s%n, wp), law_row(s%right%law), &
         & s%right%gap])
      call csv_close(csv, error)
   contains
      subroutine item(name, value, unit)
         character(len=*), intent(in) :: name, unit
         real(wp), intent(in) :: value
         call csv_line(csv, name // "," // csv_real(value) // "," // unit)
      end subroutine item
   end subroutine write_system_parameters

   !> c, n, b of a law
   pure function law_row(law) result(row)
      type(contact_law), intent(in) :: law
      real(wp) :: row(3)
      row = [law%stiffness, law%exponent, law%damping]
   end function law_row

   !> The library's system and options of a scene.
   subroutine to_library(s, chain, options)
      type(system_type), intent(in) :: s
      type(chain_type), intent(out) :: chain
      type(chain_options), intent(out) :: options
      chain%mass = s%mass
      chain%velocity = s%velocity
      chain%gap = s%gap
      chain%law = s%law
      chain%left_wall = s%left%present
      chain%left_law = s%left%law
      chain%left_gap = s%left%gap
      chain%right_wall = s%right%present
      chain%right_law = s%right%law
      chain%right_gap = s%right%gap
      chain%gravity = s%gravity
      options%t_end = s%t_end
      options%rtol = s%rtol
      options%method = s%method
      options%integrator = s%integrator
   end subroutine to_library

   !> Compute the system once for all its outputs; print the tables, write the files.
   !> `unavailable`: the computation needs the CVODE component, which this build lacks.
   subroutine run_system(sc, res, error, unavailable)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      logical, intent(out) :: unavailable
      type(chain_type) :: chain
      type(chain_options) :: options
      type(chain_result) :: result
      real(wp) :: t0, elapsed, t_stop
      integer :: stat, j, runs
      character(len=:), allocatable :: files, note

      unavailable = .false.
      call to_library(sc%system, chain, options)
      t0 = wall_clock()
      runs = 1
      if (sc%wanted(out_motion)) then
         t_stop = sc%system%t_end
         if (.not. t_stop > 0.0_wp) then
            ! the end is known only after a run
            call ode_chain(chain, options, result, stat)
            if (stat /= hcimpact_ok) then
               call failed(stat, result%message)
               return
            end if
            runs = 2
            t_stop = 1.1_wp * result%time
            options%t_end = t_stop
            if (.not. t_stop > 0.0_wp) options%t_end = -1.0_wp
         end if
         allocate(options%sample_times(sc%samples))
         do j = 1, sc%samples
            options%sample_times(j) = t_stop * (real(j - 1, wp) / real(sc%samples - 1, wp))
         end do
         options%sample_times(sc%samples) = t_stop
      end if
      call ode_chain(chain, options, result, stat)
      elapsed = wall_clock() - t0
      if (stat /= hcimpact_ok) then
         call failed(stat, result%message)
         return
      end if

      call print_tables(sc, result)
      note = ""
      if (runs == 2) note = " (2 runs: the first found the end)"
      files = ""
      if (sc%wanted(out_contacts)) then
         call write_contacts(sc, result, res, error)
         if (allocated(error)) return
         files = "contacts.csv"
      end if
      if (sc%wanted(out_final)) then
         call write_final(sc, result, res, error)
         if (allocated(error)) return
         if (len(files) > 0) files = files // ", "
         files = files // "final.csv"
      end if
      if (sc%wanted(out_motion)) then
         call write_motion(sc, options%sample_times, result, res, error)
         if (allocated(error)) return
         if (len(files) > 0) files = files // ", "
         files = files // "motion.csv, forces.csv"
      end if
      call say_text(pad("system", 12), bodies_text(sc%system%n) // ", " &
         & // count_str(int(min(result%n_contacts, int(huge(1), int64))), "contact") // " (" &
         & // str_int64(result%counters%closed_form_contacts) // " by the closed forms, " &
         & // str_int64(result%counters%integrated_contacts) // " integrated: " &
         & // str_int64(result%counters%clusters) // " cluster(s), " &
         & // str_int64(result%counters%steps) // " CVODE steps, " &
         & // str_int64(result%counters%rhs_evals) // " right-hand sides, " &
         & // str_int64(result%counters%jacobian_evals) // " Jacobians): " &
         & // duration_str(elapsed) // note // files_note(res, files))

   contains

      subroutine failed(status, message)
         integer, intent(in) :: status
         character(len=*), intent(in) :: message
         if (status == hcimpact_err_unavailable .and. .not. ode_available) then
            unavailable = .true.
            error = "the system of bodies needs the CVODE component: " // trim(message) &
               & // ". " // ode_missing
         else
            error = status_message(status) // ": " // trim(message)
         end if
      end subroutine failed

   end subroutine run_system

   !> The law of pair p (0: the left wall, n: the right wall).
   function pair_law(s, p) result(law)
      type(system_type), intent(in) :: s
      integer, intent(in) :: p
      type(contact_law) :: law
      if (p == 0) then
         law = s%left%law
      else if (p == s%n) then
         law = s%right%law
      else
         law = s%law(p)
      end if
   end function pair_law

   !> The restitution of a contact, and that of the closed forms of one impact at its
   !> approach speed, k(b V) (NaN for a contact that began touching, V = 0).
   subroutine contact_restitution(s, r, measured, closed_form)
      type(system_type), intent(in) :: s
      type(contact_record), intent(in) :: r
      real(wp), intent(out) :: measured, closed_form
      type(contact_law) :: law
      measured = nan
      closed_form = nan
      if (.not. r%approach_speed > 0.0_wp) return
      measured = r%separation_speed / r%approach_speed
      law = pair_law(s, r%pair)
      closed_form = restitution(law%damping * r%approach_speed)
   end subroutine contact_restitution

   !> The console: final state, balances, contacts, the decisions of the engine.
   subroutine print_tables(sc, result)
      type(scene_type), intent(in) :: sc
      type(chain_result), intent(in) :: result
      character(len=200) :: line
      character(len=:), allocatable :: text
      real(wp) :: e, k
      integer :: i, n, shown
      logical :: elastic

      n = sc%system%n
      call emit("")
      call emit(sc%title)
      write(line, '(a6, 4a19)') "body", "m (kg)", "v before (m/s)", "v after (m/s)", &
         & "position (m)"
      call emit(trim(line))
      do i = 1, n
         if (n > table_rows .and. i > table_rows / 2 .and. i <= n - table_rows / 2) then
            if (i == table_rows / 2 + 1) call emit("   ... " // str(n - table_rows) &
               & // " more bodies in final.csv")
            cycle
         end if
         write(line, '(i6, 4es19.10e3)') i, sc%system%mass(i), sc%system%velocity(i), &
            & result%velocities(i), result%positions(i)
         call emit(trim(line))
      end do
      call emit("")
      if (result%rested) then
         line = "came to rest on a wall at t = " // real_str(result%rest_time, 10) // " s"
      else if (sc%system%t_end > 0.0_wp .or. allocated(result%sample_positions)) then
         line = "until t = " // real_str(result%time, 10) // " s"
      else
         line = "no contact can happen after t = " // real_str(result%time, 10) // " s"
      end if
      call emit("  " // trim(line))
      call emit("  contacts: " // str_int64(result%n_contacts) // " (" &
         & // str_int64(result%counters%closed_form_contacts) // " by the closed forms, " &
         & // str_int64(result%counters%integrated_contacts) // " integrated by CVODE in " &
         & // str_int64(result%counters%clusters) // " cluster(s))")
      elastic = all(sc%system%law%damping == 0.0_wp) .and. (.not. sc%system%left%present &
         & .or. sc%system%left%law%damping == 0.0_wp) .and. (.not. sc%system%right%present &
         & .or. sc%system%right%law%damping == 0.0_wp)
      text = "  energy: initial " // real_str(result%initial_energy, 8) // " J, dissipated " &
         & // real_str(result%dissipated, 8) // " J; balance error " &
         & // real_str(result%energy_error, 3)
      if (elastic) text = text // " (b = 0: energy is conserved, to the solver's" &
         & // " tolerance where CVODE ran)"
      call emit(text)
      if (.not. ieee_is_nan(result%momentum_error)) then
         if (sc%system%left%present .or. sc%system%right%present) then
            call emit("  walls' impulses: left " // real_str(result%wall_impulse(1), 8) &
               & // " N s, right " // real_str(result%wall_impulse(2), 8) // " N s")
            call emit("  momentum: relative error " // real_str(result%momentum_error, 3) &
               & // " (against the initial momentum plus the walls' impulses and " &
               & // "gravity's M g t)")
         else if (sc%system%gravity == 0.0_wp) then
            call emit("  momentum: relative change " // real_str(result%momentum_error, 3) &
               & // " (conserved: no wall, no gravity)")
         else
            call emit("  momentum: relative error " // real_str(result%momentum_error, 3) &
               & // " (no wall: the momentum changes by gravity's impulse M g t alone)")
         end if
      end if

      if (size(result%contacts) > 0) then
         call emit("")
         write(line, '(a5, 2a17, 2a12, 2a9, a13, a14)') "pair", "start (s)", "end (s)", &
            & "V in (m/s)", "V out", "e", "k(bV)", "F_max (N)", "method"
         call emit(trim(line))
         shown = min(size(result%contacts), table_rows)
         do i = 1, shown
            call contact_restitution(sc%system, result%contacts(i), e, k)
            write(line, '(i5, 2es17.9e3, 2f12.6, 2f9.5, es13.4e3, a14)') &
               & result%contacts(i)%pair, result%contacts(i)%t_start, &
               & result%contacts(i)%t_end, result%contacts(i)%approach_speed, &
               & result%contacts(i)%separation_speed, e, k, result%contacts(i)%peak_force, &
               & merge("closed forms", "CVODE       ", &
               & result%contacts(i)%method == by_closed_forms)
            call emit(trim(line))
         end do
         if (result%n_contacts > shown) call emit("  ... " // str_int64(result%n_contacts &
            & - shown) // " more in contacts.csv")
         call emit("  (e = V out/V in; k(bV): the closed forms' restitution of one impact" &
            & // " at V in)")
      end if
      if (size(result%switches) > 0) then
         call say("  decisions of the engine (the first " // str(min(size(result%switches), &
            & 10)) // " of " // str(size(result%switches)) // "):")
         do i = 1, min(size(result%switches), 10)
            if (result%switches(i)%first == 0) then
               call say("    t = " // real_str(result%switches(i)%time, 10) // " s: the" &
                  & // " cluster dissolved (" // trim(result%switches(i)%reason) // ")")
            else
               call say("    t = " // real_str(result%switches(i)%time, 10) // " s: bodies " &
                  & // str(result%switches(i)%first) // " to " // str(result%switches(i)%last) &
                  & // " integrated: " // trim(result%switches(i)%reason))
            end if
         end do
      end if
      call emit("")
   end subroutine print_tables

   !> contacts.csv
   subroutine write_contacts(sc, result, res, error)
      type(scene_type), intent(in) :: sc
      type(chain_result), intent(in) :: result
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      real(wp) :: e, k
      integer :: i
      call csv_open(res, "contacts.csv", [character(len=32) :: "method", "pair [-]", &
         & "t_start [s]", "t_end [s]", "duration [s]", "approach_speed [m/s]", &
         & "separation_speed [m/s]", "restitution [-]", "closed_form_restitution [-]", &
         & "peak_force [N]", "max_deformation [m]", "dissipated [J]"], csv, error)
      if (allocated(error)) return
      do i = 1, size(result%contacts)
         associate (r => result%contacts(i))
            call contact_restitution(sc%system, r, e, k)
            call csv_row(csv, [real(r%pair, wp), r%t_start, r%t_end, r%t_end - r%t_start, &
               & r%approach_speed, r%separation_speed, e, k, r%peak_force, &
               & r%max_deformation, r%dissipated], &
               & label=trim(merge("closed_forms", "integration ", r%method == by_closed_forms)))
         end associate
      end do
      call csv_close(csv, error)
   end subroutine write_contacts

   !> final.csv
   subroutine write_final(sc, result, res, error)
      type(scene_type), intent(in) :: sc
      type(chain_result), intent(in) :: result
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      real(wp) :: q0
      integer :: i
      call csv_open(res, "final.csv", [character(len=28) :: "body [-]", "mass [kg]", &
         & "initial_position [m]", "initial_velocity [m/s]", "position [m]", &
         & "velocity [m/s]", "time [s]"], csv, error)
      if (allocated(error)) return
      q0 = 0.0_wp
      do i = 1, sc%system%n
         if (i > 1) q0 = q0 + sc%system%gap(i - 1)
         call csv_row(csv, [real(i, wp), sc%system%mass(i), q0, sc%system%velocity(i), &
            & result%positions(i), result%velocities(i), result%time])
      end do
      call csv_close(csv, error)
   end subroutine write_final

   !> motion.csv and forces.csv: long tables over the sample times.
   subroutine write_motion(sc, times, result, res, error)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: times(:)
      type(chain_result), intent(in) :: result
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(csv_type) :: csv
      integer :: i, j, first, last
      call csv_open(res, "motion.csv", [character(len=16) :: "time [s]", "body [-]", &
         & "position [m]", "velocity [m/s]"], csv, error)
      if (allocated(error)) return
      do j = 1, size(times)
         do i = 1, sc%system%n
            call csv_row(csv, [times(j), real(i, wp), result%sample_positions(i, j), &
               & result%sample_velocities(i, j)])
         end do
      end do
      call csv_close(csv, error)
      if (allocated(error)) return
      call csv_open(res, "forces.csv", [character(len=16) :: "time [s]", "pair [-]", &
         & "force [N]"], csv, error)
      if (allocated(error)) return
      first = merge(0, 1, sc%system%left%present)
      last = merge(sc%system%n, sc%system%n - 1, sc%system%right%present)
      do j = 1, size(times)
         do i = first, last
            call csv_row(csv, [times(j), real(i, wp), result%sample_forces(i, j)])
         end do
      end do
      call csv_close(csv, error)
   end subroutine write_motion

end module hcimpact_scene_chain
