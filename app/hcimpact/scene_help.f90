! SPDX-License-Identifier: Apache-2.0
!> The text of `hcimpact --help`: usage, options, the scene format with an example,
!> the outputs and the exit codes.
module hcimpact_scene_help
   use hcimpact_scene_system, only : write_standard_output
   use hcimpact_scene_model, only : n_outputs, output_names, output_files, &
      & output_descriptions, default_scene_lines
   implicit none
   private

   public :: print_help, print_usage_hint

contains

   !> Everything a user needs to run the program and write a scene; ok is .false. if
   !> the standard output could not take it.
   subroutine print_help(ok)
      logical, intent(out) :: ok
      integer :: i
      ok = .true.
      call p("hcimpact: the Hunt-Crossley impact m x'' = -c x^n (1 + b x') of a body on a")
      call p("wall, or of two bodies, in closed form (Lambert W) and by quadrature; and systems")
      call p("of bodies on a line (cradles, chains, stacks, bouncing balls).")
      call p("")
      call p("Usage: hcimpact [options] [SCENE]")
      call p("")
      call p("Reads the scene file SCENE (without one: the built-in default scene, the")
      call p("seed's steel ball, below), computes the outputs it asks for and nothing else,")
      call p("prints the tables and a log of what each output cost, and writes the results")
      call p("as CSV files into a directory.")
      call p("")
      call p("Options:")
      call p("  -o, --output DIR  results directory (default: hcimpact-results/<scene name>);")
      call p("                    files appear there only when the whole run succeeds")
      call p("  --outputs LIST    outputs to compute instead of the scene's, comma-separated,")
      call p("                    e.g. --outputs summary,phase")
      call p("  --figures         also compute what the seed's figures 1-8 need; then")
      call p("                    python3 python/plot_results.py DIR draws them")
      call p("  --no-files        write no results directory (console only)")
      call p("  --plan            print the plan (outputs, methods) and stop")
      call p("  --show-default    print the default scene: a template for your own")
      call p("  -q, --quiet       print only the tables and errors")
      call p("  --progress        show the progress of long work on standard error even")
      call p("                    when it is not a terminal (under mpirun, say)")
      call p("  -h, --help        print this text")
      call p("  -V, --version     print the version")
      call p("")
      call p("Scene files are Fortran namelists: groups &name ... / in any order; ! starts")
      call p("a comment; text goes in quotes; units are SI. Groups and their names:")
      call p("  &scene    title = ""...""                 title of the tables and figures")
      call p("            speeds = 0.5, 1, 2            approach speeds V (m/s); for two")
      call p("                                          bodies the relative speed")
      call p("            outputs = ""summary"", ...      see Outputs (default ""summary""); or")
      call p("            outputs = ""summary,phase""     one text, as with --outputs")
      call p("  &body1    mass = 0.1                    the moving body's mass (kg), or for a")
      call p("            radius = 0.01, density = 7800 sphere its radius (m) and density")
      call p("                                          (kg/m^3)")
      call p("            young = 2e11, poisson = 0.25  material (Pa, -) and radius of")
      call p("            radius = 0.01 (or flat = .true.)  curvature at the contact: needed")
      call p("                                          only for Hertz's constant")
      call p("  &body2    the same names: a second body, at rest. Without &body2, body 1")
      call p("            strikes a massive flat wall.")
      call p("  &wall     young = 2e11, poisson = 0.25  the wall's material (Hertz)")
      call p("  &contact  stiffness = 1.7135e10         c of the elastic law f = c x^n")
      call p("                                          (N/m^n); without it, Hertz's")
      call p("                                          constant from radii and materials")
      call p("            exponent = 1.5                n: 1.5 for spheres (default), 1 for")
      call p("                                          flat faces")
      call p("  &damping  b = 0.1                       damping b (s/m); 0: Hertz's elastic")
      call p("                                          impact. Or instead:")
      call p("            restitution = 0.8, at_speed = 1   the b that gives restitution")
      call p("                                          0.8 at 1 m/s (exactly: b = beta(e)/V)")
      call p("  &sampling samples = 201                 points per curve")
      call p("            sweep_from = 0.05, sweep_to = 5, sweep_count = 100,")
      call p("            sweep_spacing = ""linear""      speeds of the sweep (m/s; ""log""")
      call p("                                          too); default: up to the largest")
      call p("                                          speed")
      call p("            beta_max = 10                 range of the restitution curves")
      call p("            tolerances = 1e-4, 1e-6, 1e-8, 1e-10   CVODE relative tolerances")
      call p("  &impact_sweep mass = 0.01, 0.1          parameter sets of the output")
      call p("            stiffness = 1e8, 1e9          impact_sweep: effective mass,")
      call p("            exponent, b, speed = 1, 10    c, n, b, speed (lists); every")
      call p("            combine = ""product"" (""list"")  combination, or side by side")
      call p("A scene needs &body1, a stiffness (or Hertz's data), &damping and, for most")
      call p("outputs, speeds. Mistakes are reported with the file, line and group: each")
      call p("name once per group, lines of at most 1024 characters (a list may go on over")
      call p("several lines), numbers within the range of doubles.")
      call p("")
      call p("A system of bodies on a line is a scene with &bodies instead of &body1, &body2,")
      call p("&wall, &contact and &damping. Bodies are numbered from the left, velocities are")
      call p("positive to the right; a list has one value per body or per neighbouring pair,")
      call p("or one value for all (3*0.1 repeats a value):")
      call p("  &bodies   mass = 5*0.1                  masses (kg), or radius = ..., density")
      call p("            velocity = 1, 4*0             one per body (m/s)")
      call p("            gap = 0                       one per pair (m; 0, the default:")
      call p("                                          touching without preload)")
      call p("            stiffness = 1.2e10, exponent = 1.5   per pair, or Hertz's constants")
      call p("                                          from radius, young, poisson")
      call p("            b = 0                         per pair (s/m), or restitution = 0.9,")
      call p("                                          at_speed = 1")
      call p("            gravity = -9.81               along the line (m/s^2; default 0)")
      call p("            t_end = 1                     s (default: until no contact can")
      call p("                                          happen again)")
      call p("            rtol = 1e-10, method = ""auto"" (""exact"", ""integrated""),")
      call p("            integrator = ""bdf"" (""adams"")")
      call p("  &left_wall, &right_wall   stiffness, exponent, b (or restitution, at_speed),")
      call p("            gap (m, to the end body), or young and poisson for Hertz's constant")
      call p("  &sampling samples = 201                 times of the motion output")
      call p("  &system_sweep striker_speed = 0.5, 1    variations of the system for the")
      call p("            striker_body = 1              output system_sweep: the speed of")
      call p("            gap = 0, 1e-4, b = 0, 0.05    the bodies striker_body (default 1),")
      call p("            mass = 0.1, 0.2               the mass of the bodies mass_body")
      call p("            mass_body = 2, 3              (indices; 0 alone: every body),")
      call p("                                          every pair's gap, stiffness,")
      call p("            stiffness = 1e9, 2e9          exponent and damping b, or b from a")
      call p("            exponent = 1.5, 1.25          restitution at the speed at_speed,")
      call p("            restitution = 0.8, 0.9        gravity, the walls' gaps, b, c, n,")
      call p("            at_speed = 1                  and the end time (lists of values)")
      call p("            gravity = 0, -9.81")
      call p("            left_gap = 0.1, 1, left_b = 0, 0.1   (right_gap, right_b)")
      call p("            left_stiffness = 1e6, 1e7     (right_stiffness)")
      call p("            left_exponent = 1.5, 1        (right_exponent)")
      call p("            t_end = 0.5, 1")
      call p("            combine = ""product"" (""list"")  every combination, or the lists")
      call p("                                          side by side")
      call p("")
      call p("Outputs (files in the results directory):")
      do i = 1, n_outputs
         call p("  " // output_names(i) // "  " // trim(output_descriptions(i)))
         call p("               -> " // trim(output_files(i)))
      end do
      call p("  figures      one impact: summary, sweep, histories, phase, loops,")
      call p("               restitution, lambertw; a system: contacts, final, motion")
      call p("  all          every output of the scene's kind")
      call p("Every run also writes parameters.csv (the resolved m, c, n, b), scene.nml (the")
      call p("scene) and log.txt (the log); a system also pairs.csv (the pairs' laws and")
      call p("gaps). CSV files have one header row of 'name [unit]' and numbers with 17")
      call p("significant digits.")
      call p("")
      call p("Example: the default scene (hcimpact --show-default > my.nml, then edit):")
      do i = 1, size(default_scene_lines)
         call p("    " // trim(default_scene_lines(i)))
      end do
      call p("")
      call p("Another: two bodies, Hertz's constant from the materials, and the damping")
      call p("that gives a restitution of 0.9 at 1 m/s:")
      call p("    &scene  title = ""Two steel balls"", speeds = 0.5, 1, 2,")
      call p("            outputs = ""summary"", ""histories"" /")
      call p("    &body1  radius = 0.01, density = 7800, young = 2e11, poisson = 0.25 /")
      call p("    &body2  radius = 0.02, density = 7800, young = 2e11, poisson = 0.25 /")
      call p("    &damping  restitution = 0.9, at_speed = 1 /")
      call p("A Newton's cradle of five touching steel balls:")
      call p("    &bodies  radius = 0.0125, density = 7850, young = 2e11, poisson = 0.3,")
      call p("             velocity = 1, 4*0, gap = 1e-3, 3*0, b = 0 /")
      call p("More in example/scenes/ and doc/scenes.md.")
      call p("")
      call p("Examples:")
      call p("  hcimpact                              the default scene's table")
      call p("  hcimpact --figures -o out && python3 python/plot_results.py out")
      call p("  hcimpact example/scenes/glass_bead.nml --plan")
      call p("")
      call p("Exit status: 0 success; 1 a computation or a file failed (nothing is left")
      call p("half-written); 2 a bad command line or scene file; 3 an output needs a")
      call p("component this build lacks (CVODE: the 'cvode' output, and a system of bodies")
      call p("whose contacts overlap, or touch a wall under gravity).")
   contains
      !> One line on the standard output.
      subroutine p(text)
         character(len=*), intent(in) :: text
         logical :: written
         call write_standard_output(trim(text) // new_line("a"), written)
         ok = ok .and. written
      end subroutine p
   end subroutine print_help

   !> The hint after a usage error.
   subroutine print_usage_hint(unit)
      integer, intent(in) :: unit
      write(unit, '(a)') "Usage: hcimpact [options] [SCENE]   (hcimpact --help for more)"
   end subroutine print_usage_hint

end module hcimpact_scene_help
