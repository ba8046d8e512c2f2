! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_legacy_damping: the eight damping rules of multibody codes against
!> the mpmath references of test/reference/legacy_damping.csv (make_legacy_damping.py),
!> e over (0, 1]: exactly 1, just below 1 (where 1 - e^2 cancels), uniform, small and
!> subnormal (where rules 4, 6, 7 overflow to +Inf); and the NaN of e outside the
!> domain and of unknown rules.
!>
!> Safe under -ffpe-trap=invalid,zero,overflow: the references' infinities are only
!> compared for equality, and the rules must not overflow on the way to +Inf.
module test_legacy_damping
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan, ieee_is_finite, ieee_value, &
      & ieee_quiet_nan
   use testdrive, only : new_unittest, unittest_type, error_type, test_failed
   use hcimpact_check, only : ulp_error, read_labelled_table, format_real, int_text
   use hcimpact_kinds, only : wp
   use hcimpact_legacy_damping, only : legacy_damping, n_damping_rules
   implicit none
   private

   public :: collect_legacy_damping

   !> Largest error allowed, in ulps of the exact value. Every rule takes at most
   !> five rounded operations on exact or nearly exact terms (and rule 5 the
   !> exponential of the C library): measured 2.8 ulp at worst (rule 5; rules 1 to 4
   !> and 6 to 8 at most 2.3). With 1 - e*e, rules 3 to 5 lost up to every digit.
   real(wp), parameter :: max_ulps = 3.5_wp

contains

   !> Collect all exported unit tests
   subroutine collect_legacy_damping(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("against-mpmath", test_reference), &
         & new_unittest("near-one", test_near_one), &
         & new_unittest("outside-the-domain", test_domain) &
         & ]
   end subroutine collect_legacy_damping

   !> Every row of the reference file: the error in ulps, the worst per rule.
   subroutine test_reference(error)
      type(error_type), allocatable, intent(out) :: error
      call check_rows(error, "")
   end subroutine test_reference

   !> The rows with e just below 1 on their own (issue 13: 16 ulp at e = 0.9857 and a
   !> relative error of 3.4e-9 at e = 1 - 7.7e-9 when 1 - e^2 was 1 - e*e).
   subroutine test_near_one(error)
      type(error_type), allocatable, intent(out) :: error
      call check_rows(error, "near1")
   end subroutine test_near_one

   !> Compare the rows of `region` (all rows when blank) with the references.
   subroutine check_rows(error, region)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: region
      character(len=16), allocatable :: regions(:), rules(:)
      real(wp), allocatable :: values(:, :)
      real(wp) :: e, chi, err, worst(n_damping_rules), worst_e(n_damping_rules)
      integer :: i, rule, rows, ios

      call read_labelled_table(error, "legacy_damping.csv", 3, regions, rules, values)
      if (allocated(error)) return
      worst = 0.0_wp
      worst_e = 0.0_wp
      rows = 0
      do i = 1, size(values, 2)
         if (len_trim(region) > 0 .and. regions(i) /= region) cycle
         read(rules(i)(2:), *, iostat=ios) rule
         if (ios /= 0 .or. rule < 1 .or. rule > n_damping_rules) then
            call test_failed(error, "legacy_damping.csv: unknown rule " // trim(rules(i)))
            return
         end if
         rows = rows + 1
         e = values(1, i)
         chi = legacy_damping(rule, e)
         if (.not. ieee_is_finite(values(2, i))) then
            ! overflow: +Inf, and nothing else
            if (ieee_is_finite(chi) .or. ieee_is_nan(chi)) then
               call test_failed(error, "rule " // int_text(rule) // " at e = " // &
                  & format_real(e) // ": " // format_real(chi) // ", expected +Inf")
               return
            end if
            if (chi < 0.0_wp) call test_failed(error, "rule " // int_text(rule) // &
               & ": -Inf at e = " // format_real(e))
            if (allocated(error)) return
            cycle
         end if
         err = ulp_error(chi, values(2, i), values(3, i))
         if (err > worst(rule)) then
            worst(rule) = err
            worst_e(rule) = e
         end if
      end do
      if (rows == 0) then
         call test_failed(error, "legacy_damping.csv holds no rows of region " // region)
         return
      end if
      do rule = 1, n_damping_rules
         if (worst(rule) > max_ulps) then
            call test_failed(error, "rule " // int_text(rule) // ": " // &
               & format_real(worst(rule)) // " ulp at e = " // format_real(worst_e(rule)) &
               & // " (at most " // format_real(max_ulps) // ")")
            return
         end if
      end do
   end subroutine check_rows

   !> NaN for e <= 0, e > 1, NaN e and rule numbers outside 1 .. 8; 0 at e = 1.
   subroutine test_domain(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: bad(5)
      integer :: rule, i
      bad = [0.0_wp, -0.0_wp, -1.0_wp, 1.0_wp + epsilon(1.0_wp), &
         & ieee_value(1.0_wp, ieee_quiet_nan)]
      do rule = 1, n_damping_rules
         do i = 1, size(bad)
            if (.not. ieee_is_nan(legacy_damping(rule, bad(i)))) then
               call test_failed(error, "rule " // int_text(rule) // ": no NaN outside (0, 1]")
               return
            end if
         end do
         if (legacy_damping(rule, 1.0_wp) /= 0.0_wp) then
            call test_failed(error, "rule " // int_text(rule) // ": chi(1) /= 0")
            return
         end if
      end do
      if (.not. (ieee_is_nan(legacy_damping(0, 0.5_wp)) .and. &
         & ieee_is_nan(legacy_damping(n_damping_rules + 1, 0.5_wp)))) then
         call test_failed(error, "no NaN for an unknown rule")
      end if
   end subroutine test_domain

end module test_legacy_damping
