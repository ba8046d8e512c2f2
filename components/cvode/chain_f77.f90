! SPDX-License-Identifier: Apache-2.0
!> FORTRAN 77 entry point of the CVODE component: HCCHN, a system of bodies on a line
!> (`chain_simulate` of hcimpact_cvode_chain) for a fixed-form program that CALLs it
!> with an implicit interface. It is an external subroutine of libhcimpact_cvode,
!> with the conventions of the core's routines (src/hcimpact/f77/f77.f90): DOUBLE
!> PRECISION reals, default INTEGERs, every argument by reference, a LAPACK-style
!> INFO. doc/fortran77.md.

!> HCCHN(N, XM, V, GAP, PLAW, WALL, GRAV, OPTS, IOPTS, X, VF, RES, ICNT, MAXC, LDC,
!>       CONT, ICON, MSG, INFO): N bodies on a line, numbered from the left, velocities
!> positive to the right (doc/chains.md). The closed forms of one impact where
!> contacts are isolated, CVODE where they overlap.
!>
!> INFO = 0 success; -i the i-th argument is invalid (the first one found, in the
!> order of the arguments; the real outputs are NaN, the counts 0); > 0 the library's
!> status code (HCMSG gives its text; MSG says more): 9 more than MAXEVT contacts or
!> MAXSTP steps, 11 CVODE failed, 8 a cluster with METHOD = 1 (exact only) or
!> arguments each valid whose combination is outside the domain (MSG names it), 16
!> out of memory (the system is too large for the memory available).
subroutine hcchn(n, xm, v, gap, plaw, wall, grav, opts, iopts, x, vf, res, icnt, maxc, &
      & ldc, cont, icon, msg, info)
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp, nan, finite_value
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_out_of_memory, status_message
   use hcimpact_contact, only : check_parameters
   use hcimpact_f77_support, only : law_info
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, chain_result, &
      & check_rtol, sum_within_range, max_message, no_memory_tail
   use hcimpact_cvode_chain, only : chain_simulate
   use hcimpact_cvode_chain_capi_types, only : chain_options_from
   implicit none
   !> Number of bodies, N >= 1
   integer, intent(in) :: n
   !> XM(N): masses in kg (> 0; together at most a quarter of the largest double)
   real(wp), intent(in) :: xm(*)
   !> V(N): initial velocities in m/s
   real(wp), intent(in) :: v(*)
   !> GAP(N-1): gaps between neighbours in m (>= 0; 0: touching; together at most a
   !> quarter of the largest double)
   real(wp), intent(in) :: gap(*)
   !> PLAW(3, N-1): the law of pair I (bodies I and I+1): PLAW(1, I) = c in N/m**n
   !> (> 0), PLAW(2, I) = n (>= 1e-6), PLAW(3, I) = b in s/m (>= 0)
   real(wp), intent(in) :: plaw(3, *)
   !> WALL(4, 2): the left (column 1) and right (column 2) wall: c, n, b as in PLAW,
   !> then the gap to the end body in m (>= 0); c = 0: no wall on that side (the rest
   !> of that column is then not read)
   real(wp), intent(in) :: wall(4, 2)
   !> Constant acceleration along the line in m/s**2 (negative: to the left)
   real(wp), intent(in) :: grav
   !> OPTS(2): end time in s (<= 0: until no contact can happen again); CVODE's
   !> relative tolerance in (0, 0.01] (0: 1e-10)
   real(wp), intent(in) :: opts(2)
   !> IOPTS(4): method (0 auto, 1 exact only, 2 integrated); integrator (0 or 1 BDF,
   !> 2 Adams); most steps (0: 1e8); most contacts computed (0: 1e8)
   integer, intent(in) :: iopts(4)
   !> X(N): final positions in m (body 1 starts at 0, body I+1 at body I's position +
   !> GAP(I))
   real(wp), intent(out) :: x(*)
   !> VF(N): final velocities in m/s
   real(wp), intent(out) :: vf(*)
   !> RES(8): time reached, rest time (NaN unless the system came to rest on a wall),
   !> initial kinetic energy (J), relative energy error, energy dissipated (J),
   !> relative momentum error (against the initial momentum plus the outside
   !> impulses, gravity's M g t and the walls'), the impulses the left and the right
   !> wall gave the system (N s along the line: >= 0, <= 0; 0 without the wall)
   real(wp), intent(out) :: res(8)
   !> ICNT(11): contacts (all), contacts recorded in CONT, method used (1 closed forms,
   !> 2 integration, 3 both), 1 if the system came to rest, contacts by the closed
   !> forms, contacts by integration, steps, right-hand sides, Jacobians, roots,
   !> clusters (each at most HUGE(0))
   integer, intent(out) :: icnt(11)
   !> Rows of CONT and ICON to fill, MAXC >= 0: the first MAXC contacts are recorded
   integer, intent(in) :: maxc
   !> Leading dimension of CONT and ICON, LDC >= MAX(1, MAXC)
   integer, intent(in) :: ldc
   !> CONT(LDC, 7): row J is contact J (in the order they ended): start and end (s),
   !> approach and separation speed (m/s), peak force (N), largest deformation (m),
   !> energy dissipated (J)
   real(wp), intent(inout) :: cont(ldc, *)
   !> ICON(LDC, 2): row J: the pair (0 left wall, I bodies I and I+1, N right wall) and
   !> how it was computed (1 closed forms, 2 integration)
   integer, intent(inout) :: icon(ldc, *)
   !> CHARACTER*(*): "success" or what went wrong (blank-padded or cut)
   character(len=*), intent(out) :: msg
   !> 0, -i for the i-th argument, or a status code > 0
   integer, intent(out) :: info
   type(chain_type) :: chain
   type(chain_options) :: options
   type(chain_result) :: result
   integer :: i, k, stat, alloc_stat
   integer(int64) :: counts(11)

   res = nan
   icnt = 0
   call check_arguments(info, msg)
   if (info /= 0) then
      if (n >= 1) then
         x(1:n) = nan
         vf(1:n) = nan
      end if
      return
   end if

   ! the copies, checked (out of memory: INFO = hcimpact_err_out_of_memory, the outputs
   ! as after the library's own failure)
   allocate(chain%mass(n), chain%velocity(n), chain%gap(n - 1), chain%law(n - 1), &
      & stat=alloc_stat)
   if (alloc_stat /= 0) then
      msg = "out of memory (the copies of the input" // no_memory_tail
      x(1:n) = nan
      vf(1:n) = nan
      info = hcimpact_err_out_of_memory
      return
   end if
   chain%mass(:) = xm(1:n)
   chain%velocity(:) = v(1:n)
   chain%gap(:) = gap(1:n - 1)
   do i = 1, n - 1
      chain%law(i) = contact_law(stiffness=plaw(1, i), exponent=plaw(2, i), &
         & damping=plaw(3, i))
   end do
   ! an absent wall's column is not read: the library checks a wall gap even without
   ! the wall, and a NaN left there failed the call
   chain%left_wall = wall(1, 1) /= 0.0_wp
   if (chain%left_wall) then
      chain%left_law = contact_law(stiffness=wall(1, 1), exponent=wall(2, 1), &
         & damping=wall(3, 1))
      chain%left_gap = wall(4, 1)
   end if
   chain%right_wall = wall(1, 2) /= 0.0_wp
   if (chain%right_wall) then
      chain%right_law = contact_law(stiffness=wall(1, 2), exponent=wall(2, 2), &
         & damping=wall(3, 2))
      chain%right_gap = wall(4, 2)
   end if
   chain%gravity = grav
   options = chain_options_from(opts(1), opts(2), iopts(1), iopts(2), &
      & int(iopts(3), int64), int(iopts(4), int64))
   options%max_contacts = maxc

   call chain_simulate(chain, result, stat, options)
   msg = result%message
   if (stat /= hcimpact_ok) then
      if (len_trim(result%message) == 0) msg = status_message(stat)
      x(1:n) = nan
      vf(1:n) = nan
      info = stat
      return
   end if
   x(1:n) = result%positions
   vf(1:n) = result%velocities
   res = [result%time, result%rest_time, result%initial_energy, result%energy_error, &
      & result%dissipated, result%momentum_error, result%wall_impulse]
   counts = [result%n_contacts, int(size(result%contacts), int64), &
      & int(result%method_used, int64), merge(1_int64, 0_int64, result%rested), &
      & result%counters%closed_form_contacts, result%counters%integrated_contacts, &
      & result%counters%steps, result%counters%rhs_evals, result%counters%jacobian_evals, &
      & result%counters%roots, result%counters%clusters]
   icnt = int(min(counts, int(huge(0), int64)))
   do k = 1, size(result%contacts)
      cont(k, 1:7) = [result%contacts(k)%t_start, result%contacts(k)%t_end, &
         & result%contacts(k)%approach_speed, result%contacts(k)%separation_speed, &
         & result%contacts(k)%peak_force, result%contacts(k)%max_deformation, &
         & result%contacts(k)%dissipated]
      icon(k, 1:2) = [result%contacts(k)%pair, result%contacts(k)%method]
   end do

contains

   !> The first invalid argument, in their order, and what is wrong with it. The
   !> library's validator (hcimpact_chain_types' check_chain, run again by
   !> chain_simulate) decides; these checks use the library's rules for each argument
   !> (check_parameters, law_info, sum_within_range, check_rtol) only to name the
   !> argument at fault, so that none passes here to fail there.
   subroutine check_arguments(info, msg)
      integer, intent(out) :: info
      character(len=*), intent(out) :: msg
      type(chain_options) :: asked
      character(len=max_message) :: why
      integer :: i, side, stat
      info = -1
      if (n < 1) then
         msg = "N: a system needs at least one body"
         return
      end if
      info = -2
      do i = 1, n
         if (check_parameters(mass=xm(i)) /= hcimpact_ok) then
            call say(msg, "XM(", i, "): masses must be positive and finite")
            return
         end if
      end do
      if (.not. sum_within_range(xm(1:n))) then
         msg = "XM: the masses add up beyond a quarter of the range of doubles"
         return
      end if
      info = -3
      do i = 1, n
         if (.not. finite_value(v(i))) then
            call say(msg, "V(", i, ") is NaN or infinite")
            return
         end if
      end do
      info = -4
      do i = 1, n - 1
         if (.not. (finite_value(gap(i)) .and. gap(i) >= 0.0_wp)) then
            call say(msg, "GAP(", i, "): gaps must be finite and >= 0" &
               & // " (touching: 0; bodies may not overlap at the start)")
            return
         end if
      end do
      if (.not. sum_within_range(gap(1:n - 1))) then
         msg = "GAP: the gaps add up beyond a quarter of the range of doubles"
         return
      end if
      info = -5
      do i = 1, n - 1
         if (law_info(plaw(1, i), plaw(2, i), plaw(3, i)) /= 0) then
            call say(msg, "PLAW(:, ", i, "): c > 0, n >= 1e-6, b >= 0, all finite")
            return
         end if
      end do
      info = -6
      do side = 1, 2
         if (wall(1, side) == 0.0_wp) cycle
         if (law_info(wall(1, side), wall(2, side), wall(3, side)) /= 0 .or. &
            & .not. (finite_value(wall(4, side)) .and. wall(4, side) >= 0.0_wp)) then
            call say(msg, "WALL(:, ", side, "): c > 0 (0: no wall), n >= 1e-6," &
               & // " b >= 0, gap >= 0, all finite")
            return
         end if
      end do
      info = -7
      if (.not. finite_value(grav)) then
         msg = "GRAV is NaN or infinite"
         return
      end if
      info = -8
      if (.not. finite_value(opts(1))) then
         msg = "OPTS(1): the end time is NaN or infinite"
         return
      end if
      ! the tolerance as the library takes it (0: the default) against its own rule
      asked = chain_options_from(opts(1), opts(2), 0, 0, 0_int64, 0_int64)
      call check_rtol(asked%rtol, stat, why)
      if (stat /= hcimpact_ok) then
         msg = "OPTS(2): " // trim(why) // " (0: the default)"
         return
      end if
      info = -9
      if (iopts(1) < 0 .or. iopts(1) > 2 .or. iopts(2) < 0 .or. iopts(2) > 2 .or. &
         & iopts(3) < 0 .or. iopts(4) < 0) then
         msg = "IOPTS: method 0, 1 or 2; integrator 0, 1 or 2; limits >= 0"
         return
      end if
      info = -14
      if (maxc < 0) then
         msg = "MAXC is negative"
         return
      end if
      info = -15
      if (ldc < max(1, maxc)) then
         msg = "LDC must be at least MAX(1, MAXC)"
         return
      end if
      info = 0
      msg = "success"
   end subroutine check_arguments

   !> MSG = head, the index i, tail: formed whole in a buffer long enough for any i,
   !> then assigned, so that a shorter MSG is cut and a longer one blank-padded (an
   !> internal write straight into the caller's MSG stopped the program with "End of
   !> record" when the text was longer).
   subroutine say(msg, head, i, tail)
      character(len=*), intent(out) :: msg
      character(len=*), intent(in) :: head, tail
      integer, intent(in) :: i
      character(len=len(head) + len(tail) + 11) :: text
      write(text, '(a, i0, a)') head, i, tail
      msg = text
   end subroutine say

end subroutine hcchn
