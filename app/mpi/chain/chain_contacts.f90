! SPDX-License-Identifier: Apache-2.0
!> The contacts of the distributed chain (hcimpact_mpi_chain, doc/mpi.md): after each
!> step of CVODE, every rank follows the pairs it owns on CVODE's own interpolating
!> polynomial of the step and records every contact, from its start to its end, as
!> the serial chain does (`contact_record`).
!>
!> Ownership: a rank owns the pair on the left of each of its beads (the pair between
!> two blocks belongs to the block on its right), the first rank the left wall, the
!> last rank the right wall: every pair exactly one rank, and the dissipated energy of
!> a pair is a value of its owner's state.
!>
!> The interpolant: CVODE's Nordsieck array stands for a polynomial of degree q (the
!> order of the step) over the last step [t_(n-1), t_n]. Its Taylor coefficients at
!> t_n, the derivatives D_k = CVodeGetDky(t_n, k) for k = 0 .. q, give it back
!> exactly: y(t) = sum_k D_k (t - t_n)^k / k!. `taylor` holds them for the rank's
!> values (q + 1 vectors of the block: O(m) per step, like one vector operation per
!> coefficient), the left halo bead's (its displacement and velocity) come from the
!> left neighbour, `exchange_coefficients`: 2 (max_order + 1) doubles per step and
!> boundary, to the right. A pair's deformation, rate, force and force rate (with
!> the accelerations, the polynomial's derivative) at any time of the step then cost
!> O(q), whatever the length of the chain.
!>
!> Per owned pair and step, one probe at the step's end says whether anything may
!> have happened (`eventful`); only then is the polynomial sampled at `samples`
!> points, and between two samples (the first is the end of the last step):
!> - a contact starts where the deformation x rises above x_tol and ends where it
!>   falls below -x_tol (x_tol = rtol x_ref, the deformation the integration resolves:
!>   pairs touching at rest wiggle around 0 at that level), its time where the
!>   polynomial's x crosses 0, located by the Illinois variant of regula falsi (at
!>   most `max_iterations` evaluations), the approach and separation speeds the rate
!>   there;
!> - the largest deformation and force of an open contact pressed beyond x_tol: the
!>   value at the root of its rate (the deformation rate, the force rate) where that
!>   falls from > 0 to <= 0 (`new_maximum`), located likewise, and the values at the
!>   samples;
!> - the dissipated energy: the pair's value of the state (integrated with the motion)
!>   at the end, less that at the start, both from the polynomial.
!> The location needs no communication beyond that one exchange and does not touch
!> the integration (CVODE is not stopped or restarted at a contact: the force is
!> continuous, only its derivative jumps at x = 0, and the error control resolves
!> that as any other rapid change).
!>
!> Touching pairs (gap 0, or pressed at the start) follow the serial chain: a pair
!> with x >= 0 at t = 0 is in contact from t = 0 with the approach speed max(w, 0);
!> a contact that ends without ever pressing (largest force 0) is no contact and is
!> not recorded. Contacts still open at t_end are not recorded (the serial chain
!> records those that ended).
module hcimpact_mpi_chain_contacts
   use, intrinsic :: iso_fortran_env, only : int64
   use mpi_f08, only : MPI_Sendrecv, MPI_Gather, MPI_Gatherv, MPI_Bcast, MPI_Allgather, &
      & MPI_DOUBLE_PRECISION, MPI_INTEGER8, MPI_LOGICAL, MPI_STATUS_IGNORE
   use hcimpact_kinds, only : wp
   use hcimpact_chain_types, only : contact_record, by_integration, beyond_max_beta, &
      & say_beyond_max_beta
   use hcimpact_force_element, only : contact_force_type
   use hcimpact_cvode_chain_system, only : region_size, slot_state, force_rate, slot_none
   use hcimpact_mpi_chain_block, only : chain_block
   implicit none
   private

   public :: contact_tracker, tracker_start, tracker_step, exchange_coefficients
   public :: max_order, sort_by_pair, gather_contacts, beyond_domain

   !> Doubles per contact in the gathering
   integer, parameter :: record_doubles = 8

   !> The highest order of CVODE's BDF
   integer, parameter :: max_order = 5
   !> Samples of the polynomial per pair and step
   integer, parameter :: samples = 8
   !> Most evaluations of a location
   integer, parameter :: max_iterations = 60
   !> Message tag of the coefficients
   integer, parameter :: tag_coefficients = 21

   !> Which quantity of a probe a location follows
   integer, parameter :: of_deformation = 1, of_rate = 2, of_force_rate = 3

   !> A pair at one time: deformation x (m), its rate w (m/s), the force f (N), its
   !> rate df (N/s), the energy e dissipated in the pair so far (J)
   type :: probe
      real(wp) :: t = 0.0_wp, x = 0.0_wp, w = 0.0_wp, f = 0.0_wp, df = 0.0_wp, e = 0.0_wp
   end type probe

   !> A contact in progress
   type :: open_contact
      logical :: open = .false.
      real(wp) :: t_start = 0.0_wp, approach = 0.0_wp, e_base = 0.0_wp, peak = 0.0_wp, &
         & deformation = 0.0_wp
   end type open_contact

   !> The contacts of a rank's pairs
   type :: contact_tracker
      !> The region slots owned (j_first .. j_last) and the global pair of j_first
      integer :: j_first = 1, j_last = 0, pair_first = 0
      !> Taylor coefficients at the end of the last step: the block's values
      !> (0:max_order, n_local) and the left halo bead's u and v (0:max_order, 2)
      real(wp), allocatable :: taylor(:, :)
      real(wp) :: halo(0:max_order, 2) = 0.0_wp
      !> The end of the last step
      real(wp) :: t_n = 0.0_wp
      !> The deformation (m) beyond which a contact starts or ends (module header)
      real(wp) :: x_tol = 0.0_wp
      !> Per owned slot: its probe at the end of the last step, its open contact
      type(probe), allocatable :: last(:)
      type(open_contact), allocatable :: contact(:)
      !> The contacts that ended, n_records of them (in the order they ended)
      type(contact_record), allocatable :: records(:)
      integer(int64) :: n_records = 0
      !> Scratch states in the region's layout (only a slot's two beads are set)
      real(wp), allocatable :: y_region(:), dy_region(:)
      !> Locations done and locations that used all their evaluations
      integer(int64) :: locations = 0, unconverged = 0
      !> The first owned pair met touching and closing with b V beyond the model's
      !> domain (`beyond_max_beta`, as the serial chain refuses it): its number in the
      !> contacts' records (-1: none), the time, its damping and its closing speed
      integer :: beyond_pair = -1
      real(wp) :: beyond_time = 0.0_wp, beyond_damping = 0.0_wp, beyond_speed = 0.0_wp
   end type contact_tracker

