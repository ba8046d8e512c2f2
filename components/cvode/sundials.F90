! SPDX-License-Identifier: Apache-2.0
!> What differs between SUNDIALS 6 and 7 for our use of CVODE, in one place.
!>
!> - Modules: SUNDIALS 7 gathers the context, vectors, matrices and linear solvers in
!>   fsundials_core_mod; SUNDIALS 6 has fsundials_context_mod, fsundials_nvector_mod,
!>   fsundials_matrix_mod and fsundials_linearsolver_mod. This module re-exports the
!>   names the solver uses from whichever exists.
!> - Context: SUNContext_Create takes the communicator as a pointer in 6 (NULL for
!>   none) and as an MPI_Comm / integer in 7 (SUN_COMM_NULL).
!> - Errors: in 6, CVODE reports its errors and warnings to a handler set on the
!>   solver (CVodeSetErrHandlerFn); in 7, its errors to a stack of handlers on the
!>   context (SUNContext_PushErrHandler; CVodeSetErrHandlerFn is gone). Either way the
!>   handler here stores the message in the solver_report given as its user data
!>   and prints nothing: the library never writes to the terminal. SUNDIALS 7 sends
!>   CVODE's warnings (CV_WARNING) to its logger instead, which prints them on
!>   stdout by default; the solver turns off the only ones CVODE 7.1 has ("t + h = t",
!>   CVodeSetMaxHnilWarns; roots inactive at the start, CVodeSetNoInactiveRootWarn).
!>   Checked against a real SUNDIALS 7.1 C library by .ci/sundials7-check.
!>
!> HCIMPACT_SUNDIALS_MAJOR (6 or 7) comes from the build (CMake, from
!> sundials_config.h); a build that does not define it (fpm: components/cvode/fpm.toml)
!> takes SUNDIALS_VERSION_MAJOR from that header here.
#ifndef HCIMPACT_SUNDIALS_MAJOR
#include <sundials/sundials_config.h>
#define HCIMPACT_SUNDIALS_MAJOR SUNDIALS_VERSION_MAJOR
#endif
module hcimpact_cvode_sundials
   use, intrinsic :: iso_c_binding, only : c_int, c_ptr, c_char, c_size_t, c_null_ptr, &
      & c_funloc, c_associated, c_f_pointer
#if HCIMPACT_SUNDIALS_MAJOR >= 7
   use fsundials_core_mod, only : N_Vector, SUNMatrix, SUNLinearSolver, &
      & SUNLinearSolver_Ops, FSUNLinSolNewEmpty, FSUNLinSolFreeEmpty, &
      & SUNLINEARSOLVER_DIRECT, &
      & FN_VGetArrayPointer, FN_VDestroy, FSUNMatDestroy, FSUNLinSolFree, &
      & FSUNContext_Create, FSUNContext_Free, FSUNContext_ClearErrHandlers, &
      & FSUNContext_PushErrHandler, SUN_COMM_NULL
#else
   use fsundials_context_mod, only : FSUNContext_Create, FSUNContext_Free
   use fsundials_nvector_mod, only : N_Vector, FN_VGetArrayPointer, FN_VDestroy
   use fsundials_matrix_mod, only : SUNMatrix, FSUNMatDestroy
   use fsundials_linearsolver_mod, only : SUNLinearSolver, FSUNLinSolFree, &
      & SUNLinearSolver_Ops, FSUNLinSolNewEmpty, FSUNLinSolFreeEmpty, &
      & SUNLINEARSOLVER_DIRECT
   use fcvode_mod, only : FCVodeSetErrHandlerFn
#endif
   use hcimpact_cvode_report, only : solver_report
   implicit none
   private

   public :: N_Vector, SUNMatrix, SUNLinearSolver
   public :: FN_VGetArrayPointer, FN_VDestroy, FSUNMatDestroy, FSUNLinSolFree
   public :: SUNLinearSolver_Ops, FSUNLinSolNewEmpty, FSUNLinSolFreeEmpty, &
      & SUNLINEARSOLVER_DIRECT
   public :: context_create, context_free, capture_errors, sundials_major

   !> The SUNDIALS major version this component was built against
   integer, parameter :: sundials_major = HCIMPACT_SUNDIALS_MAJOR

   !> Longest message kept from the solver
   integer, parameter :: max_message = 400

   interface
      !> size_t strlen(const char *s) from the C library
      function c_strlen(s) result(n) bind(C, name="strlen")
         import :: c_ptr, c_size_t
         type(c_ptr), value :: s
         integer(c_size_t) :: n
      end function c_strlen
   end interface

