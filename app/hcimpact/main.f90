! SPDX-License-Identifier: Apache-2.0
!> hcimpact: the scene runner. Reads a scene file (or the built-in default scene, the
!> seed's steel ball), plans from the outputs it asks for, computes only those, prints
!> the tables and writes the results directory. `hcimpact --help` explains everything.
program hcimpact_main
   use, intrinsic :: iso_fortran_env, only : error_unit
   use hcimpact_version_info, only : hcimpact_version_string
   use hcimpact_scene_model, only : scene_type, n_outputs, add_outputs, output_choices, &
      & figure_outputs, default_scene_lines
   use hcimpact_scene_reader, only : read_scene_file, read_default_scene
   use hcimpact_scene_run, only : run_options, run_scene, exit_ok, exit_failure, exit_usage
   use hcimpact_scene_ode, only : ode_available
   use hcimpact_scene_help, only : print_help, print_usage_hint
   use hcimpact_scene_system, only : is_terminal, write_standard_output, &
      & ignore_output_signals
   use hcimpact_scene_sweep, only : sweep_begin, sweep_serve, sweep_end
   implicit none

   type(scene_type) :: sc
   type(run_options) :: opts
   character(len=:), allocatable :: arg, scene_path, output_dir, error, list
   logical :: replace(n_outputs), add(n_outputs), files, ok, leader, show_progress
   integer :: i, n, code

   ! a file size limit or a closed pipe then fails a write (reported, the partial files
   ! removed) instead of killing the program
   call ignore_output_signals()
   ! with MPI (mpirun -n N), ranks other than 0 only compute the impacts of sweeps
   ! (doc/mpi.md); every exit of rank 0 goes through end_program, which ends them
   call sweep_begin(leader)
   if (.not. leader) then
      call sweep_serve(code)
      call end_program(code)
   end if
   replace = .false.
   show_progress = .false.
   add = .false.
   files = .true.
   n = command_argument_count()
   i = 0
   do while (i < n)
      i = i + 1
      arg = argument(i)
      select case (arg)
      case ("-h", "--help")
         call print_help(ok)
         call finish(ok)
      case ("-V", "--version")
         if (ode_available) then
            call write_standard_output("hcimpact " // hcimpact_version_string // new_line("a") &
               & // "components: core, cvode" // new_line("a"), ok)
         else
            call write_standard_output("hcimpact " // hcimpact_version_string // new_line("a") &
               & // "components: core (built without cvode)" // new_line("a"), ok)
         end if
         call finish(ok)
      case ("--show-default")
         ok = .true.
         do code = 1, size(default_scene_lines)
            if (ok) call write_standard_output(trim(default_scene_lines(code)) // new_line("a"), ok)
         end do
         call finish(ok)
      case ("-o", "--output")
         if (i == n) call usage_error("option " // arg // " needs a directory")
         i = i + 1
         output_dir = argument(i)
      case ("--outputs")
         if (i == n) call usage_error("option --outputs needs a list, e.g. summary,phase")
         i = i + 1
         list = argument(i)
         call parse_outputs(list, replace)
      case ("--figures")
         add = add .or. figure_outputs
      case ("--no-files")
         files = .false.
      case ("--plan")
         opts%plan_only = .true.
      case ("-q", "--quiet")
         opts%quiet = .true.
      case ("--progress")
         show_progress = .true.
      case default
         if (len(arg) > 2) then
            if (arg(1:2) == "--") call usage_error("unknown option " // arg)
         end if
         if (len(arg) > 1) then
            if (arg(1:1) == "-") then
               if (arg(1:2) /= "-o" .and. arg /= "-") call usage_error("unknown option " // arg)
               ! -oDIR
               if (arg(1:2) == "-o") then
                  output_dir = arg(3:)
                  cycle
               end if
            end if
         end if
         if (allocated(scene_path)) call usage_error("more than one scene file: " &
            & // scene_path // " and " // arg)
         scene_path = arg
      end select
   end do

   if (allocated(scene_path)) then
      call read_scene_file(scene_path, sc, error, replace, add)
   else
      call read_default_scene(sc, error, replace, add)
   end if
   if (allocated(error)) then
      write(error_unit, '(a)') "error: " // error
      call end_program(exit_usage)
   end if

   opts%write_files = files
   if (allocated(output_dir)) then
      if (.not. files) call usage_error("--no-files and -o contradict each other")
      opts%output_dir = output_dir
   else
      opts%output_dir = "hcimpact-results/" // sc%name
   end if
   opts%progress = show_progress .or. is_terminal(2)
   call run_scene(sc, sc%text, opts, code)
   call end_program(code)

contains

   !> Command-line argument i.
   function argument(i) result(text)
      integer, intent(in) :: i
      character(len=:), allocatable :: text
      integer :: length
      call get_command_argument(i, length=length)
      allocate(character(len=length) :: text)
      if (length > 0) call get_command_argument(i, text)
   end function argument

   !> The outputs of a comma-separated list.
   subroutine parse_outputs(text, wanted)
      character(len=*), intent(in) :: text
      logical, intent(inout) :: wanted(n_outputs)
      character(len=:), allocatable :: unknown
      call add_outputs(text, wanted, unknown)
      if (len(unknown) > 0) call usage_error("unknown output '" // unknown // "' (outputs: " &
         & // output_choices() // ")")
      if (.not. any(wanted)) call usage_error("--outputs: the list is empty")
   end subroutine parse_outputs

   !> End after printing help or a version: exit status 1 if the standard output
   !> could not take it.
   subroutine finish(ok)
      logical, intent(in) :: ok
      if (ok) call end_program(exit_ok)
      write(error_unit, '(a)') "error: the standard output: writing failed"
      call end_program(exit_failure)
   end subroutine finish

   !> End the program with an exit code (the other MPI ranks, if any, are ended first);
   !> quietly, also on success: gfortran's STOP would otherwise note the floating-point
   !> flags raised (underflows are normal here) on standard error.
   subroutine end_program(code)
      integer, intent(in) :: code
      call sweep_end()
      stop code, quiet=.true.
   end subroutine end_program

   !> Report a bad command line and stop with exit_usage.
   subroutine usage_error(text)
      character(len=*), intent(in) :: text
      write(error_unit, '(a)') "error: " // text
      call print_usage_hint(error_unit)
      call end_program(exit_usage)
   end subroutine usage_error

end program hcimpact_main
