! SPDX-License-Identifier: Apache-2.0
!> The results directory and its CSV files, written so that nothing half-written is ever
!> left looking like a result.
!>
!> Every file is written as `<name>.partial` and renamed to `<name>` only when the whole
!> run has succeeded (`commit_results`); on failure the partial files, and the
!> directories the run created, are removed (`abandon_results`). On success, the files
!> of the earlier run that this run did not write (e.g. `phase.csv` when phase
!> trajectories are no longer asked for) are removed, so the directory holds exactly
!> this run's results: those its log.txt lists on its last line (`manifest_line`,
!> read back by `earlier_files`), and no other. A file of the user's that bears a name
!> this program writes (their own `summary.csv`) is replaced when this run writes that
!> name, and otherwise kept. The checkpoints of sweeps go with the run's other files,
!> whether it succeeds or fails with an error it reports; only a run that is killed
!> leaves them.
!>
!> Every write, the flush to the device and the close are checked (through the C
!> library, hcimpact_scene_system): a file that could not be written whole makes the
!> run fail, naming the file. A `.partial` file is created exclusively: a stale one
!> (from a run that was killed) is removed first, and whatever stands in its place
!> then (a symbolic link planted in between) makes the creation fail rather than be
!> followed.
!>
!> CSV: one header row, `name [unit]` per column; numbers with 17 significant digits
!> (they read back to the same double), `nan` for a value that does not exist.
module hcimpact_scene_output
   use hcimpact_kinds, only : wp
   use hcimpact_scene_system, only : make_directory, rename_path, remove_path, &
      & directory_exists, file_exists, output_file, create_file, write_file, close_file, &
      & read_file_tail
   use hcimpact_scene_text, only : csv_real
   implicit none
   private

   public :: results_type, csv_type
   public :: open_results, commit_results, abandon_results
   public :: csv_open, csv_row, csv_line, csv_close
   public :: all_result_files, checkpoint_path, manifest_line

   !> The checkpoints of sweeps (hcimpact_scene_checkpoint): `<output>.checkpoint`
   character(len=*), parameter :: checkpoint_files(4) = [character(len=23) :: &
      & "summary.checkpoint", "sweep.checkpoint", "system_sweep.checkpoint", &
      & "impact_sweep.checkpoint"]
   !> Every file name this program writes into a results directory
   character(len=*), parameter :: all_result_files(25) = [character(len=23) :: &
      & "summary.csv", "sweep.csv", "histories.csv", "phase.csv", "loops.csv", &
      & "restitution.csv", "lambertw.csv", "velocity_z.csv", "motion_z.csv", &
      & "legacy.csv", "cvode.csv", "contacts.csv", "final.csv", "motion.csv", &
      & "forces.csv", "pairs.csv", "parameters.csv", "system_sweep.csv", &
      & "impact_sweep.csv", "scene.nml", &
      & "log.txt", checkpoint_files]

   !> Most files of one run
   integer, parameter :: max_files = 32

   !> The beginning of log.txt's last line, which lists the files of the run: all that
   !> a later run into the directory removes (those it does not write itself)
   character(len=*), parameter :: manifest_lead = "Files of this run:"
   !> Bytes read from the end of an earlier log.txt for that line (which is shorter
   !> than size(all_result_files) * 25)
   integer, parameter :: manifest_bytes = 4096

   !> A results directory being written
   type :: results_type
      !> Directory path (no trailing /)
      character(len=:), allocatable :: path
      !> Whether files are written at all
      logical :: active = .false.
      !> Lengths of the prefixes of `path` this run created (removed again if it fails)
      integer, allocatable :: created(:)
      !> Names of the files written so far (as .partial)
      character(len=32) :: files(max_files) = ""
      integer :: n_files = 0
   end type results_type

   !> One CSV file being written
   type :: csv_type
      !> The file (a C stream)
      type(output_file) :: file
      !> Whether the file is open
      logical :: opened = .false.
      !> Whether a write has failed (reported by csv_close), and why
      logical :: failed = .false.
      character(len=:), allocatable :: reason
      integer :: columns = 0
      !> Name in the results directory, and the path being written
      character(len=:), allocatable :: name, path
   end type csv_type

