! SPDX-License-Identifier: Apache-2.0
!> A region of a system of bodies on a line as a first-order system for CVODE: the
!> right-hand side and its banded Jacobian, the state of each contact. Nothing here
!> knows about SUNDIALS (hcimpact_cvode_chain calls these procedures from its
!> callbacks).
!>
!> The region holds the bodies k = 1 .. m (global first .. first + m - 1) and the slots
!> j = 0 .. m around and between them: slot j is between local bodies j and j + 1; slot
!> 0 is the left wall or the pair with the body outside on the left (a boundary, only
!> watched), slot m likewise on the right. The state, per body k, is its displacement
!> u_k, its velocity v_k and e_k, the energy dissipated so far in slot k - 1; then
!> e_(m+1), that of slot m; then the impulses the walls have given the region so far
!> (N s, along the line, 0 without a wall): y = (u_1, v_1, e_1, ..., u_m, v_m, e_m,
!> e_(m+1), J_left, J_right), 3 m + 3 values; for the wall that gravity points to, its
!> impulse less the weight's, M g t, which it holds at rest (`wall_impulse`: three
!> bodies pressed on a wall for 810 000 steps let J, growing as M g t, add its rounding
!> of 1e-16 |J| at every step, 22 000 eps in all). Every force is the contact-force
!> element's, clamped (no contact pulls), from the exact deformation and rate of the
!> slot's two ends (contact_force_pair with the initial gap as the distance).
!>
!> Jacobian: v_k' depends on u and v of bodies k - 1, k, k + 1; u_k' = v_k. In the
!> order above that is a band with 3 diagonals above the main one and 4 below
!> (`upper_band`, `lower_band`): one step costs O(m). The e rows are left out of the
!> Jacobian (zero): e_k' depends on u, v of bodies k - 1 and k only, and nothing
!> depends on e, so Newton's iteration converges for them one iteration behind u and
!> v. The impulses' rows lie outside the band (J_left' = F_0 depends on u_1, v_1):
!> the Jacobian callback keeps their two derivatives apart (`region_jacobian`'s slope)
!> and the region's linear solver puts them into M, so that M holds the whole Jacobian.
!> Then m^T M = m^T for m = (masses at the velocities, -1 at the impulses, 0
!> elsewhere: the pair forces cancel), and every Newton iterate and step keeps
!> sum m_k v_k - J_left - J_right - M g t whatever the iteration's tolerance: the
!> momentum balance with walls (doc/chains.md) measures the bookkeeping and rounding
!> (with Adams, the rounding of its history of high order, up to 0.012 rtol). The
!> impulses are results, in the error test as the velocities are: against rtol times
!> the region's mass times v_ref (`error_weights`).
!>
!> The starts and ends of contacts, and their extrema, are found by the driver from each
!> step's cubic Hermite interpolant of every slot's deformation (hcimpact_cvode_chain).
module hcimpact_cvode_chain_system
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_force_element, only : contact_force_type, contact_force_pair
   use hcimpact_chain_types, only : contact_law, kinetic_energy, product_in_range
   use hcimpact_cvode_report, only : solver_report
   implicit none
   private

   public :: chain_region, region_size, region_rhs, region_jacobian, region_scales
   public :: region_frame, frame_motion, first_step
   public :: error_weights, wall_impulse_scale, weights_rtol, newton_factor, &
      & factor_newton_matrix, solve_newton
   public :: set_weight, wall_impulse, pushing_impulse, region_rebase, log_touch_step
   public :: slot_state, dissipation_index, impulse_index, force_rate, &
      & slot_force_rate, upper_band, lower_band
   public :: slot_none, slot_pair, slot_left_wall, slot_right_wall, slot_boundary_left, &
      & slot_boundary_right

   !> Bandwidths of the Jacobian in the order of the state (module header)
   integer, parameter :: upper_band = 3, lower_band = 4

   !> Kinds of slot
   integer, parameter :: slot_none = 0, slot_pair = 1, slot_left_wall = 2, &
      & slot_right_wall = 3, slot_boundary_left = 4, slot_boundary_right = 5

   !> What the callbacks need of a region
   type :: chain_region
      !> Bodies in the region and the common acceleration (m/s^2)
      integer :: m = 0
      real(wp) :: gravity = 0.0_wp
      !> Masses (m)
      real(wp), allocatable :: mass(:)
      !> Per slot 0 .. m: kind, law and gap at zero displacements
      integer, allocatable :: kind(:)
      type(contact_law), allocatable :: law(:)
      real(wp), allocatable :: gap0(:)
      !> The outside bodies of boundary slots (1 left, 2 right): free flight from t0
      real(wp) :: out_t0(2) = 0.0_wp, out_u0(2) = 0.0_wp, out_v0(2) = 0.0_wp
      !> The caller's halting modes (the driver turns halting off while CVODE runs)
      logical :: halting(3) = .false.
      !> Set by the solver's error handler: its last message and code
      type(solver_report) :: report
      !> The relative tolerance and the scales of the errors: deformation (m), speed
      !> (m/s) and energy (J), and impulse (N s: the mass of the region times the
      !> speed's scale, or huge beyond the range) (the driver's error weights)
      real(wp) :: rtol = 1.0e-10_wp, scale(3) = 1.0_wp, impulse_scale = 1.0_wp
      !> The impulses' rows of the last Jacobian (`region_jacobian`'s slope: set by the
      !> Jacobian callback, read by the linear solver's setup)
      real(wp) :: wall_slope(2, 2) = 0.0_wp
      !> The wall that gravity points to (1 left, 2 right; 0: none in the region, or
      !> no gravity), and the region's weight M g (N, along the line): that wall's
      !> state is its impulse less the weight's (module header)
      integer :: weight_side = 0
      real(wp) :: weight = 0.0_wp
   end type chain_region

   !> CVODE's Newton matrix M = I - gamma J of a region, factored through its
   !> structure (module header): in the rows of a displacement, M(u_k, u_k) u_k +
   !> M(u_k, v_k) v_k alone, so the displacements are eliminated and the velocities
   !> solve a tridiagonal system T (Thomas' algorithm: T is strictly diagonally
   !> dominant, as I + gamma (damping) + gamma^2 (stiffness) over the masses with
   !> non-negative derivatives of clamped forces); the dissipated energies, with rows
   !> of the identity, are divided by their diagonal. O(m) to factor and to solve,
   !> where the band LU of the same matrix (3 + 4 diagonals, with room for pivoting)
   !> costs several times more.
   type :: newton_factor
      !> M(u_k, u_k) and M(u_k, v_k), k = 1 .. m
      real(wp), allocatable :: uu(:), uv(:)
      !> M(v_k, u_(k+l)), l = -1, 0, 1
      real(wp), allocatable :: vu(:, :)
      !> Thomas' factors of T: the multipliers of the rows below the diagonal, the
      !> pivots and the entries above the diagonal
      real(wp), allocatable :: lower(:), pivot(:), upper(:)
      !> The diagonal of the energy rows, in the state's order
      real(wp), allocatable :: ee(:)
      !> The impulses' rows (side 1 left, 2 right): M(J, u), M(J, v) of the end
      !> body, and M(J, J)
      real(wp) :: wall_row(2, 2) = 0.0_wp, wall_diagonal(2) = 1.0_wp
   end type newton_factor

   !> BDF's error weights are those of rtol times this (`weights_rtol`). A light body
   !> pressed against a wall by a heavy one, oscillating about 35 periods between them
   !> (seed 34 of bench/chain/attack/run_random.py: 6300 BDF steps at rtol 1e-10,
   !> about 180 a period), ended with velocity errors of 3000, 8900 and 14000 rtol at
   !> rtol 1e-8, 1e-10 and 1e-12; at 0.05 of them, 300, 300 and 650, for 1.6 times the
   !> steps (at 0.1: 400, 540, 2100 for 1.4 times). The errors grow with the number of
   !> steps, as rtol^(-1/6) at order 5: a smaller rtol needs a smaller factor.
   real(wp), parameter :: bdf_tolerance = 0.05_wp
   !> Adams' error weights likewise (orders up to 12, fewer steps): a light body between
   !> a heavy one and a wall (seeds 42 and 22 of run_random.py) ended with 6900, 4200
   !> and 13900 rtol at rtol 1e-8, 1e-10 and 1e-12 (seed 22: 7700 at 1e-10); at 0.1 of
   !> them 416, 1397 and 924 (872) for 1.23 times the steps
   real(wp), parameter :: adams_tolerance = 0.1_wp

contains

   !> Index in the state of the energy dissipated in slot j (e_(j+1), the last value
   !> for slot m)
   pure integer function dissipation_index(m, j)
      integer, intent(in) :: m, j
      dissipation_index = 3 * j + 3
      if (j == m) dissipation_index = 3 * m + 1
   end function dissipation_index

   !> Index in the state of the impulse the wall on side 1 (left) or 2 (right) has
   !> given the region so far
   pure integer function impulse_index(m, side)
      integer, intent(in) :: m, side
      impulse_index = 3 * m + 1 + side
   end function impulse_index

   !> Number of state values of a region of m bodies
   pure integer function region_size(m)
      integer, intent(in) :: m
      region_size = 3 * m + 3
   end function region_size

   !> The two ends of slot j at the time t: positions (m) and velocities (m/s) of its
   !> left and right side, and the distance of `contact_force_pair` (x = d - (qr - ql)).
   pure subroutine slot_ends(region, j, t, y, ql, vl, qr, vr, d)
      type(chain_region), intent(in) :: region
      integer, intent(in) :: j
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: ql, vl, qr, vr, d
      real(wp) :: tau
      d = -region%gap0(j)
      select case (region%kind(j))
      case (slot_pair)
         ql = y(3 * j - 2)
         vl = y(3 * j - 1)
         qr = y(3 * j + 1)
         vr = y(3 * j + 2)
      case (slot_left_wall)
         ! the wall as a fixed left body at -gap0, distance 0
         d = 0.0_wp
         ql = -region%gap0(j)
         vl = 0.0_wp
         qr = y(1)
         vr = y(2)
      case (slot_right_wall)
         d = 0.0_wp
         ql = y(3 * region%m - 2)
         vl = y(3 * region%m - 1)
         qr = region%gap0(j)
         vr = 0.0_wp
      case (slot_boundary_left)
         tau = t - region%out_t0(1)
         ql = region%out_u0(1) + (region%out_v0(1) + 0.5_wp * (region%gravity * tau)) * tau
         vl = region%out_v0(1) + region%gravity * tau
         qr = y(1)
         vr = y(2)
      case (slot_boundary_right)
         tau = t - region%out_t0(2)
         ql = y(3 * region%m - 2)
         vl = y(3 * region%m - 1)
         qr = region%out_u0(2) + (region%out_v0(2) + 0.5_wp * (region%gravity * tau)) * tau
         vr = region%out_v0(2) + region%gravity * tau
      case default
         ql = 0.0_wp
         vl = 0.0_wp
         qr = 0.0_wp
         vr = 0.0_wp
         d = -huge(1.0_wp)
      end select
   end subroutine slot_ends

   !> Deformation x (m), its rate w (m/s) and the element of slot j at the time t
   !> (a slot that exerts no force: boundary or none, has zero force).
   pure subroutine slot_state(region, j, t, y, x, w, element)
      type(chain_region), intent(in) :: region
      integer, intent(in) :: j
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: x, w
      type(contact_force_type), intent(out) :: element
      real(wp) :: ql, vl, qr, vr, d
      call slot_ends(region, j, t, y, ql, vl, qr, vr, d)
      if (region%kind(j) == slot_none) then
         x = -huge(1.0_wp)
         w = 0.0_wp
         element = contact_force_type(0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp)
         return
      end if
      x = (d + ql) - qr
      w = vl - vr
      if (region%kind(j) == slot_boundary_left .or. region%kind(j) == slot_boundary_right) then
         element = contact_force_type(0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp)
         return
      end if
      ! Apart by more than the rounding of x (two roundings, each within an ulp of
      ! twice the largest term): the element's exact deformation is negative too, and
      ! it would return no contact; most slots of a long region are such, or touching
      ! with all three terms zero, and skip the element's exact sums and checks.
      if (x < -4.0_wp * spacing(max(abs(d), abs(ql), abs(qr))) .or. &
         & (d == 0.0_wp .and. ql == 0.0_wp .and. qr == 0.0_wp)) then
         element = contact_force_type(0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp)
         return
      end if
      call contact_force_pair(region%law(j)%stiffness, region%law(j)%exponent, &
         & region%law(j)%damping, d, ql, vl, qr, vr, element)
   end subroutine slot_state

   !> The error weights of a state of bodies (CVODE's CVEwtFn), for the serial region
   !> and a rank's block alike: y holds (u, v, e) per body and, serial, the region's
   !> last dissipated energy after them (any value past the bodies' is an energy),
   !> then with impulse_scale the two walls' impulses (the serial region's state), or
   !> the n_impulses a rank's block holds.
   !> A displacement's error is measured against rtol x_ref, not against rtol |u|:
   !> the deformations, differences of displacements that grow as the bodies move,
   !> must keep their accuracy however far the bodies have gone. A velocity's against
   !> rtol (|v| + v_ref), a dissipated energy's against rtol e_ref (scale). Every
   !> weight is multiplied by root_n, the square root of the number of values in the
   !> whole system, so that CVODE's root mean square of the weighted errors is their
   !> 2-norm: the bodies that carry the errors (those in contact) are few in a long
   !> chain, and a mean over all its bodies would let their errors grow with its size
   !> (a struck chain of 10^4 beads at rtol 1e-8 kept its energy to 1.5e-4 only). No
   !> tolerance is below 2 root_n ulps of its value (the value's own rounding): a ball
   !> dropped 25 cm has a displacement whose ulp is 5e-17 m, above rtol x_ref = 1e-17
   !> m, and CVODE stopped with CV_TOO_MUCH_ACC (its check: unit roundoff times the
   !> weighted norm of the state at most 1, which this floor keeps at 1/2). Nor is any
   !> below root_n times the smallest normal double, so that no weight overflows: the
   !> dissipated energy of bodies of 1e-300 kg has rtol e_ref = 1e-310, whose
   !> reciprocal is +Inf, and CVODE failed at t = 0 (CV_CONV_FAILURE); such energies
   !> are subnormal, with fewer digits than any tolerance asks.
   pure subroutine error_weights(y, rtol, scale, root_n, w, impulse_scale, n_impulses)
      !> The state
      real(wp), intent(in) :: y(:)
      !> Relative tolerance
      real(wp), intent(in) :: rtol
      !> x_ref, v_ref, e_ref (region_scales)
      real(wp), intent(in) :: scale(3)
      !> Square root of the number of values of the whole system
      real(wp), intent(in) :: root_n
      !> The weights
      real(wp), intent(out) :: w(:)
      !> The scale of the impulses (N s), when the state ends with them (`wall_impulse_scale`)
      real(wp), intent(in), optional :: impulse_scale
      !> How many impulses the state ends with (with impulse_scale; default 2)
      integer, intent(in), optional :: n_impulses
      real(wp) :: floor, least
      integer :: k, m, last
      floor = 2.0_wp * epsilon(1.0_wp) * root_n
      least = tiny(1.0_wp) * root_n
      last = size(y)
      if (present(impulse_scale)) then
         last = size(y) - 2
         if (present(n_impulses)) last = size(y) - n_impulses
         do k = last + 1, size(y)
            w(k) = root_n / max(rtol * impulse_scale, floor * abs(y(k)), least)
         end do
      end if
      m = last / 3
      do k = 1, m
         w(3 * k - 2) = root_n / max(rtol * scale(1), floor * abs(y(3 * k - 2)), least)
         w(3 * k - 1) = root_n / max(rtol * (abs(y(3 * k - 1)) + scale(2)), &
            & floor * abs(y(3 * k - 1)), least)
         w(3 * k) = root_n / max(rtol * scale(3), floor * abs(y(3 * k)), least)
      end do
      do k = 3 * m + 1, last
         w(k) = root_n / max(rtol * scale(3), floor * abs(y(k)), least)
      end do
   end subroutine error_weights

   !> The scale of the walls' impulses in the error weights (N s): the mass of the
   !> bodies that receive them times the speed's scale v_ref (huge beyond the range)
   pure real(wp) function wall_impulse_scale(mass, v_ref)
      real(wp), intent(in) :: mass(:), v_ref
      wall_impulse_scale = min(product_in_range(sum(mass), v_ref), huge(1.0_wp))
   end function wall_impulse_scale

   !> The relative tolerance of the error weights for a user's rtol: a fraction of it
   !> (`bdf_tolerance`, `adams_tolerance`), as the local errors of the steps add up
   !> over a body that oscillates for many periods inside a cluster.
   pure real(wp) function weights_rtol(rtol, adams)
      !> The user's relative tolerance
      real(wp), intent(in) :: rtol
      !> Adams (else BDF)
      logical, intent(in) :: adams
      weights_rtol = bdf_tolerance * rtol
      if (adams) weights_rtol = adams_tolerance * rtol
   end function weights_rtol

   !> The frame a region is integrated in, from its bodies' velocities v at its start
   !> (before region%gravity is made relative to the frame): without a wall it falls
   !> freely (a_frame = region%gravity), and where all bodies move the same way it
   !> moves with the slowest of them (v_frame, m/s); else it stands still. In it the
   !> relative motion keeps the digits of its own size, not those of a common speed
   !> or fall (doc/chains.md, "The region's frame"). Where a body is at rest the frame
   !> does not move with the bodies (it still falls without a wall), so that a body at
   !> rest added to a region leaves its integration as it was.
   pure subroutine region_frame(region, v, v_frame, a_frame)
      type(chain_region), intent(in) :: region
      real(wp), intent(in) :: v(:)
      real(wp), intent(out) :: v_frame, a_frame
      v_frame = 0.0_wp
      a_frame = 0.0_wp
      if (region%kind(0) == slot_left_wall .or. region%kind(region%m) == slot_right_wall) &
         & return
      if (minval(v) > 0.0_wp) v_frame = minval(v)
      if (maxval(v) < 0.0_wp) v_frame = maxval(v)
      a_frame = region%gravity
   end subroutine region_frame

   !> Where a frame that moved at v_frame with the constant acceleration a_frame is
   !> after tau (shift, m) and its velocity then (speed, m/s)
   elemental subroutine frame_motion(v_frame, a_frame, tau, shift, speed)
      real(wp), intent(in) :: v_frame, a_frame, tau
      real(wp), intent(out) :: shift, speed
      shift = (v_frame + 0.5_wp * (a_frame * tau)) * tau
      speed = v_frame + a_frame * tau
   end subroutine frame_motion

   !> CVODE's first step (s) in a region with the scales of `region_scales` (x_ref,
   !> v_ref, e_ref): a hundredth of sqrt(rtol) times the time x_ref / v_ref. CVODE's
   !> own estimate, from the end time, went to t = +Inf and NaN states for beads at
   !> rest given t_end = 1e159.
   !> And at most that fraction of stop_time (region_scales): a contact so
   !> damped that it stops well within x_ref (b V of 3e19 at n = 1) needs a first step
   !> of its own time, where CVODE's corrector failed ten times in a row from x_ref /
   !> v_ref (CV_CONV_FAILURE at t = 0, the Jacobian of the start, where the damping's
   !> term c b x^n is 0, far from the step's end). Not below 1e-150 s for that (nor
   !> below x_ref / v_ref's step where that is smaller): CVODE's products of times
   !> underflow below it (`region_scales`).
   pure real(wp) function first_step(rtol, scale, stop_time)
      real(wp), intent(in) :: rtol, scale(3), stop_time
      real(wp) :: elastic
      elastic = 0.01_wp * sqrt(rtol) * scale(1) / scale(2)
      first_step = max(min(elastic, 0.01_wp * sqrt(rtol) * stop_time), &
         & min(elastic, 1.0e-150_wp))
   end function first_step

   !> The natural scales of a region in the state y: the deformation x_ref (m), the
   !> smallest maximum compression of its contacts at its largest relative speed, or
   !> the static compression under gravity; that speed v_ref (m/s), twice the largest
   !> speed of a body; and the kinetic energy e_ref (J) of that speed (the error
   !> weights' scales, `chain_region`%scale); and the weakest force, the smallest of
   !> the contacts' peak forces c x^n at their compressions above (N; huge when no
   !> contact has a scale); and stop_time, the shortest time in which a damped
   !> contact stops from v_ref (s; huge without one): x_s / v_ref, x_s the compression
   !> that stops a contact whose force is c b x^n w alone, ((n + 1) mu v_ref / (c b))^(1
   !> / (n + 1)) (below x_ref where b v_ref is above about 2, the elastic scale's).
   pure subroutine region_scales(region, y, scale, weakest_force, horizon, stop_time)
      type(chain_region), intent(in) :: region
      real(wp), intent(in) :: y(:)
      real(wp), intent(out) :: scale(3), weakest_force
      !> The time left to the end of the run (s; huge: the run ends when no contact can
      !> happen again)
      real(wp), intent(in) :: horizon
      real(wp), intent(out) :: stop_time
      ! exp of at most this is a double
      real(wp), parameter :: max_log = 709.0_wp
      real(wp) :: v_ref, x_ref, x_max, mu, e_ref, total, lq, lx, mu_max
      type(contact_law) :: law
      integer :: k, j, m
      logical :: ok

      m = region%m
      v_ref = 0.0_wp
      do k = 1, m
         v_ref = max(v_ref, abs(y(3 * k - 1)))
      end do
      v_ref = 2.0_wp * v_ref
      total = sum(region%mass)
      x_ref = huge(1.0_wp)
      e_ref = 0.0_wp
      mu_max = 0.0_wp
      stop_time = huge(1.0_wp)
      weakest_force = huge(1.0_wp)
      do j = 0, m
         if (region%kind(j) == slot_none .or. region%kind(j) == slot_boundary_left &
            & .or. region%kind(j) == slot_boundary_right) cycle
         law = region%law(j)
         if (region%kind(j) == slot_pair) then
            mu = region%mass(j) * (region%mass(j + 1) / (region%mass(j) + region%mass(j + 1)))
         else if (region%kind(j) == slot_left_wall) then
            mu = region%mass(1)
         else
            mu = region%mass(m)
         end if
         ! where v_ref^2 or total g/c would leave the range of doubles (1e-300 kg at
         ! 1e160 m/s), by logarithms: a compression beyond the range is taken as the
         ! largest double, which x_ref never keeps
         ! (lx: log(x_max), also where x_max is below the doubles: a body of 1e-300 kg at
         ! 1e-20 m/s on a wall of c = 1e-300 N/m^2, whose m v^2 underflowed to 0, had no
         ! scale, and its peak force of 1e-327 N was integrated, the rebound 17 % off)
         x_max = 0.0_wp
         lx = -huge(1.0_wp)
         if (v_ref > 0.0_wp) then
            lq = log(law%exponent + 1.0_wp) + log(mu) + 2.0_wp * log(v_ref)
            ! (the numerator, then the quotient, each a normal double)
            ok = abs(lq) < max_log .and. v_ref < 1.0e150_wp .and. v_ref > 1.0e-150_wp
            lq = lq - (log(2.0_wp) + log(law%stiffness))
            lx = lq / (law%exponent + 1.0_wp)
            if (ok .and. abs(lq) < max_log) then
               x_max = ((law%exponent + 1.0_wp) * mu * v_ref**2 / (2.0_wp * law%stiffness)) &
                  & **(1.0_wp / (law%exponent + 1.0_wp))
            else
               x_max = exp(max(-max_log - 50.0_wp, min(max_log, lx)))
            end if
         end if
         if (region%gravity /= 0.0_wp) then
            lq = log(total) + log(abs(region%gravity))
            ok = abs(lq) < max_log
            lq = lq - log(law%stiffness)
            lx = max(lx, lq / law%exponent)
            if (ok .and. abs(lq) < max_log) then
               x_max = max(x_max, (total * abs(region%gravity) / law%stiffness) &
                  & **(1.0_wp / law%exponent))
            else
               x_max = max(x_max, exp(max(-max_log - 50.0_wp, min(max_log, lq / law%exponent))))
            end if
         end if
         if (lx > -huge(1.0_wp)) then
            if (x_max > 0.0_wp) then
               x_ref = min(x_ref, x_max)
               lx = log(x_max)
            end if
            ! (by logarithms: c x^n of a compression near the range's ends)
            lq = log(law%stiffness) + law%exponent * lx
            weakest_force = min(weakest_force, exp(max(-max_log - 50.0_wp, min(max_log, lq))))
         end if
         e_ref = max(e_ref, kinetic_energy(mu, v_ref))
         mu_max = max(mu_max, mu)
         ! (by logarithms: x_s / v_ref, each factor a positive double)
         if (law%damping > 0.0_wp .and. v_ref > 0.0_wp) then
            lq = (log(law%exponent + 1.0_wp) + log(mu) + log(v_ref) - log(law%stiffness) &
               & - log(law%damping)) / (law%exponent + 1.0_wp) - log(v_ref)
            stop_time = min(stop_time, exp(max(-max_log, min(max_log, lq))))
         end if
      end do
      ! a run that ends sooner reaches about the bodies' approach at v_ref, and a fall
      ! under gravity, over the time left (a scale, not a bound: contacts can speed a
      ! body up beyond v_ref, hence 4 times that; a smaller x_ref only tightens the
      ! tolerances): a column of 1e20 kg beads falling onto a floor for 10 ms had
      ! x_ref = 7.6 km, the compression that stops it, for 1 mm of contact, and ended
      ! 20 % off in position (energy balance 0.13)
      ! (beyond 1e100 s, m/s or m/s^2 not bounded: the product stays a double; nor
      ! below 1e-150 s: CVODE's first step, x_ref / v_ref, times the time to its stop
      ! would underflow to 0, which CVODE takes for a stop behind the start)
      if (horizon > 1.0e-150_wp .and. horizon < 1.0e100_wp .and. v_ref < 1.0e100_wp &
         & .and. abs(region%gravity) < 1.0e100_wp) then
         x_max = 4.0_wp * horizon * (v_ref + abs(region%gravity) * horizon)
         if (x_max > 0.0_wp) x_ref = min(x_ref, x_max)
      end if
      if (.not. (x_ref > 0.0_wp .and. x_ref < huge(1.0_wp))) x_ref = 1.0e-6_wp
      ! under gravity, at least the speed of a fall through x_ref: x_ref is then at least
      ! the static compression, and x_ref / v_ref the time scale of the first step and
      ! of the tolerances (a ball released at rest 1e-100 m above a floor met it at
      ! 4.5e-50 m/s: v_ref 1e-49 m/s gave a first step of 4e38 s, taken as too long an
      ! interval for CVODE's first checks, and the ball drifted through the floor)
      ! (a product of square roots: |g| x_ref may leave the range)
      v_ref = max(v_ref, sqrt(abs(region%gravity)) * sqrt(x_ref))
      if (.not. v_ref > 0.0_wp) v_ref = 1.0_wp
      ! (the energy's scale with it: the kinetic energy of the largest mass of a contact)
      if (mu_max > 0.0_wp) e_ref = max(e_ref, kinetic_energy(mu_max, v_ref))
      if (.not. e_ref > 0.0_wp) e_ref = kinetic_energy(total, v_ref)
      scale = [x_ref, v_ref, e_ref]
   end subroutine region_scales

   !> Right-hand side dy/dt at the time t; ok false if a force is not finite. With
   !> the optional arrays (indices 0 .. m), each slot's deformation, rate and element
   !> as `slot_state` gives them (the driver follows the contacts from these).
   pure subroutine region_rhs(region, t, y, dy, ok, xs, ws, elements)
      type(chain_region), intent(in) :: region
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: dy(:)
      logical, intent(out) :: ok
      real(wp), intent(out), optional :: xs(0:), ws(0:)
      type(contact_force_type), intent(out), optional :: elements(0:)
      type(contact_force_type) :: e
      real(wp) :: x, w, f_left
      integer :: j, m
      logical :: within

      m = region%m
      ok = .true.
      f_left = 0.0_wp
      dy(impulse_index(m, 1)) = 0.0_wp
      dy(impulse_index(m, 2)) = 0.0_wp
      do j = 0, m
         call slot_state(region, j, t, y, x, w, e)
         ! (ieee_is_finite, not a comparison: a NaN compared traps in the Debug build)
         if (.not. (ieee_is_finite(e%force) .and. ieee_is_finite(e%dissipation))) &
            & ok = .false.
         if (present(xs)) xs(j) = x
         if (present(ws)) ws(j) = w
         if (present(elements)) elements(j) = e
         ! body j between the slots j - 1 and j
         if (j >= 1) then
            dy(3 * j - 2) = y(3 * j - 1)
            call body_acceleration(region, j, f_left, e%force, dy(3 * j - 1), within)
            ok = ok .and. within
         end if
         f_left = e%force
         dy(dissipation_index(m, j)) = e%dissipation
         ! the walls' forces on the end bodies
         if (j == 0 .and. region%kind(j) == slot_left_wall) dy(impulse_index(m, 1)) = e%force
         if (j == m .and. region%kind(j) == slot_right_wall) dy(impulse_index(m, 2)) = -e%force
      end do
      ! the weight's impulse taken off the wall that holds it
      if (region%weight_side > 0) dy(impulse_index(m, region%weight_side)) = &
         & dy(impulse_index(m, region%weight_side)) + region%weight
   end subroutine region_rhs

   !> Count the region's displacements anew from the state y at its time t, which
   !> becomes time 0 (`hcimpact_cvode_chain`'s rebase): every displacement of y is set
   !> to 0 and every slot keeps its deformation, a pair's or a wall's to the bit (its
   !> gap at zero displacements is minus that deformation), a boundary's through the
   !> outside body's free flight counted from then. Velocities, energies and impulses
   !> are left as they are (the frame is not changed).
   pure subroutine region_rebase(region, t, y)
      type(chain_region), intent(inout) :: region
      real(wp), intent(in) :: t
      real(wp), intent(inout) :: y(:)
      real(wp) :: x, w, ql, vl, qr, vr, d
      type(contact_force_type) :: e
      integer :: j, m
      m = region%m
      do j = 0, m
         select case (region%kind(j))
         case (slot_pair, slot_left_wall, slot_right_wall)
            call slot_state(region, j, t, y, x, w, e)
            region%gap0(j) = -x
         case (slot_boundary_left)
            call slot_ends(region, j, t, y, ql, vl, qr, vr, d)
            region%out_t0(1) = 0.0_wp
            region%out_u0(1) = ql - y(1)
            region%out_v0(1) = vl
         case (slot_boundary_right)
            call slot_ends(region, j, t, y, ql, vl, qr, vr, d)
            region%out_t0(2) = 0.0_wp
            region%out_u0(2) = qr - y(3 * m - 2)
            region%out_v0(2) = vr
         end select
      end do
      y(1:3 * m:3) = 0.0_wp
   end subroutine region_rebase

   !> The logarithm of the step (s) that the error test allows across the first touch
   !> of slot j, closing at the rate w (m/s), for a tolerance tol of the velocities
   !> (m/s): a step h across the touch changes the relative velocity by about c w^n
   !> h^(n + 1) / mu (the force rises as (w t)^n; mu the pair's reduced mass, or the
   !> body's on a wall), so h = (tol mu / (c w^n))^(1 / (n + 1)); by logarithms, each
   !> factor a positive double. huge where w or tol is not positive, or the slot has
   !> no contact law (a boundary, none).
   pure real(wp) function log_touch_step(region, j, w, tol) result(lh)
      type(chain_region), intent(in) :: region
      integer, intent(in) :: j
      real(wp), intent(in) :: w, tol
      real(wp) :: mu
      lh = huge(1.0_wp)
      select case (region%kind(j))
      case (slot_pair)
         mu = region%mass(j) * (region%mass(j + 1) / (region%mass(j) + region%mass(j + 1)))
      case (slot_left_wall)
         mu = region%mass(1)
      case (slot_right_wall)
         mu = region%mass(region%m)
      case default
         return
      end select
      if (.not. (w > 0.0_wp .and. tol > 0.0_wp .and. mu > 0.0_wp)) return
      lh = (log(tol) + log(mu) - log(region%law(j)%stiffness) &
         & - region%law(j)%exponent * log(w)) / (region%law(j)%exponent + 1.0_wp)
   end function log_touch_step

   !> The wall that gravity points to in a region (weight_side) and the region's
   !> weight, M g (N); none where M g is beyond the range of doubles.
   pure subroutine set_weight(region)
      type(chain_region), intent(inout) :: region
      real(wp) :: weight
      region%weight_side = 0
      region%weight = 0.0_wp
      weight = product_in_range(sum(region%mass), region%gravity)
      if (.not. ieee_is_finite(weight)) return
      if (region%gravity < 0.0_wp .and. region%kind(0) == slot_left_wall) then
         region%weight_side = 1
      else if (region%gravity > 0.0_wp .and. region%kind(region%m) == slot_right_wall) then
         region%weight_side = 2
      end if
      if (region%weight_side > 0) region%weight = weight
   end subroutine set_weight

   !> The impulse the wall on `side` (1 left, 2 right) gave the region over the time
   !> `elapsed` since its start, from its state y (N s, along the line;
   !> `pushing_impulse`); exactly 0 where the region never `touched` that wall. The
   !> state of the wall that holds the weight is the impulse plus M g elapsed, and
   !> holds the impulse to the rounding of that: taking M g elapsed off left 7e-18 N s
   !> of the wrong sign for a wall never touched after 1 s, and leaves a few ulps of
   !> M g t on one that was (40960 N s, 5 ulps, for a true 2000 on a column of 1e20 kg
   !> beads falling for 10 ms).
   pure real(wp) function wall_impulse(region, side, y, elapsed, touched) result(impulse)
      type(chain_region), intent(in) :: region
      integer, intent(in) :: side
      real(wp), intent(in) :: y(:), elapsed
      logical, intent(in) :: touched
      impulse = 0.0_wp
      if (.not. touched) return
      impulse = y(impulse_index(region%m, side))
      if (side == region%weight_side) impulse = impulse - region%weight * elapsed
      impulse = pushing_impulse(side, impulse)
   end function wall_impulse

   !> A wall's impulse on the bodies as a wall can give it: it only pushes (no contact
   !> pulls), so the left wall's (side 1) is >= 0 and the right wall's (side 2) <= 0;
   !> an integrated value of the other sign, the integration's error, is 0.
   elemental real(wp) function pushing_impulse(side, impulse) result(pushed)
      integer, intent(in) :: side
      real(wp), intent(in) :: impulse
      if (side == 1) then
         pushed = max(impulse, 0.0_wp)
      else
         pushed = min(impulse, 0.0_wp)
      end if
   end function pushing_impulse

   !> The acceleration of body k (m/s^2) under gravity, the force f_left of the slot on
   !> its left (+f_left on it) and f_right of the slot on its right (-f_right), in that
   !> order (one place for region_rhs and slot_force_rate, so that both give the same
   !> value to the bit); within false where a term leaves the range (acceleration_of).
   pure subroutine body_acceleration(region, k, f_left, f_right, a, within)
      type(chain_region), intent(in) :: region
      integer, intent(in) :: k
      real(wp), intent(in) :: f_left, f_right
      real(wp), intent(out) :: a
      logical, intent(out) :: within
      real(wp) :: term
      logical :: inside
      a = region%gravity
      call acceleration_of(f_left, region%mass(k), term, within)
      call add_within(a, term, within)
      call acceleration_of(f_right, region%mass(k), term, inside)
      call add_within(a, -term, inside)
      within = within .and. inside
   end subroutine body_acceleration

   !> dF/dt of slot j in the state y at the time t, from the accelerations of its two
   !> bodies alone (the slots j - 1, j and j + 1: O(1), not a whole right-hand side),
   !> with its deformation x, rate w and element e; ok false where a force is not
   !> finite. The same value as force_rate on region_rhs's accelerations.
   pure subroutine slot_force_rate(region, j, t, y, x, w, e, rate, ok)
      type(chain_region), intent(in) :: region
      integer, intent(in) :: j
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: x, w, rate
      type(contact_force_type), intent(out) :: e
      logical, intent(out) :: ok
      real(wp) :: xn, wn, a_left, a_right, wdot
      type(contact_force_type) :: left, right
      logical :: within, inside
      call slot_state(region, j, t, y, x, w, e)
      ok = ieee_is_finite(e%force)
      a_left = 0.0_wp
      a_right = 0.0_wp
      within = .true.
      inside = .true.
      select case (region%kind(j))
      case (slot_pair)
         call slot_state(region, j - 1, t, y, xn, wn, left)
         call slot_state(region, j + 1, t, y, xn, wn, right)
         ok = ok .and. ieee_is_finite(left%force) .and. ieee_is_finite(right%force)
         if (ok) then
            call body_acceleration(region, j, left%force, e%force, a_left, within)
            call body_acceleration(region, j + 1, e%force, right%force, a_right, inside)
         end if
         wdot = a_left - a_right
      case (slot_left_wall)
         call slot_state(region, 1, t, y, xn, wn, right)
         ok = ok .and. ieee_is_finite(right%force)
         if (ok) call body_acceleration(region, 1, e%force, right%force, a_right, inside)
         wdot = -a_right
      case (slot_right_wall)
         call slot_state(region, region%m - 1, t, y, xn, wn, left)
         ok = ok .and. ieee_is_finite(left%force)
         if (ok) call body_acceleration(region, region%m, left%force, e%force, a_left, &
            & within)
         wdot = a_left
      case default
         wdot = 0.0_wp
      end select
      ok = ok .and. within .and. inside
      rate = e%dforce_dx * w + e%dforce_dv * wdot
   end subroutine slot_force_rate

   !> The acceleration f/m of a force f on a mass m > 0, and whether it lies within a
   !> quarter of the largest double, so that the few terms of a body (gravity, the
   !> forces of its two slots) or of a Jacobian entry add up without overflow; beyond,
   !> a is that bound with the sign of f. Formed without an overflow (the Debug build
   !> traps on it): a body of subnormal mass has accelerations beyond the range of
   !> doubles as soon as the force is normal.
   elemental subroutine acceleration_of(f, m, a, within)
      real(wp), intent(in) :: f, m
      real(wp), intent(out) :: a
      logical, intent(out) :: within
      real(wp), parameter :: bound = 0.25_wp * huge(1.0_wp)
      ! (nested: Fortran may evaluate both sides of .or., and m bound overflows for m >= 4)
      within = .false.
      a = 0.0_wp
      if (.not. ieee_is_finite(f)) return
      a = sign(huge(1.0_wp), f)
      if (m >= 1.0_wp) then
         a = f / m
      else if (abs(f) <= m * bound) then
         a = f / m
      end if
      within = abs(a) <= bound
      if (.not. within) a = sign(bound, f)
   end subroutine acceleration_of

   !> total + a unless that sum leaves the range of doubles (total is then unchanged
   !> and within false), formed without an overflow
   elemental subroutine add_within(total, a, within)
      real(wp), intent(inout) :: total
      real(wp), intent(in) :: a
      logical, intent(inout) :: within
      real(wp), parameter :: bound = 0.25_wp * huge(1.0_wp)
      if (abs(total) <= bound .and. abs(a) <= bound) then
         total = total + a
      else if (abs(0.5_wp * total + 0.5_wp * a) <= 0.5_wp * huge(1.0_wp)) then
         total = total + a
      else
         within = .false.
      end if
   end subroutine add_within

   !> The Jacobian into band storage (SUNDIALS' band matrix seen as a Fortran array):
   !> J(row, col) is band(smu + row - col + 1, col), smu the stored upper bandwidth.
   !> Only the nonzero entries are added to (band zeroed by the caller). With slope,
   !> the rows of the impulses, outside the band: the derivatives of J_left' = F_0
   !> and J_right' = -F_m by the displacement and velocity of their end body,
   !> slope(:, side), both -(dF/dx, dF/dw) of the wall's element (0 without a wall).
   pure subroutine region_jacobian(region, t, y, smu, band, slope)
      type(chain_region), intent(in) :: region
      real(wp), intent(in) :: t, y(:)
      integer, intent(in) :: smu
      real(wp), intent(inout) :: band(:, :)
      real(wp), intent(out), optional :: slope(2, 2)
      type(contact_force_type) :: e
      real(wp) :: x, w, fx, fv, axl, avl, axr, avr
      integer :: k, j, m, l, r
      logical :: within

      m = region%m
      if (present(slope)) slope = 0.0_wp
      do k = 1, m
         call band_add(band, smu, 3 * k - 2, 3 * k - 1, 1.0_wp)
      end do
      do j = 0, m
         call slot_state(region, j, t, y, x, w, e)
         fx = max(-huge(1.0_wp), min(e%dforce_dx, huge(1.0_wp)))
         fv = max(-huge(1.0_wp), min(e%dforce_dv, huge(1.0_wp)))
         if (fx == 0.0_wp .and. fv == 0.0_wp) cycle
         select case (region%kind(j))
         case (slot_pair)
            l = j
            r = j + 1
            ! x = ... + u_l - u_r, w = v_l - v_r (the entries bounded by a quarter of
            ! the largest double: acceleration_of)
            call acceleration_of(fx, region%mass(l), axl, within)
            call acceleration_of(fv, region%mass(l), avl, within)
            call acceleration_of(fx, region%mass(r), axr, within)
            call acceleration_of(fv, region%mass(r), avr, within)
            call band_add(band, smu, 3 * l - 1, 3 * l - 2, -axl)
            call band_add(band, smu, 3 * l - 1, 3 * r - 2, axl)
            call band_add(band, smu, 3 * l - 1, 3 * l - 1, -avl)
            call band_add(band, smu, 3 * l - 1, 3 * r - 1, avl)
            call band_add(band, smu, 3 * r - 1, 3 * l - 2, axr)
            call band_add(band, smu, 3 * r - 1, 3 * r - 2, -axr)
            call band_add(band, smu, 3 * r - 1, 3 * l - 1, avr)
            call band_add(band, smu, 3 * r - 1, 3 * r - 1, -avr)
         case (slot_left_wall)
            ! x = -(gap + u_1), w = -v_1; +F on body 1
            call acceleration_of(fx, region%mass(1), axl, within)
            call acceleration_of(fv, region%mass(1), avl, within)
            call band_add(band, smu, 2, 1, -axl)
            call band_add(band, smu, 2, 2, -avl)
            if (present(slope)) slope(:, 1) = [-fx, -fv]
         case (slot_right_wall)
            ! x = u_m - gap, w = v_m; -F on body m
            call acceleration_of(fx, region%mass(m), axr, within)
            call acceleration_of(fv, region%mass(m), avr, within)
            call band_add(band, smu, 3 * m - 1, 3 * m - 2, -axr)
            call band_add(band, smu, 3 * m - 1, 3 * m - 1, -avr)
            if (present(slope)) slope(:, 2) = [-fx, -fv]
         end select
      end do
   end subroutine region_jacobian

   !> J(row, col) += value in band storage (region_jacobian)
   pure subroutine band_add(band, smu, row, col, value)
      real(wp), intent(inout) :: band(:, :)
      integer, intent(in) :: smu, row, col
      real(wp), intent(in) :: value
      band(smu + row - col + 1, col) = band(smu + row - col + 1, col) + value
   end subroutine band_add

   !> Factor the Newton matrix M of a region of m bodies (band storage as in
   !> region_jacobian: M(row, col) = band(smu + row - col + 1, col), with the
   !> Jacobian's bandwidths around the diagonal), completed by the impulses' rows
   !> outside the band: -gamma times `region_jacobian`'s slope, gamma = -M(u_1, v_1)
   !> (u_1' = v_1).
   !> info: 0; k > 0 when the k-th pivot of T is zero or not finite (CVODE then
   !> retries with a smaller step); -1 when M has an entry outside the structure of
   !> newton_factor (the Jacobian changed without this), or the factors cannot be
   !> allocated.
   pure subroutine factor_newton_matrix(m, smu, band, slope, factor, info)
      integer, intent(in) :: m, smu
      real(wp), intent(in) :: band(:, :)
      !> `region_jacobian`'s slope of the Jacobian M was formed from
      real(wp), intent(in) :: slope(2, 2)
      type(newton_factor), intent(inout) :: factor
      integer, intent(out) :: info
      real(wp) :: t_lower, t_diag
      integer :: k, l, n, row, col, alloc_stat

      info = -1
      n = region_size(m)
      if (.not. allocated(factor%uu)) then
         allocate(factor%uu(m), factor%uv(m), factor%vu(-1:1, m), factor%lower(m), &
            & factor%pivot(m), factor%upper(m), factor%ee(m + 1), stat=alloc_stat)
         if (alloc_stat /= 0) return
      end if
      if (size(factor%uu) /= m) return
      do col = 1, n
         do row = max(1, col - upper_band), min(n, col + lower_band)
            if (entry_of_structure(m, row, col)) cycle
            if (band(smu + row - col + 1, col) /= 0.0_wp) return
         end do
      end do
      do k = 1, m
         factor%uu(k) = entry(3 * k - 2, 3 * k - 2)
         factor%uv(k) = entry(3 * k - 2, 3 * k - 1)
         do l = -1, 1
            factor%vu(l, k) = 0.0_wp
            if (k + l >= 1 .and. k + l <= m) factor%vu(l, k) = entry(3 * k - 1, 3 * (k + l) - 2)
         end do
         factor%ee(k) = entry(3 * k, 3 * k)
      end do
      factor%ee(m + 1) = entry(dissipation_index(m, m), dissipation_index(m, m))
      ! M(J, .) = e_J - gamma J'(.): the end body's columns (-gamma = M(u_1, v_1)),
      ! and the diagonal
      factor%wall_row(:, 1) = entry(1, 2) * slope(:, 1)
      factor%wall_row(:, 2) = entry(1, 2) * slope(:, 2)
      factor%wall_diagonal(1) = entry(impulse_index(m, 1), impulse_index(m, 1))
      factor%wall_diagonal(2) = entry(impulse_index(m, 2), impulse_index(m, 2))
      info = 0
      ! T(k, k + l) = M(v_k, v_(k+l)) - M(v_k, u_(k+l)) M(u, v)/M(u, u) of body k + l
      do k = 1, m
         t_diag = entry(3 * k - 1, 3 * k - 1) - factor%vu(0, k) * (factor%uv(k) / factor%uu(k))
         factor%upper(k) = 0.0_wp
         if (k < m) factor%upper(k) = entry(3 * k - 1, 3 * k + 2) &
            & - factor%vu(1, k) * (factor%uv(k + 1) / factor%uu(k + 1))
         factor%lower(k) = 0.0_wp
         if (k > 1) then
            t_lower = entry(3 * k - 1, 3 * k - 4) &
               & - factor%vu(-1, k) * (factor%uv(k - 1) / factor%uu(k - 1))
            factor%lower(k) = t_lower / factor%pivot(k - 1)
            t_diag = t_diag - factor%lower(k) * factor%upper(k - 1)
         end if
         factor%pivot(k) = t_diag
         if (.not. (abs(t_diag) > 0.0_wp .and. abs(t_diag) <= huge(1.0_wp))) then
            info = k
            return
         end if
      end do
   contains
      pure real(wp) function entry(row, col)
         integer, intent(in) :: row, col
         entry = band(smu + row - col + 1, col)
      end function entry
   end subroutine factor_newton_matrix

   !> Whether M(row, col) of a region of m bodies may be nonzero in the band: u_k with
   !> u_k, v_k; v_k with u and v of bodies k - 1 .. k + 1; an energy or an impulse
   !> with itself (an impulse's other entries are outside the band).
   pure logical function entry_of_structure(m, row, col) result(inside)
      integer, intent(in) :: m, row, col
      integer :: kr, kc, sr, sc
      ! e of slot m and the impulses: with themselves alone
      if (row > 3 * m .or. col > 3 * m) then
         inside = row == col
         return
      end if
      ! body and kind (1 u, 2 v, 3 e) of the row and the column
      kr = (row + 2) / 3
      sr = row - 3 * (kr - 1)
      kc = (col + 2) / 3
      sc = col - 3 * (kc - 1)
      select case (sr)
      case (1)
         inside = kc == kr .and. sc <= 2
      case (2)
         inside = abs(kc - kr) <= 1 .and. sc <= 2 .and. kc <= m
      case default
         inside = row == col
      end select
   end function entry_of_structure

   !> Solve M z = r in place (x holds r on entry, z on return) with the factors of
   !> factor_newton_matrix for a region of m bodies.
   pure subroutine solve_newton(m, factor, x)
      integer, intent(in) :: m
      type(newton_factor), intent(in) :: factor
      real(wp), intent(inout) :: x(:)
      real(wp) :: g
      integer :: k, l
      ! the velocities' right-hand side with the displacements eliminated
      do k = 1, m
         g = x(3 * k - 1)
         do l = -1, 1
            if (k + l >= 1 .and. k + l <= m) g = g - factor%vu(l, k) &
               & * (x(3 * (k + l) - 2) / factor%uu(k + l))
         end do
         if (k > 1) g = g - factor%lower(k) * x(3 * k - 4)
         x(3 * k - 1) = g
      end do
      ! back substitution: the velocities, then each body's displacement and energy
      do k = m, 1, -1
         g = x(3 * k - 1)
         if (k < m) g = g - factor%upper(k) * x(3 * k + 2)
         x(3 * k - 1) = g / factor%pivot(k)
      end do
      do k = 1, m
         x(3 * k - 2) = (x(3 * k - 2) - factor%uv(k) * x(3 * k - 1)) / factor%uu(k)
         x(3 * k) = x(3 * k) / factor%ee(k)
      end do
      x(3 * m + 1) = x(3 * m + 1) / factor%ee(m + 1)
      ! the impulses, from their end body's solution
      x(impulse_index(m, 1)) = (x(impulse_index(m, 1)) - factor%wall_row(1, 1) * x(1) &
         & - factor%wall_row(2, 1) * x(2)) / factor%wall_diagonal(1)
      x(impulse_index(m, 2)) = (x(impulse_index(m, 2)) - factor%wall_row(1, 2) * x(3 * m - 2) &
         & - factor%wall_row(2, 2) * x(3 * m - 1)) / factor%wall_diagonal(2)
   end subroutine solve_newton

   !> dF/dt of slot j: F_x w + F_v w', w' from the accelerations dy (region_rhs)
   pure real(wp) function force_rate(region, j, dy, w, element)
      type(chain_region), intent(in) :: region
      integer, intent(in) :: j
      real(wp), intent(in) :: dy(:), w
      type(contact_force_type), intent(in) :: element
      real(wp) :: wdot
      select case (region%kind(j))
      case (slot_pair)
         wdot = dy(3 * j - 1) - dy(3 * j + 2)
      case (slot_left_wall)
         wdot = -dy(2)
      case (slot_right_wall)
         wdot = dy(3 * region%m - 1)
      case default
         wdot = 0.0_wp
      end select
      force_rate = element%dforce_dx * w + element%dforce_dv * wdot
   end function force_rate

end module hcimpact_cvode_chain_system
