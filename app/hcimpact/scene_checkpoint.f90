! SPDX-License-Identifier: Apache-2.0
!> Checkpoints of sweeps (the outputs summary, sweep and system_sweep): a run that is
!> killed (a signal, a rank of mpirun that dies, a lost node) leaves the results it
!> has finished in `<results>/<output>.checkpoint`, and a rerun of the same scene into
!> the same results directory takes them from there and computes only the rest
!> (doc/mpi.md). A run that ends, well or with an error it reports, removes its
!> checkpoints with its other files (hcimpact_scene_output).
!>
!> A sweep is a list of items, each a column of doubles in (an impact's contact and
!> speed, a whole system) and a column of doubles out (an impact's outcome and status,
!> a system's run). The file: a first line that names the sweep (its number of items,
!> the lengths of the columns and a checksum of every input double, as bit patterns),
!> then one line per finished item: its index and the doubles of its result as 16
!> hexadecimal digits each, so that the results read back are the very doubles
!> computed, and the results of a resumed run are those of a run in one go, byte for
!> byte. A checkpoint of another sweep is ignored; a line cut short by the end of a
!> killed run, and everything after it, too.
!>
!> A resumed run first writes what it keeps to `<output>.checkpoint.new`, created
!> exclusively, and renames it over the old file; every later record is flushed to
!> the file as soon as its chunk is done. Every write is checked.
module hcimpact_scene_checkpoint
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type
   use hcimpact_impact_values, only : contact_values_size, outcome_values_size, &
      & contact_values, outcome_values, values_outcome
   use hcimpact_scene_system, only : output_file, create_file, write_file, flush_file, &
      & close_file, rename_path, remove_path, file_exists
   implicit none
   private

   public :: checkpoint_type, checkpoint_start, checkpoint_record, checkpoint_finish
   public :: checkpoint_start_columns, checkpoint_record_columns

   !> The first words of a checkpoint file (its format's version)
   character(len=*), parameter :: signature = "hcimpact-checkpoint 2"

   !> The checkpoint of one sweep being written
   type :: checkpoint_type
      !> Whether there is one (files are written, and the file could be created)
      logical :: active = .false.
      !> The file, and its path
      type(output_file) :: file
      character(len=:), allocatable :: path
      !> Doubles of a result column
      integer :: width = 0
   end type checkpoint_type

contains

   !> Start the checkpoint `path` of the sweep of the impacts `contacts` (none if `path`
   !> is empty): the impacts a checkpoint of the same sweep holds are put into `out`
   !> and `stats` and marked `done`; `resumed` counts them.
   subroutine checkpoint_start(path, contacts, out, stats, done, resumed, ck, error)
      !> The checkpoint file, or "" for none
      character(len=*), intent(in) :: path
      !> The impacts of the sweep (masses, laws, damping, speeds)
      type(contact_type), intent(in) :: contacts(:)
      !> Outcomes and statuses: those of the checkpoint filled in
      type(outcome_type), intent(inout) :: out(:)
      integer, intent(inout) :: stats(:)
      !> Which impacts the checkpoint held
      logical, intent(out) :: done(:)
      !> How many
      integer, intent(out) :: resumed
      !> The checkpoint being written
      type(checkpoint_type), intent(out) :: ck
      character(len=:), allocatable, intent(out) :: error
      real(wp), allocatable :: inputs(:, :), outputs(:, :)
      integer :: i
      done = .false.
      resumed = 0
      if (len(path) == 0) return
      allocate(inputs(contact_values_size, size(contacts)), outputs(outcome_values_size, size(contacts)))
      do i = 1, size(contacts)
         inputs(:, i) = contact_values(contacts(i))
         outputs(:, i) = outcome_values(out(i), stats(i))
      end do
      call checkpoint_start_columns(path, inputs, outputs, done, resumed, ck, error)
      do i = 1, size(contacts)
         if (done(i)) call values_outcome(outputs(:, i), out(i), stats(i))
      end do
   end subroutine checkpoint_start

   !> Record the impacts first, first + 1, ... of the sweep (given in out, stats) and
   !> flush them to the file. An error is kept in `error` unless it holds one already.
   subroutine checkpoint_record(ck, first, out, stats, error)
      type(checkpoint_type), intent(inout) :: ck
      integer, intent(in) :: first
      type(outcome_type), intent(in) :: out(:)
      integer, intent(in) :: stats(:)
      character(len=:), allocatable, intent(inout) :: error
      real(wp) :: outputs(outcome_values_size, size(out))
      integer :: i
      if (.not. ck%active) return
      do i = 1, size(out)
         outputs(:, i) = outcome_values(out(i), stats(i))
      end do
      call checkpoint_record_columns(ck, first, outputs, error)
   end subroutine checkpoint_record

   !> Start the checkpoint `path` of a sweep of the items `inputs(:, k)` (none if `path`
   !> is empty): the result columns a checkpoint of the same sweep holds are put into
   !> `outputs` and their items marked `done`; `resumed` counts them.
   subroutine checkpoint_start_columns(path, inputs, outputs, done, resumed, ck, error)
      !> The checkpoint file, or "" for none
      character(len=*), intent(in) :: path
      !> The items' input columns
      real(wp), intent(in) :: inputs(:, :)
      !> Their result columns: those of the checkpoint filled in
      real(wp), intent(inout) :: outputs(:, :)
      !> Which items the checkpoint held
      logical, intent(out) :: done(:)
      !> How many
      integer, intent(out) :: resumed
      !> The checkpoint being written
      type(checkpoint_type), intent(out) :: ck
      character(len=:), allocatable, intent(out) :: error
      character(len=:), allocatable :: key, reason
      logical :: ok
      integer :: i

      done = .false.
      resumed = 0
      if (len(path) == 0) return
      ck%width = size(outputs, 1)
      key = sweep_key(inputs, ck%width)
      if (file_exists(path)) call read_checkpoint(path, key, outputs, done)
      resumed = count(done)
      ck%path = path
      call remove_path(path // ".new")
      call create_file(path // ".new", ck%file, ok, reason)
      if (.not. ok) then
         error = path // ".new: cannot create the checkpoint: " // reason
         return
      end if
      ck%active = .true.
      call write_file(ck%file, key // new_line("a"), ok, reason)
      do i = 1, size(done)
         if (.not. ok) exit
         if (done(i)) call write_file(ck%file, record(i, outputs(:, i)), ok, reason)
      end do
      if (ok) call flush_file(ck%file, ok, reason)
      if (ok) then
         call rename_path(path // ".new", path, ok)
         if (.not. ok) reason = "cannot rename it to " // path
      end if
      if (.not. ok) then
         error = path // ".new: writing failed: " // reason
         call close_file(ck%file, ok, reason)
         ck%active = .false.
      end if
   end subroutine checkpoint_start_columns

   !> Record the result columns of the items first, first + 1, ... and flush them to
   !> the file. An error is kept in `error` unless it holds one already.
   subroutine checkpoint_record_columns(ck, first, outputs, error)
      type(checkpoint_type), intent(inout) :: ck
      integer, intent(in) :: first
      real(wp), intent(in) :: outputs(:, :)
      character(len=:), allocatable, intent(inout) :: error
      character(len=:), allocatable :: text, reason
      logical :: ok
      integer :: i, length
      if (.not. ck%active) return
      length = record_length(ck%width)
      allocate(character(len=length * size(outputs, 2)) :: text)
      do i = 1, size(outputs, 2)
         text(length * (i - 1) + 1:length * i) = record(first + i - 1, outputs(:, i))
      end do
      call write_file(ck%file, text, ok, reason)
      if (ok) call flush_file(ck%file, ok, reason)
      if (ok) return
      if (.not. allocated(error)) error = ck%path // ": writing failed: " &
         & // reason
      call close_file(ck%file, ok, reason)
      ck%active = .false.
   end subroutine checkpoint_record_columns

   !> Close the checkpoint (it stays until the run's files are committed or abandoned).
   subroutine checkpoint_finish(ck, error)
      type(checkpoint_type), intent(inout) :: ck
      character(len=:), allocatable, intent(inout) :: error
      character(len=:), allocatable :: reason
      logical :: ok
      if (.not. ck%active) return
      call close_file(ck%file, ok, reason)
      ck%active = .false.
      if (.not. ok .and. .not. allocated(error)) error = ck%path &
         & // ": writing failed: " // reason
   end subroutine checkpoint_finish

   !> Characters of one item's line for result columns of `width` doubles: the index,
   !> the doubles, the new line.
   pure integer function record_length(width)
      integer, intent(in) :: width
      record_length = 10 + 17 * width + 1
   end function record_length

   !> The result columns of a checkpoint file whose first line is `key`; a line that
   !> does not read whole ends the reading.
   subroutine read_checkpoint(path, key, outputs, done)
      character(len=*), intent(in) :: path, key
      real(wp), intent(inout) :: outputs(:, :)
      logical, intent(inout) :: done(:)
      character(len=:), allocatable :: line
      integer(int64), allocatable :: bits(:)
      integer :: unit, stat, i, j, width
      width = size(outputs, 1)
      allocate(character(len=max(record_length(width), len(key)) + 16) :: line)
      allocate(bits(width))
      open(newunit=unit, file=path, status="old", action="read", iostat=stat)
      if (stat /= 0) return
      read(unit, '(a)', iostat=stat) line
      if (stat /= 0 .or. trim(line) /= key) then
         close(unit)
         return
      end if
      do
         read(unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         if (len_trim(line) /= record_length(width) - 1) exit
         read(line, '(i10, *(1x, z16))', iostat=stat) i, bits
         if (stat /= 0) exit
         if (i < 1 .or. i > size(done)) exit
         outputs(:, i) = [(transfer(bits(j), 1.0_wp), j = 1, width)]
         done(i) = .true.
      end do
      close(unit)
   end subroutine read_checkpoint

   !> One line of a checkpoint: the index and the result's doubles as bit patterns.
   function record(i, values) result(line)
      integer, intent(in) :: i
      real(wp), intent(in) :: values(:)
      character(len=:), allocatable :: line
      integer :: j
      allocate(character(len=record_length(size(values))) :: line)
      write(line, '(i10, *(1x, z16.16))') i, [(transfer(values(j), 1_int64), &
         & j = 1, size(values))]
      line(len(line):) = new_line("a")
   end function record

   !> The first line of a sweep's checkpoint: the number of items, the lengths of the
   !> input and result columns and a checksum of every input double (their bit
   !> patterns rotated by their place and combined by exclusive or), in hexadecimal.
   function sweep_key(inputs, width) result(key)
      real(wp), intent(in) :: inputs(:, :)
      integer, intent(in) :: width
      character(len=:), allocatable :: key
      character(len=80) :: buffer
      integer(int64) :: sum
      integer :: i, k
      sum = 0_int64
      do k = 1, size(inputs, 2)
         do i = 1, size(inputs, 1)
            sum = ieor(sum, ishftc(transfer(inputs(i, k), 1_int64), &
               & modulo(k + 7 * i, 64)))
         end do
      end do
      write(buffer, '(3(i0, 1x), z16.16)') size(inputs, 2), size(inputs, 1), width, sum
      key = signature // " " // trim(buffer)
   end function sweep_key

end module hcimpact_scene_checkpoint
