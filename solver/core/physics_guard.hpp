// Physics checks a run must pass before it may report a verdict. A run whose
// physics broke (a body through the other, energy created) ends `unstable`
// with the check's name and figures instead of a stick or rebound.
//
// Interpenetration. For every live node of the particle (FE node or SPH
// particle centre) that lies inside a live element of an FE substrate, the
// depth is its distance to the substrate's live contact surface (master
// faces of the interface). The check fails when a depth exceeds
// k_interpenetration_limit times the characteristic length of the element
// holding the node: contact keeps a node on the surface to within a small
// fraction of an element, so a node an element-half deep has gone through.
// SPH substrates are not checked (the figures then read "not checked").
//
// Energy. The eroded energy (kinetic + internal energy the erosion took out)
// and the internal energy are sums of non-negative terms; either below
// -energy_limit x the reference energy means the bookkeeping broke.
#pragma once

#include <optional>
#include <string>

#include "solver/core/model_builder.hpp"
#include "solver/core/run_summary.hpp"

namespace splat {

// Depth over the local element size above which a node has gone through, -.
inline constexpr double k_interpenetration_limit = 0.5;

struct GuardInput {
  int particle = -1;          // scene body index of the particle
  int substrate = -1;         // scene body index of the substrate, -1: rigid wall
  int contact = -1;           // contact interface index, -1: none
  double energy_limit = 0.0;  // the scene's energy_balance_limit, -
};

// Checks `model` and `energy`; fills `figures` (always) and returns the first
// failed check (none when all pass), with its reason in `reason`.
std::optional<StopReason> check_physics(const Model& model, const EnergyBudget& energy,
                                        const GuardInput& in, GuardFigures& figures,
                                        std::string& reason);

// Deepest live particle node inside a live substrate element (above), and
// how many nodes are deeper than the limit.
struct Interpenetration {
  bool checked = false;
  double max_depth = 0.0;  // m
  double max_ratio = 0.0;  // depth / element characteristic length, -
  long long nodes_through = 0;
};
Interpenetration measure_interpenetration(const Model& model, const GuardInput& in);

}  // namespace splat
