! SPDX-License-Identifier: Apache-2.0
!> The files and lines of the distributed chain program (hcimpact_mpi_chain): the final
!> state, bead by bead, the contact list, and the summary. Every file is written as
!> `<name>.partial` and renamed to `<name>` only when every write and the close
!> succeeded; otherwise it is removed, so that nothing looks complete.
module hcimpact_mpi_chain_output
   use, intrinsic :: iso_c_binding, only : c_char, c_int, c_null_char
   use hcimpact_kinds, only : wp
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

   !> The file `path`: a header line, then per bead its number, position (m, the
   !> chain's convention: q_1(0) = 0) and velocity (m/s), to 17 digits.
   subroutine write_state(path, positions, velocities, ok, message)
      character(len=*), intent(in) :: path
      real(wp), intent(in) :: positions(:), velocities(:)
      logical, intent(out) :: ok
      character(len=max_message), intent(out) :: message
      integer :: i
      call write_table(path, "bead,position,velocity", [(i, i = 1, size(positions))], &
         & reshape([positions, velocities], [size(positions), 2]), ok, message)
   end subroutine write_state

   !> The contact list into the file `path`: a header line, then per contact its pair
   !> (0: the left wall and bead 1; n: bead n and the right wall), start and end (s),
   !> approach and separation speeds (m/s), largest force (N) and deformation (m) and
   !> dissipated energy (J), to 17 digits.
   subroutine write_contacts(path, records, ok, message)
      character(len=*), intent(in) :: path
      type(contact_record), intent(in) :: records(:)
      logical, intent(out) :: ok
      character(len=max_message), intent(out) :: message
      call write_table(path, "pair,t_start,t_end,approach_speed,separation_speed," &
         & // "peak_force,max_deformation,dissipated", records%pair, &
         & reshape([records%t_start, records%t_end, records%approach_speed, &
         & records%separation_speed, records%peak_force, records%max_deformation, &
         & records%dissipated], [size(records), 7]), ok, message)
   end subroutine write_contacts

   !> A CSV file `path` of one header line and, per row i, the integer label(i) and
   !> the values(i, :) to 17 digits: written as `path`.partial and renamed to `path`
   !> once every write and the close succeeded (else removed, ok false, a message).
   subroutine write_table(path, header, label, values, ok, message)
      character(len=*), intent(in) :: path, header
      integer, intent(in) :: label(:)
      real(wp), intent(in) :: values(:, :)
      logical, intent(out) :: ok
      character(len=max_message), intent(out) :: message
      character(len=32) :: row_format
      character(len=200) :: msg
      character(len=:), allocatable :: name
      integer :: unit, ios, i

      ok = .false.
      message = ""
      name = trim(path)
      write(row_format, '(a, i0, a)') '(i0, ', size(values, 2), '(",", es25.17e3))'
      open(newunit=unit, file=name // ".partial", status="replace", action="write", &
         & iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "cannot create " // name // ".partial: " // trim(msg)
         return
      end if
      write(unit, '(a)', iostat=ios, iomsg=msg) header
      do i = 1, size(label)
         if (ios /= 0) exit
         write(unit, row_format, iostat=ios, iomsg=msg) label(i), values(i, :)
      end do
      if (ios /= 0) then
         message = "writing " // name // ".partial failed: " // trim(msg)
         close(unit, status="delete", iostat=ios)
         return
      end if
      close(unit, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "closing " // name // ".partial failed: " // trim(msg)
         call remove_file(name // ".partial")
         return
      end if
      if (c_rename(name // ".partial" // c_null_char, name // c_null_char) /= 0) then
         message = "cannot rename " // name // ".partial to " // name
         call remove_file(name // ".partial")
         return
      end if
      ok = .true.
   end subroutine write_table

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
