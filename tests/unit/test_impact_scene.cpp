// The particle_impact block: which model `auto` picks and why, what the
// expansion builds for each fidelity, and clear errors for what cannot be
// modelled.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/input/impact_scene.hpp"
#include "solver/input/material_io.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"
#include "support/temp_dir.hpp"

namespace splat {
namespace {

using nlohmann::json;

json impact(json block) {
  return {{"name", "impact"}, {"particle_impact", std::move(block)}};
}

json al_on_al(double v) {
  return {{"particle",
           {{"material", "al-thesis"},
            {"radius", 12.5e-6},
            {"elements_across", 8},
            {"discretization", "fe"}}},
          {"velocity", v}};
}

std::string first_error(const json& doc) {
  try {
    read_scene(doc);
  } catch (const InputError& e) {
    return e.violations().front().pointer + ": " + e.violations().front().message;
  }
  return "";
}

TEST(ImpactScene, normal_impact_is_axisymmetric_with_plain_contact_and_no_damage) {
  const ExpandedImpact e = expand_particle_impact(impact(al_on_al(600.0)));
  EXPECT_EQ(e.choice.model, Fidelity::fe_axisym);
  EXPECT_FALSE(e.choice.rigid_substrate);
  EXPECT_NE(e.choice.why.find("normal impact"), std::string::npos) << e.choice.why;
  EXPECT_NE(e.choice.why.find("no adhesion"), std::string::npos) << e.choice.why;
  const json& s = e.scene;
  ASSERT_EQ(s.at("bodies").size(), 2u);
  EXPECT_EQ(s["bodies"][0]["discretization"]["type"], "fe-axisym");
  EXPECT_EQ(s["bodies"][0]["switches"]["damage"], false);
  EXPECT_EQ(s["interactions"][0]["type"], "contact");
  EXPECT_FALSE(s["interactions"][0].contains("adhesion"));
  // Substrate size R (4 + v / 250) = 6.4 R; element size at the impact point R / 8.
  EXPECT_NEAR(s["bodies"][1]["geometry"]["r_max"].get<double>(), 6.4 * 12.5e-6, 1e-12);
  EXPECT_NEAR(s["bodies"][1]["discretization"]["element_size"].get<double>(), 12.5e-6 / 8, 1e-15);
  EXPECT_EQ(s["boundary_conditions"].size(), 2u);  // absorbing outer and bottom
  EXPECT_GT(s["time"]["end_time"].get<double>(), 0.0);
  for (const SchemaViolation& v : validate("scene", s)) ADD_FAILURE() << to_string(v);
}

TEST(ImpactScene, field_snapshots_spread_over_the_impact_unless_switched_off) {
  const LoadedScene plain = read_scene(impact(al_on_al(500.0)));
  const std::vector<double>& times = plain.scene.output.snapshot_times;
  ASSERT_EQ(times.size(), 17u);
  EXPECT_EQ(times.front(), 0.0);  // the undeformed state
  EXPECT_EQ(times.back(), plain.scene.time.end_time);
  // Evenly over the impact's duration (3 contact times), the last at max_time.
  const double t_spread = 16.0 * times[1];
  EXPECT_NEAR(times[8], 0.5 * t_spread, 1e-20);
  EXPECT_LT(times[15], plain.scene.time.end_time);
  // max_time at 500 m/s: 100 particle transits R / c_p (al-thesis: E 70.9
  // GPa, nu 0.3, 2710 kg/m^3), longer than the impact, so that a particle
  // held by a few links has time to ring down.
  const double c_p = std::sqrt(70.9e9 * 0.7 / (1.3 * 0.4 * 2710.0));
  EXPECT_NEAR(plain.scene.time.end_time, 100.0 * 12.5e-6 / c_p, 1e-12 * 12.5e-6 / c_p);
  EXPECT_GT(plain.scene.time.end_time, t_spread);

  json off = impact(al_on_al(500.0));
  off["output"] = {{"snapshot_count", 0}};
  EXPECT_TRUE(read_scene(off).scene.output.snapshot_times.empty());
  json asked = impact(al_on_al(500.0));
  asked["output"] = {{"snapshot_times", {1e-9, 2e-9}}};
  EXPECT_EQ(read_scene(asked).scene.output.snapshot_times, (std::vector<double>{1e-9, 2e-9}));
  // The resolved scene keeps the times: running it again takes the same ones.
  EXPECT_EQ(read_scene(plain.resolved).scene.output.snapshot_times, times);
}

TEST(ImpactScene, oblique_impact_needs_full_3d) {
  json b = al_on_al(600.0);
  b["angle"] = 30.0;
  const ExpandedImpact e = expand_particle_impact(impact(b));
  EXPECT_EQ(e.choice.model, Fidelity::fe_3d_full);
  const json v = e.scene["bodies"][0]["initial"]["velocity"];
  EXPECT_NEAR(v[0].get<double>(), 300.0, 1e-9);
  EXPECT_NEAR(v[2].get<double>(), -600.0 * std::sqrt(3.0) / 2.0, 1e-9);
  b["fidelity"] = "fe-axisym";
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/fidelity"), std::string::npos);
}

TEST(ImpactScene, quarter_model_has_two_symmetry_planes_on_both_bodies) {
  json b = al_on_al(600.0);
  b["fidelity"] = "fe-3d-quarter";
  const ExpandedImpact e = expand_particle_impact(impact(b));
  EXPECT_EQ(e.scene["bodies"][0]["discretization"]["sector"], "quarter");
  int symmetry = 0;
  for (const json& bc : e.scene["boundary_conditions"]) symmetry += bc["type"] == "symmetry";
  EXPECT_EQ(symmetry, 4);
}

TEST(ImpactScene, adhesion_with_erosion_switches_damage_on) {
  json b = al_on_al(600.0);
  b["adhesion"] = {{"G_c", 30.0}, {"D_adh_max", 0.5}};
  const ExpandedImpact e = expand_particle_impact(impact(b));
  EXPECT_EQ(e.scene["bodies"][0]["switches"]["damage"], true);
  EXPECT_EQ(e.scene["interactions"][0]["adhesion"]["G_c"], 30.0);
  EXPECT_NE(e.choice.why.find("adhesion on contact pairs"), std::string::npos);
}

TEST(ImpactScene, hard_substrate_without_adhesion_becomes_a_rigid_wall) {
  json soft = {{"name", "soft"},
               {"source", "test"},
               {"density", 8960.0},
               {"elastic", {{"E", 124e9}, {"nu", 0.34}}},
               {"strength",
                {{"model", "johnson-cook"},
                 {"A", 50e6},
                 {"B", 50e6},
                 {"n", 0.3},
                 {"C", 0.0},
                 {"eps_dot_0", 1.0},
                 {"m", 1.0},
                 {"T_ref", 300.0},
                 {"T_melt", 1356.0}}},
               {"thermal", {{"c_p", 385.0}, {"heat_fraction", 0.9}}},
               {"eos", {{"model", "linear"}}}};
  json b = {{"particle", {{"material", soft}, {"radius", 10e-6}}},
            {"substrate", {{"material", "ti6al4v-thesis"}}},
            {"velocity", 300.0}};
  const ExpandedImpact e = expand_particle_impact(impact(b));
  EXPECT_TRUE(e.choice.rigid_substrate) << e.choice.why;
  ASSERT_EQ(e.scene["bodies"].size(), 1u);
  EXPECT_EQ(e.scene["interactions"][0]["type"], "rigid-wall");
  // The same pair with adhesion keeps a deformable substrate.
  b["adhesion"] = {{"G_c", 1.0}};
  EXPECT_FALSE(expand_particle_impact(impact(b)).choice.rigid_substrate);
  // Adhesion on an explicitly rigid substrate is an input error.
  b["substrate"]["type"] = "rigid";
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/substrate/type"), std::string::npos);
}

TEST(ImpactScene, two_mass_fidelity_runs_as_a_two_mass_scene) {
  json b = al_on_al(100.0);
  b["fidelity"] = "two-mass";
  b["adhesion"] = {{"G_c", 1.0}};
  const LoadedScene loaded = read_scene(impact(b));
  ASSERT_TRUE(loaded.scene.two_mass.has_value());
  ASSERT_TRUE(loaded.scene.impact.has_value());
  EXPECT_EQ(loaded.scene.impact->model, Fidelity::two_mass);
  const double M = 4.0 / 3.0 * 3.141592653589793 * std::pow(12.5e-6, 3) * 2700.0;
  EXPECT_NEAR(loaded.scene.two_mass->M / M, 1.0, 0.01);
  EXPECT_EQ(loaded.resolved["particle_impact"]["model"]["name"], "two-mass");
}

TEST(ImpactScene, bad_blocks_name_the_field) {
  json b = al_on_al(600.0);
  b["particle"]["radius"] = -1.0;
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/particle/radius"), std::string::npos);
  b = al_on_al(600.0);
  b["particle"]["material"] = "unobtainium";
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/particle/material"), std::string::npos)
      << first_error(impact(b));
  b = al_on_al(0.0);
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/velocity"), std::string::npos);
}

}  // namespace
}  // namespace splat

