! SPDX-License-Identifier: Apache-2.0
!> CVODE on the distributed chain (doc/mpi.md): the state of every rank's block in
!> one SUNDIALS parallel vector (N_Vector_Parallel: each rank holds its block, CVODE's
!> norms and dot products are reductions over all ranks), BDF with Newton's iteration,
!> the Krylov solver SPGMR and the band-block-diagonal preconditioner CVBBDPRE.
!>
!> CVBBDPRE approximates the Jacobian by its diagonal blocks, one per rank, each a band
!> that it builds by difference quotients of the block's right-hand side with the halo
!> beads held fixed (`block_local_rhs`, after one exchange: `block_communicate`); the
!> coupling between blocks (two beads per boundary) is left to SPGMR. The bandwidths
!> are those of the serial chain's Jacobian (3 above, 4 below the diagonal, in the
!> order u, v, e per bead): the band factorisation is exact for the block's motion.
!>
!> Error weights as in the serial chain (hcimpact_cvode_chain), with r the fraction of
!> rtol that `weights_rtol` gives BDF: a displacement's error against r x_ref, a
!> velocity's against r (|v| + v_ref), an energy's against r e_ref, a wall's impulse
!> against r M v_ref (M the chain's mass), every weight times the square root of the
!> global number of values, so that CVODE's root mean square is the 2-norm over the
!> whole chain.
!>
!> CVODE runs in its one-step mode up to the stop time t_end, with this program's own
!> bound of steps (max_steps: CV_TOO_MUCH_WORK, as CVODE's would say in its normal
!> mode) and of steps that leave the time where it is; after each step the step's
!> interpolating polynomial goes to the contacts (hcimpact_mpi_chain_contacts), which
!> do not act on the integration.
!>
!> Every decision CVODE takes goes through a reduction over all ranks, so the ranks
!> take the same steps and call the right-hand side together (its halo exchange is
!> a collective step of the neighbours). The right-hand side therefore never reports
!> a failure of its own rank (which only that rank would act on): a force that is
!> not finite reaches CVODE's global norms as Inf or NaN, and every rank rejects the
!> step alike.
!>
!> SUNDIALS 6 and 7: the context is created by the CVODE component's
!> `context_create` (no communicator attached: it is used for profiling only); the
!> one name whose module changes, SUN_PREC_LEFT, is imported under
!> HCIMPACT_SUNDIALS_MAJOR.
#ifndef HCIMPACT_SUNDIALS_MAJOR
#include <sundials/sundials_config.h>
#define HCIMPACT_SUNDIALS_MAJOR SUNDIALS_VERSION_MAJOR
#endif
module hcimpact_mpi_chain_cvode
   use, intrinsic :: iso_c_binding, only : c_int, c_long, c_double, c_ptr, c_int64_t, &
      & c_null_ptr, c_loc, c_funloc, c_f_pointer, c_associated
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   use hcimpact_chain_types, only : chain_type, chain_options, max_message
   use hcimpact_cvode_report, only : solver_report, report_detail
   use hcimpact_cvode_halting, only : halting_suspend, halting_resume, callback_enter, &
      & callback_leave
   use hcimpact_cvode_sundials, only : N_Vector, SUNLinearSolver, FN_VGetArrayPointer, &
      & FN_VDestroy, FSUNLinSolFree, context_create, context_free, capture_errors
   use hcimpact_cvode_solver, only : cvode_flag_name
   use hcimpact_cvode_chain_system, only : upper_band, lower_band, error_weights, weights_rtol, &
      & first_step
   use hcimpact_mpi_chain_block, only : chain_block, exchange_halo, block_rhs
   use hcimpact_mpi_chain_contacts, only : contact_tracker, tracker_start, tracker_step, &
      & max_order
   use fcvode_mod, only : FCVodeCreate, FCVodeInit, FCVodeSetUserData, &
      & FCVodeWFtolerances, FCVodeSetStopTime, FCVode, FCVodeFree, &
      & FCVodeGetNumSteps, FCVodeGetNumRhsEvals, FCVodeGetNumLinIters, &
      & FCVodeGetNumNonlinSolvIters, FCVodeGetNumPrecEvals, FCVBBDPrecInit, &
      & FCVBBDPrecGetNumGfnEvals, FCVodeGetDky, FCVodeGetLastOrder, FCVodeSetInitStep, &
      & CV_BDF, CV_ONE_STEP, &
      & CV_SUCCESS, CV_TSTOP_RETURN, CV_TOO_MUCH_WORK
   use fnvector_parallel_mod, only : FN_VNew_Parallel
   use mpi_f08, only : MPI_Allreduce, MPI_LOGICAL, MPI_LAND
   use fsunlinsol_spgmr_mod, only : FSUNLinSol_SPGMR
#if HCIMPACT_SUNDIALS_MAJOR >= 7
   use fsundials_core_mod, only : SUN_PREC_LEFT
#else
   use fsundials_linearsolver_mod, only : SUN_PREC_LEFT
#endif
   implicit none
   private

   public :: chain_integration, integrate_chain, chain_counters_mpi

   !> The work of a run, summed over every rank where it is per rank (halo exchanges
   !> are counted per rank and summed by the caller)
   type :: chain_counters_mpi
      integer(int64) :: steps = 0, rhs_evals = 0, nonlinear_iterations = 0, &
         & linear_iterations = 0, preconditioner_setups = 0, local_rhs_evals = 0
   end type chain_counters_mpi

   !> What the callbacks reach through CVODE's user data
   type :: chain_integration
      type(chain_block) :: block
      !> The contacts of the rank's pairs (hcimpact_mpi_chain_contacts)
      type(contact_tracker) :: contacts
      !> Relative tolerance, scales of deformation (m), speed (m/s), energy (J), and
      !> the square root of the global number of values
      real(wp) :: rtol = 1.0e-8_wp, scale(3) = 1.0_wp, root_n = 1.0_wp
      !> The scale of the walls' impulses (N s: `wall_impulse_scale`)
      real(wp) :: impulse_scale = 1.0_wp
      !> The shortest time in which a damped contact stops (s: `region_scales`)
      real(wp) :: stop_time = huge(1.0_wp)
      !> The caller's halting modes (off while CVODE runs)
      logical :: halting(3) = .false.
      type(solver_report) :: report
   end type chain_integration

   interface
      !> CVodeSetLinearSolver with a matrix-free solver (no matrix: NULL), bound
      !> directly: the Fortran wrapper wants a matrix object
      function cvode_set_linear_solver(mem, ls, a) result(flag) &
            & bind(C, name="CVodeSetLinearSolver")
         import :: c_ptr, c_int
         type(c_ptr), value :: mem, ls, a
         integer(c_int) :: flag
      end function cvode_set_linear_solver
   end interface

contains

   !> Integrate the block's state y (block%n_local values: u, v, e per bead, the
   !> right wall's e on the last rank, then the impulses of the walls the block holds)
   !> from 0 to t_end
   !> together with the other ranks. ok false with a message (the same on every rank:
   !> CVODE's failures are collective) if CVODE fails.
   subroutine integrate_chain(run, t_end, max_steps, y, counters, ok, message)
      type(chain_integration), target, intent(inout) :: run
      real(wp), intent(in) :: t_end
      integer(int64), intent(in) :: max_steps
      real(wp), intent(inout) :: y(:)
      type(chain_counters_mpi), intent(out) :: counters
      logical, intent(out) :: ok
      character(len=max_message), intent(out) :: message
      type(c_ptr) :: ctx, mem
      type(N_Vector), pointer :: y_vec, dky_vec
      type(SUNLinearSolver), pointer :: lin_sol
      real(c_double), pointer :: yv(:), dkyv(:)
      real(c_double) :: t_reached(1)
      real(wp) :: t_previous
      integer(c_int) :: ierr, dky_flag, order(1)
      ! steps in a row that left the time where it was, and how many are tolerated
      integer :: stalled, k
      integer, parameter :: max_stalled = 100
      integer(c_int64_t) :: n_local, n_global, mu, ml
      integer(c_long) :: count(1)
      character(len=80) :: where
      logical :: ready, ready_checked
      integer :: m

      ok = .false.
      ready_checked = .false.
      message = ""
      ctx = c_null_ptr
      mem = c_null_ptr
      y_vec => null()
      dky_vec => null()
      lin_sol => null()
      m = run%block%n_local
      n_local = int(m, c_int64_t)
      n_global = int(run%block%n_global, c_int64_t)
      run%root_n = sqrt(real(n_global, wp))
      mu = int(min(upper_band, m - 1), c_int64_t)
      ml = int(min(lower_band, m - 1), c_int64_t)

      call halting_suspend(run%halting)
      setup: block
         where = "SUNContext_Create"
         ierr = context_create(ctx)
         if (ierr /= 0) exit setup
         where = "N_VNew_Parallel"
         ierr = -1
         y_vec => FN_VNew_Parallel(run%block%comm%MPI_VAL, n_local, n_global, ctx)
         if (.not. associated(y_vec)) exit setup
         yv => FN_VGetArrayPointer(y_vec)
         yv(1:m) = y(1:m)
         where = "CVodeCreate"
         mem = FCVodeCreate(CV_BDF, ctx)
         if (.not. c_associated(mem)) exit setup
         where = "CVodeSetErrHandler"
         ierr = capture_errors(ctx, mem, c_loc(run%report))
         if (ierr /= 0) exit setup
         where = "CVodeInit"
         ierr = FCVodeInit(mem, c_funloc(chain_rhs), 0.0_c_double, y_vec)
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetUserData"
         ierr = FCVodeSetUserData(mem, c_loc(run))
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeWFtolerances"
         ierr = FCVodeWFtolerances(mem, c_funloc(chain_error_weights))
         if (ierr /= CV_SUCCESS) exit setup
         where = "SUNLinSol_SPGMR"
         ierr = -1
         lin_sol => FSUNLinSol_SPGMR(y_vec, SUN_PREC_LEFT, 0_c_int, ctx)
         if (.not. associated(lin_sol)) exit setup
         where = "CVodeSetLinearSolver"
         ierr = cvode_set_linear_solver(mem, c_loc(lin_sol), c_null_ptr)
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVBBDPrecInit"
         ierr = FCVBBDPrecInit(mem, n_local, mu, ml, mu, ml, 0.0_c_double, &
            & c_funloc(block_local_rhs), c_funloc(block_communicate))
         if (ierr /= CV_SUCCESS) exit setup
         where = "N_VNew_Parallel"
         ierr = -1
         dky_vec => FN_VNew_Parallel(run%block%comm%MPI_VAL, n_local, n_global, ctx)
         if (.not. associated(dky_vec)) exit setup
         dkyv => FN_VGetArrayPointer(dky_vec)
         where = "CVodeSetStopTime"
         ierr = FCVodeSetStopTime(mem, real(t_end, c_double))
         if (ierr /= CV_SUCCESS) exit setup
         ! the serial chain's first step (`first_step`), not CVODE's estimate from t_end
         ! (nor t_end when shorter: CVODE stops at t_end anyway, and a first step of
         ! t_end = 1e-300 s times the time to the stop, 1e-600, underflowed to 0, which
         ! CVODE took for a stop behind the start: CV_ILL_INPUT)
         where = "CVodeSetInitStep"
         ierr = FCVodeSetInitStep(mem, real(first_step(run%rtol, run%scale, run%stop_time), &
            & c_double))
         if (ierr /= CV_SUCCESS) exit setup
         ! a setup that failed on another rank only: none of them may enter CVode,
         ! whose steps every rank must take together
         where = "the setup on another rank"
         ierr = -1
         call MPI_Allreduce(.true., ready, 1, MPI_LOGICAL, MPI_LAND, run%block%comm)
         if (.not. ready) exit setup
         ready_checked = .true.
         call tracker_start(run%contacts, run%block, y, run%rtol * run%scale(1))
         ! step by step (CVODE's one-step mode up to the stop time t_end), the contacts
         ! followed on each step's interpolant (hcimpact_mpi_chain_contacts); every
         ! rank takes the same steps, so the loop's decisions are the same on all
         where = "CVode"
         t_previous = 0.0_wp
         stalled = 0
         do
            ierr = FCVodeGetNumSteps(mem, count)
            if (int(count(1), int64) >= max_steps) then
               ierr = CV_TOO_MUCH_WORK
               exit setup
            end if
            ierr = FCVode(mem, real(t_end, c_double), y_vec, t_reached, CV_ONE_STEP)
            if (ierr /= CV_SUCCESS .and. ierr /= CV_TSTOP_RETURN) exit setup
            ! steps too small to move the time (as in the serial chain)
            if (t_reached(1) > t_previous) then
               stalled = 0
            else
               stalled = stalled + 1
               if (stalled > max_stalled) then
                  where = "CVode (100 steps in a row left the time where it was)"
                  ierr = CV_TOO_MUCH_WORK
                  exit setup
               end if
            end if
            ! the Taylor coefficients of the step's polynomial at its end (derivatives
            ! of orders above the step's are 0)
            dky_flag = FCVodeGetLastOrder(mem, order)
            if (dky_flag /= CV_SUCCESS) order(1) = 0
            do k = 0, max_order
               run%contacts%taylor(k, :) = 0.0_wp
               if (k > order(1)) cycle
               dky_flag = FCVodeGetDky(mem, t_reached(1), int(k, c_int), dky_vec)
               if (dky_flag == CV_SUCCESS) run%contacts%taylor(k, :) = dkyv(1:m)
            end do
            call tracker_step(run%contacts, run%block, t_previous, real(t_reached(1), wp))
            t_previous = t_reached(1)
            if (ierr == CV_TSTOP_RETURN .or. t_reached(1) >= t_end) exit
         end do
         y(1:m) = yv(1:m)
         ok = .true.
      end block setup
      ! this rank's setup failed: tell the others before they enter CVode
      if (.not. ready_checked .and. where /= "the setup on another rank") &
         & call MPI_Allreduce(.false., ready, 1, MPI_LOGICAL, MPI_LAND, run%block%comm)
      if (.not. ok) then
         message = "CVODE failed in " // trim(where) // ": " // trim(cvode_flag_name(ierr)) &
            & // report_detail(run%report)
      end if

      if (c_associated(mem)) then
         ierr = FCVodeGetNumSteps(mem, count)
         counters%steps = int(count(1), int64)
         ierr = FCVodeGetNumRhsEvals(mem, count)
         counters%rhs_evals = int(count(1), int64)
         ierr = FCVodeGetNumNonlinSolvIters(mem, count)
         counters%nonlinear_iterations = int(count(1), int64)
         ierr = FCVodeGetNumLinIters(mem, count)
         counters%linear_iterations = int(count(1), int64)
         ierr = FCVodeGetNumPrecEvals(mem, count)
         counters%preconditioner_setups = int(count(1), int64)
         ierr = FCVBBDPrecGetNumGfnEvals(mem, count)
         counters%local_rhs_evals = int(count(1), int64)
         call FCVodeFree(mem)
      end if
      if (associated(lin_sol)) ierr = FSUNLinSolFree(lin_sol)
      if (associated(y_vec)) call FN_VDestroy(y_vec)
      if (associated(dky_vec)) call FN_VDestroy(dky_vec)
      call context_free(ctx)
      call halting_resume(run%halting)
   end subroutine integrate_chain

   !> CVRhsFn: exchange the boundary beads, then the block's right-hand side
   function chain_rhs(t, y, ydot, user_data) result(ierr) &
         & bind(C, name="hcimpact_mpi_chain_rhs")
      real(c_double), value :: t
      type(N_Vector) :: y, ydot
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(chain_integration), pointer :: run
      real(c_double), pointer :: yv(:), dv(:)
      logical :: flags(3), finite
      call c_f_pointer(user_data, run)
      call callback_enter(run%halting, flags)
      yv => FN_VGetArrayPointer(y)
      dv => FN_VGetArrayPointer(ydot)
      call exchange_halo(run%block, yv)
      call block_rhs(run%block, real(t, wp), yv, dv, finite)
      call callback_leave(run%halting, flags)
      ! not finite: left to CVODE's global norms (module header)
      ierr = 0
   end function chain_rhs

   !> CVLocalFn of CVBBDPRE: the block's right-hand side with the halo beads of the
   !> last `block_communicate`, without the walls' impulses (0): their rows depend on
   !> the end bead, outside the band, whose difference quotients would give them to the
   !> wrong columns, and the pivoting of the band's factorisation then carried that into
   !> the other values (a dissipated energy of -1.9e-30 J in a pair without damping);
   !> nothing depends on an impulse, so SPGMR alone solves their rows
   function block_local_rhs(n_local, t, y, g, user_data) result(ierr) &
         & bind(C, name="hcimpact_mpi_block_local_rhs")
      integer(c_int64_t), value :: n_local
      real(c_double), value :: t
      type(N_Vector) :: y, g
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(chain_integration), pointer :: run
      real(c_double), pointer :: yv(:), gv(:)
      logical :: flags(3), finite
      integer :: side
      call c_f_pointer(user_data, run)
      call callback_enter(run%halting, flags)
      yv => FN_VGetArrayPointer(y)
      gv => FN_VGetArrayPointer(g)
      call block_rhs(run%block, real(t, wp), yv, gv, finite)
      do side = 1, 2
         if (run%block%impulse(side) > 0) gv(run%block%impulse(side)) = 0.0_wp
      end do
      call callback_leave(run%halting, flags)
      ierr = 0
   end function block_local_rhs

   !> CVCommFn of CVBBDPRE: the halo exchange for the preconditioner's local
   !> right-hand sides
   function block_communicate(n_local, t, y, user_data) result(ierr) &
         & bind(C, name="hcimpact_mpi_block_communicate")
      integer(c_int64_t), value :: n_local
      real(c_double), value :: t
      type(N_Vector) :: y
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(chain_integration), pointer :: run
      real(c_double), pointer :: yv(:)
      logical :: flags(3)
      call c_f_pointer(user_data, run)
      call callback_enter(run%halting, flags)
      yv => FN_VGetArrayPointer(y)
      call exchange_halo(run%block, yv)
      call callback_leave(run%halting, flags)
      ierr = 0
   end function block_communicate

   !> CVEwtFn: the error weights (module header)
   function chain_error_weights(y, ewt, user_data) result(ierr) &
         & bind(C, name="hcimpact_mpi_chain_error_weights")
      type(N_Vector) :: y, ewt
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(chain_integration), pointer :: run
      real(c_double), pointer :: yv(:), wv(:)
      call c_f_pointer(user_data, run)
      yv => FN_VGetArrayPointer(y)
      wv => FN_VGetArrayPointer(ewt)
      call error_weights(yv(1:run%block%n_local), weights_rtol(run%rtol, .false.), &
         & run%scale, run%root_n, wv(1:run%block%n_local), run%impulse_scale, &
         & count(run%block%impulse > 0))
      ierr = 0
   end function chain_error_weights

end module hcimpact_mpi_chain_cvode