contains

   !> Set up the tracker at t = 0 with the block's initial state y: every owned pair
   !> with x >= 0 is in contact from now. Collective (one exchange).
   subroutine tracker_start(tracker, block, y, x_tol)
      type(contact_tracker), intent(out) :: tracker
      type(chain_block), intent(in) :: block
      real(wp), intent(in) :: y(:)
      !> The deformation beyond which a contact starts or ends (m, >= 0)
      real(wp), intent(in) :: x_tol
      integer :: j, mr
      type(probe) :: p
      mr = block%region%m
      tracker%j_first = block%n_left
      tracker%j_last = block%n_left + block%m - 1
      if (block%n_right == 0) tracker%j_last = mr
      tracker%pair_first = block%first - 1
      allocate(tracker%taylor(0:max_order, block%n_local), &
         & tracker%last(tracker%j_first:tracker%j_last), &
         & tracker%contact(tracker%j_first:tracker%j_last), tracker%records(16), &
         & tracker%y_region(region_size(mr)), tracker%dy_region(region_size(mr)))
      tracker%taylor = 0.0_wp
      tracker%taylor(0, :) = y(1:block%n_local)
      tracker%y_region = 0.0_wp
      tracker%dy_region = 0.0_wp
      tracker%t_n = 0.0_wp
      tracker%x_tol = x_tol
      call exchange_coefficients(tracker, block)
      do j = tracker%j_first, tracker%j_last
         if (block%region%kind(j) == slot_none) cycle
         call probe_at(tracker, block, j, 0.0_wp, p)
         tracker%last(j) = p
         call watch_domain(tracker, block, j, p, -tracker%x_tol)
         if (p%x >= 0.0_wp) tracker%contact(j) = open_contact(.true., 0.0_wp, &
            & max(p%w, 0.0_wp), p%e, 0.0_wp, 0.0_wp)
      end do
   end subroutine tracker_start

   !> Send this block's last bead's coefficients (u, v) to the right neighbour and take
   !> the left neighbour's as the halo bead's. Collective among neighbours.
   subroutine exchange_coefficients(tracker, block)
      type(contact_tracker), intent(inout) :: tracker
      type(chain_block), intent(in) :: block
      real(wp) :: out(0:max_order, 2), in(0:max_order, 2)
      integer :: m
      m = block%m
      out(:, 1) = tracker%taylor(:, 3 * m - 2)
      out(:, 2) = tracker%taylor(:, 3 * m - 1)
      in = 0.0_wp
      call MPI_Sendrecv(out, size(out), MPI_DOUBLE_PRECISION, block%right, &
         & tag_coefficients, in, size(in), MPI_DOUBLE_PRECISION, block%left, &
         & tag_coefficients, block%comm, MPI_STATUS_IGNORE)
      tracker%halo = in
   end subroutine exchange_coefficients

   !> After a step from t_a to t_n whose Taylor coefficients at t_n are in
   !> tracker%taylor: exchange the halo bead's, then follow every owned pair over the
   !> step (module header). Collective (one exchange).
   subroutine tracker_step(tracker, block, t_a, t_n)
      type(contact_tracker), intent(inout) :: tracker
      type(chain_block), intent(in) :: block
      real(wp), intent(in) :: t_a, t_n
      type(probe) :: p0, p1, pe
      real(wp) :: t
      integer :: j, i
      tracker%t_n = t_n
      call exchange_coefficients(tracker, block)
      do j = tracker%j_first, tracker%j_last
         if (block%region%kind(j) == slot_none) cycle
         p0 = tracker%last(j)
         call probe_at(tracker, block, j, t_n, pe)
         if (eventful(tracker, j, p0, pe)) then
            do i = 1, samples - 1
               t = t_a + (t_n - t_a) * (real(i, wp) / real(samples, wp))
               call probe_at(tracker, block, j, t, p1)
               call follow(tracker, block, j, p0, p1)
               p0 = p1
            end do
         end if
         call follow(tracker, block, j, p0, pe)
         tracker%last(j) = pe
         call watch_domain(tracker, block, j, pe, -tracker%x_tol)
      end do
   end subroutine tracker_step

   !> Keep slot j's probe p as the first beyond the model's domain when the pair
   !> touches there (x >= x_min) and closes with b V above `max_beta`
   subroutine watch_domain(tracker, block, j, p, x_min)
      type(contact_tracker), intent(inout) :: tracker
      type(chain_block), intent(in) :: block
      integer, intent(in) :: j
      type(probe), intent(in) :: p
      real(wp), intent(in) :: x_min
      if (tracker%beyond_pair >= 0) return
      if (.not. (p%w > 0.0_wp .and. p%x >= x_min)) return
      if (.not. beyond_max_beta(block%region%law(j)%damping, p%w)) return
      tracker%beyond_pair = tracker%pair_first + (j - tracker%j_first)
      tracker%beyond_time = p%t
      tracker%beyond_damping = block%region%law(j)%damping
      tracker%beyond_speed = p%w
   end subroutine watch_domain

   !> Whether any rank met a pair beyond the model's domain (`watch_domain`); found
   !> and the message (`say_beyond_max_beta`, the earliest such pair, the leftmost of
   !> those at that time) the same on every rank. Collective (one MPI_Allgather).
   subroutine beyond_domain(tracker, block, found, message)
      type(contact_tracker), intent(in) :: tracker
      type(chain_block), intent(in) :: block
      logical, intent(out) :: found
      character(len=*), intent(out) :: message
      real(wp) :: mine(4), every(4, block%n_ranks)
      integer :: r, first
      mine = [real(tracker%beyond_pair, wp), tracker%beyond_time, tracker%beyond_damping, &
         & tracker%beyond_speed]
      call MPI_Allgather(mine, 4, MPI_DOUBLE_PRECISION, every, 4, MPI_DOUBLE_PRECISION, &
         & block%comm)
      ! (the ranks hold the pairs from left to right)
      first = 0
      do r = 1, block%n_ranks
         if (every(1, r) < 0.0_wp) cycle
         if (first == 0) then
            first = r
         else if (every(2, r) < every(2, first)) then
            first = r
         end if
      end do
      found = first > 0
      message = ""
      if (found) call say_beyond_max_beta(message, nint(every(1, first)), every(2, first), &
         & every(3, first), every(4, first))
   end subroutine beyond_domain

   !> Whether slot j may have an event in the step from p0 to p1 (its ends): a start
   !> or end, a maximum of the deformation inside, or of the force of an open contact.
   !> Only such slots are sampled (one probe per slot and step otherwise).
   pure logical function eventful(tracker, j, p0, p1)
      type(contact_tracker), intent(in) :: tracker
      integer, intent(in) :: j
      type(probe), intent(in) :: p0, p1
      if (tracker%contact(j)%open) then
         eventful = p1%x < -tracker%x_tol .or. (pressed(tracker, p0, p1) .and. &
            & (new_maximum(p0%x, p0%w, p1%x, p1%w, tracker%contact(j)%deformation) .or. &
            & new_maximum(p0%f, p0%df, p1%f, p1%df, tracker%contact(j)%peak)))
      else
         eventful = p1%x > tracker%x_tol .or. (p0%w > 0.0_wp .and. p1%w <= 0.0_wp)
      end if
   end function eventful

   !> Whether a quantity with the values q0, q1 and rates r0, r1 at the ends of an
   !> interval is looked for a maximum inside it that may beat `so_far`: its rate
   !> falls from > 0 to <= 0 there, and its larger end value is above half of so_far.
   !> A screen: a maximum inside that beats so_far while both ends are below half of
   !> it would have the quantity more than double within the interval, which the step
   !> (its error control resolves the motion) does not allow. It keeps a pair that
   !> stays touching at rest, whose rates wiggle at the level of rounding, from being
   !> searched at every step.
   pure logical function new_maximum(q0, r0, q1, r1, so_far)
      real(wp), intent(in) :: q0, r0, q1, r1, so_far
      new_maximum = r0 > 0.0_wp .and. r1 <= 0.0_wp .and. max(q0, q1) > 0.5_wp * so_far
   end function new_maximum

   !> Whether a pair is pressed beyond the resolution of the integration at either end
   !> of an interval (x > x_tol): only then are its largest deformation and force looked
   !> for inside it (a pair touching at rest wiggles at the level of rounding)
   pure logical function pressed(tracker, p0, p1)
      type(contact_tracker), intent(in) :: tracker
      type(probe), intent(in) :: p0, p1
      pressed = max(p0%x, p1%x) > tracker%x_tol
   end function pressed

   !> One interval [p0%t, p1%t] of slot j (module header)
   subroutine follow(tracker, block, j, p0, p1)
      type(contact_tracker), intent(inout) :: tracker
      type(chain_block), intent(in) :: block
      integer, intent(in) :: j
      type(probe), intent(in) :: p0, p1
      type(probe) :: pc
      if (.not. tracker%contact(j)%open) then
         if (.not. p1%x > tracker%x_tol) return
         call locate(tracker, block, j, of_deformation, p0, p1, pc)
         tracker%contact(j) = open_contact(.true., pc%t, max(pc%w, 0.0_wp), pc%e, &
            & max(p1%f, 0.0_wp), max(p1%x, 0.0_wp))
         ! (its approach speed where it starts)
         call watch_domain(tracker, block, j, pc, -huge(1.0_wp))
         return
      end if
      associate (c => tracker%contact(j))
         if (pressed(tracker, p0, p1) .and. new_maximum(p0%x, p0%w, p1%x, p1%w, &
            & c%deformation)) then
            call locate(tracker, block, j, of_rate, p0, p1, pc)
            c%deformation = max(c%deformation, pc%x)
         end if
         if (pressed(tracker, p0, p1) .and. new_maximum(p0%f, p0%df, p1%f, p1%df, &
            & c%peak)) then
            call locate(tracker, block, j, of_force_rate, p0, p1, pc)
            c%peak = max(c%peak, pc%f)
         end if
         c%deformation = max(c%deformation, p1%x)
         c%peak = max(c%peak, p1%f)
         if (p1%x < -tracker%x_tol) then
            call locate(tracker, block, j, of_deformation, p0, p1, pc)
            c%open = .false.
            ! a touching pair that never pressed was no contact (the serial chain's rule)
            if (c%peak > 0.0_wp) call keep(tracker, contact_record(pair=tracker%pair_first &
               & + (j - tracker%j_first), t_start=c%t_start, t_end=pc%t, &
               & approach_speed=c%approach, separation_speed=max(-pc%w, 0.0_wp), &
               & peak_force=c%peak, max_deformation=c%deformation, &
               & dissipated=pc%e - c%e_base, method=by_integration))
         end if
      end associate
   end subroutine follow

   !> The time in [p0%t, p1%t] where the quantity `what` of slot j crosses 0 (its
   !> sign at p1 differs from that at p0, evaluated afresh on the polynomial), by the
   !> Illinois variant of regula falsi; the probe there. Where the polynomial does not
   !> change sign over the interval (the previous step's end differs from this step's
   !> polynomial there by the rounding of the step), the crossing is taken at p0.
   subroutine locate(tracker, block, j, what, p0, p1, pc)
      type(contact_tracker), intent(inout) :: tracker
      type(chain_block), intent(in) :: block
      integer, intent(in) :: j, what
      type(probe), intent(in) :: p0, p1
      type(probe), intent(out) :: pc
      type(probe) :: pa, pb
      real(wp) :: fa, fb, fc, t
      integer :: it, side
      logical :: converged
      tracker%locations = tracker%locations + 1
      call probe_at(tracker, block, j, p0%t, pa)
      pb = p1
      fa = quantity(pa)
      fb = quantity(pb)
      if ((fa > 0.0_wp) .eqv. (fb > 0.0_wp)) then
         pc = pa
         return
      end if
      pc = pb
      side = 0
      converged = .false.
      do it = 1, max_iterations
         if (pb%t - pa%t <= 4.0_wp * spacing(max(abs(pa%t), abs(pb%t)))) then
            converged = .true.
            exit
         end if
         t = pb%t - fb * (pb%t - pa%t) / (fb - fa)
         ! keep the new point strictly inside (the secant's rounding)
         if (.not. (t > pa%t .and. t < pb%t)) t = 0.5_wp * (pa%t + pb%t)
         call probe_at(tracker, block, j, t, pc)
         fc = quantity(pc)
         if (fc == 0.0_wp) then
            converged = .true.
            exit
         end if
         if ((fc > 0.0_wp) .eqv. (fb > 0.0_wp)) then
            pb = pc
            fb = fc
            if (side == 1) fa = 0.5_wp * fa
            side = 1
         else
            pa = pc
            fa = fc
            if (side == -1) fb = 0.5_wp * fb
            side = -1
         end if
      end do
      if (.not. converged) tracker%unconverged = tracker%unconverged + 1
   contains
      pure real(wp) function quantity(p)
         type(probe), intent(in) :: p
         select case (what)
         case (of_deformation)
            quantity = p%x
         case (of_rate)
            quantity = p%w
         case default
            quantity = p%df
         end select
      end function quantity
   end subroutine locate

   !> Slot j at the time t of the last step, from the polynomials
   subroutine probe_at(tracker, block, j, t, p)
      type(contact_tracker), intent(inout) :: tracker
      type(chain_block), intent(in) :: block
      integer, intent(in) :: j
      real(wp), intent(in) :: t
      type(probe), intent(out) :: p
      type(contact_force_type) :: element
      real(wp) :: dt, u, v, a, du
      integer :: r, k, mr, i_energy
      mr = block%region%m
      dt = t - tracker%t_n
      do r = max(j, 1), min(j + 1, mr)
         if (r <= block%n_left) then
            call taylor_value(tracker%halo(:, 1), dt, u, du)
            call taylor_value(tracker%halo(:, 2), dt, v, a)
         else
            k = r - block%n_left
            call taylor_value(tracker%taylor(:, 3 * k - 2), dt, u, du)
            call taylor_value(tracker%taylor(:, 3 * k - 1), dt, v, a)
         end if
         tracker%y_region(3 * r - 2) = u
         tracker%y_region(3 * r - 1) = v
         tracker%dy_region(3 * r - 2) = v
         tracker%dy_region(3 * r - 1) = a
      end do
      call slot_state(block%region, j, t, tracker%y_region, p%x, p%w, element)
      p%t = t
      p%f = element%force
      p%df = force_rate(block%region, j, tracker%dy_region, p%w, element)
      ! the pair's dissipated energy: a value of the bead on its right (for the right
      ! wall the value after the beads')
      i_energy = 3 * (j + 1 - block%n_left)
      if (j == mr) i_energy = 3 * block%m + 1
      call taylor_value(tracker%taylor(:, i_energy), dt, p%e, du)
   end subroutine probe_at

   !> The value and derivative at t_n + dt of the polynomial with the Taylor
   !> coefficients (derivatives at t_n) d(0:max_order)
   pure subroutine taylor_value(d, dt, value, derivative)
      real(wp), intent(in) :: d(0:max_order), dt
      real(wp), intent(out) :: value, derivative
      ! 1 / k! for k = 0 .. max_order
      real(wp), parameter :: inverse_factorial(0:max_order) = [1.0_wp, 1.0_wp, 0.5_wp, &
         & 1.0_wp / 6.0_wp, 1.0_wp / 24.0_wp, 1.0_wp / 120.0_wp]
      integer :: k
      value = 0.0_wp
      derivative = 0.0_wp
      ! Horner's scheme for sum (d_k / k!) dt^k and its derivative
      do k = max_order, 0, -1
         derivative = derivative * dt + value
         value = value * dt + d(k) * inverse_factorial(k)
      end do
   end subroutine taylor_value

   !> Keep a finished contact
   subroutine keep(tracker, record)
      type(contact_tracker), intent(inout) :: tracker
      type(contact_record), intent(in) :: record
      type(contact_record), allocatable :: grown(:)
      if (tracker%n_records >= size(tracker%records, kind=int64)) then
         allocate(grown(2 * size(tracker%records)))
         grown(1:size(tracker%records)) = tracker%records
         call move_alloc(grown, tracker%records)
      end if
      tracker%n_records = tracker%n_records + 1
      tracker%records(tracker%n_records) = record
   end subroutine keep

   !> The records in the order of their pairs (pair_lo .. pair_hi), those of one pair
   !> in the order they had (a counting sort: stable, O(records + pairs))
   pure subroutine sort_by_pair(records, pair_lo, pair_hi, sorted)
      type(contact_record), intent(in) :: records(:)
      integer, intent(in) :: pair_lo, pair_hi
      type(contact_record), intent(out) :: sorted(:)
      integer, allocatable :: next(:)
      integer :: i, s
      allocate(next(pair_lo:pair_hi + 1))
      next = 0
      do i = 1, size(records)
         next(records(i)%pair + 1) = next(records(i)%pair + 1) + 1
      end do
      next(pair_lo) = 1
      do s = pair_lo + 1, pair_hi + 1
         next(s) = next(s) + next(s - 1)
      end do
      do i = 1, size(records)
         s = records(i)%pair
         sorted(next(s)) = records(i)
         next(s) = next(s) + 1
      end do
   end subroutine sort_by_pair

   !> Every rank's contacts, in the order of their pairs (a pair's in the order they
   !> ended), into `records` on rank 0 (MPI_Gatherv; empty elsewhere). ok false on
   !> every rank, with a message on rank 0, when the list is too long for MPI's counts
   !> (default integers). Collective.
   subroutine gather_contacts(tracker, block, records, ok, message)
      type(contact_tracker), intent(in) :: tracker
      type(chain_block), intent(in) :: block
      type(contact_record), allocatable, intent(out) :: records(:)
      logical, intent(out) :: ok
      character(len=*), intent(out) :: message
      type(contact_record), allocatable :: sorted(:)
      real(wp), allocatable :: local(:, :), gathered(:, :)
      integer(int64), allocatable :: per_rank(:)
      integer, allocatable :: counts(:), displs(:)
      integer(int64) :: n_local, total
      integer :: i, r
      message = ""
      n_local = tracker%n_records
      allocate(sorted(n_local), local(record_doubles, n_local))
      call sort_by_pair(tracker%records(1:n_local), tracker%pair_first, &
         & tracker%pair_first + (tracker%j_last - tracker%j_first), sorted)
      do i = 1, int(n_local)
         local(:, i) = [real(sorted(i)%pair, wp), sorted(i)%t_start, sorted(i)%t_end, &
            & sorted(i)%approach_speed, sorted(i)%separation_speed, sorted(i)%peak_force, &
            & sorted(i)%max_deformation, sorted(i)%dissipated]
      end do
      allocate(per_rank(block%n_ranks))
      per_rank = 0
      call MPI_Gather(n_local, 1, MPI_INTEGER8, per_rank, 1, MPI_INTEGER8, 0, block%comm)
      total = sum(per_rank)
      ok = total * record_doubles <= huge(1)
      call MPI_Bcast(ok, 1, MPI_LOGICAL, 0, block%comm)
      if (.not. ok) then
         write(message, '(a, i0, a)') "the contact list is too long to gather (", total, &
            & " contacts)"
         allocate(records(0))
         return
      end if
      allocate(counts(block%n_ranks), displs(block%n_ranks))
      counts = int(per_rank * record_doubles)
      displs(1) = 0
      do r = 2, block%n_ranks
         displs(r) = displs(r - 1) + counts(r - 1)
      end do
      if (block%rank /= 0) total = 0
      allocate(gathered(record_doubles, total))
      call MPI_Gatherv(local, int(n_local) * record_doubles, MPI_DOUBLE_PRECISION, gathered, &
         & counts, displs, MPI_DOUBLE_PRECISION, 0, block%comm)
      allocate(records(total))
      do i = 1, int(total)
         records(i) = contact_record(pair=nint(gathered(1, i)), t_start=gathered(2, i), &
            & t_end=gathered(3, i), approach_speed=gathered(4, i), &
            & separation_speed=gathered(5, i), &
            & peak_force=gathered(6, i), max_deformation=gathered(7, i), &
            & dissipated=gathered(8, i), &
            & method=by_integration)
      end do
   end subroutine gather_contacts

end module hcimpact_mpi_chain_contacts
