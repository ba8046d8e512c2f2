! SPDX-License-Identifier: Apache-2.0
!> Calibration of the Hunt-Crossley contact model: fit it to measured data (issue #7).
!>
!> The fits, and what they return in `fit_type%parameters`:
!>
!> | procedure            | data                                   | parameters      |
!> |----------------------|----------------------------------------|-----------------|
!> | `fit_damping`        | restitution e_i at approach speeds V_i | b               |
!> | `fit_damping_linear` | the same, with the linear law e = 1 - (2b/3) V | b       |
!> | `fit_static`         | static force F_i at deflections x_i    | c, n            |
!> | `fit_elastic`        | contact time and/or peak force at V_i, b known | c, n    |
!> | `fit_impact`         | contact time, peak force, restitution at V_i | c, n, b   |
!>
!> Units: b in s/m, c in N/m^n, n dimensionless; V in m/s, x in m, F in N, times in s,
!> mass in kg.
!>
!> Models (doc/calibration.md has the derivations):
!> - Restitution: e = k(b V), the exact k of hcimpact_restitution_law (seed eq. 21).
!> - Static: ln F = ln c + n ln x, solved as weighted linear least squares (dgelsy).
!> - Impact: with X = [(n+1) m V^2/(2c)]^(1/(n+1)) and beta = b V,
!>       t_c = (X/V) tau(n, beta),   F_max = (m V^2/X) phi(n, beta),
!>   where tau and phi are the contact time and the peak force of the dimensionless
!>   impact (m = V = 1, c = (n+1)/2, so that X = 1), computed by hcimpact_impact_model.
!>   The derivatives in ln c are exact (-1/(n+1) and +1/(n+1)); those in n and beta are
!>   forward differences of tau and phi. Nonlinear least squares by Levenberg-Marquardt
!>   (hcimpact_least_squares) in the parameters (ln c, n, b), with b >= 0 and
!>   n >= min_exponent kept as bounds.
!>
!> Residuals, weights and uncertainties:
!> - Residuals are ln(observed) - ln(model) for times and forces (static and impact),
!>   observed - model for restitution. `fit%residuals` holds them unweighted, one block
!>   per series in the order time, force, restitution (only the series given).
!> - A series given with its standard deviations sigma_i (in the units of the data)
!>   is weighted by 1/sigma_i, converted to the residual's scale (sigma_i/y_i for a
!>   logarithm). A series given without them has one common sigma, estimated from its
!>   own residuals (leverage-corrected): a fit of several series is made with unit
!>   weights for those, then again with the estimated sigmas (two-step weighted least
!>   squares), so that each series weighs by its own scatter.
!> - covariance = (J^T W J)^-1 chi^2/(N - p) (the residual scatter sets the scale), or
!>   (J^T W J)^-1 alone with absolute_sigma = .true. (the sigmas are the true ones).
!>   For c the covariance is propagated from ln c to first order (sigma_c = c sigma_ln c).
!>
!> Errors (status codes of hcimpact_status; on error the fit holds no parameters):
!> hcimpact_err_size (arrays of different lengths), hcimpact_err_underdetermined (fewer
!> observations than parameters + 1, or data that cannot determine the parameters, such
!> as a contact-time-only fit at a single speed or a static curve at a single
!> deflection), hcimpact_err_not_finite, hcimpact_err_mass, hcimpact_err_velocity (a
!> speed <= 0), hcimpact_err_restitution (a restitution <= 0 or > 2), hcimpact_err_domain
!> (another non-positive value: a deflection, force, time or sigma; or a sigma more
!> than 1e100 times smaller or larger than its value, for restitution than 1),
!> hcimpact_err_damping (a given b < 0), hcimpact_err_no_convergence, and
!> hcimpact_err_size also when the work arrays for the data cannot be allocated (out
!> of memory, hcimpact_work_arrays: every array that grows with the data is allocated
!> with stat=).
!>
!> Time: linear in the number of points, but for the sorts behind the median start of
!> b and the count of distinct speeds or deflections (O(n log n), heapsort).
module hcimpact_calibration
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_velocity, hcimpact_err_damping, hcimpact_err_restitution, &
      & hcimpact_err_domain, hcimpact_err_size, hcimpact_err_underdetermined
   use hcimpact_restitution_law, only : restitution, restitution_derivative, &
      & restitution_inverse
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_least_squares, only : least_squares_model, levenberg_marquardt, &
      & linear_least_squares, jacobian_analysis
   use hcimpact_order_statistics, only : median_in_place, count_distinct_in_place
   use hcimpact_work_arrays, only : out_of_memory, allocate_copy
   implicit none
   private

   public :: fit_type
   public :: fit_damping, fit_damping_linear, fit_static, fit_elastic, fit_impact
   public :: min_exponent
   public :: hcimpact_err_underdetermined

   !> Smallest exponent n a fit may return (a lower bound of the iteration)
   real(wp), parameter :: min_exponent = 0.01_wp

   !> Points whose single-point b gives the starting value (damping_start)
   integer, parameter :: start_points = 4096

   !> The result of a fit.
   type :: fit_type
      !> Fitted parameters: (b) for fit_damping and fit_damping_linear; (c, n) for
      !> fit_static and fit_elastic; (c, n, b) for fit_impact. b in s/m, c in N/m^n
      real(wp), allocatable :: parameters(:)
      !> Standard errors of the parameters (square roots of the covariance diagonal)
      real(wp), allocatable :: standard_errors(:)
      !> Covariance matrix of the parameters (first order in c)
      real(wp), allocatable :: covariance(:, :)
      !> Residuals per observation, unweighted: ln(observed/model) for times and forces,
      !> observed - model for restitution; series in the order time, force, restitution
      real(wp), allocatable :: residuals(:)
      !> Scatter of each series' residuals: sqrt(sum r^2 / (N_k - leverage)), in the
      !> units of the residuals (relative for times and forces)
      real(wp), allocatable :: scatter(:)
      !> Weighted sum of squared residuals at the optimum
      real(wp) :: chi_square = 0.0_wp
      !> Observations minus parameters
      integer :: degrees_of_freedom = 0
      !> Levenberg-Marquardt steps taken (0 for the linear fits)
      integer :: iterations = 0
      !> Condition number of the column-scaled weighted Jacobian (or design matrix)
      real(wp) :: condition_number = 0.0_wp
   end type fit_type

   !> Largest measured restitution accepted (values above 1 are noise)
   real(wp), parameter :: max_restitution = 2.0_wp
   !> Largest |ln| of a sigma on the residual's scale (sigma, or sigma/value for times
   !> and forces): 1e-100 ... 1e100
   real(wp), parameter :: max_log_sigma = 230.2585092994046_wp

   !> Series of an impact data set, in the order of the residual blocks
   integer, parameter :: time_series = 1, force_series = 2, restitution_series = 3
   !> Parameters of the impact model, in the order of theta
   integer, parameter :: log_stiffness_index = 1, exponent_index = 2, damping_index = 3

   !> Impact data (contact time, peak force, restitution against speed) and the model
   !> of them, in the parameters (ln c, n, b) of which a subset is fitted.
   type, extends(least_squares_model) :: impact_data_model
      !> Mass in kg
      real(wp) :: mass = 1.0_wp
      !> Approach speeds (m/s) and their logarithms
      real(wp), allocatable :: velocity(:), log_velocity(:)
      !> Which series are present (time, force, restitution)
      logical :: has(3) = .false.
      !> ln(contact time / s), ln(peak force / N), restitution
      real(wp), allocatable :: log_time(:), log_force(:), restitution(:)
      !> Which of (ln c, n, b) are fitted, and the values of those that are not
      logical :: free(3) = .true.
      real(wp) :: fixed(3) = 0.0_wp
      !> ln tau and ln phi of the dimensionless impacts at (cache_n, cache_b)
      logical :: cached = .false.
      real(wp) :: cache_n = 0.0_wp, cache_b = 0.0_wp
      real(wp), allocatable :: log_tau(:), log_phi(:)
      !> Their derivatives in n and b at (deriv_n, deriv_b): they do not depend on c,
      !> and the fit asks for them again at the same point after each change of the
      !> weights
      logical :: deriv_cached = .false.
      real(wp) :: deriv_n = 0.0_wp, deriv_b = 0.0_wp
      real(wp), allocatable :: dlt_dn(:), dlf_dn(:), dlt_db(:), dlf_db(:)
   contains
      procedure :: evaluate => evaluate_impact_data
   end type impact_data_model

