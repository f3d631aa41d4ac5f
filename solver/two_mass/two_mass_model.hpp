// The two-mass adhesion problem (thesis 3.5.1.1), the cheapest scene splat
// runs: rigid mass M, velocity V0 along +x, touches at t = 0 the rigid mass m
// that rests on a spring k (rest position x = 0):
//
//     M --V0-->|m|--/\/\/\/--||    gap g = x_m - x_M >= 0, opening rate g_dot
//
// Time integration: explicit central differences with the discrete pair
// treatment the FE contact stage uses, one pair, h = 1/M + 1/m. One step:
//   1. update   v_free = v_{n-1/2} + dt (-k x_m / m) for m; M is force-free.
//   2. contact  if the predicted gap g_n + dt g_free would be negative, a
//               compressive Lagrange multiplier sets the closing rate to
//               max(-g_n / dt, -e g_prev): no penetration, and Newton's
//               impact law with restitution e = 1 on the rate at the start
//               of the step (Moreau-Jean), so the rigid collision is elastic
//               (thesis eq. 3.1: momentum and kinetic energy conserved).
//   3. link     next_link_state (activation none: active on first touch),
//               then cohesive_step: a tension impulse up to sigma_c A dt
//               (or holding the pair without a cap) against the opening
//               rate left after the contact, its work charged to G_c A.
//   4. predict  x_{n+1} = x_n + dt v_{n+1/2}.
//   5. decide   rebound: the link is exhausted and the masses can no longer
//               meet (k = 0: opening; k > 0: M moves away and is beyond the
//               reach of m's oscillation); stick: the link holds the pair in
//               contact and can carry the largest tension the remaining
//               motion needs (k = 0: none; k > 0: M k A / (M + m) for the
//               joint oscillation of amplitude A), so nothing will change;
//               or (k > 0) the remaining budget exceeds all the mechanical
//               energy left, so the link can never let go (the summary's
//               final velocities are then those at that moment).
// For k = 0 the separation velocity is exact for any dt (momentum and the
// energy-exact work rule); the release time converges at first order. For
// k > 0 everything converges at first order (impact inside a step).
//
// Without a cap (Griffith form) and with k > 0 the holding multiplier does no
// work (the rate is held at 0 before and after the step; cohesive_law.hpp),
// and the rigid masses store no energy under the link force (compliance 0):
// the link dissipates only on velocity jumps (the impacts).
#pragma once

#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "solver/core/run_summary.hpp"
#include "solver/core/simulation.hpp"
#include "solver/scene/scene.hpp"

namespace splat {

// One history record, SI units; positions and velocities along +x.
struct TwoMassRow {
  double t = 0.0;               // s
  double x_M = 0.0, x_m = 0.0;  // m
  double v_M = 0.0, v_m = 0.0;  // m/s, over the step that ended at t
  double gap = 0.0;             // m, x_m - x_M
  double link_force = 0.0;      // N, tension of the link over the step
  double contact_force = 0.0;   // N, compression of the contact over the step
  double link_work = 0.0;       // J, accumulated
  double kinetic = 0.0;         // J
  double spring = 0.0;          // J, k x_m^2 / 2
  double balance_error = 0.0;   // (kinetic + spring + link_work - initial) / initial, -
  int link_state = 0;           // LinkState as a number: 0 none .. 4 eroded
};

struct TwoMassRun {
  RunOutcome outcome = RunOutcome::stick;
  std::string reason;
  std::optional<StopReason> stop_reason;  // set when the run stops
  long long steps = 0;
  double time = 0.0;  // s
  EnergyBudget energy;
  TwoMassSummary figures;
};

// Time step when the scene gives none: 1/2000 of the shortest of the spring
// period 2 pi sqrt(m/k), the time mu V0 / (sigma_c A) the cap needs to stop
// the opening (mu = M m / (M + m)) and the end time.
double two_mass_default_dt(const TwoMassSpec& spec, double end_time);

// Integrates from first touch until decided or the end time. `record` (if
// set) receives the initial state and every step. Never throws unless
// `record` does.
TwoMassRun integrate_two_mass(const TwoMassSpec& spec, const TimeSpec& time,
                              const std::function<void(const TwoMassRow&)>& record = {},
                              const std::atomic<bool>* cancel = nullptr);

// `splat run` of a two-mass scene: integrate_two_mass, with the histories in
// DIR/<scene>.h5 (columns of TwoMassRow, units as attributes) when
// options.output_dir is set. Never throws.
RunSummary run_two_mass(const Scene& scene, const nlohmann::json& resolved,
                        const SimulationOptions& options);

}  // namespace splat
