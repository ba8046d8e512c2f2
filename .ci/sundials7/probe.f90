! SPDX-License-Identifier: Apache-2.0
!
! Test scaffolding for .ci/sundials7-check, never part of the library.
!
! Checks what the CTest suites of hcimpact::cvode do not look at directly:
!   - the component was built for the SUNDIALS major version expected (first
!     argument, e.g. 7);
!   - a CVODE failure comes back with CVODE's own message, i.e. the error handler of
!     components/cvode/sundials.F90 was called with the impact_system as its user
!     data (SUNContext_PushErrHandler in SUNDIALS 7);
!   - a run after a failure, on a fresh context, is clean (no stale message).
! Prints one line per check and stops with a non-zero code on a failure. Whatever
! SUNDIALS writes to the terminal is the caller's to check (.ci/sundials7-check
! requires stderr to stay empty).
program sundials7_probe
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_solver
   use hcimpact_impact_model, only : contact_type
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate, sundials_major
   implicit none

   type(contact_type), parameter :: ball = contact_type(mass=0.1_wp, &
      & stiffness=1.7135e10_wp, exponent=1.5_wp, damping=0.1_wp, velocity=1.0_wp)
   type(simulation_type) :: sim
   character(len=16) :: arg
   integer :: stat, expected_major, failures

   failures = 0
   call get_command_argument(1, arg)
   read(arg, *) expected_major
   call report(sundials_major == expected_major, "built for SUNDIALS major version", &
      & trim(adjustl(arg)))

   ! rtol = 1e-20: CVode refuses at the first step (CV_TOO_MUCH_ACC) and says why
   call simulate(ball, sim, stat, cvode_options(rtol=1.0e-20_wp))
   call report(stat == hcimpact_err_solver, "rtol = 1e-20 fails", sim%message)
   call report(index(sim%message, "CV_TOO_MUCH_ACC") > 0, "the flag is named", sim%message)
   call report(index(sim%message, "(CVode") > 0 .and. index(sim%message, "accuracy") > 0, &
      & "CVODE's own message reached the error handler", sim%message)

   ! the same ball with the defaults succeeds afterwards
   call simulate(ball, sim, stat)
   call report(stat == hcimpact_ok, "the next run succeeds", sim%message)
   call report(abs(sim%outcome%restitution - 0.9374755799499_wp) < 1.0e-5_wp, &
      & "and gives the restitution of MODEL.md", "")

   if (failures > 0) error stop "sundials7 probe: failures"
   write(*, '(a)') "sundials7 probe: all checks passed"

contains

   subroutine report(ok, what, detail)
      logical, intent(in) :: ok
      character(len=*), intent(in) :: what, detail
      if (ok) then
         write(*, '(a)') "  ok    " // what // ": " // detail
      else
         write(*, '(a)') "  FAIL  " // what // ": " // detail
         failures = failures + 1
      end if
   end subroutine report

end program sundials7_probe
