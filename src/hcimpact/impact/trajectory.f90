! SPDX-License-Identifier: Apache-2.0
!> The trajectory of one Hunt-Crossley impact, for any elastic law, in the scaled
!> log-velocity variable; its times by tanh-sinh quadrature and their inversion.
!>
!> With u = b x' (so 1 + u > 0, MODEL.md) and L = ln(1 + u), the equation of motion
!> m x'' = -f(x)(1 + b x') gives dL/dt = -(b/m) f(x), and its first integral (seed
!> eq. 11) reads g(L) = h(beta) - b^2 Pi(x)/m with g(L) = e^L - 1 - L = h(u),
!> beta = b V. In the scaled variable l = L/beta (l -> x'/V as beta -> 0, so that b = 0
!> needs no special case):
!>
!>     Pi(x) = m V^2 S(l),   S(l) = H - l^2 G2(beta l),        (energy)
!>     dt = -(m V / f(x)) dl,                                   (time)
!>     x'/V = expm1(beta l)/beta,                               (velocity)
!>
!> with H = h(beta)/beta^2 and G2(z) = g(z)/z^2 (both 1/2 at 0). Compression runs from
!> l_e = ln(1 + beta)/beta = 1 - beta H (impact) down to 0 (turning point); restitution
!> from 0 down to l- = ln(1 + u-)/beta = -(k + beta H) (end of contact), the last because
!> ln(1 + u) = u - h(u) and h(u-) = h(beta), u- = -k beta. The time integrand is singular
!> only where f(x) = 0, i.e. at the ends of contact, and is regular at the turning point.
!>
!> Why not the position variable: during restitution the velocity u-(t) solving h(u) = t
!> has branch points at t = +-2 pi i, which for h(beta) >> 1 sit next to the turning
!> point and slow the quadrature (about 250 instead of 130 evaluations for
!> 15 < beta < 2000). In L they do not exist: g is entire, and the integrand's only other
!> singularities are the complex zeros of S, near ln(h(beta)) +- 2 pi i. The seed's
!> warning against the velocity variable (a near-pole 1/(1+u) at the rebound end) does
!> not apply to its logarithm: u -> -1 is L -> -inf, off the interval.
!>
!> Cancellation-free forms. Near the turning point S = H (1 - q) with
!> q = l^2 G2(beta l)/H. Near an end, at the distance d from it (in l),
!> S = d R(d) exactly:
!>
!>     compression, from l_e:   R(d) = 1 - (1 + beta) d G2(-beta d),
!>     restitution, from l-:    R(d) = k - A d G2(beta d),   A = 1 + u- = 1 - k beta,
!>
!> which follow from expanding g about the end, where g = h(beta) and g' = u. Each node
!> of a quadrature gets its distances to the turning point and to the end of its phase
!> from the distances to the ends of its interval, and uses the form for the nearer one.
!>
!> The constants k, A and the ends l_e, l- are computed in double-double, because the
!> integrand is singular at the ends: a quadrature interval must end exactly where the
!> end form vanishes. An interval that reaches the end of contact ends at |l_end|
!> rounded to a double, `bound`, and its nodes on the end side take their distance to
!> `bound` as the distance to the true end: that part of the trajectory is shifted by
!> gap = |l_end| - bound (a few 1e-17) against the part near the turning point. When an
!> interval contains the seam between the two forms, the shift costs the time
!> gap*f(seam), which is added back (in `integrate_part`). (Stopping short of the true
!> end instead would leave the singularity just outside the interval, which slows the
!> tanh-sinh rule six-fold.)
module hcimpact_trajectory
   use hcimpact_kinds, only : wp, ik
   use hcimpact_libm, only : log1p, expm1
   use hcimpact_double_double, only : dd_real, dd, two_sum, two_prod, operator(+), &
      & operator(-), operator(*), operator(/), dd_exp, dd_log, dd_inverse
   use hcimpact_lambertw, only : lambert_w0p1, lambert_wm1p1
   use hcimpact_quadrature, only : integrand_type, quadrature_result, tanh_sinh, &
      & quadrature_success, tanh_sinh_max_levels
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_no_convergence
   implicit none
   private


   public :: trajectory_type, new_trajectory, phase_integrand, phase_density, phase_end_time
   public :: compression_phase, restitution_phase
   public :: h_over_square_dd, h_over_square, g2, turn_q, end_r
   public :: phase_duration, duration_from_turn, duration_from_end
   public :: invert_from_turn, invert_from_end, scaled_velocity, phase_length, branch_speed

   !> Index of the compression phase (impact to turning point)
   integer, parameter :: compression_phase = 1
   !> Index of the restitution phase (turning point to end of contact)
   integer, parameter :: restitution_phase = 2

   !> Above this beta, l = ln(1 + u)/beta of the compression's end (and of the peak)
   !> is formed from the logarithm, not as (u - h(u))/beta = 1 - beta H, which cancels:
   !> its relative error 2**-105 beta/ln(1 + beta) is below 1e-21 up to here (1e-5 of
   !> an ulp), but exceeds 1e-16 from beta = 1e19 on and is all of it above 4e33
   real(wp), parameter, public :: log_form_beta = 2.0_wp**40
   !> Below this beta, k(beta) is its Taylor series (MODEL.md): the first omitted term,
   !> 40 beta^5/189, is below 3e-26
   real(wp), parameter :: k_series_max = 1.0e-5_wp
   !> Below this |u|, h(u)/u^2 is its Taylor series (h_over_square)
   real(wp), parameter :: h_series_max = 0.125_wp
   !> Below this |u|, h(u)/u^2 is its Taylor series in double-double (h_over_square_dd:
   !> up to 54 terms, cheaper than the logarithm in double-double)
   real(wp), parameter :: h_series_max_dd = 0.5_wp
   !> 1/j for j = 1, ..., 58 (the series of h(u)/u^2 multiply by them: a division per
   !> term cost more than the sum)
   integer, private :: jj_
   real(wp), parameter :: inv_integer(58) = 1.0_wp / real([(jj_, jj_ = 1, 58)], wp)
   !> Above this beta the tanh-sinh rules cut the restitution into graded pieces
   !> (integrate_span)
   real(wp), parameter :: graded_beta = 8.0_wp
   !> Below this share of the phase, the time from the turning point is the distance
   !> times the rate there (duration_from_turn; the rate's change is second order)
   real(wp), parameter :: first_order_turn = 2.0_wp**(-30)
   !> Bound on every Newton iteration of this module
   integer, parameter :: max_newton = 60
   !> A Newton step below this share of the variable is at the noise of the quadrature
   !> (about an ulp of the time): the iteration has converged
   real(wp), parameter :: newton_done = 4.0_wp * epsilon(1.0_wp)

   !> Constants of the scaled trajectory; they depend on beta only.
   type :: trajectory_type
      !> beta = b V, exact product of the two doubles
      type(dd_real) :: beta
      !> H = h(beta)/beta^2 (1/2 at beta = 0)
      type(dd_real) :: hq
      !> Coefficient of restitution k(beta)
      type(dd_real) :: k
      !> A = 1 - k beta = exp(L-), the factor 1 + u at the end of contact
      type(dd_real) :: a
      !> 1 + beta
      type(dd_real) :: one_plus_beta
      !> L- = beta l- (double; about -beta for large beta)
      real(wp) :: ln_a = 0.0_wp
      !> The ends: l_e = 1 - beta H (compression, > 0) and l- = -(k + beta H) (< 0)
      type(dd_real) :: l_end(2)
      !> |l| of the ends rounded to doubles: where the quadratures that reach the end of
      !> contact stop
      real(wp) :: bound(2) = 0.0_wp
      !> |l_end| - bound (signed, below an ulp of bound)
      real(wp) :: gap(2) = 0.0_wp
      !> |x'|/V at the ends of contact: 1 at impact, k at separation
      real(wp) :: end_speed(2) = 1.0_wp
   end type trajectory_type

   !> Time integrand of one phase; the elastic law supplies the density.
   !>
   !> A quadrature interval is a part of the phase: `turn_gap` is the distance (in |l|)
   !> from the turning point to the end of the interval facing it, `end_gap` the
   !> distance from the other end of the interval to the end of contact (0 when the
   !> interval reaches it).
   type, abstract, extends(integrand_type) :: phase_integrand
      !> The trajectory
      type(trajectory_type) :: tr
      !> compression or restitution
      integer :: phase = compression_phase
      !> Distance from the turning point to the interval end next to it
      real(wp) :: turn_gap = 0.0_wp
      !> Distance from the other interval end to the end of contact
      real(wp) :: end_gap = 0.0_wp
      !> Constant part of the time per unit l (the density is what the quadrature adds)
      real(wp) :: flat = 0.0_wp
      !> Relative tolerance of the quadratures (epsilon: full precision)
      real(wp) :: rtol = epsilon(1.0_wp)
      !> Width in l of one unit of the quadrature's variable, a power of two
      !> (integrate_part)
      real(wp) :: unit = 1.0_wp
   contains
      !> Integrand at a node, from its distances to the interval ends
      procedure :: eval => phase_eval
      !> Time per unit l minus `flat`, at distances dturn and dend (dturn + dend = |l_end|)
      procedure(phase_density), deferred :: density
      !> Time spent in the last d (in |l|) before the end of contact, to first order in d
      procedure(phase_end_time), deferred :: end_time
   end type phase_integrand

   abstract interface
      !> Time per unit of l, minus the constant `flat`, at the point of the phase whose
      !> distances to the turning point and to the end of contact are dturn and dend.
      pure function phase_density(self, dturn, dend) result(rate)
         import :: phase_integrand, wp
         !> The integrand
         class(phase_integrand), intent(in) :: self
         !> Distance to the turning point, |l|
         real(wp), intent(in) :: dturn
         !> Distance to the end of contact, |l_end| - |l|
         real(wp), intent(in) :: dend
         !> Time per unit l, minus `flat`
         real(wp) :: rate
      end function phase_density

      !> Time to cross the last d of the phase before the end of contact, to first order
      !> in d (used for the start of Newton's method and for d below 1e-20 |l_end|).
      pure function phase_end_time(self, d) result(time)
         import :: phase_integrand, wp
         !> The integrand
         class(phase_integrand), intent(in) :: self
         !> Width in l, >= 0 and small compared with |l_end|
         real(wp), intent(in) :: d
         !> Time, in the units of the density
         real(wp) :: time
      end function phase_end_time
   end interface

contains

   !> h(u)/u^2 with h(u) = u - ln(1 + u), for u > -1, in double-double.
   !>
   !> Series sum_j (-u)^j/(j + 2) for |u| < 1/2: its first three terms in double-double,
   !> the rest, u^3 (-1/5 + u/6 - ...), in double (20, 28 or 54 terms for |u| below 1/8,
   !> 1/4, 1/2: the first omitted term is below 1e-18 of the value); the double part is
   !> below 0.06 of the value, its rounding below 1e-17 of it. Else
   !> ((u - ln(1 + u))/u)/u with 1 + u formed exactly (a logarithm in double-double,
   !> which cost twice the long series).
   elemental function h_over_square_dd(u) result(hq)
      !> Argument, u > -1
      type(dd_real), intent(in) :: u
      !> h(u)/u^2
      type(dd_real) :: hq
      ! 1/3 as two doubles
      type(dd_real), parameter :: third = dd_real(1.0_wp / 3.0_wp, 1.850371707708594e-17_wp)
      real(wp) :: x, x2, even, odd, tail
      integer :: j, top
      if (abs(u%hi) < h_series_max_dd) then
         ! tail = sum_{i=0}^{top+1} (-x)^i/(i + 5) as even - x odd, two Horner chains in
         ! x^2 side by side (one chain was the latency of this function)
         x = u%hi
         x2 = x * x
         if (abs(x) < 0.125_wp) then
            top = 18
         else if (abs(x) < 0.25_wp) then
            top = 26
         else
            top = 52
         end if
         even = inv_integer(top + 5)
         odd = inv_integer(top + 6)
         do j = top + 3, 5, -2
            even = even * x2 + inv_integer(j)
            odd = odd * x2 + inv_integer(j + 1)
         end do
         tail = even - x * odd
         ! 1/2 - u/3 + u^2/4 - u^3 tail. u^2/4 is the exact quarter of both parts
         ! (a double-double product by 1/4 rounds to the same two doubles: u^2 is
         ! normalised, so its parts scaled by 1/4 are too; only below 2^-1020, where
         ! u^2 leaves no trace in 1/2 - u/3, could they differ)
         hq = u * u
         hq = ((0.5_wp - u * third) + dd_real(0.25_wp * hq%hi, 0.25_wp * hq%lo)) &
            & - hq * (x * tail)
      else
         ! one product with 1/u^2 (two quotients by u doubled the cost, for no
         ! accuracy needed; u^2 <= max_beta^2 is far inside dd_inverse's range)
         hq = (u - dd_log(u + 1.0_wp)) * dd_inverse(u * u)
      end if
   end function h_over_square_dd

   !> h(u)/u^2 with h(u) = u - ln(1 + u), for u > -1, in double precision (for the
   !> double-precision stages of Newton iterations; about 1e-15 relative).
   !>
   !> Series sum_j (-u)^j/(j + 2) for |u| < 1/8 (20 terms), else (u - ln(1 + u))/u^2.
   elemental function h_over_square(u) result(hq)
      !> Argument, u > -1
      real(wp), intent(in) :: u
      !> h(u)/u^2
      real(wp) :: hq
      real(wp) :: u2, even, odd
      integer :: j
      if (abs(u) < h_series_max) then
         ! sum_{j=0}^{19} (-u)^j/(j + 2) as even - u odd (two chains in u^2, no division;
         ! the same two chains as h_over_square_dd's tail, written twice on purpose: with
         ! these constant bounds the loop unrolls, and a helper shared by both, with
         ! bounds as arguments, made a small-beta impact 5 % slower)
         u2 = u * u
         even = inv_integer(20)
         odd = inv_integer(21)
         do j = 18, 2, -2
            even = even * u2 + inv_integer(j)
            odd = odd * u2 + inv_integer(j + 1)
         end do
         hq = even - u * odd
      else
         hq = ((u - log1p(u)) / u) / u
      end if
   end function h_over_square

   !> G2(z) = (e^z - 1 - z)/z^2 for z <= 709 (G2(0) = 1/2).
   !>
   !> Taylor series sum_j z^j/(j + 2)! by Horner's rule for |z| <= 2 (the first omitted
   !> term is below 5e-20 relative), else (expm1(z) - z)/z^2.
   elemental function g2(z) result(r)
      !> Argument
      real(wp), intent(in) :: z
      !> G2(z) > 0
      real(wp) :: r
      ! 1/(j + 2)! for j = 0, ..., 23, computed at compile time
      integer :: j
      real(wp), parameter :: inv_factorial(0:23) = 1.0_wp / gamma(real([(j, j = 0, 23)], wp) &
         & + 3.0_wp)
      real(wp) :: z2, even, odd
      if (abs(z) <= 2.0_wp) then
         ! sum_j z^j/(j + 2)!, split in even and odd powers (two short Horner chains
         ! without divisions)
         z2 = z * z
         even = inv_factorial(22)
         odd = inv_factorial(23)
         do j = 20, 0, -2
            even = even * z2 + inv_factorial(j)
            odd = odd * z2 + inv_factorial(j + 1)
         end do
         r = even + z * odd
      else
         r = (expm1(z) - z) / (z * z)
      end if
   end function g2

   !> q = l^2 G2(beta l)/H at |l| = lt of a phase: S = H (1 - q) near the turning point.
   elemental function turn_q(tr, phase, lt) result(q)
      !> The trajectory
      type(trajectory_type), intent(in) :: tr
      !> compression or restitution
      integer, intent(in) :: phase
      !> Distance from the turning point, |l| >= 0
      real(wp), intent(in) :: lt
      !> q in [0, 1]
      real(wp) :: q
      real(wp) :: l
      l = lt
      if (phase == restitution_phase) l = -lt
      q = (l * l * g2(tr%beta%hi * l)) / tr%hq%hi
      ! the trailing part of H: q H_hi/(H_hi + H_lo)
      q = q - q * (tr%hq%lo / tr%hq%hi)
   end function turn_q

   !> R(d) at the distance d (in l) from the end of contact of a phase: S = d R(d).
   elemental function end_r(tr, phase, d) result(r)
      !> The trajectory
      type(trajectory_type), intent(in) :: tr
      !> compression or restitution
      integer, intent(in) :: phase
      !> Distance from the end, >= 0
      real(wp), intent(in) :: d
      !> R(d); R(0) = 1 (compression) or k (restitution)
      real(wp) :: r
      real(wp) :: beta, z, t
      beta = tr%beta%hi
      if (phase == compression_phase) then
         ! 1 - (1 + beta) d G2(-beta d)
         t = d * g2(-beta * d)
         r = (1.0_wp - t * tr%one_plus_beta%hi) - t * tr%one_plus_beta%lo
      else
         z = beta * d
         if (z <= 2.0_wp) then
            ! k - A d G2(beta d)
            t = d * g2(z)
            r = ((tr%k%hi - tr%a%hi * t) + tr%k%lo) - tr%a%lo * t
         else
            ! A d G2(z) = (A e^z - A (1 + z))/(beta z), and A e^z = exp(L- + z) cannot
            ! overflow (it is 1 + u <= 1)
            t = (exp(tr%ln_a + z) - tr%a%hi * (1.0_wp + z)) / (beta * z)
            r = (tr%k%hi - t) + tr%k%lo
         end if
      end if
   end function end_r

   !> The constants of the trajectory for beta = b V >= 0 (finite).
   pure function new_trajectory(beta) result(tr)
      !> beta as the exact product of b and V
      type(dd_real), intent(in) :: beta
      !> Its trajectory
      type(trajectory_type) :: tr
      type(dd_real) :: hb, u, lm, kb, phi, ea, bh
      real(wp) :: b, kb0, c, step
      integer :: it

      tr%beta = beta
      b = beta%hi
      tr%hq = h_over_square_dd(beta)
      tr%one_plus_beta = beta + 1.0_wp
      ! beta H (both ends, and h(beta) = (beta H) beta below: a double-double product
      ! does not depend on the order of its factors, Dekker's error term being exact)
      bh = beta * tr%hq

      if (b == 0.0_wp) then
         tr%k = dd(1.0_wp)
         tr%a = dd(1.0_wp)
         tr%ln_a = 0.0_wp
      else if (b < k_series_max) then
         ! MODEL.md: k = 1 - 2b/3 + 4b^2/9 - 44b^3/135 + 104b^4/405 - ...
         c = b * (-2.0_wp / 3.0_wp + b * (4.0_wp / 9.0_wp + b * (-44.0_wp / 135.0_wp &
            & + b * (104.0_wp / 405.0_wp))))
         tr%k = two_sum(1.0_wp, c)
         kb = tr%k * beta
         tr%a = 1.0_wp - kb
         tr%ln_a = log1p(-kb%hi)
      else
         hb = bh * beta
         ! 1 + W0(-exp(-1 - h)) = k beta (seed eq. 21), then Newton in double-double
         kb0 = lambert_w0p1(hb%hi)
         if (kb0 < 0.5_wp) then
            ! on h(u) - h(beta) = 0 for u = -k beta; h'(u) = u/(1 + u)
            u = dd(-kb0)
            ! from a double start, one step squares the error (below 1e-30)
            do it = 1, 1
               phi = h_over_square_dd(u) * u * u - hb
               ! the step is at the 1e-16 level: its quotient in double suffices
               u = u - phi%hi * (u%hi + 1.0_wp) / u%hi
            end do
            tr%a = u + 1.0_wp
            kb = -u
         else
            ! on g(L) - h(beta) = 0 for L = ln(1 + u-) < 0; g'(L) = e^L - 1. When k beta
            ! rounds to 1, A = e^L is below 1e-16 and L = -1 - h + A is a good start.
            if (kb0 < 1.0_wp) then
               lm = dd(log1p(-kb0))
            else
               lm = dd(-1.0_wp) - hb
            end if
            ! (from a start good to a double, one step; from L = -1 - h + A, or where
            ! 1 - k beta is small and its logarithm has lost digits, up to three)
            do it = 1, 3
               ea = dd_exp(lm)
               phi = ((ea - 1.0_wp) - lm) - hb
               ! e^L - 1 <= -1/2 here; the step in double is exact enough for its size
               step = phi%hi / (ea%hi - 1.0_wp)
               lm = lm - step
               if (abs(step) <= 1.0e-15_wp * abs(lm%hi)) exit
            end do
            if (abs(step) <= 1.0e-15_wp * abs(lm%hi)) then
               ! A = e^L = e^(L + step) e^(-step): the last exponential, moved by the step
               tr%a = ea - ea * (step - 0.5_wp * step * step)
            else
               tr%a = dd_exp(lm)
            end if
            kb = 1.0_wp - tr%a
         end if
         ! (beta >= k_series_max here: its reciprocal is normal)
         tr%k = kb * dd_inverse(beta)
      end if

      if (b > log_form_beta) then
         ! l_e = ln(1 + beta)/beta: 1 - beta H is that difference, which keeps only
         ! about 2**-105 beta/ln(beta) of it (nothing above beta = 4e33)
         tr%l_end(compression_phase) = dd_log(tr%one_plus_beta) / beta
      else
         tr%l_end(compression_phase) = 1.0_wp - bh
      end if
      tr%l_end(restitution_phase) = -(tr%k + bh)
      if (b > 0.0_wp) then
         ea = beta * tr%l_end(restitution_phase)
         tr%ln_a = ea%hi
      end if
      ! the quadrature ends and their offsets from the true ends
      tr%bound(compression_phase) = tr%l_end(compression_phase)%hi
      tr%gap(compression_phase) = tr%l_end(compression_phase)%lo
      tr%bound(restitution_phase) = -tr%l_end(restitution_phase)%hi
      tr%gap(restitution_phase) = -tr%l_end(restitution_phase)%lo
      tr%end_speed(compression_phase) = 1.0_wp
      tr%end_speed(restitution_phase) = tr%k%hi
   end function new_trajectory

   !> x'/V = u/beta on a branch at the point where the elastic energy is the share
   !> 1 - y of its largest value: h(u) = h(beta) y (the first integral, MODEL.md), so
   !> u = -(1 + W(-exp(-1 - h(beta) y))), W_-1 in compression and W_0 in restitution
   !> (seed eq. 14). For small s = beta xi, xi = sqrt(2 H y) (h(beta) y = s^2/2), the
   !> series of 1 + W about the branch point divided by beta: u+/beta = xi (1 + s/3 +
   !> s^2/36 - s^3/270 + ...), u-/beta = -xi (1 - s/3 + s^2/36 + s^3/270 + ...), so that
   !> beta -> 0 is smooth (x'/V -> +-sqrt(y)) and a tiny beta does not underflow.
   elemental function branch_speed(tr, y, phase) result(w)
      !> The trajectory
      type(trajectory_type), intent(in) :: tr
      !> y = 1 - Pi(x)/Pi(x_max), in [0, 1]
      type(dd_real), intent(in) :: y
      !> compression_phase or restitution_phase
      integer, intent(in) :: phase
      !> x'/V
      real(wp) :: w
      type(dd_real) :: t
      real(wp) :: xi, s, b
      b = tr%beta%hi
      xi = sqrt(2.0_wp * tr%hq%hi * y%hi)
      s = b * xi
      if (s < 1.0e-4_wp) then
         ! the first term left out, s^4/4320, is below 3e-20
         if (phase == compression_phase) then
            w = xi * (1.0_wp + s * (1.0_wp / 3.0_wp + s * (1.0_wp / 36.0_wp - s / 270.0_wp)))
         else
            w = -xi * (1.0_wp - s * (1.0_wp / 3.0_wp - s * (1.0_wp / 36.0_wp + s / 270.0_wp)))
         end if
      else
         t = tr%hq * tr%beta * tr%beta * y
         if (phase == compression_phase) then
            w = -lambert_wm1p1(t%hi) / b
         else
            w = -lambert_w0p1(t%hi) / b
         end if
      end if
   end function branch_speed

   !> x'/V at the point l of the trajectory: expm1(beta l)/beta (l at beta = 0).
   !>
   !> l is double-double: beta l may be hundreds in magnitude, and its error in units
   !> of its own ulp would be multiplied by it in exp(beta l).
   elemental function scaled_velocity(tr, l) result(v)
      !> The trajectory
      type(trajectory_type), intent(in) :: tr
      !> Signed l (> 0 in compression, < 0 in restitution)
      type(dd_real), intent(in) :: l
      !> Velocity in units of the approach speed
      real(wp) :: v
      type(dd_real) :: z, e
      if (tr%beta%hi == 0.0_wp) then
         v = l%hi
         return
      end if
      z = tr%beta * l
      if (abs(z%hi) < 1.0e-3_wp) then
         ! expm1(z)/z = 1 + z/2 + z^2/6 + z^3/24 + z^4/120 + O(z^5), |z^5/720| < 2e-18
         v = l%hi * (1.0_wp + z%hi * (0.5_wp + z%hi * (1.0_wp / 6.0_wp + z%hi &
            & * (1.0_wp / 24.0_wp + z%hi / 120.0_wp))))
      else
         e = (dd_exp(z) - 1.0_wp) / tr%beta
         v = e%hi
      end if
   end function scaled_velocity

   !> The integrand at a node. Every part of a phase is integrated over [0, width], the
   !> lower end facing the turning point: the distances to the interval ends, which the
   !> quadrature forms without cancellation, plus the gaps give the node's distances to
   !> the turning point and to the end of contact. The node itself is not needed.
   pure function phase_eval(self, x, dxa, dxb) result(fx)
      !> The integrand
      class(phase_integrand), intent(in) :: self
      !> Node (not used: see above)
      real(wp), intent(in) :: x
      !> Distance to the end of the interval facing the turning point
      real(wp), intent(in) :: dxa
      !> Distance to the end of the interval facing the end of contact
      real(wp), intent(in) :: dxb
      !> Density at the node
      real(wp) :: fx
      ! (the distance to the end of contact no smaller than the smallest normal number:
      ! scaled by a tiny unit, the rule's last nodes would reach 0, where the density is
      ! infinite)
      fx = self%density(self%turn_gap + dxa * self%unit, &
         & max(self%end_gap + dxb * self%unit, tiny(1.0_wp)))
   end function phase_eval

   !> |l| of the end of contact of a phase, in double-double.
   elemental function phase_length(tr, phase) result(length)
      !> The trajectory
      type(trajectory_type), intent(in) :: tr
      !> compression or restitution
      integer, intent(in) :: phase
      !> |l_end|
      type(dd_real) :: length
      if (phase == compression_phase) then
         length = tr%l_end(compression_phase)
      else
         length = -tr%l_end(restitution_phase)
      end if
   end function phase_length

   !> Integral of flat + density over a part of the current phase of the given width,
   !> whose end facing the turning point lies turn_gap from it and whose other end lies
   !> end_gap from the end of contact (0: the part reaches the end). Adds the
   !> evaluations.
   pure subroutine integrate_part(f, turn_gap, width, end_gap, total, evaluations, stat)
      class(phase_integrand), intent(inout) :: f
      real(wp), intent(in) :: turn_gap, width, end_gap
      type(dd_real), intent(out) :: total
      integer(ik), intent(inout) :: evaluations
      integer, intent(out) :: stat
      type(quadrature_result) :: res
      real(wp) :: atol, seam

      stat = hcimpact_ok
      f%turn_gap = turn_gap
      f%end_gap = end_gap
      total = dd(0.0_wp)
      if (.not. width > 0.0_wp) return
      ! For the power law the density is a correction to `flat`: its error is measured
      ! against the whole integral, of which flat*width is a part.
      atol = 0.5_wp * epsilon(1.0_wp) * f%flat * width
      ! The rule runs over [0, width/unit], width/unit in [1/2, 1), unit a power of two
      ! (exact): its nodes reach 1.7e-275 of the interval from an end but no closer than
      ! the smallest normal number, so a part narrower than 1e-33 in l (beta above 1e30)
      ! would have nodes piled up at that floor, and a singular end would not converge.
      f%unit = scale(1.0_wp, exponent(width))
      ! In l the integrands are analytic near the real axis (g is entire; the density's
      ! singularities are at the ends, where the tanh-sinh map handles them), so the
      ! rule doubles its digits per level: no level is spent confirming convergence.
      call tanh_sinh(f, 0.0_wp, width / f%unit, res, rtol=f%rtol, atol=atol / f%unit, &
         & max_levels=tanh_sinh_max_levels, analytic=.true.)
      evaluations = evaluations + res%evaluations
      if (res%status /= quadrature_success) then
         stat = hcimpact_err_no_convergence
         return
      end if
      total = two_prod(f%flat, width) + res%integral * f%unit
      ! a part that reaches the end and contains the seam: add the time of the shift
      seam = 0.5_wp * f%tr%bound(f%phase)
      if (end_gap == 0.0_wp .and. turn_gap < seam .and. f%tr%gap(f%phase) /= 0.0_wp) &
         & total = total + f%tr%gap(f%phase) * (f%flat + f%density(seam, seam))
   end subroutine integrate_part

   !> Integral of flat + density over |l| in [from, from + width] of the current phase
   !> (the span reaches the end of contact when reaches_end: from + width = bound). For
   !> beta > graded_beta the restitution is cut at |L| = beta |l| = 4, 12, 36 (below 3/4
   !> of the phase), each piece a tanh-sinh rule of its own: the complex zeros of S near
   !> L = ln h(beta) +- 2 pi i, next to the turning point on a phase of length ~beta in
   !> L, made one rule's error estimate stop early (a user law's contact time was off by
   !> up to 8e3 ulps for beta = 1e4 ... 1e6; the power law's rules cut the phase the
   !> same way, hcimpact_power_rules). Without a cut inside, the width is used as given
   !> (recomputed from the ends it would carry the rounding of the larger one).
   pure subroutine integrate_span(f, from, width, reaches_end, total, evaluations, stat)
      class(phase_integrand), intent(inout) :: f
      real(wp), intent(in) :: from, width
      logical, intent(in) :: reaches_end
      type(dd_real), intent(out) :: total
      integer(ik), intent(inout) :: evaluations
      integer, intent(out) :: stat
      type(dd_real) :: part, gap
      real(wp) :: a, b, to, cut_l, beta, phase_l, end_gap, rest

      stat = hcimpact_ok
      total = dd(0.0_wp)
      a = from
      to = from + width
      if (reaches_end) to = f%tr%bound(f%phase)
      beta = f%tr%beta%hi
      if (f%phase == restitution_phase .and. beta > graded_beta) then
         phase_l = beta * f%tr%bound(restitution_phase)
         cut_l = 4.0_wp
         do while (cut_l <= 0.75_wp * phase_l .and. cut_l <= 40.0_wp)
            b = cut_l / beta
            if (b > a .and. b < to) then
               gap = phase_length(f%tr, f%phase) - b
               call integrate_part(f, a, b - a, gap%hi, part, evaluations, stat)
               if (stat /= hcimpact_ok) return
               total = total + part
               a = b
            end if
            cut_l = 3.0_wp * cut_l
         end do
      end if
      end_gap = 0.0_wp
      if (.not. reaches_end) then
         gap = phase_length(f%tr, f%phase) - to
         end_gap = gap%hi
      end if
      rest = width
      if (a /= from) rest = to - a
      call integrate_part(f, a, rest, end_gap, part, evaluations, stat)
      total = total + part
   end subroutine integrate_span

   !> Duration of a whole phase, in the units of the density.
   pure subroutine phase_duration(f, phase, duration, evaluations, stat)
      !> The integrand (its phase and gaps are set here)
      class(phase_integrand), intent(inout) :: f
      !> compression or restitution
      integer, intent(in) :: phase
      !> Duration
      type(dd_real), intent(out) :: duration
      !> Integrand evaluations, incremented
      integer(ik), intent(inout) :: evaluations
      !> Status
      integer, intent(out) :: stat

      f%phase = phase
      call integrate_span(f, 0.0_wp, f%tr%bound(phase), .true., duration, evaluations, stat)
   end subroutine phase_duration

   !> Time between the turning point and the point at |l| = lt of a phase.
   pure subroutine duration_from_turn(f, phase, lt, duration, evaluations, stat)
      !> The integrand
      class(phase_integrand), intent(inout) :: f
      !> compression or restitution
      integer, intent(in) :: phase
      !> |l| of the point, 0 <= lt <= bound(phase)
      real(wp), intent(in) :: lt
      !> Duration
      type(dd_real), intent(out) :: duration
      !> Integrand evaluations, incremented
      integer(ik), intent(inout) :: evaluations
      !> Status
      integer, intent(out) :: stat
      type(dd_real) :: gap

      f%phase = phase
      if (lt >= f%tr%bound(phase)) then
         call integrate_span(f, 0.0_wp, f%tr%bound(phase), .true., duration, evaluations, &
            & stat)
      else if (lt <= first_order_turn * f%tr%bound(phase)) then
         ! next to the turning point the rate is flat to second order: lt times the rate
         ! there, to 2**-60 relative (and a quadrature over a span of 1e-280 would
         ! not converge: the peak at beta = 1e-280)
         stat = hcimpact_ok
         gap = phase_length(f%tr, phase)
         duration = two_prod(lt, rate_at(f, 0.0_wp, gap%hi))
      else
         call integrate_span(f, 0.0_wp, lt, .false., duration, evaluations, stat)
      end if
   end subroutine duration_from_turn

   !> Time between the end of contact of a phase (impact, or separation) and the point
   !> at the distance d (in l) from it.
   pure subroutine duration_from_end(f, phase, d, duration, evaluations, stat)
      !> The integrand
      class(phase_integrand), intent(inout) :: f
      !> compression or restitution
      integer, intent(in) :: phase
      !> Distance from the end of contact, 0 <= d <= |l_end|
      real(wp), intent(in) :: d
      !> Duration
      type(dd_real), intent(out) :: duration
      !> Integrand evaluations, incremented
      integer(ik), intent(inout) :: evaluations
      !> Status
      integer, intent(out) :: stat
      real(wp) :: width

      f%phase = phase
      width = min(d, f%tr%bound(phase))
      call integrate_span(f, f%tr%bound(phase) - width, width, .true., duration, evaluations, &
         & stat)
   end subroutine duration_from_end

   !> Rate d(time)/d|l| at a point: flat + density.
   pure function rate_at(f, dturn, dend) result(rate)
      class(phase_integrand), intent(in) :: f
      real(wp), intent(in) :: dturn, dend
      real(wp) :: rate
      rate = f%flat + f%density(dturn, dend)
   end function rate_at

   !> The point of a phase that is the time `target` away from the turning point, as its
   !> |l| = lt. Newton's method on the quadrature, safeguarded by bisection.
   !>
   !> lt is carried in double-double: the quadrature is done to lt%hi and the time of
   !> lt%lo added at the rate there. The time determines L = beta l to about an ulp
   !> absolutely, which a double lt (relative accuracy) would not hold when |L| >> 1;
   !> the force exp(L) needs it.
   pure subroutine invert_from_turn(f, phase, target, lt, evaluations, stat)
      !> The integrand
      class(phase_integrand), intent(inout) :: f
      !> compression or restitution
      integer, intent(in) :: phase
      !> Time from the turning point, 0 <= target <= the phase duration (density units)
      type(dd_real), intent(in) :: target
      !> |l| of the point
      type(dd_real), intent(out) :: lt
      !> Integrand evaluations, incremented
      integer(ik), intent(inout) :: evaluations
      !> Status
      integer, intent(out) :: stat
      real(wp) :: lo, hi, step, rate, w
      type(dd_real) :: tau, length, dend
      integer :: it

      stat = hcimpact_ok
      f%phase = phase
      length = phase_length(f%tr, phase)
      lo = 0.0_wp
      hi = f%tr%bound(phase)
      lt = dd(0.0_wp)
      if (.not. target%hi > 0.0_wp) return
      ! near the turning point the time is (flat + density(0)) lt to second order; the
      ! integrand grows towards the end, so the first guess stays in the first half
      rate = rate_at(f, 0.0_wp, length%hi)
      lt = dd(min(target%hi / rate, 0.5_wp * hi))
      do it = 1, max_newton
         w = lt%hi
         call duration_from_turn(f, phase, w, tau, evaluations, stat)
         if (stat /= hcimpact_ok) return
         dend = length - w
         if (dend%hi > 0.0_wp) then
            rate = rate_at(f, w, dend%hi)
            tau = (tau + rate * lt%lo) - target
            if (tau%hi > 0.0_wp) then
               hi = w
            else
               lo = w
            end if
            step = tau%hi / rate
         else
            ! at the end of contact the rate is infinite: bisect
            hi = w
            step = 0.5_wp * (w - lo)
         end if
         if (.not. abs(step) > newton_done * w) then
            ! converged: the last (tiny) step still refines the trailing part
            lt = lt - step
            return
         end if
         if (w - step > lo .and. w - step < hi) then
            lt = lt - step
         else
            lt = dd(0.5_wp * (lo + hi))
         end if
         if (hi - lo <= 2.0_wp * epsilon(1.0_wp) * hi) return
      end do
      stat = hcimpact_err_no_convergence
   end subroutine invert_from_turn

   !> The point of a phase that is the time `target` away from its end of contact, as
   !> rho = d^(1/power), d its distance in l from the end. Near the end the time grows
   !> like d^(1/power) (power = n + 1 for f ~ x^n), so that it is nearly linear in rho.
   !> Newton's method in rho, safeguarded by bisection; rho and d are carried in
   !> double-double (see `invert_from_turn`), and d = exp(power ln rho) is formed in
   !> double-double so that rho = d^(1/power) holds to the last bit even for tiny rho.
   pure subroutine invert_from_end(f, phase, power, target, rho, d, evaluations, stat)
      !> The integrand
      class(phase_integrand), intent(inout) :: f
      !> compression or restitution
      integer, intent(in) :: phase
      !> Exponent of the distance, > 0
      type(dd_real), intent(in) :: power
      !> Time from the end of contact, 0 <= target <= the phase duration (density units)
      type(dd_real), intent(in) :: target
      !> rho = d^(1/power)
      type(dd_real), intent(out) :: rho
      !> Distance d from the end of contact, in l
      type(dd_real), intent(out) :: d
      !> Integrand evaluations, incremented
      integer(ik), intent(inout) :: evaluations
      !> Status
      integer, intent(out) :: stat
      ! below this d/|l_end| the time is end_time(d) to the last bit
      real(wp), parameter :: first_order_only = 1.0e-20_wp
      real(wp) :: lo, hi, step, rate, drate, length, g, r
      type(dd_real) :: tau
      integer :: it

      stat = hcimpact_ok
      f%phase = phase
      rho = dd(0.0_wp)
      d = dd(0.0_wp)
      if (.not. target%hi > 0.0_wp) return
      length = phase_length_hi(f%tr, phase)
      lo = 0.0_wp
      hi = length**(1.0_wp / power%hi)
      ! start from the leading term: time = end_time(d), linear in rho
      g = first_order_only * length
      rate = f%end_time(g) / g**(1.0_wp / power%hi)
      rho = target / rate
      if (rho%hi > hi) rho = dd(hi)
      d = dd_exp(power * dd_log(rho))
      if (d%hi <= first_order_only * length) return
      do it = 1, max_newton
         r = rho%hi
         call duration_from_end(f, phase, d%hi, tau, evaluations, stat)
         if (stat /= hcimpact_ok) return
         ! d(time)/d(d) = flat + density; d(time)/d(rho) = that times power d/rho
         drate = rate_at(f, max(length - d%hi, 0.0_wp), d%hi)
         rate = drate * power%hi * (d%hi / r)
         tau = (tau + drate * d%lo) - target
         if (tau%hi > 0.0_wp) then
            hi = r
         else
            lo = r
         end if
         step = tau%hi / rate
         if (.not. abs(step) > newton_done * r) then
            ! converged: the last (tiny) step still refines the trailing part
            rho = rho - step
            d = dd_exp(power * dd_log(rho))
            return
         end if
         if (r - step > lo .and. r - step < hi) then
            rho = rho - step
         else
            rho = dd(0.5_wp * (lo + hi))
         end if
         d = dd_exp(power * dd_log(rho))
         if (hi - lo <= 2.0_wp * epsilon(1.0_wp) * hi) return
      end do
      stat = hcimpact_err_no_convergence
   end subroutine invert_from_end

   !> |l| of the end of contact of a phase, rounded to a double.
   elemental function phase_length_hi(tr, phase) result(length)
      !> The trajectory
      type(trajectory_type), intent(in) :: tr
      !> compression or restitution
      integer, intent(in) :: phase
      !> |l_end|
      real(wp) :: length
      length = abs(tr%l_end(phase)%hi)
   end function phase_length_hi


end module hcimpact_trajectory
