! SPDX-License-Identifier: Apache-2.0
!> C interface of the calibration component: thin bind(C) wrappers of
!> hcimpact_calibration that check their pointers and copy the results out.
!>
!> Arrays are C arrays of `npoints` doubles. An optional array is a NULL pointer when
!> absent (Fortran 2018 `optional` dummies of a bind(C) procedure). The rule of the
!> whole C interface: a NULL required pointer (HCIMPACT_ERR_NULL) and a size error
!> (HCIMPACT_ERR_SIZE: npoints < 0, or too large for the memory the fit needs) write
!> nothing; on any other error every output that is not NULL is set to NaN.
!> Optional inputs are copied into allocatables (unallocated: absent; the copies
!> with stat=) before they are passed on: gfortran reads the address of an absent
!> explicit-shape array when it passes it to an assumed-shape dummy, which the
!> undefined-behaviour sanitizer reports. The declarations are in
!> include/hcimpact_lapack.h.
module hcimpact_calibration_api
   use, intrinsic :: iso_c_binding, only : c_double, c_int
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_null, hcimpact_err_size
   use hcimpact_calibration, only : fit_type, fit_damping, fit_damping_linear, &
      & fit_static, fit_elastic, fit_impact
   use hcimpact_work_arrays, only : allocate_copy
   implicit none
   private

   public :: c_fit_damping, c_fit_damping_linear, c_fit_static, c_fit_elastic, &
      & c_fit_impact

