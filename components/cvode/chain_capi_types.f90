! SPDX-License-Identifier: Apache-2.0
!> The C structures of the chain interface (include/hcimpact_cvode.h:
!> `hcimpact_chain_law`, `hcimpact_chain_wall`, `hcimpact_chain_options`,
!> `hcimpact_chain_result`, `hcimpact_chain_contact`, `hcimpact_chain_samples`,
!> `hcimpact_chain_monitor`) and their one set of conversions to and from the Fortran
!> types of hcimpact_chain_types.
!>
!> The C entry point (hcimpact_cvode_chain_api) and the FORTRAN 77 routine HCCHN
!> both build their options with `chain_options_from`, so that the rule "0 means the
!> default" of rtol, the integrator and the two limits exists once. The layouts must
!> match the header field by field: test/cvode checks them from C, and the Python
!> package checks its own view against the header (python/tests/test_layout.py).
module hcimpact_cvode_chain_capi_types
   use, intrinsic :: iso_c_binding, only : c_double, c_int, c_int64_t, c_ptr, c_funptr, &
      & c_f_procpointer
   use, intrinsic :: iso_fortran_env, only : int64
   use hcimpact_kinds, only : wp, nan
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, chain_result, &
      & contact_record, integrator_bdf, chain_monitor
   implicit none
   private

   public :: hcimpact_chain_law, hcimpact_chain_wall, hcimpact_chain_options, &
      & hcimpact_chain_result, hcimpact_chain_contact, hcimpact_chain_samples, &
      & hcimpact_chain_monitor, c_monitor
   public :: to_law, wall_law, to_options, chain_options_from, from_result, from_contact, &
      & failed_result

   !> typedef struct { double stiffness, exponent, damping; } hcimpact_chain_law;
   type, bind(C) :: hcimpact_chain_law
      !> Contact constant c in N/m^n, > 0
      real(c_double) :: stiffness
      !> Exponent n, >= 1e-6 (1.5: Hertz)
      real(c_double) :: exponent
      !> Damping b in s/m, >= 0
      real(c_double) :: damping
   end type hcimpact_chain_law

   !> typedef struct { double stiffness, exponent, damping, gap; } hcimpact_chain_wall;
   type, bind(C) :: hcimpact_chain_wall
      !> The wall's contact law: c in N/m^n, n, b in s/m
      real(c_double) :: stiffness
      real(c_double) :: exponent
      real(c_double) :: damping
      !> Gap between the wall and the end body in m, >= 0
      real(c_double) :: gap
   end type hcimpact_chain_wall

   !> typedef struct { hcimpact_chain_poll poll; void *data; } hcimpact_chain_monitor;
   type, bind(C) :: hcimpact_chain_monitor
      !> The caller's function: nonzero stops the run
      type(c_funptr) :: poll
      !> Handed back to every call of poll
      type(c_ptr) :: data
   end type hcimpact_chain_monitor

   !> The monitor of a C caller: its poll calls the caller's function
   type, extends(chain_monitor) :: c_monitor
      type(hcimpact_chain_monitor) :: c
   contains
      procedure :: poll => c_monitor_poll
   end type c_monitor

   abstract interface
      !> typedef int (*hcimpact_chain_poll)(void *data, double time, int64_t steps,
      !> int64_t events);
      integer(c_int) function c_poll(data, time, steps, events) bind(C)
         import :: c_int, c_double, c_int64_t, c_ptr
         type(c_ptr), value :: data
         real(c_double), value :: time
         integer(c_int64_t), value :: steps, events
      end function c_poll
   end interface

   !> typedef struct { double t_end, rtol; int64_t max_steps, max_events;
   !> int method, integrator; } hcimpact_chain_options;
   !> All zero: the defaults.
   type, bind(C) :: hcimpact_chain_options
      !> End time in s; <= 0: until no contact can happen again
      real(c_double) :: t_end
      !> Relative tolerance of CVODE in (0, 0.01]; 0: 1e-10
      real(c_double) :: rtol
      !> Largest number of integration steps; 0: 1e8
      integer(c_int64_t) :: max_steps
      !> Largest number of contacts computed; 0: 1e8
      integer(c_int64_t) :: max_events
      !> HCIMPACT_CHAIN_AUTO (0), _EXACT (1), _INTEGRATED (2)
      integer(c_int) :: method
      !> 0 or HCIMPACT_CHAIN_BDF (1): BDF; HCIMPACT_CHAIN_ADAMS (2): Adams
      integer(c_int) :: integrator
   end type hcimpact_chain_options

   !> typedef struct { ... } hcimpact_chain_result; (include/hcimpact_cvode.h)
   type, bind(C) :: hcimpact_chain_result
      !> Time reached in s
      real(c_double) :: time
      !> When the system came to rest on a wall (NaN if it did not), s
      real(c_double) :: rest_time
      !> Initial kinetic energy in J
      real(c_double) :: initial_energy
      !> Relative error of the energy balance at the end
      real(c_double) :: energy_error
      !> Energy dissipated in J
      real(c_double) :: dissipated
      !> Relative error of the momentum against the initial one plus the outside
      !> impulses (gravity's M g t and the walls')
      real(c_double) :: momentum_error
      !> The impulses the left and right walls gave the system (N s, along the line)
      real(c_double) :: wall_impulse_left, wall_impulse_right
      !> Every contact, also those beyond the caller's capacity
      integer(c_int64_t) :: n_contacts
      !> Contacts written to the caller's array
      integer(c_int64_t) :: contacts_recorded
      !> Contacts by the closed forms, by integration
      integer(c_int64_t) :: closed_form_contacts
      integer(c_int64_t) :: integrated_contacts
      !> CVODE's steps, right-hand sides, Jacobians, roots; clusters integrated
      integer(c_int64_t) :: steps
      integer(c_int64_t) :: rhs_evals
      integer(c_int64_t) :: jacobian_evals
      integer(c_int64_t) :: roots
      integer(c_int64_t) :: clusters
      !> HCIMPACT_CHAIN_BY_CLOSED_FORMS (1), _BY_INTEGRATION (2) or _BY_BOTH (3)
      integer(c_int) :: method_used
      !> 1 when the system came to rest on a wall under gravity, else 0
      integer(c_int) :: rested
   end type hcimpact_chain_result

   !> typedef struct { double t_start, t_end, approach_speed, separation_speed,
   !> peak_force, max_deformation, dissipated; int pair, method; }
   !> hcimpact_chain_contact;
   type, bind(C) :: hcimpact_chain_contact
      !> Start and end in s
      real(c_double) :: t_start
      real(c_double) :: t_end
      !> Approach and separation speeds in m/s
      real(c_double) :: approach_speed
      real(c_double) :: separation_speed
      !> Largest force in N, largest deformation in m, energy dissipated in J
      real(c_double) :: peak_force
      real(c_double) :: max_deformation
      real(c_double) :: dissipated
      !> The pair: 0 left wall, i bodies i and i+1 (counted from 1), n right wall
      integer(c_int) :: pair
      !> HCIMPACT_CHAIN_BY_CLOSED_FORMS (1) or HCIMPACT_CHAIN_BY_INTEGRATION (2)
      integer(c_int) :: method
   end type hcimpact_chain_contact

   !> typedef struct { int count; const double *times; double *positions,
   !> *velocities, *forces; } hcimpact_chain_samples;
   type, bind(C) :: hcimpact_chain_samples
      !> Number of sample times, >= 0
      integer(c_int) :: count
      !> const double[count]: the times in s, not decreasing, >= 0
      type(c_ptr) :: times
      !> double[count][n], double[count][n], double[count][n + 1], each or NULL
      type(c_ptr) :: positions
      type(c_ptr) :: velocities
      type(c_ptr) :: forces
   end type hcimpact_chain_samples

