! SPDX-License-Identifier: Apache-2.0
!> A system of bodies on a line: what the caller describes (`chain_type`, its contact
!> laws and walls), how it is computed (`chain_options`), and what comes back
!> (`chain_result`, with the list of contacts); the one validator of such a system.
!>
!> Conventions (doc/chains.md). Bodies are numbered 1 .. n from left to right;
!> velocities are positive to the right. The bodies are points on the line: the
!> position q_i of body i is such that the gap between bodies i and i+1 is
!> q_(i+1) - q_i (their surfaces touch at gap 0, and overlap by the deformation
!> x = q_i - q_(i+1) > 0). Initially q_1 = 0 and q_(i+1) = q_i + gap(i); add the
!> bodies' sizes to q to get centres. A wall on the left stands at q_1(0) - gap_left,
!> one on the right at q_n(0) + gap_right. `gravity` is a constant acceleration of
!> every body along the line (m/s^2, negative: towards the left).
!>
!> Contact pairs are numbered 0 .. n: pair i (1 <= i < n) is bodies i and i+1, pair
!> 0 the left wall and body 1, pair n body n and the right wall.
module hcimpact_chain_types
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_positive_inf
   use hcimpact_kinds, only : wp, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_domain, hcimpact_err_size, hcimpact_err_no_convergence
   use hcimpact_contact, only : check_parameters, max_beta
   use hcimpact_power_force, only : product_of, signed_product
   use hcimpact_libm, only : expm1, log1p
   implicit none
   private

   public :: contact_law, chain_type, chain_options, contact_record, chain_result
   public :: chain_counters, chain_switch, chain_monitor, monitor_interval
   public :: check_chain, check_rtol, sum_within_range, least_contacts_to_rest
   public :: kinetic_energy, energy_balance_error, momentum_balance_error
   public :: sum_in_range, product_in_range, gravity_impulse, momentum, not_below_zero
   public :: beyond_max_beta, say_beyond_max_beta
   public :: method_auto, method_exact, method_integrated
   public :: integrator_bdf, integrator_adams
   public :: by_closed_forms, by_integration, by_both
   public :: max_message, no_memory_tail

   !> The method that decides per contact (closed forms where contacts are isolated,
   !> CVODE for clusters); the default
   integer, parameter :: method_auto = 0
   !> The method of closed forms only (a cluster is an error, hcimpact_err_domain)
   integer, parameter :: method_exact = 1
   !> The method that integrates the whole system with CVODE from the start
   integer, parameter :: method_integrated = 2

   !> CVODE's linear multistep method: BDF (default) or Adams
   integer, parameter :: integrator_bdf = 1, integrator_adams = 2

   !> How a contact was computed: by the closed forms of one impact, or by integration
   integer, parameter :: by_closed_forms = 1, by_integration = 2, by_both = 3

   !> Longest message of a result
   integer, parameter :: max_message = 256
   !> The end of the message of a system the memory cannot hold (status
   !> hcimpact_err_out_of_memory), after "out of memory (" and what did not fit
   character(len=*), parameter :: no_memory_tail = &
      & "): the system is too large for the memory available"

   !> Passes of the run's loop (each one step of a cluster, one event of the closed forms
   !> or a switch of method, or the samples due) between two calls of a monitor's `poll`
   integer, parameter :: monitor_interval = 64

   !> A caller's watch over a long run (`chain_options%monitor`): its `poll` is called
   !> from the run's loop every `monitor_interval` passes with the time reached and the
   !> work done, and a run whose poll returns true stops there with
   !> hcimpact_err_no_convergence (a bound the caller set, as max_steps is). Extend it
   !> with the data the poll needs (a progress display, a deadline, a flag another
   !> thread sets); the run keeps no other reference to it.
   type, abstract :: chain_monitor
   contains
      procedure(monitor_poll), deferred :: poll
   end type chain_monitor

   abstract interface
      !> True: stop the run now
      logical function monitor_poll(self, time, steps, events)
         import :: chain_monitor, wp, int64
         class(chain_monitor), intent(inout) :: self
         !> The time the run has reached, s
         real(wp), intent(in) :: time
         !> Integration steps so far, and events: the starts and ends of contacts the
         !> closed forms compute and the switches of method (what max_events bounds;
         !> the contacts inside an integrated cluster are not events)
         integer(int64), intent(in) :: steps, events
      end function monitor_poll
   end interface

   !> The contact law of one pair: f = c x^n, damping b
   type :: contact_law
      !> Contact constant c in N/m^n, > 0
      real(wp) :: stiffness = 0.0_wp
      !> Exponent n, >= 1e-6 (3/2: Hertz)
      real(wp) :: exponent = 1.5_wp
      !> Damping b in s/m, >= 0
      real(wp) :: damping = 0.0_wp
   end type contact_law

   !> The loosest relative tolerance of a system: a pair pressed no further than rtol
   !> times its scale, from an approach within rtol times the speeds' scale, is taken
   !> for one touching by rounding and not recorded as a contact; beyond 1 % that
   !> would drop real contacts (at rtol 0.5 it dropped every one)
   real(wp), parameter, public :: max_chain_rtol = 1.0e-2_wp

   !> A system of bodies on a line (module header: conventions)
   type :: chain_type
      !> Masses in kg (n >= 1), > 0
      real(wp), allocatable :: mass(:)
      !> Initial velocities in m/s
      real(wp), allocatable :: velocity(:)
      !> Initial gaps between neighbours in m (n - 1 of them), >= 0 (0: touching
      !> without preload)
      real(wp), allocatable :: gap(:)
      !> The law of each neighbouring pair (n - 1)
      type(contact_law), allocatable :: law(:)
      !> Walls: present or not, their laws and their gaps to the end bodies (>= 0)
      logical :: left_wall = .false., right_wall = .false.
      type(contact_law) :: left_law, right_law
      real(wp) :: left_gap = 0.0_wp, right_gap = 0.0_wp
      !> Constant acceleration along the line in m/s^2 (negative: to the left)
      real(wp) :: gravity = 0.0_wp
   end type chain_type

   !> How to compute a system
   type :: chain_options
      !> End time in s; <= 0: until no contact can happen again (all bodies
      !> separating with no wall ahead, or at rest on a wall under gravity)
      real(wp) :: t_end = -1.0_wp
      !> Relative tolerance of the integration (CVODE); the closed forms are exact
      real(wp) :: rtol = 1.0e-10_wp
      !> method_auto, method_exact or method_integrated
      integer :: method = method_auto
      !> integrator_bdf or integrator_adams
      integer :: integrator = integrator_bdf
      !> Largest number of integration steps (all clusters together)
      integer(int64) :: max_steps = 100000000_int64
      !> Largest number of contacts recorded (more are counted, not recorded)
      integer :: max_contacts = 1000000
      !> Largest number of contacts computed before giving up (a bound of the loop,
      !> e.g. for a ball that would bounce forever without gravity in contact)
      integer(int64) :: max_events = 100000000_int64
      !> Times (s) at which to sample positions, velocities and pair forces, in
      !> increasing order (optional)
      real(wp), allocatable :: sample_times(:)
      !> The caller's watch over the run, or none (chain_monitor)
      class(chain_monitor), pointer :: monitor => null()
   end type chain_options

   !> One contact between a pair, from its start to its end
   type :: contact_record
      !> The pair (0: left wall and body 1; n: body n and the right wall)
      integer :: pair = -1
      !> Start and end of the contact in s (end NaN if it has not ended)
      real(wp) :: t_start = nan, t_end = nan
      !> Approach speed at the start and separation speed at the end, m/s (>= 0)
      real(wp) :: approach_speed = nan, separation_speed = nan
      !> Largest force in N and largest deformation in m during the contact
      real(wp) :: peak_force = nan, max_deformation = nan
      !> Energy dissipated in the contact, J
      real(wp) :: dissipated = nan
      !> by_closed_forms, or by_integration (also for part of the contact)
      integer :: method = 0
   end type contact_record

   !> The work done
   type :: chain_counters
      !> Contacts computed by the closed forms
      integer(int64) :: closed_form_contacts = 0
      !> Contacts computed (at least in part) by integration
      integer(int64) :: integrated_contacts = 0
      !> Integration steps, right-hand side evaluations, Jacobians, roots located
      integer(int64) :: steps = 0, rhs_evals = 0, jacobian_evals = 0, roots = 0
      !> Clusters integrated (each from its start until it separates)
      integer(int64) :: clusters = 0
   end type chain_counters

   !> A switch between the two ways of computing (the log of the decisions)
   type :: chain_switch
      !> Time in s
      real(wp) :: time = nan
      !> First and last body of the integrated cluster (0 0 when it dissolved)
      integer :: first = 0, last = 0
      !> Why, e.g. "pair 3 starts while pair 2 is in contact"
      character(len=max_message) :: reason = ""
   end type chain_switch

   !> What `chain_simulate` computes
   type :: chain_result
      !> Time reached (s): t_end, the time after which no contact can happen, or the
      !> time at which the system came to rest
      real(wp) :: time = nan
      !> Positions (m, module header) and velocities (m/s) at that time; for a system
      !> at rest, its rest state (velocities 0): without t_end from the rest time on,
      !> with t_end once it has settled within 100 rtol of it (doc/chains.md)
      real(wp), allocatable :: positions(:), velocities(:)
      !> True when the system came to rest on a wall under gravity (rest_time: when
      !> its energy fell below what any contact needs to open)
      logical :: rested = .false.
      real(wp) :: rest_time = nan
      !> The contacts that ended, in the order they ended (one still in progress at
      !> t_end is not listed); n_contacts counts every contact that ended, also those
      !> beyond options%max_contacts
      type(contact_record), allocatable :: contacts(:)
      integer(int64) :: n_contacts = 0
      !> Samples at options%sample_times: positions and velocities (n x samples),
      !> pair forces (pairs 0 .. n x samples, 0 for a missing wall); NaN at a sample
      !> time after options%t_end
      real(wp), allocatable :: sample_positions(:, :), sample_velocities(:, :)
      real(wp), allocatable :: sample_forces(:, :)
      !> The initial energy (kinetic + gravitational), and the relative error of
      !> kinetic + elastic + gravitational + dissipated against it at the end
      real(wp) :: initial_energy = nan, energy_error = nan
      !> Dissipated energy in J (up to the time reached: contacts in progress included)
      real(wp) :: dissipated = nan
      !> The impulses the walls gave the system up to the time reached (N s, along the
      !> line: the left wall's >= 0, the right wall's <= 0; 0 without the wall),
      !> integrated with the contacts (doc/chains.md, "The momentum balance")
      real(wp) :: wall_impulse(2) = nan
      !> Relative error of the momentum against the initial one plus the outside
      !> impulses, gravity's M g t and the walls', over sum(m |v0|) + |M g t| +
      !> |wall_impulse(1)| + |wall_impulse(2)| (NaN where that sum is beyond the range
      !> of doubles)
      real(wp) :: momentum_error = nan
      !> by_closed_forms when no contact was integrated, by_integration when every
      !> contact was, 3 when both were used
      integer :: method_used = 0
      !> Work done and the decisions taken
      type(chain_counters) :: counters
      type(chain_switch), allocatable :: switches(:)
      !> "success", or what went wrong
      character(len=max_message) :: message = ""
   end type chain_result

