! SPDX-License-Identifier: Apache-2.0
!> Data sets for the calibration tests and study, generated from the model with known
!> parameters (the seed's steel ball, MODEL.md) and, on request, deterministic noise.
module calibration_cases
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : restitution
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_rng, only : rng_type, new_rng, normal
   implicit none
   private

   public :: seed_mass, seed_stiffness, seed_exponent, seed_damping
   public :: speeds, deflections, restitution_data, static_data, impact_data

   !> The seed's steel ball on a steel plate: mass (kg), c (N/m^1.5), n, b (s/m)
   real(wp), parameter :: seed_mass = 0.1_wp, seed_stiffness = 1.7135e10_wp, &
      & seed_exponent = 1.5_wp, seed_damping = 0.1_wp

   !> Streams of the generator, so that one seed gives independent noise per series
   integer, parameter :: stream_restitution = 1, stream_static = 2, stream_time = 3, &
      & stream_force = 4, stream_impact_restitution = 5

contains

   !> n speeds spread evenly over [low, high] (m/s).
   pure function speeds(n, low, high) result(v)
      integer, intent(in) :: n
      real(wp), intent(in) :: low, high
      real(wp) :: v(n)
      integer :: i
      v = [(low + (high - low) * (i - 1) / real(max(n - 1, 1), wp), i = 1, n)]
   end function speeds

   !> n deflections spread evenly in the logarithm over [2e-6, 1e-4] m.
   pure function deflections(n) result(x)
      integer, intent(in) :: n
      real(wp) :: x(n)
      integer :: i
      x = [(2.0e-6_wp * 50.0_wp**((i - 1) / real(max(n - 1, 1), wp)), i = 1, n)]
   end function deflections

   !> Restitution e = k(b V) plus normal noise of standard deviation sigma (seed 0 or
   !> sigma 0: none).
   function restitution_data(b, v, sigma, seed) result(e)
      real(wp), intent(in) :: b, v(:), sigma
      integer, intent(in) :: seed
      real(wp) :: e(size(v))
      e = restitution(b * v) + sigma * noise(size(v), seed, stream_restitution)
   end function restitution_data

   !> Static force F = c x^n of the seed's ball times exp(sigma z) (relative noise).
   function static_data(x, sigma, seed) result(f)
      real(wp), intent(in) :: x(:), sigma
      integer, intent(in) :: seed
      real(wp) :: f(size(x))
      f = seed_stiffness * x**seed_exponent * exp(sigma * noise(size(x), seed, stream_static))
   end function static_data

   !> Contact time, peak force and restitution of the seed's ball with damping b at the
   !> speeds v, with relative noise sigma_t, sigma_f on the first two and absolute
   !> noise sigma_e on the restitution.
   subroutine impact_data(b, v, sigma_t, sigma_f, sigma_e, seed, t, f, e)
      real(wp), intent(in) :: b, v(:), sigma_t, sigma_f, sigma_e
      integer, intent(in) :: seed
      real(wp), intent(out) :: t(:), f(:), e(:)
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      integer :: i, stat
      do i = 1, size(v)
         contact = contact_type(mass=seed_mass, stiffness=seed_stiffness, &
            & exponent=seed_exponent, damping=b, velocity=v(i))
         call impact(contact, outcome, stat)
         if (stat /= 0) error stop "impact_data: the model failed"
         t(i) = outcome%contact_time
         f(i) = outcome%peak_force
         e(i) = outcome%restitution
      end do
      t = t * exp(sigma_t * noise(size(v), seed, stream_time))
      f = f * exp(sigma_f * noise(size(v), seed, stream_force))
      e = e + sigma_e * noise(size(v), seed, stream_impact_restitution)
   end subroutine impact_data

   !> n standard normal deviates of the stream of a seed; zeros for seed 0.
   function noise(n, seed, stream) result(z)
      integer, intent(in) :: n, seed, stream
      real(wp) :: z(n)
      type(rng_type) :: rng
      integer :: i
      z = 0.0_wp
      if (seed == 0) return
      rng = new_rng(8 * seed + stream)
      do i = 1, n
         z(i) = normal(rng)
      end do
   end function noise

end module calibration_cases
