// The impact run: follows a particle_impact scene through the time loop with
// the stick/rebound monitor (impact_verdict.hpp), says when an adaptive run
// may stop, and turns the final state into the impact figures of the summary.
//
// Every step (after the diagnostics) it samples, in the user frame (z up, the
// substrate normal n = +z):
//   v_p, v_s   centre-of-mass velocities of particle and substrate (zero for a
//              rigid wall), m/s
//   v_n        (v_p - v_s) . n, positive away from the substrate, m/s
//   K_rel      1/2 M_p |v_p - v_s|^2, J
//   links      active links, pairs carrying a compressive force and bonded
//              area of the particle-substrate contact (rigid wall: particle
//              nodes on the wall). Links of an interface with G_c = 0 cannot
//              hold anything (their budget is empty): the monitor sees none,
//              so a particle resting in its crater without adhesion energy
//              is not called stuck (the thesis's criteria, which count them,
//              may still say stick).
// Hold time of a verdict: k_hold_transits particle transits R / c_p (c_p the
// particle's P-wave speed), long enough for the elastic ringing of the
// particle after the impact to pass through one period of its lowest modes.
//
// Figures at the end (ImpactSummary, run_summary.hpp):
//   rebound_velocity             v_n at the end
//   coefficient_of_restitution   max(v_n, 0) / v_impact
//   bonded_area                  area of the active links at the end, m^2
//   contact_area                 tributary area of the particle's surface
//                                nodes that touched the substrate at least
//                                once, on the final geometry, m^2
//   bonded_fraction              bonded_area / contact_area
//   flattening_ratio             final lateral diameter of the particle / 2R
//   penetration_depth            depth of the particle's lowest point below
//                                the undeformed substrate surface z = 0, m
//   thesis criteria              at least one active link at the end; active
//                                links > 1 % of the most ever active
#pragma once

#include <optional>

#include "solver/core/impact_verdict.hpp"
#include "solver/core/model_builder.hpp"
#include "solver/core/physics_guard.hpp"
#include "solver/core/run_summary.hpp"
#include "solver/io/result_file.hpp"
#include "solver/scene/scene.hpp"

namespace splat {

class ImpactRun {
 public:
  // `model` is the built model of the expanded scene; `max_time` its end
  // time; `energy_limit` its energy_balance_limit (the physics guard's
  // tolerance on the energy terms).
  ImpactRun(const ImpactSpec& spec, const Model& model, double max_time, double energy_limit);

  // Feeds the state after a step; returns the settled decision once there is
  // one (an adaptive run stops on it, a fixed one keeps going).
  std::optional<VerdictDecision> observe(double time, const Model& model);

  // Fills s.impact from the final state. A run that ended on its own terms
  // (stop_reason end-time, or a settled verdict passed in `settled`) and
  // passes the physics guard (physics_guard.hpp) gets the verdict as its
  // outcome (stick / rebound) with its reason and stop_reason
  // (verdict-settled, max-time or end-time); one that fails the guard, or
  // whose verdict at the maximum time is undecided, ends unstable with the
  // check's name as stop_reason; any other ending (unstable, timed-out,
  // cancelled, error) keeps its outcome and reason.
  void finish(RunSummary& s, const Model& model, const std::optional<VerdictDecision>& settled);

  double hold_time() const { return settings_.hold_time; }

 private:
  ImpactSample sample(double time, const Model& model) const;
  // The process zone of the interface law against the particle's surface
  // element size (ImpactSummary::cohesive_zone_*).
  void cohesive_zone(const Model& model, ImpactSummary& r) const;
  // Mean height of the particle nodes with active links, m.
  double bonded_height(const Model& model) const;
  // The particle's flattening ratio and penetration depth.
  void particle_shape(const Model& model, ImpactSummary& r) const;
  // Links, contact and bonded area, cohesive zone.
  void interface_figures(const Model& model, const ImpactSample& now, ImpactSummary& r) const;
  // Share of the FE particle's mass eroded (SPH particles are never deleted).
  double eroded_fraction(const Model& model) const;
  // Whether a run that ended on its own terms may report a verdict: not
  // beyond the erosion limit nor past a failed physics guard (the outcome
  // and reason then say why; r.guard gets the guard's figures).
  bool verdict_allowed(RunSummary& s, const Model& model, bool own_end, ImpactSummary& r) const;
  void apply_decision(RunSummary& s, ImpactSummary& r, const VerdictDecision& decision,
                      bool settled) const;

  ImpactSpec spec_;
  VerdictSettings settings_;
  ImpactMonitor monitor_;
  double max_time_ = 0.0;
  double energy_limit_ = 0.0;
  int particle_ = -1;        // scene body index (model.body_refs), FE or SPH
  int substrate_ = -1;       // scene body index, -1: rigid wall
  int contact_ = -1;         // contact interface index, -1: rigid wall
  bool links_hold_ = false;  // the interface has adhesion with G_c > 0
  double radius_ = 0.0;
  double half_spacing_ = 0.0;      // SPH particle: its pinball radius, added to extents, m
  double initial_kinetic_ = -1.0;  // J, of the particle at the first sample
  ImpactSample last_;
  // The interpenetration guard sampled every particle transit R / c_p
  // while the run goes on and neither body has eroded (erosion bares nodes
  // that lay inside an element, which contact then pushes out over some
  // steps: seen 0.6-1.9 element sizes deep in FE Cu/Cu, Ag and Zn runs at
  // 700-800 m/s that end clean); its worst sample kept for finish.
  double guard_interval_ = 0.0;   // s
  double next_guard_time_ = 0.0;  // s
  Interpenetration worst_;
};

// The impact figures of s.impact (set) as root attributes of the result
// file, under the summary's names; nested keys joined by a dot (links.active,
// energy.initial_kinetic, thesis_criteria.active_link as 0 / 1, model.name).
// outcome, reason, stop_reason, steps and end_time are written by the run.
void write_impact_attributes(ResultFile& file, const RunSummary& s);

}  // namespace splat
