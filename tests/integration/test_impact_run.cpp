// `splat run` on a particle_impact scene: the run ends with a verdict (stick
// or rebound) or a stated numerical outcome, its summary validates against
// schemas/result.schema.json and carries every key of issue 5, and the HDF5
// file holds the same figures as root attributes under the same names.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include <unistd.h>

#include "solver/input/schema.hpp"
#include "solver/io/result_file.hpp"
#include "support/scene_runs.hpp"

namespace splat {
namespace {

using nlohmann::json;

using Output = test_support::CommandOutput;

Output run(const std::string& args) {
  return test_support::run_command(std::string(SPLAT_BINARY) + " " + args + " 2>/dev/null");
}

const std::string scene = std::string(SPLAT_SOURCE_DIR) + "/scenes/impact_al_al.json";

json run_impact(const std::string& name, const std::string& sets, int expected_code) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("splat_impact_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  const Output o = run("run " + scene + " --json --threads 1 --out " + dir.string() + " " + sets);
  EXPECT_EQ(o.code, expected_code) << o.stdout_text;
  json printed = json::parse(o.stdout_text, nullptr, false);
  EXPECT_FALSE(printed.is_discarded()) << o.stdout_text;
  if (printed.is_discarded()) return {};
  for (const SchemaViolation& v : validate("result", printed)) ADD_FAILURE() << to_string(v);
  printed["_dir"] = dir.string();
  return printed;
}

// Issue 5's list of summary keys.
void expect_issue_keys(const json& s) {
  for (const char* key :
       {"outcome", "reason", "rebound_velocity", "coefficient_of_restitution", "bonded_area",
        "bonded_fraction", "links", "energy", "max_temperature", "max_plastic_strain",
        "flattening_ratio", "penetration_depth", "steps", "end_time", "stop_reason", "wall_seconds",
        "model", "solver_version", "thesis_criteria"}) {
    EXPECT_TRUE(s.contains(key)) << key;
  }
  for (const char* key : {"contact", "activated", "exhausted", "eroded", "active"}) {
    EXPECT_TRUE(s["links"].contains(key)) << key;
  }
  for (const char* key : {"initial_kinetic", "final_particle_kinetic", "plastic_work",
                          "adhesion_dissipated", "absorbed", "hourglass", "balance_error"}) {
    EXPECT_TRUE(s["energy"].contains(key)) << key;
    EXPECT_TRUE(s["energy"][key].is_number() && std::isfinite(s["energy"][key].get<double>()));
  }
}

// At the schema's default resolution, 12 elements across: at the scene's 8
// the 500 m/s stick does not settle before the maximum time since elements
// at the damage cap erode (it ends "stick (not settled)", moving off at 7 m/s
// with links active; docs/verification.md "FE impact robustness").
// The thesis's aluminium (al-thesis, its eased fracture: links activate from
// about 300 m/s) keeps the run short.
TEST(impact_run, thesis_scene_at_500_m_s_sticks_with_a_complete_summary_and_hdf5_attributes) {
  const json s = run_impact("stick",
                            "--set /particle_impact/particle/elements_across=12 "
                            "--set /particle_impact/particle/material=al-thesis",
                            0);
  expect_issue_keys(s);
  EXPECT_EQ(s["outcome"], "stick") << s.dump(2);
  EXPECT_EQ(s["verdict"], "stick");
  EXPECT_EQ(s["stop_reason"], "verdict-settled");
  EXPECT_EQ(s["model"]["name"], "fe-axisym");
  EXPECT_GT(s["bonded_area"].get<double>(), 0.0);
  EXPECT_GT(s["links"]["active"].get<long long>(), 0);
  EXPECT_TRUE(s["thesis_criteria"]["active_link"].get<bool>());
  // Adaptive: stopped well before the maximum time.
  EXPECT_LT(s["end_time"].get<double>(), s["max_time"].get<double>());
  // Initial kinetic energy of the particle: 1/2 (4/3 pi R^3 rho) v^2 within
  // the mesh's volume error (2 %).
  const double M = 4.0 / 3.0 * 3.14159265358979 * std::pow(12.5e-6, 3) * 2700.0;
  EXPECT_NEAR(s["energy"]["initial_kinetic"].get<double>(), 0.5 * M * 500.0 * 500.0,
              0.02 * 0.5 * M * 500.0 * 500.0);

  const auto h5 = std::filesystem::path(s["_dir"].get<std::string>()) / "impact_al_al.h5";
  const ResultSummary rs = read_result_summary(h5);
  EXPECT_EQ(rs.text_attributes.at("outcome"), "stick");
  EXPECT_EQ(rs.text_attributes.at("stop_reason"), "verdict-settled");
  EXPECT_EQ(rs.text_attributes.at("model.name"), "fe-axisym");
  for (const char* key : {"rebound_velocity", "coefficient_of_restitution", "bonded_area",
                          "bonded_fraction", "max_temperature", "max_plastic_strain",
                          "flattening_ratio", "penetration_depth", "end_time"}) {
    ASSERT_TRUE(rs.number_attributes.count(key)) << key;
    EXPECT_DOUBLE_EQ(rs.number_attributes.at(key), s[key].get<double>()) << key;
  }
  for (const char* key : {"contact", "activated", "exhausted", "eroded", "active"}) {
    const std::string name = std::string("links.") + key;
    ASSERT_TRUE(rs.number_attributes.count(name)) << name;
    EXPECT_EQ(rs.number_attributes.at(name), s["links"][key].get<double>()) << name;
  }
  for (const char* key : {"initial_kinetic", "final_particle_kinetic", "plastic_work",
                          "adhesion_dissipated", "absorbed", "hourglass", "balance_error"}) {
    const std::string name = std::string("energy.") + key;
    ASSERT_TRUE(rs.number_attributes.count(name)) << name;
    EXPECT_DOUBLE_EQ(rs.number_attributes.at(name), s["energy"][key].get<double>()) << name;
  }
}

TEST(impact_run, without_adhesion_energy_the_particle_is_not_held) {
  // G_c = 0: links may activate (the thesis's criteria count them) but hold
  // nothing, so the verdict is rebound even if the particle rests in its crater.
  const json s = run_impact("rebound", "--set /particle_impact/adhesion/G_c=0", 0);
  expect_issue_keys(s);
  EXPECT_EQ(s["outcome"], "rebound") << s.dump(2);
  const double v = s["rebound_velocity"].get<double>();
  // A plastic impact at 500 m/s returns a small part of the energy.
  EXPECT_LT(s["coefficient_of_restitution"].get<double>(), 0.5);
  EXPECT_NEAR(s["coefficient_of_restitution"].get<double>(), std::max(v, 0.0) / 500.0, 1e-12);
}

TEST(impact_run, slow_impact_rebounds_nearly_elastically) {
  // At 1 m/s the Hertz peak pressure of Al on Al (~1.2 GPa) exceeds the yield
  // stress, but only in a tiny zone (contact radius ~5 % of R, under one
  // element here): the particle leaves with most of its speed. Not a
  // verification (the contact is not resolved), a check that the slow end of
  // the range gives a settled rebound.
  const json s = run_impact("slow", "--set /particle_impact/velocity=1", 0);
  EXPECT_EQ(s["outcome"], "rebound") << s.dump(2);
  EXPECT_EQ(s["stop_reason"], "verdict-settled");
  EXPECT_GT(s["coefficient_of_restitution"].get<double>(), 0.8);
  EXPECT_LE(s["coefficient_of_restitution"].get<double>(), 1.0);
  EXPECT_LT(s["max_plastic_strain"].get<double>(), 0.01);
}

TEST(impact_run, fixed_end_time_runs_to_it_and_still_gives_a_verdict) {
  // At 300 m/s the particle is held well before 60 ns (at 500 m/s it still
  // leaves then with more energy than its one link can take: no verdict).
  const json s = run_impact(
      "fixed", "--set /particle_impact/velocity=300 --set /particle_impact/end_time=6e-8", 0);
  EXPECT_EQ(s["stop_reason"], "end-time") << s.dump(2);
  EXPECT_EQ(s["end_time_rule"], "fixed");
  EXPECT_NEAR(s["end_time"].get<double>(), 6e-8, 1e-15);
  EXPECT_TRUE(s["outcome"] == "stick" || s["outcome"] == "rebound") << s["outcome"];
}

TEST(impact_run, max_time_before_the_verdict_settles_forces_it_and_says_so) {
  // At 1 m/s the particle leaves at t ~ 8e-8 s and the rebound settles one
  // hold time (1.7e-8 s) later; stopping at 8.5e-8 s forces the verdict.
  const json s = run_impact(
      "max_time", "--set /particle_impact/velocity=1 --set /particle_impact/max_time=8.5e-8", 0);
  EXPECT_EQ(s["stop_reason"], "max-time") << s.dump(2);
  EXPECT_EQ(s["outcome"], "rebound");
  EXPECT_FALSE(s["verdict_settled"].get<bool>());
  EXPECT_NE(s["reason"].get<std::string>().find("not settled"), std::string::npos);
}

TEST(impact_run, a_particle_still_moving_in_at_the_maximum_time_gets_no_verdict) {
  const json s = run_impact("undecided", "--set /particle_impact/max_time=1e-8", 3);
  EXPECT_EQ(s["outcome"], "unstable") << s.dump(2);
  EXPECT_EQ(s["stop_reason"], "undecided");
  EXPECT_EQ(s["verdict"], "none");
  EXPECT_NE(s["reason"].get<std::string>().find("still moves into the substrate"),
            std::string::npos);
}

TEST(impact_run, schema_requires_the_impact_keys_once_a_verdict_is_reported) {
  json s = run_impact("schema", "", 0);
  s.erase("_dir");
  ASSERT_TRUE(validate("result", s).empty());
  for (const char* key : {"bonded_area", "links", "flattening_ratio", "model"}) {
    json broken = s;
    broken.erase(key);
    EXPECT_FALSE(validate("result", broken).empty()) << key;
  }
  json broken = s;
  broken["energy"].erase("initial_kinetic");
  EXPECT_FALSE(validate("result", broken).empty());
}

TEST(impact_run, field_snapshots_by_default_spread_over_the_impact) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("splat_impact_snapshots_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  // The temperature-activated scene at 600 m/s: above its critical
  // velocity (docs/validation.md), links to see.
  const std::string bonding =
      std::string(SPLAT_SOURCE_DIR) + "/scenes/impact_al_al_temperature.json";
  const Output o = run("run " + bonding + " --threads 1 --out " + dir.string() +
                       " --set /particle_impact/velocity=600");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const std::filesystem::path h5 = dir / "impact_al_al_temperature.h5";
  const std::filesystem::path xmf = dir / "impact_al_al_temperature.xmf";
  EXPECT_NE(o.stdout_text.find("(ParaView: " + xmf.string() + ")"), std::string::npos)
      << o.stdout_text;
  const ResultSummary rs = read_result_summary(h5);
  // The initial state, the ones before the verdict settled, the final state.
  EXPECT_GE(rs.snapshots, 10u);
  EXPECT_LE(rs.snapshots, 17u);
  EXPECT_EQ(read_snapshot_time(h5, 0), 0.0);
  const std::vector<double> time = read_history(h5, "time");
  EXPECT_NEAR(read_snapshot_time(h5, rs.snapshots - 1), time.back(), 1e-15);
  for (const char* body : {"particle", "substrate"}) {
    const auto shape = read_dataset_shape(
        h5, "/snapshots/" + std::to_string(rs.snapshots - 1) + "/" + body + "/stress");
    ASSERT_TRUE(shape.has_value()) << body;
    EXPECT_EQ(shape->at(1), 6u) << body;
  }
  // The interface's link states sit on the slave body's nodes: some are active.
  const std::vector<double> links =
      read_snapshot_field(h5, rs.snapshots - 1, "particle", "link_state");
  EXPECT_GT(std::count(links.begin(), links.end(), 2.0), 0) << "no active link in the snapshot";
  EXPECT_TRUE(std::filesystem::exists(xmf));

  // Switched off: histories only, and no ParaView path to an empty file.
  const Output off = run("run " + bonding + " --threads 1 --out " + dir.string() +
                         " --set '/output={\"snapshot_count\":0}'");
  ASSERT_EQ(off.code, 0) << off.stdout_text;
  EXPECT_EQ(off.stdout_text.find("ParaView"), std::string::npos) << off.stdout_text;
  EXPECT_NE(off.stdout_text.find("no field snapshots"), std::string::npos) << off.stdout_text;
  EXPECT_EQ(read_result_summary(h5).snapshots, 0u);
  EXPECT_FALSE(std::filesystem::exists(xmf));
  std::filesystem::remove_all(dir);
}

TEST(impact_run, converge_prints_one_row_per_level_and_errors_against_the_finest) {
  const Output o = run("converge " + scene +
                       " --json --set-levels /particle_impact/particle/elements_across=2,4,8");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const json doc = json::parse(o.stdout_text, nullptr, false);
  ASSERT_FALSE(doc.is_discarded()) << o.stdout_text;
  ASSERT_EQ(doc["levels"].size(), 3u);
  long long previous = 0;
  for (const json& l : doc["levels"]) {
    EXPECT_GT(l["elements"].get<long long>(), previous);  // finer levels, more elements
    previous = l["elements"].get<long long>();
    EXPECT_TRUE(l["rebound_velocity"].is_number());
    EXPECT_FALSE(l["outcome"].get<std::string>().empty());
  }
  const json& finest = doc["levels"][2];
  EXPECT_EQ(finest["rebound_velocity_error"].get<double>(), 0.0);
  EXPECT_NEAR(
      doc["levels"][0]["rebound_velocity_error"].get<double>(),
      doc["levels"][0]["rebound_velocity"].get<double>() - finest["rebound_velocity"].get<double>(),
      1e-9);
  EXPECT_TRUE(doc["richardson"].contains("rebound_velocity"));

  const Output bad = run("converge " + scene + " --set-levels elements_across=2,4");
  EXPECT_EQ(bad.code, 2);
  const Output table =
      run("converge " + scene + " --set-levels /particle_impact/particle/elements_across=2,4");
  EXPECT_EQ(table.code, 0);
  EXPECT_NE(table.stdout_text.find("bond error"), std::string::npos) << table.stdout_text;
}

}  // namespace
}  // namespace splat
