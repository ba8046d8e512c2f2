! SPDX-License-Identifier: Apache-2.0
!> Entry points for FORTRAN 77 programs: external subroutines (no module, no USE)
!> that a fixed-form program CALLs with implicit interfaces, every argument by
!> reference, DOUBLE PRECISION reals and default INTEGERs.
!>
!> The status is an INFO argument in the manner of LAPACK:
!>   INFO = 0   success;
!>   INFO = -i  the i-th argument is invalid (NaN, infinite, or outside its domain);
!>              nothing is computed and the real outputs are NaN;
!>   INFO > 0   a computational failure; the value is the library's status code
!>              (8: a result leaves the double range, 9: no convergence), whose text
!>              HCMSG returns. The array routines HCIMPA use INFO > 0 for the index
!>              of the first element that failed.
!> Array sizes follow LAPACK too: N < 0 is an invalid argument, N = 0 returns at once.
!>
!> A FORTRAN 77 program cannot write +Inf, so the routines that accept an infinite
!> radius or mass in the Fortran and C interfaces take 0 instead (see HCHERZ).
!> Reference of names, arguments, units and INFO codes: doc/fortran77.md. Each
!> routine only checks and converts; the physics is in the modules it uses.
!>
!> Names: HC + at most four letters, so that they fit the six characters of strict
!> FORTRAN 77 (gfortran appends an underscore: the C symbols are hcres_ etc.). None
!> equals a module name of the library.

!> HCVERS(MAJOR, MINOR, PATCH): version of the library (three INTEGERs).
subroutine hcvers(major, minor, patch)
   use hcimpact_version_info, only : get_hcimpact_version
   implicit none
   !> Major version number
   integer, intent(out) :: major
   !> Minor version number
   integer, intent(out) :: minor
   !> Patch version number
   integer, intent(out) :: patch
   call get_hcimpact_version(major, minor, patch)
end subroutine hcvers

!> HCMSG(ISTAT, MSG): text of a library status code (an INFO > 0 of HCIMP, or an
!> ISTAT of HCIMPA), blank-padded or truncated to LEN(MSG).
subroutine hcmsg(istat, msg)
   use hcimpact_status, only : status_message
   implicit none
   !> Status code
   integer, intent(in) :: istat
   !> CHARACTER*(*) message
   character(len=*), intent(out) :: msg
   msg = status_message(istat)
end subroutine hcmsg

