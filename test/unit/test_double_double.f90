! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_double_double: dd_exp, dd_log, dd_sqrt and the operators against
!> the mpmath references of test/reference/double_double.csv, the special values of
!> exp and log, and the exactness of two_sum and two_prod; hcimpact_kinds'
!> exponent_from_bits, which the set-up of an impact reads binary exponents with.
!>
!> The error of a result y = y%hi + y%lo against the exact value ref = ref_hi + ref_lo
!> is (y%hi - ref_hi) + (y%lo - ref_lo) (the first difference is exact when y is close),
!> and the test asserts |error| <= bound |ref| (+ 2^-1074 for exp, whose results near
!> and below the end of the normal range lose their trailing part), with the bounds
!> documented in src/hcimpact/numerics/double_double.f90. Each test also checks that the result
!> is normalised, |y%lo| <= ulp(y%hi)/2.
!>
!> Safe under -ffpe-trap=invalid,zero,overflow: no NaN is compared, no logarithm of
!> zero is taken, and nothing is formed that could overflow.
module test_double_double
   use, intrinsic :: iso_fortran_env, only : real128, int64
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf, ieee_negative_inf, &
      & ieee_is_finite, ieee_is_nan
   use testdrive, only : new_unittest, unittest_type, error_type, test_failed
   use hcimpact_check, only : format_real, read_labelled_table, int_text
   use hcimpact_kinds, only : wp, exponent_from_bits
   use hcimpact_double_double, only : dd_real, dd, two_sum, two_prod, operator(+), &
      & operator(-), operator(*), operator(/), dd_exp, dd_log, dd_sqrt
   implicit none
   private

   public :: collect_double_double

   !> Documented relative error bound of dd_exp and dd_log
   real(wp), parameter :: bound_exp_log = 2.0_wp**(-100)
   !> Documented relative error bound of dd_sqrt, products and quotients
   real(wp), parameter :: bound_mul_div = 2.0_wp**(-103)
   !> Documented relative error bound of sums and differences
   real(wp), parameter :: bound_add = 2.0_wp**(-104)
   !> Smallest positive subnormal double
   real(wp), parameter :: tiny_sub = 2.0_wp**(-1074)

   !> Name of the reference file inside the reference directory
   character(len=*), parameter :: reference_file = "double_double.csv"
   !> Length of the region and function names in the reference file
   integer, parameter :: name_len = 16
   !> Every (function, region) of the reference file with an accuracy test; a test
   !> checks that the file holds no other
   character(len=*), parameter :: accuracy_cases(2, 19) = reshape([ character(len=name_len) :: &
      & "exp", "exp_wide", "exp", "exp_mid", "exp", "exp_small", "exp", "exp_seam", &
      & "exp", "exp_edge", "log", "log_wide", "log", "log_near1", "log", "log_seam", &
      & "log", "log_subnormal", "sqrt", "sqrt", "add", "ops", "sub", "ops", "mul", "ops", &
      & "div", "ops", "addr", "ops", "mulr", "ops", "divr", "ops", "rsub", "ops", &
      & "rdiv", "ops"], [2, 19])

   !> The reference file, read once on first use
   type :: reference_table
      !> Region and function of each row
      character(len=name_len), allocatable :: region(:), func(:)
      !> Inputs a = a(1) + a(2), b = b(1) + b(2) and reference ref(1) + ref(2)
      real(wp), allocatable :: a(:, :), b(:, :), ref(:, :)
   end type reference_table

   !> Rows of the reference file, once loaded
   type(reference_table), save :: table
   !> Whether `table` holds the file
   logical, save :: table_loaded = .false.

