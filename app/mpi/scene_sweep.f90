! SPDX-License-Identifier: Apache-2.0
!> The impacts of a sweep (the outputs summary and sweep) and the runs of a sweep of
!> systems (the output system_sweep) over the ranks of MPI, in CMake builds with the
!> MPI component (doc/mpi.md). It replaces app/hcimpact/scene_sweep.f90, the module of
!> the same name and interface that computes every item on one process.
!>
!> Rank 0 runs the scene (reads it, plans, writes every file and the console); the
!> other ranks wait for sweeps. For each sweep rank 0 tells them one begins (and of
!> which kind), and every rank enters the component's collective hand-out
!> (hcimpact_mpi_sweep's `mpi_impact_sweep` for impacts, hcimpact_mpi_hand_out's
!> `mpi_hand_out` with a system worker for systems: chunks handed out dynamically, the
!> results put back in order, bit for bit those of one process). Rank 0 is told of
!> every chunk as it is done and writes its results to the sweep's checkpoint
!> (hcimpact_scene_checkpoint) and shows the progress; a rerun gives the hand-out
!> what the checkpoint holds, and only the rest is handed out.
!>
!> A rank that dies takes the run down (MPI's default error handler, and `mpirun`
!> ends the job): rank 0 never renames its `.partial` files, so nothing is left that
!> looks complete.
module hcimpact_scene_sweep
   use mpi_f08, only : MPI_Init, MPI_Finalize, MPI_Comm_rank, MPI_Comm_size, MPI_Send, &
      & MPI_Recv, MPI_Iprobe, MPI_Status, MPI_COMM_WORLD, MPI_INTEGER, MPI_ANY_TAG
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type
   use hcimpact_mpi_sweep, only : mpi_impact_sweep, sweep_listener, mpi_sweep_max_chunk
   use hcimpact_mpi_hand_out, only : mpi_hand_out, sweep_worker, items_listener
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_out_of_memory, status_message
   use hcimpact_scene_system_items, only : compute_system_item
   use hcimpact_scene_console, only : progress_begin, progress_step, progress_end
   use hcimpact_scene_text, only : str
   use hcimpact_scene_system, only : pause_microseconds
   use hcimpact_scene_checkpoint, only : checkpoint_type, checkpoint_start, &
      & checkpoint_record, checkpoint_finish, checkpoint_start_columns, &
      & checkpoint_record_columns
   implicit none
   private

   public :: sweep_begin, sweep_serve, sweep_end, sweep_description, sweep_impacts, &
      & sweep_systems

   !> Messages of rank 0 to the others between sweeps: a sweep of impacts begins, the
   !> program ends, a sweep of systems begins
   integer, parameter :: tag_sweep = 1, tag_stop = 2, tag_systems = 3
   !> Most systems of a chunk: each is a whole run, costly and of very different costs
   integer, parameter :: systems_chunk = 4

   !> The worker of a sweep of systems: one whole run of a system
   type, extends(sweep_worker) :: system_worker
   contains
      procedure :: compute => compute_system
      procedure :: verdict => every_row
   end type system_worker

   !> Rank 0's listener of a sweep of systems: each chunk's results to the checkpoint
   !> (flushed), and the progress
   type, extends(items_listener) :: systems_recorder
      !> The checkpoint being written
      type(checkpoint_type) :: ck
      !> The runs done so far, and how many (those of the checkpoint included)
      logical, allocatable :: known(:)
      integer :: finished = 0
      !> Why the checkpoint could not be written
      character(len=:), allocatable :: error
   contains
      procedure :: items_done => record_systems
   end type systems_recorder
   !> How long a rank without work sleeps before it looks for a message again, in
   !> microseconds: waiting in MPI_Probe would spin and take a core from rank 0 (which
   !> runs the rest of the scene and writes the files) and from other jobs of a shared
   !> machine
   integer, parameter :: idle_pause = 200

   !> Rank 0's listener of a sweep: each chunk's outcomes to the checkpoint, and the
   !> progress
   type, extends(sweep_listener) :: sweep_recorder
      !> The checkpoint being written
      type(checkpoint_type) :: ck
      !> The items the checkpoint held when the sweep began
      logical, allocatable :: known(:)
      !> Items done so far (those of the checkpoint included)
      integer :: finished = 0
      !> Why the checkpoint could not be written
      character(len=:), allocatable :: error
   contains
      procedure :: chunk_done => record_chunk
   end type sweep_recorder

   !> This process's rank and the number of ranks (the program runs one scene; the
   !> state of the run is kept here)
   integer :: my_rank = 0, n_ranks = 1
   !> Whether MPI has been started and finished
   logical :: started = .false., finished = .false.

