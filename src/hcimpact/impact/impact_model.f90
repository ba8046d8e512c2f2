! SPDX-License-Identifier: Apache-2.0
!> One Hunt-Crossley impact: closed forms, times by quadrature, and the time law.
!>
!> The contact is m x'' = -c x^n (1 + b x'), x(0) = 0, x'(0) = V > 0 (MODEL.md), or the
!> same with a user-supplied elastic law f(x) in place of c x^n (`impact_law`). For two
!> bodies use the effective mass and the relative velocity (hcimpact_hertz).
!>
!> What is computed, and how (power law; the references are the equations of MODEL.md):
!> - beta = b V is formed exactly, as a double-double product: every output is the
!>   value at the two doubles b and V.
!> - Restitution k(beta) (seed eq. 21) and the end of the trajectory in double-double
!>   (hcimpact_trajectory); the energy loss ratio 1 - k^2 = (1 - k)(1 + k).
!> - Maximum compression x_max = [(n+1) m V^2 H / c]^(1/(n+1)), H = h(beta)/beta^2
!>   (= h(beta)/(b^2 V^2) of MODEL.md, finite and smooth as b -> 0), evaluated as the
!>   exponential of a sum of logarithms in double-double and rounded once.
!> - Peak force F = c x^n (1 + b x'), reached in compression where n m x' = b c x^(n+1).
!>   With u = b x' = beta q the condition is n q + (n+1) beta (q^2 H(beta q) - H) = 0
!>   (from the first integral h(u) = h(beta)(1 - (x/x_max)^(n+1))); it is solved by
!>   Newton's method in double-double, and the force is evaluated along the trajectory,
!>   F = c x_max^n (1 - y)^(n/(n+1)) (1 + u), y = h(u)/h(beta), where it is stationary:
!>   an error in q costs only its square.
!> - Compression time, contact time and the time of the peak: tanh-sinh quadrature in
!>   the log-velocity variable (hcimpact_trajectory), the integrand being
!>   (x/x_max)^(-n) = 1 + delta with delta = (1 - q)^(-n/(n+1)) - 1 integrated and the
!>   constant added exactly (near the turning point delta is small and keeps its
!>   relative accuracy). Time unit x_max/((n+1) H V).
!> - Time law: the time as a function of the position is inverted by Newton's method
!>   on the quadrature, from the nearer end of the phase in time.
!>
!> Nothing here stops or prints; every procedure returns a status (hcimpact_status) and
!> NaN outputs when it is not hcimpact_ok.
!>
!> This module is the facade of the impact floor: it gathers what the modules behind it
!> compute (hcimpact_contact: the types and their validator; hcimpact_power_impact:
!> the power law; hcimpact_law_impact: a user's law; hcimpact_damping: the damping for a
!> target restitution) under the names the library has always had.
module hcimpact_impact_model
   use hcimpact_contact, only : contact_type, outcome_type, min_exponent, max_beta
   use hcimpact_damping, only : damping_for_restitution, default_min_velocity
   use hcimpact_power_impact, only : impact_power, velocity_at_depth, time_law_power, &
      & time_law_samples, compression_branch, restitution_branch, max_quadrature_exponent
   use hcimpact_law_impact, only : impact_law, time_law_law
   implicit none
   private

   public :: contact_type, outcome_type
   public :: impact, impact_law, velocity_at_depth, time_law, time_law_samples
   public :: damping_for_restitution, default_min_velocity, min_exponent, max_beta, &
      & max_quadrature_exponent
   public :: compression_branch, restitution_branch

   !> One impact: with the power law (`contact_type`), or with a user's elastic law
   !> (`impact_law`)
   interface impact
      module procedure :: impact_power
      module procedure :: impact_law
   end interface impact

   !> The time law x(t), x'(t), F(t): with the power law or with a user's elastic law
   interface time_law
      module procedure :: time_law_power
      module procedure :: time_law_law
   end interface time_law

end module hcimpact_impact_model
