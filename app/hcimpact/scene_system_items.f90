! SPDX-License-Identifier: Apache-2.0
!> The items of the output `system_sweep` (doc/scenes.md): each variation of a scene's
!> system of bodies as a column of doubles (the whole system, so that any process can
!> compute it from the column alone: MPI ranks receive nothing else), its run
!> (`chain_simulate` through hcimpact_scene_ode, or the closed forms alone in a build
!> without CVODE) and the result as a column of doubles. The same doubles go in and
!> come out on every process, so the rows of a sweep handed out over MPI ranks or
!> OpenMP threads are those of a serial run.
module hcimpact_scene_system_items
   use hcimpact_kinds, only : wp
   use hcimpact_chain_types, only : chain_type, chain_options, chain_result
   use hcimpact_scene_model, only : system_type, nan, n_sweep_lists, sweep_striker_speed, &
      & sweep_mass, sweep_gap, sweep_stiffness, sweep_exponent, sweep_b, sweep_restitution, &
      & sweep_gravity, sweep_left_gap, sweep_right_gap, sweep_left_b, sweep_right_b, &
      & sweep_left_stiffness, sweep_right_stiffness, sweep_left_exponent, &
      & sweep_right_exponent, sweep_t_end
   use hcimpact_scene_ode, only : ode_chain
   use hcimpact_scene_variations, only : variation_index, variation_count
   implicit none
   private

   public :: system_item_count, system_item_inputs, item_variation, compute_system_item
   public :: result_length, result_status, result_time, result_contacts, &
      & result_closed_forms, result_integrated, result_clusters, result_steps, &
      & result_energy_error, result_dissipated, result_method, result_velocities

   !> Where each value stands in a result column (the final velocities follow)
   integer, parameter :: result_status = 1, result_time = 2, result_contacts = 3, &
      & result_closed_forms = 4, result_integrated = 5, result_clusters = 6, &
      & result_steps = 7, result_energy_error = 8, result_dissipated = 9, &
      & result_method = 10, result_velocities = 11

