! SPDX-License-Identifier: Apache-2.0
!> What the damping rules of multibody codes really give in the Hunt-Crossley model.
!>
!> Multibody codes write the Hunt-Crossley force as F = c x^n (1 + chi x'/V) with V the
!> approach speed, i.e. b = chi/V and beta = b V = chi, and take chi from an
!> approximate formula in the target restitution e. Plugged into the exact model, such
!> a chi restitutes k(chi), not e. This program prints, for e = 0.9, 0.7, 0.5, 0.3, 0.1,
!> each rule's chi, the exact beta(e) (hcimpact_restitution_law, the inverse of k(beta),
!> seed eq. 21), the restitution k(chi) the rule actually produces and its relative
!> error (k - e)/e. The sources are listed in doc/legacy-models.md.
program legacy_models
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : restitution, restitution_inverse
   use hcimpact_legacy_damping, only : n_models => n_damping_rules, &
      & names => damping_rule_names, rule => legacy_damping
   implicit none

   integer, parameter :: n_targets = 5
   real(wp), parameter :: targets(n_targets) = [0.9_wp, 0.7_wp, 0.5_wp, 0.3_wp, 0.1_wp]

   real(wp) :: e, chi, beta, k
   integer :: i, j

   write(*, '(a)') "Damping rules of multibody codes in the exact Hunt-Crossley model"
   write(*, '(a)') "chi: the rule's beta = b V (chi/beta-1 its error against the exact beta(e));"
   write(*, '(a)') "k(chi): the restitution it produces, (k - e)/e its error"
   do i = 1, n_targets
      e = targets(i)
      beta = restitution_inverse(e)
      write(*, '(/, a, f3.1, a, f19.16)') "target e = ", e, ",  exact beta(e) = ", beta
      write(*, '(2x, a24, 5a12)') "rule", "chi", "chi/beta-1", "k(chi)", "(k - e)/e"
      do j = 1, n_models
         chi = rule(j, e)
         k = restitution(chi)
         write(*, '(2x, a24, f12.6, f11.2, a, f12.6, f11.2, a)') names(j), chi, &
            & 100.0_wp * (chi / beta - 1.0_wp), "%", k, 100.0_wp * (k - e) / e, "%"
      end do
   end do

end program legacy_models
