// The campaign behind `splat window`: from a material pair, a particle
// radius, a velocity range and an accuracy to a campaign document
// (schemas/campaign.schema.json). Pure functions; the campaign is read and
// run like any other.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>

namespace splat::campaign {

// Elements across the particle radius of each level of `--accuracy
// converged`, coarse to fine: a constant ratio, so each edge is extrapolated.
inline constexpr std::array<int, 3> k_converged_ladder{8, 16, 32};

// k_converged_ladder as text: "8, 16, 32".
std::string converged_ladder_text();

struct VelocityRange {
  double from = 100.0;  // m/s
  double to = 1200.0;   // m/s
  double step = 100.0;  // m/s
};

struct WindowRequest {
  std::string particle;           // library name or material file
  std::string substrate;          // empty: the particle's material
  double radius = 12.5e-6;        // m
  VelocityRange velocity;         // grid of the coarsest level
  std::string accuracy = "fast";  // fast: 16 elements across; converged: k_converged_ladder
  double G_c = 30.0;              // J/m^2
  int workers = 1;                // jobs run at once; also the refinement's points per round
};

// Most new velocities a refinement round runs per window (the schema's
// maximum of refinement.points_per_round).
inline constexpr int k_max_points_per_round = 64;

// "FROM:TO" or "FROM:TO:STEP" in m/s (default step 100). Throws InputError
// naming --velocity.
VelocityRange parse_velocity_range(const std::string& text);

// splat's bonding model (as scenes/impact_al_al_expansion.json): links
// capped at the weaker side's flow stress, activated where the surfaces of
// both sides have grown to Bay's surface expansion 0.3, each bonding only
// the metal exposed through the cracked films (film-cracks), never eroded;
// G_c in J/m^2.
nlohmann::json bonding_model(double G_c);

// The campaign document of a request: axisymmetric FE impacts, the velocity
// grid, refinement to 25 m/s (fast) or 10 m/s (converged) with a guard band
// of twice the tolerance and as many points per round as workers (at most
// k_max_points_per_round), and for `converged` the elements_across ladder
// k_converged_ladder refined coarse to fine. Throws InputError naming the
// option for a radius, accuracy, G_c or worker count out of range.
nlohmann::json window_campaign(const WindowRequest& request);

}  // namespace splat::campaign
