! SPDX-License-Identifier: Apache-2.0
!> The sort, median and count of distinct values behind the calibration's starting
!> values and rank checks (hcimpact_order_statistics), against slow obvious versions
!> on small arrays of every kind (sorted, reversed, equal values, ties, signed
!> zeros, extremes), on random arrays and on the patterns that hurt quicksorts
!> (sorted, reversed, organ pipe, sawtooth, few distinct values, median-of-three
!> killers) up to 3000 values; and fit_damping on a million points (the median used
!> to be an insertion sort: 205 s there).
module test_order_statistics
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
   use, intrinsic :: iso_fortran_env, only : output_unit, int64
   use testdrive, only : new_unittest, unittest_type, error_type, check
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite
   use hcimpact_restitution_law, only : restitution
   use hcimpact_order_statistics, only : sort_ascending, median_in_place, &
      & count_distinct_in_place
   use hcimpact_calibration, only : fit_type, fit_damping
   use hcimpact_rng, only : rng_type, new_rng, uniform
   implicit none
   private

   public :: collect_order_statistics

contains

   !> Collect all exported unit tests
   subroutine collect_order_statistics(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         new_unittest("small-arrays", test_small), &
         new_unittest("random-arrays", test_random), &
         new_unittest("median-odd-even-ties", test_median_cases), &
         new_unittest("patterns", test_patterns), &
         new_unittest("million-points", test_million) &
         ]
   end subroutine collect_order_statistics

   !> Median by counting: the value(s) with as many below as above.
   pure function reference_median(x) result(med)
      real(wp), intent(in) :: x(:)
      real(wp) :: med
      real(wp) :: lower, upper
      integer :: i, n
      n = size(x)
      lower = 0.0_wp
      upper = 0.0_wp
      ! the k-th smallest: a value with fewer than k below it and at least k at or below
      do i = 1, n
         if (count(x < x(i)) < (n + 1) / 2 .and. count(x <= x(i)) >= (n + 1) / 2) &
            & lower = x(i)
         if (count(x < x(i)) < n / 2 + 1 .and. count(x <= x(i)) >= n / 2 + 1) upper = x(i)
      end do
      if (mod(n, 2) == 1) then
         med = lower
      else
         med = 0.5_wp * lower + 0.5_wp * upper
      end if
   end function reference_median

   !> Whether y is x sorted: ascending, and every value as often in y as in x.
   pure logical function is_sorted_copy(x, y)
      real(wp), intent(in) :: x(:), y(:)
      integer :: i
      is_sorted_copy = size(x) == size(y)
      if (.not. is_sorted_copy) return
      do i = 2, size(y)
         if (y(i - 1) > y(i)) is_sorted_copy = .false.
      end do
      do i = 1, size(x)
         if (count(x == x(i)) /= count(y == x(i))) is_sorted_copy = .false.
      end do
   end function is_sorted_copy

   !> Distinct values by pairs.
   pure integer function reference_distinct(x)
      real(wp), intent(in) :: x(:)
      integer :: i
      reference_distinct = 0
      do i = 1, size(x)
         if (.not. any(x(1:i - 1) == x(i))) reference_distinct = reference_distinct + 1
      end do
   end function reference_distinct

   subroutine check_array(error, x, what)
      type(error_type), allocatable, intent(out) :: error
      real(wp), intent(in) :: x(:)
      character(len=*), intent(in) :: what
      real(wp) :: y(size(x)), med
      integer :: distinct
      y = x
      call sort_ascending(y)
      call check(error, is_sorted_copy(x, y), what // ": sorted")
      if (allocated(error)) return
      y = x
      call median_in_place(y, med)
      call check(error, med == reference_median(x) .or. size(x) == 0, what // ": median")
      if (allocated(error)) return
      y = x
      call count_distinct_in_place(y, distinct)
      call check(error, distinct, reference_distinct(x), what // ": distinct values")
   end subroutine check_array

   subroutine test_small(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: big = huge(1.0_wp), small = tiny(1.0_wp)
      call check_array(error, [real(wp) ::], "empty")
      if (allocated(error)) return
      call check_array(error, [3.0_wp], "one value")
      if (allocated(error)) return
      call check_array(error, [2.0_wp, 1.0_wp], "two values")
      if (allocated(error)) return
      call check_array(error, [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp, 6.0_wp], "sorted")
      if (allocated(error)) return
      call check_array(error, [6.0_wp, 5.0_wp, 4.0_wp, 3.0_wp, 2.0_wp, 1.0_wp, 0.0_wp], &
         & "reversed")
      if (allocated(error)) return
      call check_array(error, [7.0_wp, 7.0_wp, 7.0_wp, 7.0_wp], "all equal")
      if (allocated(error)) return
      call check_array(error, [1.0_wp, 3.0_wp, 3.0_wp, 3.0_wp, 2.0_wp, 3.0_wp, 1.0_wp], "ties")
      if (allocated(error)) return
      call check_array(error, [0.0_wp, -0.0_wp, -0.0_wp, 0.0_wp, 1.0_wp], "signed zeros")
      if (allocated(error)) return
      call check_array(error, [big, -big, small, -small, big, 0.0_wp], "extremes")
      if (allocated(error)) return
      call check_array(error, [big, big], "the mean of two huge values stays finite")
   end subroutine test_small

   !> Random arrays of every size 1 ... 200, values from a small set (many ties) or
   !> spread over many binades.
   subroutine test_random(error)
      type(error_type), allocatable, intent(out) :: error
      type(rng_type) :: rng
      real(wp), allocatable :: x(:)
      integer :: n, i, kind
      character(len=40) :: what
      rng = new_rng(12345)
      do kind = 1, 2
         do n = 1, 200
            allocate(x(n))
            do i = 1, n
               if (kind == 1) then
                  x(i) = real(int(5.0_wp * uniform(rng)), wp)
               else
                  x(i) = (uniform(rng) - 0.5_wp) * 10.0_wp**int(40.0_wp * uniform(rng) - 20.0_wp)
               end if
            end do
            write(what, '(a, i0, a, i0)') "random kind ", kind, ", n = ", n
            call check_array(error, x, trim(what))
            deallocate(x)
            if (allocated(error)) return
         end do
      end do
   end subroutine test_random

   subroutine test_median_cases(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: x5(5), x6(6), med
      x5 = [5.0_wp, 1.0_wp, 4.0_wp, 2.0_wp, 3.0_wp]
      call median_in_place(x5, med)
      call check(error, med == 3.0_wp, "odd count: the middle value")
      if (allocated(error)) return
      x6 = [6.0_wp, 1.0_wp, 4.0_wp, 2.0_wp, 3.0_wp, 5.0_wp]
      call median_in_place(x6, med)
      call check(error, med == 3.5_wp, "even count: the mean of the middle two")
      if (allocated(error)) return
      x6 = [2.0_wp, 9.0_wp, 2.0_wp, 2.0_wp, 9.0_wp, 9.0_wp]
      call median_in_place(x6, med)
      call check(error, med == 5.5_wp, "even count with ties")
      if (allocated(error)) return
      x5 = [2.0_wp, 9.0_wp, 2.0_wp, 2.0_wp, 9.0_wp]
      call median_in_place(x5, med)
      call check(error, med == 2.0_wp, "odd count with ties")
   end subroutine test_median_cases

   !> Insertion sort: the slow, obvious reference.
   pure subroutine reference_sort(x)
      real(wp), intent(inout) :: x(:)
      real(wp) :: value
      integer :: i, j
      do i = 2, size(x)
         value = x(i)
         j = i - 1
         do while (j >= 1)
            if (.not. x(j) > value) exit
            x(j + 1) = x(j)
            j = j - 1
         end do
         x(j + 1) = value
      end do
   end subroutine reference_sort

   !> Sizes 17 ... 3000 (past the insertion-sort threshold, odd and even) and patterns
   !> that defeat simple pivots: the sort equals the reference sort, the median its
   !> middle, the distinct count its changes.
   subroutine test_patterns(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: sizes(*) = [17, 18, 33, 100, 101, 1000, 1023, 1024, 3000]
      real(wp), allocatable :: x(:), y(:), ref(:)
      real(wp) :: med, expected
      integer :: is, pattern, n, i, distinct
      character(len=48) :: what
      do is = 1, size(sizes)
         n = sizes(is)
         allocate(x(n), y(n), ref(n))
         do pattern = 1, 7
            do i = 1, n
               select case (pattern)
               case (1)
                  x(i) = real(i, wp)
               case (2)
                  x(i) = real(n - i, wp)
               case (3)
                  x(i) = real(min(i, n + 1 - i), wp)
               case (4)
                  x(i) = real(mod(i, 7), wp)
               case (5)
                  x(i) = real(mod(i * 7919, 3), wp) - 1.0_wp
               case (6)
                  ! a median-of-three killer: large values where the pivots are drawn
                  x(i) = merge(real(n + i, wp), real(i, wp), mod(i, 2) == 0)
               case default
                  x(i) = real(mod(int(i, 8) * 48271_8, 2147483647_8), wp)
               end select
            end do
            write(what, '(a, i0, a, i0)') "pattern ", pattern, ", n = ", n
            ref = x
            call reference_sort(ref)
            y = x
            call sort_ascending(y)
            call check(error, all(y == ref), trim(what) // ": sorted")
            if (allocated(error)) return
            y = x
            call median_in_place(y, med)
            if (mod(n, 2) == 1) then
               expected = ref((n + 1) / 2)
            else
               expected = 0.5_wp * ref(n / 2) + 0.5_wp * ref(n / 2 + 1)
            end if
            call check(error, med == expected, trim(what) // ": median")
            if (allocated(error)) return
            y = x
            call count_distinct_in_place(y, distinct)
            call check(error, distinct, 1 + count(ref(2:) /= ref(:n - 1)), &
               & trim(what) // ": distinct values")
            if (allocated(error)) return
         end do
         deallocate(x, y, ref)
      end do
   end subroutine test_patterns

   !> fit_damping on 2^20 points: the noise-free b back, and a NaN among them refused
   !> before any sort. The time of the fit is printed, not asserted (doc/calibration.md
   !> reports it).
   subroutine test_million(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 2**20
      real(wp), parameter :: b = 0.1_wp
      real(wp), allocatable :: v(:), e(:)
      type(fit_type) :: fit
      integer :: stat, i
      integer(int64) :: start, finish, rate
      allocate(v(n), e(n))
      ! speeds in an order no sort can predict (a permutation by a multiplier)
      do i = 1, n
         v(i) = 0.5_wp + 4.5_wp * real(mod(int(i, 8) * 40503_8, int(n, 8)), wp) / n
      end do
      e = restitution(b * v)
      call system_clock(start, rate)
      call fit_damping(v, e, fit, stat)
      call system_clock(finish)
      write(output_unit, '(a, i0, a, f0.3, a)') "       fit_damping on ", n, " points: ", &
         & real(finish - start, wp) / real(rate, wp), " s (wall clock, not asserted)"
      call check(error, stat, hcimpact_ok, "a million points")
      if (allocated(error)) return
      call check(error, abs(fit%parameters(1) / b - 1.0_wp) < 1.0e-12_wp, &
         & "a million points: b back")
      if (allocated(error)) return
      e(n / 2) = ieee_value(1.0_wp, ieee_quiet_nan)
      call fit_damping(v, e, fit, stat)
      call check(error, stat, hcimpact_err_not_finite, "a NaN among a million points")
   end subroutine test_million

end module test_order_statistics
