! SPDX-License-Identifier: Apache-2.0
!> One Hunt-Crossley impact: closed forms, times by quadrature, and the time law.
!>
!> The contact is m x'' = -c x^n (1 + b x'), x(0) = 0, x'(0) = V > 0 (MODEL.md), or the
!> same with a user-supplied elastic law f(x) in place of c x^n (`impact_law`). For two
!> bodies use the effective mass and the relative velocity (hcimpact_hertz).
!>
!> What is computed, and how (power law; the references are the equations of MODEL.md):
!> - beta = b V is formed exactly, as a double-double product: every output is the
!>   value at the two doubles b and V.
!> - Restitution k(beta) (seed eq. 21) and the end of the trajectory in double-double
!>   (hcimpact_trajectory); the energy loss ratio 1 - k^2 = (1 - k)(1 + k).
!> - Maximum compression x_max = [(n+1) m V^2 H / c]^(1/(n+1)), H = h(beta)/beta^2
!>   (= h(beta)/(b^2 V^2) of MODEL.md, finite and smooth as b -> 0), evaluated as the
!>   exponential of a sum of logarithms in double-double and rounded once.
!> - Peak force F = c x^n (1 + b x'), reached in compression where n m x' = b c x^(n+1).
!>   With u = b x' = beta q the condition is n q + (n+1) beta (q^2 H(beta q) - H) = 0
!>   (from the first integral h(u) = h(beta)(1 - (x/x_max)^(n+1))); it is solved by
!>   Newton's method in double-double, and the force is evaluated along the trajectory,
!>   F = c x_max^n (1 - y)^(n/(n+1)) (1 + u), y = h(u)/h(beta), where it is stationary:
!>   an error in q costs only its square.
!> - Compression time, contact time and the time of the peak: tanh-sinh quadrature in
!>   the log-velocity variable (hcimpact_trajectory), the integrand being
!>   (x/x_max)^(-n) = 1 + delta with delta = (1 - q)^(-n/(n+1)) - 1 integrated and the
!>   constant added exactly (near the turning point delta is small and keeps its
!>   relative accuracy). Time unit x_max/((n+1) H V).
!> - Time law: the time as a function of the position is inverted by Newton's method
!>   on the quadrature, from the nearer end of the phase in time.
!>
!> Nothing here stops or prints; every procedure returns a status (hcimpact_status) and
!> NaN outputs when it is not hcimpact_ok.
module hcimpact_impact_model
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
   use hcimpact_kinds, only : wp, ik
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_stiffness, hcimpact_err_exponent, hcimpact_err_velocity, &
      & hcimpact_err_damping, hcimpact_err_restitution, hcimpact_err_domain, &
      & hcimpact_err_size, hcimpact_err_elastic_law
   use hcimpact_libm, only : log1p, expm1
   use hcimpact_double_double, only : dd_real, dd_two_prod_ext, dd_exp, dd_log, dd_sqrt
   use hcimpact_lambertw, only : lambert_w0p1, lambert_wm1p1
   use hcimpact_restitution_law, only : restitution_inverse
   use hcimpact_modified_cc, only : cc_max_degree, cc_moments, cc_moments_pair, &
      & cc_coefficients, cc_sum, cc_converged, cc_end_share, cc_turn_share, cc_node, &
      & inv_end_share_hi, inv_end_share_lo, sym_m0, sym_moments, sym_partial_moments, &
      & sym_q0, sym_q0_near_end, sym_series_max
   use hcimpact_elastic, only : elastic_law
   use hcimpact_trajectory, only : trajectory_type, new_trajectory, phase_integrand, &
      & compression_phase, restitution_phase, h_over_square_dd, h_over_square, turn_q, end_r, g2, &
      & phase_duration, &
      & duration_from_turn, duration_from_end, invert_from_turn, invert_from_end, &
      & scaled_velocity, phase_length
   implicit none
   private

   ! The double-double operators, inline (see dd_ops.inc)
   include "../numerics/dd_ops_interfaces.inc"

   public :: contact_type, outcome_type
   public :: impact, impact_law, velocity_at_depth, time_law, time_law_samples
   public :: damping_for_restitution, default_min_velocity, min_exponent, max_beta
   public :: compression_branch, restitution_branch
   ! for the unit tests of the graded pieces
   public :: power_phase_pieces, max_pieces, cc_max_beta, cc_max_compression_le, end_piece_le
   public :: whole_max_beta

   !> Smallest exponent n of the power law accepted (hcimpact_err_exponent below it).
   !> As n -> 0 the law c x^n tends to a step and the peak-force condition
   !> n m V = b c x^(n+1) degenerates; below about 1e-16 it is not solvable in double
   !> precision. Every physical law has n far above this bound.
   real(wp), parameter :: min_exponent = 1.0e-6_wp
   !> Largest beta = b V the closed forms accept (hcimpact_err_domain above it). Verified
   !> against mpmath up to 1e12 and free of overflow up to about 1e46; k = 1/beta and the
   !> times grow like beta there, so nothing physical lies beyond.
   real(wp), parameter :: max_beta = 1.0e40_wp

   !> One impact: with the power law (`contact_type`), or with a user's elastic law
   !> (`impact_law`)
   interface impact
      module procedure :: impact_power
      module procedure :: impact_law
   end interface impact

   !> The time law x(t), x'(t), F(t): with the power law or with a user's elastic law
   interface time_law
      module procedure :: time_law_power
      module procedure :: time_law_law
   end interface time_law

   !> Above this beta the restitution time is cut into graded pieces (power_phase_split)
   real(wp), parameter :: cc_max_beta = 8.0_wp
   !> Largest number of cuts of a phase into graded pieces (power_phase_split)
   integer, parameter :: max_pieces = 40
   integer, private :: jj_
   !> 1/(j + 2)!, j = 0 .. 23, the coefficients of G2(w) = sum_j w^j/(j + 2)! (the node
   !> loops sum it inline: g2_series.inc)
   real(wp), parameter :: inv_factorial(0:23) = 1.0_wp / gamma(real([(jj_, jj_ = 0, 23)], &
      & wp) + 3.0_wp)
   !> Up to this beta one rule with the symmetric weight covers the whole contact
   !> (power_whole_cc)
   real(wp), parameter :: whole_max_beta = 1.8_wp
   !> Above this beta the whole-contact rule starts at degree 16 (degree 12 was not
   !> accepted beyond about 0.55; 16 is, up to whole_max_beta: 17 evaluations, not 25)
   real(wp), parameter :: whole_16_beta = 0.5_wp
   !> Width in L = beta l of the compression's end piece when the phase is cut: the
   !> complex singularities L_e +- 2 pi i lie at a Bernstein ellipse rho = 5.5 of it,
   !> degree 24 converges (at 6, rho = 4.8, it sometimes needed 48)
   real(wp), parameter :: end_piece_le = 5.0_wp
   !> Above this L_e = ln(1 + beta) the compression time is cut into graded pieces. At
   !> 10 the time of the peak, an incomplete integral of one rule on the whole phase, was
   !> up to 4.6 ulp off for n = 0.1 (beta near 1.2e4); at 5 a sweep of small n and
   !> beta = 100 ... 5e4 against mpmath stays below 1.6 ulp.
   real(wp), parameter :: cc_max_compression_le = 5.0_wp
   integer :: kk_
   !> Complete moments of the plain Clenshaw-Curtis rule: int_-1^1 T_k = 2/(1 - k^2),
   !> k even, 0 for k odd
   real(wp), parameter :: plain_moment(0:cc_max_degree) = [(real(1 + (-1)**kk_, wp) &
      & / real(1 - kk_**2 + merge(1, 0, kk_ == 1), wp), kk_ = 0, cc_max_degree)]

   !> Quiet NaN, the value of every output on error
   real(wp), parameter :: nan = transfer(9221120237041090560_int64, 1.0_wp)

   !> Branch of `velocity_at_depth`: compression (x' > 0)
   integer, parameter :: compression_branch = compression_phase
   !> Branch of `velocity_at_depth`: restitution (x' < 0)
   integer, parameter :: restitution_branch = restitution_phase

   !> Default of `damping_for_restitution`'s min_velocity, in m/s: below this approach
   !> speed the damping for a target restitution is computed at this speed
   real(wp), parameter :: default_min_velocity = 1.0e-3_wp

   !> A collinear impact with the power law f = c x^n: m x'' = -c x^n (1 + b x').
   type :: contact_type
      !> Mass in kg (the effective mass m1 m2/(m1 + m2) for two bodies), > 0
      real(wp) :: mass = 0.0_wp
      !> Contact constant c in N/m^n, > 0 (hcimpact_hertz: hertz_constant)
      real(wp) :: stiffness = 0.0_wp
      !> Exponent n of the elastic law, > 0 (3/2: Hertz)
      real(wp) :: exponent = 1.5_wp
      !> Damping constant b in s/m, >= 0 (0: Hertz's elastic impact)
      real(wp) :: damping = 0.0_wp
      !> Approach speed V in m/s, > 0 (the relative velocity for two bodies)
      real(wp) :: velocity = 0.0_wp
   end type contact_type

   !> Everything `impact` computes. NaN (and 0 evaluations) until computed, or on error.
   type :: outcome_type
      !> Coefficient of restitution k = -(rebound velocity)/V, in (0, 1]
      real(wp) :: restitution = nan
      !> Share of the kinetic energy lost, 1 - k^2
      real(wp) :: energy_loss_ratio = nan
      !> Rebound velocity -k V in m/s (negative)
      real(wp) :: rebound_velocity = nan
      !> Maximum compression x_max in m
      real(wp) :: max_compression = nan
      !> Largest contact force during the impact, in N
      real(wp) :: peak_force = nan
      !> Compression at which the peak force acts, in m
      real(wp) :: compression_at_peak_force = nan
      !> Time from the start of contact to the peak force, in s
      real(wp) :: time_at_peak_force = nan
      !> Time from the start of contact to the maximum compression, in s
      real(wp) :: compression_time = nan
      !> Duration of the contact, in s
      real(wp) :: contact_time = nan
      !> Integrand evaluations spent by the quadratures (compression, restitution, peak)
      integer(ik) :: evaluations(3) = 0_ik
   end type outcome_type

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

   !> Time integrand of a user's elastic law: m V/f(x) per unit l, in seconds.
   type, extends(phase_integrand) :: law_integrand
      !> The elastic law
      class(elastic_law), allocatable :: law
      !> Mass (kg) and approach speed (m/s)
      real(wp) :: mass = 0.0_wp, velocity = 0.0_wp
      !> m V^2 (J): Pi(x) = m V^2 S(l)
      real(wp) :: energy_unit = 0.0_wp
      !> Maximum compression (m) and Pi there (J)
      real(wp) :: x_max = 0.0_wp, energy_max = 0.0_wp
      !> x f(x)/Pi(x) near x = 0: Pi grows like x^power there (n + 1 for f ~ x^n)
      real(wp) :: power = 2.0_wp
   contains
      procedure :: density => law_density
      procedure :: end_time => law_end_time
   end type law_integrand

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

   !> Check a contact; hcimpact_ok or the status of the first bad field.
   elemental function check_contact(contact) result(stat)
      type(contact_type), intent(in) :: contact
      integer :: stat
      stat = hcimpact_ok
      if (.not. (ieee_is_finite(contact%mass) .and. ieee_is_finite(contact%stiffness) &
         & .and. ieee_is_finite(contact%exponent) .and. ieee_is_finite(contact%damping) &
         & .and. ieee_is_finite(contact%velocity))) then
         stat = hcimpact_err_not_finite
      else if (.not. contact%mass > 0.0_wp) then
         stat = hcimpact_err_mass
      else if (.not. contact%stiffness > 0.0_wp) then
         stat = hcimpact_err_stiffness
      else if (.not. contact%exponent >= min_exponent) then
         stat = hcimpact_err_exponent
      else if (.not. contact%velocity > 0.0_wp) then
         stat = hcimpact_err_velocity
      else if (contact%damping < 0.0_wp) then
         stat = hcimpact_err_damping
      end if
   end function check_contact

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

   !> Time of one piece of a phase of a power-law impact by Clenshaw-Curtis rules
   !> (hcimpact_modified_cc), in the units of the integrals.
   !>
   !> The piece covers |l| in [offset + gap, offset + gap + length] (|l| the distance from
   !> the turning point). `weighted`: the piece reaches the end of contact, d (in l) is
   !> its distance from that end and D = length; the time density is then
   !> (S/H)^(-alpha) = (d/D)^(-alpha) F(d), F(d) = (D S/(d H))^(-alpha): S = d R(d) with
   !> R analytic and positive on [0, D] (trajectory), so F is analytic there and the
   !> singular factor is the weight of the rule. Otherwise the piece lies inside the
   !> phase, the density (S/H)^(-alpha) is analytic on it, and the rule is the plain
   !> Clenshaw-Curtis rule (weight 1). Each node takes the form of S for its nearer end
   !> (turn_q or end_r). Degrees 12, 24, 48 (nested) until the last two coefficients
   !> meet `tol`; `converged` false when even 48 does not. `f_turn` is the density at
   !> the end of the piece facing the turning point, `f_far` at the other end.
   pure subroutine power_piece_cc(model, phase, offset, length, gap, e0, weighted, tol, &
         & moment, moment_degree, degree, a, lin, duration, f_turn, f_far, evaluations, &
         & converged)
      type(power_model), intent(in) :: model
      integer, intent(in) :: phase
      !> Distance of the piece from the turning point, its length, and the shift of its
      !> nodes (the end of contact rounded to a double: see trajectory_type's gap)
      real(wp), intent(in) :: offset, length, gap
      !> Compression pieces of a cut phase: the distance of the piece's far end from the
      !> end of contact (0 for the piece at the end); -1 otherwise (see power_nodes)
      real(wp), intent(in) :: e0
      !> Whether the piece reaches the end of contact (weight (d/D)^(-alpha))
      logical, intent(in) :: weighted
      !> Relative tolerance for this piece
      real(wp), intent(in) :: tol
      !> Complete moments J_0 .. J_48 of the weight of the piece
      real(wp), intent(inout) :: moment(0:cc_max_degree)
      !> Highest degree of the moments given (raised to cc_max_degree here if needed)
      integer, intent(inout) :: moment_degree
      !> Degree of the accepted rule, the Chebyshev coefficients of F - A - B x and
      !> [A, B]: the interpolant is A + B x + sum'' a_k T_k(x), x = 2 d/D - 1
      integer, intent(out) :: degree
      real(wp), intent(out) :: a(0:cc_max_degree), lin(2)
      type(dd_real), intent(out) :: duration
      real(wp), intent(out) :: f_turn, f_far
      integer(ik), intent(inout) :: evaluations
      logical, intent(out) :: converged
      real(wp) :: f(0:cc_max_degree), g(0:cc_max_degree), fmax
      type(dd_real) :: sum
      integer :: j, stride, first
      logical :: ok

      converged = .false.
      duration = dd(0.0_wp)
      a = 0.0_wp
      lin = 0.0_wp
      f_turn = 1.0_wp
      f_far = 1.0_wp
      first = 0
      ! A whole phase (weighted from the turning point) at a tolerance near epsilon
      ! was never accepted at degree 12 (the pieces of a cut phase often are): its
      ! transform and test were wasted there. Its 13 values are among the 25 of
      ! degree 24, so starting at 24 costs no evaluation and changes no result.
      degree = 12
      if (weighted .and. offset == 0.0_wp .and. tol < 4.0_wp * epsilon(1.0_wp)) degree = 24
      do while (degree <= cc_max_degree)
         stride = cc_max_degree / degree
         ! the nodes of this degree not yet evaluated: all of them first, then the odd
         if (first == 0) then
            call power_nodes(model, phase, offset, length, gap, e0, weighted, 0, stride, &
               & degree + 1, f, ok)
            evaluations = evaluations + int(degree + 1, ik)
         else
            call power_nodes(model, phase, offset, length, gap, e0, weighted, stride, &
               & 2 * stride, degree / 2, f, ok)
            evaluations = evaluations + int(degree / 2, ik)
         end if
         if (.not. ok) return
         first = degree
         if (degree > moment_degree) then
            if (weighted) then
               call cc_moments(1.0_wp / model%np1, model%np1, 1.0_wp, 2.0_wp, degree, moment)
               call closed_moments(model, moment)
            else
               moment = plain_moment
            end if
            moment_degree = degree
         end if
         ! The rounding errors of the cosine transform are those of the values it is
         ! given, and the moments J_k (k >= 1) decay slowly (like k^(-2c)): their sum
         ! would amplify the noise of every coefficient to several ulps of the integral.
         ! The straight line A + B x through the two end values is taken out first and
         ! integrated exactly (J_0, J_1): what is left is a few times smaller, and so is
         ! its noise.
         lin(1) = 0.5_wp * (f(0) + f(cc_max_degree))
         lin(2) = 0.5_wp * (f(0) - f(cc_max_degree))
         do j = 0, degree
            g(j) = (f(stride * j) - lin(1)) - lin(2) * cc_node(stride * j)
         end do
         call cc_coefficients(degree, g, a)
         ! the straight line's part in double-double: it is nearly all of the integral
         sum = (two_prod(lin(1), moment(0)) + two_prod(lin(2), moment(1))) &
            & + cc_sum(degree, a, moment)
         ! the noise floor of the coefficients: that of the values, ~eps max |f| (a plain
         ! piece's density is not near 0 and the line taken out does not remove it)
         if (weighted .and. offset == 0.0_wp) then
            fmax = maxval(abs(g(0:degree)))
         else
            fmax = maxval(abs(f(0:cc_max_degree:stride)))
         end if
         if (cc_converged(degree, a, moment, sum%hi, fmax, tol)) then
            converged = .true.
            duration = sum * (0.5_wp * length)
            if (weighted) then
               f_turn = f(0)
            else
               f_turn = f(0)
               f_far = f(cc_max_degree)
            end if
            return
         end if
         degree = 2 * degree
      end do
      degree = cc_max_degree
   end subroutine power_piece_cc

   !> The times of a power-law impact by one Clenshaw-Curtis rule over the whole contact
   !> (beta <= whole_max_beta), in the units of the integrals: compression, restitution
   !> and from the impact to the peak.
   !>
   !> The contact runs in l from l_e (impact) to l- (end); with x in [-1, 1] and the
   !> distances d_c = L (1 - x)/2, d_r = L (1 + x)/2 from the two ends (L = l_e - l-, both
   !> ends rounded to doubles as in power_piece_cc), S = d_c d_r P with P analytic and
   !> positive on the contact, and the time is
   !>
   !>     int (S/H)^(-alpha) dl = (L/2) int_-1^1 (1 - x^2)^(-alpha) G(x) dx,
   !>     G = (S (L/2)^2/(H d_c d_r))^(-alpha),
   !>
   !> G analytic: its nearest singularities are the complex zeros of S (Im L = +-2 pi),
   !> far away for small beta, so degree 12 (beta up to 0.5) or 16 suffices where the two
   !> one-sided rules of the phases took 25 nodes each. Moments of the symmetric weight:
   !> hcimpact_modified_cc's sym_*; the compression and the time of the peak are the
   !> incomplete integrals from the turning point and from the peak to the impact (the
   !> turning point must lie within |x| <= 1/2, else, or if degree 48 is not accepted,
   !> `converged` is false and the caller takes the phases one by one). Each node uses
   !> the form of S for its nearest point among the two ends and the turning point.
   pure subroutine power_whole_cc(model, lp, dur, tpeak, evaluations, converged)
      type(power_model), intent(in) :: model
      !> l of the peak force
      type(dd_real), intent(in) :: lp
      !> Compression and restitution times
      type(dd_real), intent(out) :: dur(2)
      !> Time from the impact to the peak
      type(dd_real), intent(out) :: tpeak
      integer(ik), intent(inout) :: evaluations
      logical, intent(out) :: converged
      real(wp) :: f(0:cc_max_degree), g(0:cc_max_degree), a(0:cc_max_degree)
      real(wp) :: moment(0:cc_max_degree)
      real(wp) :: lin(2), b1, b2, length, nu, fmax, alpha, inv_den(cc_max_degree)
      type(dd_real) :: ls, sq, kk, total, num, x0, xp, m0
      integer :: degree, stride, first

      converged = .false.
      dur = dd(0.0_wp)
      tpeak = dd(0.0_wp)
      b1 = model%f%tr%bound(compression_phase)
      b2 = model%f%tr%bound(restitution_phase)
      ls = two_sum(b1, b2)
      length = ls%hi
      ! (L/2)^2 exactly, and (L/2)^2/H = (L/2)^2 (ih + il)
      sq = two_prod(0.5_wp * length, 0.5_wp * length)
      kk = sq * dd_real(model%inv_hq(1), model%inv_hq(2))
      alpha = model%f%alpha_hi
      nu = (1.0_wp - 2.0_wp * alpha) - 2.0_wp * model%f%alpha_lo
      ! the turning point and the peak in x: x = 1 - 2 d_c/L, L = b1 + b2 - ls%lo, and
      ! the turning point's d_c is b1 (the nodes place l = b1 - d_c), the peak's b1 - lp
      num = two_sum(b2, -b1) - ls%lo
      x0 = num / length
      xp = (num + 2.0_wp * lp) / length
      ! (the peak lies between the turning point and the impact: x0 <= xp < 1)
      if (.not. (abs(x0%hi) <= sym_series_max .and. xp%hi < 1.0_wp &
         & .and. xp%hi >= -sym_series_max)) return
      m0 = sym_m0(model%inv_np1_dd, model%np1_dd)

      ! degrees 12, 24, 48 (nested); above whole_16_beta, where 12 is not accepted,
      ! 16 (every third node of the 48 grid) and then 48
      first = 0
      degree = 12
      if (model%f%tr%beta%hi > whole_16_beta) degree = 16
      do while (degree <= cc_max_degree)
         stride = cc_max_degree / degree
         if (first == 0) then
            call whole_nodes(model, length, b1, b2, kk, sq, 0, stride, degree + 1, f, converged)
            evaluations = evaluations + int(degree + 1, ik)
         else if (2 * first == degree) then
            call whole_nodes(model, length, b1, b2, kk, sq, stride, 2 * stride, degree / 2, &
               & f, converged)
            evaluations = evaluations + int(degree / 2, ik)
         else
            ! from 16 to 48: the nodes 3j + 1 and 3j + 2
            call whole_nodes(model, length, b1, b2, kk, sq, 1, 3, first, f, converged)
            if (converged) call whole_nodes(model, length, b1, b2, kk, sq, 2, 3, first, f, &
               & converged)
            evaluations = evaluations + int(2 * first, ik)
         end if
         if (.not. converged) return
         converged = .false.
         first = degree
         ! the straight line through the end values, integrated exactly (M_1 = 0)
         lin(1) = 0.5_wp * (f(0) + f(cc_max_degree))
         lin(2) = 0.5_wp * (f(0) - f(cc_max_degree))
         g(0:degree) = (f(0:cc_max_degree:stride) - lin(1)) &
            & - lin(2) * cc_node(0:cc_max_degree:stride)
         call cc_coefficients(degree, g, a)
         call sym_moments(nu, m0%hi, degree, moment, inv_den)
         total = lin(1) * m0 + cc_sum(degree, a, moment)
         fmax = maxval(abs(g(0:degree)))
         if (cc_converged(degree, a, moment, total%hi, fmax, model%f%rtol)) then
            converged = .true.
            exit
         end if
         if (degree == 16) then
            degree = cc_max_degree
         else
            degree = 2 * degree
         end if
      end do
      if (.not. converged) return
      ! contact: the rule and the slivers the rounded ends leave (density about 1)
      total = total * (0.5_wp * length) + ((model%f%tr%gap(compression_phase) &
         & + model%f%tr%gap(restitution_phase)) + ls%lo)
      ! from the impact to the turning point, and to the peak
      dur(1) = whole_part(model, x0, m0, nu, inv_den, degree, a, lin, length) &
         & + model%f%tr%gap(compression_phase)
      dur(2) = total - dur(1)
      tpeak = whole_part(model, xp, m0, nu, inv_den, degree, a, lin, length) &
         & + model%f%tr%gap(compression_phase)
   end subroutine power_whole_cc

   !> The integral of power_whole_cc's rule (degree, a, lin) from y to 1 (the impact),
   !> times L/2
   pure function whole_part(model, y, m0, nu, inv_den, degree, a, lin, length) result(t)
      type(power_model), intent(in) :: model
      type(dd_real), intent(in) :: y, m0
      real(wp), intent(in) :: nu, inv_den(cc_max_degree)
      integer, intent(in) :: degree
      real(wp), intent(in) :: a(0:cc_max_degree), lin(2), length
      type(dd_real) :: t
      ! ln 2 as hi + lo
      type(dd_real), parameter :: ln2 = dd_real(0.6931471805599453_wp, &
         & 2.3190468138462996e-17_wp)
      real(wp) :: s, partial(0:cc_max_degree)
      type(dd_real) :: u, pref, q0
      if (y%hi <= sym_series_max) then
         s = exp(model%f%inv_np1 * log1p(-y%hi * y%hi))
         q0 = sym_q0(model%f%alpha_hi, y, m0)
      else
         ! next to the impact: u = 1 - y (exact for y >= 1/2), P = 2^(-alpha) u^(1-alpha)
         u = 1.0_wp - y
         s = exp(model%f%inv_np1 * (log(u%hi) + log1p(y%hi)))
         if (model%f%alpha_hi == 0.5_wp .and. model%f%alpha_lo == 0.0_wp) then
            ! n = 1: sqrt(u/2), a fifth of the cost
            pref = dd_sqrt(0.5_wp * u)
         else
            pref = dd_exp(model%inv_np1_dd * dd_log(u) &
               & - dd_real(model%f%alpha_hi, model%f%alpha_lo) * ln2)
         end if
         q0 = sym_q0_near_end(model%f%alpha_hi, u%hi, model%np1_dd, pref)
      end if
      call sym_partial_moments(nu, y%hi, s, q0%hi, degree, inv_den, partial)
      t = ((lin(1) * q0 + lin(2) * partial(1)) + cc_sum(degree, a, partial)) &
         & * (0.5_wp * length)
   end function whole_part

   !> G of power_whole_cc at the nodes i = first, first + step, ... (count of them) of
   !> the degree-48 grid; `ok` false when a value is not finite and positive.
   pure subroutine whole_nodes(model, length, b1, b2, kk, sq, first, step, count, f, ok)
      type(power_model), intent(in) :: model
      !> L, and the two ends' distances from the turning point
      real(wp), intent(in) :: length, b1, b2
      !> (L/2)^2/H and (L/2)^2
      type(dd_real), intent(in) :: kk, sq
      integer, intent(in) :: first, step, count
      real(wp), intent(inout) :: f(0:cc_max_degree)
      logical, intent(out) :: ok
      real(wp) :: z(0:cc_max_degree), dc, dr, r, q, l, w, g, t, w2, even, odd, wmax
      real(wp) :: rest, beta
      integer :: i, m, nterm, jt, top
      integer :: form

      beta = model%f%tr%beta%hi
      ! every form's |w| is below beta max(b1, b2)/2 (the end forms serve d <= b/2, the
      ! turning point's the l in between)
      wmax = 0.5_wp * beta * max(b1, b2)
      include "g2_terms.inc"
      do m = 0, count - 1
         i = first + m * step
         dc = length * cc_turn_share(i)
         dr = length * cc_end_share(i)
         ! the form of S: 1 next to the impact, S = d_c R(d_c); 2 next to the end of
         ! contact, S = d_r R(d_r); 3 near the turning point, S = H (1 - q), l = b1 - d_c
         if (dc <= 0.5_wp * b1) then
            form = 1
            w = -beta * dc
         else if (dr <= 0.5_wp * b2) then
            form = 2
            w = beta * dr
         else
            form = 3
            l = b1 - dc
            w = beta * l
         end if
         include "g2_series.inc"
         if (abs(w) > 2.0_wp) g = g2(w)
         select case (form)
         case (1)
            ! z = R (L/2)^2/(H d_r)
            t = dc * g
            r = (1.0_wp - t * model%f%tr%one_plus_beta%hi) - t * model%f%tr%one_plus_beta%lo
            z(i) = (r * kk%hi + r * kk%lo) / dr
         case (2)
            if (w <= 2.0_wp) then
               t = dr * g
               r = ((model%f%tr%k%hi - model%f%tr%a%hi * t) + model%f%tr%k%lo) &
                  & - model%f%tr%a%lo * t
            else
               r = end_r(model%f%tr, restitution_phase, dr)
            end if
            z(i) = (r * kk%hi + r * kk%lo) / dc
         case default
            ! q = l^2 G2(beta l)/H, z = (1 - q) (L/2)^2/(d_c d_r)
            t = l * l * g
            q = t * model%inv_hq(1) + t * model%inv_hq(2)
            z(i) = ((1.0_wp - q) * sq%hi + (1.0_wp - q) * sq%lo) / (dc * dr)
         end select
      end do
      call node_powers(model, first, step, count, z, f, ok)
   end subroutine whole_nodes

   !> Time of a whole phase by Clenshaw-Curtis rules on graded pieces (beta large).
   !>
   !> The density (S/H)^(-alpha) is singular at the zeros of S = (h(beta) - g(L))/beta^2,
   !> L = beta l, g(L) = e^L - 1 - L: the end of contact, and complex zeros near
   !> L = L_e + 2 pi i j (L_e = ln(1 + beta), the compression's end), i.e. at a distance
   !> of order 2 pi/beta in l from the compression's end and ln(beta)/beta from the
   !> turning point on the restitution side. One polynomial of degree 48 over the whole
   !> phase does not resolve them once ln(beta) is large. The phase is cut at points
   !> graded geometrically (in L) away from the near-singular side (phase_cuts): the
   !> compression's end piece is end_piece_le = 5 wide in L (its weight takes the end
   !> of contact, the complex zeros are 2 pi away), the plain pieces beyond it double
   !> in their distance from the end; the restitution's pieces start at 4 or 6 from
   !> the turning point. On each piece the nearest singularity lies far enough away
   !> for degree 24 (rarely 48) to converge. Only the piece at the end of contact
   !> carries the weight. On the restitution side the density beyond |L| = 36
   !> differs from a function smooth on the scale of the phase by e^L/h(beta) < 1e-16,
   !> so the end piece may be long. `tol` of each piece is scaled by its share of the
   !> phase (the phase's time is at least its length in l, the density being >= 1).
   !> The time of the peak is a weighted rule of its own, from the peak to the end of
   !> contact.
   pure subroutine power_phase_split(model, phase, lp, moment, moment_degree, duration, &
         & tpeak, evaluations, converged)
      type(power_model), intent(in) :: model
      integer, intent(in) :: phase
      !> l of the peak force (compression only): the time of the peak is the complete
      !> integral of a weighted rule from there to the end of contact (an incomplete
      !> one with the end piece's interpolant sums slowly decaying moments of
      !> alternating sign: up to 2.2 ulp where this gives 1.1, and 5 ulps were seen
      !> with one rule on the whole phase)
      type(dd_real), intent(in) :: lp
      !> Time from the impact to the peak (compression only)
      type(dd_real), intent(out) :: tpeak
      real(wp), intent(inout) :: moment(0:cc_max_degree)
      integer, intent(inout) :: moment_degree
      type(dd_real), intent(out) :: duration
      integer(ik), intent(inout) :: evaluations
      logical, intent(out) :: converged
      real(wp) :: cut(0:max_pieces), bound, e0, tol, width, resid, f_turn, f_far
      real(wp) :: plain(0:cc_max_degree), a_p(0:cc_max_degree), lin_p(2), gap_end, prev_far
      real(wp) :: end_length
      type(dd_real) :: part, s
      integer :: np, j, deg_p, plain_degree

      converged = .false.
      duration = dd(0.0_wp)
      tpeak = dd(0.0_wp)
      bound = model%f%tr%bound(phase)
      call phase_cuts(model%f%tr%beta%hi, bound, phase, lp%hi, cut, np)
      tol = model%f%rtol / real(np + 1, wp)
      plain_degree = 0
      prev_far = 1.0_wp
      resid = 0.0_wp
      do j = 1, np
         ! plain piece [cut(j-1), cut(j)]: its width rounded, the rest (exact) added at
         ! the density of the piece's far end
         s = two_sum(cut(j), -cut(j - 1))
         width = s%hi
         e0 = -1.0_wp
         if (phase == compression_phase) e0 = (bound - cut(j)) + (model%f%tr%gap(phase) + s%lo)
         call power_piece_cc(model, phase, cut(j - 1), width, 0.0_wp, e0, .false., &
            & max(tol * bound / width, model%f%rtol), plain, plain_degree, deg_p, a_p, lin_p, &
            & part, f_turn, f_far, evaluations, converged)
         if (.not. converged) return
         duration = duration + part + s%lo * f_far
         prev_far = f_far
      end do
      ! the end piece [cut(np), |l_end|]: length bound - cut(np) rounded; the rest and
      ! the end's own rounding shift its nodes (gap_end), the sliver they leave is added
      ! at the density there
      s = two_sum(bound, -cut(np))
      end_length = s%hi
      gap_end = s%lo + model%f%tr%gap(phase)
      ! the compression's end piece at the full tolerance (the scaled one saved no
      ! evaluation there)
      if (phase == compression_phase) then
         tol = model%f%rtol
      else
         tol = max(tol * bound / end_length, model%f%rtol)
      end if
      e0 = -1.0_wp
      if (phase == compression_phase) e0 = 0.0_wp
      call power_piece_cc(model, phase, cut(np), end_length, gap_end, e0, .true., &
         & tol, moment, moment_degree, deg_p, a_p, lin_p, part, f_turn, f_far, evaluations, &
         & converged)
      if (.not. converged) return
      duration = duration + part + gap_end * prev_far
      ! from the impact to the peak: a weighted rule of its own on [lp, |l_end|] (a
      ! complete integral; the end piece's interpolant with incomplete moments up to
      ! the peak saves its 13 to 25 evaluations but was up to 2.2 ulp off where this
      ! is 1.1), and the sliver between lp and its double
      if (phase == compression_phase) then
         s = two_sum(bound, -lp%hi)
         gap_end = s%lo + model%f%tr%gap(phase)
         call power_piece_cc(model, phase, lp%hi, s%hi, gap_end, 0.0_wp, .true., &
            & model%f%rtol, moment, moment_degree, deg_p, a_p, lin_p, part, f_turn, f_far, &
            & evaluations, converged)
         if (.not. converged) return
         tpeak = part + ((lp%hi - lp) + gap_end) * f_turn
      end if
   end subroutine power_phase_split


   !> The cuts of a phase of length `bound` (in l) into graded pieces (see
   !> power_phase_split), as distances |l| from the turning point, increasing:
   !> cut(0) = 0 < cut(1) < ... < cut(np) < bound; the pieces are [cut(j-1), cut(j)]
   !> and the end piece [cut(np), bound]. Compression: the end piece is end_piece_le
   !> wide in L = beta l (at least 1.5 times the peak's distance from the end, at most
   !> half way from the peak to the turning point), and the plain pieces double in
   !> their distance from the end of contact (a piece [e, 2e] has the end's
   !> singularity at its own width away: degree 24 converges, where [e, 3e] needed 48);
   !> restitution: the cuts start at L = 4 or 6 and grow by 3 to 4.5 up to L = 40
   !> (beyond 36 the density is smooth on the scale of the phase).
   pure subroutine phase_cuts(beta, bound, phase, lp, cut, np)
      !> beta and the length of the phase in l
      real(wp), intent(in) :: beta, bound
      !> compression_phase or restitution_phase
      integer, intent(in) :: phase
      !> l of the peak force (compression only)
      real(wp), intent(in) :: lp
      !> The cuts cut(0 .. np)
      real(wp), intent(out) :: cut(0:max_pieces)
      !> Number of cuts after cut(0) = 0: np + 1 pieces
      integer, intent(out) :: np
      real(wp) :: le, w, e, ratio
      integer :: j

      cut = 0.0_wp
      le = beta * bound
      np = 0
      if (phase == compression_phase) then
         ! distances from the end of contact (in L): the end piece's E, then 2 E, 4 E,
         ! ... The end piece reaches end_piece_le from the end, and at least half as
         ! far again as the peak, which it holds (1.5 e_p <= 1.1 for large beta)
         np = 1
         e = beta * (bound - lp)
         e = min(max(end_piece_le, 1.5_wp * e), 0.5_wp * (e + le))
         cut(1) = (le - e) / beta
         do j = 2, max_pieces - 1
            w = e
            if (le - (e + w) <= 0.25_wp * w) exit
            e = e + w
            np = np + 1
            cut(np) = (le - e) / beta
         end do
         ! increasing order
         cut(1:np) = cut(np:1:-1)
      else
         ! (the layout that needed the fewest evaluations over n = 0.5 ... 7 and
         ! beta = 6 ... 1e11, against the single rule 4, 12, 36 that it replaced: 19 %
         ! fewer in all, 29 % fewer for 400 < beta < 6e4, up to 15 % more near
         ! beta = 160 and 1e5)
         if (le < 35.0_wp) then
            w = 4.0_wp
            ratio = 3.0_wp
         else if (le < 150.0_wp) then
            w = 6.0_wp
            ratio = 4.0_wp
         else
            w = 6.0_wp
            ratio = 4.5_wp
         end if
         do j = 1, max_pieces - 1
            if (w > 0.75_wp * le .or. w > 40.0_wp) exit
            np = np + 1
            cut(np) = w / beta
            w = ratio * w
         end do
      end if
   end subroutine phase_cuts

   !> The cuts `impact` makes in a phase of a contact (power_phase_split), for the unit
   !> tests: `split` whether the phase is cut at all (beta above cc_max_beta for the
   !> restitution, ln(1 + beta) above cc_max_compression_le for the compression), the
   !> phase's length `bound` in l, and phase_cuts' cut(0 .. np).
   pure subroutine power_phase_pieces(contact, phase, split, bound, cut, np, stat)
      !> A valid contact
      type(contact_type), intent(in) :: contact
      !> compression_branch or restitution_branch
      integer, intent(in) :: phase
      !> Whether `impact` cuts this phase
      logical, intent(out) :: split
      !> Length of the phase in l
      real(wp), intent(out) :: bound
      !> The cuts (as if the phase were cut)
      real(wp), intent(out) :: cut(0:max_pieces)
      !> Their number after cut(0)
      integer, intent(out) :: np
      !> hcimpact_ok, or the error `impact` reports for the contact's set-up
      integer, intent(out) :: stat
      type(power_model) :: model
      type(dd_real) :: q, y, lp
      split = .false.
      bound = 0.0_wp
      cut = 0.0_wp
      np = 0
      stat = check_contact(contact)
      if (stat /= hcimpact_ok) return
      call new_power_model(contact, model, stat)
      if (stat /= hcimpact_ok) return
      call power_peak(model, q, y, lp)
      bound = model%f%tr%bound(phase)
      if (phase == compression_phase) then
         split = model%f%tr%beta%hi * bound > cc_max_compression_le
      else
         split = model%f%tr%beta%hi > cc_max_beta
      end if
      call phase_cuts(model%f%tr%beta%hi, bound, phase, lp%hi, cut, np)
   end subroutine power_phase_pieces

   !> J_0 = 2 (n+1) and J_1 = -2 n (n+1)/(n+2) of the complete moments in closed form:
   !> they weigh the straight line, which carries most of the integral.
   pure subroutine closed_moments(model, moment)
      type(power_model), intent(in) :: model
      real(wp), intent(inout) :: moment(0:)
      moment(0) = 2.0_wp * model%np1
      moment(1) = -2.0_wp * model%n * (model%np1 / (model%n + 2.0_wp))
   end subroutine closed_moments

   !> F at the nodes i = first, first + step, ... (count of them) of the degree-48 grid of
   !> a phase of length D (see power_phase_cc): z^(-alpha) with z = (1 - q) D/d near the
   !> turning point and z = D R(d)/H near the end. `ok` false when a z is not finite and
   !> positive (beta or the scales at the limits of the double range): the caller then
   !> leaves this phase to tanh-sinh, which reports it.
   !>
   !> All nodes at once, in loops of independent iterations, with the forms of S
   !> (hcimpact_trajectory's turn_q and end_r) written out: the divisions by H and by
   !> the node's share become products with reciprocals computed once (in two parts,
   !> so that each costs about one rounding, as the division did), and G2 is summed
   !> to the number of terms the phase's largest |beta l| needs. A call per node
   !> across modules, with its chain of dependent divisions, cost twice as much.
   pure subroutine power_nodes(model, phase, offset, length, gap, e0, weighted, first, &
         & step, count, f, ok)
      type(power_model), intent(in) :: model
      integer, intent(in) :: phase, first, step, count
      real(wp), intent(in) :: offset, length, gap, e0
      logical, intent(in) :: weighted
      real(wp), intent(inout) :: f(0:cc_max_degree)
      logical, intent(out) :: ok
      real(wp) :: z(0:cc_max_degree), ih, il, beta, sgn, l, w, g, t, r, wmax, rest, dend
      real(wp) :: w2, even, odd
      integer :: i, m, nterm, jt, top
      logical :: end_form

      beta = model%f%tr%beta%hi
      ih = model%inv_hq(1)
      il = model%inv_hq(2)
      sgn = 1.0_wp
      if (phase == restitution_phase) sgn = -1.0_wp
      wmax = beta * (offset + length + abs(gap))
      include "g2_terms.inc"
      do m = 0, count - 1
         i = first + m * step
         ! The end form for the half at the end of contact of a weighted piece, and on
         ! the compression pieces of a cut phase wherever beta d <= 4: there |l| is large
         ! against the distance d to the end, and a node placed in l (absolute error
         ! eps |l|) would move S by up to eps ln(1 + beta) relative (tens of ulps).
         end_form = weighted .and. 2 * i > cc_max_degree
         dend = length * cc_end_share(i)
         if (e0 >= 0.0_wp) then
            dend = e0 + dend
            end_form = end_form .or. beta * dend <= 4.0_wp
         end if
         if (.not. end_form) then
            ! turning-point side: |l| = offset + D (1 - x)/2 + gap, q = l^2 G2(beta l)/H
            l = sgn * ((offset + length * cc_turn_share(i)) + gap)
            w = beta * l
         else
            ! end side: S = d R(d), R from the series in w = -+beta d
            l = dend
            if (phase == compression_phase) then
               w = -beta * dend
            else
               w = beta * dend
            end if
         end if
         include "g2_series.inc"
         if (.not. end_form) then
            if (abs(w) > 2.0_wp) then
               ! l^2 G2(w)/H = (e^w - 1 - w)/h(beta): no cancellation for |w| > 2, one
               ! exponential (expm1 and a quotient cost a third more)
               t = (exp(w) - 1.0_wp) - w
               t = t * model%inv_hb(1) + t * model%inv_hb(2)
            else
               t = l * l * g
               t = t * ih + t * il
            end if
            if (weighted) then
               z(i) = (1.0_wp - t) * inv_end_share_hi(i) + (1.0_wp - t) * inv_end_share_lo(i)
            else
               z(i) = 1.0_wp - t
            end if
         else
            ! z = D R(d)/H (weighted) or S/H
            if (abs(w) <= 2.0_wp) then
               t = dend * g
               if (phase == compression_phase) then
                  r = (1.0_wp - t * model%f%tr%one_plus_beta%hi) &
                     & - t * model%f%tr%one_plus_beta%lo
               else
                  r = ((model%f%tr%k%hi - model%f%tr%a%hi * t) + model%f%tr%k%lo) &
                     & - model%f%tr%a%lo * t
               end if
            else
               r = end_r(model%f%tr, phase, dend)
            end if
            if (weighted) then
               t = length * r
            else
               t = dend * r
            end if
            z(i) = t * ih + t * il
         end if
      end do
      call node_powers(model, first, step, count, z, f, ok)
   end subroutine power_nodes

   !> f = z^(-alpha) at the nodes i = first, first + step, ... (count of them); `ok`
   !> false (f untouched) when a z is not finite and positive (beta or the scales at the
   !> limits of the double range).
   pure subroutine node_powers(model, first, step, count, z, f, ok)
      type(power_model), intent(in) :: model
      integer, intent(in) :: first, step, count
      real(wp), intent(in) :: z(0:cc_max_degree)
      real(wp), intent(inout) :: f(0:cc_max_degree)
      logical, intent(out) :: ok
      real(wp) :: lz
      integer :: i, m
      ok = .false.
      do m = 0, count - 1
         i = first + m * step
         if (.not. ieee_is_finite(z(i))) return
         if (.not. z(i) > 0.0_wp) return
      end do
      ok = .true.
      if (model%f%alpha_hi == 0.5_wp .and. model%f%alpha_lo == 0.0_wp) then
         ! n = 1: two correctly rounded operations
         do m = 0, count - 1
            i = first + m * step
            f(i) = 1.0_wp / sqrt(z(i))
         end do
      else
         ! z^(-alpha) = exp(-alpha ln z): 40% faster than pow. Its extra rounding, that of
         ! ln z times alpha, is below alpha eps |ln z|/2 relative; z lies near 1 except
         ! at large beta, and the rounding of the nodes averages out in the rule (the
         ! worst contact time of impact.csv moves by about 0.2 ulp, see doc/impact.md).
         do m = 0, count - 1
            i = first + m * step
            lz = log(z(i))
            f(i) = exp(-(model%f%alpha_hi * lz + model%f%alpha_lo * lz))
         end do
      end if
   end subroutine node_powers

   !> Everything about one impact with the power law (see `outcome_type`).
   !>
   !> Errors: hcimpact_err_not_finite (NaN or infinite field), _mass, _stiffness,
   !> _exponent, _velocity (not positive), _damping (negative), _domain (results
   !> outside the double range), _no_convergence (a quadrature failed: not seen for
   !> 0.1 <= n <= 10 and beta = b V up to 1e12).
   elemental subroutine impact_power(contact, outcome, stat, rtol)
      !> The contact
      type(contact_type), intent(in) :: contact
      !> Its outcome; every real field NaN on error
      type(outcome_type), intent(out) :: outcome
      !> Status: hcimpact_ok or an error code of hcimpact_status
      integer, intent(out) :: stat
      !> Relative tolerance of the time quadratures (default: full double precision;
      !> values below epsilon are taken as epsilon; NaN or <= 0 is hcimpact_err_domain).
      !> Only the times depend on it: the other outputs are closed forms.
      real(wp), intent(in), optional :: rtol
      type(power_model) :: model
      type(dd_real) :: k, t, dur(2), tpeak, q, y, u, lp
      integer(ik) :: ev(3)
      type(dd_real) :: xp
      logical :: whole

      outcome = outcome_type()
      stat = check_contact(contact)
      if (stat /= hcimpact_ok) return
      call new_power_model(contact, model, stat)
      if (stat /= hcimpact_ok) return
      if (present(rtol)) then
         if (ieee_is_nan(rtol)) then
            stat = hcimpact_err_domain
            return
         else if (rtol <= 0.0_wp) then
            stat = hcimpact_err_domain
            return
         end if
         model%f%rtol = max(rtol, epsilon(1.0_wp))
      end if

      ev = 0_ik
      ! the peak: q = u/beta at the peak, y = 1 - (x/x_max)^(n+1), l of the point
      call power_peak(model, q, y, lp)
      ! the times: one rule over the whole contact for small beta, else rules on the
      ! phases (and their pieces)
      whole = .false.
      if (model%f%tr%beta%hi <= whole_max_beta) &
         & call power_whole_cc(model, lp, dur, tpeak, ev(1), whole)
      if (.not. whole) call power_phase_times(model, lp, dur, tpeak, ev, stat)
      if (stat /= hcimpact_ok) return
      u = model%f%tr%beta * q

      k = model%f%tr%k
      outcome%restitution = k%hi
      t = (1.0_wp - k) * (k + 1.0_wp)
      outcome%energy_loss_ratio = t%hi
      t = -(k * contact%velocity)
      outcome%rebound_velocity = t%hi
      outcome%max_compression = model%x_max%hi
      t = model%time_unit * dur(1)
      outcome%compression_time = t%hi
      t = model%time_unit * (dur(1) + dur(2))
      outcome%contact_time = t%hi
      t = model%time_unit * tpeak
      outcome%time_at_peak_force = t%hi
      ! x_peak = x_max (1 - y)^(1/(n+1)); F = c x_peak^n (1 + u), which is
      ! (n+1) m V^2 H (1 - y) (1 + u)/x_peak since c x_peak^(n+1) = c x_max^(n+1) (1 - y)
      if (model%ln_x_max_dd) then
         t = model%ln_x_max + dd_log(1.0_wp - y) * model%inv_np1_dd
         xp = dd_exp(t)
      else
         ! n = 1: x_max sqrt(1 - y)
         xp = model%x_max * dd_sqrt(1.0_wp - y)
      end if
      outcome%compression_at_peak_force = xp%hi
      if (model%energy_ok) then
         t = model%energy * (1.0_wp - y) * (u + 1.0_wp) / xp
         outcome%peak_force = t%hi
      else
         t = dd_log(dd(contact%stiffness)) + model%n * t + dd_log(u + 1.0_wp)
         outcome%peak_force = dd_exp_hi(t)
      end if
      outcome%evaluations = ev
      call reject_unrepresentable(outcome, stat)
   end subroutine impact_power

   !> The times of a power-law impact by rules on its two phases (power_piece_cc, cut
   !> into graded pieces for large beta: power_phase_split; tanh-sinh if a rule does
   !> not converge), in the units of the integrals: compression, restitution and from
   !> the impact to the peak (the compression's interpolant where it holds the peak).
   pure subroutine power_phase_times(model, lp, dur, tpeak, ev, stat)
      !> The model (its integrand is the tanh-sinh rules' state)
      type(power_model), intent(inout) :: model
      !> l of the peak force
      type(dd_real), intent(in) :: lp
      type(dd_real), intent(out) :: dur(2), tpeak
      !> Evaluations: compression, restitution, peak (added to)
      integer(ik), intent(inout) :: ev(3)
      integer, intent(out) :: stat
      type(dd_real) :: t, ct
      real(wp) :: half, c, s, length, big_c, f_turn, f_far
      real(wp) :: moment(0:cc_max_degree), coef(0:cc_max_degree), coef2(0:cc_max_degree)
      real(wp) :: moment_peak(0:cc_max_degree)
      real(wp) :: lin(2), lin2(2)
      integer :: degree, degree2, moment_degree
      logical :: done(2), split
      type(dd_real) :: ihb

      stat = hcimpact_ok
      ! 1/h(beta) for the nodes placed in l with |beta l| > 2 (power_nodes); beta = 0 has
      ! none
      if (model%f%tr%beta%hi > 0.0_wp) then
         ihb = dd_real(model%inv_hq(1), model%inv_hq(2)) &
            & / two_prod(model%f%tr%beta%hi, model%f%tr%beta%hi)
         model%inv_hb = [ihb%hi, ihb%lo]
      end if
      split = .false.
      tpeak = dd(0.0_wp)
      ! the complete moments of the weight (d/D)^(-alpha), c = 1 - alpha = 1/(n+1), and
      ! (a whole compression phase, the peak inside it) the incomplete ones from the
      ! impact to the peak, s = d/D, for the time of the peak (no new evaluation):
      ! both at once (cc_moments_pair), to degree 24, the degree nearly always accepted
      c = 1.0_wp / model%np1
      moment_degree = 24
      s = 0.0_wp
      length = model%f%tr%bound(compression_phase)
      ! (0 < t < length also keeps out a phase of length 0: at beta near max_beta,
      ! l_end = ln(1 + beta)/beta is below the precision of 1 - beta H and rounds to 0)
      if (model%f%tr%beta%hi * length <= cc_max_compression_le) then
         t = model%f%tr%l_end(compression_phase) - lp
         if (t%hi > 0.0_wp .and. t%hi < length) s = t%hi / length
      end if
      if (s > 0.0_wp) then
         ! C = 2 s^c, with the rounding of c = 1/(n+1) corrected to first order
         ct = two_prod(c, model%np1)
         big_c = 2.0_wp * s**c
         big_c = big_c + big_c * (((1.0_wp - ct%hi) - ct%lo) / model%np1) * log(s)
         call cc_moments_pair(c, model%np1, s, big_c, moment_degree, moment, moment_peak)
      else
         call cc_moments(c, model%np1, 1.0_wp, 2.0_wp, moment_degree, moment)
      end if
      call closed_moments(model, moment)
      ! Large L_e = ln(1 + beta): the complex singularities next to the compression's
      ! end (L_e +- 2 pi i) need graded pieces (power_phase_split).
      if (model%f%tr%beta%hi * model%f%tr%bound(compression_phase) <= cc_max_compression_le) then
         length = model%f%tr%bound(compression_phase)
         call power_piece_cc(model, compression_phase, 0.0_wp, length, &
            & model%f%tr%gap(compression_phase), -1.0_wp, .true., model%f%rtol, moment, moment_degree, &
            & degree, coef, lin, dur(1), f_turn, f_far, ev(1), done(1))
         if (done(1)) dur(1) = dur(1) + model%f%tr%gap(compression_phase)
      else
         call power_phase_split(model, compression_phase, lp, moment, moment_degree, dur(1), &
            & tpeak, ev(1), done(1))
         split = done(1)
      end if
      if (.not. done(1)) call phase_duration(model%f, compression_phase, dur(1), ev(1), stat)
      if (stat /= hcimpact_ok) return
      ! For beta > 8 the restitution density varies on a scale 1/beta next to the
      ! turning point (the complex zeros of S near L = ln h(beta) +- 2 pi i): graded
      ! pieces there (power_phase_split).
      if (model%f%tr%beta%hi <= cc_max_beta) then
         call power_piece_cc(model, restitution_phase, 0.0_wp, &
            & model%f%tr%bound(restitution_phase), model%f%tr%gap(restitution_phase), -1.0_wp, &
            & .true., &
            & model%f%rtol, moment, moment_degree, degree2, coef2, lin2, dur(2), f_turn, f_far, &
            & ev(2), done(2))
         if (done(2)) dur(2) = dur(2) + model%f%tr%gap(restitution_phase)
      else
         call power_phase_split(model, restitution_phase, lp, moment, moment_degree, dur(2), &
            & t, ev(2), done(2))
      end if
      if (.not. done(2)) call phase_duration(model%f, restitution_phase, dur(2), ev(2), stat)
      if (stat /= hcimpact_ok) return

      half = 0.5_wp * model%f%tr%l_end(compression_phase)%hi
      t = model%f%tr%l_end(compression_phase) - lp
      ! length: that of the compression's piece at the impact end (the whole phase
      ! unless it was cut)
      if (split) then
         ! tpeak: the compression's end piece (power_phase_split)
         continue
      else if (done(1) .and. t%hi < length) then
         ! from the impact to the peak with the compression's own interpolant: the
         ! incomplete moments up to s = d/D (no new evaluation)
         if (s > 0.0_wp) then
            ! moments J_0 .. J_k do not depend on the degree they were computed to
            if (degree > 24) call cc_moments(c, model%np1, s, big_c, degree, moment_peak)
            moment_peak(0) = big_c * model%np1
            moment_peak(1) = big_c * model%np1 * (2.0_wp * s / (model%n + 2.0_wp) - 1.0_wp)
            tpeak = ((two_prod(lin(1), moment_peak(0)) + two_prod(lin(2), moment_peak(1))) &
               & + cc_sum(degree, coef, moment_peak)) * (0.5_wp * length)
         else
            tpeak = dd(0.0_wp)
         end if
      else if (done(1) .and. length >= model%f%tr%bound(compression_phase)) then
         tpeak = dur(1)
      else if (lp%hi <= half) then
         call duration_from_turn(model%f, compression_phase, lp%hi, t, ev(3), stat)
         tpeak = dur(1) - t
      else
         call duration_from_end(model%f, compression_phase, t%hi, tpeak, ev(3), stat)
      end if
      if (stat /= hcimpact_ok) return
   end subroutine power_phase_times

   !> exp of a double-double number, rounded to a double.
   elemental function dd_exp_hi(a) result(x)
      type(dd_real), intent(in) :: a
      real(wp) :: x
      type(dd_real) :: e
      e = dd_exp(a)
      x = e%hi
   end function dd_exp_hi

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

   !> Velocity (m/s) at the compression x on the compression or the restitution branch:
   !> V(x) = u(h(beta) (1 - (x/x_max)^(n+1)))/b (MODEL.md), u from Lambert W (seed
   !> eq. 14), or its series when the argument is small (then b -> 0 is smooth and
   !> gives +-sqrt(V^2 - 2 Pi(x)/m)).
   !>
   !> Errors: those of `impact`, and hcimpact_err_not_finite for a NaN or infinite x,
   !> hcimpact_err_domain for x < 0 or x > x_max (beyond 4 ulps) or another branch.
   elemental subroutine velocity_at_depth(contact, x, branch, v, stat)
      !> The contact
      type(contact_type), intent(in) :: contact
      !> Compression in m, 0 <= x <= x_max
      real(wp), intent(in) :: x
      !> compression_branch or restitution_branch
      integer, intent(in) :: branch
      !> Velocity x' in m/s: >= 0 on the compression branch, <= 0 on restitution
      real(wp), intent(out) :: v
      !> Status
      integer, intent(out) :: stat
      type(power_model) :: model
      type(dd_real) :: yd, t
      real(wp) :: y, xi, s, b, w

      v = nan
      stat = check_contact(contact)
      if (stat /= hcimpact_ok) return
      if (.not. ieee_is_finite(x)) then
         stat = hcimpact_err_not_finite
         return
      end if
      if (x < 0.0_wp .or. (branch /= compression_branch .and. branch /= restitution_branch)) then
         stat = hcimpact_err_domain
         return
      end if
      call new_power_model(contact, model, stat)
      if (stat /= hcimpact_ok) return
      if (x > model%x_max%hi * (1.0_wp + 4.0_wp * epsilon(1.0_wp))) then
         stat = hcimpact_err_domain
         return
      end if
      ! y = 1 - (x/x_max)^(n+1), in double-double
      if (x > 0.0_wp) then
         if (.not. model%ln_x_max_dd) model%ln_x_max = dd_log(model%x_max)
         yd = 1.0_wp - dd_exp((dd_log(dd(x)) - model%ln_x_max) * two_sum(model%n, 1.0_wp))
      else
         yd = dd(1.0_wp)
      end if
      if (yd%hi < 0.0_wp) yd = dd(0.0_wp)
      y = yd%hi
      b = model%f%tr%beta%hi
      ! velocity/V = u/beta; with xi = sqrt(2 H y) and s = beta xi = sqrt(2 t):
      ! u+/beta = xi (1 + s/3 + s^2/36 - s^3/270 + ...),
      ! u-/beta = -xi (1 - s/3 + s^2/36 + s^3/270 + ...)   (MODEL.md series of 1 + W)
      xi = sqrt(2.0_wp * model%f%tr%hq%hi * y)
      s = b * xi
      if (s < 1.0e-4_wp) then
         if (branch == compression_branch) then
            w = xi * (1.0_wp + s * (1.0_wp / 3.0_wp + s * (1.0_wp / 36.0_wp - s / 270.0_wp)))
         else
            w = -xi * (1.0_wp - s * (1.0_wp / 3.0_wp - s * (1.0_wp / 36.0_wp + s / 270.0_wp)))
         end if
      else
         t = model%f%tr%hq * model%f%tr%beta * model%f%tr%beta * yd
         if (branch == compression_branch) then
            w = -lambert_wm1p1(t%hi) / b
         else
            w = -lambert_w0p1(t%hi) / b
         end if
      end if
      v = w * contact%velocity
   end subroutine velocity_at_depth

   !> Compression x(t), velocity x'(t) and contact force F(t) = c x^n (1 + b x') at the
   !> times t(:). Before the contact (t <= 0): x = 0, x' = V, F = 0; after it
   !> (t >= contact time): x = 0, x' = -k V, F = 0.
   !>
   !> Each time costs a few quadratures (Newton's method on the time as a function of
   !> the position, bounded). Near the end of contact x(t) is ill-conditioned: it moves
   !> by |x'| times the error of the contact time (a few ulps of it).
   !>
   !> Errors: those of `impact`; hcimpact_err_not_finite if a t is NaN or infinite;
   !> hcimpact_err_size if the arrays differ in size.
   pure subroutine time_law_power(contact, t, x, v, f, stat)
      !> The contact
      type(contact_type), intent(in) :: contact
      !> Times in s from the start of contact, any order
      real(wp), intent(in) :: t(:)
      !> Compression x(t) in m
      real(wp), intent(out) :: x(:)
      !> Velocity x'(t) in m/s
      real(wp), intent(out) :: v(:)
      !> Contact force F(t) in N
      real(wp), intent(out) :: f(:)
      !> Status
      integer, intent(out) :: stat
      type(power_model) :: model
      type(dd_real) :: dur(2)
      integer(ik) :: ev
      integer :: i

      x = nan
      v = nan
      f = nan
      if (size(x) /= size(t) .or. size(v) /= size(t) .or. size(f) /= size(t)) then
         stat = hcimpact_err_size
         return
      end if
      stat = check_contact(contact)
      if (stat /= hcimpact_ok) return
      if (.not. all(ieee_is_finite(t))) then
         stat = hcimpact_err_not_finite
         return
      end if
      call new_power_model(contact, model, stat)
      if (stat /= hcimpact_ok) return
      call set_end_times(model)
      ev = 0_ik
      call phase_duration(model%f, compression_phase, dur(1), ev, stat)
      if (stat == hcimpact_ok) call phase_duration(model%f, restitution_phase, dur(2), ev, stat)
      if (stat /= hcimpact_ok) return
      do i = 1, size(t)
         call power_state(model, dur, t(i), x(i), v(i), f(i), stat)
         ! A state beyond the range of doubles is not an answer (never NaN with success)
         if (stat == hcimpact_ok .and. .not. (ieee_is_finite(x(i)) .and. ieee_is_finite(v(i)) &
            & .and. ieee_is_finite(f(i)))) stat = hcimpact_err_domain
         if (stat /= hcimpact_ok) then
            x = nan
            v = nan
            f = nan
            return
         end if
      end do
   end subroutine time_law_power

   !> The time law on nsamples equally spaced times from 0 to the contact time
   !> (both included): t(i) = contact_time (i - 1)/(nsamples - 1).
   !>
   !> Errors: those of `time_law`; hcimpact_err_size if nsamples < 2. The outputs are
   !> allocated with max(nsamples, 0) elements in every case, NaN on error.
   pure subroutine time_law_samples(contact, nsamples, t, x, v, f, stat)
      !> The contact
      type(contact_type), intent(in) :: contact
      !> Number of samples, >= 2
      integer, intent(in) :: nsamples
      !> Times in s
      real(wp), allocatable, intent(out) :: t(:)
      !> Compression in m
      real(wp), allocatable, intent(out) :: x(:)
      !> Velocity in m/s
      real(wp), allocatable, intent(out) :: v(:)
      !> Contact force in N
      real(wp), allocatable, intent(out) :: f(:)
      !> Status
      integer, intent(out) :: stat
      type(outcome_type) :: outcome
      integer :: i

      allocate(t(max(nsamples, 0)), x(max(nsamples, 0)), v(max(nsamples, 0)), &
         & f(max(nsamples, 0)))
      t = nan
      x = nan
      v = nan
      f = nan
      if (nsamples < 2) then
         stat = hcimpact_err_size
         return
      end if
      call impact(contact, outcome, stat)
      if (stat /= hcimpact_ok) return
      do i = 1, nsamples
         t(i) = outcome%contact_time * (real(i - 1, wp) / real(nsamples - 1, wp))
      end do
      t(nsamples) = outcome%contact_time
      call time_law(contact, t, x, v, f, stat)
   end subroutine time_law_samples

   !> State at the time t (s) of a power-law impact whose phase durations are known.
   !>
   !> The phase and its half nearer in time are found from the durations; the point is
   !> then located from the turning point (by its l) or from the end of contact (by
   !> rho = d^(1/(n+1)), d its distance in l from the end, which keeps the relative
   !> accuracy of x for t -> 0 and near the end of contact).
   pure subroutine power_state(model, dur, t, x, v, f, stat)
      type(power_model), intent(inout) :: model
      type(dd_real), intent(in) :: dur(2)
      real(wp), intent(in) :: t
      real(wp), intent(out) :: x, v, f
      integer, intent(out) :: stat
      type(dd_real) :: tau, target, l, e, lt, rho, d, length
      real(wp) :: sigma, sigma_n
      integer(ik) :: ev
      integer :: phase
      logical :: from_turn

      stat = hcimpact_ok
      ev = 0_ik
      if (.not. t > 0.0_wp) then
         x = 0.0_wp
         v = model%velocity
         f = 0.0_wp
         return
      end if
      ! time in units of the integrals
      tau = dd(t) / model%time_unit
      e = dur(1) + dur(2)
      if (tau%hi < 1.0e-20_wp * e%hi) then
         ! The start of the motion: x = V t, x' = V, F = c x^n (1 + b V), with relative
         ! corrections of order (t/T)^(n+1) < 1e-20, below an ulp. (The inversion below
         ! would lose a time this small, down to subnormal t, in its rounding.)
         x = model%velocity * t
         v = model%velocity
         ! F = (c x_max^n) (x/x_max)^n (1 + beta)
         f = model%force_unit%hi * (x / model%x_max%hi)**model%n &
            & * (1.0_wp + model%f%tr%beta%hi)
         return
      end if
      if (.not. tau%hi < e%hi) then
         e = -(model%f%tr%k * model%velocity)
         x = 0.0_wp
         v = e%hi
         f = 0.0_wp
         return
      end if
      if (tau%hi <= dur(1)%hi) then
         phase = compression_phase
         from_turn = tau%hi > 0.5_wp * dur(1)%hi
         if (from_turn) then
            target = dur(1) - tau
         else
            target = tau
         end if
      else
         phase = restitution_phase
         target = tau - dur(1)
         from_turn = target%hi <= 0.5_wp * dur(2)%hi
         if (.not. from_turn) target = (dur(1) + dur(2)) - tau
      end if
      if (target%hi < 0.0_wp) target = dd(0.0_wp)
      length = phase_length(model%f%tr, phase)
      if (from_turn) then
         call invert_from_turn(model%f, phase, target, lt, ev, stat)
         if (stat /= hcimpact_ok) return
         d = length - lt
      else
         call invert_from_end(model%f, phase, model%np1_dd, target, rho, d, ev, stat)
         if (stat /= hcimpact_ok) return
         lt = length - d
      end if
      ! sigma = x/x_max from the form for the nearer end of the phase (in l)
      if (lt%hi <= d%hi) then
         call turn_sigma(model, phase, lt%hi, sigma, sigma_n)
      else
         if (from_turn) rho = dd_exp(dd_log(d) / model%np1_dd)
         call end_sigma(model, phase, rho%hi, d%hi, sigma, sigma_n)
      end if
      l = lt
      if (phase == restitution_phase) l = -lt
      e = model%x_max * sigma
      x = e%hi
      v = scaled_velocity(model%f%tr, l) * model%velocity
      ! F = c x^n (1 + u), 1 + u = exp(beta l)
      e = model%force_unit * sigma_n * dd_exp(model%f%tr%beta * l)
      f = e%hi
   end subroutine power_state

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

   !> Check the arguments of the user-law entry points.
   elemental function check_law_input(mass, damping, velocity) result(stat)
      real(wp), intent(in) :: mass, damping, velocity
      integer :: stat
      stat = hcimpact_ok
      if (.not. (ieee_is_finite(mass) .and. ieee_is_finite(damping) &
         & .and. ieee_is_finite(velocity))) then
         stat = hcimpact_err_not_finite
      else if (.not. mass > 0.0_wp) then
         stat = hcimpact_err_mass
      else if (.not. velocity > 0.0_wp) then
         stat = hcimpact_err_velocity
      else if (damping < 0.0_wp) then
         stat = hcimpact_err_damping
      end if
   end function check_law_input

   !> The x with Pi(x) = energy, 0 <= energy <= Pi(x_max): Newton's method (Pi' = f)
   !> safeguarded by bisection, from the power-law guess x_max (E/E_max)^(1/power).
   pure function inverse_potential(f, energy) result(x)
      type(law_integrand), intent(in) :: f
      real(wp), intent(in) :: energy
      real(wp) :: x
      real(wp) :: lo, hi, step, force, excess, x_new
      integer :: it

      if (.not. energy > 0.0_wp) then
         x = 0.0_wp
         return
      end if
      if (energy >= f%energy_max) then
         x = f%x_max
         return
      end if
      lo = 0.0_wp
      hi = f%x_max
      x = f%x_max * (energy / f%energy_max)**(1.0_wp / f%power)
      do it = 1, 200
         excess = f%law%potential(x) - energy
         if (excess > 0.0_wp) then
            hi = x
         else
            lo = x
         end if
         force = f%law%force(x)
         if (force > 0.0_wp) then
            step = excess / force
         else
            step = huge(1.0_wp)
         end if
         if (abs(step) <= 2.0_wp * epsilon(1.0_wp) * x) then
            x = x - step
            return
         end if
         x_new = x - step
         if (.not. (x_new > lo .and. x_new < hi)) then
            ! bisection, geometric while the bracket spans orders of magnitude
            if (lo > 0.0_wp .and. hi > 1024.0_wp * lo) then
               x_new = sqrt(lo) * sqrt(hi)
            else
               x_new = 0.5_wp * (lo + hi)
            end if
         end if
         x = x_new
         if (.not. hi - lo > 2.0_wp * epsilon(1.0_wp) * hi) return
      end do
   end function inverse_potential

   !> Energy fraction S = Pi(x)/(m V^2) at the point with distances dturn, dend.
   pure function energy_fraction(tr, phase, dturn, dend) result(s)
      type(trajectory_type), intent(in) :: tr
      integer, intent(in) :: phase
      real(wp), intent(in) :: dturn, dend
      real(wp) :: s
      if (dturn <= dend) then
         s = tr%hq%hi * (1.0_wp - turn_q(tr, phase, dturn))
      else
         s = dend * end_r(tr, phase, dend)
      end if
   end function energy_fraction

   !> m V/f(x) (s per unit l) at the point with distances dturn, dend.
   pure function law_density(self, dturn, dend) result(rate)
      !> The integrand
      class(law_integrand), intent(in) :: self
      !> Distance to the turning point in l
      real(wp), intent(in) :: dturn
      !> Distance to the end of contact in l
      real(wp), intent(in) :: dend
      !> Density in s
      real(wp) :: rate
      real(wp) :: x
      x = inverse_potential(self, self%energy_unit &
         & * energy_fraction(self%tr, self%phase, dturn, dend))
      ! a force that is not positive makes the integrand non-finite: the quadrature
      ! then reports it
      rate = self%mass * self%velocity / self%law%force(x)
   end function law_density

   !> Time (s) to cross the last d in l before the end of contact, to first order:
   !> x(d)/V_end, V_end the speed at the end (V at impact, k V at separation).
   pure function law_end_time(self, d) result(time)
      !> The integrand
      class(law_integrand), intent(in) :: self
      !> Width in l
      real(wp), intent(in) :: d
      !> Time in s
      real(wp) :: time
      real(wp) :: r0
      r0 = self%tr%end_speed(self%phase)
      time = inverse_potential(self, self%energy_unit * r0 * d) / (self%velocity * r0)
   end function law_end_time

   !> Set up a user-law impact: trajectory, x_max, the exponent near 0; checks the law.
   pure subroutine new_law_model(law, mass, damping, velocity, f, stat)
      class(elastic_law), intent(in) :: law
      real(wp), intent(in) :: mass, damping, velocity
      type(law_integrand), intent(out) :: f
      integer, intent(out) :: stat
      real(wp) :: lo, hi, x, p, e, step
      integer :: it

      stat = hcimpact_ok
      if (log(damping + tiny(1.0_wp)) + log(velocity) > log(max_beta)) then
         stat = hcimpact_err_domain
         return
      end if
      allocate(f%law, source=law)
      f%tr = new_trajectory(two_prod(damping, velocity))
      f%mass = mass
      f%velocity = velocity
      f%energy_unit = mass * velocity * velocity
      if (.not. ieee_is_finite(f%energy_unit)) then
         stat = hcimpact_err_domain
         return
      end if
      ! Pi(x_max) = m V^2 H: bracket by doubling and halving from 1 mm
      e = f%energy_unit * f%tr%hq%hi
      f%energy_max = e
      lo = 1.0e-3_wp
      hi = 1.0e-3_wp
      do it = 1, 2200
         p = law%potential(hi)
         if (bad_potential(p)) then
            stat = hcimpact_err_elastic_law
            return
         end if
         if (p >= e) exit
         lo = hi
         hi = 2.0_wp * hi
      end do
      do it = 1, 2200
         p = law%potential(lo)
         if (bad_potential(p)) then
            stat = hcimpact_err_elastic_law
            return
         end if
         if (p < e .or. lo < tiny(1.0_wp)) exit
         hi = lo
         lo = 0.5_wp * lo
      end do
      if (.not. (law%potential(hi) >= e .and. law%potential(lo) <= e)) then
         stat = hcimpact_err_elastic_law
         return
      end if
      ! then Newton/bisection on Pi(x) = e, Pi' = f
      x = 0.5_wp * (lo + hi)
      do it = 1, 200
         p = law%potential(x) - e
         if (p > 0.0_wp) then
            hi = x
         else
            lo = x
         end if
         if (law%force(x) > 0.0_wp) then
            step = p / law%force(x)
         else
            step = huge(1.0_wp)
         end if
         if (abs(step) <= 2.0_wp * epsilon(1.0_wp) * x) then
            x = x - step
            exit
         end if
         if (x - step > lo .and. x - step < hi) then
            x = x - step
         else
            x = 0.5_wp * (lo + hi)
         end if
         if (.not. hi - lo > 2.0_wp * epsilon(1.0_wp) * hi) exit
      end do
      f%x_max = x
      f%energy_max = law%potential(x)
      if (.not. (f%energy_max > 0.0_wp .and. law%force(x) > 0.0_wp)) then
         stat = hcimpact_err_elastic_law
         return
      end if
      ! the exponent of Pi near 0, for the inversion near the ends of contact
      x = 1.0e-6_wp * f%x_max
      p = law%potential(x)
      if (p > 0.0_wp .and. law%force(x) > 0.0_wp) then
         f%power = x * law%force(x) / p
         if (.not. (f%power > 0.0_wp .and. f%power < 1.0e3_wp)) f%power = 2.0_wp
      end if
   end subroutine new_law_model

   !> Everything about one impact with a user-supplied elastic law f(x) (with its
   !> potential and derivative; see hcimpact_elastic): m x'' = -f(x)(1 + b x').
   !>
   !> Restitution and energy loss depend on beta = b V alone (MODEL.md) and are as
   !> accurate as for the power law. x_max solves Pi(x) = m V^2 h(beta)/beta^2; the
   !> peak force is where m f'(x) x' = b f(x)^2 during compression, found by bisection
   !> (for a law whose force has several local maxima along the compression, one of
   !> them); the times are quadratures of m V/f(x) in the log-velocity variable with
   !> x = Pi^-1(energy) at each node. Their accuracy is that of the law's procedures
   !> (a few ulps each give about 1e-15 relative).
   !>
   !> Errors: as for the power law (mass, damping, velocity), and
   !> hcimpact_err_elastic_law when the law returns a non-finite, negative or
   !> non-increasing value where it is evaluated.
   pure subroutine impact_law(law, mass, damping, velocity, outcome, stat)
      !> The elastic law
      class(elastic_law), intent(in) :: law
      !> Mass in kg (effective mass for two bodies), > 0
      real(wp), intent(in) :: mass
      !> Damping constant b in s/m, >= 0
      real(wp), intent(in) :: damping
      !> Approach speed V in m/s, > 0
      real(wp), intent(in) :: velocity
      !> The outcome; every real field NaN on error
      type(outcome_type), intent(out) :: outcome
      !> Status
      integer, intent(out) :: stat
      type(law_integrand) :: f
      type(dd_real) :: dur(2), t, k, tpeak
      integer(ik) :: ev(3)
      real(wp) :: xp, up, lp

      outcome = outcome_type()
      stat = check_law_input(mass, damping, velocity)
      if (stat /= hcimpact_ok) return
      call new_law_model(law, mass, damping, velocity, f, stat)
      if (stat /= hcimpact_ok) return
      ev = 0_ik
      call phase_duration(f, compression_phase, dur(1), ev(1), stat)
      if (stat == hcimpact_ok) call phase_duration(f, restitution_phase, dur(2), ev(2), stat)
      if (stat /= hcimpact_ok) return

      call law_peak(f, damping, xp, up)
      if (up > 0.0_wp) then
         lp = log1p(up) / f%tr%beta%hi
      else
         lp = 0.0_wp
      end if
      if (lp <= 0.5_wp * f%tr%bound(compression_phase)) then
         call duration_from_turn(f, compression_phase, lp, t, ev(3), stat)
         tpeak = dur(1) - t
      else
         t = f%tr%l_end(compression_phase) - lp
         call duration_from_end(f, compression_phase, t%hi, tpeak, ev(3), stat)
      end if
      if (stat /= hcimpact_ok) return

      k = f%tr%k
      outcome%restitution = k%hi
      t = (1.0_wp - k) * (k + 1.0_wp)
      outcome%energy_loss_ratio = t%hi
      t = -(k * velocity)
      outcome%rebound_velocity = t%hi
      outcome%max_compression = f%x_max
      outcome%compression_time = dur(1)%hi
      t = dur(1) + dur(2)
      outcome%contact_time = t%hi
      outcome%time_at_peak_force = tpeak%hi
      outcome%compression_at_peak_force = xp
      outcome%peak_force = law%force(xp) * (1.0_wp + up)
      outcome%evaluations = ev
      call reject_unrepresentable(outcome, stat)
   end subroutine impact_law

   !> Peak of the force during compression for a user law: x and u = b x' there.
   !> F = f(x)(1 + u) is stationary along the trajectory where G = m f'(x) u - b^2 f^2
   !> vanishes; G > 0 at the start and G = -b^2 f(x_max)^2 < 0 at x_max. Bisection.
   pure subroutine law_peak(f, damping, xp, up)
      type(law_integrand), intent(in) :: f
      real(wp), intent(in) :: damping
      real(wp), intent(out) :: xp, up
      real(wp) :: lo, hi, g
      integer :: it

      xp = f%x_max
      up = 0.0_wp
      if (.not. f%tr%beta%hi > 0.0_wp) return
      lo = 0.0_wp
      hi = f%x_max
      do it = 1, 200
         xp = 0.5_wp * (lo + hi)
         up = law_u(f, xp)
         g = f%mass * f%law%force_derivative(xp) * up - (damping * f%law%force(xp))**2
         if (g > 0.0_wp) then
            lo = xp
         else
            hi = xp
         end if
         if (.not. hi - lo > 2.0_wp * epsilon(1.0_wp) * hi) exit
      end do
      xp = 0.5_wp * (lo + hi)
      up = law_u(f, xp)
   end subroutine law_peak

   !> u = b x' at the compression x during compression: u+(h(beta)(1 - Pi(x)/Pi_max)).
   pure function law_u(f, x) result(u)
      type(law_integrand), intent(in) :: f
      real(wp), intent(in) :: x
      real(wp) :: u
      type(dd_real) :: t
      real(wp) :: y
      y = max(1.0_wp - f%law%potential(x) / f%energy_max, 0.0_wp)
      t = f%tr%hq * f%tr%beta * f%tr%beta * y
      u = -lambert_wm1p1(t%hi)
   end function law_u

   !> Time law with a user-supplied elastic law (see `impact_law` and `time_law`).
   pure subroutine time_law_law(law, mass, damping, velocity, t, x, v, f, stat)
      !> The elastic law
      class(elastic_law), intent(in) :: law
      !> Mass in kg, > 0
      real(wp), intent(in) :: mass
      !> Damping constant b in s/m, >= 0
      real(wp), intent(in) :: damping
      !> Approach speed V in m/s, > 0
      real(wp), intent(in) :: velocity
      !> Times in s from the start of contact
      real(wp), intent(in) :: t(:)
      !> Compression x(t) in m
      real(wp), intent(out) :: x(:)
      !> Velocity x'(t) in m/s
      real(wp), intent(out) :: v(:)
      !> Contact force F(t) in N
      real(wp), intent(out) :: f(:)
      !> Status
      integer, intent(out) :: stat
      type(law_integrand) :: integrand
      type(dd_real) :: dur(2)
      integer(ik) :: ev
      integer :: i

      x = nan
      v = nan
      f = nan
      if (size(x) /= size(t) .or. size(v) /= size(t) .or. size(f) /= size(t)) then
         stat = hcimpact_err_size
         return
      end if
      stat = check_law_input(mass, damping, velocity)
      if (stat /= hcimpact_ok) return
      if (.not. all(ieee_is_finite(t))) then
         stat = hcimpact_err_not_finite
         return
      end if
      call new_law_model(law, mass, damping, velocity, integrand, stat)
      if (stat /= hcimpact_ok) return
      ev = 0_ik
      call phase_duration(integrand, compression_phase, dur(1), ev, stat)
      if (stat == hcimpact_ok) call phase_duration(integrand, restitution_phase, dur(2), ev, stat)
      if (stat /= hcimpact_ok) return
      do i = 1, size(t)
         call law_state(integrand, dur, t(i), x(i), v(i), f(i), stat)
         if (stat == hcimpact_ok .and. .not. (ieee_is_finite(x(i)) .and. ieee_is_finite(v(i)) &
            & .and. ieee_is_finite(f(i)))) stat = hcimpact_err_domain
         if (stat /= hcimpact_ok) then
            x = nan
            v = nan
            f = nan
            return
         end if
      end do
   end subroutine time_law_law

   !> State at the time t (s) of a user-law impact (see `power_state`).
   pure subroutine law_state(integrand, dur, t, x, v, f, stat)
      type(law_integrand), intent(inout) :: integrand
      type(dd_real), intent(in) :: dur(2)
      real(wp), intent(in) :: t
      real(wp), intent(out) :: x, v, f
      integer, intent(out) :: stat
      type(dd_real) :: target, l, e, lt, rho, d, length
      integer(ik) :: ev
      integer :: phase
      logical :: from_turn

      stat = hcimpact_ok
      ev = 0_ik
      if (.not. t > 0.0_wp) then
         x = 0.0_wp
         v = integrand%velocity
         f = 0.0_wp
         return
      end if
      e = dur(1) + dur(2)
      if (.not. t < e%hi) then
         e = -(integrand%tr%k * integrand%velocity)
         x = 0.0_wp
         v = e%hi
         f = 0.0_wp
         return
      end if
      if (t <= dur(1)%hi) then
         phase = compression_phase
         from_turn = t > 0.5_wp * dur(1)%hi
         if (from_turn) then
            target = dur(1) - t
         else
            target = dd(t)
         end if
      else
         phase = restitution_phase
         target = t - dur(1)
         from_turn = target%hi <= 0.5_wp * dur(2)%hi
         if (.not. from_turn) target = (dur(1) + dur(2)) - t
      end if
      if (target%hi < 0.0_wp) target = dd(0.0_wp)
      length = phase_length(integrand%tr, phase)
      if (from_turn) then
         call invert_from_turn(integrand, phase, target, lt, ev, stat)
         if (stat /= hcimpact_ok) return
         d = length - lt
      else
         call invert_from_end(integrand, phase, dd(integrand%power), target, rho, d, ev, stat)
         if (stat /= hcimpact_ok) return
         lt = length - d
      end if
      integrand%phase = phase
      x = inverse_potential(integrand, integrand%energy_unit &
         & * energy_fraction(integrand%tr, phase, lt%hi, d%hi))
      l = lt
      if (phase == restitution_phase) l = -lt
      v = scaled_velocity(integrand%tr, l) * integrand%velocity
      e = integrand%law%force(x) * dd_exp(integrand%tr%beta * l)
      f = e%hi
   end subroutine law_state

   !> Damping constant b (s/m) that gives the restitution e at the approach speed V:
   !> b = beta(e)/V with beta(e) the exact inverse of k(beta) (hcimpact_restitution).
   !>
   !> Resting contact: as V -> 0 the exact b grows without bound. Below `min_velocity`
   !> (default `default_min_velocity` = 1e-3 m/s) b is computed at min_velocity instead,
   !> so that b stays finite and so does every force; impacts slower than that then
   !> restitute with k(b V) > e (less dissipation), tending to 1 as V -> 0. V = 0 is
   !> allowed and gives b = beta(e)/min_velocity.
   !>
   !> Errors: hcimpact_err_not_finite (NaN or infinite argument), hcimpact_err_restitution
   !> (e outside (0, 1]), hcimpact_err_velocity (V < 0, or min_velocity not positive).
   elemental subroutine damping_for_restitution(e, velocity, damping, stat, min_velocity)
      !> Target coefficient of restitution, 0 < e <= 1
      real(wp), intent(in) :: e
      !> Approach speed V in m/s, >= 0
      real(wp), intent(in) :: velocity
      !> Damping b in s/m (0 for e = 1); NaN on error
      real(wp), intent(out) :: damping
      !> Status
      integer, intent(out) :: stat
      !> Speed below which b is computed at this speed, in m/s (> 0)
      real(wp), intent(in), optional :: min_velocity
      real(wp) :: vmin

      damping = nan
      vmin = default_min_velocity
      if (present(min_velocity)) vmin = min_velocity
      if (.not. (ieee_is_finite(e) .and. ieee_is_finite(velocity) .and. ieee_is_finite(vmin))) then
         stat = hcimpact_err_not_finite
         return
      end if
      if (.not. (e > 0.0_wp .and. e <= 1.0_wp)) then
         stat = hcimpact_err_restitution
         return
      end if
      if (velocity < 0.0_wp .or. .not. vmin > 0.0_wp) then
         stat = hcimpact_err_velocity
         return
      end if
      stat = hcimpact_ok
      damping = restitution_inverse(e) / max(velocity, vmin)
   end subroutine damping_for_restitution

   !> A potential value that no law can give: NaN, infinite or negative (tested so that
   !> a NaN never meets an ordered comparison, which would trap in a Debug build)
   elemental function bad_potential(p) result(bad)
      real(wp), intent(in) :: p
      logical :: bad
      if (.not. ieee_is_finite(p)) then
         bad = .true.
      else
         bad = p < 0.0_wp
      end if
   end function bad_potential

   !> An outcome beyond the range of doubles (times of 1e300 s and more) is not an
   !> answer: a successful status never comes with a NaN or an infinity. Such an
   !> outcome becomes all NaN with hcimpact_err_domain.
   pure subroutine reject_unrepresentable(outcome, stat)
      type(outcome_type), intent(inout) :: outcome
      integer, intent(inout) :: stat
      if (stat /= hcimpact_ok) return
      if (all(ieee_is_finite([outcome%restitution, outcome%energy_loss_ratio, &
         & outcome%rebound_velocity, outcome%max_compression, outcome%compression_time, &
         & outcome%contact_time, outcome%time_at_peak_force, &
         & outcome%compression_at_peak_force, outcome%peak_force]))) return
      outcome = outcome_type()
      stat = hcimpact_err_domain
   end subroutine reject_unrepresentable

   include "../numerics/dd_ops.inc"

end module hcimpact_impact_model