contains

   !> Start MPI: rank 0 runs the scene, the others serve it (`sweep_serve`). A program
   !> not started by an MPI launcher does not start MPI (a singleton start would need
   !> the launcher's run-time, its files and sockets, for nothing) and runs alone.
   subroutine sweep_begin(leader)
      !> Whether this process runs the scene
      logical, intent(out) :: leader
      leader = .true.
      if (.not. launched()) return
      call MPI_Init()
      started = .true.
      call MPI_Comm_rank(MPI_COMM_WORLD, my_rank)
      call MPI_Comm_size(MPI_COMM_WORLD, n_ranks)
      leader = my_rank == 0
   end subroutine sweep_begin

   !> Whether an MPI launcher started this process: the variables mpirun/mpiexec of
   !> Open MPI, MPICH (Hydra) and Intel MPI, and Slurm's srun with PMI or PMIx set.
   logical function launched()
      character(len=*), parameter :: names(5) = [character(len=20) :: &
         & "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK", "MPI_LOCALNRANKS"]
      integer :: i, length, stat
      launched = .false.
      do i = 1, size(names)
         call get_environment_variable(trim(names(i)), length=length, status=stat)
         if (stat == 0) launched = .true.
      end do
   end function launched

   !> The work of a rank other than 0: take part in every sweep rank 0 begins, until it
   !> says the program ends.
   subroutine sweep_serve(code)
      !> Exit code of the process
      integer, intent(out) :: code
      type(MPI_Status) :: probe
      type(contact_type) :: no_contacts(0)
      type(outcome_type) :: no_outcomes(0)
      integer :: no_stats(0), message(1), status
      type(system_worker) :: systems
      real(wp) :: no_items(0, 0)
      logical :: arrived
      code = 0
      do
         do
            call MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, arrived, probe)
            if (arrived) exit
            call pause_microseconds(idle_pause)
         end do
         call MPI_Recv(message, 1, MPI_INTEGER, 0, probe%MPI_TAG, MPI_COMM_WORLD, probe)
         select case (probe%MPI_TAG)
         case (tag_sweep)
            call mpi_impact_sweep(MPI_COMM_WORLD, no_contacts, no_outcomes, no_stats, status)
         case (tag_systems)
            call mpi_hand_out(MPI_COMM_WORLD, systems, no_items, no_items, status)
         case default
            exit
         end select
      end do
   end subroutine sweep_serve

   !> The end of the program: rank 0 tells the other ranks, and every rank finishes MPI.
   subroutine sweep_end()
      if (.not. started .or. finished) return
      if (my_rank == 0) call tell_ranks(tag_stop)
      call MPI_Finalize()
      finished = .true.
   end subroutine sweep_end

   !> How the items of a sweep are computed, for the plan: impacts, or whole runs of a
   !> system (`systems`).
   function sweep_description(systems) result(text)
      logical, intent(in), optional :: systems
      character(len=:), allocatable :: text
      logical :: of_systems
      of_systems = .false.
      if (present(systems)) of_systems = systems
      if (.not. started) then
         text = "on this process (not started by an MPI launcher: MPI not used)"
      else if (n_ranks == 1) then
         text = "on this process (MPI, 1 rank)"
      else if (of_systems) then
         text = "over " // str(n_ranks) // " MPI ranks: chunks of up to " &
            & // str(systems_chunk) // " runs handed out by rank 0 on request (rank 0" &
            & // " computes too), the results put back in order"
      else
         text = "over " // str(n_ranks) // " MPI ranks: chunks of up to " &
            & // str(mpi_sweep_max_chunk) &
            & // " impacts handed out by rank 0 on request (rank 0 computes too), the" &
            & // " results put back in order"
      end if
   end function sweep_description

   !> The impacts `contacts` (each its own mass, law, damping and speed), with the
   !> progress shown under `label`: on rank 0, handed out to every rank; those the
   !> checkpoint holds are taken from it.
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
      !> Why the checkpoint could not be written (the impacts are all computed: the
      !> other ranks must not be left with chunks nobody takes), or that rank 0 had
      !> no memory for the sweep's copies (none is computed)
      character(len=:), allocatable, intent(out) :: error
      type(sweep_recorder) :: recorder
      logical, allocatable :: held(:)
      integer :: status

      allocate(recorder%known(size(contacts)))
      call checkpoint_start(checkpoint, contacts, out, stats, recorder%known, resumed, &
         & recorder%ck, error)
      if (allocated(error)) return
      recorder%finished = resumed
      call progress_begin(label, size(contacts), resumed)
      if (started) call tell_ranks(tag_sweep)
      ! what the checkpoint held, apart from what the recorder marks as the chunks come
      ! in; the overall status is the first failing impact's (each has its own in stats)
      held = recorder%known
      call mpi_impact_sweep(MPI_COMM_WORLD, contacts, out, stats, status, held, recorder)
      call checkpoint_finish(recorder%ck, recorder%error)
      call progress_end()
      if (allocated(recorder%error)) call move_alloc(recorder%error, error)
      ! (rank 0 could not copy the impacts: none was computed)
      if (status == hcimpact_err_out_of_memory .and. .not. allocated(error)) &
         & error = status_message(status)
   end subroutine sweep_impacts

   !> Rank 0: a chunk is done: its outcomes to the checkpoint (flushed), the progress.
   subroutine record_chunk(self, first, out, stats)
      class(sweep_recorder), intent(inout) :: self
      integer, intent(in) :: first
      type(outcome_type), intent(in) :: out(:)
      integer, intent(in) :: stats(:)
      integer :: last
      last = first + size(out) - 1
      call checkpoint_record(self%ck, first, out, stats, self%error)
      self%finished = self%finished + count(.not. self%known(first:last))
      self%known(first:last) = .true.
      call progress_step(self%finished)
   end subroutine record_chunk

   !> The runs of a sweep of systems (the output system_sweep) on rank 0, handed out to
   !> every rank a few at a time: `outputs(:, k)` from `inputs(:, k)`
   !> (hcimpact_scene_system_items), the same doubles as on one process. Each chunk's
   !> results go to the checkpoint as they come in; those it holds are not handed out.
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
      !> Why the checkpoint could not be written (the runs are all computed: the other
      !> ranks must not be left with chunks nobody takes)
      character(len=:), allocatable, intent(out) :: error
      type(system_worker) :: worker
      type(systems_recorder) :: recorder
      logical, allocatable :: held(:)
      integer :: status
      allocate(recorder%known(size(inputs, 2)))
      outputs = 0.0_wp
      call checkpoint_start_columns(checkpoint, inputs, outputs, recorder%known, resumed, &
         & recorder%ck, error)
      if (allocated(error)) return
      recorder%finished = resumed
      call progress_begin(label, size(inputs, 2), resumed)
      if (started) call tell_ranks(tag_systems)
      held = recorder%known
      call mpi_hand_out(MPI_COMM_WORLD, worker, inputs, outputs, status, held, recorder, &
         & systems_chunk)
      call checkpoint_finish(recorder%ck, recorder%error)
      call progress_end()
      if (allocated(recorder%error)) call move_alloc(recorder%error, error)
   end subroutine sweep_systems

   !> One run of a system, on any rank.
   subroutine compute_system(self, input, output)
      class(system_worker), intent(inout) :: self
      real(wp), intent(in) :: input(:)
      real(wp), intent(out) :: output(:)
      call compute_system_item(input, output)
   end subroutine compute_system

   !> Every run's status is in its row: the sweep itself succeeds.
   integer function every_row(self, outputs) result(status)
      class(system_worker), intent(in) :: self
      real(wp), intent(in) :: outputs(:, :)
      status = hcimpact_ok
   end function every_row

   !> Rank 0: runs are done: their results to the checkpoint, the progress.
   subroutine record_systems(self, first, outputs)
      class(systems_recorder), intent(inout) :: self
      integer, intent(in) :: first
      real(wp), intent(in) :: outputs(:, :)
      integer :: last
      last = first + size(outputs, 2) - 1
      call checkpoint_record_columns(self%ck, first, outputs, self%error)
      self%finished = self%finished + count(.not. self%known(first:last))
      self%known(first:last) = .true.
      call progress_step(self%finished)
   end subroutine record_systems

   !> Rank 0 sends every other rank a message with `tag` (a sweep begins, the program
   !> ends).
   subroutine tell_ranks(tag)
      integer, intent(in) :: tag
      integer :: rank, message(1)
      message = 0
      do rank = 1, n_ranks - 1
         call MPI_Send(message, 1, MPI_INTEGER, rank, tag, MPI_COMM_WORLD)
      end do
   end subroutine tell_ranks

end module hcimpact_scene_sweep
