! SPDX-License-Identifier: Apache-2.0
!> Systems of bodies on a line with CVODE for their clusters: `chain_simulate`.
!>
!> The event-driven engine of the core (hcimpact_chain_engine) computes every isolated
!> contact by the closed forms and hands each cluster of overlapping contacts to the
!> integrator of this module: SUNDIALS CVODE (BDF or Adams) with the region's banded
!> Jacobian (hcimpact_cvode_chain_system, from the contact-force element's derivatives)
!> and a linear solver that eliminates the displacements and solves for the velocities
!> (hcimpact_cvode_chain_linear_solver), root finding on every contact's start and
!> end, largest deformation and force peak, and the dissipated energy of every contact
!> integrated with the motion. One step costs O(m) for a region of m bodies.
!>
!> Tolerances: CVODE's relative tolerance is options%rtol; the absolute tolerances are
!> rtol times the natural scales of the region (the smallest maximum compression of
!> its contacts at its largest relative speed, or the static compression under
!> gravity; that speed; the kinetic energy of that speed). The error weights are at
!> a fraction of rtol (`weights_rtol`): the local errors of the steps add up, and BDF (orders
!> up to 5, larger error constants) takes two to three times Adams' steps for the same
!> tolerance, so that a body oscillating for many periods inside a cluster left it far
!> beyond the velocities' bound (bench/chain/attack/repro_bdf_accuracy.py).
!>
!> The state reaches the callbacks only through CVODE's user data (a region owned by
!> the integrator of one call): simulations in different threads share nothing.
module hcimpact_cvode_chain
   use, intrinsic :: iso_c_binding, only : c_int, c_long, c_double, c_ptr, c_int64_t, &
      & c_null_ptr, c_loc, c_funloc, c_f_pointer, c_associated
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
   use hcimpact_kinds, only : wp, nan
   use hcimpact_cvode_report, only : report_detail
   use hcimpact_cvode_halting, only : halting_suspend, halting_resume, callback_enter, &
      & callback_leave
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_solver, hcimpact_err_domain, &
      & hcimpact_err_no_convergence, hcimpact_err_out_of_memory
   use hcimpact_force_element, only : contact_force_type
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, chain_result, &
      & contact_record, by_integration, integrator_adams, method_integrated, not_below_zero, &
      & beyond_max_beta, say_beyond_max_beta
   use hcimpact_chain_engine, only : chain_engine, cluster_integrator, run_engine, &
      & slot_gap0, slot_law, slot_exists, body_state_at, engine_record, capture_margin, &
      & advance_reached, advance_grow_left, advance_grow_right, advance_dissolved, &
      & advance_captured, advance_failed, advance_split, add_wall_impulse, no_memory
   use hcimpact_cvode_chain_system, only : chain_region, region_size, region_rhs, &
      & region_jacobian, region_scales, weights_rtol, slot_state, dissipation_index, &
      & impulse_index, set_weight, wall_impulse, wall_impulse_scale, &
      & force_rate, slot_force_rate, error_weights, upper_band, lower_band, slot_none, slot_pair, &
      & region_frame, frame_motion, first_step, region_rebase, log_touch_step, &
      & slot_left_wall, slot_right_wall, slot_boundary_left, slot_boundary_right
   use hcimpact_cvode_sundials, only : N_Vector, SUNMatrix, SUNLinearSolver, &
      & FN_VGetArrayPointer, FN_VDestroy, FSUNMatDestroy, FSUNLinSolFree, &
      & context_create, context_free, capture_errors
   use hcimpact_cvode_solver, only : cvode_flag_name
   use fcvode_mod, only : FCVodeCreate, FCVodeInit, FCVodeSetUserData, &
      & FCVodeWFtolerances, FCVodeSetLinearSolver, FCVodeSetJacFn, &
      & FCVodeSetMaxNumSteps, FCVodeSetMaxHnilWarns, FCVodeSetInitStep, FCVode, &
      & FCVodeFree, FCVodeSetStopTime, FCVodeGetDky, FCVodeGetNumRhsEvals, &
      & FCVodeGetNumJacEvals, FCVodeReInit, CV_BDF, CV_ADAMS, CV_ONE_STEP, CV_SUCCESS, &
      & CV_MEM_FAIL
   use fnvector_serial_mod, only : FN_VMake_Serial
   use fsunmatrix_band_mod, only : FSUNBandMatrixStorage, FSUNBandMatrix_Data, &
      & FSUNBandMatrix_LDim, FSUNBandMatrix_StoredUpperBandwidth
   use hcimpact_cvode_chain_linear_solver, only : chain_linear_solver
   implicit none
   private

   public :: chain_simulate, cvode_chain_integrator

   !> A contact of the region in progress
   type :: open_contact
      logical :: open = .false.
      !> Start, approach speed, dissipated energy at the start (the state's e), and
      !> what the record holds so far (largest force, deformation; energy dissipated
      !> before this region)
      real(wp) :: t_start = nan, approach = nan, e_base = 0.0_wp, peak = 0.0_wp, &
         & deformation = 0.0_wp, earlier = 0.0_wp
      !> Once closed, the start and approach speed of a contact of the slot that began
      !> touching (approach within the velocities' absolute tolerance) and ended
      !> without pressing beyond the positions' (rounding), while its gap has stayed
      !> within it since; a contact that opens again began then (NaN: none)
      real(wp) :: touching_since = nan, touching_approach = nan
   end type open_contact

   !> A slot at the end of the last step: time, deformation, its rate, force, the
   !> force's rate and the energy dissipated in it so far
   type :: slot_history
      real(wp) :: t = 0.0_wp, x = 0.0_wp, w = 0.0_wp, f = 0.0_wp, df = 0.0_wp, &
         & e = 0.0_wp
   end type slot_history

   !> CVODE on a region of a chain
   type, extends(cluster_integrator) :: cvode_chain_integrator
      type(chain_region), pointer :: region => null()
      real(c_double), pointer, contiguous :: y(:) => null(), atol(:) => null()
      type(c_ptr) :: ctx = c_null_ptr, mem = c_null_ptr
      type(N_Vector), pointer :: y_vec => null(), atol_vec => null()
      type(SUNMatrix), pointer :: jac_mat => null()
      type(SUNLinearSolver), pointer :: lin_sol => null()
      type(open_contact), allocatable :: contact(:)
      type(slot_history), allocatable :: history(:)
      logical :: captured = .false.
      integer(int64) :: rhs_base = 0, jac_base = 0
      !> CVODE's time (the end of the last step); whether the contacts over that step
      !> are still to be followed (up to `next`), and what happens at `next` (a gap at
      !> the boundary that closes there: advance_grow_left or _right)
      real(wp) :: tn = 0.0_wp
      logical :: stepped = .false.
      integer :: due = advance_reached
      !> Whether a contact with the left (1) and right (2) wall opened in the region
      !> (`note_wall`): a wall never touched gave it no impulse
      logical :: wall_touched(2) = .false.
      !> Steps in a row that left the time where it was
      integer :: stalled = 0
      !> A pair that touches (within the positions' tolerance) and closes with b V
      !> beyond the model's domain (`beyond_max_beta`): its slot (-1 if none), the time
      !> and the speed. CVODE crawls through such a contact with steps at the time's
      !> resolution: its deformation stops on a scale below the positions' rounding.
      integer :: beyond = -1
      real(wp) :: beyond_time = 0.0_wp, beyond_speed = 0.0_wp
      !> Per end (1 left, 2 right): whether the boundary pair touched at the start,
      !> gap and relative speed exactly 0 (a pair of touching bodies left outside:
      !> closed_gap of hcimpact_chain_engine). The body outside flies freely and the
      !> forces on the one inside push it outwards only, so such a gap never opens:
      !> it closes as soon as the body inside is pushed.
      logical :: touching(2) = .false.
      !> The size of the last step, or before the first the initial step (s; CVODE's
      !> time)
      real(wp) :: h_last = 0.0_wp
      !> CVODE's time and the region's (that of `chain_region`'s procedures) are the
      !> engine's less `origin` (s): 0 from the region's start, the instant of the
      !> last rebase after one (`rebase`); CVODE's time at the end of the last step
      !> (tn less origin, but exact where tn is rounded); the first step CVODE begins
      !> with (s); whether a slot's law has an exponent below 1 (rebases are looked for)
      real(wp) :: origin = 0.0_wp, tn_cvode = 0.0_wp, h_start = 0.0_wp
      logical :: low_exponent = .false.
      !> The region's frame (`engine_frame`): its start (s), every body's displacement
      !> then (m), and the frame's velocity then (m/s) and acceleration (m/s^2)
      real(wp) :: t0 = 0.0_wp, v_frame = 0.0_wp, a_frame = 0.0_wp
      real(wp), allocatable :: u_ref(:)
   contains
      procedure :: begin => region_begin
      procedure :: advance => region_advance
      procedure :: state_at => region_state_at
      procedure :: finish => region_finish
   end type cvode_chain_integrator

contains

   !> A system of bodies on a line: the closed forms where contacts are isolated,
   !> CVODE for clusters (options%method: auto, exact or integrated). The result as in
   !> hcimpact_chain_types; doc/chains.md.
   !>
   !> Errors: those of `check_chain` (size, not finite, mass, the laws, domain);
   !> hcimpact_err_domain for a cluster with method exact; hcimpact_err_solver
   !> when CVODE fails (the message names its flag); hcimpact_err_no_convergence for
   !> more than options%max_events contacts (give t_end) or max_steps steps;
   !> hcimpact_err_out_of_memory when the memory available cannot hold the system
   !> ("out of memory (what): ...").
   subroutine chain_simulate(chain, result, stat, options)
      !> The system
      type(chain_type), intent(in) :: chain
      !> What is computed
      type(chain_result), intent(out) :: result
      !> Status: hcimpact_ok or an error code of hcimpact_status
      integer, intent(out) :: stat
      !> How (defaults: auto, until no contact can happen, rtol 1e-10, BDF)
      type(chain_options), intent(in), optional :: options
      type(cvode_chain_integrator) :: integrator
      type(chain_options) :: opts
      ! (the options as given: a copy would allocate their sample times unchecked)
      if (present(options)) then
         call run_engine(chain, options, result, stat, integrator)
      else
         call run_engine(chain, opts, result, stat, integrator)
      end if
      call release_all(integrator)
   end subroutine chain_simulate

   ! =================================================================================
   ! The integrator
   ! =================================================================================

   !> Start CVODE on the region self%first .. self%last at engine%time.
   subroutine region_begin(self, engine, stat)
      class(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      integer, intent(out) :: stat
      integer :: m, k, i, j, s, n_state, smu
      integer(c_int) :: ierr
      real(wp) :: x, w, h0, weakest_force, u_out, v_out, stop_time
      real(wp), allocatable :: v_start(:), round_x(:), round_w(:)
      integer :: side
      type(contact_force_type) :: e
      character(len=40) :: where
      !> Per slot: a pair touching at rest, opened now
      logical, allocatable :: resting(:)
      real(c_double), pointer, contiguous :: y(:), atol(:)
      logical :: halting(3)
      integer :: alloc_stat
      real(c_double), allocatable :: probe(:)

      stat = hcimpact_ok
      call release_all(self)
      ! CVODE is not written for trapping floating-point exceptions (module header of
      ! hcimpact_cvode_halting): halting off while it runs, back on in the callbacks
      call halting_suspend(halting)
      m = self%last - self%first + 1
      ! (the region's arrays at once, checked: out of memory, nothing is half made)
      n_state = region_size(m)
      allocate(self%region, stat=alloc_stat)
      if (alloc_stat == 0) allocate(self%region%mass(m), self%region%kind(0:m), &
         & self%region%law(0:m), self%region%gap0(0:m), self%u_ref(m), v_start(m), &
         & round_x(0:m), round_w(0:m), self%y(n_state), self%atol(n_state), &
         & self%contact(0:m), self%history(0:m), resting(0:m), stat=alloc_stat)
      if (alloc_stat /= 0) then
         call out_of_memory("the arrays of a cluster")
         return
      end if
      self%region%halting = halting
      self%region%m = m
      self%region%gravity = engine%gravity
      self%region%mass(:) = engine%chain%mass(self%first:self%last)
      ! the frame: the states at the start, every displacement from its value then
      do k = 1, m
         call body_state_at(engine, self%first + k - 1, engine%time, self%u_ref(k), &
            & v_start(k))
      end do
      self%t0 = engine%time
      do j = 0, m
         s = self%first - 1 + j
         self%region%kind(j) = slot_none
         self%region%gap0(j) = 0.0_wp
         if (s < 0 .or. s > engine%n) cycle
         if (.not. slot_exists(engine, s)) cycle
         self%region%law(j) = slot_law(engine, s)
         self%region%gap0(j) = slot_gap0(engine, s)
         if (j == 0) then
            if (s == 0) then
               self%region%kind(j) = slot_left_wall
            else
               self%region%kind(j) = slot_boundary_left
            end if
         else if (j == m) then
            if (s == engine%n) then
               self%region%kind(j) = slot_right_wall
            else
               self%region%kind(j) = slot_boundary_right
            end if
         else
            self%region%kind(j) = slot_pair
         end if
      end do
      ! without a wall, the frame falls freely, and where all bodies move the same way
      ! it moves with the slowest of them (`engine_frame`)
      call region_frame(self%region, v_start, self%v_frame, self%a_frame)
      self%region%gravity = self%region%gravity - self%a_frame
      call set_weight(self%region)
      ! the gaps at zero displacements in the frame, and the bodies outside: their
      ! free flight from now, relative to their neighbour's reference and the frame;
      ! and per slot the rounding of the engine's states it comes from (`snap_touching`)
      round_x = 0.0_wp
      round_w = 0.0_wp
      do j = 0, m
         select case (self%region%kind(j))
         case (slot_pair)
            self%region%gap0(j) = self%region%gap0(j) + (self%u_ref(j + 1) - self%u_ref(j))
            round_x(j) = spacing(max(abs(self%u_ref(j)), abs(self%u_ref(j + 1))))
            round_w(j) = spacing(max(abs(v_start(j)), abs(v_start(j + 1))))
         case (slot_left_wall)
            self%region%gap0(j) = self%region%gap0(j) + self%u_ref(1)
            round_x(j) = spacing(abs(self%u_ref(1)))
            round_w(j) = spacing(abs(v_start(1)))
         case (slot_right_wall)
            self%region%gap0(j) = self%region%gap0(j) - self%u_ref(m)
            round_x(j) = spacing(abs(self%u_ref(m)))
            round_w(j) = spacing(abs(v_start(m)))
         case (slot_boundary_left, slot_boundary_right)
            side = merge(1, 2, j == 0)
            k = merge(1, m, j == 0)
            call body_state_at(engine, merge(self%first - 1, self%last + 1, j == 0), &
               & engine%time, u_out, v_out)
            self%region%out_t0(side) = engine%time
            self%region%out_u0(side) = u_out - self%u_ref(k)
            self%region%out_v0(side) = v_out - self%v_frame
            round_x(j) = spacing(max(abs(u_out), abs(self%u_ref(k))))
            round_w(j) = spacing(max(abs(v_out), abs(v_start(k))))
         end select
      end do
      self%y = 0.0_wp
      self%y(2:3 * m:3) = v_start - self%v_frame

      ! scales: the largest relative speed, the smallest maximum compression at it
      call region_scales(self%region, self%y, self%region%scale, weakest_force, &
         & merge(engine%options%t_end - engine%time, huge(1.0_wp), &
         & engine%options%t_end > 0.0_wp), stop_time)
      ! forces below the normal range of doubles keep fewer bits than the tolerance
      ! needs (two bodies of 1 kg, c = 1e9 N/m^1.5, touching at 1e-270 m/s were
      ! integrated to 7e-8 relative with success, and at 1e-300 m/s ran to max_steps)
      if (weakest_force < tiny(1.0_wp)) then
         stat = hcimpact_err_domain
         write(engine%message, '(a, es11.3e3, a, i0, a, i0, a, es11.3e3, a)') "at t = ", &
            & engine%time, " s the contacts of bodies ", self%first, " to ", self%last, &
            & " have peak forces down to ", weakest_force, " N, below the normal range " &
            & // "of doubles, which the integration cannot resolve (method auto computes " &
            & // "an isolated contact by the closed forms where its duration is a double)"
         ! (a region that did not begin is not finished: nothing else frees it)
         call release_all(self)
         call halting_resume(halting)
         return
      end if
      call take_scales(self, engine%options%rtol)
      self%region%rtol = weights_rtol(engine%options%rtol, &
         & engine%options%integrator == integrator_adams)

      call snap_touching(self%region, engine%time, round_x, self%y)

      ! the contacts in progress: handed over by the closed forms or an earlier region;
      ! and every slot's state now, the start of the first step's interpolants
      resting = .false.
      self%wall_touched = .false.
      do j = 0, m
         s = self%first - 1 + j
         if (self%region%kind(j) == slot_none) cycle
         call slot_state(self%region, j, engine%time, self%y, x, w, e)
         self%history(j) = slot_history(engine%time, x, w, e%force, 0.0_wp, 0.0_wp)
         if (self%region%kind(j) == slot_boundary_left) self%touching(1) = &
            & x == 0.0_wp .and. abs(w) <= 2.0_wp * round_w(j)
         if (self%region%kind(j) == slot_boundary_right) self%touching(2) = &
            & x == 0.0_wp .and. abs(w) <= 2.0_wp * round_w(j)
         if (self%region%kind(j) == slot_boundary_left .or. self%region%kind(j) == &
            & slot_boundary_right) cycle
         ! a touching pair's memory from a region closed at this instant (grown)
         if (.not. ieee_is_nan(engine%exact(s)%touching_at)) then
            if (engine%exact(s)%touching_at == engine%time .and. x >= -max(self%atol(1), &
               & 2.0_wp * round_x(j))) then
               self%contact(j)%touching_since = engine%exact(s)%touching_since
               self%contact(j)%touching_approach = engine%exact(s)%touching_approach
            end if
         end if
         engine%exact(s)%touching_at = nan
         if (engine%exact(s)%handed) then
            self%contact(j) = open_contact(open=.true., t_start=engine%exact(s)%t_start, &
               & approach=engine%exact(s)%contact%velocity, e_base=0.0_wp, &
               & peak=engine%exact(s)%so_far_peak, &
               & deformation=engine%exact(s)%so_far_deformation, &
               & earlier=engine%exact(s)%so_far_dissipated)
            call note_wall(self, j)
            engine%exact(s)%handed = .false.
         else if (x >= 0.0_wp) then
            ! in contact, or touching: a touching pair that is pushed is in contact
            ! from now
            call open_at(self, j, engine%time, max(w, 0.0_wp), 0.0_wp)
            resting(j) = x == 0.0_wp .and. abs(w) <= 2.0_wp * round_w(j)
         end if
      end do
      ! pairs touching at rest next to a contact in progress (a region grown over a
      ! touching chain): pushed through it, they have been in contact since it began
      do j = 1, m
         if (resting(j) .and. self%contact(j - 1)%open) self%contact(j)%t_start = &
            & min(self%contact(j)%t_start, self%contact(j - 1)%t_start)
      end do
      do j = m - 1, 0, -1
         if (resting(j) .and. self%contact(j + 1)%open) self%contact(j)%t_start = &
            & min(self%contact(j)%t_start, self%contact(j + 1)%t_start)
      end do
      self%captured = .false.
      self%time = engine%time
      self%next = engine%time
      self%tn = engine%time
      self%origin = 0.0_wp
      self%tn_cvode = engine%time
      self%low_exponent = .false.
      do j = 0, m
         if (any(self%region%kind(j) == [slot_pair, slot_left_wall, slot_right_wall])) &
            & self%low_exponent = self%low_exponent .or. self%region%law(j)%exponent < 1.0_wp
      end do
      self%stepped = .false.
      self%due = advance_reached
      self%stalled = 0
      self%beyond = -1

      ! SUNDIALS 6's N_VClone dereferences the clone it failed to allocate (CVodeInit
      ! crashed out of memory): the memory of CVODE's vectors and band matrix, with a
      ! factor 2 to spare, is tried first and given back
      allocate(probe(2 * int(n_state, int64) * (24 + upper_band + lower_band)), &
         & stat=alloc_stat)
      if (alloc_stat /= 0) then
         call out_of_memory("CVODE's vectors and matrix")
         return
      end if
      deallocate(probe)
      setup: block
         where = "SUNContext_Create"
         ierr = context_create(self%ctx)
         if (ierr /= 0) exit setup
         where = "N_VMake_Serial"
         ierr = -1
         ! Through contiguous local pointers: passed as components of the polymorphic
         ! self, gfortran 12 packs them at run time (a copy the vectors would keep).
         y => self%y
         atol => self%atol
         self%y_vec => FN_VMake_Serial(int(n_state, c_int64_t), y, self%ctx)
         self%atol_vec => FN_VMake_Serial(int(n_state, c_int64_t), atol, self%ctx)
         if (.not. (associated(self%y_vec) .and. associated(self%atol_vec))) exit setup
         where = "CVodeCreate"
         if (engine%options%integrator == integrator_adams) then
            self%mem = FCVodeCreate(CV_ADAMS, self%ctx)
         else
            self%mem = FCVodeCreate(CV_BDF, self%ctx)
         end if
         if (.not. c_associated(self%mem)) exit setup
         where = "CVodeSetErrHandler"
         ierr = capture_errors(self%ctx, self%mem, c_loc(self%region%report))
         if (ierr /= 0) exit setup
         where = "CVodeInit"
         ierr = FCVodeInit(self%mem, c_funloc(chain_rhs_callback), real(engine%time, c_double), &
            & self%y_vec)
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetUserData"
         ierr = FCVodeSetUserData(self%mem, c_loc(self%region))
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeWFtolerances"
         ierr = FCVodeWFtolerances(self%mem, c_funloc(chain_error_weights))
         if (ierr /= CV_SUCCESS) exit setup
         where = "SUNBandMatrixStorage"
         ierr = -1
         ! (stored upper bandwidth = the upper one: no room for the band LU's pivoting,
         ! which the region's own linear solver does not do)
         self%jac_mat => FSUNBandMatrixStorage(int(n_state, c_int64_t), &
            & int(min(upper_band, n_state - 1), c_int64_t), &
            & int(min(lower_band, n_state - 1), c_int64_t), &
            & int(min(upper_band, n_state - 1), c_int64_t), self%ctx)
         if (.not. associated(self%jac_mat)) exit setup
         where = "the region's linear solver"
         self%lin_sol => chain_linear_solver(self%region, self%ctx)
         if (.not. associated(self%lin_sol)) exit setup
         where = "CVodeSetLinearSolver"
         ierr = FCVodeSetLinearSolver(self%mem, self%lin_sol, self%jac_mat)
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetJacFn"
         ierr = FCVodeSetJacFn(self%mem, c_funloc(chain_jacobian_callback))
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetInitStep"
         h0 = first_step(engine%options%rtol, self%region%scale, stop_time)
         self%h_start = h0
         if (self%first_step > 0.0_wp) h0 = self%first_step
         self%h_last = h0
         ierr = FCVodeSetInitStep(self%mem, real(h0, c_double))
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetMaxNumSteps"
         ierr = FCVodeSetMaxNumSteps(self%mem, int(huge(1_c_int), c_long))
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetMaxHnilWarns"
         ierr = FCVodeSetMaxHnilWarns(self%mem, -1_c_int)
         if (ierr /= CV_SUCCESS) exit setup
      end block setup
      if (ierr /= 0) then
         ! (a context or a constructor that fails, or CV_MEM_FAIL: CVODE's memory)
         if (ierr == -1 .or. ierr == CV_MEM_FAIL .or. where == "SUNContext_Create") then
            stat = hcimpact_err_out_of_memory
            call no_memory(engine, "CVODE's vectors and matrix in " // trim(where))
         else
            stat = hcimpact_err_solver
            engine%message = "CVODE setup failed in " // trim(where) // ": " &
               & // cvode_flag_name(ierr) // report_detail(self%region%report)
         end if
         call release_all(self)
         call halting_resume(halting)
         return
      end if
      if (engine%options%t_end > 0.0_wp) then
         ! (steps end there: the states at t_end are CVODE's, not an extrapolation)
         ierr = FCVodeSetStopTime(self%mem, real(engine%options%t_end, c_double))
      end if
      call halting_resume(halting)
      smu = 0
      self%rhs_base = 0
      self%jac_base = 0
   contains
      !> An allocation of the setup failed: nothing of the region is kept
      subroutine out_of_memory(what)
         character(len=*), intent(in) :: what
         call release_all(self)
         call halting_resume(halting)
         call no_memory(engine, what)
         stat = hcimpact_err_out_of_memory
      end subroutine out_of_memory
   end subroutine region_begin

   !> At engine%time = self%next: follow the contacts over the last step up to next
   !> and report what happens there (a boundary gap that closes: grow; the region
   !> apart: dissolved; at rest: captured); else take the next step (never beyond
   !> t_end) and find where the engine must come back: the end of the step, or the
   !> first instant in it at which a gap at the boundary closes.
   subroutine region_advance(self, engine, t_end, what, stat)
      class(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      real(wp), intent(in) :: t_end
      integer, intent(out) :: what, stat
      integer(c_int) :: ierr
      real(c_double) :: tret(1)
      integer :: m, alloc_stat
      real(wp), allocatable :: u(:), v(:)
      logical :: ended, halting(3)
      ! steps in a row that did not advance the time, and how many are tolerated
      integer, parameter :: max_stalled = 100

      stat = hcimpact_ok
      what = advance_reached
      if (.not. associated(self%region)) return
      m = self%region%m
      call halting_suspend(halting)
      self%region%halting = halting
      run: block
         if (self%stepped) then
            self%stepped = .false.
            ! (self%y holds the state at the end of the step)
            if (self%next < self%tn) call move_to(self, self%next)
            call follow_contacts(self, engine, self%next, ended)
            if (self%out_of_memory) exit run
            if (self%beyond >= 0) then
               stat = hcimpact_err_domain
               call say_beyond_max_beta(engine%message, self%first - 1 + self%beyond, &
                  & self%beyond_time, self%region%law(self%beyond)%damping, &
                  & self%beyond_speed)
               what = advance_failed
               exit run
            end if
            if (self%due /= advance_reached) then
               ! a gap at the boundary closed here: the region grows
               what = self%due
               exit run
            end if
            ! apart: back to the closed forms; with the integrated method only once
            ! no contact can ever happen again (the rest is free flight). Checked
            ! after a contact ended, and while no contact of the region has pressed
            ! yet (bodies that touch without force and never approach: no contact
            ! ever ends, and the steps would grow until the time overflowed)
            if (ended .or. .not. any(self%contact(0:m)%open .and. &
               & self%contact(0:m)%peak > 0.0_wp)) then
               if (separated(self)) then
                  if (engine%options%method /= method_integrated .or. &
                     & never_again(self, engine)) then
                     what = advance_dissolved
                     exit run
                  end if
               end if
            end if
            ! at rest on a wall under gravity, for good (reported once per region)
            if (engine%gravity /= 0.0_wp .and. .not. self%captured) then
               allocate(u(m), v(m), stat=alloc_stat)
               if (alloc_stat /= 0) self%out_of_memory = .true.
               if (self%out_of_memory) exit run
               call engine_frame(self, self%time, self%y, u, v)
               if (capture_margin(engine, self%first, self%last, u, v) < 0.0_wp) then
                  self%captured = .true.
                  what = advance_captured
                  exit run
               end if
            end if
            ! bodies apart from their neighbours: the closed forms take them back
            ! (not with the integrated method, which integrates every contact; nor
            ! on the wall gravity points to, where what leaves falls back: a ball of
            ! 10 g dropped 0.1 mm onto a stack of three on a floor split off and merged
            ! again at every bounce, 323 to 369 regions to 0.3 s at rtol 1e-8 to
            ! 1e-12, each beginning CVODE at order 1, against 24 to 49 without, in 1.5
            ! to 2.7 times the time)
            if (engine%options%method /= method_integrated .and. .not. falls_back(self)) then
               if (split_parts(self)) then
                  what = advance_split
                  self%due = what
                  exit run
               end if
               if (self%out_of_memory) exit run
            end if
         end if
         if (.not. t_end > self%time) exit run
         if (self%tn == self%time .and. too_short(t_end - self%tn, &
            & max(abs(self%tn), abs(t_end)), self%h_last)) then
            call drift_to(self, engine, t_end, stat)
            if (stat /= hcimpact_ok) what = advance_failed
            exit run
         end if
         if (engine%counters%steps >= engine%options%max_steps) then
            stat = hcimpact_err_no_convergence
            write(engine%message, '(a, es11.3e3, a, i0, a)') "CVODE at t = ", self%time, &
               & " s: more than options%max_steps = ", engine%options%max_steps, " steps"
            what = advance_failed
            exit run
         end if
         ! CVODE grows h by a factor of 10^4 at most (its first steps), and h is below
         ! the time elapsed: beyond huge * 1e-6 the next step could leave the range
         ! of doubles, where CVODE would go on with an infinite time and NaN states
         if (self%time > huge(1.0_wp) * 1.0e-6_wp) then
            stat = hcimpact_err_solver
            write(engine%message, '(a, es11.3e3, a)') "CVODE at t = ", self%time, &
               & " s: the time is about to leave the range of doubles"
            what = advance_failed
            exit run
         end if
         ! a contact of an exponent below 1 about to start where CVODE's time or the
         ! displacements no longer resolve its first steps: the region begins anew
         if (self%low_exponent .and. self%tn == self%time) then
            if (wants_rebase(self)) then
               call rebase(self, engine, stat)
               if (stat /= hcimpact_ok) then
                  what = advance_failed
                  exit run
               end if
            end if
         end if
         ! (one step: tout gives only the direction; a huge one upsets CVODE's first step)
         ierr = FCVode(self%mem, real(min(t_end - self%origin, self%tn_cvode + 1.0_wp), &
            & c_double), self%y_vec, tret, CV_ONE_STEP)
         if (ierr < 0) then
            stat = hcimpact_err_solver
            write(engine%message, '(a, es11.3e3, a)') "CVODE failed at t = ", &
               & self%origin + tret(1), " s: " // cvode_flag_name(ierr) &
               & // report_detail(self%region%report)
            call beyond_domain(self, engine, tret(1), stat)
            what = advance_failed
            exit run
         end if
         ! steps too small to move the time (t + h = t: forces that change on a scale
         ! below the time's resolution) would go on until max_steps, 1e8 by default
         if (tret(1) > self%tn_cvode) then
            self%stalled = 0
         else
            self%stalled = self%stalled + 1
            if (self%stalled > max_stalled) then
               stat = hcimpact_err_solver
               write(engine%message, '(a, es11.3e3, a, i0, a)') "CVODE at t = ", self%tn, &
                  & " s: ", max_stalled, " steps in a row did not advance the time (steps " &
                  & // "below its resolution)"
               what = advance_failed
               exit run
            end if
         end if
         if (tret(1) > self%tn_cvode) self%h_last = tret(1) - self%tn_cvode
         self%tn_cvode = max(tret(1), self%tn_cvode)
         self%tn = max(self%origin + tret(1), self%tn)
         engine%counters%steps = engine%counters%steps + 1
         self%stepped = .true.
         call boundary_closing(self)
      end block run
      ! (an allocation of the work arrays failed, here or in what was called)
      if (self%out_of_memory) then
         call no_memory(engine, "the work arrays of a cluster")
         stat = hcimpact_err_out_of_memory
         what = advance_failed
      end if
      call halting_resume(halting)
   end subroutine region_advance

   !> After CVODE failed at its time t (self%y its state there): where a contact of
   !> the region is open or closing with b V beyond the model's domain
   !> (`beyond_max_beta`: the corrector fails on such contacts), that is what stat and
   !> the message say (hcimpact_err_domain), the first such pair from the left.
   subroutine beyond_domain(self, engine, t, stat)
      type(cvode_chain_integrator), intent(in) :: self
      type(chain_engine), intent(inout) :: engine
      real(wp), intent(in) :: t
      integer, intent(inout) :: stat
      real(wp) :: x, w
      type(contact_force_type) :: e
      integer :: j
      do j = 0, self%region%m
         if (.not. any(self%region%kind(j) == [slot_pair, slot_left_wall, slot_right_wall])) &
            & cycle
         call slot_state(self%region, j, t, self%y, x, w, e)
         if (.not. (w > 0.0_wp .or. x >= 0.0_wp)) cycle
         if (beyond_max_beta(self%region%law(j)%damping, w)) then
            stat = hcimpact_err_domain
            call say_beyond_max_beta(engine%message, self%first - 1 + j, self%origin + t, &
               & self%region%law(j)%damping, w)
            return
         end if
      end do
   end subroutine beyond_domain

   !> Whether the region holds the wall that gravity points to (a body that leaves it
   !> falls back).
   pure logical function falls_back(self)
      type(cvode_chain_integrator), intent(in) :: self
      falls_back = (self%region%kind(0) == slot_left_wall .and. self%region%gravity < 0.0_wp) &
         & .or. (self%region%kind(self%region%m) == slot_right_wall .and. &
         & self%region%gravity > 0.0_wp)
   end function falls_back

   !> After the contacts were followed to self%time: whether the region should split
   !> (self%parts, self%n_parts in the engine's numbering). A body is free where both
   !> its slots are apart: beyond the positions' tolerance and not closing, with no
   !> contact open nor a touching pair's start remembered (close_contact); a closing
   !> gap joins its bodies, so that a part does not grow again at once over a body it
   !> has just let go. The other bodies fall into
   !> runs joined by slots that are not apart; a run with a contact open goes on as a
   !> part, a run without one flies freely too (as a region that has separated
   !> dissolves). The region splits when that frees at least a quarter of its bodies
   !> (each part begins CVODE anew, with the step the region had reached but at order
   !> 1: as for a growth, about 35 steps of climbing), and where the engine's frame,
   !> which the states pass through, holds them within their tolerances (three
   !> touching balls falling freely, struck at 1e-50 m/s, are 5e12 m down, whose ulp
   !> is 1e-3 m, when the first leaves: the other two, 1e-40 m into each other, would
   !> begin again with that compression lost). From the slots' states at self%time
   !> (self%history): O(m), against a step's O(m) of a larger constant, and no work
   !> array unless the free bodies are enough.
   logical function split_parts(self) result(split)
      type(cvode_chain_integrator), intent(inout) :: self
      integer :: m, k, first, kept, n_free, alloc_stat
      logical :: pressed, left_apart, right_apart
      logical, allocatable :: free(:)
      real(wp), allocatable :: u(:), v(:)
      split = .false.
      m = self%region%m
      if (m < 2) return
      n_free = 0
      left_apart = apart(0)
      do k = 1, m
         right_apart = apart(k)
         if (left_apart .and. right_apart) n_free = n_free + 1
         left_apart = right_apart
      end do
      if (n_free < max(1, m / 4)) return
      ! (out of memory: no split, self%out_of_memory)
      allocate(free(m), stat=alloc_stat)
      if (alloc_stat /= 0) then
         self%out_of_memory = .true.
         return
      end if
      do k = 1, m
         free(k) = apart(k - 1) .and. apart(k)
      end do
      if (allocated(self%parts)) then
         if (size(self%parts, 2) < m) deallocate(self%parts)
      end if
      if (.not. allocated(self%parts)) then
         allocate(self%parts(2, m), stat=alloc_stat)
         if (alloc_stat /= 0) then
            self%out_of_memory = .true.
            return
         end if
      end if
      self%n_parts = 0
      kept = 0
      k = 1
      do while (k <= m)
         if (free(k)) then
            k = k + 1
            cycle
         end if
         ! a run first .. k - 1, and whether a contact of it is open (its slots
         ! first - 1 .. k - 1: those at its ends are apart or a wall's)
         first = k
         pressed = self%contact(first - 1)%open
         do while (k <= m)
            if (free(k)) exit
            pressed = pressed .or. self%contact(k)%open
            k = k + 1
         end do
         if (.not. pressed) cycle
         self%n_parts = self%n_parts + 1
         self%parts(:, self%n_parts) = [self%first + first - 1, self%first + k - 2]
         kept = kept + (k - first)
      end do
      if (m - kept < max(1, m / 4)) return
      allocate(u(m), v(m), stat=alloc_stat)
      if (alloc_stat /= 0) then
         self%out_of_memory = .true.
         return
      end if
      call engine_frame(self, self%time, self%y, u, v)
      if (spacing(maxval(abs(u))) > self%atol(1) .or. spacing(maxval(abs(v))) &
         & > self%atol(2)) return
      split = .true.
   contains
      logical function apart(j)
         integer, intent(in) :: j
         apart = .true.
         if (self%region%kind(j) == slot_none) return
         apart = .not. self%contact(j)%open .and. ieee_is_nan(self%contact(j)%touching_since) &
            & .and. self%history(j)%t == self%time .and. self%history(j)%x < -self%atol(1) &
            & .and. self%history(j)%w <= 0.0_wp
      end function apart
   end function split_parts

   !> At a region's start (all displacements 0 in its frame): a slot whose deformation
   !> is within two ulps of the engine's displacements it was formed from (round_x)
   !> touches: its deformation is made exactly 0 (the gap at zero displacements, or
   !> the position of the body outside), below what the engine's states resolve. The
   !> engine keeps every body's displacement, of the size of how far it has gone, and
   !> a body that was integrated in a region comes back with that rounding, where a
   !> body beside it that has flown freely all along has none: a chain of touching
   !> balls falling freely 490 m, struck at 0.1 m/s, saw its touching pairs 5.7e-14 m
   !> apart as the region grew over them, and recorded their contacts from when that
   !> gap closed, 6.3e-5 s late, with approach speeds of 6e-9 m/s; and falling 68000 m,
   !> the pair whose contact the engine starts now (the cluster forms then) was 2.9e-12
   !> m apart, the region dissolved at once as nothing touched, formed again, and the
   !> contacts came 3e-4 s late (bench/chain/attack/repro_frame_attack.py). The rates
   !> are left as they are; round_w gives the touching tests of region_begin theirs.
   pure subroutine snap_touching(region, t, round_x, y)
      type(chain_region), intent(inout) :: region
      !> The region's start, and its state then
      real(wp), intent(in) :: t, round_x(0:), y(:)
      real(wp) :: x, w
      type(contact_force_type) :: e
      integer :: j
      do j = 0, region%m
         if (region%kind(j) == slot_none) cycle
         call slot_state(region, j, t, y, x, w, e)
         if (x == 0.0_wp .or. abs(x) > 2.0_wp * round_x(j)) cycle
         select case (region%kind(j))
         case (slot_pair, slot_left_wall, slot_right_wall)
            region%gap0(j) = 0.0_wp
         case (slot_boundary_left)
            region%out_u0(1) = region%gap0(j)
         case (slot_boundary_right)
            region%out_u0(2) = -region%gap0(j)
         end select
      end do
   end subroutine snap_touching

   !> Whether the interval dt from CVODE's time to t_end (both about t_scale) is too
   !> short for a step of CVODE: within a few ulps of the time (CVODE refuses an
   !> output time that close), or short against the step h the region takes (below
   !> epsilon h: CVODE's first checks, (t_end - t) h, can underflow, as at t_end =
   !> 5e-324). A Taylor step of first order is exact to rounding there (`drift_to`).
   pure logical function too_short(dt, t_scale, h)
      real(wp), intent(in) :: dt, t_scale, h
      too_short = dt <= 8.0_wp * spacing(t_scale) .or. dt <= epsilon(1.0_wp) * h
   end function too_short

   !> Carry the region from CVODE's time (self%time, no step pending) to t_end, too
   !> short an interval for CVODE (`too_short`), by one Taylor step of first order,
   !> y + (t_end - t) y': its error, of second order, is below rounding there. No
   !> contact starts or ends within it (one that does is in progress at t_end).
   subroutine drift_to(self, engine, t_end, stat)
      type(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      real(wp), intent(in) :: t_end
      integer, intent(out) :: stat
      real(wp), allocatable :: dy(:)
      logical :: ok
      integer :: alloc_stat
      stat = hcimpact_ok
      allocate(dy(size(self%y)), stat=alloc_stat)
      if (alloc_stat /= 0) then
         call no_memory(engine, "the work arrays of a cluster")
         stat = hcimpact_err_out_of_memory
         return
      end if
      call region_rhs(self%region, self%time - self%origin, self%y, dy, ok)
      if (.not. ok) then
         stat = hcimpact_err_solver
         write(engine%message, '(a, es11.3e3, a)') "at t = ", self%time, &
            & " s: a force of the region is not finite"
         return
      end if
      self%y = self%y + (t_end - self%time) * dy
      engine%counters%rhs_evals = engine%counters%rhs_evals + 1
      self%time = t_end
      self%tn = t_end
      self%tn_cvode = t_end - self%origin
      self%next = t_end
      self%stepped = .false.
   end subroutine drift_to

   !> Whether the region should begin anew (`rebase`) before its next step: a slot
   !> whose law has an exponent n below 1 closes (rate w > 0) with its touch near,
   !> where CVODE's time or its bodies' displacements no longer resolve the steps
   !> that the error test asks across the touch, h = (tol mu / (c w^n))^(1 / (n + 1))
   !> (`log_touch_step`, tol the weights' rtol times v_ref): the force rises as t^n,
   !> and at n = 0.3, rtol 1e-10, h = 5e-16 s, below half an ulp of t = 10 s, where
   !> CVODE's steps no longer moved the time ("100 steps in a row did not advance the
   !> time"). Needed where the spacing of the region's time (CVODE's) exceeds h /
   !> margin, or the spacing of the slot's displacements exceeds w h / margin; near
   !> where the touch is ahead within h / (margin^2 eps) (after the rebase, the
   !> time of the touch resolves h to 2 / margin^2 of it, and the test above is not
   !> met again before it), or came within margin h before (a step that crossed it).
   !> With exponents of 1 and above, never (the region keeps its start: h is far
   !> above the time's resolution, 1e-8 s at n = 1.5 in the case above). From the
   !> state at the end of the last step, O(m).
   function wants_rebase(self) result(wanted)
      type(cvode_chain_integrator), intent(in) :: self
      logical :: wanted
      !> How far from the resolution a rebase is made
      real(wp), parameter :: margin = 64.0_wp
      real(wp) :: x, w, lh, tol, reach, lmargin
      type(contact_force_type) :: e
      integer :: j, m
      logical :: near, needed
      wanted = .false.
      m = self%region%m
      tol = self%region%rtol * self%region%scale(2)
      lmargin = log(margin)
      do j = 0, m
         if (.not. any(self%region%kind(j) == [slot_pair, slot_left_wall, slot_right_wall])) &
            & cycle
         if (.not. self%region%law(j)%exponent < 1.0_wp) cycle
         call slot_state(self%region, j, self%tn_cvode, self%y, x, w, e)
         if (.not. w > 0.0_wp) cycle
         lh = log_touch_step(self%region, j, w, tol)
         if (.not. lh < 0.5_wp * huge(1.0_wp)) cycle
         ! (by logarithms: x / w may leave the range)
         if (x < 0.0_wp) then
            near = log(-x) - log(w) <= lh - 2.0_wp * lmargin - log(epsilon(1.0_wp))
         else
            near = x == 0.0_wp
            if (.not. near) near = log(x) - log(w) <= lh + lmargin
         end if
         if (.not. near) cycle
         select case (self%region%kind(j))
         case (slot_pair)
            reach = max(abs(self%y(3 * j - 2)), abs(self%y(3 * j + 1)))
         case (slot_left_wall)
            reach = abs(self%y(1))
         case default
            reach = abs(self%y(3 * m - 2))
         end select
         needed = log(spacing(abs(self%tn_cvode))) > lh - lmargin .or. &
            & log(spacing(reach)) > log(w) + lh - lmargin
         if (needed) then
            wanted = .true.
            return
         end if
      end do
   end function wants_rebase

   !> The absolute tolerances (self%atol: displacements, velocities, energies, the
   !> dissipated energy, the walls' impulses) and the walls' impulse scale from the
   !> region's scales (self%region%scale), each rtol times its scale.
   subroutine take_scales(self, rtol)
      type(cvode_chain_integrator), intent(inout) :: self
      real(wp), intent(in) :: rtol
      integer :: k, m
      m = self%region%m
      do k = 1, m
         self%atol(3 * k - 2) = rtol * self%region%scale(1)
         self%atol(3 * k - 1) = rtol * self%region%scale(2)
         self%atol(3 * k) = rtol * self%region%scale(3)
      end do
      self%atol(dissipation_index(m, m)) = rtol * self%region%scale(3)
      self%region%impulse_scale = wall_impulse_scale(self%region%mass, self%region%scale(2))
      self%atol(impulse_index(m, 1):) = rtol * self%region%impulse_scale
   end subroutine take_scales

   !> Begin the region anew at the end of its last step (self%time = self%tn, no step
   !> pending): its displacements counted from there (`region_rebase`: every
   !> deformation kept, the bodies' references u_ref moved by what they had gone),
   !> CVODE's time from there (origin), and CVODE restarted (CVodeReInit: order 1,
   !> the region's first step, its counters added to the engine's first), its scales
   !> those of the state where they are larger (`region_scales`; the tolerances with
   !> them, `take_scales`). The velocities, energies, impulses, the frame and the
   !> contacts' records go on as they were.
   subroutine rebase(self, engine, stat)
      type(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      integer, intent(out) :: stat
      integer(c_int) :: ierr
      integer :: m
      character(len=24) :: where
      real(wp) :: scale(3), weakest_force, stop_time, horizon
      stat = hcimpact_ok
      m = self%region%m
      call add_counters(self, engine)
      self%u_ref = self%u_ref + self%y(1:3 * m:3)
      call region_rebase(self%region, self%tn_cvode, self%y)
      self%origin = self%tn
      self%tn_cvode = 0.0_wp
      ! the scales of the state now where they are larger than the region's from its
      ! start: a ball that began the region at rest under gravity and falls onto a
      ! damped floor of n < 1 kept v_ref = 3e-8 m/s (a fall through the static
      ! compression) and e_ref = 4.5e-16 J to the touch at 10 m/s, and the
      ! dissipated energy's tolerance then asked for steps near 1e-25 s there
      horizon = huge(1.0_wp)
      if (engine%options%t_end > 0.0_wp) horizon = engine%options%t_end - self%tn
      call region_scales(self%region, self%y, scale, weakest_force, horizon, stop_time)
      self%region%scale = max(self%region%scale, scale)
      call take_scales(self, engine%options%rtol)
      self%h_last = self%h_start
      self%stalled = 0
      where = "CVodeReInit"
      ierr = FCVodeReInit(self%mem, 0.0_c_double, self%y_vec)
      if (ierr == CV_SUCCESS) then
         where = "CVodeSetInitStep"
         ierr = FCVodeSetInitStep(self%mem, real(self%h_start, c_double))
      end if
      if (ierr == CV_SUCCESS .and. engine%options%t_end > 0.0_wp) then
         where = "CVodeSetStopTime"
         ierr = FCVodeSetStopTime(self%mem, real(engine%options%t_end - self%origin, c_double))
      end if
      if (ierr /= CV_SUCCESS) then
         stat = hcimpact_err_solver
         write(engine%message, '(a, es11.3e3, a)') "CVODE at t = ", self%origin, &
            & " s: restart failed in " // trim(where) // ": " // cvode_flag_name(ierr) &
            & // report_detail(self%region%report)
      end if
   end subroutine rebase

   !> After a step: where the engine must come back (self%next, self%due): the first
   !> instant in the step at which a gap at the region's boundary closes (from the
   !> cubic Hermite interpolant of its deformation and rate between the step's ends),
   !> else the end of the step. self%y holds the state at the end of the step.
   subroutine boundary_closing(self)
      type(cvode_chain_integrator), intent(inout) :: self
      real(wp) :: x, w, h, tc, wc, t_close
      type(contact_force_type) :: e
      integer :: j
      self%next = self%tn
      self%due = advance_reached
      do j = 0, self%region%m, max(self%region%m, 1)
         select case (self%region%kind(j))
         case (slot_boundary_left, slot_boundary_right)
            call slot_state(self%region, j, self%tn_cvode, self%y, x, w, e)
            if (.not. x > 0.0_wp) cycle
            h = self%tn - self%history(j)%t
            call hermite_crossing(self%history(j)%x, self%history(j)%w, x, w, h, tc, wc)
            t_close = min(self%history(j)%t + tc, self%tn)
            if (t_close < self%next .or. self%due == advance_reached) then
               self%next = t_close
               self%due = advance_grow_left
               if (self%region%kind(j) == slot_boundary_right) self%due = advance_grow_right
            end if
         end select
      end do
   end subroutine boundary_closing

   !> The contacts from self%time up to t (within the last step; self%y holds the
   !> state at t), slot by slot, from the cubic Hermite interpolant of each slot's
   !> deformation x (with its rate w = x') between the two:
   !> - a contact starts where x rises through 0, ends where it falls through 0 (both
   !>   times from the interpolant), and a contact that started and ended within the
   !>   interval is recorded too;
   !> - the largest deformation and force of an open contact (the force's interpolant
   !>   with dF/dt).
   !> A gap at the boundary that closes is found after the step (boundary_closing):
   !> the engine comes back at that instant. self%time becomes t.
   !> CVODE's root finding is not used: functions that vanish at the start and end of
   !> every contact, thousands of times in a chain, made it stall at noise level.
   subroutine follow_contacts(self, engine, t, ended)
      type(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      !> The time of the state in self%y
      real(wp), intent(in) :: t
      !> A contact ended
      logical, intent(out) :: ended
      real(wp), allocatable :: dy(:), xs(:), ws(:)
      type(contact_force_type), allocatable :: elements(:)
      real(wp) :: x, w, df, h, t0, tc, wc, step_max, dense
      type(contact_force_type) :: e
      type(slot_history) :: last
      integer :: j, m, alloc_stat
      logical :: ok

      ended = .false.
      m = self%region%m
      ! (out of memory: nothing followed, self%out_of_memory, the run stops)
      allocate(dy(size(self%y)), xs(0:m), ws(0:m), elements(0:m), stat=alloc_stat)
      if (alloc_stat /= 0) then
         self%out_of_memory = .true.
         call no_memory(engine, "the work arrays of a cluster")
         return
      end if
      ! every slot's element once, with the accelerations its force rate needs
      call region_rhs(self%region, t - self%origin, self%y, dy, ok, xs, ws, elements)
      do j = 0, m
         if (self%region%kind(j) == slot_none) cycle
         x = xs(j)
         w = ws(j)
         e = elements(j)
         last = self%history(j)
         t0 = last%t
         h = t - t0
         select case (self%region%kind(j))
         case (slot_boundary_left, slot_boundary_right)
            self%history(j) = slot_history(t, x, w, 0.0_wp, 0.0_wp)
            cycle
         end select
         df = force_rate(self%region, j, dy, w, e)
         if (self%beyond < 0 .and. w > 0.0_wp .and. x >= -self%atol(1)) then
            if (beyond_max_beta(self%region%law(j)%damping, w)) then
               self%beyond = j
               self%beyond_time = t
               self%beyond_speed = w
            end if
         end if
         if (.not. self%contact(j)%open) then
            if (x > 0.0_wp .and. h > 0.0_wp) then
               ! started in the step
               call hermite_crossing(last%x, last%w, x, w, h, tc, wc)
               wc = dense_rate(self, j, t0 + tc, wc)
               call open_at(self, j, t0 + tc, max(wc, 0.0_wp), last%e)
            else if (x > 0.0_wp) then
               call open_at(self, j, t, max(w, 0.0_wp), self%y(dissipation_index(m, j)))
            else if (h > 0.0_wp .and. last%x <= 0.0_wp .and. &
               & hermite_max(last%x, last%w, x, w, h) > 0.0_wp) then
               ! started and ended within the step
               call open_at(self, j, t0 + h * 0.5_wp, max(last%w, 0.0_wp), last%e)
               self%contact(j)%deformation = hermite_max(last%x, last%w, x, w, h)
            end if
         end if
         if (self%contact(j)%open) then
            if (h > 0.0_wp) then
               ! a maximum inside the step: from CVODE's own interpolant, of the
               ! method's order, where the contact was open all along (the cubic's
               ! error, O(h^4), grows with the long steps of high orders, and may
               ! overshoot: Adams at rtol 1e-12 missed the peak force by 1e-8)
               step_max = hermite_max(last%x, last%w, x, w, h)
               if (last%w > 0.0_wp .and. w <= 0.0_wp .and. last%x > 0.0_wp) then
                  dense = dense_max(self, j, t0, t, .false.)
                  if (dense > 0.0_wp) step_max = dense
               end if
               self%contact(j)%deformation = max(self%contact(j)%deformation, step_max)
               step_max = hermite_max(last%f, last%df, e%force, df, h)
               if (last%df > 0.0_wp .and. df <= 0.0_wp .and. last%x > 0.0_wp) then
                  dense = dense_max(self, j, t0, t, .true.)
                  if (dense > 0.0_wp) step_max = dense
               end if
               self%contact(j)%peak = max(self%contact(j)%peak, step_max)
            end if
            self%contact(j)%peak = max(self%contact(j)%peak, e%force)
            self%contact(j)%deformation = max(self%contact(j)%deformation, x)
            ! the gap has opened: the contact ended in the step (not in no time: the
            ! state at the step's start, from CVODE's interpolant there, is off by its
            ! error, and a region that grew at its first instant closed a contact of
            ! 1.5e-14 m that the engine's rounding, 9e-13 m after a fall of 6700 m,
            ! had put at 0 (snap_touching))
            if ((x < 0.0_wp .or. (x == 0.0_wp .and. w < 0.0_wp)) .and. h > 0.0_wp) then
               tc = h
               wc = w
               if (h > 0.0_wp .and. last%x > 0.0_wp) &
                  & call hermite_crossing(last%x, last%w, x, w, h, tc, wc)
               if (h > 0.0_wp) wc = dense_rate(self, j, t0 + tc, wc)
               call close_contact(self, engine, j, self%first - 1 + j, t0 + tc, wc)
               ended = .true.
            end if
         end if
         ! a gap the integrator resolves: the pair no longer touches
         if (.not. x >= -self%atol(1)) self%contact(j)%touching_since = nan
         self%history(j) = slot_history(t, x, w, e%force, df, &
            & self%y(dissipation_index(m, j)))
      end do
      self%time = t
   end subroutine follow_contacts

   !> The largest deformation (force: the largest force) of slot j in the last step
   !> [ta, tb], where its rate (the force's rate) falls from > 0 to <= 0: the root of
   !> that rate on CVODE's interpolant of the whole state (the Illinois variant of
   !> regula falsi, at most 40 evaluations, each an O(m) interpolation and the slot's
   !> and its neighbours' elements, until the root is bracketed to 2^-24 of the
   !> step), and the largest value met; 0 where
   !> the interpolant cannot be evaluated or the rate does not change sign on it.
   !> The work arrays are local and released on every path (no state kept).
   function dense_max(self, j, ta, tb, of_force) result(best)
      type(cvode_chain_integrator), intent(in) :: self
      integer, intent(in) :: j
      real(wp), intent(in) :: ta, tb
      logical, intent(in) :: of_force
      real(wp) :: best
      real(c_double), pointer, contiguous :: dky(:)
      type(N_Vector), pointer :: dky_vec
      real(wp) :: a, b, fa, fb, c, fc, value
      integer :: it, side, alloc_stat
      logical :: ok

      best = 0.0_wp
      allocate(dky(size(self%y)), stat=alloc_stat)
      if (alloc_stat /= 0) then
         if (associated(dky)) deallocate(dky)
         return
      end if
      dky_vec => FN_VMake_Serial(int(size(dky), c_int64_t), dky, self%ctx)
      if (associated(dky_vec)) then
         search: block
            a = ta
            b = tb
            call rate_at(a, fa, value)
            if (.not. ok) exit search
            call rate_at(b, fb, value)
            if (.not. (ok .and. fa > 0.0_wp .and. fb <= 0.0_wp)) exit search
            best = value
            side = 0
            do it = 1, 40
               c = b - fb * (b - a) / (fb - fa)
               if (.not. (c > a .and. c < b)) c = 0.5_wp * (a + b)
               call rate_at(c, fc, value)
               if (.not. ok) exit
               best = max(best, value)
               if (fc > 0.0_wp) then
                  a = c
                  fa = fc
                  if (side == -1) fb = 0.5_wp * fb
                  side = -1
               else
                  b = c
                  fb = fc
                  if (side == 1) fa = 0.5_wp * fa
                  side = 1
               end if
               ! bracketed to 2^-24 of the step: the value is then that of the
               ! extremum to far below an ulp (it is flat there, an error of the time
               ! enters squared); nearer, the rate is rounding noise and the bracket
               ! shrinks by halves only
               if (fc == 0.0_wp .or. b - a <= max(4 * spacing(max(abs(a), abs(b))), &
                  & (tb - ta) * 2.0_wp**(-24))) exit
            end do
         end block search
         call FN_VDestroy(dky_vec)
      end if
      deallocate(dky)
   contains
      !> The rate (deformation's or force's) and the value at the time t
      subroutine rate_at(t, rate, val)
         real(wp), intent(in) :: t
         real(wp), intent(out) :: rate, val
         real(wp) :: x, w
         type(contact_force_type) :: e
         integer(c_int) :: ierr
         real(wp) :: tau
         tau = cvode_time(self, t)
         ierr = FCVodeGetDky(self%mem, real(tau, c_double), 0_c_int, dky_vec)
         ok = ierr == CV_SUCCESS
         rate = 0.0_wp
         val = 0.0_wp
         if (.not. ok) return
         if (of_force) then
            call slot_force_rate(self%region, j, tau, dky, x, w, e, rate, ok)
            val = e%force
         else
            call slot_state(self%region, j, tau, dky, x, w, e)
            rate = w
            val = x
         end if
      end subroutine rate_at
   end function dense_max

   !> The deformation rate of slot j at the time t within the last step, from CVODE's
   !> interpolant of the method's order (the approach and separation speeds of the
   !> contacts that start and end in the step: the cubic Hermite's slope, O(h^3),
   !> was off by 1e-8 m/s over the long Adams steps behind a wave at rtol 1e-11);
   !> `fallback` where the interpolant cannot be evaluated.
   function dense_rate(self, j, t, fallback) result(w)
      type(cvode_chain_integrator), intent(in) :: self
      integer, intent(in) :: j
      real(wp), intent(in) :: t, fallback
      real(wp) :: w
      real(c_double), allocatable, target :: dky(:)
      type(contact_force_type) :: e
      real(wp) :: x
      integer :: alloc_stat
      logical :: ok
      w = fallback
      allocate(dky(size(self%y)), stat=alloc_stat)
      if (alloc_stat /= 0) return
      call interpolate(self, t, dky, ok)
      if (ok) call slot_state(self%region, j, cvode_time(self, t), dky, x, w, e)
   end function dense_rate

   !> The time (from the step's start, in [0, h]) where the cubic Hermite interpolant
   !> with values x0, x1 and slopes w0, w1 at the ends of the step crosses 0, and its
   !> slope there (bisection, x0 and x1 of opposite signs or one zero).
   pure subroutine hermite_crossing(x0, w0, x1, w1, h, tc, wc)
      real(wp), intent(in) :: x0, w0, x1, w1, h
      real(wp), intent(out) :: tc, wc
      real(wp) :: lo, hi, mid, b, c, p
      integer :: it
      ! p(t) = x0 + h w0 t + b t^2 + c t^3, t in [0, 1]
      b = 3.0_wp * (x1 - x0) - h * (2.0_wp * w0 + w1)
      c = 2.0_wp * (x0 - x1) + h * (w0 + w1)
      lo = 0.0_wp
      hi = 1.0_wp
      do it = 1, 60
         mid = 0.5_wp * (lo + hi)
         p = x0 + mid * (h * w0 + mid * (b + mid * c))
         if ((p > 0.0_wp) .eqv. (x0 > 0.0_wp)) then
            lo = mid
         else
            hi = mid
         end if
      end do
      mid = 0.5_wp * (lo + hi)
      tc = h * mid
      wc = 0.0_wp
      if (h > 0.0_wp) wc = (h * w0 + mid * (2.0_wp * b + 3.0_wp * c * mid)) / h
   end subroutine hermite_crossing

   !> The region's state at the time t within the last step into self%y (CVODE's
   !> interpolant; self%y is only CVODE's output, not its history). Kept as it is
   !> where the interpolant cannot be evaluated.
   subroutine move_to(self, t)
      type(cvode_chain_integrator), intent(inout) :: self
      real(wp), intent(in) :: t
      real(c_double), allocatable, target :: dky(:)
      logical :: ok
      integer :: alloc_stat
      ! (out of memory: self%y kept, self%out_of_memory)
      allocate(dky(size(self%y)), stat=alloc_stat)
      if (alloc_stat /= 0) then
         self%out_of_memory = .true.
         return
      end if
      call interpolate(self, t, dky, ok)
      if (ok) self%y = dky
   end subroutine move_to

   !> The region's state at the time t within the last step from CVODE's interpolant
   !> (of the method's order) into state, of the state's size; ok false (state
   !> undefined) where it cannot be evaluated.
   subroutine interpolate(self, t, state, ok)
      type(cvode_chain_integrator), intent(in) :: self
      real(wp), intent(in) :: t
      real(c_double), intent(inout), target, contiguous :: state(:)
      logical, intent(out) :: ok
      type(N_Vector), pointer :: vec
      ok = .false.
      vec => FN_VMake_Serial(int(size(state), c_int64_t), state, self%ctx)
      if (.not. associated(vec)) return
      ok = FCVodeGetDky(self%mem, real(cvode_time(self, t), c_double), 0_c_int, vec) &
         & == CV_SUCCESS
      call FN_VDestroy(vec)
   end subroutine interpolate

   !> CVODE's time of the engine's time t within the last step: t less the origin,
   !> and after a rebase held within the last step (whose ends the engine's times
   !> keep only to their own rounding, up to steps below it: `rebase`)
   pure real(wp) function cvode_time(self, t) result(tau)
      type(cvode_chain_integrator), intent(in) :: self
      real(wp), intent(in) :: t
      tau = t - self%origin
      if (self%origin /= 0.0_wp) tau = min(max(tau, self%tn_cvode - self%h_last), &
         & self%tn_cvode)
   end function cvode_time

   !> Open the record of a contact of slot j that started at t_start with the
   !> approach speed given, the slot's dissipated energy then being e_base.
   subroutine open_at(self, j, t_start, approach, e_base)
      type(cvode_chain_integrator), intent(inout) :: self
      integer, intent(in) :: j
      real(wp), intent(in) :: t_start, approach, e_base
      real(wp) :: since, approach_then
      since = self%contact(j)%touching_since
      approach_then = self%contact(j)%touching_approach
      self%contact(j) = open_contact(open=.true., t_start=t_start, approach=approach, &
         & e_base=e_base, peak=0.0_wp, deformation=0.0_wp, earlier=0.0_wp)
      call note_wall(self, j)
      if (since <= t_start) then
         self%contact(j)%t_start = since
         self%contact(j)%approach = approach_then
      end if
   end subroutine open_at

   !> A contact of slot j opened: where that is a wall, the region has touched it
   !> (`wall_impulse`)
   pure subroutine note_wall(self, j)
      type(cvode_chain_integrator), intent(inout) :: self
      integer, intent(in) :: j
      if (self%region%kind(j) == slot_left_wall) self%wall_touched(1) = .true.
      if (self%region%kind(j) == slot_right_wall) self%wall_touched(2) = .true.
   end subroutine note_wall

   !> The largest value on [0, h] of the cubic with values p0, p1 and slopes d0, d1 at
   !> its ends (both ends and an interior maximum where the slope turns negative).
   pure real(wp) function hermite_max(p0, d0, p1, d1, h)
      real(wp), intent(in) :: p0, d0, p1, d1, h
      real(wp) :: b, c, a2, disc, t, roots(2)
      integer :: k
      hermite_max = max(p0, p1)
      if (.not. (d0 > 0.0_wp .and. d1 <= 0.0_wp)) return
      ! p(t) = p0 + h d0 t + b t^2 + c t^3 on t in [0, 1]
      b = 3.0_wp * (p1 - p0) - h * (2.0_wp * d0 + d1)
      c = 2.0_wp * (p0 - p1) + h * (d0 + d1)
      ! p'(t) = h d0 + 2 b t + 3 c t^2
      a2 = 3.0_wp * c
      if (abs(a2) <= epsilon(1.0_wp) * abs(b)) then
         if (b /= 0.0_wp) then
            t = -h * d0 / (2.0_wp * b)
            if (t > 0.0_wp .and. t < 1.0_wp) hermite_max = max(hermite_max, &
               & p0 + t * (h * d0 + t * (b + t * c)))
         end if
         return
      end if
      disc = b * b - a2 * h * d0
      if (disc < 0.0_wp) return
      roots(1) = (-b + sqrt(disc)) / a2
      roots(2) = (-b - sqrt(disc)) / a2
      do k = 1, 2
         t = roots(k)
         if (t > 0.0_wp .and. t < 1.0_wp) hermite_max = max(hermite_max, &
            & p0 + t * (h * d0 + t * (b + t * c)))
      end do
   end function hermite_max

   !> Record the contact of slot j that ends now (w: the deformation rate, < 0).
   subroutine close_contact(self, engine, j, s, t_end, w)
      type(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      integer, intent(in) :: j, s
      !> End time and the deformation rate then (< 0)
      real(wp), intent(in) :: t_end, w
      type(contact_record) :: r
      real(wp) :: e
      self%contact(j)%open = .false.
      ! a touching pair (approach within the velocities' absolute tolerance) that never
      ! pressed beyond rounding (the positions' absolute tolerance) was no contact yet:
      ! its bodies moved apart by rounding (ahead of a wave, subnormal speeds from the
      ! Newton corrections), and a contact that opens again while its gap stays that
      ! small began when this one did (before, the struck chain of 16, Adams at rtol
      ! 1e-11, recorded pair 12 from 4.2e-5 s with an approach of 1.6e-315 m/s instead
      ! of from 0). Unless it dissipated beyond the energies' tolerance: a pair that
      ! touches at rest and is pressed by a contact so damped that it stops within
      ! rounding is a contact (three touching balls struck, b V = 1e12: the second and
      ! third were not recorded, and their 0.0655 J of 0.333 was left out of the total,
      ! with success and an energy balance of 0.13). What a pair left out dissipated
      ! still counts in the total.
      e = dissipated_so_far(self, j)
      if (.not. (self%contact(j)%deformation > self%atol(1)) .and. &
         & self%contact(j)%approach <= self%atol(2) .and. &
         & .not. (e > engine%options%rtol * self%region%scale(3))) then
         self%contact(j)%touching_since = self%contact(j)%t_start
         self%contact(j)%touching_approach = self%contact(j)%approach
         if (ieee_is_finite(e)) engine%dissipated = engine%dissipated + e
         return
      end if
      if (.not. (self%contact(j)%peak > 0.0_wp)) return
      engine%counters%integrated_contacts = engine%counters%integrated_contacts + 1
      r%pair = s
      r%t_start = self%contact(j)%t_start
      r%t_end = t_end
      r%approach_speed = self%contact(j)%approach
      r%separation_speed = max(-w, 0.0_wp)
      r%peak_force = self%contact(j)%peak
      r%max_deformation = self%contact(j)%deformation
      r%dissipated = dissipated_so_far(self, j)
      r%method = by_integration
      call engine_record(engine, r)
   end subroutine close_contact

   !> What the open contact of slot j has dissipated since it began: the energy it
   !> brought from earlier regions and its share of the region's dissipation state.
   !> Never negative: the state's rate is b F x' >= 0, but CVODE's corrections leave it
   !> within its tolerance of the truth on either side (a wall contact of 2e-46 N at
   !> 1e-4 rtol ended with -2e-26 J, which the fuzzer reported).
   pure real(wp) function dissipated_so_far(self, j) result(e)
      type(cvode_chain_integrator), intent(in) :: self
      integer, intent(in) :: j
      e = self%contact(j)%earlier &
         & + (self%y(dissipation_index(self%region%m, j)) - self%contact(j)%e_base)
      ! (a NaN stays: the engine leaves it out and the balance reports it)
      e = not_below_zero(e)
   end function dissipated_so_far

   !> Whether no contact of the region is active or closing (it can be dissolved).
   function separated(self) result(apart)
      type(cvode_chain_integrator), intent(in) :: self
      logical :: apart
      integer :: j
      real(wp) :: x, w
      type(contact_force_type) :: e
      apart = .true.
      do j = 0, self%region%m
         select case (self%region%kind(j))
         case (slot_pair, slot_left_wall, slot_right_wall)
            call slot_state(self%region, j, self%time - self%origin, self%y, x, w, e)
            ! (a touching pair that has never pressed and does not approach is apart)
            if (self%contact(j)%open .and. (self%contact(j)%peak > 0.0_wp .or. x > 0.0_wp &
               & .or. w > 0.0_wp)) then
               apart = .false.
               return
            end if
            if (x > 0.0_wp .or. (x >= 0.0_wp .and. w > 0.0_wp)) then
               apart = .false.
               return
            end if
         end select
      end do
   end function separated

   !> Whether no gap of the region can close again in free flight (every pair
   !> separating or keeping its distance, no wall ahead).
   function never_again(self, engine) result(never)
      type(cvode_chain_integrator), intent(in) :: self
      type(chain_engine), intent(in) :: engine
      logical :: never
      integer :: j
      real(wp) :: x, w, g
      type(contact_force_type) :: e
      never = .true.
      do j = 0, self%region%m
         call slot_state(self%region, j, self%time - self%origin, self%y, x, w, e)
         select case (self%region%kind(j))
         case (slot_pair, slot_boundary_left, slot_boundary_right)
            ! the common acceleration cancels: the rate stays w
            if (w > 0.0_wp) never = .false.
         case (slot_left_wall, slot_right_wall)
            g = -engine%gravity
            if (self%region%kind(j) == slot_right_wall) g = engine%gravity
            ! the deformation -gap evolves as x + w tau + g tau^2/2
            if (w > 0.0_wp .or. g > 0.0_wp) never = .false.
         end select
         if (.not. never) return
      end do
   end function never_again

   !> Displacements and velocities of the region's bodies at the time t (within the
   !> last step, in [self%time, self%next]).
   subroutine region_state_at(self, engine, t, u, v)
      class(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(in) :: engine
      real(wp), intent(in) :: t
      real(wp), intent(out) :: u(:), v(:)
      real(c_double), allocatable, target :: dky(:)
      integer :: m, alloc_stat
      logical :: halting(3), ok
      m = self%region%m
      ! self%y holds the state at the end of the last step until its contacts are
      ! followed, then at self%time
      if ((self%stepped .and. t == self%tn) .or. (.not. self%stepped .and. t == self%time)) then
         call engine_frame(self, t, self%y, u, v)
         return
      end if
      ! (out of memory: NaN, self%out_of_memory, which the engine turns into its status)
      allocate(dky(region_size(m)), stat=alloc_stat)
      if (alloc_stat /= 0) then
         self%out_of_memory = .true.
         u = nan
         v = nan
         return
      end if
      call halting_suspend(halting)
      call interpolate(self, t, dky, ok)
      if (ok) then
         call engine_frame(self, t, dky, u, v)
      else
         call engine_frame(self, merge(self%tn, self%time, self%stepped), self%y, u, v)
      end if
      call halting_resume(halting)
   end subroutine region_state_at

   !> The displacements u (m) and velocities v (m/s) of the region's bodies in the
   !> engine's frame from a state y of the region at the time t. The region's state is
   !> in a frame of its own: every displacement from its value at the region's start
   !> (the deformations keep the digits of their own size, not those of how far the
   !> bodies have gone: a ball dropped 1 m rests within 1e-16 m of 1 m, and at rtol
   !> 1e-12 CVODE's steps shrank against the rounding of its displacement), relative
   !> to the frame of `region_frame` (three touching balls falling freely, one struck
   !> at 1e-6 m/s, had relative velocities off by 1.5e-5 without it, rtol applying to
   !> the fall's g t; at 1e-50 m/s CVODE failed at t = 0).
   subroutine engine_frame(self, t, y, u, v)
      type(cvode_chain_integrator), intent(in) :: self
      real(wp), intent(in) :: t, y(:)
      real(wp), intent(out) :: u(:), v(:)
      real(wp) :: shift, speed
      integer :: m
      m = self%region%m
      call frame_motion(self%v_frame, self%a_frame, t - self%t0, shift, speed)
      u = self%u_ref + (shift + y(1:3 * m:3))
      v = speed + y(2:3 * m:3)
   end subroutine engine_frame

   !> Follow the contacts up to engine%time (within [self%time, self%next]), write the
   !> region's states then back into the engine and free CVODE; a contact still in
   !> progress is left in its slot for the next region.
   subroutine region_finish(self, engine)
      class(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      integer :: k, i, j, s, m
      real(wp) :: t
      real(wp), allocatable :: u(:), v(:)
      logical :: ended, halting(3)
      integer :: alloc_stat
      if (.not. associated(self%region)) return
      m = self%region%m
      call halting_suspend(halting)
      self%region%halting = halting
      if (self%stepped) then
         t = min(max(engine%time, self%time), self%next)
         if (t < self%tn) call move_to(self, t)
         if (t > self%time) call follow_contacts(self, engine, t, ended)
         self%stepped = .false.
      end if
      allocate(u(m), v(m), stat=alloc_stat)
      if (alloc_stat /= 0) then
         ! (the bodies keep their states before the region: the run stops)
         call no_memory(engine, "the work arrays of a cluster")
         call release_all(self)
         call halting_resume(halting)
         return
      end if
      call engine_frame(self, self%time, self%y, u, v)
      do k = 1, m
         i = self%first + k - 1
         engine%body(i)%t0 = engine%time
         engine%body(i)%u0 = u(k)
         engine%body(i)%v0 = v(k)
      end do
      ! the impulses the walls gave the region
      call add_wall_impulse(engine, 1, wall_impulse(self%region, 1, self%y, &
         & self%time - self%t0, self%wall_touched(1)))
      call add_wall_impulse(engine, 2, wall_impulse(self%region, 2, self%y, &
         & self%time - self%t0, self%wall_touched(2)))
      call hand_touching(self, engine)
      ! (the parts of a region that splits go on with its step)
      if (self%due == advance_split) self%step_for_growth = self%h_last
      do j = 0, m
         if (.not. allocated(self%contact)) exit
         s = self%first - 1 + j
         ! a touching pair's memory (close_contact), for a region begun at this instant
         if (.not. (self%contact(j)%open .or. ieee_is_nan(self%contact(j)%touching_since))) then
            engine%exact(s)%touching_since = self%contact(j)%touching_since
            engine%exact(s)%touching_approach = self%contact(j)%touching_approach
            engine%exact(s)%touching_at = engine%time
         end if
         if (.not. self%contact(j)%open) cycle
         engine%exact(s)%handed = .true.
         engine%exact(s)%active = .false.
         engine%exact(s)%t_start = self%contact(j)%t_start
         engine%exact(s)%contact%velocity = self%contact(j)%approach
         engine%exact(s)%so_far_peak = self%contact(j)%peak
         engine%exact(s)%so_far_deformation = self%contact(j)%deformation
         engine%exact(s)%so_far_dissipated = dissipated_so_far(self, j)
      end do
      call add_counters(self, engine)
      call release_all(self)
      call halting_resume(halting)
   end subroutine region_finish

   !> The region grows at engine%time over a boundary pair that has touched all along
   !> (its gap exactly 0): that pair has been in contact since the body inside was
   !> first pushed, which is the start of the open contact on that body's other side
   !> (the deformation is positive from then on, below the double range at first:
   !> the reference integrations and the whole system integrated start it there too).
   !> Its contact is handed over to the grown region with that start, approach speed
   !> 0 and nothing recorded yet (without such a contact, it starts now), and the
   !> grown region may begin with the last step (step_for_growth; 0 otherwise).
   subroutine hand_touching(self, engine)
      type(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      integer :: side, j, inner, s
      real(wp) :: t_start
      self%step_for_growth = 0.0_wp
      if (.not. (allocated(self%contact) .and. associated(self%region))) return
      do side = 1, 2
         if (.not. self%touching(side)) cycle
         if (side == 1 .and. self%due /= advance_grow_left) cycle
         if (side == 2 .and. self%due /= advance_grow_right) cycle
         if (.not. engine%time >= self%next) cycle
         j = merge(0, self%region%m, side == 1)
         inner = merge(1, self%region%m - 1, side == 1)  ! (a slot 0 .. m: m >= 1)
         t_start = engine%time
         if (self%contact(inner)%open) then
            t_start = min(t_start, self%contact(inner)%t_start)
         else if (.not. ieee_is_nan(self%contact(inner)%touching_since)) then
            ! (apart by rounding only: close_contact)
            t_start = min(t_start, self%contact(inner)%touching_since)
         end if
         s = self%first - 1 + j
         engine%exact(s)%handed = .true.
         engine%exact(s)%active = .false.
         engine%exact(s)%t_start = t_start
         engine%exact(s)%contact%velocity = 0.0_wp
         engine%exact(s)%so_far_peak = 0.0_wp
         engine%exact(s)%so_far_deformation = 0.0_wp
         engine%exact(s)%so_far_dissipated = 0.0_wp
         self%step_for_growth = self%h_last
      end do
   end subroutine hand_touching

   !> CVODE's right-hand side and Jacobian evaluations into the engine's counters.
   subroutine add_counters(self, engine)
      type(cvode_chain_integrator), intent(inout) :: self
      type(chain_engine), intent(inout) :: engine
      integer(c_long) :: count(1)
      integer(c_int) :: ierr
      if (.not. c_associated(self%mem)) return
      ierr = FCVodeGetNumRhsEvals(self%mem, count)
      if (ierr == CV_SUCCESS) engine%counters%rhs_evals = engine%counters%rhs_evals + count(1)
      ierr = FCVodeGetNumJacEvals(self%mem, count)
      if (ierr == CV_SUCCESS) engine%counters%jacobian_evals = &
         & engine%counters%jacobian_evals + count(1)
   end subroutine add_counters

   !> Free everything of the integrator (idempotent).
   subroutine release_all(self)
      class(cvode_chain_integrator), intent(inout) :: self
      integer(c_int) :: ierr
      if (c_associated(self%mem)) call FCVodeFree(self%mem)
      self%mem = c_null_ptr
      if (associated(self%lin_sol)) ierr = FSUNLinSolFree(self%lin_sol)
      if (associated(self%jac_mat)) call FSUNMatDestroy(self%jac_mat)
      if (associated(self%atol_vec)) call FN_VDestroy(self%atol_vec)
      if (associated(self%y_vec)) call FN_VDestroy(self%y_vec)
      nullify(self%lin_sol, self%jac_mat, self%atol_vec, self%y_vec)
      call context_free(self%ctx)
      if (associated(self%y)) deallocate(self%y)
      if (allocated(self%u_ref)) deallocate(self%u_ref)
      if (associated(self%atol)) deallocate(self%atol)
      if (allocated(self%contact)) deallocate(self%contact)
      if (allocated(self%history)) deallocate(self%history)
      if (associated(self%region)) deallocate(self%region)
   end subroutine release_all

   ! =================================================================================
   ! CVODE's callbacks
   ! =================================================================================

   !> CVRhsFn
   function chain_rhs_callback(t, y, ydot, user_data) result(ierr) bind(C)
      real(c_double), value :: t
      type(N_Vector) :: y, ydot
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(chain_region), pointer :: region
      real(c_double), pointer :: yv(:), dv(:)
      logical :: ok, flags(3)
      call c_f_pointer(user_data, region)
      call callback_enter(region%halting, flags)
      yv => FN_VGetArrayPointer(y)
      dv => FN_VGetArrayPointer(ydot)
      call region_rhs(region, real(t, wp), yv, dv, ok)
      call callback_leave(region%halting, flags)
      ierr = 0
      ! a force beyond the double range: CVODE retries with a smaller step
      if (.not. ok) ierr = 1
   end function chain_rhs_callback

   !> The error weights (CVODE's CVEwtFn): `error_weights` of the region, the walls'
   !> impulses with them.
   function chain_error_weights(y, ewt, user_data) result(ierr) bind(C)
      type(N_Vector) :: y, ewt
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(chain_region), pointer :: region
      real(c_double), pointer :: yv(:), wv(:)
      call c_f_pointer(user_data, region)
      yv => FN_VGetArrayPointer(y)
      wv => FN_VGetArrayPointer(ewt)
      call error_weights(yv, region%rtol, region%scale, &
         & sqrt(real(region_size(region%m), wp)), wv, region%impulse_scale)
      ierr = 0
   end function chain_error_weights

   !> CVLsJacFn: the band Jacobian
   function chain_jacobian_callback(t, y, fy, jac_mat, user_data, tmp1, tmp2, tmp3) &
         & result(ierr) bind(C)
      real(c_double), value :: t
      type(N_Vector) :: y, fy, tmp1, tmp2, tmp3
      type(SUNMatrix) :: jac_mat
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(chain_region), pointer :: region
      real(c_double), pointer, contiguous :: yv(:), data(:), band(:, :)
      integer :: ldim, smu, n
      logical :: flags(3)
      call c_f_pointer(user_data, region)
      call callback_enter(region%halting, flags)
      yv => FN_VGetArrayPointer(y)
      n = region_size(region%m)
      ldim = int(FSUNBandMatrix_LDim(jac_mat))
      smu = int(FSUNBandMatrix_StoredUpperBandwidth(jac_mat))
      data => FSUNBandMatrix_Data(jac_mat)
      call c_f_pointer(c_loc(data(1)), band, [ldim, n])
      band = 0.0_c_double
      call region_jacobian(region, real(t, wp), yv, smu, band, region%wall_slope)
      call callback_leave(region%halting, flags)
      ierr = 0
   end function chain_jacobian_callback

end module hcimpact_cvode_chain