contains

   !> Prepare the results directory `path` (created if missing, parents too).
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
      allocate(res%created(0))
      if (file_exists(res%path) .and. .not. directory_exists(res%path)) then
         error = res%path // ": exists and is not a directory (choose another with -o DIR)"
         return
      end if
      call make_directory(res%path, ok, res%created)
      if (.not. ok) then
         error = res%path // ": cannot create the results directory"
         call remove_created(res)
         return
      end if
      res%active = .true.
   end subroutine open_results

   !> Create `<dir>/<name>.partial` for writing and register it; `header` holds the
   !> column titles. A plain text file when header is empty.
   subroutine csv_open(res, name, header, csv, error)
      type(results_type), intent(inout) :: res
      character(len=*), intent(in) :: name
      character(len=*), intent(in) :: header(:)
      type(csv_type), intent(out) :: csv
      character(len=:), allocatable, intent(out) :: error
      character(len=:), allocatable :: line, reason
      logical :: ok
      integer :: i
      csv%name = name
      csv%columns = size(header)
      if (.not. res%active) return
      if (res%n_files == max_files) then
         error = "too many result files"
         return
      end if
      csv%path = res%path // "/" // name // ".partial"
      ! a stale file of a killed run, or anything planted there, goes first (remove()
      ! unlinks a symbolic link itself); the creation below is exclusive
      call remove_path(csv%path)
      call create_file(csv%path, csv%file, ok, reason)
      if (.not. ok) then
         error = csv%path // ": cannot create the file: " // reason
         if (file_exists(csv%path) .or. directory_exists(csv%path)) error = error &
            & // " (a directory of this name, or a file another run is writing)"
         return
      end if
      csv%opened = .true.
      res%n_files = res%n_files + 1
      res%files(res%n_files) = name
      if (size(header) == 0) return
      line = trim(header(1))
      do i = 2, size(header)
         line = line // "," // trim(header(i))
      end do
      call csv_line(csv, line)
   end subroutine csv_open

   !> One row: an optional leading text field, then numbers.
   subroutine csv_row(csv, values, label)
      type(csv_type), intent(inout) :: csv
      real(wp), intent(in) :: values(:)
      character(len=*), intent(in), optional :: label
      character(len=:), allocatable :: line
      integer :: i
      if (.not. csv%opened) return
      line = ""
      if (present(label)) line = trim(label) // ","
      do i = 1, size(values)
         if (i > 1) line = line // ","
         line = line // csv_real(values(i))
      end do
      call csv_line(csv, line)
   end subroutine csv_row

   !> One line of text (a newline is added).
   subroutine csv_line(csv, text)
      type(csv_type), intent(inout) :: csv
      character(len=*), intent(in) :: text
      logical :: ok
      if (.not. csv%opened .or. csv%failed) return
      call write_file(csv%file, text // new_line("a"), ok, csv%reason)
      csv%failed = .not. ok
   end subroutine csv_line

   !> Close a file (it stays .partial until `commit_results`). `error` tells if a
   !> write, the flush or the close failed (unless it holds an earlier error already).
   subroutine csv_close(csv, error)
      type(csv_type), intent(inout) :: csv
      character(len=:), allocatable, intent(inout) :: error
      logical :: ok
      character(len=:), allocatable :: reason
      if (.not. csv%opened) return
      call close_file(csv%file, ok, reason)
      csv%opened = .false.
      if (allocated(error)) return
      if (csv%failed) then
         error = csv%path // ": writing failed: " // csv%reason
      else if (.not. ok) then
         error = csv%path // ": writing failed: " // reason
      end if
   end subroutine csv_close

   !> Rename every .partial file to its name and remove the results of the earlier run
   !> (`earlier_files`) that this run did not write. If a rename fails, every result
   !> file of the directory goes (the new ones, the old ones they were replacing and
   !> the earlier run's others), so that no mixture of two runs is left looking
   !> complete.
   subroutine commit_results(res, error)
      type(results_type), intent(inout) :: res
      character(len=:), allocatable, intent(out) :: error
      logical :: ok, earlier(size(all_result_files))
      integer :: i
      if (.not. res%active) return
      ! (read before this run's log.txt takes the earlier one's place)
      earlier = earlier_files(res)
      do i = 1, res%n_files
         call rename_path(res%path // "/" // trim(res%files(i)) // ".partial", &
            & res%path // "/" // trim(res%files(i)), ok)
         if (.not. ok) then
            error = res%path // "/" // trim(res%files(i)) // ": cannot rename the finished" &
               & // " file (a directory of that name?); the results in " // res%path &
               & // " were removed"
            call remove_all_results(res, earlier)
            call abandon_results(res)
            return
         end if
      end do
      do i = 1, size(all_result_files)
         if (any(res%files(1:res%n_files) == all_result_files(i))) cycle
         if (earlier(i) .or. any(checkpoint_files == all_result_files(i))) &
            & call remove_path(res%path // "/" // trim(all_result_files(i)))
      end do
      res%n_files = 0
   end subroutine commit_results

   !> The last line of log.txt: `manifest_lead` and the names of the files of the run,
   !> log.txt among them (written last).
   function manifest_line(res) result(line)
      type(results_type), intent(in) :: res
      character(len=:), allocatable :: line
      integer :: i
      line = manifest_lead
      do i = 1, res%n_files
         line = line // " " // trim(res%files(i))
      end do
   end function manifest_line

   !> Which of `all_result_files` the earlier run into the directory wrote: those the
   !> last line of its log.txt lists (`manifest_line`). None when there is no such
   !> line: no log.txt, one that is not a regular file (a link is not followed, a FIFO
   !> not read), the log of a version that did not write the line, or another file.
   function earlier_files(res) result(earlier)
      type(results_type), intent(in) :: res
      logical :: earlier(size(all_result_files))
      character(len=:), allocatable :: text, line
      logical :: ok
      integer :: start, length, i
      earlier = .false.
      call read_file_tail(res%path // "/log.txt", manifest_bytes, text, ok)
      if (.not. ok) return
      start = index(text, new_line("a") // manifest_lead, back=.true.)
      if (start > 0) then
         start = start + 1
      else if (index(text, manifest_lead) == 1) then
         start = 1
      else
         return
      end if
      length = index(text(start:), new_line("a")) - 1
      if (length < 0) length = len(text) - start + 1
      ! the names, each between blanks
      line = text(start + len(manifest_lead):start + length - 1) // " "
      do i = 1, size(all_result_files)
         earlier(i) = index(" " // line, " " // trim(all_result_files(i)) // " ") > 0
      end do
   end function earlier_files

   !> Remove every file of this run (still .partial) and the directories it created.
   subroutine abandon_results(res)
      type(results_type), intent(inout) :: res
      integer :: i
      if (.not. res%active) return
      do i = 1, res%n_files
         call remove_path(res%path // "/" // trim(res%files(i)) // ".partial")
      end do
      ! a run that ends with an error it reports keeps no checkpoint: only a run that is
      ! killed leaves one (a rerun would meet the same error)
      do i = 1, size(checkpoint_files)
         call remove_path(res%path // "/" // trim(checkpoint_files(i)))
         call remove_path(res%path // "/" // trim(checkpoint_files(i)) // ".new")
      end do
      res%n_files = 0
      call remove_created(res)
   end subroutine abandon_results

   !> The checkpoint file of output `name` ("summary", "sweep"), or "" when no files
   !> are written.
   function checkpoint_path(res, name) result(path)
      type(results_type), intent(in) :: res
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: path
      path = ""
      if (res%active) path = res%path // "/" // name // ".checkpoint"
   end function checkpoint_path

   !> Every result file of the directory: this run's, the earlier run's (`earlier`,
   !> from `earlier_files`) and the checkpoints; no other file.
   subroutine remove_all_results(res, earlier)
      type(results_type), intent(in) :: res
      logical, intent(in) :: earlier(:)
      integer :: i
      do i = 1, size(all_result_files)
         if (earlier(i) .or. any(res%files(1:res%n_files) == all_result_files(i)) &
            & .or. any(checkpoint_files == all_result_files(i))) &
            & call remove_path(res%path // "/" // trim(all_result_files(i)))
      end do
   end subroutine remove_all_results

   !> The directories this run created, deepest first (remove() leaves a directory
   !> that is not empty).
   subroutine remove_created(res)
      type(results_type), intent(inout) :: res
      integer :: i
      if (.not. allocated(res%created)) return
      do i = size(res%created), 1, -1
         call remove_path(res%path(1:res%created(i)))
      end do
      deallocate(res%created)
      allocate(res%created(0))
   end subroutine remove_created

end module hcimpact_scene_output