contains

   !> Collect all exported unit tests
   subroutine collect_double_double(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("reference-complete", test_reference_complete), &
         & new_unittest("exp-wide", test_exp_wide), &
         & new_unittest("exp-mid", test_exp_mid), &
         & new_unittest("exp-small", test_exp_small), &
         & new_unittest("exp-seam", test_exp_seam), &
         & new_unittest("exp-edge", test_exp_edge), &
         & new_unittest("log-wide", test_log_wide), &
         & new_unittest("log-near1", test_log_near1), &
         & new_unittest("log-seam", test_log_seam), &
         & new_unittest("log-subnormal", test_log_subnormal), &
         & new_unittest("sqrt", test_sqrt), &
         & new_unittest("add", test_add), &
         & new_unittest("sub", test_sub), &
         & new_unittest("mul", test_mul), &
         & new_unittest("div", test_div), &
         & new_unittest("add-double", test_addr), &
         & new_unittest("mul-double", test_mulr), &
         & new_unittest("div-double", test_divr), &
         & new_unittest("double-sub", test_rsub), &
         & new_unittest("double-div", test_rdiv), &
         & new_unittest("exp-special", test_exp_special), &
         & new_unittest("log-special", test_log_special), &
         & new_unittest("exp-log-roundtrip", test_roundtrip), &
         & new_unittest("two-sum-exact", test_two_sum), &
         & new_unittest("two-prod-exact", test_two_prod), &
         & new_unittest("exponent-from-bits", test_exponent_from_bits) &
         & ]
   end subroutine collect_double_double

   ! -----------------------------------------------------------------------
   ! Helpers
   ! -----------------------------------------------------------------------

   !> The operation named `func` of the reference file at a and b.
   elemental function evaluate(func, a, b) result(y)
      !> Function name, as in the reference file
      character(len=*), intent(in) :: func
      !> First argument
      type(dd_real), intent(in) :: a
      !> Second argument (its leading part only for the mixed operations)
      type(dd_real), intent(in) :: b
      type(dd_real) :: y
      select case (func)
      case ("exp")
         y = dd_exp(a)
      case ("log")
         y = dd_log(a)
      case ("sqrt")
         y = dd_sqrt(a)
      case ("add")
         y = a + b
      case ("sub")
         y = a - b
      case ("mul")
         y = a * b
      case ("div")
         y = a / b
      case ("addr")
         y = a + b%hi
      case ("mulr")
         y = a * b%hi
      case ("divr")
         y = a / b%hi
      case ("rsub")
         y = b%hi - a
      case ("rdiv")
         y = b%hi / a
      case default
         y = dd(huge(1.0_wp))
      end select
   end function evaluate

   !> Error |y - ref| in units of |ref| (ref = ref_hi + ref_lo), with `floor` added to
   !> the unit; huge when y is not finite or the error cannot be expressed.
   elemental function relative_error(y, ref_hi, ref_lo, floor) result(err)
      type(dd_real), intent(in) :: y
      real(wp), intent(in) :: ref_hi, ref_lo, floor
      real(wp) :: err
      real(wp) :: diff, unit
      err = huge(1.0_wp)
      if (.not. (ieee_is_finite(y%hi) .and. ieee_is_finite(y%lo))) return
      if (abs(y%hi) > 2.0_wp**1000 .or. abs(ref_hi) > 2.0_wp**1000) then
         ! halved (exact at this size), so that the difference cannot overflow
         diff = abs((0.5_wp * y%hi - 0.5_wp * ref_hi) + (0.5_wp * y%lo - 0.5_wp * ref_lo))
         unit = 0.5_wp * abs(ref_hi) + 0.5_wp * floor
      else
         diff = abs((y%hi - ref_hi) + (y%lo - ref_lo))
         unit = abs(ref_hi) + floor
      end if
      if (unit > 0.0_wp) then
         if (diff * 2.0_wp**(-900) <= unit) err = diff / unit
      else if (diff == 0.0_wp) then
         err = 0.0_wp
      end if
   end function relative_error

   !> Whether y is normalised: |y%lo| <= ulp(y%hi)/2 (checked where spacing is exact).
   elemental function normalised(y) result(ok)
      type(dd_real), intent(in) :: y
      logical :: ok
      ok = .true.
      if (ieee_is_finite(y%hi) .and. abs(y%hi) >= 2.0_wp**(-960)) ok = abs(y%lo) <= 0.5_wp * spacing(y%hi)
   end function normalised

   !> Text of a relative error as a power of two, "2^-104.3".
   function rel_text(err) result(text)
      !> Relative error
      real(wp), intent(in) :: err
      character(len=:), allocatable :: text
      character(len=32) :: buffer
      if (err >= huge(1.0_wp)) then
         text = "huge"
      else if (err <= 0.0_wp) then
         text = "0"
      else
         write(buffer, '("2^", f0.1)') log(err) / log(2.0_wp)
         text = trim(buffer)
      end if
   end function rel_text

   !> Read the reference file into `table`, once (test-drive may run the tests of a
   !> suite in OpenMP threads: the first reader holds the others back).
   subroutine load_table(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !$omp critical (test_double_double_table)
      if (.not. table_loaded) call read_table(error)
      !$omp end critical (test_double_double_table)
   end subroutine load_table

   !> Read the reference file into `table` (rows `region,func,a_hi,a_lo,b_hi,b_lo,ref_hi,ref_lo`).
   subroutine read_table(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: values(:, :)
      call read_labelled_table(error, reference_file, 6, table%region, table%func, values)
      if (allocated(error)) return
      table%a = values(1:2, :)
      table%b = values(3:4, :)
      table%ref = values(5:6, :)
      table_loaded = .true.
   end subroutine read_table

   !> Accuracy of one operation on one region of the reference file against `bound`.
   subroutine check_region(error, func, region, bound, floor)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Function name, as in the reference file
      character(len=*), intent(in) :: func
      !> Region name, as in the reference file
      character(len=*), intent(in) :: region
      !> Largest relative error allowed
      real(wp), intent(in) :: bound
      !> Absolute error allowed besides, in units of the bound (0 but for exp)
      real(wp), intent(in) :: floor
      type(dd_real), allocatable :: a(:), b(:), y(:)
      real(wp), allocatable :: ref_hi(:), ref_lo(:), err(:)
      logical, allocatable :: rows(:)
      integer :: n, worst, bad

      call load_table(error)
      if (allocated(error)) return
      rows = table%func == func .and. table%region == region
      n = count(rows)
      if (n == 0) then
         call test_failed(error, "no rows for " // func // " in region " // region &
            & // " of the reference file")
         return
      end if
      allocate(a(n), b(n))
      a(:)%hi = pack(table%a(1, :), rows)
      a(:)%lo = pack(table%a(2, :), rows)
      b(:)%hi = pack(table%b(1, :), rows)
      b(:)%lo = pack(table%b(2, :), rows)
      ref_hi = pack(table%ref(1, :), rows)
      ref_lo = pack(table%ref(2, :), rows)
      allocate(y(n), err(n))
      y(:) = evaluate(func, a, b)
      err(:) = relative_error(y, ref_hi, ref_lo, floor)
      worst = maxloc(err, dim=1)
      if (err(worst) > bound) then
         call test_failed(error, func // " on " // region // ": largest relative error " &
            & // rel_text(err(worst)) // " over " // int_text(n) // " points (bound " &
            & // rel_text(bound) // ")", "worst at a = " // format_real(a(worst)%hi) // " + " &
            & // format_real(a(worst)%lo) // ", b = " // format_real(b(worst)%hi) // " + " &
            & // format_real(b(worst)%lo) // ": got " // format_real(y(worst)%hi) // " + " &
            & // format_real(y(worst)%lo) // ", reference " // format_real(ref_hi(worst)) &
            & // " + " // format_real(ref_lo(worst)))
         return
      end if
      bad = count(.not. normalised(y))
      if (bad > 0) then
         worst = findloc(normalised(y), .false., dim=1)
         call test_failed(error, func // " on " // region // ": " // int_text(bad) &
            & // " results not normalised (|lo| > ulp(hi)/2)", "first: " &
            & // format_real(y(worst)%hi) // " + " // format_real(y(worst)%lo))
      end if
   end subroutine check_region

   !> Check that y is exactly hi + lo (both parts), with a message.
   subroutine check_exact(error, y, hi, lo, what)
      !> Error handling
      type(error_type), allocatable, intent(inout) :: error
      !> Result
      type(dd_real), intent(in) :: y
      !> Expected parts
      real(wp), intent(in) :: hi, lo
      !> Description of the call
      character(len=*), intent(in) :: what
      if (allocated(error)) return
      if (ieee_is_nan(y%hi) .or. ieee_is_nan(y%lo)) then
         call test_failed(error, what // " is NaN")
      else if (.not. (y%hi == hi .and. y%lo == lo)) then
         call test_failed(error, what // ": got " // format_real(y%hi) // " + " &
            & // format_real(y%lo) // ", expected " // format_real(hi) // " + " // format_real(lo))
      end if
   end subroutine check_exact

   ! -----------------------------------------------------------------------
   ! Accuracy against the reference file
   ! -----------------------------------------------------------------------

   !> The reference file has rows for every accuracy test and for no other case.
   subroutine test_reference_complete(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      logical :: known
      integer :: i, k
      call load_table(error)
      if (allocated(error)) return
      do i = 1, size(table%func)
         known = .false.
         do k = 1, size(accuracy_cases, 2)
            if (table%func(i) == accuracy_cases(1, k) .and. table%region(i) == accuracy_cases(2, k)) &
               & known = .true.
         end do
         if (.not. known) then
            call test_failed(error, "reference file has rows for " // trim(table%func(i)) &
               & // " in region " // trim(table%region(i)) // ", which no test checks")
            return
         end if
      end do
   end subroutine test_reference_complete

   subroutine test_exp_wide(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "exp", "exp_wide", bound_exp_log, tiny_sub / bound_exp_log)
   end subroutine test_exp_wide

   subroutine test_exp_mid(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "exp", "exp_mid", bound_exp_log, 0.0_wp)
   end subroutine test_exp_mid

   subroutine test_exp_small(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "exp", "exp_small", bound_exp_log, 0.0_wp)
   end subroutine test_exp_small

   subroutine test_exp_seam(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "exp", "exp_seam", bound_exp_log, tiny_sub / bound_exp_log)
   end subroutine test_exp_seam

   subroutine test_exp_edge(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "exp", "exp_edge", bound_exp_log, tiny_sub / bound_exp_log)
   end subroutine test_exp_edge

   subroutine test_log_wide(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "log", "log_wide", bound_exp_log, 0.0_wp)
   end subroutine test_log_wide

   subroutine test_log_near1(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "log", "log_near1", bound_exp_log, 0.0_wp)
   end subroutine test_log_near1

   subroutine test_log_seam(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "log", "log_seam", bound_exp_log, 0.0_wp)
   end subroutine test_log_seam

   subroutine test_log_subnormal(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "log", "log_subnormal", bound_exp_log, 0.0_wp)
   end subroutine test_log_subnormal

   subroutine test_sqrt(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "sqrt", "sqrt", bound_mul_div, 0.0_wp)
   end subroutine test_sqrt

   subroutine test_add(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "add", "ops", bound_add, 0.0_wp)
   end subroutine test_add

   subroutine test_sub(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "sub", "ops", bound_add, 0.0_wp)
   end subroutine test_sub

   subroutine test_mul(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "mul", "ops", bound_mul_div, 0.0_wp)
   end subroutine test_mul

   subroutine test_div(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "div", "ops", bound_mul_div, 0.0_wp)
   end subroutine test_div

   subroutine test_addr(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "addr", "ops", bound_add, 0.0_wp)
   end subroutine test_addr

   subroutine test_mulr(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "mulr", "ops", bound_mul_div, 0.0_wp)
   end subroutine test_mulr

   subroutine test_divr(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "divr", "ops", bound_mul_div, 0.0_wp)
   end subroutine test_divr

   subroutine test_rsub(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "rsub", "ops", bound_add, 0.0_wp)
   end subroutine test_rsub

   subroutine test_rdiv(error)
      type(error_type), allocatable, intent(out) :: error
      call check_region(error, "rdiv", "ops", bound_mul_div, 0.0_wp)
   end subroutine test_rdiv

   ! -----------------------------------------------------------------------
   ! Special values and exactness
   ! -----------------------------------------------------------------------

   !> exp(0) = 1 exactly; overflow gives +Inf, underflow 0; exp(tiny) = 1 + tiny.
   subroutine test_exp_special(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: inf
      type(dd_real) :: y
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      call check_exact(error, dd_exp(dd(0.0_wp)), 1.0_wp, 0.0_wp, "exp(0)")
      call check_exact(error, dd_exp(dd(-0.0_wp)), 1.0_wp, 0.0_wp, "exp(-0)")
      call check_exact(error, dd_exp(dd(710.0_wp)), inf, 0.0_wp, "exp(710)")
      call check_exact(error, dd_exp(dd(huge(1.0_wp))), inf, 0.0_wp, "exp(huge)")
      call check_exact(error, dd_exp(dd(inf)), inf, 0.0_wp, "exp(+Inf)")
      ! 709.782712893384 is 2.4e-14 below ln(huge): with lo = 5e-14 the exact value is
      ! above the largest double
      call check_exact(error, dd_exp(dd_real(709.782712893384_wp, 5e-14_wp)), inf, 0.0_wp, &
         & "exp(709.782712893384 + 5e-14)")
      if (allocated(error)) return
      y = dd_exp(dd(709.782712893384_wp))
      if (.not. (ieee_is_finite(y%hi) .and. y%hi > 1.7e308_wp)) then
         call test_failed(error, "exp(709.782712893384) should be finite and near huge, got " &
            & // format_real(y%hi))
         return
      end if
      call check_exact(error, dd_exp(dd(-746.0_wp)), 0.0_wp, 0.0_wp, "exp(-746)")
      call check_exact(error, dd_exp(dd(-huge(1.0_wp))), 0.0_wp, 0.0_wp, "exp(-huge)")
      call check_exact(error, dd_exp(dd(ieee_value(1.0_wp, ieee_negative_inf))), 0.0_wp, &
         & 0.0_wp, "exp(-Inf)")
      call check_exact(error, dd_exp(dd(1e-300_wp)), 1.0_wp, 1e-300_wp, "exp(1e-300)")
      call check_exact(error, dd_exp(dd(-1e-300_wp)), 1.0_wp, -1e-300_wp, "exp(-1e-300)")
      call check_exact(error, dd_exp(dd(tiny_sub)), 1.0_wp, tiny_sub, "exp(2^-1074)")
      ! exp(-1074 ln 2 - small) is the smallest subnormal or zero, never more
      y = dd_exp(dd(-744.5_wp))
      if (allocated(error)) return
      if (.not. (y%hi >= 0.0_wp .and. y%hi <= 2.0_wp * tiny_sub .and. y%lo == 0.0_wp)) then
         call test_failed(error, "exp(-744.5) should be a tiny subnormal, got " &
            & // format_real(y%hi) // " + " // format_real(y%lo))
      end if
   end subroutine test_exp_special

   !> log(1) = 0 exactly (both parts); log(2) and log(1/2) are +-ln 2 within the bound.
   subroutine test_log_special(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      ! ln 2 to 106 bits: the double nearest it and the double nearest the rest
      real(wp), parameter :: ln2_hi = 0.6931471805599453_wp, ln2_lo = 2.3190468138462996e-17_wp
      type(dd_real) :: y
      call check_exact(error, dd_log(dd(1.0_wp)), 0.0_wp, 0.0_wp, "log(1)")
      if (allocated(error)) return
      y = dd_log(dd(2.0_wp))
      if (relative_error(y, ln2_hi, ln2_lo, 0.0_wp) > bound_exp_log) then
         call test_failed(error, "log(2) = " // format_real(y%hi) // " + " // format_real(y%lo))
         return
      end if
      y = dd_log(dd(0.5_wp))
      if (relative_error(y, -ln2_hi, -ln2_lo, 0.0_wp) > bound_exp_log) then
         call test_failed(error, "log(1/2) = " // format_real(y%hi) // " + " // format_real(y%lo))
      end if
   end subroutine test_log_special

   !> log(exp(a)) = a within the bounds of both, over [-670, 700] (below, exp's
   !> trailing part is subnormal and carries fewer digits).
   subroutine test_roundtrip(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      type(dd_real) :: a, y
      real(wp) :: err
      integer :: i
      do i = -670, 700
         a = dd_real(real(i, wp) + 0.3_wp, 1e-18_wp)
         y = dd_log(dd_exp(a))
         ! |a| >= 0.3: the relative errors of exp (carried as absolute into log) and
         ! of log add up to below 2^-99 relative
         err = relative_error(y, a%hi, a%lo, 0.0_wp)
         if (err > 2.0_wp * bound_exp_log) then
            call test_failed(error, "log(exp(a)) /= a for a = " // format_real(a%hi) &
               & // ": relative error " // rel_text(err))
            return
         end if
      end do
   end subroutine test_roundtrip

   !> two_sum is exact: a + b = s%hi + s%lo in quadruple precision.
   subroutine test_two_sum(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: a(8), b(8)
      type(dd_real) :: s
      integer :: i
      a = [1.0_wp, 1e16_wp, -3.5_wp, 0.1_wp, 1e300_wp, 2.0_wp**(-1070), 1.0_wp, 0.0_wp]
      b = [2.0_wp**(-60), 1.0_wp, 3.5_wp, 0.2_wp, -1e284_wp, 2.0_wp**(-1074), -1e-20_wp, -5.0_wp]
      do i = 1, size(a)
         s = two_sum(a(i), b(i))
         if (s%hi /= a(i) + b(i) .or. real(s%hi, real128) + real(s%lo, real128) &
            & /= real(a(i), real128) + real(b(i), real128)) then
            call test_failed(error, "two_sum(" // format_real(a(i)) // ", " // format_real(b(i)) &
               & // ") = " // format_real(s%hi) // " + " // format_real(s%lo) // " is not exact")
            return
         end if
      end do
   end subroutine test_two_sum

   !> two_prod is exact (quadruple precision holds every product of two doubles),
   !> also for factors beyond 2^996 (scaled splitting); products beyond 2^996 keep
   !> no trailing part.
   subroutine test_two_prod(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: a(7), b(7)
      type(dd_real) :: p
      integer :: i
      a = [0.1_wp, 1.0_wp / 3.0_wp, -7.123456789_wp, 1.3_wp * 2.0_wp**1000, 1e-150_wp, &
         & 2.0_wp**27 + 1.0_wp, 1.7e308_wp]
      b = [0.3_wp, 3.0_wp, 1e200_wp, 1.7_wp * 2.0_wp**(-990), -1e-140_wp, 2.0_wp**27 - 1.0_wp, &
         & 1e-300_wp]
      do i = 1, size(a)
         p = two_prod(a(i), b(i))
         if (p%hi /= a(i) * b(i) .or. real(p%hi, real128) + real(p%lo, real128) &
            & /= real(a(i), real128) * real(b(i), real128)) then
            call test_failed(error, "two_prod(" // format_real(a(i)) // ", " // format_real(b(i)) &
               & // ") = " // format_real(p%hi) // " + " // format_real(p%lo) // " is not exact")
            return
         end if
      end do
      p = two_prod(1e300_wp, 1e8_wp)
      call check_exact(error, p, 1e300_wp * 1e8_wp, 0.0_wp, "two_prod(1e300, 1e8)")
   end subroutine test_two_prod

   !> exponent_from_bits(x) is exponent(x) for every kind of double: each binary
   !> exponent of the normal range (at 1, next to 2 and at the halfway significand, both
   !> signs), subnormals, zero, the extremes, Inf and NaN
   subroutine test_exponent_from_bits(error)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: x(14)
      integer :: e, i, j
      real(wp) :: significand(3)
      significand = [1.0_wp, 1.5_wp, 2.0_wp - epsilon(1.0_wp)]
      do e = minexponent(1.0_wp) - 1, maxexponent(1.0_wp) - 1
         do j = 1, size(significand)
            x(1) = scale(significand(j), e)
            x(2) = -x(1)
            do i = 1, 2
               call check_exponent(x(i))
               if (allocated(error)) return
            end do
         end do
      end do
      x = [0.0_wp, -0.0_wp, tiny(1.0_wp), tiny(1.0_wp) * (1.0_wp - epsilon(1.0_wp)), &
         & tiny_sub, -3.0_wp * tiny_sub, 2.0_wp**(-1030), huge(1.0_wp), -huge(1.0_wp), &
         & 0.5_wp, 1.0_wp, ieee_value(1.0_wp, ieee_positive_inf), &
         & ieee_value(1.0_wp, ieee_negative_inf), transfer(-2251799813685248_int64, 1.0_wp)]
      do i = 1, size(x)
         call check_exponent(x(i))
         if (allocated(error)) return
      end do
   contains
      subroutine check_exponent(y)
         real(wp), intent(in) :: y
         if (exponent_from_bits(y) /= exponent(y)) call test_failed(error, &
            & "exponent_from_bits(" // format_real(y) // ") = " &
            & // int_text(exponent_from_bits(y)) // ", exponent = " // int_text(exponent(y)))
      end subroutine check_exponent
   end subroutine test_exponent_from_bits

end module test_double_double
