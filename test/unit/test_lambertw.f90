! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_lambertw: accuracy against the mpmath references of
!> test/reference/lambertw.csv (issue #2), special values, monotonicity and identities.
!>
!> The accuracy goal of issue #2, per (function, region) of the reference file: the
!> largest error at most 2 ulp and the median at most 0.5 ulp. The file is found in
!> $HCIMPACT_REFERENCE_DIR (CTest sets it), else in test/reference relative to the
!> working directory (fpm runs from the project root).
!>
!> Everything here is safe under -ffpe-trap=invalid,zero,overflow (the Debug flags):
!> a NaN is never compared with < or >, and an error too large to express in ulps
!> is reported as huge(1.0_wp) instead of overflowing.
module test_lambertw
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_negative_inf, ieee_is_nan, ieee_is_finite, ieee_next_after
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact, only : wp, lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1
   use hcimpact_check, only : ulp_error, median, format_real, read_labelled_table, int_text
   implicit none
   private

   public :: collect_lambertw

   !> Accuracy goal of issue #2: largest error per region, in ulp
   real(wp), parameter :: goal_max_ulp = 2.0_wp
   !> Accuracy goal of issue #2: median error per region, in ulp
   real(wp), parameter :: goal_median_ulp = 0.5_wp

   !> Machine epsilon, 2**-52
   real(wp), parameter :: eps = epsilon(1.0_wp)
   !> The double nearest -1/e; it lies below -1/e (by 1.2e-17), and by the library's
   !> convention it is the branch point: W0 = W-1 = -1 there
   real(wp), parameter :: z_branch = -0.36787944117144233_wp
   !> 1/e rounded to a double
   real(wp), parameter :: inv_e = 0.36787944117144233_wp

   !> Name of the reference file inside the reference directory
   character(len=*), parameter :: reference_file = "lambertw.csv"

   !> Length of the region and function names in the reference file
   integer, parameter :: name_len = 16

   !> Every (function, region) of the reference file with an accuracy test; a test
   !> checks that the file holds no other (so a new region cannot go untested)
   character(len=*), parameter :: accuracy_cases(2, 29) = reshape([ character(len=name_len) :: &
      & "w0", "branch300", "w0", "near16_6", "w0", "near6_2", "w0", "pgrid", "w0", "pgrid2", &
      & "w0", "seams", "w0", "neg", &
      & "w0", "negtiny", "w0", "w0mid", "w0", "w0pos", "w0", "subnormal", &
      & "wm1", "branch300", "wm1", "near16_6", "wm1", "near6_2", "wm1", "pgrid", "wm1", "seams", &
      & "wm1", "neg", "wm1", "negtiny", "wm1", "subnormal", &
      & "w0p1", "tlog", "w0p1", "tswitch", "w0p1", "tnear", "w0p1", "sgrid", "w0p1", "seams", &
      & "wm1p1", "tlog", "wm1p1", "tswitch", "wm1p1", "tnear", "wm1p1", "sgrid", "wm1p1", "seams"], &
      & [2, 29])

   !> The reference file, read once on first use
   type :: reference_table
      !> Region and function of each row
      character(len=name_len), allocatable :: region(:), func(:)
      !> Exact double input (z or t)
      real(wp), allocatable :: x(:)
      !> Reference value: nearest double and the rest, ref = ref_hi + ref_lo
      real(wp), allocatable :: ref_hi(:), ref_lo(:)
   end type reference_table

   !> Findings of the monotonicity sweeps of one test: every sweep runs, and the
   !> first failure is reported with the number of failing sweeps
   type :: monotone_log
      !> Number of sweeps or windows that failed
      integer :: failures = 0
      !> First failure, in two lines
      character(len=:), allocatable :: first, detail
   end type monotone_log

   !> Rows of the reference file, once loaded
   type(reference_table), save :: table
   !> Whether `table` holds the file
   logical, save :: table_loaded = .false.

contains

   !> Collect all exported unit tests
   subroutine collect_lambertw(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("reference-complete", test_reference_complete), &
         & new_unittest("w0-branch300", test_w0_branch300), &
         & new_unittest("w0-near16_6", test_w0_near16_6), &
         & new_unittest("w0-near6_2", test_w0_near6_2), &
         & new_unittest("w0-pgrid", test_w0_pgrid), &
         & new_unittest("w0-pgrid2", test_w0_pgrid2), &
         & new_unittest("w0-seams", test_w0_seams), &
         & new_unittest("w0-neg", test_w0_neg), &
         & new_unittest("w0-negtiny", test_w0_negtiny), &
         & new_unittest("w0-w0mid", test_w0_w0mid), &
         & new_unittest("w0-w0pos", test_w0_w0pos), &
         & new_unittest("w0-subnormal", test_w0_subnormal), &
         & new_unittest("wm1-branch300", test_wm1_branch300), &
         & new_unittest("wm1-near16_6", test_wm1_near16_6), &
         & new_unittest("wm1-near6_2", test_wm1_near6_2), &
         & new_unittest("wm1-pgrid", test_wm1_pgrid), &
         & new_unittest("wm1-seams", test_wm1_seams), &
         & new_unittest("wm1-neg", test_wm1_neg), &
         & new_unittest("wm1-negtiny", test_wm1_negtiny), &
         & new_unittest("wm1-subnormal", test_wm1_subnormal), &
         & new_unittest("w0p1-tlog", test_w0p1_tlog), &
         & new_unittest("w0p1-tswitch", test_w0p1_tswitch), &
         & new_unittest("w0p1-tnear", test_w0p1_tnear), &
         & new_unittest("w0p1-sgrid", test_w0p1_sgrid), &
         & new_unittest("w0p1-seams", test_w0p1_seams), &
         & new_unittest("wm1p1-tlog", test_wm1p1_tlog), &
         & new_unittest("wm1p1-tswitch", test_wm1p1_tswitch), &
         & new_unittest("wm1p1-tnear", test_wm1p1_tnear), &
         & new_unittest("wm1p1-sgrid", test_wm1p1_sgrid), &
         & new_unittest("wm1p1-seams", test_wm1p1_seams), &
         & new_unittest("edge", test_edge), &
         & new_unittest("nan", test_nan), &
         & new_unittest("below-branch-point", test_below_branch_point), &
         & new_unittest("branch-point", test_branch_point), &
         & new_unittest("wm1-positive", test_wm1_positive), &
         & new_unittest("wm1-zero", test_wm1_zero), &
         & new_unittest("w0-infinite", test_w0_infinite), &
         & new_unittest("t-negative", test_t_negative), &
         & new_unittest("t-zero", test_t_zero), &
         & new_unittest("t-infinite", test_t_infinite), &
         & new_unittest("monotone-w0", test_monotone_w0), &
         & new_unittest("monotone-wm1", test_monotone_wm1), &
         & new_unittest("monotone-w0p1", test_monotone_w0p1), &
         & new_unittest("monotone-wm1p1", test_monotone_wm1p1), &
         & new_unittest("identity-w0", test_identity_w0), &
         & new_unittest("identity-wm1", test_identity_wm1), &
         & new_unittest("identity-w0p1", test_identity_w0p1), &
         & new_unittest("identity-wm1p1", test_identity_wm1p1), &
         & new_unittest("t-form-vs-z-form", test_t_form_vs_z_form) &
         & ]
   end subroutine collect_lambertw

   ! -----------------------------------------------------------------------
   ! Helpers
   ! -----------------------------------------------------------------------

   !> The library function named `func` ("w0", "wm1", "w0p1", "wm1p1") at x.
   elemental function evaluate(func, x) result(y)
      !> Function name, as in the reference file
      character(len=*), intent(in) :: func
      !> Argument: z for w0 and wm1, t for w0p1 and wm1p1
      real(wp), intent(in) :: x
      real(wp) :: y
      select case (func)
      case ("w0")
         y = lambert_w0(x)
      case ("wm1")
         y = lambert_wm1(x)
      case ("w0p1")
         y = lambert_w0p1(x)
      case ("wm1p1")
         y = lambert_wm1p1(x)
      case default
         y = ieee_value(x, ieee_quiet_nan)
      end select
   end function evaluate

   !> Text of an error in ulps, three significant digits.
   function ulp_text(err) result(text)
      !> Error in ulp
      real(wp), intent(in) :: err
      character(len=:), allocatable :: text
      character(len=32) :: buffer
      if (err >= huge(1.0_wp)) then
         text = "huge"
      else
         write(buffer, '(es10.3)') err
         text = trim(adjustl(buffer))
      end if
   end function ulp_text

   !> Read the reference file into `table`, once. (test-drive may run the tests of a
   !> suite in OpenMP threads: the first reader holds the others back.)
   subroutine load_table(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !$omp critical (test_lambertw_table)
      if (.not. table_loaded) call read_table(error)
      !$omp end critical (test_lambertw_table)
   end subroutine load_table

   !> Read the reference file into `table` (rows `region,func,x,ref_hi,ref_lo`).
   subroutine read_table(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: values(:, :)
      call read_labelled_table(error, reference_file, 3, table%region, table%func, values)
      if (allocated(error)) return
      table%x = values(1, :)
      table%ref_hi = values(2, :)
      table%ref_lo = values(3, :)
      table_loaded = .true.
   end subroutine read_table

   !> Accuracy of one function on one region of the reference file against the goal.
   subroutine check_region(error, func, region)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Function name, as in the reference file
      character(len=*), intent(in) :: func
      !> Region name, as in the reference file
      character(len=*), intent(in) :: region
      logical, allocatable :: rows(:)
      real(wp), allocatable :: x(:), ref_hi(:), ref_lo(:), actual(:), err(:)
      real(wp) :: max_err, median_err
      integer :: n, worst

      call load_table(error)
      if (allocated(error)) return
      rows = table%func == func .and. table%region == region
      n = count(rows)
      if (n == 0) then
         call test_failed(error, "no rows for " // func // " in region " // region &
            & // " of the reference file")
         return
      end if
      x = pack(table%x, rows)
      ref_hi = pack(table%ref_hi, rows)
      ref_lo = pack(table%ref_lo, rows)
      allocate(actual(n), err(n))
      actual(:) = evaluate(func, x)
      err(:) = ulp_error(actual, ref_hi, ref_lo)
      worst = maxloc(err, dim=1)
      max_err = err(worst)
      median_err = median(err)
      if (max_err > goal_max_ulp .or. median_err > goal_median_ulp) then
         call test_failed(error, func // " on " // region // ": max " // ulp_text(max_err) &
            & // " ulp, median " // ulp_text(median_err) // " ulp over " // int_text(n) &
            & // " points (goal: max <= 2, median <= 0.5)", &
            & "worst at x = " // format_real(x(worst)) // ": got " // format_real(actual(worst)) &
            & // ", reference " // format_real(ref_hi(worst)) // " + " // format_real(ref_lo(worst)))
      end if
   end subroutine check_region

   !> Check that `actual` is a NaN.
   subroutine check_nan(error, actual, what)
      !> Error handling
      type(error_type), allocatable, intent(inout) :: error
      !> Value to check
      real(wp), intent(in) :: actual
      !> Description of the call
      character(len=*), intent(in) :: what
      if (allocated(error)) return
      if (.not. ieee_is_nan(actual)) then
         call test_failed(error, what // " should be NaN, got " // format_real(actual))
      end if
   end subroutine check_nan

   !> Check that `actual` equals `expected` exactly (infinities and signed zeros
   !> included: -0.0 and +0.0 count as equal).
   subroutine check_exact(error, actual, expected, what)
      !> Error handling
      type(error_type), allocatable, intent(inout) :: error
      !> Value to check and its exact expectation
      real(wp), intent(in) :: actual, expected
      !> Description of the call
      character(len=*), intent(in) :: what
      if (allocated(error)) return
      if (ieee_is_nan(actual)) then
         call test_failed(error, what // " should be " // format_real(expected) // ", got NaN")
      else if (actual /= expected) then
         call test_failed(error, what // " should be exactly " // format_real(expected) &
            & // ", got " // format_real(actual))
      end if
   end subroutine check_exact

   !> Check that func is monotone (weakly) along x(:), which must be increasing;
   !> `increasing` says in which sense. A failure is recorded in `findings`.
   subroutine check_monotone(findings, func, x, increasing, what)
      !> Failures so far
      type(monotone_log), intent(inout) :: findings
      !> Function name
      character(len=*), intent(in) :: func
      !> Increasing abscissae
      real(wp), intent(in) :: x(:)
      !> True if func must increase along x, false if it must decrease
      logical, intent(in) :: increasing
      !> Description of the sweep
      character(len=*), intent(in) :: what
      real(wp) :: y(size(x))
      integer :: i
      y = evaluate(func, x)
      do i = 1, size(x)
         if (ieee_is_nan(y(i))) then
            call record(func // " is NaN at x = " // format_real(x(i)), "(" // what // ")")
            return
         end if
      end do
      do i = 1, size(x) - 1
         if (x(i + 1) <= x(i)) cycle     ! rounding may repeat an abscissa
         if ((increasing .and. y(i + 1) < y(i)) .or. (.not. increasing .and. y(i + 1) > y(i))) then
            call record(func // " not monotone (" // what // "): f(" // format_real(x(i)) &
               & // ") = " // format_real(y(i)), "but f(" // format_real(x(i + 1)) // ") = " &
               & // format_real(y(i + 1)))
            return
         end if
      end do
   contains
      !> Count a failure; keep the text of the first
      subroutine record(first, detail)
         !> Lines of the message
         character(len=*), intent(in) :: first, detail
         findings%failures = findings%failures + 1
         if (.not. allocated(findings%first)) then
            findings%first = first
            findings%detail = detail
         end if
      end subroutine record
   end subroutine check_monotone

   !> Fail if any sweep recorded in `findings` failed.
   subroutine report_monotone(error, findings)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Failures of the test
      type(monotone_log), intent(in) :: findings
      if (findings%failures > 0) then
         call test_failed(error, findings%first, findings%detail, int_text(findings%failures) &
            & // " sweep(s) or window(s) of consecutive doubles failed in all")
      end if
   end subroutine report_monotone

   !> `count` consecutive doubles on each side of x0, clipped to [lower, upper].
   function double_window(x0, count, lower, upper) result(x)
      !> Centre of the window
      real(wp), intent(in) :: x0
      !> Doubles on each side
      integer, intent(in) :: count
      !> Bounds of the domain to stay in
      real(wp), intent(in) :: lower, upper
      real(wp), allocatable :: x(:)
      real(wp) :: start
      integer :: i, n
      start = min(max(x0, lower), upper)
      do i = 1, count
         if (start <= lower) exit
         start = ieee_next_after(start, -huge(1.0_wp))
      end do
      allocate(x(2*count + 1))
      n = 0
      do i = 1, 2*count + 1
         n = n + 1
         x(n) = start
         if (start >= upper) exit
         start = ieee_next_after(start, huge(1.0_wp))
      end do
      x = x(:n)
   end function double_window

   !> n points spread log-uniformly from a to b (0 < a < b), increasing.
   function log_sweep(a, b, n) result(x)
      !> Ends of the sweep
      real(wp), intent(in) :: a, b
      !> Number of points
      integer, intent(in) :: n
      real(wp), allocatable :: x(:)
      integer :: i
      allocate(x(n))
      x(1) = a
      do i = 2, n - 1
         x(i) = exp(log(a) + (log(b) - log(a)) * real(i - 1, wp) / real(n - 1, wp))
      end do
      x(n) = b
   end function log_sweep

   !> Point k of a deterministic equidistributed sequence in [0, 1) (golden ratio).
   elemental function quasi_random(k) result(u)
      !> Index
      integer, intent(in) :: k
      real(wp) :: u
      real(wp), parameter :: golden = 0.61803398874989485_wp
      u = modulo(0.5_wp + golden * real(k, wp), 1.0_wp)
   end function quasi_random

   !> z = -1/e + d as a double, for an offset d > 0 from the branch point.
   elemental function above_branch(d) result(z)
      !> Offset from -1/e
      real(wp), intent(in) :: d
      real(wp) :: z
      ! 1/e = inv_e - 1.2428753672788363e-17; adding the rest first keeps tiny d right
      z = -inv_e + (d + 1.2428753672788363e-17_wp)
   end function above_branch

   ! -----------------------------------------------------------------------
   ! Reference file
   ! -----------------------------------------------------------------------

   !> The reference file has rows for every accuracy test and for no other region.
   subroutine test_reference_complete(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      integer :: i, j
      logical :: known
      call load_table(error)
      if (allocated(error)) return
      do i = 1, size(table%x)
         if (table%region(i) == "edge") cycle
         known = .false.
         do j = 1, size(accuracy_cases, 2)
            if (table%func(i) == accuracy_cases(1, j) .and. &
               & table%region(i) == accuracy_cases(2, j)) known = .true.
         end do
         if (.not. known) then
            call test_failed(error, "reference file has rows for " // trim(table%func(i)) &
               & // " in region " // trim(table%region(i)) // ", which no test checks")
            return
         end if
      end do
      do j = 1, size(accuracy_cases, 2)
         call check(error, any(table%func == accuracy_cases(1, j) .and. &
            & table%region == accuracy_cases(2, j)), "reference file has no rows for " &
            & // trim(accuracy_cases(1, j)) // " in region " // trim(accuracy_cases(2, j)))
         if (allocated(error)) return
      end do
   end subroutine test_reference_complete

   ! -----------------------------------------------------------------------
   ! Accuracy per region (see test/reference/README.md for the regions)
   ! -----------------------------------------------------------------------

   !> W0 at the first 300 doubles above -1/e
   subroutine test_w0_branch300(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "branch300")
   end subroutine test_w0_branch300

   !> W0 at z + 1/e in [1e-16, 1e-6]
   subroutine test_w0_near16_6(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "near16_6")
   end subroutine test_w0_near16_6

   !> W0 at z + 1/e in [1e-6, 1e-2]
   subroutine test_w0_near6_2(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "near6_2")
   end subroutine test_w0_near6_2

   !> W0 at 8 doubles either side of z = -1/e + p**2/(2e), p = k/64 up to 1.5
   subroutine test_w0_pgrid(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "pgrid")
   end subroutine test_w0_pgrid

   subroutine test_w0_pgrid2(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "pgrid2")
   end subroutine test_w0_pgrid2

   !> W0 at every seam of the tables of lambertw.f90 and its method switches (one
   !> double either side)
   subroutine test_w0_seams(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "seams")
   end subroutine test_w0_seams

   !> W-1 at every seam of the tables of lambertw.f90 and its method switches (one
   !> double either side)
   subroutine test_wm1_seams(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "seams")
   end subroutine test_wm1_seams

   !> 1 + W0 from t at every seam of the tables of lambertw.f90 and its method switches (one
   !> double either side)
   subroutine test_w0p1_seams(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0p1", "seams")
   end subroutine test_w0p1_seams

   !> 1 + W-1 from t at every seam of the tables of lambertw.f90 and its method switches (one
   !> double either side)
   subroutine test_wm1p1_seams(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1p1", "seams")
   end subroutine test_wm1p1_seams

   !> W0 at z in [-0.358, -1e-3]
   subroutine test_w0_neg(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "neg")
   end subroutine test_w0_neg

   !> W0 at -z in [1e-300, 1e-3]
   subroutine test_w0_negtiny(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "negtiny")
   end subroutine test_w0_negtiny

   !> W0 at z in [1e-4, 1e4]
   subroutine test_w0_w0mid(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "w0mid")
   end subroutine test_w0_w0mid

   !> W0 at z in [1e-300, 1e300]
   subroutine test_w0_w0pos(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "w0pos")
   end subroutine test_w0_w0pos

   !> W0 at subnormal z of both signs
   subroutine test_w0_subnormal(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0", "subnormal")
   end subroutine test_w0_subnormal

   !> W-1 at the first 300 doubles above -1/e
   subroutine test_wm1_branch300(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "branch300")
   end subroutine test_wm1_branch300

   !> W-1 at z + 1/e in [1e-16, 1e-6]
   subroutine test_wm1_near16_6(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "near16_6")
   end subroutine test_wm1_near16_6

   !> W-1 at z + 1/e in [1e-6, 1e-2]
   subroutine test_wm1_near6_2(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "near6_2")
   end subroutine test_wm1_near6_2

   !> W-1 at 8 doubles either side of z = -1/e + p**2/(2e), p = k/64 up to 1.40625
   subroutine test_wm1_pgrid(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "pgrid")
   end subroutine test_wm1_pgrid

   !> W-1 at z in [-0.358, -1e-3]
   subroutine test_wm1_neg(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "neg")
   end subroutine test_wm1_neg

   !> W-1 at -z in [1e-300, 0.1]
   subroutine test_wm1_negtiny(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "negtiny")
   end subroutine test_wm1_negtiny

   !> W-1 at negative subnormal z
   subroutine test_wm1_subnormal(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1", "subnormal")
   end subroutine test_wm1_subnormal

   !> 1 + W0(-exp(-1-t)) at t = 0 and t in [1e-300, 1e300]
   subroutine test_w0p1_tlog(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0p1", "tlog")
   end subroutine test_w0p1_tlog

   !> 1 + W0(-exp(-1-t)) at t in [1e-3, 10]
   subroutine test_w0p1_tswitch(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0p1", "tswitch")
   end subroutine test_w0p1_tswitch

   !> 1 + W0(-exp(-1-t)) for t in [1e-18, 1e-3]: the series at the branch point below
   !> t = 2**-54, the table `ta` above, through its lowest binades
   subroutine test_w0p1_tnear(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0p1", "tnear")
   end subroutine test_w0p1_tnear

   !> 1 + W0(-exp(-1-t)) at 8 doubles either side of t = s**2/2, s = k/32 up to 4
   subroutine test_w0p1_sgrid(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "w0p1", "sgrid")
   end subroutine test_w0p1_sgrid

   !> 1 + W-1(-exp(-1-t)) at t = 0 and t in [1e-300, 1e300]
   subroutine test_wm1p1_tlog(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1p1", "tlog")
   end subroutine test_wm1p1_tlog

   !> 1 + W-1(-exp(-1-t)) at t in [1e-3, 10]
   subroutine test_wm1p1_tswitch(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1p1", "tswitch")
   end subroutine test_wm1p1_tswitch

   !> 1 + W-1(-exp(-1-t)) for t in [1e-18, 1e-3]: the series below t = 2**-54, the table
   !> `tb` above
   subroutine test_wm1p1_tnear(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1p1", "tnear")
   end subroutine test_wm1p1_tnear

   !> 1 + W-1(-exp(-1-t)) at 8 doubles either side of t = s**2/2, s = k/32 up to 4
   subroutine test_wm1p1_sgrid(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "wm1p1", "sgrid")
   end subroutine test_wm1p1_sgrid

   !> Rows of region `edge`: exact when ref_lo = 0, else within the largest error allowed.
   subroutine test_edge(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      integer :: i, n
      real(wp) :: actual, err
      character(len=:), allocatable :: what
      call load_table(error)
      if (allocated(error)) return
      n = 0
      do i = 1, size(table%x)
         if (table%region(i) /= "edge") cycle
         n = n + 1
         actual = evaluate(trim(table%func(i)), table%x(i))
         what = trim(table%func(i)) // "(" // format_real(table%x(i)) // ")"
         if (table%ref_lo(i) == 0) then
            call check_exact(error, actual, table%ref_hi(i), what)
         else
            err = ulp_error(actual, table%ref_hi(i), table%ref_lo(i))
            if (err > goal_max_ulp) then
               call test_failed(error, what // " = " // format_real(actual) // " is " &
                  & // ulp_text(err) // " ulp from the reference " // format_real(table%ref_hi(i)))
            end if
         end if
         if (allocated(error)) return
      end do
      call check(error, n > 0, "reference file has no rows in region edge")
   end subroutine test_edge

   ! -----------------------------------------------------------------------
   ! Special values and the domain
   ! -----------------------------------------------------------------------

   !> NaN in, NaN out, for all four functions
   subroutine test_nan(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: nan
      nan = ieee_value(nan, ieee_quiet_nan)
      call check_nan(error, lambert_w0(nan), "lambert_w0(NaN)")
      call check_nan(error, lambert_wm1(nan), "lambert_wm1(NaN)")
      call check_nan(error, lambert_w0p1(nan), "lambert_w0p1(NaN)")
      call check_nan(error, lambert_wm1p1(nan), "lambert_wm1p1(NaN)")
   end subroutine test_nan

   !> Below the branch point both branches are NaN: z < -1/e, the double just below
   !> the one nearest -1/e included
   subroutine test_below_branch_point(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: z(5)
      integer :: i
      z = [ieee_next_after(z_branch, -1.0_wp), -0.37_wp, -1.0_wp, -huge(1.0_wp), &
         & ieee_value(1.0_wp, ieee_negative_inf)]
      do i = 1, size(z)
         call check_nan(error, lambert_w0(z(i)), "lambert_w0(" // format_real(z(i)) // ")")
         call check_nan(error, lambert_wm1(z(i)), "lambert_wm1(" // format_real(z(i)) // ")")
      end do
   end subroutine test_below_branch_point

   !> The double nearest -1/e is the branch point of both branches: W = -1 exactly
   subroutine test_branch_point(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_exact(error, lambert_w0(z_branch), -1.0_wp, "lambert_w0(" // format_real(z_branch) // ")")
      call check_exact(error, lambert_wm1(z_branch), -1.0_wp, "lambert_wm1(" // format_real(z_branch) // ")")
      ! and -exp(-1) as a program would write it is that double
      call check_exact(error, -exp(-1.0_wp), z_branch, "-exp(-1.0_wp)")
   end subroutine test_branch_point

   !> W-1 is NaN for z > 0
   subroutine test_wm1_positive(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: z(6)
      integer :: i
      z = [scale(1.0_wp, -1074), tiny(1.0_wp), 1.0e-300_wp, 1.0_wp, huge(1.0_wp), &
         & ieee_value(1.0_wp, ieee_positive_inf)]
      do i = 1, size(z)
         call check_nan(error, lambert_wm1(z(i)), "lambert_wm1(" // format_real(z(i)) // ")")
      end do
   end subroutine test_wm1_positive

   !> W-1(z) tends to -inf as z -> 0-: W-1(0) = -inf for either sign of zero (the
   !> library's convention), and W-1 is finite (about -751) at the least negative double
   subroutine test_wm1_zero(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: w
      call check_exact(error, lambert_wm1(-0.0_wp), ieee_value(1.0_wp, ieee_negative_inf), &
         & "lambert_wm1(-0.0)")
      call check_exact(error, lambert_wm1(0.0_wp), ieee_value(1.0_wp, ieee_negative_inf), &
         & "lambert_wm1(+0.0)")
      if (allocated(error)) return
      w = lambert_wm1(-tiny(1.0_wp))
      call check(error, ieee_is_finite(w) .and. .not. ieee_is_nan(w), &
         & "lambert_wm1(-tiny) should be finite, got " // format_real(w))
      if (allocated(error)) return
      call check(error, w < -700.0_wp .and. w > -720.0_wp, &
         & "lambert_wm1(-tiny) should be about -714.96, got " // format_real(w))
      if (allocated(error)) return
      w = lambert_wm1(-scale(1.0_wp, -1074))
      call check(error, ieee_is_finite(w) .and. .not. ieee_is_nan(w), &
         & "lambert_wm1(-2**-1074) should be finite, got " // format_real(w))
      if (allocated(error)) return
      call check(error, w < -740.0_wp .and. w > -760.0_wp, &
         & "lambert_wm1(-2**-1074) should be about -751.4, got " // format_real(w))
   end subroutine test_wm1_zero

   !> W0(+inf) = +inf, W0(0) = 0
   subroutine test_w0_infinite(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: inf
      inf = ieee_value(inf, ieee_positive_inf)
      call check_exact(error, lambert_w0(inf), inf, "lambert_w0(+inf)")
      call check_exact(error, lambert_w0(0.0_wp), 0.0_wp, "lambert_w0(0)")
   end subroutine test_w0_infinite

   !> The 1 + W forms are NaN for t < 0
   subroutine test_t_negative(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: t(5)
      integer :: i
      t = [-scale(1.0_wp, -1074), -1.0e-300_wp, -1.0_wp, -huge(1.0_wp), &
         & ieee_value(1.0_wp, ieee_negative_inf)]
      do i = 1, size(t)
         call check_nan(error, lambert_w0p1(t(i)), "lambert_w0p1(" // format_real(t(i)) // ")")
         call check_nan(error, lambert_wm1p1(t(i)), "lambert_wm1p1(" // format_real(t(i)) // ")")
      end do
   end subroutine test_t_negative

   !> At t = 0 (the branch point) both 1 + W forms are exactly 0
   subroutine test_t_zero(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_exact(error, lambert_w0p1(0.0_wp), 0.0_wp, "lambert_w0p1(0)")
      call check_exact(error, lambert_wm1p1(0.0_wp), 0.0_wp, "lambert_wm1p1(0)")
   end subroutine test_t_zero

   !> t = +inf: 1 + W0 = 1 (z = -0), 1 + W-1 = -inf
   subroutine test_t_infinite(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: inf
      inf = ieee_value(inf, ieee_positive_inf)
      call check_exact(error, lambert_w0p1(inf), 1.0_wp, "lambert_w0p1(+inf)")
      call check_exact(error, lambert_wm1p1(inf), -inf, "lambert_wm1p1(+inf)")
      ! and the largest finite t stays finite
      call check_exact(error, lambert_w0p1(huge(1.0_wp)), 1.0_wp, "lambert_w0p1(huge)")
      if (allocated(error)) return
      call check(error, ieee_is_finite(lambert_wm1p1(huge(1.0_wp))), &
         & "lambert_wm1p1(huge) should be finite (about -huge)")
   end subroutine test_t_infinite

   ! -----------------------------------------------------------------------
   ! Monotonicity: coarse sweeps over the whole domain, and runs of consecutive
   ! doubles around the points where an implementation is likely to switch
   ! between methods (grids of p = sqrt(2(1+ez)) and s = sqrt(2t) with spacing
   ! 1/32 and 1/16, powers of ten, the region ends of the reference file).
   ! -----------------------------------------------------------------------

   !> Probe points in z for a branch: near the branch point, then z in (lower, upper)
   function z_probes(lower, upper) result(z)
      !> Domain of the branch to keep to
      real(wp), intent(in) :: lower, upper
      real(wp), allocatable :: z(:)
      real(wp) :: p
      integer :: k
      allocate(z(0))
      do k = 1, 48
         p = real(k, wp) / 32
         z = [z, above_branch(p*p * inv_e / 2)]
      end do
      do k = -17, -1
         z = [z, above_branch(10.0_wp**k)]
      end do
      z = [z, -0.358_wp, -0.3_wp, -0.25_wp, -0.2_wp, -0.1_wp, -1.0e-3_wp, 1.0e-4_wp, &
         & 0.5_wp, 1.0_wp, 2.0_wp, exp(1.0_wp), 3.0_wp, 5.0_wp, 10.0_wp, 20.0_wp, 1.0e4_wp]
      do k = -300, 300, 10
         z = [z, 10.0_wp**k, -10.0_wp**k]
      end do
      do k = -20, 4
         z = [z, -10.0_wp**k, 10.0_wp**k, 2.0_wp**(3*k), -2.0_wp**(3*k)]
      end do
      z = pack(z, z > lower .and. z < upper)
   end function z_probes

   !> Probe points in t: s = sqrt(2t) on a grid of 1/16, powers of ten, region ends
   function t_probes() result(t)
      real(wp), allocatable :: t(:)
      integer :: k
      allocate(t(0))
      do k = 1, 64
         t = [t, (real(k, wp) / 16)**2 / 2]
      end do
      do k = -300, 300, 10
         t = [t, 10.0_wp**k]
      end do
      do k = -20, 4
         t = [t, 10.0_wp**k, 2.0_wp**(3*k), 3.0_wp * 10.0_wp**k]
      end do
      t = [t, 1.0e-3_wp, 10.0_wp, 0.5_wp, 1.0_wp, 2.0_wp, 5.0_wp, 20.0_wp, 36.0_wp, 40.0_wp, &
         & 700.0_wp, 745.0_wp]
   end function t_probes

   !> W0 increases with z
   subroutine test_monotone_w0(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      type(monotone_log) :: findings
      call check_monotone(findings, "w0", double_window(z_branch, 4000, z_branch, 0.0_wp), &
         & .true., "first doubles above -1/e")
      call check_monotone(findings, "w0", above_branch(log_sweep(1.0e-17_wp, 0.36_wp, 20000)), &
         & .true., "z + 1/e from 1e-17 to 0.36")
      call check_monotone(findings, "w0", -reverse(log_sweep(1.0e-300_wp, 0.36_wp, 20000)), &
         & .true., "z from -0.36 to -1e-300")
      call check_monotone(findings, "w0", log_sweep(1.0e-300_wp, huge(1.0_wp), 20000), &
         & .true., "z from 1e-300 to huge")
      call check_monotone(findings, "w0", double_window(0.0_wp, 2000, z_branch, huge(1.0_wp)), &
         & .true., "subnormals around 0")
      call check_windows(findings, "w0", z_probes(z_branch, huge(1.0_wp)), z_branch, &
         & huge(1.0_wp), .true.)
      call report_monotone(error, findings)
   end subroutine test_monotone_w0

   !> W-1 decreases with z
   subroutine test_monotone_wm1(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      type(monotone_log) :: findings
      real(wp) :: least_negative
      least_negative = -scale(1.0_wp, -1074)
      call check_monotone(findings, "wm1", double_window(z_branch, 4000, z_branch, least_negative), &
         & .false., "first doubles above -1/e")
      call check_monotone(findings, "wm1", above_branch(log_sweep(1.0e-17_wp, 0.36_wp, 20000)), &
         & .false., "z + 1/e from 1e-17 to 0.36")
      call check_monotone(findings, "wm1", -reverse(log_sweep(1.0e-300_wp, 0.36_wp, 20000)), &
         & .false., "z from -0.36 to -1e-300")
      call check_monotone(findings, "wm1", double_window(least_negative, 2000, z_branch, &
         & least_negative), .false., "negative subnormals")
      call check_windows(findings, "wm1", z_probes(z_branch, 0.0_wp), z_branch, least_negative, &
         & .false.)
      call report_monotone(error, findings)
   end subroutine test_monotone_wm1

   !> 1 + W0(-exp(-1-t)) increases with t
   subroutine test_monotone_w0p1(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_monotone_t(error, "w0p1", .true.)
   end subroutine test_monotone_w0p1

   !> 1 + W-1(-exp(-1-t)) decreases with t
   subroutine test_monotone_wm1p1(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      call check_monotone_t(error, "wm1p1", .false.)
   end subroutine test_monotone_wm1p1

   !> Monotonicity of a 1 + W form over t
   subroutine check_monotone_t(error, func, increasing)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Function name
      character(len=*), intent(in) :: func
      !> Sense of monotonicity
      logical, intent(in) :: increasing
      type(monotone_log) :: findings
      call check_monotone(findings, func, double_window(0.0_wp, 2000, 0.0_wp, huge(1.0_wp)), &
         & increasing, "first doubles from t = 0")
      call check_monotone(findings, func, log_sweep(1.0e-300_wp, huge(1.0_wp), 40000), &
         & increasing, "t from 1e-300 to huge")
      call check_monotone(findings, func, log_sweep(1.0e-3_wp, 10.0_wp, 40000), &
         & increasing, "t from 1e-3 to 10")
      call check_windows(findings, func, t_probes(), 0.0_wp, huge(1.0_wp), increasing)
      call report_monotone(error, findings)
   end subroutine check_monotone_t

   !> Monotonicity over 64 consecutive doubles on each side of every probe point
   subroutine check_windows(findings, func, probes, lower, upper, increasing)
      !> Failures so far
      type(monotone_log), intent(inout) :: findings
      !> Function name
      character(len=*), intent(in) :: func
      !> Centres of the windows
      real(wp), intent(in) :: probes(:)
      !> Domain to stay in
      real(wp), intent(in) :: lower, upper
      !> Sense of monotonicity
      logical, intent(in) :: increasing
      integer :: i
      do i = 1, size(probes)
         call check_monotone(findings, func, double_window(probes(i), 64, lower, upper), &
            & increasing, "doubles around " // format_real(probes(i)))
      end do
   end subroutine check_windows

   !> The elements of x in reverse order
   pure function reverse(x) result(y)
      !> Array
      real(wp), intent(in) :: x(:)
      real(wp) :: y(size(x))
      y = x(size(x):1:-1)
   end function reverse

   ! -----------------------------------------------------------------------
   ! Identities
   ! -----------------------------------------------------------------------

   !> Check W e^W = z at the points z(:) for one branch.
   !>
   !> With W within 2 ulp, the relative residual is at most about 4 eps |1 + W|,
   !> plus the rounding of exp and of the product; 8 eps (1 + |1 + W|) bounds both.
   subroutine check_w_identity(error, func, z)
      !> Error handling
      type(error_type), allocatable, intent(inout) :: error
      !> Function name, "w0" or "wm1"
      character(len=*), intent(in) :: func
      !> Points, none of them 0
      real(wp), intent(in) :: z(:)
      real(wp) :: w, residual, tolerance
      integer :: i
      do i = 1, size(z)
         w = evaluate(func, z(i))
         if (ieee_is_nan(w)) then
            call test_failed(error, func // "(" // format_real(z(i)) // ") is NaN")
            return
         end if
         if (.not. abs(w) < 720) then    ! beyond every W of this range; exp would overflow
            call test_failed(error, func // "(" // format_real(z(i)) // ") = " // format_real(w) &
               & // " is out of range")
            return
         end if
         residual = abs((w * exp(w) - z(i)) / z(i))
         tolerance = 8 * eps * (1 + abs(1 + w))
         if (residual > tolerance) then
            call test_failed(error, "W e^W = z fails for " // func // " at z = " // format_real(z(i)), &
               & "W = " // format_real(w) // ", relative residual " // format_real(residual) &
               & // " > " // format_real(tolerance))
            return
         end if
      end do
   end subroutine check_w_identity

   !> Check h(u) = u - ln(1 + u) = t with u = -(1 + W) at the points t(:).
   !>
   !> dh/du = u/(1+u): a 2 ulp error in u moves h by up to 4 eps u^2/|1+u|, and
   !> evaluating h costs about 4 eps |u|/t relative; the tolerance allows twice both.
   subroutine check_t_identity(error, func, t)
      !> Error handling
      type(error_type), allocatable, intent(inout) :: error
      !> Function name, "w0p1" or "wm1p1"
      character(len=*), intent(in) :: func
      !> Points, all > 0
      real(wp), intent(in) :: t(:)
      real(wp) :: u, residual, tolerance
      integer :: i
      do i = 1, size(t)
         u = -evaluate(func, t(i))
         if (ieee_is_nan(u)) then
            call test_failed(error, func // "(" // format_real(t(i)) // ") is NaN")
            return
         end if
         if (.not. 1 + u > 0) then     ! 1 + W0 < 1 and 1 + W-1 <= 0 always
            call test_failed(error, func // "(" // format_real(t(i)) // ") = " // format_real(-u) &
               & // " is out of range")
            return
         end if
         residual = abs((u - log(1 + u)) - t(i)) / t(i)
         tolerance = 8 * eps * (1 + (abs(u) / t(i)) * (abs(u) / abs(1 + u)) + abs(u) / t(i))
         if (residual > tolerance) then
            call test_failed(error, "h(-(1+W)) = t fails for " // func // " at t = " &
               & // format_real(t(i)), "1 + W = " // format_real(-u) // ", relative residual " &
               & // format_real(residual) // " > " // format_real(tolerance))
            return
         end if
      end do
   end subroutine check_t_identity

   !> W0 e^W0 = z at z spread over [-0.36, -1e-290] and [1e-290, 1e300]
   subroutine test_identity_w0(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      real(wp) :: z(4000)
      do k = 1, 2000
         z(k) = -0.36_wp * quasi_random(k)**2 - 1.0e-290_wp
         z(2000 + k) = 10.0_wp**(-290 + 590 * quasi_random(2000 + k))
      end do
      call check_w_identity(error, "w0", z)
   end subroutine test_identity_w0

   !> W-1 e^W-1 = z at z spread over [-0.36, -1e-290]
   subroutine test_identity_wm1(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      real(wp) :: z(4000)
      do k = 1, 2000
         z(k) = -0.36_wp * quasi_random(k)**2 - 1.0e-290_wp
         z(2000 + k) = -10.0_wp**(-290 + 290 * quasi_random(2000 + k)) * 0.36_wp
      end do
      call check_w_identity(error, "wm1", z)
   end subroutine test_identity_wm1

   !> h(-(1 + W0)) = t for t in [0.1, 20] (below 0.1 the check itself cancels,
   !> above 20 the 1 + W0 form is 1 to within the tolerance)
   subroutine test_identity_w0p1(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      real(wp) :: t(4000)
      do k = 1, size(t)
         t(k) = 0.1_wp * 200.0_wp**quasi_random(k)
      end do
      call check_t_identity(error, "w0p1", t)
   end subroutine test_identity_w0p1

   !> h(-(1 + W-1)) = t for t in [0.1, 1e300]
   subroutine test_identity_wm1p1(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      real(wp) :: t(4000)
      do k = 1, size(t)
         t(k) = 0.1_wp * 10.0_wp**(301 * quasi_random(k))
      end do
      call check_t_identity(error, "wm1p1", t)
   end subroutine test_identity_wm1p1

   !> Away from the branch point the 1 + W forms agree with 1 + W(z), z = -exp(-1-t):
   !> for t in [1, 700] the rounding of z moves W by at most eps |W/(1+W)|
   subroutine test_t_form_vs_z_form(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      integer :: k
      real(wp) :: t, z, from_t, from_z
      do k = 1, 2000
         t = 700.0_wp**quasi_random(k)
         z = -exp(-1 - t)
         from_t = lambert_w0p1(t)
         from_z = 1 + lambert_w0(z)
         if (ieee_is_nan(from_t) .or. ieee_is_nan(from_z)) then
            call test_failed(error, "NaN from lambert_w0p1 or lambert_w0 at t = " // format_real(t))
            return
         end if
         if (.not. (abs(from_t - from_z) <= 8 * eps)) then
            call test_failed(error, "lambert_w0p1(" // format_real(t) // ") = " // format_real(from_t), &
               & "but 1 + lambert_w0(-exp(-1-t)) = " // format_real(from_z))
            return
         end if
         from_t = lambert_wm1p1(t)
         from_z = 1 + lambert_wm1(z)
         if (ieee_is_nan(from_t) .or. ieee_is_nan(from_z)) then
            call test_failed(error, "NaN from lambert_wm1p1 or lambert_wm1 at t = " // format_real(t))
            return
         end if
         if (.not. (abs(from_t - from_z) <= 8 * eps * abs(from_z - 1))) then
            call test_failed(error, "lambert_wm1p1(" // format_real(t) // ") = " // format_real(from_t), &
               & "but 1 + lambert_wm1(-exp(-1-t)) = " // format_real(from_z))
            return
         end if
      end do
   end subroutine test_t_form_vs_z_form

end module test_lambertw
