! SPDX-License-Identifier: Apache-2.0
!> The scene of the distributed chain (hcimpact_mpi_chain, doc/mpi.md): a namelist
!> `&mpi_chain` that describes a chain of beads on a line, read from a file (or from
!> the lines of one: the scene runner hcimpact, which runs such a scene serially), and
!> the `chain_type` and `chain_options` it stands for. Nothing here knows about MPI:
!> every rank reads the same file and builds the same chain.
!>
!> A scene is uniform (one mass, one law and one gap for every bead and pair) unless
!> it gives patterns: up to `max_pattern` values that repeat along the chain (bead i
!> takes value mod(i - 1, p) + 1 of a pattern of p values; pair i likewise), so that a
!> chain of a million beads with two kinds of bead is two numbers long. Walls at
!> either end and gravity are those of the serial chain (`chain_type`).
module hcimpact_mpi_chain_scene
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, hcimpact_err_domain, hcimpact_err_size
   use hcimpact_chain_types, only : chain_type, chain_options, contact_law, check_chain, &
      & method_integrated, max_message
   use hcimpact_scene_model, only : scene_line_length
   use hcimpact_scene_lines, only : blank_comments, read_text_lines
   use hcimpact_scene_text, only : lower
   implicit none
   private

   public :: chain_scene, read_chain_scene, read_chain_lines, scene_system, max_pattern

   !> Most values of a pattern
   integer, parameter :: max_pattern = 1000

   !> A value not given (patterns, striker_speed): the namelist leaves it untouched
   real(wp), parameter :: unset = -huge(1.0_wp)

   !> A chain of beads on a line, with walls at its ends or not, under gravity or not
   type :: chain_scene
      !> Number of beads
      integer :: n_beads = 0
      !> The uniform chain: mass of a bead (kg), the law of every neighbouring pair
      !> (contact constant c in N/m^n, exponent n, damping b in s/m), the gap between
      !> neighbours (m) and the initial velocity of every bead (m/s)
      real(wp) :: mass = 0.0_wp, stiffness = 0.0_wp, exponent = 1.5_wp, &
         & damping = 0.0_wp, gap = 0.0_wp, velocity = 0.0_wp
      !> Patterns that replace the uniform values (module header); p values each
      real(wp) :: mass_pattern(max_pattern) = unset, velocity_pattern(max_pattern) = unset, &
         & stiffness_pattern(max_pattern) = unset, exponent_pattern(max_pattern) = unset, &
         & damping_pattern(max_pattern) = unset, gap_pattern(max_pattern) = unset
      !> Initial velocity of bead 1 (m/s), when given: replaces the one above
      real(wp) :: striker_speed = unset
      !> The walls: present or not, their laws and their gaps to the end beads (m)
      logical :: left_wall = .false., right_wall = .false.
      real(wp) :: left_stiffness = 0.0_wp, left_exponent = 1.5_wp, left_damping = 0.0_wp, &
         & left_gap = 0.0_wp, right_stiffness = 0.0_wp, right_exponent = 1.5_wp, &
         & right_damping = 0.0_wp, right_gap = 0.0_wp
      !> Constant acceleration along the line (m/s^2, negative: towards bead 1)
      real(wp) :: gravity = 0.0_wp
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
      integer :: unit, ios, n, k
      character(len=200) :: msg
      character(len=scene_line_length), allocatable :: lines(:), bare(:)
      character(len=:), allocatable :: error
      logical :: found
      ok = .false.
      message = ""
      open(newunit=unit, file=path, status="old", action="read", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         message = "cannot open the scene " // trim(path) // ": " // trim(msg)
         return
      end if
      ! (the limits of the scene runner's files: the same scene runs in both)
      call read_text_lines(unit, trim(path), lines, n, error)
      close(unit)
      if (allocated(error)) then
         message = "cannot read the scene " // error
         return
      end if
      ! the group there, outside comments and quotes: the compiler's reader, given no
      ! group, ends without an error, and given no lines at all it never ends
      bare = blank_comments(lines(1:n), keep_quoted=.false.)
      found = .false.
      do k = 1, n
         if (index(lower(bare(k)), "&mpi_chain") > 0) found = .true.
      end do
      if (.not. found) then
         message = "no &mpi_chain namelist in the scene " // trim(path)
         return
      end if
      call read_chain_lines(lines(1:n), scene, ios, msg)
      if (ios /= 0) then
         message = "the scene " // trim(path) // " has no valid &mpi_chain namelist: " &
            & // trim(msg)
         return
      end if
      ok = .true.
   end subroutine read_chain_scene

   !> Read the namelist &mpi_chain from the lines of a scene (an internal file); ios
   !> and msg those of the read.
   subroutine read_chain_lines(lines, scene, ios, msg)
      character(len=*), intent(in) :: lines(:)
      type(chain_scene), intent(out) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(out) :: msg
      ! (a comma before a comment at the end of a line: hcimpact_scene_lines)
      call read_namelist(scene, ios, msg, blank_comments(lines, keep_quoted=.true.))
   end subroutine read_chain_lines

   !> The one namelist &mpi_chain, read from the lines given
   subroutine read_namelist(scene, ios, msg, lines)
      type(chain_scene), intent(out) :: scene
      integer, intent(out) :: ios
      character(len=*), intent(out) :: msg
      character(len=*), intent(in) :: lines(:)
      integer :: n_beads
      integer(int64) :: max_steps
      real(wp) :: mass, stiffness, exponent, damping, gap, velocity, striker_speed, &
         & t_end, rtol, gravity, left_stiffness, left_exponent, left_damping, left_gap, &
         & right_stiffness, right_exponent, right_damping, right_gap
      real(wp) :: mass_pattern(max_pattern), velocity_pattern(max_pattern), &
         & stiffness_pattern(max_pattern), exponent_pattern(max_pattern), &
         & damping_pattern(max_pattern), gap_pattern(max_pattern)
      logical :: left_wall, right_wall
      namelist /mpi_chain/ n_beads, mass, stiffness, exponent, damping, gap, velocity, &
         & mass_pattern, velocity_pattern, stiffness_pattern, exponent_pattern, &
         & damping_pattern, gap_pattern, striker_speed, left_wall, left_stiffness, &
         & left_exponent, left_damping, left_gap, right_wall, right_stiffness, &
         & right_exponent, right_damping, right_gap, gravity, t_end, rtol, max_steps

      msg = ""
      n_beads = scene%n_beads
      mass = scene%mass
      stiffness = scene%stiffness
      exponent = scene%exponent
      damping = scene%damping
      gap = scene%gap
      velocity = scene%velocity
      mass_pattern = scene%mass_pattern
      velocity_pattern = scene%velocity_pattern
      stiffness_pattern = scene%stiffness_pattern
      exponent_pattern = scene%exponent_pattern
      damping_pattern = scene%damping_pattern
      gap_pattern = scene%gap_pattern
      striker_speed = scene%striker_speed
      left_wall = scene%left_wall
      left_stiffness = scene%left_stiffness
      left_exponent = scene%left_exponent
      left_damping = scene%left_damping
      left_gap = scene%left_gap
      right_wall = scene%right_wall
      right_stiffness = scene%right_stiffness
      right_exponent = scene%right_exponent
      right_damping = scene%right_damping
      right_gap = scene%right_gap
      gravity = scene%gravity
      t_end = scene%t_end
      rtol = scene%rtol
      max_steps = scene%max_steps
      read(lines, nml=mpi_chain, iostat=ios, iomsg=msg)
      if (ios /= 0) return
      scene = chain_scene(n_beads, mass, stiffness, exponent, damping, gap, velocity, &
         & mass_pattern, velocity_pattern, stiffness_pattern, exponent_pattern, &
         & damping_pattern, gap_pattern, striker_speed, left_wall, right_wall, &
         & left_stiffness, left_exponent, left_damping, left_gap, right_stiffness, &
         & right_exponent, right_damping, right_gap, gravity, t_end, rtol, max_steps)
   end subroutine read_namelist

   !> Number of values given in a pattern: up to its last value that is not unset
   !> (an unset value before it stays, and the validator refuses it)
   pure integer function pattern_length(pattern)
      real(wp), intent(in) :: pattern(:)
      integer :: k
      pattern_length = 0
      do k = size(pattern), 1, -1
         if (pattern(k) /= unset) then
            pattern_length = k
            return
         end if
      end do
   end function pattern_length

   !> values(i) = pattern(mod(i - 1, p) + 1), or the uniform value without a pattern
   pure subroutine spread(pattern, uniform, values)
      real(wp), intent(in) :: pattern(:), uniform
      real(wp), intent(out) :: values(:)
      integer :: p, i
      p = pattern_length(pattern)
      if (p == 0) then
         values = uniform
         return
      end if
      do i = 1, size(values)
         values(i) = pattern(mod(i - 1, p) + 1)
      end do
   end subroutine spread

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
      real(wp), allocatable :: stiffness(:), exponent(:), damping(:)
      integer :: n, i

      stat = hcimpact_ok
      message = ""
      n = max(scene%n_beads, 0)
      allocate(chain%mass(n), chain%velocity(n), chain%gap(max(n - 1, 0)), &
         & chain%law(max(n - 1, 0)), stiffness(max(n - 1, 0)), exponent(max(n - 1, 0)), &
         & damping(max(n - 1, 0)))
      call spread(scene%mass_pattern, scene%mass, chain%mass)
      call spread(scene%velocity_pattern, scene%velocity, chain%velocity)
      if (n >= 1 .and. scene%striker_speed /= unset) chain%velocity(1) = scene%striker_speed
      call spread(scene%gap_pattern, scene%gap, chain%gap)
      call spread(scene%stiffness_pattern, scene%stiffness, stiffness)
      call spread(scene%exponent_pattern, scene%exponent, exponent)
      call spread(scene%damping_pattern, scene%damping, damping)
      do i = 1, n - 1
         chain%law(i) = contact_law(stiffness(i), exponent(i), damping(i))
      end do
      chain%left_wall = scene%left_wall
      chain%right_wall = scene%right_wall
      chain%left_law = contact_law(scene%left_stiffness, scene%left_exponent, &
         & scene%left_damping)
      chain%right_law = contact_law(scene%right_stiffness, scene%right_exponent, &
         & scene%right_damping)
      chain%left_gap = scene%left_gap
      chain%right_gap = scene%right_gap
      chain%gravity = scene%gravity
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

end module hcimpact_mpi_chain_scene
