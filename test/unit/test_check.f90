! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_check, the closeness checks that every other suite uses:
!> a check that cannot fail tests nothing, so here they are made to fail.
module test_check
   use, intrinsic :: iso_fortran_env, only : wp => real64
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_negative_inf, ieee_is_nan
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_check, only : ulp_error, check_ulps, check_close, median, format_real
   implicit none
   private

   public :: collect_check

contains

   !> Collect all exported unit tests
   subroutine collect_check(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("ulp-error-finite", test_ulp_finite), &
         & new_unittest("ulp-error-two-part-reference", test_ulp_two_part), &
         & new_unittest("ulp-error-exceptional", test_ulp_exceptional), &
         & new_unittest("check-close-nan-fails", test_close_nan), &
         & new_unittest("check-close-negative-expected", test_close_negative), &
         & new_unittest("check-close-tolerances", test_close_tolerances), &
         & new_unittest("check-close-extremes", test_close_extremes), &
         & new_unittest("check-ulps", test_check_ulps), &
         & new_unittest("median", test_median), &
         & new_unittest("format-real", test_format_real) &
         & ]
   end subroutine collect_check

   !> Record whether a probing check failed, then clear it (test-drive's error
   !> type escalates an error that is deallocated while still set).
   subroutine expect(error, probe, should_fail, what, message_part)
      !> Error handling of the calling test
      type(error_type), allocatable, intent(out) :: error
      !> Outcome of the check under test; cleared on return
      type(error_type), allocatable, intent(inout) :: probe
      !> Whether the check under test should have failed
      logical, intent(in) :: should_fail
      !> Description of the case
      character(len=*), intent(in) :: what
      !> Text the failure message must contain
      character(len=*), intent(in), optional :: message_part

      logical :: failed, has_part

      failed = allocated(probe)
      has_part = .true.
      if (failed) then
         if (present(message_part)) then
            has_part = .false.
            if (allocated(probe%message)) has_part = index(probe%message, message_part) > 0
         end if
         probe%stat = 0
         deallocate(probe)
      end if
      if (failed .neqv. should_fail) then
         if (should_fail) then
            call test_failed(error, what, "the check passed but should have failed")
         else
            call test_failed(error, what, "the check failed but should have passed")
         end if
      else if (.not.has_part) then
         call test_failed(error, what, "failure message lacks '" // message_part // "'")
      end if
   end subroutine expect

   subroutine test_ulp_finite(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: one_up

      one_up = nearest(1.0_wp, 2.0_wp)
      call check(error, ulp_error(1.0_wp, 1.0_wp) == 0.0_wp, "exact match is 0 ulp")
      if (allocated(error)) return
      call check(error, ulp_error(one_up, 1.0_wp) == 1.0_wp, "next double above 1 is 1 ulp")
      if (allocated(error)) return
      call check(error, ulp_error(-one_up, -1.0_wp) == 1.0_wp, "negative reference: 1 ulp")
      if (allocated(error)) return
      call check(error, ulp_error(3.0_wp*spacing(8.0_wp) + 8.0_wp, 8.0_wp) == 3.0_wp, &
         & "3 ulp above 8")
      if (allocated(error)) return
      ! below a power of two the doubles are twice as dense; the unit stays spacing(ref)
      call check(error, ulp_error(nearest(1.0_wp, -1.0_wp), 1.0_wp) == 0.5_wp, &
         & "next double below 1 is half a spacing(1)")
      if (allocated(error)) return
      call check(error, ulp_error(tiny(1.0_wp), 0.0_wp) == 2.0_wp**52, &
         & "zero reference: the unit is the smallest subnormal 2**-1074")
      if (allocated(error)) return
      call check(error, ulp_error(nearest(nearest(nearest(1.0e-300_wp, 1.0_wp), 1.0_wp), &
         & 1.0_wp), 1.0e-300_wp) == 3.0_wp, &
         & "tiny normal reference: three doubles up is 3 ulp (not 3/2**52 of tiny)")
      if (allocated(error)) return
      call check(error, ulp_error(-huge(1.0_wp), huge(1.0_wp)) > 1.0e15_wp, &
         & "opposite huge values: large and finite, no overflow")
   end subroutine test_ulp_finite

   subroutine test_ulp_two_part(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: half_ulp

      half_ulp = 0.5_wp*spacing(1.0_wp)
      ! reference 1 + eps/2, exactly between 1 and its successor
      call check(error, ulp_error(1.0_wp, 1.0_wp, half_ulp) == 0.5_wp, "1 vs 1 + eps/2")
      if (allocated(error)) return
      call check(error, ulp_error(nearest(1.0_wp, 2.0_wp), 1.0_wp, half_ulp) == 0.5_wp, &
         & "1 + eps vs 1 + eps/2")
      if (allocated(error)) return
      ! 1 - eps/4 lies in the binade below 1, whose ulp is eps/2
      call check(error, ulp_error(1.0_wp, 1.0_wp, -0.25_wp*spacing(1.0_wp)) == 0.5_wp, &
         & "1 vs 1 - eps/4")
      if (allocated(error)) return
      call check(error, ulp_error(0.5_wp*tiny(1.0_wp), 0.0_wp, 0.5_wp*tiny(1.0_wp)) == 0.0_wp, &
         & "zero leading part: the trailing part is the reference")
   end subroutine test_ulp_two_part

   subroutine test_ulp_exceptional(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: nan, inf

      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      call check(error, ulp_error(nan, 1.0_wp) == inf, "NaN vs number is +Inf")
      if (allocated(error)) return
      call check(error, ulp_error(1.0_wp, nan) == inf, "number vs NaN is +Inf")
      if (allocated(error)) return
      call check(error, ulp_error(nan, nan) == 0.0_wp, "NaN vs NaN is 0")
      if (allocated(error)) return
      call check(error, ulp_error(inf, inf) == 0.0_wp, "+Inf vs +Inf is 0")
      if (allocated(error)) return
      call check(error, ulp_error(-inf, inf) == inf, "-Inf vs +Inf is +Inf")
      if (allocated(error)) return
      call check(error, ulp_error(huge(1.0_wp), inf) == inf, "huge vs +Inf is +Inf")
      if (allocated(error)) return
      call check(error, ulp_error(inf, 1.0_wp) == inf, "+Inf vs 1 is +Inf")
      if (allocated(error)) return
      call check(error, ulp_error(1.0_wp, 1.0_wp, inf) == inf, "infinite trailing part is invalid")
      if (allocated(error)) return
      call check(error, ulp_error(1.0e300_wp, 0.0_wp) == inf, "too many ulps for a double is +Inf")
   end subroutine test_ulp_exceptional

   subroutine test_close_nan(error)
      type(error_type), allocatable, intent(out) :: error
      type(error_type), allocatable :: probe
      real(wp) :: nan, inf

      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      call check_close(probe, nan, 1.0_wp, rel=1.0_wp)
      call expect(error, probe, .true., "NaN actual, generous rel", "NaN")
      if (allocated(error)) return
      call check_close(probe, 1.0_wp, nan, abs=inf)
      call expect(error, probe, .true., "NaN expected, infinite abs", "NaN")
      if (allocated(error)) return
      call check_close(probe, nan, nan)
      call expect(error, probe, .true., "NaN vs NaN, not allowed")
      if (allocated(error)) return
      call check_close(probe, nan, nan, allow_nan=.true.)
      call expect(error, probe, .false., "NaN vs NaN, allowed")
      if (allocated(error)) return
      call check_close(probe, nan, 1.0_wp, allow_nan=.true.)
      call expect(error, probe, .true., "NaN vs number, NaN allowed")
   end subroutine test_close_nan

   subroutine test_close_negative(error)
      type(error_type), allocatable, intent(out) :: error
      type(error_type), allocatable :: probe

      ! (actual - expected)/expected is negative here: a signed relative check
      ! would let this through
      call check_close(probe, 1.0_wp, -1.0_wp, rel=1.0e-3_wp)
      call expect(error, probe, .true., "1 vs -1 at rel 1e-3")
      if (allocated(error)) return
      call check_close(probe, -3.0_wp, -1.0_wp, rel=1.0e-3_wp)
      call expect(error, probe, .true., "-3 vs -1 at rel 1e-3")
      if (allocated(error)) return
      call check_close(probe, -1.0000001_wp, -1.0_wp, rel=1.0e-6_wp)
      call expect(error, probe, .false., "-1.0000001 vs -1 at rel 1e-6")
   end subroutine test_close_negative

   subroutine test_close_tolerances(error)
      type(error_type), allocatable, intent(out) :: error
      type(error_type), allocatable :: probe

      call check_close(probe, 1.0_wp, 1.0_wp)
      call expect(error, probe, .false., "equal values, no tolerance")
      if (allocated(error)) return
      call check_close(probe, nearest(1.0_wp, 2.0_wp), 1.0_wp, message="exact check")
      call expect(error, probe, .true., "1 ulp apart, no tolerance", "exact check")
      if (allocated(error)) return
      call check_close(probe, 1.0e-20_wp, 0.0_wp, abs=1.0e-15_wp)
      call expect(error, probe, .false., "near zero within abs")
      if (allocated(error)) return
      call check_close(probe, 1.0e-20_wp, 0.0_wp, rel=0.5_wp)
      call expect(error, probe, .true., "near zero, rel alone cannot pass")
      if (allocated(error)) return
      call check_close(probe, 101.0_wp, 100.0_wp, rel=1.0e-3_wp, abs=2.0_wp)
      call expect(error, probe, .false., "abs is the larger tolerance")
      if (allocated(error)) return
      call check_close(probe, 1.5_wp, 1.0_wp, rel=0.25_wp, message="within a quarter")
      call expect(error, probe, .true., "outside rel", "actual = 1.5000000000000000E+000")
   end subroutine test_close_tolerances

   subroutine test_close_extremes(error)
      type(error_type), allocatable, intent(out) :: error
      type(error_type), allocatable :: probe
      real(wp) :: inf, big

      inf = ieee_value(1.0_wp, ieee_positive_inf)
      big = huge(1.0_wp)
      call check_close(probe, inf, inf)
      call expect(error, probe, .false., "+Inf vs +Inf")
      if (allocated(error)) return
      call check_close(probe, -inf, inf, rel=1.0_wp)
      call expect(error, probe, .true., "-Inf vs +Inf")
      if (allocated(error)) return
      call check_close(probe, big, inf, rel=1.0_wp)
      call expect(error, probe, .true., "huge vs +Inf")
      if (allocated(error)) return
      ! the difference overflows a double: must fail cleanly, not trap
      call check_close(probe, big, -big, rel=1.0_wp)
      call expect(error, probe, .true., "huge vs -huge")
      if (allocated(error)) return
      call check_close(probe, big, nearest(big, -1.0_wp), rel=1.0e-15_wp)
      call expect(error, probe, .false., "huge vs its predecessor")
   end subroutine test_close_extremes

   subroutine test_check_ulps(error)
      type(error_type), allocatable, intent(out) :: error
      type(error_type), allocatable :: probe
      real(wp) :: nan

      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      call check_ulps(probe, nearest(1.0_wp, 2.0_wp), 1.0_wp, 1.0_wp)
      call expect(error, probe, .false., "1 ulp within 1")
      if (allocated(error)) return
      call check_ulps(probe, nearest(1.0_wp, 2.0_wp), 1.0_wp, 0.5_wp, "half an ulp")
      call expect(error, probe, .true., "1 ulp beyond 0.5", "half an ulp")
      if (allocated(error)) return
      call check_ulps(probe, -2.0_wp, -2.0_wp - 2*spacing(2.0_wp), 2.0_wp)
      call expect(error, probe, .false., "negative values, 2 ulp within 2")
      if (allocated(error)) return
      call check_ulps(probe, 1.0_wp, 1.0_wp, 0.4_wp, expected_lo=0.5_wp*spacing(1.0_wp))
      call expect(error, probe, .true., "two-part reference, 0.5 ulp beyond 0.4")
      if (allocated(error)) return
      call check_ulps(probe, nan, 1.0_wp, 1.0e300_wp)
      call expect(error, probe, .true., "NaN actual", "NaN")
      if (allocated(error)) return
      call check_ulps(probe, nan, nan, 1.0_wp)
      call expect(error, probe, .true., "NaN vs NaN, not allowed")
      if (allocated(error)) return
      call check_ulps(probe, nan, nan, 1.0_wp, allow_nan=.true.)
      call expect(error, probe, .false., "NaN vs NaN, allowed")
   end subroutine test_check_ulps

   subroutine test_median(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: values(5), empty(0)

      values = [5.0_wp, -1.0_wp, 3.0_wp, 2.0_wp, 4.0_wp]
      call check(error, median(values) == 3.0_wp, "odd count")
      if (allocated(error)) return
      call check(error, all(values == [5.0_wp, -1.0_wp, 3.0_wp, 2.0_wp, 4.0_wp]), &
         & "input left in its order")
      if (allocated(error)) return
      call check(error, median(values(1:4)) == 2.5_wp, "even count: mean of the middle two")
      if (allocated(error)) return
      call check(error, median([7.0_wp]) == 7.0_wp, "single value")
      if (allocated(error)) return
      call check(error, median([huge(1.0_wp), huge(1.0_wp)]) == huge(1.0_wp), &
         & "no overflow between two huge values")
      if (allocated(error)) return
      call check(error, ieee_is_nan(median(empty)), "empty array gives NaN")
      if (allocated(error)) return
      call check(error, ieee_is_nan(median([1.0_wp, ieee_value(1.0_wp, ieee_quiet_nan)])), &
         & "NaN in the input gives NaN")
   end subroutine test_median

   subroutine test_format_real(error)
      type(error_type), allocatable, intent(out) :: error

      call check(error, format_real(0.1_wp), "1.0000000000000001E-001", "17 significant digits")
      if (allocated(error)) return
      call check(error, format_real(-2.5_wp), "-2.5000000000000000E+000", "negative value")
      if (allocated(error)) return
      call check(error, format_real(ieee_value(1.0_wp, ieee_negative_inf)) == "-Infinity", &
         & "negative infinity")
   end subroutine test_format_real

end module test_check
