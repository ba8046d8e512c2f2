! SPDX-License-Identifier: Apache-2.0
!> Systems of bodies on a line with the core alone: `chain_exact` computes every contact
!> by the closed forms of one impact and refuses clusters (hcimpact_err_unavailable),
!> which need the CVODE component (hcimpact_cvode_chain: `chain_simulate`). The types
!> and conventions are those of hcimpact_chain_types; the engine is
!> hcimpact_chain_engine; doc/chains.md.
module hcimpact_chain
   use hcimpact_chain_types, only : contact_law, chain_type, chain_options, contact_record, &
      & chain_result, chain_counters, chain_switch, method_auto, method_exact, &
      & method_integrated, integrator_bdf, integrator_adams, by_closed_forms, by_integration
   use hcimpact_chain_engine, only : run_engine
   implicit none
   private

   public :: chain_exact
   public :: contact_law, chain_type, chain_options, contact_record, chain_result, &
      & chain_counters, chain_switch, method_auto, method_exact, method_integrated, &
      & integrator_bdf, integrator_adams, by_closed_forms, by_integration

contains

   !> A system of bodies on a line by the closed forms alone (options%method is taken
   !> as method_exact): exact while every contact is isolated; a cluster of
   !> overlapping contacts is hcimpact_err_unavailable (its message says which), as is
   !> a wall contact under gravity. The other statuses: those of chain_simulate.
   subroutine chain_exact(chain, result, stat, options)
      !> The system
      type(chain_type), intent(in) :: chain
      !> What is computed
      type(chain_result), intent(out) :: result
      !> Status: hcimpact_ok or an error code of hcimpact_status
      integer, intent(out) :: stat
      !> How (the method is exact whatever it says)
      type(chain_options), intent(in), optional :: options
      type(chain_options) :: opts
      if (present(options)) opts = options
      opts%method = method_exact
      call run_engine(chain, opts, result, stat)
   end subroutine chain_exact

end module hcimpact_chain
