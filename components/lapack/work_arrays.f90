! SPDX-License-Identifier: Apache-2.0
!> Memory of the calibration component: what a fit returns when it cannot allocate
!> its work arrays, and the checked copy it makes of an array argument.
!>
!> Every array whose size grows with the data (the points, the observations, the
!> Jacobian, LAPACK's workspace) is allocated with `stat=`, never as an automatic
!> array or an array-valued function result (gfortran gets both from malloc without
!> a check: out of memory they dereference NULL), and a failure is returned as
!> `out_of_memory`. Allocations of a fixed small size (the two or three parameters,
!> the series) are not checked.
module hcimpact_work_arrays
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_out_of_memory
   implicit none
   private

   public :: out_of_memory, allocate_copy

   !> Status of a fit whose work arrays cannot be allocated: the library's out of
   !> memory (HCIMPACT_ERR_OUT_OF_MEMORY, 16; the data are valid, the memory too small
   !> for them). The C interface then sets its outputs to NaN, as for any error but a
   !> NULL pointer or a wrong size.
   integer, parameter :: out_of_memory = hcimpact_err_out_of_memory

contains

   !> copy = source, allocated with stat= (out_of_memory when it fails; copy is then
   !> not allocated).
   pure subroutine allocate_copy(source, copy, stat)
      !> The values
      real(wp), intent(in) :: source(:)
      !> Their copy
      real(wp), allocatable, intent(out) :: copy(:)
      !> hcimpact_ok or out_of_memory
      integer, intent(out) :: stat
      integer :: alloc_stat

      allocate(copy(size(source)), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = out_of_memory
         return
      end if
      copy(:) = source
      stat = hcimpact_ok
   end subroutine allocate_copy

end module hcimpact_work_arrays
