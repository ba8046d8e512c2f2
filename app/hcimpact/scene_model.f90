! SPDX-License-Identifier: Apache-2.0
!> A scene: what the runner is asked to compute, after reading and validation: one
!> impact (bodies, contact, damping, approach speeds), or a system of bodies on a line
!> (the `&bodies` group: masses, velocities, gaps, laws, walls, gravity); and the
!> outputs wanted.
!>
!> The outputs are named in scene files and on the command line by the words of
!> `output_names`; `figures` and `all` stand for sets of them. Each output belongs to
!> one kind of scene (`system_outputs`).
module hcimpact_scene_model
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp, nan
   use hcimpact_chain_types, only : contact_law, method_auto, integrator_bdf
   use hcimpact_scene_text, only : lower
   implicit none
   private

   public :: body_type, scene_type, wall_type, system_type, nan
   public :: n_outputs, output_names, output_files, output_descriptions, output_index
   public :: add_outputs, output_choices
   public :: out_summary, out_sweep, out_histories, out_phase, out_loops, out_restitution, &
      & out_lambertw, out_legacy, out_cvode, out_contacts, out_final, out_motion, &
      & out_system_sweep, out_impact_sweep
   public :: figure_outputs, system_outputs, default_scene_lines, max_speeds
   public :: scene_line_length, max_scene_lines, max_bodies
   public :: sweep_list, n_sweep_lists, sweep_names, sweep_unit, sweep_striker_speed, &
      & sweep_mass, sweep_gap, sweep_stiffness, sweep_exponent, sweep_b, sweep_restitution, &
      & sweep_gravity, sweep_left_gap, sweep_right_gap, sweep_left_b, sweep_right_b, &
      & sweep_left_stiffness, sweep_right_stiffness, sweep_left_exponent, &
      & sweep_right_exponent, sweep_t_end
   public :: unset_bits, is_unset


   !> The bits that mark a real a scene file did not set: a quiet NaN with a payload of
   !> its own, told apart from any value a file can hold (also "nan", whose payload
   !> differs) by its bits, never by a floating-point comparison. (The integer is
   !> exported: a NaN parameter may lose its payload on its way through a module file,
   !> so each module makes its real from these bits.)
   integer(int64), parameter :: unset_bits = int(z'7FF80000DEADBEEF', int64)

   !> Most bodies of a system in a scene file (the library takes any number)
   integer, parameter :: max_bodies = 100000

   !> The parameters a sweep of systems (&system_sweep) varies, in the order in which
   !> they combine (the first varies slowest) and in which their columns stand: body 1's
   !> speed, the mass of one body, and for every pair the gap, the stiffness c, the
   !> exponent n, the damping b (or b from a restitution), then gravity, the gaps of
   !> the left and the right wall to their end body, the walls' damping b, contact
   !> constant c and exponent n, and the end time
   integer, parameter :: n_sweep_lists = 17
   integer, parameter :: sweep_striker_speed = 1, sweep_mass = 2, sweep_gap = 3, &
      & sweep_stiffness = 4, sweep_exponent = 5, sweep_b = 6, sweep_restitution = 7, &
      & sweep_gravity = 8, sweep_left_gap = 9, sweep_right_gap = 10, sweep_left_b = 11, &
      & sweep_right_b = 12, sweep_left_stiffness = 13, sweep_right_stiffness = 14, &
      & sweep_left_exponent = 15, sweep_right_exponent = 16, sweep_t_end = 17
   !> Their names in &system_sweep (their units: `sweep_unit`)
   character(len=*), parameter :: sweep_names(n_sweep_lists) = [character(len=15) :: &
      & "striker_speed", "mass", "gap", "stiffness", "exponent", "b", "restitution", &
      & "gravity", "left_gap", "right_gap", "left_b", "right_b", "left_stiffness", &
      & "right_stiffness", "left_exponent", "right_exponent", "t_end"]

   !> Most approach speeds a scene may list
   integer, parameter :: max_speeds = 1000
   !> Longest line of a scene file (trailing blanks aside)
   integer, parameter :: scene_line_length = 1024
   !> Most lines of a scene file
   integer, parameter :: max_scene_lines = 10000

   !> The outputs a scene can ask for
   integer, parameter :: out_summary = 1, out_sweep = 2, out_histories = 3, &
      & out_phase = 4, out_loops = 5, out_restitution = 6, out_lambertw = 7, &
      & out_legacy = 8, out_cvode = 9, out_contacts = 10, out_final = 11, out_motion = 12, &
      & out_system_sweep = 13, out_impact_sweep = 14
   !> Number of outputs
   integer, parameter :: n_outputs = 14

   !> The built-in default scene, as the text of a scene file: the seed's steel ball
   !> (MODEL.md). example/scenes/steel_ball.nml holds the same text.
   character(len=80), parameter :: default_scene_lines(*) = [character(len=80) :: &
      & "! The seed's worked example (MODEL.md): a steel ball of 0.1 kg strikes a", &
      & "! massive steel plate; Hertz contact with the seed's printed constant, and", &
      & "! the damping of hardened steel.", &
      & "&scene", &
      & "  title = ""Steel ball on a massive steel plate (the seed's example)""", &
      & "  speeds = 0.5, 1, 2, 3, 4, 5          ! approach speeds, m/s", &
      & "  outputs = ""summary""", &
      & "/", &
      & "&body1", &
      & "  mass = 0.1                           ! kg", &
      & "/", &
      & "&contact", &
      & "  stiffness = 1.7135e10                ! c, N/m^n", &
      & "  exponent = 1.5                       ! n (Hertz)", &
      & "/", &
      & "&damping", &
      & "  b = 0.1                              ! s/m", &
      & "/"]

   !> Their names in scene files and on the command line
   character(len=*), parameter :: output_names(n_outputs) = [character(len=12) :: &
      & "summary", "sweep", "histories", "phase", "loops", "restitution", "lambertw", &
      & "legacy", "cvode", "contacts", "final", "motion", "system_sweep", "impact_sweep"]
   !> The files each writes in the results directory
   character(len=*), parameter :: output_files(n_outputs) = [character(len=44) :: &
      & "summary.csv", "sweep.csv", "histories.csv", "phase.csv", "loops.csv", &
      & "restitution.csv", "lambertw.csv velocity_z.csv motion_z.csv", "legacy.csv", &
      & "cvode.csv", "contacts.csv", "final.csv", "motion.csv forces.csv", "system_sweep.csv", &
      & "impact_sweep.csv"]
   !> What each is
   character(len=*), parameter :: output_descriptions(n_outputs) = [character(len=100) :: &
      & "per speed: k, energy lost, x_max, peak force and its time, the times", &
      & "the summary's columns on a fine grid of speeds (sweep_from .. sweep_to)", &
      & "time histories x(t), V(t), F(t) during contact, per speed", &
      & "phase trajectories V(x) on both branches, per speed", &
      & "force against deformation F(x) (hysteresis loops), per speed", &
      & "restitution k and energy loss 1 - k^2 against beta = b V", &
      & "both real branches of Lambert W; V(z) = -(1 + W(z))/b (seed eq. 14)", &
      & "damping rules of multibody codes against the exact beta(e), per speed", &
      & "SUNDIALS CVODE against the closed form: errors, time, counters", &
      & "a system: every contact (pair, times, speeds, peak force, how computed)", &
      & "a system: every body's state at the start and at the end", &
      & "a system: positions, velocities and pair forces against time", &
      & "a system: the whole run for each variation of &system_sweep (final velocities, ...)", &
      & "one impact for each parameter set of &impact_sweep (mass, c, n, b, speed): k, x_max, ..."]
   !> The outputs behind the figures (`figures`): the seed's figures 1-8 of one
   !> impact, figures 11-13 of a system of bodies
   logical, parameter :: figure_outputs(n_outputs) = [.true., .true., .true., .true., &
      & .true., .true., .true., .false., .false., .true., .true., .true., .false., .false.]
   !> The outputs of a system of bodies (the others are those of one impact)
   logical, parameter :: system_outputs(n_outputs) = [.false., .false., .false., .false., &
      & .false., .false., .false., .false., .false., .true., .true., .true., .true., .false.]

   !> One body. Unset reals are NaN.
   type :: body_type
      !> Whether the scene has this body (group present)
      logical :: present = .false.
      !> Mass in kg (given, or (4/3) pi R^3 rho)
      real(wp) :: mass = nan
      !> Radius of curvature at the contact in m (+inf: flat)
      real(wp) :: radius = nan
      !> Density in kg/m^3 (for the mass of a sphere)
      real(wp) :: density = nan
      !> Young's modulus in Pa
      real(wp) :: young = nan
      !> Poisson's ratio
      real(wp) :: poisson = nan
      !> Whether the mass was computed from radius and density
      logical :: mass_from_density = .false.
   end type body_type

   !> A wall at one end of a system of bodies
   type :: wall_type
      !> Whether there is one
      logical :: present = .false.
      !> Its contact law with the end body, and the gap between them (m)
      type(contact_law) :: law
      real(wp) :: gap = 0.0_wp
      !> Material (young in Pa, poisson), for Hertz's constant with the end body
      real(wp) :: young = nan, poisson = nan
      !> Target restitution and its speed (m/s), when b was derived from them
      real(wp) :: target_restitution = nan, reference_speed = nan
      !> How c and b were obtained
      character(len=:), allocatable :: law_origin, damping_origin
   end type wall_type

   !> The values one parameter of a system takes in its sweep
   type :: sweep_list
      real(wp), allocatable :: values(:)
   end type sweep_list

   !> A system of bodies on a line (the &bodies group; doc/scenes.md)
   type :: system_type
      !> Number of bodies
      integer :: n = 0
      !> Masses (kg), initial velocities (m/s), gaps between neighbours (m, n - 1)
      real(wp), allocatable :: mass(:), velocity(:), gap(:)
      !> Spheres: radius (m), density (kg/m^3), material (Pa, -); NaN when not given
      real(wp), allocatable :: radius(:), density(:), young(:), poisson(:)
      !> Whether the masses came from radius and density
      logical :: mass_from_density = .false.
      !> The laws of the neighbouring pairs (n - 1) and how they were obtained; whether
      !> their stiffnesses are Hertz's constants from the radii and materials
      type(contact_law), allocatable :: law(:)
      logical :: stiffness_from_materials = .false.
      character(len=:), allocatable :: law_origin, damping_origin
      !> Where b was derived from restitutions: the speed (m/s) at which they hold when
      !> every pair's is the same, and the restitution when every pair's is the same too
      real(wp) :: target_restitution = nan, reference_speed = nan
      !> The walls
      type(wall_type) :: left, right
      !> Constant acceleration along the line, m/s^2
      real(wp) :: gravity = 0.0_wp
      !> End time in s (<= 0: until no contact can happen again), CVODE's tolerance
      real(wp) :: t_end = -1.0_wp, rtol = 1.0e-10_wp
      !> hcimpact_chain_types' method and integrator codes
      integer :: method = method_auto, integrator = integrator_bdf
      !> The variations of the output system_sweep (&system_sweep): one list per
      !> parameter of `sweep_names` (empty when not varied); their product, or the lists
      !> side by side
      type(sweep_list) :: vary(n_sweep_lists)
      logical :: vary_product = .true.
      !> The bodies whose mass the list `mass` varies, and whose velocity
      !> `striker_speed` (each value given to all of them; set with the sweep)
      integer, allocatable :: vary_mass_body(:), vary_striker_body(:)
      !> The damping b (s/m) of each value of the list `restitution`, b = beta(e)/V at
      !> the speed `vary_at_speed` (m/s)
      real(wp), allocatable :: vary_restitution_b(:)
      real(wp) :: vary_at_speed = nan
   end type system_type

   !> A validated scene
   type :: scene_type
      !> Short name (the file's stem): the default results directory
      character(len=:), allocatable :: name
      !> Title for the console and the figures
      character(len=:), allocatable :: title
      !> Where it came from (a path, or "the built-in default scene")
      character(len=:), allocatable :: source
      !> The text it was read from
      character(len=scene_line_length), allocatable :: text(:)
      !> The moving body, and the other body (absent: a massive flat wall)
      type(body_type) :: body1, body2
      !> Material of the wall (young, poisson), when body2 is absent
      type(body_type) :: wall
      !> Whether two bodies collide (else body 1 strikes a wall)
      logical :: two_bodies = .false.
      !> Effective mass in kg
      real(wp) :: mass = nan
      !> Contact constant c in N/m^n and exponent n
      real(wp) :: stiffness = nan, exponent = nan
      !> How c was obtained
      character(len=:), allocatable :: stiffness_origin
      !> Damping b in s/m
      real(wp) :: damping = nan
      !> How b was obtained
      character(len=:), allocatable :: damping_origin
      !> Target restitution and its reference speed (m/s), when b was derived from them
      real(wp) :: target_restitution = nan, reference_speed = nan
      !> Approach speeds (relative speeds for two bodies) in m/s
      real(wp), allocatable :: speeds(:)
      !> Outputs wanted
      logical :: wanted(n_outputs) = .false.
      !> Samples per curve (histories, phase, loops) and per branch of W
      integer :: samples = 201
      !> The sweep's speeds in m/s
      real(wp), allocatable :: sweep(:)
      !> Largest beta of the restitution curves
      real(wp) :: beta_max = 10.0_wp
      !> Relative tolerances of the CVODE runs
      real(wp), allocatable :: tolerances(:)
      !> The parameter sets of the output impact_sweep (&impact_sweep): the effective
      !> masses (kg), stiffnesses (N/m^n), exponents, dampings (s/m) and approach speeds
      !> (m/s) it varies (empty: the scene's own value), every combination or side by side
      real(wp), allocatable :: vary_mass(:), vary_stiffness(:), vary_exponent(:), &
         & vary_damping(:), vary_speed(:)
      logical :: vary_product = .true.
      !> Whether the scene is a system of bodies (&bodies), and the system
      logical :: is_system = .false.
      type(system_type) :: system
   end type scene_type

contains

   !> The unit of a sweep's list (of &system_sweep or &impact_sweep) by its name; "-"
   !> for a number without one.
   pure function sweep_unit(name) result(unit)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: unit
      select case (name)
      case ("striker_speed", "speed")
         unit = "m/s"
      case ("mass")
         unit = "kg"
      case ("gap", "left_gap", "right_gap")
         unit = "m"
      case ("stiffness", "left_stiffness", "right_stiffness")
         unit = "N/m^n"
      case ("b", "left_b", "right_b")
         unit = "s/m"
      case ("t_end")
         unit = "s"
      case ("gravity")
         unit = "m/s^2"
      case default
         unit = "-"
      end select
   end function sweep_unit

   !> Whether a real is the mark of a value the file did not set (by its bits).
   elemental function is_unset(x) result(yes)
      real(wp), intent(in) :: x
      logical :: yes
      yes = transfer(x, 0_int64) == unset_bits
   end function is_unset

   !> Index of an output name, or 0.
   pure function output_index(name) result(k)
      character(len=*), intent(in) :: name
      integer :: k
      character(len=len(name)) :: low
      low = lower(adjustl(name))
      do k = 1, n_outputs
         if (trim(low) == trim(output_names(k))) return
      end do
      k = 0
   end function output_index

   !> Add the outputs named in `text` to `wanted`: words separated by commas or blanks
   !> ("summary,phase", "summary, phase"), `figures` and `all` standing for their sets.
   !> `unknown` is the first word that names no output ("" if none); `named` gets the
   !> outputs named by their own words (not through a set).
   pure subroutine add_outputs(text, wanted, unknown, named)
      !> The list
      character(len=*), intent(in) :: text
      !> The outputs wanted so far
      logical, intent(inout) :: wanted(n_outputs)
      !> The first unknown word, or ""
      character(len=:), allocatable, intent(out) :: unknown
      !> The outputs named so far by their own words
      logical, intent(inout), optional :: named(n_outputs)
      integer :: start, finish, k
      unknown = ""
      finish = 0
      do
         ! the next word: from the first character that is no separator to the next one
         start = finish + 1
         do while (start <= len(text))
            if (.not. is_separator(text(start:start))) exit
            start = start + 1
         end do
         if (start > len(text)) exit
         finish = start
         do while (finish < len(text))
            if (is_separator(text(finish + 1:finish + 1))) exit
            finish = finish + 1
         end do
         k = output_index(text(start:finish))
         if (k > 0) then
            wanted(k) = .true.
            if (present(named)) named(k) = .true.
         else if (lower(text(start:finish)) == "figures") then
            wanted = wanted .or. figure_outputs
         else if (lower(text(start:finish)) == "all") then
            wanted = .true.
         else
            unknown = text(start:finish)
            return
         end if
      end do
   contains
      pure logical function is_separator(c)
         character(len=1), intent(in) :: c
         is_separator = c == "," .or. c == " " .or. c == achar(9)
      end function is_separator
   end subroutine add_outputs

   !> The words an output list may hold, for messages.
   pure function output_choices() result(text)
      character(len=:), allocatable :: text
      integer :: k
      text = trim(output_names(1))
      do k = 2, n_outputs
         text = text // ", " // trim(output_names(k))
      end do
      text = text // ", or figures, all"
   end function output_choices

end module hcimpact_scene_model
