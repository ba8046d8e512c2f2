! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_hertz: Hertz's constant, the effective mass and the velocities of
!> two bodies after an impact, against the mpmath and exact rational references of
!> test/reference/hertz.csv (make_hertz.py) over the whole range of doubles: typical
!> engineering values, log-uniform draws over all exponents (subnormals included),
!> Poisson's ratios next to -1 and 1/2, results next to overflow and underflow, and the
!> cases of issue 13 (items 7, 8, 13, 27). Each (function, region) is checked in ulps
!> of the exact value: the module promises correct rounding up to a few 1e-15 ulp
!> (`max_ulps`). Also: symmetry, the domain (NaN and statuses), and m2 = +inf.
!>
!> Safe under -ffpe-trap=invalid,zero,overflow: the functions raise none of these (that
!> is part of what is tested), and no NaN is compared here.
module test_hertz
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf, ieee_quiet_nan, &
      & ieee_is_nan
   use testdrive, only : new_unittest, unittest_type, error_type, test_failed
   use hcimpact_check, only : ulp_error, median, format_real, read_labelled_table, int_text, &
      & check_ulps
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_velocity, hcimpact_err_restitution
   use hcimpact_hertz, only : hertz_constant, effective_mass, two_body_velocities
   implicit none
   private

   public :: collect_hertz

   !> Largest error accepted, in ulps: correct rounding, up to the double-double
   !> evaluation's error (below 2^-45 ulp) when the exact value lies next to halfway
   !> between two doubles
   real(wp), parameter :: max_ulps = 0.5_wp + 2.0_wp**(-40)

   !> Region "cancel" of the velocities (a body stops, or nearly, after the impact): the
   !> three terms of v' = v1 s1 + v2 s2 -+ k V s cancel to the rounding of the inputs or
   !> to 0, and the double-double sum leaves an absolute error below this times the
   !> largest term (hcimpact_hertz; measured: 2^-104.8)
   real(wp), parameter :: cancel_bound = 2.0_wp**(-102)

   !> Name of the reference file inside the reference directory
   character(len=*), parameter :: reference_file = "hertz.csv"
   !> Length of the region and function names in the reference file
   integer, parameter :: name_len = 16
   !> Every (function, region) of the reference file; a test checks that it holds no other
   character(len=*), parameter :: cases(2, 23) = reshape([character(len=name_len) :: &
      & "hertz", "steel", "hertz", "wide", "hertz", "nu_edges", "hertz", "subnormal", &
      & "hertz", "extreme", "hertz", "edge", &
      & "effective_mass", "typical", "effective_mass", "wide", "effective_mass", "subnormal", &
      & "effective_mass", "near_overflow", "effective_mass", "edge", &
      & "v1_after", "typical", "v1_after", "wide", "v1_after", "subnormal", &
      & "v1_after", "near_overflow", "v1_after", "cancel", "v1_after", "edge", &
      & "v2_after", "typical", "v2_after", "wide", "v2_after", "subnormal", &
      & "v2_after", "near_overflow", "v2_after", "cancel", "v2_after", "edge"], [2, 23])

