! SPDX-License-Identifier: Apache-2.0
!> Sorting and what follows from it for the calibration: the median and the number of
!> distinct values of a data set, in O(n log n) time and without extra memory (the
!> caller's array is sorted in place; pass a copy to keep the original order).
!>
!> The sort is heapsort (J. W. J. Williams, "Algorithm 232: Heapsort", Communications of
!> the ACM 7, 1964; R. W. Floyd's construction of the heap, "Algorithm 245: Treesort 3",
!> the same volume): at most 2 n log2 n comparisons whatever the order of the data, no
!> recursion, no workspace. The data must hold no NaN (the fits reject NaN before).
module hcimpact_order_statistics
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: sort_ascending, median_in_place, count_distinct_in_place

contains

   !> Sort x into ascending order, in place (heapsort). x holds no NaN.
   pure subroutine sort_ascending(x)
      !> The values; sorted on return
      real(wp), intent(inout) :: x(:)
      integer :: n, last
      real(wp) :: top

      n = size(x)
      ! build a max-heap: x(i) >= x(2i), x(2i+1)
      do last = n / 2, 1, -1
         call sift_down(x, last, n)
      end do
      ! move the largest to the end, restore the heap on what is left
      do last = n, 2, -1
         top = x(1)
         x(1) = x(last)
         x(last) = top
         call sift_down(x, 1, last - 1)
      end do
   end subroutine sort_ascending

   !> Let x(root) sink in the heap x(1:n) until it is at least its children.
   pure subroutine sift_down(x, root, n)
      real(wp), intent(inout) :: x(:)
      integer, intent(in) :: root, n
      integer :: parent, child
      real(wp) :: value

      value = x(root)
      parent = root
      do
         child = 2 * parent
         if (child > n) exit
         if (child < n) then
            if (x(child + 1) > x(child)) child = child + 1
         end if
         if (.not. x(child) > value) exit
         x(parent) = x(child)
         parent = child
      end do
      x(parent) = value
   end subroutine sift_down

   !> The median of x: the middle value for an odd count, the mean of the two middle
   !> ones for an even count; 0 for no values. x is sorted in place. x holds no NaN.
   pure subroutine median_in_place(x, med)
      !> The values; sorted on return
      real(wp), intent(inout) :: x(:)
      !> Their median
      real(wp), intent(out) :: med
      integer :: n

      n = size(x)
      call sort_ascending(x)
      if (n == 0) then
         med = 0.0_wp
      else if (mod(n, 2) == 1) then
         med = x((n + 1) / 2)
      else
         ! (halves first: the sum of two values near huge() would overflow)
         med = 0.5_wp * x(n / 2) + 0.5_wp * x(n / 2 + 1)
      end if
   end subroutine median_in_place

   !> The number of distinct values in x (equal values, -0 and +0 among them, count
   !> once). x is sorted in place. x holds no NaN.
   pure subroutine count_distinct_in_place(x, count_x)
      !> The values; sorted on return
      real(wp), intent(inout) :: x(:)
      !> How many differ
      integer, intent(out) :: count_x
      integer :: i

      call sort_ascending(x)
      count_x = min(size(x), 1)
      do i = 2, size(x)
         if (x(i) /= x(i - 1)) count_x = count_x + 1
      end do
   end subroutine count_distinct_in_place

end module hcimpact_order_statistics
