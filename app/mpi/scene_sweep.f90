! SPDX-License-Identifier: Apache-2.0
!> The impacts of a sweep (the outputs summary and sweep) over the ranks of MPI, in
!> CMake builds with HCIMPACT_WITH_MPI (doc/mpi.md). It replaces
!> app/hcimpact/scene_sweep.f90, the module of the same name and interface that
!> computes every impact on one process.
!>
!> Rank 0 runs the scene (reads it, plans, writes every file and the console); the
!> other ranks only compute impacts. A sweep is cut into chunks of consecutive speeds;
!> rank 0 sends each other rank two chunks, and another one each time a chunk's
!> results come back (point-to-point messages, so that a slow chunk, or a slow rank,
!> holds up no other), and computes a chunk itself whenever no result is waiting.
!> The results land at their speed's index, so rank 0 then holds exactly the outcomes
!> a serial run computes (each impact is computed alone, by the same code, from the
!> same doubles) and writes the same files. Rank 0 writes each chunk's outcomes to the
!> sweep's checkpoint as they arrive (hcimpact_scene_checkpoint); a rerun hands out
!> only the chunks the checkpoint does not hold whole.
!>
!> A rank that dies takes the run down (MPI's default error handler, and `mpirun`
!> ends the job): rank 0 never renames its `.partial` files, so nothing is left that
!> looks complete.
module hcimpact_scene_sweep
   use mpi_f08, only : MPI_Init, MPI_Finalize, MPI_Comm_rank, MPI_Comm_size, MPI_Send, &
      & MPI_Isend, MPI_Wait, MPI_Recv, MPI_Iprobe, MPI_Status, MPI_Request, &
      & MPI_COMM_WORLD, MPI_DOUBLE_PRECISION, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_REQUEST_NULL, &
      & MPI_STATUS_IGNORE
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_scene_console, only : progress_begin, progress_step, progress_end
   use hcimpact_scene_text, only : str
   use hcimpact_scene_system, only : pause_microseconds
   use hcimpact_scene_checkpoint, only : per_impact, packed, unpack, checkpoint_type, &
      & checkpoint_start, checkpoint_record, checkpoint_finish
   implicit none
   private

   public :: sweep_begin, sweep_serve, sweep_end, sweep_description, sweep_impacts

   !> Message tags: a chunk to compute, its results, the end of the program
   integer, parameter :: tag_work = 1, tag_result = 2, tag_stop = 3
   !> Most impacts of a chunk (some milliseconds of work: a message's round trip, which
   !> on a loaded machine can cost a time slice of the scheduler, stays small beside
   !> it), and chunks handed to a rank ahead of its results (so that it never waits
   !> for rank 0 between two chunks)
   integer, parameter :: max_chunk = 1024, in_flight = 2
   !> How long a rank without work sleeps before it looks for a message again, in
   !> microseconds: waiting in MPI_Probe would spin and take a core from rank 0 (which
   !> writes the files after the sweep) and from other jobs of a shared machine
   integer, parameter :: idle_pause = 200
   !> Doubles of a chunk message (first index, count, the contact's mass, stiffness,
   !> exponent and damping, the speeds) and of a result message (first index, count,
   !> then per impact: the nine outcomes, the three evaluation counts, the status)
   integer, parameter :: head = 2, n_contact = 4
   integer, parameter :: work_size = head + n_contact + max_chunk, &
      & result_size = head + per_impact * max_chunk

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

   !> The work of a rank other than 0: compute the chunks rank 0 sends until it says
   !> the program ends.
   subroutine sweep_serve(code)
      !> Exit code of the process
      integer, intent(out) :: code
      type(MPI_Status) :: status
      type(MPI_Request) :: sending(in_flight)
      type(contact_type) :: contact
      type(outcome_type), allocatable :: out(:)
      real(wp), allocatable :: work(:)
      real(wp), allocatable, asynchronous :: results(:, :)
      integer, allocatable :: stats(:)
      integer :: count, i, slot
      logical :: arrived
      code = 0
      allocate(out(max_chunk), work(work_size), results(result_size, in_flight), &
         & stats(max_chunk))
      ! the results go back without waiting for rank 0 to take them (it may be busy with
      ! a chunk of its own), each from its own buffer until its send is complete
      sending = MPI_REQUEST_NULL
      slot = 1
      do
         do
            call MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, arrived, status)
            if (arrived) exit
            call pause_microseconds(idle_pause)
         end do
         if (status%MPI_TAG /= tag_work) then
            call MPI_Recv(work, work_size, MPI_DOUBLE_PRECISION, 0, status%MPI_TAG, &
               & MPI_COMM_WORLD, status)
            do slot = 1, in_flight
               call MPI_Wait(sending(slot), MPI_STATUS_IGNORE)
            end do
            exit
         end if
         call MPI_Recv(work, work_size, MPI_DOUBLE_PRECISION, 0, tag_work, MPI_COMM_WORLD, &
            & status)
         count = nint(work(2))
         contact = contact_type(mass=work(3), stiffness=work(4), exponent=work(5), &
            & damping=work(6))
         call impacts_of(contact, work(head + n_contact + 1:head + n_contact + count), &
            & out(1:count), stats(1:count))
         call MPI_Wait(sending(slot), MPI_STATUS_IGNORE)
         results(1:head, slot) = work(1:head)
         do i = 1, count
            results(head + per_impact * (i - 1) + 1:head + per_impact * i, slot) = &
               & packed(out(i), stats(i))
         end do
         call MPI_Isend(results(:, slot), head + per_impact * count, MPI_DOUBLE_PRECISION, 0, &
            & tag_result, MPI_COMM_WORLD, sending(slot))
         slot = modulo(slot, in_flight) + 1
      end do
   end subroutine sweep_serve

   !> The end of the program: rank 0 tells the other ranks, and every rank finishes MPI.
   subroutine sweep_end()
      real(wp) :: nothing(1)
      integer :: rank
      if (.not. started .or. finished) return
      if (my_rank == 0) then
         do rank = 1, n_ranks - 1
            call MPI_Send(nothing, 0, MPI_DOUBLE_PRECISION, rank, tag_stop, MPI_COMM_WORLD)
         end do
      end if
      call MPI_Finalize()
      finished = .true.
   end subroutine sweep_end

   !> How the impacts of a sweep are computed, for the plan.
   function sweep_description() result(text)
      character(len=:), allocatable :: text
      if (.not. started) then
         text = "on this process (not started by an MPI launcher: MPI not used)"
      else if (n_ranks == 1) then
         text = "on this process (MPI, 1 rank)"
      else
         text = "over " // str(n_ranks) // " MPI ranks: chunks of up to " // str(max_chunk) &
            & // " speeds handed out by rank 0 on request (rank 0 computes too), the" &
            & // " results put back in order"
      end if
   end function sweep_description

   !> The impacts of `contact` at each of `speeds` (its velocity replaced), with the
   !> progress shown under `label`: on rank 0, handed out to every rank; those the
   !> checkpoint holds are taken from it.
   subroutine sweep_impacts(contact, speeds, label, checkpoint, out, stats, resumed, error)
      !> The contact (masses, law, damping); its velocity is not used
      type(contact_type), intent(in) :: contact
      !> The approach speeds in m/s
      real(wp), intent(in) :: speeds(:)
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
      !> other ranks must not be left with chunks nobody takes)
      character(len=:), allocatable, intent(out) :: error
      type(checkpoint_type) :: ck
      logical, allocatable :: done(:)
      integer, allocatable :: todo(:)
      type(MPI_Status) :: status
      real(wp), allocatable :: results(:)
      ! the chunks on their way to each rank: their buffers and sends (a chunk can be
      ! larger than what MPI sends without the receiver's help, and the receiver is
      ! busy with its previous chunk: rank 0 must not wait for it)
      real(wp), allocatable, asynchronous :: work(:, :, :)
      type(MPI_Request), allocatable :: sending(:, :)
      integer, allocatable :: slot(:)
      integer :: n, chunk, n_chunks, next, received, finished, rank, k, first, count, i
      logical :: arrived

      n = size(speeds)
      allocate(done(n))
      call checkpoint_start(checkpoint, contact, speeds, out, stats, done, resumed, ck, error)
      if (allocated(error)) return
      allocate(results(result_size), work(work_size, in_flight, n_ranks - 1), &
         & sending(in_flight, n_ranks - 1), slot(n_ranks - 1))
      sending = MPI_REQUEST_NULL
      slot = 1
      ! eight chunks per rank at least, so that the last ones even out the ranks
      chunk = max(1, min(max_chunk, n / (8 * n_ranks)))
      ! the chunks still to compute: all but those the checkpoint holds whole (one it
      ! holds in part is computed again: the same doubles)
      todo = [(k, k = 1, (n + chunk - 1) / chunk)]
      todo = pack(todo, [(.not. all(done((k - 1) * chunk + 1:min(k * chunk, n))), &
         & k = 1, size(todo))])
      n_chunks = size(todo)
      next = 1
      do k = 1, in_flight
         do rank = 1, n_ranks - 1
            if (next > n_chunks) exit
            call send_chunk(rank, todo(next))
            next = next + 1
         end do
      end do
      received = 0
      finished = n - sum([(min(chunk, n - (todo(k) - 1) * chunk), k = 1, n_chunks)])
      call progress_begin(label, n, finished)
      do while (received < n_chunks)
         arrived = .false.
         if (n_ranks > 1) call MPI_Iprobe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, &
            & arrived, status)
         if (.not. arrived .and. next <= n_chunks) then
            ! nothing has come back: compute the next chunk here
            first = (todo(next) - 1) * chunk + 1
            count = min(chunk, n - first + 1)
            call impacts_of(contact, speeds(first:first + count - 1), &
               & out(first:first + count - 1), stats(first:first + count - 1))
            next = next + 1
         else
            call MPI_Recv(results, result_size, MPI_DOUBLE_PRECISION, MPI_ANY_SOURCE, &
               & tag_result, MPI_COMM_WORLD, status)
            first = nint(results(1))
            count = nint(results(2))
            do i = 1, count
               call unpack(results(head + per_impact * (i - 1) + 1:head + per_impact * i), &
                  & out(first + i - 1), stats(first + i - 1))
            end do
            if (next <= n_chunks) then
               call send_chunk(status%MPI_SOURCE, todo(next))
               next = next + 1
            end if
         end if
         call checkpoint_record(ck, first, out(first:first + count - 1), &
            & stats(first:first + count - 1), error)
         received = received + 1
         finished = finished + count
         call progress_step(finished)
      end do
      call checkpoint_finish(ck, error)
      ! every chunk's results are back, so every chunk was received: these return at once
      do rank = 1, n_ranks - 1
         do k = 1, in_flight
            call MPI_Wait(sending(k, rank), MPI_STATUS_IGNORE)
         end do
      end do
      call progress_end()

   contains

      !> Send chunk k to a rank, from the buffer of its oldest chunk (whose results are
      !> back, or which was never used), without waiting for the rank to take it.
      subroutine send_chunk(to, k)
         integer, intent(in) :: to, k
         integer :: first, count, s
         first = (k - 1) * chunk + 1
         count = min(chunk, n - first + 1)
         s = slot(to)
         slot(to) = modulo(s, in_flight) + 1
         call MPI_Wait(sending(s, to), MPI_STATUS_IGNORE)
         work(1:head + n_contact, s, to) = [real(first, wp), real(count, wp), contact%mass, &
            & contact%stiffness, contact%exponent, contact%damping]
         work(head + n_contact + 1:head + n_contact + count, s, to) = &
            & speeds(first:first + count - 1)
         call MPI_Isend(work(:, s, to), head + n_contact + count, MPI_DOUBLE_PRECISION, to, &
            & tag_work, MPI_COMM_WORLD, sending(s, to))
      end subroutine send_chunk

   end subroutine sweep_impacts

   !> The impacts of one chunk, one after the other.
   subroutine impacts_of(contact, speeds, out, stats)
      type(contact_type), intent(in) :: contact
      real(wp), intent(in) :: speeds(:)
      type(outcome_type), intent(out) :: out(:)
      integer, intent(out) :: stats(:)
      type(contact_type) :: at_speed
      integer :: i
      at_speed = contact
      do i = 1, size(speeds)
         at_speed%velocity = speeds(i)
         call impact(at_speed, out(i), stats(i))
      end do
   end subroutine impacts_of

end module hcimpact_scene_sweep
