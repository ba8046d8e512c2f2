! SPDX-License-Identifier: Apache-2.0
!> Sweeps of single impacts over the ranks of an MPI communicator (doc/mpi.md): the
!> component hcimpact::mpi (libhcimpact_mpi), built only where MPI for Fortran with
!> its mpi_f08 module is found; libhcimpact itself never links MPI.
!>
!> `mpi_impact_sweep` is collective over a communicator: rank 0 gives the contacts and
!> receives, in their order, the outcome and status of each, the very doubles `impact`
!> computes for it on one process (every impact is computed alone, by the same code,
!> from the same doubles sent as doubles); the other ranks only compute. The items go
!> out through the component's dynamic hand-out (hcimpact_mpi_hand_out: chunks of
!> consecutive contacts, at most `mpi_sweep_max_chunk`, handed to the ranks as they
!> come free, on a duplicate of the communicator). Where MPI is not initialized (or
!> already finalized) the sweep runs on the calling process alone, with the same
!> results. A rank that dies ends the job through MPI's error handler (the default one
!> aborts every rank). No state is kept between calls.
module hcimpact_mpi_sweep
   use mpi_f08, only : MPI_Comm
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_size, hcimpact_err_out_of_memory
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_impact_values, only : contact_values_size, outcome_values_size, &
      & contact_values, values_contact, outcome_values, values_outcome
   use hcimpact_mpi_hand_out, only : mpi_hand_out, mpi_sweep_refuse, mpi_sweep_rank, &
      & sweep_worker, items_listener
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

   !> The worker: one impact
   type, extends(sweep_worker) :: impact_worker
   contains
      procedure :: compute => compute_impact
      procedure :: verdict => first_failure
   end type impact_worker

   !> The hand-out's listener that tells the caller's, outcomes unpacked
   type, extends(items_listener) :: unpacking_listener
      class(sweep_listener), pointer :: caller => null()
   contains
      procedure :: items_done => tell_caller
   end type unpacking_listener

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
   !> of `contacts`, hcimpact_err_out_of_memory when rank 0 cannot allocate its copies
   !> of them (nothing computed); the same value on every rank.
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
      class(sweep_listener), intent(inout), optional, target :: listener
      type(impact_worker) :: worker
      type(unpacking_listener) :: unpacking
      real(wp), allocatable :: inputs(:, :), outputs(:, :)
      integer :: i, n, alloc_stat

      if (mpi_sweep_rank(comm) /= 0) then
         allocate(inputs(contact_values_size, 0), outputs(outcome_values_size, 0))
         call mpi_hand_out(comm, worker, inputs, outputs, status)
         return
      end if
      n = size(contacts)
      if (size(out) /= n .or. size(stats) /= n) then
         call mpi_sweep_refuse(comm, hcimpact_err_size)
         status = hcimpact_err_size
         return
      end if
      allocate(inputs(contact_values_size, n), outputs(outcome_values_size, n), &
         & stat=alloc_stat)
      if (alloc_stat /= 0) then
         call mpi_sweep_refuse(comm, hcimpact_err_out_of_memory)
         status = hcimpact_err_out_of_memory
         return
      end if
      do i = 1, n
         inputs(:, i) = contact_values(contacts(i))
         outputs(:, i) = outcome_values(out(i), stats(i))
      end do
      if (present(listener)) then
         unpacking%caller => listener
         call mpi_hand_out(comm, worker, inputs, outputs, status, known, unpacking, &
            & mpi_sweep_max_chunk)
      else
         call mpi_hand_out(comm, worker, inputs, outputs, status, known, &
            & max_chunk=mpi_sweep_max_chunk)
      end if
      if (status == hcimpact_err_size) return
      do i = 1, n
         call values_outcome(outputs(:, i), out(i), stats(i))
      end do
   end subroutine mpi_impact_sweep

   !> One impact, its contact and outcome as doubles.
   subroutine compute_impact(self, input, output)
      class(impact_worker), intent(inout) :: self
      real(wp), intent(in) :: input(:)
      real(wp), intent(out) :: output(:)
      type(outcome_type) :: out
      integer :: stat
      call impact(values_contact(input), out, stat)
      output = outcome_values(out, stat)
   end subroutine compute_impact

   !> The status of the first item that failed, or hcimpact_ok.
   integer function first_failure(self, outputs) result(status)
      class(impact_worker), intent(in) :: self
      real(wp), intent(in) :: outputs(:, :)
      integer :: i
      status = hcimpact_ok
      do i = 1, size(outputs, 2)
         status = nint(outputs(outcome_values_size, i))
         if (status /= hcimpact_ok) return
      end do
   end function first_failure

   !> A chunk is done: the caller's listener gets its outcomes and statuses.
   subroutine tell_caller(self, first, outputs)
      class(unpacking_listener), intent(inout) :: self
      integer, intent(in) :: first
      real(wp), intent(in) :: outputs(:, :)
      type(outcome_type) :: out(size(outputs, 2))
      integer :: stats(size(outputs, 2)), i
      do i = 1, size(outputs, 2)
         call values_outcome(outputs(:, i), out(i), stats(i))
      end do
      call self%caller%chunk_done(first, out, stats)
   end subroutine tell_caller

end module hcimpact_mpi_sweep
