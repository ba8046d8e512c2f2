! SPDX-License-Identifier: Apache-2.0
!> Consumer of an installed hcimpact, from Fortran: `use hcimpact` must find the
!> installed .mod files and the program must link. Exit status 1 on a wrong value.
program consumer
   use hcimpact, only : wp, hcimpact_version_string, lambert_w0, lambert_wm1
   implicit none

   !> W0(1), the omega constant, and W-1(-0.1) (mpmath, 30 digits)
   real(wp), parameter :: omega = 0.56714329040978387_wp, wm1_ref = -3.5771520639572971_wp
   real(wp) :: w0, wm1

   w0 = lambert_w0(1.0_wp)
   wm1 = lambert_wm1(-0.1_wp)
   write(*, '(a, a)') "hcimpact ", hcimpact_version_string
   write(*, '(a, es25.17)') "W0(1)     = ", w0
   write(*, '(a, es25.17)') "W-1(-0.1) = ", wm1
   if (.not.(abs(w0 - omega) <= 1.0e-14_wp) .or. .not.(abs(wm1 - wm1_ref) <= 1.0e-13_wp)) then
      write(*, '(a)') "FAIL: wrong value"
      error stop 1
   end if
   write(*, '(a)') "ok"
end program consumer
