// The interpenetration check on an SPH substrate (physics_guard.hpp): the
// quarter SPH Al/Al model as built (ball one tenth of a spacing above its
// touching position) passes; the ball moved into the block fails, by pinball
// overlap when pressed in by most of a spacing, and by enclosure when it sits
// entirely inside the block on the interstitial sites, where no pair of
// pinballs overlaps by half a spacing. And the SPH contact surfaces that
// keep the bodies apart hold every particle.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "solver/core/model_builder.hpp"
#include "solver/core/physics_guard.hpp"
#include "solver/input/scene_io.hpp"

namespace splat {
namespace {

using nlohmann::json;

constexpr double R = 12.5e-6;  // m
constexpr double d = R / 4.0;  // spacing, m

Model quarter_sph_model() {
  const json doc = {{"name", "guard"},
                    {"particle_impact",
                     {{"particle",
                       {{"material", "al-thesis"},
                        {"radius", R},
                        {"discretization", "sph"},
                        {"elements_across", 4}}},
                      {"velocity", 600.0},
                      {"fidelity", "sph-3d-quarter"}}}};
  return build_model(read_scene(doc).scene);
}

void move_particle(Model& m, const Vec3& by) {
  const SphBody& ball = m.sph_bodies[m.body_refs[0].index];
  for (std::size_t i = ball.node_begin; i < ball.node_end; ++i) m.nodes.x[i] += by;
}

constexpr GuardInput k_in{0, 1, -1, 0.1};

TEST(PhysicsGuardSph, the_model_as_built_passes) {
  const Model m = quarter_sph_model();
  ASSERT_TRUE(m.body_refs[0].sph && m.body_refs[1].sph);
  const Interpenetration p = measure_interpenetration(m, k_in);
  EXPECT_TRUE(p.checked);
  EXPECT_TRUE(p.sph);
  EXPECT_EQ(p.nodes_through, 0);
  EXPECT_DOUBLE_EQ(p.max_depth, 0.0);
}

TEST(PhysicsGuardSph, a_ball_pressed_in_by_most_of_a_spacing_fails_by_overlap) {
  Model m = quarter_sph_model();
  // The lowest ball particles sit 1.1 d above the top layer's centres,
  // straight above them (both lattices at (i + 1/2) d in x and y): 0.8 d
  // down leaves 0.3 d between centres, an overlap of 0.7 d.
  move_particle(m, Vec3(0, 0, -0.8 * d));
  const Interpenetration p = measure_interpenetration(m, k_in);
  EXPECT_GT(p.nodes_through, 0);
  EXPECT_NEAR(p.max_ratio, 0.7, 0.05);
  EXPECT_NEAR(p.max_depth, 0.7 * d, 0.05 * d);
}

TEST(PhysicsGuardSph, a_ball_inside_the_block_fails_by_enclosure) {
  Model m = quarter_sph_model();
  // Down by its diameter and three spacings more, shifted half a spacing
  // along each axis: every ball particle at the centre of a cube of block
  // particles, 0.87 d from the nearest (overlap 0.13 d, below the limit).
  move_particle(m, Vec3(0.5 * d, 0.5 * d, -(2.0 * R + 3.1 * d) - 0.5 * d));
  const Interpenetration p = measure_interpenetration(m, k_in);
  const SphBody& ball = m.sph_bodies[m.body_refs[0].index];
  EXPECT_LT(p.max_ratio, 0.5);
  EXPECT_EQ(p.nodes_through, static_cast<long long>(ball.size()));
}

// Contact pairs every particle of both SPH bodies, not only their initial
// boundary layers: a crater bares substrate particles that started deep.
TEST(PhysicsGuardSph, sph_contact_surfaces_hold_every_particle) {
  const Model m = quarter_sph_model();
  ASSERT_EQ(m.contacts.size(), 1u);
  const ContactInterface& c = m.contacts[0];
  EXPECT_EQ(c.slave_surface().nodes.size(), m.sph_bodies[m.body_refs[0].index].size());
  EXPECT_EQ(c.master_surface().faces.size(), m.sph_bodies[m.body_refs[1].index].size());
}

TEST(PhysicsGuardSph, check_physics_names_the_failure) {
  Model m = quarter_sph_model();
  move_particle(m, Vec3(0, 0, -0.8 * d));
  GuardFigures figures;
  std::string reason;
  const auto failed = check_physics(m, EnergyBudget{}, k_in, figures, reason);
  ASSERT_TRUE(failed.has_value());
  EXPECT_EQ(*failed, StopReason::interpenetration);
  EXPECT_TRUE(figures.interpenetration_checked);
  EXPECT_NE(reason.find("SPH substrate"), std::string::npos) << reason;
}

// A particle that went through the substrate while the run went on and came
// back out broke the contact as surely as one still inside: the worst state
// sampled during the run fails the check on a clean end state, and the
// reason says when.
TEST(PhysicsGuardSph, an_interpenetration_seen_during_the_run_fails_a_clean_end_state) {
  Model m = quarter_sph_model();
  move_particle(m, Vec3(0, 0, -0.8 * d));
  Interpenetration during = measure_interpenetration(m, k_in);
  during.time = 3.5e-8;
  move_particle(m, Vec3(0, 0, 0.8 * d));
  GuardFigures figures;
  std::string reason;
  EXPECT_FALSE(check_physics(m, EnergyBudget{}, k_in, figures, reason).has_value()) << reason;
  const auto failed = check_physics(m, EnergyBudget{}, k_in, figures, reason, during);
  ASSERT_TRUE(failed.has_value());
  EXPECT_EQ(*failed, StopReason::interpenetration);
  EXPECT_EQ(figures.nodes_through, during.nodes_through);
  EXPECT_NE(reason.find("(at t = 3.5e-08 s)"), std::string::npos) << reason;
}

// The plastic work is part of the internal energy: a run whose strength law
// booked more plastic work than the internal (plus eroded) energy by more
// than the energy limit fails, one within it passes.
TEST(PhysicsGuardSph, plastic_work_beyond_the_internal_energy_fails) {
  const Model m = quarter_sph_model();
  EnergyBudget e;
  e.initial_total = 1.0;
  e.internal = 0.55;
  e.eroded = 0.05;
  GuardFigures figures;
  std::string reason;
  e.plastic_work = 0.6 + 0.9 * k_in.energy_limit;
  EXPECT_FALSE(check_physics(m, e, k_in, figures, reason).has_value()) << reason;
  EXPECT_NEAR(figures.plastic_work_excess, 0.9 * k_in.energy_limit, 1e-12);
  e.plastic_work = 0.6 + 1.1 * k_in.energy_limit;
  const auto failed = check_physics(m, e, k_in, figures, reason);
  ASSERT_TRUE(failed.has_value());
  EXPECT_EQ(*failed, StopReason::plastic_work_excess);
  EXPECT_NE(reason.find("plastic work exceeds the internal energy"), std::string::npos) << reason;
}

}  // namespace
}  // namespace splat
