! SPDX-License-Identifier: Apache-2.0
!> Shared pieces of the CVODE benchmarks: a CPU clock, the reference outcomes, errors.
module bench_cvode_common
   use, intrinsic :: iso_c_binding, only : c_int, c_long
   use, intrinsic :: iso_fortran_env, only : int64, error_unit
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type
   implicit none
   private

   public :: cpu_seconds, reference_case, read_reference, rel_error, ulp_error, n_outputs
   public :: output_names, outcome_values, median, fail_run

   !> Outputs compared: contact time, restitution, maximum compression, peak force
   integer, parameter :: n_outputs = 4
   character(len=*), parameter :: output_names(n_outputs) = [character(len=11) :: &
      & "contact", "restitution", "x_max", "peak_force"]

   !> One contact with its reference outcome (hi + lo)
   type :: reference_case
      type(contact_type) :: contact
      real(wp) :: hi(n_outputs) = 0.0_wp, lo(n_outputs) = 0.0_wp
   end type reference_case

   type, bind(C) :: timespec
      integer(c_long) :: tv_sec, tv_nsec
   end type timespec

   interface
      function clock_gettime(clock_id, tp) result(stat) bind(C, name="clock_gettime")
         import :: c_int, timespec
         integer(c_int), value :: clock_id
         type(timespec), intent(out) :: tp
         integer(c_int) :: stat
      end function clock_gettime
   end interface

   !> CLOCK_THREAD_CPUTIME_ID (Linux): time spent descheduled does not count
   integer(c_int), parameter :: thread_cputime = 3_c_int

contains

   !> End a failed run: the message on standard error, exit status 1 (quietly: no
   !> backtrace after the message)
   subroutine fail_run(message)
      character(len=*), intent(in) :: message
      write(error_unit, '(a)') message
      stop 1, quiet=.true.
   end subroutine fail_run

   !> CPU time of the calling thread, in seconds.
   function cpu_seconds() result(t)
      real(wp) :: t
      type(timespec) :: ts
      if (clock_gettime(thread_cputime, ts) /= 0) then
         t = 0.0_wp
      else
         t = real(ts%tv_sec, wp) + 1.0e-9_wp * real(ts%tv_nsec, wp)
      end if
   end function cpu_seconds

   !> The outputs compared, in the order of output_names.
   pure function outcome_values(o) result(v)
      type(outcome_type), intent(in) :: o
      real(wp) :: v(n_outputs)
      v = [o%contact_time, o%restitution, o%max_compression, o%peak_force]
   end function outcome_values

   !> Read a reference file in the format of test/reference/impact.csv.
   subroutine read_reference(path, cases)
      character(len=*), intent(in) :: path
      type(reference_case), allocatable, intent(out) :: cases(:)
      ! columns: m,c,n,V,b, x_max, peak_force, compression_at_peak, time_at_peak,
      ! compression_time, contact_time, restitution (each hi,lo)
      real(wp) :: row(19)
      character(len=2048) :: line
      integer :: unit, ios, count
      type(reference_case) :: one
      logical :: header_seen

      allocate(cases(0))
      open(newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) call fail_run("cannot open " // path)
      header_seen = .false.
      count = 0
      do
         read(unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (len_trim(line) == 0 .or. line(1:1) == "#") cycle
         if (.not. header_seen) then
            header_seen = .true.
            cycle
         end if
         read(line, *) row
         one%contact = contact_type(mass=row(1), stiffness=row(2), exponent=row(3), &
            & velocity=row(4), damping=row(5))
         one%hi = [row(16), row(18), row(6), row(8)]
         one%lo = [row(17), row(19), row(7), row(9)]
         cases = [cases, one]
         count = count + 1
      end do
      close(unit)
   end subroutine read_reference

   !> |y - (hi + lo)| / |hi|
   elemental function rel_error(y, hi, lo) result(e)
      real(wp), intent(in) :: y, hi, lo
      real(wp) :: e
      e = abs((y - hi) - lo) / abs(hi)
   end function rel_error

   !> |y - (hi + lo)| in units of spacing(hi)
   elemental function ulp_error(y, hi, lo) result(e)
      real(wp), intent(in) :: y, hi, lo
      real(wp) :: e
      e = abs((y - hi) - lo) / spacing(abs(hi))
   end function ulp_error

   !> Median of a small array
   pure function median(x) result(m)
      real(wp), intent(in) :: x(:)
      real(wp) :: m, a(size(x)), t
      integer :: i, j, n
      a = x
      n = size(a)
      do i = 2, n
         t = a(i)
         j = i - 1
         do while (j >= 1)
            if (a(j) <= t) exit
            a(j + 1) = a(j)
            j = j - 1
         end do
         a(j + 1) = t
      end do
      if (mod(n, 2) == 1) then
         m = a((n + 1) / 2)
      else
         m = 0.5_wp * (a(n / 2) + a(n / 2 + 1))
      end if
   end function median

end module bench_cvode_common
