// impact_rebound: the rebound speed of a particle that yields throughout.
//
// Reference (closed form): once the whole particle has flowed, the elastic
// energy it can give back is bounded by the flow stress, and its rebound is
// set by the elastic unloading wave: the particle speed behind an elastic bar
// wave of amplitude Y,
//     v_r = Y / (rho c_0) = Y / sqrt(rho E),
// the elastic recovery of Taylor's rod-impact analysis (G. I. Taylor, "The
// use of flat-ended projectiles for determining dynamic yield stress I",
// Proc. R. Soc. Lond. A 194 (1948) 289). It is independent of the impact
// speed and linear in Y, unlike Johnson's V^(-1/4) law for contained
// plasticity (K. L. Johnson, Contact Mechanics, 1985, ch. 11), which gives
// v_r ~ Y^(5/8) and holds only while the plastic zone is small against the
// particle (rho V^2 / Y << 0.1; here rho V^2 / Y = 0.09 to 0.37).
//
// The scene: scenes/impact_al_al.json without adhesion, its al-thesis
// material made elastic-perfectly plastic (B = 0, C = 0, no damage, no
// heating), Y = 74.2, 148.4 and 296.8 MPa, 100 m/s, at 12 and 24 elements
// across. Tolerance 15 % of v_r: the closed form ignores the substrate's
// share of the recovery and the wave radiated into it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"

namespace splat {
namespace {

using nlohmann::json;

const std::filesystem::path k_source(SPLAT_SOURCE_DIR);

json perfectly_plastic_al(double yield) {
  std::ifstream in(k_source / "materials" / "al-thesis.json");
  json m = json::parse(in);
  m["name"] = "al-perfectly-plastic";
  m["strength"]["A"] = yield;
  m["strength"]["B"] = 0.0;
  m["strength"]["C"] = 0.0;
  m["thermal"]["heat_fraction"] = 0.0;
  m.erase("damage");
  return m;
}

struct Rebound {
  std::string outcome;
  double speed = 0.0;  // m/s
};

Rebound rebound(double yield, int across) {
  const std::vector<std::string> sets = {
      "/particle_impact/adhesion/G_c=0", "/particle_impact/velocity=100",
      "/particle_impact/particle/elements_across=" + std::to_string(across),
      "/particle_impact/particle/material=" + perfectly_plastic_al(yield).dump()};
  LoadedScene loaded = load_scene(k_source / "scenes" / "impact_al_al.json", sets);
  loaded.scene.time.wall_clock_limit = 120.0;
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const json s = to_json(sim.run());
  return {s.value("outcome", ""), s.value("rebound_velocity", 0.0)};
}

TEST(impact_rebound, a_fully_yielded_particle_rebounds_at_the_elastic_wave_speed_of_its_yield) {
  const double rho = 2710.0, E = 70.9e9;  // al-thesis
  for (const double yield : {74.2e6, 148.4e6, 296.8e6}) {
    const double expected = yield / std::sqrt(rho * E);
    for (const int across : {12, 24}) {
      const Rebound r = rebound(yield, across);
      std::printf("  Y %6.1f MPa, %2d across: %s at %6.2f m/s, Y / sqrt(rho E) %6.2f m/s\n",
                  yield / 1e6, across, r.outcome.c_str(), r.speed, expected);
      EXPECT_EQ(r.outcome, "rebound");
      EXPECT_NEAR(r.speed, expected, 0.15 * expected) << "Y " << yield << " Pa, " << across;
    }
  }
}

}  // namespace
}  // namespace splat
