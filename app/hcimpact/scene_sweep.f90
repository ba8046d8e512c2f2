! SPDX-License-Identifier: Apache-2.0
!> The impacts of a sweep (the outputs summary and sweep) in a build without MPI (fpm,
!> or CMake without MPI or with HCIMPACT_WITH_MPI=OFF): every impact on this process,
!> shared among OpenMP threads where the program is built with OpenMP, in blocks whose
!> outcomes go to the sweep's checkpoint as each block ends
!> (hcimpact_scene_checkpoint). CMake builds with MPI compile app/mpi/scene_sweep.f90
!> instead, a module of the same name and interface that hands the impacts out to the
!> ranks of `mpirun` (doc/mpi.md).
module hcimpact_scene_sweep
   use hcimpact_kinds, only : wp
   !$ use hcimpact_parallel, only : min_parallel_impact
   !$ use omp_lib, only : omp_get_thread_num
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_scene_console, only : progress_begin, progress_step, progress_end
   use hcimpact_scene_checkpoint, only : checkpoint_type, checkpoint_start, &
      & checkpoint_record, checkpoint_finish, checkpoint_start_columns, &
      & checkpoint_record_columns
   use hcimpact_scene_system_items, only : compute_system_item
   implicit none
   private

   public :: sweep_begin, sweep_serve, sweep_end, sweep_description, sweep_impacts, &
      & sweep_systems

   !> Impacts of a block: what a killed run loses at most
   integer, parameter :: block = 1024

contains

   !> Start: this process is the one that runs the scene (there are no others).
   subroutine sweep_begin(leader)
      !> Whether this process runs the scene (always, here)
      logical, intent(out) :: leader
      leader = .true.
   end subroutine sweep_begin

   !> The work of a process that does not run the scene: none here.
   subroutine sweep_serve(code)
      !> Exit code of the process
      integer, intent(out) :: code
      code = 0
   end subroutine sweep_serve

   !> The end of the program: nothing to release here.
   subroutine sweep_end()
   end subroutine sweep_end

   !> How the items of a sweep are computed, for the plan: impacts, or whole runs of a
   !> system (`systems`, one at a time per thread).
   function sweep_description(systems) result(text)
      logical, intent(in), optional :: systems
      character(len=:), allocatable :: text
      text = "on this process"
      !$ text = "on this process, shared among OpenMP threads"
      if (present(systems)) then
         !$ if (systems) text = text // " one run at a time"
      end if
   end function sweep_description

   !> The impacts `contacts` (each its own mass, law, damping and speed), with the
   !> progress shown under `label`; those the checkpoint holds are taken from it.
   subroutine sweep_impacts(contacts, label, checkpoint, out, stats, resumed, error)
      !> The impacts
      type(contact_type), intent(in) :: contacts(:)
      !> The progress line's label
      character(len=*), intent(in) :: label
      !> The checkpoint file, or "" for none
      character(len=*), intent(in) :: checkpoint
      !> The outcome at each speed
      type(outcome_type), intent(out) :: out(:)
      !> The status of each impact
      integer, intent(out) :: stats(:)
      !> How many impacts came from the checkpoint
      integer, intent(out) :: resumed
      !> Why the checkpoint could not be written (the impacts are all computed)
      character(len=:), allocatable, intent(out) :: error
      type(checkpoint_type) :: ck
      logical, allocatable :: done(:)
      integer :: i, first, last, finished, mine

      allocate(done(size(contacts)))
      call checkpoint_start(checkpoint, contacts, out, stats, done, resumed, ck, error)
      if (allocated(error)) return
      ! a block the checkpoint holds whole is skipped, one it holds in part computed
      ! again (the same doubles): the progress starts from the whole ones
      finished = 0
      do first = 1, size(contacts), block
         last = min(first + block - 1, size(contacts))
         if (all(done(first:last))) finished = finished + last - first + 1
      end do
      call progress_begin(label, size(contacts), finished)
      do first = 1, size(contacts), block
         last = min(first + block - 1, size(contacts))
         if (all(done(first:last))) cycle
         ! The impacts are independent: in parallel when the program is built with
         ! OpenMP (the library's array threshold and schedule); the progress line is
         ! drawn by the first thread alone.
         !$omp parallel do if (last - first + 1 >= min_parallel_impact) &
         !$omp & private(mine) schedule(dynamic, 4)
         do i = first, last
            call impact(contacts(i), out(i), stats(i))
            !$omp atomic capture
            finished = finished + 1
            mine = finished
            !$omp end atomic
            !$ if (omp_get_thread_num() /= 0) cycle
            call progress_step(mine)
         end do
         !$omp end parallel do
         call checkpoint_record(ck, first, out(first:last), stats(first:last), error)
      end do
      call checkpoint_finish(ck, error)
      call progress_end()
   end subroutine sweep_impacts

   !> The runs of a sweep of systems (the output system_sweep): `outputs(:, k)` from
   !> `inputs(:, k)` (hcimpact_scene_system_items), with the progress shown under
   !> `label`; shared among OpenMP threads one item at a time (their costs differ by
   !> orders of magnitude). Each run's result goes to the checkpoint as it ends; those
   !> the checkpoint holds are taken from it.
   subroutine sweep_systems(inputs, outputs, label, checkpoint, resumed, error)
      !> The items' columns
      real(wp), intent(in) :: inputs(:, :)
      !> Their results' columns
      real(wp), intent(out) :: outputs(:, :)
      !> The progress line's label
      character(len=*), intent(in) :: label
      !> The checkpoint file, or "" for none
      character(len=*), intent(in) :: checkpoint
      !> How many runs came from the checkpoint
      integer, intent(out) :: resumed
      !> Why the checkpoint could not be written (the runs are all computed)
      character(len=:), allocatable, intent(out) :: error
      type(checkpoint_type) :: ck
      logical, allocatable :: done(:)
      integer :: k, finished, mine
      allocate(done(size(inputs, 2)))
      outputs = 0.0_wp
      call checkpoint_start_columns(checkpoint, inputs, outputs, done, resumed, ck, error)
      if (allocated(error)) return
      call progress_begin(label, size(inputs, 2), resumed)
      finished = resumed
      !$omp parallel do private(mine) schedule(dynamic, 1)
      do k = 1, size(inputs, 2)
         if (done(k)) cycle
         call compute_system_item(inputs(:, k), outputs(:, k))
         ! one writer of the checkpoint at a time
         !$omp critical (system_checkpoint)
         call checkpoint_record_columns(ck, k, outputs(:, k:k), error)
         finished = finished + 1
         mine = finished
         !$omp end critical (system_checkpoint)
         !$ if (omp_get_thread_num() /= 0) cycle
         call progress_step(mine)
      end do
      !$omp end parallel do
      call checkpoint_finish(ck, error)
      call progress_end()
   end subroutine sweep_systems

end module hcimpact_scene_sweep