contains

   !> Collect all exported unit tests
   subroutine collect_hertz(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("reference-hertz", test_reference_hertz), &
         & new_unittest("reference-effective-mass", test_reference_effective_mass), &
         & new_unittest("reference-velocities", test_reference_velocities), &
         & new_unittest("reference-complete", test_reference_complete), &
         & new_unittest("issue-cases", test_issue_cases), &
         & new_unittest("symmetry", test_symmetry), &
         & new_unittest("domain", test_domain) &
         & ]
   end subroutine collect_hertz

   !> The reference rows of one function: inputs x(6, n), references ref(2, n), regions.
   subroutine load(error, func, region, x, ref)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: func
      character(len=name_len), allocatable, intent(out) :: region(:)
      real(wp), allocatable, intent(out) :: x(:, :), ref(:, :)
      character(len=name_len), allocatable :: all_region(:), all_func(:)
      real(wp), allocatable :: values(:, :)
      logical, allocatable :: mine(:)
      integer :: n
      call read_labelled_table(error, reference_file, 8, all_region, all_func, values)
      if (allocated(error)) return
      mine = all_func == func
      n = count(mine)
      if (n == 0) then
         call test_failed(error, reference_file // ": no rows of " // func)
         return
      end if
      region = pack(all_region, mine)
      x = reshape(pack(values(1:6, :), spread(mine, 1, 6)), [6, n])
      ref = reshape(pack(values(7:8, :), spread(mine, 1, 2)), [2, n])
   end subroutine load

   !> Errors in ulps of `actual` against ref, checked per region: largest <= max_ulps.
   !> Where `allowance` is positive, an absolute error up to half an ulp plus the
   !> allowance passes too (a cancelling sum, see test_reference_velocities).
   subroutine check_regions(error, func, region, actual, ref, x, allowance)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: func
      character(len=name_len), intent(in) :: region(:)
      real(wp), intent(in) :: actual(:), ref(:, :), x(:, :)
      real(wp), intent(in), optional :: allowance(:)
      real(wp), allocatable :: ulps(:)
      integer :: c, worst, i
      character(len=:), allocatable :: inputs
      allocate(ulps(size(actual)))
      ulps = ulp_error(actual, ref(1, :), ref(2, :))
      if (present(allowance)) then
         where (allowance > 0.0_wp)
            ! counted as passing (0 ulp) when within the allowance
            ulps = merge(0.0_wp, ulps, abs((actual - ref(1, :)) - ref(2, :)) &
               & <= 0.5_wp * spacing(abs(ref(1, :))) + allowance)
         end where
      end if
      do c = 1, size(cases, 2)
         if (cases(1, c) /= func) cycle
         if (.not. any(region == cases(2, c))) then
            call test_failed(error, func // ": the reference has no region " // trim(cases(2, c)))
            return
         end if
         worst = maxloc(ulps, 1, mask=region == cases(2, c))
         if (ulps(worst) <= max_ulps) cycle
         inputs = ""
         do i = 1, 6
            inputs = inputs // " " // format_real(x(i, worst))
         end do
         call test_failed(error, func // ", region " // trim(cases(2, c)) // ": error " &
            & // format_real(ulps(worst)) // " ulp > " // format_real(max_ulps) // " (median " &
            & // format_real(median(pack(ulps, region == cases(2, c)))) // ")", "inputs" &
            & // inputs // ": got " // format_real(actual(worst)) // ", exact " &
            & // format_real(ref(1, worst)) // " + " // format_real(ref(2, worst)))
         return
      end do
   end subroutine check_regions

   subroutine test_reference_hertz(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=name_len), allocatable :: region(:)
      real(wp), allocatable :: x(:, :), ref(:, :)
      call load(error, "hertz", region, x, ref)
      if (allocated(error)) return
      call check_regions(error, "hertz", region, hertz_constant(x(1, :), x(2, :), x(3, :), &
         & x(4, :), x(5, :), x(6, :)), ref, x)
   end subroutine test_reference_hertz

   subroutine test_reference_effective_mass(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=name_len), allocatable :: region(:)
      real(wp), allocatable :: x(:, :), ref(:, :)
      call load(error, "effective_mass", region, x, ref)
      if (allocated(error)) return
      call check_regions(error, "effective_mass", region, effective_mass(x(1, :), x(2, :)), &
         & ref, x)
   end subroutine test_reference_effective_mass

   subroutine test_reference_velocities(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: names(2) = [character(len=8) :: "v1_after", "v2_after"]
      character(len=name_len), allocatable :: region(:)
      real(wp), allocatable :: x(:, :), ref(:, :), after(:, :), allowance(:)
      integer, allocatable :: stat(:)
      integer :: i, j
      do j = 1, 2
         call load(error, names(j), region, x, ref)
         if (allocated(error)) return
         allocate(after(2, size(region)), stat(size(region)))
         call two_body_velocities(x(1, :), x(2, :), x(3, :), x(4, :), x(5, :), after(1, :), &
            & after(2, :), stat)
         if (any(stat /= hcimpact_ok)) then
            call test_failed(error, names(j) // ": status " // int_text(maxval(stat)) &
               & // " for valid inputs")
            return
         end if
         allowance = [(0.0_wp, i = 1, size(region))]
         where (region == "cancel") allowance = cancel_bound * largest_term(x(1, :), x(2, :), &
            & x(3, :), x(4, :), x(5, :))
         call check_regions(error, names(j), region, after(j, :), ref, x, allowance)
         if (allocated(error)) return
         deallocate(after, stat)
      end do
   end subroutine test_reference_velocities

   !> The largest of the three terms of the centre-of-mass form, |v1| s1, |v2| s2 and
   !> k (v1 - v2) max(s1, s2), for the moderate inputs of region "cancel" (x(1:5, i) =
   !> m1, m2, v1, v2, k).
   elemental function largest_term(m1, m2, v1, v2, k) result(t)
      real(wp), intent(in) :: m1, m2, v1, v2, k
      real(wp) :: t, s1, s2
      s1 = m1 / (m1 + m2)
      s2 = m2 / (m1 + m2)
      t = max(abs(v1) * s1, abs(v2) * s2, k * (v1 - v2) * max(s1, s2))
   end function largest_term

   !> The reference holds exactly the (function, region) pairs tested above.
   subroutine test_reference_complete(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=name_len), allocatable :: region(:), func(:)
      real(wp), allocatable :: values(:, :)
      integer :: i, c
      logical :: known
      call read_labelled_table(error, reference_file, 8, region, func, values)
      if (allocated(error)) return
      do i = 1, size(region)
         known = .false.
         do c = 1, size(cases, 2)
            known = known .or. (func(i) == cases(1, c) .and. region(i) == cases(2, c))
         end do
         if (.not. known) then
            call test_failed(error, reference_file // ": untested function/region " &
               & // trim(func(i)) // "/" // trim(region(i)))
            return
         end if
      end do
   end subroutine test_reference_complete

   !> Issue 13: the representable results that came out as 0, NaN or +-inf.
   subroutine test_issue_cases(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: v1, v2, inf
      integer :: stat
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      ! item 13: steel on steel with a subnormal second radius
      call check_ulps(error, hertz_constant(2.0e11_wp, 0.25_wp, 0.01452_wp, 2.0e11_wp, &
         & 0.25_wp, 5.0e-324_wp), 3.161256888156555e-151_wp, max_ulps, &
         & "hertz_constant with R2 = 5e-324", -1.5074047508986256e-167_wp)
      if (allocated(error)) return
      ! item 27: auxetic materials, nu next to -1
      call check_ulps(error, hertz_constant(2.0e11_wp, -0.9999999_wp, 0.01452_wp, 2.0e11_wp, &
         & -0.9999999999_wp, inf), 1.6050478684445405e+17_wp, max_ulps, &
         & "hertz_constant with nu near -1", -9.3044735965441_wp)
      if (allocated(error)) return
      ! item 8
      call check_ulps(error, effective_mass(1.0e300_wp, 1.0e-20_wp), 1.0e-20_wp, max_ulps, &
         & "effective_mass(1e300, 1e-20)")
      if (allocated(error)) return
      call check_ulps(error, effective_mass(huge(1.0_wp), 0.5_wp), 0.5_wp, max_ulps, &
         & "effective_mass(huge, 0.5)", -1.390671161567e-309_wp)
      if (allocated(error)) return
      call check_ulps(error, effective_mass(1.0_wp, 1.0e-310_wp), 1.0e-310_wp, max_ulps, &
         & "effective_mass(1, 1e-310)")
      if (allocated(error)) return
      ! item 7
      call two_body_velocities(1.0e300_wp, 1.0e-300_wp, 1.0_wp, 0.0_wp, 1.0_wp, v1, v2, stat)
      call check_pair("two_body_velocities(1e300, 1e-300, 1, 0, 1)", 1.0_wp, 2.0_wp)
      if (allocated(error)) return
      call two_body_velocities(1.0_wp, 5.0e-324_wp, 1.0_wp, 0.0_wp, 0.5_wp, v1, v2, stat)
      call check_pair("two_body_velocities(1, 5e-324, 1, 0, 0.5)", 1.0_wp, 1.5_wp)
      if (allocated(error)) return
      call two_body_velocities(1.0_wp, 1.0_wp, huge(1.0_wp), -huge(1.0_wp), 0.5_wp, v1, v2, stat)
      call check_pair("two_body_velocities(1, 1, huge, -huge, 0.5)", -0.5_wp * huge(1.0_wp), &
         & 0.5_wp * huge(1.0_wp))
   contains
      subroutine check_pair(what, expected1, expected2)
         character(len=*), intent(in) :: what
         real(wp), intent(in) :: expected1, expected2
         if (stat /= hcimpact_ok) then
            call test_failed(error, what // ": status " // int_text(stat))
            return
         end if
         call check_ulps(error, v1, expected1, max_ulps, what // ": v1'")
         if (allocated(error)) return
         call check_ulps(error, v2, expected2, max_ulps, what // ": v2'")
      end subroutine check_pair
   end subroutine test_issue_cases

   !> Swapping the bodies: the same constant and effective mass, bit for bit; and the
   !> velocities mirror (v -> -v swaps the roles of the bodies).
   subroutine test_symmetry(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=name_len), allocatable :: region(:)
      real(wp), allocatable :: x(:, :), ref(:, :)
      real(wp) :: a1, a2, b1, b2
      integer :: i, s1, s2
      call load(error, "hertz", region, x, ref)
      if (allocated(error)) return
      if (any(hertz_constant(x(1, :), x(2, :), x(3, :), x(4, :), x(5, :), x(6, :)) &
         & /= hertz_constant(x(4, :), x(5, :), x(6, :), x(1, :), x(2, :), x(3, :)))) then
         call test_failed(error, "hertz_constant changes when the bodies are swapped")
         return
      end if
      call load(error, "effective_mass", region, x, ref)
      if (allocated(error)) return
      do i = 1, size(region)
         if (x(2, i) > huge(1.0_wp)) cycle
         if (effective_mass(x(1, i), x(2, i)) /= effective_mass(x(2, i), x(1, i))) then
            call test_failed(error, "effective_mass changes when the masses are swapped", &
               & format_real(x(1, i)) // ", " // format_real(x(2, i)))
            return
         end if
      end do
      call load(error, "v1_after", region, x, ref)
      if (allocated(error)) return
      do i = 1, size(region)
         if (x(2, i) > huge(1.0_wp)) cycle
         call two_body_velocities(x(1, i), x(2, i), x(3, i), x(4, i), x(5, i), a1, a2, s1)
         call two_body_velocities(x(2, i), x(1, i), -x(4, i), -x(3, i), x(5, i), b1, b2, s2)
         if (s1 /= hcimpact_ok .or. s2 /= hcimpact_ok .or. a1 /= -b2 .or. a2 /= -b1) then
            call test_failed(error, "two_body_velocities does not mirror", "row " // int_text(i))
            return
         end if
      end do
   end subroutine test_symmetry

   !> Arguments outside the domain: NaN, or the documented status with NaN outputs.
   subroutine test_domain(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: inf, nan, v1, v2
      integer :: stat
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      if (.not. all(ieee_is_nan([ &
         & hertz_constant(0.0_wp, 0.3_wp, 0.01_wp, 2.0e11_wp, 0.25_wp, 0.01_wp), &
         & hertz_constant(inf, 0.3_wp, 0.01_wp, 2.0e11_wp, 0.25_wp, 0.01_wp), &
         & hertz_constant(2.0e11_wp, -1.0_wp, 0.01_wp, 2.0e11_wp, 0.25_wp, 0.01_wp), &
         & hertz_constant(2.0e11_wp, 0.50000000000000011_wp, 0.01_wp, 2.0e11_wp, 0.25_wp, 0.01_wp), &
         & hertz_constant(2.0e11_wp, 0.3_wp, 0.0_wp, 2.0e11_wp, 0.25_wp, 0.01_wp), &
         & hertz_constant(2.0e11_wp, 0.3_wp, inf, 2.0e11_wp, 0.25_wp, inf), &
         & hertz_constant(2.0e11_wp, 0.3_wp, nan, 2.0e11_wp, 0.25_wp, 0.01_wp), &
         & effective_mass(0.0_wp, 1.0_wp), effective_mass(inf, 1.0_wp), &
         & effective_mass(1.0_wp, -1.0_wp), effective_mass(1.0_wp, nan)]))) then
         call test_failed(error, "an argument outside the domain did not give NaN")
         return
      end if
      call expect(1.0_wp, 1.0_wp, nan, 0.0_wp, 0.5_wp, hcimpact_err_not_finite)
      call expect(1.0_wp, nan, 1.0_wp, 0.0_wp, 0.5_wp, hcimpact_err_not_finite)
      call expect(inf, 1.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, hcimpact_err_not_finite)
      call expect(0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, hcimpact_err_mass)
      call expect(1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, hcimpact_err_mass)
      call expect(1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.5_wp, hcimpact_err_velocity)
      call expect(1.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0000000000000002_wp, hcimpact_err_restitution)
      call expect(1.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, -0.0001_wp, hcimpact_err_restitution)
   contains
      subroutine expect(m1, m2, u1, u2, k, expected)
         real(wp), intent(in) :: m1, m2, u1, u2, k
         integer, intent(in) :: expected
         if (allocated(error)) return
         call two_body_velocities(m1, m2, u1, u2, k, v1, v2, stat)
         if (stat /= expected .or. .not. (ieee_is_nan(v1) .and. ieee_is_nan(v2))) &
            & call test_failed(error, "two_body_velocities: status " // int_text(stat) &
            & // ", expected " // int_text(expected) // " and NaN outputs")
      end subroutine expect
   end subroutine test_domain

end module test_hertz
