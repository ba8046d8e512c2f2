! SPDX-License-Identifier: Apache-2.0
!> C interface of the library, part 3: many impacts at once, the velocity at a depth
!> (phase trajectories) and the time law x(t), x'(t), F(t).
!>
!> Thin bind(C) wrappers over hcimpact_impact_model, with the conventions of
!> hcimpact_api (NULL pointers, sizes, NaN outputs on error). The structures are those
!> of hcimpact_capi_types (`hcimpact_contact`, `hcimpact_outcome`).
module hcimpact_api_motion
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_ptr, c_associated, c_f_pointer
   use hcimpact_kinds, only : wp, nan
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_parallel, only : failure_key, key_status, no_failure
   !$ use hcimpact_parallel, only : min_parallel_cheap, min_parallel_impact
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_null, hcimpact_err_size, &
      & hcimpact_err_out_of_memory
   use hcimpact_impact_model, only : contact_type, outcome_type, impact, velocity_at_depth, &
      & time_law, time_law_samples
   use hcimpact_capi_types, only : hcimpact_contact, hcimpact_outcome, to_contact, from_outcome
   implicit none
   private

   public :: c_impact_array, c_velocity_at_depth, c_velocity_at_depth_array
   public :: c_time_law, c_time_law_samples

contains

   !> int hcimpact_impact_array(int n, const hcimpact_contact *contacts,
   !>                           hcimpact_outcome *outcomes, int *statuses)
   !>
   !> hcimpact_impact for each of n contacts. statuses (may be NULL) receives each
   !> status; the result is HCIMPACT_OK when all succeeded, otherwise the status of the
   !> first that failed (its outcome is NaN, the others are computed regardless).
   function c_impact_array(n, contacts, outcomes, statuses) result(stat) &
         & bind(C, name="hcimpact_impact_array")
      !> Number of impacts, >= 1
      integer(c_int), value, intent(in) :: n
      !> const hcimpact_contact contacts[n]
      type(c_ptr), value, intent(in) :: contacts
      !> hcimpact_outcome outcomes[n]
      type(c_ptr), value, intent(in) :: outcomes
      !> int statuses[n], or NULL
      type(c_ptr), value, intent(in) :: statuses
      !> Status
      integer(c_int) :: stat
      type(hcimpact_contact), pointer :: c_in(:)
      type(hcimpact_outcome), pointer :: c_out(:)
      integer(c_int), pointer :: c_stat(:)
      type(outcome_type) :: outcome
      integer :: i, status
      integer(int64) :: first

      if (.not. (c_associated(contacts) .and. c_associated(outcomes))) then
         stat = hcimpact_err_null
         return
      end if
      if (n < 1) then
         stat = hcimpact_err_size
         return
      end if
      call c_f_pointer(contacts, c_in, [n])
      call c_f_pointer(outcomes, c_out, [n])
      c_stat => null()
      if (c_associated(statuses)) call c_f_pointer(statuses, c_stat, [n])
      stat = hcimpact_ok
      ! The impacts in parallel (their costs differ by some factors: chunks of 4 handed
      ! out as threads come free); the status returned is that of the lowest failing index.
      first = no_failure
      !$omp parallel do if (n >= min_parallel_impact) private(outcome, status) &
      !$omp & reduction(min: first) schedule(dynamic, 4)
      do i = 1, n
         call impact(to_contact(c_in(i)), outcome, status)
         c_out(i) = from_outcome(outcome)
         if (associated(c_stat)) c_stat(i) = int(status, c_int)
         if (status /= hcimpact_ok) first = min(first, failure_key(i, status))
      end do
      !$omp end parallel do
      stat = int(key_status(first), c_int)
   end function c_impact_array

   !> int hcimpact_velocity_at_depth(const hcimpact_contact *contact, double x,
   !>                                int branch, double *velocity)
   function c_velocity_at_depth(contact, x, branch, velocity) result(stat) &
         & bind(C, name="hcimpact_velocity_at_depth")
      !> const hcimpact_contact *
      type(c_ptr), value, intent(in) :: contact
      !> Compression in m, 0 <= x <= x_max
      real(c_double), value, intent(in) :: x
      !> HCIMPACT_COMPRESSION_BRANCH (1) or HCIMPACT_RESTITUTION_BRANCH (2)
      integer(c_int), value, intent(in) :: branch
      !> double *: x' in m/s
      type(c_ptr), value, intent(in) :: velocity
      !> Status
      integer(c_int) :: stat
      type(hcimpact_contact), pointer :: c_in
      real(c_double), pointer :: v
      integer :: status
      if (.not. (c_associated(contact) .and. c_associated(velocity))) then
         stat = hcimpact_err_null
         return
      end if
      call c_f_pointer(contact, c_in)
      call c_f_pointer(velocity, v)
      call velocity_at_depth(to_contact(c_in), real(x, wp), int(branch), v, status)
      stat = int(status, c_int)
   end function c_velocity_at_depth

   !> int hcimpact_velocity_at_depth_array(const hcimpact_contact *contact, int n,
   !>                                      const double *x, int branch, double *velocity)
   !>
   !> On an error every velocity is NaN and the status is that of the first x that failed.
   function c_velocity_at_depth_array(contact, n, x, branch, velocity) result(stat) &
         & bind(C, name="hcimpact_velocity_at_depth_array")
      !> const hcimpact_contact *
      type(c_ptr), value, intent(in) :: contact
      !> Number of depths, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double x[n], compressions in m
      type(c_ptr), value, intent(in) :: x
      !> HCIMPACT_COMPRESSION_BRANCH (1) or HCIMPACT_RESTITUTION_BRANCH (2)
      integer(c_int), value, intent(in) :: branch
      !> double velocity[n], in m/s
      type(c_ptr), value, intent(in) :: velocity
      !> Status
      integer(c_int) :: stat
      type(hcimpact_contact), pointer :: c_in
      real(c_double), pointer :: xs(:), vs(:)
      type(contact_type) :: fcontact
      integer :: i, status
      integer(int64) :: first
      if (.not. (c_associated(contact) .and. c_associated(x) .and. c_associated(velocity))) then
         stat = hcimpact_err_null
         return
      end if
      if (n < 1) then
         stat = hcimpact_err_size
         return
      end if
      call c_f_pointer(contact, c_in)
      call c_f_pointer(x, xs, [n])
      call c_f_pointer(velocity, vs, [n])
      fcontact = to_contact(c_in)
      stat = hcimpact_ok
      first = no_failure
      !$omp parallel do if (n >= min_parallel_cheap) private(status) &
      !$omp & reduction(min: first) schedule(static)
      do i = 1, n
         call velocity_at_depth(fcontact, real(xs(i), wp), int(branch), vs(i), status)
         if (status /= hcimpact_ok) first = min(first, failure_key(i, status))
      end do
      !$omp end parallel do
      if (first /= no_failure) then
         vs = nan
         stat = int(key_status(first), c_int)
      end if
   end function c_velocity_at_depth_array

   !> int hcimpact_time_law(const hcimpact_contact *contact, int n, const double *t,
   !>                       double *x, double *v, double *f)
   !>
   !> HCIMPACT_ERR_OUT_OF_MEMORY when the library cannot allocate its copies of the n
   !> values; x, v, f are then NaN.
   function c_time_law(contact, n, t, x, v, f) result(stat) bind(C, name="hcimpact_time_law")
      !> const hcimpact_contact *
      type(c_ptr), value, intent(in) :: contact
      !> Number of times, >= 1
      integer(c_int), value, intent(in) :: n
      !> const double t[n], times in s from the start of contact
      type(c_ptr), value, intent(in) :: t
      !> double x[n]: compression in m
      type(c_ptr), value, intent(in) :: x
      !> double v[n]: velocity in m/s
      type(c_ptr), value, intent(in) :: v
      !> double f[n]: contact force in N
      type(c_ptr), value, intent(in) :: f
      !> Status
      integer(c_int) :: stat
      type(hcimpact_contact), pointer :: c_in
      real(c_double), pointer :: ts(:), xs(:), vs(:), fs(:)
      real(wp), allocatable :: tt(:), xx(:), vv(:), ff(:)
      integer :: status, alloc_stat
      if (.not. (c_associated(contact) .and. c_associated(t) .and. c_associated(x) &
         & .and. c_associated(v) .and. c_associated(f))) then
         stat = hcimpact_err_null
         return
      end if
      if (n < 1) then
         stat = hcimpact_err_size
         return
      end if
      call c_f_pointer(contact, c_in)
      call c_f_pointer(t, ts, [n])
      call c_f_pointer(x, xs, [n])
      call c_f_pointer(v, vs, [n])
      call c_f_pointer(f, fs, [n])
      ! copies (the outputs may be the time array itself); out of memory for them is
      ! HCIMPACT_ERR_OUT_OF_MEMORY with NaN outputs (n too large for the memory available)
      allocate(tt(n), xx(n), vv(n), ff(n), stat=alloc_stat)
      if (alloc_stat /= 0) then
         xs = nan
         vs = nan
         fs = nan
         stat = hcimpact_err_out_of_memory
         return
      end if
      tt = ts
      call time_law(to_contact(c_in), tt, xx, vv, ff, status)
      xs = xx
      vs = vv
      fs = ff
      stat = int(status, c_int)
   end function c_time_law

   !> int hcimpact_time_law_samples(const hcimpact_contact *contact, int n, double *t,
   !>                               double *x, double *v, double *f)
   !>
   !> n >= 2 equally spaced times from 0 to the contact time, both included.
   !> HCIMPACT_ERR_OUT_OF_MEMORY when the n samples cannot be allocated; every output
   !> is then NaN.
   function c_time_law_samples(contact, n, t, x, v, f) result(stat) &
         & bind(C, name="hcimpact_time_law_samples")
      !> const hcimpact_contact *
      type(c_ptr), value, intent(in) :: contact
      !> Number of samples, >= 2
      integer(c_int), value, intent(in) :: n
      !> double t[n]: times in s
      type(c_ptr), value, intent(in) :: t
      !> double x[n]: compression in m
      type(c_ptr), value, intent(in) :: x
      !> double v[n]: velocity in m/s
      type(c_ptr), value, intent(in) :: v
      !> double f[n]: contact force in N
      type(c_ptr), value, intent(in) :: f
      !> Status
      integer(c_int) :: stat
      type(hcimpact_contact), pointer :: c_in
      real(c_double), pointer :: ts(:), xs(:), vs(:), fs(:)
      real(wp), allocatable :: tt(:), xx(:), vv(:), ff(:)
      integer :: status
      if (.not. (c_associated(contact) .and. c_associated(t) .and. c_associated(x) &
         & .and. c_associated(v) .and. c_associated(f))) then
         stat = hcimpact_err_null
         return
      end if
      if (n < 2) then
         stat = hcimpact_err_size
         return
      end if
      call c_f_pointer(contact, c_in)
      call c_f_pointer(t, ts, [n])
      call c_f_pointer(x, xs, [n])
      call c_f_pointer(v, vs, [n])
      call c_f_pointer(f, fs, [n])
      call time_law_samples(to_contact(c_in), int(n), tt, xx, vv, ff, status)
      ! on an error every output is NaN, the times included (hcimpact_impact_model
      ! leaves the sampled times when the time law itself fails)
      if (allocated(tt) .and. status == hcimpact_ok) then
         ts = tt
         xs = xx
         vs = vv
         fs = ff
      else
         ts = nan
         xs = nan
         vs = nan
         fs = nan
      end if
      stat = int(status, c_int)
   end function c_time_law_samples

end module hcimpact_api_motion
