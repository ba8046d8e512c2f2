! SPDX-License-Identifier: Apache-2.0
!> The damping rules of multibody codes: the beta = b V they use for a target restitution.
!>
!> Multibody codes write the Hunt-Crossley force as F = c x^n (1 + chi x'/V-), i.e.
!> b = chi/V- and beta = b V- = chi, and take chi(e) from an approximate formula in the
!> target coefficient of restitution e. Plugged into the exact model such a chi gives
!> the restitution k(chi) (`hcimpact_restitution_law`), not e; `restitution_inverse(e)`
!> is the exact beta. doc/legacy-models.md lists the sources, how each formula was
!> checked, and the table of what the rules really produce.
module hcimpact_legacy_damping
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_is_nan
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: n_damping_rules, damping_rule_names, legacy_damping

   !> Number of rules
   integer, parameter :: n_damping_rules = 8
   !> Their names (first author and year), in the order of the rule numbers 1 .. 8
   character(len=*), parameter :: damping_rule_names(n_damping_rules) = &
      & [character(len=24) :: "Hunt-Crossley 1975", "Herbert-McWhannell 1977", &
      & "Lankarani-Nikravesh 1990", "Gonthier et al. 2004", "Zhiying-Qishao 2006", &
      & "Flores et al. 2011", "Hu-Guo 2015", "Carvalho-Martins 2019"]

contains

   !> chi(e) = beta = b V- of damping rule `rule` for the target restitution e.
   !>
   !> 1 Hunt-Crossley 3(1-e)/2; 2 Herbert-McWhannell 6(1-e)/((2e-1)^2+3);
   !> 3 Lankarani-Nikravesh 3(1-e^2)/4; 4 Gonthier et al. (1-e^2)/e;
   !> 5 Zhiying-Qishao 3(1-e^2) exp(2(1-e))/4; 6 Flores et al. 8(1-e)/(5e);
   !> 7 Hu-Guo 3(1-e)/(2e) (as in MODEL.md); 8 Carvalho-Martins 3(1-e)(11-e)/(2(1+9e)).
   !> NaN for e outside (0, 1], NaN e, or a rule number outside 1 .. 8; +Inf where
   !> chi exceeds the double range (rules 4, 6, 7 for e below about 1e-308), without
   !> an overflow exception.
   !>
   !> 1 - e^2 is formed as (1 - e)(1 + e): 1 - e is exact for e >= 1/2, and e*e,
   !> rounded, lost up to all digits of 1 - e^2 as e -> 1 (16 ulp at e = 0.9857,
   !> 3.4e-9 relative at e = 1 - 7.7e-9). Every rule is within 2.8 ulp of the exact
   !> value over (0, 1] (test/unit/test_legacy_damping.f90, mpmath references).
   elemental function legacy_damping(rule, e) result(chi)
      !> Rule number, 1 .. n_damping_rules
      integer, intent(in) :: rule
      !> Target coefficient of restitution, 0 < e <= 1
      real(wp), intent(in) :: e
      !> The rule's beta = b V- (dimensionless)
      real(wp) :: chi

      chi = ieee_value(e, ieee_quiet_nan)
      if (ieee_is_nan(e)) return
      if (e <= 0.0_wp .or. e > 1.0_wp) return
      select case (rule)
      case (1)
         chi = 1.5_wp * (1.0_wp - e)
      case (2)
         chi = 6.0_wp * (1.0_wp - e) / ((2.0_wp * e - 1.0_wp)**2 + 3.0_wp)
      case (3)
         chi = 0.75_wp * (1.0_wp - e) * (1.0_wp + e)
      case (4)
         chi = quotient((1.0_wp - e) * (1.0_wp + e), e)
      case (5)
         chi = 0.75_wp * (1.0_wp - e) * (1.0_wp + e) * exp(2.0_wp * (1.0_wp - e))
      case (6)
         chi = quotient(8.0_wp * (1.0_wp - e), 5.0_wp * e)
      case (7)
         chi = quotient(1.5_wp * (1.0_wp - e), e)
      case (8)
         chi = 1.5_wp * (1.0_wp - e) * (11.0_wp - e) / (1.0_wp + 9.0_wp * e)
      end select
   end function legacy_damping

   !> a/b for a >= 0, b > 0, or +Inf when it exceeds the double range (without
   !> raising overflow: a trapping caller would be stopped).
   elemental function quotient(a, b) result(q)
      real(wp), intent(in) :: a, b
      real(wp) :: q
      if (b < 1.0_wp) then
         if (a > b * huge(a)) then
            q = ieee_value(a, ieee_positive_inf)
            return
         end if
      end if
      q = a / b
   end function quotient

end module hcimpact_legacy_damping
