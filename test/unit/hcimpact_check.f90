! SPDX-License-Identifier: Apache-2.0
!> Closeness checks of the hcimpact test suites.
!>
!> The real-valued `check` of the testing frameworks has two holes that matter
!> for a numerical library: in mctc-lib a NaN passes any closeness check (every
!> comparison with NaN is false, so "difference > threshold" never fires), and
!> a relative check divides by the signed expected value, so every negative
!> expectation passes. The checks here fail on NaN unless told that NaN is the
!> expected answer, measure relative errors against |expected|, and say in the
!> message what was compared, with 17 significant digits.
!>
!> Everything here is safe under `-ffpe-trap=invalid,zero,overflow`: NaN is
!> tested with ieee_is_nan before any ordered comparison, and differences that
!> could overflow are formed at half scale.
module hcimpact_check
   use, intrinsic :: iso_fortran_env, only : wp => real64, int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan, ieee_is_finite, ieee_value, &
      & ieee_positive_inf, ieee_quiet_nan
   use testdrive, only : error_type, test_failed
   implicit none
   private

   public :: ulp_error, check_ulps, check_close, median
   public :: format_real, reference_path, read_labelled_table, int_text

   !> Environment variable naming the directory of the reference data
   character(len=*), parameter :: reference_env = "HCIMPACT_REFERENCE_DIR"
   !> Reference directory used when the variable is not set (relative to the cwd)
   character(len=*), parameter :: reference_default = "test/reference"

