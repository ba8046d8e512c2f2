! SPDX-License-Identifier: Apache-2.0
!> Sweeps of single impacts over the ranks of an MPI communicator (doc/mpi.md): the
!> component hcimpact::mpi (libhcimpact_mpi), built only where MPI for Fortran with
!> its mpi_f08 module is found; libhcimpact itself never links MPI.
!>
!> `mpi_impact_sweep` is collective over a communicator: rank 0 gives the contacts and
!> receives, in their order, the outcome and status of each, the very doubles `impact`
!> computes for it on one process (every impact is computed alone, by the same code,
!> from the same doubles sent as doubles); the other ranks only compute. The contacts
!> are cut into chunks of consecutive items (at least eight per rank, at most
!> `mpi_sweep_max_chunk` items); rank 0 sends every other rank two chunks, and one
!> more each time a chunk's results come back (point-to-point messages: a costly
!> chunk, or a slow rank, holds up no other), and computes a chunk itself whenever no
!> result is waiting. The call works on a duplicate of the communicator, so that its
!> messages never meet the caller's.
!>
!> Where MPI is not initialized (or already finalized) the sweep runs on the calling
!> process alone, with the same results: a program built with MPI but started without
!> a launcher needs no second path.
!>
!> A rank that dies ends the job through MPI's error handler (the default one aborts
!> every rank). No state is kept between calls.
module hcimpact_mpi_sweep
   use, intrinsic :: iso_c_binding, only : c_int
   use mpi_f08, only : MPI_Comm, MPI_Status, MPI_Request, MPI_Initialized, MPI_Finalized, &
      & MPI_Comm_dup, MPI_Comm_free, MPI_Comm_rank, MPI_Comm_size, MPI_Send, MPI_Isend, &
      & MPI_Recv, MPI_Iprobe, MPI_Wait, MPI_DOUBLE_PRECISION, MPI_ANY_SOURCE, MPI_ANY_TAG, &
      & MPI_REQUEST_NULL, MPI_STATUS_IGNORE, MPI_COMM_NULL, operator(==)
   use hcimpact_kinds, only : wp, ik
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_size
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   implicit none
   private

   public :: mpi_impact_sweep, mpi_sweep_refuse, mpi_sweep_rank, sweep_listener, &
      & mpi_sweep_max_chunk

   !> Most items of a chunk (some milliseconds of closed forms: a message's round trip,
   !> which on a loaded machine can cost a time slice of the scheduler, stays small
   !> beside it)
   integer, parameter :: mpi_sweep_max_chunk = 1024

   !> What rank 0 is told of each chunk as its results are in (in the order they come
   !> in, not in the items' order): extend it, e.g. to checkpoint the results or show
   !> the progress
   type, abstract :: sweep_listener
   contains
      !> The items first, first + 1, ... have their outcomes and statuses
      procedure(chunk_done_interface), deferred :: chunk_done
   end type sweep_listener

   abstract interface
      !> Items first .. first + size(out) - 1 are done (on rank 0).
      subroutine chunk_done_interface(self, first, out, stats)
         import :: sweep_listener, outcome_type
         class(sweep_listener), intent(inout) :: self
         !> Index of the chunk's first item
         integer, intent(in) :: first
         !> The chunk's outcomes and statuses
         type(outcome_type), intent(in) :: out(:)
         integer, intent(in) :: stats(:)
      end subroutine chunk_done_interface
   end interface

   interface
      !> POSIX usleep: a rank without work sleeps instead of spinning in MPI
      function c_usleep(microseconds) bind(C, name="usleep") result(r)
         import :: c_int
         integer(c_int), value :: microseconds
         integer(c_int) :: r
      end function c_usleep
   end interface

   !> Message tags: a chunk to compute, its results, the end of the sweep
   integer, parameter :: tag_work = 1, tag_result = 2, tag_stop = 3
   !> Chunks handed to a rank ahead of its results, so that it never waits for rank 0
   !> between two chunks
   integer, parameter :: in_flight = 2
   !> How long a rank without work sleeps before it looks for a message again, in
   !> microseconds: waiting inside MPI would spin and take a core from rank 0 (and from
   !> other jobs of a shared machine)
   integer, parameter :: idle_pause = 200
   !> Doubles of a message's head (first index, count), of a contact (mass, stiffness,
   !> exponent, damping, velocity) and of an outcome with its status (the nine values,
   !> the three evaluation counts and the status, integers exact in doubles)
   integer, parameter :: head = 2, per_contact = 5, per_outcome = 13
   integer, parameter :: work_size = head + per_contact * mpi_sweep_max_chunk, &
      & result_size = head + per_outcome * mpi_sweep_max_chunk

