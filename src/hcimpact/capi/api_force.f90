! SPDX-License-Identifier: Apache-2.0
!> C interface of the contact-force element (hcimpact_force_element): one contact, many
!> contacts, two bodies, a body against a wall.
!>
!> Declared in include/hcimpact.h; the structure `hcimpact_force` and its conversion
!> are in hcimpact_capi_types. NULL pointers give HCIMPACT_ERR_NULL and a size below 1
!> HCIMPACT_ERR_SIZE (nothing written); every other error leaves NaN in the fields.
module hcimpact_api_force
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_ptr, c_associated, c_f_pointer
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_null, hcimpact_err_size
   use hcimpact_force_element, only : contact_force_type, contact_force, contact_force_pair, &
      & contact_force_wall
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_parallel, only : failure_key, key_status, no_failure
   !$ use hcimpact_parallel, only : min_parallel_element
   use hcimpact_capi_types, only : hcimpact_force, from_force
   implicit none
   private

   public :: c_contact_force, c_contact_force_array, c_contact_force_pair, c_contact_force_wall

contains

   !> int hcimpact_contact_force(double stiffness, double exponent, double damping,
   !>                            double x, double v, hcimpact_force *f);
   function c_contact_force(stiffness, exponent, damping, x, v, f) result(stat) &
         & bind(C, name="hcimpact_contact_force")
      !> c in N/m^n, n, b in s/m
      real(c_double), value, intent(in) :: stiffness, exponent, damping
      !> Deformation x in m and deformation rate v in m/s
      real(c_double), value, intent(in) :: x, v
      !> hcimpact_force *
      type(c_ptr), value, intent(in) :: f
      !> Status
      integer(c_int) :: stat
      type(hcimpact_force), pointer :: c_out
      type(contact_force_type) :: element
      integer :: status
      if (.not. c_associated(f)) then
         stat = int(hcimpact_err_null, c_int)
         return
      end if
      call c_f_pointer(f, c_out)
      call contact_force(real(stiffness, wp), real(exponent, wp), real(damping, wp), &
         & real(x, wp), real(v, wp), element, status)
      c_out = from_force(element)
      stat = int(status, c_int)
   end function c_contact_force

   !> int hcimpact_contact_force_array(int n, const double *stiffness,
   !>     const double *exponent, const double *damping, const double *x,
   !>     const double *v, hcimpact_force *f, int *statuses);
   !>
   !> The element of n contacts (arrays of n values each); statuses may be NULL. The
   !> result is HCIMPACT_OK when all succeeded, else the status of the first that failed
   !> (its fields are NaN, the others are computed regardless).
   function c_contact_force_array(n, stiffness, exponent, damping, x, v, f, statuses) &
         & result(stat) bind(C, name="hcimpact_contact_force_array")
      !> Number of contacts, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double[n] each
      type(c_ptr), value, intent(in) :: stiffness, exponent, damping, x, v
      !> hcimpact_force[n]
      type(c_ptr), value, intent(in) :: f
      !> int[n] or NULL
      type(c_ptr), value, intent(in) :: statuses
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: cs(:), ns(:), bs(:), xs(:), vs(:)
      type(hcimpact_force), pointer :: c_out(:)
      integer(c_int), pointer :: c_stat(:)
      type(contact_force_type) :: element
      integer :: i, status
      integer(int64) :: first
      if (.not. (c_associated(stiffness) .and. c_associated(exponent) .and. &
         & c_associated(damping) .and. c_associated(x) .and. c_associated(v) .and. &
         & c_associated(f))) then
         stat = int(hcimpact_err_null, c_int)
         return
      end if
      if (n < 1) then
         stat = int(hcimpact_err_size, c_int)
         return
      end if
      call c_f_pointer(stiffness, cs, [n])
      call c_f_pointer(exponent, ns, [n])
      call c_f_pointer(damping, bs, [n])
      call c_f_pointer(x, xs, [n])
      call c_f_pointer(v, vs, [n])
      call c_f_pointer(f, c_out, [n])
      nullify(c_stat)
      if (c_associated(statuses)) call c_f_pointer(statuses, c_stat, [n])
      stat = int(hcimpact_ok, c_int)
      ! In parallel; the status returned is that of the lowest failing index.
      first = no_failure
      !$omp parallel do if (n >= min_parallel_element) private(element, status) &
      !$omp & reduction(min: first) schedule(static)
      do i = 1, n
         call contact_force(real(cs(i), wp), real(ns(i), wp), real(bs(i), wp), &
            & real(xs(i), wp), real(vs(i), wp), element, status)
         c_out(i) = from_force(element)
         if (associated(c_stat)) c_stat(i) = int(status, c_int)
         if (status /= hcimpact_ok) first = min(first, failure_key(i, status))
      end do
      !$omp end parallel do
      stat = int(key_status(first), c_int)
   end function c_contact_force_array

   !> int hcimpact_contact_force_pair(double stiffness, double exponent, double damping,
   !>     double distance, double q1, double v1, double q2, double v2, hcimpact_force *f);
   function c_contact_force_pair(stiffness, exponent, damping, distance, q1, v1, q2, v2, &
         & f) result(stat) bind(C, name="hcimpact_contact_force_pair")
      !> c in N/m^n, n, b in s/m
      real(c_double), value, intent(in) :: stiffness, exponent, damping
      !> q2 - q1 at first touch, m
      real(c_double), value, intent(in) :: distance
      !> Positions (m) and velocities (m/s) of body 1 (left) and body 2 (right)
      real(c_double), value, intent(in) :: q1, v1, q2, v2
      !> hcimpact_force *
      type(c_ptr), value, intent(in) :: f
      !> Status
      integer(c_int) :: stat
      type(hcimpact_force), pointer :: c_out
      type(contact_force_type) :: element
      integer :: status
      if (.not. c_associated(f)) then
         stat = int(hcimpact_err_null, c_int)
         return
      end if
      call c_f_pointer(f, c_out)
      call contact_force_pair(real(stiffness, wp), real(exponent, wp), real(damping, wp), &
         & real(distance, wp), real(q1, wp), real(v1, wp), real(q2, wp), real(v2, wp), &
         & element, status)
      c_out = from_force(element)
      stat = int(status, c_int)
   end function c_contact_force_pair

   !> int hcimpact_contact_force_wall(double stiffness, double exponent, double damping,
   !>     double distance, double q, double v, double wall, int side, hcimpact_force *f);
   function c_contact_force_wall(stiffness, exponent, damping, distance, q, v, wall, side, &
         & f) result(stat) bind(C, name="hcimpact_contact_force_wall")
      !> c in N/m^n, n, b in s/m
      real(c_double), value, intent(in) :: stiffness, exponent, damping
      !> |wall - q| at first touch, m
      real(c_double), value, intent(in) :: distance
      !> Position (m) and velocity (m/s) of the body, position of the wall (m)
      real(c_double), value, intent(in) :: q, v, wall
      !> +1: wall on the right of the body; -1: on its left
      integer(c_int), value, intent(in) :: side
      !> hcimpact_force *
      type(c_ptr), value, intent(in) :: f
      !> Status
      integer(c_int) :: stat
      type(hcimpact_force), pointer :: c_out
      type(contact_force_type) :: element
      integer :: status
      if (.not. c_associated(f)) then
         stat = int(hcimpact_err_null, c_int)
         return
      end if
      call c_f_pointer(f, c_out)
      call contact_force_wall(real(stiffness, wp), real(exponent, wp), real(damping, wp), &
         & real(distance, wp), real(q, wp), real(v, wp), real(wall, wp), int(side), &
         & element, status)
      c_out = from_force(element)
      stat = int(status, c_int)
   end function c_contact_force_wall

end module hcimpact_api_force
