! SPDX-License-Identifier: Apache-2.0
!> The array forms of the C and FORTRAN 77 interfaces share their elements among
!> threads when the library is built with OpenMP (CMake's HCIMPACT_WITH_OPENMP): as
!> many as OpenMP gives a parallel region (OMP_NUM_THREADS; 1 inside a parallel
!> region of the caller's unless nesting is on). Below the sizes here, starting the
!> threads would cost more than it saves. Each element is computed alone, by the code
!> of the scalar form, so a parallel run gives the serial run's results bit for bit,
!> and the status of an array call is that of its lowest failing index, as serially.
module hcimpact_parallel
   use, intrinsic :: iso_fortran_env, only : int64
   !$ use omp_lib, only : omp_get_max_threads
   implicit none
   private

   public :: min_parallel_cheap, min_parallel_element, min_parallel_impact
   public :: array_threads, failure_key, key_status, no_failure

   !> Functions of a few nanoseconds an element (Lambert W, restitution, speed at a depth)
   integer, parameter :: min_parallel_cheap = 32768
   !> The contact-force element (tens of nanoseconds)
   integer, parameter :: min_parallel_element = 4096
   !> One impact or more per element (microseconds)
   integer, parameter :: min_parallel_impact = 16
   !> The failure key of no failure (larger than every other)
   integer(int64), parameter :: no_failure = huge(0_int64)

contains

   !> The number of threads an array form above its size threshold uses when called
   !> here and now: 1 in a build without OpenMP.
   function array_threads() result(n)
      !> Number of threads
      integer :: n
      n = 1
      !$ n = omp_get_max_threads()
   end function array_threads

   !> The key of a failure in a parallel loop: index and status in one integer, so
   !> that a min reduction over the keys (no lock) keeps the lowest failing index with
   !> its status. no_failure is the key of none.
   elemental function failure_key(i, status) result(key)
      !> Index of the element that failed and its status (0 .. 255)
      integer, intent(in) :: i, status
      !> The key
      integer(int64) :: key
      key = int(i, int64) * 256_int64 + int(status, int64)
   end function failure_key

   !> The status of the lowest failing index from the reduced key (hcimpact_ok for
   !> no_failure).
   elemental function key_status(key) result(status)
      !> The reduced key
      integer(int64), intent(in) :: key
      !> Status
      integer :: status
      status = 0
      if (key /= no_failure) status = int(modulo(key, 256_int64))
   end function key_status

end module hcimpact_parallel
