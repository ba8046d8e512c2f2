! SPDX-License-Identifier: Apache-2.0
!> The output `system_sweep` of a system of bodies (doc/scenes.md): one whole run of
!> the system for every variation `&system_sweep` asks for (the lists of
!> hcimpact_scene_model's `sweep_names`; their product or the lists side by side), the
!> runs handed out by hcimpact_scene_sweep (MPI ranks, or OpenMP threads, or one after
!> the other), one row per variation in system_sweep.csv, in the variations' order,
!> and a short table on the console. A run that fails has its status in its row (and
!> the log names the first); the sweep goes on.
module hcimpact_scene_systems
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_unavailable, status_message
   use hcimpact_chain_types, only : by_closed_forms, by_integration, method_exact
   use hcimpact_scene_ode, only : ode_available, ode_missing
   use hcimpact_scene_model, only : scene_type, n_sweep_lists, sweep_names, sweep_unit, &
      & sweep_mass, sweep_restitution, sweep_striker_speed
   use hcimpact_scene_output, only : results_type, csv_type, csv_open, csv_row, csv_close, &
      & checkpoint_path
   use hcimpact_scene_system_items, only : system_item_count, system_item_inputs, &
      & item_variation, result_length, result_status, result_time, result_contacts, &
      & result_closed_forms, result_integrated, result_clusters, result_energy_error, &
      & result_dissipated, result_method, result_velocities, result_steps
   use hcimpact_scene_sweep, only : sweep_systems
   use hcimpact_scene_console, only : say, emit, say_text, files_note, pad
   use hcimpact_scene_system, only : wall_clock
   use hcimpact_scene_text, only : str, real_str, duration_str, count_str
   implicit none
   private

   public :: system_sweep_method, run_system_sweep

   !> Rows of the console table before "... more in the file"
   integer, parameter :: table_rows = 20

contains

   !> How the output is computed, for the plan.
   function system_sweep_method(sc) result(text)
      type(scene_type), intent(in) :: sc
      character(len=:), allocatable :: text
      integer :: items, k
      items = system_item_count(sc%system)
      text = "a whole run of the system for each of " // count_str(items, "variation") &
         & // " of &system_sweep"
      if (size(sc%system%vary(sweep_restitution)%values) > 0) text = text // " (b from" &
         & // " each restitution at " // real_str(sc%system%vary_at_speed, 6) // " m/s)"
      if (size(sc%system%vary(sweep_mass)%values) > 0) text = text // "; the masses to " &
         & // bodies_text(sc%system%vary_mass_body, sc%system%n)
      if (size(sc%system%vary(sweep_striker_speed)%values) > 0) text = text &
         & // "; the speeds to " // bodies_text(sc%system%vary_striker_body, sc%system%n)
      if (.not. any([(size(sc%system%vary(k)%values) > 0, k = 1, n_sweep_lists)])) &
         & text = "one run of the system (no &system_sweep)"
   end function system_sweep_method

   !> Run every variation; the console table and system_sweep.csv.
   subroutine run_system_sweep(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      real(wp), allocatable :: inputs(:, :), outputs(:, :)
      real(wp) :: t0, elapsed
      character(len=:), allocatable :: note
      integer :: n, items, failed, first_failed, k, resumed

      n = sc%system%n
      t0 = wall_clock()
      inputs = system_item_inputs(sc%system)
      items = size(inputs, 2)
      allocate(outputs(result_length(n), items))
      call sweep_systems(inputs, outputs, "system_sweep", checkpoint_path(res, &
         & "system_sweep"), resumed, error)
      if (allocated(error)) return
      elapsed = wall_clock() - t0
      call print_table(sc, outputs)
      call write_rows(sc, outputs, res, error)
      if (allocated(error)) return
      failed = 0
      first_failed = 0
      do k = 1, items
         if (nint(outputs(result_status, k)) == hcimpact_ok) cycle
         failed = failed + 1
         if (first_failed == 0) first_failed = k
      end do
      note = ""
      if (resumed > 0) note = " (" // str(resumed) // " from the checkpoint of an earlier run)"
      call say_text(pad("system_sweep", 12), count_str(items, "run") // " of the " &
         & // str(n) // "-body system" // note // ", " // str(failed) // " failed: " &
         & // duration_str(elapsed) // files_note(res, "system_sweep.csv"))
      if (failed > 0) call say_text("  ", "variation " // str(first_failed) // " (the first" &
         & // " that failed): " // failure_text(sc, nint(outputs(result_status, first_failed))))
   end subroutine run_system_sweep

   !> Why a run failed, for the log: the status's text, or a cluster beyond a build
   !> without CVODE. (A row keeps its status alone, as doubles that every process
   !> returns alike: the library's own message, e.g. the bound on contacts a run met,
   !> comes from the variation run alone.)
   function failure_text(sc, status) result(text)
      type(scene_type), intent(in) :: sc
      integer, intent(in) :: status
      character(len=:), allocatable :: text
      text = status_message(status) // " (status " // str(status) // "; the system with" &
         & // " that variation's values, run alone for the output final, gives the" &
         & // " library's own message)"
      if (status /= hcimpact_err_unavailable) return
      if (.not. ode_available .and. sc%system%method /= method_exact) then
         text = "a cluster formed, which needs the CVODE component (status " // str(status) &
            & // "): " // ode_missing
      end if
   end function failure_text

   !> The method a run used, as a word.
   pure function method_word(code) result(word)
      real(wp), intent(in) :: code
      character(len=:), allocatable :: word
      select case (nint(code))
      case (by_closed_forms)
         word = "closed_forms"
      case (by_integration)
         word = "integration"
      case (by_closed_forms + by_integration)
         word = "both"
      case default
         word = "none"
      end select
   end function method_word

   !> system_sweep.csv: one row per variation, in their order.
   subroutine write_rows(sc, outputs, res, error)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: outputs(:, :)
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      ! (the longest: striker_speed_ and a label of 24 characters, with its unit)
      character(len=48), allocatable :: columns(:)
      type(csv_type) :: csv
      real(wp) :: values(n_sweep_lists)
      integer :: n, k, i
      character(len=48), parameter :: results(9) = [character(len=48) :: "status [-]", &
         & "time [s]", "contacts [-]", "closed_form_contacts [-]", "integrated_contacts [-]", &
         & "clusters [-]", "cvode_steps [-]", "energy_error [-]", "dissipated [J]"]
      n = sc%system%n
      allocate(columns(2 + n_sweep_lists + size(results) + n))
      columns(1:2) = [character(len=48) :: "method", "variation [-]"]
      do i = 1, n_sweep_lists
         columns(2 + i) = column_name(sc, i) // " [" // sweep_unit(trim(sweep_names(i))) // "]"
      end do
      columns(3 + n_sweep_lists:2 + n_sweep_lists + size(results)) = results
      do i = 1, n
         columns(2 + n_sweep_lists + size(results) + i) = "velocity_" // str(i) // " [m/s]"
      end do
      call csv_open(res, "system_sweep.csv", columns, csv, error)
      if (allocated(error)) return
      do k = 1, size(outputs, 2)
         call item_variation(sc%system, k, values)
         call csv_row(csv, [real(k, wp), values, outputs(result_status, k), &
            & outputs(result_time, k), outputs(result_contacts:result_clusters, k), &
            & outputs(result_steps, k), outputs(result_energy_error, k), &
            & outputs(result_dissipated, k), outputs(result_velocities:, k)], &
            & label=method_word(outputs(result_method, k)))
      end do
      call csv_close(csv, error)
   end subroutine write_rows

   !> The name of the column of the sweep's list k: its name, the mass's with its
   !> bodies (mass_2, mass_2_3, mass_all), the striker's speed with its bodies unless
   !> that is body 1 alone (striker_speed_3)
   function column_name(sc, k) result(name)
      type(scene_type), intent(in) :: sc
      integer, intent(in) :: k
      character(len=:), allocatable :: name
      name = trim(sweep_names(k))
      if (k == sweep_mass) name = name // "_" // bodies_label(sc%system%vary_mass_body, &
         & sc%system%n)
      if (k == sweep_striker_speed) then
         if (any(sc%system%vary_striker_body /= 1)) name = name // "_" &
            & // bodies_label(sc%system%vary_striker_body, sc%system%n)
      end if
   end function column_name

   !> The bodies a sweep's list goes to, as a column names them: "all" for every body
   !> of a system of several, else their indices in the order given joined by "_", a
   !> run of consecutive ones as first-last (2-12_15); "<count>_bodies" where that is
   !> longer than 24 characters (the log names them all: bodies_text)
   function bodies_label(bodies, n) result(label)
      integer, intent(in) :: bodies(:), n
      character(len=:), allocatable :: label
      if (n > 1 .and. size(bodies) == n) then
         label = "all"
      else
         label = index_runs(bodies, "_")
         if (len(label) > 24) label = str(size(bodies)) // "_bodies"
      end if
   end function bodies_label

   !> The bodies a sweep's list goes to, for the log: "every body", "body 3", or
   !> "bodies 2-12, 15"
   function bodies_text(bodies, n) result(text)
      integer, intent(in) :: bodies(:), n
      character(len=:), allocatable :: text
      if (n > 1 .and. size(bodies) == n) then
         text = "every body"
      else if (size(bodies) == 1) then
         text = "body " // str(bodies(1))
      else
         text = "bodies " // index_runs(bodies, ", ")
      end if
   end function bodies_text

   !> Indices in their order, joined by `separator`, each run of consecutive ones
   !> (k, k + 1, ...) as first-last
   function index_runs(bodies, separator) result(text)
      integer, intent(in) :: bodies(:)
      character(len=*), intent(in) :: separator
      character(len=:), allocatable :: text
      integer :: i, j
      text = ""
      i = 1
      do while (i <= size(bodies))
         j = i
         do while (j < size(bodies))
            if (bodies(j + 1) /= bodies(j) + 1) exit
            j = j + 1
         end do
         if (i > 1) text = text // separator
         text = text // str(bodies(i))
         if (j > i) text = text // "-" // str(bodies(j))
         i = j + 1
      end do
   end function index_runs

   !> The console: the first rows (variation, the values of the lists it varies,
   !> status, contacts, the energy balance, the last body's final velocity).
   subroutine print_table(sc, outputs)
      type(scene_type), intent(in) :: sc
      real(wp), intent(in) :: outputs(:, :)
      ! short headings of the parameters (sweep_names' order)
      character(len=*), parameter :: headings(n_sweep_lists) = [character(len=12) :: &
         & "v1 (m/s)", "m (kg)", "gap (m)", "c (N/m^n)", "n", "b (s/m)", "e", "g (m/s^2)", &
         & "gap L (m)", "gap R (m)", "b L (s/m)", "b R (s/m)", "c L (N/m^n)", "c R (N/m^n)", &
         & "n L", "n R", "t_end (s)"]
      character(len=200) :: line
      character(len=:), allocatable :: head
      real(wp) :: values(n_sweep_lists)
      logical :: varied(n_sweep_lists)
      integer :: k, n, shown, j
      n = sc%system%n
      do j = 1, n_sweep_lists
         varied(j) = size(sc%system%vary(j)%values) > 0
      end do
      call emit("")
      call emit(sc%title // ": system_sweep")
      head = "variation"
      do j = 1, n_sweep_lists
         if (.not. varied(j)) cycle
         if (j == sweep_mass) then
            head = head // pad13("m" // short_label(sc%system%vary_mass_body) // " (kg)")
         else if (j == sweep_striker_speed) then
            head = head // pad13("v" // short_label(sc%system%vary_striker_body) // " (m/s)")
         else
            head = head // pad13(trim(headings(j)))
         end if
      end do
      write(line, '(a7, a10, a13, a16, a14)') "status", "contacts", "energy err", &
         & "v" // str(n) // " end (m/s)", "method"
      call emit(head // trim(line))
      shown = min(size(outputs, 2), table_rows)
      do k = 1, shown
         call item_variation(sc%system, k, values)
         write(line, '(i9)') k
         head = trim(line)
         do j = 1, n_sweep_lists
            if (varied(j)) head = head // pad13(real_str(values(j), 6))
         end do
         write(line, '(i7, a10, a13, a16, a14)') nint(outputs(result_status, k)), &
            & real_str(outputs(result_contacts, k), 10), &
            & real_str(outputs(result_energy_error, k), 3), &
            & real_str(outputs(result_velocities + n - 1, k), 8), &
            & method_word(outputs(result_method, k))
         call emit(head // trim(line))
      end do
      if (size(outputs, 2) > shown) call emit("  ... " // str(size(outputs, 2) - shown) &
         & // " more in system_sweep.csv")
      call emit("")
   contains
      !> The bodies in a heading: one body's index (m2), else "_" and the column's
      !> label (m_all, v_2_3), "_*" where that is longer than 6 characters (the file
      !> and the log name them)
      function short_label(bodies) result(label)
         integer, intent(in) :: bodies(:)
         character(len=:), allocatable :: label
         label = bodies_label(bodies, n)
         if (size(bodies) == 1) return
         if (len(label) > 6) label = "*"
         label = "_" // label
      end function short_label

      !> A text at the right of a field of 13 characters, after one blank at least
      pure function pad13(text) result(field)
         character(len=*), intent(in) :: text
         character(len=:), allocatable :: field
         field = trim(adjustl(text))
         field = repeat(" ", max(1, 13 - len(field))) // field
      end function pad13
   end subroutine print_table

end module hcimpact_scene_systems