contains

   !> The Fortran law of a C one.
   elemental function to_law(c) result(law)
      !> C structure
      type(hcimpact_chain_law), intent(in) :: c
      !> Fortran type
      type(contact_law) :: law
      law = contact_law(stiffness=real(c%stiffness, wp), exponent=real(c%exponent, wp), &
         & damping=real(c%damping, wp))
   end function to_law

   !> The Fortran law of a C wall (its gap aside).
   elemental function wall_law(c) result(law)
      !> C structure
      type(hcimpact_chain_wall), intent(in) :: c
      !> Fortran type
      type(contact_law) :: law
      law = contact_law(stiffness=real(c%stiffness, wp), exponent=real(c%exponent, wp), &
         & damping=real(c%damping, wp))
   end function wall_law

   !> Options from their values, 0 standing for the default of rtol, the integrator and
   !> the two limits (other values are the validator's to judge, hcimpact_chain_types).
   pure function chain_options_from(t_end, rtol, method, integrator, max_steps, &
         & max_events) result(options)
      !> End time in s (<= 0: until no contact can happen again)
      real(wp), intent(in) :: t_end
      !> Relative tolerance (0: the default)
      real(wp), intent(in) :: rtol
      !> Method code (0 auto, 1 exact, 2 integrated)
      integer, intent(in) :: method
      !> Integrator code (0: the default, BDF)
      integer, intent(in) :: integrator
      !> Limits of the steps and of the contacts computed (0: the defaults)
      integer(int64), intent(in) :: max_steps, max_events
      !> The options
      type(chain_options) :: options
      options%t_end = t_end
      if (rtol /= 0.0_wp) options%rtol = rtol
      options%method = method
      options%integrator = integrator_bdf
      if (integrator /= 0) options%integrator = integrator
      if (max_steps /= 0) options%max_steps = max_steps
      if (max_events /= 0) options%max_events = max_events
   end function chain_options_from

   !> The Fortran options of C ones (the capacity of the caller's contact array bounds
   !> the contacts recorded).
   pure function to_options(c, capacity) result(options)
      !> C structure
      type(hcimpact_chain_options), intent(in) :: c
      !> Contacts the caller can take, >= 0
      integer, intent(in) :: capacity
      !> Fortran type
      type(chain_options) :: options
      options = chain_options_from(real(c%t_end, wp), real(c%rtol, wp), int(c%method), &
         & int(c%integrator), int(c%max_steps, int64), int(c%max_events, int64))
      options%max_contacts = capacity
   end function to_options

   !> The caller's function on the time and work of the run: true when it says stop
   !> (nonzero).
   logical function c_monitor_poll(self, time, steps, events) result(stop)
      class(c_monitor), intent(inout) :: self
      real(wp), intent(in) :: time
      integer(int64), intent(in) :: steps, events
      procedure(c_poll), pointer :: poll
      call c_f_procpointer(self%c%poll, poll)
      stop = poll(self%c%data, real(time, c_double), int(steps, c_int64_t), &
         & int(events, c_int64_t)) /= 0_c_int
   end function c_monitor_poll

   !> The C result of a Fortran one.
   pure function from_result(result) result(c)
      !> Fortran type
      type(chain_result), intent(in) :: result
      !> C structure
      type(hcimpact_chain_result) :: c
      c%time = result%time
      c%rest_time = result%rest_time
      c%initial_energy = result%initial_energy
      c%energy_error = result%energy_error
      c%dissipated = result%dissipated
      c%momentum_error = result%momentum_error
      c%wall_impulse_left = result%wall_impulse(1)
      c%wall_impulse_right = result%wall_impulse(2)
      c%n_contacts = result%n_contacts
      c%contacts_recorded = 0
      if (allocated(result%contacts)) c%contacts_recorded = size(result%contacts)
      c%closed_form_contacts = result%counters%closed_form_contacts
      c%integrated_contacts = result%counters%integrated_contacts
      c%steps = result%counters%steps
      c%rhs_evals = result%counters%rhs_evals
      c%jacobian_evals = result%counters%jacobian_evals
      c%roots = result%counters%roots
      c%clusters = result%counters%clusters
      c%method_used = result%method_used
      c%rested = merge(1_c_int, 0_c_int, result%rested)
   end function from_result

   !> The result of a call that failed: NaN in every real, 0 in every count.
   pure function failed_result() result(c)
      !> C structure
      type(hcimpact_chain_result) :: c
      c = hcimpact_chain_result(time=nan, rest_time=nan, initial_energy=nan, &
         & energy_error=nan, dissipated=nan, momentum_error=nan, wall_impulse_left=nan, &
         & wall_impulse_right=nan, n_contacts=0, &
         & contacts_recorded=0, closed_form_contacts=0, integrated_contacts=0, steps=0, &
         & rhs_evals=0, jacobian_evals=0, roots=0, clusters=0, method_used=0, rested=0)
   end function failed_result

   !> The C record of a Fortran contact.
   elemental function from_contact(record) result(c)
      !> Fortran type
      type(contact_record), intent(in) :: record
      !> C structure
      type(hcimpact_chain_contact) :: c
      c%t_start = record%t_start
      c%t_end = record%t_end
      c%approach_speed = record%approach_speed
      c%separation_speed = record%separation_speed
      c%peak_force = record%peak_force
      c%max_deformation = record%max_deformation
      c%dissipated = record%dissipated
      c%pair = record%pair
      c%method = record%method
   end function from_contact

end module hcimpact_cvode_chain_capi_types
