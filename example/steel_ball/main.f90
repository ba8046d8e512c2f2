! SPDX-License-Identifier: Apache-2.0
!> The seed's worked example (MODEL.md): a steel ball of 0.1 kg on a massive steel plate,
!> Hertz contact c = 1.7135e10 N/m^1.5, Hunt-Crossley damping b = 0.1 s/m, approach
!> speeds 0.5 to 5 m/s; then the same ball without damping at 1 m/s.
!>
!> Prints the table of MODEL.md (k, x_max, F_max, contact and compression time) to
!> 17 significant digits next to the values given there, with the difference in ulps,
!> and stops with an error if any value is more than 2 ulps from MODEL.md's (which are
!> given to 16-17 digits). Also shows the Hertz constant from the seed's material data
!> and the velocities of ball and plate if the plate were a 10 kg body.
program steel_ball
   use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf
   use, intrinsic :: iso_fortran_env, only : error_unit
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, status_message
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_hertz, only : hertz_constant, effective_mass, two_body_velocities
   implicit none

   ! MODEL.md: V, k, x_max, F_max, t_contact, t_compression
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
   ! MODEL.md, b = 0 at V = 1: x_max, t_contact, F_max
   real(wp), parameter :: elastic(3) = [3.5092181079293274e-5_wp, 1.0328594573451282e-4_wp, &
      & 3562.0470473908028_wp]
   character(len=*), parameter :: names(5) = [character(len=13) :: "k", "x_max (m)", &
      & "F_max (N)", "t_contact (s)", "t_compr. (s)"]
   character(len=*), parameter :: elastic_names(3) = [character(len=13) :: "x_max (m)", &
      & "t_contact (s)", "F_max (N)"]
   real(wp), parameter :: mass = 0.1_wp, stiffness = 1.7135e10_wp, exponent = 1.5_wp
   real(wp), parameter :: damping = 0.1_wp

   type(outcome_type) :: outcome
   real(wp) :: values(5), worst, ulps, plate, w1, w2
   integer :: i, j, stat

   write(*, '(a)') "Steel ball on a steel plate (MODEL.md, the seed's example):"
   write(*, '(a)') "m = 0.1 kg, c = 1.7135e10 N/m^1.5, n = 3/2, b = 0.1 s/m"
   write(*, '(a, es12.5, a)') "(Hertz constant from E = 2e11 Pa, nu = 0.25, R = 1.452 cm: c = ", &
      & hertz_constant(2.0e11_wp, 0.25_wp, 0.01452_wp, 2.0e11_wp, 0.25_wp, &
      & ieee_value(1.0_wp, ieee_positive_inf)), " N/m^1.5)"
   worst = 0.0_wp
   do i = 1, 6
      call impact(contact_type(mass=mass, stiffness=stiffness, exponent=exponent, &
         & damping=damping, velocity=table(1, i)), outcome, stat)
      if (stat /= hcimpact_ok) call fail("impact failed: " // status_message(stat))
      values = [outcome%restitution, outcome%max_compression, outcome%peak_force, &
         & outcome%contact_time, outcome%compression_time]
      write(*, '(/, a, f4.1, a)') "V = ", table(1, i), " m/s"
      write(*, '(4x, a13, 2a26, a8)') "", "hcimpact", "MODEL.md", "ulps"
      do j = 1, 5
         ulps = abs(values(j) - table(j + 1, i)) / spacing(table(j + 1, i))
         worst = max(worst, ulps)
         write(*, '(4x, a13, 2es26.17e2, f8.2)') names(j), values(j), table(j + 1, i), ulps
      end do
   end do

   call impact(contact_type(mass=mass, stiffness=stiffness, exponent=exponent, &
      & damping=0.0_wp, velocity=1.0_wp), outcome, stat)
   if (stat /= hcimpact_ok) call fail("impact failed: " // status_message(stat))
   write(*, '(/, a)') "The same ball without damping (b = 0), V = 1 m/s"
   values(1:3) = [outcome%max_compression, outcome%contact_time, outcome%peak_force]
   do j = 1, 3
      ulps = abs(values(j) - elastic(j)) / spacing(elastic(j))
      worst = max(worst, ulps)
      write(*, '(4x, a13, 2es26.17e2, f8.2)') elastic_names(j), values(j), elastic(j), ulps
   end do

   ! a plate of 10 kg that can move: effective mass and both velocities after impact
   plate = 10.0_wp
   call impact(contact_type(mass=effective_mass(mass, plate), stiffness=stiffness, &
      & exponent=exponent, damping=damping, velocity=1.0_wp), outcome, stat)
   call two_body_velocities(mass, plate, 1.0_wp, 0.0_wp, outcome%restitution, w1, w2, stat)
   write(*, '(/, a)') "A free 10 kg plate instead, ball at 1 m/s: effective mass 0.0990 kg"
   write(*, '(4x, a, f10.7, a, f10.7, a)') "ball ", w1, " m/s, plate ", w2, " m/s after impact"

   write(*, '(/, a, f5.2, a)') "Largest difference from MODEL.md: ", worst, " ulp"
   if (worst > 2.0_wp) call fail("more than 2 ulp from MODEL.md")

contains

   !> The message on standard error, exit status 1
   subroutine fail(message)
      character(len=*), intent(in) :: message
      write(error_unit, '(a)') message
      stop 1, quiet=.true.
   end subroutine fail

end program steel_ball