contains

   !> How many variations the system's sweep has (1: the system alone).
   pure integer function system_item_count(sys) result(items)
      type(system_type), intent(in) :: sys
      items = variation_count(list_lengths(sys), sys%vary_product)
   end function system_item_count

   !> The lengths of the sweep's lists (0: not varied)
   pure function list_lengths(sys) result(lengths)
      type(system_type), intent(in) :: sys
      integer :: lengths(n_sweep_lists)
      integer :: k
      do k = 1, n_sweep_lists
         lengths(k) = size(sys%vary(k)%values)
      end do
   end function list_lengths

   !> The value of each parameter of `sweep_names` in variation k (NaN where the sweep
   !> does not vary it), and which value of its list that is. In a product the first
   !> list varies slowest.
   pure subroutine item_variation(sys, k, values, which)
      type(system_type), intent(in) :: sys
      integer, intent(in) :: k
      real(wp), intent(out) :: values(n_sweep_lists)
      integer, intent(out), optional :: which(n_sweep_lists)
      integer :: index(n_sweep_lists), j
      index = variation_index(list_lengths(sys), sys%vary_product, k)
      values = nan
      do j = 1, n_sweep_lists
         if (size(sys%vary(j)%values) > 0) values(j) = sys%vary(j)%values(index(j))
      end do
      if (present(which)) which = index
   end subroutine item_variation

   !> The columns of every variation: the system with what the sweep varies replaced
   !> (the speed of the bodies vary_striker_body, the mass of vary_mass_body, every pair's gap,
   !> stiffness, exponent and damping, b itself or from a restitution, gravity, the
   !> walls' gaps, damping, contact constants and exponents, the end time).
   pure function system_item_inputs(sys) result(inputs)
      type(system_type), intent(in) :: sys
      real(wp), allocatable :: inputs(:, :)
      type(system_type) :: varied
      real(wp) :: values(n_sweep_lists)
      integer :: k, which(n_sweep_lists)
      logical :: given(n_sweep_lists)
      given = list_lengths(sys) > 0
      allocate(inputs(input_length(sys%n), system_item_count(sys)))
      do k = 1, size(inputs, 2)
         call item_variation(sys, k, values, which)
         varied = sys
         if (given(sweep_striker_speed)) varied%velocity(sys%vary_striker_body) = &
            & values(sweep_striker_speed)
         if (given(sweep_mass)) varied%mass(sys%vary_mass_body) = values(sweep_mass)
         if (given(sweep_gap)) varied%gap = values(sweep_gap)
         if (given(sweep_stiffness)) varied%law%stiffness = values(sweep_stiffness)
         if (given(sweep_exponent)) varied%law%exponent = values(sweep_exponent)
         if (given(sweep_b)) varied%law%damping = values(sweep_b)
         if (given(sweep_restitution)) varied%law%damping = &
            & sys%vary_restitution_b(which(sweep_restitution))
         if (given(sweep_gravity)) varied%gravity = values(sweep_gravity)
         if (given(sweep_left_gap)) varied%left%gap = values(sweep_left_gap)
         if (given(sweep_right_gap)) varied%right%gap = values(sweep_right_gap)
         if (given(sweep_left_b)) varied%left%law%damping = values(sweep_left_b)
         if (given(sweep_right_b)) varied%right%law%damping = values(sweep_right_b)
         if (given(sweep_left_stiffness)) varied%left%law%stiffness = &
            & values(sweep_left_stiffness)
         if (given(sweep_right_stiffness)) varied%right%law%stiffness = &
            & values(sweep_right_stiffness)
         if (given(sweep_left_exponent)) varied%left%law%exponent = &
            & values(sweep_left_exponent)
         if (given(sweep_right_exponent)) varied%right%law%exponent = &
            & values(sweep_right_exponent)
         if (given(sweep_t_end)) varied%t_end = values(sweep_t_end)
         inputs(:, k) = packed_system(varied)
      end do
   end function system_item_inputs

   !> Doubles of an item's column for n bodies: n, masses, velocities, per pair the
   !> gap, c, n, b, per wall whether present, c, n, b and the gap, then gravity, t_end,
   !> rtol, the method and the integrator
   pure integer function input_length(n)
      integer, intent(in) :: n
      input_length = 1 + 2 * n + 4 * (n - 1) + 10 + 5
   end function input_length

   !> Doubles of a result column for n bodies
   pure integer function result_length(n)
      integer, intent(in) :: n
      result_length = result_velocities - 1 + n
   end function result_length

   !> A system as the doubles of its column.
   pure function packed_system(sys) result(values)
      type(system_type), intent(in) :: sys
      real(wp), allocatable :: values(:)
      values = [real(sys%n, wp), sys%mass, sys%velocity, sys%gap, sys%law%stiffness, &
         & sys%law%exponent, sys%law%damping, &
         & merge(1.0_wp, 0.0_wp, sys%left%present), sys%left%law%stiffness, &
         & sys%left%law%exponent, sys%left%law%damping, sys%left%gap, &
         & merge(1.0_wp, 0.0_wp, sys%right%present), sys%right%law%stiffness, &
         & sys%right%law%exponent, sys%right%law%damping, sys%right%gap, &
         & sys%gravity, sys%t_end, sys%rtol, real(sys%method, wp), real(sys%integrator, wp)]
   end function packed_system

   !> The library's system and options of a column.
   pure subroutine unpacked_system(values, chain, options)
      real(wp), intent(in) :: values(:)
      type(chain_type), intent(out) :: chain
      type(chain_options), intent(out) :: options
      integer :: n, p, w
      n = nint(values(1))
      p = 1 + 2 * n
      chain%mass = values(2:1 + n)
      chain%velocity = values(2 + n:1 + 2 * n)
      allocate(chain%gap(n - 1), chain%law(n - 1))
      chain%gap = values(p + 1:p + n - 1)
      chain%law%stiffness = values(p + n:p + 2 * (n - 1))
      chain%law%exponent = values(p + 2 * (n - 1) + 1:p + 3 * (n - 1))
      chain%law%damping = values(p + 3 * (n - 1) + 1:p + 4 * (n - 1))
      w = p + 4 * (n - 1)
      chain%left_wall = values(w + 1) /= 0.0_wp
      chain%left_law%stiffness = values(w + 2)
      chain%left_law%exponent = values(w + 3)
      chain%left_law%damping = values(w + 4)
      chain%left_gap = values(w + 5)
      chain%right_wall = values(w + 6) /= 0.0_wp
      chain%right_law%stiffness = values(w + 7)
      chain%right_law%exponent = values(w + 8)
      chain%right_law%damping = values(w + 9)
      chain%right_gap = values(w + 10)
      chain%gravity = values(w + 11)
      options%t_end = values(w + 12)
      options%rtol = values(w + 13)
      options%method = nint(values(w + 14))
      options%integrator = nint(values(w + 15))
   end subroutine unpacked_system

   !> The run of one item: its column in, its result out (status, end time, contacts
   !> and how they were computed, CVODE steps, the energy balance, the method used, the
   !> final velocities; NaN where a failed run has no value).
   subroutine compute_system_item(input, output)
      real(wp), intent(in) :: input(:)
      real(wp), intent(out) :: output(:)
      type(chain_type) :: chain
      type(chain_options) :: options
      type(chain_result) :: result
      integer :: stat, n
      call unpacked_system(input, chain, options)
      n = size(chain%mass)
      call ode_chain(chain, options, result, stat)
      output = nan
      output(result_status) = real(stat, wp)
      output(result_time) = result%time
      output(result_contacts) = real(result%n_contacts, wp)
      output(result_closed_forms) = real(result%counters%closed_form_contacts, wp)
      output(result_integrated) = real(result%counters%integrated_contacts, wp)
      output(result_clusters) = real(result%counters%clusters, wp)
      output(result_steps) = real(result%counters%steps, wp)
      output(result_energy_error) = result%energy_error
      output(result_dissipated) = result%dissipated
      output(result_method) = real(result%method_used, wp)
      if (allocated(result%velocities)) then
         if (size(result%velocities) == n) output(result_velocities:result_velocities + n &
            & - 1) = result%velocities
      end if
   end subroutine compute_system_item

end module hcimpact_scene_system_items
