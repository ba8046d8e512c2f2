! SPDX-License-Identifier: Apache-2.0
!> Public Fortran API of hcimpact: the Hunt-Crossley model of a collinear impact.
!>
!> `use hcimpact` brings in everything a caller needs; the modules behind it may
!> also be used one by one.
module hcimpact
   use hcimpact_kinds, only : wp
   use hcimpact_version_info, only : hcimpact_version_string, hcimpact_version_compact, &
      & get_hcimpact_version
   use hcimpact_lambertw, only : lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1, &
      & lambert_w0p1_dd, lambert_wm1p1_dd
   use hcimpact_restitution_law, only : u_minus_log1p, restitution, one_minus_restitution, &
      & energy_loss_ratio, restitution_derivative, restitution_inverse
   use hcimpact_status, only : status_message, hcimpact_ok, hcimpact_err_not_finite, &
      & hcimpact_err_mass, hcimpact_err_stiffness, hcimpact_err_exponent, &
      & hcimpact_err_velocity, hcimpact_err_damping, hcimpact_err_restitution, &
      & hcimpact_err_domain, hcimpact_err_no_convergence, hcimpact_err_null, &
      & hcimpact_err_solver, hcimpact_err_unavailable, hcimpact_err_elastic_law, &
      & hcimpact_err_size, hcimpact_err_underdetermined, hcimpact_err_out_of_memory
   use hcimpact_quadrature, only : integrand_type, quadrature_result, tanh_sinh, &
      & quadrature_status_message
   use hcimpact_impact_model, only : contact_type, outcome_type, impact, impact_law, &
      & velocity_at_depth, time_law, time_law_samples, damping_for_restitution, &
      & default_min_velocity, compression_branch, restitution_branch
   use hcimpact_hertz, only : hertz_constant, effective_mass, two_body_velocities
   use hcimpact_elastic, only : elastic_law, power_law
   use hcimpact_force_element, only : contact_force_type, contact_force, contact_force_pair, &
      & contact_force_wall
   use hcimpact_chain, only : chain_exact, contact_law, chain_type, chain_options, &
      & contact_record, chain_result, chain_counters, chain_switch
   use hcimpact_legacy_damping, only : n_damping_rules, damping_rule_names, legacy_damping
   use hcimpact_parallel, only : array_threads
   implicit none
   public

end module hcimpact
