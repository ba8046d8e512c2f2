! SPDX-License-Identifier: Apache-2.0
!> Sorting and selection for the calibration: the median and the number of distinct
!> values of a data set, without extra memory (the caller's array is reordered in
!> place; pass a copy to keep the original order).
!>
!> - `sort_ascending`: introsort (D. R. Musser, "Introspective sorting and selection
!>   algorithms", Software: Practice and Experience 27, 1997): quicksort with the
!>   median of three as pivot and Hoare's partition, insertion sort for short
!>   ranges, and heapsort (J. W. J. Williams, "Algorithm 232: Heapsort", CACM 7,
!>   1964) for a range once the partitions have gone 2 log2 n deep, so that no input
!>   costs more than O(n log n).
!> - `median_in_place`: introselect, the same partitions keeping only the side that
!>   holds the middle: O(n) on average, O(n log n) at worst through the same switch
!>   to heapsort.
!>
!> The data must hold no NaN (the fits reject NaN before): every comparison assumes
!> a total order.
module hcimpact_order_statistics
   use hcimpact_kinds, only : wp
   implicit none
   private

   public :: sort_ascending, median_in_place, count_distinct_in_place

   !> Ranges up to this length are finished by insertion sort
   integer, parameter :: short_range = 16

contains

   !> Sort x into ascending order, in place (introsort). x holds no NaN.
   pure subroutine sort_ascending(x)
      !> The values; sorted on return
      real(wp), intent(inout) :: x(:)
      ! pending ranges: the larger side of each partition (at most log2 n of them)
      integer :: stack_lo(64), stack_hi(64), stack_depth(64), top
      integer :: lo, hi, depth, split

      if (size(x) < 2) return
      top = 1
      stack_lo(1) = 1
      stack_hi(1) = size(x)
      stack_depth(1) = depth_limit(size(x))
      do while (top > 0)
         lo = stack_lo(top)
         hi = stack_hi(top)
         depth = stack_depth(top)
         top = top - 1
         do while (hi - lo + 1 > short_range)
            if (depth == 0) then
               call heap_sort(x(lo:hi))
               exit
            end if
            depth = depth - 1
            call partition(x, lo, hi, split)
            ! go on with the smaller side, keep the larger for later
            top = top + 1
            if (split - lo < hi - split) then
               stack_lo(top) = split + 1
               stack_hi(top) = hi
               hi = split
            else
               stack_lo(top) = lo
               stack_hi(top) = split
               lo = split + 1
            end if
            stack_depth(top) = depth
         end do
         if (hi - lo + 1 <= short_range) call insertion_sort(x(lo:hi))
      end do
   end subroutine sort_ascending

   !> The median of x: the middle value for an odd count, the mean of the two middle
   !> ones for an even count; 0 for no values. x is reordered in place (introselect).
   !> x holds no NaN.
   pure subroutine median_in_place(x, med)
      !> The values; reordered on return
      real(wp), intent(inout) :: x(:)
      !> Their median
      real(wp), intent(out) :: med
      integer :: n, k

      n = size(x)
      if (n == 0) then
         med = 0.0_wp
         return
      end if
      k = (n + 1) / 2
      call select_in_place(x, k)
      if (mod(n, 2) == 1) then
         med = x(k)
      else
         ! x(k+1:) holds the values at or above the k-th: its least is the (k+1)-th.
         ! (halves first: the sum of two values near huge() would overflow)
         med = 0.5_wp * x(k) + 0.5_wp * minval(x(k + 1:))
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

   !> Reorder x so that x(k) is the k-th smallest, x(:k-1) at most and x(k+1:) at
   !> least that (introselect).
   pure subroutine select_in_place(x, k)
      real(wp), intent(inout) :: x(:)
      integer, intent(in) :: k
      integer :: lo, hi, depth, split

      lo = 1
      hi = size(x)
      depth = depth_limit(size(x))
      do while (hi - lo + 1 > short_range)
         if (depth == 0) then
            call heap_sort(x(lo:hi))
            return
         end if
         depth = depth - 1
         call partition(x, lo, hi, split)
         if (k <= split) then
            hi = split
         else
            lo = split + 1
         end if
      end do
      call insertion_sort(x(lo:hi))
   end subroutine select_in_place

   !> 2 floor(log2 n): how deep partitions may go before heapsort takes over.
   pure integer function depth_limit(n)
      integer, intent(in) :: n
      depth_limit = 2 * (bit_size(n) - 1 - leadz(n))
   end function depth_limit

   !> Hoare's partition of x(lo:hi), hi - lo >= 2, around the median of x(lo),
   !> x(mid), x(hi) (sorted among themselves first): x(lo:split) <= pivot <=
   !> x(split+1:hi), with lo <= split < hi.
   pure subroutine partition(x, lo, hi, split)
      real(wp), intent(inout) :: x(:)
      integer, intent(in) :: lo, hi
      integer, intent(out) :: split
      real(wp) :: pivot
      integer :: i, j, mid

      mid = lo + (hi - lo) / 2
      if (x(mid) < x(lo)) call swap(x(mid), x(lo))
      if (x(hi) < x(lo)) call swap(x(hi), x(lo))
      if (x(hi) < x(mid)) call swap(x(hi), x(mid))
      pivot = x(mid)
      i = lo - 1
      j = hi + 1
      do
         ! (each scan stops at the pivot's value at the latest: no bound checks)
         do
            i = i + 1
            if (.not. x(i) < pivot) exit
         end do
         do
            j = j - 1
            if (.not. x(j) > pivot) exit
         end do
         if (i >= j) exit
         call swap(x(i), x(j))
      end do
      split = j
   end subroutine partition

   !> Sort a short array by insertion.
   pure subroutine insertion_sort(x)
      real(wp), intent(inout) :: x(:)
      real(wp) :: value
      integer :: i, j

      do i = 2, size(x)
         value = x(i)
         j = i - 1
         do while (j >= 1)
            if (.not. x(j) > value) exit
            x(j + 1) = x(j)
            j = j - 1
         end do
         x(j + 1) = value
      end do
   end subroutine insertion_sort

   !> Heapsort: a max-heap built from the bottom, then the largest moved to the end.
   pure subroutine heap_sort(x)
      real(wp), intent(inout) :: x(:)
      integer :: n, last

      n = size(x)
      do last = n / 2, 1, -1
         call sift_down(x, last, n)
      end do
      do last = n, 2, -1
         call swap(x(1), x(last))
         call sift_down(x, 1, last - 1)
      end do
   end subroutine heap_sort

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

   elemental subroutine swap(a, b)
      real(wp), intent(inout) :: a, b
      real(wp) :: t
      t = a
      a = b
      b = t
   end subroutine swap

end module hcimpact_order_statistics
