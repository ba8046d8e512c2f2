! SPDX-License-Identifier: Apache-2.0
!> The impact as a first-order system for an ODE solver, in scaled variables: the
!> right-hand side, its Jacobian, the event functions and the stiffness measure.
!>
!> Nothing here knows about SUNDIALS: the CVODE callbacks (hcimpact_cvode_solver) unpack
!> their vectors and call these procedures, which are pure.
!>
!> Scaling (MODEL.md). With a length L, the time T = L/V and s = x/L, tau = t/T,
!> sigma = x'/V = ds/dtau, the equation m x'' = -f(x)(1 + b x') + g(t, x, x') reads
!>
!>     s' = sigma,
!>     sigma' = p [ -f(L s)(1 + beta sigma) + g(T tau, L s, V sigma) ],   p = L/(m V^2),
!>
!> with beta = b V, s(0) = 0, sigma(0) = 1. For the power law f = c x^n and
!> L = X = [(n+1) m V^2/(2c)]^(1/(n+1)) this is s'' = -((n+1)/2) s^n (1 + beta s'):
!> it depends on (n, beta) alone, so an absolute tolerance means the same thing for a
!> bead and for a hammer.
!>
!> The contact force and its derivatives are those of the contact-force element
!> (hcimpact_force_element): for the power law the element with the stiffness (n+1)/2
!> and the damping beta in the scaled variables, for a user's law the element of the
!> law in SI units. Without an external force the element's clamp is off (the exact
!> motion never reaches 1 + b x' = 0, and the unclamped force attracts a numerical
!> solution back to that line); with one it is on.
!>
!> The state is never modified here. The elastic force is evaluated at a clamped copy
!> max(s, 0) (a step may overshoot the end of contact slightly); after the end of
!> contact the body flies freely. A state for which a value
!> would overflow is reported as a recoverable failure (the solver then retries with a
!> smaller step) instead of producing Inf or NaN.
!>
!> Events (the solver locates their zeros, each crossed downwards):
!>   1. sigma = 0: maximum compression;
!>   2. dF/dtau = 0 with F = f(x)(1 + b x'): a peak of the contact force. For the power
!>      law dF/dtau = s^(n-1) (1 + beta sigma) [n sigma - ((n+1)/2) beta s^(n+1)] and the
!>      bracket alone is used (the other factors are positive during contact; MODEL.md:
!>      the peak is where n m V = b c x^(n+1)); for a user's law likewise
!>      f'(L s) L sigma - p beta f(L s)^2 without the factor 1 + beta sigma (see
!>      system_events for why), and the full derivative with an external force;
!>   3. s = 0 (the state itself, not the clamped copy): the end of contact.
module hcimpact_cvode_system
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
   use hcimpact_kinds, only : wp, finite_value
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_cvode_report, only : solver_report
   use hcimpact_elastic, only : elastic_law
   use hcimpact_force_element, only : contact_force_type, contact_force
   implicit none
   private

   public :: external_force, external_force_value
   public :: impact_system, power_system, law_system
   public :: system_rhs, system_jacobian, system_events, system_force
   public :: largest_eigenvalue, scaled_energy, guarded_product, guarded_quotient
   public :: finite_value
   public :: rhs_ok, rhs_recoverable, rhs_law_failure
   public :: n_events, event_max_compression, event_peak_force, event_end_of_contact

   !> Number of event functions
   integer, parameter :: n_events = 3
   !> Index of the event x' = 0 (maximum compression)
   integer, parameter :: event_max_compression = 1
   !> Index of the event dF/dt = 0 (peak of the contact force)
   integer, parameter :: event_peak_force = 2
   !> Index of the event x = 0, downwards (end of contact)
   integer, parameter :: event_end_of_contact = 3

   !> Kind of system: the power law, evaluated in its own scaled form
   integer, parameter :: power_system = 1
   !> Kind of system: a user's elastic law and an optional external force
   integer, parameter :: law_system = 2

   !> Status of an evaluation: success
   integer, parameter :: rhs_ok = 0
   !> Status of an evaluation: the state is too far out for finite values (retry)
   integer, parameter :: rhs_recoverable = 1
   !> Status of an evaluation: the user's law or force returned a non-finite value
   integer, parameter :: rhs_law_failure = 2

   !> Natural log of the largest value we let a product reach (a margin below huge)
   real(wp), parameter :: log_limit = 700.0_wp

   !> An external force g(t, x, x') in N acting on the body besides the contact force:
   !> m x'' = -f(x)(1 + b x') + g(t, x, x'). Extend it and implement `force`; override
   !> `derivatives` to give the solver dg/dx and dg/dx' (the default returns zeros,
   !> which only slows the Newton iteration down when g depends on the state).
   !> The procedures must be pure; parameters are components of the extending type.
   type, abstract :: external_force
   contains
      !> The force g(t, x, v) in N (positive: pushes into the obstacle)
      procedure(external_force_value), deferred :: force
      !> Its partial derivatives dg/dx (N/m) and dg/dv (N s/m)
      procedure :: derivatives => external_force_no_derivatives
   end type external_force

   abstract interface
      !> g(t, x, v): the external force at the time t (s), deformation x (m) and
      !> velocity v (m/s), in N.
      pure function external_force_value(self, t, x, v) result(g)
         import :: external_force, wp
         !> The force and its parameters
         class(external_force), intent(in) :: self
         !> Time since the start of contact in s
         real(wp), intent(in) :: t
         !> Deformation in m (negative after the end of contact)
         real(wp), intent(in) :: x
         !> Velocity x' in m/s
         real(wp), intent(in) :: v
         !> Force in N
         real(wp) :: g
      end function external_force_value
   end interface

   !> Everything the solver callbacks need, reached through the solver's user data.
   type :: impact_system
      !> power_system or law_system
      integer :: kind = power_system
      !> beta = b V (dimensionless damping)
      real(wp) :: beta = 0.0_wp
      !> Power law: exponent n and (n+1)/2
      real(wp) :: n = 1.5_wp, half_np1 = 1.25_wp
      !> Whether the contact force is clamped at 0 where 1 + b x' < 0 (the contact-force
      !> element's clamp). Off without an external force: the exact motion of one impact
      !> never reaches 1 + b x' = 0, and the unclamped force keeps a numerical solution
      !> that overshoots the line attracted to it (doc/contact-force.md); on with an
      !> external force, which may pull the body away faster than 1/b.
      logical :: clamp = .false.
      !> User law and external force (law_system only)
      class(elastic_law), allocatable :: law
      class(external_force), allocatable :: external
      !> Mass (kg), damping (s/m), approach speed (m/s)
      real(wp) :: mass = 0.0_wp, damping = 0.0_wp, velocity = 0.0_wp
      !> Length L (m) and time T = L/V (s) of the scaled variables
      real(wp) :: length = 0.0_wp, time = 0.0_wp
      !> p = L/(m V^2) in 1/N (law_system)
      real(wp) :: accel = 0.0_wp
      !> Power law: newtons per unit of s^n (1 + beta sigma): ((n+1)/2) m V^2 / X
      real(wp) :: force_unit = 0.0_wp
      !> The caller's halting modes for overflow, invalid and division by zero: the
      !> driver turns halting off while CVODE runs, the callbacks turn it back on
      logical :: halting(3) = .false.
      !> Set by the callbacks: the last evaluation failure of the user's procedures
      logical :: law_failed = .false.
      !> Set by the solver's error handler: its last message and code
      type(solver_report) :: report
   end type impact_system

contains

   !> Default derivatives of an external force: none known (zeros).
   pure subroutine external_force_no_derivatives(self, t, x, v, dg_dx, dg_dv)
      !> The force
      class(external_force), intent(in) :: self
      !> Time (s), deformation (m), velocity (m/s)
      real(wp), intent(in) :: t, x, v
      !> dg/dx in N/m and dg/dv in N s/m
      real(wp), intent(out) :: dg_dx, dg_dv
      dg_dx = 0.0_wp
      dg_dv = 0.0_wp
   end subroutine external_force_no_derivatives

   !> a/b for finite a and b /= 0, or +-huge when the quotient would overflow.
   elemental function guarded_quotient(a, b) result(c)
      !> Numerator and denominator (finite, b /= 0)
      real(wp), intent(in) :: a, b
      !> Quotient
      real(wp) :: c
      if (a == 0.0_wp) then
         c = 0.0_wp
      else if (exponent(a) - exponent(b) >= maxexponent(a) - 1) then
         c = sign(huge(a), a) * sign(1.0_wp, b)
      else
         c = a / b
      end if
   end function guarded_quotient

   !> a*b, or +-huge when the product would overflow (exponents add up too far); an
   !> infinite factor counts as +-huge, a NaN propagates (quietly).
   elemental function guarded_product(a, b) result(c)
      !> Factors
      real(wp), intent(in) :: a, b
      !> Product
      real(wp) :: c
      if (ieee_is_nan(a) .or. ieee_is_nan(b)) then
         c = a + b
      else if (.not. (ieee_is_finite(a) .and. ieee_is_finite(b))) then
         ! (exponent() of an infinity is huge(0): the sum below would overflow)
         if (a == 0.0_wp .or. b == 0.0_wp) then
            c = 0.0_wp
         else
            c = sign(huge(a), a) * sign(1.0_wp, b)
         end if
      else if (a == 0.0_wp .or. b == 0.0_wp) then
         c = 0.0_wp
      else if (exponent(a) + exponent(b) >= maxexponent(a) - 1) then
         c = sign(huge(a), a) * sign(1.0_wp, b)
      else
         c = a * b
      end if
   end function guarded_product

   !> s^e for s >= 0 with ln(result) checked against log_limit; ok false if it is not.
   elemental subroutine guarded_power(s, e, y, ok)
      real(wp), intent(in) :: s, e
      real(wp), intent(out) :: y
      logical, intent(out) :: ok
      ok = .true.
      if (s == 0.0_wp) then
         if (e > 0.0_wp) then
            y = 0.0_wp
         else if (e == 0.0_wp) then
            y = 1.0_wp
         else
            y = huge(1.0_wp)
            ok = .false.
         end if
      else if (e * log(s) > log_limit) then
         y = huge(1.0_wp)
         ok = .false.
      else
         y = s**e
      end if
   end subroutine guarded_power

   !> Right-hand side (s', sigma') of the scaled system at the time tau.
   pure subroutine system_rhs(sys, tau, y, dy, stat)
      !> The system
      type(impact_system), intent(in) :: sys
      !> Scaled time
      real(wp), intent(in) :: tau
      !> State (s, sigma)
      real(wp), intent(in) :: y(2)
      !> Derivative
      real(wp), intent(out) :: dy(2)
      !> rhs_ok, rhs_recoverable or rhs_law_failure
      integer, intent(out) :: stat
      real(wp) :: s, sigma, w, g
      type(contact_force_type) :: element
      integer :: fstat

      stat = rhs_ok
      w = 0.0_wp
      dy(1) = y(1)
      dy(2) = 0.0_wp
      if (.not. (ieee_is_finite(y(1)) .and. ieee_is_finite(y(2)))) then
         stat = rhs_recoverable
         return
      end if
      s = max(y(1), 0.0_wp)
      sigma = y(2)
      dy(1) = sigma

      select case (sys%kind)
      case (power_system)
         ! the contact force of the scaled problem: stiffness (n+1)/2, damping beta
         call contact_force(sys%half_np1, sys%n, sys%beta, s, sigma, element, &
            & clamp=sys%clamp)
         dy(2) = -element%force
         if (.not. dy(2) > -huge(w)) stat = rhs_recoverable
      case default
         call contact_force(sys%law, sys%damping, sys%length * s, sys%velocity * sigma, &
            & element, fstat, sys%clamp)
         g = 0.0_wp
         if (allocated(sys%external)) then
            g = sys%external%force(sys%time * tau, sys%length * y(1), sys%velocity * sigma)
         end if
         if (fstat /= hcimpact_ok .or. .not. ieee_is_finite(g)) then
            stat = rhs_law_failure
            return
         end if
         dy(2) = guarded_product(sys%accel, g - element%force)
         if (.not. (abs(element%force) < huge(w) .and. abs(dy(2)) < huge(w))) &
            & stat = rhs_recoverable
      end select
   end subroutine system_rhs

   !> Jacobian d(s', sigma')/d(s, sigma) of the scaled system (column-major 2x2).
   !> Entries that would overflow are capped at +-huge: the solver uses the Jacobian
   !> only in its Newton iteration, where an approximation costs iterations, not
   !> accuracy.
   pure subroutine system_jacobian(sys, tau, y, jac, stat)
      !> The system
      type(impact_system), intent(in) :: sys
      !> Scaled time
      real(wp), intent(in) :: tau
      !> State (s, sigma)
      real(wp), intent(in) :: y(2)
      !> jac(i, j) = d(dy_i)/d(y_j)
      real(wp), intent(out) :: jac(2, 2)
      !> rhs_ok, rhs_recoverable or rhs_law_failure
      integer, intent(out) :: stat
      real(wp) :: s, sigma, gx, gv
      type(contact_force_type) :: element
      integer :: fstat

      stat = rhs_ok
      jac = 0.0_wp
      jac(1, 2) = 1.0_wp
      if (.not. (ieee_is_finite(y(1)) .and. ieee_is_finite(y(2)))) then
         stat = rhs_recoverable
         return
      end if
      s = max(y(1), 0.0_wp)
      sigma = y(2)

      ! the derivatives of the contact force; at s = 0 those from the right (the
      ! element has none at x <= 0: there is no contact yet), at the smallest normal s
      s = max(s, tiny(1.0_wp))
      select case (sys%kind)
      case (power_system)
         call contact_force(sys%half_np1, sys%n, sys%beta, s, sigma, element, &
            & clamp=sys%clamp)
         jac(2, 1) = -max(-huge(1.0_wp), min(element%dforce_dx, huge(1.0_wp)))
         jac(2, 2) = -min(element%dforce_dv, huge(1.0_wp))
      case default
         call contact_force(sys%law, sys%damping, sys%length * s, sys%velocity * sigma, &
            & element, fstat, sys%clamp)
         gx = 0.0_wp
         gv = 0.0_wp
         if (allocated(sys%external)) then
            call sys%external%derivatives(sys%time * tau, sys%length * y(1), &
               & sys%velocity * sigma, gx, gv)
         end if
         if (.not. (fstat == hcimpact_ok .and. ieee_is_finite(gx) .and. ieee_is_finite(gv))) then
            stat = rhs_law_failure
            return
         end if
         ! p L [ g_x - dF/dx ]  and  p V [ g_v - dF/dv ]
         jac(2, 1) = guarded_product(sys%accel * sys%length, gx - element%dforce_dx)
         jac(2, 2) = guarded_product(sys%accel, guarded_product(sys%velocity, &
            & gv - element%dforce_dv))
      end select
   end subroutine system_jacobian

   !> The event functions (see the module header) at the state y.
   pure subroutine system_events(sys, tau, y, events, stat)
      !> The system
      type(impact_system), intent(in) :: sys
      !> Scaled time
      real(wp), intent(in) :: tau
      !> State (s, sigma)
      real(wp), intent(in) :: y(2)
      !> The three event functions
      real(wp), intent(out) :: events(n_events)
      !> rhs_ok, rhs_recoverable or rhs_law_failure
      integer, intent(out) :: stat
      real(wp) :: s, sigma, snp1, f, df, w, a, g
      logical :: ok

      stat = rhs_ok
      events = 0.0_wp
      if (.not. (ieee_is_finite(y(1)) .and. ieee_is_finite(y(2)))) then
         stat = rhs_recoverable
         return
      end if
      s = max(y(1), 0.0_wp)
      sigma = y(2)
      events(event_max_compression) = sigma
      events(event_end_of_contact) = y(1)

      select case (sys%kind)
      case (power_system)
         call guarded_power(s, sys%n + 1.0_wp, snp1, ok)
         events(event_peak_force) = guarded_product(sys%n, sigma) &
            & - guarded_product(sys%half_np1 * sys%beta, snp1)
      case default
         ! Out of contact dF/dtau vanishes identically, which CVODE's root finding
         ! rejects (CV_ILL_INPUT, "root found at and very near t") if it happens at a
         ! root: there the function is -1 ("the force does not grow").
         if (.not. y(1) > 0.0_wp) then
            events(event_peak_force) = -1.0_wp
            return
         end if
         ! With sigma' = p (-f w + g), w = 1 + beta sigma:
         !   dF/dtau = f' L sigma w + f beta sigma' = w (f' L sigma - p beta f^2) + p beta f g.
         ! The function is p times that, without the factor w > 0 when there is no
         ! external force: in the creep of large beta, w is below the rounding of
         ! 1 + beta sigma and computes as 0, and a function that vanishes on an
         ! interval is what CVODE's root finding rejects.
         f = sys%law%force(sys%length * s)
         df = sys%law%force_derivative(sys%length * s)
         if (.not. (ieee_is_finite(f) .and. ieee_is_finite(df))) then
            stat = rhs_law_failure
            return
         end if
         a = guarded_product(guarded_product(df, sys%length * sigma), sys%accel) &
            & - guarded_product(guarded_product(sys%accel * sys%beta, f), &
            & guarded_product(sys%accel, f))
         if (allocated(sys%external)) then
            g = sys%external%force(sys%time * tau, sys%length * y(1), sys%velocity * sigma)
            if (.not. ieee_is_finite(g)) then
               stat = rhs_law_failure
               return
            end if
            w = 1.0_wp + guarded_product(sys%beta, sigma)
            g = guarded_product(a, w) + guarded_product(guarded_product(sys%accel * sys%beta, &
               & f), guarded_product(sys%accel, g))
            ! w and g both 0 (creep without force): the sign is that of a
            if (g /= 0.0_wp) a = g
         end if
         events(event_peak_force) = a
      end select
   end subroutine system_events

   !> Contact force F = f(x) max(0, 1 + b x') in N at the scaled state y (the contact-force
   !> element); +huge if it overflows or the law fails (ok false then).
   pure subroutine system_force(sys, y, force, ok)
      !> The system
      type(impact_system), intent(in) :: sys
      !> State (s, sigma)
      real(wp), intent(in) :: y(2)
      !> Force in N
      real(wp), intent(out) :: force
      !> Whether the force is finite
      logical, intent(out) :: ok
      real(wp) :: s
      type(contact_force_type) :: element

      ok = .true.
      s = max(y(1), 0.0_wp)
      select case (sys%kind)
      case (power_system)
         ! force_unit s^n (1 + beta sigma) = the element with the stiffness force_unit
         call contact_force(sys%force_unit, sys%n, sys%beta, s, y(2), element, &
            & clamp=sys%clamp)
      case default
         call contact_force(sys%law, sys%damping, sys%length * s, sys%velocity * y(2), &
            & element, clamp=sys%clamp)
      end select
      force = element%force
      ok = ieee_is_finite(force) .and. abs(force) < huge(force)
      if (.not. ok) force = huge(1.0_wp)
   end subroutine system_force

   !> Largest modulus of the eigenvalues of [[0, 1], [j21, j22]], without overflow:
   !> lambda^2 - j22 lambda - j21 = 0.
   pure function largest_eigenvalue(jac) result(lambda)
      !> The Jacobian of the scaled system
      real(wp), intent(in) :: jac(2, 2)
      !> max |lambda|
      real(wp) :: lambda
      real(wp) :: p, q, scale, pn, qn, d

      p = 0.5_wp * jac(2, 2)
      q = jac(2, 1)
      scale = max(abs(p), sqrt(abs(q)))
      if (scale == 0.0_wp .or. .not. ieee_is_finite(scale)) then
         lambda = scale
         return
      end if
      pn = p / scale
      qn = (q / scale) / scale
      d = pn * pn + qn
      if (d >= 0.0_wp) then
         lambda = scale * (abs(pn) + sqrt(d))
      else
         lambda = scale * sqrt(-qn)
      end if
   end function largest_eigenvalue

   !> H(beta) = h(beta)/beta^2 = (beta - ln(1 + beta))/beta^2, so that the maximum
   !> compression of the scaled power-law problem is (2 H)^(1/(n+1)) (MODEL.md);
   !> 1/2 at beta = 0.
   elemental function scaled_energy(beta) result(h)
      !> beta = b V >= 0
      real(wp), intent(in) :: beta
      !> H(beta)
      real(wp) :: h
      real(wp) :: x
      integer :: i
      if (beta < 0.05_wp) then
         ! sum_{j>=2} (-1)^j beta^(j-2)/j, to below an ulp for beta < 0.05
         h = 0.0_wp
         x = 1.0_wp
         do i = 2, 16
            h = h + x / real(i, wp)
            x = -x * beta
         end do
      else
         h = ((beta - log(1.0_wp + beta)) / beta) / beta
      end if
   end function scaled_energy

end module hcimpact_cvode_system
