! SPDX-License-Identifier: Apache-2.0
!> Elastic laws of the contact: the force f(x) at the deformation x >= 0.
!>
!> The Hunt-Crossley force is f(x)(1 + b x') (MODEL.md). Any law with f(0) = 0 and f
!> increasing will do; the library needs the force, its potential
!> Pi(x) = integral of f from 0 to x (the elastic energy) and its derivative f'(x).
!> A law is a type extending `elastic_law`: its parameters are components of the
!> type, so the library reaches them through the object and never through global
!> state or an internal procedure. The procedures must be pure (they are called from
!> inside the quadrature), and should be accurate to a few ulps: the times of the
!> impact are as accurate as the law.
!>
!> `power_law` is f = c x^n, Pi = c x^(n+1)/(n+1): the Hertz law for n = 3/2.
module hcimpact_elastic
   use hcimpact_kinds, only : wp
   use hcimpact_power_force, only : power_law_force, power_law_potential, power_law_derivative
   implicit none
   private

   public :: elastic_law, elastic_law_value, power_law

   !> An elastic law: extend it and implement the three procedures.
   type, abstract :: elastic_law
   contains
      !> Force f(x) in N, f(0) = 0, increasing
      procedure(elastic_law_value), deferred :: force
      !> Elastic potential energy Pi(x) = integral of f from 0 to x, in J
      procedure(elastic_law_value), deferred :: potential
      !> Stiffness f'(x) in N/m
      procedure(elastic_law_value), deferred :: force_derivative
   end type elastic_law

   abstract interface
      !> A function of the deformation x >= 0 (m).
      pure function elastic_law_value(self, x) result(y)
         import :: elastic_law, wp
         !> The law and its parameters
         class(elastic_law), intent(in) :: self
         !> Deformation in m, x >= 0
         real(wp), intent(in) :: x
         !> Value (N, J or N/m)
         real(wp) :: y
      end function elastic_law_value
   end interface

   !> Power law f = c x^n (n = 3/2: Hertz; n = 1: linear spring).
   type, extends(elastic_law) :: power_law
      !> Contact constant c in N/m^n, > 0
      real(wp) :: stiffness = 0.0_wp
      !> Exponent n, > 0
      real(wp) :: exponent = 1.5_wp
   contains
      procedure :: force => power_force
      procedure :: potential => power_potential
      procedure :: force_derivative => power_force_derivative
   end type power_law

contains

   !> c x^n (hcimpact_power_force)
   pure function power_force(self, x) result(y)
      class(power_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = power_law_force(self%stiffness, self%exponent, x)
   end function power_force

   !> c x^(n+1)/(n+1) (hcimpact_power_force)
   pure function power_potential(self, x) result(y)
      class(power_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = power_law_potential(self%stiffness, self%exponent, x)
   end function power_potential

   !> n c x^(n-1), its limit from the right at x = 0 (hcimpact_power_force)
   pure function power_force_derivative(self, x) result(y)
      class(power_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = power_law_derivative(self%stiffness, self%exponent, x)
   end function power_force_derivative

end module hcimpact_elastic
