! SPDX-License-Identifier: Apache-2.0
!> Stability of the closed forms and of CVODE on stiff and extreme contacts
!> (doc/cvode.md): beta = 0, 1e-300, 1e-16, 1e-8, 1e-3, 1, 10, 1e3, 1e6, 1e300;
!> n = 1, 1.5, 2, 3; (m, c, V) the seed's steel ball and the 8 corners of
!> m in [1e-9, 1e6] kg, c in [1, 1e15] N/m^n, V in [1e-9, 1e4] m/s; b = beta/V
!> (contacts where b overflows are listed as skipped).
!>
!>   bench_cvode_stability OUT.csv [--quick]
!>
!> For every contact: the closed forms (status, values, whether finite, CPU time) and
!> CVODE with BDF and with Adams at rtol = 1e-4 and 1e-8 (status, CVODE's message,
!> counters, stiffness ratio = max |eigenvalue of the Jacobian| along the trajectory
!> times the contact time, CPU time, and the relative differences from the closed
!> forms of the contact time, restitution, maximum compression and peak force).
program bench_cvode_stability
   use, intrinsic :: iso_fortran_env, only : error_unit
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate_power, cvode_bdf, &
      & cvode_adams
   use bench_cvode_common, only : cpu_seconds, n_outputs, outcome_values, fail_run
   implicit none

   real(wp), parameter :: betas(10) = [0.0_wp, 1.0e-300_wp, 1.0e-16_wp, 1.0e-8_wp, &
      & 1.0e-3_wp, 1.0_wp, 10.0_wp, 1.0e3_wp, 1.0e6_wp, 1.0e300_wp]
   real(wp), parameter :: exponents(4) = [1.0_wp, 1.5_wp, 2.0_wp, 3.0_wp]
   real(wp), parameter :: rtols(2) = [1.0e-4_wp, 1.0e-8_wp]
   real(wp) :: sizes(3, 9)
   character(len=1024) :: out_path, arg
   integer :: unit, ib, in, is, im, ir, stat_closed, stat, i
   real(wp) :: b, t_closed, t_cvode, diff(n_outputs), ref(n_outputs), got(n_outputs)
   type(contact_type) :: contact
   type(outcome_type) :: closed
   type(simulation_type) :: sim
   logical :: quick, finite_closed, finite_cvode
   character(len=:), allocatable :: message

   if (command_argument_count() < 1) then
      call fail_run("usage: bench_cvode_stability OUT.csv [--quick]")
   end if
   call get_command_argument(1, out_path)
   quick = .false.
   if (command_argument_count() >= 2) then
      call get_command_argument(2, arg)
      quick = trim(arg) == "--quick"
   end if
   sizes(:, 1) = [0.1_wp, 1.7135e10_wp, 1.0_wp]
   i = 1
   do is = 0, 7
      i = i + 1
      sizes(:, i) = [merge(1.0e-9_wp, 1.0e6_wp, btest(is, 0)), &
         & merge(1.0_wp, 1.0e15_wp, btest(is, 1)), merge(1.0e-9_wp, 1.0e4_wp, btest(is, 2))]
   end do

   open(newunit=unit, file=trim(out_path), status="replace", action="write")
   write(unit, '(a)') "n,beta,m,c,V,b,closed_status,closed_finite,closed_seconds," // &
      & "method,rtol,status,finite,seconds,steps,rhs_evals,jacobian_evals," // &
      & "error_test_failures,nonlinear_failures,stiffness_ratio," // &
      & "diff_contact,diff_restitution,diff_x_max,diff_peak_force,message"
   do in = 1, size(exponents)
      do ib = 1, size(betas)
         do is = 1, merge(1, size(sizes, 2), quick)
            b = betas(ib) / sizes(3, is)
            if (.not. ieee_is_finite(b)) then
               write(unit, '(es10.3e3, ",", es10.3e3, 4(",", es10.3e3), a)') exponents(in), &
                  & betas(ib), sizes(:, is), huge(1.0_wp), &
                  & ",-1,0,0,skipped,0,-1,0,0,0,0,0,0,0,0,0,0,0,0,b = beta/V overflows"
               cycle
            end if
            contact = contact_type(mass=sizes(1, is), stiffness=sizes(2, is), &
               & exponent=exponents(in), damping=b, velocity=sizes(3, is))
            t_closed = cpu_seconds()
            call impact(contact, closed, stat_closed)
            t_closed = cpu_seconds() - t_closed
            ref = outcome_values(closed)
            finite_closed = all(ieee_is_finite(ref))
            do im = 1, 2
               do ir = 1, size(rtols)
                  t_cvode = cpu_seconds()
                  call simulate_power(contact, sim, stat, cvode_options( &
                     & method=merge(cvode_bdf, cvode_adams, im == 1), rtol=rtols(ir)))
                  t_cvode = cpu_seconds() - t_cvode
                  got = outcome_values(sim%outcome)
                  finite_cvode = all(ieee_is_finite(got))
                  diff = -1.0_wp
                  if (stat == 0 .and. stat_closed == 0 .and. finite_closed) then
                     diff = abs(got - ref) / abs(ref)
                  end if
                  message = sim%message
                  do i = 1, len(message)
                     if (message(i:i) == ",") message(i:i) = ";"
                  end do
                  write(unit, '(es10.3e3, ",", es10.3e3, 4(",", es10.3e3), ",", i0, ",", i0, &
                     & ",", es10.3e3, ",", a, ",", es8.1e3, ",", i0, ",", i0, ",", es10.3e3, &
                     & 5(",", i0), ",", es10.3e3, 4(",", es10.3e3), ",", a)') &
                     & exponents(in), betas(ib), sizes(:, is), b, stat_closed, &
                     & merge(1, 0, finite_closed), t_closed, &
                     & trim(merge("bdf  ", "adams", im == 1)), rtols(ir), stat, &
                     & merge(1, 0, finite_cvode), t_cvode, sim%counters%steps, &
                     & sim%counters%rhs_evals, sim%counters%jacobian_evals, &
                     & sim%counters%error_test_failures, sim%counters%nonlinear_failures, &
                     & sim%stiffness_ratio, diff, message
                  if (stat == 0 .and. .not. finite_cvode) then
                     write(error_unit, '(a)') "NaN or Inf in a finished outcome!"
                  end if
               end do
            end do
         end do
      end do
      write(error_unit, '(a, f4.1, a)') "n = ", exponents(in), " done"
   end do
   close(unit)
end program bench_cvode_stability
