! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_modified_cc: the modified Clenshaw-Curtis rule for
!> int_0^D (d/D)^(c-1) F(d) dd (Piessens and Branders 1973), c = 1/(n+1).
!>
!> References from test/reference/make_modified_cc.py (modified_cc.csv): the moments
!> J_k(y), complete (s = 1) and incomplete (s = (1+y)/2 < 1), from the exact power
!> expansion of T_k(2t-1) at 90 digits, and int_0^s t^(c-1) F(t) dt for F = e^t and
!> 1/(1+t). Besides accuracy: the rule is exact on polynomials of its degree, and
!> its acceptance test (cc_converged) accepts a resolved function and refuses one it
!> cannot resolve.
module test_modified_cc
   use testdrive, only : new_unittest, unittest_type, error_type, test_failed
   use hcimpact_check, only : format_real, reference_path
   use hcimpact_kinds, only : wp
   use hcimpact_modified_cc, only : cc_max_degree, cc_moments, cc_moments_pair, &
      & cc_coefficients, cc_sum, cc_tail, cc_converged, cc_plain, cc_end_share, cc_node, &
      & sym_m0, &
      & sym_moments, sym_partial_moments, sym_q0, sym_q0_near_end, sym_series_max
   use hcimpact_libm, only : log1p
   use hcimpact_double_double, only : dd_real, dd_log, dd_exp, two_sum, operator(+), &
      & operator(-), operator(*), operator(/)
   implicit none
   private

   public :: collect_modified_cc

   character(len=*), parameter :: reference_file = "modified_cc.csv"
   !> Exponents n of the reference file (c = 1/(n+1))
   real(wp), parameter :: exponents(8) = [0.1_wp, 0.5_wp, 1.0_wp, 1.5_wp, 2.0_wp, 3.0_wp, &
      & 7.0_wp, 12.0_wp]
   !> Bound on the moment errors in units of J_0 of the same s: moment_unit (1 + k^2/8).
   !> The forward recurrence is stable, but its rounding errors accumulate: about
   !> 4e-17 k^2 J_0 up to k = 24 for the smallest s (5e-4), then linearly (5e-14 at 48)
   real(wp), parameter :: moment_unit = 4.0e-16_wp
   !> Bound on the errors of the symmetric weight's moments, in units of the largest
   !> |Q_j| of the same (n, y): sym_unit (1 + k/8) (the recurrence damps its errors; they
   !> grow with k only through the driving terms). Measured: 3.7e-16 (1 + k/8) at worst,
   !> n = 0.1, y = 0.95, k = 3 (the rounding of s and of the driving terms 2 s T_k(y))
   real(wp), parameter :: sym_unit = 5.0e-16_wp
   !> Bound on the relative error of M_0 (sym_m0): its Chebyshev table is good to 5e-19,
   !> its double-double steps to about 1e-18; 1e-17 is a tenth of an ulp
   real(wp), parameter :: m0_bound = 1.0e-17_wp
   !> Bound on the relative error of a resolved integral (the rule's rounding: the
   !> moments' errors times the coefficients, and the noise of the transform)
   real(wp), parameter :: integral_bound = 1.0e-15_wp

   !> Rows of the reference file
   type :: reference_table
      character(len=8), allocatable :: kind(:)
      real(wp), allocatable :: n(:), s(:), value(:)
      integer, allocatable :: k(:)
   end type reference_table

contains

   !> Collect all exported unit tests
   subroutine collect_modified_cc(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("complete-moments", test_complete_moments), &
         & new_unittest("incomplete-moments", test_incomplete_moments), &
         & new_unittest("chebyshev-exactness", test_exactness), &
         & new_unittest("integral-exp", test_integral_exp), &
         & new_unittest("integral-reciprocal", test_integral_recip), &
         & new_unittest("accepts-resolved", test_accepts_resolved), &
         & new_unittest("refuses-unresolved", test_refuses_unresolved), &
         & new_unittest("moments-pair", test_moments_pair), &
         & new_unittest("symmetric-m0", test_symmetric_m0), &
         & new_unittest("symmetric-moments", test_symmetric_moments), &
         & new_unittest("plain-rule", test_plain_rule) &
         & ]
   end subroutine collect_modified_cc

   !> Read the reference file.
   subroutine read_table(table, error)
      type(reference_table), intent(out) :: table
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: path
      character(len=256) :: line, message
      integer :: unit, stat, pass, rows

      path = reference_path(reference_file)
      open(newunit=unit, file=path, status="old", action="read", iostat=stat, iomsg=message)
      if (stat /= 0) then
         call test_failed(error, "cannot open the reference file " // path, trim(message), &
            & "set HCIMPACT_REFERENCE_DIR to the directory of " // reference_file)
         return
      end if
      ! two passes: count the rows, then read them
      do pass = 1, 2
         rows = 0
         do
            read(unit, '(a)', iostat=stat) line
            if (is_iostat_end(stat)) exit
            if (stat /= 0) then
               call test_failed(error, path // ": unreadable line")
               close(unit)
               return
            end if
            if (len_trim(line) == 0 .or. line(1:1) == "#") cycle
            rows = rows + 1
            if (pass == 2) then
               read(line, *, iostat=stat) table%kind(rows), table%n(rows), table%s(rows), &
                  & table%k(rows), table%value(rows)
               if (stat /= 0) then
                  call test_failed(error, path // ": malformed line", trim(line))
                  close(unit)
                  return
               end if
            end if
         end do
         if (pass == 1) then
            allocate(table%kind(rows), table%n(rows), table%s(rows), table%k(rows), &
               & table%value(rows))
            rewind(unit)
         end if
      end do
      close(unit)
      if (rows < 1000) call test_failed(error, path // ": too few rows")
   end subroutine read_table

   !> Moments of the degree-48 recurrence for exponent n at share s, as the impact
   !> code calls it (c = 1/(n+1) rounded, 1/c = n+1 exact, C = 2 s^c).
   subroutine moments_of(n, s, moment)
      real(wp), intent(in) :: n, s
      real(wp), intent(out) :: moment(0:cc_max_degree)
      real(wp) :: c
      c = 1.0_wp / (n + 1.0_wp)
      call cc_moments(c, n + 1.0_wp, s, 2.0_wp * s**c, cc_max_degree, moment)
   end subroutine moments_of

   !> Moments against the references, for s = 1 (complete) or s < 1 (incomplete).
   subroutine check_moments(error, complete)
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in) :: complete
      type(reference_table) :: table
      real(wp) :: moment(0:cc_max_degree), scale, err, bound, worst
      integer :: i, checked, worst_row

      call read_table(table, error)
      if (allocated(error)) return
      checked = 0
      worst = 0.0_wp
      worst_row = 0
      do i = 1, size(table%value)
         if (table%kind(i) /= "moment") cycle
         if (complete .neqv. table%s(i) >= 1.0_wp) cycle
         ! J_0 of this (n, s) is the row k of the same block with k = 0
         call moments_of(table%n(i), table%s(i), moment)
         scale = abs(table%value(i - table%k(i)))
         bound = moment_unit * (1.0_wp + real(table%k(i), wp)**2 / 8.0_wp)
         err = abs(moment(table%k(i)) - table%value(i)) / (bound * scale)
         call track_worst(err, i, worst, worst_row, checked)
      end do
      call report_worst(error, table, "moment J_k(s)", "s", checked, 300, worst, worst_row)
   end subroutine check_moments

   subroutine test_complete_moments(error)
      type(error_type), allocatable, intent(out) :: error
      call check_moments(error, .true.)
   end subroutine test_complete_moments

   subroutine test_incomplete_moments(error)
      type(error_type), allocatable, intent(out) :: error
      call check_moments(error, .false.)
   end subroutine test_incomplete_moments

   !> The interpolant of T_m at the nodes of degree N is T_m itself: a_k = delta_km
   !> (2 for m = 0 and m = N, whose terms the sum halves), and the rule gives J_m.
   subroutine test_exactness(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: degrees(4) = [12, 16, 24, 48]
      real(wp) :: f(0:cc_max_degree), a(0:cc_max_degree), moment(0:cc_max_degree), x, t0, &
         & t1, t2, expected, total
      integer :: id, n, m, j, k

      call moments_of(1.5_wp, 1.0_wp, moment)
      do id = 1, size(degrees)
         n = degrees(id)
         do m = 0, n
            do j = 0, n
               ! T_m(x_j) by the recurrence (x_j from the module's own node table)
               x = cc_node(j * (cc_max_degree / n))
               t0 = 1.0_wp
               t1 = x
               if (m == 0) t1 = 1.0_wp
               do k = 2, m
                  t2 = 2.0_wp * x * t1 - t0
                  t0 = t1
                  t1 = t2
               end do
               f(j) = t1
            end do
            call cc_coefficients(n, f, a)
            do k = 0, n
               expected = 0.0_wp
               if (k == m) expected = merge(2.0_wp, 1.0_wp, m == n .or. m == 0)
               if (abs(a(k) - expected) > 1.0e-13_wp) then
                  call test_failed(error, "interpolant of T_m is not T_m", "degree " // &
                     & format_real(real(n, wp)) // ", m = " // format_real(real(m, wp)) // &
                     & ": a_k = " // format_real(a(k)) // " at k = " // format_real(real(k, wp)))
                  return
               end if
            end do
            total = cc_sum(n, a, moment)
            if (abs(total - moment(m)) > 1.0e-13_wp * moment(0)) then
               call test_failed(error, "rule of degree " // format_real(real(n, wp)) // &
                  & " misses J_m for m = " // format_real(real(m, wp)))
               return
            end if
         end do
      end do
   end subroutine test_exactness

   !> Integral over [0, s] (D = 1) of t^(c-1) F(t) by the rule of degree `degree`,
   !> F given by `which` (1: e^t, 2: 1/(1+t), 3: 1/((t - 1/2)^2 + 1e-4), 4: 1 + t).
   subroutine rule(which, n, s, degree, total, converged, tail)
      integer, intent(in) :: which, degree
      real(wp), intent(in) :: n, s
      real(wp), intent(out) :: total, tail
      logical, intent(out) :: converged
      real(wp) :: f(0:cc_max_degree), a(0:cc_max_degree), moment(0:cc_max_degree), &
         & complete(0:cc_max_degree), t
      integer :: j

      do j = 0, degree
         t = cc_end_share(j * (cc_max_degree / degree))
         select case (which)
         case (1)
            f(j) = exp(t)
         case (2)
            f(j) = 1.0_wp / (1.0_wp + t)
         case (3)
            f(j) = 1.0_wp / ((t - 0.5_wp)**2 + 1.0e-4_wp)
         case default
            f(j) = 1.0_wp + t
         end select
      end do
      call cc_coefficients(degree, f, a)
      call moments_of(n, 1.0_wp, complete)
      call moments_of(n, s, moment)
      ! the rule on [0, 1] is (1/2) sum'' a_k J_k, so with t = d/D the factor D/2
      total = 0.5_wp * cc_sum(degree, a, moment)
      tail = 0.5_wp * cc_tail(degree, a, complete)
      converged = cc_converged(degree, a, complete, cc_sum(degree, a, complete), &
         & maxval(abs(f(0:degree))), epsilon(1.0_wp))
   end subroutine rule

   !> Integrals of the reference file for F = e^t (which = 1) or 1/(1+t) (which = 2),
   !> by the rules of degree 24 and 48, complete and over [0, s].
   subroutine check_integrals(error, which, name)
      type(error_type), allocatable, intent(out) :: error
      integer, intent(in) :: which
      character(len=*), intent(in) :: name
      type(reference_table) :: table
      real(wp) :: total, tail, err
      logical :: converged
      integer :: i, id, checked
      integer, parameter :: degrees(2) = [24, 48]

      call read_table(table, error)
      if (allocated(error)) return
      checked = 0
      do i = 1, size(table%value)
         if (table%kind(i) /= name) cycle
         do id = 1, size(degrees)
            call rule(which, table%n(i), table%s(i), degrees(id), total, converged, tail)
            err = abs(total - table%value(i)) / abs(table%value(i))
            if (err > integral_bound .or. .not. converged) then
               call test_failed(error, name // " integral off or not accepted", "n = " // &
                  & format_real(table%n(i)) // ", s = " // format_real(table%s(i)) // &
                  & ", degree " // format_real(real(degrees(id), wp)) // ": relative error " &
                  & // format_real(err))
               return
            end if
            checked = checked + 1
         end do
      end do
      if (checked < 2 * 3 * size(exponents)) &
         & call test_failed(error, "too few " // name // " rows in the reference file")
   end subroutine check_integrals

   subroutine test_integral_exp(error)
      type(error_type), allocatable, intent(out) :: error
      call check_integrals(error, 1, "exp")
   end subroutine test_integral_exp

   subroutine test_integral_recip(error)
      type(error_type), allocatable, intent(out) :: error
      call check_integrals(error, 2, "recip")
   end subroutine test_integral_recip

   !> A straight line is resolved by the rule of degree 12 (its coefficients beyond
   !> the first two are rounding noise); e^t is not at degree 12 for the full
   !> precision but is at 24, and the tail bound then covers the actual error.
   subroutine test_accepts_resolved(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: total, tail, exact, c
      logical :: converged
      integer :: i

      do i = 1, size(exponents)
         c = 1.0_wp / (exponents(i) + 1.0_wp)
         call rule(4, exponents(i), 1.0_wp, 12, total, converged, tail)
         ! int_0^1 t^(c-1) (1 + t) dt = 1/c + 1/(c+1)
         exact = (exponents(i) + 1.0_wp) + 1.0_wp / (c + 1.0_wp)
         if (.not. converged .or. abs(total - exact) > 4.0_wp * epsilon(1.0_wp) * exact) then
            call test_failed(error, "1 + t: degree 12 not accepted or inexact", "n = " // &
               & format_real(exponents(i)) // ": " // format_real(total) // " against " // &
               & format_real(exact))
            return
         end if
         call rule(1, exponents(i), 1.0_wp, 24, total, converged, tail)
         if (.not. converged) then
            call test_failed(error, "e^t: degree 24 not accepted", "n = " // &
               & format_real(exponents(i)))
            return
         end if
         call rule(1, exponents(i), 1.0_wp, 12, total, converged, tail)
         if (converged) then
            call test_failed(error, "e^t: degree 12 accepted at full precision", "tail " // &
               & format_real(tail) // ", n = " // format_real(exponents(i)))
            return
         end if
      end do
   end subroutine test_accepts_resolved

   !> A near pole at t = 1/2 +- 0.01 i: no rule up to degree 48 resolves it, and each
   !> must say so, with a tail bound that is not below the actual error.
   subroutine test_refuses_unresolved(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: degrees(4) = [12, 16, 24, 48]
      real(wp) :: total, tail, best, best_tail
      logical :: converged
      integer :: i, id

      do i = 1, size(exponents)
         ! the best estimate at hand: the rule of degree 48 (itself off)
         call rule(3, exponents(i), 1.0_wp, cc_max_degree, best, converged, best_tail)
         do id = 1, size(degrees)
            call rule(3, exponents(i), 1.0_wp, degrees(id), total, converged, tail)
            if (converged) then
               call test_failed(error, "unresolved function accepted", "n = " // &
                  & format_real(exponents(i)) // ", degree " // &
                  & format_real(real(degrees(id), wp)))
               return
            end if
            if (tail < 1.0e-6_wp * abs(total)) then
               call test_failed(error, "tail bound of an unresolved function is small", &
                  & "n = " // format_real(exponents(i)) // ": " // format_real(tail))
               return
            end if
            if (degrees(id) < cc_max_degree .and. abs(total - best) > 10.0_wp &
               & * (tail + best_tail)) then
               call test_failed(error, "tail bound below the error", "n = " // &
                  & format_real(exponents(i)) // ", degree " // &
                  & format_real(real(degrees(id), wp)))
               return
            end if
         end do
      end do
   end subroutine test_refuses_unresolved

   !> cc_moments_pair gives, to the bit, what two cc_moments calls give (the complete
   !> moments, s = 1 and C = 2, and the incomplete ones for s, C): `impact` relies on it
   !> for the time of the peak. Degrees 12, 24, 48; several exponents and shares.
   subroutine test_moments_pair(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: exponents(4) = [0.1_wp, 1.0_wp, 1.5_wp, 7.42_wp]
      real(wp), parameter :: shares(4) = [0.999_wp, 0.75_wp, 0.3_wp, 5.0e-4_wp]
      integer, parameter :: degrees(4) = [12, 16, 24, 48]
      real(wp) :: complete(0:cc_max_degree), partial(0:cc_max_degree)
      real(wp) :: one(0:cc_max_degree), two(0:cc_max_degree), c, big_c
      integer :: i, j, k, n

      do i = 1, size(exponents)
         c = 1.0_wp / (exponents(i) + 1.0_wp)
         do j = 1, size(shares)
            big_c = 2.0_wp * shares(j)**c
            do k = 1, size(degrees)
               n = degrees(k)
               call cc_moments_pair(c, exponents(i) + 1.0_wp, shares(j), big_c, n, complete, &
                  & partial)
               call cc_moments(c, exponents(i) + 1.0_wp, 1.0_wp, 2.0_wp, n, one)
               call cc_moments(c, exponents(i) + 1.0_wp, shares(j), big_c, n, two)
               if (any(complete(0:n) /= one(0:n)) .or. any(partial(0:n) /= two(0:n))) then
                  call test_failed(error, "cc_moments_pair differs from cc_moments", &
                     & "n = " // format_real(exponents(i)) // ", s = " &
                     & // format_real(shares(j)) // ", degree " // format_real(real(n, wp)))
                  return
               end if
            end do
         end do
      end do
   end subroutine test_moments_pair

   !> The symmetric weight's moments as the whole-contact rule of the impact forms them
   !> (alpha = n/(n+1), 1 - alpha = 1/(n+1) in double-double; Q_0 by the series for
   !> |y| <= 1/2, else from the impact end with 2^(-alpha) u^(1-alpha) in
   !> double-double), for y = -1 the complete moments M_k.
   subroutine symmetric_of(n, y, moment, m0)
      real(wp), intent(in) :: n, y
      real(wp), intent(out) :: moment(0:cc_max_degree)
      type(dd_real), intent(out) :: m0
      type(dd_real), parameter :: ln2 = dd_real(0.6931471805599453_wp, &
         & 2.3190468138462996e-17_wp)
      type(dd_real) :: np1, a, alpha, u, pref, q0
      real(wp) :: nu, s, inv_den(cc_max_degree)
      np1 = two_sum(n, 1.0_wp)
      a = 1.0_wp / np1
      alpha = n * a
      nu = (1.0_wp - 2.0_wp * alpha%hi) - 2.0_wp * alpha%lo
      m0 = sym_m0(a, np1)
      call sym_moments(nu, m0%hi, cc_max_degree, moment, inv_den)
      if (y <= -1.0_wp) return
      if (y <= sym_series_max) then
         s = exp(a%hi * log1p(-y * y))
         q0 = sym_q0(alpha%hi, dd_real(y, 0.0_wp), m0)
      else
         u = 1.0_wp - dd_real(y, 0.0_wp)
         s = exp(a%hi * (log(u%hi) + log1p(y)))
         pref = dd_exp(a * dd_log(u) - alpha * ln2)
         q0 = sym_q0_near_end(alpha%hi, u%hi, np1, pref)
      end if
      call sym_partial_moments(nu, y, s, q0%hi, cc_max_degree, inv_den, moment)
   end subroutine symmetric_of

   !> M_0 = sqrt(pi) Gamma(1/(n+1))/Gamma(1/2 + 1/(n+1)) rounds to the reference (to
   !> within m0_bound), for the eight exponents of the reference file (rows y = -1, k = 0)
   subroutine test_symmetric_m0(error)
      type(error_type), allocatable, intent(out) :: error
      type(reference_table) :: table
      real(wp) :: moment(0:cc_max_degree), err, worst
      type(dd_real) :: m0
      integer :: i, checked
      call read_table(table, error)
      if (allocated(error)) return
      checked = 0
      worst = 0.0_wp
      do i = 1, size(table%value)
         if (table%kind(i) /= "sym" .or. table%s(i) > -1.0_wp .or. table%k(i) /= 0) cycle
         call symmetric_of(table%n(i), -1.0_wp, moment, m0)
         ! the reference is read into a double (rounded once): M_0 = hi + lo must lie
         ! within half an ulp of it (plus m0_bound), i.e. round to it
         err = abs((m0%hi - table%value(i)) + m0%lo) / table%value(i) &
            & - 0.5_wp * spacing(table%value(i)) / table%value(i)
         worst = max(worst, err)
         checked = checked + 1
         if (err > m0_bound) then
            call test_failed(error, "M_0 off", "n = " // format_real(table%n(i)) // &
               & ": relative error " // format_real(err))
            return
         end if
      end do
      if (checked < size(exponents)) call test_failed(error, "too few M_0 rows")
   end subroutine test_symmetric_m0

   !> Complete and incomplete moments of the symmetric weight against the references:
   !> every k <= 48, y in {-1, -0.4, 0, 0.3, 0.5, 0.6, 0.8, 0.95} (both forms of Q_0)
   subroutine test_symmetric_moments(error)
      type(error_type), allocatable, intent(out) :: error
      type(reference_table) :: table
      real(wp) :: moment(0:cc_max_degree), err, worst, scale
      type(dd_real) :: m0
      integer :: i, checked, worst_row
      call read_table(table, error)
      if (allocated(error)) return
      checked = 0
      worst = 0.0_wp
      worst_row = 0
      do i = 1, size(table%value)
         if (table%kind(i) /= "sym") cycle
         call symmetric_of(table%n(i), table%s(i), moment, m0)
         ! the largest |Q_j| of the same (n, y): next to y = 1, Q_0 is small against
         ! the driving terms 2 s T_k(y) of the recurrence
         scale = maxval(abs(table%value(i - table%k(i):i - table%k(i) + cc_max_degree)))
         err = abs(moment(table%k(i)) - table%value(i)) &
            & / (sym_unit * (1.0_wp + real(table%k(i), wp) / 8.0_wp) * scale)
         call track_worst(err, i, worst, worst_row, checked)
      end do
      call report_worst(error, table, "symmetric moment Q_k(y)", "y", checked, 3000, worst, &
         & worst_row)
   end subroutine test_symmetric_moments

   !> Count a checked row and keep the largest error and its row (the caller starts
   !> from worst = 0, worst_row = 0, checked = 0)
   pure subroutine track_worst(err, row, worst, worst_row, checked)
      real(wp), intent(in) :: err
      integer, intent(in) :: row
      real(wp), intent(inout) :: worst
      integer, intent(inout) :: worst_row, checked
      if (err > worst) then
         worst = err
         worst_row = row
      end if
      checked = checked + 1
   end subroutine track_worst

   !> Fail if fewer than `least` rows were checked or the largest error (in units of
   !> its bound) exceeds 1, naming the row's n, its second column (`second`) and k
   subroutine report_worst(error, table, what, second, checked, least, worst, worst_row)
      type(error_type), allocatable, intent(out) :: error
      type(reference_table), intent(in) :: table
      character(len=*), intent(in) :: what, second
      integer, intent(in) :: checked, least, worst_row
      real(wp), intent(in) :: worst
      integer :: i
      if (checked < least) then
         call test_failed(error, "too few rows for " // what // ": the reference file is &
            &incomplete")
      else if (worst > 1.0_wp) then
         i = worst_row
         call test_failed(error, what // " off", "n = " // format_real(table%n(i)) &
            & // ", " // second // " = " // format_real(table%s(i)) // ", k = " &
            & // format_real(real(table%k(i), wp)) // ": error " // format_real(worst) &
            & // " times the bound")
      end if
   end subroutine report_worst

   !> The plain rule by its weights (cc_plain) against the transform (cc_coefficients
   !> and cc_sum with the moments 2/(1 - k^2), k even) and against exact integrals over
   !> [-1, 1]: e^x (e - 1/e), 1/(2 - x) (ln 3), a constant, T_n (2/(1 - n^2): the
   !> weight of the last coefficient, which a smooth function hardly tests) and values
   !> at random (the transform's integral of their interpolant); its last two
   !> coefficients are the transform's. Degrees 12, 24 and 48.
   subroutine test_plain_rule(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: degrees(3) = [12, 24, 48]
      real(wp) :: f(0:cc_max_degree), a(0:cc_max_degree), moment(0:cc_max_degree)
      real(wp) :: a_last(2), total, exact, by_transform, fmax, x
      integer :: idegree, n, j, k, kind
      character(len=8), parameter :: names(5) = [character(len=8) :: "exp", "1/(2-x)", &
         & "1", "T_n", "random"]
      real(wp) :: noise

      do k = 0, cc_max_degree
         moment(k) = 0.0_wp
         if (mod(k, 2) == 0) moment(k) = 2.0_wp / real(1 - k * k, wp)
      end do
      do idegree = 1, size(degrees)
         n = degrees(idegree)
         do kind = 1, 5
            do j = 0, n
               x = cc_node(j * (cc_max_degree / n))
               select case (kind)
               case (1)
                  f(j) = exp(x)
               case (2)
                  f(j) = 1.0_wp / (2.0_wp - x)
               case (3)
                  f(j) = 0.75_wp
               case (4)
                  ! T_n(x_j) = cos(pi j) = (-1)^j
                  f(j) = real(1 - 2 * mod(j, 2), wp)
               case default
                  call random_number(noise)
                  f(j) = 0.5_wp + noise
               end select
            end do
            fmax = maxval(abs(f(0:n)))
            call cc_plain(n, f, total, a_last)
            call cc_coefficients(n, f, a)
            by_transform = cc_sum(n, a, moment)
            select case (kind)
            case (1)
               exact = exp(1.0_wp) - exp(-1.0_wp)
            case (2)
               exact = log(3.0_wp)
            case (3)
               exact = 1.5_wp
            case (4)
               exact = 2.0_wp / real(1 - n * n, wp)
            case default
               exact = by_transform
            end select
            ! the weights are positive and sum to 2: rounding of n + 1 terms; the
            ! transform's sum of n + 1 coefficients times moments (sum |J_k| < 3): a
            ! bound of the order of n ulps of fmax either way (a fixed 16 ulps failed on
            ! random values in one build: 8 ulps apart at degree 24)
            if (abs(total - by_transform) > 4.0_wp * n * epsilon(1.0_wp) * fmax) then
               call test_failed(error, "plain rule: weights and transform disagree", &
                  & trim(names(kind)) // ", degree " // format_real(real(n, wp)) // ": " // &
                  & format_real(total) // " against " // format_real(by_transform))
               return
            end if
            ! (both are sums of n + 1 terms of up to 2 fmax/n, in different orders)
            if (abs(a_last(1) - a(n - 1)) > 4.0_wp * n * epsilon(1.0_wp) * fmax &
               & .or. abs(a_last(2) - a(n)) > 4.0_wp * n * epsilon(1.0_wp) * fmax) then
               call test_failed(error, "plain rule: last coefficients", &
                  & trim(names(kind)) // ", degree " // format_real(real(n, wp)) // ": " // &
                  & format_real(a_last(1)) // ", " // format_real(a_last(2)) // &
                  & " against " // format_real(a(n - 1)) // ", " // format_real(a(n)))
               return
            end if
            ! 1/(2 - x) (its pole at 2: rho = 2 + sqrt(3), an error of rho^(-n), 2e-14
            ! at degree 24) is resolved at 48
            if (kind == 2 .and. n < 48) cycle
            ! random values have no exact integral but the transform's, compared above
            if (kind == 5) cycle
            if (abs(total - exact) > 4.0_wp * epsilon(1.0_wp) * fmax) then
               call test_failed(error, "plain rule: integral", trim(names(kind)) // &
                  & ", degree " // format_real(real(n, wp)) // ": " // format_real(total) // &
                  & " against " // format_real(exact))
               return
            end if
         end do
      end do
   end subroutine test_plain_rule

end module test_modified_cc
