! SPDX-License-Identifier: Apache-2.0
!> The C entry point hcimpact_chain_simulate (called here through its C binding, as a
!> C program calls it) and the FORTRAN 77 routine HCCHN (through its implicit
!> interface) against `chain_simulate` of the Fortran API: the same systems give the
!> same bits in every output (final state, the result's reals and counts, every
!> contact, the samples); and their answers to bad input (NULL, sizes, NaN, domain):
!> the documented status or INFO, nothing written or NaN as documented.
module test_cvode_chain_api
   use, intrinsic :: iso_c_binding, only : c_int, c_double, c_ptr, c_size_t, c_char, &
      & c_null_ptr, c_null_char, c_loc
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan, ieee_value, ieee_quiet_nan, &
      & ieee_positive_inf
   use testdrive, only : new_unittest, unittest_type, error_type, check
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_null, hcimpact_err_size, &
      & hcimpact_err_not_finite, hcimpact_err_mass, hcimpact_err_domain, &
      & hcimpact_err_stiffness
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, chain_result, &
      & method_exact, method_integrated, integrator_adams
   use hcimpact_cvode, only : chain_simulate
   use hcimpact_cvode_chain_capi_types, only : hcimpact_chain_law, hcimpact_chain_wall, &
      & hcimpact_chain_options, hcimpact_chain_result, hcimpact_chain_contact, &
      & hcimpact_chain_samples
   implicit none
   private

   public :: collect_chain_api

   interface
      !> The C entry point, declared as include/hcimpact_cvode.h declares it
      function hcimpact_chain_simulate(n, masses, velocities, gaps, laws, left_wall, &
            & right_wall, gravity, options, result, positions, final_velocities, &
            & contact_capacity, contacts, samples, message, message_size) result(stat) &
            & bind(C, name="hcimpact_chain_simulate")
         import :: c_int, c_double, c_ptr, c_size_t
         integer(c_int), value :: n
         type(c_ptr), value :: masses, velocities, gaps, laws, left_wall, right_wall
         real(c_double), value :: gravity
         type(c_ptr), value :: options, result, positions, final_velocities
         integer(c_int), value :: contact_capacity
         type(c_ptr), value :: contacts, samples, message
         integer(c_size_t), value :: message_size
         integer(c_int) :: stat
      end function hcimpact_chain_simulate
   end interface

   !> Steel balls of 0.1 kg; Hertz's constant of two of them (the plate's over sqrt 2)
   real(wp), parameter :: ball_mass = 0.1_wp, plate = 1.7135e10_wp, &
      & pair_stiffness = plate / 1.4142135623730951_wp

   !> Contacts the tests give room for
   integer, parameter :: capacity = 64

   !> Number of test systems (test_system)
   integer, parameter :: n_systems = 5

   !> What the C entry point gives: status, result, final state, contacts, samples,
   !> message.
   type :: c_answer
      integer :: stat = -1
      type(hcimpact_chain_result) :: result
      real(c_double), allocatable :: positions(:), velocities(:)
      type(hcimpact_chain_contact), allocatable :: contacts(:)
      real(c_double), allocatable :: sample_x(:), sample_v(:), sample_f(:)
      character(len=:), allocatable :: message
   end type c_answer

