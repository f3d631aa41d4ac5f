// Why a run stopped: the short machine-readable cause beside its outcome
// (run_summary.hpp). Its name is the `stop_reason` of the run summary
// (schemas/result.schema.json) and of the result file.
#pragma once

#include "solver/common/enum_names.hpp"

namespace splat {

enum class StopReason {
  // The run's own end.
  end_time,         // reached the end time
  verdict_settled,  // impact: the verdict held for the hold time (adaptive end)
  max_time,         // impact: the adaptive end reached max_time unsettled
  // Impact runs that ended without a verdict (impact_run.hpp).
  undecided,      // no verdict at the end
  erosion_limit,  // more of the particle eroded than max_eroded_fraction
  // Physics checks (physics_guard.hpp).
  interpenetration,
  negative_eroded_energy,
  negative_internal_energy,
  plastic_work_excess,  // more plastic work than internal energy
  // Numerical checks of every step (simulation.cpp).
  non_finite,
  time_step_collapse,
  energy_balance,
  return_mapping,     // the strength law's return mapping did not converge
  element_inverted,   // an FE element with non-positive volume, erosion off
  particle_inverted,  // an SPH particle with det F <= 0
  // Limits and interruptions.
  cancelled,
  wall_clock_limit,
  step_limit,
  error,  // could not run or write its output
  // Two-mass scenes (two_mass_model.hpp).
  separated,              // rebound: the masses can no longer meet
  settled,                // stick: nothing will change
  budget_exceeds_energy,  // stick: the link can never let go
  end_time_predicted,     // rebound of free masses still opening at the end time
};

inline constexpr NameTable<StopReason, 23> k_stop_reason_names{{
    {StopReason::end_time, "end-time"},
    {StopReason::verdict_settled, "verdict-settled"},
    {StopReason::max_time, "max-time"},
    {StopReason::undecided, "undecided"},
    {StopReason::erosion_limit, "erosion-limit"},
    {StopReason::interpenetration, "interpenetration"},
    {StopReason::negative_eroded_energy, "negative-eroded-energy"},
    {StopReason::negative_internal_energy, "negative-internal-energy"},
    {StopReason::plastic_work_excess, "plastic-work-excess"},
    {StopReason::non_finite, "non-finite"},
    {StopReason::time_step_collapse, "time-step-collapse"},
    {StopReason::energy_balance, "energy-balance"},
    {StopReason::return_mapping, "return-mapping"},
    {StopReason::element_inverted, "element-inverted"},
    {StopReason::particle_inverted, "particle-inverted"},
    {StopReason::cancelled, "cancelled"},
    {StopReason::wall_clock_limit, "wall-clock-limit"},
    {StopReason::step_limit, "step-limit"},
    {StopReason::error, "error"},
    {StopReason::separated, "separated"},
    {StopReason::settled, "settled"},
    {StopReason::budget_exceeds_energy, "budget-exceeds-energy"},
    {StopReason::end_time_predicted, "end-time-predicted"},
}};
static_assert(names_in_order(k_stop_reason_names));

constexpr const auto& names_of(StopReason) {
  return k_stop_reason_names;
}

}  // namespace splat
