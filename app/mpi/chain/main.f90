! SPDX-License-Identifier: Apache-2.0
!> hcimpact_mpi_chain: a long chain of beads integrated by CVODE over the ranks of MPI
!> (doc/mpi.md), one contiguous block of beads per rank.
!>
!>     mpirun -n N hcimpact_mpi_chain SCENE STATE.csv [CONTACTS.csv]
!>     hcimpact_mpi_chain --serial SCENE STATE.csv [CONTACTS.csv]
!>
!> SCENE holds the namelist &mpi_chain (hcimpact_mpi_chain_scene); STATE.csv receives
!> the final position and velocity of every bead in bead order, CONTACTS.csv (when
!> named) every contact that ended, in pair order (hcimpact_mpi_chain_contacts); the
!> summary (work
!> done, the halo exchanges and their bytes, the energy and momentum balances and the
!> walls' impulses) goes to the standard
!> output. --serial computes the same chain with the CVODE component's serial
!> integrator (`chain_simulate`, method_integrated) in one process without MPI: the
!> reference of the tests.
!>
!> Exit status: 0 success; 1 the integration or an output failed; 2 a bad command
!> line or scene (every rank checks the same scene, and all end alike).
program hcimpact_mpi_chain
   use, intrinsic :: iso_fortran_env, only : int64, output_unit, error_unit
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use mpi_f08, only : MPI_Init, MPI_Finalize, MPI_Comm_rank, MPI_Comm_size, MPI_Gatherv, &
      & MPI_Reduce, MPI_Allreduce, MPI_Bcast, MPI_Barrier, MPI_Wtime, MPI_COMM_WORLD, &
      & MPI_DOUBLE_PRECISION, MPI_INTEGER8, MPI_LOGICAL, MPI_SUM, MPI_MAX, MPI_LAND
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_chain_types, only : chain_type, chain_options, chain_result, max_message, &
      & contact_record, energy_balance_error, momentum_balance_error, gravity_impulse, &
      & momentum
   use hcimpact_cvode_halting, only : halting_suspend, halting_resume
   use hcimpact_cvode, only : chain_simulate
   use hcimpact_cvode_chain_system, only : chain_region, region_scales, region_size, &
      & region_frame, frame_motion, wall_impulse_scale, pushing_impulse
   use hcimpact_mpi_chain_scene, only : chain_scene, read_chain_scene, scene_system
   use hcimpact_mpi_chain_block, only : block_setup, block_partition, halo_doubles, &
      & part_region, region_energy
   use hcimpact_mpi_chain_cvode, only : chain_integration, integrate_chain, &
      & chain_counters_mpi
   use hcimpact_mpi_chain_contacts, only : sort_by_pair, gather_contacts, beyond_domain
   use hcimpact_mpi_chain_output, only : write_state, write_contacts, remove_file, &
      & summary_line
   implicit none

   integer, parameter :: exit_ok = 0, exit_failure = 1, exit_usage = 2
   !> The shortest run the distributed chain computes (s; below, t_end^2 underflows)
   real(wp), parameter :: min_t_end = 1.0e-150_wp
   character(len=4096) :: scene_path, state_path, contacts_path, arg
   logical :: serial
   integer :: n_args, first_arg

   n_args = command_argument_count()
   serial = .false.
   if (n_args >= 1) then
      call get_command_argument(1, arg)
      if (arg == "--help" .or. arg == "-h") then
         call print_usage(output_unit)
         stop exit_ok, quiet=.true.
      end if
      serial = arg == "--serial"
   end if
   first_arg = merge(2, 1, serial)
   if (n_args /= first_arg + 1 .and. n_args /= first_arg + 2) then
      write(error_unit, '(a)') "error: expected a scene, a state file and optionally " &
         & // "a contacts file"
      call print_usage(error_unit)
      stop exit_usage, quiet=.true.
   end if
   call get_command_argument(first_arg, scene_path)
   call get_command_argument(first_arg + 1, state_path)
   contacts_path = ""
   if (n_args == first_arg + 2) call get_command_argument(first_arg + 2, contacts_path)
   if (serial) then
      call run_serial()
   else
      call run_distributed()
   end if

contains

   subroutine print_usage(unit)
      integer, intent(in) :: unit
      write(unit, '(a)') "usage: mpirun -n N hcimpact_mpi_chain SCENE STATE.csv " &
         & // "[CONTACTS.csv]", &
         & "       hcimpact_mpi_chain --serial SCENE STATE.csv [CONTACTS.csv]", &
         & "SCENE: a file with the namelist &mpi_chain (doc/mpi.md)"
   end subroutine print_usage

   !> The reference: the serial chain integrator on one process, no MPI
   subroutine run_serial()
      type(chain_scene) :: scene
      type(chain_type) :: chain
      type(chain_options) :: options
      type(chain_result) :: result
      type(contact_record), allocatable :: sorted(:)
      character(len=max_message) :: message
      logical :: ok
      integer :: stat
      real(wp) :: seconds
      integer(int64) :: c0, c1, rate

      call read_chain_scene(scene_path, scene, ok, message)
      if (.not. ok) call fail_alone(exit_usage, message)
      call scene_system(scene, 1, chain, options, stat, message)
      if (stat /= hcimpact_ok) call fail_alone(exit_usage, message)
      call system_clock(c0, rate)
      call chain_simulate(chain, result, stat, options)
      call system_clock(c1)
      if (stat /= hcimpact_ok) call fail_alone(exit_failure, result%message)
      if (len_trim(contacts_path) > 0) then
         ! the order of the distributed program's list: by pair
         allocate(sorted(size(result%contacts)))
         call sort_by_pair(result%contacts, 0, size(chain%mass), sorted)
         call write_contacts(trim(contacts_path), sorted, ok, message)
         if (.not. ok) call fail_alone(exit_failure, message)
      end if
      call write_state(state_path, result%positions, result%velocities, ok, message)
      if (.not. ok) then
         if (len_trim(contacts_path) > 0) call remove_file(trim(contacts_path))
         call fail_alone(exit_failure, message)
      end if
      seconds = real(c1 - c0, wp) / real(rate, wp)
      ok = .true.
      call summary_line(output_unit, "mode", "serial (chain_simulate, method_integrated)", ok)
      call summary_line(output_unit, "beads", str_i(int(size(chain%mass), int64)), ok)
      call summary_line(output_unit, "ranks", "1", ok)
      call summary_line(output_unit, "steps", str_i(result%counters%steps), ok)
      call summary_line(output_unit, "rhs_evaluations", str_i(result%counters%rhs_evals), ok)
      call summary_line(output_unit, "jacobian_evaluations", &
         & str_i(result%counters%jacobian_evals), ok)
      call summary_line(output_unit, "contacts", str_i(result%n_contacts), ok)
      call summary_line(output_unit, "energy_error", str_r(result%energy_error), ok)
      call summary_line(output_unit, "momentum_error", str_r(result%momentum_error), ok)
      call summary_line(output_unit, "wall_impulse_left", str_full(result%wall_impulse(1)), ok)
      call summary_line(output_unit, "wall_impulse_right", str_full(result%wall_impulse(2)), &
         & ok)
      call summary_line(output_unit, "seconds", str_r(seconds), ok)
      if (.not. ok) then
         ! a failed run leaves no file that looks complete
         call remove_file(trim(state_path))
         if (len_trim(contacts_path) > 0) call remove_file(trim(contacts_path))
         call fail_alone(exit_failure, "the standard output: writing failed")
      end if
      stop exit_ok, quiet=.true.
   end subroutine run_serial

   !> The chain over the ranks of MPI_COMM_WORLD
   subroutine run_distributed()
      type(chain_scene) :: scene
      type(chain_type) :: chain
      type(chain_options) :: options
      type(chain_integration), target :: run
      type(chain_counters_mpi) :: counters
      type(chain_region) :: whole
      character(len=max_message) :: message, domain_message
      real(wp), allocatable :: y(:), local(:), u(:), v(:), positions(:), gathered(:), &
         & y_whole(:)
      integer, allocatable :: counts(:), displs(:)
      real(wp) :: dissipated_local, dissipated, energy0, energy_error, t0, t1, seconds, q0, &
         & energy_end, weakest_force, v_frame, a_frame, shift, speed, e_grav, &
         & momentum_error, walls_local(2), walls(2)
      integer(int64) :: exchanges, halo_bytes, unconverged
      type(contact_record), allocatable :: contacts(:)
      integer :: rank, n_ranks, stat, k, m, n, r, first, size_r, i
      logical :: ok, all_ok, halting(3), beyond

      call MPI_Init()
      call MPI_Comm_rank(MPI_COMM_WORLD, rank)
      call MPI_Comm_size(MPI_COMM_WORLD, n_ranks)

      ! every rank reads and checks the same scene: all end alike on a bad one
      call read_chain_scene(scene_path, scene, ok, message)
      if (.not. ok) call fail_all(rank, exit_usage, message)
      call scene_system(scene, n_ranks, chain, options, stat, message)
      if (stat /= hcimpact_ok) call fail_all(rank, exit_usage, message)
      ! CVODE takes the product of the times to its stop and to t_end from the start,
      ! t_end^2, for a stop behind the start where it underflows to 0 (CV_ILL_INPUT);
      ! the serial chain (--serial, the scene runner) computes such runs
      if (options%t_end < min_t_end) call fail_all(rank, exit_usage, "t_end below " &
         & // "1e-150 s: CVODE cannot stop there (t_end^2 underflows); --serial computes it")
      n = size(chain%mass)

      call block_setup(chain, MPI_COMM_WORLD, run%block)
      m = run%block%m
      first = run%block%first
      run%rtol = options%rtol
      ! the whole chain as the serial chain's one region: its energy now, and in the
      ! frame of that region (`region_frame`: falling freely without walls, moving
      ! with the slowest bead where all move the same way) the scales of the error
      ! weights; every rank integrates its block in that frame
      whole = part_region(chain, 1, n)
      allocate(y(region_size(n)))
      y = 0.0_wp
      y(2:3 * n - 1:3) = chain%velocity
      energy0 = region_energy(whole, y)
      call region_frame(whole, chain%velocity, v_frame, a_frame)
      run%block%region%gravity = run%block%region%gravity - a_frame
      whole%gravity = whole%gravity - a_frame
      y(2:3 * n - 1:3) = chain%velocity - v_frame
      call region_scales(whole, y, run%scale, weakest_force, options%t_end, run%stop_time)
      run%impulse_scale = wall_impulse_scale(chain%mass, run%scale(2))
      whole%gravity = chain%gravity
      ! (as the serial chain's integration: forces below the normal range keep fewer
      ! bits than the tolerance needs)
      if (weakest_force < tiny(1.0_wp)) call fail_all(rank, exit_usage, "the contacts' " &
         & // "peak forces fall below the normal range of doubles, which the " &
         & // "integration cannot resolve")
      deallocate(y)

      allocate(y(run%block%n_local))
      y = 0.0_wp
      do k = 1, m
         y(3 * k - 1) = chain%velocity(first + k - 1) - v_frame
      end do

      call MPI_Barrier(MPI_COMM_WORLD)
      t0 = MPI_Wtime()
      call integrate_chain(run, options%t_end, options%max_steps, y, counters, ok, message)
      t1 = MPI_Wtime()
      ! CVODE's failures are collective; should one rank fail alone, all still stop
      call MPI_Reduce(t1 - t0, seconds, 1, MPI_DOUBLE_PRECISION, MPI_MAX, 0, MPI_COMM_WORLD)
      ! a pair met closing with b V beyond the model's domain on any rank fails the run
      ! with that message, whether CVODE failed on it or not (as chain_simulate)
      call beyond_domain(run%contacts, run%block, beyond, domain_message)
      if (beyond) call fail_all(rank, exit_failure, domain_message)
      call MPI_Allreduce(ok, all_ok, 1, MPI_LOGICAL, MPI_LAND, MPI_COMM_WORLD)
      if (ok .and. .not. all_ok) message = "CVODE failed on another rank"
      if (.not. all_ok) call fail_all(rank, exit_failure, message)

      ! the beads in order on rank 0: displacements, then velocities
      allocate(local(2 * m))
      local(1:m) = y(1:3 * m:3)
      local(m + 1:2 * m) = y(2:3 * m:3)
      ! (the last rank's values end with the right wall's dissipated energy, then come
      ! the impulses of the walls the block holds)
      dissipated_local = sum(y(3:3 * m:3))
      if (run%block%n_motion > 3 * m) dissipated_local = dissipated_local + y(3 * m + 1)
      walls_local = 0.0_wp
      do i = 1, 2
         if (run%block%impulse(i) > 0) walls_local(i) = pushing_impulse(i, &
            & y(run%block%impulse(i)))
      end do
      allocate(counts(n_ranks), displs(n_ranks), gathered(2 * n))
      do r = 0, n_ranks - 1
         call block_partition(n, n_ranks, r, i, size_r)
         counts(r + 1) = 2 * size_r
         displs(r + 1) = 2 * (i - 1)
      end do
      call MPI_Gatherv(local, 2 * m, MPI_DOUBLE_PRECISION, gathered, counts, displs, &
         & MPI_DOUBLE_PRECISION, 0, MPI_COMM_WORLD)
      call MPI_Reduce(dissipated_local, dissipated, 1, MPI_DOUBLE_PRECISION, MPI_SUM, 0, &
         & MPI_COMM_WORLD)
      call MPI_Reduce(walls_local, walls, 2, MPI_DOUBLE_PRECISION, MPI_SUM, 0, &
         & MPI_COMM_WORLD)
      call MPI_Reduce(run%block%exchanges, exchanges, 1, MPI_INTEGER8, MPI_SUM, 0, &
         & MPI_COMM_WORLD)
      call MPI_Reduce(run%contacts%unconverged, unconverged, 1, MPI_INTEGER8, MPI_SUM, 0, &
         & MPI_COMM_WORLD)
      call gather_contacts(run%contacts, run%block, contacts, ok, message)
      if (.not. ok) call fail_all(rank, exit_failure, message)

      ok = .true.
      if (rank == 0) then
         allocate(u(n), v(n), positions(n))
         do r = 0, n_ranks - 1
            call block_partition(n, n_ranks, r, i, size_r)
            u(i:i + size_r - 1) = gathered(2 * (i - 1) + 1:2 * (i - 1) + size_r)
            v(i:i + size_r - 1) = gathered(2 * (i - 1) + size_r + 1:2 * (i - 1) + 2 * size_r)
         end do
         ! out of the frame, then positions (q_1(0) = 0, q_(i+1)(0) = q_i(0) + gap(i),
         ! plus the displacement) and the energies; a state or an energy beyond the
         ! range of doubles is a failure, found with halting off (the Debug build traps
         ! the overflow)
         call halting_suspend(halting)
         call frame_motion(v_frame, a_frame, options%t_end, shift, speed)
         u = u + shift
         v = v + speed
         q0 = 0.0_wp
         positions(1) = u(1)
         do i = 2, n
            q0 = q0 + chain%gap(i - 1)
            positions(i) = q0 + u(i)
         end do
         allocate(y_whole(region_size(n)))
         y_whole = 0.0_wp
         y_whole(1:3 * n - 2:3) = u
         y_whole(2:3 * n - 1:3) = v
         energy_end = 0.0_wp
         e_grav = 0.0_wp
         if (all(ieee_is_finite(positions)) .and. all(ieee_is_finite(v))) then
            energy_end = region_energy(whole, y_whole)
            e_grav = -sum(chain%mass * chain%gravity * u)
            ! as chain_simulate's energy_error (`energy_balance_error`)
            energy_error = energy_balance_error(energy_end, dissipated, energy0, e_grav)
            if (.not. (ieee_is_finite(energy_end) .and. ieee_is_finite(e_grav) .and. &
               & ieee_is_finite(energy_error))) then
               ok = .false.
               message = "the energies of the chain leave the range of doubles (kinetic, " &
                  & // "elastic or gravitational energy, or their balance, beyond 1.8e308 J)"
            end if
            ! the momentum against p0 + M g t + J_left + J_right, as chain_simulate's
            ! momentum_error
            momentum_error = momentum_balance_error(momentum(chain%mass, v), chain%mass, &
               & chain%velocity, [gravity_impulse(chain%mass, chain%gravity, options%t_end), &
               & walls])
         else
            ok = .false.
            write(message, '(a, es11.3e3, a)') "by t = ", options%t_end, " s a position or a " &
               & // "velocity leaves the range of doubles (beyond 1.8e308 m or m/s)"
         end if
         call halting_resume(halting)
         if (ok .and. len_trim(contacts_path) > 0) &
            & call write_contacts(trim(contacts_path), contacts, ok, message)
         if (ok) then
            call write_state(state_path, positions, v, ok, message)
            if (.not. ok .and. len_trim(contacts_path) > 0) &
               & call remove_file(trim(contacts_path))
         end if
         if (ok) then
            ! bytes of the halo exchanges: every rank sends halo_doubles doubles to each
            ! neighbour per exchange (exchanges is their sum over the ranks)
            halo_bytes = (exchanges / n_ranks) * 2_int64 * (n_ranks - 1) * halo_doubles * 8
            call summary_line(output_unit, "mode", "distributed (N_Vector_Parallel, " &
               & // "BDF, SPGMR, CVBBDPRE)", ok)
            call summary_line(output_unit, "beads", str_i(int(n, int64)), ok)
            call summary_line(output_unit, "ranks", str_i(int(n_ranks, int64)), ok)
            call summary_line(output_unit, "steps", str_i(counters%steps), ok)
            call summary_line(output_unit, "rhs_evaluations", str_i(counters%rhs_evals), ok)
            call summary_line(output_unit, "nonlinear_iterations", &
               & str_i(counters%nonlinear_iterations), ok)
            call summary_line(output_unit, "linear_iterations", &
               & str_i(counters%linear_iterations), ok)
            call summary_line(output_unit, "preconditioner_setups", &
               & str_i(counters%preconditioner_setups), ok)
            call summary_line(output_unit, "local_rhs_evaluations", &
               & str_i(counters%local_rhs_evals), ok)
            call summary_line(output_unit, "halo_exchanges", str_i(exchanges / n_ranks), ok)
            call summary_line(output_unit, "halo_bytes", str_i(halo_bytes), ok)
            call summary_line(output_unit, "halo_bytes_per_step", &
               & str_r(real(halo_bytes, wp) / real(max(counters%steps, 1_int64), wp)), ok)
            call summary_line(output_unit, "contacts", str_i(size(contacts, kind=int64)), ok)
            call summary_line(output_unit, "contact_locations_unconverged", &
               & str_i(unconverged), ok)
            call summary_line(output_unit, "energy_error", str_r(energy_error), ok)
            call summary_line(output_unit, "momentum_error", str_r(momentum_error), ok)
            call summary_line(output_unit, "wall_impulse_left", str_full(walls(1)), ok)
            call summary_line(output_unit, "wall_impulse_right", str_full(walls(2)), ok)
            call summary_line(output_unit, "seconds", str_r(seconds), ok)
            if (.not. ok) then
               ! a failed run leaves no file that looks complete
               message = "the standard output: writing failed"
               call remove_file(trim(state_path))
               if (len_trim(contacts_path) > 0) call remove_file(trim(contacts_path))
            end if
         end if
      end if
      call MPI_Bcast(ok, 1, MPI_LOGICAL, 0, MPI_COMM_WORLD)
      if (.not. ok) call fail_all(rank, exit_failure, message)
      call MPI_Finalize()
      stop exit_ok, quiet=.true.
   end subroutine run_distributed

   !> Report on rank 0, end MPI and stop every rank with `code`
   subroutine fail_all(rank, code, message)
      integer, intent(in) :: rank, code
      character(len=*), intent(in) :: message
      if (rank == 0) write(error_unit, '(a)') "error: " // trim(message)
      call MPI_Finalize()
      stop code, quiet=.true.
   end subroutine fail_all

   !> Report and stop with `code` (no MPI)
   subroutine fail_alone(code, message)
      integer, intent(in) :: code
      character(len=*), intent(in) :: message
      write(error_unit, '(a)') "error: " // trim(message)
      stop code, quiet=.true.
   end subroutine fail_alone

   pure function str_i(value) result(text)
      integer(int64), intent(in) :: value
      character(len=24) :: text
      write(text, '(i0)') value
   end function str_i

   pure function str_r(value) result(text)
      real(wp), intent(in) :: value
      character(len=24) :: text
      write(text, '(es13.5e3)') value
   end function str_r

   !> A result to 17 digits (every double read back as itself)
   pure function str_full(value) result(text)
      real(wp), intent(in) :: value
      character(len=32) :: text
      write(text, '(es25.17e3)') value
   end function str_full

end program hcimpact_mpi_chain
