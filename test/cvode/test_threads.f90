! SPDX-License-Identifier: Apache-2.0
!> Integrations running at once in different threads (OpenMP, when the tester is built
!> with it) give the same results as one after the other: every integration keeps its
!> state in its own user data.
module test_cvode_threads
   use testdrive, only : new_unittest, unittest_type, error_type, check
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_impact_model, only : contact_type
   use hcimpact_elastic, only : power_law
   use hcimpact_cvode, only : cvode_options, simulation_type, simulate, cvode_bdf, &
      & cvode_adams
   implicit none
   private

   public :: collect_threads

   integer, parameter :: n_runs = 32

contains

   !> Collect all exported unit tests
   subroutine collect_threads(testsuite)
      !> Collection of tests
      type(unittest_type), allocatable, intent(out) :: testsuite(:)

      testsuite = [ &
         & new_unittest("parallel-equals-serial", test_parallel) &
         & ]
   end subroutine collect_threads

   !> Run i of the set: alternately the power and the law path, BDF and Adams.
   subroutine one_run(i, sim, stat)
      integer, intent(in) :: i
      type(simulation_type), intent(out) :: sim
      integer, intent(out) :: stat
      real(wp) :: v, b
      v = 0.25_wp * real(i, wp)
      b = 10.0_wp**(-3 + mod(i, 7))
      if (mod(i, 2) == 0) then
         call simulate(contact_type(mass=0.1_wp, stiffness=1.7135e10_wp, exponent=1.5_wp, &
            & damping=b, velocity=v), sim, stat, cvode_options(rtol=1.0e-9_wp, &
            & method=merge(cvode_bdf, cvode_adams, mod(i, 4) == 0), record_trajectory=.true.))
      else
         call simulate(power_law(stiffness=1.0e9_wp, exponent=2.0_wp), 0.3_wp, b, v, sim, &
            & stat, cvode_options(rtol=1.0e-9_wp))
      end if
   end subroutine one_run

   subroutine test_parallel(error)
      type(error_type), allocatable, intent(out) :: error
      type(simulation_type) :: serial(n_runs), parallel(n_runs)
      integer :: stat_serial(n_runs), stat_parallel(n_runs), i

      do i = 1, n_runs
         call one_run(i, serial(i), stat_serial(i))
      end do
      !$omp parallel do schedule(dynamic, 1)
      do i = 1, n_runs
         call one_run(i, parallel(i), stat_parallel(i))
      end do
      !$omp end parallel do
      do i = 1, n_runs
         call check(error, stat_serial(i), hcimpact_ok, serial(i)%message)
         if (allocated(error)) return
         call check(error, stat_parallel(i), hcimpact_ok, parallel(i)%message)
         if (allocated(error)) return
         call check(error, serial(i)%outcome%contact_time == parallel(i)%outcome%contact_time &
            & .and. serial(i)%outcome%restitution == parallel(i)%outcome%restitution &
            & .and. serial(i)%outcome%peak_force == parallel(i)%outcome%peak_force &
            & .and. serial(i)%counters%steps == parallel(i)%counters%steps, &
            & "a parallel run differs from the serial one")
         if (allocated(error)) return
         if (allocated(serial(i)%time)) then
            call check(error, size(serial(i)%time) == size(parallel(i)%time), &
               & "trajectory sizes differ")
            if (allocated(error)) return
            call check(error, all(serial(i)%force == parallel(i)%force), &
               & "trajectories differ")
            if (allocated(error)) return
         end if
      end do
   end subroutine test_parallel

end module test_cvode_threads
