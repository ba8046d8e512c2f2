! SPDX-License-Identifier: Apache-2.0
!> Stiff and extreme contacts (a quick version of bench/cvode/stability.f90): CVODE
!> either meets its tolerance or returns a status; never a NaN in a finished outcome,
!> never a missed end of contact.
module test_cvode_stability
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use testdrive, only : new_unittest, unittest_type, error_type, check
   use hcimpact_check, only : check_close
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_domain
   use hcimpact_restitution_law, only : restitution
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate, cvode_bdf, &
      & cvode_adams
   implicit none
   private

   public :: collect_stability

   real(wp), parameter :: betas(10) = [0.0_wp, 1.0e-300_wp, 1.0e-16_wp, 1.0e-8_wp, &
      & 1.0e-3_wp, 1.0_wp, 10.0_wp, 1.0e3_wp, 1.0e6_wp, 1.0e300_wp]
   real(wp), parameter :: exponents(4) = [1.0_wp, 1.5_wp, 2.0_wp, 3.0_wp]
   real(wp), parameter :: rtol = 1.0e-6_wp

contains

   !> Collect all exported unit tests
   subroutine collect_stability(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("grid-bdf", test_grid_bdf), &
         & new_unittest("grid-adams", test_grid_adams), &
         & new_unittest("extreme-sizes", test_extreme_sizes), &
         & new_unittest("beyond-the-closed-forms", test_large_beta), &
         & new_unittest("large-exponents", test_large_exponents), &
         & new_unittest("stiffness-ratio", test_stiffness_ratio) &
         & ]
   end subroutine collect_stability

   !> One contact: CVODE against the closed forms, or both with a status.
   subroutine check_contact(error, contact, method, what)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type), intent(in) :: contact
      integer, intent(in) :: method
      character(len=*), intent(in) :: what
      type(outcome_type) :: closed
      type(simulation_type) :: sim
      integer :: stat_closed, stat
      call impact(contact, closed, stat_closed)
      call simulate(contact, sim, stat, cvode_options(method=method, rtol=rtol, &
         & max_steps=50000))
      if (stat_closed /= hcimpact_ok) then
         ! only beta = 1e300 leaves the double range here, for both paths
         call check(error, stat_closed, hcimpact_err_domain, what // ": closed forms")
         if (allocated(error)) return
         call check(error, stat, hcimpact_err_domain, what // ": CVODE: " // sim%message)
         return
      end if
      call check(error, stat, hcimpact_ok, what // ": " // sim%message)
      if (allocated(error)) return
      call check(error, all(ieee_is_finite([sim%outcome%restitution, &
         & sim%outcome%energy_loss_ratio, sim%outcome%rebound_velocity, &
         & sim%outcome%max_compression, sim%outcome%peak_force, &
         & sim%outcome%compression_at_peak_force, sim%outcome%time_at_peak_force, &
         & sim%outcome%compression_time, sim%outcome%contact_time])), &
         & what // ": a finished outcome must be finite")
      if (allocated(error)) return
      call check_close(error, sim%outcome%contact_time, closed%contact_time, &
         & rel=100.0_wp * rtol, message=what // ": contact time")
      if (allocated(error)) return
      call check_close(error, sim%outcome%restitution, closed%restitution, &
         & rel=1000.0_wp * rtol, message=what // ": restitution")
      if (allocated(error)) return
      call check_close(error, sim%outcome%max_compression, closed%max_compression, &
         & rel=1000.0_wp * rtol, message=what // ": maximum compression")
      if (allocated(error)) return
      call check_close(error, sim%outcome%peak_force, closed%peak_force, &
         & rel=1000.0_wp * rtol, message=what // ": peak force")
   end subroutine check_contact

   subroutine run_grid(error, method, name)
      type(error_type), allocatable, intent(out) :: error
      integer, intent(in) :: method
      character(len=*), intent(in) :: name
      integer :: i, j
      character(len=64) :: what
      do i = 1, size(exponents)
         do j = 1, size(betas)
            write(what, '(a, ", n = ", f3.1, ", beta = ", es8.1e3)') name, exponents(i), &
               & betas(j)
            call check_contact(error, contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, &
               & exponent=exponents(i), damping=betas(j), velocity=1.0_wp), method, &
               & trim(what))
            if (allocated(error)) return
         end do
      end do
   end subroutine run_grid

   subroutine test_grid_bdf(error)
      type(error_type), allocatable, intent(out) :: error
      call run_grid(error, cvode_bdf, "BDF")
   end subroutine test_grid_bdf

   subroutine test_grid_adams(error)
      type(error_type), allocatable, intent(out) :: error
      call run_grid(error, cvode_adams, "Adams")
   end subroutine test_grid_adams

   !> Masses 1e-9 ... 1e6 kg, stiffnesses 1 ... 1e15, speeds 1e-9 ... 1e4 m/s.
   subroutine test_extreme_sizes(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: masses(2) = [1.0e-9_wp, 1.0e6_wp]
      real(wp), parameter :: stiffnesses(2) = [1.0_wp, 1.0e15_wp]
      real(wp), parameter :: speeds(2) = [1.0e-9_wp, 1.0e4_wp]
      real(wp), parameter :: some_betas(3) = [0.0_wp, 1.0_wp, 1.0e6_wp]
      integer :: i, j, k, l, n
      character(len=96) :: what
      do i = 1, 2
         do j = 1, 2
            do k = 1, 2
               do l = 1, size(some_betas)
                  do n = 2, 4, 2
                     write(what, '("m = ", es8.1e3, ", c = ", es8.1e3, ", V = ", es8.1e3, &
                        & ", beta = ", es8.1e3, ", n = ", f3.1)') masses(i), &
                        & stiffnesses(j), speeds(k), some_betas(l), exponents(n)
                     call check_contact(error, contact_type(mass=masses(i), &
                        & stiffness=stiffnesses(j), exponent=exponents(n), &
                        & damping=some_betas(l) / speeds(k), velocity=speeds(k)), &
                        & cvode_bdf, trim(what))
                     if (allocated(error)) return
                  end do
               end do
            end do
         end do
      end do
   end subroutine test_extreme_sizes

   !> beta = 1e10 ... 1e100, where only k(beta) is checked (hcimpact_restitution_law):
   !> BDF finishes with a finite outcome; Adams finishes or returns a status.
   subroutine test_large_beta(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: large(4) = [1.0e10_wp, 1.0e30_wp, 1.0e60_wp, 1.0e100_wp]
      type(simulation_type) :: sim
      integer :: i, stat, m
      character(len=64) :: what
      do m = 1, 2
         do i = 1, size(large)
            write(what, '(a, ", beta = ", es8.1e3)') trim(merge("BDF  ", "Adams", m == 1)), &
               & large(i)
            call simulate(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
               & damping=large(i), velocity=1.0_wp), sim, stat, cvode_options( &
               & method=merge(cvode_bdf, cvode_adams, m == 1), rtol=rtol, max_steps=20000))
            if (m == 1) then
               call check(error, stat, hcimpact_ok, trim(what) // ": " // sim%message)
               if (allocated(error)) return
            end if
            if (stat /= hcimpact_ok) then
               call check(error, index(sim%message, "CV_") > 0, trim(what) // &
                  & ": a status names CVODE's flag: " // sim%message)
               if (allocated(error)) return
               cycle
            end if
            call check(error, ieee_is_finite(sim%outcome%contact_time) .and. &
               & ieee_is_finite(sim%outcome%peak_force) .and. &
               & ieee_is_finite(sim%outcome%max_compression), trim(what) // ": finite")
            if (allocated(error)) return
            call check_close(error, sim%outcome%restitution, restitution(large(i)), &
               & rel=1000.0_wp * rtol, message=trim(what) // ": restitution")
            if (allocated(error)) return
         end do
      end do
   end subroutine test_large_beta

   !> n = 10, 50, 100: a stiff wall. Newton iterates overshoot and CVODE's norms
   !> overflow, which it handles (under -ffpe-trap only because the driver turns
   !> halting off while CVODE runs); n above 100 is refused.
   subroutine test_large_exponents(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: ns(3) = [10.0_wp, 50.0_wp, 100.0_wp]
      type(simulation_type) :: sim
      integer :: i, stat
      do i = 1, size(ns)
         call simulate(contact_type(mass=0.1_wp, stiffness=1.0e10_wp, exponent=ns(i), &
            & damping=0.1_wp, velocity=1.0_wp), sim, stat, cvode_options(rtol=rtol))
         call check(error, stat, hcimpact_ok, sim%message)
         if (allocated(error)) return
         call check_close(error, sim%outcome%restitution, restitution(0.1_wp), &
            & rel=1000.0_wp * rtol, message="restitution for a large exponent")
         if (allocated(error)) return
      end do
      call simulate(contact_type(mass=0.1_wp, stiffness=1.0e10_wp, exponent=101.0_wp, &
         & damping=0.1_wp, velocity=1.0_wp), sim, stat)
      call check(error, stat, hcimpact_err_domain, "n = 101: " // sim%message)
   end subroutine test_large_exponents

   !> max |lambda| t_c grows like (n+1) beta for large beta (|lambda| ~ (n+1)/2 beta s^n
   !> at x_max, t_c ~ beta x_max/X in units of X/V): stiff beyond beta ~ 1e3.
   subroutine test_stiffness_ratio(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      call simulate(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=1.0e4_wp, velocity=1.0_wp), sim, stat, cvode_options(rtol=rtol))
      call check(error, stat, hcimpact_ok, sim%message)
      if (allocated(error)) return
      call check_close(error, sim%stiffness_ratio, 2.5_wp * 1.0e4_wp, rel=0.05_wp, &
         & message="stiffness ratio at beta = 1e4, n = 1.5")
   end subroutine test_stiffness_ratio

end module test_cvode_stability