contains

   !> Create a SUNDIALS context without a communicator; 0 on success.
   function context_create(ctx) result(ierr)
      !> The new context (c_null_ptr on failure)
      type(c_ptr), intent(out) :: ctx
      !> 0 or the SUNDIALS error code
      integer(c_int) :: ierr
      ctx = c_null_ptr
#if HCIMPACT_SUNDIALS_MAJOR >= 7
      ierr = FSUNContext_Create(SUN_COMM_NULL, ctx)
#else
      ierr = FSUNContext_Create(c_null_ptr, ctx)
#endif
      if (ierr /= 0) ctx = c_null_ptr
   end function context_create

   !> Free a context created by context_create (nothing for c_null_ptr).
   subroutine context_free(ctx)
      !> The context; c_null_ptr on return
      type(c_ptr), intent(inout) :: ctx
      integer(c_int) :: ierr
      if (c_associated(ctx)) then
         ierr = FSUNContext_Free(ctx)
      end if
      ctx = c_null_ptr
   end subroutine context_free

   !> Route the solver's error and warning messages to the system `data` points to,
   !> instead of the terminal. Call right after creating the solver memory.
   function capture_errors(ctx, cvode_mem, data) result(ierr)
      !> The context
      type(c_ptr), intent(in) :: ctx
      !> The CVODE memory
      type(c_ptr), intent(in) :: cvode_mem
      !> c_loc of the solver_report (hcimpact_cvode_report) of this integration
      type(c_ptr), intent(in) :: data
      !> 0 or the SUNDIALS error code
      integer(c_int) :: ierr
#if HCIMPACT_SUNDIALS_MAJOR >= 7
      ierr = FSUNContext_ClearErrHandlers(ctx)
      if (ierr == 0) ierr = FSUNContext_PushErrHandler(ctx, c_funloc(error_handler), data)
#else
      ierr = FCVodeSetErrHandlerFn(cvode_mem, c_funloc(error_handler), data)
#endif
   end function capture_errors

#if HCIMPACT_SUNDIALS_MAJOR >= 7
   !> SUNErrHandlerFn of SUNDIALS 7: (line, func, file, msg, err_code, err_user_data,
   !> sunctx).
   subroutine error_handler(line, func, file, msg, err_code, user_data, sunctx) bind(C)
      integer(c_int), value :: line
      type(c_ptr), value :: func, file, msg
      integer(c_int), value :: err_code
      type(c_ptr), value :: user_data, sunctx
      call record_message(user_data, err_code, func, msg)
   end subroutine error_handler
#else
   !> CVErrHandlerFn of SUNDIALS 6: (error_code, module, function, msg, eh_data).
   subroutine error_handler(error_code, module_name, func, msg, user_data) bind(C)
      integer(c_int), value :: error_code
      type(c_ptr), value :: module_name, func, msg
      type(c_ptr), value :: user_data
      call record_message(user_data, error_code, func, msg)
   end subroutine error_handler
#endif

   !> Store "function: message" and the code in the solver_report at `user_data`.
   subroutine record_message(user_data, code, func, msg)
      type(c_ptr), intent(in) :: user_data, func, msg
      integer(c_int), intent(in) :: code
      type(solver_report), pointer :: report
      character(len=:), allocatable :: func_text, msg_text
      if (.not. c_associated(user_data)) return
      call c_f_pointer(user_data, report)
      report%code = int(code)
      call copy_c_string(func, func_text)
      call copy_c_string(msg, msg_text)
      report%message = func_text // ": " // msg_text
   end subroutine record_message

   !> Copy of a NUL-terminated C string (at most max_message characters). A
   !> subroutine: a function with a deferred-length result would keep its length in
   !> a hidden static variable of the caller (gfortran), shared by threads.
   subroutine copy_c_string(ptr, text)
      type(c_ptr), intent(in) :: ptr
      character(len=:), allocatable, intent(out) :: text
      character(kind=c_char), pointer :: chars(:)
      integer :: n, i
      if (.not. c_associated(ptr)) then
         text = "?"
         return
      end if
      n = int(min(c_strlen(ptr), int(max_message, c_size_t)))
      call c_f_pointer(ptr, chars, [max(n, 1)])
      allocate(character(len=n) :: text)
      do i = 1, n
         text(i:i) = chars(i)
      end do
   end subroutine copy_c_string

end module hcimpact_cvode_sundials
