! SPDX-License-Identifier: Apache-2.0
!> Small text helpers of the scene runner: case, numbers as text, lists, durations.
module hcimpact_scene_text
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan, ieee_is_finite
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: lower, str, real_str, csv_real, csv_text, duration_str, join, word_index, count_str
   public :: printable

   !> Text of an integer or a real
   interface str
      module procedure :: int_str
      module procedure :: real_str_default
   end interface str

contains

   !> ASCII lower case.
   pure function lower(text) result(out)
      character(len=*), intent(in) :: text
      character(len=len(text)) :: out
      integer :: i, c
      out = text
      do i = 1, len(text)
         c = iachar(text(i:i))
         if (c >= iachar("A") .and. c <= iachar("Z")) out(i:i) = achar(c + 32)
      end do
   end function lower

   !> An integer without blanks.
   pure function int_str(i) result(text)
      integer, intent(in) :: i
      character(len=:), allocatable :: text
      character(len=24) :: buffer
      write(buffer, '(i0)') i
      text = trim(buffer)
   end function int_str

   !> A real in the shortest of a few forms that keeps 6 significant digits.
   pure function real_str_default(x) result(text)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: text
      text = real_str(x, 6)
   end function real_str_default

   !> A real with `digits` significant digits, in fixed notation for moderate
   !> magnitudes and scientific otherwise; trailing zeros are dropped.
   pure function real_str(x, digits) result(text)
      real(wp), intent(in) :: x
      integer, intent(in) :: digits
      character(len=:), allocatable :: text
      character(len=64) :: buffer, fmt
      integer :: e, p, mantissa_end
      if (ieee_is_nan(x)) then
         text = "nan"
         return
      end if
      if (.not. ieee_is_finite(x)) then
         if (x > 0.0_wp) then
            text = "inf"
         else
            text = "-inf"
         end if
         return
      end if
      if (x == 0.0_wp) then
         text = "0"
         return
      end if
      write(fmt, '(a, i0, a, i0, a)') "(es", digits + 10, ".", digits - 1, "e3)"
      write(buffer, fmt) x
      buffer = adjustl(buffer)
      p = index(buffer, "E")
      read(buffer(p + 1:), *) e
      if (e >= -4 .and. e < min(digits, 6)) then
         write(fmt, '(a, i0, a, i0, a)') "(f", digits + 12, ".", max(digits - 1 - e, 0), ")"
         write(buffer, fmt) x
         buffer = adjustl(buffer)
         text = strip_zeros(trim(buffer))
      else
         mantissa_end = p - 1
         text = strip_zeros(buffer(1:mantissa_end)) // "e" // int_str(e)
      end if
   end function real_str

   !> Drop trailing zeros after a decimal point (and the point itself).
   pure function strip_zeros(text) result(out)
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: out
      integer :: n
      out = text
      if (index(out, ".") == 0) return
      n = len(out)
      do while (n > 1 .and. out(n:n) == "0")
         n = n - 1
      end do
      if (out(n:n) == ".") n = n - 1
      out = out(1:n)
      if (out == "-0") out = "0"
   end function strip_zeros

   !> A real for a CSV file: 17 significant digits (round trip), or "nan".
   pure function csv_real(x) result(text)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: text
      character(len=32) :: buffer
      if (ieee_is_nan(x)) then
         text = "nan"
      else if (.not. ieee_is_finite(x)) then
         if (x > 0.0_wp) then
            text = "inf"
         else
            text = "-inf"
         end if
      else if (x == 0.0_wp) then
         text = "0"
      else
         write(buffer, '(es24.16e3)') x
         text = trim(adjustl(buffer))
      end if
   end function csv_real

   !> A text field for a CSV file: quoted, inner quotes doubled.
   pure function csv_text(text) result(out)
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: out
      integer :: i
      out = '"'
      do i = 1, len(text)
         if (text(i:i) == '"') then
            out = out // '""'
         else
            out = out // text(i:i)
         end if
      end do
      out = out // '"'
   end function csv_text

   !> A duration in s, ms or us.
   pure function duration_str(seconds) result(text)
      real(wp), intent(in) :: seconds
      character(len=:), allocatable :: text
      if (seconds >= 1.0_wp) then
         text = real_str(seconds, 3) // " s"
      else if (seconds >= 1.0e-3_wp) then
         text = real_str(1.0e3_wp * seconds, 3) // " ms"
      else
         text = real_str(1.0e6_wp * seconds, 3) // " us"
      end if
   end function duration_str

   !> A count with a noun, singular or plural ("1 speed", "6 speeds").
   pure function count_str(n, noun) result(text)
      integer, intent(in) :: n
      character(len=*), intent(in) :: noun
      character(len=:), allocatable :: text
      if (n == 1) then
         text = "1 " // noun
      else
         text = int_str(n) // " " // noun // "s"
      end if
   end function count_str

   !> The words joined by `sep`, each trimmed.
   pure function join(words, sep) result(text)
      character(len=*), intent(in) :: words(:)
      character(len=*), intent(in) :: sep
      character(len=:), allocatable :: text
      integer :: i
      text = ""
      do i = 1, size(words)
         if (i > 1) text = text // sep
         text = text // trim(words(i))
      end do
   end function join

   !> Index of `word` (case-insensitive, trimmed) in `words`, or 0.
   pure function word_index(words, word) result(k)
      character(len=*), intent(in) :: words(:)
      character(len=*), intent(in) :: word
      integer :: k
      do k = 1, size(words)
         if (lower(trim(adjustl(words(k)))) == lower(trim(adjustl(word)))) return
      end do
      k = 0
   end function word_index

   !> The text with every ASCII control character shown as ?, for a message that
   !> quotes what a user typed (a path given on the command line may hold escape
   !> sequences that a terminal would obey).
   pure function printable(text) result(out)
      character(len=*), intent(in) :: text
      character(len=len(text)) :: out
      integer :: i, c
      out = text
      do i = 1, len(text)
         c = iachar(text(i:i))
         if (c < 32 .or. c == 127) out(i:i) = "?"
      end do
   end function printable

end module hcimpact_scene_text
