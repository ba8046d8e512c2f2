! SPDX-License-Identifier: Apache-2.0
!> C interface of a system of bodies on a line: `hcimpact_chain_simulate` and
!> `hcimpact_chain_simulate_monitored` (include/hcimpact_cvode.h), over
!> `chain_simulate` of hcimpact_cvode_chain.
!>
!> Memory: every array belongs to the caller, inputs and outputs; the library keeps
!> nothing after the call and allocates nothing the caller must free (the work arrays
!> of the engine and of CVODE live for the call only). The contacts go to the caller's
!> array of `contact_capacity` records: the first that many (in the order they ended)
!> are written and `result->n_contacts` counts every contact, so a caller who needs
!> them all calls again with that capacity (the computation is deterministic: the
!> same input gives the same contacts). doc/c-api.md says why this and not a result
!> handle.
!>
!> The structures and their conversions are in hcimpact_cvode_chain_capi_types.
module hcimpact_cvode_chain_api
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_int64_t, c_ptr, c_size_t, &
      & c_associated, c_f_pointer, c_null_ptr
   use hcimpact_kinds, only : wp, nan
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_null, hcimpact_err_size, &
      & hcimpact_err_out_of_memory, status_message
   use hcimpact_chain_types, only : chain_type, chain_options, chain_result, no_memory_tail
   use hcimpact_cvode_chain, only : chain_simulate
   use hcimpact_cvode_api, only : copy_message
   use hcimpact_cvode_chain_capi_types, only : hcimpact_chain_law, hcimpact_chain_wall, &
      & hcimpact_chain_options, hcimpact_chain_result, hcimpact_chain_contact, &
      & hcimpact_chain_samples, hcimpact_chain_monitor, c_monitor, to_law, wall_law, &
      & to_options, from_result, from_contact, failed_result
   implicit none
   private

   public :: c_chain_simulate, c_chain_simulate_monitored

