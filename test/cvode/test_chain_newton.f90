! SPDX-License-Identifier: Apache-2.0
!> The linear solver of a region's Newton iterations (hcimpact_cvode_chain_system's
!> factor_newton_matrix and solve_newton, behind hcimpact_cvode_chain_linear_solver):
!> on random regions, M = I - gamma J is formed from region_jacobian in band storage
!> as CVODE forms it, and the solution of M z = r must have a normwise backward error
!> (||M z - r|| / (||M|| ||z|| + ||r||), max norms) of a few rounding errors and be
!> close to the solution of Gaussian elimination with partial pivoting in quadruple
!> precision to 1e-8 of its largest value, for matrices whose condition reaches
!> about 1e8 (the Newton iteration needs far fewer digits: an error of the solve
!> slows its convergence, it does not change what it converges to). The walls'
!> impulses' rows (outside the band, region_jacobian's slope) are part of M, and where no
!> end of the region is a boundary (every outside force a wall's) the solution keeps
!> the momentum's invariant: sum m_k z(v_k) - z(J_left) - z(J_right) equals the same
!> sum of r to a few rounding errors of its terms. A nonzero outside the structure
!> and a zero pivot must be reported.
module test_cvode_chain_newton
   use, intrinsic :: iso_fortran_env, only : real128
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use hcimpact_check, only : format_real, int_text
   use hcimpact_kinds, only : wp
   use hcimpact_chain_types, only : contact_law
   use hcimpact_cvode_chain_system, only : chain_region, region_size, region_jacobian, &
      & newton_factor, factor_newton_matrix, solve_newton, upper_band, lower_band, &
      & impulse_index, &
      & slot_pair, slot_left_wall, slot_right_wall, slot_boundary_left, &
      & slot_boundary_right, slot_none
   implicit none
   private

   public :: collect_chain_newton

   !> Stored upper bandwidth and leading dimension of the band storage (as SUNDIALS'
   !> band matrix for the band LU: upper + lower above the diagonal)
   integer, parameter :: smu = upper_band + lower_band, ldim = smu + lower_band + 1
   !> The impulses' rows of a region without walls
   real(wp), parameter :: no_slope(2, 2) = 0.0_wp

contains

   !> The tests of this suite
   subroutine collect_chain_newton(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("solves-random-regions", test_random_regions), &
         & new_unittest("reports-structure", test_structure), &
         & new_unittest("reports-zero-pivot", test_zero_pivot) &
         & ]
   end subroutine collect_chain_newton

   !> 400 random regions of 1 to 60 bodies: masses over six decades, Hertz-like and
   !> other exponents, with and without damping, each end a wall, a boundary or
   !> nothing, every slot compressed, touching or apart, gamma over six decades
   subroutine test_random_regions(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_region) :: region
      type(newton_factor) :: factor
      real(wp), allocatable :: band(:, :), y(:), r(:), z(:), dense(:, :)
      real(wp) :: gamma, u, worst, residual, forward, worst_forward, slope(2, 2)
      real(wp) :: balance, worst_balance
      integer :: trial, m, n, k, info, row, col, side, walls_only
      integer :: seed_size

      call random_seed(size=seed_size)
      call random_seed(put=[(20261126 + 7 * k, k = 1, seed_size)])
      worst = 0.0_wp
      worst_forward = 0.0_wp
      worst_balance = 0.0_wp
      walls_only = 0
      do trial = 1, 400
         call random_number(u)
         m = 1 + int(u * 60.0_wp)
         if (trial <= 4) m = trial
         call random_region(region, m, y)
         n = region_size(m)
         allocate(band(ldim, n), r(n), z(n), dense(n, n))
         band = 0.0_wp
         call region_jacobian(region, 0.0_wp, y, smu, band, slope)
         call random_number(u)
         gamma = 10.0_wp**(-9.0_wp + 6.0_wp * u)
         ! M = I - gamma J, as CVODE forms it in the band matrix
         band = -gamma * band
         do k = 1, n
            band(smu + 1, k) = band(smu + 1, k) + 1.0_wp
         end do
         dense = 0.0_wp
         do col = 1, n
            do row = max(1, col - smu), min(n, col + lower_band)
               dense(row, col) = band(smu + row - col + 1, col)
            end do
         end do
         ! the impulses' rows outside the band: -gamma J'(u, v of the end body)
         do side = 1, 2
            row = impulse_index(m, side)
            col = merge(1, 3 * m - 2, side == 1)
            dense(row, col:col + 1) = dense(row, col:col + 1) - gamma * slope(:, side)
         end do
         call factor_newton_matrix(m, smu, band, slope, factor, info)
         call check(error, info, 0, "trial " // int_text(trial) // " (m = " &
            & // int_text(m) // "): factor_newton_matrix info")
         if (allocated(error)) return
         call random_number(r)
         r = 2.0_wp * r - 1.0_wp
         z = r
         call solve_newton(m, factor, z)
         residual = maxval(abs(matmul(dense, z) - r)) / (maxval(sum(abs(dense), 2)) &
            & * maxval(abs(z)) + maxval(abs(r)))
         forward = real(maxval(abs(real(z, real128) - quad_solution(dense, r))), wp) &
            & / maxval(abs(z))
         worst = max(worst, residual)
         worst_forward = max(worst_forward, forward)
         if (region%kind(0) /= slot_boundary_left .and. region%kind(m) /= &
            & slot_boundary_right) then
            walls_only = walls_only + 1
            balance = abs(momentum_row(region, z) - momentum_row(region, r)) &
               & / momentum_magnitude(region, z, r)
            worst_balance = max(worst_balance, balance)
            if (.not. balance <= real(8 * m, wp) * epsilon(1.0_wp)) then
               call test_failed(error, "trial " // int_text(trial) // " (m = " &
                  & // int_text(m) // "): the momentum's invariant kept to " &
                  & // format_real(balance))
               return
            end if
         end if
         if (.not. (residual <= 16.0_wp * epsilon(1.0_wp) .and. forward <= 1.0e-8_wp)) then
            call test_failed(error, "trial " // int_text(trial) // " (m = " &
               & // int_text(m) // ", gamma = " // format_real(gamma) &
               & // "): backward error " // format_real(residual) // ", forward error " &
               & // format_real(forward))
            return
         end if
         deallocate(band, r, z, dense, factor%uu, factor%uv, factor%vu, factor%lower, &
            & factor%pivot, factor%upper, factor%ee)
      end do
      print '(a, es10.3, a, es10.3, a, es10.3, a, i0, a)', "  largest backward error ", &
         & worst, ", forward error ", worst_forward, " (400 regions); momentum's " &
         & // "invariant ", worst_balance / epsilon(1.0_wp), " eps (", walls_only, &
         & " regions without a boundary)"
   end subroutine test_random_regions

   !> sum m_k x(v_k) - x(J_left) - x(J_right) of a vector x of the region's state
   pure real(wp) function momentum_row(region, x) result(total)
      type(chain_region), intent(in) :: region
      real(wp), intent(in) :: x(:)
      integer :: k, m
      m = region%m
      total = 0.0_wp
      do k = 1, m
         total = total + region%mass(k) * x(3 * k - 1)
      end do
      total = total - x(impulse_index(m, 1)) - x(impulse_index(m, 2))
   end function momentum_row

   !> The magnitudes of the terms of momentum_row of x and of r
   pure real(wp) function momentum_magnitude(region, x, r) result(total)
      type(chain_region), intent(in) :: region
      real(wp), intent(in) :: x(:), r(:)
      integer :: k, m
      m = region%m
      total = 0.0_wp
      do k = 1, m
         total = total + region%mass(k) * (abs(x(3 * k - 1)) + abs(r(3 * k - 1)))
      end do
      do k = 1, 2
         total = total + abs(x(impulse_index(m, k))) + abs(r(impulse_index(m, k)))
      end do
   end function momentum_magnitude

   !> A nonzero where the structure has none (u_1 coupled to u_2): info -1
   subroutine test_structure(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_region) :: region
      type(newton_factor) :: factor
      real(wp), allocatable :: band(:, :), y(:)
      integer :: m, n, k, info
      m = 3
      call random_region(region, m, y)
      n = region_size(m)
      allocate(band(ldim, n))
      band = 0.0_wp
      call region_jacobian(region, 0.0_wp, y, smu, band)
      band = -1.0e-6_wp * band
      do k = 1, n
         band(smu + 1, k) = band(smu + 1, k) + 1.0_wp
      end do
      call factor_newton_matrix(m, smu, band, no_slope, factor, info)
      call check(error, info, 0, "the region's own matrix")
      if (allocated(error)) return
      ! M(u_1, u_2): row 1, column 4
      band(smu + 1 - 4 + 1, 4) = 1.0e-3_wp
      call factor_newton_matrix(m, smu, band, no_slope, factor, info)
      call check(error, info, -1, "an entry outside the structure")
   end subroutine test_structure

   !> A velocity row of zeros (a body of no mass, not a region CVODE would see): the
   !> pivot of that body is reported as its index
   subroutine test_zero_pivot(error)
      type(error_type), allocatable, intent(out) :: error
      type(newton_factor) :: factor
      real(wp), allocatable :: band(:, :)
      integer :: m, n, k, info
      m = 4
      n = region_size(m)
      allocate(band(ldim, n))
      band = 0.0_wp
      do k = 1, n
         band(smu + 1, k) = 1.0_wp
      end do
      ! M(v_3, v_3) = 0
      band(smu + 1, 3 * 3 - 1) = 0.0_wp
      call factor_newton_matrix(m, smu, band, no_slope, factor, info)
      call check(error, info, 3, "zero pivot of body 3")
   end subroutine test_zero_pivot

   !> A random region of m bodies and a state y in which its slots are compressed,
   !> touching or apart, moving towards or away from each other
   subroutine random_region(region, m, y)
      type(chain_region), intent(out) :: region
      integer, intent(in) :: m
      real(wp), allocatable, intent(out) :: y(:)
      real(wp) :: u(6)
      integer :: j, k
      region%m = m
      allocate(region%mass(m), region%kind(0:m), region%law(0:m), region%gap0(0:m))
      do k = 1, m
         call random_number(u)
         region%mass(k) = 10.0_wp**(-3.0_wp + 6.0_wp * u(1))
      end do
      do j = 0, m
         call random_number(u)
         region%law(j) = contact_law(stiffness=10.0_wp**(6.0_wp + 5.0_wp * u(1)), &
            & exponent=merge(1.5_wp, 1.0_wp + 2.0_wp * u(2), u(3) < 0.5_wp), &
            & damping=merge(0.0_wp, 2.0_wp * u(4), u(5) < 0.3_wp))
         region%gap0(j) = 0.0_wp
         region%kind(j) = slot_pair
      end do
      call random_number(u)
      region%kind(0) = end_kind(u(1), slot_left_wall, slot_boundary_left)
      region%kind(m) = end_kind(u(2), slot_right_wall, slot_boundary_right)
      allocate(y(region_size(m)))
      y = 0.0_wp
      ! displacements of -1e-5 .. 1e-5 m (the gaps are 0: a slot is compressed where
      ! its left body has moved right of its right one), speeds of -1 .. 1 m/s
      do k = 1, m
         call random_number(u)
         y(3 * k - 2) = 1.0e-5_wp * (2.0_wp * u(1) - 1.0_wp)
         y(3 * k - 1) = 2.0_wp * u(2) - 1.0_wp
      end do
   end subroutine random_region

   !> The solution of dense z = r by Gaussian elimination with partial pivoting in
   !> quadruple precision (the reference of test_random_regions)
   function quad_solution(dense, r) result(z)
      real(wp), intent(in) :: dense(:, :), r(:)
      real(real128) :: z(size(r))
      real(real128) :: a(size(r), size(r)), factor, swap(size(r)), t
      integer :: n, k, p, i
      n = size(r)
      a = real(dense, real128)
      z = real(r, real128)
      do k = 1, n
         p = k - 1 + maxloc(abs(a(k:n, k)), 1)
         if (p /= k) then
            swap = a(k, :)
            a(k, :) = a(p, :)
            a(p, :) = swap
            t = z(k)
            z(k) = z(p)
            z(p) = t
         end if
         do i = k + 1, n
            if (a(i, k) == 0.0_real128) cycle
            factor = a(i, k) / a(k, k)
            a(i, k:n) = a(i, k:n) - factor * a(k, k:n)
            z(i) = z(i) - factor * z(k)
         end do
      end do
      do k = n, 1, -1
         z(k) = (z(k) - sum(a(k, k + 1:n) * z(k + 1:n))) / a(k, k)
      end do
   end function quad_solution

   !> The kind of an end slot from a uniform number: a wall, a boundary or nothing
   pure integer function end_kind(u, wall, boundary) result(kind)
      real(wp), intent(in) :: u
      integer, intent(in) :: wall, boundary
      if (u < 0.4_wp) then
         kind = wall
      else if (u < 0.7_wp) then
         kind = boundary
      else
         kind = slot_none
      end if
   end function end_kind

end module test_cvode_chain_newton
