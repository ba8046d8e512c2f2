! SPDX-License-Identifier: Apache-2.0
!> The contact of one collinear impact, what an impact computes, and the one validator
!> of their parameters.
!>
!> Every entry point of the library that takes a mass, a stiffness, an exponent, a
!> damping constant or an approach speed checks it here (`check_parameters`), so that
!> the Fortran, C, FORTRAN 77 and Python interfaces, the closed forms and the ODE path
!> accept and refuse the same values with the same statuses.
module hcimpact_contact
   use hcimpact_kinds, only : wp, ik, nan, finite_value
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_stiffness, hcimpact_err_exponent, hcimpact_err_velocity, &
      & hcimpact_err_damping, hcimpact_err_domain
   implicit none
   private

   public :: contact_type, outcome_type
   public :: check_contact, check_parameters, reject_unrepresentable
   public :: min_exponent, max_beta

   !> Smallest exponent n of the power law accepted (hcimpact_err_exponent below it).
   !> As n -> 0 the law c x^n tends to a step and the peak-force condition
   !> n m V = b c x^(n+1) degenerates; below about 1e-16 it is not solvable in double
   !> precision. Every physical law has n far above this bound.
   real(wp), parameter :: min_exponent = 1.0e-6_wp
   !> Largest beta = b V the closed forms accept (hcimpact_err_domain above it). Verified
   !> against mpmath up to 1e12 and free of overflow up to about 1e46; k = 1/beta and the
   !> times grow like beta there, so nothing physical lies beyond.
   real(wp), parameter :: max_beta = 1.0e40_wp

   !> A collinear impact with the power law f = c x^n: m x'' = -c x^n (1 + b x').
   type :: contact_type
      !> Mass in kg (the effective mass m1 m2/(m1 + m2) for two bodies), > 0
      real(wp) :: mass = 0.0_wp
      !> Contact constant c in N/m^n, > 0 (hcimpact_hertz: hertz_constant)
      real(wp) :: stiffness = 0.0_wp
      !> Exponent n of the elastic law, > 0 (3/2: Hertz)
      real(wp) :: exponent = 1.5_wp
      !> Damping constant b in s/m, >= 0 (0: Hertz's elastic impact)
      real(wp) :: damping = 0.0_wp
      !> Approach speed V in m/s, > 0 (the relative velocity for two bodies)
      real(wp) :: velocity = 0.0_wp
   end type contact_type

   !> Everything `impact` computes. NaN (and 0 evaluations) until computed, or on error.
   type :: outcome_type
      !> Coefficient of restitution k = -(rebound velocity)/V, in (0, 1]
      real(wp) :: restitution = nan
      !> Share of the kinetic energy lost, 1 - k^2
      real(wp) :: energy_loss_ratio = nan
      !> Rebound velocity -k V in m/s (negative)
      real(wp) :: rebound_velocity = nan
      !> Maximum compression x_max in m
      real(wp) :: max_compression = nan
      !> Largest contact force during the impact, in N
      real(wp) :: peak_force = nan
      !> Compression at which the peak force acts, in m
      real(wp) :: compression_at_peak_force = nan
      !> Time from the start of contact to the peak force, in s
      real(wp) :: time_at_peak_force = nan
      !> Time from the start of contact to the maximum compression, in s
      real(wp) :: compression_time = nan
      !> Duration of the contact, in s
      real(wp) :: contact_time = nan
      !> Integrand evaluations spent by the quadratures (compression, restitution, peak)
      integer(ik) :: evaluations(3) = 0_ik
   end type outcome_type


contains

   !> Check the parameters of a contact, any subset of them: hcimpact_ok, or the status
   !> of the first rule broken, in this order: a value that is NaN or infinite
   !> (hcimpact_err_not_finite), mass not positive (_mass), stiffness not positive
   !> (_stiffness), exponent below `min_exponent` (_exponent), approach speed not
   !> positive (_velocity), damping negative (_damping).
   !>
   !> Finiteness is tested from the bits (finite_value), before any ordered comparison,
   !> so that a NaN, signalling ones included, never raises the invalid flag (the Debug
   !> build traps on it).
   elemental function check_parameters(mass, stiffness, exponent, damping, velocity) &
         & result(stat)
      !> Mass in kg (> 0)
      real(wp), intent(in), optional :: mass
      !> Contact constant c in N/m^n (> 0)
      real(wp), intent(in), optional :: stiffness
      !> Exponent n of the power law (>= min_exponent)
      real(wp), intent(in), optional :: exponent
      !> Damping constant b in s/m (>= 0)
      real(wp), intent(in), optional :: damping
      !> Approach speed V in m/s (> 0)
      real(wp), intent(in), optional :: velocity
      !> Status
      integer :: stat

      stat = hcimpact_err_not_finite
      if (present(mass)) then
         if (.not. finite_value(mass)) return
      end if
      if (present(stiffness)) then
         if (.not. finite_value(stiffness)) return
      end if
      if (present(exponent)) then
         if (.not. finite_value(exponent)) return
      end if
      if (present(damping)) then
         if (.not. finite_value(damping)) return
      end if
      if (present(velocity)) then
         if (.not. finite_value(velocity)) return
      end if
      stat = hcimpact_err_mass
      if (present(mass)) then
         if (.not. mass > 0.0_wp) return
      end if
      stat = hcimpact_err_stiffness
      if (present(stiffness)) then
         if (.not. stiffness > 0.0_wp) return
      end if
      stat = hcimpact_err_exponent
      if (present(exponent)) then
         if (.not. exponent >= min_exponent) return
      end if
      stat = hcimpact_err_velocity
      if (present(velocity)) then
         if (.not. velocity > 0.0_wp) return
      end if
      stat = hcimpact_err_damping
      if (present(damping)) then
         if (damping < 0.0_wp) return
      end if
      stat = hcimpact_ok
   end function check_parameters

   !> Check a contact: `check_parameters` of all its fields.
   elemental function check_contact(contact) result(stat)
      !> The contact
      type(contact_type), intent(in) :: contact
      !> hcimpact_ok or the status of the first bad field
      integer :: stat
      stat = check_parameters(contact%mass, contact%stiffness, contact%exponent, &
         & contact%damping, contact%velocity)
   end function check_contact

   !> An outcome beyond the range of doubles is not an answer: a successful status
   !> never comes with a NaN or an infinity (times of 1e300 s and more), nor with 0
   !> for a quantity that is positive (times, compressions and the peak force below
   !> the smallest subnormal, 4.9e-324: a contact of 1e-375 s). Such an outcome
   !> becomes all NaN with hcimpact_err_domain. (The energy loss is 0 without damping,
   !> and may round to 0 where k is within an ulp of 1: not a quantity of this kind.)
   pure subroutine reject_unrepresentable(outcome, stat)
      type(outcome_type), intent(inout) :: outcome
      integer, intent(inout) :: stat
      if (stat /= hcimpact_ok) return
      ! one scalar test each (the two array constructors this replaced cost more than
      ! all the tests)
      if (positive_finite(outcome%restitution) .and. &
         & finite_value(outcome%energy_loss_ratio) .and. &
         & positive_finite(-outcome%rebound_velocity) .and. &
         & positive_finite(outcome%max_compression) .and. &
         & positive_finite(outcome%compression_time) .and. &
         & positive_finite(outcome%contact_time) .and. &
         & positive_finite(outcome%time_at_peak_force) .and. &
         & positive_finite(outcome%compression_at_peak_force) .and. &
         & positive_finite(outcome%peak_force)) return
      outcome = outcome_type()
      stat = hcimpact_err_domain
   end subroutine reject_unrepresentable

   !> x finite and above 0 (false for NaN, infinities, zero and negative values): the
   !> bits first, so that a NaN never reaches the ordered comparison (check_parameters)
   elemental function positive_finite(x) result(ok)
      real(wp), intent(in) :: x
      logical :: ok
      ok = .false.
      if (finite_value(x)) ok = x > 0.0_wp
   end function positive_finite

end module hcimpact_contact