contains

   !> Fit the damping b to restitution measured at several approach speeds, with the
   !> exact law e = k(b V) (nonlinear least squares, Levenberg-Marquardt).
   !>
   !> Needs at least two points; they may all be at one speed. Measured e > 1 (noise
   !> on nearly elastic impacts) is accepted; the fitted b is kept >= 0.
   subroutine fit_damping(velocity, restitution, fit, stat, sigma, absolute_sigma)
      !> Approach speeds V_i in m/s, > 0
      real(wp), intent(in) :: velocity(:)
      !> Measured coefficients of restitution e_i, in (0, 2]
      real(wp), intent(in) :: restitution(:)
      !> The fit: parameters = (b) in s/m
      type(fit_type), intent(out) :: fit
      !> Status
      integer, intent(out) :: stat
      !> Standard deviations of the e_i, > 0 (default: estimated from the scatter)
      real(wp), intent(in), optional :: sigma(:)
      !> The sigmas are absolute: do not rescale the covariance by chi^2/dof
      logical, intent(in), optional :: absolute_sigma
      type(impact_data_model) :: model
      real(wp), allocatable :: theta(:), sigma_obs(:), sigma_in(:)
      logical :: given(1)
      integer :: n, alloc_stat
      real(wp) :: b0

      n = size(velocity)
      if (present(sigma)) then
         call allocate_copy(sigma, sigma_in, stat)
         if (stat /= hcimpact_ok) return
      end if
      stat = check_series(velocity, restitution, restitution_series, sigma_in, &
         & hcimpact_err_velocity)
      if (stat /= hcimpact_ok) return
      stat = check_count(n, 1, 1)
      if (stat /= hcimpact_ok) return

      call set_speeds(model, velocity, stat)
      if (stat /= hcimpact_ok) return
      model%has = [.false., .false., .true.]
      call allocate_copy(restitution, model%restitution, stat)
      if (stat /= hcimpact_ok) return
      model%free = [.false., .false., .true.]
      model%fixed = [0.0_wp, 1.0_wp, 0.0_wp]
      allocate(sigma_obs(n), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      call damping_start(velocity, restitution, b0, stat)
      if (stat /= hcimpact_ok) return
      theta = [b0]
      call series_sigma(restitution, restitution_series, sigma_in, sigma_obs, given(1))
      call run_fit(model, theta, [0.0_wp], [restitution_series], sigma_obs, given, &
         & flag(absolute_sigma), fit, stat)
      if (stat /= hcimpact_ok) return
      fit%parameters = theta
      call finish_errors(fit)
   end subroutine fit_damping

   !> Fit the linear law e = 1 - alpha V, common practice for small damping, and
   !> return b = 3 alpha/2 (the slope of the exact k at beta = 0 is -2/3): linear least
   !> squares through e = 1 at V = 0 (dgelsy). For comparison with `fit_damping`: on
   !> data that follow the exact law this b is biased low (doc/calibration.md).
   subroutine fit_damping_linear(velocity, restitution, fit, stat, sigma, absolute_sigma)
      !> Approach speeds V_i in m/s, > 0
      real(wp), intent(in) :: velocity(:)
      !> Measured coefficients of restitution e_i, in (0, 2]
      real(wp), intent(in) :: restitution(:)
      !> The fit: parameters = (b) in s/m, b = 3 alpha/2
      type(fit_type), intent(out) :: fit
      !> Status
      integer, intent(out) :: stat
      !> Standard deviations of the e_i, > 0 (default: estimated from the scatter)
      real(wp), intent(in), optional :: sigma(:)
      !> The sigmas are absolute: do not rescale the covariance by chi^2/dof
      logical, intent(in), optional :: absolute_sigma
      real(wp) :: coef(1), cov(1, 1)
      real(wp), allocatable :: a(:, :), w(:), rhs(:), sigma_in(:)
      real(wp) :: alpha, factor
      integer :: n, rank, alloc_stat
      logical :: given

      n = size(velocity)
      if (present(sigma)) then
         call allocate_copy(sigma, sigma_in, stat)
         if (stat /= hcimpact_ok) return
      end if
      stat = check_series(velocity, restitution, restitution_series, sigma_in, &
         & hcimpact_err_velocity)
      if (stat /= hcimpact_ok) return
      stat = check_count(n, 1, 1)
      if (stat /= hcimpact_ok) return

      ! (allocatables with stat=: automatic arrays of the data's size came from an
      ! unchecked malloc, and out of memory this dereferenced NULL)
      allocate(a(n, 1), w(n), rhs(n), fit%residuals(n), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      call series_sigma(restitution, restitution_series, sigma_in, w, given)
      w = 1.0_wp / w
      a(:, 1) = w * velocity
      rhs = w * (1.0_wp - restitution)
      call linear_least_squares(a, rhs, coef, rank, stat)
      if (stat /= hcimpact_ok) return
      alpha = coef(1)
      fit%residuals = restitution - (1.0_wp - alpha * velocity)
      fit%chi_square = sum((w * fit%residuals)**2)
      fit%degrees_of_freedom = n - 1
      call jacobian_analysis(a, cov, stat, fit%condition_number)
      if (stat /= hcimpact_ok) return
      factor = 1.0_wp
      if (.not. (given .and. flag(absolute_sigma))) &
         & factor = fit%chi_square / fit%degrees_of_freedom
      fit%parameters = [1.5_wp * alpha]
      fit%covariance = 2.25_wp * factor * cov
      fit%scatter = [sqrt(sum(fit%residuals**2) / (n - 1))]
      call finish_errors(fit)
   end subroutine fit_damping_linear

   !> Fit the elastic law F = c x^n to a static force-deflection curve: weighted linear
   !> least squares on ln F = ln c + n ln x (dgelsy), with ln x centred on its weighted
   !> mean (so that the two columns are orthogonal).
   !>
   !> Without sigma all points weigh the same in ln F: equal relative errors. Needs at
   !> least three points at no fewer than two different deflections.
   subroutine fit_static(deflection, force, fit, stat, sigma, absolute_sigma)
      !> Deflections x_i in m, > 0
      real(wp), intent(in) :: deflection(:)
      !> Static forces F_i in N, > 0
      real(wp), intent(in) :: force(:)
      !> The fit: parameters = (c, n), c in N/m^n
      type(fit_type), intent(out) :: fit
      !> Status
      integer, intent(out) :: stat
      !> Standard deviations of the forces in N, > 0 (default: equal relative errors,
      !> their size estimated from the scatter)
      real(wp), intent(in), optional :: sigma(:)
      !> The sigmas are absolute: do not rescale the covariance by chi^2/dof
      logical, intent(in), optional :: absolute_sigma
      real(wp) :: coef(2), cov(2, 2)
      real(wp), allocatable :: a(:, :), w(:), lx(:), lf(:), rhs(:), sigma_in(:)
      real(wp) :: mean_lx, log_c, factor, t(2, 2)
      integer :: n, rank, alloc_stat, distinct
      logical :: given

      n = size(deflection)
      if (present(sigma)) then
         call allocate_copy(sigma, sigma_in, stat)
         if (stat /= hcimpact_ok) return
      end if
      ! (finiteness first: a NaN deflection is hcimpact_err_not_finite, not _domain)
      stat = check_series(deflection, force, force_series, sigma_in, hcimpact_err_domain)
      if (stat /= hcimpact_ok) return
      stat = check_count(n, 2, 1)
      if (stat /= hcimpact_ok) return
      allocate(a(n, 2), w(n), lx(n), lf(n), rhs(n), fit%residuals(n), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      ! (lx as scratch: the count sorts it)
      lx = deflection
      call count_distinct_in_place(lx, distinct)
      if (distinct < 2) then
         stat = hcimpact_err_underdetermined
         return
      end if

      call series_sigma(force, force_series, sigma_in, w, given)
      w = 1.0_wp / w
      lx = log(deflection)
      lf = log(force)
      mean_lx = sum(w**2 * lx) / sum(w**2)
      a(:, 1) = w
      a(:, 2) = w * (lx - mean_lx)
      rhs = w * lf
      call linear_least_squares(a, rhs, coef, rank, stat)
      if (stat /= hcimpact_ok) return
      log_c = coef(1) - coef(2) * mean_lx
      fit%residuals = lf - (coef(1) + coef(2) * (lx - mean_lx))
      fit%chi_square = sum((w * fit%residuals)**2)
      fit%degrees_of_freedom = n - 2
      call jacobian_analysis(a, cov, stat, fit%condition_number)
      if (stat /= hcimpact_ok) return
      factor = 1.0_wp
      if (.not. (given .and. flag(absolute_sigma))) &
         & factor = fit%chi_square / fit%degrees_of_freedom
      ! from (ln c + n mean, n) to (ln c, n), then to (c, n) at first order
      t = reshape([1.0_wp, 0.0_wp, -mean_lx, 1.0_wp], [2, 2])
      cov = factor * matmul(t, matmul(cov, transpose(t)))
      fit%parameters = [exp(log_c), coef(2)]
      if (.not. ieee_is_finite(fit%parameters(1))) then
         stat = hcimpact_err_domain
         return
      end if
      fit%covariance = log_to_linear(cov, fit%parameters, [.true., .false.])
      fit%scatter = [sqrt(sum(fit%residuals**2) / (n - 2))]
      call finish_errors(fit)
   end subroutine fit_static

   !> Fit the elastic law (c, n) to impact data, the damping b being known: contact
   !> times and/or peak forces measured at several approach speeds.
   !>
   !> Either series may be absent, not both. With one series the speeds must differ
   !> (at a single speed it cannot separate c from n); contact time and peak force
   !> together determine (c, n) even at one speed (F t/(m V) depends on n and b V only).
   subroutine fit_elastic(mass, damping, velocity, fit, stat, contact_time, peak_force, &
         & sigma_time, sigma_force, absolute_sigma, guess)
      !> Mass in kg (the effective mass for two bodies), > 0
      real(wp), intent(in) :: mass
      !> Damping b in s/m, >= 0 (0: elastic impacts)
      real(wp), intent(in) :: damping
      !> Approach speeds V_i in m/s, > 0
      real(wp), intent(in) :: velocity(:)
      !> The fit: parameters = (c, n), c in N/m^n
      type(fit_type), intent(out) :: fit
      !> Status
      integer, intent(out) :: stat
      !> Measured contact times in s, > 0
      real(wp), intent(in), optional :: contact_time(:)
      !> Measured peak forces in N, > 0
      real(wp), intent(in), optional :: peak_force(:)
      !> Standard deviations of the contact times in s (default: estimated)
      real(wp), intent(in), optional :: sigma_time(:)
      !> Standard deviations of the peak forces in N (default: estimated)
      real(wp), intent(in), optional :: sigma_force(:)
      !> The sigmas are absolute: do not rescale the covariance by chi^2/dof
      logical, intent(in), optional :: absolute_sigma
      !> Starting values (c, n) (default: from the data)
      real(wp), intent(in), optional :: guess(:)

      real(wp), allocatable :: t(:), f(:), e(:), st(:), sf(:), se(:), g(:)

      if (.not. ieee_is_finite(damping)) then
         stat = hcimpact_err_not_finite
         return
      end if
      if (damping < 0.0_wp) then
         stat = hcimpact_err_damping
         return
      end if
      ! optional arrays travel on as allocatables (unallocated: absent): an absent
      ! optional array is never passed on (gfortran reads its descriptor's address)
      stat = hcimpact_ok
      if (present(contact_time)) call allocate_copy(contact_time, t, stat)
      if (present(peak_force) .and. stat == hcimpact_ok) call allocate_copy(peak_force, f, stat)
      if (present(sigma_time) .and. stat == hcimpact_ok) call allocate_copy(sigma_time, st, stat)
      if (present(sigma_force) .and. stat == hcimpact_ok) &
         & call allocate_copy(sigma_force, sf, stat)
      if (present(guess)) g = guess
      if (stat /= hcimpact_ok) return
      call fit_impact_data(mass, velocity, .false., damping, fit, stat, t, f, e, st, sf, se, &
         & flag(absolute_sigma), g)
   end subroutine fit_elastic

   !> Fit the contact law and the damping (c, n, b) jointly to impact data: contact
   !> times, peak forces and restitution measured at several approach speeds.
   !>
   !> Any of the three series may be absent as long as the rest determine the three
   !> parameters (e.g. restitution alone determines b only: status
   !> hcimpact_err_underdetermined).
   subroutine fit_impact(mass, velocity, fit, stat, contact_time, peak_force, &
         & restitution, sigma_time, sigma_force, sigma_restitution, absolute_sigma, guess)
      !> Mass in kg (the effective mass for two bodies), > 0
      real(wp), intent(in) :: mass
      !> Approach speeds V_i in m/s, > 0
      real(wp), intent(in) :: velocity(:)
      !> The fit: parameters = (c, n, b), c in N/m^n, b in s/m
      type(fit_type), intent(out) :: fit
      !> Status
      integer, intent(out) :: stat
      !> Measured contact times in s, > 0
      real(wp), intent(in), optional :: contact_time(:)
      !> Measured peak forces in N, > 0
      real(wp), intent(in), optional :: peak_force(:)
      !> Measured coefficients of restitution, in (0, 2]
      real(wp), intent(in), optional :: restitution(:)
      !> Standard deviations of the contact times in s (default: estimated)
      real(wp), intent(in), optional :: sigma_time(:)
      !> Standard deviations of the peak forces in N (default: estimated)
      real(wp), intent(in), optional :: sigma_force(:)
      !> Standard deviations of the restitution (default: estimated)
      real(wp), intent(in), optional :: sigma_restitution(:)
      !> The sigmas are absolute: do not rescale the covariance by chi^2/dof
      logical, intent(in), optional :: absolute_sigma
      !> Starting values (c, n, b) (default: from the data)
      real(wp), intent(in), optional :: guess(:)

      real(wp), allocatable :: t(:), f(:), e(:), st(:), sf(:), se(:), g(:)

      stat = hcimpact_ok
      if (present(contact_time)) call allocate_copy(contact_time, t, stat)
      if (present(peak_force) .and. stat == hcimpact_ok) call allocate_copy(peak_force, f, stat)
      if (present(restitution) .and. stat == hcimpact_ok) &
         & call allocate_copy(restitution, e, stat)
      if (present(sigma_time) .and. stat == hcimpact_ok) call allocate_copy(sigma_time, st, stat)
      if (present(sigma_force) .and. stat == hcimpact_ok) &
         & call allocate_copy(sigma_force, sf, stat)
      if (present(sigma_restitution) .and. stat == hcimpact_ok) &
         & call allocate_copy(sigma_restitution, se, stat)
      if (present(guess)) g = guess
      if (stat /= hcimpact_ok) return
      call fit_impact_data(mass, velocity, .true., 0.0_wp, fit, stat, t, f, e, st, sf, se, &
         & flag(absolute_sigma), g)
   end subroutine fit_impact

   !> The impact fits: (ln c, n) and, when fit_b, b. The series, sigmas and guess are
   !> absent when not allocated.
   subroutine fit_impact_data(mass, velocity, fit_b, damping, fit, stat, contact_time, &
         & peak_force, restitution, sigma_time, sigma_force, sigma_restitution, &
         & absolute_sigma, guess)
      real(wp), intent(in) :: mass, damping
      real(wp), intent(in) :: velocity(:)
      logical, intent(in) :: fit_b
      type(fit_type), intent(out) :: fit
      integer, intent(out) :: stat
      real(wp), allocatable, intent(in) :: contact_time(:), peak_force(:), restitution(:)
      real(wp), allocatable, intent(in) :: sigma_time(:), sigma_force(:), &
         & sigma_restitution(:)
      logical, intent(in) :: absolute_sigma
      real(wp), allocatable, intent(in) :: guess(:)
      type(impact_data_model) :: model
      real(wp), allocatable :: theta(:), lower(:), sigma_obs(:), r(:)
      integer, allocatable :: series(:)
      logical, allocatable :: given(:)
      integer :: n, p, nseries, k, i, alloc_stat
      real(wp) :: b0, n0, total

      n = size(velocity)
      p = merge(3, 2, fit_b)
      if (.not. ieee_is_finite(mass)) then
         stat = hcimpact_err_not_finite
         return
      end if
      if (.not. mass > 0.0_wp) then
         stat = hcimpact_err_mass
         return
      end if
      if (.not. (allocated(contact_time) .or. allocated(peak_force) .or. &
         & (fit_b .and. allocated(restitution)))) then
         stat = hcimpact_err_underdetermined
         return
      end if
      if (allocated(guess)) then
         if (size(guess) /= p) then
            stat = hcimpact_err_size
            return
         end if
         if (.not. all(ieee_is_finite(guess))) then
            stat = hcimpact_err_not_finite
            return
         end if
         if (.not. (guess(1) > 0.0_wp .and. guess(2) > 0.0_wp)) then
            stat = hcimpact_err_domain
            return
         end if
         if (fit_b) then
            if (guess(3) < 0.0_wp) then
               stat = hcimpact_err_damping
               return
            end if
         end if
      end if

      model%mass = mass
      ! the series given, in the order of the residual blocks
      nseries = count([allocated(contact_time), allocated(peak_force), &
         & allocated(restitution) .and. fit_b])
      allocate(series(nseries), given(nseries))
      allocate(sigma_obs(n * nseries), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      k = 0
      stat = hcimpact_ok
      if (allocated(contact_time)) then
         call add_series(time_series, contact_time, sigma_time)
         if (stat /= hcimpact_ok) return
         call allocate_copy(contact_time, model%log_time, stat)
         if (stat /= hcimpact_ok) return
         model%log_time = log(model%log_time)
      end if
      if (allocated(peak_force)) then
         call add_series(force_series, peak_force, sigma_force)
         if (stat /= hcimpact_ok) return
         call allocate_copy(peak_force, model%log_force, stat)
         if (stat /= hcimpact_ok) return
         model%log_force = log(model%log_force)
      end if
      if (allocated(restitution) .and. fit_b) then
         call add_series(restitution_series, restitution, sigma_restitution)
         if (stat /= hcimpact_ok) return
         call allocate_copy(restitution, model%restitution, stat)
         if (stat /= hcimpact_ok) return
      end if
      stat = check_count(n * nseries, p, 1)
      if (stat /= hcimpact_ok) return
      if (n < 1) then
         stat = hcimpact_err_underdetermined
         return
      end if

      call set_speeds(model, velocity, stat)
      if (stat /= hcimpact_ok) return
      model%free = [.true., .true., fit_b]
      model%fixed = [0.0_wp, 0.0_wp, damping]

      ! starting values: b from the restitution, n from the slopes, then ln c
      if (allocated(guess)) then
         theta = [log(guess(1)), guess(2:p)]
      else
         b0 = damping
         if (fit_b) then
            b0 = 0.0_wp
            if (model%has(restitution_series)) then
               call damping_start(velocity, restitution, b0, stat)
               if (stat /= hcimpact_ok) return
            end if
         end if
         call exponent_estimate(model, n0, stat)
         if (stat /= hcimpact_ok) return
         theta = [0.0_wp, n0]
         if (fit_b) theta = [theta, b0]
         allocate(r(n * nseries), stat=alloc_stat)
         if (alloc_stat /= 0) then
            stat = out_of_memory
            return
         end if
         call model%evaluate(theta, r, stat)
         if (stat /= hcimpact_ok) return
         ! residual of ln t falls by ln c/(n+1), that of ln F rises by it: ln c is the
         ! mean of -(n+1) r over the times and (n+1) r over the forces (summed in order)
         total = 0.0_wp
         k = 0
         if (model%has(time_series)) then
            do i = 1, n
               total = total + (-(n0 + 1.0_wp) * r(i))
            end do
            k = n
         end if
         if (model%has(force_series)) then
            do i = k + 1, k + n
               total = total + (n0 + 1.0_wp) * r(i)
            end do
            k = k + n
         end if
         if (k > 0) theta(1) = total / k
      end if

      allocate(lower(p))
      lower(1:2) = [-huge(1.0_wp), min_exponent]
      if (fit_b) lower(3) = 0.0_wp
      theta(2) = max(theta(2), min_exponent)
      call run_fit(model, theta, lower, series, sigma_obs, given, absolute_sigma, &
         & fit, stat)
      if (stat /= hcimpact_ok) return
      fit%parameters = [exp(theta(1)), theta(2:p)]
      if (.not. ieee_is_finite(fit%parameters(1))) then
         stat = hcimpact_err_domain
         return
      end if
      fit%covariance = log_to_linear(fit%covariance, fit%parameters, &
         & [.true., spread(.false., 1, p - 1)])
      call finish_errors(fit)

   contains

      !> Check one series and enter it as the next of the model's list (k).
      subroutine add_series(kind, values, sigma)
         integer, intent(in) :: kind
         real(wp), intent(in) :: values(:)
         real(wp), allocatable, intent(in) :: sigma(:)
         stat = check_series(velocity, values, kind, sigma, hcimpact_err_velocity)
         if (stat /= hcimpact_ok) return
         k = k + 1
         model%has(kind) = .true.
         series(k) = kind
         call series_sigma(values, kind, sigma, sigma_obs((k - 1) * n + 1:k * n), given(k))
      end subroutine add_series

   end subroutine fit_impact_data

   !> The exponent n from the slopes of ln t and ln F against ln V in the elastic
   !> limit (t ~ V^((1-n)/(n+1)), F ~ V^(2n/(n+1))); 3/2 when the speeds do not vary
   !> or the slopes are implausible. stat: hcimpact_ok or out_of_memory.
   subroutine exponent_estimate(model, n0, stat)
      type(impact_data_model), intent(in) :: model
      real(wp), intent(out) :: n0
      integer, intent(out) :: stat
      real(wp), allocatable :: speeds(:)
      real(wp) :: s, total
      integer :: count_ok, distinct

      n0 = 1.5_wp
      call allocate_copy(model%velocity, speeds, stat)
      if (stat /= hcimpact_ok) return
      call count_distinct_in_place(speeds, distinct)
      if (distinct < 2) return
      total = 0.0_wp
      count_ok = 0
      if (model%has(time_series)) then
         s = slope(model%log_velocity, model%log_time)
         if (1.0_wp + s > 0.0_wp) call take((1.0_wp - s) / (1.0_wp + s))
      end if
      if (model%has(force_series)) then
         s = slope(model%log_velocity, model%log_force)
         if (2.0_wp - s > 0.0_wp) call take(s / (2.0_wp - s))
      end if
      if (count_ok > 0) n0 = total / count_ok
   contains
      subroutine take(value)
         real(wp), intent(in) :: value
         if (value >= 0.1_wp .and. value <= 10.0_wp) then
            total = total + value
            count_ok = count_ok + 1
         end if
      end subroutine take
   end subroutine exponent_estimate

   !> Least-squares slope of y against x (x not all equal).
   pure function slope(x, y) result(s)
      real(wp), intent(in) :: x(:), y(:)
      real(wp) :: s
      real(wp) :: mean_x
      mean_x = sum(x) / size(x)
      s = sum((x - mean_x) * y) / sum((x - mean_x)**2)
   end function slope

   !> Fit `theta` of `model`, weighting each series by its given sigmas or by its own
   !> estimated scatter, and fill the statistics of `fit` for theta (covariance in
   !> theta's own coordinates).
   subroutine run_fit(model, theta, lower, series, sigma_obs, given, absolute, fit, stat)
      class(impact_data_model), intent(inout) :: model
      real(wp), intent(inout) :: theta(:)
      real(wp), intent(in) :: lower(:)
      !> Kind of each series present, in the order of the residual blocks
      integer, intent(in) :: series(:)
      !> Given sigma of each observation, in residual units (ignored where not given)
      real(wp), intent(in) :: sigma_obs(:)
      !> Whether each series came with sigmas
      logical, intent(in) :: given(:)
      logical, intent(in) :: absolute
      type(fit_type), intent(inout) :: fit
      integer, intent(out) :: stat
      real(wp), allocatable :: weight(:), scale(:), new_scale(:), r(:), jac(:, :), &
         & leverage(:), cov(:, :)
      integer :: m, p, nk, iterations, alloc_stat

      m = size(sigma_obs)
      p = size(theta)
      nk = m / size(series)
      allocate(scale(size(series)), source=1.0_wp)
      allocate(new_scale(size(series)), cov(p, p))
      allocate(r(m), jac(m, p), leverage(m), weight(m), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      call observation_weights()
      call levenberg_marquardt(model, theta, weight, lower, stat, fit%iterations)
      if (stat /= hcimpact_ok) return
      if (size(series) > 1 .and. .not. all(given)) then
         ! two-step weighting: the scales of the series without sigmas from the first
         ! fit's residuals, then the fit again with them. (Iterating this to a fixed
         ! point gains nothing in accuracy and can creep for many passes.)
         call statistics()
         if (stat /= hcimpact_ok) return
         scale = new_scale
         call observation_weights()
         call levenberg_marquardt(model, theta, weight, lower, stat, iterations)
         fit%iterations = fit%iterations + iterations
         if (stat /= hcimpact_ok) return
      end if
      call statistics()
      if (stat /= hcimpact_ok) return
      fit%chi_square = sum((weight * r)**2)
      call move_alloc(r, fit%residuals)
      fit%scatter = new_scale
      fit%degrees_of_freedom = m - p
      fit%covariance = cov
      if (.not. (absolute .and. all(given))) &
         & fit%covariance = cov * (fit%chi_square / fit%degrees_of_freedom)

   contains

      !> weight = 1/sigma of each observation: the given one, or the series' estimated
      !> scale.
      subroutine observation_weights()
         integer :: kk
         do kk = 1, size(series)
            if (given(kk)) then
               weight((kk-1)*nk+1:kk*nk) = 1.0_wp / sigma_obs((kk-1)*nk+1:kk*nk)
            else
               weight((kk-1)*nk+1:kk*nk) = 1.0_wp / scale(kk)
            end if
         end do
      end subroutine observation_weights

      !> Residuals, covariance, leverages and each series' scatter at theta.
      subroutine statistics()
         integer :: kk, j
         real(wp) :: dof
         call model%evaluate(theta, r, stat, jac)
         if (stat /= hcimpact_ok) return
         do j = 1, p
            jac(:, j) = weight * jac(:, j)
         end do
         call jacobian_analysis(jac, cov, stat, fit%condition_number, leverage)
         if (stat /= hcimpact_ok) return
         do kk = 1, size(series)
            dof = nk - sum(leverage((kk-1)*nk+1:kk*nk))
            new_scale(kk) = sqrt(sum(r((kk-1)*nk+1:kk*nk)**2) / max(dof, 0.5_wp))
            new_scale(kk) = max(new_scale(kk), epsilon(1.0_wp))
         end do
      end subroutine statistics

   end subroutine run_fit

   !> Residuals of the impact data at theta (the free ones of ln c, n, b) and, on
   !> request, their Jacobian. Element by element: no array of the data's size
   !> besides the model's own (allocated with stat=).
   subroutine evaluate_impact_data(self, theta, residual, stat, jacobian)
      !> The data and model
      class(impact_data_model), intent(inout) :: self
      !> Free parameters, in the order (ln c, n, b)
      real(wp), intent(in) :: theta(:)
      !> Residuals: ln t - ln t_model, ln F - ln F_model, e - k, per series present
      real(wp), intent(out) :: residual(:)
      !> Status
      integer, intent(out) :: stat
      !> d residual / d theta
      real(wp), intent(out), optional :: jacobian(:, :)
      real(wp) :: p(3), log_c, n, b, np1, log_x, dlogx_dn
      integer :: nv, i, row, alloc_stat, col(3)
      logical :: dynamic

      nv = size(self%velocity)
      p = unpack(theta, self%free, self%fixed)
      log_c = p(log_stiffness_index)
      n = p(exponent_index)
      b = p(damping_index)
      np1 = n + 1.0_wp
      dynamic = self%has(time_series) .or. self%has(force_series)
      stat = hcimpact_ok
      if (.not. (n > 0.0_wp .and. b >= 0.0_wp)) then
         stat = hcimpact_err_domain
         return
      end if

      if (dynamic) then
         if (.not. (self%cached .and. n == self%cache_n .and. b == self%cache_b)) then
            self%cached = .false.
            if (allocated(self%log_tau)) deallocate(self%log_tau, self%log_phi)
            allocate(self%log_tau(nv), self%log_phi(nv), stat=alloc_stat)
            if (alloc_stat /= 0) then
               stat = out_of_memory
               return
            end if
            do i = 1, nv
               call scaled_impact(n, b * self%velocity(i), self%log_tau(i), &
                  & self%log_phi(i), stat)
               if (stat /= hcimpact_ok) return
            end do
            self%cached = .true.
            self%cache_n = n
            self%cache_b = b
         end if
      end if

      row = 0
      if (self%has(time_series)) then
         do i = 1, nv
            ! ln t = ln X - ln V + ln tau
            residual(row + i) = self%log_time(i) - (scaled_log_x(i) &
               & - self%log_velocity(i) + self%log_tau(i))
         end do
         row = row + nv
      end if
      if (self%has(force_series)) then
         do i = 1, nv
            ! ln F = ln m + 2 ln V - ln X + ln phi
            residual(row + i) = self%log_force(i) - (log(self%mass) &
               & + 2.0_wp * self%log_velocity(i) - scaled_log_x(i) + self%log_phi(i))
         end do
         row = row + nv
      end if
      if (self%has(restitution_series)) then
         do i = 1, nv
            residual(row + i) = self%restitution(i) - restitution(b * self%velocity(i))
         end do
      end if
      if (.not. present(jacobian)) return

      ! the column of each free parameter (0: fixed)
      col = 0
      do i = 1, 3
         if (self%free(i)) col(i) = count(self%free(1:i))
      end do
      jacobian = 0.0_wp
      if (dynamic) then
         call scaled_derivatives(self, n, b, stat)
         if (stat /= hcimpact_ok) return
      end if
      row = 0
      if (self%has(time_series)) then
         do i = 1, nv
            ! d ln X/d n = (1 - (n+1) ln X)/(n+1)^2, d ln X/d ln c = -1/(n+1)
            log_x = scaled_log_x(i)
            dlogx_dn = (1.0_wp - np1 * log_x) / np1**2
            call put(row + i, log_stiffness_index, 1.0_wp / np1)
            call put(row + i, exponent_index, -(dlogx_dn + self%dlt_dn(i)))
            call put(row + i, damping_index, -self%dlt_db(i))
         end do
         row = row + nv
      end if
      if (self%has(force_series)) then
         do i = 1, nv
            log_x = scaled_log_x(i)
            dlogx_dn = (1.0_wp - np1 * log_x) / np1**2
            call put(row + i, log_stiffness_index, -1.0_wp / np1)
            call put(row + i, exponent_index, -(-dlogx_dn + self%dlf_dn(i)))
            call put(row + i, damping_index, -self%dlf_db(i))
         end do
         row = row + nv
      end if
      if (self%has(restitution_series)) then
         do i = 1, nv
            call put(row + i, damping_index, &
               & -self%velocity(i) * restitution_derivative(b * self%velocity(i)))
         end do
      end if

   contains

      !> ln X = ln((n+1) m V^2/(2c))/(n+1) at speed i
      pure function scaled_log_x(i) result(value)
         integer, intent(in) :: i
         real(wp) :: value
         value = (log(0.5_wp * np1) + log(self%mass) + 2.0_wp * self%log_velocity(i) &
            & - log_c) / np1
      end function scaled_log_x

      !> d residual(row)/d parameter, when the parameter is free
      subroutine put(row_index, parameter, value)
         integer, intent(in) :: row_index, parameter
         real(wp), intent(in) :: value
         if (col(parameter) > 0) jacobian(row_index, col(parameter)) = value
      end subroutine put

   end subroutine evaluate_impact_data

   !> d ln tau/d n, d ln phi/d n, and V d ln tau/d beta, V d ln phi/d beta (the
   !> derivatives in b) at every speed, by forward differences with steps of sqrt(eps)
   !> relative, for those of n and b that are free. They do not depend on c and are
   !> kept for the next call at the same (n, b). Needs log_tau and log_phi at (n, b).
   subroutine scaled_derivatives(self, n, b, stat)
      type(impact_data_model), intent(inout) :: self
      real(wp), intent(in) :: n, b
      integer, intent(out) :: stat
      real(wp) :: hn, hb, beta, lt_h, lf_h
      integer :: i, nv, alloc_stat

      stat = hcimpact_ok
      if (self%deriv_cached .and. n == self%deriv_n .and. b == self%deriv_b) return
      nv = size(self%velocity)
      self%deriv_cached = .false.
      if (allocated(self%dlt_dn)) deallocate(self%dlt_dn, self%dlf_dn, self%dlt_db, &
         & self%dlf_db)
      allocate(self%dlt_dn(nv), self%dlf_dn(nv), self%dlt_db(nv), self%dlf_db(nv), &
         & stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      self%dlt_dn = 0.0_wp
      self%dlf_dn = 0.0_wp
      self%dlt_db = 0.0_wp
      self%dlf_db = 0.0_wp
      if (self%free(exponent_index)) then
         hn = sqrt(epsilon(1.0_wp)) * max(1.0_wp, n)
         hn = (n + hn) - n
         do i = 1, nv
            call scaled_impact(n + hn, b * self%velocity(i), lt_h, lf_h, stat)
            if (stat /= hcimpact_ok) return
            self%dlt_dn(i) = (lt_h - self%log_tau(i)) / hn
            self%dlf_dn(i) = (lf_h - self%log_phi(i)) / hn
         end do
      end if
      if (self%free(damping_index)) then
         do i = 1, nv
            beta = b * self%velocity(i)
            hb = sqrt(epsilon(1.0_wp)) * max(1.0_wp, beta)
            hb = (beta + hb) - beta
            call scaled_impact(n, beta + hb, lt_h, lf_h, stat)
            if (stat /= hcimpact_ok) return
            self%dlt_db(i) = self%velocity(i) * (lt_h - self%log_tau(i)) / hb
            self%dlf_db(i) = self%velocity(i) * (lf_h - self%log_phi(i)) / hb
         end do
      end if
      self%deriv_cached = .true.
      self%deriv_n = n
      self%deriv_b = b
   end subroutine scaled_derivatives

   !> ln tau and ln phi: contact time and peak force of the dimensionless impact
   !> (m = 1, V = 1, c = (n+1)/2, hence X = 1) with exponent n and damping beta.
   subroutine scaled_impact(n, beta, log_tau, log_phi, stat)
      real(wp), intent(in) :: n, beta
      real(wp), intent(out) :: log_tau, log_phi
      integer, intent(out) :: stat
      type(contact_type) :: contact
      type(outcome_type) :: outcome

      contact = contact_type(mass=1.0_wp, stiffness=0.5_wp * (n + 1.0_wp), exponent=n, &
         & damping=beta, velocity=1.0_wp)
      call impact(contact, outcome, stat)
      log_tau = 0.0_wp
      log_phi = 0.0_wp
      if (stat /= hcimpact_ok) return
      if (.not. (outcome%contact_time > 0.0_wp .and. outcome%peak_force > 0.0_wp)) then
         stat = hcimpact_err_domain
         return
      end if
      log_tau = log(outcome%contact_time)
      log_phi = log(outcome%peak_force)
   end subroutine scaled_impact

   !> The starting b: the median of the single-point solutions b_i = beta(e_i)/V_i
   !> (e >= 1 gives 0) of every point, or of start_points points spread evenly over
   !> larger data sets (a start needs no more, and beta(e) costs about a microsecond
   !> a point: 0.75 s of a fit of 2^20 points). stat: hcimpact_ok or out_of_memory.
   subroutine damping_start(velocity, restitution, b0, stat)
      real(wp), intent(in) :: velocity(:), restitution(:)
      real(wp), intent(out) :: b0
      integer, intent(out) :: stat
      real(wp), allocatable :: b(:)
      integer :: i, j, n, m, alloc_stat

      b0 = 0.0_wp
      n = size(velocity)
      m = min(n, start_points)
      allocate(b(m), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      do i = 1, m
         ! (i for m = n)
         j = 1 + int(int(i - 1, int64) * n / m)
         b(i) = restitution_inverse(min(restitution(j), 1.0_wp)) / velocity(j)
         if (.not. ieee_is_finite(b(i))) b(i) = 0.0_wp
      end do
      call median_in_place(b, b0)
      stat = hcimpact_ok
   end subroutine damping_start

   !> The model's speeds and their logarithms, allocated with stat=.
   pure subroutine set_speeds(model, velocity, stat)
      type(impact_data_model), intent(inout) :: model
      real(wp), intent(in) :: velocity(:)
      !> hcimpact_ok or out_of_memory
      integer, intent(out) :: stat
      call allocate_copy(velocity, model%velocity, stat)
      if (stat == hcimpact_ok) call allocate_copy(velocity, model%log_velocity, stat)
      if (stat == hcimpact_ok) model%log_velocity = log(model%log_velocity)
   end subroutine set_speeds

   !> Validate a data series against the speeds (or deflections) it goes with: sizes,
   !> finiteness, positivity, and the sigmas if given.
   function check_series(abscissa, values, kind, sigma, abscissa_status) result(stat)
      real(wp), intent(in) :: abscissa(:), values(:)
      integer, intent(in) :: kind
      !> Standard deviations, or not allocated
      real(wp), allocatable, intent(in) :: sigma(:)
      !> The status of an abscissa <= 0 (hcimpact_err_velocity for speeds,
      !> hcimpact_err_domain for deflections)
      integer, intent(in) :: abscissa_status
      integer :: stat

      stat = hcimpact_ok
      if (size(values) /= size(abscissa)) then
         stat = hcimpact_err_size
      else if (allocated(sigma)) then
         if (size(sigma) /= size(values)) stat = hcimpact_err_size
      end if
      if (stat /= hcimpact_ok) return
      if (.not. (all(ieee_is_finite(abscissa)) .and. all(ieee_is_finite(values)))) then
         stat = hcimpact_err_not_finite
         return
      end if
      if (allocated(sigma)) then
         if (.not. all(ieee_is_finite(sigma))) then
            stat = hcimpact_err_not_finite
            return
         end if
      end if
      stat = check_positive(abscissa, abscissa_status)
      if (stat /= hcimpact_ok) return
      if (kind == restitution_series) then
         stat = check_positive(values, hcimpact_err_restitution)
         ! above 1 is noise on a nearly elastic impact; above 2 it is no restitution
         if (stat == hcimpact_ok .and. .not. all(values <= max_restitution)) &
            & stat = hcimpact_err_restitution
      else
         stat = check_positive(values, hcimpact_err_domain)
      end if
      if (stat /= hcimpact_ok) return
      if (allocated(sigma)) then
         stat = check_positive(sigma, hcimpact_err_domain)
         if (stat /= hcimpact_ok) return
         ! the sigma on the residual's scale (relative for logarithms) must keep the
         ! weighted residuals and their squares far from overflow
         if (kind == restitution_series) then
            if (.not. all(abs(log(sigma)) <= max_log_sigma)) stat = hcimpact_err_domain
         else
            if (.not. all(abs(log(sigma) - log(values)) <= max_log_sigma)) &
               & stat = hcimpact_err_domain
         end if
      end if
   end function check_series

   !> hcimpact_ok if every value is > 0, else `code`.
   pure function check_positive(values, code) result(stat)
      real(wp), intent(in) :: values(:)
      integer, intent(in) :: code
      integer :: stat
      if (all(values > 0.0_wp)) then
         stat = hcimpact_ok
      else
         stat = code
      end if
   end function check_positive

   !> hcimpact_ok if `observations` >= parameters + extra, else underdetermined.
   pure function check_count(observations, parameters, extra) result(stat)
      integer, intent(in) :: observations, parameters, extra
      integer :: stat
      if (observations >= parameters + extra) then
         stat = hcimpact_ok
      else
         stat = hcimpact_err_underdetermined
      end if
   end function check_count

   !> Sigma of each observation on the residual's scale: sigma_i/y_i for a logarithm
   !> (times and forces), sigma_i for restitution; ones when not given.
   pure subroutine series_sigma(values, kind, sigma, s, given)
      real(wp), intent(in) :: values(:)
      integer, intent(in) :: kind
      !> Standard deviations, or not allocated
      real(wp), allocatable, intent(in) :: sigma(:)
      !> The sigmas, size(values)
      real(wp), intent(out) :: s(:)
      logical, intent(out) :: given
      given = allocated(sigma)
      s = 1.0_wp
      if (.not. given) return
      if (kind == restitution_series) then
         s = sigma
      else
         s = sigma / values
      end if
   end subroutine series_sigma

   !> Covariance of parameters of which some were fitted as logarithms: first-order
   !> propagation, cov(p_i, p_j) = cov(ln p_i, ln p_j) p_i p_j for the logarithmic ones.
   pure function log_to_linear(cov, parameters, is_log) result(out)
      real(wp), intent(in) :: cov(:, :), parameters(:)
      logical, intent(in) :: is_log(:)
      real(wp) :: out(size(cov, 1), size(cov, 2))
      real(wp) :: factor(size(parameters))
      integer :: i, j
      factor = merge(parameters, 1.0_wp, is_log)
      do j = 1, size(cov, 2)
         do i = 1, size(cov, 1)
            out(i, j) = cov(i, j) * factor(i) * factor(j)
         end do
      end do
   end function log_to_linear

   !> Standard errors from the covariance diagonal.
   pure subroutine finish_errors(fit)
      type(fit_type), intent(inout) :: fit
      integer :: i
      fit%standard_errors = [(sqrt(max(fit%covariance(i, i), 0.0_wp)), &
         & i = 1, size(fit%parameters))]
   end subroutine finish_errors

   !> The value of an optional logical flag (default .false.).
   pure function flag(value) result(on)
      logical, intent(in), optional :: value
      logical :: on
      on = .false.
      if (present(value)) on = value
   end function flag

end module hcimpact_calibration
