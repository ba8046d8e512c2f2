! SPDX-License-Identifier: Apache-2.0
!> Tests of hcimpact_least_squares: the linear solver, the Jacobian analysis
!> (covariance, leverages, rank) and Levenberg-Marquardt on a model with a known
!> answer, with and without a bound.
module test_least_squares
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_underdetermined, hcimpact_err_size
   use hcimpact_least_squares, only : least_squares_model, levenberg_marquardt, &
      & linear_least_squares, jacobian_analysis
   use hcimpact_check, only : check_close
   implicit none
   private

   public :: collect_least_squares

   !> y = a exp(k t): residuals y_i - a exp(k t_i), theta = (a, k)
   type, extends(least_squares_model) :: exponential_model
      real(wp), allocatable :: t(:), y(:)
   contains
      procedure :: evaluate => exponential_evaluate
   end type exponential_model

   !> y = (a + b) t: a and b cannot be told apart
   type, extends(least_squares_model) :: sum_model
      real(wp), allocatable :: t(:), y(:)
   contains
      procedure :: evaluate => sum_evaluate
   end type sum_model

contains

   !> Collect all exported unit tests
   subroutine collect_least_squares(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         new_unittest("linear-exact", test_linear_exact), &
         new_unittest("linear-rank-deficient", test_linear_rank), &
         new_unittest("covariance-and-leverage", test_covariance), &
         new_unittest("lm-exponential", test_lm_exponential), &
         new_unittest("lm-lower-bound", test_lm_bound), &
         new_unittest("lm-rank-deficient", test_lm_rank), &
         new_unittest("lm-bad-sizes", test_lm_sizes) &
         ]
   end subroutine collect_least_squares

   !> A straight line through exact points is found to rounding.
   subroutine test_linear_exact(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: a(4, 2), x(2)
      integer :: rank, stat
      a(:, 1) = 1.0_wp
      a(:, 2) = [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp]
      call linear_least_squares(a, 2.0_wp + 3.0_wp * a(:, 2), x, rank, stat)
      call check(error, stat, hcimpact_ok, "linear_least_squares status")
      if (allocated(error)) return
      call check(error, rank, 2, "rank")
      if (allocated(error)) return
      call check_close(error, x(1), 2.0_wp, rel=1.0e-14_wp, message="intercept")
      if (allocated(error)) return
      call check_close(error, x(2), 3.0_wp, rel=1.0e-14_wp, message="slope")
   end subroutine test_linear_exact

   !> Two equal columns: rank 1 and the status says so.
   subroutine test_linear_rank(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: a(3, 2), x(2)
      integer :: rank, stat
      a(:, 1) = [1.0_wp, 2.0_wp, 3.0_wp]
      a(:, 2) = a(:, 1)
      call linear_least_squares(a, [1.0_wp, 2.0_wp, 3.0_wp], x, rank, stat)
      call check(error, stat, hcimpact_err_underdetermined, "status")
      if (allocated(error)) return
      call check(error, rank, 1, "rank")
   end subroutine test_linear_rank

   !> (J^T J)^-1 and the leverages of a matrix where they are known exactly.
   subroutine test_covariance(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: j(3, 2), cov(2, 2), leverage(3), condition
      integer :: stat
      ! J^T J = [[2, 1], [1, 2]] / with rows (1, 0), (1, 1), (0, 1)
      j(1, :) = [1.0_wp, 0.0_wp]
      j(2, :) = [1.0_wp, 1.0_wp]
      j(3, :) = [0.0_wp, 1.0_wp]
      call jacobian_analysis(j, cov, stat, condition, leverage)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      ! inverse of [[2, 1], [1, 2]] is [[2, -1], [-1, 2]]/3
      call check_close(error, cov(1, 1), 2.0_wp / 3.0_wp, rel=1.0e-14_wp, message="cov 11")
      if (allocated(error)) return
      call check_close(error, cov(1, 2), -1.0_wp / 3.0_wp, rel=1.0e-14_wp, message="cov 12")
      if (allocated(error)) return
      call check_close(error, cov(2, 2), 2.0_wp / 3.0_wp, rel=1.0e-14_wp, message="cov 22")
      if (allocated(error)) return
      ! hat matrix diagonal: J (J^T J)^-1 J^T = (2/3, 2/3, 2/3)
      call check_close(error, leverage(1), 2.0_wp / 3.0_wp, rel=1.0e-14_wp, message="h 1")
      if (allocated(error)) return
      call check_close(error, sum(leverage), 2.0_wp, rel=1.0e-14_wp, message="sum h")
      if (allocated(error)) return
      ! singular values of the column-scaled matrix: sqrt(3/2), sqrt(1/2)
      call check_close(error, condition, sqrt(3.0_wp), rel=1.0e-14_wp, message="condition")
      if (allocated(error)) return
      ! a zero column, and two proportional columns, are rank deficient
      j(:, 2) = 0.0_wp
      call jacobian_analysis(j, cov, stat)
      call check(error, stat, hcimpact_err_underdetermined, "zero column")
      if (allocated(error)) return
      j(:, 2) = -3.0_wp * j(:, 1)
      call jacobian_analysis(j, cov, stat)
      call check(error, stat, hcimpact_err_underdetermined, "proportional columns")
   end subroutine test_covariance

   !> Levenberg-Marquardt from a poor start recovers a exp(k t) from exact data.
   subroutine test_lm_exponential(error)
      type(error_type), allocatable, intent(out) :: error
      type(exponential_model) :: model
      real(wp) :: theta(2)
      integer :: stat, i, iterations
      allocate(model%t(13), model%y(13))
      model%t = [(0.25_wp * i, i = 0, 12)]
      model%y = 2.5_wp * exp(-1.3_wp * model%t)
      theta = [1.0_wp, 0.5_wp]
      call levenberg_marquardt(model, theta, [(1.0_wp, i = 0, 12)], [-huge(1.0_wp), &
         & -huge(1.0_wp)], stat, iterations)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call check_close(error, theta(1), 2.5_wp, rel=1.0e-13_wp, message="a")
      if (allocated(error)) return
      call check_close(error, theta(2), -1.3_wp, rel=1.0e-13_wp, message="k")
      if (allocated(error)) return
      if (iterations < 1 .or. iterations > 50) &
         & call test_failed(error, "iterations out of range", "")
   end subroutine test_lm_exponential

   !> With the bound k >= 0 the best fit sits on the bound: k = 0 and a = mean(y).
   subroutine test_lm_bound(error)
      type(error_type), allocatable, intent(out) :: error
      type(exponential_model) :: model
      real(wp) :: theta(2)
      integer :: stat, i
      allocate(model%t(13), model%y(13))
      model%t = [(0.25_wp * i, i = 0, 12)]
      model%y = 2.5_wp * exp(-1.3_wp * model%t)
      theta = [1.0_wp, 0.5_wp]
      call levenberg_marquardt(model, theta, [(1.0_wp, i = 0, 12)], [-huge(1.0_wp), &
         & 0.0_wp], stat)
      call check(error, stat, hcimpact_ok, "status")
      if (allocated(error)) return
      call check_close(error, theta(2), 0.0_wp, abs=0.0_wp, message="k on its bound")
      if (allocated(error)) return
      ! converged to ~1e-10 of a's standard error (the gradient test), which here,
      ! with residuals of order 1, is about 1e-11 relative
      call check_close(error, theta(1), sum(model%y) / size(model%y), rel=1.0e-9_wp, &
         & message="a = mean(y)")
   end subroutine test_lm_bound

   !> Parameters that only enter as a sum: the status says the data cannot tell them.
   subroutine test_lm_rank(error)
      type(error_type), allocatable, intent(out) :: error
      type(sum_model) :: model
      real(wp) :: theta(2)
      integer :: stat, i
      allocate(model%t(5), model%y(5))
      model%t = [(1.0_wp * i, i = 1, 5)]
      model%y = 3.0_wp * model%t
      theta = [1.0_wp, 1.0_wp]
      call levenberg_marquardt(model, theta, [(1.0_wp, i = 1, 5)], [-huge(1.0_wp), &
         & -huge(1.0_wp)], stat)
      call check(error, stat, hcimpact_err_underdetermined, "status")
   end subroutine test_lm_rank

   !> Fewer residuals than parameters, or bounds of the wrong size.
   subroutine test_lm_sizes(error)
      type(error_type), allocatable, intent(out) :: error
      type(exponential_model) :: model
      real(wp) :: theta(2)
      integer :: stat
      allocate(model%t(1), model%y(1))
      model%t = 0.0_wp
      model%y = 1.0_wp
      theta = [1.0_wp, 0.0_wp]
      call levenberg_marquardt(model, theta, [1.0_wp], [0.0_wp, 0.0_wp], stat)
      call check(error, stat, hcimpact_err_size, "one residual, two parameters")
      if (allocated(error)) return
      call levenberg_marquardt(model, theta, [1.0_wp, 1.0_wp, 1.0_wp], [0.0_wp], stat)
      call check(error, stat, hcimpact_err_size, "bounds of the wrong size")
   end subroutine test_lm_sizes

   subroutine exponential_evaluate(self, theta, residual, stat, jacobian)
      class(exponential_model), intent(inout) :: self
      real(wp), intent(in) :: theta(:)
      real(wp), intent(out) :: residual(:)
      integer, intent(out) :: stat
      real(wp), intent(out), optional :: jacobian(:, :)
      residual = self%y - theta(1) * exp(theta(2) * self%t)
      if (present(jacobian)) then
         jacobian(:, 1) = -exp(theta(2) * self%t)
         jacobian(:, 2) = -theta(1) * self%t * exp(theta(2) * self%t)
      end if
      stat = hcimpact_ok
   end subroutine exponential_evaluate

   subroutine sum_evaluate(self, theta, residual, stat, jacobian)
      class(sum_model), intent(inout) :: self
      real(wp), intent(in) :: theta(:)
      real(wp), intent(out) :: residual(:)
      integer, intent(out) :: stat
      real(wp), intent(out), optional :: jacobian(:, :)
      residual = self%y - (theta(1) + theta(2)) * self%t
      if (present(jacobian)) then
         jacobian(:, 1) = -self%t
         jacobian(:, 2) = -self%t
      end if
      stat = hcimpact_ok
   end subroutine sum_evaluate

end module test_least_squares
