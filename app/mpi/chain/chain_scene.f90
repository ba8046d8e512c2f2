! SPDX-License-Identifier: Apache-2.0
!> The scene of the distributed chain (hcimpact_mpi_chain, doc/mpi.md): a namelist
!> `&mpi_chain` that describes a uniform chain of beads struck at its first bead, read
!> from a file, and the `chain_type` and `chain_options` it stands for. Nothing here
!> knows about MPI: every rank reads the same file and builds the same chain.
module hcimpact_mpi_chain_scene
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_domain, hcimpact_err_size
   use hcimpact_force_element, only : contact_force_type, contact_force_pair
   use hcimpact_chain_types, only : chain_type, chain_options, contact_law, check_chain, &
      & method_integrated, max_message
   implicit none
   private

   public :: chain_scene, read_chain_scene, scene_system, chain_energy

   !> A uniform chain of beads on a line, at rest and touching or with equal gaps, its
   !> first bead moving towards the second at `striker_speed`
   type :: chain_scene
      !> Number of beads
      integer :: n_beads = 0
      !> Mass of a bead (kg), the law of every neighbouring pair: contact constant c
      !> (N/m^n), exponent n and damping b (s/m), and the gap between neighbours (m)
      real(wp) :: mass = 0.0_wp, stiffness = 0.0_wp, exponent = 1.5_wp, &
         & damping = 0.0_wp, gap = 0.0_wp
      !> Initial velocity of bead 1 (m/s), the others at rest
      real(wp) :: striker_speed = 0.0_wp
      !> End time (s, > 0) and CVODE's relative tolerance
      real(wp) :: t_end = 0.0_wp, rtol = 1.0e-8_wp
      !> Largest number of CVODE steps
      integer(int64) :: max_steps = 10000000_int64
   end type chain_scene

contains

   !> Read the namelist &mpi_chain from the file `path`. ok false with a message when
   !> the file cannot be read or the namelist is not there or not valid Fortran.
   subroutine read_chain_scene(path, scene, ok, message)
      character(len=*), intent(in) :: path
      type(chain_scene), intent(out) :: scene
      logical, intent(out) :: ok
      character(len=max_message), intent(out) :: message
      integer :: unit, ios
      character(len=200) :: msg
      integer :: n_beads
      integer(int64) :: max_steps
      real(wp) :: mass, stiffness, exponent, damping, gap, striker_speed, t_end, rtol
      namelist /mpi_chain/ n_beads, mass, stiffness, exponent, damping, gap, &
         & striker_speed, t_end, rtol, max_steps

      ok = .false.
      message = ""
      n_beads = scene%n_beads
      mass = scene%mass
      stiffness = scene%stiffness
      exponent = scene%exponent
      damping = scene%damping
      gap = scene%gap
      striker_speed = scene%striker_speed
      t_end = scene%t_end
      rtol = scene%rtol
      max_steps = scene%max_steps
      open(newunit=unit, file=path, status="old", action="read", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "cannot open the scene " // trim(path) // ": " // trim(msg)
         return
      end if
      read(unit, nml=mpi_chain, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "the scene " // trim(path) // " has no valid &mpi_chain namelist: " &
            & // trim(msg)
         close(unit)
         return
      end if
      close(unit)
      scene = chain_scene(n_beads, mass, stiffness, exponent, damping, gap, &
         & striker_speed, t_end, rtol, max_steps)
      ok = .true.
   end subroutine read_chain_scene

   !> The system and options of a scene, checked by the library's one validator
   !> (`check_chain`) and for what this program needs besides: a finite end time > 0
   !> and at least as many beads as ranks. stat is hcimpact_ok or the status of the
   !> first problem, with a message that names it.
   subroutine scene_system(scene, n_ranks, chain, options, stat, message)
      type(chain_scene), intent(in) :: scene
      integer, intent(in) :: n_ranks
      type(chain_type), intent(out) :: chain
      type(chain_options), intent(out) :: options
      integer, intent(out) :: stat
      character(len=max_message), intent(out) :: message
      integer :: n

      stat = hcimpact_ok
      message = ""
      n = max(scene%n_beads, 0)
      allocate(chain%mass(n), chain%velocity(n), chain%gap(max(n - 1, 0)), &
         & chain%law(max(n - 1, 0)))
      chain%mass = scene%mass
      chain%velocity = 0.0_wp
      if (n >= 1) chain%velocity(1) = scene%striker_speed
      chain%gap = scene%gap
      chain%law = contact_law(scene%stiffness, scene%exponent, scene%damping)
      options%t_end = scene%t_end
      options%rtol = scene%rtol
      options%method = method_integrated
      options%max_steps = scene%max_steps
      call check_chain(chain, options, stat, message)
      if (stat /= hcimpact_ok) return
      ! check_chain takes t_end <= 0 for "until no contact can happen"; this program
      ! integrates a fixed interval
      if (.not. (scene%t_end > 0.0_wp .and. scene%t_end <= huge(1.0_wp))) then
         stat = hcimpact_err_domain
         message = "t_end must be finite and > 0"
         return
      end if
      if (scene%n_beads < n_ranks) then
         stat = hcimpact_err_size
         write(message, '(a, i0, a, i0, a)') "more ranks (", n_ranks, ") than beads (", &
            & scene%n_beads, "): every rank needs at least one bead"
         return
      end if
   end subroutine scene_system

   !> Kinetic plus elastic energy (J) of the chain (no walls, no gravity) with the
   !> displacements u (m, from the initial positions) and velocities v (m/s)
   pure function chain_energy(chain, u, v) result(energy)
      type(chain_type), intent(in) :: chain
      real(wp), intent(in) :: u(:), v(:)
      real(wp) :: energy
      type(contact_force_type) :: element
      integer :: i
      energy = 0.5_wp * sum(chain%mass * v**2)
      do i = 1, size(chain%gap)
         call contact_force_pair(chain%law(i)%stiffness, chain%law(i)%exponent, &
            & chain%law(i)%damping, -chain%gap(i), u(i), v(i), u(i + 1), v(i + 1), element)
         energy = energy + element%potential
      end do
   end function chain_energy

end module hcimpact_mpi_chain_scene
