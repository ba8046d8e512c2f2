! SPDX-License-Identifier: Apache-2.0
!> Lambert W in hcimpact: values at a few points, then the accuracy of every branch
!> against the mpmath references of test/reference/lambertw.csv (issue #2).
!>
!> The reference file is looked up in $HCIMPACT_REFERENCE_DIR, else in test/reference
!> relative to the working directory. Without it the program prints the values only.
!> The accuracy goal, per (function, region): largest error <= 2 ulp, median <= 0.5 ulp.
!> Errors are measured against the exact value at each double input (the reference is
!> the sum of two doubles, ref_hi + ref_lo), in units in the last place of that value.
program lambertw_example
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact, only : wp, hcimpact_version_string, lambert_w0, lambert_wm1, &
      & lambert_w0p1, lambert_wm1p1
   implicit none

   !> Accuracy goal of issue #2, in ulp
   real(wp), parameter :: goal_max = 2.0_wp, goal_median = 0.5_wp
   !> Length of the function and region names
   integer, parameter :: name_len = 16

   !> One row of the reference file
   type :: reference_row
      character(len=name_len) :: region, func
      real(wp) :: x, ref_hi, ref_lo
   end type reference_row

   type(reference_row), allocatable :: rows(:)
   character(len=:), allocatable :: path, message

   write(*, '(a, a)') "hcimpact ", hcimpact_version_string
   call print_values()

   path = reference_path()
   call read_reference(path, rows, message)
   if (allocated(message)) then
      write(*, '(/, a)') "No accuracy table: " // message
      write(*, '(a)') "(set HCIMPACT_REFERENCE_DIR to the directory of lambertw.csv)"
   else
      call print_accuracy(path, rows)
   end if

contains

   !> W0, W-1 and the two 1 + W forms at chosen points, with 17 significant digits.
   subroutine print_values()
      real(wp) :: z(8), t(6)
      integer :: i

      ! just above the branch point -1/e, then across both branches; W-1 is NaN for z >= 0
      z = [-exp(-1.0_wp) + 1.0e-12_wp, -0.3678_wp, -0.3_wp, -0.1_wp, -1.0e-6_wp, &
         & 1.0_wp, 10.0_wp, 1.0e100_wp]
      write(*, '(/, a)') "W(z) on the two real branches (NaN: outside the branch's domain)"
      write(*, '(2x, a25, 2(1x, a25))') "z", "W0(z)", "W-1(z)"
      do i = 1, size(z)
         write(*, '(2x, es25.16e3, 2(1x, es25.16e3))') z(i), lambert_w0(z(i)), lambert_wm1(z(i))
      end do

      ! 1 + W(-exp(-1-t)) from t itself: exact near the branch point, where 1 + W(z)
      ! from a double z would have lost half of its digits or more
      t = [0.0_wp, 1.0e-20_wp, 1.0e-8_wp, 0.5_wp, 10.0_wp, 1.0e10_wp]
      write(*, '(/, a)') "1 + W(-exp(-1-t)) from t (the velocities of the impact, MODEL.md)"
      write(*, '(2x, a25, 2(1x, a25))') "t", "1 + W0", "1 + W-1"
      do i = 1, size(t)
         write(*, '(2x, es25.16e3, 2(1x, es25.16e3))') t(i), lambert_w0p1(t(i)), lambert_wm1p1(t(i))
      end do
   end subroutine print_values

   !> Path of the reference file: $HCIMPACT_REFERENCE_DIR/lambertw.csv or the default.
   function reference_path() result(file)
      character(len=:), allocatable :: file
      character(len=:), allocatable :: dir
      integer :: length, stat
      call get_environment_variable("HCIMPACT_REFERENCE_DIR", length=length, status=stat)
      if (stat == 0 .and. length > 0) then
         allocate(character(len=length) :: dir)
         call get_environment_variable("HCIMPACT_REFERENCE_DIR", dir)
      else
         dir = "test/reference"
      end if
      file = dir // "/lambertw.csv"
   end function reference_path

   !> Read every data row of the reference file (lines starting with # are comments).
   !> On failure `message` is allocated and says why.
   subroutine read_reference(file, table, message)
      !> Path of the file
      character(len=*), intent(in) :: file
      !> Rows read
      type(reference_row), allocatable, intent(out) :: table(:)
      !> Set on failure
      character(len=:), allocatable, intent(out) :: message
      character(len=256) :: line, iomsg
      integer :: unit, stat, pass, n, line_number

      open(newunit=unit, file=file, status="old", action="read", iostat=stat, iomsg=iomsg)
      if (stat /= 0) then
         message = "cannot open " // file // " (" // trim(iomsg) // ")"
         return
      end if
      ! first pass counts the rows, the second reads them
      do pass = 1, 2
         n = 0
         line_number = 0
         do
            read(unit, '(a)', iostat=stat) line
            if (is_iostat_end(stat)) exit
            line_number = line_number + 1
            if (stat /= 0 .or. len_trim(line) == len(line)) then
               message = "cannot read line " // itoa(line_number) // " of " // file
               close(unit)
               return
            end if
            if (len_trim(line) == 0 .or. line(1:1) == "#") cycle
            n = n + 1
            if (pass == 2) then
               call parse_row(trim(line), table(n), stat)
               if (stat /= 0) then
                  message = "malformed line " // itoa(line_number) // " of " // file
                  close(unit)
                  return
               end if
            end if
         end do
         if (pass == 1) then
            allocate(table(n))
            rewind(unit)
         end if
      end do
      close(unit)
   end subroutine read_reference

   !> Split `region,func,x,ref_hi,ref_lo`; stat /= 0 if malformed.
   subroutine parse_row(line, row, stat)
      !> One data line
      character(len=*), intent(in) :: line
      !> Its fields
      type(reference_row), intent(out) :: row
      !> Zero on success
      integer, intent(out) :: stat
      integer :: comma(4), i, start, next
      start = 1
      do i = 1, 4
         next = index(line(start:), ",")
         if (next == 0) then
            stat = 1
            return
         end if
         comma(i) = start + next - 1
         start = comma(i) + 1
      end do
      row%region = line(:comma(1) - 1)
      row%func = line(comma(1) + 1:comma(2) - 1)
      read(line(comma(2) + 1:comma(3) - 1), *, iostat=stat) row%x
      if (stat == 0) read(line(comma(3) + 1:comma(4) - 1), *, iostat=stat) row%ref_hi
      if (stat == 0) read(line(comma(4) + 1:), *, iostat=stat) row%ref_lo
   end subroutine parse_row

   !> Table of errors per (function, region), in the order of the file.
   subroutine print_accuracy(file, table)
      !> Path of the reference file, for the heading
      character(len=*), intent(in) :: file
      !> Its rows
      type(reference_row), intent(in) :: table(:)
      logical :: done(size(table)), in_group(size(table)), met
      real(wp) :: errors(size(table))
      real(wp), allocatable :: err(:)
      real(wp) :: max_err, median_err
      integer :: i, j, n, missed, groups

      write(*, '(/, a)') "Accuracy against " // file
      write(*, '(a)') "(goal of issue #2 per region: max <= 2 ulp, median <= 0.5 ulp;" &
         & // " region edge: exact where the reference is exact)"
      write(*, '(/, 2x, a, 1x, a, 1x, a7, 2(1x, a11), 2x, a)') &
         & "function", "region    ", "points", "max ulp", "median ulp", "goal"
      errors = error_of(table)
      done = .false.
      missed = 0
      groups = 0
      do i = 1, size(table)
         if (done(i)) cycle
         in_group = table%func == table(i)%func .and. table%region == table(i)%region
         done = done .or. in_group
         n = count(in_group)
         allocate(err(n))
         err(:) = pack(errors, in_group)
         max_err = maxval(err)
         median_err = median(err)
         if (table(i)%region == "edge") then
            met = .true.
            do j = 1, size(table)
               if (.not. in_group(j)) cycle
               if (is_zero(table(j)%ref_lo)) then
                  met = met .and. .not. errors(j) > 0
               else
                  met = met .and. .not. errors(j) > goal_max
               end if
            end do
         else
            met = .not. (max_err > goal_max .or. median_err > goal_median)
         end if
         groups = groups + 1
         if (.not. met) missed = missed + 1
         write(*, '(2x, a8, 1x, a10, 1x, i7, 2(1x, a11), 2x, a)') table(i)%func, table(i)%region, &
            & n, ulp_text(max_err), ulp_text(median_err), trim(merge("met   ", "MISSED", met))
         deallocate(err)
      end do
      if (missed == 0) then
         write(*, '(/, a, i0, a)') "All ", groups, " regions meet the goal."
      else
         write(*, '(/, i0, a, i0, a)') missed, " of ", groups, " regions miss the goal."
      end if
   end subroutine print_accuracy

   !> Error of the library at one reference row, in ulp of the exact value.
   elemental function error_of(row) result(err)
      !> Row of the reference file
      type(reference_row), intent(in) :: row
      real(wp) :: err
      real(wp) :: actual
      select case (row%func)
      case ("w0")
         actual = lambert_w0(row%x)
      case ("wm1")
         actual = lambert_wm1(row%x)
      case ("w0p1")
         actual = lambert_w0p1(row%x)
      case default
         actual = lambert_wm1p1(row%x)
      end select
      err = ulp_error(actual, row%ref_hi, row%ref_lo)
   end function error_of

   !> |actual - (ref_hi + ref_lo)| in units in the last place of ref_hi + ref_lo;
   !> huge(1.0) for NaN, an infinity, or more than 2**1000 ulp.
   !>
   !> The ulp is that of the exact value: 2**-1074 below the normal range, and half of
   !> spacing(ref_hi) when ref_hi is a power of two and the reference lies just below
   !> it in magnitude. (spacing() itself is no use for tiny values: it never goes
   !> below tiny(1.0).) Near the reference, actual - ref_hi is exact.
   elemental function ulp_error(actual, ref_hi, ref_lo) result(err)
      !> Value from the library
      real(wp), intent(in) :: actual
      !> Reference rounded to the nearest double, and the rest
      real(wp), intent(in) :: ref_hi, ref_lo
      real(wp) :: err
      real(wp) :: diff, ulp
      integer :: e
      integer, parameter :: e_least = minexponent(1.0_wp) - digits(1.0_wp)   ! 2**-1074

      if (.not. (abs(actual) <= huge(actual))) then     ! NaN or infinite
         err = huge(1.0_wp)
         return
      end if
      if (abs(ref_hi) < tiny(ref_hi)) then
         e = e_least
      else
         e = exponent(ref_hi) - digits(ref_hi)
         if (is_power_of_two(ref_hi) .and. ((ref_lo < 0 .and. ref_hi > 0) &
            & .or. (ref_lo > 0 .and. ref_hi < 0))) e = e - 1
         e = max(e, e_least)
      end if
      ulp = scale(1.0_wp, e)
      diff = abs((actual - ref_hi) - ref_lo)
      if (diff > 0 .and. exponent(diff) - e > 1000) then
         err = huge(1.0_wp)
      else
         err = diff / ulp
      end if
   end function ulp_error

   !> True if |x| is a power of two (all stored significand bits zero; x normal).
   elemental function is_power_of_two(x) result(yes)
      !> Value
      real(wp), intent(in) :: x
      logical :: yes
      yes = ibits(transfer(x, 0_int64), 0, digits(x) - 1) == 0_int64
   end function is_power_of_two

   !> True if x is +0 or -0 (without an exact real comparison).
   elemental function is_zero(x) result(yes)
      !> Value
      real(wp), intent(in) :: x
      logical :: yes
      yes = .not. abs(x) > 0
   end function is_zero

   !> Median (mean of the two middle values for an even count).
   function median(values) result(med)
      !> Values, none of them NaN
      real(wp), intent(in) :: values(:)
      real(wp) :: med
      real(wp) :: sorted(size(values)), key
      integer :: i, j, n
      n = size(values)
      sorted = values
      ! insertion sort: a few thousand values per region
      do i = 2, n
         key = sorted(i)
         j = i - 1
         do while (j >= 1)
            if (.not. sorted(j) > key) exit
            sorted(j + 1) = sorted(j)
            j = j - 1
         end do
         sorted(j + 1) = key
      end do
      if (n == 0) then
         med = 0
      else if (mod(n, 2) == 1) then
         med = sorted(n/2 + 1)
      else
         med = 0.5_wp * (sorted(n/2) + sorted(n/2 + 1))
      end if
   end function median

   !> An error in ulp as text: 3 decimals, or "huge"
   function ulp_text(err) result(text)
      !> Error in ulp
      real(wp), intent(in) :: err
      character(len=11) :: text
      if (err >= huge(1.0_wp)) then
         text = "huge"
      else if (err < 1.0e6_wp) then
         write(text, '(f11.3)') err
      else
         write(text, '(es11.3)') err
      end if
      text = adjustr(text)
   end function ulp_text

   !> An integer as text
   function itoa(i) result(text)
      !> Value
      integer, intent(in) :: i
      character(len=:), allocatable :: text
      character(len=12) :: buffer
      write(buffer, '(i0)') i
      text = trim(buffer)
   end function itoa

end program lambertw_example
