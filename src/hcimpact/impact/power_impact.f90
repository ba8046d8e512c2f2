! SPDX-License-Identifier: Apache-2.0
!> One impact with the power law f = c x^n: its outcome (`impact_power`), the velocity
!> at a depth (phase curves) and the time law x(t), x'(t), F(t).
!>
!> Nothing here stops or prints; every procedure returns a status (hcimpact_status) and
!> NaN outputs when it is not hcimpact_ok. The method: doc/impact.md.
module hcimpact_power_impact
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
   use hcimpact_kinds, only : wp, ik, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_domain, &
      & hcimpact_err_size, hcimpact_err_no_convergence, hcimpact_err_out_of_memory
   use hcimpact_double_double, only : dd_real, dd, operator(+), &
      & operator(-), operator(*), operator(/), &
      & dd_exp, dd_log, dd_sqrt, dd_inverse
   use hcimpact_contact, only : contact_type, outcome_type, check_contact, &
      & reject_unrepresentable
   use hcimpact_trajectory, only : compression_phase, restitution_phase, &
      & invert_from_turn, invert_from_end, scaled_velocity, phase_length, branch_speed
   use hcimpact_power_model, only : power_model, new_power_model, set_end_times, &
      & power_peak, turn_log_share, end_log_share, peak_ratio_m1, peak_series_max_y
   use hcimpact_force_element, only : contact_force_type, contact_force
   use hcimpact_power_rules, only : power_phase_times, power_whole_cc, whole_max_beta, &
      & contact_max_beta
   implicit none
   private

   public :: impact_power, velocity_at_depth, time_law_power, time_law_samples
   public :: compression_branch, restitution_branch, max_quadrature_exponent

   !> Largest exponent n for which `impact` and the time law integrate the times
   !> (hcimpact_err_no_convergence above). Their weight (1 - x^2)^(-n/(n+1)) tends to a
   !> non-integrable one as n grows: against mpmath the times are within 2.7 ulp up to
   !> n = 200, 5 ulp at 1e3, 27 at 1e5, and from about 5e16 on (n/(n+1) rounding to 1)
   !> the rules divide by zero. velocity_at_depth needs no quadrature: any n.
   real(wp), parameter :: max_quadrature_exponent = 100.0_wp
   !> Branch of `velocity_at_depth`: compression (x' > 0)
   integer, parameter :: compression_branch = compression_phase
   !> Branch of `velocity_at_depth`: restitution (x' < 0)
   integer, parameter :: restitution_branch = restitution_phase

contains

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
      type(dd_real) :: k, t, dur(2), tpeak, y, u, lp
      integer(ik) :: ev(3)
      ! the compression at the peak force, and (x_peak/x_max)^(n+1) = 1 - y there
      type(dd_real) :: xp, share

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

      ! the peak (u = beta q there, y = 1 - (x/x_max)^(n+1), l of the point), the times
      call power_times(model, u, y, lp, dur, tpeak, ev, stat)
      if (stat /= hcimpact_ok) return

      k = model%f%tr%k
      outcome%restitution = k%hi
      t = (1.0_wp - k) * (k + 1.0_wp)
      outcome%energy_loss_ratio = t%hi
      outcome%rebound_velocity = rebound_velocity(model)
      outcome%max_compression = model%x_max%hi
      t = model%time_unit * dur(1)
      outcome%compression_time = t%hi
      t = model%time_unit * (dur(1) + dur(2))
      outcome%contact_time = t%hi
      t = model%time_unit * tpeak
      outcome%time_at_peak_force = t%hi
      ! x_peak = x_max (1 - y)^(1/(n+1)); F = c x_peak^n (1 + u), which is
      ! (n+1) m V^2 H (1 - y) (1 + u)/x_peak since c x_peak^(n+1) = c x_max^(n+1) (1 - y)
      share = 1.0_wp - y
      if (model%ln_x_max_dd .and. model%energy_ok .and. y%hi < peak_series_max_y) then
         ! small beta: x_max (1 + (x_peak/x_max - 1)) by two short series (where the
         ! scales are within energy_ok's range: the peak force below needs no ln x_peak)
         xp = model%x_max + model%x_max * peak_ratio_m1(y, model%inv_np1_dd)
      else if (model%ln_x_max_dd) then
         t = model%ln_x_max + dd_log(share) * model%inv_np1_dd
         xp = dd_exp(t)
      else
         ! n = 1: x_max sqrt(1 - y)
         xp = model%x_max * dd_sqrt(share)
      end if
      outcome%compression_at_peak_force = xp%hi
      if (model%energy_ok) then
         ! (x_peak <= x_max < 2**700 here; a product with 1/x_peak where it is normal)
         t = model%energy * share * (u + 1.0_wp)
         if (xp%hi > 2.0_wp**(-990)) then
            t = t * dd_inverse(xp)
         else
            t = t / xp
         end if
         outcome%peak_force = t%hi
      else
         t = dd_log(dd(contact%stiffness)) + model%n * t + dd_log(u + 1.0_wp)
         outcome%peak_force = dd_exp_hi(t)
      end if
      outcome%evaluations = ev
      call reject_unrepresentable(outcome, stat)
   end subroutine impact_power

   !> The peak of the force and the times of a power-law impact, in the units of the
   !> integrals: u = beta q, y = 1 - (x/x_max)^(n+1) and l at the peak; the compression
   !> and restitution times and the time from the impact to the peak. One rule over the
   !> whole contact for small beta, else rules on the phases (and their pieces). The
   !> time law takes the same times, so that its contact time is `impact`'s.
   pure subroutine power_times(model, u, y, lp, dur, tpeak, ev, stat)
      type(power_model), intent(inout) :: model
      type(dd_real), intent(out) :: u, y, lp, dur(2), tpeak
      !> Evaluations (compression, restitution, peak)
      integer(ik), intent(out) :: ev(3)
      integer, intent(out) :: stat
      logical :: whole
      type(dd_real) :: contact
      stat = hcimpact_ok
      ev = 0_ik
      if (model%n > max_quadrature_exponent) then
         stat = hcimpact_err_no_convergence
         return
      end if
      call power_peak(model, u, y, lp)
      whole = .false.
      if (model%f%tr%beta%hi <= whole_max_beta) then
         call power_whole_cc(model, lp, .true., dur, tpeak, ev(1), whole)
      else if (model%f%tr%beta%hi <= contact_max_beta) then
         ! the contact time over the whole contact, the compression by its own rule
         call power_whole_cc(model, lp, .false., dur, tpeak, ev(2), whole)
         if (whole) then
            contact = dur(1)
            call power_phase_times(model, lp, dur, tpeak, ev, stat, contact)
            return
         end if
      end if
      if (.not. whole) call power_phase_times(model, lp, dur, tpeak, ev, stat)
   end subroutine power_times

   !> exp of a double-double number, rounded to a double.
   elemental function dd_exp_hi(a) result(x)
      type(dd_real), intent(in) :: a
      real(wp) :: x
      type(dd_real) :: e
      e = dd_exp(a)
      x = e%hi
   end function dd_exp_hi

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
      real(wp) :: w

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
      call new_power_model(contact, model, stat, depth_only=.true.)
      if (stat /= hcimpact_ok) return
      if (x > model%x_max%hi * (1.0_wp + 4.0_wp * epsilon(1.0_wp))) then
         stat = hcimpact_err_domain
         return
      end if
      ! y = 1 - (x/x_max)^(n+1), in double-double: (x/x_max)^(n+1) = exp(r (n+1)) with
      ! r = ln(x/x_max) <= 0 (r > 0 is x within 4 ulps beyond x_max: y = 0); when
      ! r (n+1) is below -746 the power is 0 (r (n+1) itself may overflow, n = DBL_MAX)
      if (x == 0.0_wp) then
         yd = dd(1.0_wp)
      else
         if (.not. model%ln_x_max_dd) model%ln_x_max = dd_log(model%x_max)
         t = dd_log(dd(x)) - model%ln_x_max
         if (.not. t%hi < 0.0_wp) then
            yd = dd(0.0_wp)
         else if (t%hi < -746.0_wp / model%np1) then
            yd = dd(1.0_wp)
         else
            yd = 1.0_wp - dd_exp(t * model%np1_dd)
         end if
      end if
      if (yd%hi < 0.0_wp) yd = dd(0.0_wp)
      if (yd%hi == 1.0_wp .and. yd%lo == 0.0_wp) then
         ! the ends of the branches (x = 0, or (x/x_max)^(n+1) below 2^-106), exactly as
         ! `impact` gives them: V, and -k V
         if (branch == compression_branch) then
            v = contact%velocity
         else
            v = rebound_velocity(model)
         end if
         return
      end if
      w = branch_speed(model%f%tr, yd, branch)
      v = within_branch(model, branch, w * contact%velocity)
      ! a successful status never comes with a NaN or an infinity
      if (.not. ieee_is_finite(v)) then
         v = nan
         stat = hcimpact_err_domain
      end if
   end subroutine velocity_at_depth

   !> Compression x(t), velocity x'(t) and contact force F(t) = c x^n (1 + b x') at the
   !> times t(:). Before the contact (t <= 0): x = 0, x' = V, F = 0; after it
   !> (t >= contact time): x = 0, x' = -k V, F = 0.
   !>
   !> Each time costs a few quadratures (Newton's method on the time as a function of
   !> the position, bounded). Near the end of contact x(t) is ill-conditioned: it moves
   !> by |x'| times the error of the contact time (a few ulps of it).
   !>
   !> Errors: those of `impact` (but a time whose state is representable is answered
   !> where only another output of `impact`, the peak force, is beyond the range);
   !> hcimpact_err_domain for a state beyond the range of doubles;
   !> hcimpact_err_no_convergence where a point cannot be located to double accuracy
   !> (large n with heavy damping: the restitution creeps within 1e-16 of its end in
   !> l); hcimpact_err_not_finite if a t is NaN or infinite; hcimpact_err_size if the
   !> arrays differ in size.
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
      type(dd_real) :: dur(2), u, y, lp, tpeak, e
      integer(ik) :: ev(3)
      real(wp) :: contact_time
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
      ! the phases' durations of `impact`, and its contact time: from that double on the
      ! contact is over (x = 0, F = 0 exactly), as `impact` and the samples say
      call power_times(model, u, y, lp, dur, tpeak, ev, stat)
      if (stat /= hcimpact_ok) return
      e = model%time_unit * (dur(1) + dur(2))
      contact_time = e%hi
      do i = 1, size(t)
         call power_state(model, dur, contact_time, t(i), x(i), v(i), f(i), stat)
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
   !> Errors: those of `time_law`; hcimpact_err_size if nsamples < 2;
   !> hcimpact_err_out_of_memory if the four arrays of nsamples elements cannot be
   !> allocated (then none of them is allocated). Otherwise the outputs are allocated
   !> with max(nsamples, 0) elements in every case, NaN on error.
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
      integer :: i, alloc_stat

      allocate(t(max(nsamples, 0)), x(max(nsamples, 0)), v(max(nsamples, 0)), &
         & f(max(nsamples, 0)), stat=alloc_stat)
      if (alloc_stat /= 0) then
         ! out of memory: nothing is allocated
         if (allocated(t)) deallocate(t)
         if (allocated(x)) deallocate(x)
         if (allocated(v)) deallocate(v)
         if (allocated(f)) deallocate(f)
         stat = hcimpact_err_out_of_memory
         return
      end if
      t = nan
      x = nan
      v = nan
      f = nan
      if (nsamples < 2) then
         stat = hcimpact_err_size
         return
      end if
      call impact_power(contact, outcome, stat)
      if (stat /= hcimpact_ok) return
      do i = 1, nsamples
         t(i) = outcome%contact_time * (real(i - 1, wp) / real(nsamples - 1, wp))
      end do
      t(nsamples) = outcome%contact_time
      call time_law_power(contact, t, x, v, f, stat)
   end subroutine time_law_samples

   !> State at the time t (s) of a power-law impact whose phase durations are known.
   !>
   !> The phase and its half nearer in time are found from the durations; the point is
   !> then located from the turning point (by its l) or from the end of contact (by
   !> rho = d^(1/(n+1)), d its distance in l from the end, which keeps the relative
   !> accuracy of x for t -> 0 and near the end of contact).
   pure subroutine power_state(model, dur, contact_time, t, x, v, f, stat)
      type(power_model), intent(inout) :: model
      type(dd_real), intent(in) :: dur(2)
      !> The contact time of `impact`, in s
      real(wp), intent(in) :: contact_time
      real(wp), intent(in) :: t
      real(wp), intent(out) :: x, v, f
      integer, intent(out) :: stat
      ! a point nearer than this share of the phase's length in l to the end it was
      ! located from is located from the other end
      real(wp), parameter :: far_end = 2.0_wp**(-20)
      type(dd_real) :: tau, turn_time, end_time, l, e, lt, rho, d, length, ln_share
      type(contact_force_type) :: element
      integer(ik) :: ev
      integer :: phase, attempt
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
      if (tau%hi < 1.0e-20_wp * dur(1)%hi) then
         ! The start of the motion: x = V t, x' = V, F = c x^n (1 + b V), with relative
         ! corrections of order (t/t_c)^(n+1) < 1e-20, t_c the compression time, below an
         ! ulp (of the compression, not of the contact: above beta = 1e20 the compression
         ! is shorter than 1e-20 of the contact, and the whole of it was taken as its
         ! start before issue 13). (The inversion below
         ! would lose a time this small, down to subnormal t, in its rounding.) The
         ! state is the two doubles x and V exactly: its force is the contact-force
         ! element's (hcimpact_force_element)
         x = model%velocity * t
         v = model%velocity
         call contact_force(model%stiffness, model%n, model%damping, x, v, element)
         f = element%force
         return
      end if
      if (.not. (t < contact_time .and. tau%hi < e%hi)) then
         x = 0.0_wp
         v = rebound_velocity(model)
         f = 0.0_wp
         return
      end if
      ! the times from the turning point and from the end of contact of the phase
      if (tau%hi <= dur(1)%hi) then
         phase = compression_phase
         turn_time = dur(1) - tau
         end_time = tau
      else
         phase = restitution_phase
         turn_time = tau - dur(1)
         end_time = (dur(1) + dur(2)) - tau
      end if
      if (turn_time%hi < 0.0_wp) turn_time = dd(0.0_wp)
      if (end_time%hi < 0.0_wp) end_time = dd(0.0_wp)
      length = phase_length(model%f%tr, phase)
      ! Located from the nearer end in time first. The nearer end in l may be the other
      ! one: with a large exponent and damping (n = 82, b V = 6600) the restitution
      ! creeps out at -k V for most of its time within 1e-16 of the end of contact in
      ! l, and l - length from the turning point cancelled to nothing (x 2e7 times
      ! x_max). A point within 2^-20 of the far end in l is located again from that
      ! end (once: the two ends cannot both be that near).
      from_turn = turn_time%hi <= end_time%hi
      do attempt = 1, 2
         if (from_turn) then
            call invert_from_turn(model%f, phase, turn_time, lt, ev, stat)
            if (stat /= hcimpact_ok) return
            d = length - lt
            if (.not. d%hi < far_end * length%hi) exit
         else
            call invert_from_end(model%f, phase, model%np1_dd, end_time, rho, d, ev, stat)
            if (stat /= hcimpact_ok) return
            lt = length - d
            if (.not. lt%hi < far_end * length%hi) exit
         end if
         if (attempt == 1) from_turn = .not. from_turn
      end do
      if (d%hi < 0.0_wp) d = dd(0.0_wp)
      if (lt%hi < 0.0_wp) lt = dd(0.0_wp)
      ! ln((x/x_max)^(n+1)) from the form of S for the nearer end of the phase (in l),
      ! in double-double: x and F are each one exponential of it, rounded once. In
      ! compression the end form R(d) = 1 - (1 + beta) d G2(-beta d) cancels to about
      ! 1/(beta d) where beta d is large (a large beta, 9 ulps of x at 3.6e28): there the
      ! turning point's form, whose 1 - q does not cancel (as in power_nodes).
      if (lt%hi <= d%hi .or. (phase == compression_phase &
         & .and. model%f%tr%beta%hi * d%hi > 4.0_wp)) then
         ln_share = turn_log_share(model, phase, lt)
      else if (from_turn) then
         ln_share = end_log_share(model, phase, dd_log(d), d%hi)
      else
         ln_share = end_log_share(model, phase, model%np1_dd * dd_log(rho), d%hi)
      end if
      l = lt
      if (phase == restitution_phase) l = -lt
      ! x = x_max (x/x_max)
      e = dd_exp(model%ln_x_max + ln_share * model%inv_np1_dd)
      x = e%hi
      v = within_branch(model, phase, scaled_velocity(model%f%tr, l) * model%velocity)
      ! The force along the trajectory, F = c x^n (1 + u) = c x_max^n (x/x_max)^n
      ! exp(beta l): from the trajectory's double-double quantities, not from the
      ! rounded x and x' (the contact-force element at those doubles is exact for them,
      ! but their roundings would cost F up to about 4.5 ulps)
      e = dd_exp(model%ln_force_unit + ln_share * dd_real(model%f%alpha_hi, &
         & model%f%alpha_lo) + model%f%tr%beta * l)
      f = e%hi
   end subroutine power_state

   !> A velocity of the phase held within its exact bounds: 0 <= x' <= V in compression,
   !> -k V <= x' <= 0 in restitution. Near the ends of a phase x'/V is about 1 or -k,
   !> and its rounding may cross the bound by an ulp or two (found by the fuzz test at
   !> beta = 7e-6): the bound itself is then the nearer double.
   pure function within_branch(model, phase, v) result(bounded)
      type(power_model), intent(in) :: model
      !> compression_phase or restitution_phase
      integer, intent(in) :: phase
      !> The velocity in m/s
      real(wp), intent(in) :: v
      real(wp) :: bounded
      if (phase == compression_phase) then
         bounded = min(v, model%velocity)
      else
         bounded = max(v, rebound_velocity(model))
      end if
   end function within_branch

   !> The rebound velocity -k V, rounded once from k in double-double: the outcome's,
   !> and the end of every velocity of the restitution.
   pure function rebound_velocity(model) result(v)
      type(power_model), intent(in) :: model
      real(wp) :: v
      type(dd_real) :: t
      t = -(model%f%tr%k * model%velocity)
      v = t%hi
   end function rebound_velocity

end module hcimpact_power_impact
