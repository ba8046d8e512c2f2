! SPDX-License-Identifier: Apache-2.0
!> C interface of the library, part 1: special functions, restitution, two bodies,
!> status messages and the version. Thin bind(C) wrappers that convert and check.
!>
!> Every name here is declared in include/hcimpact.h (doc/c-api.md); the physics lives
!> in the Fortran modules this one calls. The impact itself, the trajectory and the
!> time law are in hcimpact_api_impact and hcimpact_api_motion, their structures in
!> hcimpact_capi_types.
!>
!> Conventions of the whole C layer:
!> - a function that returns a double answers NaN outside its domain and never fails
!>   otherwise; everything else returns an `int` status (hcimpact_status, the
!>   `HCIMPACT_*` macros) and writes its results through pointers;
!> - a NULL pointer gives HCIMPACT_ERR_NULL and nothing is written; a size below 1
!>   (below 2 for sampled time laws) gives HCIMPACT_ERR_SIZE and nothing is written;
!> - on any other error every output is NaN;
!> - array forms take `int n` and plain C arrays (explicit shape here); an output array
!>   may be the input array itself (in place), other overlaps are not allowed;
!> - no state: every function may be called from several threads at once.
!>
!> Binding labels must differ from every module name of the program (gfortran
!> miscompiles the pair, doc/c-api.md); test/api/check_names.cmake enforces it.
module hcimpact_api
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_char, c_ptr, c_null_char, &
      & c_associated, c_f_pointer, c_loc
   use hcimpact_kinds, only : wp
   use hcimpact_version_info, only : hcimpact_version_string, hcimpact_version_compact
   use hcimpact_parallel, only : array_threads
   !$ use hcimpact_parallel, only : min_parallel_cheap
   use hcimpact_status, only : status_texts, max_status_code, hcimpact_ok, hcimpact_err_null, hcimpact_err_size
   use hcimpact_lambertw, only : lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1
   use hcimpact_restitution_law, only : u_minus_log1p, restitution, one_minus_restitution, &
      & energy_loss_ratio, restitution_derivative, restitution_inverse
   use hcimpact_hertz, only : hertz_constant, effective_mass, two_body_velocities
   use hcimpact_impact_model, only : damping_for_restitution
   implicit none
   private

   public :: c_lambert_w0, c_lambert_wm1, c_lambert_w0p1, c_lambert_wm1p1
   public :: c_lambert_w0_array, c_lambert_wm1_array, c_lambert_w0p1_array, &
      & c_lambert_wm1p1_array
   public :: c_restitution, c_restitution_inverse, c_one_minus_restitution, &
      & c_energy_loss_ratio, c_restitution_derivative, c_u_minus_log1p
   public :: c_restitution_array, c_restitution_inverse_array, &
      & c_one_minus_restitution_array, c_energy_loss_ratio_array, &
      & c_restitution_derivative_array
   public :: c_damping_for_restitution
   public :: c_hertz_constant, c_effective_mass, c_two_body_velocities
   public :: c_status_message, c_version, c_version_number, c_array_threads
   public :: message_length, last_status

   !> Length of every entry of the message table, the terminating NUL included
   integer, parameter :: message_length = len(status_texts) + 1
   !> Largest status code with a message of its own (hcimpact_status)
   integer, parameter :: last_status = max_status_code
   integer, private :: row_

   !> The texts of hcimpact_status (status_texts: codes 0 .. last_status, then the one
   !> for unknown codes), NUL-terminated for C. Never written: reading them from several
   !> threads at once is safe, and hcimpact_status_message returns pointers into this
   !> table.
   character(kind=c_char, len=message_length), target, save :: &
      & message_table(0:last_status + 1) = [character(kind=c_char, len=message_length) :: &
      & (trim(status_texts(row_)) // c_null_char, row_ = 0, last_status + 1)]

   !> The version string, NUL-terminated ("0.2.0"); never written
   character(kind=c_char, len=len(hcimpact_version_string) + 1), target, save :: &
      & version_text = hcimpact_version_string // c_null_char

contains

   ! ---------------------------------------------------------------------------
   ! Lambert W
   ! ---------------------------------------------------------------------------

   !> double hcimpact_lambert_w0(double z): W0(z) for z >= -1/e; NaN outside.
   function c_lambert_w0(z) result(w) bind(C, name="hcimpact_lambert_w0")
      !> Argument
      real(c_double), value, intent(in) :: z
      !> W0(z)
      real(c_double) :: w
      w = lambert_w0(z)
   end function c_lambert_w0

   !> double hcimpact_lambert_wm1(double z): W-1(z) for -1/e <= z < 0; NaN outside.
   function c_lambert_wm1(z) result(w) bind(C, name="hcimpact_lambert_wm1")
      !> Argument
      real(c_double), value, intent(in) :: z
      !> W-1(z)
      real(c_double) :: w
      w = lambert_wm1(z)
   end function c_lambert_wm1

   !> double hcimpact_lambert_w0p1(double t): 1 + W0(-exp(-1-t)) for t >= 0.
   function c_lambert_w0p1(t) result(v) bind(C, name="hcimpact_lambert_w0p1")
      !> Offset from the branch point, t >= 0
      real(c_double), value, intent(in) :: t
      !> 1 + W0
      real(c_double) :: v
      v = lambert_w0p1(t)
   end function c_lambert_w0p1

   !> double hcimpact_lambert_wm1p1(double t): 1 + W-1(-exp(-1-t)) for t >= 0.
   function c_lambert_wm1p1(t) result(v) bind(C, name="hcimpact_lambert_wm1p1")
      !> Offset from the branch point, t >= 0
      real(c_double), value, intent(in) :: t
      !> 1 + W-1
      real(c_double) :: v
      v = lambert_wm1p1(t)
   end function c_lambert_wm1p1

   !> int hcimpact_lambert_w0_array(int n, const double *z, double *w)
   function c_lambert_w0_array(n, z, w) result(stat) bind(C, name="hcimpact_lambert_w0_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double z[n]
      type(c_ptr), value, intent(in) :: z
      !> double w[n]
      type(c_ptr), value, intent(in) :: w
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, z, w, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = lambert_w0(x(i))
      end do
      !$omp end parallel do
   end function c_lambert_w0_array

   !> int hcimpact_lambert_wm1_array(int n, const double *z, double *w)
   function c_lambert_wm1_array(n, z, w) result(stat) bind(C, name="hcimpact_lambert_wm1_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double z[n]
      type(c_ptr), value, intent(in) :: z
      !> double w[n]
      type(c_ptr), value, intent(in) :: w
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, z, w, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = lambert_wm1(x(i))
      end do
      !$omp end parallel do
   end function c_lambert_wm1_array

   !> int hcimpact_lambert_w0p1_array(int n, const double *t, double *v)
   function c_lambert_w0p1_array(n, t, v) result(stat) &
         & bind(C, name="hcimpact_lambert_w0p1_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double t[n]
      type(c_ptr), value, intent(in) :: t
      !> double v[n]
      type(c_ptr), value, intent(in) :: v
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, t, v, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = lambert_w0p1(x(i))
      end do
      !$omp end parallel do
   end function c_lambert_w0p1_array

   !> int hcimpact_lambert_wm1p1_array(int n, const double *t, double *v)
   function c_lambert_wm1p1_array(n, t, v) result(stat) &
         & bind(C, name="hcimpact_lambert_wm1p1_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double t[n]
      type(c_ptr), value, intent(in) :: t
      !> double v[n]
      type(c_ptr), value, intent(in) :: v
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, t, v, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = lambert_wm1p1(x(i))
      end do
      !$omp end parallel do
   end function c_lambert_wm1p1_array

   ! ---------------------------------------------------------------------------
   ! Restitution, beta = b V
   ! ---------------------------------------------------------------------------

   !> double hcimpact_restitution(double beta): k(beta) for beta >= 0; NaN outside.
   function c_restitution(beta) result(k) bind(C, name="hcimpact_restitution")
      !> beta = b V >= 0
      real(c_double), value, intent(in) :: beta
      !> k
      real(c_double) :: k
      k = restitution(beta)
   end function c_restitution

   !> double hcimpact_restitution_inverse(double e): beta with k(beta) = e, 0 < e <= 1.
   function c_restitution_inverse(e) result(beta) bind(C, name="hcimpact_restitution_inverse")
      !> Target restitution
      real(c_double), value, intent(in) :: e
      !> beta
      real(c_double) :: beta
      beta = restitution_inverse(e)
   end function c_restitution_inverse

   !> double hcimpact_one_minus_restitution(double beta): 1 - k(beta) without cancellation.
   function c_one_minus_restitution(beta) result(d) &
         & bind(C, name="hcimpact_one_minus_restitution")
      !> beta = b V >= 0
      real(c_double), value, intent(in) :: beta
      !> 1 - k
      real(c_double) :: d
      d = one_minus_restitution(beta)
   end function c_one_minus_restitution

   !> double hcimpact_energy_loss_ratio(double beta): 1 - k(beta)^2.
   function c_energy_loss_ratio(beta) result(r) bind(C, name="hcimpact_energy_loss_ratio")
      !> beta = b V >= 0
      real(c_double), value, intent(in) :: beta
      !> 1 - k^2
      real(c_double) :: r
      r = energy_loss_ratio(beta)
   end function c_energy_loss_ratio

   !> double hcimpact_restitution_derivative(double beta): dk/dbeta (the sensitivity).
   function c_restitution_derivative(beta) result(dk) &
         & bind(C, name="hcimpact_restitution_derivative")
      !> beta = b V >= 0
      real(c_double), value, intent(in) :: beta
      !> dk/dbeta
      real(c_double) :: dk
      dk = restitution_derivative(beta)
   end function c_restitution_derivative

   !> double hcimpact_u_minus_log1p(double u): h(u) = u - ln(1 + u) for u > -1.
   function c_u_minus_log1p(u) result(h) bind(C, name="hcimpact_u_minus_log1p")
      !> u > -1
      real(c_double), value, intent(in) :: u
      !> h(u)
      real(c_double) :: h
      h = u_minus_log1p(u)
   end function c_u_minus_log1p

   !> int hcimpact_restitution_array(int n, const double *beta, double *k)
   function c_restitution_array(n, beta, k) result(stat) &
         & bind(C, name="hcimpact_restitution_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double beta[n]
      type(c_ptr), value, intent(in) :: beta
      !> double k[n]
      type(c_ptr), value, intent(in) :: k
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, beta, k, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = restitution(x(i))
      end do
      !$omp end parallel do
   end function c_restitution_array

   !> int hcimpact_restitution_inverse_array(int n, const double *e, double *beta)
   function c_restitution_inverse_array(n, e, beta) result(stat) &
         & bind(C, name="hcimpact_restitution_inverse_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double e[n]
      type(c_ptr), value, intent(in) :: e
      !> double beta[n]
      type(c_ptr), value, intent(in) :: beta
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, e, beta, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = restitution_inverse(x(i))
      end do
      !$omp end parallel do
   end function c_restitution_inverse_array

   !> int hcimpact_one_minus_restitution_array(int n, const double *beta, double *d)
   function c_one_minus_restitution_array(n, beta, d) result(stat) &
         & bind(C, name="hcimpact_one_minus_restitution_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double beta[n]
      type(c_ptr), value, intent(in) :: beta
      !> double d[n]
      type(c_ptr), value, intent(in) :: d
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, beta, d, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = one_minus_restitution(x(i))
      end do
      !$omp end parallel do
   end function c_one_minus_restitution_array

   !> int hcimpact_energy_loss_ratio_array(int n, const double *beta, double *r)
   function c_energy_loss_ratio_array(n, beta, r) result(stat) &
         & bind(C, name="hcimpact_energy_loss_ratio_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double beta[n]
      type(c_ptr), value, intent(in) :: beta
      !> double r[n]
      type(c_ptr), value, intent(in) :: r
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, beta, r, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = energy_loss_ratio(x(i))
      end do
      !$omp end parallel do
   end function c_energy_loss_ratio_array

   !> int hcimpact_restitution_derivative_array(int n, const double *beta, double *dk)
   function c_restitution_derivative_array(n, beta, dk) result(stat) &
         & bind(C, name="hcimpact_restitution_derivative_array")
      !> Number of elements, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double beta[n]
      type(c_ptr), value, intent(in) :: beta
      !> double dk[n]
      type(c_ptr), value, intent(in) :: dk
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: x(:), y(:)
      integer :: i
      stat = array_pair(n, beta, dk, x, y)
      if (stat /= hcimpact_ok) return
      !$omp parallel do if (size(x) >= min_parallel_cheap) schedule(static)
      do i = 1, size(x)
         y(i) = restitution_derivative(x(i))
      end do
      !$omp end parallel do
   end function c_restitution_derivative_array

   !> int hcimpact_damping_for_restitution(double e, double velocity, double min_velocity,
   !>                                      double *damping)
   !>
   !> b = beta(e)/max(V, min_velocity); statuses of hcimpact_impact_model's
   !> damping_for_restitution (NOT_FINITE, RESTITUTION, VELOCITY), NULL.
   function c_damping_for_restitution(e, velocity, min_velocity, damping) result(stat) &
         & bind(C, name="hcimpact_damping_for_restitution")
      !> Target restitution, 0 < e <= 1
      real(c_double), value, intent(in) :: e
      !> Approach speed in m/s, >= 0
      real(c_double), value, intent(in) :: velocity
      !> Speed in m/s below which b is computed at this speed, > 0
      real(c_double), value, intent(in) :: min_velocity
      !> double *damping: b in s/m
      type(c_ptr), value, intent(in) :: damping
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: b
      integer :: status
      if (.not. c_associated(damping)) then
         stat = hcimpact_err_null
         return
      end if
      call c_f_pointer(damping, b)
      call damping_for_restitution(real(e, wp), real(velocity, wp), b, status, &
         & min_velocity=real(min_velocity, wp))
      stat = int(status, c_int)
   end function c_damping_for_restitution

   ! ---------------------------------------------------------------------------
   ! Two bodies
   ! ---------------------------------------------------------------------------

   !> double hcimpact_hertz_constant(double young1, double poisson1, double radius1,
   !>                                double young2, double poisson2, double radius2)
   function c_hertz_constant(young1, poisson1, radius1, young2, poisson2, radius2) result(c) &
         & bind(C, name="hcimpact_hertz_constant")
      !> Young's modulus of body 1 in Pa
      real(c_double), value, intent(in) :: young1
      !> Poisson's ratio of body 1
      real(c_double), value, intent(in) :: poisson1
      !> Radius of body 1 in m (+inf: flat)
      real(c_double), value, intent(in) :: radius1
      !> Young's modulus of body 2 in Pa
      real(c_double), value, intent(in) :: young2
      !> Poisson's ratio of body 2
      real(c_double), value, intent(in) :: poisson2
      !> Radius of body 2 in m (+inf: flat)
      real(c_double), value, intent(in) :: radius2
      !> c in N/m^(3/2), NaN outside the domain
      real(c_double) :: c
      c = hertz_constant(young1, poisson1, radius1, young2, poisson2, radius2)
   end function c_hertz_constant

   !> double hcimpact_effective_mass(double mass1, double mass2): m1 m2/(m1 + m2).
   function c_effective_mass(mass1, mass2) result(m) bind(C, name="hcimpact_effective_mass")
      !> Mass of body 1 in kg, > 0 finite
      real(c_double), value, intent(in) :: mass1
      !> Mass of body 2 in kg, > 0 (+inf: immovable)
      real(c_double), value, intent(in) :: mass2
      !> Effective mass in kg, NaN outside the domain
      real(c_double) :: m
      m = effective_mass(mass1, mass2)
   end function c_effective_mass

   !> int hcimpact_two_body_velocities(double mass1, double mass2, double velocity1,
   !>     double velocity2, double restitution, double *velocity1_after,
   !>     double *velocity2_after)
   function c_two_body_velocities(mass1, mass2, velocity1, velocity2, restitution, &
         & velocity1_after, velocity2_after) result(stat) &
         & bind(C, name="hcimpact_two_body_velocities")
      !> Mass of body 1 in kg
      real(c_double), value, intent(in) :: mass1
      !> Mass of body 2 in kg (+inf allowed)
      real(c_double), value, intent(in) :: mass2
      !> Velocity of body 1 before the impact in m/s
      real(c_double), value, intent(in) :: velocity1
      !> Velocity of body 2 before the impact in m/s
      real(c_double), value, intent(in) :: velocity2
      !> Coefficient of restitution in [0, 1]
      real(c_double), value, intent(in) :: restitution
      !> double *: velocity of body 1 after the impact in m/s
      type(c_ptr), value, intent(in) :: velocity1_after
      !> double *: velocity of body 2 after the impact in m/s
      type(c_ptr), value, intent(in) :: velocity2_after
      !> Status
      integer(c_int) :: stat
      real(c_double), pointer :: v1, v2
      integer :: status
      if (.not. (c_associated(velocity1_after) .and. c_associated(velocity2_after))) then
         stat = hcimpact_err_null
         return
      end if
      call c_f_pointer(velocity1_after, v1)
      call c_f_pointer(velocity2_after, v2)
      call two_body_velocities(mass1, mass2, velocity1, velocity2, restitution, v1, v2, status)
      stat = int(status, c_int)
   end function c_two_body_velocities

   ! ---------------------------------------------------------------------------
   ! Status and version
   ! ---------------------------------------------------------------------------

   !> const char *hcimpact_status_message(int status): a pointer into a constant table
   !> (never NULL, never to be freed; unknown codes get "unknown status code").
   function c_status_message(status) result(message) bind(C, name="hcimpact_status_message")
      !> Status code
      integer(c_int), value, intent(in) :: status
      !> const char *
      type(c_ptr) :: message
      integer :: i
      i = last_status + 1
      if (status >= 0 .and. status <= last_status) i = int(status)
      message = c_loc(message_table(i))
   end function c_status_message

   !> const char *hcimpact_version(void): "major.minor.patch" (constant storage).
   function c_version() result(text) bind(C, name="hcimpact_version")
      !> const char *
      type(c_ptr) :: text
      text = c_loc(version_text)
   end function c_version

   !> int hcimpact_version_number(void): 10000*major + 100*minor + patch.
   function c_version_number() result(number) bind(C, name="hcimpact_version_number")
      !> Version number (HCIMPACT_VERSION of the header the library was built with)
      integer(c_int) :: number
      number = int(hcimpact_version_compact, c_int)
   end function c_version_number

   !> int hcimpact_array_threads(void): the number of threads the array forms share
   !> their elements among when called from here (OpenMP's; 1 without OpenMP).
   function c_array_threads() result(n) bind(C, name="hcimpact_array_threads")
      !> Number of threads
      integer(c_int) :: n
      n = int(array_threads(), c_int)
   end function c_array_threads

   ! ---------------------------------------------------------------------------
   ! Helpers
   ! ---------------------------------------------------------------------------

   !> Check an input and an output array of n doubles and point x and y at them.
   function array_pair(n, input, output, x, y) result(stat)
      !> Number of elements
      integer(c_int), intent(in) :: n
      !> const double input[n]
      type(c_ptr), intent(in) :: input
      !> double output[n]
      type(c_ptr), intent(in) :: output
      !> The input as a Fortran array (unassociated on error)
      real(c_double), pointer, intent(out) :: x(:)
      !> The output as a Fortran array (unassociated on error)
      real(c_double), pointer, intent(out) :: y(:)
      !> Status: ok, NULL or SIZE
      integer(c_int) :: stat
      x => null()
      y => null()
      if (.not. (c_associated(input) .and. c_associated(output))) then
         stat = hcimpact_err_null
      else if (n < 1) then
         stat = hcimpact_err_size
      else
         call c_f_pointer(input, x, [n])
         call c_f_pointer(output, y, [n])
         stat = hcimpact_ok
      end if
   end function array_pair

end module hcimpact_api
