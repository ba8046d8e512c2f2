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
   use hcimpact_scene_text, only : str, real_str
   implicit none
   private

   public :: console_begin, console_log, console_failed, console_reason
   public :: say, emit, say_wrapped, say_text, shout, files_note, pad, str_int64
   public :: progress_begin, progress_step, progress_clear, progress_end, progress_line

   !> Log of the run (also written to log.txt)
   character(len=:), allocatable :: log_text
   !> Console settings of the run
   logical :: quiet_mode = .false., progress_mode = .false.
   !> Whether a write to the standard output failed (the run then fails), and why
   logical :: write_failed = .false.
   character(len=:), allocatable :: failure_reason
   !> Progress state: the label, the total, the steps already done when the work began
   !> (taken from a checkpoint: they do not count in the rate), the percentage shown
   !> (-1: no line), the length of the line shown and when the work began
   character(len=:), allocatable :: progress_label
   integer :: progress_total = 0, progress_resumed = 0, progress_shown = -1, &
      & progress_width = 0
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
   !> the work has taken a moment); `resumed` of them are done already (taken from a
   !> checkpoint), so the rate counts only the others.
   subroutine progress_begin(label, total, resumed)
      character(len=*), intent(in) :: label
      integer, intent(in) :: total
      integer, intent(in), optional :: resumed
      progress_label = label
      progress_total = total
      progress_resumed = 0
      if (present(resumed)) progress_resumed = resumed
      progress_shown = -1
      progress_start = wall_clock()
   end subroutine progress_begin

   !> Step `done` of the total is finished.
   subroutine progress_step(done)
      integer, intent(in) :: done
      character(len=:), allocatable :: line
      integer :: percent
      real(wp) :: elapsed
      if (.not. progress_mode .or. progress_total <= 1) return
      elapsed = wall_clock() - progress_start
      if (elapsed < 0.2_wp) return
      percent = percent_of(done, progress_total)
      if (percent == progress_shown) return
      progress_shown = percent
      line = progress_line(progress_label, done, progress_total, progress_resumed, elapsed)
      ! blanks over what is left of a longer line shown before
      write(error_unit, '(a, a, a)', advance="no") achar(13), line, &
         & repeat(" ", max(0, progress_width - len(line)))
      flush(error_unit)
      progress_width = max(progress_width, len(line))
   end subroutine progress_step

   !> The progress line: `label: done/total (percent%), rate/s, time left`. The rate
   !> counts the steps done since the work began (`done - resumed` in `elapsed`
   !> seconds), the time left assumes it for the remaining steps; while no step has
   !> been done here, or less than a millisecond has passed (the line is shown only
   !> after 0.2 s), both are unknown: "- /s, - left".
   pure function progress_line(label, done, total, resumed, elapsed) result(line)
      character(len=*), intent(in) :: label
      integer, intent(in) :: done, total, resumed
      real(wp), intent(in) :: elapsed
      character(len=:), allocatable :: line
      real(wp) :: steps
      line = label // ": " // str(done) // "/" // str(total) // " (" &
         & // str(percent_of(done, total)) // "%), "
      if (done > resumed .and. elapsed >= 1.0e-3_wp) then
         ! at most 2^31 steps in at least a millisecond: no overflow either way
         steps = real(done - resumed, wp)
         line = line // real_str(steps / elapsed, 3) // "/s, " &
            & // duration_text(real(max(total - done, 0), wp) * elapsed / steps) // " left"
      else
         line = line // "- /s, - left"
      end if
   end function progress_line

   !> The whole percentage of the total that `done` steps are (0 for no total).
   pure integer function percent_of(done, total)
      integer, intent(in) :: done, total
      percent_of = 0
      if (total > 0) percent_of = int(100.0_wp * real(done, wp) / real(total, wp))
   end function percent_of

   !> A time to come in whole seconds, minutes or hours: "42 s", "3 min 05 s",
   !> "2 h 07 min", beyond 99 hours "> 99 h".
   pure function duration_text(seconds) result(text)
      real(wp), intent(in) :: seconds
      character(len=:), allocatable :: text
      character(len=24) :: buffer
      integer :: whole
      if (.not. (seconds < 99.0_wp * 3600.0_wp)) then
         text = "> 99 h"
         return
      end if
      whole = nint(max(seconds, 0.0_wp))
      if (whole < 60) then
         write(buffer, '(i0, " s")') whole
      else if (whole < 3600) then
         write(buffer, '(i0, " min ", i2.2, " s")') whole / 60, modulo(whole, 60)
      else
         write(buffer, '(i0, " h ", i2.2, " min")') whole / 3600, modulo(whole, 3600) / 60
      end if
      text = trim(buffer)
   end function duration_text

   !> Remove the progress line, if one is shown.
   subroutine progress_clear()
      if (progress_shown < 0) return
      write(error_unit, '(a, a, a)', advance="no") achar(13), repeat(" ", progress_width), &
         & achar(13)
      flush(error_unit)
      progress_shown = -1
      progress_width = 0
   end subroutine progress_clear

   !> The work is done.
   subroutine progress_end()
      call progress_clear()
      progress_total = 0
   end subroutine progress_end

end module hcimpact_scene_console
