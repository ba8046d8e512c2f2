! SPDX-License-Identifier: Apache-2.0
!> bench_lambertw_random: the largest error in ulps of hcimpact's Lambert W (through the C
!> API) on millions of random doubles over whole ranges, against references computed in
!> quadruple precision (real128) by methods of their own:
!> - W(z) for z <= -0.3 and the 1 + W forms from t: 1 + W = -u with u - ln(1 + u) = t
!>   (t = -1 - ln(-z) for W), solved by Newton's method from the double result;
!> - W0 elsewhere: w = z exp(-w) by Newton's method; W-1 for z > -0.3: w + ln(-w) = ln(-z);
!>   1 + W0 for t > 30: 1 + W0(-exp(-1 - t)).
!> The references carry about 30 significant digits more than a double, so an error is
!> good to far below 0.001 ulp. Not a test (it takes minutes): the unit tests check the
!> mpmath references of test/reference/lambertw.csv; this checks many more points.
!>
!> Usage: bench_lambertw_random [points per family, default 1000000] [seed]
!> Output: one line per family (function, range): points, largest error, its argument.
program bench_lambertw_random
   use, intrinsic :: iso_fortran_env, only : dp => real64, qp => real128, int64, output_unit
   use, intrinsic :: iso_c_binding, only : c_double
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   implicit none

   interface
      function c_w0(z) result(w) bind(C, name="hcimpact_lambert_w0")
         import :: c_double
         real(c_double), value :: z
         real(c_double) :: w
      end function c_w0
      function c_wm1(z) result(w) bind(C, name="hcimpact_lambert_wm1")
         import :: c_double
         real(c_double), value :: z
         real(c_double) :: w
      end function c_wm1
      function c_w0p1(t) result(v) bind(C, name="hcimpact_lambert_w0p1")
         import :: c_double
         real(c_double), value :: t
         real(c_double) :: v
      end function c_w0p1
      function c_wm1p1(t) result(v) bind(C, name="hcimpact_lambert_wm1p1")
         import :: c_double
         real(c_double), value :: t
         real(c_double) :: v
      end function c_wm1p1
   end interface

   !> The double nearest -1/e and 1/e as a quadruple
   real(dp), parameter :: z_branch = -0.36787944117144233_dp
   real(qp), parameter :: inv_e_q = 0.367879441171442321595523770161460867445811131_qp
   integer(int64) :: state, points
   character(len=32) :: arg
   integer :: stat

   points = 1000000_int64
   state = int(z'6863696D70616374', int64)
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg)
      read(arg, *, iostat=stat) points
      if (stat /= 0 .or. points < 1) stop "bench_lambertw_random: bad number of points"
   end if
   if (command_argument_count() >= 2) then
      call get_command_argument(2, arg)
      read(arg, *, iostat=stat) state
      if (stat /= 0) stop "bench_lambertw_random: bad seed"
   end if

   write(output_unit, '(a)') "| function | inputs | points | max ulp | at |"
   write(output_unit, '(a)') "|---|---|---:|---:|---:|"
   call family("W0", "z = -1/e + d, d log-uniform in [2^-54, 0.12]", 1)
   call family("W0", "z uniform in (-1/e, 0)", 2)
   call family("W0", "z = -s, s log-uniform in [1e-300, 0.25]", 3)
   call family("W0", "z log-uniform in [1e-300, 1e300]", 4)
   call family("W0", "z log-uniform in [1e-12, 2e3]", 5)
   call family("W-1", "z = -1/e + d, d log-uniform in [2^-54, 0.12]", 6)
   call family("W-1", "z uniform in (-1/e, 0)", 7)
   call family("W-1", "z = -s, s log-uniform in [4.9e-324, 0.3]", 8)
   call family("1+W0", "t log-uniform in [1e-300, 1e3]", 9)
   call family("1+W0", "t log-uniform in [1e-18, 1e2]", 10)
   call family("1+W-1", "t log-uniform in [1e-300, 1e3]", 11)
   call family("1+W-1", "t log-uniform in [1e-18, 1e2]", 12)

