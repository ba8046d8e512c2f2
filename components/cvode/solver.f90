! SPDX-License-Identifier: Apache-2.0
!> The Hunt-Crossley impact integrated by SUNDIALS CVODE (BDF or Adams, dense linear
!> solver with the analytic Jacobian, root finding for the events of the contact).
!>
!> Two entry points, both collected in the generic `simulate`:
!> - `simulate_power(contact, simulation, stat[, options])`: the power law
!>   m x'' = -c x^n (1 + b x'), integrated as s'' = -((n+1)/2) s^n (1 + beta s') in
!>   the scaled variables of MODEL.md (hcimpact_cvode_system), the path that can be
!>   compared with the closed forms;
!> - `simulate_law(law, mass, damping, velocity, simulation, stat[, options,
!>   external])`: any elastic law (hcimpact_elastic) and an optional external force
!>   g(t, x, x') (hcimpact_cvode_system), the path for what has no closed form.
!>
!> The outcome (restitution, maximum compression, peak force, times) is read at the
!> roots CVODE locates: x' = 0 (maximum compression), dF/dt = 0 (a peak of the
!> contact force) and x = 0 crossed downwards (end of contact). The state reaches
!> the callbacks only through CVODE's user data (c_loc of a local impact_system), so
!> integrations in different threads do not share anything.
!>
!> Tolerances. `rtol` is CVODE's relative tolerance. The absolute tolerances apply
!> to the scaled state and are relative to its natural size: atol * s_max for
!> s = x/X (s_max the scaled maximum compression, known from beta) and atol * k for
!> sigma = x'/V (k the restitution, the speed at the end of contact). They are
!> refused below 1e-150 (hcimpact_err_domain), where CVODE's error weights would
!> overflow: that excludes beta above about 1e140 (k < 1e-140) from this path.
!>
!> What the outcome guarantees: every field is CVODE's, with CVODE's error (measured
!> in doc/cvode.md: the contact time within 50 rtol, the rest within a few hundred),
!> and, without an external force, 0 < k <= 1 and 0 <= 1 - k^2 <= 1 as for the exact
!> model. The solver's k exceeds 1 by some rtol when b V is small against the
!> tolerance (b = 0: k - 1 = 17 rtol at rtol = 1e-6); k = 1 is reported then, never
!> further from the exact value than the solver's, which simulation_type keeps
!> (solver_restitution, restitution_clamped).
!>
!> Floating-point traps: CVODE's C code may overflow in its norms on a diverging
!> Newton iterate (and recovers); halting on overflow, invalid and division by zero is
!> therefore off while CVODE runs, and back to the caller's setting inside the
!> callbacks (our own code) and on return.
!>
!> Failures: every CVODE failure returns hcimpact_err_solver (or
!> hcimpact_err_elastic_law when the user's procedures returned non-finite values)
!> with a message naming CVODE's flag, e.g. "CV_TOO_MUCH_WORK"; the SUNDIALS objects
!> are freed on every path, and nothing is printed.
module hcimpact_cvode_solver
   use, intrinsic :: iso_c_binding, only : c_int, c_long, c_double, c_ptr, c_int64_t, &
      & c_null_ptr, c_loc, c_funloc, c_f_pointer, c_associated
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
   use hcimpact_kinds, only : wp, nan
   use hcimpact_cvode_halting, only : halting_suspend, halting_resume, callback_enter, &
      & callback_leave
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_stiffness, hcimpact_err_exponent, hcimpact_err_velocity, &
      & hcimpact_err_damping, hcimpact_err_domain, hcimpact_err_no_convergence, &
      & hcimpact_err_solver, hcimpact_err_elastic_law, status_message
   use hcimpact_elastic, only : elastic_law
   use hcimpact_restitution_law, only : restitution
   use hcimpact_impact_model, only : contact_type, outcome_type
   use hcimpact_contact, only : check_contact, check_parameters
   use hcimpact_cvode_system, only : impact_system, external_force, power_system, &
      & law_system, system_rhs, system_jacobian, system_events, system_force, &
      & largest_eigenvalue, scaled_energy, guarded_product, guarded_quotient, finite_value, &
      & rhs_ok, rhs_recoverable, rhs_law_failure, &
      & n_events, event_max_compression, event_peak_force, event_end_of_contact
   use hcimpact_cvode_report, only : report_detail
   use hcimpact_cvode_sundials, only : N_Vector, SUNMatrix, SUNLinearSolver, &
      & FN_VGetArrayPointer, FN_VDestroy, FSUNMatDestroy, FSUNLinSolFree, &
      & context_create, context_free, capture_errors
   use fcvode_mod, only : FCVodeCreate, FCVodeInit, FCVodeSetUserData, &
      & FCVodeSVtolerances, FCVodeSetLinearSolver, FCVodeSetJacFn, FCVodeRootInit, &
      & FCVodeSetRootDirection, FCVodeSetMaxNumSteps, FCVodeSetMaxHnilWarns, FCVodeSetInitStep, &
      & FCVodeSetNoInactiveRootWarn, FCVode, FCVodeGetRootInfo, FCVodeFree, &
      & FCVodeGetNumSteps, FCVodeGetNumRhsEvals, FCVodeGetNumJacEvals, &
      & FCVodeGetNumGEvals, FCVodeGetNumErrTestFails, FCVodeGetNumNonlinSolvIters, &
      & FCVodeGetNumNonlinSolvConvFails, FCVodeGetNumLinSolvSetups, &
      & FCVodeGetNumLinRhsEvals, &
      & CV_BDF, CV_ADAMS, CV_ONE_STEP, CV_SUCCESS, CV_TSTOP_RETURN, CV_ROOT_RETURN, &
      & CV_WARNING, CV_TOO_MUCH_WORK, CV_TOO_MUCH_ACC, CV_ERR_FAILURE, CV_CONV_FAILURE, &
      & CV_LINIT_FAIL, CV_LSETUP_FAIL, CV_LSOLVE_FAIL, CV_RHSFUNC_FAIL, &
      & CV_FIRST_RHSFUNC_ERR, CV_REPTD_RHSFUNC_ERR, CV_UNREC_RHSFUNC_ERR, &
      & CV_RTFUNC_FAIL, CV_NLS_INIT_FAIL, CV_NLS_SETUP_FAIL, CV_CONSTR_FAIL, &
      & CV_NLS_FAIL, CV_MEM_FAIL, CV_MEM_NULL, CV_ILL_INPUT, CV_NO_MALLOC, CV_BAD_K, &
      & CV_BAD_T, CV_BAD_DKY, CV_TOO_CLOSE, CV_VECTOROP_ERR
   use fnvector_serial_mod, only : FN_VMake_Serial
   use fsunmatrix_dense_mod, only : FSUNDenseMatrix, FSUNDenseMatrix_Data
   use fsunlinsol_dense_mod, only : FSUNLinSol_Dense
   implicit none
   private

   public :: cvode_options, cvode_counters, simulation_type
   public :: simulate, simulate_power, simulate_law
   public :: cvode_bdf, cvode_adams, cvode_flag_name

   !> Linear multistep method: backward differentiation formulas (stiff problems)
   integer, parameter :: cvode_bdf = 2
   !> Linear multistep method: Adams-Moulton (non-stiff problems)
   integer, parameter :: cvode_adams = 1

   !> Largest exponent n of the power law on this path: beyond, (n+1)/2 s^n is a wall
   !> that no step size resolves, and products of n with the state leave the range
   real(wp), parameter :: max_exponent = 100.0_wp
   !> Smallest absolute tolerance handed to CVODE (see the module header)
   real(wp), parameter :: min_atol = 1.0e-150_wp
   !> Initial capacity of the trajectory arrays
   integer, parameter :: initial_samples = 256
   !> The message when the trajectory arrays cannot grow (hcimpact_err_solver, as for
   !> CVODE's own CV_MEM_FAIL)
   character(len=*), parameter :: out_of_memory_message = "out of memory recording " &
      & // "the trajectory (options%record_trajectory)"

   !> Settings of one integration. The defaults give a relative error of a few 1e-8
   !> in the contact time (doc/cvode.md).
   type :: cvode_options
      !> cvode_bdf (default) or cvode_adams
      integer :: method = cvode_bdf
      !> Relative tolerance, 0 < rtol < 1
      real(wp) :: rtol = 1.0e-8_wp
      !> Absolute tolerance of the scaled state, relative to its natural size (module
      !> header); negative (default): the same as rtol
      real(wp) :: atol = -1.0_wp
      !> Analytic Jacobian (default) or CVODE's difference quotients
      logical :: analytic_jacobian = .true.
      !> Largest number of steps
      integer :: max_steps = 500000
      !> Record the trajectory: every step CVODE takes and every root
      logical :: record_trajectory = .false.
      !> Give up when the contact has not ended at this time (s); <= 0: automatic,
      !> 100 times a bound of the contact time from beta alone; huge(1.0_wp): no limit
      !> but max_steps
      real(wp) :: max_time = -1.0_wp
      !> First step (s), at most a tenth of x_max/V (larger values are taken as that);
      !> <= 0: automatic, 0.01 rtol^(1/(n+1)) x_max/V (power law;
      !> n = 1 for a user's law). CVODE's own estimate is not used: it assumes a
      !> smooth right-hand side, and s^n (1 + beta s') is not, at s = 0, on the scale
      !> x_max/X = (2/beta)^(1/(n+1)) of large beta
      real(wp) :: initial_step = -1.0_wp
      !> simulate_law only: the length unit L (m) of the scaled variables; <= 0:
      !> the maximum compression from the energy balance Pi(L) = m V^2 h(beta)/beta^2
      !> (exact without an external force), which needs the law's potential
      real(wp) :: length_scale = -1.0_wp
   end type cvode_options

   !> CVODE's counters after one integration
   type :: cvode_counters
      !> Internal steps
      integer(int64) :: steps = 0
      !> Right-hand side evaluations (without those of difference-quotient Jacobians)
      integer(int64) :: rhs_evals = 0
      !> Right-hand side evaluations spent on difference-quotient Jacobians
      integer(int64) :: jacobian_rhs_evals = 0
      !> Jacobian evaluations
      integer(int64) :: jacobian_evals = 0
      !> Evaluations of the event (root) functions
      integer(int64) :: root_evals = 0
      !> Local error test failures
      integer(int64) :: error_test_failures = 0
      !> Newton iterations
      integer(int64) :: nonlinear_iterations = 0
      !> Newton convergence failures
      integer(int64) :: nonlinear_failures = 0
      !> Linear solver setups (LU factorizations)
      integer(int64) :: linear_setups = 0
   end type cvode_counters

   !> Everything one integration returns
   type :: simulation_type
      !> The same outcome as the closed forms (hcimpact_impact_model); NaN on error.
      !> `evaluations` is 0 here (see `counters`)
      type(outcome_type) :: outcome
      !> CVODE's counters (also after a failure: the work done until then)
      type(cvode_counters) :: counters
      !> Largest modulus of the Jacobian's eigenvalues over the steps, in 1/s
      real(wp) :: max_eigenvalue = nan
      !> max_eigenvalue times the contact time: above about 1e3 the problem is
      !> stiff for an explicit method
      real(wp) :: stiffness_ratio = nan
      !> The solver's restitution -x'/V at the end of contact, as CVODE located it. The
      !> outcome's restitution is this, except where it exceeds 1 without an external
      !> force (the exact k is at most 1 then): the outcome has k = 1, energy loss 0
      !> and rebound velocity -V, and restitution_clamped is set
      real(wp) :: solver_restitution = nan
      !> Whether the outcome's restitution was lowered to 1 (see solver_restitution)
      logical :: restitution_clamped = .false.
      !> The length (m) and time (s) units of the scaled integration
      real(wp) :: length_unit = nan, time_unit = nan
      !> With options%record_trajectory: time (s), compression (m), velocity (m/s) and
      !> contact force (N) at every step and root, from the impact to the end of
      !> contact (also after a failure: up to it). Allocated with stat=: out of memory
      !> the run stops with hcimpact_err_solver ("out of memory recording the
      !> trajectory") and keeps what was recorded (nothing if even that cannot be cut
      !> to size)
      real(wp), allocatable :: time(:), compression(:), velocity(:), force(:)
      !> "success", or what went wrong (with CVODE's flag name and message)
      character(len=:), allocatable :: message
   end type simulation_type

   !> One impact integrated by CVODE: the power law or a user's law
   interface simulate
      module procedure :: simulate_power
      module procedure :: simulate_law
   end interface simulate

contains

   !> The power-law impact m x'' = -c x^n (1 + b x') integrated by CVODE.
   !>
   !> Errors: the input errors of the closed forms (hcimpact_err_not_finite, _mass,
   !> _stiffness, _exponent, _velocity, _damping); hcimpact_err_domain for options out
   !> of range, scales outside the double range, n above 100, or beta too large for
   !> the absolute tolerances (above about 1e140); hcimpact_err_solver when CVODE fails;
   !> hcimpact_err_no_convergence when the contact has not ended by max_time.
   subroutine simulate_power(contact, simulation, stat, options)
      !> The contact
      type(contact_type), intent(in) :: contact
      !> The result
      type(simulation_type), intent(out) :: simulation
      !> Status: hcimpact_ok or an error code of hcimpact_status
      integer, intent(out) :: stat
      !> Settings (defaults: cvode_options())
      type(cvode_options), intent(in), optional :: options
      type(cvode_options) :: opts
      type(impact_system), target :: sys
      real(wp) :: n, a, beta, ln_x, ln_f, s_max, k, atol(2), tau_max, h0
      character(len=:), allocatable :: why

      simulation%message = "success"
      opts = cvode_options()
      if (present(options)) opts = options
      call check_options(opts, stat, why)
      if (stat == hcimpact_ok) call check_power_input(contact, stat, why)
      if (stat /= hcimpact_ok) then
         simulation%message = why
         return
      end if

      n = contact%exponent
      a = 0.5_wp * (n + 1.0_wp)
      if (n > max_exponent) then
         stat = hcimpact_err_domain
         simulation%message = "the ODE path takes exponents n up to 100"
         return
      end if
      if (.not. product_fits(contact%damping, contact%velocity)) then
         stat = hcimpact_err_domain
         simulation%message = "b V overflows"
         return
      end if
      beta = contact%damping * contact%velocity
      ! X^(n+1) = (n+1) m V^2/(2 c), force unit c X^n = ((n+1)/2) m V^2/X
      ln_x = (log(a) + log(contact%mass) + 2.0_wp * log(contact%velocity) &
         & - log(contact%stiffness)) / (n + 1.0_wp)
      ln_f = log(a) + log(contact%mass) + 2.0_wp * log(contact%velocity) - ln_x
      if (abs(ln_x) > 690.0_wp &
         & .or. abs(ln_x - log(contact%velocity)) > 690.0_wp .or. abs(ln_f) > 690.0_wp) then
         stat = hcimpact_err_domain
         simulation%message = "the scales of this impact (b V, X, X/V or the force) " &
            & // "leave the double range"
         return
      end if

      k = restitution(beta)
      s_max = (2.0_wp * scaled_energy(beta))**(1.0_wp / (n + 1.0_wp))
      atol = opts%atol * [s_max, k]
      if (minval(atol) < min_atol) then
         stat = hcimpact_err_domain
         simulation%message = "the absolute tolerances atol*x_max/X and atol*k fall " &
            & // "below 1e-150 (beta = b V too large, or atol too small, for CVODE)"
         return
      end if

      sys%kind = power_system
      sys%n = n
      sys%half_np1 = a
      sys%beta = beta
      sys%mass = contact%mass
      sys%damping = contact%damping
      sys%velocity = contact%velocity
      sys%length = exp(ln_x)
      sys%time = exp(ln_x - log(contact%velocity))
      sys%force_unit = exp(ln_f)

      call time_limits(opts, sys%time, 100.0_wp * (1.0_wp + s_max * (1.0_wp + 1.0_wp / k)), &
         & 0.01_wp * opts%rtol**(1.0_wp / (n + 1.0_wp)) * s_max, 0.1_wp * s_max, tau_max, h0)
      call integrate(sys, opts, atol, tau_max, h0, simulation, stat)
   end subroutine simulate_power

   !> An impact with a user's elastic law f (hcimpact_elastic) and an optional
   !> external force g(t, x, x') (hcimpact_cvode_system):
   !> m x'' = -f(x)(1 + b x') + g(t, x, x'), x(0) = 0, x'(0) = V, integrated by CVODE
   !> in the variables s = x/L, tau = t V/L (L: options%length_scale, or the maximum
   !> compression from the law's potential). The law's force and force_derivative
   !> are used at every step; the potential only to find L.
   !>
   !> With an external force the contact may last longer than the automatic bound, or
   !> never end: set options%max_time. Outcome fields: restitution = -x'/V at the end
   !> of contact (with an external force not necessarily below 1), the largest x at
   !> an x' = 0 event, the largest F = f(x)(1 + b x') at a dF/dt = 0 event.
   !>
   !> Errors: hcimpact_err_not_finite, _mass, _velocity, _damping for bad arguments;
   !> hcimpact_err_domain for options out of range or scales outside the double range;
   !> hcimpact_err_elastic_law when the law's potential gives no scale or its
   !> procedures return non-finite values; hcimpact_err_solver when CVODE fails;
   !> hcimpact_err_no_convergence when the contact has not ended by max_time.
   subroutine simulate_law(law, mass, damping, velocity, simulation, stat, options, &
         & external)
      !> The elastic law
      class(elastic_law), intent(in) :: law
      !> Mass in kg, > 0
      real(wp), intent(in) :: mass
      !> Damping b in s/m, >= 0
      real(wp), intent(in) :: damping
      !> Approach speed V in m/s, > 0
      real(wp), intent(in) :: velocity
      !> The result
      type(simulation_type), intent(out) :: simulation
      !> Status: hcimpact_ok or an error code of hcimpact_status
      integer, intent(out) :: stat
      !> Settings (defaults: cvode_options())
      type(cvode_options), intent(in), optional :: options
      !> An external force acting during and after the contact
      class(external_force), intent(in), optional :: external
      type(cvode_options) :: opts
      type(impact_system), target :: sys
      real(wp) :: beta, k, length, atol(2), tau_max, h0, ln_energy
      character(len=:), allocatable :: why

      simulation%message = "success"
      opts = cvode_options()
      if (present(options)) opts = options
      call check_options(opts, stat, why)
      if (stat == hcimpact_ok) then
         stat = check_parameters(mass=mass, damping=damping, velocity=velocity)
         why = status_message(stat)
      end if
      if (stat /= hcimpact_ok) then
         simulation%message = why
         return
      end if

      if (.not. product_fits(damping, velocity)) then
         stat = hcimpact_err_domain
         simulation%message = "b V overflows"
         return
      end if
      beta = damping * velocity
      k = restitution(beta)
      ! m V^2 h(beta)/beta^2, the kinetic energy that goes into compression
      ln_energy = log(mass) + 2.0_wp * log(velocity) + log(scaled_energy(beta))
      if (abs(ln_energy) > 690.0_wp) then
         stat = hcimpact_err_domain
         simulation%message = "the energy m V^2 h(beta)/beta^2 leaves the double range"
         return
      end if
      if (opts%length_scale > 0.0_wp) then
         length = opts%length_scale
      else
         call energy_length(law, exp(ln_energy), length, stat)
         if (stat /= hcimpact_ok) then
            simulation%message = "no length scale: the law's potential does not reach " &
               & // "m V^2 h(beta)/beta^2 for a finite positive x (give " &
               & // "options%length_scale)"
            return
         end if
      end if
      sys%kind = law_system
      allocate(sys%law, source=law)
      if (present(external)) then
         allocate(sys%external, source=external)
         sys%clamp = .true.
      end if
      sys%beta = beta
      sys%mass = mass
      sys%damping = damping
      sys%velocity = velocity
      sys%length = length
      ! T = L/V and p = L/(m V^2), in logarithms (no overflow before the check)
      if (abs(log(length) - log(velocity)) > 690.0_wp .or. &
         & abs(log(length) - log(mass) - 2.0_wp * log(velocity)) > 690.0_wp) then
         stat = hcimpact_err_domain
         simulation%message = "the scales L/V or L/(m V^2) leave the double range"
         return
      end if
      sys%time = exp(log(length) - log(velocity))
      sys%accel = exp(log(length) - log(mass) - 2.0_wp * log(velocity))

      atol = opts%atol * [1.0_wp, k]
      if (minval(atol) < min_atol) then
         stat = hcimpact_err_domain
         simulation%message = "the absolute tolerances atol and atol*k fall below 1e-150 " &
            & // "(beta = b V too large, or atol too small, for CVODE)"
         return
      end if
      call time_limits(opts, sys%time, 100.0_wp * (2.0_wp + 1.0_wp / k), &
         & 0.01_wp * sqrt(opts%rtol), 0.1_wp, tau_max, h0)
      call integrate(sys, opts, atol, tau_max, h0, simulation, stat)
   end subroutine simulate_law

   !> The scaled time at which to give up and the scaled first step, from the options
   !> (in s) or the automatic values. A time given in s becomes tau = t/T without
   !> overflow (options%max_time = huge(1.0_wp) with T < 1 s overflowed, and trapped
   !> in a build with -ffpe-trap): beyond the double range it is huge(1.0_wp), which
   !> CVODE takes as "no limit" (max_steps still bounds the run). The first step is
   !> at most largest_step, a tenth of the scaled maximum compression: a longer first
   !> step steps over the compression (CVODE would fail its error test on it).
   pure subroutine time_limits(opts, time_unit, auto_tau_max, auto_h0, largest_step, &
         & tau_max, h0)
      !> Checked options
      type(cvode_options), intent(in) :: opts
      !> T in s
      real(wp), intent(in) :: time_unit
      !> Automatic values of tau_max and h0, and the largest first step (scaled)
      real(wp), intent(in) :: auto_tau_max, auto_h0, largest_step
      !> Scaled time to give up at, scaled first step
      real(wp), intent(out) :: tau_max, h0
      if (opts%max_time > 0.0_wp) then
         tau_max = guarded_quotient(opts%max_time, time_unit)
      else
         tau_max = auto_tau_max
      end if
      if (opts%initial_step > 0.0_wp) then
         h0 = min(guarded_quotient(opts%initial_step, time_unit), largest_step)
      else
         h0 = min(auto_h0, largest_step)
      end if
   end subroutine time_limits

   !> Whether a*b (a >= 0, b > 0, both finite) is below the overflow threshold.
   pure logical function product_fits(a, b)
      real(wp), intent(in) :: a, b
      product_fits = .true.
      if (a > 0.0_wp) product_fits = log(a) + log(b) < log(huge(a))
   end function product_fits

   !> Check the options; the defaults of atol are filled in.
   subroutine check_options(opts, stat, why)
      type(cvode_options), intent(inout) :: opts
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: why

      stat = hcimpact_ok
      why = "success"
      if (.not. (finite_value(opts%rtol) .and. finite_value(opts%atol))) then
         stat = hcimpact_err_not_finite
         why = "the tolerances must be finite"
      else if (.not. (finite_value(opts%max_time) .and. finite_value(opts%initial_step) &
         & .and. finite_value(opts%length_scale))) then
         stat = hcimpact_err_not_finite
         why = "options%max_time, initial_step and length_scale must be finite"
      else if (.not. (opts%rtol > 0.0_wp .and. opts%rtol < 1.0_wp)) then
         stat = hcimpact_err_domain
         why = "rtol must lie in (0, 1)"
      else if (opts%method /= cvode_bdf .and. opts%method /= cvode_adams) then
         stat = hcimpact_err_domain
         why = "method must be cvode_bdf or cvode_adams"
      else if (opts%max_steps < 1) then
         stat = hcimpact_err_domain
         why = "max_steps must be positive"
      end if
      if (stat == hcimpact_ok) then
         if (opts%atol < 0.0_wp) opts%atol = opts%rtol
      end if
   end subroutine check_options

   !> Check a power-law contact (the rules of the closed forms, one validator).
   subroutine check_power_input(contact, stat, why)
      type(contact_type), intent(in) :: contact
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: why

      ! the library's one validator (hcimpact_contact): the closed forms and this path
      ! accept and refuse the same contacts
      stat = check_contact(contact)
      why = status_message(stat)
   end subroutine check_power_input

   !> The x > 0 with Pi(x) = energy (J) for a user's law, to a relative 1e-6 (it is
   !> only a scale): bracketed by powers of 2 from 1 m, then bisection in log x.
   subroutine energy_length(law, energy, length, stat)
      class(elastic_law), intent(in) :: law
      real(wp), intent(in) :: energy
      real(wp), intent(out) :: length
      integer, intent(out) :: stat
      real(wp) :: lo, hi, mid, p
      integer :: it

      stat = hcimpact_err_elastic_law
      length = nan
      if (.not. (ieee_is_finite(energy) .and. energy > 0.0_wp)) return
      lo = 1.0_wp
      hi = 1.0_wp
      p = law%potential(hi)
      if (ieee_is_nan(p)) return
      do it = 1, 1000
         if (p >= energy) exit
         lo = hi
         hi = 2.0_wp * hi
         if (hi > 1.0e300_wp) return
         p = law%potential(hi)
         if (ieee_is_nan(p)) return
      end do
      if (lo == hi) then
         do it = 1, 1000
            lo = 0.5_wp * lo
            if (lo < 1.0e-300_wp) return
            p = law%potential(lo)
            if (ieee_is_nan(p)) return
            if (p < energy) exit
            hi = lo
         end do
      end if
      do it = 1, 200
         if (hi <= lo * (1.0_wp + 1.0e-6_wp)) exit
         mid = sqrt(lo) * sqrt(hi)
         p = law%potential(mid)
         if (ieee_is_nan(p)) return
         if (p < energy) then
            lo = mid
         else
            hi = mid
         end if
      end do
      length = sqrt(lo) * sqrt(hi)
      stat = hcimpact_ok
   end subroutine energy_length

   !> Integrate the system from the impact to the end of contact, and fill in the
   !> simulation (SI units) from the roots located on the way.
   subroutine integrate(sys, opts, atol, tau_max, h0, simulation, stat)
      !> The system; its address is CVODE's user data
      type(impact_system), intent(inout), target :: sys
      !> Settings (checked)
      type(cvode_options), intent(in) :: opts
      !> Absolute tolerances of s and sigma
      real(wp), intent(in) :: atol(2)
      !> Scaled time at which to give up
      real(wp), intent(in) :: tau_max
      !> Scaled first step
      real(wp), intent(in) :: h0
      !> The result
      type(simulation_type), intent(inout) :: simulation
      !> Status
      integer, intent(out) :: stat
      type(c_ptr) :: ctx, cvode_mem
      type(N_Vector), pointer :: y_vec, atol_vec
      type(SUNMatrix), pointer :: jac_mat
      type(SUNLinearSolver), pointer :: lin_sol
      real(c_double), target :: y(2), atol_c(2)
      real(c_double) :: tret(1), jac(2, 2)
      integer(c_int) :: ierr, lmm, rootsfound(n_events), rootdir(n_events)
      integer :: nsamples, ev, jstat, steps, alloc_stat
      real(wp) :: lambda_max, tau_comp, tau_peak, tau_end, y_comp(2), y_peak(2), &
         & y_end(2), f_peak, f_here
      logical :: have_comp, have_peak, have_end, ok, recorded
      character(len=:), allocatable :: where

      stat = hcimpact_ok
      ctx = c_null_ptr
      cvode_mem = c_null_ptr
      nullify(y_vec, atol_vec, jac_mat, lin_sol)
      ! CVODE's C code is not written for trapping floating-point exceptions: a
      ! diverging Newton iterate may overflow its weighted norms, which it treats as a
      ! convergence failure (a smaller step). A caller that traps exceptions would be
      ! killed there, so halting is off while CVODE runs; the callbacks switch the
      ! caller's halting back on for our own code (traps still catch our bugs).
      call halting_suspend(sys%halting)
      sys%law_failed = .false.
      sys%report%code = 0
      simulation%length_unit = sys%length
      simulation%time_unit = sys%time
      y = [0.0_c_double, 1.0_c_double]
      atol_c = atol
      lmm = CV_BDF
      if (opts%method == cvode_adams) lmm = CV_ADAMS
      nsamples = 0
      if (opts%record_trajectory) then
         allocate(simulation%time(initial_samples), simulation%compression(initial_samples), &
            & simulation%velocity(initial_samples), simulation%force(initial_samples), &
            & stat=alloc_stat)
         recorded = alloc_stat == 0
         if (recorded) call append_sample(simulation, nsamples, sys, 0.0_wp, y, recorded)
         if (.not. recorded) then
            stat = hcimpact_err_solver
            simulation%message = out_of_memory_message
            call restore_halting(sys)
            return
         end if
      end if

      setup: block
         ierr = context_create(ctx)
         if (ierr /= 0) then
            where = "SUNContext_Create"
            exit setup
         end if
         y_vec => FN_VMake_Serial(2_c_int64_t, y, ctx)
         atol_vec => FN_VMake_Serial(2_c_int64_t, atol_c, ctx)
         if (.not. (associated(y_vec) .and. associated(atol_vec))) then
            ierr = CV_MEM_FAIL
            where = "N_VMake_Serial"
            exit setup
         end if
         cvode_mem = FCVodeCreate(lmm, ctx)
         if (.not. c_associated(cvode_mem)) then
            ierr = CV_MEM_FAIL
            where = "CVodeCreate"
            exit setup
         end if
         where = "CVodeSetErrHandler"
         ierr = capture_errors(ctx, cvode_mem, c_loc(sys%report))
         if (ierr /= 0) exit setup
         where = "CVodeInit"
         ierr = FCVodeInit(cvode_mem, c_funloc(rhs_callback), 0.0_c_double, y_vec)
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetUserData"
         ierr = FCVodeSetUserData(cvode_mem, c_loc(sys))
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSVtolerances"
         ierr = FCVodeSVtolerances(cvode_mem, real(opts%rtol, c_double), atol_vec)
         if (ierr /= CV_SUCCESS) exit setup
         jac_mat => FSUNDenseMatrix(2_c_int64_t, 2_c_int64_t, ctx)
         if (.not. associated(jac_mat)) then
            ierr = CV_MEM_FAIL
            where = "SUNDenseMatrix"
            exit setup
         end if
         lin_sol => FSUNLinSol_Dense(y_vec, jac_mat, ctx)
         if (.not. associated(lin_sol)) then
            ierr = CV_MEM_FAIL
            where = "SUNLinSol_Dense"
            exit setup
         end if
         where = "CVodeSetLinearSolver"
         ierr = FCVodeSetLinearSolver(cvode_mem, lin_sol, jac_mat)
         if (ierr /= CV_SUCCESS) exit setup
         if (opts%analytic_jacobian) then
            where = "CVodeSetJacFn"
            ierr = FCVodeSetJacFn(cvode_mem, c_funloc(jacobian_callback))
            if (ierr /= CV_SUCCESS) exit setup
         end if
         where = "CVodeRootInit"
         ierr = FCVodeRootInit(cvode_mem, int(n_events, c_int), c_funloc(events_callback))
         if (ierr /= CV_SUCCESS) exit setup
         ! every event is wanted when its function decreases through zero
         rootdir = -1_c_int
         where = "CVodeSetRootDirection"
         ierr = FCVodeSetRootDirection(cvode_mem, rootdir)
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetInitStep"
         ierr = FCVodeSetInitStep(cvode_mem, real(h0, c_double))
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetMaxNumSteps"
         ierr = FCVodeSetMaxNumSteps(cvode_mem, int(opts%max_steps, c_long))
         if (ierr /= CV_SUCCESS) exit setup
         ! No warnings: the events x = 0 and dF/dt = 0 (n > 1) vanish at the impact
         ! by construction, and "t + h = t" is reported as a failure if it matters.
         where = "CVodeSetMaxHnilWarns"
         ierr = FCVodeSetMaxHnilWarns(cvode_mem, -1_c_int)
         if (ierr /= CV_SUCCESS) exit setup
         where = "CVodeSetNoInactiveRootWarn"
         ierr = FCVodeSetNoInactiveRootWarn(cvode_mem)
         if (ierr /= CV_SUCCESS) exit setup
      end block setup

      have_comp = .false.
      have_peak = .false.
      have_end = .false.
      f_peak = -huge(1.0_wp)
      lambda_max = 0.0_wp
      tau_comp = nan
      tau_peak = nan
      tau_end = nan
      y_comp = nan
      y_peak = nan
      y_end = nan
      if (ierr /= 0) then
         stat = hcimpact_err_solver
         simulation%message = "CVODE setup failed in " // where // ": " &
            & // cvode_flag_name(ierr) // report_detail(sys%report)
      else
         tret = 0.0_c_double
         ! CVODE's own limit (CVodeSetMaxNumSteps) counts the steps of one call, and
         ! in CV_ONE_STEP mode every call is one step: the limit is enforced here.
         steps = 0
         march: do
            if (steps >= opts%max_steps) then
               stat = hcimpact_err_solver
               simulation%message = "CVODE failed at t = " &
                  & // trim(real_text(guarded_product(tret(1), sys%time))) // " s: " &
                  & // cvode_flag_name(CV_TOO_MUCH_WORK) // " (options%max_steps = " &
                  & // trim(integer_text(opts%max_steps)) &
                  & // " steps taken before the end of contact)"
               exit march
            end if
            ierr = FCVode(cvode_mem, real(tau_max, c_double), y_vec, tret, CV_ONE_STEP)
            if (ierr < 0) then
               stat = hcimpact_err_solver
               if (sys%law_failed .and. (ierr == CV_RHSFUNC_FAIL .or. &
                  & ierr == CV_FIRST_RHSFUNC_ERR .or. ierr == CV_REPTD_RHSFUNC_ERR .or. &
                  & ierr == CV_UNREC_RHSFUNC_ERR .or. ierr == CV_RTFUNC_FAIL .or. &
                  & ierr == CV_LSETUP_FAIL .or. ierr == CV_CONV_FAILURE)) then
                  stat = hcimpact_err_elastic_law
               end if
               simulation%message = "CVODE failed at t = " &
                  & // trim(real_text(guarded_product(tret(1), sys%time))) // " s: " &
                  & // cvode_flag_name(ierr) // report_detail(sys%report)
               exit march
            end if
            ! every step is returned once with CV_SUCCESS (a root in it is returned
            ! before, with CV_ROOT_RETURN)
            if (ierr == CV_SUCCESS) steps = steps + 1
            if (.not. (ieee_is_finite(y(1)) .and. ieee_is_finite(y(2)))) then
               stat = hcimpact_err_solver
               simulation%message = "CVODE returned a non-finite state at t = " &
                  & // trim(real_text(guarded_product(tret(1), sys%time))) // " s"
               exit march
            end if
            call system_jacobian(sys, tret(1), y, jac, jstat)
            if (jstat == rhs_ok) lambda_max = max(lambda_max, largest_eigenvalue(jac))
            if (opts%record_trajectory) then
               call append_sample(simulation, nsamples, sys, tret(1), y, recorded)
               if (.not. recorded) then
                  stat = hcimpact_err_solver
                  simulation%message = out_of_memory_message
                  exit march
               end if
            end if

            if (ierr == CV_ROOT_RETURN) then
               ierr = FCVodeGetRootInfo(cvode_mem, rootsfound)
               do ev = 1, n_events
                  if (rootsfound(ev) == 0) cycle
                  select case (ev)
                  case (event_max_compression)
                     ! (y_comp is NaN until the first event: no ordered comparison)
                     if (.not. have_comp) then
                        tau_comp = tret(1)
                        y_comp = y
                     else if (y(1) > y_comp(1)) then
                        tau_comp = tret(1)
                        y_comp = y
                     end if
                     have_comp = .true.
                  case (event_peak_force)
                     call system_force(sys, y, f_here, ok)
                     if (f_here > f_peak .or. .not. have_peak) then
                        tau_peak = tret(1)
                        y_peak = y
                        f_peak = f_here
                     end if
                     have_peak = .true.
                  case (event_end_of_contact)
                     tau_end = tret(1)
                     y_end = y
                     have_end = .true.
                  end select
               end do
               if (have_end) exit march
            end if
            if (tret(1) >= tau_max) then
               stat = hcimpact_err_no_convergence
               simulation%message = "the contact has not ended at t = " &
                  & // trim(real_text(guarded_product(tret(1), sys%time))) &
                  & // " s (options%max_time)"
               exit march
            end if
         end do march
      end if

      if (c_associated(cvode_mem)) call get_counters(cvode_mem, simulation%counters)
      ! free in the reverse order of creation
      if (c_associated(cvode_mem)) call FCVodeFree(cvode_mem)
      if (associated(lin_sol)) ierr = FSUNLinSolFree(lin_sol)
      if (associated(jac_mat)) call FSUNMatDestroy(jac_mat)
      if (associated(atol_vec)) call FN_VDestroy(atol_vec)
      if (associated(y_vec)) call FN_VDestroy(y_vec)
      call context_free(ctx)
      call restore_halting(sys)

      if (opts%record_trajectory) then
         call shrink_samples(simulation, nsamples, recorded)
         if (.not. recorded) then
            if (stat == hcimpact_ok) then
               stat = hcimpact_err_solver
               simulation%message = out_of_memory_message
            else
               simulation%message = simulation%message // "; then " // out_of_memory_message
            end if
         end if
      end if
      if (stat /= hcimpact_ok) return
      if (.not. (have_comp .and. have_peak)) then
         stat = hcimpact_err_solver
         simulation%message = "the end of contact was reached without locating the " &
            & // "maximum compression or the peak force (an event was stepped over)"
         return
      end if

      associate(o => simulation%outcome)
         ! (products guarded: a result beyond the double range is reported as such)
         simulation%solver_restitution = -y_end(2)
         o%restitution = -y_end(2)
         ! Without an external force the exact k is at most 1 (b >= 0 and f >= 0: the
         ! damping only dissipates, m V^2 (1 - k^2)/2 = integral of b f(x) x'^2 dt); the
         ! solver's k carries its error, some rtol either side, and comes out above 1
         ! when b V is small against the tolerance. 1 is then nearer the exact value.
         if (.not. allocated(sys%external) .and. o%restitution > 1.0_wp) then
            o%restitution = 1.0_wp
            simulation%restitution_clamped = .true.
         end if
         o%energy_loss_ratio = guarded_product(1.0_wp - o%restitution, 1.0_wp + o%restitution)
         o%rebound_velocity = -guarded_product(o%restitution, sys%velocity)
         o%max_compression = guarded_product(y_comp(1), sys%length)
         o%compression_time = guarded_product(tau_comp, sys%time)
         o%peak_force = f_peak
         o%compression_at_peak_force = guarded_product(max(y_peak(1), 0.0_wp), sys%length)
         o%time_at_peak_force = guarded_product(tau_peak, sys%time)
         o%contact_time = guarded_product(tau_end, sys%time)
         o%evaluations = 0
      end associate
      simulation%max_eigenvalue = guarded_quotient(lambda_max, sys%time)
      simulation%stiffness_ratio = guarded_product(lambda_max, tau_end)
      if (.not. ok_outcome(simulation%outcome)) then
         stat = hcimpact_err_domain
         simulation%message = "a result overflows the double range"
         simulation%outcome = outcome_type()
      end if
   end subroutine integrate

   !> Whether every real field of an outcome is finite.
   pure function ok_outcome(o) result(ok)
      type(outcome_type), intent(in) :: o
      logical :: ok
      real(wp) :: v(9)
      v = [o%restitution, o%energy_loss_ratio, o%rebound_velocity, o%max_compression, &
         & o%peak_force, o%compression_at_peak_force, o%time_at_peak_force, &
         & o%compression_time, o%contact_time]
      ok = all(ieee_is_finite(v))
      if (ok) ok = all(abs(v) < huge(1.0_wp))
   end function ok_outcome

   !> CVODE's counters of the integration behind cvode_mem.
   subroutine get_counters(cvode_mem, counters)
      type(c_ptr), intent(in) :: cvode_mem
      type(cvode_counters), intent(out) :: counters
      integer(c_long) :: value(1)
      integer(c_int) :: ierr

      value = 0
      ierr = FCVodeGetNumSteps(cvode_mem, value)
      counters%steps = value(1)
      ierr = FCVodeGetNumRhsEvals(cvode_mem, value)
      counters%rhs_evals = value(1)
      ierr = FCVodeGetNumLinRhsEvals(cvode_mem, value)
      counters%jacobian_rhs_evals = value(1)
      ierr = FCVodeGetNumJacEvals(cvode_mem, value)
      counters%jacobian_evals = value(1)
      ierr = FCVodeGetNumGEvals(cvode_mem, value)
      counters%root_evals = value(1)
      ierr = FCVodeGetNumErrTestFails(cvode_mem, value)
      counters%error_test_failures = value(1)
      ierr = FCVodeGetNumNonlinSolvIters(cvode_mem, value)
      counters%nonlinear_iterations = value(1)
      ierr = FCVodeGetNumNonlinSolvConvFails(cvode_mem, value)
      counters%nonlinear_failures = value(1)
      ierr = FCVodeGetNumLinSolvSetups(cvode_mem, value)
      counters%linear_setups = value(1)
   end subroutine get_counters

   !> What goes wrong while CVODE runs is restored: the flags it raised are cleared
   !> and the caller's halting modes come back.
   subroutine restore_halting(sys)
      type(impact_system), intent(in) :: sys
      call halting_resume(sys%halting)
   end subroutine restore_halting

   !> Append the state at the scaled time tau to the trajectory, in SI units; `added`
   !> is false when the arrays could not grow (out of memory; nothing appended).
   subroutine append_sample(simulation, nsamples, sys, tau, y, added)
      type(simulation_type), intent(inout) :: simulation
      integer, intent(inout) :: nsamples
      type(impact_system), intent(in) :: sys
      real(wp), intent(in) :: tau, y(2)
      logical, intent(out) :: added
      real(wp) :: force
      logical :: ok

      added = .true.
      if (nsamples == size(simulation%time)) then
         call resize(simulation%time, 2 * nsamples, added)
         if (added) call resize(simulation%compression, 2 * nsamples, added)
         if (added) call resize(simulation%velocity, 2 * nsamples, added)
         if (added) call resize(simulation%force, 2 * nsamples, added)
         if (.not. added) return
      end if
      nsamples = nsamples + 1
      call system_force(sys, y, force, ok)
      simulation%time(nsamples) = guarded_product(tau, sys%time)
      simulation%compression(nsamples) = guarded_product(y(1), sys%length)
      simulation%velocity(nsamples) = guarded_product(y(2), sys%velocity)
      simulation%force(nsamples) = force
   end subroutine append_sample

   !> Give an array a new size, keeping its first values; ok false (array unchanged)
   !> when the memory cannot be allocated.
   subroutine resize(array, new_size, ok)
      real(wp), allocatable, intent(inout) :: array(:)
      integer, intent(in) :: new_size
      logical, intent(out) :: ok
      real(wp), allocatable :: tmp(:)
      integer :: alloc_stat, kept
      allocate(tmp(new_size), stat=alloc_stat)
      ok = alloc_stat == 0
      if (.not. ok) return
      kept = min(new_size, size(array))
      tmp(:kept) = array(:kept)
      call move_alloc(tmp, array)
   end subroutine resize

   !> Cut the trajectory arrays to the samples recorded; out of memory (ok false) the
   !> trajectory is dropped.
   subroutine shrink_samples(simulation, nsamples, ok)
      type(simulation_type), intent(inout) :: simulation
      integer, intent(in) :: nsamples
      logical, intent(out) :: ok
      call resize(simulation%time, nsamples, ok)
      if (ok) call resize(simulation%compression, nsamples, ok)
      if (ok) call resize(simulation%velocity, nsamples, ok)
      if (ok) call resize(simulation%force, nsamples, ok)
      if (.not. ok) deallocate(simulation%time, simulation%compression, &
         & simulation%velocity, simulation%force)
   end subroutine shrink_samples

   !> CVRhsFn: (s, sigma)' at the scaled time t. 0; 1 (recoverable: CVODE retries
   !> with a smaller step) when the state is too far out; -1 when the user's law failed.
   function rhs_callback(t, y, ydot, user_data) result(ierr) bind(C)
      real(c_double), value :: t
      type(N_Vector) :: y, ydot
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(impact_system), pointer :: sys
      real(c_double), pointer :: yv(:), dv(:)
      real(wp) :: state(2), dy(2)
      integer :: stat
      logical :: flags(3)

      call c_f_pointer(user_data, sys)
      call callback_enter(sys%halting, flags)
      yv => FN_VGetArrayPointer(y)
      dv => FN_VGetArrayPointer(ydot)
      ! (a copy: a section of the pointer as the argument would make gfortran's
      ! -fcheck=array-temps keep a static once-only warning flag)
      state = yv(1:2)
      call system_rhs(sys, t, state, dy, stat)
      dv(1:2) = dy
      call callback_leave(sys%halting, flags)
      ierr = callback_flag(sys, stat)
   end function rhs_callback

   !> CVLsJacFn: the dense Jacobian of the right-hand side.
   function jacobian_callback(t, y, fy, jac_mat, user_data, tmp1, tmp2, tmp3) &
         & result(ierr) bind(C)
      real(c_double), value :: t
      type(N_Vector) :: y, fy, tmp1, tmp2, tmp3
      type(SUNMatrix) :: jac_mat
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(impact_system), pointer :: sys
      real(c_double), pointer :: yv(:), data(:), jv(:, :)
      real(wp) :: state(2), jac(2, 2)
      integer :: stat
      logical :: flags(3)

      call c_f_pointer(user_data, sys)
      call callback_enter(sys%halting, flags)
      yv => FN_VGetArrayPointer(y)
      ! the wrapper returns a pointer of size 1 to the column-major 2x2 data
      data => FSUNDenseMatrix_Data(jac_mat)
      call c_f_pointer(c_loc(data(1)), jv, [2, 2])
      state = yv(1:2)
      call system_jacobian(sys, t, state, jac, stat)
      jv = jac
      call callback_leave(sys%halting, flags)
      ierr = callback_flag(sys, stat)
   end function jacobian_callback

   !> The return value of the right-hand side and Jacobian callbacks for the status
   !> of an evaluation: 0 (success), 1 (recoverable: a state so far out that a value
   !> would overflow, which only a rejected Newton iterate reaches; CVODE retries with
   !> a smaller step) or -1 (unrecoverable: the user's law or force returned a value
   !> that is not finite at an x >= 0, where a law must be defined). A law failure
   !> was recoverable once: CVODE then crept towards the compression where the law
   !> breaks down in ever smaller steps, and gave up after max_steps (CV_TOO_MUCH_WORK,
   !> 1.8 s) instead of naming the law (CV_RHSFUNC_FAIL, hcimpact_err_elastic_law).
   function callback_flag(sys, stat) result(ierr)
      type(impact_system), intent(inout) :: sys
      integer, intent(in) :: stat
      integer(c_int) :: ierr
      select case (stat)
      case (rhs_ok)
         ierr = 0
      case (rhs_law_failure)
         sys%law_failed = .true.
         ierr = -1
      case default
         ierr = 1
      end select
   end function callback_flag

   !> CVRootFn: the three event functions.
   function events_callback(t, y, gout, user_data) result(ierr) bind(C)
      real(c_double), value :: t
      type(N_Vector) :: y
      real(c_double) :: gout(n_events)
      type(c_ptr), value :: user_data
      integer(c_int) :: ierr
      type(impact_system), pointer :: sys
      real(c_double), pointer :: yv(:)
      real(wp) :: state(2), g(n_events)
      integer :: stat
      logical :: flags(3)

      call c_f_pointer(user_data, sys)
      call callback_enter(sys%halting, flags)
      yv => FN_VGetArrayPointer(y)
      state = yv(1:2)
      call system_events(sys, t, state, g, stat)
      gout = g
      call callback_leave(sys%halting, flags)
      ierr = 0
      if (stat == rhs_law_failure) sys%law_failed = .true.
      if (stat /= rhs_ok) ierr = -1
   end function events_callback

   !> The name of a CVODE return flag, blank-padded.
   pure function flag_label(flag) result(name)
      integer(c_int), intent(in) :: flag
      character(len=24) :: name

      select case (flag)
      case (CV_SUCCESS)
         name = "CV_SUCCESS"
      case (CV_TSTOP_RETURN)
         name = "CV_TSTOP_RETURN"
      case (CV_ROOT_RETURN)
         name = "CV_ROOT_RETURN"
      case (CV_WARNING)
         name = "CV_WARNING"
      case (CV_TOO_MUCH_WORK)
         name = "CV_TOO_MUCH_WORK"
      case (CV_TOO_MUCH_ACC)
         name = "CV_TOO_MUCH_ACC"
      case (CV_ERR_FAILURE)
         name = "CV_ERR_FAILURE"
      case (CV_CONV_FAILURE)
         name = "CV_CONV_FAILURE"
      case (CV_LINIT_FAIL)
         name = "CV_LINIT_FAIL"
      case (CV_LSETUP_FAIL)
         name = "CV_LSETUP_FAIL"
      case (CV_LSOLVE_FAIL)
         name = "CV_LSOLVE_FAIL"
      case (CV_RHSFUNC_FAIL)
         name = "CV_RHSFUNC_FAIL"
      case (CV_FIRST_RHSFUNC_ERR)
         name = "CV_FIRST_RHSFUNC_ERR"
      case (CV_REPTD_RHSFUNC_ERR)
         name = "CV_REPTD_RHSFUNC_ERR"
      case (CV_UNREC_RHSFUNC_ERR)
         name = "CV_UNREC_RHSFUNC_ERR"
      case (CV_RTFUNC_FAIL)
         name = "CV_RTFUNC_FAIL"
      case (CV_NLS_INIT_FAIL)
         name = "CV_NLS_INIT_FAIL"
      case (CV_NLS_SETUP_FAIL)
         name = "CV_NLS_SETUP_FAIL"
      case (CV_CONSTR_FAIL)
         name = "CV_CONSTR_FAIL"
      case (CV_NLS_FAIL)
         name = "CV_NLS_FAIL"
      case (CV_MEM_FAIL)
         name = "CV_MEM_FAIL"
      case (CV_MEM_NULL)
         name = "CV_MEM_NULL"
      case (CV_ILL_INPUT)
         name = "CV_ILL_INPUT"
      case (CV_NO_MALLOC)
         name = "CV_NO_MALLOC"
      case (CV_BAD_K)
         name = "CV_BAD_K"
      case (CV_BAD_T)
         name = "CV_BAD_T"
      case (CV_BAD_DKY)
         name = "CV_BAD_DKY"
      case (CV_TOO_CLOSE)
         name = "CV_TOO_CLOSE"
      case (CV_VECTOROP_ERR)
         name = "CV_VECTOROP_ERR"
      case default
         name = "CV_UNKNOWN_FLAG"
      end select
   end function flag_label

   !> An integer as text, left-adjusted and blank-padded (trim it).
   pure function integer_text(i) result(text)
      integer, intent(in) :: i
      character(len=12) :: text
      write(text, '(i0)') i
   end function integer_text

   !> Length of cvode_flag_name(flag).
   pure function flag_name_length(flag) result(length)
      integer(c_int), intent(in) :: flag
      integer :: length
      length = len_trim(flag_label(flag)) + len_trim(integer_text(int(flag))) + 3
   end function flag_name_length

   !> Name of a CVODE return flag, e.g. "CV_TOO_MUCH_WORK (-1)".
   pure function cvode_flag_name(flag) result(name)
      !> The flag
      integer(c_int), intent(in) :: flag
      !> Its name and value
      character(len=flag_name_length(flag)) :: name

      name = trim(flag_label(flag)) // " (" // trim(integer_text(int(flag))) // ")"
   end function cvode_flag_name

   !> A real with 6 significant digits, left-adjusted and blank-padded (trim it).
   pure function real_text(x) result(text)
      real(wp), intent(in) :: x
      character(len=24) :: text
      write(text, '(es12.5)') x
      text = adjustl(text)
   end function real_text

end module hcimpact_cvode_solver