contains

   !> Check a system and its options. hcimpact_ok or the status of the first problem,
   !> with a message that names it:
   !> - hcimpact_err_size: no body (n < 1), or arrays of different sizes (velocity n,
   !>   gap and law n - 1), or sample times out of order;
   !> - hcimpact_err_not_finite: a NaN or infinite value;
   !> - hcimpact_err_mass: a mass not positive;
   !> - the statuses of `check_parameters` for a law (stiffness, exponent, damping);
   !> - hcimpact_err_domain: a negative gap (initial overlap), gaps that add up beyond a
   !>   quarter of the range of doubles (masses too), rtol outside (0, 0.01], a
   !>   method or an integrator that does not exist, max_steps, max_events < 1,
   !>   max_contacts < 0, t_end unset for a system that never ends (`never_ends`);
   !> - hcimpact_err_no_convergence: t_end unset for one body that needs more than ten
   !>   times options%max_events contacts to come to rest on a wall
   !>   (`least_contacts_to_rest`), where the run would end with that status after
   !>   max_events of them (checked last).
   pure subroutine check_chain(chain, options, stat, message)
      !> The system
      type(chain_type), intent(in) :: chain
      !> The options
      type(chain_options), intent(in) :: options
      !> Status
      integer, intent(out) :: stat
      !> What is wrong ("success" when nothing is)
      character(len=max_message), intent(out) :: message
      integer :: n, i
      real(wp) :: least

      stat = hcimpact_err_size
      if (.not. allocated(chain%mass)) then
         message = "no masses"
         return
      end if
      n = size(chain%mass)
      if (n < 1) then
         message = "a system needs at least one body"
         return
      end if
      if (.not. allocated(chain%velocity)) then
         message = "no velocities"
         return
      end if
      if (size(chain%velocity) /= n) then
         write(message, '(a, i0, a, i0, a)') "velocities: ", size(chain%velocity), &
            & " given for ", n, " bodies"
         return
      end if
      if (n > 1) then
         if (.not. (allocated(chain%gap) .and. allocated(chain%law))) then
            message = "the gaps and the contact laws between neighbours are missing"
            return
         end if
         if (size(chain%gap) /= n - 1 .or. size(chain%law) /= n - 1) then
            write(message, '(a, i0, a, i0, a, i0, a)') "gaps and laws: ", n - 1, &
               & " needed (one per neighbouring pair), ", size(chain%gap), " and ", &
               & size(chain%law), " given"
            return
         end if
      end if
      stat = hcimpact_err_not_finite
      do i = 1, n
         if (.not. (ieee_is_finite(chain%mass(i)) .and. ieee_is_finite(chain%velocity(i)))) &
            & then
            write(message, '(a, i0, a)') "body ", i, ": mass or velocity NaN or infinite"
            return
         end if
      end do
      if (.not. (ieee_is_finite(chain%gravity) .and. ieee_is_finite(chain%left_gap) .and. &
         & ieee_is_finite(chain%right_gap))) then
         message = "gravity or a wall gap is NaN or infinite"
         return
      end if
      stat = hcimpact_err_mass
      do i = 1, n
         if (.not. chain%mass(i) > 0.0_wp) then
            write(message, '(a, i0, a)') "body ", i, ": mass must be positive"
            return
         end if
      end do
      ! the result reports the energies and the momentum: they must be doubles; and the
      ! engine forms sums of masses (a pair's, for its effective mass, a stack's)
      stat = hcimpact_err_domain
      if (.not. sum_within_range(chain%mass)) then
         message = "the masses add up beyond a quarter of the range of doubles"
         return
      end if
      if (.not. within_range(chain%mass, chain%velocity)) then
         message = "the initial kinetic energy or momentum is beyond the range of doubles"
         return
      end if
      do i = 1, n - 1
         stat = hcimpact_err_not_finite
         if (.not. ieee_is_finite(chain%gap(i))) then
            write(message, '(a, i0, a)') "gap ", i, " is NaN or infinite"
            return
         end if
         stat = hcimpact_err_domain
         if (chain%gap(i) < 0.0_wp) then
            write(message, '(a, i0, a)') "gap ", i, &
               & " is negative (bodies may touch, gap 0, but not overlap at the start)"
            return
         end if
         stat = law_status(chain%law(i))
         if (stat /= hcimpact_ok) then
            write(message, '(a, i0, a)') "the law of pair ", i, &
               & " (stiffness > 0, exponent >= 1e-6, damping >= 0, all finite)"
            return
         end if
      end do
      if (chain%left_wall) then
         stat = law_status(chain%left_law)
         if (stat /= hcimpact_ok) then
            message = "the law of the left wall (stiffness > 0, exponent >= 1e-6, damping >= 0)"
            return
         end if
         stat = hcimpact_err_domain
         if (chain%left_gap < 0.0_wp) then
            message = "the left wall's gap is negative (no overlap at the start)"
            return
         end if
      end if
      if (chain%right_wall) then
         stat = law_status(chain%right_law)
         if (stat /= hcimpact_ok) then
            message = "the law of the right wall (stiffness > 0, exponent >= 1e-6, damping >= 0)"
            return
         end if
         stat = hcimpact_err_domain
         if (chain%right_gap < 0.0_wp) then
            message = "the right wall's gap is negative (no overlap at the start)"
            return
         end if
      end if
      stat = hcimpact_err_domain
      if (.not. extent_within_range(chain)) then
         message = "the gaps (with the walls') add up beyond the range of doubles: the " &
            & // "positions and the distance between the ends must be doubles"
         return
      end if
      stat = hcimpact_err_not_finite
      if (.not. (ieee_is_finite(options%t_end) .and. ieee_is_finite(options%rtol))) then
         message = "t_end or rtol is NaN or infinite"
         return
      end if
      call check_rtol(options%rtol, stat, message)
      if (stat /= hcimpact_ok) return
      stat = hcimpact_err_domain
      if (options%method < method_auto .or. options%method > method_integrated) then
         message = "method must be auto, exact or integrated"
         return
      end if
      if (options%integrator /= integrator_bdf .and. options%integrator /= integrator_adams) &
         & then
         message = "the integrator must be BDF or Adams"
         return
      end if
      if (options%max_steps < 1 .or. options%max_events < 1 .or. options%max_contacts < 0) &
         & then
         message = "max_steps and max_events must be positive, max_contacts not negative"
         return
      end if
      if (.not. options%t_end > 0.0_wp .and. never_ends(chain)) then
         message = "t_end is unset, but this system never ends: bodies between two walls " &
            & // "without gravity keep colliding, and an undamped system falling onto a " &
            & // "wall keeps bouncing (give t_end)"
         return
      end if
      if (allocated(options%sample_times)) then
         stat = hcimpact_err_not_finite
         if (.not. all(ieee_is_finite(options%sample_times))) then
            message = "a sample time is NaN or infinite"
            return
         end if
         stat = hcimpact_err_size
         do i = 2, size(options%sample_times)
            if (.not. options%sample_times(i) >= options%sample_times(i - 1)) then
               message = "the sample times must not decrease"
               return
            end if
         end do
         stat = hcimpact_err_domain
         if (size(options%sample_times) > 0) then
            if (options%sample_times(1) < 0.0_wp) then
               message = "the sample times must not be negative"
               return
            end if
         end if
      end if
      if (.not. options%t_end > 0.0_wp) then
         ! (ten times max_events: the bound is of the exact motion, and a run whose
         ! integration loses more energy than the damping rests in fewer contacts;
         ! 2 more for a contact in progress at the start, which is no event)
         least = least_contacts_to_rest(chain)
         if (least > 10.00001_wp * real(options%max_events, wp) + 2.0_wp) then
            stat = hcimpact_err_no_convergence
            write(message, '(a, es9.2e3, a, i0, a)') "t_end is unset, but the body needs at " &
               & // "least ", least, " contacts to come to rest on the wall, over ten times " &
               & // "options%max_events = ", options%max_events, " (give t_end, or a " &
               & // "larger max_events)"
            return
         end if
      end if
      stat = hcimpact_ok
      message = "success"
   end subroutine check_chain

   !> Check a relative tolerance of a system (`chain_options`%rtol): the one rule of
   !> its domain, (0, max_chain_rtol], for check_chain and for the interfaces that name
   !> the argument at fault (HCCHN). hcimpact_ok, hcimpact_err_not_finite or
   !> hcimpact_err_domain, with a message ("success" when nothing is wrong).
   pure subroutine check_rtol(rtol, stat, message)
      !> Relative tolerance
      real(wp), intent(in) :: rtol
      !> Status
      integer, intent(out) :: stat
      !> What is wrong
      character(len=*), intent(out) :: message
      stat = hcimpact_err_not_finite
      if (.not. ieee_is_finite(rtol)) then
         message = "rtol is NaN or infinite"
         return
      end if
      stat = hcimpact_err_domain
      if (.not. (rtol > 0.0_wp .and. rtol <= max_chain_rtol)) then
         message = "rtol must lie in (0, 0.01]"
         return
      end if
      stat = hcimpact_ok
      message = "success"
   end subroutine check_rtol

   !> Whether no end time would ever be reached by running "until no contact can happen
   !> again" (a valid chain): between two walls without gravity a body in motion hits
   !> them for ever (damping slows the bodies but never stops them), and under gravity
   !> towards a wall with every contact undamped the energy stays and the bodies bounce
   !> or oscillate for ever (even released touching at rest), whatever the damping of
   !> a wall on the other side (reached or not). Left to the limits on
   !> steps and contacts, such runs took minutes to hours to fail.
   pure logical function never_ends(chain)
      type(chain_type), intent(in) :: chain
      logical :: undamped
      never_ends = .false.
      if (chain%gravity == 0.0_wp) then
         never_ends = chain%left_wall .and. chain%right_wall .and. &
            & any(chain%velocity /= 0.0_wp)
         return
      end if
      ! (a single body's laws may be missing, or of any size: none is read; it was, and
      ! a body released above a floor with no law array given crashed the Debug build)
      undamped = .true.
      if (size(chain%mass) > 1) undamped = all(chain%law%damping == 0.0_wp)
      ! (a damped wall on the other side does not end it: gravity pulls the bodies
      ! away from it, and once they no longer reach it, they bounce without loss)
      if (chain%gravity < 0.0_wp .and. chain%left_wall) then
         never_ends = undamped .and. chain%left_law%damping == 0.0_wp
      else if (chain%gravity > 0.0_wp .and. chain%right_wall) then
         never_ends = undamped .and. chain%right_law%damping == 0.0_wp
      end if
   end function never_ends

   !> A lower bound on the contacts one body (n = 1) under gravity needs to come to
   !> rest on the wall gravity points to (damped: `never_ends` is false), 0 where the
   !> bound does not apply (more bodies, no such wall, or a start too fast for it).
   !> Found by the energy; from it check_chain refuses, without t_end, a run that could
   !> only end at options%max_events (a ball that would bounce for a day).
   !>
   !> E: the body's energy over its rest touching the wall (x = 0), kinetic plus
   !> elastic c x^(n+1)/(n+1) minus W x (W = m |g| the weight, x the deformation);
   !> constant in flight, not increasing in a contact (the no-pull clamp dissipates
   !> less than b c x^n x'^2). E never falls below -B, B = W x* n/(n+1) the largest
   !> W x - c x^(n+1)/(n+1), at x* = (W/c)^(1/n), and the body rests only once E < 0
   !> (it leaves a contact at x = 0 with E = m v^2/2 >= 0; a turn back inside the
   !> contact needs W > c x^n, where E < 0). So in a contact that starts with E,
   !> |x'| <= U = sqrt(2 (E + B)/m), the deformation reached has c x^(n+1)/(n+1) <=
   !> E + W x <= E + c x^(n+1)/(2 (n+1)) + 2^(1/n) B, and the contact up to its end,
   !> or up to E < 0, dissipates at most
   !>   phi(E) = b U 2 max c x^(n+1)/(n+1) <= 4 b sqrt(2 (E + B)/m) (E + 2^(1/n) B).
   !> A wall on the other side counts only where the body cannot reach it (its
   !> distance from the touch of the floor above E0/W): one within reach can hold the
   !> body in one cluster through many contacts, which are then no events of the
   !> engine (a ball between two walls at gap 0 took 185 contacts in one event).
   !>
   !> The energy falls from E0 (the start) to below 0 through segments [E_k+1, E_k],
   !> one per contact, each no longer than phi(E_k). Cut [0, E0] into bands
   !> (0, E1], (E1, 2 E1], (2 E1, 4 E1], ... (the last one ends at E0): the segments
   !> that start in a band with top T each cover at most phi(T) of it, and one that
   !> starts above it at most phi(T) too where phi' <= 1 above E1 (phi(E) - E does not
   !> grow). So a band of width w holds at least w/phi(T) - 1 starts (w/phi(T) for
   !> the band of E0, which no segment enters from above), and the contacts are at
   !> least the sum over the bands. phi' <= 1 on [E1, E0] holds where
   !>   4 b sqrt(2 (E0 + B)/m) ((t + c)/(2 (t + 1)) + 1) <= 1,
   !> E1 = t B with t = (c + sqrt(c^2 + 8 c))/2, c = 2^(1/n) (where E1/phi(E1) is
   !> largest); elsewhere the bound is 0. Bands from the 200th up (each adds 2^(-1/2)
   !> of the one before, once E >> B) are left out, which keeps it a lower bound.
   !> Every term is formed from logarithms (W, x*, B span the range of doubles).
   pure function least_contacts_to_rest(chain) result(least)
      type(chain_type), intent(in) :: chain
      real(wp) :: least
      integer, parameter :: max_bands = 200
      type(contact_law) :: law
      real(wp) :: damping, gap, v, log_m, log_w, log_b, log_c, log_t, log_e0, log_e1, &
         & log_low, log_top, log_width, log_k, term, n
      integer :: band
      logical :: other
      least = 0.0_wp
      if (size(chain%mass) /= 1 .or. chain%gravity == 0.0_wp) return
      if (chain%gravity < 0.0_wp .and. chain%left_wall) then
         law = chain%left_law
         gap = chain%left_gap
         other = chain%right_wall
      else if (chain%gravity > 0.0_wp .and. chain%right_wall) then
         law = chain%right_law
         gap = chain%right_gap
         other = chain%left_wall
      else
         return
      end if
      damping = law%damping
      if (.not. damping > 0.0_wp) return
      n = law%exponent
      v = chain%velocity(1)
      log_m = log(chain%mass(1))
      log_w = log_m + log(abs(chain%gravity))
      ! B = W x* n/(n + 1), log x* = (log W - log c)/n
      log_b = log_w + (log_w - log(law%stiffness)) / n + log(n / (n + 1.0_wp))
      ! c = 2^(1/n) and t = c (1 + sqrt(1 + 8/c))/2 (8/c underflows harmlessly)
      log_c = log(2.0_wp) / n
      log_t = log_c + log(0.5_wp * (1.0_wp + sqrt(1.0_wp + 8.0_wp * exp(-log_c))))
      log_e1 = log_t + log_b
      ! E0 = m v^2/2 + W gap
      log_e0 = -huge(1.0_wp)
      if (v /= 0.0_wp) log_e0 = log_m + 2.0_wp * log(abs(v)) - log(2.0_wp)
      if (gap > 0.0_wp) log_e0 = log_sum(log_e0, log_w + log(gap))
      if (log_e0 <= -huge(1.0_wp)) return
      ! a wall on the other side out of reach: the walls' gaps (the floor's to the
      ! ceiling's touch) above E0/W, by a margin over the logarithms' rounding
      if (other) then
         if (.not. chain%left_gap + chain%right_gap > 0.0_wp) return
         if (.not. log(chain%left_gap + chain%right_gap) > log_e0 - log_w + 1.0e-9_wp) return
      end if
      ! phi(E) = k sqrt(E + B) (E + c B), k = 4 b sqrt(2/m)
      log_k = log(4.0_wp) + log(damping) + 0.5_wp * (log(2.0_wp) - log_m)
      if (log_e0 > log_e1) then
         ! phi' <= 1 on [E1, E0]; (t + c)/(t + 1) = exp(log(t + c) - log(t + 1))
         if (log_k + 0.5_wp * log_sum(log_e0, log_b) + log1p(0.5_wp * exp(log_sum(log_t, &
            & log_c) - log_sum(log_t, 0.0_wp))) > 0.0_wp) return
      end if
      ! the band (0, min(E1, E0)], then (E1 2^(k-1), E1 2^k] up to E0
      log_top = min(log_e1, log_e0)
      least = band_starts(log_top, log_top, log_e0 > log_top)
      log_low = log_e1
      do band = 1, max_bands
         if (log_low >= log_e0) exit
         log_top = min(log_low + log(2.0_wp), log_e0)
         if (.not. log_top > log_low) exit
         ! the width: top - low
         log_width = log_top + log(-expm1(log_low - log_top))
         term = band_starts(log_width, log_top, log_e0 > log_top)
         ! (a sum beyond the doubles stays at the largest one)
         if (term > huge(1.0_wp) - least) then
            least = huge(1.0_wp)
            exit
         end if
         least = least + term
         log_low = log_top
      end do
   contains
      !> At least this many contacts start in a band of width exp(log_width) whose
      !> top is exp(log_top) (less one for a segment from above, when `entered`)
      pure real(wp) function band_starts(log_width, log_top, entered)
         real(wp), intent(in) :: log_width, log_top
         logical, intent(in) :: entered
         real(wp) :: log_phi
         log_phi = log_k + 0.5_wp * log_sum(log_top, log_b) + log_sum(log_top, log_c + log_b)
         band_starts = exp(min(log_width - log_phi, log(huge(1.0_wp))))
         if (entered) band_starts = max(band_starts - 1.0_wp, 0.0_wp)
      end function band_starts
      !> log(exp(a) + exp(b)) without overflow
      pure real(wp) function log_sum(a, b)
         real(wp), intent(in) :: a, b
         log_sum = max(a, b) + log1p(exp(-abs(a - b)))
      end function log_sum
   end function least_contacts_to_rest

   !> Whether values not negative add up to at most a quarter of the range of doubles,
   !> found without forming a sum beyond it: check_chain's rule for the masses and
   !> the gaps (HCCHN applies it to XM and GAP to name the argument).
   pure logical function sum_within_range(values, start)
      real(wp), intent(in) :: values(:)
      !> A sum so far (not negative, within the limit) that the values add to
      real(wp), intent(in), optional :: start
      real(wp), parameter :: limit = 0.25_wp * huge(1.0_wp)
      real(wp) :: total
      integer :: i
      sum_within_range = .false.
      total = 0.0_wp
      if (present(start)) total = start
      do i = 1, size(values)
         if (values(i) > limit - total) return
         total = total + values(i)
      end do
      sum_within_range = .true.
   end function sum_within_range

   !> Whether the extent of a system (its gaps, with the walls' gaps, all finite and
   !> not negative) stays a factor 4 short of the range of doubles, found without
   !> forming a sum beyond it: the positions are partial sums of the gaps, and the
   !> engine forms differences of positions and the distance between the walls.
   pure logical function extent_within_range(chain)
      type(chain_type), intent(in) :: chain
      real(wp) :: walls(2)
      walls = 0.0_wp
      if (chain%left_wall) walls(1) = chain%left_gap
      if (chain%right_wall) walls(2) = chain%right_gap
      ! (the walls' gaps first, then the gaps: no array joined, which would be a
      ! temporary of the system's size that gfortran allocates unchecked)
      extent_within_range = sum_within_range(walls)
      if (extent_within_range .and. size(chain%mass) > 1) extent_within_range = &
         & sum_within_range(chain%gap, sum(walls))
   end function extent_within_range

   !> The status of a contact law (the library's one validator)
   elemental function law_status(law) result(stat)
      type(contact_law), intent(in) :: law
      integer :: stat
      stat = check_parameters(stiffness=law%stiffness, exponent=law%exponent, &
         & damping=law%damping)
   end function law_status

   !> Kinetic energy 1/2 m v^2 in J for a mass > 0, formed as ((m |v|) |v|)/2 where
   !> that stays normal (v^2 alone overflows above 1.3e154 m/s), else from logarithms
   !> (`product_of`): +Inf beyond the range of doubles, without raising the overflow
   !> (a caller's Debug build traps on it). A velocity that is not finite gives Inf or
   !> NaN.
   elemental function kinetic_energy(mass, velocity) result(energy)
      !> Mass in kg
      real(wp), intent(in) :: mass
      !> Velocity in m/s
      real(wp), intent(in) :: velocity
      real(wp) :: energy
      if (ieee_is_finite(velocity)) then
         energy = product_of([mass, abs(velocity), abs(velocity), 0.5_wp])
      else
         energy = 0.5_wp * (mass * abs(velocity))
      end if
   end function kinetic_energy

   !> The energy balance of a system as a relative error (`chain_result`%energy_error):
   !> |E_end + dissipated - E_start| over the initial kinetic energy plus the
   !> gravitational energy released, e_kin0 + |e_grav| (tiny when both are 0). A system
   !> begins without elastic energy (no initial overlap) and with its gravitational
   !> energy at 0 (counted from the initial positions), so E_start = e_kin0; e_end is
   !> the kinetic, elastic and gravitational energy at the end, e_grav the last part.
   elemental function energy_balance_error(e_end, dissipated, e_kin0, e_grav) result(error)
      real(wp), intent(in) :: e_end, dissipated, e_kin0, e_grav
      real(wp) :: error
      error = abs(e_end + dissipated - e_kin0) / max(e_kin0 + abs(e_grav), tiny(1.0_wp))
   end function energy_balance_error

   !> The momentum balance of a system as a relative error (`chain_result`%
   !> momentum_error): the final momentum p (`momentum`) against the initial one
   !> p0 = sum m v0 plus the impulses from outside (gravity's M g t, the walls'), over
   !> sum m |v0| plus the impulses' magnitudes (they count in the scale as the energy
   !> gravity puts in counts in the energy's; not max(scale, tiny): momenta of
   !> subnormal size are errors of their size). NaN where p, an impulse's sum or the
   !> difference is beyond the range of doubles (no balance to form); nothing is
   !> raised on the way.
   pure function momentum_balance_error(p, mass, velocity0, impulses) result(error)
      !> Final momentum (N s)
      real(wp), intent(in) :: p
      !> The bodies' masses (kg) and initial velocities (m/s), as check_chain passed
      !> them (sum m |v0| a double)
      real(wp), intent(in) :: mass(:), velocity0(:)
      !> The impulses from outside (N s)
      real(wp), intent(in) :: impulses(:)
      real(wp) :: error
      real(wp) :: p0, scale0, outside, magnitude, scale, d
      integer :: i
      error = nan
      if (.not. ieee_is_finite(p)) return
      p0 = 0.0_wp
      scale0 = 0.0_wp
      do i = 1, size(mass)
         p0 = p0 + mass(i) * velocity0(i)
         scale0 = scale0 + mass(i) * abs(velocity0(i))
      end do
      outside = 0.0_wp
      magnitude = 0.0_wp
      do i = 1, size(impulses)
         outside = sum_in_range(outside, impulses(i))
         magnitude = sum_in_range(magnitude, abs(impulses(i)))
      end do
      ! (then |p0 + outside| <= scale0 + magnitude, a double)
      if (.not. ieee_is_finite(magnitude)) return
      if (magnitude > huge(1.0_wp) - scale0) return
      scale = scale0 + magnitude
      ! (p far from p0 + outside: their difference beyond the range has no balance,
      ! a quotient beyond it is the largest double)
      d = sum_in_range(p, -(p0 + outside))
      if (.not. ieee_is_finite(d)) return
      error = 0.0_wp
      if (.not. scale > 0.0_wp) return
      ! (separate tests: .or. does not spare huge * scale, an overflow for scale > 1)
      if (scale >= 1.0_wp) then
         error = abs(d) / scale
      else if (abs(d) <= huge(1.0_wp) * scale) then
         error = abs(d) / scale
      else
         error = huge(1.0_wp)
      end if
   end function momentum_balance_error

   !> a + b, or +-Inf where it is beyond the range of doubles and NaN where it has no
   !> value (infinities of both signs), without raising an exception on the way
   elemental function sum_in_range(a, b) result(total)
      real(wp), intent(in) :: a, b
      real(wp) :: total
      if (ieee_is_nan(a) .or. ieee_is_nan(b)) then
         total = nan
      else if (ieee_is_finite(a) .and. ieee_is_finite(b)) then
         if ((a > 0.0_wp .eqv. b > 0.0_wp) .and. abs(a) > huge(1.0_wp) - abs(b)) then
            total = sign(ieee_value(1.0_wp, ieee_positive_inf), a)
         else
            total = a + b
         end if
      else if (ieee_is_finite(a) .or. ieee_is_finite(b) .or. (a > 0.0_wp .eqv. b > 0.0_wp)) then
         ! an infinity and a finite value, or two of one sign: exact, nothing raised
         total = a + b
      else
         total = nan
      end if
   end function sum_in_range

   !> An energy that cannot be negative (dissipated) where rounding or an integrator's
   !> tolerance left it below 0: 0 there (also for -Inf), NaN kept, without comparing a
   !> NaN (which would raise the invalid exception)
   elemental function not_below_zero(x) result(y)
      real(wp), intent(in) :: x
      real(wp) :: y
      y = x
      if (ieee_is_nan(x)) return
      if (x < 0.0_wp) y = 0.0_wp
   end function not_below_zero

   !> Whether a contact of damping b (s/m) at the relative speed w (m/s) has b |w|
   !> above max_beta (1e40), beyond the model's domain: one impact refuses it
   !> (hcimpact_err_domain), and an integrator meets a force that drops by 40 orders
   !> of magnitude within the contact's first instant, where CVODE's corrector fails.
   elemental logical function beyond_max_beta(damping, w)
      real(wp), intent(in) :: damping, w
      beyond_max_beta = product_in_range(damping, abs(w)) > max_beta
   end function beyond_max_beta

   !> The message of a system that meets such a contact (pair numbered as in the
   !> contacts' records), at the time t.
   pure subroutine say_beyond_max_beta(message, pair, t, damping, w)
      character(len=*), intent(out) :: message
      integer, intent(in) :: pair
      real(wp), intent(in) :: t, damping, w
      write(message, '(a, i0, a, es11.3e3, a, es23.16e3, a, es10.3e3, a)') "pair ", pair, &
         & " at t = ", t, " s: b V = ", product_in_range(damping, abs(w)), &
         & " (damping times approach speed) is above ", max_beta, &
         & ", outside the model's domain (as for one impact)"
   end subroutine say_beyond_max_beta

   !> a b, or +-Inf where it is beyond the range of doubles, without raising the
   !> overflow (the rounding as a b's where it is a double); an infinity times a
   !> non-zero is that infinity, a NaN or an infinity times 0 is NaN, both without
   !> raising the invalid exception (exponent() of an infinity is huge(0), which the
   !> sum below overflowed: the fuzzer found a state at t = 6.5e300 s reaching it)
   elemental function product_in_range(a, b) result(y)
      real(wp), intent(in) :: a, b
      real(wp) :: y, f
      if (ieee_is_nan(a) .or. ieee_is_nan(b)) then
         y = nan
      else if (.not. (ieee_is_finite(a) .and. ieee_is_finite(b))) then
         if (a == 0.0_wp .or. b == 0.0_wp) then
            y = nan
         else
            y = a * b
         end if
      else if (a == 0.0_wp .or. b == 0.0_wp .or. exponent(a) + exponent(b) < maxexponent(1.0_wp)) &
         & then
         y = a * b
      else
         ! near or beyond the top: the product of the fractions, in [1/4, 1), scaled
         f = fraction(a) * fraction(b)
         if (exponent(a) + exponent(b) + exponent(f) > maxexponent(1.0_wp)) then
            y = sign(ieee_value(1.0_wp, ieee_positive_inf), f)
         else
            y = scale(f, exponent(a) + exponent(b))
         end if
      end if
   end function product_in_range

   !> The momentum sum m v (N s) of bodies, +-Inf where it is beyond the range of
   !> doubles, without raising the overflow on the way
   pure function momentum(mass, velocity) result(p)
      real(wp), intent(in) :: mass(:), velocity(:)
      real(wp) :: p
      integer :: i
      p = 0.0_wp
      do i = 1, size(mass)
         p = sum_in_range(p, signed_product(velocity(i), [mass(i)]))
      end do
   end function momentum

   !> The impulse of gravity g on bodies of the masses `mass` over the time t >= 0,
   !> M g t, without overflow on the way (the Debug build traps on it): +-Inf where it
   !> is beyond the range of doubles. (The masses add up to a quarter of the range at
   !> most: check_chain.)
   pure function gravity_impulse(mass, g, t) result(impulse)
      real(wp), intent(in) :: mass(:), g, t
      real(wp) :: impulse
      impulse = sign(product_of([sum(mass), abs(g), t]), g)
   end function gravity_impulse

   !> Whether the kinetic energy and the momentum sum(m |v|) of bodies are doubles,
   !> found without forming a value beyond the range (the Debug build traps an
   !> overflow): a body's speed and m v^2 are checked against the range before they
   !> are formed (a factor 4 short of it, which no physical system approaches), then
   !> every partial sum against what is left of the range.
   pure function within_range(mass, velocity) result(ok)
      !> Masses in kg, > 0
      real(wp), intent(in) :: mass(:)
      !> Velocities in m/s, finite
      real(wp), intent(in) :: velocity(:)
      logical :: ok
      real(wp) :: a, e, p, e_i, p_i
      integer :: i
      ok = .false.
      e = 0.0_wp
      p = 0.0_wp
      do i = 1, size(mass)
         a = abs(velocity(i))
         ! (twice a speed is a scale of the integrator's error weights)
         if (a > 0.25_wp * huge(1.0_wp)) return
         ! a <= 1: m a <= m and m a^2 <= m
         if (a > 1.0_wp) then
            if (mass(i) > 0.25_wp * ((huge(1.0_wp) / a) / a)) return
         end if
         e_i = kinetic_energy(mass(i), velocity(i))
         p_i = mass(i) * a
         if (e_i > huge(1.0_wp) - e .or. p_i > huge(1.0_wp) - p) return
         e = e + e_i
         p = p + p_i
      end do
      ok = .true.
   end function within_range

end module hcimpact_chain_types