contains

   !> Error of `actual` in units in the last place of the reference.
   !>
   !> The reference is the unevaluated sum ref_hi + ref_lo of two doubles
   !> (ref_lo defaults to 0), so that it can be known to more than double
   !> precision. The result is
   !>
   !>     |(actual - ref_hi) - ref_lo| / ulp(ref_hi + ref_lo)
   !>
   !> where ulp is the unit in the last place of the exact reference, not of
   !> ref_hi: when ref_hi is a power of two and ref_lo points towards zero, the
   !> reference lies in the binade below and its ulp is half of spacing(ref_hi).
   !> Zero and subnormal references have the ulp 2**-1074 (a zero ref_hi is
   !> first replaced by ref_lo). The Fortran intrinsic spacing() is not used:
   !> gfortran clamps it at tiny(1.0) for every |x| < 2**-970, which would hide
   !> errors of millions of ulps for tiny values.
   !>
   !> Exceptional values: NaN against NaN is 0; NaN against a number, or a
   !> number against NaN, is +Inf; an infinity against the same infinity is 0,
   !> against anything else +Inf; a finite value against an infinite reference
   !> is +Inf. A non-finite ref_lo makes the reference invalid (+Inf). Results
   !> too large for a double are +Inf.
   elemental function ulp_error(actual, ref_hi, ref_lo) result(ulps)
      !> Computed value
      real(wp), intent(in) :: actual
      !> Reference value, leading part
      real(wp), intent(in) :: ref_hi
      !> Reference value, trailing part (|ref_lo| <= spacing(ref_hi)/2 for a
      !> normalised pair); default 0
      real(wp), intent(in), optional :: ref_lo
      !> Error in ulps of the reference, >= 0
      real(wp) :: ulps

      real(wp) :: hi, lo, unit, diff, infinity

      infinity = ieee_value(1.0_wp, ieee_positive_inf)
      hi = ref_hi
      lo = 0.0_wp
      if (present(ref_lo)) lo = ref_lo

      if (ieee_is_nan(hi) .or. ieee_is_nan(lo)) then
         if (ieee_is_nan(actual)) then
            ulps = 0.0_wp
         else
            ulps = infinity
         end if
         return
      end if
      if (ieee_is_nan(actual) .or. .not.ieee_is_finite(lo)) then
         ulps = infinity
         return
      end if
      if (.not.ieee_is_finite(hi) .or. .not.ieee_is_finite(actual)) then
         if (actual == hi) then
            ulps = 0.0_wp
         else
            ulps = infinity
         end if
         return
      end if

      if (hi == 0.0_wp) then
         hi = lo
         lo = 0.0_wp
      end if
      unit = reference_ulp(hi, lo)

      ! actual - hi cannot overflow when both are at most huge/2 in magnitude;
      ! otherwise work at half scale (exact for numbers this large).
      if (abs(actual) > 0.5_wp*huge(hi) .or. abs(hi) > 0.5_wp*huge(hi)) then
         diff = abs((0.5_wp*actual - 0.5_wp*hi) - 0.5_wp*lo)
         unit = 0.5_wp*unit
      else
         diff = abs((actual - hi) - lo)
      end if

      ! diff/unit overflows only if unit < 1. (Nested ifs: Fortran may evaluate
      ! both operands of .and., and huge*unit overflows for unit > 1.)
      ulps = infinity
      if (unit >= 1.0_wp) then
         ulps = diff / unit
      else if (diff <= huge(diff)*unit) then
         ulps = diff / unit
      end if
   end function ulp_error

   !> Unit in the last place of the exact value ref_hi + ref_lo (ref_hi finite).
   elemental function reference_ulp(ref_hi, ref_lo) result(ulp)
      !> Reference rounded to the nearest double
      real(wp), intent(in) :: ref_hi
      !> Rest of the reference
      real(wp), intent(in) :: ref_lo
      !> The ulp, at least 2**-1074
      real(wp) :: ulp
      integer, parameter :: e_min = minexponent(1.0_wp) - digits(1.0_wp)   ! 2**-1074
      integer :: e
      logical :: towards_zero

      if (abs(ref_hi) < tiny(ref_hi)) then
         e = e_min
      else
         ! |ref_hi| in [2**(e+52), 2**(e+53))
         e = exponent(ref_hi) - digits(ref_hi)
         towards_zero = (ref_lo < 0.0_wp .and. ref_hi > 0.0_wp) .or. &
            & (ref_lo > 0.0_wp .and. ref_hi < 0.0_wp)
         ! A power of two has all stored significand bits zero
         if (towards_zero) then
            if (ibits(transfer(ref_hi, 0_int64), 0, digits(ref_hi) - 1) == 0_int64) e = e - 1
         end if
         e = max(e, e_min)
      end if
      ulp = scale(1.0_wp, e)
   end function reference_ulp

   !> Check that `actual` is within `max_ulps` units in the last place of
   !> `expected` (+ `expected_lo`), as measured by ulp_error.
   !>
   !> NaN fails, whether actual or expected, unless both are NaN and
   !> allow_nan is true.
   subroutine check_ulps(error, actual, expected, max_ulps, message, expected_lo, allow_nan)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Computed value
      real(wp), intent(in) :: actual
      !> Reference value (leading part)
      real(wp), intent(in) :: expected
      !> Largest acceptable error in ulps of expected
      real(wp), intent(in) :: max_ulps
      !> What was checked, first line of the failure message
      character(len=*), intent(in), optional :: message
      !> Trailing part of the reference value (default 0)
      real(wp), intent(in), optional :: expected_lo
      !> Accept NaN when NaN is expected (default false)
      logical, intent(in), optional :: allow_nan

      real(wp) :: ulps, lo
      character(len=:), allocatable :: what, reference

      lo = 0.0_wp
      if (present(expected_lo)) lo = expected_lo
      what = "Value out of tolerance"
      if (present(message)) what = message
      reference = format_real(expected)
      if (lo /= 0.0_wp .or. ieee_is_nan(lo)) reference = reference // " + " // format_real(lo)

      if (ieee_is_nan(actual) .or. ieee_is_nan(expected)) then
         if (ieee_is_nan(actual) .and. ieee_is_nan(expected) .and. flag(allow_nan)) return
         call test_failed(error, what, "NaN: actual = " // format_real(actual) // &
            & ", expected = " // reference)
         return
      end if
      if (ieee_is_nan(max_ulps)) then
         call test_failed(error, what, "max_ulps is NaN")
         return
      end if

      ulps = ulp_error(actual, expected, lo)
      if (ulps <= max_ulps) return

      call test_failed(error, what, "actual = " // format_real(actual) // &
         & ", expected = " // reference // ", error = " // format_ulps(ulps) // &
         & " ulp > " // format_ulps(max_ulps) // " ulp")
   end subroutine check_ulps

   !> Check |actual - expected| <= max(abs, rel*|expected|).
   !>
   !> With neither rel nor abs given the values must be equal. Infinities pass
   !> only against the same infinity. NaN fails, whether actual or expected,
   !> unless both are NaN and allow_nan is true.
   subroutine check_close(error, actual, expected, rel, abs, message, allow_nan)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Computed value
      real(wp), intent(in) :: actual
      !> Reference value
      real(wp), intent(in) :: expected
      !> Relative tolerance, measured against |expected| (default 0)
      real(wp), intent(in), optional :: rel
      !> Absolute tolerance (default 0)
      real(wp), intent(in), optional :: abs
      !> What was checked, first line of the failure message
      character(len=*), intent(in), optional :: message
      !> Accept NaN when NaN is expected (default false)
      logical, intent(in), optional :: allow_nan

      real(wp) :: rel_tol, abs_tol, diff, tol, scale
      character(len=:), allocatable :: what, tolerances

      rel_tol = 0.0_wp
      if (present(rel)) rel_tol = rel
      abs_tol = 0.0_wp
      if (present(abs)) abs_tol = abs
      what = "Value out of tolerance"
      if (present(message)) what = message

      if (ieee_is_nan(actual) .or. ieee_is_nan(expected)) then
         if (ieee_is_nan(actual) .and. ieee_is_nan(expected) .and. flag(allow_nan)) return
         call test_failed(error, what, "NaN: actual = " // format_real(actual) // &
            & ", expected = " // format_real(expected))
         return
      end if
      if (ieee_is_nan(rel_tol) .or. ieee_is_nan(abs_tol)) then
         call test_failed(error, what, "tolerance is NaN")
         return
      end if

      if (.not.ieee_is_finite(actual) .or. .not.ieee_is_finite(expected)) then
         if (actual == expected) return
         call test_failed(error, what, "actual = " // format_real(actual) // &
            & ", expected = " // format_real(expected))
         return
      end if

      ! Half scale when the difference could overflow.
      scale = 1.0_wp
      if (magnitude(actual) > 0.5_wp*huge(actual) .or. magnitude(expected) > 0.5_wp*huge(actual)) &
         & scale = 0.5_wp
      diff = magnitude(scale*actual - scale*expected)
      tol = max(scale*abs_tol, rel_tol*magnitude(scale*expected))
      if (diff <= tol) return

      ! the difference as reported, +Inf if it exceeds the double range
      if (diff > scale*huge(diff)) then
         diff = ieee_value(diff, ieee_positive_inf)
      else
         diff = diff / scale
      end if
      tolerances = ""
      if (present(rel)) tolerances = tolerances // " rel = " // format_ulps(rel_tol)
      if (present(abs)) tolerances = tolerances // " abs = " // format_ulps(abs_tol)
      if (len(tolerances) == 0) tolerances = " exact"
      call test_failed(error, what, "actual = " // format_real(actual) // &
         & ", expected = " // format_real(expected) // ", |difference| = " // &
         & format_real(diff) // " >" // tolerances)
   end subroutine check_close

   !> Median of the values of x (x itself is not reordered).
   !>
   !> The mean of the two middle values for an even count; NaN for an empty
   !> array or if any value is NaN.
   pure function median(x) result(med)
      !> Values
      real(wp), intent(in) :: x(:)
      !> Their median
      real(wp) :: med

      real(wp), allocatable :: sorted(:)
      integer :: n

      n = size(x)
      if (n == 0) then
         med = ieee_value(1.0_wp, ieee_quiet_nan)
         return
      end if
      if (any(ieee_is_nan(x))) then
         med = ieee_value(1.0_wp, ieee_quiet_nan)
         return
      end if
      allocate(sorted, source=x)
      call heap_sort(sorted)
      if (modulo(n, 2) == 1) then
         med = sorted(n/2 + 1)
      else
         ! halves first: the sum of two large values could overflow
         med = 0.5_wp*sorted(n/2) + 0.5_wp*sorted(n/2 + 1)
      end if
   end function median

   !> Path of a reference data file: $HCIMPACT_REFERENCE_DIR/<name>, or
   !> test/reference/<name> (relative to the working directory) when the
   !> variable is unset or empty. CTest sets the variable; fpm runs the tests
   !> from the project root, where the default works.
   function reference_path(name) result(path)
      !> File name inside the reference directory
      character(len=*), intent(in) :: name
      !> Path to open
      character(len=:), allocatable :: path

      character(len=:), allocatable :: dir
      integer :: length, stat

      call get_environment_variable(reference_env, length=length, status=stat)
      if (stat == 0 .and. length > 0) then
         allocate(character(len=length) :: dir)
         call get_environment_variable(reference_env, dir, status=stat)
      end if
      if (.not.allocated(dir)) then
         dir = reference_default
      else if (stat /= 0) then
         dir = reference_default
      end if
      if (dir(len(dir):len(dir)) == "/") then
         path = dir // name
      else
         path = dir // "/" // name
      end if
   end function reference_path

   !> Read a reference file of rows `region,func,v1,...,vn` (n = size(values, 1)):
   !> two text labels and n reals. Empty lines and lines starting with `#` are
   !> skipped. On an unreadable or malformed line, or a file that cannot be opened,
   !> `error` says which (path and line number) and the arrays are not allocated.
   subroutine read_labelled_table(error, name, columns, region, func, values)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> File name inside the reference directory (see reference_path)
      character(len=*), intent(in) :: name
      !> Number n of reals per row
      integer, intent(in) :: columns
      !> The labels of each row
      character(len=*), allocatable, intent(out) :: region(:), func(:)
      !> The reals, one column per row
      real(wp), allocatable, intent(out) :: values(:, :)

      character(len=:), allocatable :: path
      character(len=1024) :: line, message
      integer :: unit, stat, pass, rows, line_number, c1, c2

      path = reference_path(name)
      open(newunit=unit, file=path, status="old", action="read", iostat=stat, iomsg=message)
      if (stat /= 0) then
         call test_failed(error, "cannot open the reference file " // path, trim(message), &
            & "set " // reference_env // " to the directory of " // name)
         return
      end if
      ! Two passes: count the rows, then read them into arrays of that size.
      do pass = 1, 2
         rows = 0
         line_number = 0
         do
            read(unit, '(a)', iostat=stat) line
            if (is_iostat_end(stat)) exit
            line_number = line_number + 1
            if (stat /= 0 .or. len_trim(line) == len(line)) then
               call fail(": cannot read line ")
               return
            end if
            if (len_trim(line) == 0 .or. line(1:1) == "#") cycle
            rows = rows + 1
            if (pass == 1) cycle
            c1 = index(line, ",")
            c2 = 0
            if (c1 > 0) c2 = index(line(c1 + 1:), ",") + c1
            stat = 1
            if (c2 > c1) read(line(c2 + 1:), *, iostat=stat) values(:, rows)
            if (stat /= 0) then
               call fail(": malformed line ")
               return
            end if
            region(rows) = line(:c1 - 1)
            func(rows) = line(c1 + 1:c2 - 1)
         end do
         if (pass == 1) then
            allocate(region(rows), func(rows), values(columns, rows))
            rewind(unit)
         end if
      end do
      close(unit)

   contains

      !> Report the current line, close the file and leave nothing allocated.
      subroutine fail(what)
         character(len=*), intent(in) :: what
         call test_failed(error, path // what // int_text(line_number), trim(line))
         close(unit)
         if (allocated(values)) deallocate(region, func, values)
      end subroutine fail
   end subroutine read_labelled_table

   !> An integer as text, without blanks.
   pure function int_text(i) result(text)
      !> The integer
      integer, intent(in) :: i
      !> Its decimal digits
      character(len=:), allocatable :: text
      character(len=16) :: buffer
      write(buffer, '(i0)') i
      text = trim(buffer)
   end function int_text

   !> A double with 17 significant digits (enough to identify it), or
   !> NaN / Infinity / -Infinity.
   pure function format_real(x) result(text)
      !> Value to format
      real(wp), intent(in) :: x
      !> Its text
      character(len=:), allocatable :: text
      character(len=32) :: buffer

      write(buffer, '(es24.16e3)') x
      text = trim(adjustl(buffer))
   end function format_real

   !> A tolerance or an error in ulps, with 4 significant digits
   pure function format_ulps(x) result(text)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: text
      character(len=32) :: buffer

      write(buffer, '(es11.3e3)') x
      text = trim(adjustl(buffer))
   end function format_ulps

   !> |x|, under a name that the dummy argument `abs` of check_close does
   !> not hide
   elemental function magnitude(x) result(m)
      real(wp), intent(in) :: x
      real(wp) :: m

      m = abs(x)
   end function magnitude

   !> Value of an optional logical flag, false when absent
   pure function flag(value) result(on)
      logical, intent(in), optional :: value
      logical :: on

      on = .false.
      if (present(value)) on = value
   end function flag

   !> Sort in ascending order (heapsort: in place, O(n log n), no recursion).
   !> The values must not be NaN.
   pure subroutine heap_sort(a)
      real(wp), intent(inout) :: a(:)

      integer :: n, start, last
      real(wp) :: swap

      n = size(a)
      ! build a max-heap, children of node i are 2i and 2i+1
      do start = n/2, 1, -1
         call sift_down(a, start, n)
      end do
      ! move the maximum behind the shrinking heap
      do last = n, 2, -1
         swap = a(1)
         a(1) = a(last)
         a(last) = swap
         call sift_down(a, 1, last - 1)
      end do
   end subroutine heap_sort

   !> Restore the heap property below node `root` within a(1:last)
   pure subroutine sift_down(a, root, last)
      real(wp), intent(inout) :: a(:)
      integer, intent(in) :: root, last

      integer :: parent, child
      real(wp) :: swap

      parent = root
      do
         child = 2*parent
         if (child > last) exit
         if (child < last) then
            if (a(child + 1) > a(child)) child = child + 1
         end if
         if (a(parent) >= a(child)) exit
         swap = a(parent)
         a(parent) = a(child)
         a(child) = swap
         parent = child
      end do
   end subroutine sift_down

end module hcimpact_check