contains

   !> b (s/m) from restitution against speed with the exact law e = k(b V).
   function c_fit_damping(npoints, velocity, restitution, sigma, absolute_sigma, &
         & damping, standard_error, residuals) result(stat) &
         & bind(C, name="hcimpact_fit_damping")
      !> Number of points, >= 2
      integer(c_int), value, intent(in) :: npoints
      !> Approach speeds in m/s
      real(c_double), intent(in), optional :: velocity(npoints)
      !> Measured restitution
      real(c_double), intent(in), optional :: restitution(npoints)
      !> Standard deviations of the restitution, or NULL (estimated from the scatter)
      real(c_double), intent(in), optional :: sigma(npoints)
      !> Nonzero: sigma is absolute (no rescaling by chi^2/dof)
      integer(c_int), value, intent(in) :: absolute_sigma
      !> The fitted b in s/m
      real(c_double), intent(out), optional :: damping
      !> Its standard error in s/m, or NULL
      real(c_double), intent(out), optional :: standard_error
      !> Residuals e - k(b V), npoints, or NULL
      real(c_double), intent(out), optional :: residuals(npoints)
      !> Status
      integer(c_int) :: stat
      type(fit_type) :: fit
      real(wp), allocatable :: sigma_in(:)
      integer :: istat

      if (npoints < 0) then
         stat = hcimpact_err_size
         return
      end if
      if (.not. (present(velocity) .and. present(restitution) .and. present(damping))) then
         stat = hcimpact_err_null
         return
      end if
      istat = hcimpact_ok
      if (present(sigma)) call allocate_copy(sigma, sigma_in, istat)
      if (istat == hcimpact_ok) &
         & call fit_damping(velocity, restitution, fit, istat, sigma_in, absolute_sigma /= 0)
      stat = int(istat, c_int)
      if (istat == hcimpact_err_size) return
      if (istat /= hcimpact_ok) then
         damping = nan()
         if (present(standard_error)) standard_error = nan()
         if (present(residuals)) residuals = nan()
         return
      end if
      damping = fit%parameters(1)
      if (present(standard_error)) standard_error = fit%standard_errors(1)
      if (present(residuals)) residuals = fit%residuals
   end function c_fit_damping

   !> b = 3 alpha/2 (s/m) from the linear law e = 1 - alpha V (for comparison).
   function c_fit_damping_linear(npoints, velocity, restitution, sigma, absolute_sigma, &
         & damping, standard_error, residuals) result(stat) &
         & bind(C, name="hcimpact_fit_damping_linear")
      !> Number of points, >= 2
      integer(c_int), value, intent(in) :: npoints
      !> Approach speeds in m/s
      real(c_double), intent(in), optional :: velocity(npoints)
      !> Measured restitution
      real(c_double), intent(in), optional :: restitution(npoints)
      !> Standard deviations of the restitution, or NULL (estimated from the scatter)
      real(c_double), intent(in), optional :: sigma(npoints)
      !> Nonzero: sigma is absolute (no rescaling by chi^2/dof)
      integer(c_int), value, intent(in) :: absolute_sigma
      !> b = 3 alpha/2 in s/m
      real(c_double), intent(out), optional :: damping
      !> Its standard error in s/m, or NULL
      real(c_double), intent(out), optional :: standard_error
      !> Residuals e - (1 - alpha V), npoints, or NULL
      real(c_double), intent(out), optional :: residuals(npoints)
      !> Status
      integer(c_int) :: stat
      type(fit_type) :: fit
      real(wp), allocatable :: sigma_in(:)
      integer :: istat

      if (npoints < 0) then
         stat = hcimpact_err_size
         return
      end if
      if (.not. (present(velocity) .and. present(restitution) .and. present(damping))) then
         stat = hcimpact_err_null
         return
      end if
      istat = hcimpact_ok
      if (present(sigma)) call allocate_copy(sigma, sigma_in, istat)
      if (istat == hcimpact_ok) &
         & call fit_damping_linear(velocity, restitution, fit, istat, sigma_in, absolute_sigma /= 0)
      stat = int(istat, c_int)
      if (istat == hcimpact_err_size) return
      if (istat /= hcimpact_ok) then
         damping = nan()
         if (present(standard_error)) standard_error = nan()
         if (present(residuals)) residuals = nan()
         return
      end if
      damping = fit%parameters(1)
      if (present(standard_error)) standard_error = fit%standard_errors(1)
      if (present(residuals)) residuals = fit%residuals
   end function c_fit_damping_linear

   !> (c, n) of F = c x^n from a static force-deflection curve.
   function c_fit_static(npoints, deflection, force, sigma, absolute_sigma, parameters, &
         & covariance, residuals) result(stat) bind(C, name="hcimpact_fit_static")
      !> Number of points, >= 3
      integer(c_int), value, intent(in) :: npoints
      !> Deflections in m
      real(c_double), intent(in), optional :: deflection(npoints)
      !> Static forces in N
      real(c_double), intent(in), optional :: force(npoints)
      !> Standard deviations of the forces in N, or NULL (equal relative errors)
      real(c_double), intent(in), optional :: sigma(npoints)
      !> Nonzero: sigma is absolute (no rescaling by chi^2/dof)
      integer(c_int), value, intent(in) :: absolute_sigma
      !> c in N/m^n and n
      real(c_double), intent(out), optional :: parameters(2)
      !> Covariance of (c, n), 2 x 2, or NULL
      real(c_double), intent(out), optional :: covariance(2, 2)
      !> Residuals ln F - ln(c x^n), npoints, or NULL
      real(c_double), intent(out), optional :: residuals(npoints)
      !> Status
      integer(c_int) :: stat
      type(fit_type) :: fit
      real(wp), allocatable :: sigma_in(:)
      integer :: istat

      if (npoints < 0) then
         stat = hcimpact_err_size
         return
      end if
      if (.not. (present(deflection) .and. present(force) .and. present(parameters))) then
         stat = hcimpact_err_null
         return
      end if
      istat = hcimpact_ok
      if (present(sigma)) call allocate_copy(sigma, sigma_in, istat)
      if (istat == hcimpact_ok) &
         & call fit_static(deflection, force, fit, istat, sigma_in, absolute_sigma /= 0)
      stat = int(istat, c_int)
      if (istat == hcimpact_err_size) return
      if (istat /= hcimpact_ok) then
         parameters = nan()
         if (present(covariance)) covariance = nan()
         if (present(residuals)) residuals = nan()
         return
      end if
      parameters = fit%parameters
      if (present(covariance)) covariance = fit%covariance
      if (present(residuals)) residuals = fit%residuals
   end function c_fit_static

   !> (c, n) from contact times and/or peak forces against speed, b known.
   function c_fit_elastic(npoints, mass, damping, velocity, contact_time, peak_force, &
         & sigma_time, sigma_force, absolute_sigma, guess, parameters, covariance, &
         & residuals) result(stat) bind(C, name="hcimpact_fit_elastic")
      !> Number of speeds
      integer(c_int), value, intent(in) :: npoints
      !> Mass in kg
      real(c_double), value, intent(in) :: mass
      !> Damping b in s/m, >= 0
      real(c_double), value, intent(in) :: damping
      !> Approach speeds in m/s
      real(c_double), intent(in), optional :: velocity(npoints)
      !> Contact times in s, or NULL
      real(c_double), intent(in), optional :: contact_time(npoints)
      !> Peak forces in N, or NULL
      real(c_double), intent(in), optional :: peak_force(npoints)
      !> Standard deviations of the contact times in s, or NULL (estimated)
      real(c_double), intent(in), optional :: sigma_time(npoints)
      !> Standard deviations of the peak forces in N, or NULL (estimated)
      real(c_double), intent(in), optional :: sigma_force(npoints)
      !> Nonzero: the sigmas are absolute (no rescaling by chi^2/dof)
      integer(c_int), value, intent(in) :: absolute_sigma
      !> Starting values (c, n), or NULL (from the data)
      real(c_double), intent(in), optional :: guess(2)
      !> c in N/m^n and n
      real(c_double), intent(out), optional :: parameters(2)
      !> Covariance of (c, n), 2 x 2, or NULL
      real(c_double), intent(out), optional :: covariance(2, 2)
      !> Residuals (ln t, then ln F, for the series given), or NULL
      real(c_double), intent(out), optional :: residuals(*)
      !> Status
      integer(c_int) :: stat
      type(fit_type) :: fit
      real(wp), allocatable :: t(:), f(:), st(:), sf(:), g(:)
      integer :: istat, m

      ! (the number of residuals, 2 npoints at most, must fit an int)
      if (npoints < 0 .or. 2 * int(npoints, int64) > huge(npoints)) then
         stat = hcimpact_err_size
         return
      end if
      if (.not. (present(velocity) .and. present(parameters))) then
         stat = hcimpact_err_null
         return
      end if
      m = npoints * (count([present(contact_time), present(peak_force)]))
      istat = hcimpact_ok
      if (present(contact_time)) call allocate_copy(contact_time, t, istat)
      if (present(peak_force) .and. istat == hcimpact_ok) call allocate_copy(peak_force, f, istat)
      if (present(sigma_time) .and. istat == hcimpact_ok) &
         & call allocate_copy(sigma_time, st, istat)
      if (present(sigma_force) .and. istat == hcimpact_ok) &
         & call allocate_copy(sigma_force, sf, istat)
      if (present(guess)) g = guess
      if (istat == hcimpact_ok) call fit_elastic(mass, damping, velocity, fit, istat, t, f, &
         & st, sf, absolute_sigma /= 0, g)
      stat = int(istat, c_int)
      if (istat == hcimpact_err_size) return
      if (istat /= hcimpact_ok) then
         parameters = nan()
         if (present(covariance)) covariance = nan()
         if (present(residuals)) residuals(1:m) = nan()
         return
      end if
      parameters = fit%parameters
      if (present(covariance)) covariance = fit%covariance
      if (present(residuals)) residuals(1:m) = fit%residuals
   end function c_fit_elastic

   !> (c, n, b) from contact times, peak forces and restitution against speed.
   function c_fit_impact(npoints, mass, velocity, contact_time, peak_force, restitution, &
         & sigma_time, sigma_force, sigma_restitution, absolute_sigma, guess, parameters, &
         & covariance, residuals) result(stat) bind(C, name="hcimpact_fit_impact")
      !> Number of speeds
      integer(c_int), value, intent(in) :: npoints
      !> Mass in kg
      real(c_double), value, intent(in) :: mass
      !> Approach speeds in m/s
      real(c_double), intent(in), optional :: velocity(npoints)
      !> Contact times in s, or NULL
      real(c_double), intent(in), optional :: contact_time(npoints)
      !> Peak forces in N, or NULL
      real(c_double), intent(in), optional :: peak_force(npoints)
      !> Restitution, or NULL
      real(c_double), intent(in), optional :: restitution(npoints)
      !> Standard deviations of the contact times in s, or NULL (estimated)
      real(c_double), intent(in), optional :: sigma_time(npoints)
      !> Standard deviations of the peak forces in N, or NULL (estimated)
      real(c_double), intent(in), optional :: sigma_force(npoints)
      !> Standard deviations of the restitution, or NULL (estimated)
      real(c_double), intent(in), optional :: sigma_restitution(npoints)
      !> Nonzero: the sigmas are absolute (no rescaling by chi^2/dof)
      integer(c_int), value, intent(in) :: absolute_sigma
      !> Starting values (c, n, b), or NULL (from the data)
      real(c_double), intent(in), optional :: guess(3)
      !> c in N/m^n, n, b in s/m
      real(c_double), intent(out), optional :: parameters(3)
      !> Covariance of (c, n, b), 3 x 3, or NULL
      real(c_double), intent(out), optional :: covariance(3, 3)
      !> Residuals (ln t, ln F, e - k, for the series given), or NULL
      real(c_double), intent(out), optional :: residuals(*)
      !> Status
      integer(c_int) :: stat
      type(fit_type) :: fit
      real(wp), allocatable :: t(:), f(:), e(:), st(:), sf(:), se(:), g(:)
      integer :: istat, m

      ! (the number of residuals, 3 npoints at most, must fit an int)
      if (npoints < 0 .or. 3 * int(npoints, int64) > huge(npoints)) then
         stat = hcimpact_err_size
         return
      end if
      if (.not. (present(velocity) .and. present(parameters))) then
         stat = hcimpact_err_null
         return
      end if
      m = npoints * count([present(contact_time), present(peak_force), present(restitution)])
      istat = hcimpact_ok
      if (present(contact_time)) call allocate_copy(contact_time, t, istat)
      if (present(peak_force) .and. istat == hcimpact_ok) call allocate_copy(peak_force, f, istat)
      if (present(restitution) .and. istat == hcimpact_ok) &
         & call allocate_copy(restitution, e, istat)
      if (present(sigma_time) .and. istat == hcimpact_ok) &
         & call allocate_copy(sigma_time, st, istat)
      if (present(sigma_force) .and. istat == hcimpact_ok) &
         & call allocate_copy(sigma_force, sf, istat)
      if (present(sigma_restitution) .and. istat == hcimpact_ok) &
         & call allocate_copy(sigma_restitution, se, istat)
      if (present(guess)) g = guess
      if (istat == hcimpact_ok) call fit_impact(mass, velocity, fit, istat, t, f, e, st, sf, &
         & se, absolute_sigma /= 0, g)
      stat = int(istat, c_int)
      if (istat == hcimpact_err_size) return
      if (istat /= hcimpact_ok) then
         parameters = nan()
         if (present(covariance)) covariance = nan()
         if (present(residuals)) residuals(1:m) = nan()
         return
      end if
      parameters = fit%parameters
      if (present(covariance)) covariance = fit%covariance
      if (present(residuals)) residuals(1:m) = fit%residuals
   end function c_fit_impact

   !> A quiet NaN.
   function nan() result(x)
      real(wp) :: x
      x = ieee_value(1.0_wp, ieee_quiet_nan)
   end function nan

end module hcimpact_calibration_api
