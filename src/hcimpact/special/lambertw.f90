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
!> Method (errors measured by test/unit/test_lambertw.f90 against mpmath, at most 0.52 ulp
!> anywhere; see doc/lambertw.md). Plain double arithmetic with one final rounding of a
!> dominant term plus a small correction; no iteration but for 1 + W-1 at t >= 1024.
!> - "Geometric" tables (tools/make_lambertw_tables.py): the key x (an exact double:
!>   z + 1/e_hi for z <= -1/4, |z|, t, or ln|z| as a double-double) is cut into intervals
!>   [2**k (1 + j/32), 2**k (1 + (j+1)/32)) found from the bits of x (no search), each
!>   with a degree-8 near-minimax polynomial in x - centre whose leading coefficient is a
!>   double-double (lambertw_eval.inc). They reach down to the branch point itself: by
!>   z + 1/e_hi to its least nonzero value 2**-54, by t to 2**-54, so that no square root
!>   and no series is needed there.
!> - One path, without a branch between tables, for most of each function's domain: W0 on
!>   [-1/e, 0) (tables by z + 1/e_hi and -z, chosen by an integer mask from the bits of z)
!>   and on [0, 2**10) (by z), |z| < 2**-9 clamped to a row holding W0's Taylor polynomial
!>   at 0; W-1 on [-1/e, -2**-20] (by z + 1/e_hi and -z); 1 + W0 for t >= 2**-54 (t clamped
!>   at 64, where 1 + W0 rounds to 1); 1 + W-1 on [2**-54, 2**10). Random arguments then
!>   cost no mispredicted branch (W0's branch on the sign of z only if the signs are
!>   mixed). Beyond: W0 and W-1 by ln|z| (a table logarithm,
!>   lambertw_ln.inc, no call), 1 + W-1 by Newton's method on u - ln(1 + u) = t, and for
!>   t < 2**-54 the series at the branch point in s = sqrt(2t) (lambertw_small_t.inc).
!> The hot paths are written inline (include files): gfortran does not inline procedures
!> used in several places, and a call costs as much as the rest of a table evaluation.
!>
!> Every loop is bounded. No procedure stops or prints; outside the domain the result is NaN.
module hcimpact_lambertw
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_libm, only : log1p
   use hcimpact_lambertw_tables, only : s_coef, ln_tab, ln_bits, geo_shift, &
      & wa_off, wa_base, wa_row0, wb_off, wb_base, wb_row0, wc_off, wc_base, wc_row0, &
      & wd_off, wd_base, wd_row0, we_off, we_base, ta_off, ta_base, ta_key_max, &
      & tb_off, tb_base, ya_off, ya_base, yb_off, yb_base
   implicit none
   private

   public :: lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1
   public :: lambert_w0p1_dd, lambert_wm1p1_dd

   !> A quiet NaN and -inf as constants: ieee_value is a library call, whose memory
   !> argument would give every function a stack frame on its fast paths too
   real(wp), parameter :: quiet_nan = transfer(int(z'7FF8000000000000', int64), 1.0_wp)
   real(wp), parameter :: minus_inf = transfer(int(z'FFF0000000000000', int64), 1.0_wp)
   !> 1/e rounded to a double: z + 1/e_hi is exact for z <= -1/4 (Sterbenz), the key of the
   !> tables `wa` and `wb`, zero at the double nearest -1/e
   real(wp), parameter :: inv_e_hi = 0.36787944117144233_wp
   !> All bits of a binary64 but its sign
   integer(int64), parameter :: magnitude_bits = int(z'7FFFFFFFFFFFFFFF', int64)
   !> The bits of +inf: a finite non-negative double has fewer
   integer(int64), parameter :: inf_bits = int(z'7FF0000000000000', int64)
   !> The bits of 1/e_hi: -1/e_hi <= z < 0 is a sign bit and at most these
   integer(int64), parameter :: inv_e_bits = transfer(inv_e_hi, 0_int64)
   !> W0 and W-1 for z <= -1/4 come from the tables `wa` and `wb`, keyed by z + 1/e_hi:
   !> the bits of 1/4 (|z| >= 1/4)
   integer(int64), parameter :: quarter_bits = transfer(0.25_wp, 0_int64)
   !> W0 from the tables for z < 2**10 (beyond, by ln z): the bits below those of 2**10
   integer(int64), parameter :: w0_table_top = transfer(2.0_wp**10, 0_int64) - 1_int64
   !> W-1 from the tables for -z >= 2**-20 (below, by ln(-z)): the bits of 2**-20
   real(wp), parameter :: tiny_zmax = 2.0_wp**(-20)
   integer(int64), parameter :: wm1_table_bottom = transfer(tiny_zmax, 0_int64)
   !> 1 + W from the tables `ta`/`tb` keyed by t for t >= 2**-54 (1 + W-1: t < 2**10):
   !> below, the series at the branch point
   real(wp), parameter :: t_table_min = 2.0_wp**(-54)
   integer(int64), parameter :: t_table_bottom = transfer(t_table_min, 0_int64)
   real(wp), parameter :: tb_tmax = 2.0_wp**10
   integer(int64), parameter :: tb_table_top = transfer(tb_tmax, 0_int64)
   !> Bits of the key at which 1 + W0's table is clamped (its top row, the constant 1)
   integer(int64), parameter :: ta_key_max_bits = transfer(ta_key_max, 0_int64)
   !> Scale that brings a subnormal argument of ln into the normal range
   real(wp), parameter :: scale_up = 2.0_wp**600
   !> ln 2 in two parts, k*ln2_hi exact for |k| < 2**21 (lambertw_ln.inc)
   real(wp), parameter :: ln2_hi = 0.6931471803691238_wp, ln2_lo = 1.9082149292705877e-10_wp
   !> Fraction bits and the exponent of 1 of a binary64 (lambertw_ln.inc)
   integer(int64), parameter :: fraction_bits = int(z'000FFFFFFFFFFFFF', int64)
   integer(int64), parameter :: exponent_one = int(z'3FF0000000000000', int64)
   !> Sign, exponent and first ln_bits fraction bits of a binary64, and the bit below them
   integer(int64), parameter :: m0_mask = not(2_int64**(52 - ln_bits) - 1_int64)
   integer(int64), parameter :: m0_half = 2_int64**(51 - ln_bits)
   !> t below which s = sqrt(2t) < 2**-6 (the series at the branch point in
   !> lambert_w0p1_dd and lambert_wm1p1_dd)
   real(wp), parameter :: fast_tmax = 0.5_wp * (2.0_wp**(-6))**2
   !> 1 + W0 from t in double-double: the table `ta` below this t (beyond, 1 + W0(z))
   real(wp), parameter :: ta_tmax = 2.0_wp**5
   !> Bound on the number of iterations of every loop in this module
   integer, parameter :: max_iter = 8