contains

   !> int hcimpact_chain_simulate(int n, const double *masses, const double *velocities,
   !>     const double *gaps, const hcimpact_chain_law *laws,
   !>     const hcimpact_chain_wall *left_wall, const hcimpact_chain_wall *right_wall,
   !>     double gravity, const hcimpact_chain_options *options,
   !>     hcimpact_chain_result *result, double *positions, double *final_velocities,
   !>     int contact_capacity, hcimpact_chain_contact *contacts,
   !>     hcimpact_chain_samples *samples, char *message, size_t message_size);
   !>
   !> Statuses: HCIMPACT_ERR_NULL (a required pointer is NULL) and HCIMPACT_ERR_SIZE
   !> (n < 1, contact_capacity < 0, samples->count < 0): nothing is written but the
   !> message. Every other error: those of chain_simulate, with NaN in the result's
   !> reals, 0 in its counts and NaN in the output arrays; so is
   !> HCIMPACT_ERR_OUT_OF_MEMORY, also for the copies of the input made here.
   function c_chain_simulate(n, masses, velocities, gaps, laws, left_wall, right_wall, &
         & gravity, options, result, positions, final_velocities, contact_capacity, &
         & contacts, samples, message, message_size) result(stat) &
         & bind(C, name="hcimpact_chain_simulate")
      !> Number of bodies, >= 1
      integer(c_int), value :: n
      !> const double[n]: masses (kg) and initial velocities (m/s)
      type(c_ptr), value :: masses, velocities
      !> const double[n - 1]: gaps (m); const hcimpact_chain_law[n - 1] (both may be
      !> NULL when n = 1)
      type(c_ptr), value :: gaps, laws
      !> const hcimpact_chain_wall *, or NULL: no wall on that side
      type(c_ptr), value :: left_wall, right_wall
      !> Constant acceleration along the line, m/s^2
      real(c_double), value :: gravity
      !> const hcimpact_chain_options *, or NULL: the defaults
      type(c_ptr), value :: options
      !> hcimpact_chain_result * (required)
      type(c_ptr), value :: result
      !> double[n] each, or NULL: final positions (m) and velocities (m/s)
      type(c_ptr), value :: positions, final_velocities
      !> Records the caller's contact array holds, >= 0
      integer(c_int), value :: contact_capacity
      !> hcimpact_chain_contact[contact_capacity] (NULL when the capacity is 0)
      type(c_ptr), value :: contacts
      !> hcimpact_chain_samples *, or NULL: no samples
      type(c_ptr), value :: samples
      !> char[message_size], or NULL
      type(c_ptr), value :: message
      !> Size of the message buffer in bytes
      integer(c_size_t), value :: message_size
      !> Status
      integer(c_int) :: stat
      character(len=:), allocatable :: text

      call simulate_from_c(n, masses, velocities, gaps, laws, left_wall, right_wall, &
         & gravity, options, result, positions, final_velocities, contact_capacity, &
         & contacts, samples, c_null_ptr, stat, text)
      call copy_message(text, message, message_size)
   end function c_chain_simulate

   !> int hcimpact_chain_simulate_monitored(... as hcimpact_chain_simulate ...,
   !>     hcimpact_chain_samples *samples, const hcimpact_chain_monitor *monitor,
   !>     char *message, size_t message_size);
   !>
   !> hcimpact_chain_simulate with the caller's monitor (NULL: none), whose poll is
   !> called every monitor_interval passes of the run's loop; nonzero stops the run
   !> with HCIMPACT_ERR_NO_CONVERGENCE. A monitor whose poll is NULL is
   !> HCIMPACT_ERR_NULL.
   function c_chain_simulate_monitored(n, masses, velocities, gaps, laws, left_wall, &
         & right_wall, gravity, options, result, positions, final_velocities, &
         & contact_capacity, contacts, samples, monitor, message, message_size) &
         & result(stat) bind(C, name="hcimpact_chain_simulate_monitored")
      integer(c_int), value :: n
      type(c_ptr), value :: masses, velocities, gaps, laws, left_wall, right_wall
      real(c_double), value :: gravity
      type(c_ptr), value :: options, result, positions, final_velocities
      integer(c_int), value :: contact_capacity
      type(c_ptr), value :: contacts, samples
      !> const hcimpact_chain_monitor *, or NULL: none
      type(c_ptr), value :: monitor
      type(c_ptr), value :: message
      integer(c_size_t), value :: message_size
      integer(c_int) :: stat
      character(len=:), allocatable :: text

      call simulate_from_c(n, masses, velocities, gaps, laws, left_wall, right_wall, &
         & gravity, options, result, positions, final_velocities, contact_capacity, &
         & contacts, samples, monitor, stat, text)
      call copy_message(text, message, message_size)
   end function c_chain_simulate_monitored

   !> The checks of the pointers and sizes, the conversions, the computation and the
   !> copies to the caller's arrays.
   subroutine simulate_from_c(n, masses, velocities, gaps, laws, left_wall, right_wall, &
         & gravity, options, result, positions, final_velocities, contact_capacity, &
         & contacts, samples, monitor, stat, text)
      integer(c_int), intent(in) :: n, contact_capacity
      type(c_ptr), intent(in) :: masses, velocities, gaps, laws, left_wall, right_wall, &
         & options, result, positions, final_velocities, contacts, samples, monitor
      real(c_double), intent(in) :: gravity
      integer(c_int), intent(out) :: stat
      character(len=:), allocatable, intent(out) :: text
      real(c_double), pointer :: c_mass(:), c_velocity(:), c_gap(:), c_times(:)
      type(hcimpact_chain_law), pointer :: c_laws(:)
      type(hcimpact_chain_wall), pointer :: c_wall
      type(hcimpact_chain_options), pointer :: c_options
      type(hcimpact_chain_result), pointer :: c_result
      type(hcimpact_chain_samples), pointer :: c_samples
      type(hcimpact_chain_monitor), pointer :: c_watch
      type(c_monitor), target :: watch
      type(chain_type) :: chain
      type(chain_options) :: opts
      type(chain_result) :: fortran_result
      integer :: status, count, i, alloc_stat
      integer(c_int64_t) :: recorded

      stat = int(hcimpact_err_null, c_int)
      if (.not. c_associated(result)) then
         text = "result is NULL"
         return
      end if
      if (.not. (c_associated(masses) .and. c_associated(velocities))) then
         text = "masses or velocities is NULL"
         return
      end if
      stat = int(hcimpact_err_size, c_int)
      if (n < 1) then
         text = "a system needs at least one body (n >= 1)"
         return
      end if
      if (contact_capacity < 0) then
         text = "contact_capacity is negative"
         return
      end if
      count = 0
      nullify(c_samples)
      if (c_associated(samples)) then
         call c_f_pointer(samples, c_samples)
         count = c_samples%count
         if (count < 0) then
            text = "samples->count is negative"
            return
         end if
      end if
      stat = int(hcimpact_err_null, c_int)
      if (n > 1 .and. .not. (c_associated(gaps) .and. c_associated(laws))) then
         text = "gaps or laws is NULL (needed for n > 1)"
         return
      end if
      if (contact_capacity > 0 .and. .not. c_associated(contacts)) then
         text = "contacts is NULL with a capacity above 0"
         return
      end if
      if (count > 0) then
         if (.not. c_associated(c_samples%times)) then
            text = "samples->times is NULL"
            return
         end if
      end if
      if (c_associated(monitor)) then
         call c_f_pointer(monitor, c_watch)
         if (.not. c_associated(c_watch%poll)) then
            text = "monitor->poll is NULL"
            return
         end if
         watch%c = c_watch
      end if

      ! the options first: their sample times are among the copies allocated below
      if (c_associated(options)) then
         call c_f_pointer(options, c_options)
         opts = to_options(c_options, int(contact_capacity))
      else
         opts%max_contacts = int(contact_capacity)
      end if
      ! the copies of the input, checked (out of memory: HCIMPACT_ERR_OUT_OF_MEMORY,
      ! every output NaN as for the engine's own failure)
      allocate(chain%mass(n), chain%velocity(n), chain%gap(n - 1), chain%law(n - 1), &
         & opts%sample_times(count), stat=alloc_stat)
      if (alloc_stat /= 0) then
         status = hcimpact_err_out_of_memory
         text = "out of memory (the copies of the input" // no_memory_tail
         call fail_outputs()
         return
      end if
      call c_f_pointer(masses, c_mass, [n])
      call c_f_pointer(velocities, c_velocity, [n])
      chain%mass(:) = real(c_mass, wp)
      chain%velocity(:) = real(c_velocity, wp)
      if (n > 1) then
         call c_f_pointer(gaps, c_gap, [n - 1])
         call c_f_pointer(laws, c_laws, [n - 1])
         chain%gap(:) = real(c_gap, wp)
         do i = 1, n - 1
            chain%law(i) = to_law(c_laws(i))
         end do
      end if
      if (c_associated(left_wall)) then
         call c_f_pointer(left_wall, c_wall)
         chain%left_wall = .true.
         chain%left_law = wall_law(c_wall)
         chain%left_gap = real(c_wall%gap, wp)
      end if
      if (c_associated(right_wall)) then
         call c_f_pointer(right_wall, c_wall)
         chain%right_wall = .true.
         chain%right_law = wall_law(c_wall)
         chain%right_gap = real(c_wall%gap, wp)
      end if
      chain%gravity = real(gravity, wp)
      if (count > 0) then
         call c_f_pointer(c_samples%times, c_times, [count])
         opts%sample_times(:) = real(c_times, wp)
      else
         deallocate(opts%sample_times)
      end if

      if (c_associated(monitor)) opts%monitor => watch
      call chain_simulate(chain, fortran_result, status, opts)
      stat = int(status, c_int)
      text = trim(fortran_result%message)
      if (len(text) == 0) text = status_message(status)

      if (status /= hcimpact_ok) then
         call fail_outputs()
         return
      end if
      call c_f_pointer(result, c_result)
      c_result = from_result(fortran_result)
      call put(positions, fortran_result%positions)
      call put(final_velocities, fortran_result%velocities)
      recorded = c_result%contacts_recorded
      if (recorded > 0) call put_contacts(contacts, fortran_result)
      if (count > 0) then
         ! (sample after sample, as the arrays are stored: no reshaped copy)
         call put_samples(c_samples%positions, fortran_result%sample_positions)
         call put_samples(c_samples%velocities, fortran_result%sample_velocities)
         call put_samples(c_samples%forces, fortran_result%sample_forces)
      end if

   contains

      !> A failed run: the status, NaN in the result's reals and every output array
      subroutine fail_outputs()
         stat = int(status, c_int)
         call c_f_pointer(result, c_result)
         c_result = failed_result()
         call fill(positions, int(n, c_int64_t), nan)
         call fill(final_velocities, int(n, c_int64_t), nan)
         if (count > 0) then
            call fill(c_samples%positions, int(n, c_int64_t) * count, nan)
            call fill(c_samples%velocities, int(n, c_int64_t) * count, nan)
            call fill(c_samples%forces, (int(n, c_int64_t) + 1) * count, nan)
         end if
      end subroutine fail_outputs
   end subroutine simulate_from_c

   !> Samples (one column a sample) into the caller's array at `where`, in the same
   !> order (nothing for NULL).
   subroutine put_samples(where, values)
      type(c_ptr), intent(in) :: where
      real(wp), intent(in) :: values(:, :)
      real(c_double), pointer :: out(:, :)
      if (.not. c_associated(where)) return
      call c_f_pointer(where, out, shape(values))
      out(:, :) = values
   end subroutine put_samples

   !> values into the caller's array at `where` (nothing for NULL).
   subroutine put(where, values)
      type(c_ptr), intent(in) :: where
      real(wp), intent(in) :: values(:)
      real(c_double), pointer :: out(:)
      if (.not. c_associated(where)) return
      call c_f_pointer(where, out, [size(values)])
      out = values
   end subroutine put

   !> `count` copies of value into the caller's array at `where` (nothing for NULL).
   subroutine fill(where, count, value)
      type(c_ptr), intent(in) :: where
      integer(c_int64_t), intent(in) :: count
      real(wp), intent(in) :: value
      real(c_double), pointer :: out(:)
      if (.not. c_associated(where)) return
      call c_f_pointer(where, out, [count])
      out = value
   end subroutine fill

   !> The recorded contacts into the caller's array.
   subroutine put_contacts(where, fortran_result)
      type(c_ptr), intent(in) :: where
      type(chain_result), intent(in) :: fortran_result
      type(hcimpact_chain_contact), pointer :: out(:)
      integer :: i
      call c_f_pointer(where, out, [size(fortran_result%contacts)])
      do i = 1, size(out)
         out(i) = from_contact(fortran_result%contacts(i))
      end do
   end subroutine put_contacts

end module hcimpact_cvode_chain_api
