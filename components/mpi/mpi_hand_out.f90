! SPDX-License-Identifier: Apache-2.0
!> The dynamic hand-out of independent work items over the ranks of an MPI
!> communicator (doc/mpi.md), the one place of it: the sweeps of single impacts
!> (hcimpact_mpi_sweep) and the scene runner's sweeps of systems of bodies are
!> clients. An item is a column of doubles in, a column of doubles out; a worker
!> turns one into the other, on whichever rank computes it, and rank 0 receives every
!> item's column at its index: the very doubles a serial loop over the items computes,
!> for any number of ranks.
!>
!> Rank 0 cuts the items into chunks of consecutive items (at least eight per rank,
!> at most `max_chunk`); it sends every other rank two chunks, and one more each time
!> a chunk's results come back (point-to-point messages: a costly chunk, or a slow
!> rank, holds up no other), and computes a chunk itself whenever no result is
!> waiting. The call works on a duplicate of the communicator, so that its messages
!> never meet the caller's. Where MPI is not initialized (or already finalized) every
!> item is computed on the calling process. No state is kept between calls.
module hcimpact_mpi_hand_out
   use, intrinsic :: iso_c_binding, only : c_int
   use mpi_f08, only : MPI_Comm, MPI_Status, MPI_Request, MPI_Initialized, MPI_Finalized, &
      & MPI_Comm_dup, MPI_Comm_free, MPI_Comm_rank, MPI_Comm_size, MPI_Send, MPI_Isend, &
      & MPI_Recv, MPI_Iprobe, MPI_Wait, MPI_DOUBLE_PRECISION, MPI_ANY_SOURCE, MPI_ANY_TAG, &
      & MPI_REQUEST_NULL, MPI_STATUS_IGNORE, MPI_COMM_NULL, MPI_Get_count, operator(==)
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_size
   implicit none
   private

   public :: mpi_hand_out, mpi_sweep_refuse, mpi_sweep_rank, sweep_worker, items_listener

   !> Turns an item's doubles into its result's (on every rank: each rank's worker must
   !> compute the same doubles for the same item)
   type, abstract :: sweep_worker
   contains
      !> output = the result of the item `input`
      procedure(compute_interface), deferred :: compute
      !> Rank 0, after every item: the status every rank returns
      procedure(verdict_interface), deferred :: verdict
   end type sweep_worker

   !> What rank 0 is told of each chunk as its results are in (in the order they come in)
   type, abstract :: items_listener
   contains
      procedure(items_done_interface), deferred :: items_done
   end type items_listener

   abstract interface
      !> The result of one item.
      subroutine compute_interface(self, input, output)
         import :: sweep_worker, wp
         class(sweep_worker), intent(inout) :: self
         real(wp), intent(in) :: input(:)
         real(wp), intent(out) :: output(:)
      end subroutine compute_interface

      !> Rank 0: the status of the whole hand-out, from every item's result.
      integer function verdict_interface(self, outputs)
         import :: sweep_worker, wp
         class(sweep_worker), intent(in) :: self
         real(wp), intent(in) :: outputs(:, :)
      end function verdict_interface

      !> Items first .. first + size(outputs, 2) - 1 are done (rank 0).
      subroutine items_done_interface(self, first, outputs)
         import :: items_listener, wp
         class(items_listener), intent(inout) :: self
         integer, intent(in) :: first
         real(wp), intent(in) :: outputs(:, :)
      end subroutine items_done_interface
   end interface

   interface
      !> POSIX usleep: a rank without work sleeps instead of spinning in MPI
      function c_usleep(microseconds) bind(C, name="usleep") result(r)
         import :: c_int
         integer(c_int), value :: microseconds
         integer(c_int) :: r
      end function c_usleep
   end interface

   !> Message tags: a chunk to compute, its results, the end of the hand-out
   integer, parameter :: tag_work = 1, tag_result = 2, tag_stop = 3
   !> Chunks handed to a rank ahead of its results, so that it never waits for rank 0
   !> between two chunks
   integer, parameter :: in_flight = 2
   !> How long a rank without work sleeps before it looks for a message again, in
   !> microseconds: waiting inside MPI would spin and take a core from rank 0 (and from
   !> other jobs of a shared machine)
   integer, parameter :: idle_pause = 200
   !> Doubles of a message's head: first index, count, the sizes of an item's input and
   !> output columns (integers, exact in doubles)
   integer, parameter :: head = 4

