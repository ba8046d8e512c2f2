! SPDX-License-Identifier: Apache-2.0
!> The output `impact_sweep` of a scene of one impact (doc/scenes.md): one impact for
!> every parameter set `&impact_sweep` asks for (the effective mass, the stiffness,
!> the exponent, the damping and the approach speed; their product or the lists side
!> by side; the scene's own value where a name is not varied), the impacts handed out
!> by hcimpact_scene_sweep (MPI ranks, or OpenMP threads, or one after the other, with
!> its checkpoint), one row per set in impact_sweep.csv, in the sets' order, and a
!> short table on the console. A set whose impact fails has its status in its row
!> and NaN outcomes (and the log names the first); the sweep goes on.
module hcimpact_scene_impacts
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, status_message
   use hcimpact_impact_model, only : contact_type, outcome_type
   use hcimpact_scene_model, only : scene_type, nan
   use hcimpact_scene_variations, only : variation_index, variation_count
   use hcimpact_scene_output, only : results_type, csv_type, csv_open, csv_row, csv_close, &
      & checkpoint_path
   use hcimpact_scene_sweep, only : sweep_impacts
   use hcimpact_scene_console, only : emit, say_text, files_note, pad
   use hcimpact_scene_system, only : wall_clock
   use hcimpact_scene_text, only : str, real_str, duration_str, count_str
   implicit none
   private

   public :: impact_sweep_method, run_impact_sweep

   !> Rows of the console table before "... more in the file"
   integer, parameter :: table_rows = 20

contains

   !> How the output is computed, for the plan.
   function impact_sweep_method(sc) result(text)
      type(scene_type), intent(in) :: sc
      character(len=:), allocatable :: text
      text = "closed forms (as summary) for each of " &
         & // count_str(size(impact_sets(sc)), "parameter set")
   end function impact_sweep_method

   !> The impact of every parameter set, in their order: the scene's contact with the
   !> values the set varies replaced (a product: the first list varies slowest). The
   !> scene's own speed, where the sweep varies none, is its first.
   function impact_sets(sc) result(contacts)
      type(scene_type), intent(in) :: sc
      type(contact_type), allocatable :: contacts(:)
      integer :: lengths(5), which(5), k
      real(wp) :: own_speed
      own_speed = nan
      if (size(sc%speeds) > 0) own_speed = sc%speeds(1)
      lengths = [size(sc%vary_mass), size(sc%vary_stiffness), size(sc%vary_exponent), &
         & size(sc%vary_damping), size(sc%vary_speed)]
      allocate(contacts(variation_count(lengths, sc%vary_product)))
      do k = 1, size(contacts)
         which = variation_index(lengths, sc%vary_product, k)
         contacts(k) = contact_type(mass=sc%mass, stiffness=sc%stiffness, &
            & exponent=sc%exponent, damping=sc%damping, velocity=own_speed)
         if (lengths(1) > 0) contacts(k)%mass = sc%vary_mass(which(1))
         if (lengths(2) > 0) contacts(k)%stiffness = sc%vary_stiffness(which(2))
         if (lengths(3) > 0) contacts(k)%exponent = sc%vary_exponent(which(3))
         if (lengths(4) > 0) contacts(k)%damping = sc%vary_damping(which(4))
         if (lengths(5) > 0) contacts(k)%velocity = sc%vary_speed(which(5))
      end do
   end function impact_sets

   !> Compute every set; the console table and impact_sweep.csv.
   subroutine run_impact_sweep(sc, res, error)
      type(scene_type), intent(in) :: sc
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      type(contact_type), allocatable :: contacts(:)
      type(outcome_type), allocatable :: out(:)
      integer, allocatable :: stats(:)
      real(wp) :: t0, elapsed
      character(len=:), allocatable :: note
      integer :: k, failed, first_failed, resumed

      t0 = wall_clock()
      contacts = impact_sets(sc)
      allocate(out(size(contacts)), stats(size(contacts)))
      call sweep_impacts(contacts, "impact_sweep", checkpoint_path(res, "impact_sweep"), &
         & out, stats, resumed, error)
      if (allocated(error)) return
      elapsed = wall_clock() - t0
      failed = 0
      first_failed = 0
      do k = 1, size(contacts)
         if (stats(k) == hcimpact_ok) cycle
         ! a failed impact's outcome is NaN whatever the library left in it
         out(k) = outcome_type()
         failed = failed + 1
         if (first_failed == 0) first_failed = k
      end do
      call print_table(sc, contacts, out, stats)
      call write_rows(contacts, out, stats, res, error)
      if (allocated(error)) return
      note = ""
      if (resumed > 0) note = " (" // str(resumed) // " from the checkpoint of an earlier run)"
      call say_text(pad("impact_sweep", 12), count_str(size(contacts), "impact") // note &
         & // ", " // str(failed) // " failed: " // duration_str(elapsed) &
         & // files_note(res, "impact_sweep.csv"))
      if (failed > 0) call say_text("  ", "set " // str(first_failed) // " (the first that" &
         & // " failed): " // status_message(stats(first_failed)))
   end subroutine run_impact_sweep

   !> impact_sweep.csv: one row per parameter set, in their order.
   subroutine write_rows(contacts, out, stats, res, error)
      type(contact_type), intent(in) :: contacts(:)
      type(outcome_type), intent(in) :: out(:)
      integer, intent(in) :: stats(:)
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      character(len=32), allocatable :: columns(:)
      type(csv_type) :: csv
      integer :: k
      columns = [character(len=32) :: "set [-]", "mass [kg]", "stiffness [N/m^n]", &
         & "exponent [-]", "b [s/m]", "speed [m/s]", "status [-]", "beta [-]", &
         & "restitution [-]", "energy_loss_ratio [-]", "rebound_velocity [m/s]", &
         & "max_compression [m]", "peak_force [N]", "time_at_peak_force [s]", &
         & "compression_time [s]", "contact_time [s]"]
      call csv_open(res, "impact_sweep.csv", columns, csv, error)
      if (allocated(error)) return
      do k = 1, size(contacts)
         associate (c => contacts(k), o => out(k))
            call csv_row(csv, [real(k, wp), c%mass, c%stiffness, c%exponent, c%damping, &
               & c%velocity, real(stats(k), wp), c%damping * c%velocity, o%restitution, &
               & o%energy_loss_ratio, o%rebound_velocity, o%max_compression, o%peak_force, &
               & o%time_at_peak_force, o%compression_time, o%contact_time])
         end associate
      end do
      call csv_close(csv, error)
   end subroutine write_rows

   !> The console: the first rows (set, its parameters, status, restitution, x_max,
   !> contact time).
   subroutine print_table(sc, contacts, out, stats)
      type(scene_type), intent(in) :: sc
      type(contact_type), intent(in) :: contacts(:)
      type(outcome_type), intent(in) :: out(:)
      integer, intent(in) :: stats(:)
      character(len=200) :: line
      integer :: k, shown
      call emit("")
      call emit(sc%title // ": impact_sweep")
      write(line, '(a5, 5a12, a7, 3a14)') "set", "m (kg)", "c (N/m^n)", "n", "b (s/m)", &
         & "V (m/s)", "status", "k", "x_max (m)", "t_c (s)"
      call emit(trim(line))
      shown = min(size(contacts), table_rows)
      do k = 1, shown
         write(line, '(i5, 5a12, i7, 3a14)') k, real_str(contacts(k)%mass, 6), &
            & real_str(contacts(k)%stiffness, 6), real_str(contacts(k)%exponent, 6), &
            & real_str(contacts(k)%damping, 6), real_str(contacts(k)%velocity, 6), stats(k), &
            & real_str(out(k)%restitution, 8), real_str(out(k)%max_compression, 8), &
            & real_str(out(k)%contact_time, 8)
         call emit(trim(line))
      end do
      if (size(contacts) > shown) call emit("  ... " // str(size(contacts) - shown) &
         & // " more in impact_sweep.csv")
      call emit("")
   end subroutine print_table

end module hcimpact_scene_impacts
