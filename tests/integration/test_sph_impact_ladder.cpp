// `splat run` on each SPH rung of the impact ladder (sph-3d-quarter,
// sph-3d-full, sph-on-fe-3d-quarter, sph-on-fe-3d-full): a short, coarse
// Al/Al impact (3 spacings across R, 300 m/s, 10 ns) expands, runs and ends
// with a summary that validates against schemas/result.schema.json, names the
// model, and keeps the energy balance; and the SPH window scene runs through
// `splat converge`.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include <unistd.h>

#include "solver/input/schema.hpp"
#include "support/scene_runs.hpp"

namespace splat {
namespace {

using nlohmann::json;
using Output = test_support::CommandOutput;

const std::string scene = std::string(SPLAT_SOURCE_DIR) + "/scenes/impact_al_al_sph.json";

Output run(const std::string& args) {
  return test_support::run_splat(args, false);
}

TEST(sph_impact_ladder, every_sph_level_runs_a_short_impact_to_a_valid_summary) {
  for (const char* level :
       {"sph-3d-quarter", "sph-3d-full", "sph-on-fe-3d-quarter", "sph-on-fe-3d-full"}) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("splat_sph_ladder_" + std::string(level) + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    const Output o = run("run " + scene + " --json --threads 1 --out " + dir.string() +
                         " --set /particle_impact/fidelity=" + level +
                         " --set /particle_impact/particle/elements_across=3"
                         " --set /particle_impact/velocity=300"
                         " --set /particle_impact/end_time=1e-8");
    const json s = json::parse(o.stdout_text, nullptr, false);
    ASSERT_FALSE(s.is_discarded()) << level << ": " << o.stdout_text;
    for (const SchemaViolation& v : validate("result", s)) ADD_FAILURE() << level << to_string(v);
    EXPECT_EQ(s["model"]["name"], level);
    EXPECT_EQ(s["stop_reason"], "undecided") << level << ": " << s["reason"];
    EXPECT_NEAR(s["end_time"].get<double>(), 1e-8, 1e-15) << level;
    // 10 ns after first touch the particle is still moving in at 300 m/s:
    // no verdict yet, and the run says so (exit code 3).
    EXPECT_EQ(s["outcome"], "unstable") << level;
    EXPECT_NE(s["reason"].get<std::string>().find("still moves into the substrate"),
              std::string::npos)
        << level << ": " << s["reason"];
    EXPECT_EQ(o.code, 3) << level;
    EXPECT_GT(s["links"]["contact"].get<long long>(), 0) << level;
    EXPECT_GT(s["max_plastic_strain"].get<double>(), 0.0) << level;
    EXPECT_LT(std::abs(s["energy"]["balance_error"].get<double>()), 0.1) << level;
    EXPECT_TRUE(std::filesystem::exists(dir / "impact_al_al_sph.h5")) << level;
    std::filesystem::remove_all(dir);
  }
}

TEST(sph_impact_ladder, sph_window_scene_runs_through_converge_over_spacing_levels) {
  const Output o = run("converge " + scene +
                       " --json --threads 1 --set /particle_impact/end_time=5e-9"
                       " --set-levels /particle_impact/particle/elements_across=2,3");
  const json doc = json::parse(o.stdout_text, nullptr, false);
  ASSERT_FALSE(doc.is_discarded()) << o.stdout_text;
  ASSERT_EQ(doc["levels"].size(), 2u);
  // Finer spacing, more particles.
  EXPECT_LT(doc["levels"][0]["elements"].get<long long>(),
            doc["levels"][1]["elements"].get<long long>());
  for (const json& l : doc["levels"]) EXPECT_TRUE(l["rebound_velocity"].is_number());
}

}  // namespace
}  // namespace splat