!> HCW0(Z, W, INFO): principal branch W0(Z) of Lambert W, Z >= -1/e.
subroutine hcw0(z, w, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_lambertw, only : lambert_w0
   implicit none
   !> Argument
   real(wp), intent(in) :: z
   !> W0(Z)
   real(wp), intent(out) :: w
   !> 0, or -1 for Z outside the domain
   integer, intent(out) :: info
   w = lambert_w0(z)
   info = 0
   if (ieee_is_nan(w)) info = -1
end subroutine hcw0

!> HCWM1(Z, W, INFO): lower branch W-1(Z) of Lambert W, -1/e <= Z < 0.
subroutine hcwm1(z, w, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_lambertw, only : lambert_wm1
   implicit none
   !> Argument
   real(wp), intent(in) :: z
   !> W-1(Z)
   real(wp), intent(out) :: w
   !> 0, or -1 for Z outside the domain
   integer, intent(out) :: info
   w = lambert_wm1(z)
   info = 0
   if (ieee_is_nan(w)) info = -1
end subroutine hcwm1

!> HCW0P1(T, V, INFO): V = 1 + W0(-EXP(-1-T)) from T >= 0 (no loss near T = 0).
subroutine hcw0p1(t, v, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_lambertw, only : lambert_w0p1
   implicit none
   !> Offset from the branch point, T >= 0
   real(wp), intent(in) :: t
   !> 1 + W0
   real(wp), intent(out) :: v
   !> 0, or -1 for T < 0 or NaN
   integer, intent(out) :: info
   v = lambert_w0p1(t)
   info = 0
   if (ieee_is_nan(v)) info = -1
end subroutine hcw0p1

!> HCWM1P(T, V, INFO): V = 1 + W-1(-EXP(-1-T)) from T >= 0 (no loss near T = 0).
subroutine hcwm1p(t, v, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_lambertw, only : lambert_wm1p1
   implicit none
   !> Offset from the branch point, T >= 0
   real(wp), intent(in) :: t
   !> 1 + W-1
   real(wp), intent(out) :: v
   !> 0, or -1 for T < 0 or NaN
   integer, intent(out) :: info
   v = lambert_wm1p1(t)
   info = 0
   if (ieee_is_nan(v)) info = -1
end subroutine hcwm1p

!> HCRES(BETA, RK, INFO): coefficient of restitution k(BETA), BETA = b V >= 0.
subroutine hcres(beta, rk, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : restitution
   implicit none
   !> BETA = b V >= 0 (dimensionless)
   real(wp), intent(in) :: beta
   !> k
   real(wp), intent(out) :: rk
   !> 0, or -1 for BETA < 0 or NaN
   integer, intent(out) :: info
   rk = restitution(beta)
   info = 0
   if (ieee_is_nan(rk)) info = -1
end subroutine hcres

!> HCRESI(E, BETA, INFO): the exact inverse, BETA >= 0 with k(BETA) = E, 0 < E <= 1.
subroutine hcresi(e, beta, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : restitution_inverse
   implicit none
   !> Target restitution, 0 < E <= 1
   real(wp), intent(in) :: e
   !> BETA = b V (b = BETA/V)
   real(wp), intent(out) :: beta
   !> 0, or -1 for E outside (0, 1]
   integer, intent(out) :: info
   beta = restitution_inverse(e)
   info = 0
   if (ieee_is_nan(beta)) info = -1
end subroutine hcresi

!> HCRES1(BETA, D, INFO): 1 - k(BETA), accurate where k is close to 1.
subroutine hcres1(beta, d, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : one_minus_restitution
   implicit none
   !> BETA = b V >= 0
   real(wp), intent(in) :: beta
   !> 1 - k
   real(wp), intent(out) :: d
   !> 0, or -1 for BETA < 0 or NaN
   integer, intent(out) :: info
   d = one_minus_restitution(beta)
   info = 0
   if (ieee_is_nan(d)) info = -1
end subroutine hcres1

!> HCELOS(BETA, R, INFO): share of the kinetic energy lost, 1 - k(BETA)**2.
subroutine hcelos(beta, r, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : energy_loss_ratio
   implicit none
   !> BETA = b V >= 0
   real(wp), intent(in) :: beta
   !> 1 - k**2
   real(wp), intent(out) :: r
   !> 0, or -1 for BETA < 0 or NaN
   integer, intent(out) :: info
   r = energy_loss_ratio(beta)
   info = 0
   if (ieee_is_nan(r)) info = -1
end subroutine hcelos

!> HCRESD(BETA, DK, INFO): sensitivity dk/dBETA (negative, -2/3 at 0).
subroutine hcresd(beta, dk, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : restitution_derivative
   implicit none
   !> BETA = b V >= 0
   real(wp), intent(in) :: beta
   !> dk/dBETA
   real(wp), intent(out) :: dk
   !> 0, or -1 for BETA < 0 or NaN
   integer, intent(out) :: info
   dk = restitution_derivative(beta)
   info = 0
   if (ieee_is_nan(dk)) info = -1
end subroutine hcresd

!> HCRESA(N, BETA, RK, INFO): RK(I) = k(BETA(I)), I = 1..N.
subroutine hcresa(n, beta, rk, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : restitution
   !$ use hcimpact_parallel, only : min_parallel_cheap
   implicit none
   !> Number of elements, N >= 0
   integer, intent(in) :: n
   !> BETA(N), each >= 0
   real(wp), intent(in) :: beta(*)
   !> RK(N)
   real(wp), intent(inout) :: rk(*)
   !> 0; -1 for N < 0; -2 if some BETA(I) is outside the domain (its RK(I) is NaN, the
   !> others are computed)
   integer, intent(out) :: info
   logical :: bad
   integer :: i
   info = 0
   if (n < 0) then
      info = -1
      return
   end if
   bad = .false.
   !$omp parallel do if (n >= min_parallel_cheap) reduction(.or.: bad) schedule(static)
   do i = 1, n
      rk(i) = restitution(beta(i))
      bad = bad .or. ieee_is_nan(rk(i))
   end do
   !$omp end parallel do
   if (bad) info = -2
end subroutine hcresa

!> HCRSIA(N, E, BETA, INFO): BETA(I) with k(BETA(I)) = E(I), I = 1..N.
subroutine hcrsia(n, e, beta, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
   use hcimpact_kinds, only : wp
   use hcimpact_restitution_law, only : restitution_inverse
   !$ use hcimpact_parallel, only : min_parallel_cheap
   implicit none
   !> Number of elements, N >= 0
   integer, intent(in) :: n
   !> E(N), each in (0, 1]
   real(wp), intent(in) :: e(*)
   !> BETA(N)
   real(wp), intent(inout) :: beta(*)
   !> 0; -1 for N < 0; -2 if some E(I) is outside (0, 1] (its BETA(I) is NaN)
   integer, intent(out) :: info
   logical :: bad
   integer :: i
   info = 0
   if (n < 0) then
      info = -1
      return
   end if
   bad = .false.
   !$omp parallel do if (n >= min_parallel_cheap) reduction(.or.: bad) schedule(static)
   do i = 1, n
      beta(i) = restitution_inverse(e(i))
      bad = bad .or. ieee_is_nan(beta(i))
   end do
   !$omp end parallel do
   if (bad) info = -2
end subroutine hcrsia

!> HCDAMP(E, V, B, INFO): damping b (s/m) giving the restitution E at the approach
!> speed V (m/s), b = beta(E)/MAX(V, 1e-3 m/s).
subroutine hcdamp(e, v, b, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : damping_for_restitution
   use hcimpact_f77_support, only : nan
   implicit none
   !> Target restitution, 0 < E <= 1
   real(wp), intent(in) :: e
   !> Approach speed in m/s, V >= 0
   real(wp), intent(in) :: v
   !> Damping b in s/m
   real(wp), intent(out) :: b
   !> 0; -1 (E outside (0, 1]), -2 (V negative or not finite)
   integer, intent(out) :: info
   integer :: stat
   b = nan
   info = 0
   if (.not. ieee_is_finite(e)) then
      info = -1
   else if (.not. (e > 0.0_wp .and. e <= 1.0_wp)) then
      info = -1
   else if (.not. ieee_is_finite(v)) then
      info = -2
   else if (v < 0.0_wp) then
      info = -2
   else
      call damping_for_restitution(e, v, b, stat)
      info = stat
   end if
end subroutine hcdamp

!> HCHERZ(E1, PR1, R1, E2, PR2, R2, C, INFO): Hertz's contact constant C (N/m**1.5) of
!> two elastic spheres; a radius R = 0 stands for a flat body (a plate, R = infinity).
subroutine hcherz(e1, pr1, r1, e2, pr2, r2, c, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_value, ieee_positive_inf
   use hcimpact_kinds, only : wp
   use hcimpact_hertz, only : hertz_constant
   use hcimpact_f77_support, only : nan
   implicit none
   !> Young's modulus of body 1 in Pa, > 0
   real(wp), intent(in) :: e1
   !> Poisson's ratio of body 1, -1 < PR1 <= 0.5
   real(wp), intent(in) :: pr1
   !> Radius of body 1 in m, > 0, or 0 for flat
   real(wp), intent(in) :: r1
   !> Young's modulus of body 2 in Pa, > 0
   real(wp), intent(in) :: e2
   !> Poisson's ratio of body 2, -1 < PR2 <= 0.5
   real(wp), intent(in) :: pr2
   !> Radius of body 2 in m, > 0, or 0 for flat
   real(wp), intent(in) :: r2
   !> Contact constant in N/m**1.5
   real(wp), intent(out) :: c
   !> 0; -1 .. -6 for the first invalid argument (-6 also when both radii are 0)
   integer, intent(out) :: info
   real(wp) :: inf
   c = nan
   info = 0
   if (.not. valid_material(e1)) then
      info = -1
   else if (.not. valid_ratio(pr1)) then
      info = -2
   else if (.not. valid_radius(r1)) then
      info = -3
   else if (.not. valid_material(e2)) then
      info = -4
   else if (.not. valid_ratio(pr2)) then
      info = -5
   else if (.not. valid_radius(r2) .or. (r1 == 0.0_wp .and. r2 == 0.0_wp)) then
      info = -6
   end if
   if (info /= 0) return
   inf = ieee_value(inf, ieee_positive_inf)
   c = hertz_constant(e1, pr1, merge(inf, r1, r1 == 0.0_wp), e2, pr2, &
      & merge(inf, r2, r2 == 0.0_wp))
contains
   pure logical function valid_material(young)
      real(wp), intent(in) :: young
      valid_material = ieee_is_finite(young)
      if (valid_material) valid_material = young > 0.0_wp
   end function valid_material
   pure logical function valid_ratio(poisson)
      real(wp), intent(in) :: poisson
      valid_ratio = ieee_is_finite(poisson)
      if (valid_ratio) valid_ratio = poisson > -1.0_wp .and. poisson <= 0.5_wp
   end function valid_ratio
   pure logical function valid_radius(radius)
      real(wp), intent(in) :: radius
      valid_radius = ieee_is_finite(radius)
      if (valid_radius) valid_radius = radius >= 0.0_wp
   end function valid_radius
end subroutine hcherz

!> HCEMAS(M1, M2, EM, INFO): effective mass EM = M1 M2/(M1 + M2) in kg.
subroutine hcemas(m1, m2, em, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_hertz, only : effective_mass
   use hcimpact_f77_support, only : nan
   implicit none
   !> Mass of body 1 in kg, > 0
   real(wp), intent(in) :: m1
   !> Mass of body 2 in kg, > 0
   real(wp), intent(in) :: m2
   !> Effective mass in kg
   real(wp), intent(out) :: em
   !> 0; -1 (M1), -2 (M2) not positive or not finite
   integer, intent(out) :: info
   em = nan
   info = 0
   if (.not. positive(m1)) then
      info = -1
   else if (.not. positive(m2)) then
      info = -2
   else
      em = effective_mass(m1, m2)
   end if
contains
   pure logical function positive(x)
      real(wp), intent(in) :: x
      positive = ieee_is_finite(x)
      if (positive) positive = x > 0.0_wp
   end function positive
end subroutine hcemas

!> HCTWOB(M1, M2, V1, V2, RK, V1A, V2A, INFO): velocities of two bodies after a
!> collinear impact with the coefficient of restitution RK (V1 > V2: they approach).
subroutine hctwob(m1, m2, v1, v2, rk, v1a, v2a, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_hertz, only : two_body_velocities
   use hcimpact_f77_support, only : nan
   implicit none
   !> Mass of body 1 in kg, > 0
   real(wp), intent(in) :: m1
   !> Mass of body 2 in kg, > 0
   real(wp), intent(in) :: m2
   !> Velocity of body 1 before, m/s
   real(wp), intent(in) :: v1
   !> Velocity of body 2 before, m/s (V2 < V1)
   real(wp), intent(in) :: v2
   !> Coefficient of restitution in [0, 1]
   real(wp), intent(in) :: rk
   !> Velocity of body 1 after, m/s
   real(wp), intent(out) :: v1a
   !> Velocity of body 2 after, m/s
   real(wp), intent(out) :: v2a
   !> 0; -1 .. -5 for the first invalid argument (-4 when V2 >= V1)
   integer, intent(out) :: info
   integer :: stat
   v1a = nan
   v2a = nan
   info = 0
   if (.not. all(ieee_is_finite([m1, m2, v1, v2, rk]))) then
      ! the first that is NaN or infinite
      info = -findloc(ieee_is_finite([m1, m2, v1, v2, rk]), .false., dim=1)
   else if (.not. m1 > 0.0_wp) then
      info = -1
   else if (.not. m2 > 0.0_wp) then
      info = -2
   else if (.not. v2 < v1) then
      info = -4
   else if (.not. (rk >= 0.0_wp .and. rk <= 1.0_wp)) then
      info = -5
   else
      call two_body_velocities(m1, m2, v1, v2, rk, v1a, v2a, stat)
      info = stat
   end if
end subroutine hctwob

!> HCIMP(M, C, EN, B, V, OUT, INFO): one impact with the power law f = C x**EN.
!> OUT(1..8) = k, 1 - k**2, rebound velocity (m/s), x_max (m), peak force (N),
!> compression at the peak force (m), compression time (s), contact time (s).
subroutine hcimp(m, c, en, b, v, out, info)
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_f77_support, only : nan, contact_info, outcome_array
   implicit none
   !> Mass in kg, > 0
   real(wp), intent(in) :: m
   !> Contact constant in N/m**EN, > 0
   real(wp), intent(in) :: c
   !> Exponent of the elastic law, >= 1e-6 (1.5: Hertz)
   real(wp), intent(in) :: en
   !> Damping in s/m, >= 0
   real(wp), intent(in) :: b
   !> Approach speed in m/s, > 0
   real(wp), intent(in) :: v
   !> OUT(8), see above
   real(wp), intent(out) :: out(8)
   !> 0; -1 .. -5 for the first invalid argument; 8 or 9 for a computational failure
   integer, intent(out) :: info
   type(outcome_type) :: outcome
   integer :: stat
   out = nan
   info = contact_info(m, c, en, b, v)
   if (info /= 0) return
   call impact(contact_type(mass=m, stiffness=c, exponent=en, damping=b, velocity=v), &
      & outcome, stat)
   info = stat
   if (info == 0) out = outcome_array(outcome, 8)
end subroutine hcimp

!> HCIMPN(M, C, EN, B, V, NOUT, OUT, INFO): HCIMP with the number of results chosen by
!> the caller: OUT(1..NOUT), 1 <= NOUT <= 9, the eight of HCIMP and then OUT(9), the
!> time from the start of contact to the peak force (s). Results added in later
!> versions are appended, so a program keeps working with its NOUT.
subroutine hcimpn(m, c, en, b, v, nout, out, info)
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_f77_support, only : nan, n_outputs, contact_info, outcome_array
   implicit none
   !> Mass in kg, > 0
   real(wp), intent(in) :: m
   !> Contact constant in N/m**EN, > 0
   real(wp), intent(in) :: c
   !> Exponent of the elastic law, >= 1e-6 (1.5: Hertz)
   real(wp), intent(in) :: en
   !> Damping in s/m, >= 0
   real(wp), intent(in) :: b
   !> Approach speed in m/s, > 0
   real(wp), intent(in) :: v
   !> Number of results wanted, 1 .. 9
   integer, intent(in) :: nout
   !> OUT(NOUT), see above
   real(wp), intent(out) :: out(*)
   !> 0; -1 .. -5 for the first invalid argument of M .. V, -6 for NOUT out of range
   !> (OUT not written); 8 or 9 for a computational failure
   integer, intent(out) :: info
   type(outcome_type) :: outcome
   integer :: stat
   if (nout < 1 .or. nout > n_outputs) then
      info = -6
      return
   end if
   out(1:nout) = nan
   info = contact_info(m, c, en, b, v)
   if (info /= 0) return
   call impact(contact_type(mass=m, stiffness=c, exponent=en, damping=b, velocity=v), &
      & outcome, stat)
   info = stat
   if (info == 0) out(1:nout) = outcome_array(outcome, nout)
end subroutine hcimpn

!> HCIMPL(FORCE, POTEN, DFORCE, M, B, V, OUT, INFO): one impact with the caller's elastic
!> law, given as three EXTERNAL DOUBLE PRECISION FUNCTIONs of the compression X (m):
!> FORCE(X) = f(x) in N (increasing, f(0) = 0), POTEN(X) = its potential, the integral of
!> f from 0 to X, in J, and DFORCE(X) = f'(x) in N/m. They must not change what they
!> read (parameters may come through a COMMON block). OUT(8) as in HCIMP.
!> INFO: 0; -4, -5, -6 for the first of M, B, V that is NaN, infinite or outside its
!> domain (M, V > 0; B >= 0); 13 when the law returns a value that is not finite or not
!> increasing; 8 or 9 for a computational failure.
subroutine hcimpl(force, poten, dforce, m, b, v, out, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : outcome_type, impact_law
   use hcimpact_f77_support, only : nan, outcome_array, f77_law, f77_law_fn
   implicit none
   !> The force f(x), N
   procedure(f77_law_fn) :: force
   !> The potential of f, J
   procedure(f77_law_fn) :: poten
   !> The derivative f'(x), N/m
   procedure(f77_law_fn) :: dforce
   !> Mass in kg, > 0
   real(wp), intent(in) :: m
   !> Damping in s/m, >= 0
   real(wp), intent(in) :: b
   !> Approach speed in m/s, > 0
   real(wp), intent(in) :: v
   !> OUT(8), see HCIMP
   real(wp), intent(out) :: out(8)
   !> Status, see above
   integer, intent(out) :: info
   type(f77_law) :: law
   type(outcome_type) :: outcome
   integer :: stat
   out = nan
   if (.not. ieee_is_finite(m)) then
      info = -4
   else if (.not. m > 0.0_wp) then
      info = -4
   else if (.not. ieee_is_finite(b)) then
      info = -5
   else if (.not. b >= 0.0_wp) then
      info = -5
   else if (.not. ieee_is_finite(v)) then
      info = -6
   else if (.not. v > 0.0_wp) then
      info = -6
   else
      law%f => force
      law%p => poten
      law%d => dforce
      call impact_law(law, m, b, v, outcome, stat)
      info = stat
      if (info == 0) out = outcome_array(outcome, 8)
   end if
end subroutine hcimpl

!> HCIMPA(NI, M, C, EN, B, V, OUT, ISTAT, INFO): NI impacts at once; the contacts are
!> the arrays M(NI), C(NI), EN(NI), B(NI), V(NI), the results OUT(8, NI) as in HCIMP.
subroutine hcimpa(ni, m, c, en, b, v, out, istat, info)
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_impact_model, only : contact_type, outcome_type, impact
   use hcimpact_f77_support, only : nan, outcome_array, first_failure
   !$ use hcimpact_parallel, only : min_parallel_impact
   implicit none
   !> Number of impacts, NI >= 0
   integer, intent(in) :: ni
   !> Masses in kg
   real(wp), intent(in) :: m(*)
   !> Contact constants in N/m**EN
   real(wp), intent(in) :: c(*)
   !> Exponents
   real(wp), intent(in) :: en(*)
   !> Damping constants in s/m
   real(wp), intent(in) :: b(*)
   !> Approach speeds in m/s
   real(wp), intent(in) :: v(*)
   !> OUT(8, NI): column I is the result of impact I (NaN if it failed)
   real(wp), intent(inout) :: out(8, *)
   !> ISTAT(NI): the library status code of each impact (0 = success; HCMSG gives
   !> its text)
   integer, intent(inout) :: istat(*)
   !> 0; -1 for NI < 0; J > 0: impact J is the first that failed (see ISTAT(J))
   integer, intent(out) :: info
   type(outcome_type) :: outcome
   integer :: i
   info = 0
   if (ni < 0) then
      info = -1
      return
   end if
   !$omp parallel do if (ni >= min_parallel_impact) private(outcome) schedule(dynamic, 4)
   do i = 1, ni
      call impact(contact_type(mass=m(i), stiffness=c(i), exponent=en(i), damping=b(i), &
         & velocity=v(i)), outcome, istat(i))
      if (istat(i) == hcimpact_ok) then
         out(:, i) = outcome_array(outcome, 8)
      else
         out(:, i) = nan
      end if
   end do
   !$omp end parallel do
   info = first_failure(ni, istat)
end subroutine hcimpa

!> HCVEL(M, C, EN, B, V, X, IBR, XDOT, INFO): velocity XDOT (m/s) at the compression
!> X (m) on the compression (IBR = 1) or restitution (IBR = 2) branch.
subroutine hcvel(m, c, en, b, v, x, ibr, xdot, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_domain
   use hcimpact_impact_model, only : contact_type, outcome_type, impact, velocity_at_depth, &
      & compression_branch, restitution_branch
   use hcimpact_f77_support, only : nan, contact_info
   implicit none
   !> Mass in kg
   real(wp), intent(in) :: m
   !> Contact constant in N/m**EN
   real(wp), intent(in) :: c
   !> Exponent
   real(wp), intent(in) :: en
   !> Damping in s/m
   real(wp), intent(in) :: b
   !> Approach speed in m/s
   real(wp), intent(in) :: v
   !> Compression in m, 0 <= X <= x_max
   real(wp), intent(in) :: x
   !> Branch: 1 compression, 2 restitution
   integer, intent(in) :: ibr
   !> Velocity in m/s
   real(wp), intent(out) :: xdot
   !> 0; -1 .. -5 contact, -6 X outside [0, x_max], -7 IBR; 8 or 9 failure
   integer, intent(out) :: info
   type(contact_type) :: contact
   type(outcome_type) :: outcome
   integer :: stat
   xdot = nan
   info = contact_info(m, c, en, b, v)
   if (info /= 0) return
   if (ibr /= compression_branch .and. ibr /= restitution_branch) then
      info = -7
      return
   end if
   if (.not. ieee_is_finite(x)) then
      info = -6
      return
   end if
   if (x < 0.0_wp) then
      info = -6
      return
   end if
   contact = contact_type(mass=m, stiffness=c, exponent=en, damping=b, velocity=v)
   call velocity_at_depth(contact, x, ibr, xdot, stat)
   info = stat
   if (stat == hcimpact_err_domain) then
      ! X beyond x_max, unless the impact itself leaves the double range
      call impact(contact, outcome, stat)
      info = merge(-6, stat, stat == hcimpact_ok)
   end if
end subroutine hcvel

!> HCTLAW(M, C, EN, B, V, NT, T, X, XDOT, F, INFO): time law at the NT times T (s):
!> compression X (m), velocity XDOT (m/s), contact force F (N).
subroutine hctlaw(m, c, en, b, v, nt, t, x, xdot, f, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, time_law
   use hcimpact_f77_support, only : nan, contact_info
   implicit none
   !> Mass in kg
   real(wp), intent(in) :: m
   !> Contact constant in N/m**EN
   real(wp), intent(in) :: c
   !> Exponent
   real(wp), intent(in) :: en
   !> Damping in s/m
   real(wp), intent(in) :: b
   !> Approach speed in m/s
   real(wp), intent(in) :: v
   !> Number of times, NT >= 0
   integer, intent(in) :: nt
   !> T(NT): times in s from the start of contact
   real(wp), intent(in) :: t(*)
   !> X(NT): compression in m
   real(wp), intent(inout) :: x(*)
   !> XDOT(NT): velocity in m/s
   real(wp), intent(inout) :: xdot(*)
   !> F(NT): contact force in N
   real(wp), intent(inout) :: f(*)
   !> 0; -1 .. -5 contact, -6 NT < 0, -7 a T(I) NaN or infinite; 8 or 9 failure
   integer, intent(out) :: info
   integer :: stat
   if (nt < 0) then
      info = -6
      return
   end if
   info = contact_info(m, c, en, b, v)
   if (nt == 0) return
   if (info == 0) then
      if (.not. all(ieee_is_finite(t(1:nt)))) then
         info = -7
      else
         call time_law(contact_type(mass=m, stiffness=c, exponent=en, damping=b, &
            & velocity=v), t(1:nt), x(1:nt), xdot(1:nt), f(1:nt), stat)
         info = stat
      end if
   end if
   if (info /= 0) then
      x(1:nt) = nan
      xdot(1:nt) = nan
      f(1:nt) = nan
   end if
end subroutine hctlaw

!> HCTSAM(M, C, EN, B, V, NT, T, X, XDOT, F, INFO): the time law on NT >= 2 equally
!> spaced times T(I) = contact time (I-1)/(NT-1), written to T.
subroutine hctsam(m, c, en, b, v, nt, t, x, xdot, f, info)
   use hcimpact_kinds, only : wp
   use hcimpact_impact_model, only : contact_type, time_law_samples
   use hcimpact_f77_support, only : nan, contact_info
   implicit none
   !> Mass in kg
   real(wp), intent(in) :: m
   !> Contact constant in N/m**EN
   real(wp), intent(in) :: c
   !> Exponent
   real(wp), intent(in) :: en
   !> Damping in s/m
   real(wp), intent(in) :: b
   !> Approach speed in m/s
   real(wp), intent(in) :: v
   !> Number of samples, NT >= 2
   integer, intent(in) :: nt
   !> T(NT): times in s
   real(wp), intent(inout) :: t(*)
   !> X(NT): compression in m
   real(wp), intent(inout) :: x(*)
   !> XDOT(NT): velocity in m/s
   real(wp), intent(inout) :: xdot(*)
   !> F(NT): contact force in N
   real(wp), intent(inout) :: f(*)
   !> 0; -1 .. -5 contact, -6 NT < 2; 8 or 9 failure; 16 out of memory for NT samples
   integer, intent(out) :: info
   real(wp), allocatable :: ts(:), xs(:), vs(:), fs(:)
   integer :: stat
   info = contact_info(m, c, en, b, v)
   if (info == 0 .and. nt < 2) info = -6
   if (info /= 0) then
      if (nt >= 1) then
         t(1:nt) = nan
         x(1:nt) = nan
         xdot(1:nt) = nan
         f(1:nt) = nan
      end if
      return
   end if
   call time_law_samples(contact_type(mass=m, stiffness=c, exponent=en, damping=b, &
      & velocity=v), nt, ts, xs, vs, fs, stat)
   info = stat
   if (info == 0) then
      t(1:nt) = ts
      x(1:nt) = xs
      xdot(1:nt) = vs
      f(1:nt) = fs
   else
      t(1:nt) = nan
      x(1:nt) = nan
      xdot(1:nt) = nan
      f(1:nt) = nan
   end if
end subroutine hctsam

!> HCFRC(C, EN, B, X, XDOT, F, INFO): the contact-force element of one power-law contact
!> f = C x**EN with the damping B (s/m), at the deformation X (m; X <= 0: no contact)
!> and the deformation rate XDOT (m/s, > 0 while the bodies approach). F(1..5) = force
!> (N, never pulling: clamped at 0 where 1 + B XDOT < 0), dF/dX (N/m), dF/dXDOT (N s/m),
!> elastic potential energy (J), dissipated power (W). See doc/contact-force.md.
subroutine hcfrc(c, en, b, x, xdot, f, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_force_element, only : contact_force_type, contact_force
   use hcimpact_f77_support, only : nan, law_info, force_array
   implicit none
   !> Contact constant in N/m**EN, > 0
   real(wp), intent(in) :: c
   !> Exponent of the elastic law, >= 1e-6
   real(wp), intent(in) :: en
   !> Damping in s/m, >= 0
   real(wp), intent(in) :: b
   !> Deformation in m
   real(wp), intent(in) :: x
   !> Deformation rate in m/s
   real(wp), intent(in) :: xdot
   !> F(5), see above
   real(wp), intent(out) :: f(5)
   !> 0; -1 .. -5 for the first invalid argument (C, EN, B out of their domain; X or
   !> XDOT NaN or infinite)
   integer, intent(out) :: info
   type(contact_force_type) :: element
   f = nan
   info = law_info(c, en, b)
   if (info /= 0) return
   if (.not. ieee_is_finite(x)) then
      info = -4
   else if (.not. ieee_is_finite(xdot)) then
      info = -5
   else
      call contact_force(c, en, b, x, xdot, element)
      f = force_array(element)
   end if
end subroutine hcfrc

!> HCFRCA(N, C, EN, B, X, XDOT, F, ISTAT, INFO): HCFRC for N contacts at once: C(N),
!> EN(N), B(N), X(N), XDOT(N) give F(5, N); ISTAT(N) the library status of each.
subroutine hcfrca(n, c, en, b, x, xdot, f, istat, info)
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok
   use hcimpact_force_element, only : contact_force_type, contact_force
   use hcimpact_f77_support, only : force_array, first_failure
   !$ use hcimpact_parallel, only : min_parallel_element
   implicit none
   !> Number of contacts, N >= 0
   integer, intent(in) :: n
   !> Contact constants (N/m**EN), exponents, damping constants (s/m)
   real(wp), intent(in) :: c(*), en(*), b(*)
   !> Deformations (m) and deformation rates (m/s)
   real(wp), intent(in) :: x(*), xdot(*)
   !> F(5, N): column I is the element of contact I (NaN if it failed)
   real(wp), intent(inout) :: f(5, *)
   !> ISTAT(N): the library status code of each contact (0 = success; HCMSG)
   integer, intent(inout) :: istat(*)
   !> 0; -1 for N < 0; J > 0: contact J is the first that failed (see ISTAT(J))
   integer, intent(out) :: info
   type(contact_force_type) :: element
   integer :: i
   info = 0
   if (n < 0) then
      info = -1
      return
   end if
   !$omp parallel do if (n >= min_parallel_element) private(element) schedule(static)
   do i = 1, n
      call contact_force(c(i), en(i), b(i), x(i), xdot(i), element, istat(i))
      f(:, i) = force_array(element)
   end do
   !$omp end parallel do
   info = first_failure(n, istat)
end subroutine hcfrca

!> HCFRCP(C, EN, B, D, Q1, V1, Q2, V2, F, INFO): the element of two bodies on a line,
!> body 1 (position Q1, velocity V1) left of body 2 (Q2, V2): deformation
!> D - (Q2 - Q1) and rate V1 - V2, both without rounding error; D = Q2 - Q1 at first
!> touch (the sum of the radii for centres). The force on body 2 is +F(1), on body 1
!> -F(1). F(5) as in HCFRC.
subroutine hcfrcp(c, en, b, d, q1, v1, q2, v2, f, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_force_element, only : contact_force_type, contact_force_pair
   use hcimpact_f77_support, only : nan, law_info, force_array
   implicit none
   !> Contact constant (N/m**EN), exponent, damping (s/m)
   real(wp), intent(in) :: c, en, b
   !> Q2 - Q1 at first touch, m
   real(wp), intent(in) :: d
   !> Position (m) and velocity (m/s) of body 1 and of body 2
   real(wp), intent(in) :: q1, v1, q2, v2
   !> F(5)
   real(wp), intent(out) :: f(5)
   !> 0; -1 .. -8 for the first invalid argument; 8 for an overlap or relative speed
   !> beyond the double range
   integer, intent(out) :: info
   type(contact_force_type) :: element
   real(wp) :: args(5)
   integer :: i
   f = nan
   info = law_info(c, en, b)
   if (info /= 0) return
   args = [d, q1, v1, q2, v2]
   do i = 1, 5
      if (.not. ieee_is_finite(args(i))) then
         info = -3 - i
         return
      end if
   end do
   call contact_force_pair(c, en, b, d, q1, v1, q2, v2, element, info)
   f = force_array(element)
end subroutine hcfrcp

!> HCFRCW(C, EN, B, D, Q, V, W, ISIDE, F, INFO): the element of a body (position Q,
!> velocity V) against a fixed wall at W: ISIDE = 1 when the wall is on the body's
!> right, -1 on its left; D = |W - Q| at first touch. The force on the body is
!> -ISIDE F(1). F(5) as in HCFRC.
subroutine hcfrcw(c, en, b, d, q, v, w, iside, f, info)
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
   use hcimpact_kinds, only : wp
   use hcimpact_force_element, only : contact_force_type, contact_force_wall
   use hcimpact_f77_support, only : nan, law_info, force_array
   implicit none
   !> Contact constant (N/m**EN), exponent, damping (s/m)
   real(wp), intent(in) :: c, en, b
   !> |W - Q| at first touch, m
   real(wp), intent(in) :: d
   !> Position (m) and velocity (m/s) of the body, position of the wall (m)
   real(wp), intent(in) :: q, v, w
   !> 1: wall on the right of the body; -1: on its left
   integer, intent(in) :: iside
   !> F(5)
   real(wp), intent(out) :: f(5)
   !> 0; -1 .. -8 for the first invalid argument (-8: ISIDE not 1 or -1); 8 for an
   !> overlap or speed beyond the double range
   integer, intent(out) :: info
   type(contact_force_type) :: element
   real(wp) :: args(4)
   integer :: i
   f = nan
   info = law_info(c, en, b)
   if (info /= 0) return
   args = [d, q, v, w]
   do i = 1, 4
      if (.not. ieee_is_finite(args(i))) then
         info = -3 - i
         return
      end if
   end do
   if (iside /= 1 .and. iside /= -1) then
      info = -8
      return
   end if
   call contact_force_wall(c, en, b, d, q, v, w, iside, element, info)
   f = force_array(element)
end subroutine hcfrcw
