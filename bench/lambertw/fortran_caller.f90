! SPDX-License-Identifier: Apache-2.0
!> Fortran callers of hcimpact's Lambert W for bench_lambertw_speed (the column
!> "Fortran"): a loop in Fortran calling the module procedures, as a Fortran
!> program using the library does (through the shared library when the benchmark
!> links it). One module per function: each renames its function to `f` and
!> includes the same pass (fortran_pass.inc) under its own C name.
module bench_fortran_w0
   use, intrinsic :: iso_c_binding, only : c_double, c_int32_t, c_int64_t
   use hcimpact_lambertw, only : f => lambert_w0
   implicit none
   private
   public :: pass
   character(len=*), parameter :: c_name = "hcimpact_bench_fortran_w0"
contains
   include "fortran_pass.inc"
end module bench_fortran_w0

module bench_fortran_wm1
   use, intrinsic :: iso_c_binding, only : c_double, c_int32_t, c_int64_t
   use hcimpact_lambertw, only : f => lambert_wm1
   implicit none
   private
   public :: pass
   character(len=*), parameter :: c_name = "hcimpact_bench_fortran_wm1"
contains
   include "fortran_pass.inc"
end module bench_fortran_wm1

module bench_fortran_w0p1
   use, intrinsic :: iso_c_binding, only : c_double, c_int32_t, c_int64_t
   use hcimpact_lambertw, only : f => lambert_w0p1
   implicit none
   private
   public :: pass
   character(len=*), parameter :: c_name = "hcimpact_bench_fortran_w0p1"
contains
   include "fortran_pass.inc"
end module bench_fortran_w0p1

module bench_fortran_wm1p1
   use, intrinsic :: iso_c_binding, only : c_double, c_int32_t, c_int64_t
   use hcimpact_lambertw, only : f => lambert_wm1p1
   implicit none
   private
   public :: pass
   character(len=*), parameter :: c_name = "hcimpact_bench_fortran_wm1p1"
contains
   include "fortran_pass.inc"
end module bench_fortran_wm1p1
