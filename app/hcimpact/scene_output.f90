! SPDX-License-Identifier: Apache-2.0
!> The results directory and its CSV files, written so that nothing half-written is ever
!> left looking like a result.
!>
!> Every file is written as `<name>.partial` and renamed to `<name>` only when the whole
!> run has succeeded (`commit_results`); on failure the partial files are removed
!> (`abandon_results`). On success, files of earlier runs that this run did not write
!> (e.g. `phase.csv` when phase trajectories are no longer asked for) are removed, so
!> the directory holds exactly this run's results. Only files whose names this
!> program writes are ever touched.
!>
!> CSV: one header row, `name [unit]` per column; numbers with 17 significant digits
!> (they read back to the same double), `nan` for a value that does not exist.
module hcimpact_scene_output
   use hcimpact_kinds, only : wp
   use hcimpact_scene_system, only : make_directory, rename_path, remove_path, &
      & directory_exists, file_exists
   use hcimpact_scene_text, only : csv_real
   implicit none
   private

   public :: results_type, csv_type
   public :: open_results, commit_results, abandon_results, csv_open, csv_row, csv_close
   public :: all_result_files

   !> Every file name this program writes into a results directory
   character(len=*), parameter :: all_result_files(14) = [character(len=20) :: &
      & "summary.csv", "sweep.csv", "histories.csv", "phase.csv", "loops.csv", &
      & "restitution.csv", "lambertw.csv", "velocity_z.csv", "motion_z.csv", &
      & "legacy.csv", "cvode.csv", "parameters.csv", "scene.nml", "log.txt"]

   !> Most files of one run
   integer, parameter :: max_files = 32

   !> A results directory being written
   type :: results_type
      !> Directory path (no trailing /)
      character(len=:), allocatable :: path
      !> Whether files are written at all
      logical :: active = .false.
      !> Whether this run created the directory (removed again if the run fails)
      logical :: created = .false.
      !> Names of the files written so far (as .partial)
      character(len=32) :: files(max_files) = ""
      integer :: n_files = 0
   end type results_type

   !> One CSV file being written
   type :: csv_type
      !> Fortran unit (newunit numbers are negative)
      integer :: unit = 0
      !> Whether the file is open
      logical :: opened = .false.
      integer :: columns = 0
      character(len=:), allocatable :: name
   end type csv_type

contains

   !> Prepare the results directory `path` (created if missing).
   subroutine open_results(path, res, error)
      character(len=*), intent(in) :: path
      type(results_type), intent(out) :: res
      character(len=:), allocatable, intent(out) :: error
      logical :: ok
      integer :: n
      n = len_trim(path)
      do while (n > 1)
         if (path(n:n) /= "/") exit
         n = n - 1
      end do
      res%path = path(1:n)
      if (file_exists(res%path) .and. .not. directory_exists(res%path)) then
         error = res%path // ": exists and is not a directory (choose another with -o DIR)"
         return
      end if
      res%created = .not. directory_exists(res%path)
      call make_directory(res%path, ok)
      if (.not. ok) then
         error = res%path // ": cannot create the results directory"
         return
      end if
      res%active = .true.
   end subroutine open_results

   !> Open `<dir>/<name>.partial` for writing and register it; `header` holds the
   !> column titles. A plain text file when header is empty.
   subroutine csv_open(res, name, header, csv, error)
      type(results_type), intent(inout) :: res
      character(len=*), intent(in) :: name
      character(len=*), intent(in) :: header(:)
      type(csv_type), intent(out) :: csv
      character(len=:), allocatable, intent(out) :: error
      character(len=256) :: msg
      integer :: ios, i
      csv%name = name
      csv%columns = size(header)
      if (.not. res%active) return
      if (res%n_files == max_files) then
         error = "too many result files"
         return
      end if
      open(newunit=csv%unit, file=res%path // "/" // name // ".partial", status="replace", &
         & action="write", form="formatted", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         error = res%path // "/" // name // ".partial: cannot write (" // trim(msg) // ")"
         return
      end if
      csv%opened = .true.
      res%n_files = res%n_files + 1
      res%files(res%n_files) = name
      if (size(header) == 0) return
      do i = 1, size(header)
         if (i > 1) write(csv%unit, '(a)', advance="no") ","
         write(csv%unit, '(a)', advance="no") trim(header(i))
      end do
      write(csv%unit, '(a)') ""
   end subroutine csv_open

   !> One row: an optional leading text field, then numbers.
   subroutine csv_row(csv, values, label)
      type(csv_type), intent(in) :: csv
      real(wp), intent(in) :: values(:)
      character(len=*), intent(in), optional :: label
      integer :: i
      logical :: first
      if (.not. csv%opened) return
      first = .true.
      if (present(label)) then
         write(csv%unit, '(a)', advance="no") trim(label)
         first = .false.
      end if
      do i = 1, size(values)
         if (.not. first) write(csv%unit, '(a)', advance="no") ","
         write(csv%unit, '(a)', advance="no") csv_real(values(i))
         first = .false.
      end do
      write(csv%unit, '(a)') ""
   end subroutine csv_row

   !> Close a file (it stays .partial until `commit_results`).
   subroutine csv_close(csv)
      type(csv_type), intent(inout) :: csv
      if (csv%opened) close(csv%unit)
      csv%opened = .false.
   end subroutine csv_close

   !> Rename every .partial file to its name and remove results of earlier runs that
   !> this run did not write.
   subroutine commit_results(res, error)
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      logical :: ok
      integer :: i
      if (.not. res%active) return
      do i = 1, res%n_files
         call rename_path(res%path // "/" // trim(res%files(i)) // ".partial", &
            & res%path // "/" // trim(res%files(i)), ok)
         if (.not. ok) then
            error = res%path // "/" // trim(res%files(i)) // ": cannot rename the finished file"
            call abandon_results(res)
            return
         end if
      end do
      do i = 1, size(all_result_files)
         if (any(res%files(1:res%n_files) == all_result_files(i))) cycle
         call remove_path(res%path // "/" // trim(all_result_files(i)))
      end do
      res%n_files = 0
   end subroutine commit_results

   !> Remove every .partial file of this run.
   subroutine abandon_results(res)
      type(results_type), intent(inout) :: res
      integer :: i
      logical :: opened
      integer :: unit
      if (.not. res%active) return
      do i = 1, res%n_files
         inquire(file=res%path // "/" // trim(res%files(i)) // ".partial", opened=opened, &
            & number=unit)
         if (opened) close(unit)
         call remove_path(res%path // "/" // trim(res%files(i)) // ".partial")
      end do
      res%n_files = 0
      ! an empty directory made by this run goes too (remove fails on a non-empty one)
      if (res%created) call remove_path(res%path)
   end subroutine abandon_results

end module hcimpact_scene_output
