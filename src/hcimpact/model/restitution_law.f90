! SPDX-License-Identifier: Apache-2.0
!> Restitution of the Hunt-Crossley impact as a function of beta = b V, and its inverse.
!>
!> With h(u) = u - ln(1 + u), the first integral (seed eq. 11) links the approach and
!> rebound velocities through h(b V+) = h(b V-), so the coefficient of restitution
!> depends on beta = b V- alone, for any elastic law and any mass (seed eq. 21):
!>
!>     k(beta) = (1 + W0(-(1 + beta) exp(-(1 + beta)))) / beta = V(h(beta)) / beta,
!>
!> where V(t) = 1 + W0(-exp(-1 - t)) is `lambert_w0p1`. Computing k this way in double
!> precision with a library W0 loses everything for small beta (the argument of W0 is
!> next to -1/e and 1 + W0 cancels). Here:
!> - beta < 40.1: local Taylor polynomials of k itself (generated with the other Lambert W
!>   tables), summed with one rounding;
!> - beyond: z = -(1 + beta) exp(-(1 + beta)) is below 2**-55, so 1 + W0(z) = 1 + z and
!>   k = (1 + z)/beta with one rounding;
!> - 1 - k, dk/dbeta and the inverse use h(beta) as a double-double and V from it
!>   (`lambert_w0p1_dd`), which keeps 1 - k accurate where k is close to 1.
!>
!> Accuracy against mpmath (test/unit/test_restitution.f90, doc/restitution.md): k within
!> 2 ulp for beta in [1e-300, 1e300], the inverse within 4 ulp for e in [1e-300, 1).
module hcimpact_restitution_law
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_libm, only : log1p
   use hcimpact_lambertw, only : lambert_w0p1_dd
   use hcimpact_restitution_tables, only : k_step_inv, k_last, k_coef, k_lo, m_step_inv, m_last, &
      & m_coef, m_lo
   implicit none
   private

   public :: u_minus_log1p, restitution, one_minus_restitution, energy_loss_ratio, &
      & restitution_derivative, restitution_inverse

   !> Below this beta the Taylor series of k at 0 is exact to double precision
   real(wp), parameter :: series_max = 2.0_wp**(-17)
   !> Above this beta, 1 + W0 = 1 exactly in double precision (exp(-1-h) < 2**-60)
   real(wp), parameter :: huge_beta = 2.0_wp**60
   !> Up to this beta, k comes from its Taylor table (tools/make_lambertw_tables.py)
   real(wp), parameter :: k_table_max = (k_last + 0.5_wp) / k_step_inv
   !> Up to this beta, k comes from the coarser second table
   real(wp), parameter :: m_table_max = (m_last + 0.5_wp) / m_step_inv
   !> Bound on the Newton iterations of the inverse
   integer, parameter :: max_newton = 40

