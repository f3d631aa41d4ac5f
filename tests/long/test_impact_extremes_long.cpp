// impact_extremes (long part): the particle_impact scene
// (scenes/impact_al_al.json) at the largest resolution the schema allows (64
// elements across the radius) and at 16: each run ends with a valid summary,
// finite figures and a stated outcome. Minutes of CPU.
// Run with: ctest --test-dir build -L long -R impact_extremes --output-on-failure
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"

namespace splat {
namespace {

using nlohmann::json;

void expect_finite(const json& j, const std::string& where) {
  if (j.is_number_float()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << where;
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it)
      expect_finite(it.value(), where + "/" + it.key());
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) expect_finite(j[i], where + "/" + std::to_string(i));
  }
}

void run_at(int across) {
  const LoadedScene loaded =
      load_scene(std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes" / "impact_al_al.json",
                 {"/particle_impact/particle/elements_across=" + std::to_string(across)});
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const json s = to_json(sim.run());
  for (const SchemaViolation& v : validate("result", s)) ADD_FAILURE() << to_string(v);
  expect_finite(s, "");
  const std::string outcome = s.value("outcome", "");
  EXPECT_TRUE(outcome == "stick" || outcome == "rebound" || outcome == "unstable") << outcome;
  EXPECT_FALSE(s.value("reason", "").empty());
  std::printf("%d across: %s (%s), steps %lld, wall %.1f s\n", across, outcome.c_str(),
              s.value("reason", "").c_str(), s.value("steps", 0LL), s.value("wall_seconds", 0.0));
}

TEST(impact_extremes_long, sixteen_elements_across) {
  run_at(16);
}

TEST(impact_extremes_long, largest_allowed_resolution) {
  run_at(64);
}

}  // namespace
}  // namespace splat
