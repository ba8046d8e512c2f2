! SPDX-License-Identifier: Apache-2.0
!> Explicit interfaces of the LAPACK drivers the calibration component calls.
!>
!> LAPACK is an external library with implicit Fortran 77 interfaces; declaring them
!> here lets the compiler check every call (argument count, kinds, ranks). Only the
!> double-precision drivers used by hcimpact_least_squares are listed. Integers are
!> default integers, the LP64 convention of reference LAPACK, OpenBLAS and MKL's LP64
!> layer.
module hcimpact_lapack_interfaces
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: dgels, dgelsy, dgesvd

   interface
      !> Least squares of a full-rank matrix by QR (or LQ): minimise ||A x - b||.
      !> On exit the first n rows of b hold the solution.
      subroutine dgels(trans, m, n, nrhs, a, lda, b, ldb, work, lwork, info)
         import :: wp
         !> 'N': solve with A; 'T': with its transpose
         character(len=1), intent(in) :: trans
         !> Rows and columns of A, right-hand sides
         integer, intent(in) :: m, n, nrhs
         !> Leading dimension of a
         integer, intent(in) :: lda
         !> The matrix; overwritten by its factorisation
         real(wp), intent(inout) :: a(lda, *)
         !> Leading dimension of b
         integer, intent(in) :: ldb
         !> Right-hand sides on entry, solutions on exit
         real(wp), intent(inout) :: b(ldb, *)
         !> Size of work; -1 asks for the optimal size in work(1)
         integer, intent(in) :: lwork
         !> Workspace
         real(wp), intent(inout) :: work(*)
         !> 0: success; < 0: bad argument; > 0: A is exactly rank deficient
         integer, intent(out) :: info
      end subroutine dgels

      !> Minimum-norm least squares by a complete orthogonal factorisation (QR with
      !> column pivoting); the effective rank is decided by rcond.
      subroutine dgelsy(m, n, nrhs, a, lda, b, ldb, jpvt, rcond, rank, work, lwork, info)
         import :: wp
         !> Rows and columns of A, right-hand sides
         integer, intent(in) :: m, n, nrhs
         !> Leading dimension of a
         integer, intent(in) :: lda
         !> The matrix; overwritten by its factorisation
         real(wp), intent(inout) :: a(lda, *)
         !> Leading dimension of b
         integer, intent(in) :: ldb
         !> Right-hand sides on entry, solutions on exit
         real(wp), intent(inout) :: b(ldb, *)
         !> Column pivots: 0 on entry lets every column move
         integer, intent(inout) :: jpvt(*)
         !> Columns whose estimated condition would exceed 1/rcond are dropped
         real(wp), intent(in) :: rcond
         !> Effective rank found
         integer, intent(out) :: rank
         !> Size of work; -1 asks for the optimal size in work(1)
         integer, intent(in) :: lwork
         !> Workspace
         real(wp), intent(inout) :: work(*)
         !> 0: success; < 0: bad argument
         integer, intent(out) :: info
      end subroutine dgelsy

      !> Singular value decomposition A = U diag(s) V^T.
      subroutine dgesvd(jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, work, lwork, info)
         import :: wp
         !> Which columns of U to compute ('A', 'S', 'O' or 'N')
         character(len=1), intent(in) :: jobu
         !> Which rows of V^T to compute ('A', 'S', 'O' or 'N')
         character(len=1), intent(in) :: jobvt
         !> Rows and columns of A
         integer, intent(in) :: m, n
         !> Leading dimension of a
         integer, intent(in) :: lda
         !> The matrix; destroyed
         real(wp), intent(inout) :: a(lda, *)
         !> Singular values, in decreasing order
         real(wp), intent(out) :: s(*)
         !> Leading dimension of u
         integer, intent(in) :: ldu
         !> Left singular vectors
         real(wp), intent(inout) :: u(ldu, *)
         !> Leading dimension of vt
         integer, intent(in) :: ldvt
         !> Right singular vectors, as rows
         real(wp), intent(inout) :: vt(ldvt, *)
         !> Size of work; -1 asks for the optimal size in work(1)
         integer, intent(in) :: lwork
         !> Workspace
         real(wp), intent(inout) :: work(*)
         !> 0: success; < 0: bad argument; > 0: the QR iteration did not converge
         integer, intent(out) :: info
      end subroutine dgesvd
   end interface

end module hcimpact_lapack_interfaces
