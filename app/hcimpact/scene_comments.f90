! SPDX-License-Identifier: Apache-2.0
!> The comments of a scene's namelist text. The compiler's namelist reader takes a
!> comma before a comment that ends the line, and the end of the line, as two
!> separators, so that a list going on over lines with a comment after a comma reads a
!> null value between ("mass = 0.1, ! the striker" and 0.2 on the next line gave
!> 0.1, (none), 0.2). The scene runner and the distributed chain's reader both blank
!> the comments first.
module hcimpact_scene_comments
   implicit none
   private

   public :: blank_comments

contains

   !> The lines with their comments (from `!` outside quotes to the end of the line)
   !> blanked, and their quoted text too unless keep_quoted (a quote may go on over
   !> lines).
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
               if (bare(l)(i:i) == quote) quote = " "
               if (.not. keep_quoted) bare(l)(i:i) = " "
            else if (bare(l)(i:i) == '"' .or. bare(l)(i:i) == "'") then
               quote = bare(l)(i:i)
               if (.not. keep_quoted) bare(l)(i:i) = " "
            else if (bare(l)(i:i) == "!") then
               bare(l)(i:) = " "
               exit
            end if
         end do
      end do
   end function blank_comments

end module hcimpact_scene_comments
