! SPDX-License-Identifier: Apache-2.0
!> One impact with an elastic law supplied by the caller (hcimpact_elastic):
!> m x'' = -f(x)(1 + b x'). Its outcome (`impact_law`) and time law (`time_law_law`).
!>
!> The trajectory (restitution, the ends of the phases) is that of the power law; x
!> along it comes from inverting the law's potential, and the times are quadratures of
!> m V/f(x) in the log-velocity variable (hcimpact_trajectory).
module hcimpact_law_impact
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_positive_inf
   use hcimpact_kinds, only : wp, ik, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_domain, &
      & hcimpact_err_size, hcimpact_err_elastic_law, hcimpact_err_out_of_memory
   use hcimpact_double_double, only : dd_real, dd, two_prod, operator(+), &
      & operator(-), operator(*), operator(/), &
      & dd_exp
   use hcimpact_elastic, only : elastic_law
   use hcimpact_contact, only : outcome_type, check_parameters, reject_unrepresentable, &
      & max_beta
   use hcimpact_trajectory, only : trajectory_type, new_trajectory, phase_integrand, &
      & compression_phase, restitution_phase, turn_q, end_r, phase_duration, &
      & duration_from_turn, duration_from_end, invert_from_turn, invert_from_end, &
      & scaled_velocity, phase_length, branch_speed
   implicit none
   private

   public :: impact_law, time_law_law

   !> Share of x_max next to an end of contact below which a zero force (the law's
   !> value below the double range) is taken as no time: the time spent there is
   !> about end_share times the contact time or less (law_density)
   real(wp), parameter :: end_share = 2.0_wp**(-64)

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


contains

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
         step = newton_step(excess, force)
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

   !> The Newton step excess/force of an inversion of the potential (Pi' = f), or the
   !> largest double where the force is not positive and finite or the quotient would
   !> overflow (not formed: the Debug build traps): the caller then bisects.
   elemental function newton_step(excess, force) result(step)
      real(wp), intent(in) :: excess, force
      real(wp) :: step
      step = huge(1.0_wp)
      if (force > 0.0_wp .and. force <= huge(1.0_wp) .and. abs(excess) <= huge(1.0_wp)) then
         if (exponent(excess) - exponent(force) < maxexponent(1.0_wp) - 1) &
            & step = excess / force
      end if
   end function newton_step

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
      real(wp) :: x, force
      logical :: within
      x = inverse_potential(self, self%energy_unit &
         & * energy_fraction(self%tr, self%phase, dturn, dend))
      force = self%law%force(x)
      ! (m V/f < 2**(e_m + e_V - e_f + 1): its range from the binary exponents, read only
      ! of a positive finite f)
      within = .false.
      if (force > 0.0_wp .and. force <= huge(1.0_wp)) within = exponent(self%mass) &
         & + exponent(self%velocity) - exponent(force) < maxexponent(1.0_wp)
      if (force > huge(1.0_wp)) then
         ! (an infinite force: no time)
         rate = 0.0_wp
      else if (within) then
         rate = self%mass * self%velocity / force
      else if (x <= end_share * self%x_max .and. .not. ieee_is_nan(force)) then
         ! next to an end of contact, where the law's force is 0 (x or f(x) below the
         ! double range) or m V/f beyond it: the time spent below x is about x/|x'|
         ! there, below end_share of the contact time, and the node adds nothing to
         ! the integral
         rate = 0.0_wp
      else
         ! a force that is not positive, or m V/f beyond the double range, elsewhere:
         ! a non-finite integrand (not formed: the Debug build traps on an overflow),
         ! which the quadrature reports
         rate = ieee_value(1.0_wp, ieee_positive_inf)
      end if
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
      integer :: it, alloc_stat

      stat = hcimpact_ok
      if (log(damping + tiny(1.0_wp)) + log(velocity) > log(max_beta)) then
         stat = hcimpact_err_domain
         return
      end if
      allocate(f%law, source=law, stat=alloc_stat)
      if (alloc_stat /= 0) then
         ! out of memory for the copy of the law
         stat = hcimpact_err_out_of_memory
         return
      end if
      f%tr = new_trajectory(two_prod(damping, velocity))
      f%mass = mass
      f%velocity = velocity
      ! m V^2 < 2**(e_m + 2 e_V): tested on the binary exponents before the product,
      ! which must not overflow on the way (the Debug build traps)
      if (exponent(mass) + 2 * exponent(velocity) >= maxexponent(1.0_wp)) then
         stat = hcimpact_err_domain
         return
      end if
      f%energy_unit = mass * velocity * velocity
      ! Pi(x_max) = m V^2 H: bracket by doubling and halving from 1 mm. The law's
      ! energies are doubles in J: below the normal range they would have lost their
      ! relative precision (the power law itself handles such scales: hcimpact_err_domain)
      e = f%energy_unit * f%tr%hq%hi
      if (.not. e >= tiny(1.0_wp)) then
         stat = hcimpact_err_domain
         return
      end if
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
         if (hi > 0.5_wp * huge(1.0_wp)) then
            ! Pi below m V^2 H up to the largest double: x_max is beyond the range
            stat = hcimpact_err_domain
            return
         end if
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
         step = newton_step(p, law%force(x))
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
      ! (x f/p from a positive finite x f and p only where no overflow can occur)
      step = law%force(x)
      if (p > 0.0_wp .and. step > 0.0_wp .and. step <= huge(1.0_wp)) then
         if (exponent(x) + exponent(step) - exponent(p) < maxexponent(1.0_wp) - 1) &
            & f%power = (x * step) / p
         if (.not. (f%power > 0.0_wp .and. f%power < 1.0e3_wp)) f%power = 2.0_wp
      end if
      ! Next to an end of contact the quadratures ask the law for x at the energies
      ! Pi_max s, s -> 0; where they are subnormal they have lost digits. That part of
      ! the contact takes about the share (tiny/Pi_max)^(1/power) of its time, which
      ! must stay below 2**-56: else hcimpact_err_domain (Pi_max below about 1e-290 for a
      ! linear law, 1e-120 for f ~ x^10).
      if (log(f%energy_max) - log(tiny(1.0_wp)) < 56.0_wp * log(2.0_wp) * f%power) then
         stat = hcimpact_err_domain
         return
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
   !> non-increasing value where it is evaluated; hcimpact_err_domain also when the
   !> peak force acts closer to the impact than the smallest double (a law that jumps
   !> at x = 0, e.g. c x^n with n near 0); hcimpact_err_out_of_memory when the copy of
   !> the law cannot be allocated.
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
      real(wp) :: xp, up, dist, w_peak, force
      logical :: from_turn

      outcome = outcome_type()
      stat = check_parameters(mass=mass, damping=damping, velocity=velocity)
      if (stat /= hcimpact_ok) return
      call new_law_model(law, mass, damping, velocity, f, stat)
      if (stat /= hcimpact_ok) return
      ev = 0_ik
      call phase_duration(f, compression_phase, dur(1), ev(1), stat)
      if (stat == hcimpact_ok) call phase_duration(f, restitution_phase, dur(2), ev(2), stat)
      if (stat /= hcimpact_ok) return

      ! the peak: its distance in l from the turning point or from the impact
      call law_peak(f, damping, from_turn, dist, xp, w_peak, stat)
      if (stat /= hcimpact_ok) return
      if (.not. xp > 0.0_wp) then
         ! the peak lies closer to the impact than the smallest double (a law that jumps
         ! at 0, such as c x^n with n near 0: G < 0 down to x = 2^-1074); f(0) = 0 cannot
         ! stand for the force there, so its value and place are beyond the range
         stat = hcimpact_err_domain
         return
      end if
      ! the trajectory never passes x_max; next to the turning point the potential's
      ! inverse at the peak's l can round an ulp beyond it (b V = 1e-263)
      xp = min(xp, f%x_max)
      if (from_turn) then
         call duration_from_turn(f, compression_phase, dist, t, ev(3), stat)
         tpeak = dur(1) - t
      else
         call duration_from_end(f, compression_phase, dist, tpeak, ev(3), stat)
      end if
      if (stat /= hcimpact_ok) return
      up = f%tr%beta%hi * w_peak

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
      ! F = f(x)(1 + u) at the peak, u = b x' = beta w > 0 (no cancellation in 1 + u)
      force = law%force(xp)
      if (.not. (force >= 0.0_wp .and. force <= huge(1.0_wp))) then
         outcome = outcome_type()
         stat = hcimpact_err_elastic_law
         return
      else if (exponent(force) + exponent(1.0_wp + up) < maxexponent(1.0_wp)) then
         outcome%peak_force = force * (1.0_wp + up)
      else
         ! beyond the double range (not formed: the Debug build traps on an overflow)
         outcome%peak_force = ieee_value(1.0_wp, ieee_positive_inf)
      end if
      outcome%evaluations = ev
      call reject_unrepresentable(outcome, stat)
   end subroutine impact_law

   !> Peak of the force during compression for a user law: where along the trajectory
   !> (its distance `dist` from the turning point, from_turn, or from the impact), the
   !> compression xp and the speed there as w = x'/V.
   !>
   !> F = f(x)(1 + b x') is stationary along the trajectory where
   !> G = m f'(x) x' - b f(x)^2 vanishes (MODEL.md); G > 0 at the impact and
   !> G = -b f(x_max)^2 < 0 at the turning point. Bisection on the sign of G along the
   !> trajectory in l (hcimpact_trajectory): in l from the turning point on the half
   !> next to it, in the distance d from the impact on the other, geometric while the
   !> bracket spans decades. In l, not in x: near x_max (small beta) x hardly moves
   !> while x' goes from V beta to 0, and the time of the peak needs l (a bisection in
   !> x left it 1e-8 off). The sign is decided by comparing the products m V f' w and
   !> b f f without forming them (greater_product), so that neither (b f)^2 can
   !> overflow nor m f' x' underflow (m = 1e300 or b = 1e-300 made G infinite or 0 all
   !> along, and the bisection ran to an end). Where f or f' is outside the normal
   !> range (0, subnormal or infinite) the sign follows from bounds on them when they
   !> decide it, else hcimpact_err_domain. hcimpact_err_elastic_law if the law returns
   !> a NaN, a force that is negative or not finite, or a negative derivative.
   pure subroutine law_peak(f, damping, from_turn, dist, xp, w_peak, stat)
      type(law_integrand), intent(in) :: f
      real(wp), intent(in) :: damping
      logical, intent(out) :: from_turn
      real(wp), intent(out) :: dist, xp, w_peak
      integer, intent(out) :: stat
      real(wp) :: lo, hi, half
      logical :: rising
      integer :: it

      stat = hcimpact_ok
      from_turn = .true.
      dist = 0.0_wp
      xp = f%x_max
      w_peak = 0.0_wp
      if (.not. f%tr%beta%hi > 0.0_wp) return
      half = 0.5_wp * f%tr%bound(compression_phase)
      call peak_sign(f, damping, .true., half, rising, xp, w_peak, stat)
      if (stat /= hcimpact_ok) return
      ! from the turning point (G < 0) towards the impact (G > 0): lo on the turning
      ! point's side, hi on the impact's side, in the variable of the half
      from_turn = rising
      lo = 0.0_wp
      hi = half
      if (from_turn) then
         lo = 2.0_wp**(-1074)
      else
         hi = 2.0_wp**(-1074)
         lo = half
      end if
      do it = 1, 300
         ! geometric while the bracket spans decades (a peak near the turning point at
         ! tiny beta lies at l of order beta), else arithmetic
         if (max(lo, hi) > 1024.0_wp * min(lo, hi)) then
            dist = sqrt(lo) * sqrt(hi)
         else
            dist = 0.5_wp * (lo + hi)
         end if
         call peak_sign(f, damping, from_turn, dist, rising, xp, w_peak, stat)
         if (stat /= hcimpact_ok) return
         if (rising) then
            hi = dist
         else
            lo = dist
         end if
         if (.not. abs(hi - lo) > 2.0_wp * epsilon(1.0_wp) * max(lo, hi)) exit
      end do
      dist = 0.5_wp * (lo + hi)
      call peak_sign(f, damping, from_turn, dist, rising, xp, w_peak, stat)
   end subroutine law_peak

   !> The sign of G = m f'(x) x' - b f(x)^2 (law_peak) at the point of the compression
   !> the distance dist in l from the turning point (from_turn) or from the impact;
   !> `rising` is G > 0. Also x and w = x'/V there.
   pure subroutine peak_sign(f, damping, from_turn, dist, rising, x, w, stat)
      type(law_integrand), intent(in) :: f
      real(wp), intent(in) :: damping
      logical, intent(in) :: from_turn
      real(wp), intent(in) :: dist
      logical, intent(out) :: rising
      real(wp), intent(out) :: x, w
      integer, intent(out) :: stat
      type(dd_real) :: l, other
      real(wp) :: force, slope, share, slope_lo, slope_hi, force_lo, force_hi
      logical :: surely_rising, surely_falling

      stat = hcimpact_ok
      if (from_turn) then
         l = dd(dist)
         other = f%tr%l_end(compression_phase) - dist
         share = energy_fraction(f%tr, compression_phase, dist, other%hi)
      else
         l = f%tr%l_end(compression_phase) - dist
         share = energy_fraction(f%tr, compression_phase, l%hi, dist)
      end if
      x = inverse_potential(f, f%energy_unit * share)
      w = scaled_velocity(f%tr, l)
      force = f%law%force(x)
      slope = f%law%force_derivative(x)
      rising = .false.
      if (ieee_is_nan(force) .or. ieee_is_nan(slope)) then
         stat = hcimpact_err_elastic_law
         return
      end if
      if (.not. (force >= 0.0_wp .and. force <= huge(1.0_wp) .and. slope >= 0.0_wp)) then
         stat = hcimpact_err_elastic_law
         return
      end if
      if (.not. w > 0.0_wp) then
         ! at the turning point: G = -b f^2 < 0
         rising = .false.
      else if (force >= tiny(1.0_wp) .and. slope >= tiny(1.0_wp) &
            & .and. slope <= huge(1.0_wp)) then
         rising = greater_product([f%mass, f%velocity, slope, w], [damping, force, force])
      else
         ! f or f' outside the normal range (0 or subnormal: below tiny, with few digits
         ! left; infinite: above huge): the sign from bounds on them when they decide
         ! it, else G is not known
         slope_lo = slope
         slope_hi = slope
         if (slope < tiny(1.0_wp)) then
            slope_lo = 0.0_wp
            slope_hi = tiny(1.0_wp)
         else if (slope > huge(1.0_wp)) then
            slope_lo = huge(1.0_wp)
         end if
         force_lo = force
         force_hi = force
         if (force < tiny(1.0_wp)) then
            force_lo = 0.0_wp
            force_hi = tiny(1.0_wp)
         end if
         ! (the products only of positive finite factors: Fortran's .and. may evaluate
         ! both operands)
         surely_rising = .false.
         surely_falling = .false.
         if (slope_lo > 0.0_wp) surely_rising = greater_product([f%mass, f%velocity, &
            & slope_lo, w], [damping, force_hi, force_hi])
         if (.not. surely_rising .and. force_lo > 0.0_wp .and. slope_hi <= huge(1.0_wp)) then
            surely_falling = greater_product([damping, force_lo, force_lo], &
               & [f%mass, f%velocity, slope_hi, w])
         end if
         if (surely_rising) then
            rising = .true.
         else if (surely_falling) then
            rising = .false.
         else
            stat = hcimpact_err_domain
         end if
      end if
   end subroutine peak_sign

   !> Whether the product of the positive finite doubles a(:) exceeds that of b(:),
   !> without forming either: the significands in [1/2, 1) are multiplied (no overflow
   !> or underflow for up to a few factors), the binary exponents added, and the two
   !> compared with the difference of the exponents moved onto one of them (exact).
   !> As accurate as the products of the significands (a rounding each), where
   !> logarithms would add the roundings of ln of each factor, about eps |ln|.
   pure function greater_product(a, b) result(greater)
      real(wp), intent(in) :: a(:), b(:)
      logical :: greater
      real(wp) :: fa, fb
      integer :: ea, eb
      call split_product(a, fa, ea)
      call split_product(b, fb, eb)
      ! fa, fb in [2**-size, 1): exponents apart by more than that decide alone
      if (ea - eb > size(b)) then
         greater = .true.
      else if (eb - ea > size(a)) then
         greater = .false.
      else
         greater = scale(fa, ea - eb) > fb
      end if
   end function greater_product

   !> The product of positive finite doubles as significand * 2**exponent: the product
   !> of their significands (each in [1/2, 1)) and the sum of their binary exponents
   pure subroutine split_product(factors, significand, binary_exponent)
      real(wp), intent(in) :: factors(:)
      real(wp), intent(out) :: significand
      integer, intent(out) :: binary_exponent
      integer :: i
      significand = 1.0_wp
      binary_exponent = 0
      do i = 1, size(factors)
         significand = significand * fraction(factors(i))
         binary_exponent = binary_exponent + exponent(factors(i))
      end do
   end subroutine split_product

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
      stat = check_parameters(mass=mass, damping=damping, velocity=velocity)
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

end module hcimpact_law_impact
