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
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_domain
   use hcimpact_libm, only : log1p, expm1
   use hcimpact_double_double, only : dd_real, dd, two_sum, two_prod, operator(+), &
      & operator(-), operator(*), operator(/), &
      & dd_exp, dd_log, dd_sqrt
   use hcimpact_contact, only : contact_type, max_beta
   use hcimpact_trajectory, only : new_trajectory, phase_integrand, compression_phase, &
      & restitution_phase, h_over_square_dd, h_over_square, turn_q, end_r
   implicit none
   private

   public :: power_integrand, power_model, new_power_model, set_end_times, power_peak
   public :: turn_sigma, end_sigma

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
      !> c x_max^n (N), set by set_end_times (the time law only)
      type(dd_real) :: force_unit
      !> Seconds per unit of the integrals: x_max/((n+1) H V)
      type(dd_real) :: time_unit
      !> Contact constant c
      real(wp) :: stiffness = 0.0_wp
      !> (n+1) m V^2 H in J, when `energy_ok` (its factors well inside the double range)
      type(dd_real) :: energy
      logical :: energy_ok = .false.
      !> 1/H as the double nearest to it and the rest (the nodes multiply by it)
      real(wp) :: inv_hq(2) = 0.0_wp
      !> 1/(beta_hi^2 H) = 1/h(beta) as two doubles (the phases' nodes with |beta l| > 2;
      !> set by power_phase_times)
      real(wp) :: inv_hb(2)
   end type power_model