contains

   !> The impacts of `contacts` over the ranks of `comm`, collectively: every rank of
   !> `comm` calls it. On rank 0: `contacts` are read; `out(i)` and `stats(i)` receive
   !> the outcome and status of `impact` for `contacts(i)`, the same doubles as on one
   !> process, except the items `known` marks, which are left as given (a chunk that
   !> holds an unknown item is computed whole: the same doubles); `listener` is told
   !> of every chunk as it is done. On the other ranks these arguments are not used
   !> (arrays of size 0 will do). `status` on every rank: hcimpact_ok when every item
   !> succeeded, otherwise the status of the first (lowest index) that failed;
   !> hcimpact_err_size when, on rank 0, `out`, `stats` or `known` is not of the size
   !> of `contacts` (nothing computed); the same value on every rank.
   subroutine mpi_impact_sweep(comm, contacts, out, stats, status, known, listener)
      !> The communicator (its rank 0 gives the contacts)
      type(MPI_Comm), intent(in) :: comm
      !> The contacts (rank 0)
      type(contact_type), intent(in) :: contacts(:)
      !> Their outcomes and statuses (rank 0)
      type(outcome_type), intent(inout) :: out(:)
      integer, intent(inout) :: stats(:)
      !> hcimpact_ok or the first failure (every rank)
      integer, intent(out) :: status
      !> Items whose outcome and status are given already (rank 0)
      logical, intent(in), optional :: known(:)
      !> Told of each chunk done (rank 0)
      class(sweep_listener), intent(inout), optional :: listener
      type(MPI_Comm) :: own
      integer :: rank, ranks, n
      logical :: active

      call open_sweep(comm, own, rank, ranks, active)
      if (rank /= 0) then
         call serve(own, status)
         call MPI_Comm_free(own)
         return
      end if
      n = size(contacts)
      status = hcimpact_ok
      if (size(out) /= n .or. size(stats) /= n) status = hcimpact_err_size
      if (present(known)) then
         if (size(known) /= n) status = hcimpact_err_size
      end if
      if (status == hcimpact_ok) then
         call hand_out(own, ranks, contacts, out, stats, known, listener)
         status = first_failure(stats)
      end if
      call close_sweep(own, ranks, active, status)
   end subroutine mpi_impact_sweep

   !> Rank 0's side of a sweep it refuses before any work (a bad argument of an
   !> interface above this one): every other rank, in its `mpi_impact_sweep`, returns
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

   !> This process's rank in `comm`, as the sweep sees it: 0 where MPI is not running
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

   !> The sweep's own communicator, this process's rank and the number of ranks; where
   !> MPI is not running, rank 0 of 1 and `active` false.
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

   !> Rank 0 ends the sweep: every other rank is sent the status, and the duplicate
   !> communicator is freed.
   subroutine close_sweep(own, ranks, active, status)
      type(MPI_Comm), intent(inout) :: own
      integer, intent(in) :: ranks, status
      logical, intent(in) :: active
      real(wp) :: message(1)
      integer :: rank
      if (.not. active) return
      message(1) = real(status, wp)
      do rank = 1, ranks - 1
         call MPI_Send(message, 1, MPI_DOUBLE_PRECISION, rank, tag_stop, own)
      end do
      call MPI_Comm_free(own)
   end subroutine close_sweep

   !> The status of the first item that failed, or hcimpact_ok.
   pure integer function first_failure(stats)
      integer, intent(in) :: stats(:)
      integer :: i
      first_failure = hcimpact_ok
      do i = 1, size(stats)
         if (stats(i) /= hcimpact_ok) then
            first_failure = stats(i)
            return
         end if
      end do
   end function first_failure

   !> Rank 0: hand the chunks out, compute some, put the results in place.
   subroutine hand_out(own, ranks, contacts, out, stats, known, listener)
      type(MPI_Comm), intent(in) :: own
      integer, intent(in) :: ranks
      type(contact_type), intent(in) :: contacts(:)
      type(outcome_type), intent(inout) :: out(:)
      integer, intent(inout) :: stats(:)
      logical, intent(in), optional :: known(:)
      class(sweep_listener), intent(inout), optional :: listener
      type(MPI_Status) :: probe
      real(wp), allocatable :: results(:)
      ! the chunks on their way to each rank: their buffers and sends (a chunk can be
      ! larger than what MPI sends without the receiver's help, and the receiver is
      ! busy with its previous chunk: rank 0 must not wait for it)
      real(wp), allocatable, asynchronous :: work(:, :, :)
      type(MPI_Request), allocatable :: sending(:, :)
      integer, allocatable :: slot(:), todo(:)
      integer :: n, chunk, n_chunks, next, received, rank, k, first, count, i
      logical :: arrived

      n = size(contacts)
      if (n == 0) return
      ! eight chunks per rank at least, so that the last ones even out the ranks
      chunk = max(1, min(mpi_sweep_max_chunk, n / (8 * ranks)))
      ! the chunks still to compute: all but those `known` covers whole
      todo = [(k, k = 1, (n + chunk - 1) / chunk)]
      if (present(known)) todo = pack(todo, [(.not. all(known((k - 1) * chunk + 1: &
         & min(k * chunk, n))), k = 1, size(todo))])
      n_chunks = size(todo)
      allocate(results(result_size), work(work_size, in_flight, ranks - 1), &
         & sending(in_flight, ranks - 1), slot(ranks - 1))
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
            call impacts_of(contacts(first:first + count - 1), out(first:first + count - 1), &
               & stats(first:first + count - 1))
            next = next + 1
         else
            call MPI_Recv(results, result_size, MPI_DOUBLE_PRECISION, MPI_ANY_SOURCE, &
               & tag_result, own, probe)
            first = nint(results(1))
            count = nint(results(2))
            do i = 1, count
               call unpack_outcome(results(head + per_outcome * (i - 1) + 1: &
                  & head + per_outcome * i), out(first + i - 1), stats(first + i - 1))
            end do
            if (next <= n_chunks) then
               call send_chunk(probe%MPI_SOURCE, todo(next))
               next = next + 1
            end if
         end if
         if (present(listener)) call listener%chunk_done(first, out(first:first + count - 1), &
            & stats(first:first + count - 1))
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
         integer :: first, count, s, i
         first = (k - 1) * chunk + 1
         count = min(chunk, n - first + 1)
         s = slot(to)
         slot(to) = modulo(s, in_flight) + 1
         call MPI_Wait(sending(s, to), MPI_STATUS_IGNORE)
         work(1:head, s, to) = [real(first, wp), real(count, wp)]
         do i = 1, count
            work(head + per_contact * (i - 1) + 1:head + per_contact * i, s, to) = &
               & packed_contact(contacts(first + i - 1))
         end do
         call MPI_Isend(work(:, s, to), head + per_contact * count, MPI_DOUBLE_PRECISION, to, &
            & tag_work, own, sending(s, to))
      end subroutine send_chunk

   end subroutine hand_out

   !> A rank other than 0: compute the chunks rank 0 sends until it ends the sweep;
   !> `status` is the sweep's, as rank 0 sends it.
   subroutine serve(own, status)
      type(MPI_Comm), intent(in) :: own
      integer, intent(out) :: status
      type(MPI_Status) :: probe
      type(MPI_Request) :: sending(in_flight)
      type(contact_type), allocatable :: contacts(:)
      type(outcome_type), allocatable :: out(:)
      real(wp), allocatable :: work(:)
      real(wp), allocatable, asynchronous :: results(:, :)
      integer, allocatable :: stats(:)
      integer :: count, i, slot, ignored
      logical :: arrived
      allocate(contacts(mpi_sweep_max_chunk), out(mpi_sweep_max_chunk), work(work_size), &
         & results(result_size, in_flight), stats(mpi_sweep_max_chunk))
      ! the results go back without waiting for rank 0 to take them (it may be busy with
      ! a chunk of its own), each from its own buffer until its send is complete
      sending = MPI_REQUEST_NULL
      slot = 1
      do
         do
            call MPI_Iprobe(0, MPI_ANY_TAG, own, arrived, probe)
            if (arrived) exit
            ignored = c_usleep(int(idle_pause, c_int))
         end do
         call MPI_Recv(work, work_size, MPI_DOUBLE_PRECISION, 0, probe%MPI_TAG, own, probe)
         if (probe%MPI_TAG /= tag_work) then
            status = nint(work(1))
            do slot = 1, in_flight
               call MPI_Wait(sending(slot), MPI_STATUS_IGNORE)
            end do
            return
         end if
         count = nint(work(2))
         do i = 1, count
            contacts(i) = unpacked_contact(work(head + per_contact * (i - 1) + 1: &
               & head + per_contact * i))
         end do
         call impacts_of(contacts(1:count), out(1:count), stats(1:count))
         call MPI_Wait(sending(slot), MPI_STATUS_IGNORE)
         results(1:head, slot) = work(1:head)
         do i = 1, count
            results(head + per_outcome * (i - 1) + 1:head + per_outcome * i, slot) = &
               & packed_outcome(out(i), stats(i))
         end do
         call MPI_Isend(results(:, slot), head + per_outcome * count, MPI_DOUBLE_PRECISION, 0, &
            & tag_result, own, sending(slot))
         slot = modulo(slot, in_flight) + 1
      end do
   end subroutine serve

   !> The impacts of one chunk, one after the other.
   subroutine impacts_of(contacts, out, stats)
      type(contact_type), intent(in) :: contacts(:)
      type(outcome_type), intent(out) :: out(:)
      integer, intent(out) :: stats(:)
      integer :: i
      do i = 1, size(contacts)
         call impact(contacts(i), out(i), stats(i))
      end do
   end subroutine impacts_of

   !> A contact as the doubles of a message.
   pure function packed_contact(contact) result(values)
      type(contact_type), intent(in) :: contact
      real(wp) :: values(per_contact)
      values = [contact%mass, contact%stiffness, contact%exponent, contact%damping, &
         & contact%velocity]
   end function packed_contact

   !> The inverse of `packed_contact`.
   pure function unpacked_contact(values) result(contact)
      real(wp), intent(in) :: values(per_contact)
      type(contact_type) :: contact
      contact = contact_type(mass=values(1), stiffness=values(2), exponent=values(3), &
         & damping=values(4), velocity=values(5))
   end function unpacked_contact

   !> An outcome and its status as the doubles of a message.
   pure function packed_outcome(out, stat) result(values)
      type(outcome_type), intent(in) :: out
      integer, intent(in) :: stat
      real(wp) :: values(per_outcome)
      values = [out%restitution, out%energy_loss_ratio, out%rebound_velocity, &
         & out%max_compression, out%peak_force, out%compression_at_peak_force, &
         & out%time_at_peak_force, out%compression_time, out%contact_time, &
         & real(out%evaluations, wp), real(stat, wp)]
   end function packed_outcome

   !> The inverse of `packed_outcome`.
   pure subroutine unpack_outcome(values, out, stat)
      real(wp), intent(in) :: values(per_outcome)
      type(outcome_type), intent(inout) :: out
      integer, intent(inout) :: stat
      out%restitution = values(1)
      out%energy_loss_ratio = values(2)
      out%rebound_velocity = values(3)
      out%max_compression = values(4)
      out%peak_force = values(5)
      out%compression_at_peak_force = values(6)
      out%time_at_peak_force = values(7)
      out%compression_time = values(8)
      out%contact_time = values(9)
      out%evaluations = int(values(10:12), ik)
      stat = nint(values(13))
   end subroutine unpack_outcome

end module hcimpact_mpi_sweep
