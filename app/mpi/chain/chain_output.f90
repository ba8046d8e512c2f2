! SPDX-License-Identifier: Apache-2.0
!> The files and lines of the distributed chain program (hcimpact_mpi_chain): the final
!> state, bead by bead, and the summary. Every write and close is checked; a state file
!> that could not be written whole is deleted, so that nothing looks complete.
module hcimpact_mpi_chain_output
   use hcimpact_kinds, only : wp
   use, intrinsic :: iso_c_binding, only : c_char, c_int, c_null_char
   use hcimpact_chain_types, only : max_message, contact_record
   implicit none
   private

   public :: write_state, write_contacts, remove_file, summary_line

   interface
      !> C's rename(3)
      function c_rename(from, to) result(status) bind(C, name="rename")
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: from(*), to(*)
         integer(c_int) :: status
      end function c_rename
   end interface

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

   !> The contact list into the file `path`: written whole as `path`.partial, renamed
   !> to `path` only when every write and the close succeeded (else removed). A
   !> header line, then per contact its pair (0: the left wall and bead 1; n: bead n
   !> and the right wall), start and end (s), approach and separation speeds (m/s),
   !> largest force (N) and deformation (m) and dissipated energy (J), to 17 digits.
   subroutine write_contacts(path, records, ok, message)
      character(len=*), intent(in) :: path
      type(contact_record), intent(in) :: records(:)
      logical, intent(out) :: ok
      character(len=max_message), intent(out) :: message
      integer :: unit, ios, i
      character(len=200) :: msg

      ok = .false.
      message = ""
      open(newunit=unit, file=path // ".partial", status="replace", action="write", &
         & iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "cannot create " // trim(path) // ".partial: " // trim(msg)
         return
      end if
      write(unit, '(a)', iostat=ios, iomsg=msg) "pair,t_start,t_end,approach_speed," &
         & // "separation_speed,peak_force,max_deformation,dissipated"
      do i = 1, size(records)
         if (ios /= 0) exit
         associate (r => records(i))
            write(unit, '(i0, 7(",", es25.17e3))', iostat=ios, iomsg=msg) r%pair, &
               & r%t_start, r%t_end, r%approach_speed, r%separation_speed, r%peak_force, &
               & r%max_deformation, r%dissipated
         end associate
      end do
      if (ios /= 0) then
         message = "writing " // trim(path) // ".partial failed: " // trim(msg)
         close(unit, status="delete", iostat=ios)
         return
      end if
      close(unit, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "closing " // trim(path) // ".partial failed: " // trim(msg)
         call remove_file(path // ".partial")
         return
      end if
      if (c_rename(path // ".partial" // c_null_char, path // c_null_char) /= 0) then
         message = "cannot rename " // trim(path) // ".partial to " // trim(path)
         call remove_file(path // ".partial")
         return
      end if
      ok = .true.
   end subroutine write_contacts

   !> Remove the file `path` if it exists (a result that must not look complete)
   subroutine remove_file(path)
      character(len=*), intent(in) :: path
      integer :: unit, ios
      open(newunit=unit, file=path, status="old", iostat=ios)
      if (ios == 0) close(unit, status="delete", iostat=ios)
   end subroutine remove_file

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