contains

   !> Set up the scales of a power-law impact (the contact must be valid).
   !>
   !> x_max^(n+1) = (n+1) m V^2 H / c is formed as a double-double product when it and
   !> its factors are well inside the double range (one logarithm then), else as a
   !> sum of logarithms; either way x_max = exp(ln(x_max^(n+1))/(n+1)) in double-double.
   !> c x_max^n = (n+1) m V^2 H / x_max needs no further exponential.
   pure subroutine new_power_model(contact, model, stat)
      type(contact_type), intent(in) :: contact
      type(power_model), intent(out) :: model
      integer, intent(out) :: stat
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
      ! (b V < 2**(e_b + e_V), exponent(0) = 0), then the product itself
      if (exponent(contact%damping) + exponent(contact%velocity) > exponent(max_beta) + 1) then
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
      model%n = contact%exponent
      np1 = two_sum(contact%exponent, 1.0_wp)
      model%np1 = np1%hi
      model%np1_dd = np1
      model%velocity = contact%velocity
      model%stiffness = contact%stiffness
      ! 1/(n+1) once: ln x_max and the compression at the peak divide by n + 1 too
      model%inv_np1_dd = 1.0_wp / np1
      alpha = contact%exponent * model%inv_np1_dd
      model%f%alpha_hi = alpha%hi
      model%f%alpha_lo = alpha%lo
      model%f%inv_np1 = 1.0_wp / np1%hi
      model%f%flat = 1.0_wp
      ! 1/H = ih + il: il = (1 - H ih)/H from the exact residual of the product
      model%inv_hq(1) = 1.0_wp / hq%hi
      t = two_prod(hq%hi, model%inv_hq(1))
      model%inv_hq(2) = (((1.0_wp - t%hi) - t%lo) - hq%lo * model%inv_hq(1)) * model%inv_hq(1)

      ! x_max^(n+1) = (n+1) m V^2 H / c. The range tests read the binary exponents (a
      ! logarithm each cost more than the product): e ln 2 is ln x to within ln 2.
      em = exponent(contact%mass)
      ev = exponent(contact%velocity)
      ec = exponent(contact%stiffness)
      eh = exponent(hq%hi)
      model%energy_ok = max(abs(em), abs(ev), abs(ec), abs(eh)) < safe_exponent
      if (model%energy_ok) then
         ! (n+1) m V^2 H (J), the energy unit of the peak force too
         energy = ((np1 * contact%mass) * contact%velocity) * contact%velocity * hq
         model%energy = energy
         base = energy / contact%stiffness
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
      if (abs(model%ln_x_max%hi) > log_limit) then
         stat = hcimpact_err_domain
         return
      end if
      if (model%ln_x_max_dd) model%x_max = dd_exp(model%ln_x_max)
      ! c x_max^n (force_unit) only serves the time law: set_end_times forms it; ln c to
      ! within ln 2 (the margin from log_limit to overflow is 19)
      if (abs(ec * ln2 + contact%exponent * model%ln_x_max%hi) > log_limit) then
         stat = hcimpact_err_domain
         return
      end if
      ! dt = x_max/((n+1) H V) (x/x_max)^(-n) dl; its unit must be representable too
      if (abs(model%ln_x_max%hi - (exponent(np1%hi) + eh + ev) * ln2) > log_limit) then
         stat = hcimpact_err_domain
         return
      end if
      ! x_max/((n+1) H V): products with 1/(n+1) and 1/H (both to 2**-104), one quotient
      ! by the double V
      model%time_unit = (model%x_max * model%inv_np1_dd &
         & * dd_real(model%inv_hq(1), model%inv_hq(2))) / contact%velocity
   end subroutine new_power_model

   !> The constants only the time law needs: those of `power_end_time` (only the time
   !> law inverts from an end) and the force unit c x_max^n (a quotient or an
   !> exponential `impact` need not pay for).
   pure subroutine set_end_times(model)
      type(power_model), intent(inout) :: model
      type(dd_real) :: t, alpha
      real(wp) :: r0
      integer :: phase
      if (model%energy_ok) then
         model%force_unit = model%energy / model%x_max
      else
         t = dd_log(dd(model%stiffness)) + model%n * model%ln_x_max
         model%force_unit = dd_exp(t)
      end if
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
      real(wp) :: q, s, p
      if (dturn <= dend) then
         ! (x/x_max)^(n+1) = 1 - q: delta = exp(-alpha ln(1 - q)) - 1, small near the turn
         q = turn_q(self%tr, self%phase, dturn)
         s = log1p(-q)
         rate = expm1(-(self%alpha_hi * s + self%alpha_lo * s))
      else
         ! (x/x_max)^(n+1) = d R(d)/H, singular like d^(-alpha) at the end
         p = dend * end_r(self%tr, self%phase, dend) / self%tr%hq%hi
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

   !> The peak of the force during compression (power law): q = u/beta there,
   !> y = 1 - (x/x_max)^(n+1) = h(u)/h(beta), and the point's l = (u - h(u))/beta.
   !>
   !> F(q) = n q + (n+1) beta (q^2 H(beta q) - H) = 0 is increasing and convex with
   !> F(0) < 0 <= F((n+1) beta H/n): Newton's method from the right end converges
   !> monotonically; a double iteration, then one step in double-double.
   pure subroutine power_peak(model, q, y, lp)
      type(power_model), intent(in) :: model
      type(dd_real), intent(out) :: q, y, lp
      type(dd_real) :: beta, hq, u, fq, hd
      real(wp) :: qd, b, n, np1, h, step, hu, hprime, dfq, dq
      integer :: it

      beta = model%f%tr%beta
      b = beta%hi
      hq = model%f%tr%hq
      if (b == 0.0_wp) then
         q = dd(0.0_wp)
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
      lp = q - beta * q * q * hd
   end subroutine power_peak

   !> sigma = x/x_max and sigma^n near the turning point: sigma^(n+1) = 1 - q.
   pure subroutine turn_sigma(model, phase, lt, sigma, sigma_n)
      type(power_model), intent(in) :: model
      integer, intent(in) :: phase
      real(wp), intent(in) :: lt
      real(wp), intent(out) :: sigma, sigma_n
      real(wp) :: s
      s = log1p(-turn_q(model%f%tr, phase, lt)) / model%np1
      sigma = exp(s)
      sigma_n = exp(model%n * s)
   end subroutine turn_sigma

   !> sigma = x/x_max and sigma^n near an end: sigma^(n+1) = d R(d)/H, d = rho^(n+1),
   !> so sigma = rho (R/H)^(1/(n+1)) keeps its relative accuracy for tiny rho.
   pure subroutine end_sigma(model, phase, rho, d, sigma, sigma_n)
      type(power_model), intent(in) :: model
      integer, intent(in) :: phase
      real(wp), intent(in) :: rho, d
      real(wp), intent(out) :: sigma, sigma_n
      real(wp) :: ratio
      ratio = end_r(model%f%tr, phase, d) / model%f%tr%hq%hi
      ratio = ratio - ratio * (model%f%tr%hq%lo / model%f%tr%hq%hi)
      sigma = rho * ratio**model%f%inv_np1
      sigma_n = rho**model%n * ratio**(model%n * model%f%inv_np1)
   end subroutine end_sigma

end module hcimpact_power_model
