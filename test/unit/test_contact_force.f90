! SPDX-License-Identifier: Apache-2.0
!> Tests of the contact-force element (hcimpact_force_element) and the power law it
!> evaluates (hcimpact_power_force):
!> - every field against the mpmath references of test/reference/contact_force.csv
!>   (make_contact_force.py: exact double inputs over the physical range, next to the
!>   clamp, small x with n < 1, the whole double range, edges), in ulps;
!> - the derivatives against central differences of the element's own force and
!>   against forward-mode dual numbers of the formula (an independent evaluation);
!> - the clamp, no contact, the pair and wall forms (against quadruple precision),
!>   the law form, the array form, bad input;
!> - the energy bookkeeping of a whole impact integrated with the element by a
!>   classical Runge-Kutta method, and its agreement with the closed forms.
module test_contact_force
   use, intrinsic :: iso_fortran_env, only : output_unit
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan, ieee_is_finite, ieee_value, &
      & ieee_quiet_nan, ieee_positive_inf
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_stiffness, &
      & hcimpact_err_exponent, hcimpact_err_damping, hcimpact_err_domain, &
      & hcimpact_err_elastic_law
   use hcimpact_force_element, only : contact_force_type, contact_force, contact_force_pair, &
      & contact_force_wall
   use hcimpact_elastic, only : elastic_law, power_law
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_check, only : ulp_error, median, format_real, read_labelled_table
   implicit none
   private

   public :: collect_contact_force

   !> Quadruple precision (gfortran's real(16)) for the pair test's references
   integer, parameter :: qp = selected_real_kind(30)
   !> Goal of every field against the references, in ulp
   real(wp), parameter :: goal_ulps = 4.0_wp
   !> Names of the fields, in the order of the reference columns
   character(len=*), parameter :: field_name(5) = [character(len=11) :: "force", &
      & "dforce_dx", "dforce_dv", "potential", "dissipation"]

   !> A dual number a + a' eps (eps^2 = 0): the formula differentiated forward
   type :: dual
      real(wp) :: v = 0.0_wp, d = 0.0_wp
   end type dual

   !> A law that gives NaN (bad-input)
   type, extends(elastic_law) :: broken_law
   contains
      procedure :: force => broken_value
      procedure :: potential => broken_value
      procedure :: force_derivative => broken_value
   end type broken_law

contains

   !> Collect all exported unit tests
   subroutine collect_contact_force(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         new_unittest("reference-accuracy", test_reference_accuracy), &
         new_unittest("derivatives-finite-differences", test_finite_differences), &
         new_unittest("derivatives-dual-numbers", test_dual_numbers), &
         new_unittest("clamp", test_clamp), &
         new_unittest("no-contact", test_no_contact), &
         new_unittest("pair-and-wall", test_pair_and_wall), &
         new_unittest("law-form", test_law_form), &
         new_unittest("array-form", test_array_form), &
         new_unittest("bad-input", test_bad_input), &
         new_unittest("huge-exponent", test_huge_exponent), &
         new_unittest("energy-and-closed-forms", test_energy_and_closed_forms) &
         ]
   end subroutine collect_contact_force

   !> Every field within goal_ulps of the references, region by region (the largest
   !> and median errors are printed).
   subroutine test_reference_accuracy(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=16), allocatable :: region(:), func(:)
      real(wp), allocatable :: values(:, :), errs(:, :)
      type(contact_force_type) :: e
      real(wp) :: got(5)
      integer :: i, j, stat, worst(5)
      character(len=*), parameter :: regions(6) = [character(len=9) :: "typical", "clamp", &
         & "small_x", "extreme", "edges", "underflow"]
      integer :: r

      call read_labelled_table(error, "contact_force.csv", 15, region, func, values)
      if (allocated(error)) return
      allocate(errs(5, size(region)))
      do i = 1, size(region)
         call contact_force(values(1, i), values(2, i), values(3, i), values(4, i), &
            & values(5, i), e, stat)
         if (stat /= hcimpact_ok) then
            call test_failed(error, "row " // trim(format_real(real(i, wp))) // &
               & ": status " // trim(format_real(real(stat, wp))))
            return
         end if
         got = [e%force, e%dforce_dx, e%dforce_dv, e%potential, e%dissipation]
         do j = 1, 5
            errs(j, i) = ulp_error(got(j), values(4 + 2 * j, i), values(5 + 2 * j, i))
         end do
      end do
      do r = 1, size(regions)
         write(output_unit, '(a)', advance="no") "  contact_force " // regions(r) // ":"
         do j = 1, 5
            write(output_unit, '(1x, a, " max ", f6.2, " median ", f5.2)', advance="no") &
               & trim(field_name(j)), maxval(errs(j, :), mask=region == regions(r)), &
               & median(pack(errs(j, :), region == regions(r)))
         end do
         write(output_unit, '(a)') " (ulp)"
      end do
      do j = 1, 5
         worst(j) = maxloc(errs(j, :), 1)
         if (errs(j, worst(j)) > goal_ulps) then
            call test_failed(error, trim(field_name(j)) // " off by " // &
               & trim(format_real(errs(j, worst(j)))) // " ulp at row " // &
               & trim(format_real(real(worst(j), wp))) // " (" // trim(region(worst(j))) // &
               & ")", "goal " // trim(format_real(goal_ulps)) // " ulp")
            return
         end if
      end do
   end subroutine test_reference_accuracy

   !> dF/dx and dF/dv against central differences of the element's force, on states
   !> over the physical range, next to the clamp (without crossing it) and with x -> 0
   !> for n < 1 (relative steps 1e-6: truncation ~1e-12, rounding ~1e-10).
   subroutine test_finite_differences(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e, ep, em
      real(wp) :: c, n, b, x, v, h, fd, r(6)
      integer :: i

      call random_seed_fixed()
      do i = 1, 3000
         call random_number(r)
         c = 10.0_wp**(12.0_wp * r(1))
         n = 0.1_wp + 3.0_wp * r(2)
         b = 10.0_wp**(-3.0_wp + 4.0_wp * r(3))
         x = 10.0_wp**(-9.0_wp + 7.0_wp * r(4))
         if (mod(i, 3) == 0) then
            ! x -> 0 with n < 1: dF/dx grows without bound
            n = 0.1_wp + 0.85_wp * r(2)
            x = 10.0_wp**(-300.0_wp * r(4))
         end if
         select case (mod(i, 2))
         case (0)
            v = sign(10.0_wp**(-4.0_wp + 6.0_wp * r(5)), r(6) - 0.5_wp)
            if (1.0_wp + b * v < 1.0e-3_wp) v = abs(v)
         case default
            ! 1 + b v = delta in (1e-5, 1e-3), above the clamp
            v = -(1.0_wp - 10.0_wp**(-5.0_wp + 2.0_wp * r(5))) / b
         end select
         call contact_force(c, n, b, x, v, e)
         h = 1.0e-6_wp
         call contact_force(c, n, b, x * (1.0_wp + h), v, ep)
         call contact_force(c, n, b, x * (1.0_wp - h), v, em)
         fd = (ep%force - em%force) / (x * (1.0_wp + h) - x * (1.0_wp - h))
         call check(error, abs(fd - e%dforce_dx) <= 1.0e-7_wp * abs(e%dforce_dx), &
            & "dF/dx against a central difference: " // trim(format_real(e%dforce_dx)) // &
            & " vs " // trim(format_real(fd)))
         if (allocated(error)) return
         ! the steps as taken (v +- h rounded), not as asked
         h = 1.0e-6_wp * (1.0_wp + b * v) / b
         call contact_force(c, n, b, x, v + h, ep)
         call contact_force(c, n, b, x, v - h, em)
         fd = (ep%force - em%force) / ((v + h) - (v - h))
         call check(error, abs(fd - e%dforce_dv) <= 1.0e-7_wp * abs(e%dforce_dv), &
            & "dF/dv against a central difference: " // trim(format_real(e%dforce_dv)) // &
            & " vs " // trim(format_real(fd)))
         if (allocated(error)) return
      end do
   end subroutine test_finite_differences

   !> dF/dx and dF/dv against dual numbers: c x^n (1 + b v) evaluated with x + eps (then
   !> v + eps) gives the derivatives from the chain rule of each operation, independent
   !> of the element's formulas n F/x and b c x^n.
   subroutine test_dual_numbers(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e
      type(dual) :: fx, fv
      real(wp) :: c, n, b, x, v, r(5)
      integer :: i

      call random_seed_fixed()
      do i = 1, 3000
         call random_number(r)
         c = 10.0_wp**(12.0_wp * r(1))
         n = 0.05_wp + 4.0_wp * r(2)
         b = 10.0_wp**(-3.0_wp + 4.0_wp * r(3))
         x = 10.0_wp**(-50.0_wp * r(4))
         v = sign(10.0_wp**(-4.0_wp + 6.0_wp * r(5)), r(1) - 0.5_wp)
         if (1.0_wp + b * v <= 1.0e-3_wp) v = -v
         call contact_force(c, n, b, x, v, e)
         fx = dual_force(c, n, b, dual(x, 1.0_wp), dual(v, 0.0_wp))
         fv = dual_force(c, n, b, dual(x, 0.0_wp), dual(v, 1.0_wp))
         call check(error, abs(fx%v - e%force) <= 1.0e-14_wp * e%force &
            & .and. abs(fx%d - e%dforce_dx) <= 1.0e-13_wp * e%dforce_dx &
            & .and. abs(fv%d - e%dforce_dv) <= 1.0e-13_wp * e%dforce_dv, &
            & "element against dual numbers at x = " // trim(format_real(x)) // ", n = " // &
            & trim(format_real(n)))
         if (allocated(error)) return
      end do
   end subroutine test_dual_numbers

   !> Found by the fuzzer (bench/fuzz): exponents near the largest double made n ln x
   !> overflow inside the logarithmic product, and the element returned NaN in every
   !> field with status OK (c = 1.7e-77, n = 2.5e307, x = 3.8e-10). c x^n, n c x^(n-1)
   !> and c x^(n+1)/(n+1) are 0 (below the smallest double) for x < 1 and +inf for
   !> x > 1 there, as the header promises for results beyond the range.
   subroutine test_huge_exponent(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e
      integer :: stat, i
      real(wp), parameter :: exponents(4) = [2.4945427586795597e307_wp, 1.0e300_wp, &
         & 1.0e20_wp, huge(1.0_wp)]
      do i = 1, size(exponents)
         call contact_force(1.727973921681797e-77_wp, exponents(i), 9.2244979367616184e18_wp, &
            & 3.7653080653399229e-10_wp, 0.0_wp, e, stat)
         call check(error, stat == hcimpact_ok .and. e%force == 0.0_wp &
            & .and. e%dforce_dx == 0.0_wp .and. e%dforce_dv == 0.0_wp &
            & .and. e%potential == 0.0_wp .and. e%dissipation == 0.0_wp, &
            & "x < 1, n = " // trim(format_real(exponents(i))) // ": F " &
            & // trim(format_real(e%force)) // ", dF/dx " // trim(format_real(e%dforce_dx)) &
            & // ", potential " // trim(format_real(e%potential)))
         if (allocated(error)) return
         call contact_force(1.0_wp, exponents(i), 0.0_wp, 2.0_wp, 1.0_wp, e, stat)
         call check(error, stat == hcimpact_ok .and. e%force > huge(1.0_wp) &
            & .and. e%dforce_dx > huge(1.0_wp) .and. e%potential > huge(1.0_wp), &
            & "x = 2, n = " // trim(format_real(exponents(i))) // ": F " &
            & // trim(format_real(e%force)) // ", dF/dx " // trim(format_real(e%dforce_dx)) &
            & // ", potential " // trim(format_real(e%potential)))
         if (allocated(error)) return
      end do
   end subroutine test_huge_exponent

   !> The clamp: F = 0 and both derivatives 0 where 1 + b v <= 0; the dissipation
   !> -f(x) v there; F continuous across the kink (it tends to 0 from above).
   subroutine test_clamp(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e, above
      real(wp), parameter :: c = 1.0e9_wp, n = 1.5_wp, b = 2.0_wp, x = 1.0e-4_wp
      real(wp) :: v, f0

      f0 = c * x**n
      ! 1 + b v = -1
      call contact_force(c, n, b, x, -1.0_wp, e)
      call check(error, e%force == 0.0_wp .and. e%dforce_dx == 0.0_wp .and. &
         & e%dforce_dv == 0.0_wp, "clamped: no force, no derivatives")
      if (allocated(error)) return
      call check(error, abs(e%dissipation - f0) <= 4.0_wp * epsilon(1.0_wp) * f0, &
         & "clamped: dissipation -f(x) v = f(x)")
      if (allocated(error)) return
      ! exactly at the kink (b v = -1 exactly): the clamped side
      call contact_force(c, n, b, x, -0.5_wp, e)
      call check(error, e%force == 0.0_wp .and. e%dforce_dx == 0.0_wp .and. &
         & e%dforce_dv == 0.0_wp, "at the kink: the clamped side")
      if (allocated(error)) return
      ! v one ulp beyond -1/b: 1 + b v = -2**-52, clamped
      call contact_force(c, n, b, x, -nearest(0.5_wp, 1.0_wp), e)
      call check(error, e%force == 0.0_wp, "v one ulp beyond -1/b: clamped")
      if (allocated(error)) return
      ! v one ulp inside: 1 + b v = 2**-53 exactly (the naive 1 + b*v gives 2**-53 too,
      ! but only because b = 2 makes b*v exact; the references test the general case)
      v = -nearest(0.5_wp, -1.0_wp)
      call contact_force(c, n, b, x, v, above)
      call check(error, above%force > 0.0_wp .and. &
         & abs(above%force - f0 * 2.0_wp**(-53)) <= 4.0_wp * epsilon(1.0_wp) * above%force, &
         & "v one ulp inside: F = f(x) 2**-53, got " // trim(format_real(above%force)))
      if (allocated(error)) return
      call check(error, above%dforce_dv > 0.0_wp .and. &
         & abs(above%dforce_dv - b * f0) <= 4.0_wp * epsilon(1.0_wp) * b * f0, &
         & "dF/dv = b f(x) right above the kink")
      if (allocated(error)) return
      ! clamp = .false.: the formula as written, pulling where 1 + b v < 0
      call contact_force(c, n, b, x, -1.0_wp, e, clamp=.false.)
      call check(error, abs(e%force + f0) <= 4.0_wp * epsilon(1.0_wp) * f0 .and. &
         & abs(e%dforce_dx + n * f0 / x) <= 4.0_wp * epsilon(1.0_wp) * n * f0 / x .and. &
         & abs(e%dforce_dv - b * f0) <= 4.0_wp * epsilon(1.0_wp) * b * f0 .and. &
         & abs(e%dissipation - b * f0) <= 4.0_wp * epsilon(1.0_wp) * b * f0, &
         & "unclamped at 1 + b v = -1: F = -f(x), dissipation b f(x) v^2")
   end subroutine test_clamp

   !> x <= 0 (incl. -0): every field is 0, whatever v.
   subroutine test_no_contact(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e
      real(wp) :: xs(4), vs(3)
      integer :: i, j

      xs = [0.0_wp, -0.0_wp, -1.0e-300_wp, -huge(1.0_wp)]
      vs = [-1.0e10_wp, 0.0_wp, 1.0e10_wp]
      do i = 1, size(xs)
         do j = 1, size(vs)
            call contact_force(1.0e10_wp, 0.5_wp, 0.3_wp, xs(i), vs(j), e)
            call check(error, e%force == 0.0_wp .and. e%dforce_dx == 0.0_wp .and. &
               & e%dforce_dv == 0.0_wp .and. e%potential == 0.0_wp .and. &
               & e%dissipation == 0.0_wp, "x <= 0: no contact")
            if (allocated(error)) return
         end do
      end do
   end subroutine test_no_contact

   !> The pair and wall forms: x and v from positions far from the origin and close to
   !> each other, against the element at the exact x (quadruple precision) and, next
   !> to the clamp, against F evaluated in quadruple precision.
   subroutine test_pair_and_wall(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e, ref, w
      real(wp), parameter :: c = 5.0e9_wp, n = 1.5_wp, b = 0.2_wp, d = 0.02_wp
      real(wp) :: q1, q2, v1, v2, x, r(3)
      real(qp) :: xq, fq
      integer :: i, stat

      call random_seed_fixed()
      do i = 1, 500
         call random_number(r)
         q1 = 1.0e3_wp * (1.0_wp + r(1))
         q2 = q1 + d - 1.0e-6_wp * (0.5_wp + r(2))
         v1 = 1.0_wp + r(3)
         v2 = -0.5_wp
         xq = real(d, qp) + real(q1, qp) - real(q2, qp)
         x = real(xq, wp)
         call contact_force_pair(c, n, b, d, q1, v1, q2, v2, e, stat)
         call contact_force(c, n, b, x, v1 - v2, ref)
         call check(error, stat == hcimpact_ok .and. &
            & abs(e%force - ref%force) <= 2.0_wp * spacing(ref%force), &
            & "pair: F at the exact deformation")
         if (allocated(error)) return
         ! the same body against a wall at q2 on its right, and a body at q2 against a
         ! wall at q1 on its left
         call contact_force_wall(c, n, b, d, q1, v1 - v2, q2, 1, w, stat)
         ! (the wall form takes v1 - v2 rounded: the pair form's exact difference may
         ! differ from it in the last bits)
         call check(error, stat == hcimpact_ok .and. close_to(w%force, e%force, 2), &
            & "right wall")
         if (allocated(error)) return
         call contact_force_wall(c, n, b, d, q2, v2 - v1, q1, -1, w, stat)
         call check(error, stat == hcimpact_ok .and. close_to(w%force, e%force, 2), &
            & "left wall")
         if (allocated(error)) return
      end do
      ! next to the clamp: 1 + b (v1 - v2) ~ 1e-12, with v1 - v2 not a double (its
      ! rounding alone would move 1 + b v by 1e-4 of itself)
      q1 = 0.0_wp
      q2 = d - 1.0e-5_wp
      v1 = -3.0_wp
      v2 = 2.0_wp - 5.0e-12_wp
      call contact_force_pair(c, n, b, d, q1, v1, q2, v2, e, stat)
      xq = real(d, qp) + real(q1, qp) - real(q2, qp)
      fq = real(c, qp) * xq**real(n, qp) * (1.0_qp + real(b, qp) * (real(v1, qp) - &
         & real(v2, qp)))
      call check(error, stat == hcimpact_ok .and. fq > 0.0_qp .and. &
         & abs(real(e%force, qp) - fq) <= 8.0_qp * epsilon(1.0_wp) * fq, &
         & "pair next to the clamp: F from the exact v1 - v2 (" // &
         & trim(format_real(e%force)) // " vs " // trim(format_real(real(fq, wp))) // ")")
   end subroutine test_pair_and_wall

   !> The law form with hcimpact_elastic's power_law agrees with the power form.
   subroutine test_law_form(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e, el
      type(power_law) :: law
      real(wp) :: r(5), c, n, b, x, v
      integer :: i, stat

      call random_seed_fixed()
      do i = 1, 1000
         call random_number(r)
         c = 10.0_wp**(12.0_wp * r(1))
         n = 0.3_wp + 3.0_wp * r(2)
         b = 10.0_wp**(-3.0_wp + 4.0_wp * r(3))
         x = 10.0_wp**(-9.0_wp + 7.0_wp * r(4))
         v = sign(10.0_wp**(-4.0_wp + 5.0_wp * r(5)), r(1) - 0.5_wp)
         law = power_law(stiffness=c, exponent=n)
         call contact_force(c, n, b, x, v, e)
         call contact_force(law, b, x, v, el, stat)
         call check(error, stat == hcimpact_ok .and. close_to(el%force, e%force, 4) .and. &
            & close_to(el%dforce_dx, e%dforce_dx, 4) .and. &
            & close_to(el%dforce_dv, e%dforce_dv, 4) .and. &
            & close_to(el%potential, e%potential, 4) .and. &
            & close_to(el%dissipation, e%dissipation, 6), "law form against the power form")
         if (allocated(error)) return
      end do
   end subroutine test_law_form

   !> The elemental call over arrays equals the scalar calls.
   subroutine test_array_form(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: m = 257
      real(wp) :: x(m), v(m)
      type(contact_force_type) :: many(m), one
      integer :: stats(m), i

      call random_seed_fixed()
      call random_number(x)
      call random_number(v)
      x = 1.0e-3_wp * (x - 0.2_wp)
      v = 10.0_wp * (v - 0.5_wp)
      call contact_force(2.0e10_wp, 1.5_wp, 0.3_wp, x, v, many, stats)
      do i = 1, m
         call contact_force(2.0e10_wp, 1.5_wp, 0.3_wp, x(i), v(i), one)
         call check(error, stats(i) == hcimpact_ok .and. many(i)%force == one%force .and. &
            & many(i)%dforce_dx == one%dforce_dx .and. many(i)%dissipation == one%dissipation, &
            & "array form = scalar form")
         if (allocated(error)) return
      end do
   end subroutine test_array_form

   !> Bad parameters and states: the statuses of the library, NaN fields.
   subroutine test_bad_input(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_force_type) :: e
      type(broken_law) :: broken
      real(wp) :: nan, inf
      integer :: stat

      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      call expect(1.0_wp, 1.5_wp, 0.1_wp, 1.0e-3_wp, nan, hcimpact_err_not_finite, "v NaN")
      if (allocated(error)) return
      call expect(1.0_wp, 1.5_wp, 0.1_wp, inf, 1.0_wp, hcimpact_err_not_finite, "x Inf")
      if (allocated(error)) return
      call expect(nan, 1.5_wp, 0.1_wp, 1.0e-3_wp, 1.0_wp, hcimpact_err_not_finite, "c NaN")
      if (allocated(error)) return
      call expect(0.0_wp, 1.5_wp, 0.1_wp, 1.0e-3_wp, 1.0_wp, hcimpact_err_stiffness, "c = 0")
      if (allocated(error)) return
      call expect(-1.0_wp, 1.5_wp, 0.1_wp, 1.0e-3_wp, 1.0_wp, hcimpact_err_stiffness, "c < 0")
      if (allocated(error)) return
      call expect(1.0_wp, 1.0e-7_wp, 0.1_wp, 1.0e-3_wp, 1.0_wp, hcimpact_err_exponent, &
         & "n below 1e-6")
      if (allocated(error)) return
      call expect(1.0_wp, -1.5_wp, 0.1_wp, 1.0e-3_wp, 1.0_wp, hcimpact_err_exponent, "n < 0")
      if (allocated(error)) return
      call expect(1.0_wp, 1.5_wp, -0.1_wp, 1.0e-3_wp, 1.0_wp, hcimpact_err_damping, "b < 0")
      if (allocated(error)) return
      call expect(1.0_wp, 1.5_wp, inf, 1.0e-3_wp, 1.0_wp, hcimpact_err_not_finite, "b Inf")
      if (allocated(error)) return
      call contact_force_wall(1.0_wp, 1.5_wp, 0.1_wp, 0.01_wp, 0.0_wp, 1.0_wp, 0.005_wp, 0, &
         & e, stat)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(e%force), "wall side 0")
      if (allocated(error)) return
      call contact_force_pair(1.0_wp, 1.5_wp, 0.1_wp, 0.01_wp, nan, 1.0_wp, 0.0_wp, 0.0_wp, &
         & e, stat)
      call check(error, stat == hcimpact_err_not_finite .and. ieee_is_nan(e%dissipation), &
         & "pair: q1 NaN")
      if (allocated(error)) return
      ! bodies apart by more than the largest double: no contact, not an error
      call contact_force_pair(1.0_wp, 1.5_wp, 0.1_wp, 0.01_wp, -huge(1.0_wp), 0.0_wp, &
         & huge(1.0_wp), 0.0_wp, e, stat)
      call check(error, stat == hcimpact_ok .and. e%force == 0.0_wp, &
         & "pair: bodies 2 huge(1.0) apart")
      if (allocated(error)) return
      ! overlapping by more than the largest double: a status
      call contact_force_pair(1.0_wp, 1.5_wp, 0.1_wp, 0.01_wp, huge(1.0_wp), 0.0_wp, &
         & -huge(1.0_wp), 0.0_wp, e, stat)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(e%force), &
         & "pair: overlap beyond the double range")
      if (allocated(error)) return
      call contact_force(broken, 0.1_wp, 1.0e-3_wp, 1.0_wp, e, stat)
      call check(error, stat == hcimpact_err_elastic_law .and. ieee_is_nan(e%force), &
         & "law returning NaN")
      if (allocated(error)) return
      call contact_force(broken, -0.1_wp, 1.0e-3_wp, 1.0_wp, e, stat)
      call check(error, stat == hcimpact_err_damping .and. ieee_is_nan(e%potential), &
         & "law form, b < 0")

   contains

      subroutine expect(c, n, b, x, v, status, what)
         real(wp), intent(in) :: c, n, b, x, v
         integer, intent(in) :: status
         character(len=*), intent(in) :: what
         call contact_force(c, n, b, x, v, e, stat)
         call check(error, stat == status .and. ieee_is_nan(e%force) .and. &
            & ieee_is_nan(e%dforce_dx) .and. ieee_is_nan(e%dforce_dv) .and. &
            & ieee_is_nan(e%potential) .and. ieee_is_nan(e%dissipation), &
            & what // ": status and NaN fields")
      end subroutine expect
   end subroutine test_bad_input

   !> One impact integrated with the element by the classical Runge-Kutta method (fixed
   !> steps, the end of contact located by cubic Hermite interpolation): kinetic +
   !> potential + dissipated energy stays the initial kinetic energy, and restitution,
   !> contact time, maximum compression and peak force agree with the closed forms.
   subroutine test_energy_and_closed_forms(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: contacts(4)
      type(outcome_type) :: outcome
      real(wp) :: y(3), yold(3), k1(3), k2(3), k3(3), k4(3), h, t, e0, drift, xmax, fmax
      real(wp) :: theta, tc, vend, m
      type(contact_force_type) :: e
      integer :: i, step, stat
      integer, parameter :: steps = 40000

      contacts = [contact_type(0.1_wp, 1.7135e10_wp, 1.5_wp, 0.1_wp, 5.0_wp), &
         & contact_type(2.0_wp, 3.0e6_wp, 1.0_wp, 0.8_wp, 2.0_wp), &
         & contact_type(0.05_wp, 4.0e11_wp, 2.5_wp, 0.5_wp, 9.0_wp), &
         & contact_type(1.0_wp, 1.0e8_wp, 1.5_wp, 0.0_wp, 1.0_wp)]
      do i = 1, size(contacts)
         call impact(contacts(i), outcome, stat)
         if (stat /= hcimpact_ok) then
            call test_failed(error, "closed forms failed")
            return
         end if
         m = contacts(i)%mass
         h = 1.1_wp * outcome%contact_time / steps
         ! state: x, v, dissipated energy
         y = [0.0_wp, contacts(i)%velocity, 0.0_wp]
         e0 = 0.5_wp * m * contacts(i)%velocity**2
         t = 0.0_wp
         drift = 0.0_wp
         xmax = 0.0_wp
         fmax = 0.0_wp
         tc = -1.0_wp
         do step = 1, 2 * steps
            yold = y
            k1 = rate(y)
            k2 = rate(y + 0.5_wp * h * k1)
            k3 = rate(y + 0.5_wp * h * k2)
            k4 = rate(y + h * k3)
            y = y + h / 6.0_wp * (k1 + 2.0_wp * k2 + 2.0_wp * k3 + k4)
            t = t + h
            call contact_force(contacts(i)%stiffness, contacts(i)%exponent, &
               & contacts(i)%damping, y(1), y(2), e)
            xmax = max(xmax, y(1))
            fmax = max(fmax, e%force)
            if (y(1) > 0.0_wp) drift = max(drift, abs(0.5_wp * m * y(2)**2 + e%potential &
               & + y(3) - e0) / e0)
            if (y(1) <= 0.0_wp .and. step > 1) then
               ! end of contact between the last two steps: Hermite cubic in x
               theta = hermite_root(yold(1), yold(2), y(1), y(2), h)
               tc = t - h + theta * h
               vend = yold(2) + theta * (y(2) - yold(2))
               exit
            end if
         end do
         write(output_unit, '(a, i0, a, es9.2, a, 4es9.2)') "  contact ", i, &
            & ": energy bookkeeping drift ", drift, &
            & "; relative differences from the closed forms (contact time, x_max, " // &
            & "peak force, k):", abs(tc / outcome%contact_time - 1.0_wp), &
            & abs(xmax / outcome%max_compression - 1.0_wp), &
            & abs(fmax / outcome%peak_force - 1.0_wp), &
            & abs(sqrt(max(0.0_wp, 1.0_wp - (yold(3) + theta * (y(3) - yold(3))) / e0)) &
            & / outcome%restitution - 1.0_wp)
         call check(error, drift < 1.0e-9_wp, "energy bookkeeping drifts by " // &
            & trim(format_real(drift)))
         if (allocated(error)) return
         call check(error, tc > 0.0_wp .and. abs(tc - outcome%contact_time) < &
            & 1.0e-7_wp * outcome%contact_time .and. abs(xmax - outcome%max_compression) &
            & < 1.0e-8_wp * outcome%max_compression .and. abs(fmax - outcome%peak_force) < &
            & 1.0e-7_wp * outcome%peak_force, "integrated impact against the closed forms: " &
            & // "contact time " // trim(format_real(tc)) // " vs " // &
            & trim(format_real(outcome%contact_time)))
         if (allocated(error)) return
         ! the velocity at the end, from the energy (the interpolation of v is only
         ! linear): k = sqrt(1 - dissipated/E0)
         vend = sqrt(max(0.0_wp, 1.0_wp - (yold(3) + theta * (y(3) - yold(3))) / e0))
         call check(error, abs(vend - outcome%restitution) < 1.0e-7_wp, &
            & "restitution from the integrated dissipation: " // trim(format_real(vend)) // &
            & " vs " // trim(format_real(outcome%restitution)))
         if (allocated(error)) return
      end do

   contains

      !> (x', v', E_d') of the body: x' = v, m v' = -F, E_d' = dissipation
      function rate(s) result(ds)
         real(wp), intent(in) :: s(3)
         real(wp) :: ds(3)
         type(contact_force_type) :: f
         call contact_force(contacts(i)%stiffness, contacts(i)%exponent, &
            & contacts(i)%damping, s(1), s(2), f)
         ds = [s(2), -f%force / m, f%dissipation]
      end function rate
   end subroutine test_energy_and_closed_forms

   !> The root in (0, 1] of the cubic Hermite interpolant of x from (x0, v0) to (x1, v1)
   !> over a step h (bisection: x0 > 0 >= x1).
   pure function hermite_root(x0, v0, x1, v1, h) result(theta)
      real(wp), intent(in) :: x0, v0, x1, v1, h
      real(wp) :: theta
      real(wp) :: lo, hi, s, p
      integer :: it
      lo = 0.0_wp
      hi = 1.0_wp
      do it = 1, 100
         s = 0.5_wp * (lo + hi)
         p = (2.0_wp * s**3 - 3.0_wp * s**2 + 1.0_wp) * x0 + (s**3 - 2.0_wp * s**2 + s) * h * v0 &
            & + (-2.0_wp * s**3 + 3.0_wp * s**2) * x1 + (s**3 - s**2) * h * v1
         if (p > 0.0_wp) then
            lo = s
         else
            hi = s
         end if
      end do
      theta = 0.5_wp * (lo + hi)
   end function hermite_root

   !> c x^n (1 + b v) in dual numbers
   elemental function dual_force(c, n, b, x, v) result(f)
      real(wp), intent(in) :: c, n, b
      type(dual), intent(in) :: x, v
      type(dual) :: f, xn, s
      ! x^n: value x^n, derivative n x^(n-1) x'
      xn%v = x%v**n
      xn%d = n * x%v**(n - 1.0_wp) * x%d
      s%v = 1.0_wp + b * v%v
      s%d = b * v%d
      f%v = c * xn%v * s%v
      f%d = c * (xn%d * s%v + xn%v * s%d)
   end function dual_force

   !> |a - b| within k ulps of b (or both 0)
   elemental function close_to(a, b, k) result(ok)
      real(wp), intent(in) :: a, b
      integer, intent(in) :: k
      logical :: ok
      ok = abs(a - b) <= k * spacing(max(abs(b), tiny(1.0_wp)))
   end function close_to

   !> A fixed seed: the same states in every run
   subroutine random_seed_fixed()
      integer :: n, i
      call random_seed(size=n)
      call random_seed(put=[(20261125 + 7919 * i, i = 1, n)])
   end subroutine random_seed_fixed

   pure function broken_value(self, x) result(y)
      class(broken_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = ieee_value(x, ieee_quiet_nan)
   end function broken_value

end module test_contact_force
