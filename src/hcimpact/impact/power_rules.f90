! SPDX-License-Identifier: Apache-2.0
!> The quadrature rules of the times of a power-law impact, and their schedule.
!>
!> One modified Clenshaw-Curtis rule with the symmetric weight (1 - x^2)^(-alpha) over
!> the whole contact for beta <= whole_max_beta (`power_whole_cc`), and for the contact
!> time alone up to contact_max_beta; otherwise a rule on each phase (`power_piece_cc`,
!> the compression's only below contact_max_beta), cut into graded pieces for large beta
!> (`power_phase_split`), and tanh-sinh (hcimpact_trajectory) where a rule does not
!> converge. doc/quadrature.md explains the rules, doc/impact.md the schedule.
module hcimpact_power_rules
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp, ik
   use hcimpact_libm, only : log1p
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_double_double, only : dd_real, dd, two_sum, two_prod, operator(+), &
      & operator(-), operator(*), operator(/), &
      & dd_exp, dd_log, dd_sqrt, dd_inverse
   use hcimpact_modified_cc, only : cc_max_degree, cc_moments, cc_moments_pair, &
      & cc_coefficients, cc_sum, cc_converged, cc_plain, cc_end_share, cc_turn_share, &
      & cc_node, inv_end_share_hi, inv_end_share_lo, sym_m0, sym_moments, sym_partial_moments, &
      & sym_q0, sym_q0_near_end, sym_series_max
   use hcimpact_contact, only : contact_type, check_contact
   use hcimpact_trajectory, only : compression_phase, restitution_phase, turn_q, end_r, g2, &
      & phase_duration, duration_from_turn, duration_from_end
   use hcimpact_power_model, only : power_model, new_power_model, power_peak
   implicit none
   private

   public :: power_phase_times, power_whole_cc
   ! the thresholds and the cuts, for the unit tests of the graded pieces
   public :: power_phase_pieces, max_pieces, cc_max_beta, cc_max_compression_le, end_piece_le
   public :: whole_max_beta, contact_max_beta

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
   !> Up to this beta (above whole_max_beta) the contact time is one rule over the whole
   !> contact at degree 24 (25 evaluations up to beta = 6, 49 beyond for most n) and the
   !> compression a rule of its own (25), where the rules on the two phases took 25 + 49
   !> (the restitution's was never accepted at 24 above beta = 1.8): never more
   !> evaluations, mostly 24 fewer. The compression and the time of the peak as
   !> incomplete integrals of the whole contact's rule (as below whole_max_beta) were
   !> up to 6 ulp off for n = 10 from beta = 3.5 on (issue 17). Above, the restitution's
   !> graded pieces.
   real(wp), parameter :: contact_max_beta = cc_max_beta
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

contains

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
   !> the end of the piece facing the turning point, `f_far` at the other end (plain
   !> pieces), `f_middle` (weighted pieces, if asked for) in the middle.
   pure subroutine power_piece_cc(model, phase, offset, length, gap, e0, weighted, tol, &
         & moment, moment_degree, degree, a, lin, duration, f_turn, f_far, evaluations, &
         & converged, f_middle)
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
      !> [A, B]: the interpolant is A + B x + sum'' a_k T_k(x), x = 2 d/D - 1 (of a
      !> plain piece only a_(degree-1) and a_degree are set)
      integer, intent(out) :: degree
      real(wp), intent(out) :: a(0:cc_max_degree), lin(2)
      type(dd_real), intent(out) :: duration
      real(wp), intent(out) :: f_turn, f_far
      real(wp), intent(out), optional :: f_middle
      integer(ik), intent(inout) :: evaluations
      logical, intent(out) :: converged
      real(wp) :: f(0:cc_max_degree), g(0:cc_max_degree), fmax, rest
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
      ! Nor was the restitution's end piece cut at |beta l| <= 12 (the layouts of beta
      ! up to about 30; cut at 24 or 27 it often is): the same outcomes to the bit over
      ! 9e4 random contacts, 8 <= beta <= 1e8.
      degree = 12
      if (weighted .and. offset == 0.0_wp .and. tol < 4.0_wp * epsilon(1.0_wp)) degree = 24
      if (weighted .and. phase == restitution_phase &
         & .and. model%f%tr%beta%hi * offset <= 12.5_wp) degree = 24
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
         if (weighted) then
            call cc_coefficients(degree, g, a)
            ! the straight line's part in double-double: it is nearly all of the integral
            sum = (two_prod(lin(1), moment(0)) + two_prod(lin(2), moment(1))) &
               & + cc_sum(degree, a, moment)
         else
            ! weight 1: the rule's fixed weights on the values, no transform; of the
            ! coefficients only the last two, for the test (J_0 = 2, J_1 = 0)
            call cc_plain(degree, g, rest, a(degree - 1:degree))
            sum = two_prod(lin(1), moment(0)) + rest
         end if
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
               ! the density (d/D)^(-alpha) F in the middle, d = D/2 (node 24)
               if (present(f_middle)) f_middle = exp(model%f%alpha_hi * log(2.0_wp)) &
                  & * f(cc_max_degree / 2)
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
   !> With `parts` false, only the contact time (in dur(1); dur(2) and tpeak 0) and no
   !> condition on the turning point.
   pure subroutine power_whole_cc(model, lp, parts, dur, tpeak, evaluations, converged)
      type(power_model), intent(in) :: model
      !> l of the peak force
      type(dd_real), intent(in) :: lp
      !> Whether the compression and the time of the peak are wanted too
      logical, intent(in) :: parts
      !> Compression and restitution times (parts), else the contact time and 0
      type(dd_real), intent(out) :: dur(2)
      !> Time from the impact to the peak (parts), else 0
      type(dd_real), intent(out) :: tpeak
      integer(ik), intent(inout) :: evaluations
      logical, intent(out) :: converged
      real(wp) :: f(0:cc_max_degree), g(0:cc_max_degree), a(0:cc_max_degree)
      real(wp) :: moment(0:cc_max_degree)
      real(wp) :: lin(2), b1, b2, length, nu, fmax, alpha, inv_den(cc_max_degree)
      type(dd_real) :: ls, sq, kk, total, num, x0, xp, m0, inv_length
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
      x0 = dd(0.0_wp)
      xp = dd(0.0_wp)
      if (parts) then
         ! the turning point and the peak in x: x = 1 - 2 d_c/L, L = b1 + b2 - ls%lo, and
         ! the turning point's d_c is b1 (the nodes place l = b1 - d_c), the peak's
         ! b1 - lp
         ! (two products with 1/L, L of order 1, instead of two quotients)
         num = two_sum(b2, -b1) - ls%lo
         inv_length = dd_inverse(dd(length))
         x0 = num * inv_length
         xp = (num + 2.0_wp * lp) * inv_length
         ! (the peak lies between the turning point and the impact: x0 <= xp < 1)
         if (.not. (abs(x0%hi) <= sym_series_max .and. xp%hi < 1.0_wp &
            & .and. xp%hi >= -sym_series_max)) return
      end if
      m0 = sym_m0(model%inv_np1_dd, model%np1_dd)

      ! degrees 12, 24, 48 (nested); above whole_16_beta, where 12 is not accepted,
      ! 16 (every third node of the 48 grid) and then 48
      first = 0
      degree = 12
      if (model%f%tr%beta%hi > whole_16_beta) degree = 16
      if (model%f%tr%beta%hi > whole_max_beta) degree = 24
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
      if (.not. parts) then
         dur(1) = total
         return
      end if
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
      real(wp) :: cut(0:max_pieces), bound, e0, tol, width, resid, f_turn, f_far, f_middle
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
      if (phase == compression_phase) then
         call power_piece_cc(model, phase, cut(np), end_length, gap_end, 0.0_wp, .true., &
            & tol, moment, moment_degree, deg_p, a_p, lin_p, part, f_turn, f_far, &
            & evaluations, converged)
         if (.not. converged) return
         duration = duration + part + gap_end * prev_far
      else
         ! The restitution's end piece is about 1 long in l, gap_end about an ulp of
         ! that, while next to the cut the density varies on the scale 1/beta in l:
         ! shifted by gap_end, the nodes next to the cut would move by beta gap_end in L
         ! (past the turning point from beta = 1e17 on). Its nodes on the turning point's
         ! side are placed from the cut, those on the other side from the end of
         ! contact, and the sliver gap_end between the two halves is added at the
         ! density in the middle, which is flat on the scale of gap_end there (as the
         ! tanh-sinh parts do, hcimpact_trajectory's integrate_part).
         call power_piece_cc(model, phase, cut(np), end_length, 0.0_wp, -1.0_wp, .true., &
            & tol, moment, moment_degree, deg_p, a_p, lin_p, part, f_turn, f_far, &
            & evaluations, converged, f_middle)
         if (.not. converged) return
         duration = duration + part + gap_end * f_middle
      end if
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
      type(dd_real) :: u, y, lp
      split = .false.
      bound = 0.0_wp
      cut = 0.0_wp
      np = 0
      stat = check_contact(contact)
      if (stat /= hcimpact_ok) return
      call new_power_model(contact, model, stat)
      if (stat /= hcimpact_ok) return
      call power_peak(model, u, y, lp)
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

   !> The times of a power-law impact by rules on its two phases (power_piece_cc, cut
   !> into graded pieces for large beta: power_phase_split; tanh-sinh if a rule does
   !> not converge), in the units of the integrals: compression, restitution and from
   !> the impact to the peak (the compression's interpolant where it holds the peak).
   !> With `contact` (the contact time of power_whole_cc) the restitution is the contact
   !> less the compression: no rule on it.
   pure subroutine power_phase_times(model, lp, dur, tpeak, ev, stat, contact)
      !> The model (its integrand is the tanh-sinh rules' state)
      type(power_model), intent(inout) :: model
      !> l of the peak force
      type(dd_real), intent(in) :: lp
      type(dd_real), intent(out) :: dur(2), tpeak
      !> Evaluations: compression, restitution, peak (added to)
      integer(ik), intent(inout) :: ev(3)
      integer, intent(out) :: stat
      !> The contact time, if known
      type(dd_real), intent(in), optional :: contact
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
      ! (big_c serves only where s > 0, and is set there; set here too, since GCC's
      ! inlining cannot see that and warns: -Werror=maybe-uninitialized failed a
      ! C++ program's -Wall -Werror link of the static library with link-time
      ! optimisation)
      big_c = 0.0_wp
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
      if (present(contact)) then
         dur(2) = contact - dur(1)
         done(2) = .true.
      else if (model%f%tr%beta%hi <= cc_max_beta) then
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

end module hcimpact_power_rules
