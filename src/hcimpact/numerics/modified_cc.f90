! SPDX-License-Identifier: Apache-2.0
!> Modified Clenshaw-Curtis quadrature for integrals with an algebraic end singularity,
!>
!>     int_0^D (d/D)^(c-1) F(d) dd,      0 < c <= 1,  F analytic on [0, D],
!>
!> the method of Piessens and Branders ("The evaluation and application of some modified
!> moments", BIT 13, 1973, 443-450; QUADPACK's QAWS, Piessens et al. 1983): F is
!> interpolated at the Chebyshev points x_j = cos(pi j/N) of [-1, 1] (d = D (1 + x)/2),
!> its Chebyshev coefficients a_k come from a discrete cosine transform, and the integral
!> is (D/2) sum'' a_k J_k with the modified moments
!>
!>     J_k(y) = int_-1^y ((1 + x)/2)^(c-1) T_k(x) dx,
!>
!> complete (y = 1) for a whole interval, incomplete (y < 1) for the part [0, d]
!> of it, d = D (1 + y)/2, from the same coefficients (no new evaluation of F).
!>
!> The moments obey a three-term recurrence, derived here from
!> 2 T_m = T'_(m+1)/(m+1) - T'_(m-1)/(m-1) and the integration by parts
!> int_-1^y w (1+x) T'_m dx = C T_m(y) - c J_m(y),  w = ((1+x)/2)^(c-1),
!> C = (1+y) w(y) = 2 ((1+y)/2)^c (no boundary term at -1, since c > 0):
!>
!>     (m+1+c) J_(m+1) = C T_(m+1)(y) - C T_(m-1)(y) (m+1)/(m-1) - 2 (m+1) J_m
!>                      + (c+1-m) (m+1)/(m-1) J_(m-1),          m >= 2,
!>
!> with J_0 = C/c, J_1 = C (2s/(c+1) - 1/c) (s = (1+y)/2) and
!> (2+c) J_2 = C T_2(y) - 4 J_1 - 2 J_0. Its homogeneous solutions grow only linearly
!> ((r+1)^2 = 0 asymptotically), so the forward recurrence is stable: checked against
!> mpmath (test/unit/test_modified_cc.f90) for 0.1 <= n <= 12 (c = 1/(n+1)),
!> -0.999 <= y <= 1, k <= 48, the error grows like 4e-17 k^2 J_0(y) up to k = 24
!> (2e-14 J_0 there, 3e-15 J_0 for the complete moments), then linearly (5e-14 J_0 at
!> k = 48); the coefficients a_k it multiplies decay geometrically, so the moments'
!> share of the error of an accepted rule stays near 1e-16 of the integral.
!>
!> The rules are nested: N = 12, 24, 48 share their nodes, so a rule that does not
!> converge hands all its values to the next. Convergence is judged by the last two
!> coefficients (an analytic F has geometrically decaying a_k; their sum bounds the
!> neglected tail and the aliasing error when the decay is faster than 1/2 per degree).
!>
!> The whole contact of a small-beta impact has a singularity of the same order at both
!> ends: its rule uses the symmetric weight (1 - x^2)^(-alpha) (alpha = 1 - c) and the
!> moments M_k = int_-1^1 (1 - x^2)^(-alpha) T_k dx, Q_k(y) = int_y^1 (same) dx. With
!> x = cos(theta), nu = 1 - 2 alpha, and the integration by parts of
!> d/dtheta [sin^(nu+1) cos(k theta)] they obey (theta_y = acos y, s = (1 - y^2)^(1-alpha))
!>
!>     (k+1+nu) Q_(k+1) = 2 s T_k(y) + (k-1-nu) Q_(k-1),    Q_1 = s/(nu+1),
!>
!> and M_k the same with s = 0 (M_1 = 0); |k-1-nu| < k+1+nu: the forward recurrence
!> damps its errors. M_0 = sqrt(pi) Gamma(1-alpha)/Gamma(3/2-alpha) from a Chebyshev
!> table (tools/make_gegenbauer_table.py); Q_0(y) = M_0/2 - int_0^y (1 - x^2)^(-alpha) dx,
!> the last by its power series for |y| <= 1/2.
!> See doc/quadrature.md.
module hcimpact_modified_cc
   use hcimpact_kinds, only : wp
   use hcimpact_double_double, only : dd_real, two_sum, operator(+), operator(-), &
      & operator(*)
   implicit none
   private

   public :: cc_max_degree, cc_moments, cc_moments_pair, cc_coefficients, cc_sum, cc_tail, &
      & cc_converged, cc_plain
   public :: cc_end_share, cc_turn_share, cc_node, inv_end_share_hi, inv_end_share_lo
   public :: sym_m0, sym_moments, sym_partial_moments, sym_q0, sym_q0_near_end, sym_series_max

   !> Largest degree N of the rules (nodes of every rule are among its N + 1)
   integer, parameter :: cc_max_degree = 48

   integer, parameter :: qp = selected_real_kind(30)
   integer, parameter :: xp = merge(qp, wp, qp > 0)
   integer :: i_, j_
   real(xp), parameter :: pi_xp = acos(-1.0_xp)

   !> cos(pi j k/48), j, k = 0 .. 48 (folded by the compiler, rounded once)
   real(wp), parameter :: cosines(0:cc_max_degree, 0:cc_max_degree) = reshape( &
      & [((real(cos(pi_xp * real(i_ * j_, xp) / cc_max_degree), wp), i_ = 0, cc_max_degree), &
      & j_ = 0, cc_max_degree)], [cc_max_degree + 1, cc_max_degree + 1])
   !> (1 + x_j)/2 = cos^2(pi j/96): node j's distance from the singular end, per unit D
   real(wp), parameter :: cc_end_share(0:cc_max_degree) = &
      & [(real(cos(pi_xp * i_ / (2 * cc_max_degree))**2, wp), i_ = 0, cc_max_degree)]
   !> 2/(1 + x_j) = 1/cos^2(pi j/96), j <= 24, as the double nearest to it and the
   !> double nearest to the rest: a product with both costs about one rounding, as a
   !> division by cc_end_share did (the callers scale by it at every node)
   real(wp), parameter :: inv_end_share_hi(0:cc_max_degree / 2) = &
      & [(real(1.0_xp / cos(pi_xp * i_ / (2 * cc_max_degree))**2, wp), &
      & i_ = 0, cc_max_degree / 2)]
   !> The rest 2/(1 + x_j) - inv_end_share_hi(j)
   real(wp), parameter :: inv_end_share_lo(0:cc_max_degree / 2) = &
      & [(real(1.0_xp / cos(pi_xp * i_ / (2 * cc_max_degree))**2 &
      & - real(real(1.0_xp / cos(pi_xp * i_ / (2 * cc_max_degree))**2, wp), xp), wp), &
      & i_ = 0, cc_max_degree / 2)]
   !> (1 - x_j)/2 = sin^2(pi j/96): node j's distance from the regular end, per unit D
   real(wp), parameter :: cc_turn_share(0:cc_max_degree) = &
      & [(real(sin(pi_xp * i_ / (2 * cc_max_degree))**2, wp), i_ = 0, cc_max_degree)]

   !> (m + 1)/(m - 1) of the moment recurrence
   real(wp), parameter :: ratio(2:cc_max_degree) = &
      & [(real(i_ + 1, wp) / real(i_ - 1, wp), i_ = 2, cc_max_degree)]
   !> The nodes x_j = cos(pi j/48)
   real(wp), parameter :: cc_node(0:cc_max_degree) = cosines(:, 1)

   ! The cosines each degree's transform reads, cos(pi j k/n), folded as `cosines` is
   ! (the same doubles, so the same results to the bit; gfortran 12 fails on a
   ! constant built from elements of `cosines` itself) into one table per degree and
   ! parity of k, with k running fastest, the rows padded with zeros to a multiple of 4
   ! (block_sums forms four coefficients at a time; the padded ones are not used): the
   ! transform then reads consecutive memory instead of every (2 stride)-th double of a
   ! 49 x 49 table.
   !> cos(pi j (2m)/12), m, j = 0 .. 6
   real(wp), parameter :: cos_even12(0:7, 0:6) = reshape([((merge(real(cos(pi_xp &
      & * real((8 * i_) * j_, xp) / cc_max_degree), wp), 0.0_wp, i_ <= 6), &
      & i_ = 0, 7), j_ = 0, 6)], [8, 7])
   !> cos(pi j (2m+1)/12), m, j = 0 .. 5
   real(wp), parameter :: cos_odd12(0:7, 0:5) = reshape([((merge(real(cos(pi_xp &
      & * real((4 * (2 * i_ + 1)) * j_, xp) / cc_max_degree), wp), 0.0_wp, i_ <= 5), &
      & i_ = 0, 7), j_ = 0, 5)], [8, 6])
   !> cos(pi j (2m)/16), m, j = 0 .. 8 (degree 16: every third node of the 48 grid)
   real(wp), parameter :: cos_even16(0:11, 0:8) = reshape([((merge(real(cos(pi_xp &
      & * real((6 * i_) * j_, xp) / cc_max_degree), wp), 0.0_wp, i_ <= 8), &
      & i_ = 0, 11), j_ = 0, 8)], [12, 9])
   !> cos(pi j (2m+1)/16), m, j = 0 .. 7
   real(wp), parameter :: cos_odd16(0:7, 0:7) = reshape([((real(cos(pi_xp &
      & * real((3 * (2 * i_ + 1)) * j_, xp) / cc_max_degree), wp), &
      & i_ = 0, 7), j_ = 0, 7)], [8, 8])
   !> cos(pi j (2m)/24), m, j = 0 .. 12
   real(wp), parameter :: cos_even24(0:15, 0:12) = reshape([((merge(real(cos(pi_xp &
      & * real((4 * i_) * j_, xp) / cc_max_degree), wp), 0.0_wp, i_ <= 12), &
      & i_ = 0, 15), j_ = 0, 12)], [16, 13])
   !> cos(pi j (2m+1)/24), m, j = 0 .. 11
   real(wp), parameter :: cos_odd24(0:11, 0:11) = reshape([((merge(real(cos(pi_xp &
      & * real((2 * (2 * i_ + 1)) * j_, xp) / cc_max_degree), wp), 0.0_wp, i_ <= 11), &
      & i_ = 0, 11), j_ = 0, 11)], [12, 12])
   !> cos(pi j (2m)/48), m, j = 0 .. 24
   real(wp), parameter :: cos_even48(0:27, 0:24) = reshape([((merge(real(cos(pi_xp &
      & * real((2 * i_) * j_, xp) / cc_max_degree), wp), 0.0_wp, i_ <= 24), &
      & i_ = 0, 27), j_ = 0, 24)], [28, 25])
   !> cos(pi j (2m+1)/48), m, j = 0 .. 23
   real(wp), parameter :: cos_odd48(0:23, 0:23) = reshape([((merge(real(cos(pi_xp &
      & * real((2 * i_ + 1) * j_, xp) / cc_max_degree), wp), 0.0_wp, i_ <= 23), &
      & i_ = 0, 23), j_ = 0, 23)], [24, 24])

   ! The plain Clenshaw-Curtis rule (weight 1) of degree n on [-1, 1]: its weights
   ! w_j = c_j (2/n) sum''_k 2/(1 - k^2) cos(pi j k/n) (k even; c_0 = c_n = 1/2, the
   ! last k halved), the integral of the interpolant sum''_k a_k int T_k as a sum over
   ! the values; computed in the extended kind and rounded once.
   !> The terms of the weights of degree 12: node j (first index), k = 2m (second)
   real(xp), parameter :: plain_terms12(0:12, 0:6) = reshape([((merge(0.5_xp, 1.0_xp, &
      & i_ == 0 .or. i_ == 12) * merge(0.5_xp, 1.0_xp, j_ == 0 .or. j_ == 6) &
      & * (2.0_xp / 12) * 2.0_xp / (1.0_xp - real(2 * j_, xp)**2) &
      & * cos(pi_xp * real(2 * i_ * j_, xp) / 12), i_ = 0, 12), j_ = 0, 6)], [13, 7])
   !> Weights of the plain rule of degree 12 at its nodes j = 0 .. 12
   real(wp), parameter :: plain_weight12(0:12) = real(sum(plain_terms12, dim=2), wp)
   !> The terms of the weights of degree 24: node j (first index), k = 2m (second)
   real(xp), parameter :: plain_terms24(0:24, 0:12) = reshape([((merge(0.5_xp, 1.0_xp, &
      & i_ == 0 .or. i_ == 24) * merge(0.5_xp, 1.0_xp, j_ == 0 .or. j_ == 12) &
      & * (2.0_xp / 24) * 2.0_xp / (1.0_xp - real(2 * j_, xp)**2) &
      & * cos(pi_xp * real(2 * i_ * j_, xp) / 24), i_ = 0, 24), j_ = 0, 12)], [25, 13])
   !> Weights of the plain rule of degree 24 at its nodes j = 0 .. 24
   real(wp), parameter :: plain_weight24(0:24) = real(sum(plain_terms24, dim=2), wp)
   !> The terms of the weights of degree 48: node j (first index), k = 2m (second)
   real(xp), parameter :: plain_terms48(0:48, 0:24) = reshape([((merge(0.5_xp, 1.0_xp, &
      & i_ == 0 .or. i_ == 48) * merge(0.5_xp, 1.0_xp, j_ == 0 .or. j_ == 24) &
      & * (2.0_xp / 48) * 2.0_xp / (1.0_xp - real(2 * j_, xp)**2) &
      & * cos(pi_xp * real(2 * i_ * j_, xp) / 48), i_ = 0, 48), j_ = 0, 24)], [49, 25])
   !> Weights of the plain rule of degree 48 at its nodes j = 0 .. 48
   real(wp), parameter :: plain_weight48(0:48) = real(sum(plain_terms48, dim=2), wp)

   !> The rows of a_(n-1) and a_n of the plain rule of degree 12: (2/n) c_j (-1)^j x_j
   !> and (2/n) c_j (-1)^j, c_0 = c_n = 1/2 (n even: (-1)^n = 1)
   real(wp), parameter :: plain_last12(0:12, 2) = reshape([ &
      & (real(merge(0.5_xp, 1.0_xp, i_ == 0 .or. i_ == 12) * (2.0_xp / 12) * (-1)**i_ &
      & * cos(pi_xp * real(i_, xp) / 12), wp), i_ = 0, 12), &
      & (real(merge(0.5_xp, 1.0_xp, i_ == 0 .or. i_ == 12) * (2.0_xp / 12) * (-1)**i_, wp), &
      & i_ = 0, 12)], [13, 2])
   !> The rows of a_(n-1) and a_n of the plain rule of degree 24: (2/n) c_j (-1)^j x_j
   !> and (2/n) c_j (-1)^j, c_0 = c_n = 1/2 (n even: (-1)^n = 1)
   real(wp), parameter :: plain_last24(0:24, 2) = reshape([ &
      & (real(merge(0.5_xp, 1.0_xp, i_ == 0 .or. i_ == 24) * (2.0_xp / 24) * (-1)**i_ &
      & * cos(pi_xp * real(i_, xp) / 24), wp), i_ = 0, 24), &
      & (real(merge(0.5_xp, 1.0_xp, i_ == 0 .or. i_ == 24) * (2.0_xp / 24) * (-1)**i_, wp), &
      & i_ = 0, 24)], [25, 2])
   !> The rows of a_(n-1) and a_n of the plain rule of degree 48: (2/n) c_j (-1)^j x_j
   !> and (2/n) c_j (-1)^j, c_0 = c_n = 1/2 (n even: (-1)^n = 1)
   real(wp), parameter :: plain_last48(0:48, 2) = reshape([ &
      & (real(merge(0.5_xp, 1.0_xp, i_ == 0 .or. i_ == 48) * (2.0_xp / 48) * (-1)**i_ &
      & * cos(pi_xp * real(i_, xp) / 48), wp), i_ = 0, 48), &
      & (real(merge(0.5_xp, 1.0_xp, i_ == 0 .or. i_ == 48) * (2.0_xp / 48) * (-1)**i_, wp), &
      & i_ = 0, 48)], [49, 2])

   !> Largest |y| for which sym_q0 sums its series (terms fall like y^2 per step)
   real(wp), parameter :: sym_series_max = 0.5_wp
   !> 1/j and 1/(2j + 1), j = 1 .. 64, for the series of Q_0
   real(wp), parameter :: inv_j(64) = 1.0_wp / real([(i_, i_ = 1, 64)], wp)
   real(wp), parameter :: inv_odd(64) = 1.0_wp / real([(2 * i_ + 1, i_ = 1, 64)], wp)

! BEGIN GENERATED (tools/make_gegenbauer_table.py)
   !> Chebyshev coefficients of Gamma(a + 1)/Gamma(a + 1/2) in t = 2a - 1 on
   !> a in [0, 1] (largest relative error of the series 4.8e-19)
   integer, parameter :: gamma_ratio_terms = 26
   real(wp), parameter :: gamma_ratio_c0(2) = [0.866650769496302_wp, 2.3427745861985013e-17_wp]
   real(wp), parameter :: gamma_ratio_c1(2) = [0.27943049691747673_wp, 9.596155628525831e-18_wp]
   real(wp), parameter :: gamma_ratio_c(2:25) = [ &
      & -0.019960668703532653_wp, 0.002598685361474483_wp, -0.0003948152833967102_wp, &
      & 6.376940445818292e-05_wp, -1.0597496398716859e-05_wp, 1.7867336517860292e-06_wp, &
      & -3.035654943024611e-07_wp, 5.1793917559040564e-08_wp, -8.857978064942612e-09_wp, &
      & 1.5169690695229992e-09_wp, -2.599896442165651e-10_wp, 4.4579033652117226e-11_wp, &
      & -7.645728723086847e-12_wp, 1.3115156317726404e-12_wp, -2.2499190563921933e-13_wp, &
      & 3.8599625168091036e-14_wp, -6.622357889629328e-15_wp, 1.1361876415139594e-15_wp, &
      & -1.949360186093393e-16_wp, 3.344543415990613e-17_wp, -5.73829910532464e-18_wp, &
      & 9.84533426843277e-19_wp, -1.689189228035182e-19_wp, 2.898187415787308e-20_wp ]
! END GENERATED (tools/make_gegenbauer_table.py)

contains

   !> Modified moments J_k(y), k = 0 .. n, of the weight ((1 + x)/2)^(c-1) on [-1, y],
   !> given s = (1 + y)/2 in (0, 1] (s = 1: the complete moments) and C = 2 s^c.
   pure subroutine cc_moments(c, inv_c, s, big_c, n, moment)
      !> Exponent c = 1 - alpha, 0 < c <= 1
      real(wp), intent(in) :: c
      !> 1/c, given separately because it may be exact where c is not (c = 1/(n+1))
      real(wp), intent(in) :: inv_c
      !> (1 + y)/2, the share of the interval, 0 < s <= 1
      real(wp), intent(in) :: s
      !> 2 s^c
      real(wp), intent(in) :: big_c
      !> Highest degree, 2 <= n <= cc_max_degree
      integer, intent(in) :: n
      !> J_0 .. J_n
      real(wp), intent(out) :: moment(0:)
      real(wp) :: y, t(0:cc_max_degree + 1)
      real(wp) :: inv_den(2:cc_max_degree), drive(2:cc_max_degree)
      integer :: m

      y = 2.0_wp * s - 1.0_wp
      if (s >= 1.0_wp) y = 1.0_wp
      t(0) = 1.0_wp
      t(1) = y
      do m = 1, n
         t(m + 1) = 2.0_wp * y * t(m) - t(m - 1)
      end do
      moment(0) = big_c * inv_c
      moment(1) = big_c * (2.0_wp * s / (c + 1.0_wp) - inv_c)
      moment(2) = (big_c * t(2) - 4.0_wp * moment(1) - 2.0_wp * moment(0)) / (2.0_wp + c)
      ! The divisions by m + 1 + c do not depend on the moments: taken out of the
      ! recurrence as reciprocals, they no longer lengthen its chain of dependent
      ! operations (a division takes four to five times as long as a product), and
      ! the extra rounding is far below the recurrence's own error growth.
      do m = 2, n - 1
         inv_den(m) = 1.0_wp / (real(m + 1, wp) + c)
         drive(m) = big_c * (t(m + 1) - ratio(m) * t(m - 1))
      end do
      do m = 2, n - 1
         moment(m + 1) = (drive(m) - 2.0_wp * real(m + 1, wp) * moment(m) &
            & + (c + 1.0_wp - real(m, wp)) * ratio(m) * moment(m - 1)) * inv_den(m)
      end do
   end subroutine cc_moments

   !> The complete moments (s = 1, C = 2) and the incomplete ones for s, C together:
   !> the same values as two calls of cc_moments, to the bit (the same operations), in
   !> one pass. The two recurrences are chains of dependent products; interleaved,
   !> each fills the other's wait, and the reciprocals 1/(m + 1 + c) are formed once.
   pure subroutine cc_moments_pair(c, inv_c, s, big_c, n, complete, partial)
      !> Exponent c = 1 - alpha, 0 < c <= 1
      real(wp), intent(in) :: c
      !> 1/c (see cc_moments)
      real(wp), intent(in) :: inv_c
      !> (1 + y)/2 of the incomplete moments, 0 < s <= 1
      real(wp), intent(in) :: s
      !> 2 s^c
      real(wp), intent(in) :: big_c
      !> Highest degree, 2 <= n <= cc_max_degree
      integer, intent(in) :: n
      !> J_0 .. J_n for y = 1 and for y = 2 s - 1
      real(wp), intent(out) :: complete(0:), partial(0:)
      real(wp) :: y, t(0:cc_max_degree + 1)
      real(wp) :: inv_den(2:cc_max_degree), drive(2:cc_max_degree), drive1(2:cc_max_degree)
      integer :: m

      y = 2.0_wp * s - 1.0_wp
      if (s >= 1.0_wp) y = 1.0_wp
      t(0) = 1.0_wp
      t(1) = y
      do m = 1, n
         t(m + 1) = 2.0_wp * y * t(m) - t(m - 1)
      end do
      ! y = 1: T_k(1) = 1 (the recurrence 2 * 1 * 1 - 1 is exact)
      complete(0) = 2.0_wp * inv_c
      complete(1) = 2.0_wp * (2.0_wp * 1.0_wp / (c + 1.0_wp) - inv_c)
      complete(2) = (2.0_wp * 1.0_wp - 4.0_wp * complete(1) - 2.0_wp * complete(0)) &
         & / (2.0_wp + c)
      partial(0) = big_c * inv_c
      partial(1) = big_c * (2.0_wp * s / (c + 1.0_wp) - inv_c)
      partial(2) = (big_c * t(2) - 4.0_wp * partial(1) - 2.0_wp * partial(0)) / (2.0_wp + c)
      do m = 2, n - 1
         inv_den(m) = 1.0_wp / (real(m + 1, wp) + c)
         drive(m) = big_c * (t(m + 1) - ratio(m) * t(m - 1))
         drive1(m) = 2.0_wp * (1.0_wp - ratio(m) * 1.0_wp)
      end do
      do m = 2, n - 1
         complete(m + 1) = (drive1(m) - 2.0_wp * real(m + 1, wp) * complete(m) &
            & + (c + 1.0_wp - real(m, wp)) * ratio(m) * complete(m - 1)) * inv_den(m)
         partial(m + 1) = (drive(m) - 2.0_wp * real(m + 1, wp) * partial(m) &
            & + (c + 1.0_wp - real(m, wp)) * ratio(m) * partial(m - 1)) * inv_den(m)
      end do
   end subroutine cc_moments_pair

   !> Chebyshev coefficients a_k, k = 0 .. n, of the interpolant of f at the nodes
   !> x_j = cos(pi j/n): a_k = (2/n) sum''_j f_j cos(pi j k/n) (first and last halved).
   !> n is 12, 16, 24 or 48; f(j) is the value at node j of this rule.
   pure subroutine cc_coefficients(n, f, a)
      !> Degree: 12, 16, 24 or 48
      integer, intent(in) :: n
      !> Values at the n + 1 nodes
      real(wp), intent(in) :: f(0:)
      !> Coefficients
      real(wp), intent(out) :: a(0:)
      real(wp) :: even(0:cc_max_degree / 2), odd(0:cc_max_degree / 2), scale
      integer :: j, half

      ! cos(pi (n-j) k/n) = (-1)^k cos(pi j k/n): fold the nodes j and n - j first
      half = n / 2
      even(0) = 0.5_wp * (f(0) + f(n))
      odd(0) = 0.5_wp * (f(0) - f(n))
      do j = 1, half - 1
         even(j) = f(j) + f(n - j)
         odd(j) = f(j) - f(n - j)
      end do
      even(half) = f(half)
      odd(half) = 0.0_wp
      scale = 2.0_wp / real(n, wp)
      select case (n)
      case (12)
         call fold_transform(half, even, odd, cos_even12, cos_odd12, scale, a)
      case (16)
         call fold_transform(half, even, odd, cos_even16, cos_odd16, scale, a)
      case (24)
         call fold_transform(half, even, odd, cos_even24, cos_odd24, scale, a)
      case default
         call fold_transform(half, even, odd, cos_even48, cos_odd48, scale, a)
      end select
   end subroutine cc_coefficients

   !> The coefficients from the folded values: a_(2m) = scale sum_j even_j cos_even(m, j),
   !> a_(2m+1) = scale sum_j odd_j cos_odd(m, j), j = 0 .. h (odd: h - 1).
   pure subroutine fold_transform(h, even, odd, cos_even, cos_odd, scale, a)
      !> Half the degree
      integer, intent(in) :: h
      !> Folded values f_j + f_(n-j) and f_j - f_(n-j) (see cc_coefficients)
      real(wp), intent(in) :: even(0:), odd(0:)
      !> This degree's cosines, k (as m) running fastest, rows padded with zeros to a
      !> multiple of 4
      real(wp), intent(in) :: cos_even(0:, 0:), cos_odd(0:, 0:)
      !> 2/n
      real(wp), intent(in) :: scale
      !> Coefficients a_0 .. a_(2h)
      real(wp), intent(out) :: a(0:)
      real(wp) :: ae(0:cc_max_degree / 2 + 3), ao(0:cc_max_degree / 2 + 3)
      ! Blocks of four coefficients, their sums in registers over all j: each a_k is
      ! still summed over j in increasing order (the same roundings as a sum per
      ! coefficient, so the same values), the four sums are independent chains, and
      ! no partial sum goes through memory. The padded rows give 0 and are not used.
      call block_sums(h + 1, size(cos_even, 1), even, cos_even, ae)
      call block_sums(h, size(cos_odd, 1), odd, cos_odd, ao)
      a(0:2 * h:2) = ae(0:h) * scale
      a(1:2 * h - 1:2) = ao(0:h - 1) * scale
   end subroutine fold_transform

   !> s_m = sum_j v_j c(m, j), j = 0 .. nj - 1, m = 0 .. nm - 1 (nm a multiple of 4),
   !> each summed in increasing j
   pure subroutine block_sums(nj, nm, v, c, sums)
      !> Number of terms and of sums
      integer, intent(in) :: nj, nm
      !> Values and table
      real(wp), intent(in) :: v(0:), c(0:, 0:)
      !> The sums
      real(wp), intent(out) :: sums(0:)
      real(wp) :: s0, s1, s2, s3
      integer :: j, m
      do m = 0, nm - 4, 4
         s0 = 0.0_wp
         s1 = 0.0_wp
         s2 = 0.0_wp
         s3 = 0.0_wp
         do j = 0, nj - 1
            s0 = s0 + v(j) * c(m, j)
            s1 = s1 + v(j) * c(m + 1, j)
            s2 = s2 + v(j) * c(m + 2, j)
            s3 = s3 + v(j) * c(m + 3, j)
         end do
         sums(m) = s0
         sums(m + 1) = s1
         sums(m + 2) = s2
         sums(m + 3) = s3
      end do
   end subroutine block_sums

   !> The plain Clenshaw-Curtis rule (weight 1) of degree n on values g at its nodes
   !> x_j = cos(pi j/n): the integral of the interpolant over [-1, 1], sum_j w_j g_j
   !> with the rule's weights, and the two coefficients a_(n-1), a_n of the
   !> interpolant that cc_converged reads. The same integral as cc_coefficients and
   !> cc_sum with the moments 2/(1 - k^2) (k even), without the transform: the weights
   !> do not depend on the integrand, so a plain rule costs three products per node.
   pure subroutine cc_plain(n, g, total, a_last)
      !> Degree: 12, 24 or 48
      integer, intent(in) :: n
      !> Values at the n + 1 nodes of this rule
      real(wp), intent(in) :: g(0:)
      !> The integral sum_j w_j g_j
      real(wp), intent(out) :: total
      !> a_(n-1) and a_n: (2/n) sum''_j (-1)^j x_j g_j and (2/n) sum''_j (-1)^j g_j
      !> (cos(pi j (n-1)/n) = (-1)^j x_j, cos(pi j) = (-1)^j)
      real(wp), intent(out) :: a_last(2)
      select case (n)
      case (12)
         call plain_sums(12, g, plain_weight12, plain_last12, total, a_last)
      case (24)
         call plain_sums(24, g, plain_weight24, plain_last24, total, a_last)
      case default
         call plain_sums(48, g, plain_weight48, plain_last48, total, a_last)
      end select
   end subroutine cc_plain

   !> The three sums of cc_plain over the nodes j = 0 .. n, in increasing j: three
   !> independent chains of products and sums
   pure subroutine plain_sums(n, g, weight, last, total, a_last)
      integer, intent(in) :: n
      real(wp), intent(in) :: g(0:), weight(0:), last(0:, :)
      real(wp), intent(out) :: total, a_last(2)
      real(wp) :: s, s1, s2
      integer :: j
      s = 0.0_wp
      s1 = 0.0_wp
      s2 = 0.0_wp
      do j = 0, n
         s = s + weight(j) * g(j)
         s1 = s1 + last(j, 1) * g(j)
         s2 = s2 + last(j, 2) * g(j)
      end do
      total = s
      a_last = [s1, s2]
   end subroutine plain_sums

   !> sum''_k a_k J_k (first and last terms halved), k = 0 .. n.
   pure function cc_sum(n, a, moment) result(total)
      !> Degree
      integer, intent(in) :: n
      !> Coefficients and moments
      real(wp), intent(in) :: a(0:), moment(0:)
      !> The sum
      real(wp) :: total
      integer :: k
      total = 0.5_wp * (a(0) * moment(0) + a(n) * moment(n))
      do k = n - 1, 1, -1
         total = total + a(k) * moment(k)
      end do
   end function cc_sum

   !> Bound on the error of the degree-n rule, in units of the integral sum'' a_k J_k:
   !> (|a_(n-1)| + |a_n|) J_0, the size of the first neglected coefficients (assumed
   !> decaying at least geometrically) against the largest moment.
   pure function cc_tail(n, a, moment) result(bound)
      !> Degree
      integer, intent(in) :: n
      !> Coefficients and complete moments
      real(wp), intent(in) :: a(0:), moment(0:)
      !> Absolute error bound
      real(wp) :: bound
      bound = (abs(a(n - 1)) + abs(a(n))) * abs(moment(0))
   end function cc_tail

   !> Whether the degree-n rule is accepted: its tail bound `cc_tail` is at most
   !> tol |total|, or at most the rounding noise of the transform, 4 eps max_j |f_j| J_0
   !> (the coefficients of a resolved function stop decaying at the level of the
   !> rounding errors of its values; no higher degree would do better).
   pure function cc_converged(n, a, moment, total, fmax, tol) result(ok)
      !> Degree
      integer, intent(in) :: n
      !> Coefficients and complete moments
      real(wp), intent(in) :: a(0:), moment(0:)
      !> The integral sum'' a_k J_k of this rule (or the part of it the a_k are added to)
      real(wp), intent(in) :: total
      !> Largest |f_j| given to cc_coefficients
      real(wp), intent(in) :: fmax
      !> Relative tolerance
      real(wp), intent(in) :: tol
      !> True when accepted
      logical :: ok
      ok = cc_tail(n, a, moment) <= tol * abs(total) &
         & + 4.0_wp * epsilon(1.0_wp) * fmax * abs(moment(0))
   end function cc_converged

   !> M_0 = int_-1^1 (1 - x^2)^(-alpha) dx = sqrt(pi) Gamma(a)/Gamma(a + 1/2) for
   !> a = 1 - alpha in (0, 1]: sqrt(pi) f(a) (1/a) with f(a) = Gamma(a + 1)/Gamma(a + 1/2)
   !> from its Chebyshev series in t = 2a - 1, the first two terms in double-double, the
   !> rest (below 0.023 f in all) by Clenshaw's sum in double. About 5e-18 relative.
   pure function sym_m0(a, inv_a) result(m0)
      !> 1 - alpha = 1/(n+1), and its reciprocal n + 1 (exact where a is not)
      type(dd_real), intent(in) :: a, inv_a
      type(dd_real) :: m0
      type(dd_real), parameter :: sqrt_pi = dd_real(1.772453850905516_wp, &
         & -7.666586499825799e-17_wp)
      type(dd_real) :: t
      real(wp) :: b0, b1, b2, tail
      integer :: k
      t = two_sum(2.0_wp * a%hi, -1.0_wp) + 2.0_wp * a%lo
      ! sum_{k>=2} c_k T_k(t), Clenshaw
      b1 = 0.0_wp
      b2 = 0.0_wp
      do k = gamma_ratio_terms - 1, 2, -1
         b0 = gamma_ratio_c(k) + 2.0_wp * t%hi * b1 - b2
         b2 = b1
         b1 = b0
      end do
      ! the step k = 1 with c_1 = 0, then c_0 = 0 + t b_1 - b_2
      b0 = 2.0_wp * t%hi * b1 - b2
      tail = t%hi * b0 - b1
      m0 = ((dd_real(gamma_ratio_c0(1), gamma_ratio_c0(2)) &
         & + dd_real(gamma_ratio_c1(1), gamma_ratio_c1(2)) * t) + tail) * (sqrt_pi * inv_a)
   end function sym_m0

   !> Complete moments M_0 .. M_n of the symmetric weight (M_0 given, its double part),
   !> and the reciprocals 1/(k + 1 + nu), k = 1 .. n - 1, that sym_partial_moments uses
   !> too (a division in the recurrence's chain cost four times a product)
   pure subroutine sym_moments(nu, m0, n, moment, inv_den)
      !> nu = 1 - 2 alpha, in (-1, 1)
      real(wp), intent(in) :: nu
      !> M_0 (rounded)
      real(wp), intent(in) :: m0
      !> Highest degree
      integer, intent(in) :: n
      real(wp), intent(out) :: moment(0:)
      real(wp), intent(out) :: inv_den(cc_max_degree)
      integer :: k
      do k = 1, n - 1
         inv_den(k) = 1.0_wp / (real(k + 1, wp) + nu)
      end do
      moment(0) = m0
      moment(1) = 0.0_wp
      do k = 1, n - 1, 2
         moment(k + 1) = moment(k - 1) * ((real(k - 1, wp) - nu) * inv_den(k))
      end do
      moment(3:n:2) = 0.0_wp
   end subroutine sym_moments

   !> Incomplete moments Q_k(y) = int_y^1 (1 - x^2)^(-alpha) T_k dx, k = 0 .. n, given
   !> Q_0 (sym_q0, rounded here), s = (1 - y^2)^(1 - alpha) and sym_moments' inv_den
   pure subroutine sym_partial_moments(nu, y, s, q0, n, inv_den, moment)
      real(wp), intent(in) :: nu, y, s, q0
      integer, intent(in) :: n
      real(wp), intent(in) :: inv_den(cc_max_degree)
      real(wp), intent(out) :: moment(0:)
      real(wp) :: drive(cc_max_degree), t0, t1, t2
      integer :: k
      ! the driving terms 2 s T_k(y) first: the recurrence is then one product and one
      ! sum per step
      t0 = 1.0_wp
      t1 = y
      do k = 1, n - 1
         drive(k) = 2.0_wp * s * t1 * inv_den(k)
         t2 = 2.0_wp * y * t1 - t0
         t0 = t1
         t1 = t2
      end do
      moment(0) = q0
      moment(1) = s / (nu + 1.0_wp)
      do k = 1, n - 1
         moment(k + 1) = drive(k) + ((real(k - 1, wp) - nu) * inv_den(k)) * moment(k - 1)
      end do
   end subroutine sym_partial_moments

   !> Q_0(y) = int_y^1 (1 - x^2)^(-alpha) dx = M_0/2 - D(y) for |y| <= sym_series_max:
   !> D(y) = sum_j (alpha)_j/j! y^(2j+1)/(2j+1), its first term y in double-double, the
   !> rest in double (below 0.05 |y|).
   pure function sym_q0(alpha, y, m0) result(q0)
      real(wp), intent(in) :: alpha
      type(dd_real), intent(in) :: y, m0
      type(dd_real) :: q0
      real(wp) :: y2, p, rest
      integer :: j
      y2 = y%hi * y%hi
      p = 1.0_wp
      rest = 0.0_wp
      do j = 1, 64
         p = p * ((alpha + real(j - 1, wp)) * inv_j(j)) * y2
         rest = rest + p * inv_odd(j)
         if (p < 1.0e-20_wp) exit
      end do
      ! M_0/2 - y - y rest
      q0 = (0.5_wp * m0 - y) - y%hi * rest
   end function sym_q0

   !> Q_0(y) = int_y^1 (1 - x^2)^(-alpha) dx for y = 1 - u, 0 < u <= 1/2: with x = 1 - t,
   !> (1 - x^2)^(-alpha) = (2t)^(-alpha) (1 - t/2)^(-alpha), so
   !> Q_0 = P sum_j (alpha)_j/j! (u/2)^j/(j + 1 - alpha), P = 2^(-alpha) u^(1-alpha)
   !> (the caller forms it in double-double), the first term 1/(1 - alpha) = n + 1 in
   !> double-double, the rest (below 1/4 of it) in double.
   pure function sym_q0_near_end(alpha, u, np1, pref) result(q0)
      real(wp), intent(in) :: alpha, u
      type(dd_real), intent(in) :: np1, pref
      type(dd_real) :: q0
      real(wp) :: p, rest, c
      integer :: j
      c = 1.0_wp - alpha
      p = 1.0_wp
      rest = 0.0_wp
      do j = 1, 64
         p = p * ((alpha + real(j - 1, wp)) * inv_j(j)) * (0.5_wp * u)
         rest = rest + p / (real(j, wp) + c)
         if (p < 1.0e-20_wp) exit
      end do
      q0 = (np1 + rest) * pref
   end function sym_q0_near_end

end module hcimpact_modified_cc