contains

   !> One family: `points` random arguments, the largest error and where it occurs.
   subroutine family(name, inputs, kind)
      character(len=*), intent(in) :: name, inputs
      integer, intent(in) :: kind
      integer(int64) :: i
      real(dp) :: x, y, err, worst, worst_x
      real(qp) :: ref

      worst = 0.0_dp
      worst_x = 0.0_dp
      do i = 1, points
         select case (kind)
         case (1, 6)
            x = z_branch + log_uniform(2.0_dp**(-54), 0.12_dp)
         case (2, 7)
            x = z_branch * (1.0_dp - uniform())
            if (x <= z_branch .or. x >= 0.0_dp) cycle
         case (3)
            x = -log_uniform(1.0e-300_dp, 0.25_dp)
         case (4)
            x = log_uniform(1.0e-300_dp, 1.0e300_dp)
         case (5)
            x = log_uniform(1.0e-12_dp, 2.0e3_dp)
         case (8)
            x = -log_uniform(scale(1.0_dp, -1074), 0.3_dp)
            if (x >= 0.0_dp) cycle
         case (9, 11)
            x = log_uniform(1.0e-300_dp, 1.0e3_dp)
         case default
            x = log_uniform(1.0e-18_dp, 1.0e2_dp)
         end select
         select case (kind)
         case (1:5)
            y = c_w0(x)
            ref = ref_w0(x, y)
         case (6:8)
            y = c_wm1(x)
            ref = ref_wm1(x, y)
         case (9, 10)
            y = c_w0p1(x)
            ref = ref_p1(real(x, qp), 0, y)
         case default
            y = c_wm1p1(x)
            ref = ref_p1(real(x, qp), -1, y)
         end select
         err = ulp_error(y, ref)
         if (err > worst) then
            worst = err
            worst_x = x
         end if
      end do
      write(output_unit, '("| ", a, " | ", a, " | ", i0, " | ", f6.4, " | ", es25.16e3, " |")') &
         & name, inputs, points, worst, worst_x
      flush(output_unit)
   end subroutine family

   !> |y - ref| in ulps of ref (the spacing of the doubles at the exact value: halved just
   !> below a power of two); NaN counts as a huge error.
   function ulp_error(y, ref) result(err)
      real(dp), intent(in) :: y
      real(qp), intent(in) :: ref
      real(dp) :: err, hi
      real(qp) :: u
      if (ieee_is_nan(y)) then
         err = huge(1.0_dp)
         return
      end if
      hi = real(ref, dp)
      u = real(spacing(hi), qp)
      if (abs(fraction(hi)) == 0.5_dp .and. abs(ref) < abs(real(hi, qp))) u = u / 2
      err = real(abs(real(y, qp) - ref) / u, dp)
   end function ulp_error

   !> W0(z) in quadruple precision near the double result w
   function ref_w0(z, w) result(r)
      real(dp), intent(in) :: z, w
      real(qp) :: r, zq, step
      integer :: k
      if (z <= -0.3_dp) then
         r = ref_p1(-1.0_qp - log(-real(z, qp)), 0, 1.0_dp + w) - 1.0_qp
         return
      end if
      ! w = z exp(-w): Newton on f(w) = w - z exp(-w), f' = 1 + z exp(-w) = 1 + w
      zq = real(z, qp)
      r = real(w, qp)
      if (z == 0.0_dp) return
      do k = 1, 60
         step = (r - zq * exp(-r)) / (1.0_qp + zq * exp(-r))
         r = r - step
         if (abs(step) <= 1.0e-32_qp * abs(r)) exit
      end do
   end function ref_w0

   !> W-1(z) in quadruple precision near the double result w
   function ref_wm1(z, w) result(r)
      real(dp), intent(in) :: z, w
      real(qp) :: r, lz, step
      integer :: k
      if (z <= -0.3_dp) then
         r = ref_p1(-1.0_qp - log(-real(z, qp)), -1, 1.0_dp + w) - 1.0_qp
         return
      end if
      ! w + ln(-w) = ln(-z), w < -1: Newton, f' = 1 + 1/w
      lz = log(-real(z, qp))
      r = real(w, qp)
      do k = 1, 60
         step = (r + log(-r) - lz) / (1.0_qp + 1.0_qp / r)
         r = r - step
         if (abs(step) <= 1.0e-32_qp * abs(r)) exit
      end do
   end function ref_wm1

   !> 1 + W(-exp(-1 - t)) for the branch (0 or -1) in quadruple precision near the double
   !> result v: -u with h(u) = u - ln(1 + u) = t (W0: -1 < u <= 0, W-1: u >= 0); for W0
   !> at t > 30, 1 + W0(z) with z = -exp(-1 - t), where 1 + u would underflow
   recursive function ref_p1(t, branch, v) result(r)
      real(qp), intent(in) :: t
      integer, intent(in) :: branch
      real(dp), intent(in) :: v
      real(qp) :: r, u, zq, w, step
      integer :: k
      if (t <= 0.0_qp) then
         r = 0.0_qp
         return
      end if
      if (branch == 0 .and. t > 30.0_qp) then
         zq = -exp(-1.0_qp - t)
         w = zq
         do k = 1, 60
            step = (w - zq * exp(-w)) / (1.0_qp + zq * exp(-w))
            w = w - step
            if (abs(step) <= 1.0e-32_qp * abs(w)) exit
         end do
         r = 1.0_qp + w
         return
      end if
      u = -real(v, qp)
      if (branch == 0) then
         u = max(min(u, 0.0_qp), -1.0_qp + 1.0e-30_qp)
      else
         u = max(u, 0.0_qp)
      end if
      if (u == 0.0_qp) u = merge(-1.0_qp, 1.0_qp, branch == 0) * sqrt(2.0_qp * t)
      do k = 1, 80
         step = (h(u) - t) * (1.0_qp + u) / u
         u = u - step
         if (abs(step) <= 1.0e-32_qp * abs(u)) exit
      end do
      r = -u
   end function ref_p1

   !> u - ln(1 + u), by its series where it cancels
   function h(u) result(r)
      real(qp), intent(in) :: u
      real(qp) :: r, term
      integer :: k
      if (abs(u) < 0.125_qp) then
         r = 0.0_qp
         term = u
         do k = 2, 70
            term = -term * u
            r = r - term / k
         end do
         ! r = u**2/2 - u**3/3 + ... = sum_{k>=2} (-1)**k u**k / k
      else
         r = u - log(1.0_qp + u)
      end if
   end function h

   !> splitmix64
   function next_bits() result(z)
      integer(int64) :: z
      state = state + int(z'9E3779B97F4A7C15', int64)
      z = state
      z = ieor(z, shiftr(z, 30)) * int(z'BF58476D1CE4E5B9', int64)
      z = ieor(z, shiftr(z, 27)) * int(z'94D049BB133111EB', int64)
      z = ieor(z, shiftr(z, 31))
   end function next_bits

   !> Uniform in [0, 1)
   function uniform() result(r)
      real(dp) :: r
      r = real(shiftr(next_bits(), 11), dp) * 2.0_dp**(-53)
   end function uniform

   !> Log-uniform in [lo, hi]
   function log_uniform(lo, hi) result(r)
      real(dp), intent(in) :: lo, hi
      real(dp) :: r
      r = min(hi, max(lo, exp(log(lo) + (log(hi) - log(lo)) * uniform())))
   end function log_uniform

end program bench_lambertw_random