contains

   !> h(u) = u - ln(1 + u) for u > -1 (MODEL.md): h >= 0, h(0) = 0, h ~ u**2/2.
   !>
   !> Accurate to about an ulp for all u > -1, including |u| near 0 where the difference
   !> cancels. NaN and u < -1 give NaN; u = -1 and u = +inf give +inf.
   elemental function u_minus_log1p(u) result(h)
      !> Argument, u > -1
      real(wp), intent(in) :: u
      !> u - ln(1 + u)
      real(wp) :: h
      real(wp) :: hh, hl, lh, ll

      if (ieee_is_nan(u)) then
         h = ieee_value(u, ieee_quiet_nan)
      else if (u < -1.0_wp) then
         h = ieee_value(u, ieee_quiet_nan)
      else if (u <= -1.0_wp .or. u > huge(u)) then
         h = ieee_value(u, ieee_positive_inf)
      else if (u < -0.5_wp) then
         ! 1 + u is exact here (Sterbenz); the logarithm carries ~3e-17 absolute error
         call log_dd(1.0_wp + u, 0, lh, ll)
         h = (u - lh) - ll
      else
         call h_dd(u, hh, hl)
         h = hh + hl
      end if
   end function u_minus_log1p

   !> Coefficient of restitution k(beta) = -V+/V- of the Hunt-Crossley impact.
   !>
   !> beta = b V- >= 0 (damping times approach speed, dimensionless). k(0) = 1 (Hertz),
   !> k decreases to 0 and k ~ 1/beta for large beta. NaN and beta < 0 give NaN;
   !> beta = +inf gives 0.
   elemental function restitution(beta) result(k)
      !> beta = b V-, dimensionless
      real(wp), intent(in) :: beta
      !> Coefficient of restitution
      real(wp) :: k
      real(wp) :: vh, vl, ql, ah, al, z
      integer :: i

      if (ieee_is_nan(beta)) then
         k = ieee_value(beta, ieee_quiet_nan)
      else if (beta < 0.0_wp) then
         k = ieee_value(beta, ieee_quiet_nan)
      else if (beta < series_max) then
         ! Taylor series at 0; the first omitted term, 40/189 beta**5, is below 2**-86
         k = 1.0_wp + beta*(-2.0_wp/3.0_wp + beta*(4.0_wp/9.0_wp + beta*(-44.0_wp/135.0_wp &
            & + beta*(104.0_wp/405.0_wp))))
      else if (beta < k_table_max) then
         i = int(beta * k_step_inv + 0.5_wp)
         k = taylor_plain(k_coef(:, i), k_lo(0, i), beta - i / k_step_inv)
      else if (beta < m_table_max) then
         i = int(beta * m_step_inv + 0.5_wp)
         k = taylor_plain(m_coef(:, i), m_lo(0, i), beta - i / m_step_inv)
      else if (beta <= huge_beta) then
         ! z = -(1 + beta) exp(-(1 + beta)), |z| < 7e-17: W0(z) = z - z**2 + ... = z to
         ! 2**-100 relative. 1 + beta = ah + al is kept exact. (Underflow of exp for
         ! beta > 745 is harmless.)
         call sum_parts(1.0_wp, beta, ah, al)
         z = -(ah * exp(-ah)) * (1.0_wp + al * (1.0_wp / ah - 1.0_wp))
         call fast_sum_parts(1.0_wp, z, vh, vl)
         call div_dd(vh, vl, beta, k, ql)
         k = k + ql
      else
         k = 1.0_wp / beta
      end if
   end function restitution

   !> 1 - k(beta), accurate (to a few ulp) also where k is close to 1.
   !>
   !> Equals 2 beta/3 - 4 beta**2/9 + ... for small beta. Same domain rules as `restitution`.
   elemental function one_minus_restitution(beta) result(d)
      !> beta = b V-, dimensionless
      real(wp), intent(in) :: beta
      !> 1 - k(beta)
      real(wp) :: d

      if (ieee_is_nan(beta)) then
         d = ieee_value(beta, ieee_quiet_nan)
      else if (beta < 0.0_wp) then
         d = ieee_value(beta, ieee_quiet_nan)
      else
         d = one_minus_k(beta)
      end if
   end function one_minus_restitution

   !> Fraction of the kinetic energy lost in the impact, 1 - k(beta)**2 = dT/T-.
   !>
   !> Computed as (1 - k)(1 + k) so that it keeps its relative accuracy for small beta
   !> (it equals 4 beta/3 - ... there). Same domain rules as `restitution`.
   elemental function energy_loss_ratio(beta) result(r)
      !> beta = b V-, dimensionless
      real(wp), intent(in) :: beta
      !> 1 - k**2
      real(wp) :: r
      real(wp) :: d

      d = one_minus_restitution(beta)
      r = d * (2.0_wp - d)
   end function energy_loss_ratio

   !> Derivative dk/dbeta of the coefficient of restitution (negative; -2/3 at beta = 0).
   !>
   !> Differentiating h(-k beta) = h(beta) gives
   !> dk/dbeta = -(1 + k) (k beta - (1 - k)) / (k beta (1 + beta)), whose factors do not
   !> cancel; the Taylor series is used for small beta. Same domain rules as `restitution`;
   !> beta = +inf gives -0.
   elemental function restitution_derivative(beta) result(dk)
      !> beta = b V-, dimensionless
      real(wp), intent(in) :: beta
      !> dk/dbeta
      real(wp) :: dk
      real(wp) :: vh, vl, k, d

      if (ieee_is_nan(beta)) then
         dk = ieee_value(beta, ieee_quiet_nan)
      else if (beta < 0.0_wp) then
         dk = ieee_value(beta, ieee_quiet_nan)
      else if (beta < series_max) then
         dk = -2.0_wp/3.0_wp + beta*(8.0_wp/9.0_wp + beta*(-44.0_wp/45.0_wp &
            & + beta*(416.0_wp/405.0_wp)))
      else if (beta > huge_beta) then
         ! k = 1/beta exactly in double precision here
         dk = -(1.0_wp / beta) / beta
      else
         call rebound_dd(beta, vh, vl)
         k = (vh + vl) / beta
         ! k beta - (1 - k) = V - (1 - k), V = k beta: for small V subtract 1 - k from V;
         ! for V near 1 add k to V - 1 (exact), or the difference would cancel.
         if (vh < 0.5_wp) then
            d = (vh - one_minus_k(beta)) + vl
         else
            d = ((vh - 1.0_wp) + vl) + k
         end if
         dk = -((1.0_wp + k) * d) / ((vh + vl) * (1.0_wp + beta))
      end if
   end function restitution_derivative

   !> The exact inverse: the beta >= 0 with k(beta) = e, for a target restitution e in (0, 1].
   !>
   !> Then b = beta/V- gives that restitution at approach speed V-. beta(1) = 0,
   !> beta(0.5) = 1.4327505332713750, beta ~ 1/e for small e. e outside (0, 1] and NaN
   !> give NaN; e below 1/huge (where the exact beta exceeds the largest double) gives
   !> +inf. Newton's method on 1 - k(beta) = 1 - e (for e >= 1/2, where 1 - e is exact)
   !> or on k(beta) = e, at most 40 steps.
   elemental function restitution_inverse(e) result(beta)
      !> Target coefficient of restitution, 0 < e <= 1
      real(wp), intent(in) :: e
      !> beta = b V-
      real(wp) :: beta
      real(wp) :: delta, r, step, trial
      integer :: iter
      logical :: near_one

      if (ieee_is_nan(e)) then
         beta = ieee_value(e, ieee_quiet_nan)
         return
      else if (e <= 0.0_wp .or. e > 1.0_wp) then
         beta = ieee_value(e, ieee_quiet_nan)
         return
      else if (e >= 1.0_wp) then
         beta = 0.0_wp
         return
      else if (e < 1.0_wp / huge(e)) then
         beta = ieee_value(e, ieee_positive_inf)
         return
      else if (e < 1.0_wp / huge_beta) then
         ! beta > 2**60, where k = (1 - exp(-1 - h))/beta = 1/beta to far below an ulp
         beta = 1.0_wp / e
         return
      end if

      near_one = e >= 0.5_wp
      delta = 1.0_wp - e
      if (near_one) then
         ! Series inverse of 1 - k = 2 beta/3 - 4 beta**2/9 + 44 beta**3/135 - ...
         beta = 1.5_wp * delta * (1.0_wp + delta * (1.0_wp + delta * 0.9_wp))
      else if (e < 0.05_wp) then
         ! k = (1 + W0)/beta with 1 + W0 -> 1 for large beta
         beta = 1.0_wp / e
      else
         ! Carvalho and Martins (2019): close to the exact inverse on this range
         beta = 1.5_wp * delta * (11.0_wp - e) / (1.0_wp + 9.0_wp * e)
      end if

      do iter = 1, max_newton
         if (near_one) then
            r = one_minus_k(beta) - delta
            step = r / restitution_derivative(beta)
            trial = beta + step
         else
            r = restitution(beta) - e
            step = r / restitution_derivative(beta)
            trial = beta - step
         end if
         ! Stay inside the domain if a step overshoots below zero
         if (trial <= 0.0_wp) trial = 0.25_wp * beta
         if (abs(trial - beta) <= 2.0_wp**(-30) * beta) then
            ! Quadratic convergence: this step is exact to far below an ulp
            beta = trial
            exit
         end if
         beta = trial
      end do
   end function restitution_inverse

   ! ---------------------------------------------------------------------------------
   ! Building blocks
   ! ---------------------------------------------------------------------------------

   !> 1 - k(beta) for beta >= 0 (not NaN): series for small beta, (beta - V)/beta with
   !> V = k beta as a double-double otherwise, so the difference does not cancel.
   elemental function one_minus_k(beta) result(d)
      real(wp), intent(in) :: beta
      real(wp) :: d
      real(wp) :: vh, vl, sh, sl

      if (beta < series_max) then
         d = beta*(2.0_wp/3.0_wp + beta*(-4.0_wp/9.0_wp + beta*(44.0_wp/135.0_wp &
            & + beta*(-104.0_wp/405.0_wp))))
      else if (beta > huge_beta) then
         d = 1.0_wp - 1.0_wp / beta
      else
         call rebound_dd(beta, vh, vl)
         call sum_parts(beta, -vh, sh, sl)
         d = (sh + (sl - vl)) / beta
      end if
   end function one_minus_k

   !> k beta = 1 + W0(-exp(-1 - h(beta))) as a double-double, beta > 0 finite.
   elemental subroutine rebound_dd(beta, vh, vl)
      real(wp), intent(in) :: beta
      real(wp), intent(out) :: vh, vl
      real(wp) :: hh, hl
      call h_dd(beta, hh, hl)
      call lambert_w0p1_dd(hh, hl, vh, vl)
   end subroutine rebound_dd

   !> h(u) = u - ln(1 + u) as a double-double hh + hl, for -1/2 <= u finite.
   !>
   !> |u| <= 1: with y = u/(2 + u), ln(1 + u) = 2 atanh(y), so
   !>     h = u**2/(2 + u) - 2 (y**3/3 + y**5/5 + ...),
   !> two positive-leaning terms without cancellation; the first is formed as a
   !> double-double, the second (at most 7% of h) in double. u > 1: u - ln(1 + u) with
   !> the logarithm as a double-double (absolute error ~3e-17, below an ulp of h >= 0.3).
   elemental subroutine h_dd(u, hh, hl)
      real(wp), intent(in) :: u
      real(wp), intent(out) :: hh, hl
      real(wp) :: ph, pl, dh, dl, qh, ql, y, y2, series, ah, al, lh, ll, sh, sl
      integer :: k

      if (abs(u) <= 1.0_wp) then
         call product_parts(u, u, ph, pl)
         call sum_parts(2.0_wp, u, dh, dl)
         ! (ph + pl)/(dh + dl) as a double-double
         qh = ph / dh
         call product_parts(qh, dh, sh, sl)
         ql = ((((ph - sh) - sl) + pl) - qh * dl) / dh
         y = u / dh
         y2 = y * y
         ! sum_{j>=0} y2**j/(2j + 3): 18 terms reach 2**-57 relative for |y| <= 1/3
         series = 1.0_wp / 39.0_wp
         do k = 17, 0, -1
            series = series * y2 + 1.0_wp / real(2*k + 3, wp)
         end do
         series = 2.0_wp * y * y2 * series
         call sum_parts(qh, -series, sh, sl)
         call fast_sum_parts(sh, sl + ql, hh, hl)
      else
         call sum_parts(1.0_wp, u, ah, al)
         call log_dd(ah, 0, lh, ll)
         ll = ll + al / ah
         call sum_parts(u, -lh, sh, sl)
         call fast_sum_parts(sh, sl - ll, hh, hl)
      end if
   end subroutine h_dd

   !> c0 + c1 d + ... + c13 d**13 with c0 extended by c0_lo, for the k tables.
   !>
   !> On these tables |c1 d| is at most 2% of k (spacing 1/16 near beta = 0, where
   !> k' = -2/3), so the polynomial part can be summed in plain double and added to c0
   !> last: the result is rounded once up to ~0.01 ulp. Estrin's scheme keeps the
   !> dependency chain short; the rounding of d = beta - xc is negligible for the same
   !> reason, so the index needs no exact rounding.
   pure function taylor_plain(c, c0_lo, d) result(y)
      real(wp), intent(in) :: c(0:13), c0_lo, d
      real(wp) :: y
      real(wp) :: d2, d4, d8, p
      d2 = d * d
      d4 = d2 * d2
      d8 = d4 * d4
      p = ((c(1) + c(2)*d) + d2*(c(3) + c(4)*d)) + d4*((c(5) + c(6)*d) + d2*(c(7) + c(8)*d)) &
         & + d8*(((c(9) + c(10)*d) + d2*(c(11) + c(12)*d)) + d4*c(13))
      y = c(0) + (c0_lo + d * p)
   end function taylor_plain

   !> (ah + al) / b as a double-double (b a nonzero double of moderate size)
   elemental subroutine div_dd(ah, al, b, qh, ql)
      real(wp), intent(in) :: ah, al, b
      real(wp), intent(out) :: qh, ql
      real(wp) :: ph, pl
      qh = ah / b
      call product_parts(qh, b, ph, pl)
      ql = (((ah - ph) - pl) + al) / b
   end subroutine div_dd

   include "../numerics/ddarith.inc"

end module hcimpact_restitution_law
