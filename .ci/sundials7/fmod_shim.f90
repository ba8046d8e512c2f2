! SPDX-License-Identifier: Apache-2.0
!
! Test scaffolding for .ci/sundials7-check, never part of the library.
!
! A stand-in for the Fortran 2003 interface of SUNDIALS 7 (the SWIG-generated
! modules fsundials_core_mod, fnvector_serial_mod, fsunmatrix_dense_mod,
! fsunlinsol_dense_mod, fsunmatrix_band_mod and fcvode_mod),
! written by hand for exactly the names that
! components/cvode uses. The C library it calls is a real SUNDIALS 7.1 build (CVODES,
! whose C functions have the same names and signatures as CVODE's).
!
! The Fortran side of every procedure follows the conventions of SUNDIALS' generated
! wrappers, so that our code meets the same argument rules as with a real install:
!   - opaque C pointers (void*, SUNContext) are `type(c_ptr)` passed by reference,
!     without an intent;
!   - N_Vector, SUNMatrix and SUNLinearSolver arguments are the derived types,
!     `target, intent(inout)`, and constructors return Fortran pointers to them;
!   - scalar inputs are `intent(in)` (passed by reference on the Fortran side);
!   - C output pointers (long*, int*, sunrealtype*) are assumed-size arrays,
!     `target, intent(inout)`;
!   - function pointers are `type(c_funptr), intent(in), value`;
!   - FN_VGetArrayPointer and FSUNDenseMatrix_Data return `real(c_double)` pointer
!     arrays of the local length of the vector and of the whole matrix data.
! The real wrappers go through a C layer (_wrap_F...); here each procedure calls
! the SUNDIALS C function directly through a bind(C) interface.
!
! Assumes the default SUNDIALS 7 configuration: double precision, 64-bit
! sunindextype, no MPI (SUNComm is an int).

!> fsundials_core_mod: context, error handlers and the generic vector, matrix and
!> linear solver objects.
module fsundials_core_mod
   use, intrinsic :: iso_c_binding, only : c_int, c_int64_t, c_double, c_ptr, c_funptr, &
      & c_loc, c_f_pointer, c_associated
   implicit none
   private

   !> No communicator (SUNComm is an int without MPI)
   integer(c_int), parameter, public :: SUN_COMM_NULL = 0_c_int
   integer(c_int), parameter, public :: SUN_SUCCESS = 0_c_int

   !> struct _generic_N_Vector
   type, bind(C), public :: N_Vector
      type(c_ptr), public :: content
      type(c_ptr), public :: ops
      type(c_ptr), public :: sunctx
   end type N_Vector

   !> struct _generic_SUNMatrix
   type, bind(C), public :: SUNMatrix
      type(c_ptr), public :: content
      type(c_ptr), public :: ops
      type(c_ptr), public :: sunctx
   end type SUNMatrix

   !> struct _generic_SUNLinearSolver
   type, bind(C), public :: SUNLinearSolver
      type(c_ptr), public :: content
      type(c_ptr), public :: ops
      type(c_ptr), public :: sunctx
   end type SUNLinearSolver

   !> struct _generic_SUNLinearSolver_Ops (SUNDIALS 7.1: the same fields in the same
   !> order as in 6.4)
   type, bind(C), public :: SUNLinearSolver_Ops
      type(c_funptr), public :: gettype, getid, setatimes, setpreconditioner, &
         & setscalingvectors, setzeroguess, initialize, setup, solve, numiters, &
         & resnorm, lastflag, space, resid, free
   end type SUNLinearSolver_Ops

   !> SUNLinearSolver_Type: direct
   integer(c_int), parameter, public :: SUNLINEARSOLVER_DIRECT = 0_c_int

   public :: FSUNContext_Create, FSUNContext_Free, FSUNContext_PushErrHandler, &
      & FSUNContext_ClearErrHandlers
   public :: FN_VDestroy, FN_VGetLocalLength, FN_VGetArrayPointer
   public :: FSUNMatDestroy, FSUNLinSolFree, FSUNLinSolNewEmpty, FSUNLinSolFreeEmpty

   interface
      ! SUNErrCode SUNContext_Create(SUNComm comm, SUNContext* sunctx_out)
      function c_context_create(comm, ctx_out) result(code) &
            & bind(C, name="SUNContext_Create")
         import :: c_int, c_ptr
         integer(c_int), value :: comm
         type(c_ptr), value :: ctx_out
         integer(c_int) :: code
      end function c_context_create
      ! SUNErrCode SUNContext_Free(SUNContext* ctx)
      function c_context_free(ctx) result(code) bind(C, name="SUNContext_Free")
         import :: c_int, c_ptr
         type(c_ptr), value :: ctx
         integer(c_int) :: code
      end function c_context_free
      ! SUNErrCode SUNContext_PushErrHandler(SUNContext, SUNErrHandlerFn, void*)
      function c_push_err_handler(ctx, fn, user_data) result(code) &
            & bind(C, name="SUNContext_PushErrHandler")
         import :: c_int, c_ptr, c_funptr
         type(c_ptr), value :: ctx
         type(c_funptr), value :: fn
         type(c_ptr), value :: user_data
         integer(c_int) :: code
      end function c_push_err_handler
      ! SUNErrCode SUNContext_ClearErrHandlers(SUNContext)
      function c_clear_err_handlers(ctx) result(code) &
            & bind(C, name="SUNContext_ClearErrHandlers")
         import :: c_int, c_ptr
         type(c_ptr), value :: ctx
         integer(c_int) :: code
      end function c_clear_err_handlers
      ! void N_VDestroy(N_Vector)
      subroutine c_nv_destroy(v) bind(C, name="N_VDestroy")
         import :: c_ptr
         type(c_ptr), value :: v
      end subroutine c_nv_destroy
      ! sunrealtype* N_VGetArrayPointer(N_Vector)
      function c_nv_array(v) result(p) bind(C, name="N_VGetArrayPointer")
         import :: c_ptr
         type(c_ptr), value :: v
         type(c_ptr) :: p
      end function c_nv_array
      ! sunindextype N_VGetLocalLength(N_Vector)
      function c_nv_local_length(v) result(n) bind(C, name="N_VGetLocalLength")
         import :: c_ptr, c_int64_t
         type(c_ptr), value :: v
         integer(c_int64_t) :: n
      end function c_nv_local_length
      ! void SUNMatDestroy(SUNMatrix)
      subroutine c_mat_destroy(a) bind(C, name="SUNMatDestroy")
         import :: c_ptr
         type(c_ptr), value :: a
      end subroutine c_mat_destroy
      ! SUNErrCode SUNLinSolFree(SUNLinearSolver)
      function c_ls_free(s) result(code) bind(C, name="SUNLinSolFree")
         import :: c_int, c_ptr
         type(c_ptr), value :: s
         integer(c_int) :: code
      end function c_ls_free
      ! SUNLinearSolver SUNLinSolNewEmpty(SUNContext)
      function c_ls_new_empty(ctx) result(s) bind(C, name="SUNLinSolNewEmpty")
         import :: c_ptr
         type(c_ptr), value :: ctx
         type(c_ptr) :: s
      end function c_ls_new_empty
      ! void SUNLinSolFreeEmpty(SUNLinearSolver)
      subroutine c_ls_free_empty(s) bind(C, name="SUNLinSolFreeEmpty")
         import :: c_ptr
         type(c_ptr), value :: s
      end subroutine c_ls_free_empty
   end interface

contains

   function FSUNContext_Create(comm, sunctx_out) result(code)
      integer :: comm
      type(c_ptr), target, intent(inout) :: sunctx_out
      integer(c_int) :: code
      code = c_context_create(int(comm, c_int), c_loc(sunctx_out))
   end function FSUNContext_Create

   function FSUNContext_Free(ctx) result(code)
      type(c_ptr), target, intent(inout) :: ctx
      integer(c_int) :: code
      code = c_context_free(c_loc(ctx))
   end function FSUNContext_Free

   function FSUNContext_PushErrHandler(sunctx, err_fn, err_user_data) result(code)
      type(c_ptr) :: sunctx
      type(c_funptr), intent(in), value :: err_fn
      type(c_ptr) :: err_user_data
      integer(c_int) :: code
      code = c_push_err_handler(sunctx, err_fn, err_user_data)
   end function FSUNContext_PushErrHandler

   function FSUNContext_ClearErrHandlers(sunctx) result(code)
      type(c_ptr) :: sunctx
      integer(c_int) :: code
      code = c_clear_err_handlers(sunctx)
   end function FSUNContext_ClearErrHandlers

   subroutine FN_VDestroy(v)
      type(N_Vector), target, intent(inout) :: v
      call c_nv_destroy(c_loc(v))
   end subroutine FN_VDestroy

   function FN_VGetLocalLength(v) result(n)
      type(N_Vector), target, intent(inout) :: v
      integer(c_int64_t) :: n
      n = c_nv_local_length(c_loc(v))
   end function FN_VGetLocalLength

   !> The data of a vector as a Fortran array of its local length
   function FN_VGetArrayPointer(v) result(x)
      type(N_Vector), target, intent(inout) :: v
      real(c_double), dimension(:), pointer :: x
      call c_f_pointer(c_nv_array(c_loc(v)), x, [FN_VGetLocalLength(v)])
   end function FN_VGetArrayPointer

   subroutine FSUNMatDestroy(a)
      type(SUNMatrix), target, intent(inout) :: a
      call c_mat_destroy(c_loc(a))
   end subroutine FSUNMatDestroy

   function FSUNLinSolFree(s) result(code)
      type(SUNLinearSolver), target, intent(inout) :: s
      integer(c_int) :: code
      code = c_ls_free(c_loc(s))
   end function FSUNLinSolFree

   function FSUNLinSolNewEmpty(sunctx) result(s)
      type(c_ptr) :: sunctx
      type(SUNLinearSolver), pointer :: s
      type(c_ptr) :: p
      nullify(s)
      p = c_ls_new_empty(sunctx)
      if (c_associated(p)) call c_f_pointer(p, s)
   end function FSUNLinSolNewEmpty

   subroutine FSUNLinSolFreeEmpty(s)
      type(SUNLinearSolver), target, intent(inout) :: s
      call c_ls_free_empty(c_loc(s))
   end subroutine FSUNLinSolFreeEmpty

end module fsundials_core_mod


!> fnvector_serial_mod: the serial vector.
module fnvector_serial_mod
   use, intrinsic :: iso_c_binding, only : c_int64_t, c_double, c_ptr, c_loc, c_f_pointer
   use fsundials_core_mod, only : N_Vector
   implicit none
   private

   public :: FN_VMake_Serial

   interface
      ! N_Vector N_VMake_Serial(sunindextype, sunrealtype* v_data, SUNContext)
      function c_make_serial(n, v_data, ctx) result(v) bind(C, name="N_VMake_Serial")
         import :: c_int64_t, c_ptr
         integer(c_int64_t), value :: n
         type(c_ptr), value :: v_data
         type(c_ptr), value :: ctx
         type(c_ptr) :: v
      end function c_make_serial
   end interface

contains

   !> A vector around the caller's data (not copied, not freed by FN_VDestroy)
   function FN_VMake_Serial(vec_length, v_data, sunctx) result(v)
      integer(c_int64_t), intent(in) :: vec_length
      real(c_double), dimension(*), target, intent(inout) :: v_data
      type(c_ptr) :: sunctx
      type(N_Vector), pointer :: v
      call c_f_pointer(c_make_serial(vec_length, c_loc(v_data(1)), sunctx), v)
   end function FN_VMake_Serial

end module fnvector_serial_mod


!> fsunmatrix_dense_mod: the dense matrix.
module fsunmatrix_dense_mod
   use, intrinsic :: iso_c_binding, only : c_int64_t, c_double, c_ptr, c_loc, c_f_pointer
   use fsundials_core_mod, only : SUNMatrix
   implicit none
   private

   public :: FSUNDenseMatrix, FSUNDenseMatrix_Data, FSUNDenseMatrix_LData

   interface
      ! SUNMatrix SUNDenseMatrix(sunindextype M, sunindextype N, SUNContext)
      function c_dense_matrix(m, n, ctx) result(a) bind(C, name="SUNDenseMatrix")
         import :: c_int64_t, c_ptr
         integer(c_int64_t), value :: m, n
         type(c_ptr), value :: ctx
         type(c_ptr) :: a
      end function c_dense_matrix
      ! sunrealtype* SUNDenseMatrix_Data(SUNMatrix)
      function c_dense_data(a) result(p) bind(C, name="SUNDenseMatrix_Data")
         import :: c_ptr
         type(c_ptr), value :: a
         type(c_ptr) :: p
      end function c_dense_data
      ! sunindextype SUNDenseMatrix_LData(SUNMatrix)
      function c_dense_ldata(a) result(n) bind(C, name="SUNDenseMatrix_LData")
         import :: c_ptr, c_int64_t
         type(c_ptr), value :: a
         integer(c_int64_t) :: n
      end function c_dense_ldata
   end interface

contains

   function FSUNDenseMatrix(m, n, sunctx) result(a)
      integer(c_int64_t), intent(in) :: m, n
      type(c_ptr) :: sunctx
      type(SUNMatrix), pointer :: a
      call c_f_pointer(c_dense_matrix(m, n, sunctx), a)
   end function FSUNDenseMatrix

   function FSUNDenseMatrix_LData(a) result(n)
      type(SUNMatrix), target, intent(inout) :: a
      integer(c_int64_t) :: n
      n = c_dense_ldata(c_loc(a))
   end function FSUNDenseMatrix_LData

   !> The column-major data of the matrix, all M*N entries
   function FSUNDenseMatrix_Data(a) result(x)
      type(SUNMatrix), target, intent(inout) :: a
      real(c_double), dimension(:), pointer :: x
      call c_f_pointer(c_dense_data(c_loc(a)), x, [FSUNDenseMatrix_LData(a)])
   end function FSUNDenseMatrix_Data

end module fsunmatrix_dense_mod


!> fsunlinsol_dense_mod: the dense direct linear solver.
module fsunlinsol_dense_mod
   use, intrinsic :: iso_c_binding, only : c_ptr, c_loc, c_f_pointer
   use fsundials_core_mod, only : N_Vector, SUNMatrix, SUNLinearSolver
   implicit none
   private

   public :: FSUNLinSol_Dense

   interface
      ! SUNLinearSolver SUNLinSol_Dense(N_Vector y, SUNMatrix A, SUNContext)
      function c_linsol_dense(y, a, ctx) result(s) bind(C, name="SUNLinSol_Dense")
         import :: c_ptr
         type(c_ptr), value :: y, a, ctx
         type(c_ptr) :: s
      end function c_linsol_dense
   end interface

contains

   function FSUNLinSol_Dense(y, a, sunctx) result(s)
      type(N_Vector), target, intent(inout) :: y
      type(SUNMatrix), target, intent(inout) :: a
      type(c_ptr) :: sunctx
      type(SUNLinearSolver), pointer :: s
      call c_f_pointer(c_linsol_dense(c_loc(y), c_loc(a), sunctx), s)
   end function FSUNLinSol_Dense

end module fsunlinsol_dense_mod


!> fsunmatrix_band_mod: the band matrix (the systems of bodies on a line).
module fsunmatrix_band_mod
   use, intrinsic :: iso_c_binding, only : c_int64_t, c_double, c_ptr, c_loc, c_f_pointer
   use fsundials_core_mod, only : SUNMatrix
   implicit none
   private

   public :: FSUNBandMatrixStorage, FSUNBandMatrix_Data, FSUNBandMatrix_LData, &
      & FSUNBandMatrix_LDim, FSUNBandMatrix_StoredUpperBandwidth

   interface
      ! SUNMatrix SUNBandMatrixStorage(sunindextype N, sunindextype mu,
      ! sunindextype ml, sunindextype smu, SUNContext)
      function c_band_matrix(n, mu, ml, smu, ctx) result(a) &
            & bind(C, name="SUNBandMatrixStorage")
         import :: c_int64_t, c_ptr
         integer(c_int64_t), value :: n, mu, ml, smu
         type(c_ptr), value :: ctx
         type(c_ptr) :: a
      end function c_band_matrix
      ! sunrealtype* SUNBandMatrix_Data(SUNMatrix)
      function c_band_data(a) result(p) bind(C, name="SUNBandMatrix_Data")
         import :: c_ptr
         type(c_ptr), value :: a
         type(c_ptr) :: p
      end function c_band_data
      ! sunindextype SUNBandMatrix_LData(SUNMatrix)
      function c_band_ldata(a) result(n) bind(C, name="SUNBandMatrix_LData")
         import :: c_ptr, c_int64_t
         type(c_ptr), value :: a
         integer(c_int64_t) :: n
      end function c_band_ldata
      ! sunindextype SUNBandMatrix_LDim(SUNMatrix)
      function c_band_ldim(a) result(n) bind(C, name="SUNBandMatrix_LDim")
         import :: c_ptr, c_int64_t
         type(c_ptr), value :: a
         integer(c_int64_t) :: n
      end function c_band_ldim
      ! sunindextype SUNBandMatrix_StoredUpperBandwidth(SUNMatrix)
      function c_band_smu(a) result(n) bind(C, name="SUNBandMatrix_StoredUpperBandwidth")
         import :: c_ptr, c_int64_t
         type(c_ptr), value :: a
         integer(c_int64_t) :: n
      end function c_band_smu
   end interface

contains

   function FSUNBandMatrixStorage(n, mu, ml, smu, sunctx) result(a)
      integer(c_int64_t), intent(in) :: n, mu, ml, smu
      type(c_ptr) :: sunctx
      type(SUNMatrix), pointer :: a
      call c_f_pointer(c_band_matrix(n, mu, ml, smu, sunctx), a)
   end function FSUNBandMatrixStorage

   function FSUNBandMatrix_LData(a) result(n)
      type(SUNMatrix), target, intent(inout) :: a
      integer(c_int64_t) :: n
      n = c_band_ldata(c_loc(a))
   end function FSUNBandMatrix_LData

   function FSUNBandMatrix_LDim(a) result(n)
      type(SUNMatrix), target, intent(inout) :: a
      integer(c_int64_t) :: n
      n = c_band_ldim(c_loc(a))
   end function FSUNBandMatrix_LDim

   function FSUNBandMatrix_StoredUpperBandwidth(a) result(n)
      type(SUNMatrix), target, intent(inout) :: a
      integer(c_int64_t) :: n
      n = c_band_smu(c_loc(a))
   end function FSUNBandMatrix_StoredUpperBandwidth

   !> The column-major data of the matrix, all of its stored entries
   function FSUNBandMatrix_Data(a) result(x)
      type(SUNMatrix), target, intent(inout) :: a
      real(c_double), dimension(:), pointer :: x
      call c_f_pointer(c_band_data(c_loc(a)), x, [FSUNBandMatrix_LData(a)])
   end function FSUNBandMatrix_Data

end module fsunmatrix_band_mod


!> fcvode_mod: the CVODE integrator (bound to the functions of CVODES, which
!> carry the same C names and signatures).
module fcvode_mod
   use, intrinsic :: iso_c_binding, only : c_int, c_long, c_double, c_ptr, c_funptr, c_loc
   use fsundials_core_mod, only : N_Vector, SUNMatrix, SUNLinearSolver
   implicit none
   private

   ! cvode.h / cvodes.h (the return codes down to -28 are shared by both)
   integer(c_int), parameter, public :: CV_ADAMS = 1_c_int
   integer(c_int), parameter, public :: CV_BDF = 2_c_int
   integer(c_int), parameter, public :: CV_NORMAL = 1_c_int
   integer(c_int), parameter, public :: CV_ONE_STEP = 2_c_int
   integer(c_int), parameter, public :: CV_SUCCESS = 0_c_int
   integer(c_int), parameter, public :: CV_TSTOP_RETURN = 1_c_int
   integer(c_int), parameter, public :: CV_ROOT_RETURN = 2_c_int
   integer(c_int), parameter, public :: CV_WARNING = 99_c_int
   integer(c_int), parameter, public :: CV_TOO_MUCH_WORK = -1_c_int
   integer(c_int), parameter, public :: CV_TOO_MUCH_ACC = -2_c_int
   integer(c_int), parameter, public :: CV_ERR_FAILURE = -3_c_int
   integer(c_int), parameter, public :: CV_CONV_FAILURE = -4_c_int
   integer(c_int), parameter, public :: CV_LINIT_FAIL = -5_c_int
   integer(c_int), parameter, public :: CV_LSETUP_FAIL = -6_c_int
   integer(c_int), parameter, public :: CV_LSOLVE_FAIL = -7_c_int
   integer(c_int), parameter, public :: CV_RHSFUNC_FAIL = -8_c_int
   integer(c_int), parameter, public :: CV_FIRST_RHSFUNC_ERR = -9_c_int
   integer(c_int), parameter, public :: CV_REPTD_RHSFUNC_ERR = -10_c_int
   integer(c_int), parameter, public :: CV_UNREC_RHSFUNC_ERR = -11_c_int
   integer(c_int), parameter, public :: CV_RTFUNC_FAIL = -12_c_int
   integer(c_int), parameter, public :: CV_NLS_INIT_FAIL = -13_c_int
   integer(c_int), parameter, public :: CV_NLS_SETUP_FAIL = -14_c_int
   integer(c_int), parameter, public :: CV_CONSTR_FAIL = -15_c_int
   integer(c_int), parameter, public :: CV_NLS_FAIL = -16_c_int
   integer(c_int), parameter, public :: CV_MEM_FAIL = -20_c_int
   integer(c_int), parameter, public :: CV_MEM_NULL = -21_c_int
   integer(c_int), parameter, public :: CV_ILL_INPUT = -22_c_int
   integer(c_int), parameter, public :: CV_NO_MALLOC = -23_c_int
   integer(c_int), parameter, public :: CV_BAD_K = -24_c_int
   integer(c_int), parameter, public :: CV_BAD_T = -25_c_int
   integer(c_int), parameter, public :: CV_BAD_DKY = -26_c_int
   integer(c_int), parameter, public :: CV_TOO_CLOSE = -27_c_int
   integer(c_int), parameter, public :: CV_VECTOROP_ERR = -28_c_int

   public :: FCVodeCreate, FCVodeInit, FCVodeSetUserData, FCVodeSVtolerances, &
      & FCVodeSetLinearSolver, FCVodeSetJacFn, FCVodeRootInit, FCVodeSetRootDirection, &
      & FCVodeSetMaxNumSteps, FCVodeSetMaxHnilWarns, FCVodeSetInitStep, &
      & FCVodeSetNoInactiveRootWarn, FCVode, FCVodeGetRootInfo, FCVodeFree, &
      & FCVodeGetNumSteps, FCVodeGetNumRhsEvals, FCVodeGetNumJacEvals, &
      & FCVodeGetNumGEvals, FCVodeGetNumErrTestFails, FCVodeGetNumNonlinSolvIters, &
      & FCVodeGetNumNonlinSolvConvFails, FCVodeGetNumLinSolvSetups, &
      & FCVodeGetNumLinRhsEvals, FCVodeWFtolerances, FCVodeSetStopTime, FCVodeGetDky, &
      & FCVodeReInit

   interface
      ! void* CVodeCreate(int lmm, SUNContext)
      function c_create(lmm, ctx) result(mem) bind(C, name="CVodeCreate")
         import :: c_int, c_ptr
         integer(c_int), value :: lmm
         type(c_ptr), value :: ctx
         type(c_ptr) :: mem
      end function c_create
      ! int CVodeInit(void*, CVRhsFn, sunrealtype t0, N_Vector y0)
      function c_init(mem, f, t0, y0) result(flag) bind(C, name="CVodeInit")
         import :: c_int, c_ptr, c_funptr, c_double
         type(c_ptr), value :: mem
         type(c_funptr), value :: f
         real(c_double), value :: t0
         type(c_ptr), value :: y0
         integer(c_int) :: flag
      end function c_init
      ! int CVodeReInit(void*, sunrealtype t0, N_Vector y0)
      function c_reinit(mem, t0, y0) result(flag) bind(C, name="CVodeReInit")
         import :: c_int, c_ptr, c_double
         type(c_ptr), value :: mem
         real(c_double), value :: t0
         type(c_ptr), value :: y0
         integer(c_int) :: flag
      end function c_reinit
      ! int CVodeSetUserData(void*, void*)
      function c_set_user_data(mem, data) result(flag) bind(C, name="CVodeSetUserData")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, data
         integer(c_int) :: flag
      end function c_set_user_data
      ! int CVodeSVtolerances(void*, sunrealtype reltol, N_Vector abstol)
      function c_sv_tolerances(mem, reltol, abstol) result(flag) &
            & bind(C, name="CVodeSVtolerances")
         import :: c_int, c_ptr, c_double
         type(c_ptr), value :: mem
         real(c_double), value :: reltol
         type(c_ptr), value :: abstol
         integer(c_int) :: flag
      end function c_sv_tolerances
      ! int CVodeWFtolerances(void*, CVEwtFn efun)
      function c_wf_tolerances(mem, efun) result(flag) bind(C, name="CVodeWFtolerances")
         import :: c_int, c_ptr, c_funptr
         type(c_ptr), value :: mem
         type(c_funptr), value :: efun
         integer(c_int) :: flag
      end function c_wf_tolerances
      ! int CVodeSetStopTime(void*, sunrealtype tstop)
      function c_set_stop_time(mem, tstop) result(flag) bind(C, name="CVodeSetStopTime")
         import :: c_int, c_ptr, c_double
         type(c_ptr), value :: mem
         real(c_double), value :: tstop
         integer(c_int) :: flag
      end function c_set_stop_time
      ! int CVodeGetDky(void*, sunrealtype t, int k, N_Vector dky)
      function c_get_dky(mem, t, k, dky) result(flag) bind(C, name="CVodeGetDky")
         import :: c_int, c_ptr, c_double
         type(c_ptr), value :: mem
         real(c_double), value :: t
         integer(c_int), value :: k
         type(c_ptr), value :: dky
         integer(c_int) :: flag
      end function c_get_dky
      ! int CVodeSetLinearSolver(void*, SUNLinearSolver, SUNMatrix)
      function c_set_linear_solver(mem, ls, a) result(flag) &
            & bind(C, name="CVodeSetLinearSolver")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, ls, a
         integer(c_int) :: flag
      end function c_set_linear_solver
      ! int CVodeSetJacFn(void*, CVLsJacFn)
      function c_set_jac_fn(mem, jac) result(flag) bind(C, name="CVodeSetJacFn")
         import :: c_int, c_ptr, c_funptr
         type(c_ptr), value :: mem
         type(c_funptr), value :: jac
         integer(c_int) :: flag
      end function c_set_jac_fn
      ! int CVodeRootInit(void*, int nrtfn, CVRootFn)
      function c_root_init(mem, nrtfn, g) result(flag) bind(C, name="CVodeRootInit")
         import :: c_int, c_ptr, c_funptr
         type(c_ptr), value :: mem
         integer(c_int), value :: nrtfn
         type(c_funptr), value :: g
         integer(c_int) :: flag
      end function c_root_init
      ! int CVodeSetRootDirection(void*, int* rootdir)
      function c_set_root_direction(mem, rootdir) result(flag) &
            & bind(C, name="CVodeSetRootDirection")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, rootdir
         integer(c_int) :: flag
      end function c_set_root_direction
      ! int CVodeSetMaxNumSteps(void*, long int)
      function c_set_max_num_steps(mem, mxsteps) result(flag) &
            & bind(C, name="CVodeSetMaxNumSteps")
         import :: c_int, c_long, c_ptr
         type(c_ptr), value :: mem
         integer(c_long), value :: mxsteps
         integer(c_int) :: flag
      end function c_set_max_num_steps
      ! int CVodeSetMaxHnilWarns(void*, int)
      function c_set_max_hnil_warns(mem, mxhnil) result(flag) &
            & bind(C, name="CVodeSetMaxHnilWarns")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem
         integer(c_int), value :: mxhnil
         integer(c_int) :: flag
      end function c_set_max_hnil_warns
      ! int CVodeSetInitStep(void*, sunrealtype)
      function c_set_init_step(mem, hin) result(flag) bind(C, name="CVodeSetInitStep")
         import :: c_int, c_ptr, c_double
         type(c_ptr), value :: mem
         real(c_double), value :: hin
         integer(c_int) :: flag
      end function c_set_init_step
      ! int CVodeSetNoInactiveRootWarn(void*)
      function c_set_no_inactive_root_warn(mem) result(flag) &
            & bind(C, name="CVodeSetNoInactiveRootWarn")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem
         integer(c_int) :: flag
      end function c_set_no_inactive_root_warn
      ! int CVode(void*, sunrealtype tout, N_Vector yout, sunrealtype* tret, int itask)
      function c_cvode(mem, tout, yout, tret, itask) result(flag) bind(C, name="CVode")
         import :: c_int, c_ptr, c_double
         type(c_ptr), value :: mem
         real(c_double), value :: tout
         type(c_ptr), value :: yout, tret
         integer(c_int), value :: itask
         integer(c_int) :: flag
      end function c_cvode
      ! int CVodeGetRootInfo(void*, int* rootsfound)
      function c_get_root_info(mem, rootsfound) result(flag) &
            & bind(C, name="CVodeGetRootInfo")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, rootsfound
         integer(c_int) :: flag
      end function c_get_root_info
      ! void CVodeFree(void** cvode_mem)
      subroutine c_free(mem_ptr) bind(C, name="CVodeFree")
         import :: c_ptr
         type(c_ptr), value :: mem_ptr
      end subroutine c_free
   end interface

   ! int CVodeGetNum...(void*, long int*)
   interface
      function c_get_num_steps(mem, out) result(flag) bind(C, name="CVodeGetNumSteps")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_steps
      function c_get_num_rhs_evals(mem, out) result(flag) &
            & bind(C, name="CVodeGetNumRhsEvals")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_rhs_evals
      function c_get_num_jac_evals(mem, out) result(flag) &
            & bind(C, name="CVodeGetNumJacEvals")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_jac_evals
      function c_get_num_g_evals(mem, out) result(flag) bind(C, name="CVodeGetNumGEvals")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_g_evals
      function c_get_num_err_test_fails(mem, out) result(flag) &
            & bind(C, name="CVodeGetNumErrTestFails")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_err_test_fails
      function c_get_num_nonlin_solv_iters(mem, out) result(flag) &
            & bind(C, name="CVodeGetNumNonlinSolvIters")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_nonlin_solv_iters
      function c_get_num_nonlin_solv_conv_fails(mem, out) result(flag) &
            & bind(C, name="CVodeGetNumNonlinSolvConvFails")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_nonlin_solv_conv_fails
      function c_get_num_lin_solv_setups(mem, out) result(flag) &
            & bind(C, name="CVodeGetNumLinSolvSetups")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_lin_solv_setups
      function c_get_num_lin_rhs_evals(mem, out) result(flag) &
            & bind(C, name="CVodeGetNumLinRhsEvals")
         import :: c_int, c_ptr
         type(c_ptr), value :: mem, out
         integer(c_int) :: flag
      end function c_get_num_lin_rhs_evals
   end interface

contains

   function FCVodeCreate(lmm, sunctx) result(mem)
      integer(c_int), intent(in) :: lmm
      type(c_ptr) :: sunctx
      type(c_ptr) :: mem
      mem = c_create(lmm, sunctx)
   end function FCVodeCreate

   function FCVodeInit(cvode_mem, f, t0, y0) result(flag)
      type(c_ptr) :: cvode_mem
      type(c_funptr), intent(in), value :: f
      real(c_double), intent(in) :: t0
      type(N_Vector), target, intent(inout) :: y0
      integer(c_int) :: flag
      flag = c_init(cvode_mem, f, t0, c_loc(y0))
   end function FCVodeInit

   function FCVodeReInit(cvode_mem, t0, y0) result(flag)
      type(c_ptr) :: cvode_mem
      real(c_double), intent(in) :: t0
      type(N_Vector), target, intent(inout) :: y0
      integer(c_int) :: flag
      flag = c_reinit(cvode_mem, t0, c_loc(y0))
   end function FCVodeReInit

   function FCVodeSetUserData(cvode_mem, user_data) result(flag)
      type(c_ptr) :: cvode_mem
      type(c_ptr) :: user_data
      integer(c_int) :: flag
      flag = c_set_user_data(cvode_mem, user_data)
   end function FCVodeSetUserData

   function FCVodeSVtolerances(cvode_mem, reltol, abstol) result(flag)
      type(c_ptr) :: cvode_mem
      real(c_double), intent(in) :: reltol
      type(N_Vector), target, intent(inout) :: abstol
      integer(c_int) :: flag
      flag = c_sv_tolerances(cvode_mem, reltol, c_loc(abstol))
   end function FCVodeSVtolerances

   function FCVodeSetLinearSolver(cvode_mem, ls, a) result(flag)
      type(c_ptr) :: cvode_mem
      type(SUNLinearSolver), target, intent(inout) :: ls
      type(SUNMatrix), target, intent(inout) :: a
      integer(c_int) :: flag
      flag = c_set_linear_solver(cvode_mem, c_loc(ls), c_loc(a))
   end function FCVodeSetLinearSolver

   function FCVodeWFtolerances(cvode_mem, efun) result(flag)
      type(c_ptr) :: cvode_mem
      type(c_funptr), intent(in), value :: efun
      integer(c_int) :: flag
      flag = c_wf_tolerances(cvode_mem, efun)
   end function FCVodeWFtolerances

   function FCVodeSetStopTime(cvode_mem, tstop) result(flag)
      type(c_ptr) :: cvode_mem
      real(c_double), intent(in) :: tstop
      integer(c_int) :: flag
      flag = c_set_stop_time(cvode_mem, tstop)
   end function FCVodeSetStopTime

   function FCVodeGetDky(cvode_mem, t, k, dky) result(flag)
      type(c_ptr) :: cvode_mem
      real(c_double), intent(in) :: t
      integer(c_int), intent(in) :: k
      type(N_Vector), target, intent(inout) :: dky
      integer(c_int) :: flag
      flag = c_get_dky(cvode_mem, t, k, c_loc(dky))
   end function FCVodeGetDky

   function FCVodeSetJacFn(cvode_mem, jac) result(flag)
      type(c_ptr) :: cvode_mem
      type(c_funptr), intent(in), value :: jac
      integer(c_int) :: flag
      flag = c_set_jac_fn(cvode_mem, jac)
   end function FCVodeSetJacFn

   function FCVodeRootInit(cvode_mem, nrtfn, g) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_int), intent(in) :: nrtfn
      type(c_funptr), intent(in), value :: g
      integer(c_int) :: flag
      flag = c_root_init(cvode_mem, nrtfn, g)
   end function FCVodeRootInit

   function FCVodeSetRootDirection(cvode_mem, rootdir) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_int), dimension(*), target, intent(inout) :: rootdir
      integer(c_int) :: flag
      flag = c_set_root_direction(cvode_mem, c_loc(rootdir(1)))
   end function FCVodeSetRootDirection

   function FCVodeSetMaxNumSteps(cvode_mem, mxsteps) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), intent(in) :: mxsteps
      integer(c_int) :: flag
      flag = c_set_max_num_steps(cvode_mem, mxsteps)
   end function FCVodeSetMaxNumSteps

   function FCVodeSetMaxHnilWarns(cvode_mem, mxhnil) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_int), intent(in) :: mxhnil
      integer(c_int) :: flag
      flag = c_set_max_hnil_warns(cvode_mem, mxhnil)
   end function FCVodeSetMaxHnilWarns

   function FCVodeSetInitStep(cvode_mem, hin) result(flag)
      type(c_ptr) :: cvode_mem
      real(c_double), intent(in) :: hin
      integer(c_int) :: flag
      flag = c_set_init_step(cvode_mem, hin)
   end function FCVodeSetInitStep

   function FCVodeSetNoInactiveRootWarn(cvode_mem) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_int) :: flag
      flag = c_set_no_inactive_root_warn(cvode_mem)
   end function FCVodeSetNoInactiveRootWarn

   function FCVode(cvode_mem, tout, yout, tret, itask) result(flag)
      type(c_ptr) :: cvode_mem
      real(c_double), intent(in) :: tout
      type(N_Vector), target, intent(inout) :: yout
      real(c_double), dimension(*), target, intent(inout) :: tret
      integer(c_int), intent(in) :: itask
      integer(c_int) :: flag
      flag = c_cvode(cvode_mem, tout, c_loc(yout), c_loc(tret(1)), itask)
   end function FCVode

   function FCVodeGetRootInfo(cvode_mem, rootsfound) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_int), dimension(*), target, intent(inout) :: rootsfound
      integer(c_int) :: flag
      flag = c_get_root_info(cvode_mem, c_loc(rootsfound(1)))
   end function FCVodeGetRootInfo

   !> Frees the solver memory and sets cvode_mem to NULL (CVodeFree(&cvode_mem))
   subroutine FCVodeFree(cvode_mem)
      type(c_ptr), target, intent(inout) :: cvode_mem
      call c_free(c_loc(cvode_mem))
   end subroutine FCVodeFree

   function FCVodeGetNumSteps(cvode_mem, nsteps) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: nsteps
      integer(c_int) :: flag
      flag = c_get_num_steps(cvode_mem, c_loc(nsteps(1)))
   end function FCVodeGetNumSteps

   function FCVodeGetNumRhsEvals(cvode_mem, nfevals) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: nfevals
      integer(c_int) :: flag
      flag = c_get_num_rhs_evals(cvode_mem, c_loc(nfevals(1)))
   end function FCVodeGetNumRhsEvals

   function FCVodeGetNumJacEvals(cvode_mem, njevals) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: njevals
      integer(c_int) :: flag
      flag = c_get_num_jac_evals(cvode_mem, c_loc(njevals(1)))
   end function FCVodeGetNumJacEvals

   function FCVodeGetNumGEvals(cvode_mem, ngevals) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: ngevals
      integer(c_int) :: flag
      flag = c_get_num_g_evals(cvode_mem, c_loc(ngevals(1)))
   end function FCVodeGetNumGEvals

   function FCVodeGetNumErrTestFails(cvode_mem, netfails) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: netfails
      integer(c_int) :: flag
      flag = c_get_num_err_test_fails(cvode_mem, c_loc(netfails(1)))
   end function FCVodeGetNumErrTestFails

   function FCVodeGetNumNonlinSolvIters(cvode_mem, nniters) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: nniters
      integer(c_int) :: flag
      flag = c_get_num_nonlin_solv_iters(cvode_mem, c_loc(nniters(1)))
   end function FCVodeGetNumNonlinSolvIters

   function FCVodeGetNumNonlinSolvConvFails(cvode_mem, nnfails) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: nnfails
      integer(c_int) :: flag
      flag = c_get_num_nonlin_solv_conv_fails(cvode_mem, c_loc(nnfails(1)))
   end function FCVodeGetNumNonlinSolvConvFails

   function FCVodeGetNumLinSolvSetups(cvode_mem, nlinsetups) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: nlinsetups
      integer(c_int) :: flag
      flag = c_get_num_lin_solv_setups(cvode_mem, c_loc(nlinsetups(1)))
   end function FCVodeGetNumLinSolvSetups

   function FCVodeGetNumLinRhsEvals(cvode_mem, nfevalsls) result(flag)
      type(c_ptr) :: cvode_mem
      integer(c_long), dimension(*), target, intent(inout) :: nfevalsls
      integer(c_int) :: flag
      flag = c_get_num_lin_rhs_evals(cvode_mem, c_loc(nfevalsls(1)))
   end function FCVodeGetNumLinRhsEvals

end module fcvode_mod
