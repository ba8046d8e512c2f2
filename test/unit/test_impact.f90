! SPDX-License-Identifier: Apache-2.0
!> Tests of one impact (issue #3): hcimpact_impact_model, hcimpact_hertz,
!> hcimpact_elastic and the C entry point hcimpact_impact.
!>
!> Accuracy against the mpmath references test/reference/impact.csv and timelaw.csv
!> (see test/reference/IMPACT.md), in ulps of the exact value at the double inputs.
!> Goals of issue #3: maximum compression <= 2 ulp, peak force <= 4, compression and
!> contact time <= 4, x(t) <= 8 where it is well conditioned, at most 200 integrand
!> evaluations per quadrature for beta = b V <= 100. The other outputs are held to the
!> goals of their neighbours (restitution 2 ulp as in issue #2's restitution tests;
!> the place and time of the peak 4 ulp).
!>
!> Near the end of contact x(t) is ill-conditioned (IMPACT.md): an error of one ulp
!> in the contact time moves x by |x'| ulp(t). The time-law tests therefore allow
!> 8 (1 + kappa) ulps with kappa = t |y'|/|y| the condition number of each output.
!>
!> Everything here is safe under -ffpe-trap=invalid,zero,overflow.
module test_impact
   use, intrinsic :: iso_c_binding, only : c_loc, c_null_ptr, c_int, c_long
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_is_nan, ieee_is_finite
   use testdrive, only : new_unittest, unittest_type, error_type, check, test_failed
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp, ik
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_not_finite, hcimpact_err_mass, &
      & hcimpact_err_stiffness, hcimpact_err_exponent, hcimpact_err_velocity, &
      & hcimpact_err_damping, hcimpact_err_restitution, hcimpact_err_domain, &
      & hcimpact_err_null, hcimpact_err_size, hcimpact_err_elastic_law, &
      & hcimpact_err_no_convergence, hcimpact_err_out_of_memory
   use hcimpact_impact_model, only : contact_type, outcome_type, impact, impact_law, &
      & velocity_at_depth, time_law, time_law_samples, damping_for_restitution, &
      & default_min_velocity, compression_branch, restitution_branch, min_exponent, max_beta, &
      & max_quadrature_exponent
   use hcimpact_api_motion, only : c_time_law, c_time_law_samples
   use hcimpact_restitution_law, only : restitution_inverse
   use hcimpact_power_rules, only : power_phase_pieces, max_pieces, cc_max_beta, &
      & cc_max_compression_le, end_piece_le, whole_max_beta
   use hcimpact_power_model, only : peak_ratio_m1, peak_series_max_y
   use hcimpact_double_double, only : dd_real, dd, operator(+), operator(-), &
      & operator(*), dd_exp, dd_log, dd_inverse
   use hcimpact_hertz, only : hertz_constant, effective_mass, two_body_velocities
   use hcimpact_elastic, only : elastic_law, power_law
   use hcimpact_capi_types, only : hcimpact_contact, hcimpact_outcome
   use hcimpact_api_impact, only : c_impact
   use hcimpact_check, only : ulp_error, median, format_real, reference_path, check_close, &
      & int_text
   implicit none
   private

   public :: collect_impact

   !> Outputs of impact.csv, in the order of its columns
   integer, parameter :: n_outputs = 7
   character(len=*), parameter :: output_names(n_outputs) = [character(len=20) :: &
      & "max_compression", "peak_force", "compression_at_peak", "time_at_peak", &
      & "compression_time", "contact_time", "restitution"]
   !> Goals on the largest error, in ulp, per output
   real(wp), parameter :: goal_max(n_outputs) = [2.0_wp, 4.0_wp, 4.0_wp, 4.0_wp, 4.0_wp, &
      & 4.0_wp, 2.0_wp]
   !> Goal on the median error, in ulp, every output
   real(wp), parameter :: goal_median = 0.5_wp
   !> Goal of the time law, in ulp, for a well-conditioned point
   real(wp), parameter :: goal_time_law = 8.0_wp
   !> Largest number of integrand evaluations of one quadrature for beta <= 100
   integer, parameter :: goal_evaluations = 200
   !> Largest number of evaluations of one quadrature on graded pieces, beta up to 1e12
   !> and n in 0.1 .. 10 (113 are needed: 2 to 4 pieces of 13 to 49 values, and the
   !> peak's rule; the first layout took up to 240)
   integer, parameter :: goal_piece_evaluations = 150
   !> Goal of F(t), in ulp times (1 + kappa): it is one exponential of the trajectory's
   !> double-double quantities (issue 13: 8.46 ulp at beta = 1e4 with kappa = 0, and
   !> 2.6 (1 + kappa) over timelaw.csv, from the product of rounded factors; now 1.01
   !> there, 1.61 at beta = 4e28, where F moves by kappa = 27 ulps per ulp of t)
   real(wp), parameter :: goal_time_law_force = 2.0_wp
   !> Goal of velocity_at_depth, in ulp of the exact value at the double depth times
   !> (1 + kappa), kappa = x |dv/dx|/|v| = (n+1)(1 - y)/(2y), y = 1 - (x/x_max)^(n+1):
   !> near x_max the velocity moves by kappa ulps per ulp of x, and y by about 1e-17
   !> relative with x_max (its H = h(beta)/beta^2 is a double-double only to 1e-17)
   real(wp), parameter :: goal_velocity = 3.0_wp
   !> Largest second difference of a time across a seam of the graded pieces, in ulp:
   !> the rounding noise of three values of up to goal_max = 4 ulps error each, less
   !> than that in practice (7 seen: for n = 0.1 the time of the peak just below the
   !> compression's seam is 4.25 ulp off by mpmath, on the side that is not cut)
   real(wp), parameter :: goal_seam = 10.0_wp
   !> Goal on the median error of the time of the peak over impact_whole.csv (beta 1.5
   !> to 10, where the compression's one-sided rule holds the peak): 0.55 measured,
   !> before and after issue 17
   real(wp), parameter :: goal_median_peak_whole = 0.6_wp
   !> Exponents of the graded-piece tests
   real(wp), parameter :: piece_exponents(6) = [0.1_wp, 0.5_wp, 1.0_wp, 1.5_wp, 3.0_wp, &
      & 10.0_wp]

   !> Rows of impact.csv: inputs m, c, n, V, b, then (hi, lo) of each output
   type :: impact_table
      real(wp), allocatable :: input(:, :)
      real(wp), allocatable :: ref_hi(:, :), ref_lo(:, :)
   end type impact_table

   !> Rows of timelaw.csv: case (row of impact.csv), t, and (hi, lo) of x, v, F
   type :: timelaw_table
      integer, allocatable :: case_id(:)
      real(wp), allocatable :: t(:)
      real(wp), allocatable :: ref_hi(:, :), ref_lo(:, :)
   end type timelaw_table

   !> Rows of velocity_extremes.csv: case (row of impact_extremes.csv), x, branch, (hi, lo)
   type :: velocity_table
      integer, allocatable :: case_id(:), branch(:)
      real(wp), allocatable :: x(:), ref_hi(:), ref_lo(:)
   end type velocity_table

   !> struct rlimit of <sys/resource.h> (rlim_t is an unsigned long on Linux; the
   !> values used here are far below 2^63)
   type, bind(C) :: rlimit_type
      integer(c_long) :: cur
      integer(c_long) :: max
   end type rlimit_type
   !> RLIMIT_AS of Linux: the address space of the process
   integer(c_int), parameter :: rlimit_as = 9_c_int

   interface
      !> int getrlimit(int resource, struct rlimit *rlim)
      function c_getrlimit(resource, rlim) result(stat) bind(C, name="getrlimit")
         import :: c_int, rlimit_type
         integer(c_int), value :: resource
         type(rlimit_type), intent(out) :: rlim
         integer(c_int) :: stat
      end function c_getrlimit
      !> int setrlimit(int resource, const struct rlimit *rlim)
      function c_setrlimit(resource, rlim) result(stat) bind(C, name="setrlimit")
         import :: c_int, rlimit_type
         integer(c_int), value :: resource
         type(rlimit_type), intent(in) :: rlim
         integer(c_int) :: stat
      end function c_setrlimit
   end interface

   type(impact_table), save :: impacts, extremes, wholes
   type(timelaw_table), save :: timelaws, extreme_laws
   type(velocity_table), save :: velocities
   logical, save :: impacts_loaded = .false., timelaws_loaded = .false.
   logical, save :: extremes_loaded = .false., extreme_laws_loaded = .false.
   logical, save :: velocities_loaded = .false., wholes_loaded = .false.

   !> A linear spring f = k x, written as a user law (not via power_law)
   type, extends(elastic_law) :: linear_spring
      real(wp) :: k = 1.0_wp
   contains
      procedure :: force => linear_force
      procedure :: potential => linear_potential
      procedure :: force_derivative => linear_force_derivative
   end type linear_spring

   !> A stiffening spring f = k1 x + k3 x^3
   type, extends(elastic_law) :: cubic_spring
      real(wp) :: k1 = 1.0_wp, k3 = 1.0_wp
   contains
      procedure :: force => cubic_force
      procedure :: potential => cubic_potential
      procedure :: force_derivative => cubic_force_derivative
   end type cubic_spring

   !> The power law c x^n as a caller would write it (Fortran's **, C's pow): each
   !> value within an ulp or two, not the library's own evaluation
   type, extends(elastic_law) :: plain_power_law
      real(wp) :: c = 1.0_wp, n = 1.5_wp
   contains
      procedure :: force => plain_power_force
      procedure :: potential => plain_power_potential
      procedure :: force_derivative => plain_power_derivative
   end type plain_power_law

   !> A law that goes wrong beyond `limit` (negative potential)
   type, extends(elastic_law) :: broken_law
      real(wp) :: limit = 1.0e-3_wp
   contains
      procedure :: force => broken_force
      procedure :: potential => broken_potential
      procedure :: force_derivative => broken_force_derivative
   end type broken_law

contains

   !> Collect all exported unit tests
   subroutine collect_impact(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("reference-file", test_reference_file), &
         & new_unittest("max-compression", test_max_compression), &
         & new_unittest("peak-force", test_peak_force), &
         & new_unittest("compression-at-peak", test_compression_at_peak), &
         & new_unittest("time-at-peak", test_time_at_peak), &
         & new_unittest("compression-time", test_compression_time), &
         & new_unittest("contact-time", test_contact_time), &
         & new_unittest("restitution", test_restitution), &
         & new_unittest("evaluations", test_evaluations), &
         & new_unittest("time-law", test_time_law), &
         & new_unittest("steel-ball", test_steel_ball), &
         & new_unittest("hertz-limit", test_hertz_limit), &
         & new_unittest("damping-to-zero", test_damping_to_zero), &
         & new_unittest("invalid-contact", test_invalid_contact), &
         & new_unittest("invalid-time-law", test_invalid_time_law), &
         & new_unittest("velocity-at-depth", test_velocity_at_depth), &
         & new_unittest("time-law-samples", test_time_law_samples), &
         & new_unittest("two-bodies", test_two_bodies), &
         & new_unittest("hertz-constant", test_hertz_constant), &
         & new_unittest("target-restitution", test_target_restitution), &
         & new_unittest("resting-contact", test_resting_contact), &
         & new_unittest("user-law-power", test_user_law_power), &
         & new_unittest("user-law-linear", test_user_law_linear), &
         & new_unittest("user-law-cubic", test_user_law_cubic), &
         & new_unittest("user-law-invalid", test_user_law_invalid), &
         & new_unittest("c-interface", test_c_interface), &
         & new_unittest("tiny-exponent", test_tiny_exponent), &
         & new_unittest("fuzz-findings", test_fuzz_findings), &
         & new_unittest("graded-pieces-tile", test_graded_pieces_tile), &
         & new_unittest("graded-pieces-evaluations", test_graded_pieces_evaluations), &
         & new_unittest("graded-pieces-seams", test_graded_pieces_seams), &
         & new_unittest("peak-ratio-series", test_peak_ratio_series), &
         & new_unittest("whole-contact-seam", test_whole_contact_seam), &
         & new_unittest("whole-contact-reference", test_whole_contact_reference), &
         & new_unittest("extremes-reference", test_extremes_reference), &
         & new_unittest("extreme-damping-setup", test_extreme_damping_setup), &
         & new_unittest("extreme-scales", test_extreme_scales), &
         & new_unittest("large-exponents", test_large_exponents), &
         & new_unittest("time-law-force", test_time_law_force), &
         & new_unittest("time-law-end", test_time_law_end), &
         & new_unittest("velocity-reference", test_velocity_reference), &
         & new_unittest("velocity-huge-exponent", test_velocity_huge_exponent), &
         & new_unittest("velocity-bounds", test_velocity_bounds), &
         & new_unittest("times-below-subnormals", test_times_below_subnormals), &
         & new_unittest("time-law-creeping-restitution", test_time_law_creeping), &
         & new_unittest("user-law-ranges", test_user_law_ranges), &
         & new_unittest("user-law-peak-below-range", test_user_law_peak_below_range), &
         & new_unittest("user-law-peak-within-x-max", test_user_law_peak_within_x_max), &
         & new_unittest("damping-extremes", test_damping_extremes), &
         & new_unittest("out-of-memory", test_out_of_memory) &
         & ]
   end subroutine collect_impact

   ! ------------------------------------------------------------------------------
   ! Reference files
   ! ------------------------------------------------------------------------------

   !> Text of an error in ulps
   pure function utoa(x) result(text)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: text
      character(len=16) :: buffer
      if (x >= huge(1.0_wp)) then
         text = "huge"
      else if (x >= 1.0e6_wp) then
         write(buffer, '(es12.3)') x
         text = trim(adjustl(buffer))
      else
         write(buffer, '(f0.3)') x
         text = trim(buffer)
      end if
   end function utoa

   !> Read a CSV reference file: rows after the header, numbers only (list-directed).
   subroutine read_csv(error, name, ncol, data)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: name
      integer, intent(in) :: ncol
      real(wp), allocatable, intent(out) :: data(:, :)
      character(len=:), allocatable :: path
      character(len=2048) :: line
      character(len=256) :: message
      integer :: unit, stat, pass, rows
      logical :: header_seen

      path = reference_path(name)
      open(newunit=unit, file=path, status="old", action="read", iostat=stat, iomsg=message)
      if (stat /= 0) then
         call test_failed(error, "cannot open the reference file " // path, trim(message), &
            & "set HCIMPACT_REFERENCE_DIR to the directory of " // name)
         return
      end if
      do pass = 1, 2
         rows = 0
         header_seen = .false.
         do
            read(unit, '(a)', iostat=stat) line
            if (is_iostat_end(stat)) exit
            if (stat /= 0) then
               call test_failed(error, path // ": read error")
               close(unit)
               return
            end if
            if (len_trim(line) == 0 .or. line(1:1) == "#") cycle
            if (.not. header_seen) then
               header_seen = .true.
               cycle
            end if
            rows = rows + 1
            if (pass == 2) then
               read(line, *, iostat=stat) data(:, rows)
               if (stat /= 0) then
                  call test_failed(error, path // ": malformed row " // int_text(rows), trim(line))
                  close(unit)
                  return
               end if
            end if
         end do
         if (pass == 1) then
            allocate(data(ncol, rows))
            rewind(unit)
         end if
      end do
      close(unit)
   end subroutine read_csv

   !> impact.csv, read once
   subroutine load_impacts(error)
      type(error_type), allocatable, intent(out) :: error
      !$omp critical (test_impact_tables)
      call load_impact_table(error, "impact.csv", impacts, impacts_loaded)
      !$omp end critical (test_impact_tables)
   end subroutine load_impacts

   !> timelaw.csv, read once
   subroutine load_timelaws(error)
      type(error_type), allocatable, intent(out) :: error
      !$omp critical (test_impact_tables)
      call load_timelaw_table(error, "timelaw.csv", timelaws, timelaws_loaded)
      !$omp end critical (test_impact_tables)
   end subroutine load_timelaws

   !> impact_extremes.csv, timelaw_extremes.csv and velocity_extremes.csv, read once
   subroutine load_extremes(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), allocatable :: data(:, :)
      !$omp critical (test_impact_tables)
      call load_impact_table(error, "impact_extremes.csv", extremes, extremes_loaded)
      if (.not. allocated(error)) call load_timelaw_table(error, "timelaw_extremes.csv", &
         & extreme_laws, extreme_laws_loaded)
      if (.not. (allocated(error) .or. velocities_loaded)) then
         call read_csv(error, "velocity_extremes.csv", 5, data)
         if (.not. allocated(error)) then
            velocities%case_id = nint(data(1, :))
            velocities%x = data(2, :)
            velocities%branch = nint(data(3, :))
            velocities%ref_hi = data(4, :)
            velocities%ref_lo = data(5, :)
            velocities_loaded = .true.
         end if
      end if
      !$omp end critical (test_impact_tables)
   end subroutine load_extremes

   !> A table of impacts (the columns of impact.csv), unless loaded already
   subroutine load_impact_table(error, name, table, loaded)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: name
      type(impact_table), intent(inout) :: table
      logical, intent(inout) :: loaded
      real(wp), allocatable :: data(:, :)
      if (loaded) return
      call read_csv(error, name, 5 + 2 * n_outputs, data)
      if (allocated(error)) return
      table%input = data(1:5, :)
      table%ref_hi = data(6:5 + 2 * n_outputs:2, :)
      table%ref_lo = data(7:5 + 2 * n_outputs:2, :)
      loaded = .true.
   end subroutine load_impact_table

   !> A table of time-law points (the columns of timelaw.csv), unless loaded already
   subroutine load_timelaw_table(error, name, table, loaded)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: name
      type(timelaw_table), intent(inout) :: table
      logical, intent(inout) :: loaded
      real(wp), allocatable :: data(:, :)
      if (loaded) return
      call read_csv(error, name, 8, data)
      if (allocated(error)) return
      table%case_id = nint(data(1, :))
      table%t = data(2, :)
      table%ref_hi = data(3:7:2, :)
      table%ref_lo = data(4:8:2, :)
      loaded = .true.
   end subroutine load_timelaw_table

   !> The contact of row i of impact.csv
   function row_contact(i) result(contact)
      integer, intent(in) :: i
      type(contact_type) :: contact
      contact = table_contact(impacts, i)
   end function row_contact

   !> The contact of row i of a table of impacts
   function table_contact(table, i) result(contact)
      type(impact_table), intent(in) :: table
      integer, intent(in) :: i
      type(contact_type) :: contact
      contact = contact_type(mass=table%input(1, i), stiffness=table%input(2, i), &
         & exponent=table%input(3, i), velocity=table%input(4, i), &
         & damping=table%input(5, i))
   end function table_contact

   !> The outputs of an outcome in the order of impact.csv
   pure function outputs(outcome) result(y)
      type(outcome_type), intent(in) :: outcome
      real(wp) :: y(n_outputs)
      y = [outcome%max_compression, outcome%peak_force, outcome%compression_at_peak_force, &
         & outcome%time_at_peak_force, outcome%compression_time, outcome%contact_time, &
         & outcome%restitution]
   end function outputs

   subroutine test_reference_file(error)
      type(error_type), allocatable, intent(out) :: error
      call load_impacts(error)
      if (allocated(error)) return
      call check(error, size(impacts%input, 2) >= 27, &
         & "impact.csv holds " // int_text(size(impacts%input, 2)) // " rows, expected >= 27")
      if (allocated(error)) return
      call load_timelaws(error)
      if (allocated(error)) return
      call check(error, size(timelaws%t) > 0, "timelaw.csv holds no rows")
   end subroutine test_reference_file

   !> Largest and median error of output j over impact.csv against its goals.
   subroutine check_output(error, j)
      type(error_type), allocatable, intent(out) :: error
      integer, intent(in) :: j
      type(outcome_type) :: outcome
      real(wp), allocatable :: err(:), actual(:)
      integer :: i, n, stat, worst

      call load_impacts(error)
      if (allocated(error)) return
      n = size(impacts%input, 2)
      allocate(err(n), actual(n))
      do i = 1, n
         call impact(row_contact(i), outcome, stat)
         if (stat /= hcimpact_ok) then
            call test_failed(error, "impact.csv row " // int_text(i) // ": status " &
               & // int_text(stat))
            return
         end if
         actual(i) = element(outputs(outcome), j)
         err(i) = ulp_error(actual(i), impacts%ref_hi(j, i), impacts%ref_lo(j, i))
      end do
      worst = maxloc(err, dim=1)
      if (err(worst) > goal_max(j) .or. median(err) > goal_median) then
         call test_failed(error, trim(output_names(j)) // ": max " // utoa(err(worst)) &
            & // " ulp, median " // utoa(median(err)) // " ulp over " // int_text(n) &
            & // " impacts (goal: max <= " // utoa(goal_max(j)) // ", median <= " &
            & // utoa(goal_median) // ")", "worst: row " // int_text(worst) // ", got " &
            & // format_real(actual(worst)) // ", reference " &
            & // format_real(impacts%ref_hi(j, worst)))
      end if
   end subroutine check_output

   !> Element j of a vector (so that a function result can be indexed)
   pure function element(y, j) result(x)
      real(wp), intent(in) :: y(:)
      integer, intent(in) :: j
      real(wp) :: x
      x = y(j)
   end function element

   subroutine test_max_compression(error)
      type(error_type), allocatable, intent(out) :: error
      call check_output(error, 1)
   end subroutine test_max_compression

   subroutine test_peak_force(error)
      type(error_type), allocatable, intent(out) :: error
      call check_output(error, 2)
   end subroutine test_peak_force

   subroutine test_compression_at_peak(error)
      type(error_type), allocatable, intent(out) :: error
      call check_output(error, 3)
   end subroutine test_compression_at_peak

   subroutine test_time_at_peak(error)
      type(error_type), allocatable, intent(out) :: error
      call check_output(error, 4)
   end subroutine test_time_at_peak

   subroutine test_compression_time(error)
      type(error_type), allocatable, intent(out) :: error
      call check_output(error, 5)
   end subroutine test_compression_time

   subroutine test_contact_time(error)
      type(error_type), allocatable, intent(out) :: error
      call check_output(error, 6)
   end subroutine test_contact_time

   subroutine test_restitution(error)
      type(error_type), allocatable, intent(out) :: error
      call check_output(error, 7)
   end subroutine test_restitution

   !> At most goal_evaluations per quadrature for every row with beta <= 100.
   subroutine test_evaluations(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      integer :: i, stat, worst, most
      real(wp) :: beta

      call load_impacts(error)
      if (allocated(error)) return
      most = 0
      worst = 0
      do i = 1, size(impacts%input, 2)
         beta = impacts%input(4, i) * impacts%input(5, i)
         if (beta > 100.0_wp) cycle
         call impact(row_contact(i), outcome, stat)
         if (maxval(outcome%evaluations) > most) then
            most = maxval(outcome%evaluations)
            worst = i
         end if
      end do
      call check(error, most <= goal_evaluations, "a quadrature took " // int_text(most) &
         & // " evaluations (row " // int_text(worst) // "), goal <= " &
         & // int_text(goal_evaluations))
   end subroutine test_evaluations

   !> x(t), x'(t), F(t) against timelaw.csv, weighted by their condition numbers.
   subroutine test_time_law(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: worst(3)
      integer :: worst_row(3), k
      character(len=*), parameter :: names(3) = ["x", "v", "F"]

      call load_impacts(error)
      if (allocated(error)) return
      call load_timelaws(error)
      if (allocated(error)) return
      call time_law_errors(error, impacts, timelaws, "timelaw.csv", worst, worst_row)
      if (allocated(error)) return
      do k = 1, 3
         if (worst(k) > goal_time_law) then
            call test_failed(error, names(k) // "(t): error / (1 + condition) = " &
               & // utoa(worst(k)) // " ulp at timelaw.csv row " // int_text(worst_row(k)) &
               & // " (goal <= " // utoa(goal_time_law) // ")")
            return
         end if
      end do
   end subroutine test_time_law

   !> The largest error/(1 + condition) of x(t), x'(t), F(t) over a table of time-law
   !> points (and its row), with the condition numbers kappa = t |y'|/|y| of each
   !> output from the equation of motion; only points with kappa <= kappa_max (default:
   !> all) count. A status other than hcimpact_ok fails.
   subroutine time_law_errors(error, table, laws, name, worst, worst_row, kappa_max)
      type(error_type), allocatable, intent(out) :: error
      type(impact_table), intent(in) :: table
      type(timelaw_table), intent(in) :: laws
      character(len=*), intent(in) :: name
      real(wp), intent(out) :: worst(3)
      integer, intent(out) :: worst_row(3)
      real(wp), intent(in), optional :: kappa_max
      real(wp) :: x(1), v(1), f(1), err(3), cond(3), m, c, n, b, t, xr, vr, fr
      integer :: i, id, stat, k

      worst = 0.0_wp
      worst_row = 0
      do i = 1, size(laws%t)
         id = laws%case_id(i)
         t = laws%t(i)
         call time_law(table_contact(table, id), [t], x, v, f, stat)
         if (stat /= hcimpact_ok) then
            call test_failed(error, name // " row " // int_text(i) // ": status " &
               & // int_text(stat))
            return
         end if
         err(1) = ulp_error(x(1), laws%ref_hi(1, i), laws%ref_lo(1, i))
         err(2) = ulp_error(v(1), laws%ref_hi(2, i), laws%ref_lo(2, i))
         err(3) = ulp_error(f(1), laws%ref_hi(3, i), laws%ref_lo(3, i))
         ! condition numbers t |y'/y| from the equation of motion:
         ! x' = v, v' = -F/m, (ln F)' = n v/x - (b/m) c x^n
         m = table%input(1, id)
         c = table%input(2, id)
         n = table%input(3, id)
         b = table%input(5, id)
         xr = laws%ref_hi(1, i)
         vr = laws%ref_hi(2, i)
         fr = laws%ref_hi(3, i)
         cond = 0.0_wp
         if (xr > 0.0_wp) then
            ! (each a product of positive factors, formed from their logarithms: the
            ! products themselves leave the double range at the extremes)
            cond(1) = t * abs(vr) / xr
            ! (|x'| at least the smallest normal number: x' passes through 0 at the
            ! turning point; at the extremes it is 1e-44 V there)
            cond(2) = 0.0_wp
            if (fr > 0.0_wp) cond(2) = exp(log(t) + log(fr) - log(m) &
               & - log(max(abs(vr), tiny(1.0_wp))))
            ! d ln F/dt = n x'/x - (b/m) c x^n
            cond(3) = t * abs(n * vr / xr)
            if (b > 0.0_wp) cond(3) = t * abs(n * vr / xr - exp(log(b) - log(m) + log(c) &
               & + n * log(xr)))
         else
            ! x = F = 0 exactly (t = 0 or past the end): compare absolutely
            if (x(1) == 0.0_wp) err(1) = 0.0_wp
            if (f(1) == 0.0_wp) err(3) = 0.0_wp
         end if
         do k = 1, 3
            if (present(kappa_max)) then
               if (cond(k) > kappa_max) cycle
            end if
            if (err(k) / (1.0_wp + cond(k)) > worst(k)) then
               worst(k) = err(k) / (1.0_wp + cond(k))
               worst_row(k) = i
            end if
         end do
      end do
   end subroutine time_law_errors

   ! ------------------------------------------------------------------------------
   ! The seed's example and the limits
   ! ------------------------------------------------------------------------------

   !> MODEL.md's steel ball (m = 0.1 kg, c = 1.7135e10, n = 3/2, b = 0.1 s/m) to the
   !> 16-17 digits given there, and the same ball with b = 0.
   subroutine test_steel_ball(error)
      type(error_type), allocatable, intent(out) :: error
      ! V, k, x_max, F_max, t_contact, t_compression
      real(wp), parameter :: table(6, 6) = reshape([ &
         & 0.5_wp, 0.9677385785309325_wp, 1.9893579643308693e-5_wp, 1521.9160892838993_wp, &
         & 1.1904584326151915e-4_wp, 5.8859751374268991e-5_wp, &
         & 1.0_wp, 0.93747557994990506_wp, 3.4204625278143626e-5_wp, 3441.1122331638547_wp, &
         & 1.0399469349496538e-4_wp, 5.0856853135224197e-5_wp, &
         & 2.0_wp, 0.88218998624730638_wp, 5.8156728355576902e-5_wp, 7709.8673680931372_wp, &
         & 9.1181013535146273e-5_wp, 4.3649774771233254e-5_wp, &
         & 3.0_wp, 0.83286979226560167_wp, 7.8679668816420547e-5_wp, 12322.929545918441_wp, &
         & 8.4701327451018694e-5_wp, 3.9721750506275539e-5_wp, &
         & 4.0_wp, 0.78853912590706515_wp, 9.7008052543829528e-5_wp, 17199.324205797322_wp, &
         & 8.0573545729318647e-5_wp, 3.7040161639485758e-5_wp, &
         & 5.0_wp, 0.74843493159743416_wp, 1.1372585556115339e-4_wp, 22315.267380743067_wp, &
         & 7.7655384043269703e-5_wp, 3.5014163526885175e-5_wp], [6, 6])
      type(outcome_type) :: outcome
      real(wp) :: actual(5)
      integer :: i, j, stat
      character(len=*), parameter :: names(5) = [character(len=16) :: "restitution", &
         & "x_max", "F_max", "t_contact", "t_compression"]

      do i = 1, 6
         call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
            & damping=0.1_wp, velocity=table(1, i)), outcome, stat)
         call check(error, stat, hcimpact_ok)
         if (allocated(error)) return
         actual = [outcome%restitution, outcome%max_compression, outcome%peak_force, &
            & outcome%contact_time, outcome%compression_time]
         do j = 1, 5
            ! the decimals carry 16-17 digits: within 2 ulp of the double they round to
            if (ulp_error(actual(j), table(j + 1, i)) > 2.0_wp) then
               call test_failed(error, "steel ball, V = " // format_real(table(1, i)) // ": " &
                  & // trim(names(j)) // " = " // format_real(actual(j)) // ", MODEL.md " &
                  & // format_real(table(j + 1, i)))
               return
            end if
         end do
      end do
      call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.0_wp, velocity=1.0_wp), outcome, stat)
      call check(error, ulp_error(outcome%max_compression, 3.5092181079293274e-5_wp) <= 2.0_wp &
         & .and. ulp_error(outcome%contact_time, 1.0328594573451282e-4_wp) <= 2.0_wp &
         & .and. ulp_error(outcome%peak_force, 3562.0470473908028_wp) <= 2.0_wp &
         & .and. outcome%restitution == 1.0_wp, "steel ball, b = 0: x_max " &
         & // format_real(outcome%max_compression) // ", t_c " &
         & // format_real(outcome%contact_time) // ", F " // format_real(outcome%peak_force))
   end subroutine test_steel_ball

   !> b = 0: t_c = 2 (x_max/V) sqrt(pi) Gamma(1 + 1/(n+1))/Gamma(1/2 + 1/(n+1)) (MODEL.md),
   !> symmetric phases, peak at x_max.
   subroutine test_hertz_limit(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: exponents(5) = [1.0_wp, 1.5_wp, 2.0_wp, 3.0_wp, 0.5_wp]
      ! t_c V/x_max from MODEL.md for n = 1, 3/2, 2 (pi for n = 1); 0: not given
      real(wp), parameter :: model_md(5) = [3.141592653589793_wp, 2.9432751843247047_wp, &
         & 2.8043642106509085_wp, 0.0_wp, 0.0_wp]
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      real(wp) :: ratio, q, closed
      integer :: i, stat

      do i = 1, size(exponents)
         contact = contact_type(mass=0.7_wp, stiffness=3.0e7_wp, exponent=exponents(i), &
            & damping=0.0_wp, velocity=1.3_wp)
         call impact(contact, outcome, stat)
         call check(error, stat, hcimpact_ok)
         if (allocated(error)) return
         ratio = outcome%contact_time * contact%velocity / outcome%max_compression
         q = 1.0_wp / (exponents(i) + 1.0_wp)
         closed = 2.0_wp * sqrt(acos(-1.0_wp)) * gamma(1.0_wp + q) / gamma(0.5_wp + q)
         call check_close(error, ratio, closed, rel=2.0e-15_wp, &
            & message="Hertz contact time, n = " // format_real(exponents(i)))
         if (allocated(error)) return
         if (model_md(i) > 0.0_wp) then
            call check_close(error, ratio, model_md(i), rel=1.0e-15_wp, &
               & message="MODEL.md constant, n = " // format_real(exponents(i)))
            if (allocated(error)) return
         end if
         call check_close(error, 2.0_wp * outcome%compression_time, outcome%contact_time, &
            & rel=4.0_wp * epsilon(1.0_wp), message="b = 0: compression is half the contact")
         if (allocated(error)) return
         call check(error, outcome%compression_at_peak_force == outcome%max_compression &
            & .and. outcome%time_at_peak_force == outcome%compression_time &
            & .and. outcome%restitution == 1.0_wp .and. outcome%energy_loss_ratio == 0.0_wp, &
            & "b = 0: peak at x_max, k = 1")
         if (allocated(error)) return
         call check_close(error, outcome%peak_force, contact%stiffness &
            & * outcome%max_compression**exponents(i), rel=8.0_wp * epsilon(1.0_wp), &
            & message="b = 0: peak force c x_max^n")
         if (allocated(error)) return
      end do
   end subroutine test_hertz_limit

   !> b -> 0 approaches the values at b = 0 monotonically, without NaN.
   subroutine test_damping_to_zero(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome, previous, elastic
      real(wp) :: b
      integer :: i, stat
      logical :: ok

      call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.0_wp, velocity=1.0_wp), elastic, stat)
      ! b = 1e-1, 1e-2, ..., 1e-20, then down to 1e-300 in steps of 1e-10, then tiny
      do i = 1, 50
         if (i <= 20) then
            b = 10.0_wp**(-real(i, wp))
         else if (i < 50) then
            b = 10.0_wp**(-real(20 + 10 * (i - 20), wp))
         else
            b = tiny(1.0_wp)
         end if
         call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
            & damping=b, velocity=1.0_wp), outcome, stat)
         call check(error, stat == hcimpact_ok .and. all(ieee_is_finite(outputs(outcome))), &
            & "b = " // format_real(b) // ": status " // int_text(stat) // " or a NaN")
         if (allocated(error)) return
         if (i > 1) then
            ! towards b = 0: x_max, k and the compression time grow, the contact time
            ! shrinks (up to rounding)
            ok = outcome%max_compression >= previous%max_compression &
               & - 2.0_wp * spacing(previous%max_compression)
            ok = ok .and. outcome%restitution >= previous%restitution &
               & - 2.0_wp * spacing(previous%restitution)
            ok = ok .and. outcome%contact_time <= previous%contact_time &
               & + 2.0_wp * spacing(previous%contact_time)
            ok = ok .and. outcome%compression_time >= previous%compression_time &
               & - 2.0_wp * spacing(previous%compression_time)
            ok = ok .and. outcome%contact_time >= elastic%contact_time &
               & - 2.0_wp * spacing(elastic%contact_time)
            ok = ok .and. outcome%max_compression <= elastic%max_compression &
               & + 2.0_wp * spacing(elastic%max_compression)
            call check(error, ok, "not monotone towards b = 0 at b = " // format_real(b))
            if (allocated(error)) return
         end if
         previous = outcome
      end do
      ! the smallest b gives the elastic values
      call check(error, all(abs(outputs(outcome) - outputs(elastic)) &
         & <= 2.0_wp * spacing(outputs(elastic)) .or. outputs(outcome) == outputs(elastic)), &
         & "b = tiny differs from b = 0")
   end subroutine test_damping_to_zero

   ! ------------------------------------------------------------------------------
   ! Invalid input
   ! ------------------------------------------------------------------------------

   !> Status and NaN outcome for a bad contact.
   subroutine check_bad(error, contact, expected, what)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type), intent(in) :: contact
      integer, intent(in) :: expected
      character(len=*), intent(in) :: what
      type(outcome_type) :: outcome
      integer :: stat
      call impact(contact, outcome, stat)
      call check(error, stat == expected .and. all(ieee_is_nan(outputs(outcome))) &
         & .and. ieee_is_nan(outcome%energy_loss_ratio) &
         & .and. ieee_is_nan(outcome%rebound_velocity), &
         & what // ": status " // int_text(stat) // ", expected " // int_text(expected) &
         & // " and NaN outputs")
   end subroutine check_bad

   subroutine test_invalid_contact(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: good, bad
      real(wp) :: nan, inf
      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      good = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=1.0_wp)
      bad = good; bad%mass = 0.0_wp
      call check_bad(error, bad, hcimpact_err_mass, "mass 0")
      if (allocated(error)) return
      bad = good; bad%mass = -1.0_wp
      call check_bad(error, bad, hcimpact_err_mass, "mass -1")
      if (allocated(error)) return
      bad = good; bad%mass = nan
      call check_bad(error, bad, hcimpact_err_not_finite, "mass NaN")
      if (allocated(error)) return
      bad = good; bad%stiffness = inf
      call check_bad(error, bad, hcimpact_err_not_finite, "stiffness Inf")
      if (allocated(error)) return
      bad = good; bad%stiffness = 0.0_wp
      call check_bad(error, bad, hcimpact_err_stiffness, "stiffness 0")
      if (allocated(error)) return
      bad = good; bad%exponent = 0.0_wp
      call check_bad(error, bad, hcimpact_err_exponent, "exponent 0")
      if (allocated(error)) return
      bad = good; bad%exponent = -1.5_wp
      call check_bad(error, bad, hcimpact_err_exponent, "exponent -1.5")
      if (allocated(error)) return
      bad = good; bad%velocity = 0.0_wp
      call check_bad(error, bad, hcimpact_err_velocity, "velocity 0")
      if (allocated(error)) return
      bad = good; bad%velocity = -2.0_wp
      call check_bad(error, bad, hcimpact_err_velocity, "velocity -2")
      if (allocated(error)) return
      bad = good; bad%velocity = -inf
      call check_bad(error, bad, hcimpact_err_not_finite, "velocity -Inf")
      if (allocated(error)) return
      bad = good; bad%damping = -1.0e-3_wp
      call check_bad(error, bad, hcimpact_err_damping, "damping < 0")
      if (allocated(error)) return
      bad = good; bad%damping = nan
      call check_bad(error, bad, hcimpact_err_not_finite, "damping NaN")
      if (allocated(error)) return
      ! results beyond the double range
      bad = good; bad%mass = 1.0e300_wp; bad%velocity = 1.0e300_wp; bad%stiffness = 1.0e-300_wp
      call check_bad(error, bad, hcimpact_err_domain, "x_max overflows")
      if (allocated(error)) return
      ! the default contact is incomplete
      call check_bad(error, contact_type(), hcimpact_err_mass, "default contact")
   end subroutine test_invalid_contact

   subroutine test_invalid_time_law(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: contact
      real(wp) :: x(3), v(3), f(3), x2(2)
      real(wp), allocatable :: ts(:), xs(:), vs(:), fs(:)
      integer :: stat
      contact = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=1.0_wp)
      call time_law(contact, [0.0_wp, 1.0e-5_wp, ieee_value(1.0_wp, ieee_quiet_nan)], &
         & x, v, f, stat)
      call check(error, stat == hcimpact_err_not_finite .and. all(ieee_is_nan(x)), &
         & "NaN time: status " // int_text(stat))
      if (allocated(error)) return
      call time_law(contact, [0.0_wp, 1.0e-5_wp, 2.0e-5_wp], x2, v, f, stat)
      call check(error, stat, hcimpact_err_size, "arrays of different sizes")
      if (allocated(error)) return
      contact%mass = -1.0_wp
      call time_law(contact, [0.0_wp, 1.0e-5_wp, 2.0e-5_wp], x, v, f, stat)
      call check(error, stat == hcimpact_err_mass .and. all(ieee_is_nan(f)), &
         & "bad mass: status " // int_text(stat))
      if (allocated(error)) return
      contact%mass = 0.1_wp
      call time_law_samples(contact, 1, ts, xs, vs, fs, stat)
      call check(error, stat, hcimpact_err_size, "one sample")
   end subroutine test_invalid_time_law

   ! ------------------------------------------------------------------------------
   ! Velocity at depth, time law samples
   ! ------------------------------------------------------------------------------

   subroutine test_velocity_at_depth(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      real(wp) :: v, v2, x(1), vt(1), f(1), t, xm
      integer :: stat

      contact = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=2.0_wp)
      call impact(contact, outcome, stat)
      ! the ends of the branches
      call velocity_at_depth(contact, 0.0_wp, compression_branch, v, stat)
      call check(error, ulp_error(v, contact%velocity) <= 1.0_wp .and. stat == hcimpact_ok, &
         & "V(0) on compression = " // format_real(v))
      if (allocated(error)) return
      call velocity_at_depth(contact, 0.0_wp, restitution_branch, v, stat)
      call check(error, ulp_error(v, outcome%rebound_velocity) <= 2.0_wp, &
         & "V(0) on restitution = " // format_real(v) // ", -kV = " &
         & // format_real(outcome%rebound_velocity))
      if (allocated(error)) return
      call velocity_at_depth(contact, outcome%max_compression, compression_branch, v, stat)
      call check(error, abs(v) <= 1.0e-7_wp * contact%velocity .and. stat == hcimpact_ok, &
         & "V(x_max) = " // format_real(v))
      if (allocated(error)) return
      ! agrees with the time law, on both branches
      t = 0.3_wp * outcome%compression_time
      call time_law(contact, [t], x, vt, f, stat)
      call velocity_at_depth(contact, x(1), compression_branch, v, stat)
      call check_close(error, v, vt(1), rel=1.0e-14_wp, message="V(x(t)) = x'(t) in compression")
      if (allocated(error)) return
      t = outcome%compression_time + 0.6_wp * (outcome%contact_time - outcome%compression_time)
      call time_law(contact, [t], x, vt, f, stat)
      call velocity_at_depth(contact, x(1), restitution_branch, v, stat)
      call check_close(error, v, vt(1), rel=1.0e-13_wp, message="V(x(t)) = x'(t) in restitution")
      if (allocated(error)) return
      ! b -> 0 and b = 0: V(x) = +-sqrt(V^2 - 2 Pi(x)/m)
      contact%damping = 1.0e-12_wp
      call impact(contact, outcome, stat)
      xm = 0.7_wp * outcome%max_compression
      call velocity_at_depth(contact, xm, restitution_branch, v, stat)
      v2 = -sqrt(contact%velocity**2 - 2.0_wp * contact%stiffness * xm**2.5_wp &
         & / (2.5_wp * contact%mass))
      call check_close(error, v, v2, rel=1.0e-10_wp, message="b -> 0: energy conservation")
      if (allocated(error)) return
      contact%damping = 0.0_wp
      call velocity_at_depth(contact, xm, compression_branch, v, stat)
      call check_close(error, v, -v2, rel=1.0e-13_wp, message="b = 0: energy conservation")
      if (allocated(error)) return
      ! bad input
      call velocity_at_depth(contact, -1.0e-9_wp, compression_branch, v, stat)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(v), "x < 0")
      if (allocated(error)) return
      call velocity_at_depth(contact, 1.0_wp, compression_branch, v, stat)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(v), "x > x_max")
      if (allocated(error)) return
      call velocity_at_depth(contact, xm, 3, v, stat)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(v), "bad branch")
      if (allocated(error)) return
      call velocity_at_depth(contact, ieee_value(1.0_wp, ieee_quiet_nan), compression_branch, &
         & v, stat)
      call check(error, stat == hcimpact_err_not_finite .and. ieee_is_nan(v), "x NaN")
   end subroutine test_velocity_at_depth

   subroutine test_time_law_samples(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      real(wp), allocatable :: t(:), x(:), v(:), f(:)
      integer :: stat, n

      contact = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=3.0_wp)
      call impact(contact, outcome, stat)
      n = 101
      call time_law_samples(contact, n, t, x, v, f, stat)
      call check(error, stat, hcimpact_ok)
      if (allocated(error)) return
      call check(error, size(t) == n .and. t(1) == 0.0_wp .and. t(n) == outcome%contact_time, &
         & "sample times")
      if (allocated(error)) return
      call check(error, x(1) == 0.0_wp .and. x(n) == 0.0_wp .and. f(1) == 0.0_wp &
         & .and. f(n) == 0.0_wp .and. v(1) == contact%velocity &
         & .and. v(n) == outcome%rebound_velocity, "ends of the contact")
      if (allocated(error)) return
      call check(error, all(x >= 0.0_wp) .and. maxval(x) <= outcome%max_compression &
         & * (1.0_wp + 4.0_wp * epsilon(1.0_wp)) .and. maxval(f) <= outcome%peak_force &
         & * (1.0_wp + 4.0_wp * epsilon(1.0_wp)) .and. all(f >= 0.0_wp), &
         & "x and F within [0, x_max] and [0, F_max]")
      if (allocated(error)) return
      ! the velocity decreases all along the contact
      call check(error, all(v(2:) <= v(:n - 1)), "x' decreasing")
   end subroutine test_time_law_samples

   ! ------------------------------------------------------------------------------
   ! Two bodies, Hertz constant, target restitution
   ! ------------------------------------------------------------------------------

   subroutine test_two_bodies(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: m1, m2, v1, v2, k, w1, w2, inf
      integer :: stat
      type(outcome_type) :: outcome

      inf = ieee_value(1.0_wp, ieee_positive_inf)
      m1 = 0.25_wp
      m2 = 0.75_wp
      v1 = 3.0_wp
      v2 = -0.5_wp
      call check_close(error, effective_mass(m1, m2), 0.1875_wp, rel=epsilon(1.0_wp), &
         & message="effective mass")
      if (allocated(error)) return
      call impact(contact_type(mass=effective_mass(m1, m2), stiffness=1.0e9_wp, &
         & exponent=1.5_wp, damping=0.2_wp, velocity=v1 - v2), outcome, stat)
      k = outcome%restitution
      call two_body_velocities(m1, m2, v1, v2, k, w1, w2, stat)
      call check(error, stat, hcimpact_ok)
      if (allocated(error)) return
      call check_close(error, m1 * w1 + m2 * w2, m1 * v1 + m2 * v2, rel=4.0_wp * epsilon(1.0_wp), &
         & message="momentum conserved")
      if (allocated(error)) return
      call check_close(error, w1 - w2, outcome%rebound_velocity, rel=8.0_wp * epsilon(1.0_wp), &
         & message="relative rebound velocity -kV")
      if (allocated(error)) return
      ! energy lost = (1 - k^2) of the kinetic energy of the relative motion
      call check_close(error, 0.5_wp * (m1 * v1**2 + m2 * v2**2 - m1 * w1**2 - m2 * w2**2), &
         & outcome%energy_loss_ratio * 0.5_wp * effective_mass(m1, m2) * (v1 - v2)**2, &
         & rel=1.0e-14_wp, message="energy lost")
      if (allocated(error)) return
      ! an immovable obstacle
      call check(error, effective_mass(m1, inf) == m1, "effective mass against a wall")
      if (allocated(error)) return
      call two_body_velocities(m1, inf, v1, 0.0_wp, 0.5_wp, w1, w2, stat)
      call check(error, w1 == -1.5_wp .and. w2 == 0.0_wp .and. stat == hcimpact_ok, &
         & "rebound from a wall")
      if (allocated(error)) return
      ! errors
      call two_body_velocities(m1, m2, v2, v1, k, w1, w2, stat)
      call check(error, stat == hcimpact_err_velocity .and. ieee_is_nan(w1), "not approaching")
      if (allocated(error)) return
      call two_body_velocities(0.0_wp, m2, v1, v2, k, w1, w2, stat)
      call check(error, stat == hcimpact_err_mass .and. ieee_is_nan(w2), "zero mass")
      if (allocated(error)) return
      call two_body_velocities(m1, m2, v1, v2, 1.5_wp, w1, w2, stat)
      call check(error, stat, hcimpact_err_restitution, "k > 1")
      if (allocated(error)) return
      call check(error, ieee_is_nan(effective_mass(-1.0_wp, m2)) &
         & .and. ieee_is_nan(effective_mass(inf, m2)), "effective mass of bad masses")
   end subroutine test_two_bodies

   subroutine test_hertz_constant(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: c, inf, r
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      ! MODEL.md: steel ball of R = 1.452 cm on a steel plate, E = 2e11 Pa, nu = 0.25
      ! (the seed's data) gives c = 1.7138e10 (the seed prints the rounded 1.7135e10)
      r = 0.01452_wp
      c = hertz_constant(2.0e11_wp, 0.25_wp, r, 2.0e11_wp, 0.25_wp, inf)
      call check_close(error, c, 1.7138e10_wp, rel=5.0e-5_wp, message="steel ball on a plate")
      if (allocated(error)) return
      call check_close(error, c, (2.0_wp / 3.0_wp) * 2.0e11_wp * sqrt(r) / (1.0_wp - 0.25_wp**2), &
         & rel=4.0_wp * epsilon(1.0_wp), message="c = (2/3) E sqrt(R)/(1 - nu^2)")
      if (allocated(error)) return
      ! symmetric in the bodies; two equal spheres: R* = R/2
      call check_close(error, &
         & hertz_constant(1.0e9_wp, 0.3_wp, 0.01_wp, 2.0e11_wp, 0.25_wp, 0.02_wp), &
         & hertz_constant(2.0e11_wp, 0.25_wp, 0.02_wp, 1.0e9_wp, 0.3_wp, 0.01_wp), &
         & rel=2.0_wp * epsilon(1.0_wp), message="symmetry")
      if (allocated(error)) return
      call check_close(error, hertz_constant(2.0e11_wp, 0.25_wp, r, 2.0e11_wp, 0.25_wp, r), &
         & c / sqrt(2.0_wp), rel=4.0_wp * epsilon(1.0_wp), message="two equal balls")
      if (allocated(error)) return
      call check(error, ieee_is_nan(hertz_constant(0.0_wp, 0.3_wp, r, 2.0e11_wp, 0.25_wp, r)) &
         & .and. ieee_is_nan(hertz_constant(2.0e11_wp, 0.6_wp, r, 2.0e11_wp, 0.25_wp, r)) &
         & .and. ieee_is_nan(hertz_constant(2.0e11_wp, 0.3_wp, -r, 2.0e11_wp, 0.25_wp, r)) &
         & .and. ieee_is_nan(hertz_constant(2.0e11_wp, 0.3_wp, inf, 2.0e11_wp, 0.25_wp, inf)) &
         & .and. ieee_is_nan(hertz_constant(2.0e11_wp, ieee_value(1.0_wp, ieee_quiet_nan), r, &
         & 2.0e11_wp, 0.25_wp, r)), "invalid materials or radii give NaN")
   end subroutine test_hertz_constant

   !> The damping for a target e gives k = e at the design speed.
   subroutine test_target_restitution(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: targets(5) = [0.99_wp, 0.9_wp, 0.5_wp, 0.1_wp, 0.01_wp]
      type(outcome_type) :: outcome
      real(wp) :: b
      integer :: i, stat

      do i = 1, size(targets)
         call damping_for_restitution(targets(i), 2.0_wp, b, stat)
         call check(error, stat, hcimpact_ok)
         if (allocated(error)) return
         call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
            & damping=b, velocity=2.0_wp), outcome, stat)
         call check_close(error, outcome%restitution, targets(i), rel=1.0e-14_wp, &
            & message="k at the design speed, e = " // format_real(targets(i)))
         if (allocated(error)) return
      end do
      call damping_for_restitution(1.0_wp, 2.0_wp, b, stat)
      call check(error, b == 0.0_wp .and. stat == hcimpact_ok, "e = 1: no damping")
      if (allocated(error)) return
      call damping_for_restitution(0.0_wp, 2.0_wp, b, stat)
      call check(error, stat == hcimpact_err_restitution .and. ieee_is_nan(b), "e = 0")
      if (allocated(error)) return
      call damping_for_restitution(1.5_wp, 2.0_wp, b, stat)
      call check(error, stat, hcimpact_err_restitution, "e > 1")
      if (allocated(error)) return
      call damping_for_restitution(ieee_value(1.0_wp, ieee_quiet_nan), 2.0_wp, b, stat)
      call check(error, stat, hcimpact_err_not_finite, "e NaN")
      if (allocated(error)) return
      call damping_for_restitution(0.5_wp, -1.0_wp, b, stat)
      call check(error, stat, hcimpact_err_velocity, "V < 0")
      if (allocated(error)) return
      call damping_for_restitution(0.5_wp, 1.0_wp, b, stat, min_velocity=0.0_wp)
      call check(error, stat, hcimpact_err_velocity, "min_velocity = 0")
   end subroutine test_target_restitution

   !> V -> 0 in target-restitution mode: b stays finite, and so does every force.
   subroutine test_resting_contact(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      real(wp) :: b, b_min, v
      integer :: i, stat

      call damping_for_restitution(0.5_wp, default_min_velocity, b_min, stat)
      do i = 0, 12
         v = 10.0_wp**(-3 - 2 * i)
         call damping_for_restitution(0.5_wp, v, b, stat)
         call check(error, stat == hcimpact_ok .and. b == b_min, &
            & "below min_velocity b is computed there: V = " // format_real(v))
         if (allocated(error)) return
         call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
            & damping=b, velocity=v), outcome, stat)
         call check(error, stat == hcimpact_ok .and. all(ieee_is_finite(outputs(outcome))) &
            & .and. outcome%restitution >= 0.5_wp, "V = " // format_real(v) // ": status " &
            & // int_text(stat) // ", k = " // format_real(outcome%restitution))
         if (allocated(error)) return
      end do
      call damping_for_restitution(0.5_wp, 0.0_wp, b, stat)
      call check(error, stat == hcimpact_ok .and. b == b_min, "V = 0")
      if (allocated(error)) return
      call damping_for_restitution(0.5_wp, 0.0_wp, b, stat, min_velocity=1.0e-6_wp)
      call check_close(error, b, 1.0e3_wp * b_min, rel=4.0_wp * epsilon(1.0_wp), &
         & message="min_velocity = 1e-6")
   end subroutine test_resting_contact

   ! ------------------------------------------------------------------------------
   ! User laws
   ! ------------------------------------------------------------------------------

   pure function linear_force(self, x) result(y)
      class(linear_spring), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%k * x
   end function linear_force

   pure function linear_potential(self, x) result(y)
      class(linear_spring), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = 0.5_wp * self%k * x * x
   end function linear_potential

   pure function linear_force_derivative(self, x) result(y)
      class(linear_spring), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%k + 0.0_wp * x
   end function linear_force_derivative

   pure function plain_power_force(self, x) result(y)
      class(plain_power_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%c * x**self%n
   end function plain_power_force

   pure function plain_power_potential(self, x) result(y)
      class(plain_power_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%c * x**(self%n + 1.0_wp) / (self%n + 1.0_wp)
   end function plain_power_potential

   pure function plain_power_derivative(self, x) result(y)
      class(plain_power_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%c * self%n * x**(self%n - 1.0_wp)
   end function plain_power_derivative

   pure function cubic_force(self, x) result(y)
      class(cubic_spring), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = x * (self%k1 + self%k3 * x * x)
   end function cubic_force

   pure function cubic_potential(self, x) result(y)
      class(cubic_spring), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = x * x * (0.5_wp * self%k1 + 0.25_wp * self%k3 * x * x)
   end function cubic_potential

   pure function cubic_force_derivative(self, x) result(y)
      class(cubic_spring), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = self%k1 + 3.0_wp * self%k3 * x * x
   end function cubic_force_derivative

   pure function broken_force(self, x) result(y)
      class(broken_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = 1.0e3_wp * x
      if (x > self%limit) y = -1.0_wp
   end function broken_force

   pure function broken_potential(self, x) result(y)
      class(broken_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = 500.0_wp * x * x
      if (x > self%limit) y = -1.0_wp
   end function broken_potential

   pure function broken_force_derivative(self, x) result(y)
      class(broken_law), intent(in) :: self
      real(wp), intent(in) :: x
      real(wp) :: y
      y = 1.0e3_wp
      if (x > self%limit) y = -1.0_wp
   end function broken_force_derivative

   !> power_law through impact_law gives the power-law results.
   subroutine test_user_law_power(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: dampings(4) = [0.0_wp, 0.1_wp, 3.0_wp, 500.0_wp]
      type(contact_type) :: contact
      type(outcome_type) :: direct, general
      real(wp) :: t(4), x1(4), v1(4), f1(4), x2(4), v2(4), f2(4)
      integer :: i, stat

      do i = 1, size(dampings)
         contact = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
            & damping=dampings(i), velocity=2.0_wp)
         call impact(contact, direct, stat)
         call impact_law(power_law(stiffness=contact%stiffness, exponent=contact%exponent), &
            & contact%mass, contact%damping, contact%velocity, general, stat)
         call check(error, stat, hcimpact_ok)
         if (allocated(error)) return
         call check(error, all(abs(outputs(general) - outputs(direct)) &
            & <= 1.0e-14_wp * abs(outputs(direct))), "impact_law(power_law) differs, b = " &
            & // format_real(dampings(i)))
         if (allocated(error)) return
         t = [0.1_wp, 0.7_wp, 1.3_wp, 1.9_wp] * direct%compression_time
         call time_law(contact, t, x1, v1, f1, stat)
         call time_law(power_law(stiffness=contact%stiffness, exponent=contact%exponent), &
            & contact%mass, contact%damping, contact%velocity, t, x2, v2, f2, stat)
         call check(error, stat == hcimpact_ok .and. all(abs(x2 - x1) <= 1.0e-13_wp * x1) &
            & .and. all(abs(f2 - f1) <= 1.0e-13_wp * f1) &
            & .and. all(abs(v2 - v1) <= 1.0e-13_wp * contact%velocity), &
            & "time law of power_law differs, b = " // format_real(dampings(i)))
         if (allocated(error)) return
      end do
   end subroutine test_user_law_power

   !> A linear spring: t_c = pi sqrt(m/k) and x_max = V sqrt(m/k) for b = 0; k(beta)
   !> does not depend on the law.
   subroutine test_user_law_linear(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome, power
      real(wp) :: m, k, v
      integer :: stat
      m = 2.0_wp
      k = 8.0e5_wp
      v = 0.5_wp
      call impact_law(linear_spring(k=k), m, 0.0_wp, v, outcome, stat)
      call check(error, stat, hcimpact_ok)
      if (allocated(error)) return
      call check_close(error, outcome%contact_time, acos(-1.0_wp) * sqrt(m / k), rel=1.0e-14_wp, &
         & message="linear spring: pi sqrt(m/k)")
      if (allocated(error)) return
      call check_close(error, outcome%max_compression, v * sqrt(m / k), rel=1.0e-15_wp, &
         & message="linear spring: V sqrt(m/k)")
      if (allocated(error)) return
      call check_close(error, outcome%peak_force, k * v * sqrt(m / k), rel=1.0e-15_wp, &
         & message="linear spring: peak force")
      if (allocated(error)) return
      call impact_law(linear_spring(k=k), m, 0.4_wp, v, outcome, stat)
      call impact(contact_type(mass=m, stiffness=k, exponent=1.0_wp, damping=0.4_wp, &
         & velocity=v), power, stat)
      call check(error, outcome%restitution == power%restitution &
         & .and. abs(outcome%contact_time - power%contact_time) <= 1.0e-14_wp &
         & * power%contact_time .and. abs(outcome%peak_force - power%peak_force) <= 1.0e-14_wp &
         & * power%peak_force, "linear spring = power law n = 1")
   end subroutine test_user_law_linear

   !> A stiffening spring: energy at x_max, symmetric elastic impact, k independent of
   !> the law.
   subroutine test_user_law_cubic(error)
      type(error_type), allocatable, intent(out) :: error
      type(cubic_spring) :: law
      type(outcome_type) :: outcome, power
      real(wp) :: m, v, x(1), vt(1), f(1)
      integer :: stat
      law = cubic_spring(k1=1.0e5_wp, k3=1.0e11_wp)
      m = 0.3_wp
      v = 1.7_wp
      call impact_law(law, m, 0.0_wp, v, outcome, stat)
      call check(error, stat, hcimpact_ok)
      if (allocated(error)) return
      call check_close(error, law%potential(outcome%max_compression), 0.5_wp * m * v**2, &
         & rel=1.0e-15_wp, message="Pi(x_max) = m V^2/2")
      if (allocated(error)) return
      call check_close(error, 2.0_wp * outcome%compression_time, outcome%contact_time, &
         & rel=1.0e-14_wp, message="b = 0: symmetric phases")
      if (allocated(error)) return
      call time_law(law, m, 0.0_wp, v, [outcome%compression_time], x, vt, f, stat)
      call check_close(error, x(1), outcome%max_compression, rel=1.0e-14_wp, &
         & message="x(t_compression) = x_max")
      if (allocated(error)) return
      call impact_law(law, m, 0.25_wp, v, outcome, stat)
      call impact(contact_type(mass=m, stiffness=1.0_wp, exponent=1.0_wp, damping=0.25_wp, &
         & velocity=v), power, stat)
      call check(error, outcome%restitution == power%restitution .and. stat == hcimpact_ok, &
         & "k depends on b V only")
      if (allocated(error)) return
      call check(error, law%potential(outcome%max_compression) < 0.5_wp * m * v**2 &
         & .and. outcome%peak_force > law%force(outcome%compression_at_peak_force) &
         & .and. outcome%time_at_peak_force < outcome%compression_time, &
         & "damped: x_max below the elastic one, peak before x_max with 1 + b V > 1")
   end subroutine test_user_law_cubic

   !> Found by the fuzzer (bench/fuzz): a law that jumps at 0 (c x^n with n near 0:
   !> f(0) = 0, f(0+) = c) has its peak force closer to the impact than the smallest
   !> double; the bisection ended at x = 0 and impact_law returned the peak force
   !> f(0) = 0 at x = 0 and t = 0 with status OK. Now HCIMPACT_ERR_DOMAIN (the peak's
   !> compression leaves the double range), and a law whose peak is in range (n = 1e-3)
   !> still gives the power law's outcome.
   subroutine test_user_law_peak_below_range(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome, exact
      integer :: stat, i
      ! m, c, n, b, V: two contacts of the fuzzer's, and one of the issue's scale
      real(wp), parameter :: cases(5, 3) = reshape([ &
         & 5.9629770128710697e18_wp, 2.6820542935133372e154_wp, 7.1614220280550012e-304_wp, &
         & 1.4901161193847656e-8_wp, 5.4210108624275222e-20_wp, &
         & 1.8845331111599917e-15_wp, 6.4514064662082355e18_wp, 9.7903276935863817e-307_wp, &
         & 6.0794466300197322e-19_wp, 8.6981533087282514e-12_wp, &
         & 0.1_wp, 1.7135e10_wp, 1.0e-12_wp, 0.5_wp, 1.0_wp], [5, 3])
      do i = 1, 3
         call impact_law(power_law(stiffness=cases(2, i), exponent=cases(3, i)), cases(1, i), &
            & cases(4, i), cases(5, i), outcome, stat)
         if (stat == hcimpact_ok) then
            call check(error, outcome%peak_force > 0.0_wp &
               & .and. outcome%compression_at_peak_force > 0.0_wp &
               & .and. outcome%time_at_peak_force > 0.0_wp, "case " // int_text(i) &
               & // ": peak force " // format_real(outcome%peak_force) // " at x = " &
               & // format_real(outcome%compression_at_peak_force) // " with status OK")
         else
            call check(error, stat, hcimpact_err_domain, "case " // int_text(i))
            if (allocated(error)) return
            call check(error, ieee_is_nan(outcome%peak_force), "NaN on error")
         end if
         if (allocated(error)) return
      end do
      call impact_law(power_law(stiffness=1.7135e10_wp, exponent=1.0e-3_wp), 0.1_wp, 0.5_wp, &
         & 1.0_wp, outcome, stat)
      call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.0e-3_wp, &
         & damping=0.5_wp, velocity=1.0_wp), exact, stat)
      call check(error, stat == hcimpact_ok .and. outcome%peak_force > 0.0_wp &
         & .and. abs(outcome%peak_force - exact%peak_force) <= 1e-13_wp * exact%peak_force, &
         & "n = 1e-3: peak force " // format_real(outcome%peak_force) // ", closed forms " &
         & // format_real(exact%peak_force))
   end subroutine test_user_law_peak_below_range

   !> Found by the fuzzer (bench/fuzz): with b V tiny the peak lies next to the turning
   !> point, and its compression, from the potential's inverse at a point of the
   !> trajectory, came out one ulp above x_max (the power law through C's pow,
   !> m = 1.03e-6, c = 2648, n = 1/4, b = 3.75e-273, V = 3058.34375). The compression
   !> at the peak is at most x_max.
   subroutine test_user_law_peak_within_x_max(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      integer :: stat, i
      real(wp) :: damping
      do i = 0, 40
         damping = 3.7548046705201132e-273_wp * 10.0_wp**i
         call impact_law(plain_power_law(c=2648.0_wp, n=0.25_wp), &
            & 1.0283110896125436e-6_wp, damping, 3058.34375_wp, outcome, stat)
         call check(error, stat == hcimpact_ok .and. outcome%compression_at_peak_force > 0.0_wp &
            & .and. outcome%compression_at_peak_force <= outcome%max_compression, &
            & "b = " // format_real(damping) // ": x at the peak " &
            & // format_real(outcome%compression_at_peak_force) // ", x_max " &
            & // format_real(outcome%max_compression))
         if (allocated(error)) return
      end do
   end subroutine test_user_law_peak_within_x_max

   subroutine test_user_law_invalid(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      integer :: stat
      call impact_law(broken_law(), 1.0_wp, 0.1_wp, 1.0_wp, outcome, stat)
      call check(error, stat == hcimpact_err_elastic_law .and. ieee_is_nan(outcome%peak_force), &
         & "a law with a negative potential: status " // int_text(stat))
      if (allocated(error)) return
      call impact_law(linear_spring(), -1.0_wp, 0.1_wp, 1.0_wp, outcome, stat)
      call check(error, stat, hcimpact_err_mass, "user law, mass < 0")
      if (allocated(error)) return
      call impact_law(linear_spring(), 1.0_wp, -0.1_wp, 1.0_wp, outcome, stat)
      call check(error, stat, hcimpact_err_damping, "user law, damping < 0")
      if (allocated(error)) return
      call impact_law(linear_spring(), 1.0_wp, 0.1_wp, 0.0_wp, outcome, stat)
      call check(error, stat, hcimpact_err_velocity, "user law, V = 0")
   end subroutine test_user_law_invalid

   ! ------------------------------------------------------------------------------
   ! C interface (the bind(C) function, called from Fortran)
   ! ------------------------------------------------------------------------------

   subroutine test_c_interface(error)
      type(error_type), allocatable, intent(out) :: error
      type(hcimpact_contact), target :: c_contact
      type(hcimpact_outcome), target :: c_outcome
      type(outcome_type) :: outcome
      integer(c_int) :: stat
      integer :: fstat

      c_contact = hcimpact_contact(0.1_wp, 1.7135e10_wp, 1.5_wp, 0.1_wp, 1.0_wp)
      stat = c_impact(c_loc(c_contact), c_loc(c_outcome))
      call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=1.0_wp), outcome, fstat)
      call check(error, stat == 0 .and. c_outcome%restitution == outcome%restitution &
         & .and. c_outcome%energy_loss_ratio == outcome%energy_loss_ratio &
         & .and. c_outcome%rebound_velocity == outcome%rebound_velocity &
         & .and. c_outcome%max_compression == outcome%max_compression &
         & .and. c_outcome%peak_force == outcome%peak_force &
         & .and. c_outcome%compression_at_peak_force == outcome%compression_at_peak_force &
         & .and. c_outcome%time_at_peak_force == outcome%time_at_peak_force &
         & .and. c_outcome%compression_time == outcome%compression_time &
         & .and. c_outcome%contact_time == outcome%contact_time, &
         & "C outcome differs from the Fortran one")
      if (allocated(error)) return
      call check(error, c_impact(c_null_ptr, c_loc(c_outcome)) == hcimpact_err_null &
         & .and. c_impact(c_loc(c_contact), c_null_ptr) == hcimpact_err_null, "NULL pointers")
      if (allocated(error)) return
      c_contact%damping = -1.0_wp
      stat = c_impact(c_loc(c_contact), c_loc(c_outcome))
      call check(error, stat == hcimpact_err_damping .and. ieee_is_nan(c_outcome%contact_time) &
         & .and. ieee_is_nan(c_outcome%restitution), "bad damping through C")
   end subroutine test_c_interface

   !> Found by the fuzzer: a subnormal exponent with extreme inputs gave a successful
   !> outcome with a NaN peak force. Exponents below min_exponent are rejected, and just
   !> above it every output is finite.
   subroutine test_tiny_exponent(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      integer :: stat
      contact = contact_type(mass=146601410560.0_wp, stiffness=7.5825847337118724e-15_wp, &
         & exponent=9.2349256822808651e-311_wp, damping=146601410560.0_wp, &
         & velocity=7.5791152867599187e-15_wp)
      call impact(contact, outcome, stat)
      call check(error, stat, hcimpact_err_exponent, "subnormal exponent must be rejected")
      if (allocated(error)) return
      call check(error, ieee_is_nan(outcome%peak_force), "outputs are NaN on error")
      if (allocated(error)) return
      contact%exponent = min_exponent
      contact%damping = 1.0e4_wp / contact%velocity
      call impact(contact, outcome, stat)
      call check(error, stat, hcimpact_ok, "the smallest exponent accepted must work")
      if (allocated(error)) return
      call check(error, ieee_is_finite(outcome%peak_force) .and. &
         & ieee_is_finite(outcome%compression_at_peak_force) .and. &
         & ieee_is_finite(outcome%contact_time), "finite outputs at the smallest exponent")
   end subroutine test_tiny_exponent

   !> Found by the fuzzer (doc/robustness.md): times beyond the range of doubles gave NaN
   !> with success, and a subnormal time gave a NaN state.
   subroutine test_fuzz_findings(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      real(wp) :: t(2), x(2), v(2), f(2)
      integer :: stat
      contact = contact_type(mass=1.7776949456947198e56_wp, stiffness=1.043855498239993e-312_wp, &
         & exponent=0.25_wp, damping=52841979075100672.0_wp, velocity=3229849766330368.0_wp)
      call impact(contact, outcome, stat)
      call check(error, stat, hcimpact_err_domain, "times beyond the double range: a status")
      if (allocated(error)) return
      call check(error, ieee_is_nan(outcome%contact_time), "and NaN outputs")
      if (allocated(error)) return
      ! beta above max_beta: a status, not an overflow trap (found by the CVODE stability
      ! sweep in a trapping Debug build at beta = 1e47)
      contact = contact_type(mass=1.0_wp, stiffness=1.0e10_wp, exponent=1.5_wp, &
         & damping=1.0e47_wp, velocity=1.0_wp)
      call impact(contact, outcome, stat)
      call check(error, stat, hcimpact_err_domain, "beta = 1e47 is beyond max_beta")
      if (allocated(error)) return
      contact%damping = max_beta
      call impact(contact, outcome, stat)
      call check(error, stat, hcimpact_ok, "beta = max_beta still works")
      if (allocated(error)) return
      contact = contact_type(mass=10665.625_wp, stiffness=8.046341370970822e-12_wp, &
         & exponent=3.875_wp, damping=11250560.0_wp, velocity=8.053002709118573e-12_wp)
      t = [7.2390265773146817e-315_wp, 1.0e-300_wp]
      call time_law(contact, t, x, v, f, stat)
      call check(error, stat, hcimpact_ok, "tiny times are valid")
      if (allocated(error)) return
      ! x = V t to the last bit (rounded to the subnormal range), x' = V
      call check(error, all(x == contact%velocity * t) .and. all(v == contact%velocity) &
         & .and. all(ieee_is_finite(f)), "x = V t, x' = V at the start of the motion")
   end subroutine test_fuzz_findings

   ! ------------------------------------------------------------------------------
   ! Graded pieces of the time quadratures (large beta)
   ! ------------------------------------------------------------------------------

   !> The cuts of a cut phase tile it: 0 = cut(0) < cut(1) < ... < cut(np) < length,
   !> np < max_pieces, and are graded as power_phase_split intends. Compression: the
   !> end piece is end_piece_le wide in L = beta l (or half the phase), no plain piece
   !> is wider than 1.25 times its distance from the end of contact (the singularity),
   !> and the distances from the end double from the end piece on; restitution: the
   !> cuts lie at L = 4, 12, 36 (phase shorter than 35 in L), 6, 24 (shorter than 150)
   !> or 6, 27, below 3/4 of the phase and 40. Whether a phase is cut follows the
   !> thresholds cc_max_beta (restitution) and cc_max_compression_le (compression, on
   !> ln(1 + beta)).
   subroutine test_graded_pieces_tile(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: cut(0:max_pieces), bound, beta, ratio, first
      integer :: i, k, j, np, stat, phase
      logical :: split
      character(len=:), allocatable :: label

      do i = 1, size(piece_exponents)
         do k = 0, 44
            beta = 10.0_wp**(0.25_wp * real(k, wp) + 1.0_wp)
            do phase = compression_branch, restitution_branch
               label = "n = " // format_real(piece_exponents(i)) // ", beta = " &
                  & // format_real(beta) // ", phase " // int_text(phase)
               call power_phase_pieces(contact_type(mass=1.0_wp, stiffness=1.0_wp, &
                  & exponent=piece_exponents(i), velocity=1.0_wp, damping=beta), phase, &
                  & split, bound, cut, np, stat)
               call check(error, stat == hcimpact_ok, label // ": status " // int_text(stat))
               if (allocated(error)) return
               if (phase == restitution_branch) then
                  call check(error, split .eqv. (beta > cc_max_beta), label &
                     & // ": cut against the threshold cc_max_beta")
               else
                  call check(error, split .eqv. (beta * bound > cc_max_compression_le), &
                     & label // ": cut against the threshold cc_max_compression_le")
               end if
               if (allocated(error)) return
               if (.not. split) cycle
               call check(error, np >= 1 .and. np < max_pieces, label // ": " &
                  & // int_text(np) // " cuts")
               if (allocated(error)) return
               call check(error, cut(0) == 0.0_wp .and. all(cut(1:np) > cut(0:np - 1)) &
                  & .and. cut(np) < bound, label // ": the cuts do not tile [0, " &
                  & // format_real(bound) // "]")
               if (allocated(error)) return
               if (phase == compression_branch) then
                  ! the end piece: end_piece_le wide in L (or half the phase)
                  call check(error, beta * (bound - cut(np)) >= (1.0_wp - 1.0e-9_wp) &
                     & * min(end_piece_le, 0.5_wp * beta * bound), label &
                     & // ": end piece " // format_real(beta * (bound - cut(np))) // " wide in L")
                  if (allocated(error)) return
                  do j = 1, np
                     call check(error, cut(j) - cut(j - 1) <= 1.25_wp * (bound - cut(j)) &
                        & * (1.0_wp + 1.0e-9_wp), label // ": piece " // int_text(j) &
                        & // " wider than 1.25 times its distance from the end")
                     if (allocated(error)) return
                  end do
                  do j = 2, np
                     ratio = (bound - cut(j - 1)) / (bound - cut(j))
                     call check(error, abs(ratio - 2.0_wp) < 1.0e-6_wp, label &
                        & // ": distances from the end grow by " // format_real(ratio))
                     if (allocated(error)) return
                  end do
               else
                  ! first cut and ratio by the length of the phase in L
                  if (beta * bound < 35.0_wp) then
                     first = 4.0_wp
                     ratio = 3.0_wp
                  else if (beta * bound < 150.0_wp) then
                     first = 6.0_wp
                     ratio = 4.0_wp
                  else
                     first = 6.0_wp
                     ratio = 4.5_wp
                  end if
                  do j = 1, np
                     call check(error, abs(beta * cut(j) - first * ratio**(j - 1)) &
                        & <= 1.0e-12_wp * ratio**j .and. beta * cut(j) <= 0.75_wp &
                        & * beta * bound .and. beta * cut(j) <= 40.0_wp, label // ": cut " &
                        & // int_text(j) // " at L = " // format_real(beta * cut(j)))
                     if (allocated(error)) return
                  end do
               end if
            end do
         end do
      end do
   end subroutine test_graded_pieces_tile

   !> Every quadrature converges, in at most goal_piece_evaluations evaluations, for
   !> n in 0.1 .. 10 and beta from 1e-6 to 1e12 (the peak's time from the compression's
   !> own rule: no third quadrature), and every output is finite.
   subroutine test_graded_pieces_evaluations(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      real(wp) :: beta
      integer :: i, k, stat

      do i = 1, size(piece_exponents)
         do k = 0, 36
            beta = 10.0_wp**(0.5_wp * real(k, wp) - 6.0_wp)
            call impact(contact_type(mass=2.0_wp, stiffness=3.0e9_wp, &
               & exponent=piece_exponents(i), velocity=0.5_wp, damping=beta / 0.5_wp), &
               & outcome, stat)
            call check(error, stat == hcimpact_ok .and. ieee_is_finite(outcome%contact_time) &
               & .and. ieee_is_finite(outcome%time_at_peak_force) &
               & .and. ieee_is_finite(outcome%peak_force), "n = " &
               & // format_real(piece_exponents(i)) // ", beta = " // format_real(beta) &
               & // ": status " // int_text(stat) // " or a non-finite output")
            if (allocated(error)) return
            call check(error, maxval(outcome%evaluations(1:2)) <= goal_piece_evaluations &
               & .and. outcome%evaluations(3) == 0_ik, "n = " &
               & // format_real(piece_exponents(i)) // ", beta = " // format_real(beta) &
               & // ": evaluations " // int_text(int(outcome%evaluations(1))) // ", " &
               & // int_text(int(outcome%evaluations(2))) // ", " &
               & // int_text(int(outcome%evaluations(3))) // " (goal <= " &
               & // int_text(goal_piece_evaluations) // ", no third)")
            if (allocated(error)) return
         end do
      end do
   end subroutine test_graded_pieces_evaluations

   !> The times are continuous across the seams where a phase starts to be cut: at
   !> beta = cc_max_beta (restitution) and where ln(1 + beta) passes
   !> cc_max_compression_le (compression, beta near 147). Four contacts a step
   !> h = 2**-40 beta apart, two on each side (checked with power_phase_pieces): the
   !> times change by about 1e4 ulps per step, smoothly, so the second differences
   !> t(k-1) - 2 t(k) + t(k+1) are rounding noise, and a jump J at the seam would add
   !> J to them.
   subroutine test_graded_pieces_seams(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: beta0, t(-1:2, 3), cut(0:max_pieces), bound, step
      integer :: i, k, phase, np, stat, first
      logical :: split(-8:8)

      do i = 1, size(piece_exponents)
         do phase = compression_branch, restitution_branch
            if (phase == restitution_branch) then
               beta0 = cc_max_beta
            else
               beta0 = exp(cc_max_compression_le) - 1.0_wp
            end if
            step = beta0 * 2.0_wp**(-40)
            ! the seam: the first step k with the phase cut, k - 1 not
            do k = -8, 8
               call power_phase_pieces(seam_contact(piece_exponents(i), beta0 &
                  & + real(k, wp) * step), phase, split(k), bound, cut, np, stat)
            end do
            first = 99
            do k = 8, -7, -1
               if (split(k) .and. .not. split(k - 1)) first = k
            end do
            call check(error, first <= 7, "n = " // format_real(piece_exponents(i)) &
               & // ", phase " // int_text(phase) // ": no seam within 8 steps of beta = " &
               & // format_real(beta0))
            if (allocated(error)) return
            ! t(k, :): k = -1, 0 uncut, 1, 2 cut
            do k = -1, 2
               t(k, :) = seam_times(seam_contact(piece_exponents(i), beta0 &
                  & + real(first - 1 + k, wp) * step))
            end do
            call check_seam(error, t, "n = " // format_real(piece_exponents(i)) &
               & // ", phase " // int_text(phase) // ", at the seam beta = " &
               & // format_real(beta0 + real(first, wp) * step))
            if (allocated(error)) return
         end do
      end do
   contains
      !> The contact with exponent n and beta = b (V = 1, so that beta is exact)
      function seam_contact(n, b) result(contact)
         real(wp), intent(in) :: n, b
         type(contact_type) :: contact
         contact = contact_type(mass=1.0_wp, stiffness=1.0_wp, exponent=n, &
            & velocity=1.0_wp, damping=b)
      end function seam_contact
      !> Time at the peak, compression time and contact time of a contact
      function seam_times(contact) result(times)
         type(contact_type), intent(in) :: contact
         real(wp) :: times(3)
         type(outcome_type) :: outcome
         integer :: stat_
         call impact(contact, outcome, stat_)
         times = [outcome%time_at_peak_force, outcome%compression_time, &
            & outcome%contact_time]
      end function seam_times
   end subroutine test_graded_pieces_seams

   !> The times are continuous across beta = whole_max_beta, where one rule over the
   !> whole contact (symmetric weight, no restitution evaluations) hands over to the
   !> rules on the two phases: four contacts a step 2**-40 beta apart, two on each side
   !> (checked through the evaluation counts), whose second differences stay within
   !> goal_seam ulps, as at the seams of the graded pieces.
   !> x_peak/x_max - 1 = (1 - y)^(1/(n+1)) - 1 by the series of peak_ratio_m1 (small
   !> beta) against the logarithm and exponential in double-double it replaces, over
   !> y from 2^-60 to the threshold (both sides of it) and n from 1e-6 to 100: within
   !> 2^-66 of the value (the series claim 2^-68), plus the reference's own 2^-104
   !> (an exponential near 1 minus 1). y = 0 gives 0 exactly.
   subroutine test_peak_ratio_series(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: exponents(6) = [1.0e-6_wp, 0.5_wp, 1.0_wp, 1.5_wp, 3.0_wp, &
         & 100.0_wp]
      type(dd_real) :: inv_np1, y, ratio, ref, diff
      real(wp) :: bound
      integer :: i, j
      do j = 1, size(exponents)
         inv_np1 = dd_inverse(dd(exponents(j)) + 1.0_wp)
         ratio = peak_ratio_m1(dd(0.0_wp), inv_np1)
         call check(error, ratio%hi == 0.0_wp .and. ratio%lo == 0.0_wp, "y = 0: not 0")
         if (allocated(error)) return
         do i = 0, 520
            ! y = 2^-60 .. 2^-8 (the last just below the threshold), a trailing part too
            y = dd(min(2.0_wp**(-60.0_wp + 0.1_wp * real(i, wp)), &
               & peak_series_max_y * (1.0_wp - epsilon(1.0_wp))))
            y = dd_real(y%hi, y%hi * 0.37_wp * epsilon(1.0_wp))
            ratio = peak_ratio_m1(y, inv_np1)
            ref = dd_exp(dd_log(1.0_wp - y) * inv_np1) - 1.0_wp
            diff = ratio - ref
            bound = 2.0_wp**(-66) * abs(ref%hi) + 2.0_wp**(-104)
            call check(error, abs(diff%hi) <= bound, "n = " // format_real(exponents(j)) &
               & // ", y = " // format_real(y%hi) // ": series " // format_real(ratio%hi) &
               & // " differs from exp(ln(1 - y)/(n+1)) - 1 by " // format_real(diff%hi))
            if (allocated(error)) return
         end do
      end do
   end subroutine test_peak_ratio_series

   subroutine test_whole_contact_seam(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      real(wp) :: t(-1:2, 3), beta
      integer :: i, k, stat
      do i = 1, size(piece_exponents)
         do k = -1, 2
            beta = whole_max_beta * (1.0_wp + real(k, wp) * 2.0_wp**(-40))
            call impact(contact_type(mass=1.0_wp, stiffness=1.0_wp, &
               & exponent=piece_exponents(i), velocity=1.0_wp, damping=beta), outcome, stat)
            call check(error, stat == hcimpact_ok .and. ((k <= 0) .eqv. &
               & (outcome%evaluations(2) == 0_ik)), "n = " // format_real(piece_exponents(i)) &
               & // ", beta = " // format_real(beta) // ": status " // int_text(stat) &
               & // ", the rule over the whole contact " // merge("not taken", "taken    ", &
               & k <= 0) // " (evaluations " // int_text(int(outcome%evaluations(1))) // ", " &
               & // int_text(int(outcome%evaluations(2))) // ")")
            if (allocated(error)) return
            t(k, :) = [outcome%time_at_peak_force, outcome%compression_time, &
               & outcome%contact_time]
         end do
         call check_seam(error, t, "n = " // format_real(piece_exponents(i)) &
            & // ", at beta = whole_max_beta")
         if (allocated(error)) return
      end do
   end subroutine test_whole_contact_seam

   !> impact_whole.csv (make_impact_whole.py, mpmath at the exact double inputs): beta
   !> log-uniform in [1.5, 10] and both sides of the seams whole_max_beta = 1.8, 5.5
   !> and contact_max_beta = cc_max_beta = 8, exponents 0.05 to 10. Issue 17: from
   !> whole_max_beta to contact_max_beta the contact time is one rule over the whole
   !> contact (25 evaluations up to about 6, 49 beyond) and the compression a rule of
   !> its own (25), where the rules on the two phases took 25 + 49. Every output within
   !> the goals of impact.csv, and at most 50 evaluations in all up to beta = 5.5 (the
   !> continuity across beta = 8: graded-pieces-seams). The median error
   !> of the time of the peak over this range is 0.55 ulp, above goal_median, before
   !> issue 17 as after (its rule did not change): it is held to
   !> goal_median_peak_whole.
   subroutine test_whole_contact_reference(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      real(wp), allocatable :: err(:, :)
      real(wp) :: beta, med_goal
      integer :: i, j, n, stat, worst
      !$omp critical (test_impact_tables)
      call load_impact_table(error, "impact_whole.csv", wholes, wholes_loaded)
      !$omp end critical (test_impact_tables)
      if (allocated(error)) return
      n = size(wholes%input, 2)
      call check(error, n >= 180, "impact_whole.csv holds " // int_text(n) &
         & // " rows, expected >= 180")
      if (allocated(error)) return
      allocate(err(n_outputs, n))
      do i = 1, n
         call impact(table_contact(wholes, i), outcome, stat)
         call check(error, stat == hcimpact_ok, "impact_whole.csv row " // int_text(i) &
            & // ": status " // int_text(stat))
         if (allocated(error)) return
         beta = wholes%input(4, i) * wholes%input(5, i)
         ! (up to 5.5 the whole contact's rule is accepted at degree 24)
         if (beta <= 5.5_wp) then
            call check(error, sum(outcome%evaluations) <= 50_ik, "impact_whole.csv row " &
               & // int_text(i) // ", beta = " // format_real(beta) // ": evaluations " &
               & // int_text(int(outcome%evaluations(1))) // ", " &
               & // int_text(int(outcome%evaluations(2))) // ", " &
               & // int_text(int(outcome%evaluations(3))) // " (expected at most 50 in all)")
            if (allocated(error)) return
         end if
         do j = 1, n_outputs
            err(j, i) = ulp_error(element(outputs(outcome), j), wholes%ref_hi(j, i), &
               & wholes%ref_lo(j, i))
         end do
      end do
      do j = 1, n_outputs
         worst = maxloc(err(j, :), dim=1)
         med_goal = merge(goal_median_peak_whole, goal_median, j == 4)
         call check(error, err(j, worst) <= goal_max(j) .and. median(err(j, :)) <= med_goal, &
            & "impact_whole.csv, " // trim(output_names(j)) // ": max " &
            & // utoa(err(j, worst)) // " ulp (row " // int_text(worst) // "), median " &
            & // utoa(median(err(j, :))) // " (goals " // utoa(goal_max(j)) &
            & // ", " // utoa(med_goal) // ")")
         if (allocated(error)) return
      end do
   end subroutine test_whole_contact_reference

   !> The second differences t(k-1) - 2 t(k) + t(k+1), k = 0, 1, of the three times
   !> (peak, compression, contact) of four contacts across a seam, within goal_seam ulps
   subroutine check_seam(error, t, label)
      type(error_type), allocatable, intent(out) :: error
      real(wp), intent(in) :: t(-1:2, 3)
      character(len=*), intent(in) :: label
      real(wp) :: d
      integer :: k, m
      do m = 1, 3
         do k = 0, 1
            d = (t(k - 1, m) - 2.0_wp * t(k, m) + t(k + 1, m)) / spacing(t(0, m))
            call check(error, abs(d) <= goal_seam, label // ": time " // int_text(m) &
               & // " jumps by " // format_real(d) // " ulp")
            if (allocated(error)) return
         end do
      end do
   end subroutine check_seam


   ! ------------------------------------------------------------------------------
   ! Issue 13: the extremes of the inputs
   ! ------------------------------------------------------------------------------

   !> The status `impact` owes row i of a table: hcimpact_err_no_convergence above
   !> max_quadrature_exponent, hcimpact_err_domain where an output lies outside the
   !> double range (the reference rounds it to 0 or to an infinity), else hcimpact_ok.
   pure function expected_status(table, i) result(stat)
      type(impact_table), intent(in) :: table
      integer, intent(in) :: i
      integer :: stat
      stat = hcimpact_ok
      if (table%input(3, i) > max_quadrature_exponent) then
         stat = hcimpact_err_no_convergence
      else if (any(table%ref_hi(:, i) == 0.0_wp) &
         & .or. .not. all(ieee_is_finite(table%ref_hi(:, i)))) then
         stat = hcimpact_err_domain
      end if
   end function expected_status

   !> impact_extremes.csv (make_impact_extremes.py, mpmath at the exact double inputs):
   !> beta up to max_beta = 1e40 (the steel ball at V = 1e40; issue 13: the
   !> compression time and the time of the peak were 0 above beta = 4e33, and off by
   !> 8 ulps at 1e19), masses, stiffnesses and speeds over the double range, exponents
   !> 0.05 to 1000, the damping DBL_MAX. Every output within the goals of impact.csv, a
   !> status only where expected_status says.
   subroutine test_extremes_reference(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      real(wp), allocatable :: err(:, :)
      logical, allocatable :: counted(:)
      integer :: i, j, n, stat, worst
      call load_extremes(error)
      if (allocated(error)) return
      n = size(extremes%input, 2)
      allocate(err(n_outputs, n), counted(n))
      err = 0.0_wp
      do i = 1, n
         call impact(table_contact(extremes, i), outcome, stat)
         call check(error, stat == expected_status(extremes, i), "impact_extremes.csv row " &
            & // int_text(i) // ": status " // int_text(stat) // ", expected " &
            & // int_text(expected_status(extremes, i)))
         if (allocated(error)) return
         counted(i) = stat == hcimpact_ok
         if (.not. counted(i)) cycle
         do j = 1, n_outputs
            err(j, i) = ulp_error(element(outputs(outcome), j), extremes%ref_hi(j, i), &
               & extremes%ref_lo(j, i))
         end do
      end do
      do j = 1, n_outputs
         worst = maxloc(err(j, :), dim=1)
         call check(error, err(j, worst) <= goal_max(j) &
            & .and. median(pack(err(j, :), counted)) <= goal_median, &
            & "impact_extremes.csv, " // trim(output_names(j)) // ": max " &
            & // utoa(err(j, worst)) // " ulp (row " // int_text(worst) // "), median " &
            & // utoa(median(pack(err(j, :), counted))) // " (goals " // utoa(goal_max(j)) &
            & // ", " // utoa(goal_median) // ")")
         if (allocated(error)) return
      end do
   end subroutine test_extremes_reference

   !> Issue 13: the damping DBL_MAX with a subnormal speed (b V = 0.043) formed b V with
   !> a NaN trailing part (the splitting of DBL_MAX overflows), whose binary exponent,
   !> huge(0), overflowed the set-up's range tests (signed overflow, found with
   !> -fsanitize=undefined). The contact of the issue has a peak force of 1e-504 N
   !> (hcimpact_err_domain, documented); with m = 1e300, c = 7e-270 every output is a
   !> double, and must be given (the NaN gave hcimpact_err_domain there too).
   subroutine test_extreme_damping_setup(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      integer :: stat
      call impact(contact_type(mass=1.3e-18_wp, stiffness=1.13e-306_wp, &
         & exponent=1.500001_wp, damping=huge(1.0_wp), velocity=2.4e-310_wp), outcome, stat)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(outcome%peak_force), &
         & "issue 13's contact: status " // int_text(stat) // " (peak force below the range)")
      if (allocated(error)) return
      call impact(contact_type(mass=1.0e300_wp, stiffness=7.0e-270_wp, exponent=1.5_wp, &
         & damping=huge(1.0_wp), velocity=2.4e-310_wp), outcome, stat)
      call check(error, stat == hcimpact_ok .and. all(ieee_is_finite(outputs(outcome))) &
         & .and. all(outputs(outcome) > 0.0_wp), "b = DBL_MAX, V = 2.4e-310 with every " &
         & // "output a double: status " // int_text(stat))
      if (allocated(error)) return
      ! b V = 2^-6 (2 - 2^-52) exactly: the restitution of beta given as b = beta, V = 1
      call check_same_restitution(error, huge(1.0_wp), 2.0_wp**(-1030), &
         & scale(huge(1.0_wp), -1030), 1.0_wp)
      if (allocated(error)) return
      ! and the other way round: V = DBL_MAX, b subnormal
      call check_same_restitution(error, 2.0_wp**(-1030), huge(1.0_wp), 1.0_wp, &
         & scale(huge(1.0_wp), -1030))
   contains
      !> impact with (b1, V1) and (b2, V2), b1 V1 = b2 V2 exactly: the same restitution
      subroutine check_same_restitution(error, b1, v1, b2, v2)
         type(error_type), allocatable, intent(out) :: error
         real(wp), intent(in) :: b1, v1, b2, v2
         type(outcome_type) :: o1, o2
         integer :: s1, s2
         call impact(contact_type(mass=1.0_wp, stiffness=1.0_wp, exponent=1.5_wp, &
            & damping=b1, velocity=v1), o1, s1)
         call impact(contact_type(mass=1.0_wp, stiffness=1.0_wp, exponent=1.5_wp, &
            & damping=b2, velocity=v2), o2, s2)
         call check(error, s2 == hcimpact_ok .and. (s1 == hcimpact_ok .or. &
            & s1 == hcimpact_err_domain), "b V = " // format_real(b2 * v2) // ": status " &
            & // int_text(s1) // ", " // int_text(s2))
         if (allocated(error)) return
         ! (with V = 2^-1030 the times are beyond the double range: only k is compared)
         if (s1 == hcimpact_ok) then
            call check(error, o1%restitution == o2%restitution, "restitution at b V = " &
               & // format_real(b2 * v2) // ": " // format_real(o1%restitution) // " vs " &
               & // format_real(o2%restitution))
         end if
      end subroutine check_same_restitution
   end subroutine test_extreme_damping_setup

   !> Above max_quadrature_exponent the times are not integrated: impact and the time
   !> law give hcimpact_err_no_convergence (up to n = 5e16 they gave numbers 5 ulps and
   !> more off, beyond it a division by zero trapped the Debug build), velocity_at_depth
   !> still works. Up to the limit, impact_extremes.csv checks the outputs.
   subroutine test_large_exponents(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: exponents(6) = [100.5_wp, 1.0e3_wp, 1.0e17_wp, 1.0e100_wp, &
         & 1.0e300_wp, huge(1.0_wp)]
      real(wp), parameter :: betas(4) = [0.0_wp, 0.1_wp, 5.0_wp, 1.0e4_wp]
      type(outcome_type) :: outcome
      real(wp) :: x(2), v(2), f(2)
      integer :: i, k, stat
      do i = 1, size(exponents)
         do k = 1, size(betas)
            call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, &
               & exponent=exponents(i), damping=betas(k), velocity=1.0_wp), outcome, stat)
            call check(error, (stat == hcimpact_err_no_convergence .or. &
               & stat == hcimpact_err_domain) .and. ieee_is_nan(outcome%contact_time), &
               & "impact, n = " // format_real(exponents(i)) // ", beta = " &
               & // format_real(betas(k)) // ": status " // int_text(stat))
            if (allocated(error)) return
            call time_law(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, &
               & exponent=exponents(i), damping=betas(k), velocity=1.0_wp), &
               & [1.0e-3_wp, 0.5_wp], x, v, f, stat)
            call check(error, (stat == hcimpact_err_no_convergence .or. &
               & stat == hcimpact_err_domain) .and. all(ieee_is_nan(x)), "time law, n = " &
               & // format_real(exponents(i)) // ": status " // int_text(stat))
            if (allocated(error)) return
         end do
      end do
      call impact(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, &
         & exponent=max_quadrature_exponent, damping=5.0_wp, velocity=1.0_wp), outcome, stat)
      call check(error, stat == hcimpact_ok .and. ieee_is_finite(outcome%contact_time), &
         & "n = max_quadrature_exponent: status " // int_text(stat))
   end subroutine test_large_exponents

   !> F(t), from the trajectory's double-double quantities, within
   !> goal_time_law_force (1 + kappa) over timelaw.csv and timelaw_extremes.csv
   !> (exponents 0.5 to 6, beta up to 1.3e5, points early in compression, issue 13's
   !> contact at beta = 1e4 at its time of the peak) wherever kappa <= 1e3, and x(t),
   !> x'(t), F(t) within goal_time_law (1 + kappa) at the extremes everywhere. (At the
   !> last points of a contact x itself is off by its condition, about t/(t_c - t), up
   !> to 1e16, and F ~ x^n by the n-th power of that: no longer a linear error.)
   subroutine test_time_law_force(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp) :: worst(3)
      integer :: worst_row(3), k
      character(len=*), parameter :: names(3) = ["x", "v", "F"]
      call load_impacts(error)
      if (allocated(error)) return
      call load_timelaws(error)
      if (allocated(error)) return
      call time_law_errors(error, impacts, timelaws, "timelaw.csv", worst, worst_row, &
         & kappa_max=1.0e3_wp)
      if (allocated(error)) return
      call check(error, worst(3) <= goal_time_law_force, "timelaw.csv: F(t) error / (1 + " &
         & // "condition) = " // utoa(worst(3)) // " ulp at row " // int_text(worst_row(3)) &
         & // " (goal <= " // utoa(goal_time_law_force) // ")")
      if (allocated(error)) return
      call load_extremes(error)
      if (allocated(error)) return
      call time_law_errors(error, extremes, extreme_laws, "timelaw_extremes.csv", worst, &
         & worst_row, kappa_max=1.0e3_wp)
      if (allocated(error)) return
      call check(error, worst(3) <= goal_time_law_force, "timelaw_extremes.csv: F(t) " &
         & // "error / (1 + condition) = " // utoa(worst(3)) // " ulp at row " &
         & // int_text(worst_row(3)) // " (goal <= " // utoa(goal_time_law_force) // ")")
      if (allocated(error)) return
      call time_law_errors(error, extremes, extreme_laws, "timelaw_extremes.csv", worst, &
         & worst_row)
      if (allocated(error)) return
      do k = 1, 3
         call check(error, worst(k) <= goal_time_law, "timelaw_extremes.csv: " // names(k) &
            & // "(t) error / (1 + condition) = " // utoa(worst(k)) // " ulp at row " &
            & // int_text(worst_row(k)) // " (goal <= " // utoa(goal_time_law) // ")")
         if (allocated(error)) return
      end do
   end subroutine test_time_law_force

   !> At and after the contact time of `impact` the contact is over: x = 0, x' = -k V
   !> and F = 0 exactly (issue 13: x was 1e-16 x_max there, F = 0.07 N for n = 0.5),
   !> and time_law_samples ends at x = 0 (6 of 40 contacts did not). Over exponents
   !> 0.3 to 7, beta 0 to 1e5, issue 13's contact and masses, stiffnesses and speeds
   !> over many decades.
   subroutine test_time_law_end(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: exponents(6) = [0.3_wp, 0.5_wp, 1.0_wp, 1.5_wp, 3.0_wp, 7.0_wp]
      real(wp), parameter :: betas(8) = [0.0_wp, 1.0e-9_wp, 1.0e-3_wp, 0.5_wp, 3.0_wp, &
         & 30.0_wp, 1.0e3_wp, 1.0e5_wp]
      real(wp), parameter :: scales(3, 3) = reshape([0.1_wp, 1.7135e10_wp, 1.0_wp, &
         & 5735.88734395135_wp, 914.5400816745746_wp, 8.973330480019602_wp, &
         & 3.0e-9_wp, 2.0e14_wp, 3.0e-4_wp], [3, 3])
      type(contact_type) :: contact
      integer :: i, k, j
      do j = 1, 3
         do i = 1, size(exponents)
            do k = 1, size(betas)
               contact = contact_type(mass=scales(1, j), stiffness=scales(2, j), &
                  & exponent=exponents(i), velocity=scales(3, j), &
                  & damping=betas(k) / scales(3, j))
               call check_end(error, contact)
               if (allocated(error)) return
            end do
         end do
      end do
      ! issue 13's contact
      call check_end(error, contact_type(mass=5735.88734395135_wp, &
         & stiffness=914.5400816745746_wp, exponent=1.5_wp, damping=0.20059441742482975_wp, &
         & velocity=8.973330480019602_wp))
   contains
      subroutine check_end(error, contact)
         type(error_type), allocatable, intent(out) :: error
         type(contact_type), intent(in) :: contact
         type(outcome_type) :: outcome
         real(wp) :: t(2), x(2), v(2), f(2)
         real(wp), allocatable :: ts(:), xs(:), vs(:), fs(:)
         integer :: stat, n
         character(len=:), allocatable :: label
         label = "n = " // format_real(contact%exponent) // ", beta = " &
            & // format_real(contact%damping * contact%velocity) // ", m = " &
            & // format_real(contact%mass)
         call impact(contact, outcome, stat)
         call check(error, stat, hcimpact_ok, label)
         if (allocated(error)) return
         t = [outcome%contact_time, nearest(outcome%contact_time, 1.0_wp)]
         call time_law(contact, t, x, v, f, stat)
         call check(error, stat == hcimpact_ok .and. all(x == 0.0_wp) .and. all(f == 0.0_wp) &
            & .and. all(v == outcome%rebound_velocity), label // ": at the contact time x = " &
            & // format_real(x(1)) // ", F = " // format_real(f(1)) // ", x' = " &
            & // format_real(v(1)) // " (-k V = " // format_real(outcome%rebound_velocity) &
            & // ")")
         if (allocated(error)) return
         do n = 2, 11, 9
            call time_law_samples(contact, n, ts, xs, vs, fs, stat)
            call check(error, stat == hcimpact_ok .and. xs(n) == 0.0_wp .and. fs(n) == 0.0_wp &
               & .and. vs(n) == outcome%rebound_velocity .and. xs(1) == 0.0_wp &
               & .and. fs(1) == 0.0_wp .and. vs(1) == contact%velocity &
               & .and. ts(n) == outcome%contact_time, label // ", " // int_text(n) &
               & // " samples: the last at x = " // format_real(xs(n)) // ", F = " &
               & // format_real(fs(n)))
            if (allocated(error)) return
         end do
      end subroutine check_end
   end subroutine test_time_law_end

   !> velocity_at_depth against velocity_extremes.csv: both branches, depths from 0 to
   !> x_max (exact doubles), every contact of impact_extremes.csv but the time-law
   !> ones, within goal_velocity (1 + kappa) ulps; at x = 0 exactly V and the
   !> outcome's -k V (issue 13: 2 ulps below V, and 1.3 ulps from -k V).
   subroutine test_velocity_reference(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      real(wp) :: v, err, worst, y, kappa, np1
      integer :: i, stat, stat_impact, worst_row
      call load_extremes(error)
      if (allocated(error)) return
      worst = 0.0_wp
      worst_row = 0
      do i = 1, size(velocities%x)
         contact = table_contact(extremes, velocities%case_id(i))
         call velocity_at_depth(contact, velocities%x(i), velocities%branch(i), v, stat)
         call check(error, stat, hcimpact_ok, "velocity_extremes.csv row " // int_text(i))
         if (allocated(error)) return
         ! the condition number, from x_max of the reference
         np1 = contact%exponent + 1.0_wp
         kappa = 0.0_wp
         if (velocities%x(i) > 0.0_wp) then
            y = 1.0_wp - exp(np1 * log(velocities%x(i) / extremes%ref_hi(1, &
               & velocities%case_id(i))))
            kappa = huge(1.0_wp)
            if (y > 0.0_wp) kappa = np1 * (1.0_wp - y) / (2.0_wp * y)
         end if
         err = ulp_error(v, velocities%ref_hi(i), velocities%ref_lo(i)) / (1.0_wp + kappa)
         if (err > worst) then
            worst = err
            worst_row = i
         end if
         if (velocities%x(i) == 0.0_wp) then
            call impact(contact, outcome, stat_impact)
            if (velocities%branch(i) == compression_branch) then
               call check(error, v == contact%velocity, "x = 0, compression: " &
                  & // format_real(v) // ", V = " // format_real(contact%velocity))
            else if (stat_impact == hcimpact_ok) then
               call check(error, v == outcome%rebound_velocity, "x = 0, restitution: " &
                  & // format_real(v) // ", -k V = " // format_real(outcome%rebound_velocity))
            end if
            if (allocated(error)) return
         end if
      end do
      call check(error, worst <= goal_velocity, "velocity_extremes.csv: max error/(1 + " &
         & // "condition) " // utoa(worst) // " ulp at row " // int_text(worst_row) &
         & // " (goal <= " // utoa(goal_velocity) // ")")
      if (allocated(error)) return
      ! issue 13's contacts at x = 0
      contact = contact_type(mass=6.894269419916452e-12_wp, stiffness=20459768806906.133_wp, &
         & exponent=1.0_wp, damping=6351.512264347015_wp, velocity=0.0007872140982969571_wp)
      call velocity_at_depth(contact, 0.0_wp, compression_branch, v, stat)
      call check(error, stat == hcimpact_ok .and. v == contact%velocity, "issue 13, branch 1")
      if (allocated(error)) return
      contact = contact_type(mass=4.3787021513947266e-05_wp, stiffness=5130862410770.172_wp, &
         & exponent=1.0_wp, damping=17342.098284939988_wp, velocity=1.729894474537273e-05_wp)
      call impact(contact, outcome, stat)
      call velocity_at_depth(contact, 0.0_wp, restitution_branch, v, stat)
      call check(error, stat == hcimpact_ok .and. v == outcome%rebound_velocity, &
         & "issue 13, branch 2")
   end subroutine test_velocity_reference

   !> Issue 13: n = DBL_MAX gave hcimpact_ok with NaN ((x/x_max)^(n+1) from an
   !> overflowing product, and 1/(n+1) outside the normal range). A status or a finite
   !> velocity for every huge exponent; where the scales are formed (n up to 1e300),
   !> (x/x_max)^(n+1) = 0 below x_max and the velocity is V, resp. -k V, exactly.
   subroutine test_velocity_huge_exponent(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: exponents(5) = [1.0e20_wp, 1.0e100_wp, 1.0e250_wp, 1.0e300_wp, &
         & huge(1.0_wp)]
      type(contact_type) :: contact
      type(outcome_type) :: outcome_k
      real(wp) :: v
      integer :: i, branch, stat
      ! -k V at beta = 0.1, V = 1 (k depends on beta alone)
      call impact(contact_type(mass=1.0_wp, stiffness=1.0_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=1.0_wp), outcome_k, stat)
      do i = 1, size(exponents)
         contact = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=exponents(i), &
            & damping=0.1_wp, velocity=1.0_wp)
         do branch = compression_branch, restitution_branch
            call velocity_at_depth(contact, 1.0e-5_wp, branch, v, stat)
            call check(error, stat /= hcimpact_ok .or. ieee_is_finite(v), "n = " &
               & // format_real(exponents(i)) // ": status " // int_text(stat) // " with " &
               & // format_real(v))
            if (allocated(error)) return
            if (exponents(i) <= 1.0e250_wp) then
               call check(error, stat == hcimpact_ok .and. v == merge(1.0_wp, &
                  & outcome_k%rebound_velocity, branch == compression_branch), "n = " &
                  & // format_real(exponents(i)) // ", branch " // int_text(branch) // ": " &
                  & // format_real(v) // ", status " // int_text(stat))
               if (allocated(error)) return
            end if
         end do
      end do
   end subroutine test_velocity_huge_exponent

   !> The velocity never leaves its exact bounds: 0 <= x' <= V in compression, -k V <=
   !> x' <= 0 in restitution (-k V the rebound velocity of `impact`), at depths from
   !> x_max 2^-1000 to x_max, over beta from 1e-15 to 1e6, V from 1e-100 to 1e100 and n
   !> from 0.5 to 5. The fuzz test found x' = V (1 + 2^-51) near x = 0 at beta = 7e-6
   !> (the series of the compression branch rounded above 1); time_law's velocities too.
   subroutine test_velocity_bounds(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n_depths = 400, n_times = 64
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      real(wp) :: v, lo, hi, x, t(n_times), xt(n_times), vt(n_times), ft(n_times)
      integer :: ib, iv, in, j, branch, stat
      do ib = 0, 21
         do iv = 0, 4
            do in = 0, 3
               contact = contact_type(mass=1.7_wp, stiffness=3.1e9_wp, &
                  & exponent=0.5_wp + 1.5_wp * in, damping=1.0_wp, velocity=10.0_wp**(50 * iv - 100))
               contact%damping = 10.0_wp**(ib - 15) * (1.0_wp + 0.37_wp * in) / contact%velocity
               if (ib == 21) then
                  ! the fuzz test's contact
                  contact = contact_type(mass=48409113264128.0_wp, &
                     & stiffness=9.8978976260217198e-18_wp, exponent=2.90203857421875_wp, &
                     & damping=6.8053803355962693e-20_wp, velocity=107869177380864.0_wp)
               end if
               call impact(contact, outcome, stat)
               if (stat /= hcimpact_ok) cycle
               do j = 0, n_depths
                  ! x_max 2^-(1000 j/n_depths) at both ends, the middle in between
                  if (j < n_depths / 2) then
                     x = outcome%max_compression * 2.0_wp**(-(1000.0_wp * j) / n_depths)
                  else
                     x = outcome%max_compression * 2.0_wp**(-1000.0_wp * (n_depths - j) / n_depths)
                  end if
                  do branch = compression_branch, restitution_branch
                     call velocity_at_depth(contact, x, branch, v, stat)
                     if (stat /= hcimpact_ok) then
                        call test_failed(error, "velocity-bounds: status " // int_text(stat) &
                           & // " at x = " // format_real(x))
                        return
                     end if
                     lo = merge(0.0_wp, outcome%rebound_velocity, branch == compression_branch)
                     hi = merge(contact%velocity, 0.0_wp, branch == compression_branch)
                     call check(error, v >= lo .and. v <= hi, "beta = " &
                        & // format_real(contact%damping * contact%velocity) // ", V = " &
                        & // format_real(contact%velocity) // ", x = " // format_real(x) &
                        & // ", branch " // int_text(branch) // ": x' = " // format_real(v) &
                        & // " outside [" // format_real(lo) // ", " // format_real(hi) // "]")
                     if (allocated(error)) return
                  end do
               end do
               ! times from contact_time 2^-60 to the whole contact, both ends
               do j = 1, n_times
                  t(j) = outcome%contact_time * 2.0_wp**(-60.0_wp * (j - 1) / (n_times - 1))
               end do
               t(n_times / 2) = outcome%contact_time * (1.0_wp - epsilon(1.0_wp))
               call time_law(contact, t, xt, vt, ft, stat)
               if (stat /= hcimpact_ok) then
                  call test_failed(error, "velocity-bounds: time_law status " // int_text(stat))
                  return
               end if
               do j = 1, n_times
                  call check(error, vt(j) >= outcome%rebound_velocity &
                     & .and. vt(j) <= contact%velocity, "time_law, beta = " &
                     & // format_real(contact%damping * contact%velocity) // ", V = " &
                     & // format_real(contact%velocity) // ", t = " // format_real(t(j)) &
                     & // ": x' = " // format_real(vt(j)) // " outside [-k V, V]")
                  if (allocated(error)) return
               end do
            end do
         end do
      end do
   end subroutine test_velocity_bounds

   !> A contact shorter than the smallest subnormal (4.9e-324 s) has no representable
   !> time: status hcimpact_err_domain with NaN, not 0 with success (the fuzz test's
   !> user-law contacts of about 1e-360 s, and a scan of such scales for both paths).
   subroutine test_times_below_subnormals(error)
      type(error_type), allocatable, intent(out) :: error
      type(outcome_type) :: outcome
      ! m, c, n, b, V
      real(wp), parameter :: cases(5, 2) = reshape([ &
         & 5.8397324167364294e-308_wp, 1.2675264745131617e+274_wp, 1.7264428818844491e-15_wp, &
         & 0.0_wp, 8.5866571032201171e+221_wp, &
         & 2.0642817800620248e-310_wp, 7.80469395600715e+222_wp, 1.390671158792012e-309_wp, &
         & 1.5753696752126182e-310_wp, 1.1279124644811399e+158_wp], [5, 2])
      real(wp) :: m, v
      integer :: i, j, k, stat
      do i = 1, size(cases, 2)
         call impact_law(power_law(stiffness=cases(2, i), exponent=cases(3, i)), cases(1, i), &
            & cases(4, i), cases(5, i), outcome, stat)
         ! (the comparisons only on success: a NaN compared traps in the Debug build)
         if (stat /= hcimpact_ok) cycle
         call check(error, outcome%compression_time > 0.0_wp .and. outcome%contact_time &
            & > 0.0_wp, "user law, case " // int_text(i) // ": status OK with compression " &
            & // "time " // format_real(outcome%compression_time))
         if (allocated(error)) return
      end do
      ! the power law and the user law over masses and speeds that take the contact
      ! time from 1e-280 s down through the subnormals
      do j = 0, 12
         do k = 0, 1
            m = 1.0e-300_wp * 10.0_wp**(-j)
            v = 10.0_wp**(150 + 5 * j)
            call impact(contact_type(mass=m, stiffness=1.0e300_wp, exponent=1.5_wp, &
               & damping=0.3_wp * k / v, velocity=v), outcome, stat)
            if (stat == hcimpact_ok) then
               call check(error, outcome%compression_time > 0.0_wp .and. &
                  & outcome%contact_time > 0.0_wp .and. outcome%time_at_peak_force > 0.0_wp &
                  & .and. outcome%max_compression > 0.0_wp, "power law, m = " &
                  & // format_real(m) // ", V = " // format_real(v) &
                  & // ": status OK with contact time " // format_real(outcome%contact_time))
            else
               call check(error, stat, hcimpact_err_domain, "power law, m = " // format_real(m))
            end if
            if (allocated(error)) return
         end do
      end do
   end subroutine test_times_below_subnormals

   !> n = 81.6 and b V = 6650: after a compression of 0.035 s the bodies creep apart at
   !> -k V for 209 s, most of it within 1e-16 of the end of contact in l. Located from
   !> the turning point, l - length cancelled: x reached 2e7 times x_max (the fuzz
   !> test). Now at every time either a status or 0 <= x <= x_max with |x'| <= V,
   !> x falling through the restitution, and most times answered.
   subroutine test_time_law_creeping(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n_times = 400
      type(contact_type) :: contact
      type(outcome_type) :: outcome
      real(wp) :: t(1), x(1), v(1), f(1), last_x
      integer :: i, stat, answered
      contact = contact_type(mass=5.2813803830685131e+33_wp, stiffness=81.568359375_wp, &
         & exponent=81.568359375_wp, damping=81.568359375_wp, velocity=81.505859375_wp)
      call impact(contact, outcome, stat)
      call check(error, stat, hcimpact_ok, "impact")
      if (allocated(error)) return
      last_x = outcome%max_compression
      answered = 0
      do i = 1, n_times
         t(1) = outcome%compression_time + (outcome%contact_time &
            & - outcome%compression_time) * (real(i, wp) / n_times)
         call time_law(contact, t, x, v, f, stat)
         if (stat /= hcimpact_ok) cycle
         answered = answered + 1
         call check(error, x(1) >= 0.0_wp .and. x(1) <= last_x .and. &
            & abs(v(1)) <= contact%velocity, "t = " // format_real(t(1)) // ": x = " &
            & // format_real(x(1)) // " (x_max " // format_real(outcome%max_compression) &
            & // ", the last time answered " // format_real(last_x) // "), x' = " &
            & // format_real(v(1)))
         if (allocated(error)) return
         last_x = x(1)
      end do
      call check(error, answered >= n_times / 2, "only " // int_text(answered) // " of " &
         & // int_text(n_times) // " times answered")
   end subroutine test_time_law_creeping

   !> Issue 13: impact_law's peak force came from a bisection on m f' u - (b f)^2, which
   !> overflowed or underflowed at large or tiny scales and gave wrong forces with
   !> hcimpact_ok (2.0e155 N for 8.9e184, 4.3e-87 N for 24573 N, 0 for 2.1e290). The
   !> user-law path with hcimpact_elastic's power_law against the power-law path, over
   !> exponents 0.1 to 10, beta 0, 1e-300 to 1e-8 and 1e-8 to 1e40, masses, stiffnesses
   !> and speeds over 60 decades: the same status, and outputs within what the law
   !> path's method allows (x_max by Newton's method on the law's potential: 4 ulps;
   !> the peak force f(x_p)(1 + u_p) with x_p from that inversion, f ~ x^n multiplying
   !> its error by n: (4 + n) ulps; x_p 8; the times by tanh-sinh on m V/f(x) with
   !> x = Pi^-1 at each node: 12 ulps; k identical). Beyond, with m, c, V over the
   !> whole double range, the law path may refuse (hcimpact_err_domain: the law's
   !> energies, forces or derivatives leave the double range where it evaluates them)
   !> but agrees wherever it answers; issue 13's first two contacts agree, the third
   !> (f' beyond the double range along the compression) is refused.
   subroutine test_user_law_ranges(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: tolerance(n_outputs) = [4.0_wp, 4.0_wp, 8.0_wp, 12.0_wp, &
         & 12.0_wp, 12.0_wp, 0.0_wp]
      real(wp) :: r(6), beta, decades
      type(contact_type) :: contact
      integer :: i, refused, pass
      refused = 0
      do pass = 1, 2
         decades = merge(30.0_wp, 300.0_wp, pass == 1)
         do i = 1, 300
            call lcg_uniform(i + 1000 * pass, r)
            contact%exponent = 10.0_wp**(2.0_wp * r(4) - 1.0_wp)
            contact%mass = 10.0_wp**(decades * (2.0_wp * r(1) - 1.0_wp))
            contact%stiffness = 10.0_wp**(decades * (2.0_wp * r(2) - 1.0_wp))
            contact%velocity = 10.0_wp**(decades * (2.0_wp * r(3) - 1.0_wp) / 2.5_wp)
            if (r(5) < 0.1_wp) then
               beta = 0.0_wp
            else if (r(5) < 0.2_wp) then
               beta = 10.0_wp**(-300.0_wp + 292.0_wp * r(6))
            else
               beta = 10.0_wp**(-8.0_wp + 48.0_wp * r(6))
            end if
            contact%damping = beta / contact%velocity
            call compare_law(error, contact, pass == 2, refused)
            if (allocated(error)) return
         end do
      end do
      ! issue 13's contacts
      call compare_law(error, contact_type(mass=1.0e300_wp, stiffness=1.7135e10_wp, &
         & exponent=1.5_wp, damping=0.1_wp, velocity=5.0_wp), .false., refused)
      if (allocated(error)) return
      call compare_law(error, contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, &
         & exponent=1.5_wp, damping=1.0e-300_wp, velocity=5.0_wp), .false., refused)
      if (allocated(error)) return
      ! (f'(x) = n f/x is 4e572 along the compression here: the law path cannot tell the
      ! sign of m f' x' - b f^2 next to the peak, and says so)
      call compare_law(error, contact_type(mass=10132144.0_wp, &
         & stiffness=3.198e304_wp, exponent=0.05_wp, damping=8.88e-16_wp, velocity=1.0_wp), &
         & .true., refused)
   contains
      !> impact and impact_law(power_law) of a contact: both hcimpact_ok and within
      !> `tolerance`, or (`may_refuse`) the law path hcimpact_err_domain
      subroutine compare_law(error, contact, may_refuse, refused)
         type(error_type), allocatable, intent(out) :: error
         type(contact_type), intent(in) :: contact
         logical, intent(in) :: may_refuse
         integer, intent(inout) :: refused
         type(outcome_type) :: direct, general
         real(wp) :: diff(n_outputs), allowed(n_outputs)
         integer :: stat, stat_law
         character(len=:), allocatable :: label
         call impact(contact, direct, stat)
         if (stat /= hcimpact_ok) return
         call impact_law(power_law(stiffness=contact%stiffness, exponent=contact%exponent), &
            & contact%mass, contact%damping, contact%velocity, general, stat_law)
         label = "m = " // format_real(contact%mass) // ", c = " &
            & // format_real(contact%stiffness) // ", n = " // format_real(contact%exponent) &
            & // ", b = " // format_real(contact%damping) // ", V = " &
            & // format_real(contact%velocity)
         if (may_refuse .and. stat_law == hcimpact_err_domain) then
            refused = refused + 1
            return
         end if
         call check(error, stat_law, hcimpact_ok, label // ": impact_law status")
         if (allocated(error)) return
         diff = abs(outputs(general) - outputs(direct)) / spacing(outputs(direct))
         allowed = tolerance
         allowed(2) = tolerance(2) + contact%exponent
         call check(error, all(diff <= allowed), label // ": impact_law(power_law) differs by " &
            & // utoa(diff(1)) // ", " // utoa(diff(2)) // ", " // utoa(diff(3)) // ", " &
            & // utoa(diff(4)) // ", " // utoa(diff(5)) // ", " // utoa(diff(6)) // ", " &
            & // utoa(diff(7)) // " ulp")
      end subroutine compare_law
   end subroutine test_user_law_ranges

   !> Uniform numbers in (0, 1) from a fixed sequence started at `seed` (Park and
   !> Miller's minimal standard generator, x -> 48271 x mod (2^31 - 1), whose products
   !> fit in 64 bits): the same on every compiler and run
   pure subroutine lcg_uniform(seed, r)
      integer, intent(in) :: seed
      real(wp), intent(out) :: r(:)
      integer(int64), parameter :: modulus = 2147483647_int64
      integer(int64) :: state
      integer :: i, j
      state = modulo(int(seed, int64) * 16807_int64 + 12345_int64, modulus)
      if (state == 0_int64) state = 1_int64
      ! (a few steps first: neighbouring seeds then give unrelated numbers)
      do j = 1, 8
         state = modulo(state * 48271_int64, modulus)
      end do
      do i = 1, size(r)
         state = modulo(state * 48271_int64, modulus)
         r(i) = real(state, wp) / real(modulus, wp)
      end do
   end subroutine lcg_uniform

   !> damping_for_restitution over e from 1e-320 to 1 and speeds from subnormal to
   !> DBL_MAX: b = beta(e)/V whenever that is a double (issue 13: b = +Inf with
   !> hcimpact_ok for e = 1e-310, where b = 1/(e V) = 1e300 at V = 1e10 is a double),
   !> hcimpact_err_domain with NaN where it exceeds the largest double
   !> ((1e-310, 1, 1e-3) and (0.5, 0, 1e-320) of the issue). The expectation: ln b
   !> from the mpmath inverse of restitution.csv (beta = 1/e below 2^-60), decided
   !> away from the boundary by ln 4; where b V is a normal double, b V = beta(e)
   !> within 2 ulps.
   subroutine test_damping_extremes(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: targets(9) = [1.0e-320_wp, 1.0e-310_wp, 1.0e-300_wp, &
         & 1.0e-100_wp, 1.0e-20_wp, 0.01_wp, 0.5_wp, 0.9_wp, 1.0_wp - epsilon(1.0_wp)]
      real(wp), parameter :: speeds(10) = [0.0_wp, 1.0e-320_wp, 1.0e-300_wp, 1.0e-10_wp, &
         & 1.0_wp, 1.0e10_wp, 1.0e100_wp, 1.0e300_wp, 1.7e308_wp, huge(1.0_wp)]
      real(wp) :: b, beta, ln_b, speed
      integer :: i, j, stat
      character(len=:), allocatable :: label
      do i = 1, size(targets)
         do j = 1, size(speeds)
            speed = max(speeds(j), 1.0e-320_wp)
            call damping_for_restitution(targets(i), speeds(j), b, stat, &
               & min_velocity=1.0e-320_wp)
            label = "e = " // format_real(targets(i)) // ", V = " // format_real(speeds(j))
            if (targets(i) < 2.0_wp**(-60)) then
               ! ln(1/(e V)) without forming it
               ln_b = -(log(targets(i)) + log(speed))
            else
               call restitution_of(targets(i), beta)
               ln_b = log(beta) - log(speed)
            end if
            if (ln_b > log(huge(1.0_wp)) + log(4.0_wp)) then
               call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(b), label &
                  & // ": b beyond DBL_MAX, status " // int_text(stat))
            else if (ln_b < log(huge(1.0_wp)) - log(4.0_wp)) then
               call check(error, stat == hcimpact_ok .and. ieee_is_finite(b) .and. &
                  & b >= 0.0_wp, label // ": status " // int_text(stat) // ", b = " &
                  & // format_real(b))
               if (allocated(error)) return
               ! b = beta/V to its rounding (a subnormal b has fewer digits)
               if (b >= tiny(1.0_wp)) then
                  call check(error, abs(log(b) - ln_b) <= 1.0e-13_wp * max(1.0_wp, abs(ln_b)), &
                     & label // ": ln b = " // format_real(log(b)) // ", expected " &
                     & // format_real(ln_b))
                  if (allocated(error)) return
                  if (speed >= 1.0e-150_wp .and. speed <= 1.0e150_wp .and. &
                     & targets(i) >= 2.0_wp**(-60)) then
                     call check(error, abs(b * speed - beta) <= 2.0_wp * spacing(beta), &
                        & label // ": b V = " // format_real(b * speed) // ", beta(e) = " &
                        & // format_real(beta))
                  end if
               end if
            end if
            if (allocated(error)) return
         end do
      end do
      ! issue 13's cases, and b = 1/(e V) = 1e300 exactly as the product and quotient of
      ! the doubles give it
      call damping_for_restitution(1.0e-310_wp, 1.0_wp, b, stat, min_velocity=1.0e-3_wp)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(b), &
         & "(1e-310, 1, 1e-3): status " // int_text(stat))
      if (allocated(error)) return
      call damping_for_restitution(0.5_wp, 0.0_wp, b, stat, min_velocity=1.0e-320_wp)
      call check(error, stat == hcimpact_err_domain .and. ieee_is_nan(b), &
         & "(0.5, 0, 1e-320): status " // int_text(stat))
      if (allocated(error)) return
      call damping_for_restitution(1.0e-310_wp, 1.0e10_wp, b, stat)
      call check(error, stat == hcimpact_ok .and. abs(b - 1.0_wp / (1.0e-310_wp * 1.0e10_wp)) &
         & <= spacing(b), "(1e-310, 1e10): b = " // format_real(b))
   contains
      !> beta(e), the exact inverse of k(beta) (hcimpact_restitution_law, within 4 ulps
      !> of mpmath's restitution.csv)
      subroutine restitution_of(e, beta)
         real(wp), intent(in) :: e
         real(wp), intent(out) :: beta
         beta = restitution_inverse(e)
      end subroutine restitution_of
   end subroutine test_damping_extremes

   !> Out of memory is a status, not an abort (issue 13: "Error allocating 320000000
   !> bytes" stopped the process in time_law_samples and in the C wrappers of the time
   !> law): with the address space limited (setrlimit RLIMIT_AS, Linux) to what the
   !> process uses plus 16 MB, time_law_samples of 2^22 samples and the C entry points
   !> hcimpact_time_law and hcimpact_time_law_samples, whose copies need 128 MB, give
   !> hcimpact_err_out_of_memory (not hcimpact_err_size: the size is valid) with NaN
   !> outputs and nothing allocated; the limit is restored and the same calls with 11
   !> samples work.
   subroutine test_out_of_memory(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 2**22
      type(rlimit_type), target :: old_limit, new_limit
      type(hcimpact_contact), target :: c_contact
      real(wp), allocatable, target :: t(:), x(:), v(:), f(:)
      real(wp), allocatable :: ts(:), xs(:), vs(:), fs(:), probe(:)
      integer(c_long) :: used
      integer :: stat, alloc_stat
      integer(c_int) :: c_stat
      type(contact_type) :: contact

      contact = contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
         & damping=0.1_wp, velocity=1.0_wp)
      c_contact = hcimpact_contact(0.1_wp, 1.7135e10_wp, 1.5_wp, 0.1_wp, 1.0_wp)
      ! the caller's arrays, before the limit
      allocate(t(n), x(n), v(n), f(n))
      t = 1.0e-5_wp
      x = 0.0_wp
      used = address_space_used()
      if (used <= 0_c_long .or. c_getrlimit(rlimit_as, old_limit) /= 0) then
         call test_failed(error, "cannot read the address space used (/proc/self/status) " &
            & // "or its limit (getrlimit): this test needs Linux")
         return
      end if
      new_limit = rlimit_type(used + 16_c_long * 2_c_long**20, old_limit%max)
      if (c_setrlimit(rlimit_as, new_limit) /= 0) then
         call test_failed(error, "setrlimit(RLIMIT_AS) failed")
         return
      end if
      ! the limit acts: 32 MB cannot be had
      allocate(probe(n), stat=alloc_stat)
      if (alloc_stat == 0) then
         deallocate(probe)
         stat = c_setrlimit(rlimit_as, old_limit)
         call test_failed(error, "the address-space limit does not act on allocate")
         return
      end if
      call time_law_samples(contact, n, ts, xs, vs, fs, stat)
      c_stat = c_time_law(c_loc(c_contact), int(n, c_int), c_loc(t), c_loc(x), c_loc(v), &
         & c_loc(f))
      ! restore before any check (the checks' messages allocate)
      alloc_stat = c_setrlimit(rlimit_as, old_limit)
      call check(error, alloc_stat == 0, "setrlimit could not restore the limit")
      if (allocated(error)) return
      call check(error, stat == hcimpact_err_out_of_memory .and. .not. (allocated(ts) .or. &
         & allocated(xs) .or. allocated(vs) .or. allocated(fs)), "time_law_samples, " &
         & // int_text(n) // " samples without the memory: status " // int_text(stat))
      if (allocated(error)) return
      call check(error, c_stat == hcimpact_err_out_of_memory .and. ieee_is_nan(x(1)) &
         & .and. ieee_is_nan(f(n)), "hcimpact_time_law without the memory: status " &
         & // int_text(int(c_stat)))
      if (allocated(error)) return
      ! hcimpact_time_law_samples, under the limit again
      used = address_space_used()
      new_limit = rlimit_type(used + 16_c_long * 2_c_long**20, old_limit%max)
      stat = c_setrlimit(rlimit_as, new_limit)
      c_stat = c_time_law_samples(c_loc(c_contact), int(n, c_int), c_loc(t), c_loc(x), &
         & c_loc(v), c_loc(f))
      alloc_stat = c_setrlimit(rlimit_as, old_limit)
      call check(error, stat == 0 .and. alloc_stat == 0 &
         & .and. c_stat == hcimpact_err_out_of_memory &
         & .and. ieee_is_nan(t(1)) .and. ieee_is_nan(x(n)), "hcimpact_time_law_samples " &
         & // "without the memory: status " // int_text(int(c_stat)))
      if (allocated(error)) return
      ! and with the memory, the same calls work
      call time_law_samples(contact, 11, ts, xs, vs, fs, stat)
      call check(error, stat == hcimpact_ok .and. size(xs) == 11 .and. xs(11) == 0.0_wp, &
         & "time_law_samples after the limit: status " // int_text(stat))
      if (allocated(error)) return
      c_stat = c_time_law_samples(c_loc(c_contact), 11_c_int, c_loc(t), c_loc(x), c_loc(v), &
         & c_loc(f))
      call check(error, c_stat == hcimpact_ok .and. x(11) == 0.0_wp .and. t(1) == 0.0_wp, &
         & "hcimpact_time_law_samples after the limit: status " // int_text(int(c_stat)))
   end subroutine test_out_of_memory

   !> The address space of this process in bytes (VmSize of /proc/self/status), or 0
   function address_space_used() result(bytes)
      integer(c_long) :: bytes
      character(len=256) :: line
      integer :: unit, stat
      integer(c_long) :: kb
      bytes = 0_c_long
      open(newunit=unit, file="/proc/self/status", status="old", action="read", iostat=stat)
      if (stat /= 0) return
      do
         read(unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         if (line(1:7) == "VmSize:") then
            read(line(8:), *, iostat=stat) kb
            if (stat == 0) bytes = kb * 1024_c_long
            exit
         end if
      end do
      close(unit)
   end function address_space_used

   !> Contacts of a sweep of 15000 random contacts with m, c, b, V over the whole double
   !> range and n up to 1e308, through every entry point of one impact in the build that
   !> traps overflows (no trap, and never hcimpact_ok with a non-finite output, over
   !> all of them): x_max = 3.6e282, whose time unit's product with 1/H overflowed
   !> before its quotient by V (hcimpact_err_domain in Release, a trap in Debug: now
   !> the outcome, checked against impact_extremes.csv by extremes-reference); beta =
   !> 2.1e38 with n = 9.3, where d R(d) underflowed next to the end of contact in the
   !> time law's density (a division by zero); and three user laws at scales where the
   !> bracket of x_max doubled past the largest double or a Newton step on the
   !> potential overflowed (now statuses).
   subroutine test_extreme_scales(error)
      type(error_type), allocatable, intent(out) :: error
      real(wp), parameter :: inputs(5, 5) = reshape([ &
         & 2.29562955624599565e183_wp, 1.72121672058806109e-67_wp, 0.936194925387041965_wp, &
         & 8.83804562301416088e-135_wp, 4.08593997108846904e162_wp, &
         & 1.73107294698573407e-203_wp, 1.43134534168580123e-57_wp, 9.33407117475858250_wp, &
         & 3.94631707913109737e-128_wp, 5.24414686115013018e165_wp, &
         & 3.75489264331336674e225_wp, 3.69129862836096908e-276_wp, 0.160580950885196_wp, &
         & 1.65858497925692866e-264_wp, 1.56504507912742615e9_wp, &
         & 2.07614115590699577e71_wp, 5.74450124233698532e-268_wp, 477.674489747353789_wp, &
         & 2.97902984870660906e-55_wp, 4.12899553943894592e17_wp, &
         & 1.07689106738678592e113_wp, 3.70945170210246938e-66_wp, 538.543965254746922_wp, &
         & 1.89916783817655915e-273_wp, 5.09913261691190638e43_wp], [5, 5])
      type(contact_type) :: contact
      type(outcome_type) :: outcome, general
      real(wp) :: x(3), v(3), f(3), w
      integer :: i, stat, stat_law, branch
      character(len=:), allocatable :: label
      do i = 1, size(inputs, 2)
         contact = contact_type(mass=inputs(1, i), stiffness=inputs(2, i), &
            & exponent=inputs(3, i), damping=inputs(4, i), velocity=inputs(5, i))
         label = "contact " // int_text(i)
         call impact(contact, outcome, stat)
         if (i <= 2) then
            call check(error, stat == hcimpact_ok, label // ": every output is a double, " &
               & // "status " // int_text(stat))
            if (allocated(error)) return
         end if
         call check(error, stat /= hcimpact_ok .or. all(ieee_is_finite(outputs(outcome))), &
            & label // ": impact")
         if (allocated(error)) return
         if (stat == hcimpact_ok) then
            call time_law(contact, [0.01_wp, 0.5_wp, 0.99_wp] * outcome%contact_time, x, v, &
               & f, stat)
            call check(error, stat == hcimpact_ok .and. all(ieee_is_finite([x, v, f])) &
               & .and. all(x > 0.0_wp), label // ": time law, status " // int_text(stat))
            if (allocated(error)) return
            do branch = compression_branch, restitution_branch
               call velocity_at_depth(contact, 0.5_wp * outcome%max_compression, branch, w, &
                  & stat)
               call check(error, stat == hcimpact_ok .and. ieee_is_finite(w), label &
                  & // ": velocity at a depth, status " // int_text(stat))
               if (allocated(error)) return
            end do
         end if
         call impact_law(power_law(stiffness=contact%stiffness, exponent=contact%exponent), &
            & contact%mass, contact%damping, contact%velocity, general, stat_law)
         call check(error, stat_law /= hcimpact_ok .or. &
            & all(ieee_is_finite(outputs(general))), label // ": impact_law")
         if (allocated(error)) return
      end do
   end subroutine test_extreme_scales

end module test_impact
