! SPDX-License-Identifier: Apache-2.0
!> A contact law and an external force for the example: what the closed forms cannot do.
module example_laws
   use hcimpact_kinds, only : wp
   use hcimpact_elastic, only : elastic_law
   use hcimpact_cvode, only : external_force
   implicit none
   private

   public :: stiffening_law, weight

   !> Hertz's law c x^(3/2) below the knee x0, and c x^(3/2) (x/x0)^(3/2) above it
   !> (a layer that stiffens): continuous with a continuous derivative at x0.
   type, extends(elastic_law) :: stiffening_law
      !> c in N/m^1.5
      real(wp) :: stiffness = 0.0_wp
      !> x0 in m
      real(wp) :: knee = 1.0_wp
   contains
      procedure :: force => stiffening_force
      procedure :: potential => stiffening_potential
      procedure :: force_derivative => stiffening_derivative
   end type stiffening_law

   !> A constant force pressing the body into the obstacle (its weight), in N
   type, extends(external_force) :: weight
      real(wp) :: force_value = 0.0_wp
   contains
      procedure :: force => weight_force
   end type weight

   interface weight
      module procedure :: new_weight
   end interface weight

contains

   pure function new_weight(force) result(w)
      real(wp), intent(in) :: force
      type(weight) :: w
      w%force_value = force
   end function new_weight

   pure function weight_force(self, t, x, v) result(g)
      class(weight), intent(in) :: self
      real(wp), intent(in) :: t, x, v
      real(wp) :: g
      g = self%force_value + 0.0_wp * (t + x + v)
   end function weight_force

   pure function stiffening_force(self, x) result(f)
      class(stiffening_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: f
      f = self%stiffness * x * sqrt(x)
      if (x > self%knee) f = f * (x / self%knee)**1.5_wp
   end function stiffening_force

   pure function stiffening_potential(self, x) result(p)
      class(stiffening_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: p, x0
      x0 = self%knee
      if (x <= x0) then
         p = self%stiffness * x**2.5_wp / 2.5_wp
      else
         p = self%stiffness * (x0**2.5_wp / 2.5_wp + (x**4 - x0**4) / (4.0_wp * x0**1.5_wp))
      end if
   end function stiffening_potential

   pure function stiffening_derivative(self, x) result(df)
      class(stiffening_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: df
      if (x <= self%knee) then
         df = 1.5_wp * self%stiffness * sqrt(x)
      else
         df = 3.0_wp * self%stiffness * x**2 / self%knee**1.5_wp
      end if
   end function stiffening_derivative

end module example_laws
