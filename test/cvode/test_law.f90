! SPDX-License-Identifier: Apache-2.0
!> A user's elastic law and an external force (simulate_law) against exact solutions.
module test_cvode_law
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
   use testdrive, only : new_unittest, unittest_type, error_type, check
   use hcimpact_check, only : check_close
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_elastic_law, &
      & hcimpact_err_no_convergence
   use hcimpact_elastic, only : elastic_law, power_law
   use hcimpact_impact_model, only : contact_type
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate, cvode_adams, &
      & external_force
   implicit none
   private

   public :: collect_law

   real(wp), parameter :: pi = 3.14159265358979323846_wp

   !> A constant force g0 (N)
   type, extends(external_force) :: constant_force
      real(wp) :: g0 = 0.0_wp
   contains
      procedure :: force => constant_value
   end type constant_force

   !> A spring -k2 x acting besides the contact (N), with its derivatives
   type, extends(external_force) :: extra_spring
      real(wp) :: k2 = 0.0_wp
   contains
      procedure :: force => spring_value
      procedure :: derivatives => spring_derivatives
   end type extra_spring

   !> A linear law that returns NaN beyond x_bad (a broken user law)
   type, extends(elastic_law) :: broken_law
      real(wp) :: c = 1.0_wp, x_bad = 1.0_wp
   contains
      procedure :: force => broken_force
      procedure :: potential => broken_potential
      procedure :: force_derivative => broken_derivative
   end type broken_law

