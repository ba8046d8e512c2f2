! SPDX-License-Identifier: Apache-2.0
!> The files and lines of the distributed chain program (hcimpact_mpi_chain): the final
!> state, bead by bead, and the summary. Every write and close is checked; a state file
!> that could not be written whole is deleted, so that nothing looks complete.
module hcimpact_mpi_chain_output
   use hcimpact_kinds, only : wp
   use hcimpact_chain_types, only : max_message
   implicit none
   private

   public :: write_state, summary_line

contains

   !> The file `path` (replaced): a header line, then per bead its number, position
   !> (m, the chain's convention: q_1(0) = 0) and velocity (m/s), to 17 digits.
   subroutine write_state(path, positions, velocities, ok, message)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: positions(:), velocities(:)
      logical, intent(out) :: ok
      character(len=max_message), intent(out) :: message
      integer :: unit, ios, i
      character(len=200) :: msg

      ok = .false.
      message = ""
      open(newunit=unit, file=path, status="replace", action="write", iostat=ios, &
         & iomsg=msg)
      if (ios /= 0) then
         message = "cannot create " // trim(path) // ": " // trim(msg)
         return
      end if
      write(unit, '(a)', iostat=ios, iomsg=msg) "bead,position,velocity"
      do i = 1, size(positions)
         if (ios /= 0) exit
         write(unit, '(i0, 2(",", es25.17e3))', iostat=ios, iomsg=msg) i, positions(i), &
            & velocities(i)
      end do
      if (ios /= 0) then
         message = "writing " // trim(path) // " failed: " // trim(msg)
         close(unit, status="delete", iostat=ios)
         return
      end if
      close(unit, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "closing " // trim(path) // " failed: " // trim(msg)
         close(unit, status="delete", iostat=ios)
         return
      end if
      ok = .true.
   end subroutine write_state

   !> One line "name value" of the summary on `unit`; ok turned false if it fails
   subroutine summary_line(unit, name, value, ok)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: name, value
      logical, intent(inout) :: ok
      integer :: ios
      write(unit, '(a, t34, a)', iostat=ios) name, trim(adjustl(value))
      if (ios /= 0) ok = .false.
   end subroutine summary_line

end module hcimpact_mpi_chain_output
