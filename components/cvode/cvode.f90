! SPDX-License-Identifier: Apache-2.0
!> Public Fortran API of the CVODE component (hcimpact::cvode): the impact integrated
!> by SUNDIALS CVODE, for comparison with the closed forms and for what has no closed
!> form (a user's elastic law, an external force).
!>
!> `use hcimpact_cvode` brings in everything; `use hcimpact` is still needed for the
!> core (contact_type, outcome_type, the closed forms, the status codes).
module hcimpact_cvode
   use hcimpact_cvode_system, only : external_force, external_force_value
   use hcimpact_cvode_solver, only : cvode_options, cvode_counters, simulation_type, &
      & simulate, simulate_power, simulate_law, cvode_bdf, cvode_adams, cvode_flag_name
   use hcimpact_cvode_sundials, only : sundials_major
   use hcimpact_cvode_chain, only : chain_simulate
   implicit none
   public

end module hcimpact_cvode
