! SPDX-License-Identifier: Apache-2.0
!> The lines of a scene file, for both readers of scenes (the scene runner's and the
!> distributed chain's, hcimpact_mpi_chain): read whole from an open file with the
!> limits of a scene (its lines' length and number, plain UTF-8 text), and their
!> comments blanked. The compiler's namelist reader takes a comma before a comment
!> that ends the line, and the end of the line, as two separators, so that a list
!> going on over lines with a comment after a comma reads a null value between
!> ("mass = 0.1, ! the striker" and 0.2 on the next line gave 0.1, (none), 0.2):
!> both readers blank the comments first. blank_comments is the one place that says
!> where a comment starts: the scene runner's reader also finds its groups, the names
!> given and the lines its messages name on the lines blanked by it.
module hcimpact_scene_lines
   use hcimpact_scene_model, only : scene_line_length, max_scene_lines
   use hcimpact_scene_text, only : str
   implicit none
   private

   public :: read_text_lines, blank_comments

contains

   !> Every line of the file open on `unit` (lines(1:n)), or a message that begins
   !> with `shown` (the file's name) and the line's number: a line longer than
   !> scene_line_length, more than max_scene_lines lines, a character that is not
   !> text. The byte order mark some editors put first is dropped.
   subroutine read_text_lines(unit, shown, lines, n, error)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: shown
      character(len=scene_line_length), allocatable, intent(out) :: lines(:)
      integer, intent(out) :: n
      character(len=:), allocatable, intent(out) :: error
      character(len=scene_line_length), allocatable :: more(:)
      character(len=:), allocatable :: line
      integer :: column
      logical :: at_end
      allocate(lines(64))
      n = 0
      do
         call read_line(unit, line, at_end, error)
         if (allocated(error)) then
            error = shown // ":" // str(n + 1) // ": " // error
            exit
         end if
         if (at_end) exit
         n = n + 1
         ! the byte order mark some editors put first (U+FEFF in UTF-8) is no text
         if (n == 1 .and. len(line) >= 3) then
            if (iachar(line(1:1)) == 239 .and. iachar(line(2:2)) == 187 &
               & .and. iachar(line(3:3)) == 191) line = line(4:)
         end if
         if (n > max_scene_lines) then
            error = shown // ": more than " // str(max_scene_lines) // " lines: a scene file" &
               & // " is a short text (is this the right file?)"
            exit
         end if
         column = not_text(line)
         if (column > 0) then
            error = shown // ":" // str(n) // ": character " // str(column) // " is not text (" &
               & // byte_name(line, column) // "): a scene file is plain text (UTF-8)"
            exit
         end if
         if (len_trim(line) > scene_line_length) then
            error = shown // ":" // str(n) // ": the line is longer than " &
               & // str(scene_line_length) // " characters: split it (a list of values may" &
               & // " go on over several lines)"
            exit
         end if
         if (n > size(lines)) then
            allocate(more(2 * size(lines)))
            more(1:size(lines)) = lines
            call move_alloc(more, lines)
         end if
         lines(n) = line
      end do
   end subroutine read_text_lines

   !> The next line of the file, whole, or `at_end`. Read in pieces; reading stops
   !> once the line has more than scene_line_length characters before its trailing
   !> blanks (too long), or a million characters in all, so that a line without end
   !> costs no more.
   subroutine read_line(unit, line, at_end, error)
      integer, intent(in) :: unit
      character(len=:), allocatable, intent(out) :: line
      logical, intent(out) :: at_end
      character(len=:), allocatable, intent(out) :: error
      integer, parameter :: max_read = 2**20
      character(len=256) :: piece
      character(len=512) :: msg
      integer :: ios, got, total
      line = ""
      at_end = .false.
      total = 0
      do
         got = 0
         read(unit, '(a)', advance="no", iostat=ios, size=got, iomsg=msg) piece
         line = line // piece(1:got)
         total = total + got
         if (is_iostat_eor(ios)) return
         if (is_iostat_end(ios)) then
            ! a last line without a newline ends with an end of record first
            at_end = .true.
            return
         end if
         if (ios /= 0) then
            error = "cannot read the line (" // trim(msg) // ")"
            return
         end if
         ! trailing blanks may follow a full line: only text beyond them is too long
         if (len_trim(line) > scene_line_length) return
         if (total > max_read) then
            error = "the line has more than " // str(max_read) // " characters"
            return
         end if
         if (len(line) > scene_line_length + len(piece)) line = line(1:scene_line_length + 1)
      end do
   end subroutine read_line

   !> Position of the first character of `line` that is not text: an ASCII control
   !> character other than the tab, a C1 control (U+0080 to U+009F), or a byte that
   !> is not part of a UTF-8 sequence; 0 if there is none.
   pure function not_text(line) result(column)
      character(len=*), intent(in) :: line
      integer :: column
      integer :: i, c, follow, k
      i = 1
      do while (i <= len(line))
         column = i
         c = iachar(line(i:i))
         if (c < 32 .and. c /= 9) return
         if (c == 127) return
         if (c < 128) then
            i = i + 1
            cycle
         end if
         ! the length of a UTF-8 sequence from its first byte
         if (c >= 194 .and. c <= 223) then
            follow = 1
         else if (c >= 224 .and. c <= 239) then
            follow = 2
         else if (c >= 240 .and. c <= 244) then
            follow = 3
         else
            return
         end if
         if (i + follow > len(line)) return
         do k = 1, follow
            if (iachar(line(i + k:i + k)) < 128 .or. iachar(line(i + k:i + k)) > 191) return
         end do
         ! C1 controls: U+0080 to U+009F, C2 80 to C2 9F
         if (c == 194 .and. iachar(line(i + 1:i + 1)) <= 159) return
         i = i + follow + 1
      end do
      column = 0
   end function not_text

   !> "byte 0x1B", for the character at `column`.
   pure function byte_name(line, column) result(text)
      character(len=*), intent(in) :: line
      integer, intent(in) :: column
      character(len=:), allocatable :: text
      character(len=2) :: hex
      write(hex, '(z2.2)') iachar(line(column:column))
      text = "byte 0x" // hex
   end function byte_name

   !> The lines with their comments (from `!` outside quotes to the end of the line)
   !> blanked, and the text between quotes too unless keep_quoted (the quotes stay, so
   !> that a name just before a quote is not taken for one before "="; a quote may go
   !> on over lines). The one place that says where a comment starts.
   pure function blank_comments(lines, keep_quoted) result(bare)
      character(len=*), intent(in) :: lines(:)
      logical, intent(in) :: keep_quoted
      character(len=len(lines)) :: bare(size(lines))
      character(len=1) :: quote
      integer :: l, i
      bare = lines
      quote = " "
      do l = 1, size(bare)
         do i = 1, len_trim(bare(l))
            if (quote /= " ") then
               if (bare(l)(i:i) == quote) then
                  quote = " "
               else if (.not. keep_quoted) then
                  bare(l)(i:i) = " "
               end if
            else if (bare(l)(i:i) == '"' .or. bare(l)(i:i) == "'") then
               quote = bare(l)(i:i)
            else if (bare(l)(i:i) == "!") then
               bare(l)(i:) = " "
               exit
            end if
         end do
      end do
   end function blank_comments

end module hcimpact_scene_lines