contains

   !> Hand the items out, collectively: every rank of `comm` calls it with its worker.
   !> On rank 0 `outputs(:, i)` receives `worker%compute(inputs(:, i))`, except for the
   !> items `known` marks when their whole chunk is known (a chunk with an unknown item
   !> is computed whole: the same doubles); `listener` is told of every chunk as it is
   !> done. The other ranks' `inputs`, `outputs`, `known`, `listener` and `max_chunk`
   !> are not used. `status` on every rank: `worker%verdict(outputs)` of rank 0, or
   !> hcimpact_err_size when rank 0's `outputs` or `known` does not have as many items
   !> as `inputs` (nothing computed).
   subroutine mpi_hand_out(comm, worker, inputs, outputs, status, known, listener, max_chunk)
      !> The communicator (its rank 0 gives the items)
      type(MPI_Comm), intent(in) :: comm
      !> Computes an item (every rank)
      class(sweep_worker), intent(inout) :: worker
      !> The items, one per column (rank 0)
      real(wp), intent(in) :: inputs(:, :)
      !> Their results, one per column (rank 0)
      real(wp), intent(inout) :: outputs(:, :)
      !> The verdict, or hcimpact_err_size (every rank)
      integer, intent(out) :: status
      !> Items whose results are given already (rank 0)
      logical, intent(in), optional :: known(:)
      !> Told of each chunk done (rank 0)
      class(items_listener), intent(inout), optional :: listener
      !> Most items of a chunk (rank 0; default 1024)
      integer, intent(in), optional :: max_chunk
      type(MPI_Comm) :: own
      integer :: rank, ranks, n, limit
      logical :: active

      call open_sweep(comm, own, rank, ranks, active)
      if (rank /= 0) then
         call serve(own, worker, status)
         call MPI_Comm_free(own)
         return
      end if
      n = size(inputs, 2)
      status = hcimpact_ok
      if (size(outputs, 2) /= n) status = hcimpact_err_size
      if (present(known)) then
         if (size(known) /= n) status = hcimpact_err_size
      end if
      limit = 1024
      if (present(max_chunk)) limit = max(1, max_chunk)
      if (status == hcimpact_ok) then
         call hand_out(own, ranks, worker, inputs, outputs, known, listener, limit)
         status = worker%verdict(outputs)
      end if
      call close_sweep(own, ranks, active, status)
   end subroutine mpi_hand_out

   !> Rank 0's side of a hand-out it refuses before any work (a bad argument of an
   !> interface above this one): every other rank, in its `mpi_hand_out`, returns
   !> `status`.
   subroutine mpi_sweep_refuse(comm, status)
      !> The communicator of the collective call
      type(MPI_Comm), intent(in) :: comm
      !> The status every rank returns
      integer, intent(in) :: status
      type(MPI_Comm) :: own
      integer :: rank, ranks
      logical :: active
      call open_sweep(comm, own, rank, ranks, active)
      call close_sweep(own, ranks, active, status)
   end subroutine mpi_sweep_refuse

   !> This process's rank in `comm`, as the hand-out sees it: 0 where MPI is not running
   !> (not initialized, already finalized) or `comm` is MPI_COMM_NULL.
   integer function mpi_sweep_rank(comm) result(rank)
      !> The communicator
      type(MPI_Comm), intent(in) :: comm
      rank = 0
      if (running(comm)) call MPI_Comm_rank(comm, rank)
   end function mpi_sweep_rank

   !> Whether MPI is running (initialized, not finalized) and `comm` is a communicator.
   logical function running(comm)
      type(MPI_Comm), intent(in) :: comm
      logical :: initialized, finalized
      call MPI_Initialized(initialized)
      call MPI_Finalized(finalized)
      running = initialized .and. .not. finalized
      if (running) running = .not. (comm == MPI_COMM_NULL)
   end function running

   !> The hand-out's own communicator, this process's rank and the number of ranks;
   !> where MPI is not running, rank 0 of 1 and `active` false.
   subroutine open_sweep(comm, own, rank, ranks, active)
      type(MPI_Comm), intent(in) :: comm
      type(MPI_Comm), intent(out) :: own
      integer, intent(out) :: rank, ranks
      logical, intent(out) :: active
      rank = 0
      ranks = 1
      active = running(comm)
      if (.not. active) return
      call MPI_Comm_dup(comm, own)
      call MPI_Comm_rank(own, rank)
      call MPI_Comm_size(own, ranks)
   end subroutine open_sweep

   !> Rank 0 ends the hand-out: every other rank is sent the status, and the duplicate
   !> communicator is freed.
   subroutine close_sweep(own, ranks, active, status)
      type(MPI_Comm), intent(inout) :: own
      integer, intent(in) :: ranks, status
      logical, intent(in) :: active
      real(wp) :: message(head)
      integer :: rank
      if (.not. active) return
      message = 0.0_wp
      message(1) = real(status, wp)
      do rank = 1, ranks - 1
         call MPI_Send(message, head, MPI_DOUBLE_PRECISION, rank, tag_stop, own)
      end do
      call MPI_Comm_free(own)
   end subroutine close_sweep

   !> Rank 0: hand the chunks out, compute some, put the results in place.
   subroutine hand_out(own, ranks, worker, inputs, outputs, known, listener, limit)
      type(MPI_Comm), intent(in) :: own
      integer, intent(in) :: ranks, limit
      class(sweep_worker), intent(inout) :: worker
      real(wp), intent(in) :: inputs(:, :)
      real(wp), intent(inout) :: outputs(:, :)
      logical, intent(in), optional :: known(:)
      class(items_listener), intent(inout), optional :: listener
      type(MPI_Status) :: probe
      real(wp), allocatable :: results(:)
      ! the chunks on their way to each rank: their buffers and sends (a chunk can be
      ! larger than what MPI sends without the receiver's help, and the receiver is
      ! busy with its previous chunk: rank 0 must not wait for it)
      real(wp), allocatable, asynchronous :: work(:, :, :)
      type(MPI_Request), allocatable :: sending(:, :)
      integer, allocatable :: slot(:), todo(:)
      integer :: n, n_in, n_out, chunk, n_chunks, next, received, rank, k, first, count, i
      logical :: arrived

      n = size(inputs, 2)
      n_in = size(inputs, 1)
      n_out = size(outputs, 1)
      if (n == 0) return
      ! eight chunks per rank at least, so that the last ones even out the ranks
      chunk = max(1, min(limit, n / (8 * ranks)))
      ! the chunks still to compute: all but those `known` covers whole
      todo = [(k, k = 1, (n + chunk - 1) / chunk)]
      if (present(known)) todo = pack(todo, [(.not. all(known((k - 1) * chunk + 1: &
         & min(k * chunk, n))), k = 1, size(todo))])
      n_chunks = size(todo)
      allocate(results(head + n_out * chunk), work(head + n_in * chunk, in_flight, &
         & ranks - 1), sending(in_flight, ranks - 1), slot(ranks - 1))
      sending = MPI_REQUEST_NULL
      slot = 1
      next = 1
      do k = 1, in_flight
         do rank = 1, ranks - 1
            if (next > n_chunks) exit
            call send_chunk(rank, todo(next))
            next = next + 1
         end do
      end do
      received = 0
      do while (received < n_chunks)
         arrived = .false.
         if (ranks > 1) call MPI_Iprobe(MPI_ANY_SOURCE, tag_result, own, arrived, probe)
         if (.not. arrived .and. next <= n_chunks) then
            ! nothing has come back: compute the next chunk here
            first = (todo(next) - 1) * chunk + 1
            count = min(chunk, n - first + 1)
            do i = first, first + count - 1
               call worker%compute(inputs(:, i), outputs(:, i))
            end do
            next = next + 1
         else
            call MPI_Recv(results, size(results), MPI_DOUBLE_PRECISION, MPI_ANY_SOURCE, &
               & tag_result, own, probe)
            first = nint(results(1))
            count = nint(results(2))
            outputs(:, first:first + count - 1) = reshape(results(head + 1:head + n_out &
               & * count), [n_out, count])
            if (next <= n_chunks) then
               call send_chunk(probe%MPI_SOURCE, todo(next))
               next = next + 1
            end if
         end if
         if (present(listener)) call listener%items_done(first, &
            & outputs(:, first:first + count - 1))
         received = received + 1
      end do
      ! every chunk's results are back, so every chunk was received: these return at once
      do rank = 1, ranks - 1
         do k = 1, in_flight
            call MPI_Wait(sending(k, rank), MPI_STATUS_IGNORE)
         end do
      end do

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
         work(1:head, s, to) = [real(first, wp), real(count, wp), real(n_in, wp), &
            & real(n_out, wp)]
         work(head + 1:head + n_in * count, s, to) = reshape(inputs(:, first:first + count &
            & - 1), [n_in * count])
         call MPI_Isend(work(:, s, to), head + n_in * count, MPI_DOUBLE_PRECISION, to, &
            & tag_work, own, sending(s, to))
      end subroutine send_chunk

   end subroutine hand_out

   !> A rank other than 0: compute the chunks rank 0 sends until it ends the hand-out;
   !> `status` is the one rank 0 sends.
   subroutine serve(own, worker, status)
      type(MPI_Comm), intent(in) :: own
      class(sweep_worker), intent(inout) :: worker
      integer, intent(out) :: status
      type(MPI_Status) :: probe
      type(MPI_Request) :: sending(in_flight)
      real(wp), allocatable :: work(:)
      ! one buffer per result in flight, each until its send is complete
      type :: result_buffer
         real(wp), allocatable :: values(:)
      end type result_buffer
      type(result_buffer), asynchronous :: results(in_flight)
      integer :: count, i, slot, ignored, size_of_message, n_in, n_out
      logical :: arrived
      sending = MPI_REQUEST_NULL
      slot = 1
      do
         do
            call MPI_Iprobe(0, MPI_ANY_TAG, own, arrived, probe)
            if (arrived) exit
            ignored = c_usleep(int(idle_pause, c_int))
         end do
         call doubles_of(probe, size_of_message)
         if (allocated(work)) then
            if (size(work) < size_of_message) deallocate(work)
         end if
         if (.not. allocated(work)) allocate(work(max(size_of_message, head)))
         call MPI_Recv(work, size(work), MPI_DOUBLE_PRECISION, 0, probe%MPI_TAG, own, probe)
         if (probe%MPI_TAG /= tag_work) then
            status = nint(work(1))
            do slot = 1, in_flight
               call MPI_Wait(sending(slot), MPI_STATUS_IGNORE)
            end do
            return
         end if
         count = nint(work(2))
         n_in = nint(work(3))
         n_out = nint(work(4))
         call MPI_Wait(sending(slot), MPI_STATUS_IGNORE)
         if (allocated(results(slot)%values)) then
            if (size(results(slot)%values) < head + n_out * count) &
               & deallocate(results(slot)%values)
         end if
         if (.not. allocated(results(slot)%values)) &
            & allocate(results(slot)%values(head + n_out * count))
         results(slot)%values(1:head) = work(1:head)
         do i = 1, count
            call worker%compute(work(head + n_in * (i - 1) + 1:head + n_in * i), &
               & results(slot)%values(head + n_out * (i - 1) + 1:head + n_out * i))
         end do
         call MPI_Isend(results(slot)%values, head + n_out * count, MPI_DOUBLE_PRECISION, 0, &
            & tag_result, own, sending(slot))
         slot = modulo(slot, in_flight) + 1
      end do
   end subroutine serve

   !> The number of doubles of a probed message.
   subroutine doubles_of(probe, count)
      type(MPI_Status), intent(in) :: probe
      integer, intent(out) :: count
      call MPI_Get_count(probe, MPI_DOUBLE_PRECISION, count)
   end subroutine doubles_of

end module hcimpact_mpi_hand_out
