! SPDX-License-Identifier: Apache-2.0
!> Real branches of the Lambert W function, accurate to the last bit near the branch point.
!>
!> W(z) solves W exp(W) = z. On the reals it has two branches that meet at the branch
!> point z = -1/e, W = -1: the principal branch W0 on [-1/e, inf) with W0 >= -1, and the
!> lower branch W-1 on [-1/e, 0) with W-1 <= -1.
!>
!> The impact formulas need 1 + W(-exp(-1 - t)) for t >= 0 (MODEL.md, seed eq. 14): near
!> t = 0 it is a difference of nearly equal numbers, so `lambert_w0p1` and `lambert_wm1p1`
!> take t itself and never form z.
!>
!> Methods, by region (errors measured by test/unit/test_lambertw.f90 against mpmath, at
!> most 0.54 ulp anywhere; see doc/lambertw.md). Everything is plain double arithmetic
!> with one final rounding of a dominant term plus a small correction; no iteration.
!> - Next to the branch point (p = +-sqrt(2(1 + e z)) < 2**-6, s = +-sqrt(2t) < 2**-6):
!>   the series at the branch point (DLMF 4.13.6), z + 1/e exact with 1/e split in two
!>   doubles; W from its odd and even parts in q = p**2 (lambertw_branch.inc), which
!>   overlap the square root; for 1 + W from t, s carries its rounding error as a low part.
!> - Elsewhere, "geometric" tables (tools/make_lambertw_tables.py): the key x (an exact
!>   double: z + 1/e_hi for z <= -1/4, |z|, z, t, or ln|z| as a double-double) is cut
!>   into intervals [2**k (1 + j/32), 2**k (1 + (j+1)/32)) found from the bits of x (no
!>   search), each with a degree-8 near-minimax polynomial in x - centre whose leading
!>   coefficient is a double-double (lambertw_eval.inc). Tables: W0 by z + 1/e_hi
!>   (z <= -1/4), by -z (-1/4 < z <= -2**-6), by z (2**-6 <= z < 2**10), by ln z (beyond);
!>   W-1 by z + 1/e_hi (z <= -1/4), by -z (to -2**-20), by -ln(-z) (beyond, subnormals
!>   included); 1 + W0 by t (t < 32; beyond, 1 + W0(z) with z = -exp(-1-t) tiny);
!>   1 + W-1 by t (t < 1024; beyond, Newton's method on u - ln(1 + u) = t).
!> - W0 for |z| < 2**-6: z - z**2 R(z), R a near-minimax polynomial.
!> - ln|z| comes from a 128-entry table and a short series (lambertw_ln.inc), no call.
!> The hot paths are written inline (include files): gfortran does not inline procedures
!> used in several places, and a call costs as much as the rest of a table evaluation.
!>
!> Every loop is bounded. No procedure stops or prints; outside the domain the result is NaN.
module hcimpact_lambertw
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_libm, only : log1p
   use hcimpact_lambertw_tables, only : s_coef, p_coef, w0_small, ln_tab, ln_bits, &
      & geo_tab, geo_shift, wa_off, wa_base, wb_off, wb_base, wc_off, wc_base, wd_off, wd_base, &
      & we_off, we_base, ta_off, ta_base, tb_off, tb_base, ya_off, ya_base, yb_off, yb_base
   implicit none
   private

   public :: lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1
   public :: lambert_w0p1_dd, lambert_wm1p1_dd

   !> A quiet NaN and -inf as constants: ieee_value is a library call, whose memory
   !> argument would give every function a stack frame on its fast paths too
   real(wp), parameter :: quiet_nan = transfer(int(z'7FF8000000000000', int64), 1.0_wp)
   real(wp), parameter :: minus_inf = transfer(int(z'FFF0000000000000', int64), 1.0_wp)
   !> 1/e as the unevaluated sum of two doubles
   real(wp), parameter :: inv_e_hi = 0.36787944117144233_wp, inv_e_lo = -1.2428753672788363e-17_wp
   !> e as the unevaluated sum of two doubles
   real(wp), parameter :: e_hi = 2.718281828459045_wp, e_lo = 1.4456468917292502e-16_wp
   !> W0 and W-1 for z <= -1/4 come from the tables `wa` and `wb`, keyed by z + 1/e_hi
   real(wp), parameter :: near_zmax = -0.25_wp
   !> Below this |z|, W0 = z - z**2 R(z) with the fit R = `w0_small`
   real(wp), parameter :: small_zmax = 2.0_wp**(-6)
   !> Below this |z|, W0(z) rounds to z itself (|W0 - z| < z**2 < 2**-60 |z|)
   real(wp), parameter :: tiny_w0 = 2.0_wp**(-60)
   !> Up to this z, W0 comes from the table `wd` keyed by z; beyond, from `ya` keyed by ln z
   real(wp), parameter :: mid_zmax = 2.0_wp**10
   !> W-1 for -z >= this comes from the table `we` keyed by -z; below, from `yb` (ln(-z))
   real(wp), parameter :: tiny_zmax = 2.0_wp**(-20)
   !> 1 + W0 from t: the table `ta` for fast_tmax <= t < ta_tmax
   real(wp), parameter :: ta_tmax = 2.0_wp**5
   !> 1 + W-1 from t: the table `tb` for fast_tmax <= t < tb_tmax
   real(wp), parameter :: tb_tmax = 2.0_wp**10
   !> Scale that brings a subnormal argument of ln into the normal range
   real(wp), parameter :: scale_up = 2.0_wp**600
   !> Below this p (and s), the Taylor series at the branch point in plain double
   !> arithmetic is accurate to 0.52 ulp: p's own rounding moves W by < 0.01 ulp
   real(wp), parameter :: fast_max = 2.0_wp**(-6)
   !> z + 1/e below which p = sqrt(2 e (z + 1/e)) < fast_max
   real(wp), parameter :: fast_dmax = fast_max**2 / (2.0_wp * e_hi)
   !> The same bound on z + 1/e_hi (one addition less on the other paths)
   real(wp), parameter :: fast_dmax_hi = fast_dmax - inv_e_lo
   !> Below this z + 1/e_hi, q = p**2 < 2**-16 and the series at the branch point stops at
   !> p**6 (lambertw_branch_short.inc)
   real(wp), parameter :: short_dmax_hi = 2.0_wp**(-16) / (2.0_wp * e_hi) - inv_e_lo
   !> Its bits: 0 < d < short_dmax_hi is 0 < bits(d) < short_dmax_bits, one range test on
   !> integers that NaN, -0 and negative d fail too, without the ordered comparison of a
   !> NaN that raises the invalid flag
   integer(int64), parameter :: short_dmax_bits = transfer(short_dmax_hi, 0_int64)
   !> The bits of fast_dmax_hi, 2**-6 and 1/e_hi (tests of lambert_w0 on the bits of d and |z|)
   integer(int64), parameter :: fast_dmax_bits = transfer(fast_dmax_hi, 0_int64)
   integer(int64), parameter :: small_bits = transfer(small_zmax, 0_int64)
   integer(int64), parameter :: inv_e_bits = transfer(inv_e_hi, 0_int64)
   !> t below which s = sqrt(2t) < fast_max (plain Taylor series at the branch point)
   real(wp), parameter :: fast_tmax = 0.5_wp * fast_max**2
   !> ln 2 in two parts, k*ln2_hi exact for |k| < 2**21 (lambertw_ln.inc)
   real(wp), parameter :: ln2_hi = 0.6931471803691238_wp, ln2_lo = 1.9082149292705877e-10_wp
   !> Fraction bits and the exponent of 1 of a binary64 (lambertw_ln.inc)
   integer(int64), parameter :: fraction_bits = int(z'000FFFFFFFFFFFFF', int64)
   integer(int64), parameter :: exponent_one = int(z'3FF0000000000000', int64)
   !> Sign, exponent and first ln_bits fraction bits of a binary64, and the bit below them
   integer(int64), parameter :: m0_mask = not(2_int64**(52 - ln_bits) - 1_int64)
   integer(int64), parameter :: m0_half = 2_int64**(51 - ln_bits)
   !> Bound on the number of iterations of every loop in this module
   integer, parameter :: max_iter = 8

contains

   !> Principal branch W0(z) of the Lambert W function.
   !>
   !> Domain z >= -1/e; W0 >= -1. NaN and z below the branch point give NaN. The double
   !> nearest to -1/e (-0.36787944117144233, 1.2e-17 below -1/e) stands for the branch
   !> point and gives -1 exactly; every lower double gives NaN. W0(+inf) = +inf.
   elemental function lambert_w0(z) result(w)
      !> Argument
      real(wp), value, intent(in) :: z
      !> W0(z)
      real(wp) :: w

      real(wp) :: key, key_lo, c1_lo, d, d2, y_lo, x, m, f, g, g2, p, kr, y1, lh, ll, q, q2, a, b
      integer :: row, shift, j
      integer(int64) :: bits

      ! The branch point's neighbourhood first, with as few tests as possible: for
      ! z <= -1/4, d = z + 1/e_hi is exact (Sterbenz): the key of the table `wa`, and with
      ! the low part of 1/e the exact offset from the branch point; d = 0 is the double
      ! nearest -1/e, and d < 0 lies outside the domain. d < fast_dmax_hi only for such z
      ! (beyond -1/4, d > 0.1), so the tests on d come first, the shorter series first.
      ! Each branch ends in its result (no early return), which lets the compiler lay the
      ! common paths out straight. The first tests are range tests on bits (the short
      ! series on d, the tables `wa`/`wc` on d and -z, the small-|z| form on |z|), which
      ! NaN fails; NaN is tested for after them, before any ordered comparison: with NaN
      ! that raises the invalid flag (and traps in a build with -ffpe-trap=invalid).
      c1_lo = 0.0_wp
      d = z + inv_e_hi
      bits = transfer(d, 0_int64)
      if (bits > 0_int64 .and. bits < short_dmax_bits) then
         q = (2.0_wp * e_hi) * (d + inv_e_lo)
         include "lambertw_branch_short.inc"
         w = -1.0_wp + (sqrt(q) * a + q * b)
      else if (bits >= fast_dmax_bits .and. mag_bits(z) >= small_bits &
         & .and. mag_bits(z) < inv_e_bits) then
         ! -1/e_hi < z <= -2**-6 with d >= fast_dmax_hi, tested on the bits (NaN fails)
         if (z <= near_zmax) then
            ! Table `wa`, key d = z + 1/e_hi (exact for z <= -1/4)
            key = d
            row = geo_row(d, wa_base, wa_off)
         else
            ! Table `wc`, key -z
            key = -z
            row = geo_row(key, wc_base, wc_off)
         end if
         include "lambertw_eval.inc"
         w = geo_tab(2, row) + y_lo
      else if (transfer(abs(z), 0_int64) < small_bits) then
         ! |z| < 2**-6, tested on the bits (NaN fails)
         w = w0_small_z(z)
      else if (ieee_is_nan(z)) then
         w = quiet_nan
      else if (d < fast_dmax_hi) then
         if (d > 0.0_wp) then
            q = (2.0_wp * e_hi) * (d + inv_e_lo)
            include "lambertw_branch.inc"
            w = -1.0_wp + (sqrt(q) * a + q * b)
         else if (d >= 0.0_wp) then
            w = -1.0_wp
         else
            w = quiet_nan
         end if
      else if (z < mid_zmax) then
         ! 2**-6 <= z < 2**10 (the tests above leave no other z here)
         key = z
         row = geo_row(z, wd_base, wd_off)
         include "lambertw_eval.inc"
         w = geo_tab(2, row) + y_lo
      else if (z > huge(z)) then
         w = z
      else
         ! W0 as a function of y = ln z: ln z is a double-double (absolute error ~2e-18),
         ! and dW/dy = W/(1 + W) < 1, so its error stays far below an ulp of W > 5.
         x = z
         shift = 0
         include "lambertw_ln.inc"
         call fast_two_sum(lh, ll, key, key_lo)
         ! The row from y1 (within 2**-17 of y): the polynomials hold 1/64 of their
         ! half-width (> 2**-11 here) beyond their intervals, and key - xc stays exact.
         row = geo_row(y1, ya_base, ya_off)
         c1_lo = geo_tab(3, row) * key_lo
         include "lambertw_eval.inc"
         w = geo_tab(2, row) + y_lo
      end if
   end function lambert_w0

   !> Lower branch W-1(z) of the Lambert W function.
   !>
   !> Domain -1/e <= z < 0; W-1 <= -1. NaN, z > 0 and z below the branch point give NaN;
   !> z = 0 (either sign) gives -inf, the limit from below. The double nearest to -1/e
   !> gives -1 exactly, as for `lambert_w0`.
   elemental function lambert_wm1(z) result(w)
      !> Argument
      real(wp), value, intent(in) :: z
      !> W-1(z)
      real(wp) :: w

      real(wp) :: key, key_lo, c1_lo, d, d2, y_lo, x, m, f, g, g2, p, kr, y1, lh, ll, q, q2, a, b
      integer :: row, shift, j
      integer(int64) :: bits

      ! Tests ordered as in lambert_w0: the branch point's neighbourhood (bits first,
      ! then NaN), each branch ending in its result.
      c1_lo = 0.0_wp
      d = z + inv_e_hi
      bits = transfer(d, 0_int64)
      if (bits > 0_int64 .and. bits < short_dmax_bits) then
         q = (2.0_wp * e_hi) * (d + inv_e_lo)
         include "lambertw_branch_short.inc"
         w = -1.0_wp + (q * b - sqrt(q) * a)
      else if (ieee_is_nan(z)) then
         w = quiet_nan
      else if (d < fast_dmax_hi) then
         if (d > 0.0_wp) then
            q = (2.0_wp * e_hi) * (d + inv_e_lo)
            include "lambertw_branch.inc"
            w = -1.0_wp + (q * b - sqrt(q) * a)
         else if (d >= 0.0_wp) then
            w = -1.0_wp
         else
            w = quiet_nan
         end if
      else if (z <= near_zmax) then
         ! Table `wb`, key d = z + 1/e_hi (exact for z <= -1/4)
         key = d
         row = geo_row(d, wb_base, wb_off)
         include "lambertw_eval.inc"
         w = geo_tab(2, row) + y_lo
      else if (z <= -tiny_zmax) then
         ! Table `we`, key -z
         key = -z
         row = geo_row(key, we_base, we_off)
         include "lambertw_eval.inc"
         w = geo_tab(2, row) + y_lo
      else if (z < 0.0_wp) then
         ! W-1 as a function of y = -ln(-z) > 13.8, ln(-z) a double-double (subnormal z
         ! scaled first): dW/dy = -W/(1 + W) is near 1, so the ~2e-18 error of y stays far
         ! below an ulp of |W| > 17.
         x = -z
         shift = 0
         if (x < tiny(x)) then
            x = x * scale_up
            shift = -600
         end if
         include "lambertw_ln.inc"
         call fast_two_sum(-lh, -ll, key, key_lo)
         row = geo_row(-y1, yb_base, yb_off)     ! y1: see lambert_w0
         c1_lo = geo_tab(3, row) * key_lo
         include "lambertw_eval.inc"
         w = geo_tab(2, row) + y_lo
      else if (z <= 0.0_wp) then
         w = minus_inf
      else
         w = quiet_nan
      end if
   end function lambert_wm1

   !> 1 + W0(-exp(-1 - t)) for t >= 0, computed from t without forming z.
   !>
   !> Equals sqrt(2t) - 2t/3 + ... for small t and tends to 1 as t grows: it is the
   !> root v in [0, 1) of -v - ln(1 - v) = t. NaN and t < 0 give NaN; +inf gives 1.
   elemental function lambert_w0p1(t) result(v)
      !> Offset from the branch point, t = -1 - ln(-z)
      real(wp), value, intent(in) :: t
      !> 1 + W0(-exp(-1 - t))
      real(wp) :: v

      real(wp), parameter :: sgn = 1.0_wp
      real(wp), parameter :: split_factor = 134217729.0_wp   ! 2**27 + 1
      real(wp) :: key, c1_lo, d, d2, y_lo, vl, sh, sl, x, c, ah, al, s, s2, tail
      integer :: row

      ! The methods of lambert_w0p1_dd with tl = 0, written out so that the common paths
      ! need no call.
      if (ieee_is_nan(t)) then
         v = quiet_nan
      else if (t < 0.0_wp) then
         v = quiet_nan
      else if (t <= 0.0_wp) then
         v = 0.0_wp
      else if (t < fast_tmax) then
         include "lambertw_small_t.inc"
         v = sh + (sl + tail)
      else if (t < ta_tmax) then
         key = t
         row = geo_row(t, ta_base, ta_off)
         c1_lo = 0.0_wp
         include "lambertw_eval.inc"
         v = geo_tab(2, row) + y_lo
      else
         call lambert_w0p1_dd(t, 0.0_wp, v, vl)
      end if
   end function lambert_w0p1

   !> 1 + W-1(-exp(-1 - t)) for t >= 0, computed from t without forming z.
   !>
   !> Equals -sqrt(2t) - 2t/3 - ... for small t and tends to -inf as t grows: it is -u
   !> for the root u >= 0 of u - ln(1 + u) = t. NaN and t < 0 give NaN; +inf gives -inf.
   elemental function lambert_wm1p1(t) result(v)
      !> Offset from the branch point, t = -1 - ln(-z)
      real(wp), value, intent(in) :: t
      !> 1 + W-1(-exp(-1 - t))
      real(wp) :: v

      real(wp), parameter :: sgn = -1.0_wp
      real(wp), parameter :: split_factor = 134217729.0_wp   ! 2**27 + 1
      real(wp) :: key, c1_lo, d, d2, y_lo, vl, sh, sl, x, c, ah, al, s, s2, tail
      integer :: row

      ! See lambert_w0p1: the methods of lambert_wm1p1_dd with tl = 0, written out.
      if (ieee_is_nan(t)) then
         v = quiet_nan
      else if (t < 0.0_wp) then
         v = quiet_nan
      else if (t <= 0.0_wp) then
         v = 0.0_wp
      else if (t < fast_tmax) then
         include "lambertw_small_t.inc"
         v = -sh + (tail - sl)
      else if (t < tb_tmax) then
         key = t
         row = geo_row(t, tb_base, tb_off)
         c1_lo = 0.0_wp
         include "lambertw_eval.inc"
         v = geo_tab(2, row) + y_lo
      else
         call lambert_wm1p1_dd(t, 0.0_wp, v, vl)
      end if
   end function lambert_wm1p1

   !> 1 + W0(-exp(-1 - t)) in double-double arithmetic: t = th + tl in, v = vh + vl out.
   !>
   !> For callers that compute t with extra precision (the restitution k(beta) needs
   !> t = beta - ln(1 + beta) to more than 53 bits) and divide v afterwards: vh is the
   !> correctly rounded value in the sense of `lambert_w0p1`, vl carries the next bits
   !> (as accurate as the method: about 1e-18 relative). Same domain rules as
   !> `lambert_w0p1`, applied to th; |tl| must be at most an ulp of th.
   elemental subroutine lambert_w0p1_dd(th, tl, vh, vl)
      !> Offset from the branch point, high part
      real(wp), intent(in) :: th
      !> Offset from the branch point, low part
      real(wp), intent(in) :: tl
      !> 1 + W0(-exp(-1 - t)), high part
      real(wp), intent(out) :: vh
      !> 1 + W0(-exp(-1 - t)), low part
      real(wp), intent(out) :: vl

      real(wp) :: sh, sl, key, c1_lo, d, d2, y_lo
      integer :: row

      vl = 0.0_wp
      if (ieee_is_nan(th)) then
         vh = quiet_nan
      else if (th < 0.0_wp) then
         vh = quiet_nan
      else if (th <= 0.0_wp) then
         vh = 0.0_wp
      else if (th < fast_tmax) then
         call sqrt_2t(th, tl, sh, sl)
         call fast_two_sum(sh, sl + sh * sh * series_tail(s_coef(2:8, 0), sh), vh, vl)
      else if (th < ta_tmax) then
         key = th
         row = geo_row(th, ta_base, ta_off)
         c1_lo = geo_tab(3, row) * tl
         include "lambertw_eval.inc"
         call fast_two_sum(geo_tab(2, row), y_lo, vh, vl)
      else
         ! t >= 32: z = -exp(-1-t) is above -6e-15; its rounding moves W0 by far less
         ! than an ulp of 1 + W0, and vl keeps W0 itself.
         call fast_two_sum(1.0_wp, lambert_w0(-exp(-1.0_wp - th)), vh, vl)
      end if
   end subroutine lambert_w0p1_dd

   !> 1 + W-1(-exp(-1 - t)) in double-double arithmetic: t = th + tl in, v = vh + vl out.
   !> See `lambert_w0p1_dd`; same domain rules as `lambert_wm1p1`, applied to th.
   elemental subroutine lambert_wm1p1_dd(th, tl, vh, vl)
      !> Offset from the branch point, high part
      real(wp), intent(in) :: th
      !> Offset from the branch point, low part
      real(wp), intent(in) :: tl
      !> 1 + W-1(-exp(-1 - t)), high part
      real(wp), intent(out) :: vh
      !> 1 + W-1(-exp(-1 - t)), low part
      real(wp), intent(out) :: vl

      real(wp) :: sh, sl, key, c1_lo, d, d2, y_lo
      integer :: row

      vl = 0.0_wp
      if (ieee_is_nan(th)) then
         vh = quiet_nan
      else if (th < 0.0_wp) then
         vh = quiet_nan
      else if (th <= 0.0_wp) then
         vh = 0.0_wp
      else if (th > huge(th)) then
         vh = minus_inf
      else if (th < fast_tmax) then
         call sqrt_2t(th, tl, sh, sl)
         call fast_two_sum(-sh, sh * sh * series_tail(s_coef(2:8, 0), -sh) - sl, vh, vl)
      else if (th < tb_tmax) then
         key = th
         row = geo_row(th, tb_base, tb_off)
         c1_lo = geo_tab(3, row) * tl
         include "lambertw_eval.inc"
         call fast_two_sum(geo_tab(2, row), y_lo, vh, vl)
      else
         call log1pmx_root(th, tl, vh, vl)
         vh = -vh
         vl = -vl
      end if
   end subroutine lambert_wm1p1_dd

   ! ---------------------------------------------------------------------------------
   ! Building blocks
   ! ---------------------------------------------------------------------------------

   !> c(1) + c(2) x + ... + c(7) x**6 by Estrin's scheme (short dependency chain)
   pure function series_tail(c, x) result(r)
      real(wp), intent(in) :: c(7), x
      real(wp) :: r
      real(wp) :: x2
      x2 = x * x
      r = ((c(1) + c(2)*x) + x2*(c(3) + c(4)*x)) + (x2*x2)*((c(5) + c(6)*x) + x2*c(7))
   end function series_tail

   !> W0(z) for |z| < 2**-6: z - z**2 R(z), R the near-minimax fit `w0_small` (11 terms,
   !> Estrin's scheme). z**2 R is at most 2**-6 |W0|, so its rounding errors hardly
   !> count and the result is rounded essentially once. Below 2**-60, W0 rounds to z.
   elemental function w0_small_z(z) result(w)
      real(wp), intent(in) :: z
      real(wp) :: w
      real(wp) :: z2, z4, r

      if (abs(z) < tiny_w0) then
         w = z
      else
         z2 = z * z
         z4 = z2 * z2
         r = ((w0_small(0) + w0_small(1)*z) + z2*(w0_small(2) + w0_small(3)*z)) &
            & + z4*(((w0_small(4) + w0_small(5)*z) + z2*(w0_small(6) + w0_small(7)*z)) &
            & + z4*((w0_small(8) + w0_small(9)*z) + z2*w0_small(10)))
         w = z - z2 * r
      end if
   end function w0_small_z

   !> Row in geo_tab of the key x > 0 (normal) for one table: the biased exponent and the
   !> first five fraction bits of x, minus the table's base, plus its offset. No clamp
   !> (it would lengthen the hot path): every caller's range of keys is an exact
   !> inequality on the same double that lies inside its table, and the Debug build
   !> checks the bounds.
   !> The bits of -z as an integer: for z < 0 they order as -z does; NaN gives more than
   !> those of any number
   elemental function mag_bits(z) result(m)
      real(wp), intent(in) :: z
      integer(int64) :: m
      m = transfer(-z, 0_int64)
   end function mag_bits

   elemental function geo_row(x, base, off) result(i)
      real(wp), intent(in) :: x
      integer, intent(in) :: base, off
      integer :: i
      i = int(shiftr(transfer(x, 0_int64), geo_shift)) + (off - base)
   end function geo_row

   !> s = sqrt(2t) as sh + sl for t = th + tl > 0 (2t is exact; tiny t is scaled so that
   !> the low part keeps its bits).
   elemental subroutine sqrt_2t(th, tl, sh, sl)
      real(wp), intent(in) :: th, tl
      real(wp), intent(out) :: sh, sl
      real(wp), parameter :: tiny_t = 2.0_wp**(-600)
      real(wp), parameter :: up = 2.0_wp**600, down = 2.0_wp**(-300)

      if (th < tiny_t) then
         call sqrt_dd(2.0_wp*(th*up), 2.0_wp*(tl*up), sh, sl)
         sh = sh * down
         sl = sl * down
      else
         call sqrt_dd(2.0_wp*th, 2.0_wp*tl, sh, sl)
      end if
   end subroutine sqrt_2t

   !> Root u = uh + ul > 3 of u - ln(1 + u) = t for t = th + tl >= 1024 here (so that
   !> -u = 1 + W-1(-exp(-1-t))). Newton's method; ln(1 + u) is evaluated as a
   !> double-double so the residual is accurate to about 3e-17 absolute, and the last
   !> correction is kept in ul.
   elemental subroutine log1pmx_root(th, tl, uh, ul)
      real(wp), intent(in) :: th, tl
      real(wp), intent(out) :: uh, ul
      real(wp) :: u, ah, al, lh, ll, r, du
      integer :: iter

      u = th + log1p(th + log1p(th))
      do iter = 1, max_iter
         call two_sum(1.0_wp, u, ah, al)
         call log_dd(ah, 0, lh, ll)
         ll = ll + al / ah
         r = (((u - th) - lh) - tl) - ll
         du = r * (ah / u)
         ! Newton's error after this step is below du**2/(2u(1+u)): negligible once
         ! |du| <= 2**-28 u, so this last step is applied in double-double.
         if (abs(du) <= 2.0_wp**(-28) * u .or. iter == max_iter) exit
         u = u - du
      end do
      call fast_two_sum(u, -du, uh, ul)
   end subroutine log1pmx_root

   include "../numerics/ddarith.inc"

   !> Square root of the double-double ah + al (ah > 0, normal and not huge).
   elemental subroutine sqrt_dd(ah, al, rh, rl)
      real(wp), intent(in) :: ah, al
      real(wp), intent(out) :: rh, rl
      real(wp) :: qh, ql
      rh = sqrt(ah)
      call two_prod(rh, rh, qh, ql)
      rl = (((ah - qh) - ql) + al) / (2.0_wp * rh)
   end subroutine sqrt_dd

end module hcimpact_lambertw
