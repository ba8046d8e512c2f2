! SPDX-License-Identifier: Apache-2.0
!> The scales of one power-law impact (x_max, the time and force units, the trajectory
!> in double-double) and its time integrand; the peak of the force.
!>
!> m x'' = -c x^n (1 + b x'): beta = b V is formed exactly, x_max from a sum of
!> logarithms (or one product) in double-double, the trajectory (restitution, the ends
!> of the phases) in hcimpact_trajectory. The rules that integrate the time integrand
!> are scheduled in hcimpact_power_rules; the outputs are assembled in
!> hcimpact_power_impact.
module hcimpact_power_model
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp, exponent_from_bits
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_domain
   use hcimpact_libm, only : log1p, expm1
   use hcimpact_double_double, only : dd_real, dd, two_sum, two_prod, operator(+), &
      & operator(-), operator(*), operator(/), &
      & dd_exp, dd_log, dd_sqrt, dd_scale, dd_inverse
   use hcimpact_contact, only : contact_type, max_beta
   use hcimpact_trajectory, only : new_trajectory, phase_integrand, compression_phase, &
      & restitution_phase, h_over_square_dd, h_over_square, turn_q, end_r, log_form_beta
   implicit none
   private

   public :: power_integrand, power_model, new_power_model, set_end_times, power_peak
   public :: turn_log_share, end_log_share, peak_ratio_m1, peak_series_max_y

   !> Time integrand of the power law: (x/x_max)^(-n) - 1 per unit l; `flat` = 1.
   type, extends(phase_integrand) :: power_integrand
      !> alpha = n/(n+1) as a double-double number
      real(wp) :: alpha_hi = 0.0_wp, alpha_lo = 0.0_wp
      !> Time of the last d before an end of contact = end_coef d^(1/(n+1))
      real(wp) :: end_coef(2) = 0.0_wp
      !> 1/(n+1)
      real(wp) :: inv_np1 = 0.0_wp
   contains
      procedure :: density => power_density
      procedure :: end_time => power_end_time
   end type power_integrand

   !> Scales of one power-law impact
   type :: power_model
      !> The integrand, with the trajectory
      type(power_integrand) :: f
      !> n, n + 1, approach speed
      real(wp) :: n = 0.0_wp, np1 = 0.0_wp, velocity = 0.0_wp
      !> n + 1 exactly
      type(dd_real) :: np1_dd
      !> 1/(n + 1) (to 2**-105 relative)
      type(dd_real) :: inv_np1_dd
      !> ln x_max and x_max (m). For n = 1 with `energy_ok`, x_max is a square root and
      !> ln_x_max only its double part (ln_x_max_dd false: dd_log(x_max) where needed)
      type(dd_real) :: ln_x_max, x_max
      logical :: ln_x_max_dd = .true.
      !> ln(c x_max^n), c x_max^n in N: set by set_end_times (the time law only)
      type(dd_real) :: ln_force_unit
      !> Seconds per unit of the integrals: x_max/((n+1) H V)
      type(dd_real) :: time_unit
      !> Contact constant c and damping b
      real(wp) :: stiffness = 0.0_wp, damping = 0.0_wp
      !> (n+1) m V^2 H in J, when `energy_ok` (its factors well inside the double range)
      type(dd_real) :: energy
      logical :: energy_ok = .false.
      !> 1/H as the double nearest to it and the rest (the nodes multiply by it)
      real(wp) :: inv_hq(2) = 0.0_wp
      !> 1/(beta_hi^2 H) = 1/h(beta) as two doubles (the phases' nodes with |beta l| > 2;
      !> set by power_phase_times)
      real(wp) :: inv_hb(2)
   end type power_model

   !> Below this y = 1 - (x_peak/x_max)^(n+1) (beta below about 0.04), x_peak/x_max - 1
   !> by the series of `peak_ratio_m1` instead of a logarithm and an exponential in
   !> double-double
   real(wp), parameter :: peak_series_max_y = 2.0_wp**(-8)

contains

   !> Set up the scales of a power-law impact (the contact must be valid).
   !>
   !> x_max^(n+1) = (n+1) m V^2 H / c is formed as a double-double product when it and
   !> its factors are well inside the double range (one logarithm then), else as a
   !> sum of logarithms; either way x_max = exp(ln(x_max^(n+1))/(n+1)) in double-double.
   !> c x_max^n = (n+1) m V^2 H / x_max needs no further exponential.
   pure subroutine new_power_model(contact, model, stat, depth_only)
      type(contact_type), intent(in) :: contact
      type(power_model), intent(out) :: model
      integer, intent(out) :: stat
      !> Only beta, the trajectory and x_max are wanted (velocity_at_depth): the ranges
      !> of the force and time units, which only the outcome and the time law need, are
      !> not required
      logical, intent(in), optional :: depth_only
      ! results beyond exp(+-log_limit) would overflow or lose their precision
      real(wp), parameter :: log_limit = 690.0_wp
      ! a product of factors each within 2**(+-safe_exponent) (about exp(+-120)) cannot
      ! leave the double range
      integer, parameter :: safe_exponent = 173
      real(wp), parameter :: ln2 = 0.69314718055994531_wp
      type(dd_real) :: beta, np1, alpha, hq, ln_v, t, energy, base
      integer :: em, ev, ec, eh

      stat = hcimpact_ok
      ! beta = b V above max_beta: the exponents first, for a product that would overflow
      ! (b V < 2**(e_b + e_V); b = 0 is beta = 0 whatever V), then the product itself
      if (contact%damping > 0.0_wp .and. &
         & exponent_from_bits(contact%damping) + exponent_from_bits(contact%velocity) &
         & > exponent(max_beta) + 1) then
         stat = hcimpact_err_domain
         return
      end if
      beta = two_prod(contact%damping, contact%velocity)
      if (beta%hi > max_beta) then
         stat = hcimpact_err_domain
         return
      end if
      model%f%tr = new_trajectory(beta)
      hq = model%f%tr%hq
      ! (never true for a valid contact; the range tests below read binary exponents,
      ! and exponent() of a NaN or an infinity is huge(0), which must not be added to)
      if (.not. ieee_is_finite(hq%hi)) then
         stat = hcimpact_err_domain
         return
      end if
      model%n = contact%exponent
      np1 = two_sum(contact%exponent, 1.0_wp)
      ! n + 1 above 2^996: 1/(n+1) and the products with it would leave the range of
      ! the double-double arithmetic (its splitting overflows), and x_max = 1 m to the
      ! last bit for any contact there anyway
      if (.not. np1%hi < 2.0_wp**996) then
         stat = hcimpact_err_domain
         return
      end if
      model%np1 = np1%hi
      model%np1_dd = np1
      model%velocity = contact%velocity
      model%stiffness = contact%stiffness
      model%damping = contact%damping
      ! 1/(n+1) once: ln x_max and the compression at the peak divide by n + 1 too
      ! (2**-104 relative: its products are rounded to doubles far above that)
      model%inv_np1_dd = dd_inverse(np1)
      alpha = contact%exponent * model%inv_np1_dd
      model%f%alpha_hi = alpha%hi
      model%f%alpha_lo = alpha%lo
      model%f%inv_np1 = 1.0_wp / np1%hi
      model%f%flat = 1.0_wp
      ! 1/H = ih + il: il = (1 - H ih)/H from the exact residual of the product
      t = dd_inverse(hq)
      model%inv_hq = [t%hi, t%lo]

      ! x_max^(n+1) = (n+1) m V^2 H / c. The range tests read the binary exponents (a
      ! logarithm each cost more than the product): e ln 2 is ln x to within ln 2.
      em = exponent_from_bits(contact%mass)
      ev = exponent_from_bits(contact%velocity)
      ec = exponent_from_bits(contact%stiffness)
      eh = exponent_from_bits(hq%hi)
      model%energy_ok = max(abs(em), abs(ev), abs(ec), abs(eh)) < safe_exponent &
         & .and. np1%hi < 2.0_wp**safe_exponent
      if (model%energy_ok) then
         ! (n+1) m V^2 H (J), the energy unit of the peak force too
         energy = ((np1 * contact%mass) * contact%velocity) * contact%velocity * hq
         model%energy = energy
         ! (by the reciprocal of c, within 2**(+-173) here)
         base = energy * dd_inverse(dd(contact%stiffness))
         if (alpha%hi == 0.5_wp .and. alpha%lo == 0.0_wp) then
            ! n = 1: x_max = sqrt(base), one root instead of a logarithm and an
            ! exponential in double-double (base is within the range: energy_ok)
            model%x_max = dd_sqrt(base)
            model%ln_x_max = dd(log(model%x_max%hi))
            model%ln_x_max_dd = .false.
         else
            model%ln_x_max = dd_log(base) * model%inv_np1_dd
         end if
      else
         ln_v = dd_log(dd(contact%velocity))
         model%ln_x_max = (dd_log(np1) + dd_log(dd(contact%mass)) + ln_v + ln_v &
            & + dd_log(hq) - dd_log(dd(contact%stiffness))) * model%inv_np1_dd
      end if
      ! (written so that a NaN fails the tests too: for n near DBL_MAX, 1/(n+1) leaves
      ! the normal range and the scales are not formed)
      if (.not. abs(model%ln_x_max%hi) <= log_limit) then
         stat = hcimpact_err_domain
         return
      end if
      if (model%ln_x_max_dd) model%x_max = dd_exp(model%ln_x_max)
      if (present(depth_only)) then
         if (depth_only) return
      end if
      ! c x_max^n (the force unit) only serves the time law: set_end_times forms it; ln c to
      ! within ln 2 (the margin from log_limit to overflow is 19)
      if (.not. abs(ec * ln2 + contact%exponent * model%ln_x_max%hi) <= log_limit) then
         stat = hcimpact_err_domain
         return
      end if
      ! dt = x_max/((n+1) H V) (x/x_max)^(-n) dl; its unit must be representable too
      if (.not. abs(model%ln_x_max%hi - (exponent_from_bits(np1%hi) + eh + ev) * ln2) &
         & <= log_limit) then
         stat = hcimpact_err_domain
         return
      end if
      ! x_max/((n+1) H V): products with 1/(n+1) and 1/H (both to 2**-104), one quotient
      ! by the double V. Above x_max = 2^800 the product with 1/H (up to 2^134) could
      ! overflow before the quotient brings it back into the range: x_max and V are
      ! scaled to [1/2, 1) first and the result back (exact)
      if (model%energy_ok) then
         ! 1/((n+1) H V) = m V/E with E = (n+1) m V^2 H formed above (its factors within
         ! 2**(+-173), E within 2**(+-865): its reciprocal is normal), x_max below 2**700
         model%time_unit = model%x_max * (two_prod(contact%mass, contact%velocity) &
            & * dd_inverse(energy))
      else if (model%x_max%hi < 2.0_wp**800) then
         model%time_unit = (model%x_max * model%inv_np1_dd &
            & * dd_real(model%inv_hq(1), model%inv_hq(2))) / contact%velocity
      else
         em = exponent_from_bits(model%x_max%hi)
         model%time_unit = dd_scale((dd_scale(model%x_max, -em) * model%inv_np1_dd &
            & * dd_real(model%inv_hq(1), model%inv_hq(2))) / fraction(contact%velocity), &
            & em - ev)
      end if
   end subroutine new_power_model

   !> The constants only the time law needs: those of `power_end_time` (only the time
   !> law inverts from an end) and the logarithm of the force unit c x_max^n (the time
   !> law's force is one exponential of a sum: no product of it can overflow on the way;
   !> two logarithms `impact` need not pay for). ln x_max in double-double first, where
   !> new_power_model kept only its double part (n = 1).
   pure subroutine set_end_times(model)
      type(power_model), intent(inout) :: model
      type(dd_real) :: t, alpha
      real(wp) :: r0
      integer :: phase
      if (.not. model%ln_x_max_dd) then
         model%ln_x_max = dd_log(model%x_max)
         model%ln_x_max_dd = .true.
      end if
      model%ln_force_unit = dd_log(dd(model%stiffness)) + model%n * model%ln_x_max
      ! time of the last d in l before an end, in units of the integral, to first order:
      ! integral of (d R(0)/H)^(-alpha) from 0 to d = (n+1) (H/R(0))^alpha d^(1/(n+1))
      alpha = dd_real(model%f%alpha_hi, model%f%alpha_lo)
      do phase = compression_phase, restitution_phase
         r0 = model%f%tr%end_speed(phase)
         t = dd_exp(alpha * dd_log(model%f%tr%hq / r0)) * model%np1_dd
         model%f%end_coef(phase) = t%hi
      end do
   end subroutine set_end_times

   !> (x/x_max)^(-n) - 1 at the point with distances dturn, dend of the current phase.
   pure function power_density(self, dturn, dend) result(rate)
      !> The integrand
      class(power_integrand), intent(in) :: self
      !> Distance to the turning point in l
      real(wp), intent(in) :: dturn
      !> Distance to the end of contact in l
      real(wp), intent(in) :: dend
      !> Density
      real(wp) :: rate
      real(wp) :: q, s, p, r
      if (dturn <= dend) then
         ! (x/x_max)^(n+1) = 1 - q: delta = exp(-alpha ln(1 - q)) - 1, small near the turn
         q = turn_q(self%tr, self%phase, dturn)
         s = log1p(-q)
         rate = expm1(-(self%alpha_hi * s + self%alpha_lo * s))
      else
         ! (x/x_max)^(n+1) = d R(d)/H, singular like d^(-alpha) at the end
         r = end_r(self%tr, self%phase, dend)
         p = dend * r
         if (p < tiny(1.0_wp)) then
            ! (d R below the normal range, d next to the end at large beta, where R(0) = k
            ! and H are both about 1/beta: their quotient first, which does not underflow)
            p = dend * (r / self%tr%hq%hi)
         else
            p = p / self%tr%hq%hi
         end if
         p = p - p * (self%tr%hq%lo / self%tr%hq%hi)
         rate = p**(-self%alpha_hi) * (1.0_wp - self%alpha_lo * log(p)) - 1.0_wp
      end if
   end function power_density

   !> Time (in units of the integral) to cross the last d in l before the end of
   !> contact, to first order in d.
   pure function power_end_time(self, d) result(time)
      !> The integrand
      class(power_integrand), intent(in) :: self
      !> Width in l
      real(wp), intent(in) :: d
      !> Time
      real(wp) :: time
      time = self%end_coef(self%phase) * d**self%inv_np1
   end function power_end_time

   !> The peak of the force during compression (power law): u = beta q there (q the
   !> unknown below; u is what the outcome needs, formed once here), y = 1 -
   !> (x/x_max)^(n+1) = h(u)/h(beta), and the point's l = (u - h(u))/beta.
   !>
   !> F(q) = n q + (n+1) beta (q^2 H(beta q) - H) = 0 is increasing and convex with
   !> F(0) < 0 <= F((n+1) beta H/n): Newton's method from the right end converges
   !> monotonically; a double iteration, then one step in double-double.
   pure subroutine power_peak(model, u, y, lp)
      type(power_model), intent(in) :: model
      type(dd_real), intent(out) :: u, y, lp
      type(dd_real) :: beta, hq, q, fq, hd
      real(wp) :: qd, b, n, np1, h, step, hu, hprime, dfq, dq
      integer :: it

      beta = model%f%tr%beta
      b = beta%hi
      hq = model%f%tr%hq
      if (b == 0.0_wp) then
         u = dd(0.0_wp)
         y = dd(0.0_wp)
         lp = dd(0.0_wp)
         return
      end if
      n = model%n
      np1 = model%np1
      h = hq%hi
      qd = np1 * b * h / n
      do it = 1, 100
         hu = h_over_square(b * qd)
         step = (n * qd + np1 * b * (qd * qd * hu - h)) / (n + np1 * b * qd / (1.0_wp + b * qd))
         qd = qd - step
         ! quadratic convergence: after a step below 1e-8 q the error is below
         ! |F''| q/(2 F') 1e-16 q <= (n+1)/(8n) 1e-16 q (F'' = (n+1) beta/(1+u)^2,
         ! F' >= n, u/(1+u)^2 <= 1/4), which the step in double-double below squares;
         ! one more step in double would only confirm it
         if (.not. abs(step) > 1.0e-8_wp * qd) exit
      end do
      ! The double iteration leaves q within a few ulps: one step in double-double
      ! squares that error. H(beta q) at the final q is the value at the start of the
      ! step moved by H'(u) du, du = beta (step), in double (du is at the ulp level).
      q = dd(qd)
      u = beta * q
      hd = h_over_square_dd(u)
      fq = n * q + np1 * (beta * (q * q * hd - hq))
      ! the step needs only its leading digits (it is at the ulp level of q): its
      ! derivative and quotient in double, not two double-double quotients
      dfq = n + np1 * u%hi / (u%hi + 1.0_wp)
      dq = fq%hi / dfq
      q = q - dq
      u = beta * q
      ! H'(u) = (1/(1 + u) - 2 H(u))/u, or its series -1/3 + u/2 - 3u^2/5 near 0
      if (abs(u%hi) < 1.0e-3_wp) then
         hprime = -1.0_wp / 3.0_wp + u%hi * (0.5_wp - 0.6_wp * u%hi)
      else
         hprime = (1.0_wp / (1.0_wp + u%hi) - 2.0_wp * hd%hi) / u%hi
      end if
      hd = hd - hprime * (b * dq)
      ! /H as the product with 1/H = inv_hq (2**-104 relative: far below what y needs)
      y = q * q * hd * dd_real(model%inv_hq(1), model%inv_hq(2))
      if (b > log_form_beta) then
         ! l = (u - h(u))/beta = ln(1 + u)/beta, the first form cancelling (trajectory)
         lp = dd_log(u + 1.0_wp) / beta
      else
         ! (beta q q hd, its first product u = beta q already formed)
         lp = q - u * q * hd
      end if
   end subroutine power_peak

   !> x_peak/x_max - 1 = (1 - y)^(1/(n+1)) - 1 = expm1(log1p(-y)/(n+1)) for
   !> 0 <= y < peak_series_max_y, by the two series: the first two terms of each in
   !> double-double, the rest (below y^2 of the sum) in double from the leading parts.
   !> Their rounding and the terms left out are below 2**-68 of the sum, which is
   !> below y/(n+1) <= 2**-8: below 2**-76 of x_peak, far below its rounding. About a
   !> third of the cost of dd_log and dd_exp, which it replaces where beta is small.
   pure function peak_ratio_m1(y, inv_np1) result(ratio)
      !> y = 1 - (x_peak/x_max)^(n+1), 0 <= y < peak_series_max_y
      type(dd_real), intent(in) :: y
      !> 1/(n+1)
      type(dd_real), intent(in) :: inv_np1
      !> x_peak/x_max - 1 (<= 0)
      type(dd_real) :: ratio
      integer :: k
      type(dd_real) :: y2, z, z2
      real(wp) :: tail
      ! ln(1 - y) = -y - y^2/2 - y^3 sum_{k>=3} y^(k-3)/k, to k = 11 (the first term
      ! left out is below y^11 <= 2**-88 of the sum; the double part below y^2/3)
      tail = 1.0_wp / 11.0_wp
      do k = 10, 3, -1
         tail = tail * y%hi + 1.0_wp / real(k, wp)
      end do
      y2 = y * y
      z = (-(y + dd_real(0.5_wp * y2%hi, 0.5_wp * y2%lo)) - y%hi * y2%hi * tail) * inv_np1
      ! expm1(z) = z + z^2/2 + z^3 sum_{k>=3} z^(k-3)/k!, to k = 8, |z| <= |ln(1 - y)|
      ! (n + 1 >= 1) below 1.01 2**-8: the first term left out is below 2**-82 of the
      ! sum, the double part below z^2/6
      tail = 1.0_wp / 40320.0_wp
      tail = tail * z%hi + 1.0_wp / 5040.0_wp
      tail = tail * z%hi + 1.0_wp / 720.0_wp
      tail = tail * z%hi + 1.0_wp / 120.0_wp
      tail = tail * z%hi + 1.0_wp / 24.0_wp
      tail = tail * z%hi + 1.0_wp / 6.0_wp
      z2 = z * z
      ratio = (z + dd_real(0.5_wp * z2%hi, 0.5_wp * z2%lo)) + z%hi * z2%hi * tail
   end function peak_ratio_m1

   !> ln((x/x_max)^(n+1)) near the turning point, at |l| = lt: (x/x_max)^(n+1) = 1 - q,
   !> formed exactly from q (double-double; accurate relative to itself near the turn).
   !> q at lt%hi, moved by the trailing part: dq/d|l| = |x'/V|/H = |expm1(beta l)|/(beta H),
   !> which for large beta |l| is beta q, so that the rounding of |l| would cost
   !> beta |l| times an ulp of q (9 ulps of x at beta = 4e28).
   pure function turn_log_share(model, phase, lt) result(ln_share)
      type(power_model), intent(in) :: model
      integer, intent(in) :: phase
      type(dd_real), intent(in) :: lt
      type(dd_real) :: ln_share
      real(wp) :: q, slope, beta, l
      beta = model%f%tr%beta%hi
      q = turn_q(model%f%tr, phase, lt%hi)
      l = lt%hi
      if (phase == restitution_phase) l = -lt%hi
      if (beta > 0.0_wp) then
         slope = abs(expm1(beta * l) / beta) / model%f%tr%hq%hi
      else
         slope = lt%hi / model%f%tr%hq%hi
      end if
      ln_share = dd_log(two_sum(1.0_wp, -q) - slope * lt%lo)
   end function turn_log_share

   !> ln((x/x_max)^(n+1)) near an end of contact: (x/x_max)^(n+1) = d R(d)/H, given
   !> ln d (double-double: from rho = d^(1/(n+1)) it is (n+1) ln rho, which keeps x's
   !> relative accuracy for tiny d, even where d itself would underflow).
   pure function end_log_share(model, phase, ln_d, d) result(ln_share)
      type(power_model), intent(in) :: model
      integer, intent(in) :: phase
      !> ln d and d (the latter only for R(d))
      type(dd_real), intent(in) :: ln_d
      real(wp), intent(in) :: d
      type(dd_real) :: ln_share
      ln_share = ln_d + dd_log(end_r(model%f%tr, phase, d) &
         & * dd_real(model%inv_hq(1), model%inv_hq(2)))
   end function end_log_share

end module hcimpact_power_model
