! SPDX-License-Identifier: Apache-2.0
!> Systems of bodies on a line with the core alone: `chain_exact` computes every contact
!> by the closed forms of one impact and refuses clusters, which need the CVODE component (hcimpact_cvode_chain: `chain_simulate`). The types
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

   !> A system of bodies on a line by the closed forms alone: exact while every contact
   !> is isolated. A cluster of overlapping contacts (or a wall contact under gravity
   !> that gravity changes) is hcimpact_err_unavailable with options%method auto (the
   !> default: it needs the CVODE component; the message says which contacts) and
   !> hcimpact_err_domain with method exact (as in chain_simulate); method integrated is
   !> hcimpact_err_unavailable. The other statuses: those of chain_simulate.
   subroutine chain_exact(chain, result, stat, options)
      !> The system
      type(chain_type), intent(in) :: chain
      !> What is computed
      type(chain_result), intent(out) :: result
      !> Status: hcimpact_ok or an error code of hcimpact_status
      integer, intent(out) :: stat
      !> How (without CVODE: method auto or exact)
      type(chain_options), intent(in), optional :: options
      type(chain_options) :: opts
      ! (the options as given: a copy would allocate their sample times unchecked)
      if (present(options)) then
         call run_engine(chain, options, result, stat)
      else
         call run_engine(chain, opts, result, stat)
      end if
   end subroutine chain_exact

end module hcimpact_chain
