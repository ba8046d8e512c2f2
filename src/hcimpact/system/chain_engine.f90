! SPDX-License-Identifier: Apache-2.0
!> The event-driven engine of a system of bodies on a line: exact where contacts are
!> isolated, an integrator (the CVODE component) for clusters, the switch decided with
!> bounds that cannot be wrong.
!>
!> Between contacts every body flies freely with the common acceleration g. A contact
!> of two bodies is a Hunt-Crossley impact of their relative motion (g cancels there),
!> with the effective mass and the approach speed: its closed forms (hcimpact_impact_model)
!> give its duration, the outgoing velocities and, through the time law, the state at
!> any instant. A contact with a wall is one too when g = 0 (with g /= 0 the force of
!> gravity acts inside the contact and no closed form exists: it is integrated).
!>
!> The decision. A contact of the pair (L, R) that starts at t_s is computed by the
!> closed forms only if no other contact can start involving L or R before it ends at
!> t_s + T. Inside a contact the velocity of each body is monotone (a contact only
!> pushes: the left body slows down, the right one speeds up), so on any interval
!> [ta, tb] the rate of a neighbouring gap is bounded below by its value at tb, and
!> gap(t) >= gap(ta) + min(0, rate(tb)) (tb - ta) (minus |g| (tb - ta) for a wall, whose
!> gap also feels gravity). The engine evaluates this bound on the whole contact and,
!> where it cannot prove the gap positive, on halves of it (to 30 levels), with the
!> exact states from the time law. A contact is called isolated only when the bound
!> proves every neighbouring gap positive throughout: the decision may send an isolated
!> contact to the integrator (when the bound is not sharp enough), never the reverse.
!> The same bound watches every gap next to a contact in progress.
!>
!> Clusters. When a contact is not isolated, its bodies, every body in contact with
!> them and every neighbour in a contact of its own form a contiguous region that an
!> integrator (`cluster_integrator`, implemented by the CVODE component) integrates
!> from that instant, with the states of the closed forms as initial values. The region
!> grows when a body outside touches it, and dissolves, back to the closed forms, when
!> no contact inside it is active or closing. Clusters apart are regions of their own,
!> each with its own integrator and clock, kept apart by at least one body in free
!> flight (a region that reaches another merges with it); the engine handles the
!> events of all of them and of the closed forms in the order of time (see
!> `cluster_integrator`). A cluster is hcimpact_err_domain with method_exact, and
!> hcimpact_err_unavailable without an integrator (the core alone).
!>
!> Coordinates: every body's displacement u from its initial position (q_i(0) of
!> hcimpact_chain_types) and its velocity; a gap is its initial value plus a difference
!> of displacements, which keeps the deformation's relative accuracy far from the
!> origin.
module hcimpact_chain_engine
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_positive_inf
   use hcimpact_kinds, only : wp, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_unavailable, &
      & hcimpact_err_no_convergence, hcimpact_err_domain, hcimpact_err_solver, &
      & hcimpact_err_out_of_memory
   use hcimpact_contact, only : contact_type, outcome_type
   use hcimpact_impact_model, only : impact, time_law
   use hcimpact_force_element, only : contact_force_type, contact_force_pair, &
      & contact_force_wall
   use hcimpact_power_force, only : power_law_potential, product_of, signed_product
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, contact_record, &
      & chain_result, chain_counters, chain_switch, check_chain, method_auto, method_exact, &
      & method_integrated, by_closed_forms, by_integration, by_both, max_message, &
      & kinetic_energy, energy_balance_error, momentum_balance_error, sum_in_range, &
      & not_below_zero, beyond_max_beta, say_beyond_max_beta, &
      & gravity_impulse, momentum, product_in_range, monitor_interval, no_memory_tail
   implicit none
   private

   public :: chain_engine, cluster_integrator, run_engine
   public :: slot_gap0, slot_law, slot_exists, body_state_at, engine_record, no_memory
   public :: capture_margin, rest_state, add_wall_impulse
   public :: advance_reached, advance_grow_left, advance_grow_right, advance_dissolved, &
      & advance_captured, advance_failed, advance_split

   !> What `advance` of an integrator ended with (split: the region goes on as the
   !> parts it gives, its other bodies fly freely again)
   integer, parameter :: advance_reached = 0, advance_grow_left = 1, &
      & advance_grow_right = 2, advance_dissolved = 3, advance_captured = 4, &
      & advance_failed = 5, advance_split = 6

   !> The message of a result whose energies leave the range of doubles
   character(len=*), parameter :: energies_beyond_range = "the energies of the system " &
      & // "leave the range of doubles (kinetic, elastic or gravitational energy, or " &
      & // "their balance, beyond 1.8e308 J)"

   !> Kinds of the event of a slot
   integer, parameter :: event_none = 0, event_start = 1, event_end = 2, event_cluster = 3

   !> Levels of halving in the bound of a gap
   integer, parameter :: max_depth = 30

   !> A body as the closed forms see it
   type :: body_state
      !> Free flight: displacement and velocity at the time t0
      real(wp) :: t0 = 0.0_wp, u0 = 0.0_wp, v0 = 0.0_wp
      !> The slot of the contact the body is in (closed forms), -1 if none
      integer :: busy = -1
      !> The integrated region the body is in (its index in engine%regions), 0 if none
      integer :: region = 0
   end type body_state

   !> A contact computed by the closed forms (the slot of its pair)
   type :: exact_contact
      logical :: active = .false.
      real(wp) :: t_start = nan, t_end = nan
      !> The impact: effective mass, law, approach speed; and its outcome
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      !> The impact the time law runs on, and the factors that carry its compression,
      !> velocity, time and force to this contact's (1: the same; `scaled_impact`)
      type(contact_type) :: law_contact
      real(wp) :: scale_x = 1.0_wp, scale_v = 1.0_wp, scale_t = 1.0_wp, scale_f = 1.0_wp
      !> Centre of mass of a pair at t_start: displacement and velocity; the velocities
      !> of its two bodies then
      real(wp) :: ucm0 = nan, vcm0 = nan, vl0 = nan, vr0 = nan
      !> Handed over to the integrator in the middle: what the closed forms had
      !> computed of its record so far (dissipated energy, peak force, deformation)
      logical :: handed = .false.
      real(wp) :: so_far_dissipated = 0.0_wp, so_far_peak = 0.0_wp, so_far_deformation = 0.0_wp
      !> Left by a region closed at the time touching_at (NaN: none) for a region begun
      !> at that instant: a touching pair that stopped touching by rounding only, and
      !> the start and approach speed of its contact (a contact that opens again began
      !> then; the integrator's own rule, hcimpact_cvode_chain)
      real(wp) :: touching_since = nan, touching_approach = nan, touching_at = nan
   end type exact_contact

   !> An integrator of a region of bodies (the CVODE component implements it); one
   !> object per region, made from the one given to `run_engine` (`mold`).
   !>
   !> The engine calls `begin` when a cluster forms (the region's bodies' states at
   !> engine%time are in engine%body, u0 and v0 at t0 = engine%time). The region then
   !> runs on its own clock: `time` is how far its contacts have been followed (and
   !> recorded), `next` the time at which the engine must call `advance` again (the end
   !> of its last step, or where a gap at its boundary closes within that step), and
   !> its state is known on [time, next] from the integrator's interpolant. The engine
   !> handles every event of the system in the order of time, so that no region has
   !> followed its contacts beyond the time of an event that could change it: at
   !> engine%time = next it calls `advance`, which follows the contacts up to `next`
   !> and reports what happened there (what), or steps on; `state_at` gives the state
   !> at a time in [time, next]; `finish` follows the contacts up to engine%time (<=
   !> next), writes the states back into engine%body (t0, u0, v0) and stops. While a
   !> region exists its bodies' contacts are the integrator's: it records them with
   !> `engine_record`.
   type, abstract :: cluster_integrator
      !> The region's bodies first .. last
      integer :: first = 0, last = 0
      !> Contacts followed up to `time`; `advance` is due at `next` (s)
      real(wp) :: time = 0.0_wp, next = 0.0_wp
      !> Whether `begin` has been called, and whether the region is at rest for good
      logical :: begun = .false., rested = .false.
      !> A first step to try (s; 0: the integrator's own choice), and the one its
      !> `finish` leaves for the region that grows from it (0: none). A region that
      !> grows over bodies touching it at rest, where no new impact begins, can go on
      !> with the step it had reached, where a start from scratch climbs back from a
      !> tiny step and order 1 (on a struck chain of touching beads, which grows as
      !> its wave sets beads moving, that doubled the steps); after a growth over a
      !> gap that closed, a new impact begins and the integrator chooses.
      real(wp) :: first_step = 0.0_wp, step_for_growth = 0.0_wp
      !> With advance_split: the first and last body of each part that stays
      !> integrated (parts(:, 1 .. n_parts), in order, apart by bodies in free flight)
      integer, allocatable :: parts(:, :)
      integer :: n_parts = 0
      !> An allocation of the integrator failed where it could not tell the engine
      !> (`state_at`, `finish`): the engine stops with hcimpact_err_out_of_memory
      logical :: out_of_memory = .false.
   contains
      procedure(integrator_begin), deferred :: begin
      procedure(integrator_advance), deferred :: advance
      procedure(integrator_state), deferred :: state_at
      procedure(integrator_finish), deferred :: finish
   end type cluster_integrator

   !> An integrated region: its integrator, which knows its bodies and its clock
   type :: region_entry
      class(cluster_integrator), allocatable :: integrator
   end type region_entry

   !> The state of a whole computation
   type :: chain_engine
      !> Number of bodies and the common acceleration
      integer :: n = 0
      real(wp) :: gravity = 0.0_wp
      type(chain_type) :: chain
      type(chain_options) :: options
      !> Current time
      real(wp) :: time = 0.0_wp
      type(body_state), allocatable :: body(:)
      !> Contacts by slot 0 .. n, and the event of each slot
      type(exact_contact), allocatable :: exact(:)
      real(wp), allocatable :: event_time(:)
      integer, allocatable :: event_kind(:)
      !> Indexed binary heap of the slots by event time
      integer, allocatable :: heap(:), heap_pos(:)
      integer :: heap_size = 0
      !> The integrated regions (each with an integrator of its own), apart from one
      !> another by at least one body in free flight
      type(region_entry), allocatable :: regions(:)
      integer :: n_regions = 0
      !> Records of the contacts that ended
      type(contact_record), allocatable :: records(:)
      integer :: n_records = 0
      integer(int64) :: n_contacts = 0
      !> Energy dissipated so far (J) and the counters
      real(wp) :: dissipated = 0.0_wp
      !> The impulses the walls (1 left, 2 right) have given the system so far, along
      !> the line (N s): the closed-form contacts that ended or were handed over, the
      !> integrated regions written back, a system settled at rest
      real(wp) :: wall_impulse(2) = 0.0_wp
      !> A system settled at rest on a wall: since when (s), and on which (1, 2; 0
      !> none), whose impulse then grows by the weight
      real(wp) :: settle_time = nan
      integer :: settle_side = 0
      type(chain_counters) :: counters
      type(chain_switch), allocatable :: switches(:)
      integer :: n_switches = 0
      !> Events processed (bounded by options%max_events)
      integer(int64) :: events = 0
      !> Rest on a wall under gravity
      logical :: rested = .false.
      real(wp) :: rest_time = nan
      !> Samples done so far
      integer :: next_sample = 1
      real(wp), allocatable :: sample_u(:, :), sample_v(:, :), sample_f(:, :)
      !> Initial positions q_i(0) and the failure message
      real(wp), allocatable :: q_initial(:)
      character(len=max_message) :: message = "success"
      !> An allocation failed (`no_memory`): the run stops with
      !> hcimpact_err_out_of_memory at the next pass of its loop, and what failed
      !> returned without a change it could not complete
      logical :: out_of_memory = .false.
      !> Memory held for the way out: `no_memory` frees it, so that what gfortran
      !> allocates unchecked while the engine is taken down (the finalisation of the
      !> regions and of the engine: a few small blocks) finds room
      real(wp), allocatable :: reserve(:)
   end type chain_engine

   abstract interface
      !> Start integrating the region self%first .. self%last at engine%time
      subroutine integrator_begin(self, engine, stat)
         import :: cluster_integrator, chain_engine
         class(cluster_integrator), intent(inout) :: self
         type(chain_engine), intent(inout) :: engine
         integer, intent(out) :: stat
      end subroutine integrator_begin
      !> At engine%time = self%next: follow the contacts up to it and report what
      !> happened there (what), else step on (never beyond t_end) and set self%next
      subroutine integrator_advance(self, engine, t_end, what, stat)
         import :: cluster_integrator, chain_engine, wp
         class(cluster_integrator), intent(inout) :: self
         type(chain_engine), intent(inout) :: engine
         real(wp), intent(in) :: t_end
         integer, intent(out) :: what, stat
      end subroutine integrator_advance
      !> Displacements and velocities of the region's bodies at the time t in
      !> [self%time, self%next]
      subroutine integrator_state(self, engine, t, u, v)
         import :: cluster_integrator, chain_engine, wp
         class(cluster_integrator), intent(inout) :: self
         type(chain_engine), intent(in) :: engine
         real(wp), intent(in) :: t
         real(wp), intent(out) :: u(:), v(:)
      end subroutine integrator_state
      !> Follow the contacts up to engine%time, write the region's states then into
      !> engine%body and stop
      subroutine integrator_finish(self, engine)
         import :: cluster_integrator, chain_engine
         class(cluster_integrator), intent(inout) :: self
         type(chain_engine), intent(inout) :: engine
      end subroutine integrator_finish
   end interface

contains

   ! =================================================================================
   ! The run
   ! =================================================================================

   !> Compute a system with the closed forms and, for clusters, the integrator given
   !> (none: clusters are hcimpact_err_unavailable; `refuse_cluster`). The result as in
   !> hcimpact_chain_types.
   subroutine run_engine(chain, options, result, stat, integrator)
      type(chain_type), intent(in) :: chain
      type(chain_options), intent(in) :: options
      type(chain_result), intent(out) :: result
      integer, intent(out) :: stat
      !> The integrator of clusters: each region gets an object of its type (mold)
      class(cluster_integrator), intent(in), optional :: integrator
      type(chain_engine) :: engine
      real(wp) :: t_event, t_end, t_sample, t_region, t_next
      integer :: what, slot, k, r
      integer(int64) :: passes, max_passes
      ! clusters dissolved in a row at the same time, and how many are tolerated
      integer :: idle_dissolves
      integer, parameter :: max_idle_dissolves = 100
      real(wp) :: t_dissolved
      logical :: until_rest

      call check_chain(chain, options, stat, result%message)
      if (stat /= hcimpact_ok) return
      if (options%method == method_integrated .and. .not. present(integrator)) then
         stat = hcimpact_err_unavailable
         result%message = "the integrated method needs the CVODE component"
         return
      end if
      call setup(engine, chain, options, stat)
      if (stat /= hcimpact_ok) then
         call fail(engine, result, stat)
         return
      end if
      until_rest = .not. options%t_end > 0.0_wp
      t_end = huge(1.0_wp)
      if (.not. until_rest) t_end = options%t_end

      if (options%method == method_integrated) then
         call form_region(engine, 1, engine%n, "the integrated method: the whole system", &
            & integrator)
      else
         call schedule_all(engine)
      end if

      ! every pass of the loop steps a region, handles an event, switches a region or
      ! takes a sample, each of which the options bound; a pass that does none of
      ! them is bounded here too
      passes = 0_int64
      idle_dissolves = 0
      t_dissolved = -huge(1.0_wp)
      max_passes = 4_int64 * (min(options%max_steps, 2_int64**40) &
         & + min(options%max_events, 2_int64**40)) + 1000_int64
      if (allocated(options%sample_times)) max_passes = max_passes &
         & + int(size(options%sample_times), int64)
      main: do
         do k = 1, engine%n_regions
            if (engine%regions(k)%integrator%out_of_memory) &
               & call no_memory(engine, "the work arrays of a cluster")
         end do
         if (engine%out_of_memory) exit main
         passes = passes + 1_int64
         if (passes > max_passes) then
            stat = hcimpact_err_no_convergence
            write(engine%message, '(a, i0, a, es11.3e3, a)') "no progress after ", &
               & max_passes, " passes of the event loop (at t = ", engine%time, " s)"
            exit main
         end if
         if (associated(options%monitor) .and. mod(passes, int(monitor_interval, int64)) &
            & == 0_int64) then
            if (options%monitor%poll(engine%time, engine%counters%steps, engine%events)) then
               stat = hcimpact_err_no_convergence
               write(engine%message, '(a, es11.3e3, a, i0, a, i0, a)') "stopped by the " &
                  & // "caller's monitor at t = ", engine%time, " s, after ", &
                  & engine%counters%steps, " steps and ", engine%events, " events"
               exit main
            end if
         end if
         do k = 1, engine%n_regions
            if (engine%regions(k)%integrator%begun) cycle
            call engine%regions(k)%integrator%begin(engine, stat)
            if (stat /= hcimpact_ok) exit main
            engine%regions(k)%integrator%begun = .true.
         end do
         ! at rest for good, and nothing else can happen: the region is the whole
         ! system (a body outside it, in free flight under gravity, would fall onto it)
         if (until_rest .and. engine%n_regions == 1 .and. engine%heap_size == 0) then
            if (whole_at_rest(engine%regions(1)%integrator, engine%n)) then
               call close_region(engine, 1)
               call settle_at_rest(engine, 1, engine%n)
               exit main
            end if
         end if
         if (engine%events >= options%max_events) then
            stat = hcimpact_err_no_convergence
            write(engine%message, '(a, i0, a)') "more than options%max_events = ", &
               & options%max_events, " contacts and switches: give t_end (a system " // &
               & "that never stops, e.g. bouncing without loss between walls)"
            exit main
         end if
         ! the next thing to happen: an event of a slot, a sample, the end, or a
         ! region's (ties: the region first, the lowest index of equal ones)
         t_event = huge(1.0_wp)
         if (engine%heap_size > 0) t_event = engine%event_time(engine%heap(1))
         t_sample = next_sample_time(engine)
         r = 0
         t_region = huge(1.0_wp)
         do k = 1, engine%n_regions
            if (engine%regions(k)%integrator%next < t_region) then
               r = k
               t_region = engine%regions(k)%integrator%next
            end if
         end do
         t_next = min(t_event, t_sample, t_end, t_region)
         if (t_next >= huge(1.0_wp)) then
            ! nothing more within the range of times; a gap still bound to close meets
            ! beyond it, where "no contact can happen again" would be false
            if (until_rest) call meeting_beyond_range(engine, stat)
            exit main
         end if
         engine%time = max(engine%time, t_next)
         if (t_sample <= t_next) then
            call take_samples(engine)
            cycle main
         end if
         if (t_end <= t_next) exit main
         if (r > 0 .and. t_region <= t_event) then
            call engine%regions(r)%integrator%advance(engine, t_end, what, stat)
            if (stat /= hcimpact_ok) exit main
            select case (what)
            case (advance_reached)
               ! at rest for good and settled to the tolerance before t_end: the rest
               ! of the decay is below what the integration resolves (it went on
               ! for minutes to the state at t_end = 1e300)
               if (.not. until_rest .and. engine%n_regions == 1 .and. &
                  & engine%heap_size == 0) then
                  if (settled(engine, engine%regions(1)%integrator)) then
                     call close_region(engine, 1)
                     call settle_at_rest(engine, 1, engine%n)
                  end if
               end if
            case (advance_grow_left, advance_grow_right)
               call grow_region(engine, r, what == advance_grow_left, integrator)
            case (advance_split)
               call split_region(engine, r, integrator)
            case (advance_dissolved)
               call dissolve_region(engine, r)
               ! a cluster that forms and dissolves again and again without the time
               ! advancing (seen at extreme scales) is no progress
               if (engine%time > t_dissolved) then
                  idle_dissolves = 0
               else
                  idle_dissolves = idle_dissolves + 1
                  if (idle_dissolves > max_idle_dissolves) then
                     stat = hcimpact_err_no_convergence
                     write(engine%message, '(a, i0, a, es11.3e3, a)') "a cluster formed and " &
                        & // "dissolved ", max_idle_dissolves, " times at t = ", engine%time, &
                        & " s without the time advancing"
                     exit main
                  end if
               end if
               t_dissolved = engine%time
            case (advance_captured)
               associate (it => engine%regions(r)%integrator)
                  it%rested = .true.
                  ! the system rests when the resting region is all of it (a stack at
                  ! rest while another body is still falling onto it is not)
                  if (.not. engine%rested .and. it%first == 1 .and. it%last == engine%n) then
                     engine%rested = .true.
                     engine%rest_time = engine%time
                  end if
               end associate
            case default
               stat = hcimpact_err_no_convergence
               exit main
            end select
            cycle main
         end if
         slot = engine%heap(1)
         engine%events = engine%events + 1
         call process_event(engine, slot, stat, integrator)
         if (stat /= hcimpact_ok) exit main
      end do main

      ! the regions still open are written back at the final time (or where the run
      ! failed)
      do while (engine%n_regions > 0)
         call close_region(engine, engine%n_regions)
      end do
      if (engine%out_of_memory) stat = hcimpact_err_out_of_memory
      if (stat /= hcimpact_ok) then
         call fail(engine, result, stat)
         return
      end if
      if (.not. until_rest) engine%time = max(engine%time, t_end)
      ! samples after the end: nothing more happens (until_rest), or none (t_end)
      if (until_rest) call take_samples(engine, all=.true.)
      if (engine%out_of_memory) then
         stat = hcimpact_err_out_of_memory
      else
         call fill_result(engine, result, stat)
      end if
      if (stat /= hcimpact_ok) then
         result = chain_result()
         call fail(engine, result, stat)
      end if
   end subroutine run_engine

   !> Whether the region of `it` is at rest for good and is the whole system of n bodies
   pure logical function whole_at_rest(it, n)
      class(cluster_integrator), intent(in) :: it
      integer, intent(in) :: n
      whole_at_rest = it%rested .and. it%first == 1 .and. it%last == n
   end function whole_at_rest

   !> Initial state: bodies at rest in their initial positions, the slots' events.
   !> hcimpact_err_out_of_memory (and engine%message) when the memory does not hold the
   !> arrays.
   subroutine setup(engine, chain, options, stat)
      type(chain_engine), intent(out) :: engine
      type(chain_type), intent(in) :: chain
      type(chain_options), intent(in) :: options
      integer, intent(out) :: stat
      integer :: n, i, nsamples, alloc_stat

      n = size(chain%mass)
      engine%n = n
      nsamples = 0
      if (allocated(options%sample_times)) nsamples = size(options%sample_times)
      ! (the copies of the system and the options field by field: an assignment of the
      ! types would allocate their arrays unchecked)
      allocate(engine%chain%mass(n), engine%chain%velocity(n), &
         & engine%chain%gap(n - 1), engine%chain%law(n - 1), &
         & engine%options%sample_times(nsamples), stat=alloc_stat)
      if (alloc_stat == 0) allocate(engine%body(n), engine%exact(0:n), &
         & engine%event_time(0:n), engine%event_kind(0:n), engine%heap(n + 1), &
         & engine%heap_pos(0:n), engine%q_initial(n), stat=alloc_stat)
      if (alloc_stat == 0) allocate(engine%records(min(max(options%max_contacts, 0), 1024)), &
         & engine%switches(16), stat=alloc_stat)
      if (alloc_stat == 0) allocate(engine%sample_u(n, nsamples), &
         & engine%sample_v(n, nsamples), engine%sample_f(0:n, nsamples), stat=alloc_stat)
      ! (64 KiB)
      if (alloc_stat == 0) allocate(engine%reserve(8192), stat=alloc_stat)
      if (alloc_stat /= 0) then
         call no_memory(engine, "the system's arrays")
         stat = hcimpact_err_out_of_memory
         return
      end if
      stat = hcimpact_ok
      engine%chain%mass(:) = chain%mass
      engine%chain%velocity(:) = chain%velocity
      ! (a single body's gaps and laws may be missing, or of any size: none is read)
      if (n > 1) then
         engine%chain%gap(:) = chain%gap
         engine%chain%law(:) = chain%law
      end if
      engine%chain%left_wall = chain%left_wall
      engine%chain%right_wall = chain%right_wall
      engine%chain%left_law = chain%left_law
      engine%chain%right_law = chain%right_law
      engine%chain%left_gap = chain%left_gap
      engine%chain%right_gap = chain%right_gap
      engine%chain%gravity = chain%gravity
      engine%options%t_end = options%t_end
      engine%options%rtol = options%rtol
      engine%options%method = options%method
      engine%options%integrator = options%integrator
      engine%options%max_steps = options%max_steps
      engine%options%max_contacts = options%max_contacts
      engine%options%max_events = options%max_events
      if (nsamples > 0) engine%options%sample_times(:) = options%sample_times
      if (.not. allocated(options%sample_times)) deallocate(engine%options%sample_times)
      engine%gravity = chain%gravity
      engine%time = 0.0_wp
      engine%q_initial(1) = 0.0_wp
      do i = 2, n
         engine%q_initial(i) = engine%q_initial(i - 1) + chain%gap(i - 1)
      end do
      do i = 1, n
         engine%body(i) = body_state(t0=0.0_wp, u0=0.0_wp, v0=chain%velocity(i))
      end do
      engine%event_time = huge(1.0_wp)
      engine%event_kind = event_none
      engine%heap_pos = 0
      engine%heap_size = 0
      ! (a sample time after t_end is never taken: NaN, not what the memory held)
      engine%sample_u = nan
      engine%sample_v = nan
      engine%sample_f = nan
      engine%next_sample = 1
   end subroutine setup

   ! =================================================================================
   ! Slots: their gaps, laws and events
   ! =================================================================================

   !> Whether slot s has a contact partner on both sides (walls may be absent)
   pure logical function slot_exists(engine, s)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      if (s == 0) then
         slot_exists = engine%chain%left_wall
      else if (s == engine%n) then
         slot_exists = engine%chain%right_wall
      else
         slot_exists = s > 0 .and. s < engine%n
      end if
   end function slot_exists

   !> The gap of slot s at zero displacements (the initial gap)
   pure real(wp) function slot_gap0(engine, s)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      if (s == 0) then
         slot_gap0 = engine%chain%left_gap
      else if (s == engine%n) then
         slot_gap0 = engine%chain%right_gap
      else
         slot_gap0 = engine%chain%gap(s)
      end if
   end function slot_gap0

   !> The contact law of slot s
   pure function slot_law(engine, s) result(law)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      type(contact_law) :: law
      if (s == 0) then
         law = engine%chain%left_law
      else if (s == engine%n) then
         law = engine%chain%right_law
      else
         law = engine%chain%law(s)
      end if
   end function slot_law

   !> Displacement and velocity of body i at the time t, from the closed forms (free
   !> flight or its contact's time law). Not for bodies of the region.
   subroutine body_state_at(engine, i, t, u, v)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: i
      real(wp), intent(in) :: t
      real(wp), intent(out) :: u, v
      real(wp) :: tau, x, xd, f, mass_l, mass_r, total, ucm, gt
      integer :: s
      s = engine%body(i)%busy
      if (s < 0) then
         ! u0 + (v0 + g tau/2) tau and v0 + g tau, +-Inf beyond the range of doubles
         ! without raising the overflow (a caller's Debug build traps on it)
         tau = t - engine%body(i)%t0
         gt = product_in_range(engine%gravity, tau)
         u = sum_in_range(engine%body(i)%u0, product_in_range(sum_in_range(engine%body(i)%v0, &
            & 0.5_wp * gt), tau))
         v = sum_in_range(engine%body(i)%v0, gt)
         return
      end if
      call contact_state(engine, s, t, x, xd, f)
      tau = t - engine%exact(s)%t_start
      if (s == 0) then
         ! left wall: x = -(gap_left + u_1)
         u = -(engine%chain%left_gap + x)
         v = -xd
      else if (s == engine%n) then
         u = engine%chain%right_gap + x
         v = xd
      else
         mass_l = engine%chain%mass(s)
         mass_r = engine%chain%mass(s + 1)
         total = mass_l + mass_r
         ucm = engine%exact(s)%ucm0 + (engine%exact(s)%vcm0 + 0.5_wp * (engine%gravity * tau)) &
            & * tau
         ! u_L - u_R = x + gap0
         if (i == s) then
            u = ucm + (mass_r / total) * (x + engine%chain%gap(s))
         else
            u = ucm - (mass_l / total) * (x + engine%chain%gap(s))
         end if
         v = pair_velocity(engine, s, i == s, xd, tau)
      end if
   end subroutine body_state_at

   !> (m_l a_l + m_r a_r) / (m_l + m_r), the centre of mass's displacement or velocity,
   !> with both masses scaled by the power of two that puts the larger in [1/2, 1):
   !> unscaled, the products underflow for small masses and speeds (1e-150 kg at
   !> 3e-174 m/s: a momentum of 3e-324 kg m/s, one digit, and both bodies of an
   !> elastic pair ended 1e-174 m/s off, with success) and overflow for large ones.
   pure real(wp) function mass_weighted(m_l, a_l, m_r, a_r) result(a)
      real(wp), intent(in) :: m_l, a_l, m_r, a_r
      real(wp) :: sl, sr
      integer :: e
      e = exponent(max(m_l, m_r))
      sl = scale(m_l, -e)
      sr = scale(m_r, -e)
      a = (sl * a_l + sr * a_r) / (sl + sr)
   end function mass_weighted

   !> The velocity of the left (or right) body of the exact pair contact s, its
   !> deformation rate being xd at tau after its start: that of the centre of mass
   !> plus (minus) m_R / M (m_L / M) times xd. Below the normal range the centre of
   !> mass's velocity loses the speed (half of 5e-324 m/s rounds to 0, and both bodies
   !> stopped): there the body's own velocity at the start plus the share of the change
   !> of xd, sums of subnormals that are exact.
   pure real(wp) function pair_velocity(engine, s, left, xd, tau) result(v)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      logical, intent(in) :: left
      real(wp), intent(in) :: xd, tau
      real(wp) :: share
      associate (c => engine%exact(s), m => engine%chain%mass)
         if (left) then
            share = m(s + 1) / (m(s) + m(s + 1))
         else
            share = -(m(s) / (m(s) + m(s + 1)))
         end if
         if (abs(c%vcm0) < 4.0_wp * tiny(1.0_wp)) then
            v = merge(c%vl0, c%vr0, left) + share * (xd - c%contact%velocity) &
               & + engine%gravity * tau
         else
            v = (c%vcm0 + engine%gravity * tau) + share * xd
         end if
      end associate
   end function pair_velocity

   !> Deformation, its rate and the force of the exact contact of slot s at the time t
   !> (from the time law; after its end x = 0, x' = -k V, F = 0)
   subroutine contact_state(engine, s, t, x, xd, f)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      real(wp), intent(in) :: t
      real(wp), intent(out) :: x, xd, f
      real(wp) :: tt(1), xx(1), vv(1), ff(1)
      integer :: stat
      tt(1) = t - engine%exact(s)%t_start
      ! (from t_end on, which t_start + the contact time rounds to: t_end - t_start may
      ! fall an ulp short of the contact time, and the time law there cost as much as
      ! the rest of a dilute system)
      if (t >= engine%exact(s)%t_end .or. tt(1) >= engine%exact(s)%outcome%contact_time) then
         x = 0.0_wp
         xd = engine%exact(s)%outcome%rebound_velocity
         f = 0.0_wp
         return
      end if
      ! at its start (what the time law gives for t <= 0, without its set-up and
      ! quadratures: the bound of every neighbouring gap starts here)
      if (.not. tt(1) > 0.0_wp) then
         x = 0.0_wp
         xd = engine%exact(s)%contact%velocity
         f = 0.0_wp
         return
      end if
      associate (c => engine%exact(s))
         tt(1) = tt(1) / c%scale_t
         call time_law(c%law_contact, tt, xx, vv, ff, stat)
         x = max(xx(1), 0.0_wp) * c%scale_x
         xd = vv(1) * c%scale_v
         f = ff(1) * c%scale_f
      end associate
      if (stat /= hcimpact_ok) then
         x = 0.0_wp
         xd = engine%exact(s)%contact%velocity
         f = 0.0_wp
      end if
   end subroutine contact_state

   !> The acceleration of slot s's gap while its bodies fly freely: 0 between two
   !> bodies, +-g against a wall.
   pure real(wp) function gap_acceleration(engine, s)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      gap_acceleration = 0.0_wp
      if (s == 0) gap_acceleration = engine%gravity
      if (s == engine%n) gap_acceleration = -engine%gravity
   end function gap_acceleration

   !> The gap of slot s and its rate of change at the time t (both bodies known to the
   !> closed forms); huge for a missing wall.
   subroutine slot_gap_at(engine, s, t, gap, rate)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      real(wp), intent(in) :: t
      real(wp), intent(out) :: gap, rate
      real(wp) :: ul, vl, ur, vr
      if (s == 0) then
         call body_state_at(engine, 1, t, ur, vr)
         gap = engine%chain%left_gap + ur
         rate = vr
      else if (s == engine%n) then
         call body_state_at(engine, engine%n, t, ul, vl)
         gap = engine%chain%right_gap - ul
         rate = -vl
      else
         call body_state_at(engine, s, t, ul, vl)
         call body_state_at(engine, s + 1, t, ur, vr)
         gap = engine%chain%gap(s) + (ur - ul)
         rate = vr - vl
      end if
   end subroutine slot_gap_at

   !> The bodies of slot s (0 for a wall)
   pure subroutine slot_bodies(engine, s, left, right)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      integer, intent(out) :: left, right
      left = s
      right = s + 1
      if (s == engine%n) right = 0
   end subroutine slot_bodies

   !> Schedule every slot (at the start).
   subroutine schedule_all(engine)
      type(chain_engine), intent(inout) :: engine
      integer :: s
      do s = 0, engine%n
         call schedule(engine, s)
      end do
   end subroutine schedule_all

   !> Compute the next event of slot s from the current state.
   subroutine schedule(engine, s)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      integer :: left, right
      real(wp) :: t_next, limit
      logical :: left_busy, right_busy

      if (s < 0 .or. s > engine%n) return
      t_next = huge(1.0_wp)
      engine%event_kind(s) = event_none
      call slot_bodies(engine, s, left, right)
      if (.not. slot_exists(engine, s)) then
         call heap_update(engine, s, t_next)
         return
      end if
      ! the regions' slots and their boundaries are watched by their integrators
      if (touches_region(engine, s)) then
         call heap_update(engine, s, t_next)
         return
      end if
      if (engine%exact(s)%active) then
         engine%event_kind(s) = event_end
         call heap_update(engine, s, engine%exact(s)%t_end)
         return
      end if
      left_busy = .false.
      right_busy = .false.
      limit = huge(1.0_wp)
      if (left > 0) then
         if (engine%body(left)%busy >= 0) then
            left_busy = .true.
            limit = min(limit, engine%exact(engine%body(left)%busy)%t_end)
         end if
      end if
      if (right > 0) then
         if (engine%body(right)%busy >= 0) then
            right_busy = .true.
            limit = min(limit, engine%exact(engine%body(right)%busy)%t_end)
         end if
      end if
      if (.not. (left_busy .or. right_busy)) then
         t_next = free_contact_time(engine, s)
         if (t_next < huge(1.0_wp)) engine%event_kind(s) = event_start
      else
         ! a body in a contact of its own: can this gap close before that contact ends?
         t_next = first_possible_touch(engine, s, engine%time, limit)
         if (t_next < huge(1.0_wp)) engine%event_kind(s) = event_cluster
      end if
      call heap_update(engine, s, t_next)
   end subroutine schedule

   !> When the gap of slot s closes, both bodies flying freely (huge if never).
   function free_contact_time(engine, s) result(t_next)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      real(wp) :: t_next
      real(wp) :: gap, rate, g, tau
      t_next = huge(1.0_wp)
      call slot_gap_at(engine, s, engine%time, gap, rate)
      g = gap_acceleration(engine, s)
      tau = first_zero(gap, rate, g)
      ! (a time beyond the range of doubles is never)
      if (tau <= huge(1.0_wp) - engine%time) t_next = engine%time + tau
   end function free_contact_time

   !> Where the run ends without t_end because nothing more happens within the range
   !> of doubles: a free gap that closes all the same (its meeting time is beyond
   !> 1.8e308 s) makes it hcimpact_err_domain, naming the pair.
   subroutine meeting_beyond_range(engine, stat)
      type(chain_engine), intent(inout) :: engine
      integer, intent(inout) :: stat
      real(wp) :: gap, rate, g
      integer :: s
      do s = 0, engine%n
         if (.not. slot_exists(engine, s)) cycle
         if (touches_region(engine, s)) cycle
         if (engine%exact(s)%active) cycle
         call slot_gap_at(engine, s, engine%time, gap, rate)
         g = gap_acceleration(engine, s)
         if (.not. (gap > 0.0_wp .and. closes_ever(gap, rate, g))) cycle
         stat = hcimpact_err_domain
         write(engine%message, '(a, i0, a, es11.3e3, a)') "pair ", s, " closes at t = ", &
            & engine%time, " s but meets beyond the range of doubles (after 1.8e308 s): " &
            & // "give t_end"
         return
      end do
   end subroutine meeting_beyond_range

   !> Whether gap + rate tau + g tau^2/2 (gap > 0) reaches 0 at some tau > 0, however
   !> late: closing at a constant rate, decelerated towards 0 by g, or closing faster
   !> than g opens it (rate^2 >= 2 g gap, compared by logarithms: the products leave
   !> the range of doubles).
   pure logical function closes_ever(gap, rate, g)
      real(wp), intent(in) :: gap, rate, g
      if (g < 0.0_wp) then
         closes_ever = .true.
      else if (g == 0.0_wp .or. .not. rate < 0.0_wp) then
         closes_ever = rate < 0.0_wp
      else
         closes_ever = 2.0_wp * log(abs(rate)) >= log(2.0_wp) + log(g) + log(gap)
      end if
   end function closes_ever

   !> The first tau >= 0 at which gap + rate tau + g tau^2/2 reaches 0 while
   !> decreasing (huge if never); a gap already closed and closing gives 0.
   pure function first_zero(gap, rate, g) result(tau)
      real(wp), intent(in) :: gap, rate, g
      real(wp) :: tau
      real(wp) :: disc, q, r1, r2, w, sc, gs, rs, gg
      tau = huge(1.0_wp)
      if (gap <= 0.0_wp .and. (rate < 0.0_wp .or. (rate == 0.0_wp .and. g < 0.0_wp))) then
         tau = 0.0_wp
         return
      end if
      if (g == 0.0_wp) then
         ! (the quotient without the overflow: a gap of 1e300 m closing at 1e-10 m/s)
         if (rate < 0.0_wp .and. gap > 0.0_wp) tau = quotient_or_huge(gap, -rate)
         return
      end if
      ! g tau^2/2 + rate tau + gap = 0 in the stable form: roots q/g and 2 gap/q. The
      ! discriminant rate^2 - 2 g gap is formed scaled by s^2, s the larger of |rate|
      ! and w = sqrt(2 |g gap|): unscaled, it underflows to 0 for a gravity of 5e-324
      ! (a root of 6e160 s lost) or overflows for speeds beyond 1e154 m/s
      ! (2 |g| formed only where it is a double: sqrt(2) sqrt(|g|) above)
      if (abs(g) <= 0.5_wp * huge(1.0_wp)) then
         w = sqrt(2.0_wp * abs(g)) * sqrt(abs(gap))
      else
         w = (sqrt(2.0_wp) * sqrt(abs(g))) * sqrt(abs(gap))
      end if
      sc = max(abs(rate), w)
      if (.not. sc > 0.0_wp) return
      ! q is up to 2.5 s and the tests below form g q / g: where s is beyond huge / 16
      ! (speeds of 1e307 m/s) the same roots come from the equation divided by 32
      ! (q overflowed to an infinity there, which the fuzzer found)
      gs = gap
      rs = rate
      gg = g
      if (sc > 0.0625_wp * huge(1.0_wp)) then
         gs = gap / 32.0_wp
         rs = rate / 32.0_wp
         gg = g / 32.0_wp
         w = w / 32.0_wp
         sc = sc / 32.0_wp
      end if
      disc = (rs / sc)**2 - sign(1.0_wp, gg) * sign(1.0_wp, gs) * (w / sc)**2
      if (disc < 0.0_wp) return
      q = -(rs + sign(sc * sqrt(disc), rs))
      if (q == 0.0_wp) return
      ! a root beyond the range of doubles is never reached: huge, formed without
      ! the overflow (q / g for a gravity of 5e-324 trapped in the Debug build)
      r1 = quotient_or_huge(q, gg)
      r2 = quotient_or_huge(gs, q)
      r2 = sign(2.0_wp * min(abs(r2), 0.5_wp * huge(1.0_wp)), r2)
      ! the smallest positive root where the gap decreases (g tau + rate < 0)
      if (r1 > 0.0_wp .and. gg * r1 + rs < 0.0_wp) tau = min(tau, r1)
      if (r2 > 0.0_wp .and. gg * r2 + rs < 0.0_wp) tau = min(tau, r2)
   end function first_zero

   !> a / b for b /= 0, or +-huge where the quotient may be beyond the range of doubles
   !> (from the binary exponents: also for some within a factor 2 of its top), without
   !> raising the overflow (gfortran's binary exponent of a subnormal is the value's,
   !> which the bound needs); NaN for a NaN, +-huge or 0 for an infinity (whose binary
   !> exponent is huge(0): the difference is formed in 64 bits)
   elemental function quotient_or_huge(a, b) result(y)
      real(wp), intent(in) :: a, b
      real(wp) :: y
      if (ieee_is_nan(a) .or. ieee_is_nan(b)) then
         y = a + b
      else if (a == 0.0_wp) then
         y = 0.0_wp
      else if (int(exponent(a), int64) - exponent(b) < maxexponent(1.0_wp)) then
         y = a / b
      else if (int(exponent(a), int64) - exponent(b) == maxexponent(1.0_wp) .and. &
         & abs(fraction(a)) < abs(fraction(b))) then
         ! within a factor 2 of the top: the quotient of the fractions (in (1/2, 1),
         ! rounded once) times 2^maxexponent is a double (a meeting at 1.4e308 s was lost)
         y = scale(fraction(a) / fraction(b), maxexponent(1.0_wp))
      else
         y = sign(huge(1.0_wp), a) * sign(1.0_wp, b)
      end if
   end function quotient_or_huge

   !> The first time in [t_from, t_to] at which the bound cannot exclude that the gap
   !> of slot s is closed (huge when the gap provably stays open on the interval).
   !> Subintervals are examined from the left, each halved where its bound is not
   !> conclusive, down to max_depth halvings and within max_bounds evaluations of the
   !> bound in all (each needs the states at two times, from the time law); where the
   !> budget runs out the answer is the start of the subinterval that was not settled,
   !> which can only make a contact go to the integrator, never the reverse.
   function first_possible_touch(engine, s, t_from, t_to) result(t_touch)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      real(wp), intent(in) :: t_from, t_to
      real(wp) :: t_touch
      integer, parameter :: max_bounds = 64
      real(wp) :: ta(max_depth + 1), tb(max_depth + 1)
      integer :: depth(max_depth + 1)
      real(wp) :: gap_a, rate_a, gap_b, rate_b, rate_low, tm
      integer :: top, evaluations, level

      t_touch = huge(1.0_wp)
      if (.not. t_to > t_from) return
      if (t_to >= huge(1.0_wp)) then
         t_touch = t_from
         return
      end if
      ! a stack of the subintervals still to settle, the leftmost on top
      top = 1
      ta(1) = t_from
      tb(1) = t_to
      depth(1) = 0
      evaluations = 0
      do while (top > 0)
         evaluations = evaluations + 1
         call slot_gap_at(engine, s, ta(top), gap_a, rate_a)
         if (.not. gap_a > 0.0_wp .or. evaluations > max_bounds) then
            t_touch = ta(top)
            return
         end if
         call slot_gap_at(engine, s, tb(top), gap_b, rate_b)
         rate_low = rate_b
         ! a wall's gap also feels gravity, either way
         if (s == 0 .or. s == engine%n) rate_low = rate_low - abs(engine%gravity) &
            & * (tb(top) - ta(top))
         if (gap_a + min(0.0_wp, rate_low) * (tb(top) - ta(top)) > 0.0_wp) then
            ! settled: open throughout
            top = top - 1
            cycle
         end if
         level = depth(top)
         tm = 0.5_wp * (ta(top) + tb(top))
         if (level >= max_depth .or. .not. (tm > ta(top) .and. tm < tb(top))) then
            t_touch = ta(top)
            return
         end if
         ! replace by its halves, the left one on top
         tb(top + 1) = tm
         ta(top + 1) = ta(top)
         ta(top) = tm
         depth(top) = level + 1
         depth(top + 1) = level + 1
         top = top + 1
      end do
   end function first_possible_touch

   ! =================================================================================
   ! Events
   ! =================================================================================

   !> Whether a cluster that forms now (why) can be integrated: hcimpact_ok, or
   !> hcimpact_err_domain with method exact (the closed forms cannot compute contacts
   !> that overlap: the system is outside that method's domain), or
   !> hcimpact_err_unavailable in a build without the CVODE component.
   subroutine refuse_cluster(engine, why, have_integrator, stat)
      type(chain_engine), intent(inout) :: engine
      character(len=*), intent(in) :: why
      logical, intent(in) :: have_integrator
      integer, intent(out) :: stat
      stat = hcimpact_ok
      if (engine%options%method == method_exact) then
         stat = hcimpact_err_domain
         write(engine%message, '(a, es11.3e3, a)') "method exact: at t = ", engine%time, &
            & " s a cluster forms (" // trim(why) // "), contacts that overlap, which " &
            & // "the closed forms do not compute (method auto or integrated)"
      else if (.not. have_integrator) then
         stat = hcimpact_err_unavailable
         engine%message = "a cluster forms (" // trim(why) // &
            & "): it needs the CVODE component (method auto or integrated)"
      end if
   end subroutine refuse_cluster

   !> Process the event of slot s at its time.
   subroutine process_event(engine, s, stat, integrator)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      integer, intent(out) :: stat
      !> The integrator of clusters (absent: the closed forms alone)
      class(cluster_integrator), intent(in), optional :: integrator
      character(len=max_message) :: why
      integer :: neighbour
      logical :: have_integrator

      have_integrator = present(integrator)

      stat = hcimpact_ok
      engine%time = max(engine%time, engine%event_time(s))
      select case (engine%event_kind(s))
      case (event_end)
         call end_exact(engine, s)
      case (event_start)
         call start_contact(engine, s, why, neighbour, stat)
         if (stat /= hcimpact_ok) return
         if (len_trim(why) > 0) then
            call refuse_cluster(engine, why, have_integrator, stat)
            if (stat /= hcimpact_ok) return
            call form_cluster(engine, s, why, neighbour, integrator)
         end if
      case (event_cluster)
         call compose(why, "the gap of pair ", s, &
            & " may close while a neighbouring contact goes on")
         call refuse_cluster(engine, why, have_integrator, stat)
         if (stat /= hcimpact_ok) return
         call form_cluster(engine, s, why, -1, integrator)
      case default
         call heap_update(engine, s, huge(1.0_wp))
      end select
   end subroutine process_event

   !> A contact of slot s starts now: by the closed forms if it is isolated (why
   !> empty), else why says what prevents it; hcimpact_err_domain (stat, with the
   !> engine's message) where its b V is beyond the model's domain.
   subroutine start_contact(engine, s, why, neighbour, stat)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      character(len=max_message), intent(out) :: why
      !> The neighbouring slot that may close during the contact (-1: none)
      integer, intent(out) :: neighbour
      integer, intent(out) :: stat
      integer :: left, right, side, impact_stat
      real(wp) :: gap, rate, mass, ul, vl, ur, vr
      type(contact_law) :: law
      type(exact_contact) :: c
      logical :: pressed

      why = ""
      neighbour = -1
      stat = hcimpact_ok
      call slot_bodies(engine, s, left, right)
      call slot_gap_at(engine, s, engine%time, gap, rate)
      ! touching a wall without speed, gravity pushing the body into it: a contact
      ! starts (with the rate 0 alone it was taken as grazing, rescheduled at the
      ! same instant, and the run never advanced: a ball released on a floor)
      pressed = rate == 0.0_wp .and. ((s == 0 .and. engine%gravity < 0.0_wp) .or. &
         & (s == engine%n .and. engine%gravity > 0.0_wp))
      if (.not. (rate < 0.0_wp .or. pressed)) then
         ! grazing: nothing happens
         call schedule(engine, s)
         return
      end if
      law = slot_law(engine, s)
      ! (neither the closed forms nor CVODE compute it: said here, not as a cluster
      ! whose integration fails)
      if (beyond_max_beta(law%damping, rate)) then
         stat = hcimpact_err_domain
         call say_beyond_max_beta(engine%message, s, engine%time, law%damping, rate)
         return
      end if
      if (pressed) then
         call compose(why, "a body pressed on a wall (pair ", s, &
            & ") by gravity has no closed form")
         return
      end if
      if (s == 0) then
         mass = engine%chain%mass(1)
      else if (s == engine%n) then
         mass = engine%chain%mass(engine%n)
      else
         mass = engine%chain%mass(left) * (engine%chain%mass(right) &
            & / (engine%chain%mass(left) + engine%chain%mass(right)))
      end if
      ! a neighbour in a region: the contact joins it
      do side = -1, 1, 2
         if (s + side >= 0 .and. s + side <= engine%n) then
            if (touches_region(engine, s + side)) then
               call compose(why, "pair ", s, " starts next to an integrated cluster")
               return
            end if
         end if
      end do
      c%active = .true.
      c%t_start = engine%time
      c%contact = contact_type(mass=mass, stiffness=law%stiffness, exponent=law%exponent, &
         & damping=law%damping, velocity=-rate)
      call scaled_impact(c, impact_stat)
      ! a compression, duration or force beyond the range of doubles in any units: the
      ! integration does not resolve it either (CVODE failed, crawled for hours, or, at
      ! the scales where it does not notice, ended with success and a wrong rebound)
      if (impact_stat == hcimpact_err_domain) then
         stat = hcimpact_err_domain
         write(engine%message, '(a, i0, a, es11.3e3, a)') "pair ", s, " at t = ", &
            & engine%time, " s: the contact's compression, duration or force leaves " &
            & // "the range of doubles"
         return
      end if
      if (impact_stat /= hcimpact_ok) then
         call compose(why, "the closed forms cannot compute pair ", s, &
            & " (status of the one impact)")
         return
      end if
      ! against a wall under gravity: the closed forms (without gravity) only where
      ! gravity changes nothing within the contact, its speed g T against the approach
      ! speed (and its displacement g T^2/2 against v T) below an eighth of rounding
      if ((s == 0 .or. s == engine%n) .and. engine%gravity /= 0.0_wp) then
         if (.not. abs(engine%gravity) * c%outcome%contact_time <= &
            & 0.125_wp * epsilon(1.0_wp) * abs(rate)) then
            call compose(why, "a wall contact (pair ", s, &
               & ") under gravity has no closed form")
            return
         end if
      end if
      c%t_end = c%t_start + c%outcome%contact_time
      if (s > 0 .and. s < engine%n) then
         call body_state_at(engine, left, engine%time, ul, vl)
         call body_state_at(engine, right, engine%time, ur, vr)
         c%ucm0 = mass_weighted(engine%chain%mass(left), ul, engine%chain%mass(right), ur)
         c%vcm0 = mass_weighted(engine%chain%mass(left), vl, engine%chain%mass(right), vr)
         c%vl0 = vl
         c%vr0 = vr
      end if
      ! tentatively in contact, then the neighbouring gaps over its duration
      call occupy(engine, s, c)
      if (.not. isolated(engine, s, why, neighbour)) then
         call release(engine, s)
         return
      end if
      engine%counters%closed_form_contacts = engine%counters%closed_form_contacts + 1
      call schedule(engine, s)
      call schedule(engine, s - 1)
      call schedule(engine, s + 1)
   end subroutine start_contact

   !> The outcome of the impact c%contact, and the impact its time law runs on. Where
   !> the closed forms refuse it for its scale, the same impact is computed in units
   !> where it is a double and carried back (the outcome depends on b V alone once
   !> the scales are taken out; p = 1 / (n + 1)):
   !> - an approach speed V below 1 m/s (below about 1e-260 m/s its peak force leaves
   !>   the normal range): at 1 m/s with the damping b V, compression scaled as
   !>   V^(2p), velocity as V, time as V^((1 - n) p) and force as V^(2 n p), each a
   !>   power of V (the compression, the duration and the force carry the rounding of
   !>   the exponent, amplified by |ln V|: about 1e-13 relative at 1e-300 m/s);
   !> - else, or where that is refused too: the unit impact (m = c = V = 1, b V),
   !>   compression scaled by L = (m V^2 / c)^p, time by L / V, force by c L^n,
   !>   from logarithms (1e-13 relative where they are near 700): masses and
   !>   stiffnesses 600 decades apart (1e-300 kg on 1e300 N/m, a contact of 3e-300
   !>   s) were refused, and integrated at steps of 1e-300 s for hours.
   !> The velocities are the closed forms' in both. The peak force may be subnormal,
   !> or 0 where it is below the range; a duration beyond the range is refused.
   subroutine scaled_impact(c, stat)
      type(exact_contact), intent(inout) :: c
      integer, intent(out) :: stat
      type(contact_type) :: unit
      type(outcome_type) :: o
      real(wp) :: v, n, lx, lt, lf
      ! (less a margin for the products with the unit impact's outcome)
      real(wp), parameter :: log_huge = 700.0_wp
      c%law_contact = c%contact
      c%scale_x = 1.0_wp
      c%scale_v = 1.0_wp
      c%scale_t = 1.0_wp
      c%scale_f = 1.0_wp
      call impact(c%contact, c%outcome, stat)
      if (stat /= hcimpact_err_domain) return
      v = c%contact%velocity
      n = c%contact%exponent
      ! (b V is at most max_beta here: start_contact refused more)
      unit = c%contact
      unit%velocity = 1.0_wp
      unit%damping = c%contact%damping * v
      ! (the powers of V only where each is a normal double, told from their logarithms:
      ! V^(2p) of 1e-200 m/s at n = 0.2 underflowed to 0, and a compression of 3e-84 m
      ! came out 0; V^((1 - n) p) overflows for large n)
      lx = 2.0_wp / (n + 1.0_wp) * log(v)
      lt = (1.0_wp - n) / (n + 1.0_wp) * log(v)
      lf = 2.0_wp * n / (n + 1.0_wp) * log(v)
      if (v < 1.0_wp .and. min(lx, lt, lf) > log(tiny(1.0_wp)) .and. &
         & max(lx, lt, lf) < log_huge) then
         call impact(unit, o, stat)
         if (stat == hcimpact_ok) then
            ! (the exponents each rounded once; each scale formed directly)
            if (lt + log(o%contact_time) > log_huge) then
               stat = hcimpact_err_domain
               return
            end if
            call carry_back(c, unit, o, v, v**(2.0_wp / (n + 1.0_wp)), &
               & v**((1.0_wp - n) / (n + 1.0_wp)), v**(2.0_wp * n / (n + 1.0_wp)))
            return
         end if
      end if
      unit%mass = 1.0_wp
      unit%stiffness = 1.0_wp
      call impact(unit, o, stat)
      if (stat /= hcimpact_ok) then
         stat = hcimpact_err_domain
         return
      end if
      lx = (log(c%contact%mass) + 2.0_wp * log(v) - log(c%contact%stiffness)) / (n + 1.0_wp)
      lt = lx - log(v)
      lf = log(c%contact%stiffness) + n * lx
      ! (the scales themselves are doubles too: the states inside the contact are the
      ! unit impact's times them; a compression of 1e300 m at c = 1e-100 N/m^0.2 had
      ! the scale e^767 and came out +Inf with success)
      if (lt + log(o%contact_time) > log_huge .or. lx + log(o%max_compression) > log_huge &
         & .or. lf + log(o%peak_force) > log_huge .or. max(lx, lt, lf) > log_huge) then
         stat = hcimpact_err_domain
         return
      end if
      call carry_back(c, unit, o, v, exp(max(-log_huge - 50.0_wp, lx)), &
         & exp(max(-log_huge - 50.0_wp, lt)), exp(max(-log_huge - 50.0_wp, lf)))
      ! the outcome's own values from logarithms: a scale below the normal range keeps
      ! few digits where the value it gives is a normal double
      c%outcome%max_compression = scaled_log(lx, o%max_compression)
      c%outcome%compression_at_peak_force = scaled_log(lx, o%compression_at_peak_force)
      c%outcome%peak_force = scaled_log(lf, o%peak_force)
      c%outcome%time_at_peak_force = scaled_log(lt, o%time_at_peak_force)
      c%outcome%compression_time = scaled_log(lt, o%compression_time)
      c%outcome%contact_time = scaled_log(lt, o%contact_time)
   contains
      !> e^l y for y >= 0 (0 stays 0), without forming e^l
      pure real(wp) function scaled_log(l, y)
         real(wp), intent(in) :: l, y
         scaled_log = 0.0_wp
         if (y > 0.0_wp) scaled_log = exp(max(-log_huge - 50.0_wp, l + log(y)))
      end function scaled_log
   end subroutine scaled_impact

   !> The outcome o of the impact `unit` in the units of c%contact: velocities times
   !> sv, compressions times sx, times times st, forces times sf (`scaled_impact`).
   pure subroutine carry_back(c, unit, o, sv, sx, st, sf)
      type(exact_contact), intent(inout) :: c
      type(contact_type), intent(in) :: unit
      type(outcome_type), intent(in) :: o
      real(wp), intent(in) :: sv, sx, st, sf
      c%law_contact = unit
      c%scale_v = sv
      c%scale_x = sx
      c%scale_t = st
      c%scale_f = sf
      c%outcome = o
      c%outcome%rebound_velocity = o%rebound_velocity * sv
      c%outcome%max_compression = o%max_compression * sx
      c%outcome%compression_at_peak_force = o%compression_at_peak_force * sx
      c%outcome%peak_force = o%peak_force * sf
      c%outcome%time_at_peak_force = o%time_at_peak_force * st
      c%outcome%compression_time = o%compression_time * st
      c%outcome%contact_time = o%contact_time * st
   end subroutine carry_back

   !> Whether slot s is inside a region or at its boundary (one of its bodies is
   !> integrated)
   pure logical function touches_region(engine, s)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      touches_region = .false.
      if (s >= 1) touches_region = engine%body(s)%region > 0
      if (s + 1 <= engine%n) touches_region = touches_region .or. &
         & engine%body(s + 1)%region > 0
   end function touches_region

   !> Put the bodies of slot s into the exact contact c.
   subroutine occupy(engine, s, c)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      type(exact_contact), intent(in) :: c
      integer :: left, right
      real(wp) :: u, v
      call slot_bodies(engine, s, left, right)
      ! free bodies are re-referenced at the start (their flight so far)
      if (left > 0) then
         call body_state_at(engine, left, c%t_start, u, v)
         engine%body(left) = body_state(t0=c%t_start, u0=u, v0=v, busy=-1)
      end if
      if (right > 0) then
         call body_state_at(engine, right, c%t_start, u, v)
         engine%body(right) = body_state(t0=c%t_start, u0=u, v0=v, busy=-1)
      end if
      engine%exact(s) = c
      if (left > 0) engine%body(left)%busy = s
      if (right > 0) engine%body(right)%busy = s
   end subroutine occupy

   !> Undo `occupy` (the bodies fly freely from the start of the contact).
   subroutine release(engine, s)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      integer :: left, right
      call slot_bodies(engine, s, left, right)
      if (left > 0) engine%body(left)%busy = -1
      if (right > 0) engine%body(right)%busy = -1
      engine%exact(s)%active = .false.
   end subroutine release

   !> Whether the exact contact of slot s (occupied) is isolated: every neighbouring
   !> gap provably open until it ends.
   function isolated(engine, s, why, neighbour) result(ok)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      character(len=max_message), intent(out) :: why
      integer, intent(out) :: neighbour
      logical :: ok
      integer :: side, other
      real(wp) :: t_touch
      ok = .true.
      why = ""
      neighbour = -1
      do side = -1, 1, 2
         other = s + side
         if (other < 0 .or. other > engine%n) cycle
         if (.not. slot_exists(engine, other)) cycle
         t_touch = first_possible_touch(engine, other, engine%time, engine%exact(s)%t_end)
         if (t_touch < huge(1.0_wp)) then
            ok = .false.
            neighbour = other
            call compose(why, "pair ", other, " may touch while pair ", s, &
               & " is in contact")
            return
         end if
      end do
   end function isolated

   !> Whether the balances of an integrated run (energy_error finite) are off beyond
   !> any tolerance: by more than max(1/2, 1e4 rtol) of their scales. The integration
   !> can go wrong without CVODE noticing, at scales it does not resolve: a body of
   !> 1e300 kg on a wall of 1e100 N/m at 1e-300 m/s ended with 5e18 times its energy,
   !> one of 2.7e158 kg at 4.9e-267 m/s (its energy below the doubles) rebounded at
   !> 1.9 times its speed, a momentum balance off by its whole scale; both with
   !> success. The closed forms keep the balances to rounding, an integration to a few
   !> hundred rtol.
   pure logical function gross_balance(result, rtol) result(gross)
      type(chain_result), intent(in) :: result
      real(wp), intent(in) :: rtol
      real(wp) :: limit
      limit = max(0.5_wp, 1.0e4_wp * rtol)
      gross = result%energy_error > limit
      ! (a NaN compared raises the invalid exception: no balance without its terms)
      if (.not. ieee_is_nan(result%momentum_error)) gross = gross .or. &
         & result%momentum_error > limit
   end function gross_balance

   !> The exact contact of slot s ends now.
   subroutine end_exact(engine, s)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      integer :: left, right
      real(wp) :: t_end, u, tau, ucm, total, xd
      type(contact_record) :: r

      t_end = engine%exact(s)%t_end
      call slot_bodies(engine, s, left, right)
      xd = engine%exact(s)%outcome%rebound_velocity
      tau = t_end - engine%exact(s)%t_start
      if (s == 0) then
         engine%body(1) = body_state(t0=t_end, u0=-engine%chain%left_gap, v0=-xd)
      else if (s == engine%n) then
         engine%body(engine%n) = body_state(t0=t_end, u0=engine%chain%right_gap, v0=xd)
      else
         total = engine%chain%mass(left) + engine%chain%mass(right)
         ucm = engine%exact(s)%ucm0 + (engine%exact(s)%vcm0 + 0.5_wp * (engine%gravity * tau)) &
            & * tau
         u = ucm + (engine%chain%mass(right) / total) * engine%chain%gap(s)
         engine%body(left) = body_state(t0=t_end, u0=u, v0=pair_velocity(engine, s, &
            & .true., xd, tau))
         u = ucm - (engine%chain%mass(left) / total) * engine%chain%gap(s)
         engine%body(right) = body_state(t0=t_end, u0=u, v0=pair_velocity(engine, s, &
            & .false., xd, tau))
      end if
      r%pair = s
      r%t_start = engine%exact(s)%t_start
      r%t_end = t_end
      r%approach_speed = engine%exact(s)%contact%velocity
      r%separation_speed = -xd
      r%peak_force = engine%exact(s)%outcome%peak_force
      r%max_deformation = engine%exact(s)%outcome%max_compression
      r%dissipated = kinetic_energy(engine%exact(s)%contact%mass, &
         & engine%exact(s)%contact%velocity) * engine%exact(s)%outcome%energy_loss_ratio
      r%method = by_closed_forms
      call engine_record(engine, r)
      call add_exact_wall_impulse(engine, s, xd)
      engine%exact(s)%active = .false.
      engine%time = max(engine%time, t_end)
      call schedule(engine, s)
      call schedule(engine, s - 1)
      call schedule(engine, s + 1)
   end subroutine end_exact

   !> Keep a finished contact (counted always, recorded up to options%max_contacts)
   !> and its dissipated energy.
   subroutine engine_record(engine, r)
      type(chain_engine), intent(inout) :: engine
      type(contact_record), intent(in) :: r
      type(contact_record), allocatable :: grown(:)
      integer :: alloc_stat
      engine%n_contacts = engine%n_contacts + 1
      if (ieee_is_finite(r%dissipated)) engine%dissipated = engine%dissipated + r%dissipated
      if (engine%n_records >= engine%options%max_contacts) return
      if (engine%n_records == size(engine%records)) then
         allocate(grown(min(2 * max(size(engine%records), 8), engine%options%max_contacts)), &
            & stat=alloc_stat)
         if (alloc_stat /= 0) then
            call no_memory(engine, "the list of contacts")
            return
         end if
         grown(:engine%n_records) = engine%records(:engine%n_records)
         call move_alloc(grown, engine%records)
      end if
      engine%n_records = engine%n_records + 1
      engine%records(engine%n_records) = r
   end subroutine engine_record

   ! =================================================================================
   ! The integrated regions
   ! =================================================================================

   !> A cluster forms at slot s now: a region around it (with every region it
   !> reaches).
   subroutine form_cluster(engine, s, why, neighbour, integrator)
      type(chain_engine), intent(inout) :: engine
      !> The slot whose contact cannot be computed alone
      integer, intent(in) :: s
      character(len=*), intent(in) :: why
      !> A neighbouring slot that may close during it (-1: none)
      integer, intent(in) :: neighbour
      !> The integrator of clusters (each region gets an object of its type)
      class(cluster_integrator), intent(in) :: integrator
      integer :: left, right, first, last
      call slot_bodies(engine, s, left, right)
      first = left
      last = right
      if (first == 0) first = 1
      if (last == 0) last = engine%n
      if (neighbour >= 0) then
         call slot_bodies(engine, neighbour, left, right)
         if (left > 0) first = min(first, left)
         if (right > 0) last = max(last, right)
      end if
      call form_region(engine, first, last, why, integrator)
   end subroutine form_cluster

   !> Make bodies first .. last a region, at the current time, with their closed-form
   !> states: widened to whole contacts and busy or touching neighbours, and merged
   !> with every region it overlaps or borders (regions stay apart by at least one
   !> body in free flight: the body next to a region's end must fly freely, its
   !> integrator watches that gap). A region merged is written back first.
   subroutine form_region(engine, first, last, why, integrator, step_hint)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: first, last
      character(len=*), intent(in) :: why
      !> The integrator of clusters (the new region gets an object of its type)
      class(cluster_integrator), intent(in) :: integrator
      !> A first step for its integrator to try (s; grow_region), if any
      real(wp), intent(in), optional :: step_hint
      type(region_entry), allocatable :: grown(:)
      integer :: a, b, i, s, k, alloc_stat
      real(wp) :: u, v, hint
      logical :: merged

      a = first
      b = last
      merged = .false.
      hint = 0.0_wp
      if (present(step_hint)) hint = step_hint
      ! the regions within the range or next to it
      i = max(a - 1, 1)
      do while (i <= min(b + 1, engine%n))
         call absorb_region(engine, i, a, b, merged)
         i = i + 1
      end do
      ! the whole contacts of the bodies at the ends (a body inside has its partner
      ! inside), neighbours in a contact of their own or touching (a touching pair at
      ! rest has a gap of exactly 0, whose closing no sign change can show), and
      ! regions reached on the way: each step adds a body or a region, so the widening
      ! costs what it adds
      do
         if (a > 1) then
            if (engine%body(a - 1)%region > 0) then
               call absorb_region(engine, a - 1, a, b, merged)
               cycle
            end if
            if (engine%body(a)%busy == a - 1 .or. engine%body(a - 1)%busy >= 0 &
               & .or. closed_gap(engine, a - 1)) then
               a = a - 1
               cycle
            end if
         end if
         if (b < engine%n) then
            if (engine%body(b + 1)%region > 0) then
               call absorb_region(engine, b + 1, a, b, merged)
               cycle
            end if
            if (engine%body(b)%busy == b .or. engine%body(b + 1)%busy >= 0 &
               & .or. closed_gap(engine, b)) then
               b = b + 1
               cycle
            end if
         end if
         exit
      end do
      ! the closed-form contacts inside become integrated: their states now, and the
      ! part of their record known so far (the integrator finishes it)
      do i = a, b
         call body_state_at(engine, i, engine%time, u, v)
         s = engine%body(i)%busy
         engine%body(i) = body_state(t0=engine%time, u0=u, v0=v, busy=s)
      end do
      do s = max(a - 1, 0), min(b, engine%n)
         if (engine%exact(s)%active) call hand_over(engine, s)
      end do
      ! (out of memory, the bodies stay free: nothing refers to a region not formed)
      alloc_stat = 0
      if (.not. allocated(engine%regions)) allocate(engine%regions(4), stat=alloc_stat)
      if (alloc_stat == 0 .and. engine%n_regions == size(engine%regions)) then
         allocate(grown(2 * size(engine%regions)), stat=alloc_stat)
         if (alloc_stat == 0) then
            do k = 1, engine%n_regions
               call move_alloc(engine%regions(k)%integrator, grown(k)%integrator)
            end do
            call move_alloc(grown, engine%regions)
         end if
      end if
      k = engine%n_regions + 1
      if (alloc_stat == 0) allocate(engine%regions(k)%integrator, mold=integrator, &
         & stat=alloc_stat)
      if (alloc_stat /= 0) then
         call no_memory(engine, "a cluster's region")
         return
      end if
      engine%n_regions = k
      ! (a new region has not begun, nor rested: a body falling onto a stack at rest
      ! joined it, and with the old region's flag the run ended as it landed)
      engine%regions(k)%integrator%first = a
      engine%regions(k)%integrator%last = b
      engine%regions(k)%integrator%time = engine%time
      engine%regions(k)%integrator%next = engine%time
      engine%regions(k)%integrator%begun = .false.
      engine%regions(k)%integrator%rested = .false.
      ! (regions merged: contacts between them begin, the integrator chooses)
      engine%regions(k)%integrator%first_step = merge(0.0_wp, hint, merged)
      do i = a, b
         engine%body(i)%busy = -1
         engine%body(i)%region = k
      end do
      if (.not. merged) engine%counters%clusters = engine%counters%clusters + 1
      call log_switch(engine, a, b, why)
      do s = max(a - 2, 0), min(b + 1, engine%n)
         call schedule(engine, s)
      end do
   end subroutine form_region

   !> Whether the gap of pair s is closed now: below 0, or exactly 0 and closing. A
   !> touching pair that is not closing (at rest, or in the same free flight) stays
   !> outside: the region watches that boundary, and grows where the body inside
   !> pushes into the one outside (the deformation rises above 0 on its interpolant),
   !> so a struck chain of touching beads is integrated as far as its wave has set
   !> beads moving, not along all of its length.
   logical function closed_gap(engine, s)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      real(wp) :: gap, rate
      call slot_gap_at(engine, s, engine%time, gap, rate)
      closed_gap = .not. gap >= 0.0_wp
      if (gap == 0.0_wp) closed_gap = .not. rate >= 0.0_wp
   end function closed_gap

   !> An exact contact in progress is handed to the integrator: what its record holds
   !> so far stays in the slot (start, approach speed, and the dissipated energy, peak
   !> force and deformation up to now), for the integrator to finish.
   subroutine hand_over(engine, s)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      real(wp) :: x, xd, f, tau
      call contact_state(engine, s, engine%time, x, xd, f)
      tau = engine%time - engine%exact(s)%t_start
      engine%exact(s)%handed = .true.
      engine%exact(s)%so_far_dissipated = exact_dissipated(engine, s)
      call add_exact_wall_impulse(engine, s, xd)
      engine%exact(s)%so_far_peak = f
      if (tau >= engine%exact(s)%outcome%time_at_peak_force) &
         & engine%exact(s)%so_far_peak = engine%exact(s)%outcome%peak_force
      engine%exact(s)%so_far_deformation = x
      if (tau >= engine%exact(s)%outcome%compression_time) &
         & engine%exact(s)%so_far_deformation = engine%exact(s)%outcome%max_compression
      engine%exact(s)%active = .false.
      ! the integrator counts it when it ends
      engine%counters%closed_form_contacts = engine%counters%closed_form_contacts - 1
   end subroutine hand_over

   !> Where the closed-form contact of slot s is one with a wall (s = 0 or n): add the
   !> impulse (N s, along the line) it has given its body from its start up to the rate
   !> xd of its deformation, m (v - v_in), to that wall's; the body's velocity is -xd
   !> against the left wall and xd against the right one (so v_in = -+ the approach
   !> speed). Nothing for a pair of bodies.
   pure subroutine add_exact_wall_impulse(engine, s, xd)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      real(wp), intent(in) :: xd
      if (s == 0) call add_wall_impulse(engine, 1, product_in_range(engine%chain%mass(1), &
         & sum_in_range(engine%exact(s)%contact%velocity, -xd)))
      if (s == engine%n) call add_wall_impulse(engine, 2, &
         & product_in_range(engine%chain%mass(engine%n), &
         & sum_in_range(xd, -engine%exact(s)%contact%velocity)))
   end subroutine add_exact_wall_impulse

   !> Add the impulse (N s) to what the wall on side 1 (left) or 2 (right) has given
   !> the system (+-Inf beyond the range of doubles: the run then fails in
   !> fill_result)
   pure subroutine add_wall_impulse(engine, side, impulse)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: side
      real(wp), intent(in) :: impulse
      engine%wall_impulse(side) = sum_in_range(engine%wall_impulse(side), impulse)
   end subroutine add_wall_impulse

   !> The energy a closed-form contact of slot s in progress has dissipated so far:
   !> its energy in the frame of the pair's centre of mass at the start, less its
   !> kinetic and elastic energy now.
   function exact_dissipated(engine, s) result(e)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: s
      real(wp) :: e
      real(wp) :: x, xd, f
      type(contact_law) :: law
      call contact_state(engine, s, engine%time, x, xd, f)
      law = slot_law(engine, s)
      e = kinetic_energy(engine%exact(s)%contact%mass, engine%exact(s)%contact%velocity) &
         & - (kinetic_energy(engine%exact(s)%contact%mass, xd) &
         & + power_law_potential(law%stiffness, law%exponent, x))
      e = max(e, 0.0_wp)
   end function exact_dissipated

   !> If body i is in a region: close that region (written back) and widen a .. b over
   !> it (merged becomes true).
   subroutine absorb_region(engine, i, a, b, merged)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: i
      integer, intent(inout) :: a, b
      logical, intent(inout) :: merged
      integer :: k
      k = engine%body(i)%region
      if (k == 0) return
      a = min(a, engine%regions(k)%integrator%first)
      b = max(b, engine%regions(k)%integrator%last)
      call close_region(engine, k)
      merged = .true.
   end subroutine absorb_region

   !> Grow region k on one side, where a body outside touched it: by that body and a
   !> quarter of the region's size more (free bodies integrate at little cost, and a
   !> region that grows by a fraction of itself is begun O(log N) times, not O(N)
   !> times, as a wave runs along a chain with gaps); regions reached are merged.
   subroutine grow_region(engine, k, left_side, integrator)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: k
      logical, intent(in) :: left_side
      !> The integrator of clusters
      class(cluster_integrator), intent(in) :: integrator
      character(len=max_message) :: why
      integer :: a, b, more
      real(wp) :: h
      a = engine%regions(k)%integrator%first
      b = engine%regions(k)%integrator%last
      more = max(1, (b - a + 1) / 4)
      if (left_side) then
         call compose(why, "body ", a - 1, " touches the cluster")
         a = max(a - more, 1)
      else
         call compose(why, "body ", b + 1, " touches the cluster")
         b = min(b + more, engine%n)
      end if
      call close_region(engine, k, h)
      call form_region(engine, a, b, why, integrator, h)
   end subroutine grow_region

   !> Region k goes on as the parts its integrator gives (`parts`): bodies apart from
   !> their neighbours fly freely again, the closed forms' from now (pairs among them
   !> that close again are theirs, or form a cluster), and each part with a contact
   !> in progress is a region of its own that goes on with the step the region had
   !> reached. Behind a wave along a chain the region kept every bead it had crossed
   !> (on 10^4 beads to 10 ms, 379 bodies a step for a wave a few beads wide).
   subroutine split_region(engine, k, integrator)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: k
      !> The integrator of clusters
      class(cluster_integrator), intent(in) :: integrator
      character(len=max_message) :: why
      integer, allocatable :: parts(:, :)
      integer :: a, b, p, s, alloc_stat
      real(wp) :: h
      a = engine%regions(k)%integrator%first
      b = engine%regions(k)%integrator%last
      allocate(parts(2, engine%regions(k)%integrator%n_parts), stat=alloc_stat)
      if (alloc_stat /= 0) then
         call no_memory(engine, "the parts of a cluster that splits")
         return
      end if
      parts(:, :) = engine%regions(k)%integrator%parts(:, 1:engine%regions(k)%integrator%n_parts)
      call close_region(engine, k, h)
      if (size(parts, 2) == 0) then
         call compose(why, "the cluster of bodies ", a, " to ", b, &
            & " splits into bodies apart from their neighbours: closed forms again")
         call log_switch(engine, 0, 0, why)
      end if
      do p = 1, size(parts, 2)
         call compose(why, "the cluster of bodies ", a, " to ", &
            & b, " splits: bodies ", parts(1, p), " to ", parts(2, p), &
            & " go on integrated, bodies apart from their neighbours fly freely")
         call form_region(engine, parts(1, p), parts(2, p), why, integrator, h)
         if (engine%out_of_memory) return
      end do
      do s = max(a - 1, 0), min(b, engine%n)
         call schedule(engine, s)
      end do
   end subroutine split_region

   !> Close region k: its integrator (if begun) follows its contacts up to now and
   !> writes its bodies' states back, the bodies are free again (a contact in progress
   !> stays in its slot, handed over), and the last region takes its index.
   subroutine close_region(engine, k, step_for_growth)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: k
      !> The first step its integrator leaves for a region grown from it (s; 0: none)
      real(wp), intent(out), optional :: step_for_growth
      integer :: i, n
      if (engine%regions(k)%integrator%begun) call engine%regions(k)%integrator%finish(engine)
      if (engine%regions(k)%integrator%out_of_memory) &
         & call no_memory(engine, "the work arrays of a cluster")
      if (present(step_for_growth)) step_for_growth = &
         & engine%regions(k)%integrator%step_for_growth
      do i = engine%regions(k)%integrator%first, engine%regions(k)%integrator%last
         engine%body(i)%region = 0
         engine%body(i)%busy = -1
      end do
      deallocate(engine%regions(k)%integrator)
      n = engine%n_regions
      if (k < n) then
         call move_alloc(engine%regions(n)%integrator, engine%regions(k)%integrator)
         do i = engine%regions(k)%integrator%first, engine%regions(k)%integrator%last
            engine%body(i)%region = k
         end do
      end if
      engine%n_regions = n - 1
   end subroutine close_region

   !> Region k has separated: its bodies fly freely again.
   subroutine dissolve_region(engine, k)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: k
      character(len=max_message) :: why
      integer :: a, b, s
      a = engine%regions(k)%integrator%first
      b = engine%regions(k)%integrator%last
      call close_region(engine, k)
      call compose(why, "the cluster of bodies ", a, " to ", b, &
         & " has separated: closed forms again")
      call log_switch(engine, 0, 0, why)
      do s = max(a - 2, 0), min(b + 1, engine%n)
         call schedule(engine, s)
      end do
   end subroutine dissolve_region

   !> Append to the log of decisions.
   subroutine log_switch(engine, first, last, why)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: first, last
      character(len=*), intent(in) :: why
      type(chain_switch), allocatable :: grown(:)
      integer :: alloc_stat
      if (engine%n_switches == size(engine%switches)) then
         allocate(grown(2 * size(engine%switches)), stat=alloc_stat)
         if (alloc_stat /= 0) then
            call no_memory(engine, "the log of decisions")
            return
         end if
         grown(:engine%n_switches) = engine%switches
         call move_alloc(grown, engine%switches)
      end if
      engine%n_switches = engine%n_switches + 1
      engine%switches(engine%n_switches) = chain_switch(time=engine%time, first=first, &
         & last=last, reason=why)
   end subroutine log_switch

   ! =================================================================================
   ! Rest under gravity
   ! =================================================================================

   !> For a region resting against the wall that gravity points to: the energy it has
   !> above its static equilibrium minus the least energy any of its contacts needs to
   !> open (negative: no contact can ever open again, the region is at rest for good).
   !> The region's energy relative to everything open is
   !>   E = kinetic + sum_j (Pi_j(x_j) - W_j x_j),
   !> W_j the weight beyond contact j (gravity's potential is linear in the
   !> deformations); its least value, at the equilibrium x_j* = (W_j/c_j)^(1/n_j), is
   !> -sum_j B_j with B_j = W_j x_j* n_j/(n_j + 1), and any state with contact j open
   !> has E >= -sum B + B_j. So E + sum B < min B means at rest. Huge when the region
   !> is not a stack on such a wall. u and v: the displacements and velocities of the
   !> region's bodies a .. b.
   !>
   !> The bound is met with equality by a region released touching at rest (E = 0,
   !> sum B = min B for one contact), and E carries the integration's error: the margin
   !> is E + sum B - min B plus max(rtol, 16 eps) times the sum of the magnitudes of its
   !> terms, so rest is declared only when the bound holds beyond that error. A region
   !> whose contacts are all undamped (b = 0) keeps its energy and never rests: huge.
   function capture_margin(engine, a, b, u, v) result(margin)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: a, b
      real(wp), intent(in) :: u(:), v(:)
      real(wp) :: margin
      real(wp) :: e, b_sum, b_min, weight, x, xs, bound, term, scale
      integer :: i, k, s
      type(contact_law) :: law
      logical :: from_left, damped

      margin = huge(1.0_wp)
      if (a <= 0 .or. engine%gravity == 0.0_wp) return
      from_left = engine%gravity < 0.0_wp
      if (from_left .and. .not. (a == 1 .and. engine%chain%left_wall)) return
      if (.not. from_left .and. .not. (b == engine%n .and. engine%chain%right_wall)) return
      e = 0.0_wp
      do i = a, b
         e = e + kinetic_energy(engine%chain%mass(i), v(i - a + 1))
      end do
      scale = e
      damped = .false.
      b_sum = 0.0_wp
      b_min = huge(1.0_wp)
      ! contacts from the outermost inwards to the wall, the weight beyond each
      ! accumulated on the way (O(m))
      weight = 0.0_wp
      do k = b - a, 0, -1
         if (from_left) then
            s = a - 1 + k
            weight = weight + engine%chain%mass(s + 1) * abs(engine%gravity)
         else
            s = b - k
            weight = weight + engine%chain%mass(s) * abs(engine%gravity)
         end if
         law = slot_law(engine, s)
         damped = damped .or. law%damping > 0.0_wp
         x = region_deformation(engine, a, s, u)
         term = power_law_potential(law%stiffness, law%exponent, max(x, 0.0_wp))
         e = e + term - weight * x
         scale = scale + term + abs(weight * x)
         xs = (weight / law%stiffness)**(1.0_wp / law%exponent)
         bound = weight * xs * (law%exponent / (law%exponent + 1.0_wp))
         b_sum = b_sum + bound
         b_min = min(b_min, bound)
      end do
      if (.not. damped) return
      scale = scale + b_sum
      margin = e + b_sum - b_min + max(engine%options%rtol, 16.0_wp * epsilon(1.0_wp)) * scale
   end function capture_margin

   !> Kinetic + elastic + gravitational energy of the region of bodies a .. b
   !> (displacements u and velocities v of its bodies; the slots inside it and its
   !> walls)
   function region_energy(engine, a, b, u, v) result(e)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: a, b
      real(wp), intent(in) :: u(:), v(:)
      real(wp) :: e
      integer :: i, s
      type(contact_law) :: law
      e = 0.0_wp
      do i = a, b
         e = e + kinetic_energy(engine%chain%mass(i), v(i - a + 1)) &
            & - engine%chain%mass(i) * engine%chain%gravity * u(i - a + 1)
      end do
      do s = a - 1, b
         if (s < 0 .or. s > engine%n) cycle
         if (.not. slot_exists(engine, s)) cycle
         if ((s == a - 1 .and. s > 0) .or. (s == b .and. s < engine%n)) cycle
         law = slot_law(engine, s)
         e = e + power_law_potential(law%stiffness, law%exponent, &
            & region_deformation(engine, a, s, u))
      end do
   end function region_energy

   !> The deformation of slot s of a region from the displacements u of its bodies
   !> (the first of them is a)
   pure real(wp) function region_deformation(engine, a, s, u)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: a, s
      real(wp), intent(in) :: u(:)
      if (s == 0) then
         region_deformation = -(engine%chain%left_gap + u(1 - a + 1))
      else if (s == engine%n) then
         region_deformation = u(engine%n - a + 1) - engine%chain%right_gap
      else
         region_deformation = (u(s - a + 1) - u(s + 1 - a + 1)) - engine%chain%gap(s)
      end if
   end function region_deformation

   !> Whether the region of `it`, at rest for good (captured) and the whole system, has
   !> settled at engine%time: its energy E above the static equilibrium (kinetic, and
   !> per contact c/(n+1) (x^(n+1) - x_s^(n+1)) - c x_s^n (x - x_s), formed from the
   !> deviation x - x_s without cancellation) bounds every compression's deviation by
   !> sqrt(2 E / k) near the equilibrium, k = n c x_s^(n-1) its stiffness there, and
   !> the sum of these bounds over the contacts, a bound of every body's deviation, is
   !> below 100 rtol x_min (x_min the least static compression) or 1000 eps of the
   !> largest displacement, what the integration resolves. E only decreases from then
   !> on (the contacts dissipate, gravity and the walls do no work over a cycle), so the
   !> bodies stay that close. A slow mode (a stack on a soft floor) enters through its
   !> soft contact's k; a test of speeds against the stiffest contact's period alone
   !> settled such a stack 150 times farther out.
   logical function settled(engine, it)
      type(chain_engine), intent(in) :: engine
      class(cluster_integrator), intent(inout) :: it
      real(wp), allocatable :: u(:), v(:), u_rest(:), x_rest(:)
      real(wp) :: energy, bound, delta, tolerance, x_min
      type(contact_law) :: law
      integer :: i, s, n, alloc_stat
      settled = .false.
      if (.not. whole_at_rest(it, engine%n)) return
      n = engine%n
      ! (out of memory: not settled, the integration goes on and fails itself)
      allocate(u(n), v(n), u_rest(n), x_rest(0:n), stat=alloc_stat)
      if (alloc_stat /= 0) return
      call it%state_at(engine, engine%time, u, v)
      call rest_state(engine, 1, n, u_rest, x_rest)
      energy = sum(kinetic_energy(engine%chain%mass, v))
      x_min = huge(1.0_wp)
      do s = 0, n
         if (.not. slot_exists(engine, s)) cycle
         law = slot_law(engine, s)
         ! the deviation of the slot's compression from its rest
         ! (a wall at the free end, open at rest: delta is its compression itself)
         if (s == 0) then
            delta = -(u(1) - u_rest(1))
            if (.not. x_rest(s) > 0.0_wp) delta = -(engine%chain%left_gap + u(1))
         else if (s == n) then
            delta = u(n) - u_rest(n)
            if (.not. x_rest(s) > 0.0_wp) delta = u(n) - engine%chain%right_gap
         else
            delta = (u(s) - u_rest(s)) - (u(s + 1) - u_rest(s + 1))
         end if
         energy = energy + bregman(law, x_rest(s), delta)
         if (x_rest(s) > 0.0_wp) x_min = min(x_min, x_rest(s))
      end do
      if (.not. x_min < huge(1.0_wp)) return
      bound = 0.0_wp
      do s = 0, n
         if (.not. slot_exists(engine, s)) cycle
         if (.not. x_rest(s) > 0.0_wp) cycle
         law = slot_law(engine, s)
         bound = bound + sqrt(2.0_wp * energy / (law%exponent * law%stiffness &
            & * x_rest(s)**(law%exponent - 1.0_wp)))
      end do
      tolerance = 100.0_wp * engine%options%rtol * x_min
      do i = 1, n
         tolerance = max(tolerance, 1000.0_wp * epsilon(1.0_wp) * abs(u(i)))
      end do
      settled = bound <= tolerance
   end function settled

   !> The energy of a contact law at the compression x_s + delta above its tangent at
   !> x_s >= 0 (J): c/(n+1) (x^(n+1) - x_s^(n+1)) - c x_s^n delta, >= 0. With w =
   !> delta / x_s, x_s^(n+1) c ((1+w)^(n+1) - 1 - (n+1) w) / (n+1); for |w| <= 1e-5 its
   !> series n w^2/2 (1 + (n-1) w/3), whose first neglected term is below 1e-10 of it.
   !> A slot open at rest (x_s = 0): the potential of the compression delta.
   pure real(wp) function bregman(law, x_s, delta) result(e)
      type(contact_law), intent(in) :: law
      real(wp), intent(in) :: x_s, delta
      real(wp) :: w, n
      n = law%exponent
      if (.not. x_s > 0.0_wp) then
         e = power_law_potential(law%stiffness, n, max(delta, 0.0_wp))
         return
      end if
      w = delta / x_s
      if (abs(w) <= 1.0e-5_wp) then
         e = 0.5_wp * n * w**2 * (1.0_wp + (n - 1.0_wp) * w / 3.0_wp)
      else
         e = (max(1.0_wp + w, 0.0_wp)**(n + 1.0_wp) - 1.0_wp - (n + 1.0_wp) * w) &
            & / (n + 1.0_wp)
      end if
      e = max(e, 0.0_wp) * (law%stiffness * x_s**(n + 1.0_wp))
   end function bregman

   !> The static equilibrium of the region of bodies a .. b resting on its wall:
   !> displacements u, velocities 0; and the compressions of its slots a - 1 .. b at
   !> rest (m; 0 for the slot at its free end).
   subroutine rest_state(engine, a, b, u, compression)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: a, b
      real(wp), intent(out) :: u(:)
      real(wp), intent(out), optional :: compression(a - 1:)
      integer :: k, s
      real(wp) :: weight, xs, total
      type(contact_law) :: law
      logical :: from_left
      from_left = engine%gravity < 0.0_wp
      ! the weight beyond each contact: all of the region beyond the wall's, less
      ! one body per contact further out (O(m))
      total = sum(engine%chain%mass(a:b))
      weight = total
      do k = 0, b - a
         if (from_left) then
            s = a - 1 + k
         else
            s = b - k
         end if
         law = slot_law(engine, s)
         xs = (weight * abs(engine%gravity) / law%stiffness)**(1.0_wp / law%exponent)
         if (present(compression)) then
            if (k == 0) compression = 0.0_wp
            compression(s) = xs
         end if
         if (from_left) then
            if (s == 0) then
               u(1) = -(engine%chain%left_gap + xs)
            else
               u(s + 1 - a + 1) = u(s - a + 1) - xs - engine%chain%gap(s)
            end if
            weight = weight - engine%chain%mass(s + 1)
         else
            if (s == engine%n) then
               u(b - a + 1) = engine%chain%right_gap + xs
            else
               u(s - a + 1) = u(s + 1 - a + 1) + xs + engine%chain%gap(s)
            end if
            weight = weight - engine%chain%mass(s)
         end if
      end do
   end subroutine rest_state

   !> The region of bodies a .. b (written back, closed) has come to rest for good and
   !> nothing else can happen: its bodies are put at their static equilibrium.
   subroutine settle_at_rest(engine, a, b)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: a, b
      real(wp), allocatable :: u(:), u_now(:), v_now(:)
      real(wp) :: above_rest
      integer :: i, alloc_stat
      allocate(u(b - a + 1), u_now(b - a + 1), v_now(b - a + 1), stat=alloc_stat)
      if (alloc_stat /= 0) then
         call no_memory(engine, "the state at rest")
         return
      end if
      do i = a, b
         u_now(i - a + 1) = engine%body(i)%u0
         v_now(i - a + 1) = engine%body(i)%v0
      end do
      call rest_state(engine, a, b, u)
      ! what the region has above its equilibrium will all be dissipated, and the
      ! momentum it has left goes into the wall it rests on, which from now on holds
      ! its weight
      ! (the rest state has the least energy: a difference below 0 is rounding)
      above_rest = region_energy(engine, a, b, u_now, v_now) &
         & - region_energy(engine, a, b, u, 0.0_wp * v_now)
      engine%dissipated = engine%dissipated + not_below_zero(above_rest)
      engine%settle_side = merge(1, 2, engine%gravity < 0.0_wp)
      engine%settle_time = engine%time
      do i = a, b
         call add_wall_impulse(engine, engine%settle_side, &
            & -product_in_range(engine%chain%mass(i), v_now(i - a + 1)))
      end do
      do i = a, b
         engine%body(i) = body_state(t0=engine%time, u0=u(i - a + 1), v0=0.0_wp)
      end do
      ! at rest: the velocities stay 0 (gravity is held by the contacts)
      engine%gravity = 0.0_wp
   end subroutine settle_at_rest

   ! =================================================================================
   ! Samples and the result
   ! =================================================================================

   !> The next sample time not yet taken (huge if none)
   pure real(wp) function next_sample_time(engine)
      type(chain_engine), intent(in) :: engine
      next_sample_time = huge(1.0_wp)
      if (.not. allocated(engine%options%sample_times)) return
      if (engine%next_sample <= size(engine%options%sample_times)) &
         & next_sample_time = engine%options%sample_times(engine%next_sample)
   end function next_sample_time

   !> Take every sample due at the current time or before it (all: every sample left,
   !> when nothing can happen after the end).
   subroutine take_samples(engine, all)
      type(chain_engine), intent(inout) :: engine
      logical, intent(in), optional :: all
      real(wp) :: ts, u, v
      real(wp), allocatable :: ur(:), vr(:)
      integer :: k, i, s, r, a, alloc_stat
      type(contact_force_type) :: f
      type(contact_law) :: law
      logical :: every

      if (.not. allocated(engine%options%sample_times)) return
      every = .false.
      if (present(all)) every = all
      do while (engine%next_sample <= size(engine%options%sample_times))
         ts = engine%options%sample_times(engine%next_sample)
         if (ts > engine%time .and. .not. every) exit
         k = engine%next_sample
         do i = 1, engine%n
            if (engine%body(i)%region > 0) cycle
            call body_state_at(engine, i, ts, u, v)
            engine%sample_u(i, k) = engine%q_initial(i) + u
            engine%sample_v(i, k) = v
         end do
         ! the regions' bodies from their integrators (ts is within [time, next] of each)
         do r = 1, engine%n_regions
            associate (it => engine%regions(r)%integrator)
               a = it%first
               allocate(ur(it%last - a + 1), vr(it%last - a + 1), stat=alloc_stat)
               if (alloc_stat /= 0) then
                  call no_memory(engine, "a sample")
                  return
               end if
               call it%state_at(engine, ts, ur, vr)
               engine%sample_u(a:it%last, k) = engine%q_initial(a:it%last) + ur
               engine%sample_v(a:it%last, k) = vr
               deallocate(ur, vr)
            end associate
         end do
         do s = 0, engine%n
            engine%sample_f(s, k) = 0.0_wp
            if (.not. slot_exists(engine, s)) cycle
            law = slot_law(engine, s)
            if (s == 0) then
               call contact_force_wall(law%stiffness, law%exponent, law%damping, &
                  & 0.0_wp, engine%sample_u(1, k), engine%sample_v(1, k), &
                  & -engine%chain%left_gap, -1, f)
            else if (s == engine%n) then
               call contact_force_wall(law%stiffness, law%exponent, law%damping, &
                  & 0.0_wp, engine%sample_u(s, k), engine%sample_v(s, k), &
                  & engine%q_initial(s) + engine%chain%right_gap, 1, f)
            else
               call contact_force_pair(law%stiffness, law%exponent, law%damping, 0.0_wp, &
                  & engine%sample_u(s, k), engine%sample_v(s, k), engine%sample_u(s + 1, k), &
                  & engine%sample_v(s + 1, k), f)
            end if
            engine%sample_f(s, k) = f%force
         end do
         engine%next_sample = engine%next_sample + 1
      end do
   end subroutine take_samples

   !> The result from the final state of the engine.
   !> hcimpact_err_domain (and engine%message) where a final or sampled position or
   !> velocity, an energy of the result, the momentum or a term of the energy balance
   !> is beyond the range of doubles (the initial energy and momentum are checked with
   !> the input); nothing is formed that would raise an overflow on the way.
   subroutine fill_result(engine, result, stat)
      type(chain_engine), intent(inout) :: engine
      type(chain_result), intent(inout) :: result
      integer, intent(out) :: stat
      integer :: i, s, nsamples
      real(wp) :: u, v, e_kin0, e_kin, e_el, e_grav, p, x, in_progress, impulse
      real(wp) :: walls(2), xd, f, reach
      real(wp), allocatable :: displacement(:)
      type(contact_law) :: law
      integer :: alloc_stat

      result%time = engine%time
      nsamples = size(engine%sample_u, 2)
      allocate(result%positions(engine%n), result%velocities(engine%n), displacement(engine%n), &
         & result%contacts(engine%n_records), result%sample_positions(engine%n, nsamples), &
         & result%sample_velocities(engine%n, nsamples), &
         & result%sample_forces(0:engine%n, nsamples), result%switches(engine%n_switches), &
         & stat=alloc_stat)
      if (alloc_stat /= 0) then
         ! (the caller clears the result)
         call no_memory(engine, "the result")
         stat = hcimpact_err_out_of_memory
         return
      end if
      do i = 1, engine%n
         call body_state_at(engine, i, engine%time, displacement(i), result%velocities(i))
         result%positions(i) = sum_in_range(engine%q_initial(i), displacement(i))
      end do
      ! a final state beyond the range of doubles, before anything is formed from it
      if (.not. (all(ieee_is_finite(result%positions)) .and. &
         & all(ieee_is_finite(result%velocities)))) then
         stat = hcimpact_err_domain
         call state_beyond_range(engine)
         return
      end if
      ! the energies and the momentum, +-Inf where beyond the range of doubles (then the
      ! run fails below), without raising the overflow on the way
      e_kin = 0.0_wp
      e_grav = 0.0_wp
      p = momentum(engine%chain%mass, result%velocities)
      do i = 1, engine%n
         u = displacement(i)
         v = result%velocities(i)
         e_kin = sum_in_range(e_kin, kinetic_energy(engine%chain%mass(i), v))
         ! -m g u, and the sum, without an overflow on the way (+-Inf beyond the range;
         ! the run then fails below)
         if (engine%chain%gravity /= 0.0_wp .and. u /= 0.0_wp) e_grav = sum_in_range(e_grav, &
            & sign(1.0_wp, u) * signed_product(-engine%chain%gravity, [engine%chain%mass(i), &
            & abs(u)]))
      end do
      e_el = 0.0_wp
      do s = 0, engine%n
         if (.not. slot_exists(engine, s)) cycle
         law = slot_law(engine, s)
         if (s == 0) then
            x = -(engine%chain%left_gap + (result%positions(1) - engine%q_initial(1)))
            reach = max(engine%chain%left_gap, abs(result%positions(1)), &
               & abs(engine%q_initial(1)))
         else if (s == engine%n) then
            x = (result%positions(s) - engine%q_initial(s)) - engine%chain%right_gap
            reach = max(engine%chain%right_gap, abs(result%positions(s)), &
               & abs(engine%q_initial(s)))
         else
            x = result%positions(s) - result%positions(s + 1)
            reach = max(abs(result%positions(s)), abs(result%positions(s + 1)), &
               & abs(engine%q_initial(s)), abs(engine%q_initial(s + 1)))
         end if
         ! an overlap within the rounding of the positions it comes from (initial
         ! position plus displacement) is none: two bodies of 1e-200 kg that met 1e196 m
         ! away ended one ulp (1e180 m) into each other, whose elastic energy at c = 1
         ! N/m left the range and failed the run
         if (x <= 4.0_wp * spacing(reach)) x = min(x, 0.0_wp)
         e_el = sum_in_range(e_el, power_law_potential(law%stiffness, law%exponent, x))
      end do
      e_kin0 = 0.0_wp
      do i = 1, engine%n
         e_kin0 = e_kin0 + kinetic_energy(engine%chain%mass(i), engine%chain%velocity(i))
      end do
      result%initial_energy = e_kin0
      ! and what the contacts still in progress have dissipated so far (a region's,
      ! written back at the end, or a closed-form contact's)
      in_progress = 0.0_wp
      do s = 0, engine%n
         if (engine%exact(s)%handed) then
            in_progress = in_progress + engine%exact(s)%so_far_dissipated
         else if (engine%exact(s)%active) then
            in_progress = in_progress + exact_dissipated(engine, s)
         end if
      end do
      result%dissipated = sum_in_range(engine%dissipated, in_progress)
      ! the balance only of energies that are doubles, with its terms and its scale (an
      ! infinity in it would raise the invalid exception, an overflow the overflow: the
      ! Debug build traps on both)
      if (.not. (ieee_is_finite(p) .and. ieee_is_finite(sum_in_range(sum_in_range( &
         & sum_in_range(sum_in_range(e_kin, e_el), e_grav), result%dissipated), -e_kin0)) &
         & .and. ieee_is_finite(sum_in_range(e_kin0, abs(e_grav))))) then
         stat = hcimpact_err_domain
         engine%message = energies_beyond_range
         return
      end if
      ! the energy put in by gravity counts in the scale of the error
      result%energy_error = energy_balance_error(e_kin + e_el + e_grav, result%dissipated, &
         & e_kin0, e_grav)
      ! the walls' impulses: besides those written back, a closed-form contact with a
      ! wall still in progress, and the weight a wall has held since the system
      ! settled on it
      do s = 0, engine%n, engine%n
         if (.not. (slot_exists(engine, s) .and. engine%exact(s)%active)) cycle
         call contact_state(engine, s, engine%time, x, xd, f)
         call add_exact_wall_impulse(engine, s, xd)
      end do
      if (engine%settle_side > 0) call add_wall_impulse(engine, engine%settle_side, &
         & -gravity_impulse(engine%chain%mass, engine%chain%gravity, &
         & engine%time - engine%settle_time))
      walls = engine%wall_impulse
      result%wall_impulse = walls
      ! the outside forces are gravity's and the walls': p = p0 + M g t + J_left +
      ! J_right (NaN where their impulses are beyond the range of doubles: the run
      ! fails below for the walls', not for gravity's)
      impulse = gravity_impulse(engine%chain%mass, engine%chain%gravity, engine%time)
      result%momentum_error = momentum_balance_error(p, engine%chain%mass, &
         & engine%chain%velocity, [impulse, walls])
      result%rested = engine%rested
      result%rest_time = engine%rest_time
      result%n_contacts = engine%n_contacts
      result%contacts(:) = engine%records(:engine%n_records)
      result%sample_positions(:, :) = engine%sample_u
      result%sample_velocities(:, :) = engine%sample_v
      result%sample_forces(:, :) = engine%sample_f
      result%counters = engine%counters
      result%switches(:) = engine%switches(:engine%n_switches)
      ! a cluster still integrated at t_end has recorded no contact yet, but it was
      ! integrated all the same
      if (engine%counters%integrated_contacts == 0 .and. engine%counters%clusters == 0) then
         result%method_used = by_closed_forms
      else if (engine%counters%closed_form_contacts == 0) then
         result%method_used = by_integration
      else
         result%method_used = by_both
      end if
      result%message = "success"
      stat = hcimpact_ok
      if (.not. (ieee_is_finite(result%initial_energy) .and. ieee_is_finite(result%dissipated) &
         & .and. ieee_is_finite(result%energy_error) .and. ieee_is_finite(e_kin + e_el + e_grav) &
         & .and. (ieee_is_nan(result%momentum_error) .or. ieee_is_finite(result%momentum_error)))) &
         & then
         stat = hcimpact_err_domain
         engine%message = energies_beyond_range
      else if (.not. all(ieee_is_finite(result%wall_impulse))) then
         stat = hcimpact_err_domain
         engine%message = "the impulses of the walls leave the range of doubles (beyond " &
            & // "1.8e308 N s)"
      else if (engine%counters%clusters > 0 .and. gross_balance(result, engine%options%rtol)) &
         & then
         stat = hcimpact_err_solver
         write(engine%message, '(a, es10.3e3, a, es10.3e3, a, es10.3e3, a)') "the " &
            & // "integration did not resolve the contacts: its balances are off by ", &
            & result%energy_error, " (energy) and ", result%momentum_error, &
            & " (momentum) at rtol ", engine%options%rtol, " (scales beyond what CVODE resolves?)"
      end if
      ! (samples after t_end are NaN, not infinite; ieee_is_nan, not a comparison: a NaN
      ! compared traps in the Debug build)
      if (.not. (all(ieee_is_finite(result%positions)) .and. &
         & all(ieee_is_finite(result%velocities))) .or. &
         & any(.not. (ieee_is_finite(result%sample_positions) .or. &
         & ieee_is_nan(result%sample_positions))) .or. &
         & any(.not. (ieee_is_finite(result%sample_velocities) .or. &
         & ieee_is_nan(result%sample_velocities)))) then
         stat = hcimpact_err_domain
         call state_beyond_range(engine)
      end if
   end subroutine fill_result

   !> The message of a final or sampled state beyond the range of doubles
   subroutine state_beyond_range(engine)
      type(chain_engine), intent(inout) :: engine
      write(engine%message, '(a, es11.3e3, a)') "by t = ", engine%time, " s a position or " &
         & // "a velocity (final or sampled) leaves the range of doubles (beyond 1.8e308 " &
         & // "m or m/s)"
   end subroutine state_beyond_range

   !> why = t1 i1 t2 i2 ... (the integers as with i0): a reason of the log of decisions
   !> without an internal write, whose format libgfortran allocates unchecked (out of
   !> memory the runtime stopped the program there)
   subroutine compose(why, t1, i1, t2, i2, t3, i3, t4, i4, t5)
      character(len=*), intent(out) :: why
      character(len=*), intent(in) :: t1
      integer, intent(in), optional :: i1, i2, i3, i4
      character(len=*), intent(in), optional :: t2, t3, t4, t5
      integer :: at
      why = ""
      at = 0
      call put_text(t1)
      if (present(i1)) call put_int(i1)
      if (present(t2)) call put_text(t2)
      if (present(i2)) call put_int(i2)
      if (present(t3)) call put_text(t3)
      if (present(i3)) call put_int(i3)
      if (present(t4)) call put_text(t4)
      if (present(i4)) call put_int(i4)
      if (present(t5)) call put_text(t5)
   contains
      subroutine put_text(t)
         character(len=*), intent(in) :: t
         integer :: k
         do k = 1, len(t)
            if (at >= len(why)) return
            at = at + 1
            why(at:at) = t(k:k)
         end do
      end subroutine put_text
      subroutine put_int(i)
         integer, intent(in) :: i
         character(len=12) :: digits
         integer :: k, q
         ! (from the last digit; huge(1) has 10, a sign one more)
         digits = ""
         k = len(digits)
         q = abs(i)
         do
            digits(k:k) = achar(iachar("0") + mod(q, 10))
            k = k - 1
            q = q / 10
            if (q == 0) exit
         end do
         if (i < 0) then
            digits(k:k) = "-"
            k = k - 1
         end if
         call put_text(digits(k + 1:))
      end subroutine put_int
   end subroutine compose

   !> An allocation failed: the run stops with hcimpact_err_out_of_memory, the message
   !> says what did not fit (the first that failed).
   subroutine no_memory(engine, what)
      type(chain_engine), intent(inout) :: engine
      character(len=*), intent(in) :: what
      if (.not. engine%out_of_memory) engine%message = "out of memory (" // what // &
         & no_memory_tail
      engine%out_of_memory = .true.
      if (allocated(engine%reserve)) deallocate(engine%reserve)
   end subroutine no_memory

   !> A failed run: the message, nothing else.
   subroutine fail(engine, result, stat)
      type(chain_engine), intent(in) :: engine
      type(chain_result), intent(inout) :: result
      integer, intent(in) :: stat
      result%message = engine%message
      result%time = engine%time
      if (stat == hcimpact_ok) result%message = "success"
   end subroutine fail

   ! =================================================================================
   ! The heap of events (indexed binary min-heap over the slots)
   ! =================================================================================

   !> Set the event time of slot s (huge: remove it from the heap).
   subroutine heap_update(engine, s, t)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: s
      real(wp), intent(in) :: t
      integer :: k
      engine%event_time(s) = t
      k = engine%heap_pos(s)
      if (t >= huge(1.0_wp)) then
         if (k > 0) call heap_remove(engine, k)
         return
      end if
      if (k == 0) then
         engine%heap_size = engine%heap_size + 1
         k = engine%heap_size
         engine%heap(k) = s
         engine%heap_pos(s) = k
      end if
      call sift_up(engine, k)
      call sift_down(engine, engine%heap_pos(s))
   end subroutine heap_update

   subroutine heap_remove(engine, k)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: k
      integer :: s, last
      s = engine%heap(k)
      last = engine%heap(engine%heap_size)
      engine%heap_pos(s) = 0
      engine%heap_size = engine%heap_size - 1
      if (k > engine%heap_size) return
      engine%heap(k) = last
      engine%heap_pos(last) = k
      call sift_up(engine, k)
      call sift_down(engine, engine%heap_pos(last))
   end subroutine heap_remove

   subroutine sift_up(engine, start)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: start
      integer :: k, parent
      k = start
      do while (k > 1)
         parent = k / 2
         if (.not. before(engine, engine%heap(k), engine%heap(parent))) exit
         call swap_heap(engine, k, parent)
         k = parent
      end do
   end subroutine sift_up

   subroutine sift_down(engine, start)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: start
      integer :: k, child
      k = start
      do
         child = 2 * k
         if (child > engine%heap_size) exit
         if (child < engine%heap_size) then
            if (before(engine, engine%heap(child + 1), engine%heap(child))) child = child + 1
         end if
         if (.not. before(engine, engine%heap(child), engine%heap(k))) exit
         call swap_heap(engine, k, child)
         k = child
      end do
   end subroutine sift_down

   !> Exchange the heap entries at positions i and j, and their recorded positions
   subroutine swap_heap(engine, i, j)
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: i, j
      integer :: s
      s = engine%heap(i)
      engine%heap(i) = engine%heap(j)
      engine%heap(j) = s
      engine%heap_pos(engine%heap(i)) = i
      engine%heap_pos(engine%heap(j)) = j
   end subroutine swap_heap

   !> Slot a's event comes before slot b's (ties: the lower slot first, so that the
   !> order is the same in every run)
   pure logical function before(engine, a, b)
      type(chain_engine), intent(in) :: engine
      integer, intent(in) :: a, b
      before = engine%event_time(a) < engine%event_time(b) .or. &
         & (engine%event_time(a) == engine%event_time(b) .and. a < b)
   end function before

end module hcimpact_chain_engine