contains

   !> Principal branch W0(z) of the Lambert W function.
   !>
   !> Domain z >= -1/e; W0 >= -1. NaN and z below the branch point give NaN. The double
   !> nearest to -1/e (-0.36787944117144233, 1.2e-17 below -1/e) stands for the branch
   !> point and gives -1 exactly; every lower double gives NaN. W0(+inf) = +inf,
   !> W0(+-0) = +-0.
   elemental function lambert_w0(z) result(w)
      use hcimpact_lambertw_tables, only : tab => geo_z
      !> Argument
      real(wp), value, intent(in) :: z
      !> W0(z)
      real(wp) :: w

      real(wp) :: key, key_lo, d, d2, y_lo, x, m, f, g, g2, p, kr, y1, lh, ll
      integer :: row, shift, j, near
      integer(int64) :: zb, ab

      ! One table evaluation for -1/e_hi <= z < 2**10 (but -0): the branch on the sign is
      ! the only one on the way (arguments of one sign do not mispredict it); between the
      ! two tables of negative z an integer mask chooses, not a branch (merge_bits, bitwise
      ! operations; gfortran compiles `merge` to a jump, and with random arguments a
      ! branch between tables is mispredicted often, each time costing more than the
      ! work): z <= -1/4: `wa` by d = z + 1/e_hi (exact there by Sterbenz; d = 0, the
      ! double nearest -1/e, clamps to its bottom row, -1); -1/4 < z < 0: `wc` by -z;
      ! 0 <= z < 2**10: `wd` by z. |z| < 2**-9 clamps to the bottom row of `wc`/`wd`, W0's
      ! Taylor polynomial at 0. The range tests are on integers: NaN fails them without
      ! an ordered comparison (which would raise the invalid flag, a trap in the Debug
      ! build).
      zb = transfer(z, 0_int64)
      if (zb < 0_int64) then
         ab = iand(zb, magnitude_bits)
         if (ab > 0_int64 .and. ab <= inv_e_bits) then
            near = int(shifta(quarter_bits - 1_int64 - ab, 63))     ! -1 for z <= -1/4
            d = z + inv_e_hi
            key = transfer(merge_bits(transfer(d, 0_int64), ab, int(near, int64)), key)
            row = max(merge_bits(wa_row0, wc_row0, near), &
               & int(shiftr(transfer(key, 0_int64), geo_shift)) &
               & + merge_bits(wa_off - wa_base, wc_off - wc_base, near))
            include "lambertw_eval.inc"
            w = tab(2, row) + y_lo
         else if (ab == 0_int64) then
            w = z                                                 ! -0
         else
            w = quiet_nan                                         ! below -1/e, NaN
         end if
      else if (zb <= w0_table_top) then
         key = z
         row = max(wd_row0, geo_row(z, wd_base, wd_off))
         include "lambertw_eval.inc"
         w = tab(2, row) + y_lo
      else if (zb < inf_bits) then
         ! 2**10 <= z < inf: W0 as a function of y = ln z: ln z is a double-double
         ! (absolute error ~2e-18), and dW/dy = W/(1 + W) < 1, so its error stays far
         ! below an ulp of W > 5.
         x = z
         shift = 0
         include "lambertw_ln.inc"
         call fast_sum_parts(lh, ll, key, key_lo)
         ! The row from y1 (within 2**-17 of y): the polynomials hold 1/64 of their
         ! half-width (> 2**-11 here) beyond their intervals, and key - xc stays exact.
         row = geo_row(y1, ya_base, ya_off)
         include "lambertw_eval.inc"
         w = tab(2, row) + (y_lo + tab(3, row) * key_lo)
      else if (ieee_is_nan(z)) then
         w = quiet_nan
      else
         w = z                                                    ! +inf
      end if
   end function lambert_w0

   !> Lower branch W-1(z) of the Lambert W function.
   !>
   !> Domain -1/e <= z < 0; W-1 <= -1. NaN, z > 0 and z below the branch point give NaN;
   !> z = 0 (either sign: the end of the domain, as for ln(+-0)) gives -inf, the limit
   !> from below. The double nearest to -1/e gives -1 exactly, as for `lambert_w0`.
   elemental function lambert_wm1(z) result(w)
      use hcimpact_lambertw_tables, only : tab => geo_z
      !> Argument
      real(wp), value, intent(in) :: z
      !> W-1(z)
      real(wp) :: w

      real(wp) :: key, key_lo, d, d2, y_lo, x, m, f, g, g2, p, kr, y1, lh, ll
      integer :: row, shift, j, near
      integer(int64) :: zb, ab

      ! -1/e_hi <= z <= -2**-20 (most calls): one table evaluation, the table chosen by
      ! an integer mask as in lambert_w0: z <= -1/4: `wb` by d = z + 1/e_hi (d = 0 clamps
      ! to its bottom row, -1); beyond: `we` by -z. Range tests on integers (NaN fails).
      zb = transfer(z, 0_int64)
      ab = iand(zb, magnitude_bits)
      if (zb < 0_int64 .and. ab >= wm1_table_bottom .and. ab <= inv_e_bits) then
         near = int(shifta(quarter_bits - 1_int64 - ab, 63))       ! -1 for z <= -1/4
         d = z + inv_e_hi
         key = transfer(merge_bits(transfer(d, 0_int64), ab, int(near, int64)), key)
         row = max(merge_bits(wb_row0, we_off, near), &
            & int(shiftr(transfer(key, 0_int64), geo_shift)) &
            & + merge_bits(wb_off - wb_base, we_off - we_base, near))
         include "lambertw_eval.inc"
         w = tab(2, row) + y_lo
      else if (ieee_is_nan(z)) then
         w = quiet_nan
      else if (zb < 0_int64 .and. ab < wm1_table_bottom .and. ab > 0_int64) then
         ! -2**-20 < z < 0: W-1 as a function of y = -ln(-z) > 13.8, ln(-z) a double-double
         ! (subnormal z scaled first): dW/dy = -W/(1 + W) is near 1, so the ~2e-18 error
         ! of y stays far below an ulp of |W| > 17.
         x = -z
         shift = 0
         if (x < tiny(x)) then
            x = x * scale_up
            shift = -600
         end if
         include "lambertw_ln.inc"
         call fast_sum_parts(-lh, -ll, key, key_lo)
         row = geo_row(-y1, yb_base, yb_off)     ! y1: see lambert_w0
         include "lambertw_eval.inc"
         w = tab(2, row) + (y_lo + tab(3, row) * key_lo)
      else if (ab == 0_int64) then
         w = minus_inf
      else
         w = quiet_nan                           ! z > 0, or below the branch point
      end if
   end function lambert_wm1

   !> 1 + W0(-exp(-1 - t)) for t >= 0, computed from t without forming z.
   !>
   !> Equals sqrt(2t) - 2t/3 + ... for small t and tends to 1 as t grows: it is the
   !> root v in [0, 1) of -v - ln(1 - v) = t. NaN and t < 0 give NaN; +inf gives 1.
   elemental function lambert_w0p1(t) result(v)
      use hcimpact_lambertw_tables, only : tab => geo_t
      !> Offset from the branch point, t = -1 - ln(-z)
      real(wp), value, intent(in) :: t
      !> 1 + W0(-exp(-1 - t))
      real(wp) :: v

      real(wp), parameter :: sgn = 1.0_wp
      real(wp), parameter :: split_factor = 134217729.0_wp   ! 2**27 + 1
      real(wp) :: key, d, d2, y_lo, sh, sl, x, c, ah, al, s, s2, tail
      integer :: row
      integer(int64) :: tbits

      ! 2**-54 <= t < inf (NaN and t < 0 fail the integer range test): the table `ta` by t,
      ! the key clamped at 64 (as integers: the bits of non-negative doubles order as
      ! they do), where the table's top row holds 1 + W0 = 1.
      tbits = transfer(t, 0_int64)
      if (tbits >= t_table_bottom .and. tbits < inf_bits) then
         key = transfer(min(tbits, ta_key_max_bits), key)
         row = geo_row(key, ta_base, ta_off)
         include "lambertw_eval.inc"
         v = tab(2, row) + y_lo
      else if (ieee_is_nan(t)) then
         v = quiet_nan
      else if (t < 0.0_wp) then
         v = quiet_nan
      else if (t <= 0.0_wp) then
         v = 0.0_wp
      else if (t < t_table_min) then
         include "lambertw_small_t.inc"
         v = sh + (sl + tail)
      else
         v = 1.0_wp                              ! t = +inf
      end if
   end function lambert_w0p1

   !> 1 + W-1(-exp(-1 - t)) for t >= 0, computed from t without forming z.
   !>
   !> Equals -sqrt(2t) - 2t/3 - ... for small t and tends to -inf as t grows: it is -u
   !> for the root u >= 0 of u - ln(1 + u) = t. NaN and t < 0 give NaN; +inf gives -inf.
   elemental function lambert_wm1p1(t) result(v)
      use hcimpact_lambertw_tables, only : tab => geo_t
      !> Offset from the branch point, t = -1 - ln(-z)
      real(wp), value, intent(in) :: t
      !> 1 + W-1(-exp(-1 - t))
      real(wp) :: v

      real(wp), parameter :: sgn = -1.0_wp
      real(wp), parameter :: split_factor = 134217729.0_wp   ! 2**27 + 1
      real(wp) :: key, d, d2, y_lo, vl, sh, sl, x, c, ah, al, s, s2, tail, t_copy
      integer :: row
      integer(int64) :: tbits

      ! 2**-54 <= t < 2**10 (integer range test: NaN and t < 0 fail it): the table `tb`.
      tbits = transfer(t, 0_int64)
      if (tbits >= t_table_bottom .and. tbits < tb_table_top) then
         key = t
         row = geo_row(t, tb_base, tb_off)
         include "lambertw_eval.inc"
         v = tab(2, row) + y_lo
      else if (ieee_is_nan(t)) then
         v = quiet_nan
      else if (t < 0.0_wp) then
         v = quiet_nan
      else if (t <= 0.0_wp) then
         v = 0.0_wp
      else if (t < t_table_min) then
         include "lambertw_small_t.inc"
         v = -sh + (tail - sl)
      else
         ! t >= 2**10: Newton's method. The call takes its arguments by reference: a copy
         ! of t, so that t itself never needs an address (the fast path would otherwise
         ! store it and load its bits back, a store-to-load round trip on every call).
         t_copy = t
         call lambert_wm1p1_dd(t_copy, 0.0_wp, v, vl)
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
      use hcimpact_lambertw_tables, only : tab => geo_t
      !> Offset from the branch point, high part
      real(wp), intent(in) :: th
      !> Offset from the branch point, low part
      real(wp), intent(in) :: tl
      !> 1 + W0(-exp(-1 - t)), high part
      real(wp), intent(out) :: vh
      !> 1 + W0(-exp(-1 - t)), low part
      real(wp), intent(out) :: vl

      real(wp) :: sh, sl, key, d, d2, y_lo
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
         call fast_sum_parts(sh, sl + sh * sh * series_tail(s_coef(2:8, 0), sh), vh, vl)
      else if (th < ta_tmax) then
         key = th
         row = geo_row(th, ta_base, ta_off)
         include "lambertw_eval.inc"
         call fast_sum_parts(tab(2, row), y_lo + tab(3, row) * tl, vh, vl)
      else
         ! t >= 32: z = -exp(-1-t) is above -6e-15; its rounding moves W0 by far less
         ! than an ulp of 1 + W0, and vl keeps W0 itself.
         call fast_sum_parts(1.0_wp, lambert_w0(-exp(-1.0_wp - th)), vh, vl)
      end if
   end subroutine lambert_w0p1_dd

   !> 1 + W-1(-exp(-1 - t)) in double-double arithmetic: t = th + tl in, v = vh + vl out.
   !> See `lambert_w0p1_dd`; same domain rules as `lambert_wm1p1`, applied to th.
   elemental subroutine lambert_wm1p1_dd(th, tl, vh, vl)
      use hcimpact_lambertw_tables, only : tab => geo_t
      !> Offset from the branch point, high part
      real(wp), intent(in) :: th
      !> Offset from the branch point, low part
      real(wp), intent(in) :: tl
      !> 1 + W-1(-exp(-1 - t)), high part
      real(wp), intent(out) :: vh
      !> 1 + W-1(-exp(-1 - t)), low part
      real(wp), intent(out) :: vl

      real(wp) :: sh, sl, key, d, d2, y_lo
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
         call fast_sum_parts(-sh, sh * sh * series_tail(s_coef(2:8, 0), -sh) - sl, vh, vl)
      else if (th < tb_tmax) then
         key = th
         row = geo_row(th, tb_base, tb_off)
         include "lambertw_eval.inc"
         call fast_sum_parts(tab(2, row), y_lo + tab(3, row) * tl, vh, vl)
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

   !> Row in the table array of the key x > 0 for one table: the biased exponent and the first
   !> five fraction bits of x, minus the table's base, plus its offset. No clamp here:
   !> every caller's range of keys is an exact inequality on the same double that lies
   !> inside its table, or the caller clamps to the table's bottom row (max) or its key
   !> to the table's top row (min); the Debug build checks the bounds.
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
         call sum_parts(1.0_wp, u, ah, al)
         call log_dd(ah, 0, lh, ll)
         ll = ll + al / ah
         r = (((u - th) - lh) - tl) - ll
         du = r * (ah / u)
         ! Newton's error after this step is below du**2/(2u(1+u)): negligible once
         ! |du| <= 2**-28 u, so this last step is applied in double-double.
         if (abs(du) <= 2.0_wp**(-28) * u .or. iter == max_iter) exit
         u = u - du
      end do
      call fast_sum_parts(u, -du, uh, ul)
   end subroutine log1pmx_root

   include "../numerics/ddarith.inc"

   !> Square root of the double-double ah + al (ah > 0, normal and not huge).
   elemental subroutine sqrt_dd(ah, al, rh, rl)
      real(wp), intent(in) :: ah, al
      real(wp), intent(out) :: rh, rl
      real(wp) :: qh, ql
      rh = sqrt(ah)
      call product_parts(rh, rh, qh, ql)
      rl = (((ah - qh) - ql) + al) / (2.0_wp * rh)
   end subroutine sqrt_dd

end module hcimpact_lambertw
