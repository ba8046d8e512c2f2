! SPDX-License-Identifier: Apache-2.0
!> One impact with an elastic law supplied by the caller (hcimpact_elastic):
!> m x'' = -f(x)(1 + b x'). Its outcome (`impact_law`) and time law (`time_law_law`).
!>
!> The trajectory (restitution, the ends of the phases) is that of the power law; x
!> along it comes from inverting the law's potential, and the times are quadratures of
!> m V/f(x) in the log-velocity variable (hcimpact_trajectory).
module hcimpact_law_impact
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp, ik, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_domain, &
      & hcimpact_err_size, hcimpact_err_elastic_law
   use hcimpact_libm, only : log1p
   use hcimpact_double_double, only : dd_real, dd, two_sum, operator(+), &
      & operator(-), operator(*), operator(/), &
      & dd_exp
   use hcimpact_lambertw, only : lambert_wm1p1
   use hcimpact_elastic, only : elastic_law
   use hcimpact_contact, only : outcome_type, check_parameters, reject_unrepresentable, &
      & max_beta
   use hcimpact_trajectory, only : trajectory_type, new_trajectory, phase_integrand, &
      & compression_phase, restitution_phase, turn_q, end_r, phase_duration, &
      & duration_from_turn, duration_from_end, invert_from_turn, invert_from_end, &
      & scaled_velocity, phase_length, damping_product
   implicit none
   private

   public :: impact_law, time_law_law

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
      integer :: it, alloc_stat

      stat = hcimpact_ok
      if (log(damping + tiny(1.0_wp)) + log(velocity) > log(max_beta)) then
         stat = hcimpact_err_domain
         return
      end if
      allocate(f%law, source=law, stat=alloc_stat)
      if (alloc_stat /= 0) then
         ! out of memory for the copy of the law
         stat = hcimpact_err_size
         return
      end if
      f%tr = new_trajectory(damping_product(damping, velocity))
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
      stat = check_parameters(mass=mass, damping=damping, velocity=velocity)
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