namespace splat {
namespace {

// Issue 22, item 9: an expanded scene (a stored campaign job) holds the
// impact velocity in the particle body and in the particle_impact block. A
// run with only one of them changed flew at the body's velocity and judged
// the verdict against the block's: such a scene is refused, naming the field.
TEST(ImpactScene, expanded_scene_with_disagreeing_velocities_is_refused) {
  nlohmann::json expanded = read_scene(impact(al_on_al(550.0))).resolved;
  EXPECT_EQ(first_error(expanded), "");
  nlohmann::json changed = expanded;
  changed["particle_impact"]["velocity"] = 5.0;
  const std::string error = first_error(changed);
  EXPECT_EQ(error.rfind("/particle_impact/velocity", 0), 0u) << error;
  EXPECT_NE(error.find("550"), std::string::npos) << error;
  // Both changed together is a consistent scene.
  for (auto& body : changed["bodies"]) {
    if (body["name"] == "particle") body["initial"]["velocity"] = {0.0, 0.0, -5.0};
  }
  EXPECT_EQ(first_error(changed), "");
}

// The model an expanded scene names is read back as its fidelity; a name
// that is no fidelity is refused, naming the field.
TEST(ImpactScene, expanded_scene_reads_its_model_back) {
  nlohmann::json expanded = read_scene(impact(al_on_al(550.0))).resolved;
  EXPECT_EQ(read_scene(expanded).scene.impact->model, Fidelity::fe_axisym);
  expanded["particle_impact"]["model"].erase("name");
  EXPECT_FALSE(read_scene(expanded).scene.impact->model.has_value());
  expanded["particle_impact"]["model"]["name"] = "fe-3d";
  const std::string error = first_error(expanded);
  EXPECT_EQ(error.rfind("/particle_impact/model/name", 0), 0u) << error;
}

}  // namespace
}  // namespace splat

namespace splat {
namespace {

// Materials of a particle_impact block take every form a body's do: a file
// relative to the scene's folder (not the working folder), and a library
// material with fields changed ({"base": NAME, ...}).
TEST(ImpactScene, materials_resolve_like_a_bodys) {
  test_support::TempDir t;
  std::filesystem::create_directories(t.path / "mats");
  json m = material_document("al-thesis");
  m["name"] = "al-copy";
  std::ofstream(t.path / "mats" / "al-copy.json") << m.dump();
  json block = al_on_al(300.0);
  block["particle"]["material"] = "mats/al-copy.json";
  block["substrate"] = {{"material", {{"base", "al-thesis"}, {"density", 2700.0}}}};
  const LoadedScene s = read_scene(impact(block), t.path);
  ASSERT_EQ(s.scene.bodies.size(), 2u);
  EXPECT_DOUBLE_EQ(s.scene.bodies[1].material.density, 2700.0);
  EXPECT_NE(first_error(impact(block)).find("/particle_impact/particle/material"),
            std::string::npos);  // from the working folder the file is not found
}

}  // namespace
}  // namespace splat
