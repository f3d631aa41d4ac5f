// choose_model, the pure rule set that turns a particle_impact request into a
// model: one test per rule of solver/input/impact_scene.hpp (fidelity, the
// FE/SPH switch, discretizations, resolution, rigid substrate), each on a
// request read once and then changed field by field.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "solver/input/impact_scene.hpp"
#include "solver/input/schema.hpp"

namespace splat {
namespace {

using nlohmann::json;

constexpr double R = 12.5e-6;  // m

// Al on Al at 300 m/s, everything else left to `auto`.
ImpactRequest al_on_al() {
  const json doc = {
      {"name", "choice"},
      {"particle_impact",
       {{"particle", {{"material", "al-thesis"}, {"radius", R}}}, {"velocity", 300.0}}}};
  return read_impact_request(doc);
}

// A soft aluminium (al-deck: flow stress about 0.2 GPa at eps_p = 1, 1e7 /s)
// on titanium (ti6al4v-thesis: yield stress 0.86 GPa, more than 3x that).
ImpactRequest al_on_ti() {
  const json doc = {{"name", "choice"},
                    {"particle_impact",
                     {{"particle", {{"material", "al-deck"}, {"radius", R}}},
                      {"substrate", {{"material", "ti6al4v-thesis"}}},
                      {"velocity", 300.0}}}};
  return read_impact_request(doc);
}

// The JSON pointer of the first violation choose_model reports, "" if none.
std::string refused_field(const ImpactRequest& r) {
  try {
    choose_model(r);
  } catch (const InputError& e) {
    return e.violations().front().pointer;
  }
  return "";
}

bool says(const ImpactModelChoice& c, const std::string& text) {
  return c.why.find(text) != std::string::npos;
}

TEST(ImpactModelChoice, normal_impact_is_axisymmetric_fe_at_12_elements_across) {
  const ImpactModelChoice c = choose_model(al_on_al());
  EXPECT_EQ(c.model, Fidelity::fe_axisym);
  EXPECT_FALSE(c.rigid_substrate);
  EXPECT_EQ(c.elements_across, 12);
  EXPECT_DOUBLE_EQ(c.element_size, R / 12);
  EXPECT_TRUE(says(c, "normal impact: axisymmetric")) << c.why;
  EXPECT_TRUE(says(c, "no adhesion asked")) << c.why;
  EXPECT_TRUE(says(c, "damage off")) << c.why;
}

TEST(ImpactModelChoice, oblique_fe_impact_is_full_3d) {
  ImpactRequest r = al_on_al();
  r.angle = 30.0;
  const ImpactModelChoice c = choose_model(r);
  EXPECT_EQ(c.model, Fidelity::fe_3d_full);
  EXPECT_TRUE(says(c, "oblique impact (angle 30")) << c.why;
}

TEST(ImpactModelChoice, above_the_fe_limit_the_particle_is_sph_and_a_softer_substrate_too) {
  ImpactRequest r = al_on_al();
  r.velocity = 500.0;  // the limit itself stays FE
  EXPECT_EQ(choose_model(r).model, Fidelity::fe_axisym);
  r.velocity = 501.0;
  ImpactModelChoice c = choose_model(r);
  EXPECT_EQ(c.model, Fidelity::sph_3d_quarter);
  EXPECT_TRUE(says(c, "is above 500")) << c.why;
  EXPECT_TRUE(says(c, "so it jets too")) << c.why;
  EXPECT_EQ(c.elements_across, 5);
  EXPECT_DOUBLE_EQ(c.element_size, R / 5);
  EXPECT_TRUE(says(c, "particle spacing 2.5")) << c.why;
  r.angle = 10.0;
  EXPECT_EQ(choose_model(r).model, Fidelity::sph_3d_full);
  r.particle_discretization = "fe";  // an FE particle asked for stays FE at any speed
  r.velocity = 3000.0;
  EXPECT_EQ(choose_model(r).model, Fidelity::fe_3d_full);
}

TEST(ImpactModelChoice, sph_particle_on_a_harder_substrate_gets_an_fe_block) {
  ImpactRequest r = al_on_ti();
  r.particle_discretization = "sph";
  ImpactModelChoice c = choose_model(r);
  EXPECT_EQ(c.model, Fidelity::sph_on_fe_3d_quarter);
  EXPECT_TRUE(says(c, "SPH particle as asked")) << c.why;
  EXPECT_TRUE(says(c, "FE substrate")) << c.why;
  r.substrate_discretization = "sph";
  c = choose_model(r);
  EXPECT_EQ(c.model, Fidelity::sph_3d_quarter);
  EXPECT_TRUE(says(c, "SPH substrate as asked")) << c.why;
}

TEST(ImpactModelChoice, an_asked_fidelity_is_kept_and_checked) {
  ImpactRequest r = al_on_al();
  r.fidelity = "fe-3d-quarter";
  const ImpactModelChoice c = choose_model(r);
  EXPECT_EQ(c.model, Fidelity::fe_3d_quarter);
  EXPECT_TRUE(says(c, "fidelity fe-3d-quarter as asked")) << c.why;
  r.angle = 20.0;  // an oblique impact breaks the quarter model's symmetry
  EXPECT_EQ(refused_field(r), "/particle_impact/fidelity");
  r.angle = 0.0;
  r.fidelity = "fe-2d";
  EXPECT_EQ(refused_field(r), "/particle_impact/fidelity");
}

TEST(ImpactModelChoice, discretizations_must_match_the_model) {
  ImpactRequest r = al_on_al();
  r.fidelity = "sph-3d-quarter";
  r.particle_discretization = "fe";
  EXPECT_EQ(refused_field(r), "/particle_impact/particle/discretization");
  r.fidelity = "fe-axisym";
  r.particle_discretization = "sph";
  EXPECT_EQ(refused_field(r), "/particle_impact/particle/discretization");
  r.particle_discretization = "auto";
  r.substrate_discretization = "sph";
  EXPECT_EQ(refused_field(r), "/particle_impact/substrate/discretization");
  r.fidelity = "sph-on-fe-3d-quarter";
  EXPECT_EQ(refused_field(r), "/particle_impact/substrate/discretization");
}

TEST(ImpactModelChoice, resolution_is_elements_across_or_the_sph_spacing_within_bounds) {
  ImpactRequest r = al_on_al();
  r.block["particle"]["elements_across"] = 24;
  EXPECT_DOUBLE_EQ(choose_model(r).element_size, R / 24);
  r.block["particle"]["spacing"] = 1e-6;  // FE particles take elements_across only
  EXPECT_EQ(refused_field(r), "/particle_impact/particle/spacing");
  r.fidelity = "sph-3d-quarter";  // and not both
  EXPECT_EQ(refused_field(r), "/particle_impact/particle/spacing");
  r.block["particle"].erase("elements_across");
  EXPECT_DOUBLE_EQ(choose_model(r).element_size, 1e-6);
  r.block["particle"]["spacing"] = 0.6 * R;  // fewer than 2 spacings across R
  EXPECT_EQ(refused_field(r), "/particle_impact/particle/spacing");
  r.block["particle"]["spacing"] = R / 65;  // more than 64 across
  EXPECT_EQ(refused_field(r), "/particle_impact/particle/spacing");
  r.block["particle"]["spacing"] = R / 64;
  EXPECT_EQ(refused_field(r), "");
}

TEST(ImpactModelChoice, a_substrate_that_cannot_yield_is_a_rigid_wall_unless_it_bonds) {
  ImpactRequest r = al_on_ti();
  ImpactModelChoice c = choose_model(r);
  EXPECT_TRUE(c.rigid_substrate);
  EXPECT_TRUE(says(c, "at least 3x the particle's flow stress")) << c.why;
  r.substrate_type = "deformable";
  EXPECT_FALSE(choose_model(r).rigid_substrate);
  r.substrate_type = "auto";
  r.fidelity = "two-mass";  // the two-mass model has its own substrate mass
  c = choose_model(r);
  EXPECT_FALSE(c.rigid_substrate);
  EXPECT_TRUE(says(c, "rigid hemisphere of mass")) << c.why;
  r.fidelity = "auto";
  r.has_adhesion = true;
  c = choose_model(r);
  EXPECT_FALSE(c.rigid_substrate);
  EXPECT_TRUE(says(c, "adhesion on contact pairs")) << c.why;
  r.substrate_type = "rigid";  // a rigid wall carries no links
  EXPECT_EQ(refused_field(r), "/particle_impact/substrate/type");
  r.has_adhesion = false;
  EXPECT_TRUE(says(choose_model(r), "rigid substrate as asked"));
  r = al_on_al();
  EXPECT_FALSE(choose_model(r).rigid_substrate);  // a substrate as soft as the particle
}

}  // namespace
}  // namespace splat
