! SPDX-License-Identifier: Apache-2.0
! Reproducers of the second attack of 26 November under floating-point traps (a Debug build's
! -ffpe-trap=invalid,zero,overflow takes effect only when the main program has it):
!   cmake -S . -B build/debug-shared -G Ninja -DCMAKE_BUILD_TYPE=Debug \
!         -DHCIMPACT_DEBUG_CHECKS=ON -DBUILD_SHARED_LIBS=ON
!   cmake --build build/debug-shared --target hcimpact hcimpact_cvode
!   B=build/debug-shared; gfortran -g -ffpe-trap=invalid,zero,overflow -fbacktrace \
!     -I$B/modules bench/chain/attack/repro_second_attack_traps.f90 -o /tmp/drv \
!     -L$B -lhcimpact_cvode -lhcimpact -Wl,-rpath,$B
!   /tmp/drv 5   (SIGFPE in scaled_impact: scale_x / v overflows, n = 100, V = 5e-324)
!   /tmp/drv 6   (SIGFPE in body_state_at from take_samples: a sample position overflows)
! Cases 3, 4, 7-12 run without a trap (3 and 4 give the wrong answers of
! repro_second_attack.py; 12: masses 1 and 3 at 5e-324 m/s end at [-5e-324, 0], momentum reversed,
! which subnormals cannot avoid).
program drv
   use hcimpact_kinds, only : wp
   use hcimpact_chain_types
   use hcimpact_cvode_chain, only : chain_simulate
   implicit none
   type(chain_type) :: ch
   type(chain_options) :: op
   type(chain_result) :: res
   integer :: stat, which
   character(len=16) :: arg
   call get_command_argument(1, arg)
   read(arg, *) which
   select case (which)
   case (3)   ! exponent 0.5 at 1e-250 m/s
      ch%mass = [2.0_wp, 0.3_wp]; ch%velocity = [1.0e-250_wp, 0.0_wp]; ch%gap = [0.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp, exponent=0.5_wp, damping=0.3_wp / 1.0e-250_wp)]
      op%sample_times = [1.0e-95_wp]
   case (4)   ! subnormal, t_end inside
      ch%mass = [1.0_wp, 1.0_wp]; ch%velocity = [5.0e-324_wp, 0.0_wp]; ch%gap = [0.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp, exponent=1.0_wp, damping=0.0_wp)]
      op%t_end = 3.5e-5_wp
   case (5)   ! exponent 100, subnormal
      ch%mass = [1.0_wp, 1.0_wp]; ch%velocity = [5.0e-324_wp, 0.0_wp]; ch%gap = [0.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp, exponent=100.0_wp, damping=0.0_wp)]
   case (6)   ! sample beyond range
      ch%mass = [1.0_wp, 1.0_wp]; ch%velocity = [1.0e150_wp, 1.0e150_wp]; ch%gap = [1.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp, exponent=1.5_wp, damping=0.0_wp)]
      ch%gravity = -1.0e-150_wp; op%t_end = 2.0e300_wp; op%sample_times = [1.0e300_wp]
   case (7)   ! landing under g = -5e-324
      ch%mass = [1.0_wp]; ch%velocity = [0.0_wp]; allocate(ch%gap(0), ch%law(0))
      ch%left_wall = .true.; ch%left_law = contact_law(stiffness=1.0e9_wp, exponent=1.5_wp, damping=0.5_wp)
      ch%left_gap = 1.0_wp; ch%gravity = -5.0e-324_wp; op%t_end = 1.0e162_wp
   case (8)   ! settle at a far t_end
      ch%mass = [0.1_wp, 0.1_wp]; ch%velocity = [0.0_wp, 0.0_wp]; ch%gap = [0.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp, exponent=1.5_wp, damping=1.0_wp)]
      ch%left_wall = .true.; ch%left_law = contact_law(stiffness=1.0e9_wp, exponent=1.5_wp, damping=1.0_wp)
      ch%gravity = -9.81_wp; op%t_end = 1.0e300_wp; op%sample_times = [1.0_wp, 1.0e299_wp]
   case (9)   ! three touching, t_end 5e-324
      ch%mass = [1.0_wp, 1.0_wp, 1.0_wp]; ch%velocity = [1.0_wp, 0.0_wp, 0.0_wp]; ch%gap = [0.0_wp, 0.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp), contact_law(stiffness=1.0e9_wp)]
      op%t_end = 5.0e-324_wp
   case (10)  ! tiny speed pair n = 1.5, unequal, damped
      ch%mass = [2.0_wp, 0.3_wp]; ch%velocity = [1.0e-300_wp, 0.0_wp]; ch%gap = [0.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp, exponent=1.5_wp, damping=0.3e300_wp)]
      op%sample_times = [1.0e55_wp, 1.0e56_wp]
   case (11)  ! extent limit
      ch%mass = [1.0_wp, 1.0_wp]; ch%velocity = [1.0e10_wp, -1.0e10_wp]; ch%gap = [0.25_wp * huge(1.0_wp)]
      ch%law = [contact_law(stiffness=1.0e9_wp)]
   case (12)  ! subnormal pair with the split at the end
      ch%mass = [1.0_wp, 3.0_wp]; ch%velocity = [5.0e-324_wp, 0.0_wp]; ch%gap = [0.0_wp]
      ch%law = [contact_law(stiffness=1.0e9_wp, exponent=1.5_wp)]
   end select
   call chain_simulate(ch, res, stat, op)
   print *, 'stat', stat, trim(res%message)
   if (stat == 0) print *, 'time', res%time, 'v', res%velocities
end program drv
