! SPDX-License-Identifier: Apache-2.0
!> Reading and validating scene files.
!>
!> A scene file is a sequence of Fortran namelist groups (`&name ... /`), in any order:
!> `&scene` (title, speeds, outputs), `&body1` (the moving body), `&body2` (the other
!> body; without it body 1 strikes a massive flat wall, whose material may be given in
!> `&wall`), `&contact` (stiffness and exponent, else Hertz's constant from the
!> materials), `&damping` (b, or a target restitution at a reference speed) and
!> `&sampling` (how finely the curves are sampled). `!` starts a comment.
!>
!> The file is first scanned as text: every group must be known, appear once, start on
!> its own line and end with `/`, and nothing else may stand outside the groups (a
!> compiler's namelist reader silently skips unknown groups). Each group is then read
!> with the compiler's namelist reader from its own lines. When that fails, the group is
!> read again line by line to find the line at fault, and the compiler's message
!> (iomsg) is quoted together with ours. Values are checked after reading. Every message
!> starts with `file:line:` and names the group.
module hcimpact_scene_reader
   use, intrinsic :: iso_fortran_env, only : int64
   use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_positive_inf
   use, intrinsic :: ieee_exceptions, only : ieee_get_halting_mode, ieee_set_halting_mode, &
      & ieee_set_flag, ieee_usual
   use hcimpact_kinds, only : wp
   use hcimpact_status, only : hcimpact_ok, status_message
   use hcimpact_hertz, only : hertz_constant, effective_mass
   use hcimpact_impact_model, only : damping_for_restitution
   use hcimpact_scene_model, only : scene_type, body_type, wall_type, system_type, nan, n_outputs, output_names, &
      & add_outputs, output_choices, out_summary, out_sweep, out_histories, out_phase, &
      & out_loops, out_legacy, out_cvode, max_speeds, default_scene_lines, &
      & scene_line_length, max_scene_lines, unset_bits, is_unset, max_bodies, system_outputs, &
      & out_contacts, out_final, out_motion, out_impact_sweep, n_sweep_lists, sweep_names, sweep_unit, &
      & sweep_striker_speed, sweep_mass, sweep_gap, sweep_stiffness, sweep_exponent, sweep_b, &
      & sweep_restitution, sweep_gravity, sweep_left_gap, sweep_right_gap, sweep_left_b, &
      & sweep_right_b, sweep_left_stiffness, sweep_right_stiffness, sweep_left_exponent, &
      & sweep_right_exponent, sweep_t_end
   use hcimpact_scene_bodies, only : read_bodies, bodies_text_length, body_mass => mass, &
      & body_radius => radius, body_density => density, body_young => young, &
      & body_poisson => poisson, body_velocity => velocity, body_gap => gap, &
      & body_stiffness => stiffness, body_exponent => exponent, body_b => b, &
      & body_restitution => restitution, body_at_speed => at_speed, &
      & body_gravity => gravity, body_t_end => t_end, body_rtol => rtol, &
      & body_method => method, body_integrator => integrator
   use hcimpact_scene_variations, only : read_variations, max_variations, &
      & variations_text_length, vary_speed => striker_speed, vary_gap => gap, &
      & vary_b => b, vary_combine => combine, vary_mass => mass, &
      & vary_stiffness => stiffness, vary_exponent => exponent, vary_impact_speed => speed, &
      & vary_restitution => restitution, vary_gravity => gravity, vary_at_speed => at_speed, &
      & vary_mass_body => mass_body, vary_left_gap => left_gap, &
      & vary_right_gap => right_gap, vary_left_b => left_b, vary_right_b => right_b, &
      & vary_t_end => t_end, vary_striker_body => striker_body, &
      & vary_left_stiffness => left_stiffness, vary_right_stiffness => right_stiffness, &
      & vary_left_exponent => left_exponent, vary_right_exponent => right_exponent
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, check_chain, &
      & max_chain_rtol, &
      & max_message, method_auto, method_exact, method_integrated, integrator_bdf, &
      & integrator_adams
   use hcimpact_scene_text, only : lower, str, real_str, join, printable, count_str
   use hcimpact_scene_system, only : directory_exists
   use hcimpact_scene_numbers, only : power_product, quotient_of, decimal_exponent
   use hcimpact_restitution_law, only : restitution_inverse
   use hcimpact_mpi_chain_scene, only : chain_scene, read_chain_lines, scene_system
   use hcimpact_scene_lines, only : blank_comments, read_text_lines
   implicit none
   private

   public :: read_scene_file, read_scene_lines, read_default_scene
   public :: group_names, group_variables

   !> The mark of a real not given (hcimpact_scene_model's unset_bits)
   real(wp), parameter :: unset = transfer(unset_bits, 1.0_wp)

   !> Most outputs and tolerances one list may hold
   integer, parameter :: max_list = 32

   integer, parameter :: g_scene = 1, g_body1 = 2, g_body2 = 3, g_wall = 4, g_contact = 5, &
      & g_damping = 6, g_sampling = 7, g_bodies = 8, g_left_wall = 9, g_right_wall = 10, &
      & g_system_sweep = 11, g_mpi_chain = 12, g_impact_sweep = 13, n_groups = 13
   !> The groups of a scene file
   character(len=*), parameter :: group_names(n_groups) = [character(len=12) :: "scene", &
      & "body1", "body2", "wall", "contact", "damping", "sampling", "bodies", "left_wall", &
      & "right_wall", "system_sweep", "mpi_chain", "impact_sweep"]
   !> The variables each group takes
   character(len=*), parameter :: group_variables(n_groups) = [character(len=256) :: &
      & "title, speeds, outputs", &
      & "mass, radius, density, young, poisson, flat", &
      & "mass, radius, density, young, poisson, flat", &
      & "young, poisson", &
      & "stiffness, exponent", &
      & "b, restitution, at_speed", &
      & "samples, sweep_from, sweep_to, sweep_count, sweep_spacing, beta_max, tolerances", &
      & "mass, radius, density, young, poisson, velocity, gap, stiffness, exponent, b, " &
      & // "restitution, at_speed, gravity, t_end, rtol, method, integrator", &
      & "stiffness, exponent, b, restitution, at_speed, gap, young, poisson", &
      & "stiffness, exponent, b, restitution, at_speed, gap, young, poisson", &
      & "striker_speed, striker_body, mass, mass_body, gap, stiffness, exponent, b, " &
      & // "restitution, at_speed, gravity, left_gap, right_gap, left_b, right_b, " &
      & // "left_stiffness, right_stiffness, left_exponent, right_exponent, t_end, " &
      & // "combine", &
      & "those of hcimpact_mpi_chain (doc/mpi.md)", &
      & "mass, stiffness, exponent, b, speed, combine"]
   !> Names that take a list of values
   character(len=*), parameter :: array_variables(3) = [character(len=10) :: "speeds", &
      & "outputs", "tolerances"]
   !> Names of &bodies that take a list (one value per body or per pair)
   character(len=*), parameter :: body_lists(12) = [character(len=11) :: "mass", "radius", &
      & "density", "young", "poisson", "velocity", "gap", "stiffness", "exponent", "b", &
      & "restitution", "at_speed"]
   !> Names whose values are text (they need quotes)
   character(len=*), parameter :: text_variables(6) = [character(len=13) :: "title", &
      & "outputs", "sweep_spacing", "method", "integrator", "combine"]

   !> Marks an integer the file did not set (a file that writes this value is caught by
   !> looking for the name in the text, `given`)
   integer, parameter :: unset_int = -huge(1)

   !> The bounds of a sweep's list (`check_sweep_list`): any finite value, >= 0, > 0,
   !> in (0, 1]
   integer, parameter :: any_finite = 0, not_negative = 1, positive = 2, unit_interval = 3
   !> Length of the text variables; a text that fills one may have been cut, and is
   !> refused
   integer, parameter :: text_length = 256
   !> Longest title
   integer, parameter :: max_title = 200
   !> Said of a value that is not finite (1e999 reads as inf)
   character(len=*), parameter :: finite_hint = " (inf, nan, or beyond the largest double," &
      & // " 1.8e308)"
   !> Names whose values are logicals
   character(len=*), parameter :: logical_variables(1) = [character(len=4) :: "flat"]

   !> Where a group stands in the source
   type :: group_place
      logical :: present = .false.
      integer :: first = 0, last = 0
   end type group_place

   !> The text of a scene and where its groups are
   type :: scene_source
      character(len=:), allocatable :: name
      !> The lines as written (shown in messages)
      character(len=scene_line_length), allocatable :: lines(:)
      !> The lines with their comments blanked (hcimpact_scene_lines' blank_comments):
      !> what the compiler's reader is given
      character(len=scene_line_length), allocatable :: code(:)
      !> The lines with their comments and the text between quotes blanked (the quotes
      !> stay): where names stand
      character(len=scene_line_length), allocatable :: bare(:)
      type(group_place) :: groups(n_groups)
   end type scene_source

   ! The namelist variables; shared by the groups that take the same names, and reset
   ! before each read.
   character(len=text_length) :: title
   real(wp) :: speeds(max_speeds)
   character(len=text_length) :: outputs(max_list)
   real(wp) :: mass, radius, density, young, poisson
   logical :: flat
   real(wp) :: stiffness, exponent
   real(wp) :: b, restitution, at_speed, gap
   integer :: samples, sweep_count
   real(wp) :: sweep_from, sweep_to, beta_max
   character(len=text_length) :: sweep_spacing
   real(wp) :: tolerances(max_list)

   namelist /scene/ title, speeds, outputs
   namelist /body1/ mass, radius, density, young, poisson, flat
   namelist /body2/ mass, radius, density, young, poisson, flat
   namelist /wall/ young, poisson
   namelist /contact/ stiffness, exponent
   namelist /damping/ b, restitution, at_speed
   namelist /sampling/ samples, sweep_from, sweep_to, sweep_count, sweep_spacing, beta_max, &
      & tolerances
   namelist /left_wall/ stiffness, exponent, b, restitution, at_speed, gap, young, poisson
   namelist /right_wall/ stiffness, exponent, b, restitution, at_speed, gap, young, poisson

contains

   !> Read and validate the scene file `path`. On failure `error` holds the message.
   !>
   !> The file is read whole, line by line in pieces, so that a line is never cut
   !> silently: a line longer than `scene_line_length` characters (trailing blanks
   !> aside), a file of more than `max_scene_lines` lines, or a character that is not
   !> text (a control character other than the tab, or bytes that are not UTF-8) is
   !> refused, with its line. Reading stops there: a device without end (/dev/zero) or
   !> a file of 100 MB is refused after at most max_scene_lines lines of at most
   !> scene_line_length characters.
   subroutine read_scene_file(path, sc, error, replace, add)
      !> Path of the scene file
      character(len=*), intent(in) :: path
      !> The scene
      type(scene_type), intent(out) :: sc
      !> Message naming the file, line and group; unallocated on success
      character(len=:), allocatable, intent(out) :: error
      !> Outputs wanted instead of the scene's (command line)
      logical, intent(in), optional :: replace(n_outputs)
      !> Outputs wanted besides the scene's (command line)
      logical, intent(in), optional :: add(n_outputs)
      character(len=scene_line_length), allocatable :: lines(:)
      character(len=:), allocatable :: shown
      character(len=512) :: msg
      integer :: unit, ios, n
      logical :: exists

      shown = printable(path)
      if (directory_exists(path)) then
         error = shown // ": is a directory, not a scene file"
         return
      end if
      inquire(file=path, exist=exists)
      if (.not. exists) then
         error = shown // ": no such scene file"
         return
      end if
      open(newunit=unit, file=path, status="old", action="read", form="formatted", &
         & access="sequential", iostat=ios, iomsg=msg)
      if (ios /= 0) then
         error = shown // ": cannot open the scene file (" // trim(msg) // ")"
         return
      end if
      call read_text_lines(unit, shown, lines, n, error)
      close(unit)
      if (allocated(error)) return
      if (all(len_trim(lines(1:n)) == 0)) then
         error = shown // ": the scene file is empty (hcimpact --show-default prints a" &
            & // " scene to start from)"
         return
      end if
      call read_scene_lines(lines(1:n), shown, printable(stem(path)), sc, error, replace, add)
   end subroutine read_scene_file

   !> The built-in default scene (`default_scene_lines`).
   subroutine read_default_scene(sc, error, replace, add)
      !> The scene
      type(scene_type), intent(out) :: sc
      !> Message; unallocated on success (the built-in scene is valid)
      character(len=:), allocatable, intent(out) :: error
      !> Outputs wanted instead of the scene's (command line)
      logical, intent(in), optional :: replace(n_outputs)
      !> Outputs wanted besides the scene's (command line)
      logical, intent(in), optional :: add(n_outputs)
      character(len=scene_line_length) :: lines(size(default_scene_lines))
      integer :: i
      do i = 1, size(default_scene_lines)
         lines(i) = default_scene_lines(i)
      end do
      call read_scene_lines(lines, "the built-in default scene", "steel_ball", sc, error, &
         & replace, add)
   end subroutine read_default_scene

   !> Read and validate a scene given as the lines of a scene file.
   subroutine read_scene_lines(lines, source_name, name, sc, error, replace, add)
      !> The lines
      character(len=*), intent(in) :: lines(:)
      !> Name of the source in messages (a path)
      character(len=*), intent(in) :: source_name
      !> Short name of the scene (the default results directory)
      character(len=*), intent(in) :: name
      !> The scene
      type(scene_type), intent(out) :: sc
      !> Message; unallocated on success
      character(len=:), allocatable, intent(out) :: error
      !> Outputs wanted instead of the scene's (command line)
      logical, intent(in), optional :: replace(n_outputs)
      !> Outputs wanted besides the scene's (command line)
      logical, intent(in), optional :: add(n_outputs)
      type(scene_source) :: src
      integer :: i

      src%name = source_name
      allocate(src%lines(size(lines)))
      do i = 1, size(lines)
         src%lines(i) = lines(i)
      end do
      ! where a comment starts is decided once, for the whole file (a quote may go on
      ! over lines)
      src%code = blank_comments(src%lines, keep_quoted=.true.)
      src%bare = blank_comments(src%lines, keep_quoted=.false.)
      sc%name = name
      sc%source = source_name
      sc%text = src%lines
      call scan_groups(src, error)
      if (allocated(error)) return
      call load_scene_group(src, sc, error)
      if (allocated(error)) return
      ! the command line's outputs, as far as they are of this scene's kind
      if (present(replace)) then
         if (any(replace)) then
            if (.not. any(replace .and. (system_outputs .eqv. sc%is_system))) then
               if (sc%is_system) then
                  error = source_name // ": --outputs: none of these outputs is for a" &
                     & // " system of bodies (" // kind_choices(.true.) // ")"
               else
                  error = source_name // ": --outputs: none of these outputs is for one" &
                     & // " impact (" // kind_choices(.false.) // ")"
               end if
               return
            end if
            sc%wanted = replace .and. (system_outputs .eqv. sc%is_system)
         end if
      end if
      if (present(add)) sc%wanted = sc%wanted .or. (add .and. (system_outputs .eqv. sc%is_system))
      if (sc%is_system .and. src%groups(g_impact_sweep)%present) then
         error = at(src, g_impact_sweep, "") // "&impact_sweep is for one impact: a system of" &
            & // " bodies is varied by &system_sweep (doc/scenes.md)"
         return
      end if
      if (src%groups(g_mpi_chain)%present) then
         call load_mpi_chain(src, sc, error)
         return
      end if
      if (sc%is_system) then
         call load_system(src, sc, error)
         return
      end if
      do i = g_bodies, g_system_sweep
         if (.not. src%groups(i)%present) cycle
         error = at(src, i, "") // "&" // trim(group_names(i)) // " belongs to a system of" &
            & // " bodies: give the bodies in &bodies (doc/scenes.md)"
         return
      end do
      call load_body(src, g_body1, sc%body1, error)
      if (allocated(error)) return
      call load_body(src, g_body2, sc%body2, error)
      if (allocated(error)) return
      call load_body(src, g_wall, sc%wall, error)
      if (allocated(error)) return
      call load_contact(src, sc, error)
      if (allocated(error)) return
      call load_damping(src, sc, error)
      if (allocated(error)) return
      call load_sampling(src, sc, error)
      if (allocated(error)) return
      call load_impact_variations(src, sc, error)
   end subroutine read_scene_lines

   ! ------------------------------------------------------------------------------
   ! The text scan
   ! ------------------------------------------------------------------------------

   !> Find the groups: known names, once each, on their own lines, closed by `/`, and
   !> nothing but comments outside them.
   subroutine scan_groups(src, error)
      type(scene_source), intent(inout) :: src
      character(len=:), allocatable, intent(out) :: error
      character(len=1) :: ch, quote
      character(len=scene_line_length) :: line
      character(len=:), allocatable :: gname
      integer :: l, i, j, n, open_group, gid, quote_line
      logical :: line_has_text

      open_group = 0
      quote = " "
      quote_line = 0
      do l = 1, size(src%code)
         ! comments are blanks here; messages show the line as written
         line = src%code(l)
         n = len_trim(line)
         i = 1
         line_has_text = .false.
         do while (i <= n)
            ch = line(i:i)
            if (quote /= " ") then
               if (ch == quote) quote = " "
               i = i + 1
               cycle
            end if
            if (open_group == 0) then
               if (ch == " " .or. ch == achar(9)) then
                  i = i + 1
                  cycle
               end if
               if (ch /= "&" .and. ch /= "$") then
                  error = place(src, l) // "text outside a group: '" // clip(src%lines(l)(i:)) &
                     & // "' (a group starts with &name and ends with /; ! starts a comment)"
                  return
               end if
               j = i + 1
               do while (j <= n)
                  if (.not. is_name_char(src%lines(l)(j:j))) exit
                  j = j + 1
               end do
               gname = lower(src%lines(l)(i + 1:j - 1))
               if (len(gname) == 0) then
                  error = place(src, l) // "'" // ch // "' without a group name (groups: " &
                     & // join(group_names, ", ") // ")"
                  return
               end if
               if (line_has_text) then
                  error = place(src, l) // "start the group &" // gname // " on a line of its own"
                  return
               end if
               gid = group_id(gname)
               if (gid == 0) then
                  error = place(src, l) // "unknown group &" // gname // " (a scene file has " &
                     & // join(group_names, ", ") // ")"
                  return
               end if
               if (src%groups(gid)%present) then
                  error = place(src, l) // "a second &" // gname // " group (the first is at line " &
                     & // str(src%groups(gid)%first) // ")"
                  return
               end if
               src%groups(gid)%present = .true.
               src%groups(gid)%first = l
               open_group = gid
               line_has_text = .true.
               i = j
               cycle
            end if
            ! inside a group
            line_has_text = .true.
            if (ch == '"' .or. ch == "'") then
               quote = ch
               quote_line = l
            else if (ch == "/") then
               src%groups(open_group)%last = l
               open_group = 0
            else if (ch == "&" .or. ch == "$") then
               j = i + 1
               do while (j <= n)
                  if (.not. is_name_char(src%lines(l)(j:j))) exit
                  j = j + 1
               end do
               if (lower(src%lines(l)(i + 1:j - 1)) == "end") then
                  src%groups(open_group)%last = l
                  open_group = 0
                  i = j
                  cycle
               end if
               error = place(src, src%groups(open_group)%first) // "the group &" &
                  & // trim(group_names(open_group)) // " is not closed with / before line " &
                  & // str(l)
               return
            end if
            i = i + 1
         end do
         if (quote /= " " .and. open_group == 0) then
            error = place(src, l) // "unbalanced quote " // quote
            return
         end if
      end do
      if (quote /= " ") then
         ! a text never closed takes the rest of the file, the group's / included
         error = place(src, quote_line) // "the text in quotes that starts here is never" &
            & // " closed with " // quote
         return
      end if
      if (open_group /= 0) then
         error = place(src, src%groups(open_group)%first) // "the group &" &
            & // trim(group_names(open_group)) // " is never closed with /"
         return
      end if
   end subroutine scan_groups

   !> Whether c may appear in a name.
   elemental function is_name_char(c) result(yes)
      character(len=1), intent(in) :: c
      logical :: yes
      yes = (c >= "a" .and. c <= "z") .or. (c >= "A" .and. c <= "Z") &
         & .or. (c >= "0" .and. c <= "9") .or. c == "_"
   end function is_name_char

   !> Index of a group name, or 0.
   pure function group_id(name) result(gid)
      character(len=*), intent(in) :: name
      integer :: gid
      do gid = 1, n_groups
         if (trim(group_names(gid)) == name) return
      end do
      gid = 0
   end function group_id

   !> "file:line: " or "file: " (line 0).
   function place(src, line) result(text)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: line
      character(len=:), allocatable :: text
      if (line > 0) then
         text = src%name // ":" // str(line) // ": "
      else
         text = src%name // ": "
      end if
   end function place

   !> "file:line: &group: " for the line of `variable` in the group (its first line if
   !> the variable does not appear).
   function at(src, gid, variable) result(text)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: variable
      character(len=:), allocatable :: text
      integer :: line
      line = src%groups(gid)%first
      if (len(variable) > 0) line = variable_line(src, gid, variable)
      text = place(src, line) // "&" // trim(group_names(gid)) // ": "
   end function at

   !> The line of the group where `variable =` (or `variable(`) stands, else its first line.
   function variable_line(src, gid, variable) result(line)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: variable
      integer :: line
      integer :: l
      do l = src%groups(gid)%first, src%groups(gid)%last
         if (name_position(src%bare(l), variable) > 0) then
            line = l
            return
         end if
      end do
      line = src%groups(gid)%first
   end function variable_line

   !> Position of `name` on the line as a name being assigned (followed by = or ();
   !> 0 if it is not there. The line's comments and quoted text are blanks
   !> (scene_source's bare).
   pure function name_position(line, name) result(pos)
      character(len=*), intent(in) :: line, name
      integer :: pos
      character(len=len(line)) :: low
      integer :: i, j, n
      logical :: before_ok
      low = lower(line)
      n = len_trim(low)
      pos = 0
      i = 1
      do
         j = index(low(i:n), lower(name))
         if (j == 0) return
         j = i + j - 1
         before_ok = j == 1
         if (.not. before_ok) before_ok = .not. is_name_char(low(j - 1:j - 1))
         i = j + len(name)
         if (before_ok) then
            do while (i <= n)
               if (low(i:i) /= " " .and. low(i:i) /= achar(9)) exit
               i = i + 1
            end do
            if (i <= n) then
               if (low(i:i) == "=" .or. low(i:i) == "(") then
                  pos = j
                  return
               end if
            end if
         end if
         if (i > n) return
      end do
   end function name_position

   !> At most 40 characters of a text.
   pure function clip(text) result(out)
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: out
      if (len_trim(text) > 40) then
         out = text(1:37) // "..."
      else
         out = trim(text)
      end if
   end function clip

   !> The stem of a path: the file name without directory and extension.
   pure function stem(path) result(name)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: name
      integer :: i, j
      i = index(path, "/", back=.true.)
      name = path(i + 1:)
      j = index(name, ".", back=.true.)
      if (j > 1) name = name(1:j - 1)
      if (len(name) == 0) name = "scene"
   end function stem

   ! ------------------------------------------------------------------------------
   ! The namelist reads
   ! ------------------------------------------------------------------------------

   !> Set every namelist variable to "not given".
   subroutine reset_variables()
      title = ""
      speeds = unset
      outputs = ""
      mass = unset
      radius = unset
      density = unset
      young = unset
      poisson = unset
      flat = .false.
      stiffness = unset
      exponent = unset
      b = unset
      restitution = unset
      at_speed = unset
      gap = unset
      samples = unset_int
      sweep_count = unset_int
      sweep_from = unset
      sweep_to = unset
      beta_max = unset
      sweep_spacing = ""
      tolerances = unset
   end subroutine reset_variables

   !> Read one group from the records `rec` with the compiler's namelist reader.
   !>
   !> The compiler's reader converts numbers with the C library's strtod, which raises
   !> the overflow exception for a number beyond the largest double (1e999, read as
   !> inf and refused by `take`): the traps of the Debug build are held off while it
   !> reads, and the flags it raised are cleared.
   subroutine read_records(gid, rec, ios, msg)
      integer, intent(in) :: gid
      character(len=*), intent(in) :: rec(:)
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      logical :: halting(size(ieee_usual))
      call reset_variables()
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      select case (gid)
      case (g_scene)
         read(rec, nml=scene, iostat=ios, iomsg=msg)
      case (g_body1)
         read(rec, nml=body1, iostat=ios, iomsg=msg)
      case (g_body2)
         read(rec, nml=body2, iostat=ios, iomsg=msg)
      case (g_wall)
         read(rec, nml=wall, iostat=ios, iomsg=msg)
      case (g_contact)
         read(rec, nml=contact, iostat=ios, iomsg=msg)
      case (g_damping)
         read(rec, nml=damping, iostat=ios, iomsg=msg)
      case (g_bodies)
         call read_bodies(rec, ios, msg)
      case (g_left_wall)
         read(rec, nml=left_wall, iostat=ios, iomsg=msg)
      case (g_right_wall)
         read(rec, nml=right_wall, iostat=ios, iomsg=msg)
      case (g_system_sweep)
         call read_variations(rec, .false., ios, msg)
      case (g_impact_sweep)
         call read_variations(rec, .true., ios, msg)
      case default
         read(rec, nml=sampling, iostat=ios, iomsg=msg)
      end select
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
   end subroutine read_records

   !> Read the group `gid` into the namelist variables (all unset if the group is
   !> absent); on failure find the line at fault and explain.
   subroutine read_group(src, gid, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=:), allocatable, intent(out) :: error
      character(len=scene_line_length), allocatable :: rec(:)
      character(len=512) :: msg, first_msg
      integer :: ios, first, last, k, bad

      character(len=scene_line_length), allocatable :: lines(:)

      call reset_variables()
      if (.not. src%groups(gid)%present) return
      first = src%groups(gid)%first
      last = src%groups(gid)%last
      ! (a comma before a comment at the end of a line: hcimpact_scene_lines)
      lines = src%code(first:last)
      msg = ""
      call read_records(gid, lines, ios, msg)
      if (ios == 0) then
         call check_repeated_names(src, gid, error)
         if (allocated(error)) call reset_variables()
         return
      end if
      first_msg = msg
      ! the first prefix of the group (closed by an extra "/") that fails holds the fault
      bad = first
      do k = first, last
         rec = [lines(1:k - first + 1), repeat(" ", scene_line_length)]
         rec(size(rec)) = "/"
         msg = ""
         call read_records(gid, rec, ios, msg)
         if (ios /= 0) then
            bad = k
            first_msg = msg
            exit
         end if
      end do
      error = place(src, bad) // "&" // trim(group_names(gid)) // ": " &
         & // explain(src%lines(bad), src%bare(bad), group_text(src, first, bad), gid, &
         & trim(first_msg)) &
         & // " (Fortran: " // trim(first_msg) // ")"
      call reset_variables()
   end subroutine read_group

   !> A name given twice in the group: the compiler's reader would keep the last value
   !> silently (b = 0.1d0, b = 0.2 gives b = 0.2). An indexed name, speeds(2) = 1,
   !> counts as its name.
   subroutine check_repeated_names(src, gid, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=:), allocatable, intent(out) :: error
      character(len=scene_line_length) :: bare
      character(len=scene_line_length), allocatable :: names(:), more(:)
      integer, allocatable :: at_line(:), more_lines(:)
      integer :: l, i, n, k, name_start, name_end
      allocate(names(16), at_line(16))
      n = 0
      do l = src%groups(gid)%first, src%groups(gid)%last
         ! quoted text (which may go on over lines) and comments are blanks
         bare = src%bare(l)
         ! each "=" assigns the name before it (and its index, if any)
         do i = 1, len_trim(bare)
            if (bare(i:i) /= "=") cycle
            call name_before(bare(1:i - 1), name_start, name_end)
            if (name_end < name_start) cycle
            do k = 1, n
               if (lower(trim(names(k))) == lower(bare(name_start:name_end))) then
                  error = place(src, l) // "&" // trim(group_names(gid)) // ": " &
                     & // bare(name_start:name_end) // " is given twice (lines " &
                     & // str(at_line(k)) // " and " // str(l) // "): give each name once" &
                     & // " (a list of values, e.g. speeds = 1, 2, 3, in one place)"
                  return
               end if
            end do
            if (n == size(names)) then
               allocate(more(2 * n), more_lines(2 * n))
               more(1:n) = names
               more_lines(1:n) = at_line
               call move_alloc(more, names)
               call move_alloc(more_lines, at_line)
            end if
            n = n + 1
            names(n) = bare(name_start:name_end)
            at_line(n) = l
         end do
      end do
   end subroutine check_repeated_names

   !> The name that ends `text` (blanks and an index in parentheses after it skipped):
   !> text(first:last), or last < first if there is none.
   pure subroutine name_before(text, first, last)
      character(len=*), intent(in) :: text
      integer, intent(out) :: first, last
      last = len_trim(text)
      if (last >= 1) then
         if (text(last:last) == ")") last = index(text(1:last), "(", back=.true.) - 1
      end if
      last = len_trim(text(1:max(last, 0)))
      first = last + 1
      do while (first > 1)
         if (.not. is_name_char(text(first - 1:first - 1))) exit
         first = first - 1
      end do
   end subroutine name_before

   !> Our reading of a namelist error message on a line of group gid.
   function explain(line, bare, context, gid, msg) result(text)
      !> The line at fault, as written (shown)
      character(len=*), intent(in) :: line
      !> The same line with its comments and quoted text blanked (scene_source's bare)
      character(len=*), intent(in) :: bare
      !> The group's text up to and including that line, without comments
      character(len=*), intent(in) :: context
      integer, intent(in) :: gid
      character(len=*), intent(in) :: msg
      character(len=:), allocatable :: text
      character(len=*), parameter :: no_match = "Cannot match namelist object name "
      ! &system_sweep's lists of bodies' indices (body_list_text)
      character(len=*), parameter :: body_index_lists(2) = [character(len=12) :: &
         & "mass_body", "striker_body"]
      character(len=:), allocatable :: token, owner
      integer :: p

      p = index(msg, no_match)
      if (p > 0) then
         token = trim(msg(p + len(no_match):))
         if (name_position(bare, token) > 0) then
            text = "unknown name '" // token // "' (&" // trim(group_names(gid)) // " takes " &
               & // trim(group_variables(gid)) // ")"
            return
         end if
         owner = assigned_name(context, token)
         if (len(owner) > 0 .and. gid == g_bodies .and. any(lower(owner) == body_lists) &
            & .and. is_number(token)) then
            text = "too many values for " // owner // " (at most " // str(max_bodies) &
               & // " bodies)"
         else if (len(owner) > 0 .and. gid == g_system_sweep .and. &
            & any(lower(owner) == body_index_lists)) then
            if (is_number(token) .or. scan(token, "0123456789+-.") == 1) then
               text = "too many values for " // owner // " (at most " // str(max_bodies) &
                  & // " bodies)"
            else
               text = body_list_text(lower(owner)) // " ('" // token // "' is not read)"
            end if
         else if (len(owner) > 0 .and. gid == g_system_sweep .and. lower(owner) == "at_speed") then
            text = "at_speed takes one value, the speed in m/s at which the restitutions" &
               & // " hold ('" // token // "' is one too many)"
         else if (len(owner) > 0 .and. (gid == g_system_sweep .or. gid == g_impact_sweep) &
            & .and. lower(owner) /= "combine" .and. (is_number(token) .or. &
            & scan(token, "0123456789+-.") == 1)) then
            ! (a name never begins as a number does: gfortran names the values past the
            ! list's end, from the second past it on two of them run together, 1e-41e-4)
            text = "too many values for " // owner // " (at most " // str(max_variations) &
               & // ")"
         else if (len(owner) > 0 .and. any(lower(owner) == array_variables) &
            & .and. (is_number(token) .or. token(1:1) == '"' .or. token(1:1) == "'")) then
            text = "too many values for " // owner // " (at most " // str(max_speeds) &
               & // " speeds, " // str(max_list) // " outputs or tolerances)"
         else if (len(owner) == 0) then
            text = "'" // token // "' is neither a name of the group nor a value (&" &
               & // trim(group_names(gid)) // " takes " // trim(group_variables(gid)) // ")"
         else if (any(lower(owner) == text_variables)) then
            text = "the text '" // token // "' of " // owner // " must be in quotes, e.g. " &
               & // owner // " = """ // token // """"
         else if (any(lower(owner) == logical_variables)) then
            text = owner // " takes .true. or .false., not '" // token // "'"
         else if (is_number(token)) then
            text = owner // " takes a single value here, '" // token // "' is one too many"
         else
            text = "'" // token // "' is not a number (the value of " // owner // ")"
         end if
         return
      end if
      p = index(msg, "Bad data for namelist object ")
      if (p > 0) then
         ! a list that reads on into the next line's name: that name is unknown
         owner = unknown_name(bare, gid)
         if (len(owner) > 0) then
            text = "unknown name '" // owner // "' (&" // trim(group_names(gid)) // " takes " &
               & // trim(group_variables(gid)) // ")"
            return
         end if
         token = trim(msg(p + len("Bad data for namelist object "):))
         text = "a value of " // token // " is not of the right kind: " // clip(adjustl(line))
         if (gid == g_system_sweep .and. any(lower(token) == body_index_lists)) &
            & text = body_list_text(lower(token)) // ": " // clip(adjustl(line))
         return
      end if
      if (index(msg, "Integer overflow") > 0) then
         text = "a whole number on this line is too large: " // clip(adjustl(line))
         return
      end if
      p = index(msg, "Bad real number")
      if (p == 0) p = index(msg, "Bad integer")
      if (p == 0) p = index(msg, "Bad logical")
      if (p > 0) then
         text = "a value on this line is not of the right kind: " // clip(adjustl(line))
         return
      end if
      if (index(msg, "out of range") > 0 .or. index(msg, "Repeat count too large") > 0) then
         if (gid == g_system_sweep .or. gid == g_impact_sweep) then
            text = "too many values, or an index out of range (at most " &
               & // str(max_variations) // " values per list)"
         else
            text = "too many values, or an index out of range (at most " // str(max_speeds) &
               & // " speeds, " // str(max_list) // " outputs or tolerances, " &
               & // str(max_bodies) // " bodies)"
         end if
         return
      end if
      if (index(msg, "End of file") > 0) then
         text = "the group ends too early (a quote or a value not closed?)"
         return
      end if
      text = "cannot read this line: " // clip(adjustl(line))
   end function explain

   !> The first name assigned on the line (name = ...) that group gid does not take, or
   !> "". The line's comments and quoted text are blanks (scene_source's bare).
   function unknown_name(line, gid) result(name)
      character(len=*), intent(in) :: line
      integer, intent(in) :: gid
      character(len=:), allocatable :: name
      character(len=len(line)) :: bare
      character(len=len(group_variables(gid)) + 2) :: known
      integer :: i, first, last
      name = ""
      bare = lower(line)
      known = ", " // lower(group_variables(gid))
      do i = 1, len_trim(bare)
         if (bare(i:i) /= "=") cycle
         call name_before(bare(1:i - 1), first, last)
         if (last < first) cycle
         if (index(trim(known) // ",", ", " // bare(first:last) // ",") == 0) then
            name = trim(line(first:last))
            return
         end if
      end do
   end function unknown_name

   !> Lines first..last of the source joined by blanks, quoted text kept and comments
   !> dropped.
   function group_text(src, first, last) result(text)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: first, last
      character(len=:), allocatable :: text
      integer :: l
      text = ""
      do l = first, last
         text = text // " " // trim(src%code(l))
      end do
   end function group_text

   !> The name assigned before the last occurrence of the value `token` ("" if none).
   function assigned_name(line, token) result(name)
      character(len=*), intent(in) :: line, token
      character(len=:), allocatable :: name
      character(len=len(line)) :: low
      integer :: p, e, i, j
      low = lower(line)
      p = index(low, lower(token), back=.true.)
      if (p == 0) p = len_trim(low) + 1
      e = index(low(1:p - 1), "=", back=.true.)
      name = ""
      if (e == 0) return
      j = e - 1
      do while (j >= 1)
         if (low(j:j) /= " ") exit
         j = j - 1
      end do
      if (j >= 1) then
         if (low(j:j) == ")") j = index(low(1:j), "(", back=.true.) - 1
      end if
      i = j
      do while (i >= 1)
         if (.not. is_name_char(low(i:i))) exit
         i = i - 1
      end do
      if (j >= i + 1) name = low(i + 1:j)
   end function assigned_name

   !> Whether the text reads as a number (the traps held off as in read_records: 1e999
   !> reads as inf).
   function is_number(text) result(yes)
      character(len=*), intent(in) :: text
      logical :: yes
      real(wp) :: x
      integer :: ios
      logical :: halting(size(ieee_usual))
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      read(text, *, iostat=ios) x
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
      yes = ios == 0
   end function is_number

   ! ------------------------------------------------------------------------------
   ! The groups, checked
   ! ------------------------------------------------------------------------------

   !> A real the file set: finite (error otherwise); NaN when not given.
   subroutine take(src, gid, name, value, out, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: value
      real(wp), intent(out) :: out
      character(len=:), allocatable, intent(inout) :: error
      out = nan
      if (allocated(error)) return
      if (is_unset(value)) return
      if (.not. ieee_is_finite(value)) then
         error = at(src, gid, name) // name // " is not a finite number" // finite_hint
         return
      end if
      out = value
   end subroutine take

   !> Whether the group assigns `name` in the text (for integers, whose mark of "not
   !> given" a file could write).
   function given(src, gid, name) result(yes)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: name
      logical :: yes
      integer :: l
      yes = .false.
      if (.not. src%groups(gid)%present) return
      do l = src%groups(gid)%first, src%groups(gid)%last
         yes = name_position(src%bare(l), name) > 0
         if (yes) return
      end do
   end function given

   !> The number of values given in a list (speeds, tolerances): the leading ones; a
   !> value left out before a given one (speeds = 1, , 3) is an error.
   subroutine count_list(src, gid, name, values, n, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: values(:)
      integer, intent(out) :: n
      character(len=:), allocatable, intent(out) :: error
      n = 0
      do while (n < size(values))
         if (is_unset(values(n + 1))) exit
         n = n + 1
      end do
      if (n < size(values)) then
         if (.not. all(is_unset(values(n + 1:)))) then
            error = at(src, gid, name) // name // " has a gap: value " // str(n + 1) &
               & // " is not given"
            return
         end if
      end if
   end subroutine count_list

   !> The &scene group: title, speeds, outputs.
   subroutine load_scene_group(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      integer :: i, n
      character(len=:), allocatable :: unknown
      logical :: named(n_outputs)

      call read_group(src, g_scene, error)
      if (allocated(error)) return
      if (len_trim(title) > max_title) then
         error = at(src, g_scene, "title") // "the title has more than " // str(max_title) &
            & // " characters"
         return
      end if
      sc%title = trim(title)
      if (len(sc%title) == 0) sc%title = sc%name
      call count_list(src, g_scene, "speeds", speeds, n, error)
      if (allocated(error)) return
      do i = 1, n
         if (.not. ieee_is_finite(speeds(i))) then
            error = at(src, g_scene, "speeds") // "speed " // str(i) // " is not a finite number" &
               & // finite_hint
            return
         end if
         if (.not. speeds(i) > 0.0_wp) then
            error = at(src, g_scene, "speeds") // "speed " // str(i) // " = " &
               & // real_str(speeds(i), 6) // " m/s: approach speeds must be positive"
            return
         end if
      end do
      sc%speeds = speeds(1:n)
      ! outputs: a list of texts, each a name or names separated by commas
      sc%wanted = .false.
      named = .false.
      do i = 1, max_list
         if (len_trim(outputs(i)) == len(outputs(i))) then
            error = at(src, g_scene, "outputs") // "output text " // str(i) // " is longer than " &
               & // str(len(outputs(i)) - 1) // " characters"
            return
         end if
         call add_outputs(outputs(i), sc%wanted, unknown, named)
         if (len(unknown) > 0) then
            error = at(src, g_scene, "outputs") // "unknown output '" // unknown &
               & // "' (outputs: " // output_choices() // "; outputs = ""summary"", ""phase""" &
               & // " or outputs = ""summary,phase"")"
            return
         end if
      end do
      ! each output belongs to one kind of scene: one impact, or a system (&bodies)
      sc%is_system = src%groups(g_bodies)%present .or. src%groups(g_mpi_chain)%present
      do i = 1, n_outputs
         if (.not. named(i) .or. (system_outputs(i) .eqv. sc%is_system)) cycle
         if (sc%is_system) then
            error = at(src, g_scene, "outputs") // "the output '" // trim(output_names(i)) &
               & // "' is for one impact: a system of bodies (&bodies) has the outputs " &
               & // kind_choices(.true.)
         else
            error = at(src, g_scene, "outputs") // "the output '" // trim(output_names(i)) &
               & // "' is for a system of bodies (&bodies): one impact has the outputs " &
               & // kind_choices(.false.)
         end if
         return
      end do
      sc%wanted = sc%wanted .and. (system_outputs .eqv. sc%is_system)
      call default_outputs(sc)
   end subroutine load_scene_group

   !> The outputs of one kind of scene, for messages: "contacts, final, motion".
   pure function kind_choices(system) result(text)
      logical, intent(in) :: system
      character(len=:), allocatable :: text
      integer :: i
      text = ""
      do i = 1, n_outputs
         if (system_outputs(i) .neqv. system) cycle
         if (len(text) > 0) text = text // ", "
         text = text // trim(output_names(i))
      end do
   end function kind_choices

   !> The default outputs of a scene that asks for none: the summary of one impact, the
   !> contacts and final state of a system.
   pure subroutine default_outputs(sc)
      type(scene_type), intent(inout) :: sc
      if (any(sc%wanted)) return
      if (sc%is_system) then
         sc%wanted([out_contacts, out_final]) = .true.
      else
         sc%wanted(out_summary) = .true.
      end if
   end subroutine default_outputs

   !> &body1, &body2 or &wall: masses and materials.
   subroutine load_body(src, gid, body, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      type(body_type), intent(inout) :: body
      character(len=:), allocatable, intent(out) :: error
      real(wp), parameter :: pi = acos(-1.0_wp)

      call read_group(src, gid, error)
      if (allocated(error)) return
      body%present = src%groups(gid)%present
      if (.not. body%present) then
         if (gid == g_body1) then
            error = src%name // ": no &body1 group: the moving body needs its mass, e.g." &
               & // " &body1 mass = 0.1 / (kg), or its radius and density"
         end if
         return
      end if
      call take(src, gid, "mass", mass, body%mass, error)
      call take(src, gid, "radius", radius, body%radius, error)
      call take(src, gid, "density", density, body%density, error)
      call take(src, gid, "young", young, body%young, error)
      call take(src, gid, "poisson", poisson, body%poisson, error)
      if (allocated(error)) return
      if (gid == g_body2 .and. src%groups(g_wall)%present) then
         error = at(src, gid, "") // "give either &body2 (a second body) or &wall (a massive" &
            & // " flat obstacle), not both"
         return
      end if
      if (.not. ieee_is_nan(body%young)) then
         if (.not. body%young > 0.0_wp) then
            error = at(src, gid, "young") // "young = " // real_str(body%young, 6) &
               & // ": Young's modulus (Pa) must be positive"
            return
         end if
      end if
      if (.not. ieee_is_nan(body%poisson)) then
         if (.not. (body%poisson > -1.0_wp .and. body%poisson <= 0.5_wp)) then
            error = at(src, gid, "poisson") // "poisson = " // real_str(body%poisson, 6) &
               & // ": Poisson's ratio must lie in (-1, 0.5]"
            return
         end if
      end if
      if (gid == g_wall) then
         body%radius = ieee_value(1.0_wp, ieee_positive_inf)
         return
      end if
      if (.not. ieee_is_nan(body%radius)) then
         if (.not. body%radius > 0.0_wp) then
            error = at(src, gid, "radius") // "radius = " // real_str(body%radius, 6) &
               & // " m: must be positive"
            return
         end if
         if (flat) then
            error = at(src, gid, "flat") // "give radius or flat = .true., not both"
            return
         end if
      end if
      if (.not. ieee_is_nan(body%density)) then
         if (.not. body%density > 0.0_wp) then
            error = at(src, gid, "density") // "density = " // real_str(body%density, 6) &
               & // " kg/m^3: must be positive"
            return
         end if
      end if
      if (.not. ieee_is_nan(body%mass)) then
         if (.not. body%mass > 0.0_wp) then
            error = at(src, gid, "mass") // "mass = " // real_str(body%mass, 6) &
               & // " kg: must be positive"
            return
         end if
         if (.not. ieee_is_nan(body%density)) then
            error = at(src, gid, "density") // "give mass, or radius and density, not both"
            return
         end if
      else if (.not. ieee_is_nan(body%density)) then
         if (ieee_is_nan(body%radius)) then
            error = at(src, gid, "density") // "the mass from the density needs the radius" &
               & // " (a sphere, m = 4/3 pi R^3 rho): give radius too, or mass"
            return
         end if
         ! without overflow or underflow on the way (a radius of 1e-110 or 1e110)
         body%mass = power_product([4.0_wp / 3.0_wp * pi, body%radius, body%density], &
            & [1.0_wp, 3.0_wp, 1.0_wp])
         if (.not. (body%mass >= tiny(1.0_wp) .and. body%mass <= huge(1.0_wp))) then
            error = at(src, gid, "density") // "the mass of this sphere, 4/3 pi R^3 rho, about" &
               & // " 1e" // str(decimal_exponent([4.0_wp / 3.0_wp * pi, body%radius, &
               & body%density], [1.0_wp, 3.0_wp, 1.0_wp])) // " kg, lies outside the range of" &
               & // " doubles (1e-308 to 1e308): check radius and density"
            return
         end if
         body%mass_from_density = .true.
      else
         error = at(src, gid, "") // "missing mass: give mass (kg), or radius (m) and density" &
            & // " (kg/m^3)"
         return
      end if
      if (flat) body%radius = ieee_value(1.0_wp, ieee_positive_inf)
   end subroutine load_body

   !> &contact: the stiffness c and exponent n, or Hertz's constant from the materials.
   !> Also sets the effective mass.
   subroutine load_contact(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      character(len=:), allocatable :: missing, other
      type(body_type) :: obstacle

      sc%two_bodies = sc%body2%present
      if (sc%two_bodies) then
         sc%mass = effective_mass(sc%body1%mass, sc%body2%mass)
         obstacle = sc%body2
         other = "body2"
      else
         sc%mass = sc%body1%mass
         obstacle = sc%wall
         obstacle%radius = ieee_value(1.0_wp, ieee_positive_inf)
         other = "wall"
      end if
      call read_group(src, g_contact, error)
      if (allocated(error)) return
      call take(src, g_contact, "stiffness", stiffness, sc%stiffness, error)
      call take(src, g_contact, "exponent", exponent, sc%exponent, error)
      if (allocated(error)) return
      if (.not. ieee_is_nan(sc%exponent)) then
         if (.not. sc%exponent > 0.0_wp) then
            error = at(src, g_contact, "exponent") // "exponent = " // real_str(sc%exponent, 6) &
               & // ": the exponent n of f = c x^n must be positive"
            return
         end if
      end if
      if (.not. ieee_is_nan(sc%stiffness)) then
         if (.not. sc%stiffness > 0.0_wp) then
            error = at(src, g_contact, "stiffness") // "stiffness = " &
               & // real_str(sc%stiffness, 6) // ": the contact constant c (N/m^n) must be positive"
            return
         end if
         if (ieee_is_nan(sc%exponent)) then
            sc%exponent = 1.5_wp
            sc%stiffness_origin = "c given; n = 3/2 (Hertz) as no exponent is given"
         else
            sc%stiffness_origin = "given"
         end if
         return
      end if
      ! Hertz's constant from the materials and radii
      if (.not. ieee_is_nan(sc%exponent)) then
         if (sc%exponent /= 1.5_wp) then
            error = at(src, g_contact, "exponent") // "without a stiffness, c is Hertz's constant," &
               & // " which is for n = 1.5; give the stiffness for n = " // real_str(sc%exponent, 6)
            return
         end if
      end if
      missing = ""
      if (ieee_is_nan(sc%body1%radius)) missing = missing // " body1 radius (or flat),"
      if (ieee_is_nan(sc%body1%young)) missing = missing // " body1 young,"
      if (ieee_is_nan(sc%body1%poisson)) missing = missing // " body1 poisson,"
      if (ieee_is_nan(obstacle%radius)) missing = missing // " " // other // " radius (or flat),"
      if (ieee_is_nan(obstacle%young)) missing = missing // " " // other // " young,"
      if (ieee_is_nan(obstacle%poisson)) missing = missing // " " // other // " poisson,"
      if (len(missing) > 0) then
         missing = missing(2:len(missing) - 1)
         if (src%groups(g_contact)%present) then
            error = at(src, g_contact, "") // "no stiffness given, and Hertz's constant needs " &
               & // missing
         else
            error = src%name // ": no &contact group: give &contact stiffness = ... (N/m^n)," &
               & // " exponent = ... /, or the materials for Hertz's constant (missing: " &
               & // missing // ")"
         end if
         return
      end if
      sc%exponent = 1.5_wp
      sc%stiffness = hertz_constant(sc%body1%young, sc%body1%poisson, sc%body1%radius, &
         & obstacle%young, obstacle%poisson, obstacle%radius)
      if (ieee_is_nan(sc%stiffness)) then
         error = src%name // ": Hertz's constant cannot be formed from these radii (two flat" &
            & // " faces?): give &contact stiffness"
         return
      end if
      sc%stiffness_origin = "c: Hertz's constant from the radii and materials"
   end subroutine load_contact

   !> &damping: b, or a target restitution at a reference speed.
   subroutine load_damping(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      real(wp) :: bb, e, v

      if (.not. src%groups(g_damping)%present) then
         error = src%name // ": no &damping group: give &damping b = 0.1 / (s/m; 0 for Hertz's" &
            & // " elastic impact), or &damping restitution = 0.8, at_speed = 1 /"
         return
      end if
      call read_group(src, g_damping, error)
      if (allocated(error)) return
      call take(src, g_damping, "b", b, bb, error)
      call take(src, g_damping, "restitution", restitution, e, error)
      call take(src, g_damping, "at_speed", at_speed, v, error)
      if (allocated(error)) return
      if (.not. ieee_is_nan(bb)) then
         if (.not. (ieee_is_nan(e) .and. ieee_is_nan(v))) then
            error = at(src, g_damping, "restitution") // "give b, or restitution and at_speed," &
               & // " not both"
            return
         end if
         if (bb < 0.0_wp) then
            error = at(src, g_damping, "b") // "b = " // real_str(bb, 6) &
               & // " s/m: the damping must not be negative"
            return
         end if
         sc%damping = bb
         sc%damping_origin = "given"
         return
      end if
      if (ieee_is_nan(e)) then
         if (.not. ieee_is_nan(v)) then
            error = at(src, g_damping, "at_speed") // "at_speed needs the restitution wanted at" &
               & // " that speed: give restitution too"
         else
            error = at(src, g_damping, "") // "missing damping: give b (s/m), or restitution" &
               & // " and at_speed (m/s)"
         end if
         return
      end if
      if (ieee_is_nan(v)) then
         error = at(src, g_damping, "restitution") // "restitution needs the speed at which it" &
            & // " holds: give at_speed (m/s)"
         return
      end if
      call restitution_damping(src, g_damping, e, v, sc%damping, error)
      if (allocated(error)) return
      sc%target_restitution = e
      sc%reference_speed = v
      sc%damping_origin = "the exact damping for the restitution e = " // real_str(e, 6) &
         & // " at V = " // real_str(v, 6) // " m/s: b = beta(e)/V"
   end subroutine load_damping

   !> The damping b that gives the restitution e at the speed v (b = beta(e)/V, the
   !> library's damping_for_restitution); an error where e is not in (0, 1], v is not
   !> positive and finite, b would exceed the largest double or the library finds none.
   subroutine restitution_damping(src, gid, e, v, b, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      real(wp), intent(in) :: e, v
      real(wp), intent(out) :: b
      character(len=:), allocatable, intent(out) :: error
      integer :: stat
      logical :: ok
      b = nan
      ! (finite first, alone: an ordered comparison with NaN would trap in the Debug
      ! build, and Fortran's .and. may evaluate both operands)
      ok = ieee_is_finite(e)
      if (ok) ok = e > 0.0_wp .and. e <= 1.0_wp
      if (.not. ok) then
         error = at(src, gid, "restitution") // "restitution = " // real_str(e, 6) &
            & // ": a coefficient of restitution lies in (0, 1]"
         return
      end if
      ok = ieee_is_finite(v)
      if (ok) ok = v > 0.0_wp
      if (.not. ok) then
         error = at(src, gid, "at_speed") // "at_speed = " // real_str(v, 6) &
            & // " m/s: must be positive and finite"
         return
      end if
      ! b = beta(e)/V must be a double (the library's damping_for_restitution raises
      ! the overflow exception, which the Debug build traps, before it says so)
      if (.not. quotient_of(restitution_inverse(e), v) <= huge(1.0_wp)) then
         error = at(src, gid, "at_speed") // "the damping for restitution = " &
            & // real_str(e, 10) // " at " // real_str(v, 6) // " m/s, b = beta(e)/V, exceeds" &
            & // " the largest double (1.8e308): a larger at_speed or restitution"
         return
      end if
      call damping_for_restitution(e, v, b, stat, min_velocity=tiny(1.0_wp))
      if (stat /= hcimpact_ok) error = at(src, gid, "restitution") // "no damping for this" &
         & // " restitution: " // status_message(stat)
   end subroutine restitution_damping

   !> &sampling, and the checks that involve several groups.
   subroutine load_sampling(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      real(wp) :: from, to, bmax, x
      integer :: i, n

      call read_group(src, g_sampling, error)
      if (allocated(error)) return
      if (samples /= unset_int .or. given(src, g_sampling, "samples")) then
         if (samples < 11 .or. samples > 100001) then
            error = at(src, g_sampling, "samples") // "samples = " // str(samples) &
               & // ": between 11 and 100001 points per curve"
            return
         end if
         sc%samples = samples
      end if
      call take(src, g_sampling, "beta_max", beta_max, bmax, error)
      call take(src, g_sampling, "sweep_from", sweep_from, from, error)
      call take(src, g_sampling, "sweep_to", sweep_to, to, error)
      if (allocated(error)) return
      if (.not. ieee_is_nan(bmax)) then
         if (.not. (bmax > 0.0_wp .and. bmax <= 1.0e6_wp)) then
            error = at(src, g_sampling, "beta_max") // "beta_max = " // real_str(bmax, 6) &
               & // ": must lie in (0, 1e6]"
            return
         end if
         sc%beta_max = bmax
      end if

      ! the sweep: defaults from the speeds
      if (ieee_is_nan(to) .and. size(sc%speeds) > 0) to = maxval(sc%speeds)
      if (ieee_is_nan(from) .and. .not. ieee_is_nan(to)) from = to / 100.0_wp
      n = 100
      if (sweep_count /= unset_int .or. given(src, g_sampling, "sweep_count")) n = sweep_count
      if (sc%wanted(out_sweep)) then
         if (ieee_is_nan(to)) then
            error = at(src, g_sampling, "sweep_to") // "the sweep needs its range: give" &
               & // " sweep_from and sweep_to (m/s) in &sampling, or speeds in &scene"
            return
         end if
         if (.not. from > 0.0_wp) then
            error = at(src, g_sampling, "sweep_from") // "sweep_from = " // real_str(from, 6) &
               & // " m/s: must be positive"
            return
         end if
         if (.not. to > from) then
            error = at(src, g_sampling, "sweep_to") // "sweep_to = " // real_str(to, 6) &
               & // " m/s must exceed sweep_from = " // real_str(from, 6) // " m/s"
            return
         end if
         if (n < 2 .or. n > 100000) then
            error = at(src, g_sampling, "sweep_count") // "sweep_count = " // str(n) &
               & // ": between 2 and 100000 speeds"
            return
         end if
         if (len_trim(sweep_spacing) == len(sweep_spacing)) then
            error = at(src, g_sampling, "sweep_spacing") // "sweep_spacing: use ""linear""" &
               & // " or ""log"""
            return
         end if
         if (len_trim(sweep_spacing) == 0 .and. given(src, g_sampling, "sweep_spacing")) then
            error = at(src, g_sampling, "sweep_spacing") // "sweep_spacing = '': an empty" &
               & // " value (leave sweep_spacing out for ""linear""): use ""linear"" or ""log"""
            return
         end if
         allocate(sc%sweep(n))
         select case (lower(trim(adjustl(sweep_spacing))))
         case ("", "linear")
            do i = 1, n
               x = real(i - 1, wp) / real(n - 1, wp)
               sc%sweep(i) = from + (to - from) * x
            end do
         case ("log")
            ! log(to) - log(from), not log(to/from): the quotient overflows for a sweep
            ! from 1e-300 to 1e300
            do i = 1, n
               x = real(i - 1, wp) / real(n - 1, wp)
               sc%sweep(i) = exp(log(from) + (log(to) - log(from)) * x)
            end do
         case default
            error = at(src, g_sampling, "sweep_spacing") // "sweep_spacing = '" &
               & // trim(sweep_spacing) // "': use ""linear"" or ""log"""
            return
         end select
         sc%sweep(1) = from
         sc%sweep(n) = to
      else
         allocate(sc%sweep(0))
      end if

      ! CVODE tolerances
      call count_list(src, g_sampling, "tolerances", tolerances, n, error)
      if (allocated(error)) return
      if (n == 0) then
         sc%tolerances = [1.0e-4_wp, 1.0e-6_wp, 1.0e-8_wp, 1.0e-10_wp]
      else
         sc%tolerances = tolerances(1:n)
         do i = 1, n
            if (.not. ieee_is_finite(sc%tolerances(i))) then
               error = at(src, g_sampling, "tolerances") // "tolerance " // str(i) &
                  & // " is not a finite number" // finite_hint
               return
            end if
            if (.not. (sc%tolerances(i) >= 1.0e-14_wp .and. sc%tolerances(i) <= 0.1_wp)) then
               error = at(src, g_sampling, "tolerances") // "tolerance " // str(i) // " = " &
                  & // real_str(sc%tolerances(i), 6) // ": relative tolerances lie in [1e-14, 0.1]"
               return
            end if
         end do
      end if

      ! b V, formed for every speed, must be a double
      if (sc%damping > 0.0_wp) then
         do i = 1, size(sc%speeds) + size(sc%sweep)
            if (i <= size(sc%speeds)) then
               x = sc%speeds(i)
            else
               x = sc%sweep(i - size(sc%speeds))
            end if
            if (power_product([sc%damping, x], [1.0_wp, 1.0_wp]) <= huge(1.0_wp)) cycle
            error = at(src, g_damping, "") // "b V = " // real_str(sc%damping, 6) // " s/m x " &
               & // real_str(x, 6) // " m/s exceeds the largest double (1.8e308)"
            return
         end do
      end if

      ! outputs that need approach speeds
      if (size(sc%speeds) == 0) then
         do i = 1, n_outputs
            if (.not. sc%wanted(i)) cycle
            if (any(i == [out_summary, out_histories, out_phase, out_loops, out_legacy, &
               & out_cvode])) then
               error = at(src, g_scene, "speeds") // "the output '" // trim(output_names(i)) &
                  & // "' needs approach speeds: give speeds = ... (m/s) in &scene"
               return
            end if
         end do
      end if
   end subroutine load_sampling

   ! ------------------------------------------------------------------------------
   ! A system of bodies on a line
   ! ------------------------------------------------------------------------------

   !> A system of bodies (&bodies, &left_wall, &right_wall, and &sampling's samples);
   !> the groups of one impact are refused. The library's validator has the last word
   !> (check_chain), after the checks that name a line.
   subroutine load_system(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      real(wp), parameter :: pi = acos(-1.0_wp)
      type(system_type) :: sys
      type(chain_type) :: chain
      type(chain_options) :: options
      character(len=max_message) :: message
      real(wp), allocatable :: c(:), e(:), v(:)
      integer :: gid, n, count_mass, count_radius, count_density, i, stat

      do gid = g_body1, g_damping
         if (.not. src%groups(gid)%present) cycle
         error = at(src, gid, "") // "&" // trim(group_names(gid)) // " is for one impact:" &
            & // " a system of bodies has everything in &bodies (and its walls in" &
            & // " &left_wall, &right_wall): give one kind of scene or the other"
         return
      end do
      if (size(sc%speeds) > 0) then
         error = at(src, g_scene, "speeds") // "speeds are the approach speeds of one impact:" &
            & // " the bodies of &bodies have their own velocities"
         return
      end if
      call read_group(src, g_bodies, error)
      if (allocated(error)) return

      ! how many bodies: the longest list of one value per body (one value stands for
      ! every body, except velocity); the masses, or the radii with the density
      call count_list(src, g_bodies, "mass", body_mass, count_mass, error)
      if (allocated(error)) return
      call count_list(src, g_bodies, "radius", body_radius, count_radius, error)
      if (allocated(error)) return
      call count_list(src, g_bodies, "density", body_density, count_density, error)
      if (allocated(error)) return
      n = max(count_mass, count_radius, count_density)
      call count_list(src, g_bodies, "young", body_young, i, error)
      if (allocated(error)) return
      n = max(n, i)
      call count_list(src, g_bodies, "poisson", body_poisson, i, error)
      if (allocated(error)) return
      n = max(n, i)
      call count_list(src, g_bodies, "velocity", body_velocity, i, error)
      if (allocated(error)) return
      n = max(n, i)
      if (count_mass > 0) then
         if (count_density > 0) then
            error = at(src, g_bodies, "density") // "give mass, or radius and density, not both"
            return
         end if
      else if (.not. (count_radius > 0 .and. count_density > 0)) then
         error = at(src, g_bodies, "") // "no masses: give mass = 0.1, 0.1, 0.1 (kg, one per" &
            & // " body, left to right), or radius (m) and density (kg/m^3)"
         return
      end if
      sys%n = n
      call per_body("radius", body_radius, sys%radius, 0.0_wp, .false.)
      call per_body("density", body_density, sys%density, 0.0_wp, .false.)
      call per_body("young", body_young, sys%young, 0.0_wp, .false.)
      call per_body("poisson", body_poisson, sys%poisson, -1.0_wp, .false.)
      if (allocated(error)) return
      if (count_mass > 0) then
         call per_body("mass", body_mass, sys%mass, 0.0_wp, .false.)
         if (allocated(error)) return
      else
         allocate(sys%mass(n))
         do i = 1, n
            ! without overflow or underflow on the way
            sys%mass(i) = power_product([4.0_wp / 3.0_wp * pi, sys%radius(i), &
               & sys%density(i)], [1.0_wp, 3.0_wp, 1.0_wp])
            if (.not. (sys%mass(i) >= tiny(1.0_wp) .and. sys%mass(i) <= huge(1.0_wp))) then
               error = at(src, g_bodies, "density") // "the mass of sphere " // str(i) &
                  & // ", 4/3 pi R^3 rho, lies outside the range of doubles: check radius" &
                  & // " and density"
               return
            end if
         end do
         sys%mass_from_density = .true.
      end if
      do i = 1, n
         ! (NaN where not given: no ordered comparison with it, which would trap)
         if (ieee_is_nan(sys%poisson(i))) cycle
         if (sys%poisson(i) > 0.5_wp) then
            error = at(src, g_bodies, "poisson") // "Poisson's ratio must lie in (-1, 0.5]"
            return
         end if
      end do
      call per_body("velocity", body_velocity, sys%velocity, -huge(1.0_wp), .true.)
      if (allocated(error)) return

      ! the neighbouring pairs: gaps and laws
      call per_pair(src, g_bodies, "gap", body_gap, n - 1, 0.0_wp, .true., sys%gap, error)
      if (allocated(error)) return
      call per_pair(src, g_bodies, "exponent", body_exponent, n - 1, 1.5_wp, .false., e, error)
      if (allocated(error)) return
      call per_pair(src, g_bodies, "stiffness", body_stiffness, n - 1, nan, .false., c, &
         & error)
      if (allocated(error)) return
      if (n > 1) then
         if (all(ieee_is_nan(c))) then
            ! Hertz's constants of neighbouring spheres from their radii and materials
            if (any(ieee_is_nan(sys%radius)) .or. any(ieee_is_nan(sys%young)) .or. &
               & any(ieee_is_nan(sys%poisson))) then
               error = at(src, g_bodies, "") // "no stiffness given, and Hertz's constants" &
                  & // " need every body's radius, young and poisson"
               return
            end if
            if (any(e /= 1.5_wp)) then
               error = at(src, g_bodies, "exponent") // "without a stiffness, c is Hertz's" &
                  & // " constant, which is for n = 1.5: give the stiffness for other exponents"
               return
            end if
            c = hertz_constant(sys%young(1:n - 1), sys%poisson(1:n - 1), sys%radius(1:n - 1), &
               & sys%young(2:n), sys%poisson(2:n), sys%radius(2:n))
            sys%stiffness_from_materials = .true.
            sys%law_origin = "Hertz's constants from the radii and materials"
         else
            sys%law_origin = "given"
         end if
      end if
      call pair_damping(src, g_bodies, body_b, body_restitution, body_at_speed, n - 1, v, &
         & sys%damping_origin, sys%target_restitution, sys%reference_speed, error)
      if (allocated(error)) return
      allocate(sys%law(n - 1))
      do i = 1, n - 1
         sys%law(i) = contact_law(stiffness=c(i), exponent=e(i), damping=v(i))
      end do

      ! the whole system
      call take(src, g_bodies, "gravity", body_gravity, sys%gravity, error)
      call take(src, g_bodies, "t_end", body_t_end, sys%t_end, error)
      call take(src, g_bodies, "rtol", body_rtol, sys%rtol, error)
      if (allocated(error)) return
      if (ieee_is_nan(sys%gravity)) sys%gravity = 0.0_wp
      if (ieee_is_nan(sys%t_end)) then
         sys%t_end = -1.0_wp
      else if (.not. sys%t_end > 0.0_wp) then
         error = at(src, g_bodies, "t_end") // "t_end = " // real_str(sys%t_end, 6) &
            & // " s: must be positive (leave it out to run until no contact can happen again)"
         return
      end if
      if (ieee_is_nan(sys%rtol)) then
         sys%rtol = 1.0e-10_wp
      else if (.not. (sys%rtol >= 1.0e-14_wp .and. sys%rtol <= max_chain_rtol)) then
         error = at(src, g_bodies, "rtol") // "rtol = " // real_str(sys%rtol, 6) &
            & // ": the relative tolerance of a system lies in [1e-14, " &
            & // real_str(max_chain_rtol, 6) // "]"
         return
      end if
      call choose(src, "method", body_method, [character(len=10) :: "auto", "exact", &
         & "integrated"], [method_auto, method_exact, method_integrated], sys%method, error)
      if (allocated(error)) return
      call choose(src, "integrator", body_integrator, [character(len=10) :: "bdf", "adams"], &
         & [integrator_bdf, integrator_adams], sys%integrator, error)
      if (allocated(error)) return

      call load_wall(src, g_left_wall, sys, 1, sys%left, error)
      if (allocated(error)) return
      call load_wall(src, g_right_wall, sys, n, sys%right, error)
      if (allocated(error)) return
      call system_sampling(src, sc, error)
      if (allocated(error)) return

      ! the library's own check of what will be computed
      chain%mass = sys%mass
      chain%velocity = sys%velocity
      chain%gap = sys%gap
      chain%law = sys%law
      chain%left_wall = sys%left%present
      chain%left_law = sys%left%law
      chain%left_gap = sys%left%gap
      chain%right_wall = sys%right%present
      chain%right_law = sys%right%law
      chain%right_gap = sys%right%gap
      chain%gravity = sys%gravity
      options%t_end = sys%t_end
      options%rtol = sys%rtol
      options%method = sys%method
      options%integrator = sys%integrator
      call load_variations(src, sys, error)
      if (allocated(error)) return
      ! a sweep of end times gives every run its own (each checked by the library as it
      ! runs): the system itself, when nothing else runs it, with the shortest of them
      if (size(sys%vary(sweep_t_end)%values) > 0 .and. .not. any(sc%wanted([out_contacts, &
         & out_final, out_motion]))) options%t_end = minval(sys%vary(sweep_t_end)%values)
      call check_chain(chain, options, stat, message)
      if (stat /= hcimpact_ok) then
         error = at(src, g_bodies, "") // trim(message) // " (" // status_message(stat) // ")"
         return
      end if
      sc%system = sys

   contains

      !> One value per body (or one for all) of the list `values`, each above `lowest`
      !> (finite); NaN for every body when the list is not given. `required`: the list
      !> must be given, one value per body.
      subroutine per_body(name, values, out, lowest, required)
         character(len=*), intent(in) :: name
         real(wp), intent(in) :: values(:)
         real(wp), allocatable, intent(out) :: out(:)
         real(wp), intent(in) :: lowest
         logical, intent(in) :: required
         integer :: count, j
         if (allocated(error)) return
         call count_list(src, g_bodies, name, values, count, error)
         if (allocated(error)) return
         allocate(out(n))
         if (required .and. count /= n) then
            error = at(src, g_bodies, name) // name // ": " // count_str(count, "value") &
               & // " for " // str(n) // " bodies: give one per body, left to right (a repeat count" &
               & // " helps: " // name // " = 1, " // str(max(n - 1, 1)) // "*0)"
            return
         end if
         if (count == 0) then
            out = nan
            return
         end if
         if (count /= 1 .and. count /= n) then
            error = at(src, g_bodies, name) // name // ": " // count_str(count, "value") &
               & // " for " // str(n) // " bodies: give one per body, or one for all"
            return
         end if
         do j = 1, count
            if (.not. ieee_is_finite(values(j))) then
               error = at(src, g_bodies, name) // name // " value " // str(j) &
                  & // " is not a finite number" // finite_hint
               return
            end if
            if (.not. values(j) > lowest) then
               error = at(src, g_bodies, name) // name // " value " // str(j) // " = " &
                  & // real_str(values(j), 6) // ": must be above " // real_str(lowest, 6)
               return
            end if
         end do
         if (count == 1) then
            out = values(1)
         else
            out = values(1:n)
         end if
      end subroutine per_body

   end subroutine load_system

   !> &mpi_chain (doc/mpi.md): the scene of the distributed chain hcimpact_mpi_chain,
   !> read and checked by the same module (hcimpact_mpi_chain_scene, the library's
   !> `check_chain`), here a system of bodies that `chain_simulate` computes serially
   !> with the method 'integrated', as `hcimpact_mpi_chain --serial` does. It goes
   !> with &scene and &sampling only; its max_steps is that program's (the runner's
   !> runs keep the library's bound).
   subroutine load_mpi_chain(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      type(chain_scene) :: scene
      type(system_type) :: sys
      type(chain_type) :: chain
      type(chain_options) :: options
      character(len=max_message) :: message
      character(len=512) :: msg
      character(len=*), parameter :: origin = "given in &mpi_chain"
      logical :: halting(size(ieee_usual))
      integer :: gid, ios, stat

      do gid = g_body1, g_system_sweep
         if (gid == g_sampling .or. .not. src%groups(gid)%present) cycle
         error = at(src, gid, "") // "&" // trim(group_names(gid)) // " cannot go with" &
            & // " &mpi_chain, which describes the whole chain (doc/mpi.md)"
         return
      end do
      if (size(sc%speeds) > 0) then
         error = at(src, g_scene, "speeds") // "speeds are the approach speeds of one impact:" &
            & // " the beads of &mpi_chain have their own velocities"
         return
      end if
      ! (the number reader's overflow exception held off, as in read_records)
      call ieee_get_halting_mode(ieee_usual, halting)
      call ieee_set_halting_mode(ieee_usual, .false.)
      call read_chain_lines(src%lines(src%groups(g_mpi_chain)%first: &
         & src%groups(g_mpi_chain)%last), scene, ios, msg)
      call ieee_set_flag(ieee_usual, .false.)
      call ieee_set_halting_mode(ieee_usual, halting)
      if (ios /= 0) then
         error = at(src, g_mpi_chain, "") // "the namelist cannot be read: " // trim(msg)
         return
      end if
      call scene_system(scene, 1, chain, options, stat, message)
      if (stat /= hcimpact_ok) then
         error = at(src, g_mpi_chain, "") // trim(message) // " (" // status_message(stat) &
            & // ")"
         return
      end if
      sys%n = size(chain%mass)
      sys%mass = chain%mass
      sys%velocity = chain%velocity
      sys%gap = chain%gap
      sys%law = chain%law
      allocate(sys%radius(sys%n), sys%density(sys%n), sys%young(sys%n), &
         & sys%poisson(sys%n))
      sys%radius = nan
      sys%density = nan
      sys%young = nan
      sys%poisson = nan
      sys%law_origin = origin
      sys%damping_origin = origin
      sys%left = wall_type(present=chain%left_wall, law=chain%left_law, &
         & gap=chain%left_gap, law_origin=origin, damping_origin=origin)
      sys%right = wall_type(present=chain%right_wall, law=chain%right_law, &
         & gap=chain%right_gap, law_origin=origin, damping_origin=origin)
      sys%gravity = chain%gravity
      sys%t_end = options%t_end
      sys%rtol = options%rtol
      sys%method = method_integrated
      sys%integrator = integrator_bdf
      ! no variations (&system_sweep is refused above), but their empty lists: the
      ! output system_sweep runs the chain once (it crashed on their absence)
      call load_variations(src, sys, error)
      if (allocated(error)) return
      call system_sampling(src, sc, error)
      if (allocated(error)) return
      sc%system = sys
   end subroutine load_mpi_chain

   !> One value per neighbouring pair (or one for all) of the list `values` of group
   !> gid: `default` for every pair when not given; every value finite and positive
   !> (or not negative when `zero_ok`).
   subroutine per_pair(src, gid, name, values, pairs, default, zero_ok, out, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: values(:)
      integer, intent(in) :: pairs
      real(wp), intent(in) :: default
      logical, intent(in) :: zero_ok
      real(wp), allocatable, intent(out) :: out(:)
      character(len=:), allocatable, intent(out) :: error
      integer :: count, j
      call count_list(src, gid, name, values, count, error)
      if (allocated(error)) return
      allocate(out(pairs))
      out = default
      if (count == 0) return
      if (pairs == 0) then
         error = at(src, gid, name) // name // " is given, but a single body has no" &
            & // " neighbouring pair"
         return
      end if
      if (count /= 1 .and. count /= pairs) then
         error = at(src, gid, name) // name // ": " // count_str(count, "value") // " for " &
            & // str(pairs) // " neighbouring pairs: give one per pair, or one for all"
         return
      end if
      do j = 1, count
         if (.not. ieee_is_finite(values(j))) then
            error = at(src, gid, name) // name // " value " // str(j) &
               & // " is not a finite number" // finite_hint
            return
         end if
         if (values(j) < 0.0_wp .or. (values(j) == 0.0_wp .and. .not. zero_ok)) then
            error = at(src, gid, name) // name // " value " // str(j) // " = " &
               & // real_str(values(j), 6) // ": must be " // trim(merge("not negative", &
               & "positive    ", zero_ok))
            if (name == "gap") error = error // " (bodies may touch, gap 0, not overlap)"
            return
         end if
      end do
      if (count == 1) then
         out = values(1)
      else
         out = values(1:pairs)
      end if
   end subroutine per_pair

   !> The damping of `pairs` contacts: b given (one per pair or one for all), or the
   !> b that gives the restitution e at the speed V (b = beta(e)/V).
   subroutine pair_damping(src, gid, b_values, e_values, v_values, pairs, damping, origin, &
         & target, speed, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      real(wp), intent(in) :: b_values(:), e_values(:), v_values(:)
      integer, intent(in) :: pairs
      real(wp), allocatable, intent(out) :: damping(:)
      character(len=:), allocatable, intent(out) :: origin
      real(wp), intent(out) :: target, speed
      character(len=:), allocatable, intent(out) :: error
      real(wp), allocatable :: e(:), v(:)
      integer :: j
      target = nan
      speed = nan
      call per_pair(src, gid, "b", b_values, pairs, nan, .true., damping, error)
      if (allocated(error)) return
      call per_pair(src, gid, "restitution", e_values, pairs, nan, .false., e, error)
      if (allocated(error)) return
      call per_pair(src, gid, "at_speed", v_values, pairs, nan, .false., v, error)
      if (allocated(error)) return
      if (pairs == 0) return
      if (.not. ieee_is_nan(damping(1))) then
         if (.not. (ieee_is_nan(e(1)) .and. ieee_is_nan(v(1)))) then
            error = at(src, gid, "restitution") // "give b, or restitution and at_speed," &
               & // " not both"
            return
         end if
         origin = "given"
         return
      end if
      if (ieee_is_nan(e(1)) .or. ieee_is_nan(v(1))) then
         error = at(src, gid, "") // "missing damping: give b (s/m, 0 for elastic contacts), or" &
            & // " restitution and at_speed (m/s)"
         return
      end if
      do j = 1, pairs
         call restitution_damping(src, gid, e(j), v(j), damping(j), error)
         if (allocated(error)) return
      end do
      ! the speed of every pair's restitution when they share one (the default of a
      ! sweep's restitutions), the target too when they share that
      if (all(v == v(1))) speed = v(1)
      if (all(e == e(1)) .and. all(v == v(1))) then
         target = e(1)
         origin = "the exact damping for the restitution e = " // real_str(e(1), 6) &
            & // " at V = " // real_str(v(1), 6) // " m/s: b = beta(e)/V"
      else
         origin = "the exact damping for each pair's restitution at its speed: b = beta(e)/V"
      end if
   end subroutine pair_damping

   !> A text choice of &bodies (method, integrator): its code, `codes(1)` when not given;
   !> an empty value given (method = "") is refused as an unknown one is.
   subroutine choose(src, name, text, words, codes, code, error)
      type(scene_source), intent(in) :: src
      character(len=*), intent(in) :: name, text
      character(len=*), intent(in) :: words(:)
      integer, intent(in) :: codes(:)
      integer, intent(out) :: code
      character(len=:), allocatable, intent(out) :: error
      integer :: k
      code = codes(1)
      if (len_trim(text) == len(text)) then
         error = at(src, g_bodies, name) // name // ": the text is longer than " &
            & // str(bodies_text_length - 1) // " characters"
         return
      end if
      if (len_trim(text) == 0) then
         if (given(src, g_bodies, name)) error = at(src, g_bodies, name) // name &
            & // " = '': an empty value (leave " // name // " out for " // trim(words(1)) &
            & // "): use " // join(words, ", ")
         return
      end if
      do k = 1, size(words)
         if (lower(trim(adjustl(text))) == trim(words(k))) then
            code = codes(k)
            return
         end if
      end do
      error = at(src, g_bodies, name) // name // " = '" // trim(text) // "': use " &
         & // join(words, ", ")
   end subroutine choose

   !> &system_sweep: the variations of the output system_sweep (none: the system alone),
   !> one list per parameter of `sweep_names`, each value checked (`check_sweep_list`):
   !> striker_speed and gravity finite, masses, stiffnesses and exponents positive, gaps
   !> (of pairs and walls) and b (of pairs and walls) >= 0, end times > 0, restitutions
   !> in (0, 1] at the speed at_speed (> 0; default the speed of &bodies' restitution)
   !> and turned into b here, b or restitution but not both, a wall's gap, b, c and n
   !> only with that wall (n other than 1.5 not with Hertz's c from the materials
   !> unless c is varied too), striker_body and mass_body bodies' indices with their list;
   !> "product" (default) or "list" (the lists given of one length). A variation the
   !> library refuses (check_chain: an exponent out of its domain) gets its status in
   !> its row, as one that fails.
   subroutine load_variations(src, sys, error)
      type(scene_source), intent(in) :: src
      type(system_type), intent(inout) :: sys
      character(len=:), allocatable, intent(out) :: error
      integer :: n(n_sweep_lists), k, i
      real(wp) :: values(max_variations)
      do k = 1, n_sweep_lists
         allocate(sys%vary(k)%values(0))
      end do
      allocate(sys%vary_restitution_b(0))
      sys%vary_mass_body = [1]
      sys%vary_striker_body = [1]
      sys%vary_product = .true.
      call read_group(src, g_system_sweep, error)
      if (allocated(error)) return
      if (.not. src%groups(g_system_sweep)%present) return
      do k = 1, n_sweep_lists
         call count_list(src, g_system_sweep, trim(sweep_names(k)), &
            & sweep_values(trim(sweep_names(k))), n(k), error)
         if (allocated(error)) return
         call check_sweep_list(src, g_system_sweep, trim(sweep_names(k)), &
            & sweep_unit(trim(sweep_names(k))), sweep_values(trim(sweep_names(k))), n(k), &
            & sweep_bound(trim(sweep_names(k))), error)
         if (allocated(error)) return
         ! every pair's value: a system of one body has none
         if (n(k) > 0 .and. sys%n < 2 .and. k >= sweep_gap .and. k <= sweep_restitution) then
            error = at(src, g_system_sweep, trim(sweep_names(k))) // "one body has no pair:" &
               & // " " // trim(sweep_names(k)) // " cannot be varied"
            return
         end if
      end do
      do k = sweep_left_gap, sweep_right_exponent
         ! (the walls' gaps, b, c and n, left and right)
         if (n(k) == 0) cycle
         if (any(k == [sweep_left_gap, sweep_left_b, sweep_left_stiffness, &
            & sweep_left_exponent])) then
            if (sys%left%present) cycle
            error = at(src, g_system_sweep, trim(sweep_names(k))) // trim(sweep_names(k)) &
               & // " is a value of the left wall: the system has none (&left_wall)"
         else
            if (sys%right%present) cycle
            error = at(src, g_system_sweep, trim(sweep_names(k))) // trim(sweep_names(k)) &
               & // " is a value of the right wall: the system has none (&right_wall)"
         end if
         return
      end do
      if (sum(n) == 0) then
         error = at(src, g_system_sweep, "") // "&system_sweep varies nothing: give " &
            & // join(sweep_names, ", ") // " (lists of values)"
         return
      end if
      if (n(sweep_exponent) > 0 .and. n(sweep_stiffness) == 0 .and. &
         & sys%stiffness_from_materials) then
         if (any(vary_exponent(1:n(sweep_exponent)) /= 1.5_wp)) then
            error = at(src, g_system_sweep, "exponent") // "the pairs' c is Hertz's constant" &
               & // " from the materials, which is for n = 1.5: vary stiffness too, or give" &
               & // " it in &bodies"
            return
         end if
      end if
      call wall_hertz_exponents(src, sys%left, "left", n(sweep_left_exponent), &
         & n(sweep_left_stiffness), vary_left_exponent, error)
      if (allocated(error)) return
      call wall_hertz_exponents(src, sys%right, "right", n(sweep_right_exponent), &
         & n(sweep_right_stiffness), vary_right_exponent, error)
      if (allocated(error)) return
      if (n(sweep_b) > 0 .and. n(sweep_restitution) > 0) then
         error = at(src, g_system_sweep, "restitution") // "vary b or restitution, not both" &
            & // " (each sets every pair's damping)"
         return
      end if
      call choose_body(src, "mass_body", vary_mass_body, "mass", n(sweep_mass), sys%n, &
         & sys%vary_mass_body, error)
      if (allocated(error)) return
      call choose_body(src, "striker_body", vary_striker_body, "striker_speed", &
         & n(sweep_striker_speed), sys%n, sys%vary_striker_body, error)
      if (allocated(error)) return
      if (.not. is_unset(vary_at_speed) .and. n(sweep_restitution) == 0) then
         error = at(src, g_system_sweep, "at_speed") // "at_speed is the speed of the" &
            & // " restitutions: give restitution too"
         return
      end if
      if (n(sweep_restitution) > 0) then
         if (.not. is_unset(vary_at_speed)) then
            sys%vary_at_speed = vary_at_speed
         else if (ieee_is_nan(sys%reference_speed)) then
            error = at(src, g_system_sweep, "restitution") // "restitution needs the speed at" &
               & // " which it holds: give at_speed (m/s), as &bodies gives no restitution" &
               & // " at one speed for every pair"
            return
         else
            sys%vary_at_speed = sys%reference_speed
         end if
         deallocate(sys%vary_restitution_b)
         allocate(sys%vary_restitution_b(n(sweep_restitution)))
         do i = 1, n(sweep_restitution)
            call restitution_damping(src, g_system_sweep, vary_restitution(i), &
               & sys%vary_at_speed, sys%vary_restitution_b(i), error)
            if (allocated(error)) return
         end do
      end if
      call combine_lists(src, g_system_sweep, sweep_names, n, sys%vary_product, error)
      if (allocated(error)) return
      do k = 1, n_sweep_lists
         values = sweep_values(trim(sweep_names(k)))
         sys%vary(k)%values = values(1:n(k))
      end do

   end subroutine load_variations

   !> A wall whose c is Hertz's constant from the materials (for n = 1.5) takes no other
   !> exponent from the list `side`_exponent (n values) unless its c is varied too
   !> (n_c values).
   subroutine wall_hertz_exponents(src, wall, side, n, n_c, values, error)
      type(scene_source), intent(in) :: src
      type(wall_type), intent(in) :: wall
      character(len=*), intent(in) :: side
      integer, intent(in) :: n, n_c
      real(wp), intent(in) :: values(:)
      character(len=:), allocatable, intent(out) :: error
      if (n == 0 .or. n_c > 0 .or. .not. allocated(wall%law_origin)) return
      if (wall%law_origin == "given" .or. all(values(1:n) == 1.5_wp)) return
      error = at(src, g_system_sweep, side // "_exponent") // "the " // side &
         & // " wall's c is Hertz's constant from the materials, which is for n = 1.5:" &
         & // " vary " // side // "_stiffness too, or give it in &" // side // "_wall"
   end subroutine wall_hertz_exponents

   !> &system_sweep's indices `name` (mass_body, striker_body: `values` as read, unset
   !> where not) of the bodies to which the list `list` (n values) gives each of its
   !> values: body 1 when not given, else only with its list, distinct indices of
   !> bodies (whole numbers, in any order) in one run of values, or 0 alone for every
   !> body.
   subroutine choose_body(src, name, values, list, n, n_bodies, bodies, error)
      type(scene_source), intent(in) :: src
      character(len=*), intent(in) :: name, list
      real(wp), intent(in) :: values(:)
      integer, intent(in) :: n, n_bodies
      integer, allocatable, intent(out) :: bodies(:)
      character(len=:), allocatable, intent(out) :: error
      integer :: count, i
      logical :: whole
      bodies = [1]
      call count_list(src, g_system_sweep, name, values, count, error)
      if (allocated(error)) return
      if (count == 0 .and. .not. given(src, g_system_sweep, name)) return
      if (count == 0) then
         error = at(src, g_system_sweep, name) // name // " has no value: give the index" &
            & // " of a body, several, or 0 for every body"
         return
      else if (n == 0) then
         error = at(src, g_system_sweep, name) // name // " names the bodies whose " &
            & // trim(merge("mass    ", "velocity", list == "mass")) // " the list " // list &
            & // " varies: give " // list // " too"
         return
      end if
      do i = 1, count
         ! (a whole number, tested before it is converted: NaN or Inf is not one; the
         ! finite test first, a NaN compared would trap)
         whole = ieee_is_finite(values(i))
         if (whole) whole = values(i) == aint(values(i))
         if (.not. whole) then
            error = at(src, g_system_sweep, name) // body_list_text(name) // ": " &
               & // real_str(values(i), 17) // " is not one"
            return
         end if
      end do
      if (count == 1 .and. values(1) == 0.0_wp) then
         bodies = [(i, i = 1, n_bodies)]
         return
      end if
      do i = 1, count
         if (values(i) < 1.0_wp .or. values(i) > real(n_bodies, wp)) then
            error = at(src, g_system_sweep, name) // name // " = " // real_str(values(i), 10) &
               & // ": the bodies are 1 to " // str(n_bodies)
            if (values(i) == 0.0_wp) error = error // " (0 alone: every body)"
            return
         end if
         if (any(values(1:i - 1) == values(i))) then
            error = at(src, g_system_sweep, name) // name // " names body " &
               & // str(nint(values(i))) // " twice"
            return
         end if
      end do
      bodies = nint(values(1:count))
   end subroutine choose_body

   !> What &system_sweep's mass_body or striker_body (`name`) takes, for a value that
   !> is not a whole number
   pure function body_list_text(name) result(text)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: text
      text = name // " takes whole numbers, the indices of the bodies whose " &
         & // trim(merge("mass    ", "velocity", name == "mass_body")) // " the list " &
         & // trim(merge("mass         ", "striker_speed", name == "mass_body")) &
         & // " varies (0 alone: every body)"
   end function body_list_text

   !> The values of the sweep list `name` as the namelist groups &system_sweep and
   !> &impact_sweep read it (the two share the lists of one name)
   function sweep_values(name) result(values)
      character(len=*), intent(in) :: name
      real(wp) :: values(max_variations)
      select case (name)
      case ("striker_speed")
         values = vary_speed
      case ("mass")
         values = vary_mass
      case ("gap")
         values = vary_gap
      case ("stiffness")
         values = vary_stiffness
      case ("exponent")
         values = vary_exponent
      case ("b")
         values = vary_b
      case ("restitution")
         values = vary_restitution
      case ("gravity")
         values = vary_gravity
      case ("left_gap")
         values = vary_left_gap
      case ("right_gap")
         values = vary_right_gap
      case ("left_b")
         values = vary_left_b
      case ("right_b")
         values = vary_right_b
      case ("left_stiffness")
         values = vary_left_stiffness
      case ("right_stiffness")
         values = vary_right_stiffness
      case ("left_exponent")
         values = vary_left_exponent
      case ("right_exponent")
         values = vary_right_exponent
      case ("t_end")
         values = vary_t_end
      case ("speed")
         values = vary_impact_speed
      case default
         values = unset
      end select
   end function sweep_values

   !> The bound of the values of the sweep list `name` (`check_sweep_list`): speeds and
   !> gravity any finite value, gaps and b (of pairs and walls) >= 0 (no damping:
   !> Hertz), restitutions in (0, 1], the rest (masses, stiffnesses, exponents, end
   !> times) positive
   pure integer function sweep_bound(name)
      character(len=*), intent(in) :: name
      select case (name)
      case ("striker_speed", "gravity")
         sweep_bound = any_finite
      case ("gap", "b", "left_gap", "right_gap", "left_b", "right_b")
         sweep_bound = not_negative
      case ("restitution")
         sweep_bound = unit_interval
      case default
         sweep_bound = positive
      end select
   end function sweep_bound

   !> Check the first n values of the sweep list `name` (unit `unit`) of group gid:
   !> finite, and `lowest` any_finite, not_negative (>= 0), positive (> 0) or
   !> unit_interval (in (0, 1]).
   subroutine check_sweep_list(src, gid, name, unit, values, n, lowest, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: name, unit
      real(wp), intent(in) :: values(:)
      integer, intent(in) :: n, lowest
      character(len=:), allocatable, intent(out) :: error
      character(len=:), allocatable :: unit_text
      integer :: i
      unit_text = " " // unit
      if (unit == "-") unit_text = ""
      do i = 1, n
         ! finite first: an ordered comparison with NaN would trap in the Debug build
         if (.not. ieee_is_finite(values(i))) then
            error = at(src, gid, name) // name // " " // str(i) // " is not a finite number" &
               & // finite_hint
         else if ((lowest == positive .or. lowest == unit_interval) .and. &
            & .not. values(i) > 0.0_wp) then
            error = at(src, gid, name) // name // " " // str(i) // " = " &
               & // real_str(values(i), 6) // unit_text // ": must be positive"
         else if (lowest == not_negative .and. values(i) < 0.0_wp) then
            error = at(src, gid, name) // name // " " // str(i) // " = " &
               & // real_str(values(i), 6) // unit_text // ": must be >= 0"
         else if (lowest == unit_interval .and. values(i) > 1.0_wp) then
            error = at(src, gid, name) // name // " " // str(i) // " = " &
               & // real_str(values(i), 6) // unit_text // ": a coefficient of restitution" &
               & // " lies in (0, 1]"
         end if
         if (allocated(error)) return
      end do
   end subroutine check_sweep_list

   !> How the lists `names` of the sweep group `gid` (`lengths` values given; 0: not
   !> varied) combine: `combine` "product" (default: every combination) or "list" (side
   !> by side, the lists given of one length), at most `max_sweep_items` variations.
   subroutine combine_lists(src, gid, names, lengths, every_combination, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      character(len=*), intent(in) :: names(:)
      integer, intent(in) :: lengths(:)
      logical, intent(out) :: every_combination
      character(len=:), allocatable, intent(out) :: error
      integer, parameter :: max_sweep_items = 100000
      character(len=:), allocatable :: given_lengths
      integer :: k
      every_combination = .true.
      if (len_trim(vary_combine) >= variations_text_length) then
         error = at(src, gid, "combine") // "combine is too long"
         return
      end if
      if (len_trim(vary_combine) == 0 .and. given(src, gid, "combine")) then
         error = at(src, gid, "combine") // "combine = '': an empty value (leave combine out" &
            & // " for ""product""): give ""product"" (every combination) or ""list"" (side by side)"
         return
      end if
      select case (lower(trim(vary_combine)))
      case ("", "product")
         every_combination = .true.
         ! counted in doubles, exact here: a product of several lists of 1000 passes
         ! the default integer's range
         if (product(real(max(lengths, 1), wp)) > max_sweep_items) then
            error = at(src, gid, "") // real_str(product(real(max(lengths, 1), wp)), 15) &
               & // " variations: at most " // str(max_sweep_items)
            return
         end if
      case ("list")
         every_combination = .false.
         if (any(lengths /= maxval(lengths) .and. lengths /= 0)) then
            given_lengths = ""
            do k = 1, size(names)
               if (lengths(k) == 0) cycle
               if (len(given_lengths) > 0) given_lengths = given_lengths // ", "
               given_lengths = given_lengths // trim(names(k)) // " " // str(lengths(k))
            end do
            error = at(src, gid, "combine") // "combine = ""list"" takes the lists" &
               & // " side by side: give them of one length (" // given_lengths // " values)"
            return
         end if
      case default
         error = at(src, gid, "combine") // "combine = '" // trim(vary_combine) &
            & // "': give ""product"" (every combination) or ""list"" (side by side)"
         return
      end select
   end subroutine combine_lists

   !> &impact_sweep: the parameter sets of the output impact_sweep (one impact each):
   !> lists of effective masses, stiffnesses, exponents, dampings b and approach speeds,
   !> each value checked as the scene's own (finite; mass, stiffness, exponent and speed
   !> positive, b >= 0), at least one list, combined by `combine_lists`. Without the
   !> group the output takes the scene's own contact at each of its speeds.
   subroutine load_impact_variations(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      character(len=*), parameter :: names(5) = [character(len=9) :: "mass", "stiffness", &
         & "exponent", "b", "speed"]
      integer :: n(5), k
      allocate(sc%vary_mass(0), sc%vary_stiffness(0), sc%vary_exponent(0), &
         & sc%vary_damping(0), sc%vary_speed(0))
      sc%vary_product = .true.
      call read_group(src, g_impact_sweep, error)
      if (allocated(error)) return
      if (.not. src%groups(g_impact_sweep)%present) then
         ! the scene's own contact at each of its speeds (as `all` asks for any scene)
         sc%vary_speed = sc%speeds
         if (sc%wanted(out_impact_sweep) .and. size(sc%speeds) == 0) error = at(src, &
            & g_scene, "speeds") // "the output 'impact_sweep' without &impact_sweep" &
            & // " needs approach speeds: give speeds = ... (m/s) in &scene"
         return
      end if
      do k = 1, size(names)
         call count_list(src, g_impact_sweep, trim(names(k)), sweep_values(trim(names(k))), &
            & n(k), error)
         if (allocated(error)) return
         call check_sweep_list(src, g_impact_sweep, trim(names(k)), sweep_unit(trim(names(k))), &
            & sweep_values(trim(names(k))), n(k), sweep_bound(trim(names(k))), error)
         if (allocated(error)) return
      end do
      if (sum(n) == 0) then
         error = at(src, g_impact_sweep, "") // "&impact_sweep varies nothing: give mass," &
            & // " stiffness, exponent, b or speed (lists of values)"
         return
      end if
      if (n(5) == 0 .and. size(sc%speeds) == 0) then
         error = at(src, g_impact_sweep, "") // "&impact_sweep varies no speed and the scene" &
            & // " has none: give speed = ... (m/s) here or speeds = ... in &scene"
         return
      end if
      call combine_lists(src, g_impact_sweep, names, n, sc%vary_product, error)
      if (allocated(error)) return
      sc%vary_mass = vary_mass(1:n(1))
      sc%vary_stiffness = vary_stiffness(1:n(2))
      sc%vary_exponent = vary_exponent(1:n(3))
      sc%vary_damping = vary_b(1:n(4))
      sc%vary_speed = vary_impact_speed(1:n(5))

   end subroutine load_impact_variations

   !> &left_wall or &right_wall: the law with the end body `end_body` (stiffness, or
   !> Hertz's constant of the body's sphere on the flat wall from young and poisson),
   !> the damping and the gap (default 0: touching).
   subroutine load_wall(src, gid, sys, end_body, wall, error)
      type(scene_source), intent(in) :: src
      integer, intent(in) :: gid
      type(system_type), intent(in) :: sys
      integer, intent(in) :: end_body
      type(wall_type), intent(out) :: wall
      character(len=:), allocatable, intent(out) :: error
      real(wp), allocatable :: c(:), e(:), g(:), v(:)
      real(wp) :: radius_flat
      wall%present = src%groups(gid)%present
      if (.not. wall%present) return
      call read_group(src, gid, error)
      if (allocated(error)) return
      call per_pair(src, gid, "stiffness", [stiffness, unset], 1, nan, .false., c, error)
      if (allocated(error)) return
      call per_pair(src, gid, "exponent", [exponent, unset], 1, 1.5_wp, .false., e, error)
      if (allocated(error)) return
      call per_pair(src, gid, "gap", [gap, unset], 1, 0.0_wp, .true., g, error)
      if (allocated(error)) return
      call take(src, gid, "young", young, wall%young, error)
      call take(src, gid, "poisson", poisson, wall%poisson, error)
      if (allocated(error)) return
      if (ieee_is_nan(c(1))) then
         if (ieee_is_nan(wall%young) .or. ieee_is_nan(wall%poisson) .or. &
            & ieee_is_nan(sys%radius(end_body)) .or. ieee_is_nan(sys%young(end_body)) .or. &
            & ieee_is_nan(sys%poisson(end_body))) then
            error = at(src, gid, "") // "no stiffness given, and Hertz's constant needs the" &
               & // " wall's young and poisson, and the radius, young and poisson of body " &
               & // str(end_body)
            return
         end if
         if (e(1) /= 1.5_wp) then
            error = at(src, gid, "exponent") // "without a stiffness, c is Hertz's constant," &
               & // " which is for n = 1.5"
            return
         end if
         if (.not. (wall%young > 0.0_wp .and. wall%poisson > -1.0_wp .and. &
            & wall%poisson <= 0.5_wp)) then
            error = at(src, gid, "young") // "young must be positive and poisson in (-1, 0.5]"
            return
         end if
         radius_flat = ieee_value(1.0_wp, ieee_positive_inf)
         c(1) = hertz_constant(sys%young(end_body), sys%poisson(end_body), &
            & sys%radius(end_body), wall%young, wall%poisson, radius_flat)
         wall%law_origin = "Hertz's constant of body " // str(end_body) // " on the flat wall"
      else
         wall%law_origin = "given"
      end if
      call pair_damping(src, gid, [b, unset], [restitution, unset], [at_speed, unset], 1, v, &
         & wall%damping_origin, wall%target_restitution, wall%reference_speed, error)
      if (allocated(error)) return
      wall%law = contact_law(stiffness=c(1), exponent=e(1), damping=v(1))
      wall%gap = g(1)
   end subroutine load_wall

   !> &sampling of a system: only the number of samples of the motion.
   subroutine system_sampling(src, sc, error)
      type(scene_source), intent(in) :: src
      type(scene_type), intent(inout) :: sc
      character(len=:), allocatable, intent(out) :: error
      character(len=*), parameter :: others(6) = [character(len=13) :: "sweep_from", &
         & "sweep_to", "sweep_count", "sweep_spacing", "beta_max", "tolerances"]
      integer :: k
      call read_group(src, g_sampling, error)
      if (allocated(error)) return
      do k = 1, size(others)
         if (.not. given(src, g_sampling, trim(others(k)))) cycle
         error = at(src, g_sampling, trim(others(k))) // trim(others(k)) // " is for one" &
            & // " impact: a system of bodies takes only samples (times of the motion output)"
         return
      end do
      if (samples /= unset_int .or. given(src, g_sampling, "samples")) then
         if (samples < 2 .or. samples > 100001) then
            error = at(src, g_sampling, "samples") // "samples = " // str(samples) &
               & // ": between 2 and 100001 times of the motion"
            return
         end if
         sc%samples = samples
      end if
      allocate(sc%sweep(0))
      sc%tolerances = [real(wp) ::]
   end subroutine system_sampling

end module hcimpact_scene_reader