contains

   !> Collect all exported unit tests
   subroutine collect_law(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("power-law-as-user-law", test_power_as_law), &
         & new_unittest("large-beta-user-law", test_large_beta_law), &
         & new_unittest("linear-spring", test_linear_spring), &
         & new_unittest("constant-external-force", test_constant_force), &
         & new_unittest("external-force-derivatives", test_extra_spring), &
         & new_unittest("length-scale-option", test_length_scale), &
         & new_unittest("broken-law", test_broken_law), &
         & new_unittest("law-broken-early", test_law_broken_early), &
         & new_unittest("contact-never-ends", test_never_ends) &
         & ]
   end subroutine collect_law

   pure function constant_value(self, t, x, v) result(g)
      class(constant_force), intent(in) :: self
      real(wp), intent(in) :: t, x, v
      real(wp) :: g
      g = self%g0 + 0.0_wp * (t + x + v)
   end function constant_value

   pure function spring_value(self, t, x, v) result(g)
      class(extra_spring), intent(in) :: self
      real(wp), intent(in) :: t, x, v
      real(wp) :: g
      g = -self%k2 * x + 0.0_wp * (t + v)
   end function spring_value

   pure subroutine spring_derivatives(self, t, x, v, dg_dx, dg_dv)
      class(extra_spring), intent(in) :: self
      real(wp), intent(in) :: t, x, v
      real(wp), intent(out) :: dg_dx, dg_dv
      dg_dx = -self%k2 + 0.0_wp * (t + x + v)
      dg_dv = 0.0_wp
   end subroutine spring_derivatives

   pure function broken_force(self, x) result(f)
      class(broken_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: f
      f = self%c * x
      if (x > self%x_bad) f = ieee_value(f, ieee_quiet_nan)
   end function broken_force

   pure function broken_potential(self, x) result(p)
      class(broken_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: p
      p = 0.5_wp * self%c * x * x
   end function broken_potential

   pure function broken_derivative(self, x) result(df)
      class(broken_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: df
      df = self%c + 0.0_wp * x
   end function broken_derivative

   !> simulate_law with hcimpact_elastic's power_law against simulate_power.
   subroutine test_power_as_law(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: by_law, by_power
      integer :: stat
      real(wp), parameter :: rtol = 1.0e-8_wp
      call simulate(power_law(stiffness=1.7135e10_wp, exponent=1.5_wp), 0.1_wp, 0.1_wp, &
         & 3.0_wp, by_law, stat, cvode_options(rtol=rtol))
      call check(error, stat, hcimpact_ok, by_law%message)
      if (allocated(error)) return
      call simulate(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=3.0_wp), by_power, stat, cvode_options(rtol=rtol))
      call check(error, stat, hcimpact_ok, by_power%message)
      if (allocated(error)) return
      ! the law path's length unit is x_max itself
      call check_close(error, by_law%length_unit, by_power%outcome%max_compression, &
         & rel=1.0e-5_wp, message="length unit = x_max")
      if (allocated(error)) return
      call check_close(error, by_law%outcome%contact_time, 8.4701327451018694e-5_wp, &
         & rel=100.0_wp * rtol, message="contact time (MODEL.md)")
      if (allocated(error)) return
      call check_close(error, by_law%outcome%restitution, 0.83286979226560167_wp, &
         & rel=1000.0_wp * rtol, message="restitution (MODEL.md)")
      if (allocated(error)) return
      call check_close(error, by_law%outcome%peak_force, 12322.929545918441_wp, &
         & rel=1000.0_wp * rtol, message="peak force (MODEL.md)")
      if (allocated(error)) return
      call check_close(error, by_law%outcome%time_at_peak_force, &
         & by_power%outcome%time_at_peak_force, rel=1000.0_wp * rtol, &
         & message="time of the peak")
   end subroutine test_power_as_law

   !> beta = 1e3 and 1e5: after the peak the body creeps back at x' = -1/b, where
   !> 1 + b x' is below the rounding of its terms; with and without a (zero) external
   !> force, against the power-law path.
   subroutine test_large_beta_law(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: by_law, by_power
      integer :: stat, i, j
      real(wp), parameter :: rtol = 1.0e-8_wp, betas(2) = [1.0e3_wp, 1.0e5_wp]
      do i = 1, size(betas)
         call simulate(contact_type(mass=0.3_wp, stiffness=1.0e9_wp, exponent=2.0_wp, &
            & damping=betas(i) / 2.0_wp, velocity=2.0_wp), by_power, stat, &
            & cvode_options(rtol=rtol))
         call check(error, stat, hcimpact_ok, by_power%message)
         if (allocated(error)) return
         do j = 1, 2
            if (j == 1) then
               call simulate(power_law(stiffness=1.0e9_wp, exponent=2.0_wp), 0.3_wp, &
                  & betas(i) / 2.0_wp, 2.0_wp, by_law, stat, cvode_options(rtol=rtol))
            else
               call simulate(power_law(stiffness=1.0e9_wp, exponent=2.0_wp), 0.3_wp, &
                  & betas(i) / 2.0_wp, 2.0_wp, by_law, stat, cvode_options(rtol=rtol), &
                  & external=constant_force(g0=0.0_wp))
            end if
            call check(error, stat, hcimpact_ok, by_law%message)
            if (allocated(error)) return
            call check_close(error, by_law%outcome%contact_time, &
               & by_power%outcome%contact_time, rel=100.0_wp * rtol, &
               & message="large beta: contact time")
            if (allocated(error)) return
            call check_close(error, by_law%outcome%restitution, &
               & by_power%outcome%restitution, rel=1000.0_wp * rtol, &
               & message="large beta: restitution")
            if (allocated(error)) return
            call check_close(error, by_law%outcome%peak_force, &
               & by_power%outcome%peak_force, rel=1000.0_wp * rtol, &
               & message="large beta: peak force")
            if (allocated(error)) return
         end do
      end do
   end subroutine test_large_beta_law

   !> m x'' = -c x: x = (V/w) sin(w t), contact time pi/w, k = 1.
   subroutine test_linear_spring(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      real(wp), parameter :: m = 2.0_wp, c = 5.0e4_wp, v = 0.3_wp, rtol = 1.0e-9_wp
      real(wp) :: w
      w = sqrt(c / m)
      call simulate(power_law(stiffness=c, exponent=1.0_wp), m, 0.0_wp, v, sim, stat, &
         & cvode_options(rtol=rtol, method=cvode_adams))
      call check(error, stat, hcimpact_ok, sim%message)
      if (allocated(error)) return
      call check_close(error, sim%outcome%contact_time, pi / w, rel=100.0_wp * rtol, &
         & message="contact time pi/w")
      if (allocated(error)) return
      call check_close(error, sim%outcome%compression_time, 0.5_wp * pi / w, &
         & rel=1000.0_wp * rtol, message="compression time pi/(2w)")
      if (allocated(error)) return
      call check_close(error, sim%outcome%max_compression, v / w, rel=1000.0_wp * rtol, &
         & message="x_max = V/w")
      if (allocated(error)) return
      call check_close(error, sim%outcome%peak_force, c * v / w, rel=1000.0_wp * rtol, &
         & message="peak force c V/w")
      if (allocated(error)) return
      call check_close(error, sim%outcome%restitution, 1.0_wp, rel=1000.0_wp * rtol, &
         & message="k = 1")
   end subroutine test_linear_spring

   !> m x'' = -c x + g0: x = A (1 - cos w t) + B sin w t with A = g0/c, B = V/w; the
   !> contact ends at w t = 2 pi - 2 atan(B/A), with the speed V (energy conserved).
   subroutine test_constant_force(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      real(wp), parameter :: m = 0.5_wp, c = 2.0e5_wp, v = 0.2_wp, g0 = 300.0_wp
      real(wp), parameter :: rtol = 1.0e-9_wp
      real(wp) :: w, a, b, theta
      w = sqrt(c / m)
      a = g0 / c
      b = v / w
      theta = 2.0_wp * pi - 2.0_wp * atan(b / a)
      call simulate(power_law(stiffness=c, exponent=1.0_wp), m, 0.0_wp, v, sim, stat, &
         & cvode_options(rtol=rtol), external=constant_force(g0=g0))
      call check(error, stat, hcimpact_ok, sim%message)
      if (allocated(error)) return
      call check_close(error, sim%outcome%contact_time, theta / w, rel=100.0_wp * rtol, &
         & message="contact time with a constant force")
      if (allocated(error)) return
      call check_close(error, sim%outcome%max_compression, a + sqrt(a * a + b * b), &
         & rel=1000.0_wp * rtol, message="x_max = A + sqrt(A^2 + B^2)")
      if (allocated(error)) return
      ! the speed reaches sqrt(V^2 + g0^2/(c m)) = 4.8 V in between, and the global
      ! error at the end, relative to V, is larger than in a plain impact (measured:
      ! 300 rtol at rtol = 1e-9, BDF)
      call check_close(error, sim%outcome%restitution, 1.0_wp, rel=1.0e4_wp * rtol, &
         & message="k = 1 (conservative force)")
   end subroutine test_constant_force

   !> The contact spring c plus an external spring k2: a spring c + k2, but the contact
   !> force reported is c x only.
   subroutine test_extra_spring(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      real(wp), parameter :: m = 1.0_wp, c = 1.0e4_wp, k2 = 3.0e4_wp, v = 1.0_wp
      real(wp), parameter :: rtol = 1.0e-9_wp
      real(wp) :: w
      w = sqrt((c + k2) / m)
      call simulate(power_law(stiffness=c, exponent=1.0_wp), m, 0.0_wp, v, sim, stat, &
         & cvode_options(rtol=rtol), external=extra_spring(k2=k2))
      call check(error, stat, hcimpact_ok, sim%message)
      if (allocated(error)) return
      call check_close(error, sim%outcome%contact_time, pi / w, rel=100.0_wp * rtol, &
         & message="contact time pi/sqrt((c + k2)/m)")
      if (allocated(error)) return
      call check_close(error, sim%outcome%peak_force, c * v / w, rel=1000.0_wp * rtol, &
         & message="contact force c x_max")
   end subroutine test_extra_spring

   subroutine test_length_scale(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      real(wp), parameter :: rtol = 1.0e-8_wp
      call simulate(power_law(stiffness=1.7135e10_wp, exponent=1.5_wp), 0.1_wp, 0.1_wp, &
         & 1.0_wp, sim, stat, cvode_options(rtol=rtol, length_scale=1.0e-3_wp))
      call check(error, stat, hcimpact_ok, sim%message)
      if (allocated(error)) return
      call check(error, sim%length_unit == 1.0e-3_wp, "length unit")
      if (allocated(error)) return
      call check_close(error, sim%outcome%contact_time, 1.0399469349496538e-4_wp, &
         & rel=100.0_wp * rtol, message="contact time with L = 1 mm")
   end subroutine test_length_scale

   subroutine test_broken_law(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      ! x_max = V sqrt(m/c) = 1e-2 m; the law breaks at half of it
      call simulate(broken_law(c=1.0e4_wp, x_bad=5.0e-3_wp), 1.0_wp, 0.0_wp, 1.0_wp, &
         & sim, stat)
      call check(error, stat, hcimpact_err_elastic_law, "broken law: " // sim%message)
      if (allocated(error)) return
      call check(error, index(sim%message, "CV_") > 0, "CVODE's flag: " // sim%message)
   end subroutine test_broken_law

   !> A law that breaks down (NaN) early in the compression, with damping: the
   !> status names the law at once (CVODE's CV_RHSFUNC_FAIL or CV_LSETUP_FAIL). When
   !> a law's failure was recoverable, CVODE crept towards x_bad in ever smaller steps
   !> and gave up after max_steps (500 000 steps, 1.8 s, hcimpact_err_solver).
   subroutine test_law_broken_early(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      ! x_max is about 1e-2 m; the law breaks at 5e-3 of it
      call simulate(broken_law(c=1.0e4_wp, x_bad=5.0e-5_wp), 1.0_wp, 0.1_wp, 1.0_wp, &
         & sim, stat)
      call check(error, stat, hcimpact_err_elastic_law, "broken early: " // sim%message)
      if (allocated(error)) return
      call check(error, sim%counters%steps < 1000, "broken early: steps taken before " &
         & // "the status (at most 1000): " // sim%message)
   end subroutine test_law_broken_early

   !> Hunt-Crossley damping and a force pressing harder than the spring can push back
   !> before the motion dies out: the body settles at x = g0/c and never leaves.
   subroutine test_never_ends(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: sim
      integer :: stat
      call simulate(power_law(stiffness=1.0e4_wp, exponent=1.0_wp), 1.0_wp, 5.0_wp, &
         & 1.0_wp, sim, stat, cvode_options(max_time=1.0_wp), &
         & external=constant_force(g0=1.0e3_wp))
      call check(error, stat, hcimpact_err_no_convergence, "never ends: " // sim%message)
      if (allocated(error)) return
      call check(error, index(sim%message, "has not ended") > 0, sim%message)
   end subroutine test_never_ends

end module test_cvode_law
