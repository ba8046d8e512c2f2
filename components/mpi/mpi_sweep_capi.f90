! SPDX-License-Identifier: Apache-2.0
!> The C interface of the MPI component (include/hcimpact_mpi.h): a sweep of single
!> impacts over the ranks of a communicator, through `mpi_impact_sweep`.
module hcimpact_mpi_sweep_capi
   use, intrinsic :: iso_c_binding, only : c_int, c_size_t, c_ptr, c_associated, c_f_pointer
   use mpi_f08, only : MPI_Comm
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_null, hcimpact_err_size, &
      & hcimpact_err_out_of_memory
   use hcimpact_impact_model, only : contact_type, outcome_type
   use hcimpact_capi_types, only : hcimpact_contact, hcimpact_outcome, to_contact, from_outcome
   use hcimpact_mpi_sweep, only : mpi_impact_sweep, mpi_sweep_refuse, mpi_sweep_rank
   implicit none
   private

   public :: c_mpi_impact_sweep

contains

   !> int hcimpact_mpi_impact_sweep(MPI_Fint comm, size_t n,
   !>     const hcimpact_contact *contacts, hcimpact_outcome *outcomes, int *statuses)
   !>
   !> Collective over comm (a Fortran handle: MPI_Comm_c2f); rank 0's n, contacts,
   !> outcomes and statuses are read, the other ranks' are not. The result, the same on
   !> every rank: HCIMPACT_OK, the status of the first impact that failed, or
   !> HCIMPACT_ERR_NULL (contacts or outcomes NULL while n > 0), HCIMPACT_ERR_SIZE
   !> (n beyond a C int) or HCIMPACT_ERR_OUT_OF_MEMORY (the copies cannot be
   !> allocated), which write nothing.
   function c_mpi_impact_sweep(comm, n, contacts, outcomes, statuses) result(stat) &
         & bind(C, name="hcimpact_mpi_impact_sweep")
      !> MPI_Fint handle of the communicator
      integer(c_int), value, intent(in) :: comm
      !> Number of impacts (rank 0), >= 0
      integer(c_size_t), value, intent(in) :: n
      !> const hcimpact_contact contacts[n] (rank 0)
      type(c_ptr), value, intent(in) :: contacts
      !> hcimpact_outcome outcomes[n] (rank 0)
      type(c_ptr), value, intent(in) :: outcomes
      !> int statuses[n], or NULL (rank 0)
      type(c_ptr), value, intent(in) :: statuses
      !> Status
      integer(c_int) :: stat
      type(MPI_Comm) :: f_comm
      type(hcimpact_contact), pointer :: c_in(:)
      type(hcimpact_outcome), pointer :: c_out(:)
      integer(c_int), pointer :: c_stat(:)
      type(contact_type), allocatable :: in(:)
      type(outcome_type), allocatable :: out(:)
      integer, allocatable :: stats(:)
      integer :: status, m, failed

      f_comm%MPI_VAL = comm
      if (mpi_sweep_rank(f_comm) /= 0) then
         allocate(in(0), out(0), stats(0))
         call mpi_impact_sweep(f_comm, in, out, stats, status)
         stat = int(status, c_int)
         return
      end if
      status = hcimpact_ok
      if (n > 0 .and. .not. (c_associated(contacts) .and. c_associated(outcomes))) then
         status = hcimpact_err_null
      else if (n > int(huge(1), c_size_t)) then
         status = hcimpact_err_size
      end if
      m = 0
      if (status == hcimpact_ok) then
         m = int(n)
         allocate(in(m), out(m), stats(m), stat=failed)
         if (failed /= 0) status = hcimpact_err_out_of_memory
      end if
      if (status /= hcimpact_ok) then
         ! the other ranks are in the collective call: they return the same status
         call mpi_sweep_refuse(f_comm, status)
         stat = int(status, c_int)
         return
      end if
      if (m > 0) then
         call c_f_pointer(contacts, c_in, [m])
         in = to_contact(c_in)
      end if
      call mpi_impact_sweep(f_comm, in, out, stats, status)
      ! (out of memory for the sweep's own copies: nothing computed, nothing written)
      if (m > 0 .and. status /= hcimpact_err_out_of_memory) then
         call c_f_pointer(outcomes, c_out, [m])
         c_out = from_outcome(out)
         if (c_associated(statuses)) then
            call c_f_pointer(statuses, c_stat, [m])
            c_stat = int(stats, c_int)
         end if
      end if
      stat = int(status, c_int)
   end function c_mpi_impact_sweep

end module hcimpact_mpi_sweep_capi
