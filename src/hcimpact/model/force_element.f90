! SPDX-License-Identifier: Apache-2.0
!> The contact-force element: the Hunt-Crossley force of one contact at a given
!> deformation and deformation rate, with its derivatives and energies, for a code that
!> integrates the motion itself.
!>
!> For a contact at the deformation x (m, > 0 while the bodies overlap) and the
!> deformation rate v = dx/dt (m/s, > 0 while they approach), with the elastic law f(x)
!> (c x^n, or any `elastic_law`) and the damping b (s/m):
!>
!>     F = f(x) max(0, 1 + b v)                       (N, pushes the bodies apart)
!>     dF/dx = f'(x) (1 + b v),  dF/dv = b f(x)       where 1 + b v > 0, else 0
!>     potential  = Pi(x) = integral of f from 0 to x  (J, elastic energy stored)
!>     dissipation = (F - f(x)) v                      (W, >= 0)
!>
!> - No force for x <= 0 (the bodies apart or just touching): every field is 0.
!> - The force never pulls. Where 1 + b v < 0 (the bodies separate faster than 1/b) the
!>   damped force would be negative; it is clamped at 0 and so are both derivatives,
!>   consistent with the clamped function (at the kink 1 + b v = 0 exactly, the
!>   derivatives of the clamped side, 0, are returned). The energy bookkeeping stays
!>   exact with the clamp: the power the contact takes from the bodies, F v, is the rate
!>   of change of the potential, f(x) v, plus the dissipation, so
!>   kinetic + potential + integral of dissipation is conserved. Unclamped the
!>   dissipation is b f(x) v^2, clamped -f(x) v; both are >= 0.
!> - In a single Hunt-Crossley impact 1 + b v > 0 all along (MODEL.md's first integral),
!>   so the clamp only acts when other forces pull the bodies apart.
!> - `clamp = .false.` gives the formula as written, F = f(x)(1 + b v) of either sign,
!>   with its derivatives and the dissipation b f(x) v^2. An ODE solver that integrates
!>   one impact on its own wants it: the line v = -1/b, which the exact motion never
!>   crosses, then attracts a numerical solution that overshoots it, while the clamped
!>   force leaves such a solution to drift (the CVODE component measured a contact
!>   time 10 to 100 times less accurate with the clamp at b V = 100 and 1000, rtol
!>   1e-6; doc/contact-force.md).
!>
!> Accuracy (power law): 1 + b v is formed from the exact product b v (an error-free
!> product and sum), so it keeps its relative accuracy next to the clamp, where the
!> naive expression cancels; x^n is one call of the power function. Every field is then
!> a product of a few correctly rounded factors: within a few ulps of the exact value at
!> the double inputs (test/unit/test_contact_force.f90 measures it against mpmath). A
!> product whose factors would overflow or underflow on the way is recomputed from
!> double-double logarithms, so a representable result is returned as such; a result
!> beyond the largest double is +Inf, one below the smallest subnormal 0. For n < 1,
!> dF/dx = n F/x grows without bound as x -> 0+: it is +Inf only where its exact value
!> exceeds the largest double.
!>
!> Forms: one contact given x and v (`contact_force`), two bodies given their positions
!> and velocities (`contact_force_pair`), a body against a fixed wall
!> (`contact_force_wall`); all are elemental, so arrays of contacts cost one call.
!> Bad parameters get the statuses of the whole library (hcimpact_contact's
!> `check_parameters`: stiffness > 0, exponent >= 1e-6, damping >= 0, all finite), a
!> NaN or infinite x or v hcimpact_err_not_finite; every field is then NaN.
module hcimpact_force_element
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_value, ieee_positive_inf
   use hcimpact_kinds, only : wp, nan, finite_value, bit_exponent
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_domain, &
      & hcimpact_err_elastic_law
   use hcimpact_double_double, only : dd_real, dd, two_sum, two_prod, operator(+), &
      & operator(*)
   use hcimpact_power_force, only : power_product, product_of, signed_product, safe_power
   use hcimpact_contact, only : check_parameters
   use hcimpact_elastic, only : elastic_law
   implicit none
   private

   public :: contact_force_type, contact_force, contact_force_pair, contact_force_wall

   !> The element of one contact at one state (SI units). NaN in every field when the
   !> input was rejected.
   type :: contact_force_type
      !> Contact force F in N (>= 0; it pushes the two bodies apart)
      real(wp) :: force = nan
      !> dF/dx in N/m (x: the deformation)
      real(wp) :: dforce_dx = nan
      !> dF/dv in N s/m (v = dx/dt: the deformation rate)
      real(wp) :: dforce_dv = nan
      !> Elastic potential energy Pi(x) in J
      real(wp) :: potential = nan
      !> Dissipated power in W (>= 0)
      real(wp) :: dissipation = nan
   end type contact_force_type

   !> The element of one contact at the deformation x and deformation rate v: with the
   !> power law (stiffness, exponent, damping, x, v, element[, stat]) or with an
   !> `elastic_law` (law, damping, x, v, element[, stat]).
   interface contact_force
      module procedure :: power_contact_force
      module procedure :: law_contact_force
   end interface contact_force

   !> No force: the element where x <= 0
   type(contact_force_type), parameter :: no_contact = contact_force_type(0.0_wp, &
      & 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp)

contains

   !> The element of a power-law contact f = c x^n (see the module header).
   elemental subroutine power_contact_force(stiffness, exponent, damping, x, v, element, &
         & stat, clamp)
      !> Contact constant c in N/m^n, > 0
      real(wp), intent(in) :: stiffness
      !> Exponent n of the elastic law, >= 1e-6
      real(wp), intent(in) :: exponent
      !> Damping b in s/m, >= 0
      real(wp), intent(in) :: damping
      !> Deformation x in m (<= 0: no contact)
      real(wp), intent(in) :: x
      !> Deformation rate v = dx/dt in m/s
      real(wp), intent(in) :: v
      !> The element; NaN fields on error
      type(contact_force_type), intent(out) :: element
      !> hcimpact_ok or the status of the first bad argument
      integer, intent(out), optional :: stat
      !> Clamp the force at 0 where 1 + b v < 0 (default); false: the formula as written
      !> (see the module header)
      logical, intent(in), optional :: clamp
      integer :: status

      status = check_state(stiffness, exponent, damping, x, v)
      if (status == hcimpact_ok) then
         element = power_element(stiffness, exponent, damping, x, dd(v), &
            & clamp_default(clamp))
      else
         element = contact_force_type()
      end if
      if (present(stat)) stat = status
   end subroutine power_contact_force

   !> The element of a contact with a user's elastic law f (its force, potential and
   !> derivative at x; see hcimpact_elastic). Its accuracy is that of the law's
   !> procedures. A law that returns a value that is not finite, or a negative force or
   !> potential, gives hcimpact_err_elastic_law.
   elemental subroutine law_contact_force(law, damping, x, v, element, stat, clamp)
      !> The elastic law
      class(elastic_law), intent(in) :: law
      !> Damping b in s/m, >= 0
      real(wp), intent(in) :: damping
      !> Deformation x in m (<= 0: no contact)
      real(wp), intent(in) :: x
      !> Deformation rate v = dx/dt in m/s
      real(wp), intent(in) :: v
      !> The element; NaN fields on error
      type(contact_force_type), intent(out) :: element
      !> hcimpact_ok or the status of the first bad argument
      integer, intent(out), optional :: stat
      !> Clamp the force at 0 where 1 + b v < 0 (default); false: the formula as written
      logical, intent(in), optional :: clamp
      integer :: status

      status = check_parameters(damping=damping)
      if (status == hcimpact_ok .and. .not. (ieee_is_finite(x) .and. ieee_is_finite(v))) &
         & status = hcimpact_err_not_finite
      element = contact_force_type()
      if (status == hcimpact_ok) call law_element(law, damping, x, dd(v), &
         & clamp_default(clamp), element, status)
      if (present(stat)) stat = status
   end subroutine law_contact_force

   !> The element of the contact between two bodies on a line, body 1 on the left of
   !> body 2, from their positions and velocities: x = distance - (q2 - q1) and
   !> v = v1 - v2, formed with error-free sums (the result is that of the exact x and v
   !> of these doubles, whatever their size). `distance` is q2 - q1 at first touch (the
   !> sum of the radii when q are the centres). The force on body 2 is +F, on body 1
   !> -F; by the chain rule dF/dq1 = dF/dx, dF/dq2 = -dF/dx, dF/dv1 = dF/dv,
   !> dF/dv2 = -dF/dv. Bodies apart by more than the largest double have no contact;
   !> an overlap or a relative speed beyond it (with the bodies in contact) gives
   !> hcimpact_err_domain.
   elemental subroutine contact_force_pair(stiffness, exponent, damping, distance, q1, v1, &
         & q2, v2, element, stat)
      !> Contact constant c in N/m^n, > 0
      real(wp), intent(in) :: stiffness
      !> Exponent n of the elastic law, >= 1e-6
      real(wp), intent(in) :: exponent
      !> Damping b in s/m, >= 0
      real(wp), intent(in) :: damping
      !> q2 - q1 at first touch, in m
      real(wp), intent(in) :: distance
      !> Position (m) and velocity (m/s) of body 1, the left one
      real(wp), intent(in) :: q1, v1
      !> Position (m) and velocity (m/s) of body 2, the right one
      real(wp), intent(in) :: q2, v2
      !> The element; NaN fields on error
      type(contact_force_type), intent(out) :: element
      !> hcimpact_ok or the status of the first bad argument
      integer, intent(out), optional :: stat
      integer :: status
      real(wp) :: x
      type(dd_real) :: rate

      status = check_parameters(stiffness=stiffness, exponent=exponent, damping=damping)
      if (status == hcimpact_ok .and. .not. (ieee_is_finite(distance) .and. &
         & ieee_is_finite(q1) .and. ieee_is_finite(v1) .and. ieee_is_finite(q2) .and. &
         & ieee_is_finite(v2))) status = hcimpact_err_not_finite
      if (status == hcimpact_ok) then
         x = sum_of_three(distance, q1, -q2)
         rate%hi = sum_or_infinity(v1, -v2)
         if (ieee_is_finite(rate%hi)) rate = two_sum(v1, -v2)
         if (.not. x > 0.0_wp) then
            ! apart (also by more than the largest double): no contact
            element = no_contact
         else if (ieee_is_finite(x) .and. ieee_is_finite(rate%hi)) then
            element = power_element(stiffness, exponent, damping, x, rate, .true.)
         else
            ! an overlap or a relative speed beyond the double range
            element = contact_force_type()
            status = hcimpact_err_domain
         end if
      else
         element = contact_force_type()
      end if
      if (present(stat)) stat = status
   end subroutine contact_force_pair

   !> The element of a body against a fixed wall at the position `wall`: side = +1 when
   !> the wall is on the body's right (x = distance - (wall - q), v = dq/dt), side = -1
   !> when it is on its left (x = distance - (q - wall), v = -dq/dt). `distance` is
   !> |wall - q| at first touch (the radius when q is the centre). The force on the body
   !> is -side F; dx/dq = side, so d(force on the body)/dq = -dF/dx and
   !> d(force on the body)/d(dq/dt) = -dF/dv. A side other than +1 or -1 gives
   !> hcimpact_err_domain.
   elemental subroutine contact_force_wall(stiffness, exponent, damping, distance, q, v, &
         & wall, side, element, stat)
      !> Contact constant c in N/m^n, > 0
      real(wp), intent(in) :: stiffness
      !> Exponent n of the elastic law, >= 1e-6
      real(wp), intent(in) :: exponent
      !> Damping b in s/m, >= 0
      real(wp), intent(in) :: damping
      !> |wall - q| at first touch, in m
      real(wp), intent(in) :: distance
      !> Position (m) and velocity (m/s) of the body
      real(wp), intent(in) :: q, v
      !> Position of the wall, in m
      real(wp), intent(in) :: wall
      !> +1: the wall is on the right of the body; -1: on its left
      integer, intent(in) :: side
      !> The element; NaN fields on error
      type(contact_force_type), intent(out) :: element
      !> hcimpact_ok or the status of the first bad argument
      integer, intent(out), optional :: stat
      integer :: status

      if (side == 1) then
         call contact_force_pair(stiffness, exponent, damping, distance, q, v, wall, &
            & 0.0_wp, element, status)
      else if (side == -1) then
         call contact_force_pair(stiffness, exponent, damping, distance, wall, 0.0_wp, q, &
            & v, element, status)
      else
         status = check_parameters(stiffness=stiffness, exponent=exponent, damping=damping)
         if (status == hcimpact_ok) status = hcimpact_err_domain
         element = contact_force_type()
      end if
      if (present(stat)) stat = status
   end subroutine contact_force_wall

   ! ---------------------------------------------------------------------------------

   !> The value of an optional `clamp`: true unless given false.
   elemental function clamp_default(clamp) result(on)
      logical, intent(in), optional :: clamp
      logical :: on
      on = .true.
      if (present(clamp)) on = clamp
   end function clamp_default

   !> Status of the arguments of a power-law element.
   elemental function check_state(stiffness, exponent, damping, x, v) result(stat)
      real(wp), intent(in) :: stiffness, exponent, damping, x, v
      integer :: stat
      stat = check_parameters(stiffness=stiffness, exponent=exponent, damping=damping)
      if (stat == hcimpact_ok .and. .not. (ieee_is_finite(x) .and. ieee_is_finite(v))) &
         & stat = hcimpact_err_not_finite
   end function check_state

   !> d + a + b rounded once from the exact sum of two error-free sums (a + b cancels
   !> when the bodies are far from the origin and close to each other). A sum beyond
   !> the double range is returned as the infinity of its sign (no arithmetic on it).
   elemental function sum_of_three(d, a, b) result(x)
      real(wp), intent(in) :: d, a, b
      real(wp) :: x
      type(dd_real) :: s, t
      x = sum_or_infinity(a, b)
      if (.not. ieee_is_finite(x)) return
      x = sum_or_infinity(d, x)
      if (.not. ieee_is_finite(x)) return
      s = two_sum(a, b)
      t = two_sum(d, s%hi)
      x = t%hi + (t%lo + s%lo)
   end function sum_of_three

   !> a + b of finite doubles, or the infinity of its sign when it overflows, without
   !> raising the overflow (the Debug build traps on it): halves are added first when
   !> a summand is near the largest double.
   elemental function sum_or_infinity(a, b) result(c)
      real(wp), intent(in) :: a, b
      real(wp) :: c
      ! (both below 2^1023 in magnitude, read from the bits: `exponent` is a library
      ! call, frexp, a quarter of this function's cost)
      if (max(bit_exponent(a), bit_exponent(b)) < maxexponent(1.0_wp) - 1) then
         c = a + b
         return
      end if
      c = 0.5_wp * a + 0.5_wp * b
      if (abs(c) > 0.5_wp * huge(1.0_wp)) then
         c = sign(ieee_value(1.0_wp, ieee_positive_inf), c)
      else
         c = a + b
      end if
   end function sum_or_infinity

   !> 1 + b v from the exact product b v (rate = v as hi + lo): the sum rounded once,
   !> so it keeps its relative accuracy where 1 and b v cancel. Also b v itself (its
   !> double part), for the dissipation.
   elemental subroutine damping_factor(damping, rate, factor, bv)
      real(wp), intent(in) :: damping
      type(dd_real), intent(in) :: rate
      !> 1 + b v, rounded once (+-Inf when b v overflows)
      real(wp), intent(out) :: factor
      !> b v rounded
      real(wp), intent(out) :: bv
      type(dd_real) :: p, s
      ! b v beyond the double range: an infinity of its sign, formed without an
      ! overflow (the Debug build traps on it)
      if (damping /= 0.0_wp .and. rate%hi /= 0.0_wp) then
         if (bit_exponent(damping) + bit_exponent(rate%hi) >= maxexponent(1.0_wp) - 2) then
            factor = sign(ieee_value(1.0_wp, ieee_positive_inf), rate%hi)
            bv = factor
            return
         end if
      end if
      p = two_prod(damping, rate%hi)
      bv = p%hi
      if (.not. ieee_is_finite(p%hi)) then
         factor = p%hi
         return
      end if
      s = two_sum(1.0_wp, p%hi)
      factor = s%hi + (s%lo + (p%lo + damping * rate%lo))
   end subroutine damping_factor

   !> The power-law element for valid parameters and finite x, v (see the header);
   !> with `clamp` false the formula as written, negative where 1 + b v < 0.
   elemental function power_element(c, n, b, x, rate, clamp) result(e)
      real(wp), intent(in) :: c, n, b, x
      type(dd_real), intent(in) :: rate
      logical, intent(in) :: clamp
      type(contact_force_type) :: e
      real(wp) :: s, bv, xn, speed, magnitude
      type(dd_real) :: np1

      if (.not. x > 0.0_wp) then
         e = no_contact
         return
      end if
      call damping_factor(b, rate, s, bv)
      speed = abs(rate%hi)
      np1 = two_sum(n, 1.0_wp)
      if (products_stay_normal(c, n, b, x, speed, s)) then
         e = direct_element(c, n, b, x, speed, s, np1%hi, clamp)
         return
      end if
      xn = safe_power(x, n)
      ! Pi = c x^n x/(n + 1)
      e%potential = power_product(xn, x, n, [c, x], np1%hi)
      if (s > 0.0_wp .or. .not. clamp) then
         if (s == 0.0_wp) then
            e%force = 0.0_wp
            e%dforce_dx = 0.0_wp
         else if (ieee_is_finite(s)) then
            magnitude = abs(s)
            e%force = sign(power_product(xn, x, n, [c, magnitude], 1.0_wp), s)
            ! dF/dx = n F/x, dF/dv = b c x^n
            e%dforce_dx = sign(power_product(xn, x, n, [c, magnitude, n], x), s)
         else
            ! b v beyond the double range: 1 + b v = b v to far below an ulp
            e%force = sign(power_product(xn, x, n, [c, b, speed], 1.0_wp), s)
            e%dforce_dx = sign(power_product(xn, x, n, [c, b, speed, n], x), s)
         end if
         if (b > 0.0_wp) then
            e%dforce_dv = power_product(xn, x, n, [c, b], 1.0_wp)
            ! (F - f(x)) v = b f(x) v^2
            e%dissipation = 0.0_wp
            if (speed > 0.0_wp) e%dissipation = power_product(xn, x, n, &
               & [c, b, speed, speed], 1.0_wp)
         else
            e%dforce_dv = 0.0_wp
            e%dissipation = 0.0_wp
         end if
      else
         ! clamped: no force; the contact still gives back no elastic energy, so the
         ! kinetic energy it would have returned is lost: -f(x) v
         e%force = 0.0_wp
         e%dforce_dx = 0.0_wp
         e%dforce_dv = 0.0_wp
         e%dissipation = power_product(xn, x, n, [c, speed], 1.0_wp)
      end if
   end function power_element

   !> Whether x^n and every product and quotient of the element's factors (c, n, b, x,
   !> |v|, |1 + b v|, n + 1) stay normal doubles: the binary exponents, weighted by how
   !> often each factor enters, add up to less than the normal range's. Then
   !> `direct_element` multiplies them as they are (each rounding relative, no
   !> overflow or underflow possible), with power_product's order of operations.
   elemental logical function products_stay_normal(c, n, b, x, speed, s) result(ok)
      real(wp), intent(in) :: c, n, b, x, speed, s
      real(wp) :: budget
      integer, parameter :: range = minexponent(1.0_wp) + 8
      ok = .false.
      if (.not. finite_value(s) .or. s == 0.0_wp) return
      ! the budget below is at least n: a large n fails it without forming n (e(x) + 1),
      ! which overflows for n near the largest double (a trap in the Debug build)
      if (.not. abs(n) < real(-range, wp)) return
      ! log2 of x^n is within n of n e(x); x enters once more (Pi, dF/dx)
      budget = abs(n) * real(abs(bit_exponent(x)) + 1, wp) + abs(bit_exponent(x)) &
         & + abs(bit_exponent(c)) + abs(bit_exponent(n)) + abs(bit_exponent(s)) + 4
      if (b > 0.0_wp) budget = budget + abs(bit_exponent(b))
      if (speed > 0.0_wp) budget = budget + 2 * abs(bit_exponent(speed))
      ok = budget < real(-range, wp)
   end function products_stay_normal

   !> The power-law element by direct products, where products_stay_normal holds: the
   !> same operations in the same order as power_product's direct path, so the same
   !> results bit for bit, without its range checks.
   elemental function direct_element(c, n, b, x, speed, s, np1, clamp) result(e)
      real(wp), intent(in) :: c, n, b, x, speed, s, np1
      logical, intent(in) :: clamp
      type(contact_force_type) :: e
      real(wp) :: f

      f = x**n * c
      e%potential = f * x / np1
      if (s > 0.0_wp .or. .not. clamp) then
         e%force = sign(f * abs(s), s)
         e%dforce_dx = sign(f * abs(s) * n / x, s)
         e%dforce_dv = 0.0_wp
         e%dissipation = 0.0_wp
         if (b > 0.0_wp) then
            e%dforce_dv = f * b
            if (speed > 0.0_wp) e%dissipation = f * b * speed * speed
         end if
      else
         e%force = 0.0_wp
         e%dforce_dx = 0.0_wp
         e%dforce_dv = 0.0_wp
         e%dissipation = f * speed
      end if
   end function direct_element

   !> The element of a user's law for a valid damping and finite x, v.
   pure subroutine law_element(law, b, x, rate, clamp, e, stat)
      class(elastic_law), intent(in) :: law
      real(wp), intent(in) :: b, x
      type(dd_real), intent(in) :: rate
      logical, intent(in) :: clamp
      type(contact_force_type), intent(inout) :: e
      integer, intent(out) :: stat
      real(wp) :: f, fp, p, s, bv, speed

      stat = hcimpact_ok
      if (.not. x > 0.0_wp) then
         e = no_contact
         return
      end if
      f = law%force(x)
      fp = law%force_derivative(x)
      p = law%potential(x)
      if (.not. (ieee_is_finite(f) .and. ieee_is_finite(fp) .and. ieee_is_finite(p))) then
         stat = hcimpact_err_elastic_law
         return
      end if
      if (f < 0.0_wp .or. p < 0.0_wp) then
         stat = hcimpact_err_elastic_law
         return
      end if
      call damping_factor(b, rate, s, bv)
      speed = abs(rate%hi)
      e%potential = p
      if (s > 0.0_wp .or. .not. clamp) then
         if (ieee_is_finite(s)) then
            e%force = signed_product(s, [f])
            e%dforce_dx = signed_product(fp, [abs(s)]) * sign(1.0_wp, s)
         else
            e%force = sign(product_of([f, b, speed]), s)
            e%dforce_dx = signed_product(fp, [b, speed]) * sign(1.0_wp, s)
         end if
         e%dforce_dv = product_of([f, b])
         e%dissipation = product_of([f, b, speed, speed])
      else
         e%force = 0.0_wp
         e%dforce_dx = 0.0_wp
         e%dforce_dv = 0.0_wp
         e%dissipation = product_of([f, speed])
      end if
   end subroutine law_element

end module hcimpact_force_element
