! SPDX-License-Identifier: Apache-2.0
!> Least squares with LAPACK: linear fits, Levenberg-Marquardt, and the covariance of
!> the parameters from the Jacobian.
!>
!> - `linear_least_squares`: min ||A x - y|| by a complete orthogonal factorisation
!>   (LAPACK dgelsy, QR with column pivoting), which also reports the numerical rank.
!> - `levenberg_marquardt`: min sum (w_i r_i(theta))^2 for a `least_squares_model`.
!>   Each step solves the damped linear problem
!>       [ J           ]         [ -r ]
!>       [ sqrt(mu) D  ] delta = [  0 ]
!>   by QR (LAPACK dgels) rather than through the normal equations (whose condition
!>   number is the square of J's); D holds the largest column norms of J seen so far
!>   (Marquardt's scaling, as in MINPACK's lmder: Moré, "The Levenberg-Marquardt
!>   algorithm: implementation and theory", Lecture Notes in Mathematics 630, 1978).
!>   mu = 0 is the Gauss-Newton step, tried first; a step that does not lower the sum
!>   of squares is retried with mu raised tenfold. Lower bounds are kept by freezing a
!>   parameter that sits on its bound and is pushed outwards, and by clipping the
!>   others at theirs.
!> - `jacobian_analysis`: the singular value decomposition (LAPACK dgesvd) of the
!>   column-scaled weighted Jacobian gives the rank (hence whether the data determine
!>   the parameters), the unscaled covariance (J^T W J)^-1 = V S^-2 V^T, and the
!>   leverages (diagonal of the hat matrix) of the observations.
!>
!> Nothing here prints or stops; errors are status codes of hcimpact_status. Arrays
!> that grow with the observations are allocated with stat= (hcimpact_work_arrays:
!> out_of_memory when that fails).
module hcimpact_least_squares
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_no_convergence, &
      & hcimpact_err_underdetermined, hcimpact_err_size, hcimpact_err_domain
   use hcimpact_lapack_interfaces, only : dgels, dgelsy, dgesvd
   use hcimpact_work_arrays, only : out_of_memory
   implicit none
   private

   public :: least_squares_model, levenberg_marquardt, linear_least_squares, &
      & jacobian_analysis
   public :: rank_tolerance, default_max_iterations

   !> Singular values below rank_tolerance times the largest (of the column-scaled
   !> Jacobian) count as zero: the data then cannot determine the parameters
   real(wp), parameter :: rank_tolerance = 1.0e-10_wp

   !> Default bound on the Levenberg-Marquardt iterations (accepted steps)
   integer, parameter :: default_max_iterations = 200

   !> Relative size of a step (in the scaled norm ||D delta|| / ||D theta||) below
   !> which the iteration has converged; with the Gauss-Newton step's fast convergence
   !> the remaining error is far smaller still
   real(wp), parameter :: step_tolerance = 1.0e-11_wp
   !> Largest cosine between the residual vector and a column of the Jacobian at a
   !> minimum (the scaled gradient, MINPACK's gtol): immune to the rounding of the
   !> sum of squares, it holds noisy fits to about 1e-10 of their standard errors
   real(wp), parameter :: gradient_tolerance = 1.0e-10_wp
   !> Relative decrease of the sum of squares, on a Gauss-Newton step, that counts as
   !> stagnation at the level of rounding
   real(wp), parameter :: cost_tolerance = 1.0e-15_wp
   !> Damping used after the first rejected Gauss-Newton step, and the largest tried
   real(wp), parameter :: mu_first = 1.0e-3_wp, mu_max = 1.0e20_wp
   !> Below this the damping is dropped (back to Gauss-Newton steps)
   real(wp), parameter :: mu_min = 1.0e-7_wp

   !> A model for nonlinear least squares: residuals r(theta) and their Jacobian.
   type, abstract :: least_squares_model
   contains
      !> Residuals (observed - model) and, on request, the Jacobian dr/dtheta
      procedure(evaluate_interface), deferred :: evaluate
   end type least_squares_model

   abstract interface
      !> Residuals of the model at theta and, when `jacobian` is present, their
      !> derivatives. A status other than hcimpact_ok marks theta as unusable (the
      !> iteration then takes a shorter step).
      subroutine evaluate_interface(self, theta, residual, stat, jacobian)
         import :: least_squares_model, wp
         !> The model (may cache what the Jacobian reuses)
         class(least_squares_model), intent(inout) :: self
         !> Parameters
         real(wp), intent(in) :: theta(:)
         !> Residuals, one per observation
         real(wp), intent(out) :: residual(:)
         !> Status: hcimpact_ok or an error code
         integer, intent(out) :: stat
         !> Jacobian d residual(i) / d theta(j)
         real(wp), intent(out), optional :: jacobian(:, :)
      end subroutine evaluate_interface
   end interface

contains

   !> Linear least squares: x minimising ||a x - y||_2, with the numerical rank of a
   !> (LAPACK dgelsy; columns with an estimated condition beyond 1/rank_tolerance are
   !> dropped). The caller scales the columns of a to comparable norms.
   !>
   !> Errors: hcimpact_err_size (shapes disagree or fewer rows than columns),
   !> hcimpact_err_underdetermined (rank below the number of columns; x is then the
   !> minimum-norm solution), hcimpact_err_domain (LAPACK rejected an argument),
   !> out_of_memory.
   subroutine linear_least_squares(a, y, x, rank, stat)
      !> Matrix, m x p with m >= p
      real(wp), intent(in) :: a(:, :)
      !> Right-hand side, m
      real(wp), intent(in) :: y(:)
      !> Solution, p
      real(wp), intent(out) :: x(:)
      !> Numerical rank of a
      integer, intent(out) :: rank
      !> Status
      integer, intent(out) :: stat
      real(wp), allocatable :: af(:, :), b(:, :), work(:)
      integer, allocatable :: jpvt(:)
      real(wp) :: query(1)
      integer :: m, p, info, alloc_stat

      m = size(a, 1)
      p = size(a, 2)
      x = 0.0_wp
      rank = 0
      if (size(y) /= m .or. size(x) /= p .or. m < p .or. p < 1) then
         stat = hcimpact_err_size
         return
      end if
      allocate(af(m, p), b(m, 1), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      af(:, :) = a
      b(:, 1) = y
      allocate(jpvt(p), source=0)
      call dgelsy(m, p, 1, af, m, b, m, jpvt, rank_tolerance, rank, query, -1, info)
      allocate(work(max(1, nint(query(1)))), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      call dgelsy(m, p, 1, af, m, b, m, jpvt, rank_tolerance, rank, work, size(work), info)
      if (info /= 0) then
         stat = hcimpact_err_domain
         return
      end if
      x = b(1:p, 1)
      if (rank < p) then
         stat = hcimpact_err_underdetermined
      else
         stat = hcimpact_ok
      end if
   end subroutine linear_least_squares

   !> Rank, covariance and leverages from a weighted Jacobian J (rows already
   !> multiplied by the weights 1/sigma_i).
   !>
   !> The columns are scaled to unit norm (the rank then does not depend on the units
   !> of the parameters), the scaled matrix is decomposed by LAPACK dgesvd, and
   !>     covariance = (J^T J)^-1 = D^-1 V S^-2 V^T D^-1,  leverage_i = sum_k U_ik^2.
   !> The covariance of a fit is this times the variance of unit weight.
   !>
   !> Errors: hcimpact_err_underdetermined (a zero column, or a singular value below
   !> rank_tolerance times the largest: outputs NaN-free but meaningless),
   !> hcimpact_err_size, hcimpact_err_no_convergence (the SVD did not converge),
   !> out_of_memory.
   subroutine jacobian_analysis(jacobian, covariance, stat, condition, leverage)
      !> Weighted Jacobian, m x p with m >= p
      real(wp), intent(in) :: jacobian(:, :)
      !> (J^T J)^-1, p x p
      real(wp), intent(out) :: covariance(:, :)
      !> Status
      integer, intent(out) :: stat
      !> Condition number of the column-scaled Jacobian (largest over smallest
      !> singular value); huge() when singular
      real(wp), intent(out), optional :: condition
      !> Leverage of each observation, m (they sum to p)
      real(wp), intent(out), optional :: leverage(:)
      real(wp), allocatable :: a(:, :), s(:), u(:, :), vt(:, :), work(:), scale(:)
      real(wp) :: query(1)
      integer :: m, p, info, j, k, alloc_stat

      m = size(jacobian, 1)
      p = size(jacobian, 2)
      covariance = 0.0_wp
      if (present(condition)) condition = huge(1.0_wp)
      if (present(leverage)) leverage = 0.0_wp
      if (m < p .or. p < 1 .or. size(covariance, 1) /= p .or. size(covariance, 2) /= p) then
         stat = hcimpact_err_size
         return
      end if
      allocate(scale(p))
      do j = 1, p
         scale(j) = norm2(jacobian(:, j))
      end do
      if (.not. all(scale > 0.0_wp)) then
         stat = hcimpact_err_underdetermined
         return
      end if
      allocate(a(m, p), s(p), u(m, p), vt(p, p), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      do j = 1, p
         a(:, j) = jacobian(:, j) / scale(j)
      end do
      call dgesvd('S', 'A', m, p, a, m, s, u, m, vt, p, query, -1, info)
      allocate(work(max(1, nint(query(1)))), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      call dgesvd('S', 'A', m, p, a, m, s, u, m, vt, p, work, size(work), info)
      if (info /= 0) then
         stat = hcimpact_err_no_convergence
         return
      end if
      if (.not. s(p) > rank_tolerance * s(1)) then
         stat = hcimpact_err_underdetermined
         return
      end if
      if (present(condition)) condition = s(1) / s(p)
      ! (J^T J)^-1 with J = A D: D^-1 (A^T A)^-1 D^-1, and (A^T A)^-1 = V S^-2 V^T
      do k = 1, p
         vt(k, :) = vt(k, :) / s(k)
      end do
      covariance = matmul(transpose(vt), vt)
      do j = 1, p
         covariance(:, j) = covariance(:, j) / scale(j)
         covariance(j, :) = covariance(j, :) / scale(j)
      end do
      if (present(leverage)) then
         if (size(leverage) == m) then
            ! (a loop: sum(u**2, dim=2) may build u**2 as an unchecked temporary)
            leverage = 0.0_wp
            do k = 1, p
               leverage = leverage + u(:, k)**2
            end do
         end if
      end if
      stat = hcimpact_ok
   end subroutine jacobian_analysis

   !> Minimise sum_i (weight_i r_i(theta))^2 by Levenberg-Marquardt, from the theta
   !> given, keeping theta >= lower.
   !>
   !> Stops when a step changes theta by at most step_tolerance relative (in the scaled
   !> norm), when the residuals are orthogonal to the Jacobian's columns within
   !> gradient_tolerance, when the sum of squares falls by at most cost_tolerance
   !> relative on a Gauss-Newton step, when no step can lower it any more (a minimum to
   !> working precision), or when it is zero.
   !>
   !> Errors: the model's status at the starting point; hcimpact_err_underdetermined
   !> (the starting Jacobian is rank deficient: the data cannot determine theta);
   !> hcimpact_err_no_convergence (max_iterations reached); hcimpact_err_size;
   !> out_of_memory (also from the model at a trial point: any other status there
   !> only rejects the step).
   subroutine levenberg_marquardt(model, theta, weight, lower, stat, iterations, &
         & max_iterations)
      !> The model
      class(least_squares_model), intent(inout) :: model
      !> Parameters: the start on entry, the minimum on exit
      real(wp), intent(inout) :: theta(:)
      !> Weight of each residual (1/sigma_i), > 0
      real(wp), intent(in) :: weight(:)
      !> Lower bound of each parameter (-huge() for none)
      real(wp), intent(in) :: lower(:)
      !> Status
      integer, intent(out) :: stat
      !> Accepted steps taken
      integer, intent(out), optional :: iterations
      !> Bound on the accepted steps (default default_max_iterations)
      integer, intent(in), optional :: max_iterations
      real(wp), allocatable :: r(:), rt(:), jac(:, :), jac_trial(:, :), d(:), step(:), &
         & trial(:), dx(:)
      logical, allocatable :: frozen(:)
      real(wp) :: cost, cost_trial, mu, reduction
      integer :: m, p, iter, max_iter, j, alloc_stat
      logical :: accepted, converged, moved, solved

      m = size(weight)
      p = size(theta)
      if (present(iterations)) iterations = 0
      max_iter = default_max_iterations
      if (present(max_iterations)) max_iter = max_iterations
      if (size(lower) /= p .or. m < p .or. p < 1) then
         stat = hcimpact_err_size
         return
      end if
      allocate(r(m), rt(m), jac(m, p), jac_trial(m, p), d(p), step(p), trial(p), dx(p), &
         & frozen(p), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if

      call weighted_evaluation(model, theta, weight, r, stat, jac)
      if (stat /= hcimpact_ok) return
      call check_rank(jac, stat)
      if (stat /= hcimpact_ok) return
      cost = dot_product(r, r)
      do j = 1, p
         d(j) = norm2(jac(:, j))
      end do

      mu = 0.0_wp
      converged = cost == 0.0_wp
      iter = 0
      do while (.not. converged .and. iter < max_iter)
         accepted = .false.
         moved = .false.
         do
            call damped_step(jac, r, d, mu, theta, lower, step, frozen, solved, stat)
            if (stat /= hcimpact_ok) return
            if (solved) then
               trial = max(theta + step, lower)
               dx = trial - theta
               moved = any(dx /= 0.0_wp)
               if (.not. moved) exit
               call weighted_evaluation(model, trial, weight, rt, stat)
               if (stat == out_of_memory) return
               if (stat == hcimpact_ok) then
                  cost_trial = dot_product(rt, rt)
                  accepted = cost_trial < cost
               end if
               if (accepted) then
                  ! the Jacobian there too; a point where it fails is not taken
                  call weighted_evaluation(model, trial, weight, rt, stat, jac_trial)
                  if (stat == out_of_memory) return
                  if (stat == hcimpact_ok) exit
                  accepted = .false.
               end if
            end if
            mu = max(10.0_wp * mu, mu_first)
            if (mu > mu_max) exit
         end do
         if (.not. accepted) then
            ! no step lowers the sum of squares: a minimum to working precision
            converged = .true.
            exit
         end if
         iter = iter + 1
         if (present(iterations)) iterations = iter
         reduction = cost - cost_trial
         theta = trial
         r = rt
         cost = cost_trial
         jac = jac_trial
         do j = 1, p
            d(j) = max(d(j), norm2(jac(:, j)))
         end do
         converged = cost == 0.0_wp &
            & .or. norm2(d * dx) <= step_tolerance * norm2(d * theta) &
            & .or. (mu == 0.0_wp .and. reduction <= cost_tolerance * cost) &
            & .or. small_gradient(jac, r, theta, lower)
         mu = 0.1_wp * mu
         if (mu < mu_min) mu = 0.0_wp
      end do
      if (converged) then
         stat = hcimpact_ok
      else
         stat = hcimpact_err_no_convergence
      end if
   end subroutine levenberg_marquardt

   !> Residuals (and Jacobian) of the model times the weights.
   subroutine weighted_evaluation(model, theta, weight, r, stat, jac)
      class(least_squares_model), intent(inout) :: model
      real(wp), intent(in) :: theta(:), weight(:)
      real(wp), intent(out) :: r(:)
      integer, intent(out) :: stat
      real(wp), intent(out), optional :: jac(:, :)
      integer :: j

      if (present(jac)) then
         call model%evaluate(theta, r, stat, jac)
      else
         call model%evaluate(theta, r, stat)
      end if
      if (stat /= hcimpact_ok) return
      if (.not. all(ieee_is_finite(r))) then
         stat = hcimpact_err_domain
         return
      end if
      r = weight * r
      if (present(jac)) then
         if (.not. all(ieee_is_finite(jac))) then
            stat = hcimpact_err_domain
            return
         end if
         do j = 1, size(jac, 2)
            jac(:, j) = weight * jac(:, j)
         end do
      end if
   end subroutine weighted_evaluation

   !> Whether every free column of the Jacobian is nearly orthogonal to the residuals:
   !> |J_j^T r| <= gradient_tolerance ||J_j|| ||r|| (a parameter on its lower bound
   !> pushed outwards counts as converged).
   pure function small_gradient(jac, r, theta, lower) result(small)
      real(wp), intent(in) :: jac(:, :), r(:), theta(:), lower(:)
      logical :: small
      real(wp) :: g, rnorm
      integer :: j
      rnorm = norm2(r)
      small = .true.
      do j = 1, size(jac, 2)
         ! the gradient of the sum of squares is 2 J^T r; outwards at a bound is g > 0
         g = dot_product(jac(:, j), r)
         if (theta(j) <= lower(j) .and. g >= 0.0_wp) cycle
         if (.not. abs(g) <= gradient_tolerance * norm2(jac(:, j)) * rnorm) then
            small = .false.
            return
         end if
      end do
   end function small_gradient

   !> hcimpact_ok when the column-scaled matrix has full column rank (singular values),
   !> hcimpact_err_underdetermined when not, out_of_memory.
   subroutine check_rank(jac, stat)
      real(wp), intent(in) :: jac(:, :)
      integer, intent(out) :: stat
      real(wp), allocatable :: cov(:, :)
      allocate(cov(size(jac, 2), size(jac, 2)))
      call jacobian_analysis(jac, cov, stat)
      if (stat /= hcimpact_ok .and. stat /= out_of_memory) stat = hcimpact_err_underdetermined
   end subroutine check_rank

   !> The Levenberg-Marquardt step: min ||J delta + r||^2 + mu ||D delta||^2 over the
   !> parameters that are free (a parameter on its lower bound whose unconstrained step
   !> points outwards is frozen at zero step), by QR of the stacked matrix (dgels).
   subroutine damped_step(jac, r, d, mu, theta, lower, step, frozen, solved, stat)
      real(wp), intent(in) :: jac(:, :), r(:), d(:), mu, theta(:), lower(:)
      real(wp), intent(out) :: step(:)
      logical, intent(out) :: frozen(:)
      !> False when the linear problem could not be solved (singular without damping)
      logical, intent(out) :: solved
      !> hcimpact_ok or out_of_memory
      integer, intent(out) :: stat
      integer :: pass

      frozen = .false.
      do pass = 1, size(theta)
         call solve_free(jac, r, d, mu, frozen, step, solved, stat)
         if (stat /= hcimpact_ok .or. .not. solved) return
         ! freeze the parameters on their bounds that the step pushes outwards
         if (.not. any(.not. frozen .and. theta <= lower .and. step < 0.0_wp)) exit
         where (theta <= lower .and. step < 0.0_wp) frozen = .true.
         if (all(frozen)) then
            step = 0.0_wp
            exit
         end if
      end do
   end subroutine damped_step

   !> The damped least-squares step over the columns not frozen.
   subroutine solve_free(jac, r, d, mu, frozen, step, solved, stat)
      real(wp), intent(in) :: jac(:, :), r(:), d(:), mu
      logical, intent(in) :: frozen(:)
      real(wp), intent(out) :: step(:)
      logical, intent(out) :: solved
      integer, intent(out) :: stat
      real(wp), allocatable :: a(:, :), b(:, :), work(:)
      integer, allocatable :: cols(:)
      real(wp) :: query(1)
      integer :: m, q, rows, info, k, alloc_stat

      m = size(jac, 1)
      cols = pack([(k, k = 1, size(jac, 2))], .not. frozen)
      q = size(cols)
      step = 0.0_wp
      solved = .true.
      stat = hcimpact_ok
      if (q == 0) return
      solved = .false.
      if (mu > 0.0_wp) then
         rows = m + q
      else
         rows = m
      end if
      allocate(a(rows, q), b(rows, 1), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      do k = 1, q
         a(1:m, k) = jac(:, cols(k))
      end do
      b(1:m, 1) = -r
      if (mu > 0.0_wp) then
         a(m+1:, :) = 0.0_wp
         do k = 1, q
            a(m+k, k) = sqrt(mu) * d(cols(k))
         end do
         b(m+1:, 1) = 0.0_wp
      end if
      call dgels('N', rows, q, 1, a, rows, b, rows, query, -1, info)
      allocate(work(max(1, nint(query(1)))), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      call dgels('N', rows, q, 1, a, rows, b, rows, work, size(work), info)
      if (info /= 0) return
      if (.not. all(ieee_is_finite(b(1:q, 1)))) return
      step(cols) = b(1:q, 1)
      solved = .true.
   end subroutine solve_free

end module hcimpact_least_squares
