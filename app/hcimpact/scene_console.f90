! SPDX-License-Identifier: Apache-2.0
!> The console of a run of the scene runner: the log (on the standard output unless
!> quiet, and kept for log.txt), the tables (standard output only), errors (standard
!> error and the log), the progress of long work on a terminal, and whether a write
!> to the standard output failed (which fails the run: the tables are results).
!>
!> The program runs one scene at a time: the state of the run is kept here.
module hcimpact_scene_console
   use, intrinsic :: iso_fortran_env, only : error_unit, int64
   use hcimpact_kinds, only : wp
   use hcimpact_scene_output, only : results_type
   use hcimpact_scene_system, only : wall_clock, write_standard_output, last_system_error
   implicit none
   private

   public :: console_begin, console_log, console_failed, console_reason
   public :: say, emit, say_wrapped, say_text, shout, files_note, pad, str_int64
   public :: progress_begin, progress_step, progress_clear, progress_end

   !> Log of the run (also written to log.txt)
   character(len=:), allocatable :: log_text
   !> Console settings of the run
   logical :: quiet_mode = .false., progress_mode = .false.
   !> Whether a write to the standard output failed (the run then fails), and why
   logical :: write_failed = .false.
   character(len=:), allocatable :: failure_reason
   !> Progress state
   character(len=:), allocatable :: progress_label
   integer :: progress_total = 0, progress_shown = -1
   real(wp) :: progress_start = 0.0_wp

contains

   !> Start the console of a run: quiet (tables and errors only), and whether to show
   !> progress (on a terminal).
   subroutine console_begin(quiet, progress)
      logical, intent(in) :: quiet, progress
      quiet_mode = quiet
      progress_mode = progress .and. .not. quiet
      write_failed = .false.
      log_text = ""
   end subroutine console_begin

   !> The log so far (lines ended by new lines).
   function console_log() result(text)
      character(len=:), allocatable :: text
      text = log_text
   end function console_log

   !> Whether a write to the standard output has failed.
   logical function console_failed()
      console_failed = write_failed
   end function console_failed

   !> Why it failed.
   function console_reason() result(text)
      character(len=:), allocatable :: text
      text = ""
      if (allocated(failure_reason)) text = failure_reason
   end function console_reason

   !> A log line: on the console unless quiet, and in log.txt.
   subroutine say(text)
      character(len=*), intent(in) :: text
      log_text = log_text // text // new_line("a")
      if (quiet_mode) return
      call progress_clear()
      call emit(text)
   end subroutine say

   !> A line on the standard output (not in the log); a failure is remembered and fails
   !> the run at its end.
   subroutine emit(text)
      character(len=*), intent(in) :: text
      logical :: ok
      call write_standard_output(text // new_line("a"), ok)
      if (ok .or. write_failed) return
      write_failed = .true.
      failure_reason = last_system_error()
   end subroutine emit

   !> A list after a lead text, wrapped at 88 columns.
   subroutine say_wrapped(lead, items)
      character(len=*), intent(in) :: lead
      character(len=*), intent(in) :: items(:)
      character(len=:), allocatable :: line
      integer :: i
      line = lead
      do i = 1, size(items)
         if (len(line) + len_trim(items(i)) + 2 > 88 .and. len(line) > len(lead)) then
            call say(line // ",")
            line = repeat(" ", len(lead))
         else if (i > 1) then
            line = line // ", "
         end if
         line = line // trim(items(i))
      end do
      call say(line)
   end subroutine say_wrapped

   !> A text after a lead, wrapped at 88 columns at blanks, continuation lines indented
   !> like the text.
   subroutine say_text(lead, text)
      character(len=*), intent(in) :: lead, text
      character(len=:), allocatable :: rest, line
      integer :: width, cut
      width = max(88 - len(lead), 30)
      rest = text
      line = lead
      do while (len(rest) > width)
         cut = index(rest(1:width + 1), " ", back=.true.)
         if (cut <= 1) cut = width + 1
         call say(line // rest(1:cut - 1))
         rest = adjustl(rest(cut:))
         rest = trim(rest)
         line = repeat(" ", len(lead))
      end do
      call say(line // rest)
   end subroutine say_text

   !> An error line: on standard error always, and in the log.
   subroutine shout(text)
      character(len=*), intent(in) :: text
      log_text = log_text // text // new_line("a")
      call progress_clear()
      write(error_unit, '(a)') text
      flush(error_unit)
   end subroutine shout

   !> " -> file" when files are written.
   function files_note(res, names) result(text)
      type(results_type), intent(in) :: res
      character(len=*), intent(in) :: names
      character(len=:), allocatable :: text
      if (res%active) then
         text = " -> " // names
      else
         text = ""
      end if
   end function files_note

   !> The text padded with blanks to n characters.
   pure function pad(text, n) result(out)
      character(len=*), intent(in) :: text
      integer, intent(in) :: n
      character(len=max(n, len_trim(text) + 1)) :: out
      out = text
   end function pad

   !> An int64 without blanks.
   pure function str_int64(i) result(text)
      integer(int64), intent(in) :: i
      character(len=:), allocatable :: text
      character(len=24) :: buffer
      write(buffer, '(i0)') i
      text = trim(buffer)
   end function str_int64

   !> Start showing the progress of `total` steps (only on a terminal, and only once
   !> the work has taken a moment).
   subroutine progress_begin(label, total)
      character(len=*), intent(in) :: label
      integer, intent(in) :: total
      progress_label = label
      progress_total = total
      progress_shown = -1
      progress_start = wall_clock()
   end subroutine progress_begin

   !> Step `done` of the total is finished.
   subroutine progress_step(done)
      integer, intent(in) :: done
      integer :: percent
      if (.not. progress_mode .or. progress_total <= 1) return
      if (wall_clock() - progress_start < 0.2_wp) return
      percent = int(100.0_wp * real(done, wp) / real(progress_total, wp))
      if (percent == progress_shown) return
      progress_shown = percent
      write(error_unit, '(a, a, a, i0, a, i0, a, i0, a)', advance="no") achar(13), &
         & progress_label, ": ", done, "/", progress_total, " (", percent, "%)   "
      flush(error_unit)
   end subroutine progress_step

   !> Remove the progress line, if one is shown.
   subroutine progress_clear()
      if (progress_shown < 0) return
      write(error_unit, '(a, a, a)', advance="no") achar(13), repeat(" ", 60), achar(13)
      flush(error_unit)
      progress_shown = -1
   end subroutine progress_clear

   !> The work is done.
   subroutine progress_end()
      call progress_clear()
      progress_total = 0
   end subroutine progress_end

end module hcimpact_scene_console
