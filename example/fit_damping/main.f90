! SPDX-License-Identifier: Apache-2.0
!> Fit the Hunt-Crossley damping b to measured restitution (issue #7).
!>
!>     fit_damping [data.csv]
!>
!> reads a CSV file of approach speeds V (m/s) and coefficients of restitution e
!> (lines starting with `#` and a header line are skipped), fits b with the exact law
!> e = k(b V) and prints it with its standard error, the residuals, and, for
!> comparison, the b of the common linear law e = 1 - (2b/3) V.
!>
!> Without an argument it reads example/fit_damping/restitution_data.csv (written by
!> make_data.py in the same directory) from the working directory, else from the
!> source tree found through HCIMPACT_REFERENCE_DIR (<source>/test/reference, set by
!> CTest). Needs the LAPACK component: CMake only (components.txt).
program fit_damping_example
   use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : status_message
   use hcimpact_restitution_law, only : restitution
   use hcimpact_calibration, only : fit_type, fit_damping, fit_damping_linear
   implicit none
   character(len=*), parameter :: default_file = "example/fit_damping/restitution_data.csv"
   character(len=:), allocatable :: path
   real(wp), allocatable :: velocity(:), measured(:)
   type(fit_type) :: exact, linear
   integer :: stat, i
   real(wp) :: b, se

   path = data_file()
   call read_data(path, velocity, measured, stat)
   if (stat /= 0) then
      write(error_unit, '(a)') "fit_damping: cannot read " // path
      stop 1, quiet=.true.
   end if
   write(output_unit, '("Data: ", a, " (", i0, " points, V = ", f5.3, " ... ", f5.3, &
      & " m/s)")') path, size(velocity), minval(velocity), maxval(velocity)

   call fit_damping(velocity, measured, exact, stat)
   if (stat /= 0) then
      write(error_unit, '(a)') "fit_damping: " // status_message(stat)
      stop 1, quiet=.true.
   end if
   b = exact%parameters(1)
   se = exact%standard_errors(1)
   write(output_unit, '(/, "Exact law e = k(b V):", /, "  b = ", f8.5, " +- ", f7.5, &
      & " s/m   (standard error; 95 % interval about ", f7.5, " ... ", f7.5, ")")') &
      & b, se, b - 2 * se, b + 2 * se
   write(output_unit, '("  residual scatter ", f6.4, " (", i0, " degrees of freedom), ", &
      & i0, " iterations")') exact%scatter(1), exact%degrees_of_freedom, exact%iterations

   write(output_unit, '(/, a)') "     V (m/s)   e measured   k(b V)   residual"
   do i = 1, size(velocity)
      write(output_unit, '(f12.4, f13.4, f9.4, f11.4)') velocity(i), measured(i), &
         & restitution(b * velocity(i)), exact%residuals(i)
   end do

   call fit_damping_linear(velocity, measured, linear, stat)
   if (stat /= 0) then
      write(error_unit, '(a)') "fit_damping_linear: " // status_message(stat)
      stop 1, quiet=.true.
   end if
   write(output_unit, '(/, "Linear law e = 1 - (2b/3) V, for comparison:", /, "  b = ", &
      & f8.5, " +- ", f7.5, " s/m   (", f0.1, " % from the exact-law fit, ", f0.1, &
      & " of its standard errors)")') linear%parameters(1), linear%standard_errors(1), &
      & 100 * (linear%parameters(1) / b - 1), (linear%parameters(1) - b) / se
   write(output_unit, '("  residual scatter ", f6.4)') linear%scatter(1)

contains

   !> The file named on the command line, else the sample data.
   function data_file() result(name)
      character(len=:), allocatable :: name
      character(len=4096) :: buffer
      integer :: length, stat
      logical :: found
      if (command_argument_count() >= 1) then
         call get_command_argument(1, buffer, length)
         name = buffer(1:length)
         return
      end if
      name = default_file
      inquire(file=name, exist=found)
      if (found) return
      call get_environment_variable("HCIMPACT_REFERENCE_DIR", buffer, length, stat)
      if (stat == 0 .and. length > 0) name = buffer(1:length) // "/../../" // default_file
   end function data_file

   !> Read the pairs (V, e) of a CSV file.
   subroutine read_data(name, v, e, stat)
      character(len=*), intent(in) :: name
      real(wp), allocatable, intent(out) :: v(:), e(:)
      integer, intent(out) :: stat
      character(len=512) :: line
      real(wp) :: vi, ei
      integer :: unit, rstat

      allocate(v(0), e(0))
      open(newunit=unit, file=name, status="old", action="read", iostat=stat)
      if (stat /= 0) return
      do
         read(unit, '(a)', iostat=rstat) line
         if (rstat /= 0) exit
         line = adjustl(line)
         if (len_trim(line) == 0 .or. line(1:1) == "#") cycle
         read(line, *, iostat=rstat) vi, ei
         if (rstat /= 0) cycle        ! the header line
         v = [v, vi]
         e = [e, ei]
      end do
      close(unit)
   end subroutine read_data

end program fit_damping_example