contains

   !> Collect all exported unit tests
   subroutine collect_chain_api(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("c-matches-fortran", test_c_matches_fortran), &
         & new_unittest("f77-matches-fortran", test_f77_matches_fortran), &
         & new_unittest("c-capacity-and-message", test_c_capacity), &
         & new_unittest("c-default-options", test_c_default_options), &
         & new_unittest("c-null-and-sizes", test_c_null_and_sizes), &
         & new_unittest("c-bad-values", test_c_bad_values), &
         & new_unittest("f77-bad-arguments", test_f77_bad_arguments) &
         & ]
   end subroutine collect_chain_api

   ! ---------------------------------------------------------------------------------
   ! The systems
   ! ---------------------------------------------------------------------------------

   !> System k of the comparisons, with its options (sample times for some).
   subroutine test_system(k, chain, options, what)
      integer, intent(in) :: k
      type(chain_type), intent(out) :: chain
      type(chain_options), intent(out) :: options
      character(len=:), allocatable, intent(out) :: what
      integer :: i
      select case (k)
      case (1)
         what = "two steel balls, b = 0.1 (closed forms)"
         call line_of(chain, 2, 0.1_wp, [1.5_wp, -0.5_wp], 2.0e-4_wp)
      case (2)
         what = "three touching balls, b = 0.05 (a cluster), sampled"
         call line_of(chain, 3, 0.05_wp, [1.0_wp, 0.0_wp, 0.0_wp], 0.0_wp)
         options%sample_times = [(1.0e-5_wp * real(i, wp), i = 0, 30)]
      case (3)
         what = "three balls with gaps between two walls, t_end"
         call line_of(chain, 3, 0.1_wp, [2.0_wp, 0.0_wp, -1.0_wp], 1.0e-5_wp)
         chain%left_wall = .true.
         chain%left_law = contact_law(plate, 1.5_wp, 0.2_wp)
         chain%left_gap = 1.0e-4_wp
         chain%right_wall = .true.
         chain%right_law = contact_law(plate, 1.5_wp, 0.0_wp)
         chain%right_gap = 3.0e-5_wp
         options%t_end = 2.0e-3_wp
      case (4)
         what = "a ball dropped on a floor, integrated, Adams, t_end"
         call line_of(chain, 1, 0.5_wp, [0.0_wp], 0.0_wp)
         chain%left_wall = .true.
         chain%left_law = contact_law(plate, 1.5_wp, 0.5_wp)
         chain%left_gap = 1.0e-3_wp
         chain%gravity = -9.81_wp
         options%t_end = 0.03_wp
         options%method = method_integrated
         options%integrator = integrator_adams
         options%rtol = 1.0e-8_wp
         options%sample_times = [0.0_wp, 0.01_wp, 0.02_wp]
      case default
         what = "one free body"
         call line_of(chain, 1, 0.0_wp, [3.0_wp], 0.0_wp)
      end select
   end subroutine test_system

   !> n steel balls of damping b with the initial velocities v and equal gaps.
   subroutine line_of(chain, n, b, v, gap)
      type(chain_type), intent(out) :: chain
      integer, intent(in) :: n
      real(wp), intent(in) :: b, v(n), gap
      allocate(chain%mass(n))
      chain%mass = ball_mass
      chain%velocity = v
      allocate(chain%gap(n - 1), chain%law(n - 1))
      chain%gap = gap
      chain%law = contact_law(pair_stiffness, 1.5_wp, b)
   end subroutine line_of

   ! ---------------------------------------------------------------------------------
   ! Calls
   ! ---------------------------------------------------------------------------------

   !> Call hcimpact_chain_simulate as a C program would, with the arrays of `chain`.
   subroutine call_c(chain, options, answer, capacity_given, message_size, null_options)
      type(chain_type), intent(in) :: chain
      type(chain_options), intent(in) :: options
      type(c_answer), intent(out), target :: answer
      integer, intent(in), optional :: capacity_given
      integer, intent(in), optional :: message_size
      logical, intent(in), optional :: null_options
      real(c_double), allocatable, target :: masses(:), velocities(:), gaps(:), times(:)
      type(hcimpact_chain_law), allocatable, target :: laws(:)
      type(hcimpact_chain_wall), target :: left, right
      type(hcimpact_chain_options), target :: c_options
      type(hcimpact_chain_samples), target :: samples
      character(kind=c_char), allocatable, target :: buffer(:)
      type(c_ptr) :: p_left, p_right, p_options, p_samples, p_gaps, p_laws, p_contacts
      integer :: n, i, ns, cap, msize

      n = size(chain%mass)
      cap = capacity
      if (present(capacity_given)) cap = capacity_given
      msize = 256
      if (present(message_size)) msize = message_size
      masses = chain%mass
      velocities = chain%velocity
      gaps = chain%gap
      allocate(laws(n - 1))
      do i = 1, n - 1
         laws(i) = hcimpact_chain_law(chain%law(i)%stiffness, chain%law(i)%exponent, &
            & chain%law(i)%damping)
      end do
      p_gaps = c_null_ptr
      p_laws = c_null_ptr
      if (n > 1) then
         p_gaps = c_loc(gaps)
         p_laws = c_loc(laws)
      end if
      p_left = c_null_ptr
      if (chain%left_wall) then
         left = hcimpact_chain_wall(chain%left_law%stiffness, chain%left_law%exponent, &
            & chain%left_law%damping, chain%left_gap)
         p_left = c_loc(left)
      end if
      p_right = c_null_ptr
      if (chain%right_wall) then
         right = hcimpact_chain_wall(chain%right_law%stiffness, chain%right_law%exponent, &
            & chain%right_law%damping, chain%right_gap)
         p_right = c_loc(right)
      end if
      c_options = hcimpact_chain_options(t_end=options%t_end, rtol=options%rtol, &
         & max_steps=options%max_steps, max_events=options%max_events, &
         & method=options%method, integrator=options%integrator)
      p_options = c_loc(c_options)
      if (present(null_options)) then
         if (null_options) p_options = c_null_ptr
      end if
      ns = 0
      if (allocated(options%sample_times)) ns = size(options%sample_times)
      allocate(answer%positions(n), answer%velocities(n), answer%contacts(max(cap, 1)), &
         & answer%sample_x(n * ns), answer%sample_v(n * ns), answer%sample_f((n + 1) * ns))
      p_samples = c_null_ptr
      if (ns > 0) then
         times = options%sample_times
         samples = hcimpact_chain_samples(ns, c_loc(times), c_loc(answer%sample_x), &
            & c_loc(answer%sample_v), c_loc(answer%sample_f))
         p_samples = c_loc(samples)
      end if
      p_contacts = c_null_ptr
      if (cap > 0) p_contacts = c_loc(answer%contacts)
      allocate(buffer(max(msize, 1)))
      buffer = "#"
      answer%stat = hcimpact_chain_simulate(int(n, c_int), c_loc(masses), c_loc(velocities), &
         & p_gaps, p_laws, p_left, p_right, real(chain%gravity, c_double), p_options, &
         & c_loc(answer%result), c_loc(answer%positions), c_loc(answer%velocities), &
         & int(cap, c_int), p_contacts, p_samples, c_loc(buffer), int(msize, c_size_t))
      answer%message = ""
      do i = 1, size(buffer)
         if (buffer(i) == c_null_char) exit
         answer%message = answer%message // buffer(i)
      end do
      if (msize > 0 .and. i > size(buffer)) answer%message = "(no NUL)"
   end subroutine call_c

   !> The Fortran answer with the options the C call had (its capacity).
   subroutine call_fortran(chain, options, result, stat)
      type(chain_type), intent(in) :: chain
      type(chain_options), intent(in) :: options
      type(chain_result), intent(out) :: result
      integer, intent(out) :: stat
      type(chain_options) :: opts
      opts = options
      opts%max_contacts = capacity
      call chain_simulate(chain, result, stat, opts)
   end subroutine call_fortran

   !> Same bits (NaN of the same payload included)
   elemental logical function same(a, b)
      real(wp), intent(in) :: a, b
      same = transfer(a, 0_int64) == transfer(b, 0_int64)
   end function same

   ! ---------------------------------------------------------------------------------
   ! C and FORTRAN 77 against Fortran
   ! ---------------------------------------------------------------------------------

   subroutine test_c_matches_fortran(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_type) :: chain
      type(chain_options) :: options
      type(chain_result) :: expected
      type(c_answer) :: got
      character(len=:), allocatable :: what
      integer :: k, stat, i, n

      do k = 1, n_systems
         call test_system(k, chain, options, what)
         call call_fortran(chain, options, expected, stat)
         call check(error, stat, hcimpact_ok, what // " (Fortran): " // trim(expected%message))
         if (allocated(error)) return
         call call_c(chain, options, got)
         call check(error, got%stat, hcimpact_ok, what // " (C): " // got%message)
         if (allocated(error)) return
         call check(error, got%message, trim(expected%message), what // ": message")
         if (allocated(error)) return
         n = size(chain%mass)
         call check(error, all(same(got%positions, expected%positions)) .and. &
            & all(same(got%velocities, expected%velocities)), what // ": final state")
         if (allocated(error)) return
         call check(error, all(same([got%result%time, got%result%rest_time, &
            & got%result%initial_energy, got%result%energy_error, got%result%dissipated, &
            & got%result%momentum_error, got%result%wall_impulse_left, &
            & got%result%wall_impulse_right], [expected%time, &
            & expected%rest_time, expected%initial_energy, expected%energy_error, &
            & expected%dissipated, expected%momentum_error, expected%wall_impulse])), &
            & what // ": the result's reals")
         if (allocated(error)) return
         call check(error, all([got%result%n_contacts, got%result%contacts_recorded, &
            & got%result%closed_form_contacts, got%result%integrated_contacts, &
            & got%result%steps, got%result%rhs_evals, got%result%jacobian_evals, &
            & got%result%roots, got%result%clusters, int(got%result%method_used, int64), &
            & int(got%result%rested, int64)] == [expected%n_contacts, &
            & int(size(expected%contacts), int64), &
            & expected%counters%closed_form_contacts, expected%counters%integrated_contacts, &
            & expected%counters%steps, expected%counters%rhs_evals, &
            & expected%counters%jacobian_evals, expected%counters%roots, &
            & expected%counters%clusters, int(expected%method_used, int64), &
            & merge(1_int64, 0_int64, expected%rested)]), what // ": the result's counts")
         if (allocated(error)) return
         do i = 1, size(expected%contacts)
            call check(error, got%contacts(i)%pair == expected%contacts(i)%pair .and. &
               & got%contacts(i)%method == expected%contacts(i)%method .and. &
               & all(same([got%contacts(i)%t_start, got%contacts(i)%t_end, &
               & got%contacts(i)%approach_speed, got%contacts(i)%separation_speed, &
               & got%contacts(i)%peak_force, got%contacts(i)%max_deformation, &
               & got%contacts(i)%dissipated], [expected%contacts(i)%t_start, &
               & expected%contacts(i)%t_end, expected%contacts(i)%approach_speed, &
               & expected%contacts(i)%separation_speed, expected%contacts(i)%peak_force, &
               & expected%contacts(i)%max_deformation, expected%contacts(i)%dissipated])), &
               & what // ": a contact")
            if (allocated(error)) return
         end do
         if (allocated(options%sample_times)) then
            call check(error, all(same(got%sample_x, reshape(expected%sample_positions, &
               & [size(got%sample_x)]))) .and. all(same(got%sample_v, &
               & reshape(expected%sample_velocities, [size(got%sample_v)]))) .and. &
               & all(same(got%sample_f, reshape(expected%sample_forces, &
               & [size(got%sample_f)]))), what // ": samples")
            if (allocated(error)) return
         end if
         ! the systems mean something: contacts happened (but the free body)
         if (k < n_systems) then
            call check(error, expected%n_contacts > 0, what // ": no contact at all")
            if (allocated(error)) return
         end if
      end do
   end subroutine test_c_matches_fortran

   subroutine test_f77_matches_fortran(error)
      type(error_type), allocatable, intent(out) :: error
      external :: hcchn
      type(chain_type) :: chain
      type(chain_options) :: options
      type(chain_result) :: expected
      character(len=:), allocatable :: what
      character(len=200) :: msg
      real(wp), allocatable :: gap(:), plaw(:, :), x(:), vf(:)
      real(wp) :: wall(4, 2), opts(2), res(8), cont(capacity, 7)
      integer :: iopts(4), icnt(11), icon(capacity, 2), info, k, stat, i, n

      do k = 1, n_systems
         call test_system(k, chain, options, what)
         if (allocated(options%sample_times)) deallocate(options%sample_times)
         call call_fortran(chain, options, expected, stat)
         call check(error, stat, hcimpact_ok, what // " (Fortran)")
         if (allocated(error)) return
         n = size(chain%mass)
         gap = [chain%gap, 0.0_wp]
         allocate(plaw(3, max(n - 1, 1)))
         do i = 1, n - 1
            plaw(:, i) = [chain%law(i)%stiffness, chain%law(i)%exponent, chain%law(i)%damping]
         end do
         wall = 0.0_wp
         if (chain%left_wall) wall(:, 1) = [chain%left_law%stiffness, &
            & chain%left_law%exponent, chain%left_law%damping, chain%left_gap]
         if (chain%right_wall) wall(:, 2) = [chain%right_law%stiffness, &
            & chain%right_law%exponent, chain%right_law%damping, chain%right_gap]
         opts = [options%t_end, options%rtol]
         iopts = [options%method, options%integrator, int(options%max_steps), &
            & int(options%max_events)]
         allocate(x(n), vf(n))
         call hcchn(n, chain%mass, chain%velocity, gap, plaw, wall, chain%gravity, opts, &
            & iopts, x, vf, res, icnt, capacity, capacity, cont, icon, msg, info)
         call check(error, info, 0, what // " (HCCHN): " // trim(msg))
         if (allocated(error)) return
         call check(error, trim(msg), trim(expected%message), what // ": MSG")
         if (allocated(error)) return
         call check(error, all(same(x, expected%positions)) .and. &
            & all(same(vf, expected%velocities)), what // ": X, VF")
         if (allocated(error)) return
         call check(error, all(same(res, [expected%time, expected%rest_time, &
            & expected%initial_energy, expected%energy_error, expected%dissipated, &
            & expected%momentum_error, expected%wall_impulse])), what // ": RES")
         if (allocated(error)) return
         call check(error, all(int(icnt, int64) == [expected%n_contacts, &
            & int(size(expected%contacts), int64), int(expected%method_used, int64), &
            & merge(1_int64, 0_int64, expected%rested), &
            & expected%counters%closed_form_contacts, expected%counters%integrated_contacts, &
            & expected%counters%steps, expected%counters%rhs_evals, &
            & expected%counters%jacobian_evals, expected%counters%roots, &
            & expected%counters%clusters]), what // ": ICNT")
         if (allocated(error)) return
         do i = 1, size(expected%contacts)
            call check(error, icon(i, 1) == expected%contacts(i)%pair .and. &
               & icon(i, 2) == expected%contacts(i)%method .and. &
               & all(same(cont(i, :), [expected%contacts(i)%t_start, &
               & expected%contacts(i)%t_end, expected%contacts(i)%approach_speed, &
               & expected%contacts(i)%separation_speed, expected%contacts(i)%peak_force, &
               & expected%contacts(i)%max_deformation, expected%contacts(i)%dissipated])), &
               & what // ": CONT, ICON")
            if (allocated(error)) return
         end do
         deallocate(plaw, x, vf)
      end do
   end subroutine test_f77_matches_fortran

   ! ---------------------------------------------------------------------------------
   ! The C interface's own rules
   ! ---------------------------------------------------------------------------------

   !> A capacity below the number of contacts keeps the first ones and counts all; a
   !> short message buffer is cut and NUL-terminated.
   subroutine test_c_capacity(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_type) :: chain
      type(chain_options) :: options
      type(c_answer) :: full, few, none
      character(len=:), allocatable :: what
      integer :: i

      call test_system(3, chain, options, what)
      call call_c(chain, options, full)
      call check(error, full%stat, hcimpact_ok, what)
      if (allocated(error)) return
      call check(error, full%result%n_contacts >= 3 .and. full%result%n_contacts <= capacity, &
         & "the walled system has a few contacts")
      if (allocated(error)) return
      call call_c(chain, options, few, capacity_given=2, message_size=4)
      call check(error, few%stat, hcimpact_ok, "capacity 2")
      if (allocated(error)) return
      call check(error, few%result%n_contacts == full%result%n_contacts .and. &
         & few%result%contacts_recorded == 2, "capacity 2: all counted, two recorded")
      if (allocated(error)) return
      do i = 1, 2
         call check(error, few%contacts(i)%pair == full%contacts(i)%pair .and. &
            & same(few%contacts(i)%t_end, full%contacts(i)%t_end), "capacity 2: the first two")
         if (allocated(error)) return
      end do
      call check(error, few%message, "suc", "a buffer of 4 bytes holds 3 characters")
      if (allocated(error)) return
      call check(error, all(same(few%velocities, full%velocities)), &
         & "the capacity changes no result")
      if (allocated(error)) return
      call call_c(chain, options, none, capacity_given=0, message_size=0)
      call check(error, none%stat, hcimpact_ok, "capacity 0, contacts NULL")
      if (allocated(error)) return
      call check(error, none%result%n_contacts == full%result%n_contacts .and. &
         & none%result%contacts_recorded == 0, "capacity 0: counted, none recorded")
   end subroutine test_c_capacity

   !> Options of zeros and NULL options are the defaults of chain_options.
   subroutine test_c_default_options(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_type) :: chain
      type(chain_options) :: options, zeros
      type(chain_result) :: expected
      type(c_answer) :: by_zeros, by_null
      character(len=:), allocatable :: what
      integer :: stat

      call test_system(2, chain, options, what)
      call call_fortran(chain, chain_options(), expected, stat)
      call check(error, stat, hcimpact_ok, what)
      if (allocated(error)) return
      zeros%t_end = 0.0_wp
      zeros%rtol = 0.0_wp
      zeros%method = 0
      zeros%integrator = 0
      zeros%max_steps = 0
      zeros%max_events = 0
      call call_c(chain, zeros, by_zeros)
      call call_c(chain, zeros, by_null, null_options=.true.)
      call check(error, by_zeros%stat == hcimpact_ok .and. by_null%stat == hcimpact_ok, &
         & "zeros and NULL accepted")
      if (allocated(error)) return
      call check(error, all(same(by_zeros%velocities, expected%velocities)) .and. &
         & all(same(by_null%velocities, expected%velocities)) .and. &
         & by_zeros%result%steps == expected%counters%steps .and. &
         & by_null%result%steps == expected%counters%steps, &
         & "zeros and NULL give the Fortran defaults' answer")
   end subroutine test_c_default_options

   !> NULL pointers and sizes: the status, nothing written but the message.
   subroutine test_c_null_and_sizes(error)
      type(error_type), allocatable, intent(out) :: error
      real(c_double), target :: m(3), v(3), gaps(2), x(3), times(2)
      type(hcimpact_chain_law), target :: laws(2)
      type(hcimpact_chain_result), target :: res
      type(hcimpact_chain_samples), target :: samples
      type(hcimpact_chain_contact), target :: contacts(2)
      character(kind=c_char), target :: buffer(128)
      integer :: stat

      m = ball_mass
      v = [1.0_wp, 0.0_wp, 0.0_wp]
      gaps = 0.0_wp
      laws = hcimpact_chain_law(pair_stiffness, 1.5_wp, 0.0_wp)
      res%time = -7.0_wp
      x = -7.0_wp

      stat = run(3, c_loc(m), c_loc(v), c_loc(gaps), c_loc(laws), c_null_ptr, 0, c_null_ptr)
      call expect(hcimpact_err_null, "result NULL")
      if (allocated(error)) return
      stat = run(3, c_null_ptr, c_loc(v), c_loc(gaps), c_loc(laws), c_loc(res), 0, c_null_ptr)
      call expect(hcimpact_err_null, "masses NULL")
      if (allocated(error)) return
      stat = run(3, c_loc(m), c_null_ptr, c_loc(gaps), c_loc(laws), c_loc(res), 0, c_null_ptr)
      call expect(hcimpact_err_null, "velocities NULL")
      if (allocated(error)) return
      stat = run(3, c_loc(m), c_loc(v), c_null_ptr, c_loc(laws), c_loc(res), 0, c_null_ptr)
      call expect(hcimpact_err_null, "gaps NULL with n = 3")
      if (allocated(error)) return
      stat = run(3, c_loc(m), c_loc(v), c_loc(gaps), c_null_ptr, c_loc(res), 0, c_null_ptr)
      call expect(hcimpact_err_null, "laws NULL with n = 3")
      if (allocated(error)) return
      stat = run(3, c_loc(m), c_loc(v), c_loc(gaps), c_loc(laws), c_loc(res), 2, c_null_ptr)
      call expect(hcimpact_err_null, "contacts NULL with capacity 2")
      if (allocated(error)) return
      stat = run(0, c_loc(m), c_loc(v), c_loc(gaps), c_loc(laws), c_loc(res), 0, c_null_ptr)
      call expect(hcimpact_err_size, "n = 0")
      if (allocated(error)) return
      stat = run(-5, c_loc(m), c_loc(v), c_loc(gaps), c_loc(laws), c_loc(res), 0, c_null_ptr)
      call expect(hcimpact_err_size, "n = -5")
      if (allocated(error)) return
      stat = run(3, c_loc(m), c_loc(v), c_loc(gaps), c_loc(laws), c_loc(res), -1, &
         & c_loc(contacts))
      call expect(hcimpact_err_size, "capacity -1")
      if (allocated(error)) return
      samples = hcimpact_chain_samples(-1, c_loc(times), c_null_ptr, c_null_ptr, c_null_ptr)
      stat = run(3, c_loc(m), c_loc(v), c_loc(gaps), c_loc(laws), c_loc(res), 0, c_null_ptr, &
         & c_loc(samples))
      call expect(hcimpact_err_size, "samples->count -1")
      if (allocated(error)) return
      samples = hcimpact_chain_samples(2, c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr)
      stat = run(3, c_loc(m), c_loc(v), c_loc(gaps), c_loc(laws), c_loc(res), 0, c_null_ptr, &
         & c_loc(samples))
      call expect(hcimpact_err_null, "samples->times NULL")
      if (allocated(error)) return
      ! one body: gaps and laws are not read, NULL is fine
      stat = run(1, c_loc(m), c_loc(v), c_null_ptr, c_null_ptr, c_loc(res), 0, c_null_ptr)
      call check(error, stat, hcimpact_ok, "n = 1 with gaps and laws NULL")
      if (allocated(error)) return
      call check(error, .not. (same(res%time, -7.0_wp) .or. same(x(1), -7.0_wp)), &
         & "n = 1: the result and the position are written")

   contains

      integer function run(n, pm, pv, pg, pl, pr, cap, pc, ps)
         integer, intent(in) :: n, cap
         type(c_ptr), intent(in) :: pm, pv, pg, pl, pr, pc
         type(c_ptr), intent(in), optional :: ps
         type(c_ptr) :: samples_pointer
         samples_pointer = c_null_ptr
         if (present(ps)) samples_pointer = ps
         buffer = "#"
         run = hcimpact_chain_simulate(int(n, c_int), pm, pv, pg, pl, c_null_ptr, c_null_ptr, &
            & 0.0_c_double, c_null_ptr, pr, c_loc(x), c_null_ptr, int(cap, c_int), pc, &
            & samples_pointer, c_loc(buffer), int(size(buffer), c_size_t))
      end function run

      !> The status, a message, and nothing written
      subroutine expect(status, what)
         integer, intent(in) :: status
         character(len=*), intent(in) :: what
         call check(error, stat, status, what)
         if (allocated(error)) return
         call check(error, same(res%time, -7.0_wp) .and. all(same(x, -7.0_wp)), &
            & what // ": something was written")
         if (allocated(error)) return
         call check(error, buffer(1) /= "#" .and. any(buffer == c_null_char), &
            & what // ": no message")
      end subroutine expect

   end subroutine test_c_null_and_sizes

   !> Bad values: the validator's status, NaN in every real output, counts 0.
   subroutine test_c_bad_values(error)
      type(error_type), allocatable, intent(out) :: error
      type(chain_type) :: chain, bad
      type(chain_options) :: options, bad_options
      type(c_answer) :: got
      character(len=:), allocatable :: what
      real(wp) :: nan, inf

      nan = ieee_value(nan, ieee_quiet_nan)
      inf = ieee_value(inf, ieee_positive_inf)
      call test_system(2, chain, options, what)

      bad = chain
      bad%mass(2) = 0.0_wp
      call expect(bad, options, hcimpact_err_mass, "a zero mass")
      if (allocated(error)) return
      bad = chain
      bad%velocity(3) = nan
      call expect(bad, options, hcimpact_err_not_finite, "a NaN velocity")
      if (allocated(error)) return
      bad = chain
      bad%gap(1) = -1.0e-9_wp
      call expect(bad, options, hcimpact_err_domain, "a negative gap (initial overlap)")
      if (allocated(error)) return
      bad = chain
      bad%gap(2) = inf
      call expect(bad, options, hcimpact_err_not_finite, "an infinite gap")
      if (allocated(error)) return
      bad = chain
      bad%law(1)%stiffness = 0.0_wp
      call expect(bad, options, hcimpact_err_stiffness, "a zero stiffness")
      if (allocated(error)) return
      bad = chain
      bad%gravity = nan
      call expect(bad, options, hcimpact_err_not_finite, "gravity NaN")
      if (allocated(error)) return
      bad = chain
      bad%left_wall = .true.
      bad%left_law = contact_law(plate, 1.5_wp, 0.0_wp)
      bad%left_gap = -1.0_wp
      call expect(bad, options, hcimpact_err_domain, "a wall overlapping its body")
      if (allocated(error)) return
      bad_options = options
      bad_options%rtol = -1.0e-10_wp
      call expect(chain, bad_options, hcimpact_err_domain, "rtol < 0")
      if (allocated(error)) return
      bad_options = options
      bad_options%rtol = 1.0_wp
      call expect(chain, bad_options, hcimpact_err_domain, "rtol = 1")
      if (allocated(error)) return
      bad_options = options
      bad_options%t_end = nan
      call expect(chain, bad_options, hcimpact_err_not_finite, "t_end NaN")
      if (allocated(error)) return
      bad_options = options
      bad_options%method = 7
      call expect(chain, bad_options, hcimpact_err_domain, "an unknown method")
      if (allocated(error)) return
      bad_options = options
      bad_options%integrator = 3
      call expect(chain, bad_options, hcimpact_err_domain, "an unknown integrator")
      if (allocated(error)) return
      bad_options = options
      bad_options%max_events = -1
      call expect(chain, bad_options, hcimpact_err_domain, "max_events < 0")
      if (allocated(error)) return
      bad_options = options
      bad_options%sample_times = [1.0e-5_wp, 0.0_wp]
      call expect(chain, bad_options, hcimpact_err_size, "sample times that decrease")
      if (allocated(error)) return
      ! the touching balls are a cluster, which the closed forms alone refuse
      bad_options = options
      bad_options%method = method_exact
      call expect(chain, bad_options, hcimpact_err_domain, "a cluster, method exact")

   contains

      subroutine expect(system, opts, status, what)
         type(chain_type), intent(in) :: system
         type(chain_options), intent(in) :: opts
         integer, intent(in) :: status
         character(len=*), intent(in) :: what
         call call_c(system, opts, got)
         call check(error, got%stat, status, what // ": " // got%message)
         if (allocated(error)) return
         call check(error, len(got%message) > 0 .and. got%message /= "success", &
            & what // ": a message")
         if (allocated(error)) return
         call check(error, ieee_is_nan(got%result%time) .and. &
            & ieee_is_nan(got%result%energy_error) .and. got%result%n_contacts == 0 .and. &
            & got%result%contacts_recorded == 0 .and. all(ieee_is_nan(got%positions)) .and. &
            & all(ieee_is_nan(got%velocities)) .and. all(ieee_is_nan(got%sample_x)) .and. &
            & all(ieee_is_nan(got%sample_f)), what // ": outputs must be NaN, counts 0")
      end subroutine expect

   end subroutine test_c_bad_values

   ! ---------------------------------------------------------------------------------
   ! FORTRAN 77
   ! ---------------------------------------------------------------------------------

   !> Each argument in turn: its INFO = -i, NaN outputs, a message naming it.
   subroutine test_f77_bad_arguments(error)
      type(error_type), allocatable, intent(out) :: error
      external :: hcchn
      real(wp) :: xm(3), v(3), gap(2), plaw(3, 2), wall(4, 2), grav, opts(2), x(3), vf(3), &
         & res(8), cont(4, 7), nan
      integer :: iopts(4), icnt(11), icon(4, 2), maxc, ldc, info
      character(len=120) :: msg

      nan = ieee_value(nan, ieee_quiet_nan)
      call good()
      call hcchn(3, xm, v, gap, plaw, wall, grav, opts, iopts, x, vf, res, icnt, maxc, ldc, &
         & cont, icon, msg, info)
      call check(error, info, 0, "the good system: " // trim(msg))
      if (allocated(error)) return
      call check(error, icnt(1) >= 2 .and. icnt(2) == min(icnt(1), maxc), &
         & "the good system: contacts counted and recorded")
      if (allocated(error)) return

      call hcchn(0, xm, v, gap, plaw, wall, grav, opts, iopts, x, vf, res, icnt, maxc, ldc, &
         & cont, icon, msg, info)
      call expect(-1, "N = 0")
      if (allocated(error)) return
      call good(); xm(2) = -0.1_wp
      call run(-2, "XM(2) < 0")
      if (allocated(error)) return
      call good(); xm(3) = nan
      call run(-2, "XM(3) NaN")
      if (allocated(error)) return
      call good(); xm(1) = 1.0e308_wp; xm(3) = 1.0e308_wp
      call run(-2, "XM adding up beyond a quarter of the range")
      if (allocated(error)) return
      call good(); v(1) = nan
      call run(-3, "V(1) NaN")
      if (allocated(error)) return
      call good(); gap(2) = -1.0e-12_wp
      call run(-4, "GAP(2) < 0")
      if (allocated(error)) return
      call good(); plaw(2, 1) = 0.0_wp
      call run(-5, "PLAW(2, 1) = 0")
      if (allocated(error)) return
      call good(); plaw(3, 2) = -0.1_wp
      call run(-5, "PLAW(3, 2) < 0")
      if (allocated(error)) return
      call good(); wall(1, 1) = plate; wall(4, 1) = -1.0_wp
      call run(-6, "left wall with a negative gap")
      if (allocated(error)) return
      call good(); wall(1, 2) = nan
      call run(-6, "right wall stiffness NaN")
      if (allocated(error)) return
      call good(); grav = nan
      call run(-7, "GRAV NaN")
      if (allocated(error)) return
      call good(); opts(2) = 1.5_wp
      call run(-8, "RTOL = 1.5")
      if (allocated(error)) return
      call good(); opts(2) = 0.02_wp
      call run(-8, "RTOL = 0.02 (the library's domain is (0, 0.01])")
      if (allocated(error)) return
      call good(); opts(1) = nan
      call run(-8, "T_END NaN")
      if (allocated(error)) return
      call good(); iopts(1) = 3
      call run(-9, "METHOD = 3")
      if (allocated(error)) return
      call good(); iopts(4) = -2
      call run(-9, "MAXEVT < 0")
      if (allocated(error)) return
      call good(); maxc = -1
      call run(-14, "MAXC < 0")
      if (allocated(error)) return
      call good(); ldc = 1
      call run(-15, "LDC < MAXC")
      if (allocated(error)) return
      ! a computational failure: INFO is the status code
      call good(); iopts(1) = 1
      call hcchn(3, xm, v, gap, plaw, wall, grav, opts, iopts, x, vf, res, icnt, maxc, ldc, &
         & cont, icon, msg, info)
      call check(error, info, hcimpact_err_domain, "touching balls, exact only: " &
         & // trim(msg))

   contains

      !> Three touching balls
      subroutine good()
         xm = ball_mass
         v = [1.0_wp, 0.0_wp, 0.0_wp]
         gap = 0.0_wp
         plaw(:, 1) = [pair_stiffness, 1.5_wp, 0.05_wp]
         plaw(:, 2) = plaw(:, 1)
         wall = 0.0_wp
         grav = 0.0_wp
         opts = 0.0_wp
         iopts = 0
         maxc = 4
         ldc = 4
      end subroutine good

      subroutine run(expected, what)
         integer, intent(in) :: expected
         character(len=*), intent(in) :: what
         x = -7.0_wp
         call hcchn(3, xm, v, gap, plaw, wall, grav, opts, iopts, x, vf, res, icnt, maxc, &
            & ldc, cont, icon, msg, info)
         call expect(expected, what)
      end subroutine run

      subroutine expect(expected, what)
         integer, intent(in) :: expected
         character(len=*), intent(in) :: what
         call check(error, info, expected, what // ": " // trim(msg))
         if (allocated(error)) return
         call check(error, all(ieee_is_nan(res)) .and. all(icnt == 0), &
            & what // ": RES NaN, ICNT 0")
         if (allocated(error)) return
         if (expected /= -1) then
            call check(error, all(ieee_is_nan(x)) .and. all(ieee_is_nan(vf)), &
               & what // ": X and VF NaN")
            if (allocated(error)) return
         end if
         call check(error, len_trim(msg) > 0 .and. msg /= "success", what // ": MSG")
      end subroutine expect

   end subroutine test_f77_bad_arguments

end module test_cvode_chain_api
