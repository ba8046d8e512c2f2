! SPDX-License-Identifier: Apache-2.0
!> What CVODE's error handler said, for every integrator of the component: the last
!> message and its code (hcimpact_cvode_sundials' handler fills it in), and its form
!> in the integrators' own messages.
module hcimpact_cvode_report
   implicit none
   private

   public :: solver_report, report_detail, report_detail_length

   !> The last message of CVODE's error handler and its code
   type :: solver_report
      character(len=:), allocatable :: message
      integer :: code = 0
   end type solver_report

contains

   !> Length of report_detail(report).
   pure function report_detail_length(report) result(length)
      type(solver_report), intent(in) :: report
      integer :: length
      length = 0
      if (allocated(report%message)) then
         if (len(report%message) > 0) length = len(report%message) + 3
      end if
   end function report_detail_length

   !> The last message, if any, as " (<message>)"; empty without one. (A result of a
   !> length given by a specification function: a deferred-length result would keep
   !> its length in a hidden static variable, shared by threads.)
   pure function report_detail(report) result(text)
      type(solver_report), intent(in) :: report
      character(len=report_detail_length(report)) :: text
      if (len(text) > 0) text = " (" // report%message // ")"
   end function report_detail

end module hcimpact_cvode_report
