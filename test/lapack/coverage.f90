! SPDX-License-Identifier: Apache-2.0
!> Counting how often the reported intervals hold the true parameter, and checking
!> the share against bounds.
module calibration_coverage
   use testdrive, only : error_type, test_failed
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: coverage_type, add_estimate, check_coverage

   !> Counts of the estimates within 1 and 2 standard errors of the truth
   type :: coverage_type
      !> Estimates counted
      integer :: total = 0
      !> Within one, and within two standard errors
      integer :: within1 = 0, within2 = 0
   end type coverage_type

contains

   !> Count one estimate with its standard error.
   subroutine add_estimate(coverage, estimate, standard_error, truth)
      !> The counts
      type(coverage_type), intent(inout) :: coverage
      !> Estimate, its standard error, and the true value
      real(wp), intent(in) :: estimate, standard_error, truth
      coverage%total = coverage%total + 1
      if (abs(estimate - truth) <= standard_error) coverage%within1 = coverage%within1 + 1
      if (abs(estimate - truth) <= 2.0_wp * standard_error) &
         & coverage%within2 = coverage%within2 + 1
   end subroutine add_estimate

   !> Fail unless low1 <= share within 1 sigma <= high1 and share within 2 sigma >= low2.
   !> (Normal errors give 68.3 % and 95.4 %; a scale estimated from few residuals gives
   !> somewhat less, Student's t: 65.3 % and 91.9 % for 8 degrees of freedom.)
   subroutine check_coverage(error, what, coverage, low1, high1, low2)
      !> Error handling
      type(error_type), allocatable, intent(out) :: error
      !> Which parameter of which fit
      character(len=*), intent(in) :: what
      !> The counts
      type(coverage_type), intent(in) :: coverage
      !> Bounds on the shares
      real(wp), intent(in) :: low1, high1, low2
      real(wp) :: share1, share2
      character(len=64) :: text
      if (coverage%total == 0) then
         call test_failed(error, what // ": no estimates counted")
         return
      end if
      share1 = real(coverage%within1, wp) / coverage%total
      share2 = real(coverage%within2, wp) / coverage%total
      if (share1 < low1 .or. share1 > high1 .or. share2 < low2) then
         write(text, '("1 sigma: ", f6.3, ", 2 sigma: ", f6.3, " of ", i0)') share1, &
            & share2, coverage%total
         call test_failed(error, what // ": coverage of the reported intervals", trim(text))
      end if
   end subroutine check_coverage

end module calibration_coverage
