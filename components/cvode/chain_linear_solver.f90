! SPDX-License-Identifier: Apache-2.0
!> The linear solver of a region's Newton iterations: a SUNDIALS linear solver object
!> (SUNLinearSolver, of the direct, matrix-based type) whose setup and solve are
!> factor_newton_matrix and solve_newton of hcimpact_cvode_chain_system, O(m) each.
!> CVODE forms M = I - gamma J in the band matrix from the Jacobian callback as it
!> does for SUNDIALS' band solver; this object reads M from it, eliminates the
!> displacements and solves the tridiagonal system of the velocities, where the band
!> solver's LU with partial pivoting works on 3 + 4 diagonals and 3 more of fill.
!>
!> Its state (the factors) is allocated by `chain_linear_solver` and freed by the
!> object's free operation (SUNLinSolFree). Like SUNDIALS' own solvers, its
!> operations run with the caller's floating-point halting off (hcimpact_cvode_halting):
!> a diverging Newton iterate may overflow here and is then CVODE's to reject.
module hcimpact_cvode_chain_linear_solver
   use, intrinsic :: iso_c_binding, only : c_int, c_double, c_ptr, c_loc, c_funloc, &
      & c_f_pointer, c_associated, c_null_ptr
   use hcimpact_kinds, only : wp
   use hcimpact_cvode_sundials, only : N_Vector, SUNMatrix, SUNLinearSolver, &
      & SUNLinearSolver_Ops, FN_VGetArrayPointer, FSUNLinSolNewEmpty, &
      & FSUNLinSolFreeEmpty, SUNLINEARSOLVER_DIRECT
   use fsunmatrix_band_mod, only : FSUNBandMatrix_Data, FSUNBandMatrix_LDim, &
      & FSUNBandMatrix_StoredUpperBandwidth
   use hcimpact_cvode_chain_system, only : chain_region, newton_factor, &
      & factor_newton_matrix, solve_newton, region_size
   implicit none
   private

   public :: chain_linear_solver

   !> What the object's content points to
   type :: solver_state
      !> Bodies of the region, and the region (the impulses' rows of its last Jacobian,
      !> kept by the Jacobian callback)
      integer :: m = 0
      type(chain_region), pointer :: region => null()
      type(newton_factor) :: factor
   end type solver_state

   !> Return codes of SUNDIALS' linear solvers: success; a recoverable failure of the
   !> factorisation (CVODE retries with a smaller step; SUNLS_LUFACT_FAIL, 808 in
   !> SUNDIALS 6 and 7); an unrecoverable one (SUNLS_PACKAGE_FAIL_UNREC, -809)
   integer(c_int), parameter :: ls_success = 0_c_int, ls_factor_failed = 808_c_int, &
      & ls_unrecoverable = -809_c_int

contains

   !> A new linear solver for a region in the SUNDIALS context ctx; null when it
   !> cannot be made (out of memory). The region must outlive the solver.
   function chain_linear_solver(region, ctx) result(solver)
      type(chain_region), pointer, intent(in) :: region
      type(c_ptr), intent(in) :: ctx
      type(SUNLinearSolver), pointer :: solver
      type(SUNLinearSolver_Ops), pointer :: ops
      type(solver_state), pointer :: state
      integer :: alloc_stat, m

      solver => FSUNLinSolNewEmpty(ctx)
      if (.not. associated(solver)) return
      allocate(state, stat=alloc_stat)
      ! the factors now, checked (not at the first setup, where out of memory CVODE
      ! failed with CV_LSETUP_FAIL)
      if (alloc_stat == 0) then
         m = region%m
         allocate(state%factor%uu(m), state%factor%uv(m), state%factor%vu(-1:1, m), &
            & state%factor%lower(m), state%factor%pivot(m), state%factor%upper(m), &
            & state%factor%ee(m + 1), stat=alloc_stat)
         if (alloc_stat /= 0) then
            deallocate(state)
            alloc_stat = 1
         end if
      end if
      if (alloc_stat /= 0 .or. .not. c_associated(solver%ops)) then
         if (alloc_stat == 0) deallocate(state)
         call FSUNLinSolFreeEmpty(solver)
         nullify(solver)
         return
      end if
      state%m = region%m
      state%region => region
      solver%content = c_loc(state)
      call c_f_pointer(solver%ops, ops)
      ops%gettype = c_funloc(solver_type)
      ops%setup = c_funloc(solver_setup)
      ops%solve = c_funloc(solver_solve)
      ops%free = c_funloc(solver_free)
   end function chain_linear_solver

   !> SUNLinSolGetType: direct, with a matrix
   function solver_type(solver) result(kind) bind(C)
      type(SUNLinearSolver) :: solver
      integer(c_int) :: kind
      kind = SUNLINEARSOLVER_DIRECT
   end function solver_type

   !> SUNLinSolSetup: factor M, held by CVODE in the band matrix a
   function solver_setup(solver, a) result(ierr) bind(C)
      type(SUNLinearSolver) :: solver
      type(SUNMatrix) :: a
      integer(c_int) :: ierr
      type(solver_state), pointer :: state
      real(c_double), pointer, contiguous :: data(:), band(:, :)
      integer :: info

      ierr = ls_unrecoverable
      if (.not. c_associated(solver%content)) return
      call c_f_pointer(solver%content, state)
      data => FSUNBandMatrix_Data(a)
      call c_f_pointer(c_loc(data(1)), band, &
         & [int(FSUNBandMatrix_LDim(a)), region_size(state%m)])
      call factor_newton_matrix(state%m, int(FSUNBandMatrix_StoredUpperBandwidth(a)), &
         & band, state%region%wall_slope, state%factor, info)
      if (info == 0) then
         ierr = ls_success
      else if (info > 0) then
         ierr = ls_factor_failed
      end if
   end function solver_setup

   !> SUNLinSolSolve: x = M^-1 b with the factors of the last setup
   function solver_solve(solver, a, x, b, tol) result(ierr) bind(C)
      type(SUNLinearSolver) :: solver
      type(SUNMatrix) :: a
      type(N_Vector) :: x, b
      real(c_double), value :: tol
      integer(c_int) :: ierr
      type(solver_state), pointer :: state
      real(c_double), pointer :: xv(:), bv(:)

      ierr = ls_unrecoverable
      if (.not. c_associated(solver%content)) return
      call c_f_pointer(solver%content, state)
      if (.not. allocated(state%factor%pivot)) return
      xv => FN_VGetArrayPointer(x)
      bv => FN_VGetArrayPointer(b)
      xv = bv
      call solve_newton(state%m, state%factor, xv)
      ierr = ls_success
   end function solver_solve

   !> SUNLinSolFree: the state, then the object
   function solver_free(solver) result(ierr) bind(C)
      type(SUNLinearSolver), target :: solver
      integer(c_int) :: ierr
      type(solver_state), pointer :: state
      type(SUNLinearSolver), pointer :: object
      if (c_associated(solver%content)) then
         call c_f_pointer(solver%content, state)
         deallocate(state)
         solver%content = c_null_ptr
      end if
      object => solver
      call FSUNLinSolFreeEmpty(object)
      ierr = ls_success
   end function solver_free

end module hcimpact_cvode_chain_linear_solver
