! SPDX-License-Identifier: Apache-2.0
!> Contact time by the closed forms' quadratures (modified Clenshaw-Curtis, with
!> tanh-sinh where that does not converge): integrand evaluations, time per call and
!> the error reached, against the number of significant digits requested (issue #3:
!> "report evaluations and time per call against the number of significant digits";
!> issue #4: the time per call against CVODE's).
!>
!> The contacts are the rows of test/reference/impact.csv (mpmath references at the
!> exact double inputs), split into beta = bV <= 100 and beta > 100. For each requested
!> tolerance rtol = 10**-d, d = 3, 6, 9, 12 and full precision, it reports over the rows:
!> the largest and median number of evaluations of the compression + restitution
!> quadratures, the median time of one `impact` call (each timed as the median of 5
!> batches of `batch` calls: one call is below the clock's resolution), and the largest
!> error of the contact time in ulps.
!>
!> Usage: bench_contact_time [path/to/impact.csv]     (default test/reference/impact.csv)
program bench_contact_time
   use, intrinsic :: iso_fortran_env, only : int64, output_unit, error_unit
   use hcimpact, only : wp, contact_type, outcome_type, impact
   implicit none
   integer, parameter :: max_rows = 1000, ntol = 5
   real(wp) :: m(max_rows), c(max_rows), n(max_rows), v(max_rows), b(max_rows)
   real(wp) :: tc_hi(max_rows), tc_lo(max_rows)
   real(wp) :: tols(ntol), err, worst, t_call
   integer :: nrows, i, it, group, stat, ev, cnt
   integer, allocatable :: evals(:)
   real(wp), allocatable :: times(:)
   character(len=512) :: path, line
   character(len=*), parameter :: group_name(2) = [character(len=12) :: "beta <= 100", "beta > 100"]
   type(contact_type) :: contact
   type(outcome_type) :: outcome

   path = "test/reference/impact.csv"
   if (command_argument_count() > 0) call get_command_argument(1, path)
   call read_rows()
   tols = [1.0e-3_wp, 1.0e-6_wp, 1.0e-9_wp, 1.0e-12_wp, epsilon(1.0_wp)]

   write(output_unit, '(a)') "| beta | rtol | rows | evaluations max | evaluations median |" // &
      & " time per impact (us, median) | contact time error max (ulp) |"
   write(output_unit, '(a)') "|---|---:|---:|---:|---:|---:|---:|"
   do group = 1, 2
      do it = 1, ntol
         allocate(evals(0), times(0))
         worst = 0.0_wp
         cnt = 0
         do i = 1, nrows
            if ((group == 1) .neqv. (b(i) * v(i) <= 100.0_wp)) cycle
            contact%mass = m(i)
            contact%stiffness = c(i)
            contact%exponent = n(i)
            contact%damping = b(i)
            contact%velocity = v(i)
            t_call = time_impact(contact, tols(it), outcome, stat)
            if (stat /= 0) then
               write(error_unit, '(a, i0, a, i0)') "row ", i, ": status ", stat
               cycle
            end if
            ev = outcome%evaluations(1) + outcome%evaluations(2)
            evals = [evals, ev]
            times = [times, t_call]
            err = abs((outcome%contact_time - tc_hi(i)) - tc_lo(i)) / spacing(tc_hi(i))
            worst = max(worst, err)
            cnt = cnt + 1
         end do
         write(output_unit, '("| ", a, " | ", es8.1, " | ", i4, " | ", i5, " | ", i5, " | ", &
            & f8.1, " | ", es9.2, " |")') trim(group_name(group)), tols(it), cnt, &
            & maxval(evals), int(median(real(evals, wp))), median(times), worst
         deallocate(evals, times)
      end do
   end do

contains

   !> Median time in microseconds of one impact call (5 batches of `batch` calls), and
   !> its outcome
   function time_impact(contact, rtol, outcome, stat) result(us)
      type(contact_type), intent(in) :: contact
      real(wp), intent(in) :: rtol
      type(outcome_type), intent(out) :: outcome
      integer, intent(out) :: stat
      integer, parameter :: batch = 50
      real(wp) :: us, t(5)
      integer(int64) :: t0, t1, rate
      integer :: r, j
      do r = 1, size(t)
         call system_clock(t0, rate)
         do j = 1, batch
            call impact(contact, outcome, stat, rtol=rtol)
         end do
         call system_clock(t1)
         t(r) = 1.0e6_wp * real(t1 - t0, wp) / real(rate, wp) / batch
      end do
      us = median(t)
   end function time_impact

   subroutine read_rows()
      integer :: unit, ios
      real(wp) :: vals(19)
      open(newunit=unit, file=trim(path), status="old", action="read", iostat=ios)
      if (ios /= 0) then
         write(error_unit, '(a)') "cannot open " // trim(path)
         stop 1, quiet=.true.
      end if
      nrows = 0
      do
         read(unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:1) == "m") cycle
         read(line, *, iostat=ios) vals
         if (ios /= 0 .or. nrows == max_rows) cycle
         nrows = nrows + 1
         m(nrows) = vals(1); c(nrows) = vals(2); n(nrows) = vals(3)
         v(nrows) = vals(4); b(nrows) = vals(5)
         tc_hi(nrows) = vals(16); tc_lo(nrows) = vals(17)
      end do
      close(unit)
   end subroutine read_rows

   pure function median(x) result(med)
      real(wp), intent(in) :: x(:)
      real(wp) :: med, y(size(x)), t
      integer :: i, j
      y = x
      do i = 2, size(y)
         t = y(i)
         j = i - 1
         do while (j >= 1)
            if (y(j) <= t) exit
            y(j + 1) = y(j)
            j = j - 1
         end do
         y(j + 1) = t
      end do
      med = 0.0_wp
      if (size(y) == 0) return
      if (mod(size(y), 2) == 1) then
         med = y((size(y) + 1) / 2)
      else
         med = 0.5_wp * (y(size(y) / 2) + y(size(y) / 2 + 1))
      end if
   end function median

end program bench_contact_time
