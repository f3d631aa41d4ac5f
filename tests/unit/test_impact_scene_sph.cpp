// The SPH rungs of the impact fidelity ladder (particle_impact block):
// sph-3d-quarter / sph-3d-full (SPH ball on an SPH block, the thesis's Al/Al
// model) and sph-on-fe-3d-quarter / -full (SPH ball on a hex FE block); when
// `auto` picks them and why, how the particle resolution maps to the spacing,
// the geometry they build, and errors naming the field.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "solver/input/impact_scene.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"

namespace splat {
namespace {

using nlohmann::json;

constexpr double R = 12.5e-6;  // m

json impact(json block) {
  return {{"name", "impact"}, {"particle_impact", std::move(block)}};
}

json al_on_al(double v, const std::string& particle_discretization) {
  json p = {{"material", "al-thesis"}, {"radius", R}};
  if (!particle_discretization.empty()) p["discretization"] = particle_discretization;
  return {{"particle", p}, {"velocity", v}};
}

std::string first_error(const json& doc) {
  try {
    read_scene(doc);
  } catch (const InputError& e) {
    return e.violations().front().pointer + ": " + e.violations().front().message;
  }
  return "";
}

int count_bcs(const json& scene, const std::string& body, const std::string& type) {
  int n = 0;
  for (const json& bc : scene["boundary_conditions"]) n += bc["body"] == body && bc["type"] == type;
  return n;
}

TEST(ImpactSceneSph, sph_particle_on_al_picks_the_quarter_sph_on_sph_model) {
  const ExpandedImpact e = expand_particle_impact(impact(al_on_al(600.0, "sph")));
  EXPECT_EQ(e.choice.model, Fidelity::sph_3d_quarter);
  EXPECT_NE(e.choice.why.find("SPH particle as asked"), std::string::npos) << e.choice.why;
  EXPECT_NE(e.choice.why.find("SPH substrate"), std::string::npos) << e.choice.why;
  const json& s = e.scene;
  ASSERT_EQ(s["bodies"].size(), 2u);
  const json& ball = s["bodies"][0];
  const json& block = s["bodies"][1];
  // Default spacing R / 5 (thesis: SPH radius 1.25 um at R 12.5 um).
  const double d = R / 5;
  EXPECT_EQ(ball["discretization"]["type"], "sph");
  EXPECT_NEAR(ball["discretization"]["element_size"].get<double>(), d, 1e-15);
  EXPECT_EQ(ball["discretization"]["sector"], "quarter");
  EXPECT_NEAR(ball["geometry"]["centre"][2].get<double>(), R + 0.1 * d, 1e-15);
  EXPECT_EQ(block["discretization"]["type"], "sph");
  EXPECT_EQ(block["discretization"]["sph"]["lattice"], "cubic");
  // Block half-width and depth R (2.4 + 600 / 1500) = 2.8 R = 14 spacings.
  EXPECT_NEAR(block["geometry"]["max"][0].get<double>(), 14 * d, 1e-12);
  EXPECT_NEAR(block["geometry"]["min"][2].get<double>(), -14 * d, 1e-12);
  EXPECT_EQ(count_bcs(s, "particle", "symmetry"), 2);
  EXPECT_EQ(count_bcs(s, "substrate", "symmetry"), 2);
  EXPECT_EQ(count_bcs(s, "substrate", "absorbing"), 3);
  // The SPH ball is the contact slave, single pass.
  EXPECT_EQ(s["interactions"][0]["slave"], "particle");
  EXPECT_FALSE(s["interactions"][0].value("two_pass", false));
  for (const SchemaViolation& v : validate("scene", s)) ADD_FAILURE() << to_string(v);
  const LoadedScene loaded = read_scene(impact(al_on_al(600.0, "sph")));
  EXPECT_EQ(loaded.scene.impact->model, Fidelity::sph_3d_quarter);
}

TEST(ImpactSceneSph, auto_switches_to_sph_above_the_fe_erosion_velocity_and_says_why) {
  EXPECT_EQ(expand_particle_impact(impact(al_on_al(500.0, ""))).choice.model, Fidelity::fe_axisym);
  const ExpandedImpact fast = expand_particle_impact(impact(al_on_al(501.0, "")));
  EXPECT_EQ(fast.choice.model, Fidelity::sph_3d_quarter);
  EXPECT_NE(fast.choice.why.find("above which the FE particle's jetting rim erodes"),
            std::string::npos)
      << fast.choice.why;
  // An explicit FE particle stays FE at any speed.
  EXPECT_EQ(expand_particle_impact(impact(al_on_al(3000.0, "fe"))).choice.model,
            Fidelity::fe_axisym);
  // Oblique: full 3D.
  json b = al_on_al(800.0, "");
  b["angle"] = 20.0;
  EXPECT_EQ(expand_particle_impact(impact(b)).choice.model, Fidelity::sph_3d_full);
}

TEST(ImpactSceneSph, harder_substrate_gets_an_fe_block_under_the_sph_ball) {
  json b = al_on_al(800.0, "");
  b["substrate"] = {{"material", "ti6al4v-thesis"}};
  b["adhesion"] = {{"G_c", 1.0}};  // keeps the substrate deformable
  const ExpandedImpact e = expand_particle_impact(impact(b));
  EXPECT_EQ(e.choice.model, Fidelity::sph_on_fe_3d_quarter);
  const json& block = e.scene["bodies"][1];
  EXPECT_EQ(block["discretization"]["type"], "fe-hex");
  EXPECT_NEAR(block["discretization"]["element_size"].get<double>(), R / 5, 1e-15);
  EXPECT_EQ(count_bcs(e.scene, "substrate", "symmetry"), 2);
  for (const SchemaViolation& v : validate("scene", e.scene)) ADD_FAILURE() << to_string(v);
  b["substrate"]["discretization"] = "sph";
  EXPECT_EQ(expand_particle_impact(impact(b)).choice.model, Fidelity::sph_3d_quarter);
}

TEST(ImpactSceneSph, every_sph_level_expands_to_a_valid_scene) {
  for (const char* level :
       {"sph-3d-quarter", "sph-3d-full", "sph-on-fe-3d-quarter", "sph-on-fe-3d-full"}) {
    json b = al_on_al(300.0, "");
    b["fidelity"] = level;
    b["adhesion"] = {{"G_c", 30.0}};
    const ExpandedImpact e = expand_particle_impact(impact(b));
    EXPECT_EQ(to_string(e.choice.model), level);
    const bool quarter = std::string(level).find("quarter") != std::string::npos;
    const bool sph_block = std::string(level).rfind("sph-3d", 0) == 0;
    EXPECT_EQ(e.scene["bodies"][0]["discretization"]["type"], "sph") << level;
    EXPECT_EQ(e.scene["bodies"][1]["discretization"]["type"], sph_block ? "sph" : "fe-hex")
        << level;
    EXPECT_EQ(count_bcs(e.scene, "particle", "symmetry"), quarter ? 2 : 0) << level;
    EXPECT_EQ(count_bcs(e.scene, "substrate", "absorbing"), quarter ? 3 : 5) << level;
    for (const SchemaViolation& v : validate("scene", e.scene)) ADD_FAILURE() << to_string(v);
    EXPECT_EQ(first_error(impact(b)), "") << level;
  }
}

TEST(ImpactSceneSph, resolution_is_the_spacing_or_spacings_across_the_radius) {
  json b = al_on_al(600.0, "sph");
  b["particle"]["elements_across"] = 4;
  EXPECT_NEAR(expand_particle_impact(impact(b))
                  .scene["bodies"][0]["discretization"]["element_size"]
                  .get<double>(),
              R / 4, 1e-15);
  b = al_on_al(600.0, "sph");
  b["particle"]["spacing"] = 2e-6;
  EXPECT_NEAR(expand_particle_impact(impact(b))
                  .scene["bodies"][0]["discretization"]["element_size"]
                  .get<double>(),
              2e-6, 1e-15);
  b["particle"]["elements_across"] = 4;
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/particle/spacing"), std::string::npos);
  // At most 64 spacings across R, the bound of elements_across: 1e-8 m (1250
  // across) ran out of memory with std::bad_alloc.
  b = al_on_al(600.0, "sph");
  b["particle"]["spacing"] = R / 64;
  EXPECT_EQ(first_error(impact(b)), "");
  b["particle"]["spacing"] = 1e-8;
  EXPECT_NE(
      first_error(impact(b)).find("/particle_impact/particle/spacing: must be at least R / 64"),
      std::string::npos)
      << first_error(impact(b));
}

TEST(ImpactSceneSph, contradictions_name_the_field) {
  json b = al_on_al(600.0, "sph");
  b["fidelity"] = "fe-axisym";
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/particle/discretization"),
            std::string::npos)
      << first_error(impact(b));
  b = al_on_al(600.0, "fe");
  b["fidelity"] = "sph-3d-full";
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/particle/discretization"),
            std::string::npos);
  b = al_on_al(600.0, "");
  b["fidelity"] = "sph-on-fe-3d-full";
  b["substrate"] = {{"discretization", "sph"}};
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/substrate/discretization"),
            std::string::npos);
  b = al_on_al(600.0, "");
  b["fidelity"] = "sph-3d-quarter";
  b["angle"] = 10.0;
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/fidelity"), std::string::npos);
  b = al_on_al(600.0, "fe");
  b["particle"]["spacing"] = 2e-6;
  EXPECT_NE(first_error(impact(b)).find("/particle_impact/particle/spacing"), std::string::npos);
}

TEST(ImpactSceneSph, heat_conduction_is_refused_for_sph_and_reaches_both_fe_bodies) {
  json b = al_on_al(600.0, "sph");
  b["heat_conduction"] = true;
  EXPECT_EQ(first_error(impact(b)),
            "/particle_impact/heat_conduction: SPH bodies conduct no heat; ask for an FE fidelity "
            "(fe-axisym, fe-3d-quarter, fe-3d-full)");
  b = al_on_al(600.0, "fe");
  b["heat_conduction"] = true;
  const Scene scene = read_scene(impact(b)).scene;
  ASSERT_EQ(scene.bodies.size(), 2u);
  for (const BodySpec& body : scene.bodies) {
    EXPECT_TRUE(body.switches.heat_conduction) << body.name;
    EXPECT_EQ(body.material.thermal.conductivity, 237.0) << body.name;  // al-thesis
  }
  b.erase("heat_conduction");
  for (const BodySpec& body : read_scene(impact(b)).scene.bodies)
    EXPECT_FALSE(body.switches.heat_conduction) << body.name;
}

}  // namespace
}  // namespace splat
