// Contact between deformable bodies, verified on problems with an
// independent reference:
//  - elastic_bar_impact_velocity_exchange: two equal elastic bars with
//    non-matching meshes (a contact patch test in 1D uniaxial strain): the
//    striker stops and the target leaves at the impact velocity after the
//    contact time 2 L / c_L (elementary 1D wave theory); momentum is conserved
//    exactly.
//  - elastic_sphere_bounce_lagrange: an elastic sphere bouncing on an elastic
//    block conserves energy (the conserved quantity is the reference); the
//    contact's own work stays negligible.
//  - elastic_sphere_bounce_penalty: the same with penalty contact; its loss is
//    measured and printed, and its energy bookkeeping closes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"
#include "support/scene_runs.hpp"

namespace splat {
namespace {

using nlohmann::json;

using test_support::run_scene;

json elastic_al() {
  return json::parse(R"({"base": "al-thesis", "strength": {"A": 10e9}})");
}
json elastic_switches() {
  return json::parse(
      R"({"damage": false, "thermal_softening": false, "rate_hardening": false,
          "adiabatic_heating": false})");
}

// Two aluminium bars of length L along z, radius 2 mm, radial motion fixed
// on the outer surface (uniaxial strain, so the exact solution is 1D),
// striker above at v towards the target. Meshes differ in both directions so
// no slave node faces a master node.
json bar_scene(double v, const std::string& method) {
  json striker = {
      {"name", "striker"},
      {"material", elastic_al()},
      {"geometry",
       {{"type", "rectangle"}, {"r_max", 2e-3}, {"z_min", 1e-7}, {"z_max", 10e-3 + 1e-7}}},
      {"discretization", {{"type", "fe-axisym"}, {"element_size", 0.2e-3}}},
      {"initial", {{"velocity", {0, 0, -v}}}},
      {"switches", elastic_switches()},
      {"hourglass", {{"type", "stiffness"}, {"coefficient", 0.05}}}};
  json target = {
      {"name", "target"},
      {"material", elastic_al()},
      {"geometry", {{"type", "rectangle"}, {"r_max", 2e-3}, {"z_min", -10e-3}, {"z_max", 0.0}}},
      {"discretization", {{"type", "fe-axisym"}, {"element_size", 0.29e-3}}},
      {"switches", elastic_switches()},
      {"hourglass", {{"type", "stiffness"}, {"coefficient", 0.05}}}};
  return {{"name", "bar_impact"},
          {"bodies", {striker, target}},
          {"boundary_conditions",
           {{{"body", "striker"}, {"on", "outer"}, {"type", "symmetry"}},
            {{"body", "target"}, {"on", "outer"}, {"type", "symmetry"}}}},
          {"interactions",
           {{{"type", "contact"}, {"master", "target"}, {"slave", "striker"}, {"method", method}}}},
          {"time", {{"end_time", 5e-6}, {"energy_balance_limit", 0.05}}}};
}

TEST(ContactImpact, elastic_bar_impact_velocity_exchange) {
  const double v = 10.0;
  for (const char* method : {"lagrange", "penalty"}) {
    SCOPED_TRACE(method);
    const RunSummary s = run_scene(bar_scene(v, method));
    ASSERT_EQ(s.outcome, RunOutcome::finished) << s.reason;
    ASSERT_EQ(s.bodies.size(), 2u);
    const BodySummary& striker = s.bodies[0];
    const BodySummary& target = s.bodies[1];
    // c_L = sqrt((K + 4G/3) / rho) = 5933 m/s: contact ends at 2 L / c_L =
    // 3.37 us, well before the end time (5 us).
    const double vs = striker.centroid_velocity.z(), vt = target.centroid_velocity.z();
    std::printf(
        "%s: striker %.4f m/s, target %.4f m/s (exact 0 and %.1f), contact work %.3e J, "
        "balance %.2e, max penetration %.3e m\n",
        method, vs, vt, -v, s.energy.contact_work, s.energy.balance_error,
        s.interfaces[0].max_penetration);
    // Momentum is exchanged by equal and opposite impulses: conserved to
    // rounding (both bars have the same mass).
    EXPECT_NEAR((striker.mass * vs + target.mass * vt) / (striker.mass * v), -1.0, 1e-9);
    // 1D wave theory: complete exchange. Tolerance 2 % of v for the
    // dispersion of the discrete wave front (Gibbs ringing behind it).
    EXPECT_NEAR(vs, 0.0, 0.02 * v);
    EXPECT_NEAR(vt, -v, 0.02 * v);
    EXPECT_EQ(s.interfaces[0].pairs_in_contact, 0);  // separated
    EXPECT_LT(std::abs(s.energy.balance_error), 5e-3);
  }
}

json sphere_scene(const std::string& method, const char* file = "elastic_sphere_bounce_axisym") {
  json doc = read_json_file(std::string(SPLAT_SOURCE_DIR) + "/scenes/" + file + ".json");
  doc["interactions"][0]["method"] = method;
  return doc;
}

TEST(ContactImpact, elastic_sphere_bounce_lagrange) {
  const RunSummary s = run_scene(sphere_scene("lagrange"));
  ASSERT_EQ(s.outcome, RunOutcome::finished) << s.reason;
  const EnergyBudget& e = s.energy;
  const double physical = e.kinetic + e.internal + e.hourglass + e.artificial_viscosity;
  std::printf(
      "lagrange: E0 %.4e J, end %.4e J (loss %.3e), contact work %.3e, hourglass %.3e, "
      "viscosity %.3e, sphere v %.3f m/s, sphere KE %.4f E0, max pairs %lld\n",
      e.initial_total, physical, 1.0 - physical / e.initial_total, e.contact_work / e.initial_total,
      e.hourglass / e.initial_total, e.artificial_viscosity / e.initial_total,
      s.bodies[0].centroid_velocity.z(), s.bodies[0].kinetic_energy / e.initial_total,
      s.interfaces[0].max_pairs_in_contact);
  // Energy is conserved: everything the bodies hold or their elements
  // dissipated (hourglass, bulk viscosity) adds up to the initial kinetic
  // energy to 0.5 % (the node-level impacts of the discrete contact; measured
  // 0.13 %), and the contact forces themselves do no net work (< 0.1 %).
  EXPECT_NEAR(physical / e.initial_total, 1.0, 5e-3);
  EXPECT_LT(std::abs(e.contact_work) / e.initial_total, 1e-3);
  // It bounced: separated, moving up with most of the energy (the rest rings
  // in the block).
  EXPECT_EQ(s.interfaces[0].pairs_in_contact, 0);
  EXPECT_GT(s.bodies[0].centroid_velocity.z(), 0.0);
  EXPECT_GT(s.bodies[0].kinetic_energy / e.initial_total, 0.9);
  EXPECT_GT(s.interfaces[0].max_pairs_in_contact, 1);
}

TEST(ContactImpact, elastic_sphere_bounce_penalty) {
  const RunSummary s = run_scene(sphere_scene("penalty"));
  ASSERT_EQ(s.outcome, RunOutcome::finished) << s.reason;
  const EnergyBudget& e = s.energy;
  const double physical = e.kinetic + e.internal + e.hourglass + e.artificial_viscosity;
  const InterfaceSummary& c = s.interfaces[0];
  std::printf(
      "penalty: loss %.3e of E0, contact dissipated %.3e of E0, stored %.3e, "
      "max penetration %.3e m, sphere v %.3f m/s, sphere KE %.4f E0\n",
      1.0 - physical / e.initial_total, c.dissipated / e.initial_total, c.stored / e.initial_total,
      c.max_penetration, s.bodies[0].centroid_velocity.z(),
      s.bodies[0].kinetic_energy / e.initial_total);
  // The bookkeeping closes: what the bodies lost is the springs' work.
  EXPECT_LT(std::abs(e.balance_error), 1e-3);
  EXPECT_EQ(c.stored, 0.0);  // separated at the end
  EXPECT_NEAR(c.dissipated, -c.work, 1e-12 * e.initial_total);
  EXPECT_GT(s.bodies[0].centroid_velocity.z(), 0.0);
}

// 3D, node on quad face, on a deliberately coarse mesh (6 elements across
// the sphere's radius, a quarter model). The coarse hexahedra's own energy
// bookkeeping limits the tolerance here: the same sphere on the existing
// rigid wall (no contact code) ends with a balance error of +4.6 %; with
// Lagrange contact +2.2 % (measured), so 3 % is stated.
TEST(ContactImpact, elastic_sphere_bounce_lagrange_3d) {
  const RunSummary s = run_scene(sphere_scene("lagrange", "elastic_sphere_bounce_3d"));
  ASSERT_EQ(s.outcome, RunOutcome::finished) << s.reason;
  const EnergyBudget& e = s.energy;
  std::printf(
      "lagrange 3d: balance %.3e, contact work %.3e of E0, sphere v %.3f m/s, max pairs "
      "%lld, max sweeps %d\n",
      e.balance_error, e.contact_work / e.initial_total, s.bodies[0].centroid_velocity.z(),
      s.interfaces[0].max_pairs_in_contact, s.interfaces[0].max_solver_iterations);
  EXPECT_LT(std::abs(e.balance_error), 0.03);
  // A pair that lands books the kinetic energy its row loses,
  // p C (v_before + v_after) / 2 <= 0, a pair that stays closed p C v_after
  // (zero), and a pair already penetrating is only stopped and moved out
  // through positions (split impulse), so the contact never makes energy: its
  // work is the loss of the node-level landings on the faceted sphere
  // (measured -2.06e-3 of E0; -1.26e-3 when a landing booked only
  // p C v_after, which missed part of it), a small fraction of E0.
  EXPECT_LE(e.contact_work, 0.0);
  EXPECT_LT(-e.contact_work / e.initial_total, 3e-3);
  EXPECT_EQ(s.interfaces[0].pairs_in_contact, 0);
  EXPECT_GT(s.bodies[0].centroid_velocity.z(), 0.9 * 20.0);
}

// Coulomb friction at the body level: an elastic block hits a fixed block
// obliquely (40 m/s along x, 10 m/s down) and slides throughout the contact
// (mu dv_z stays well below 40 m/s), so the tangential impulse is mu times
// the normal one: the striker's velocity changes obey dv_x = -mu dv_z
// (momentum, whatever the contact history, while every pair slips; to 1 %
// for the small tilt of the deformed surfaces' normals). mu = 0 leaves v_x
// nearly untouched (the same tilt).
TEST(ContactImpact, oblique_block_impact_coulomb_friction) {
  json striker = {
      {"name", "striker"},
      {"material", elastic_al()},
      {"geometry",
       {{"type", "box"}, {"min", {5e-6, 5e-6, 0.05e-6}}, {"max", {15e-6, 15e-6, 5.05e-6}}}},
      {"discretization", {{"type", "fe-hex"}, {"element_size", 2.5e-6}}},
      {"initial", {{"velocity", {40.0, 0, -10.0}}}},
      {"switches", elastic_switches()},
      {"hourglass", {{"type", "stiffness"}, {"coefficient", 0.05}}}};
  json target = {
      {"name", "target"},
      {"material", elastic_al()},
      {"geometry", {{"type", "box"}, {"min", {0, 0, -5e-6}}, {"max", {25e-6, 20e-6, 0}}}},
      {"discretization", {{"type", "fe-hex"}, {"element_size", 3.3e-6}}},
      {"switches", elastic_switches()},
      {"hourglass", {{"type", "stiffness"}, {"coefficient", 0.05}}}};
  for (double mu : {0.0, 0.1, 0.3}) {
    SCOPED_TRACE(mu);
    json doc = {
        {"name", "oblique_block_impact"},
        {"bodies", {striker, target}},
        {"boundary_conditions", {{{"body", "target"}, {"on", "z_min"}, {"type", "fixed"}}}},
        {"interactions",
         {{{"type", "contact"}, {"master", "target"}, {"slave", "striker"}, {"friction", mu}}}},
        {"time", {{"end_time", 1e-8}}}};
    const RunSummary s = run_scene(doc);
    ASSERT_EQ(s.outcome, RunOutcome::finished) << s.reason;
    const Vec3 v = s.bodies[0].centroid_velocity;
    const double dvx = v.x() - 40.0, dvz = v.z() + 10.0;
    std::printf("mu %.1f: dv_x %.5f m/s, dv_z %.5f m/s, ratio %.6f, balance %.3e\n", mu, dvx, dvz,
                dvx / dvz, s.energy.balance_error);
    ASSERT_GT(dvz, 1.0);  // the contact pushed it back
    EXPECT_NEAR(dvx, -mu * dvz, 0.01 * (mu + 0.01) * dvz);
    EXPECT_NEAR(v.y(), 0.0, 1e-3 * dvz);
  }
}

// Contact patch test: two elastic blocks (axisymmetric, 2 mm radius and
// height each) pressed together slowly: the bottom of the lower block and
// both outer surfaces slide on symmetry planes, the top of the upper one
// moves down at 0.1 m/s for 80 us (about 100 wave transits, so the response
// is quasi-static). The exact state is uniform uniaxial strain,
// sigma_zz = -(K + 4G/3) v t / (2 H) in both blocks.
//  - matching meshes (0.25 mm both): every element within 1 % of it (the
//    dynamic part, rho c v, is 0.9 % of the final stress);
//  - non-matching meshes (0.25 / 0.33 mm): the mean stress (equilibrium
//    through the interface) within 0.5 %; the spread is printed, not
//    asserted: node-to-surface contact does not pass the patch test on
//    non-matching meshes (measured 15 % with one pass); two passes spread it
//    less, and on matching meshes (every master node on a slave node, whose
//    second-pass rows repeat the first-pass ones and are left out) they keep
//    every element within 1 %.
struct PatchResult {
  double exact = 0.0, mean = 0.0, lo = 0.0, hi = 0.0;
};

PatchResult pressed_blocks(double lower_size, bool two_pass) {
  auto block = [](const char* name, double z_min, double size) {
    return json{
        {"name", name},
        {"material", elastic_al()},
        {"geometry",
         {{"type", "rectangle"}, {"r_max", 2e-3}, {"z_min", z_min}, {"z_max", z_min + 2e-3}}},
        {"discretization", {{"type", "fe-axisym"}, {"element_size", size}}},
        {"switches", elastic_switches()},
        {"hourglass", {{"type", "stiffness"}, {"coefficient", 0.05}}}};
  };
  const double v = 0.1, t_end = 8e-5, E = 70.9e9, nu = 0.3;
  const double M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));  // K + 4G/3, Pa
  json doc = {
      {"name", "pressed_blocks"},
      {"bodies", {block("upper", 0.0, 0.25e-3), block("lower", -2e-3, lower_size)}},
      {"boundary_conditions",
       {{{"body", "lower"}, {"on", "bottom"}, {"type", "symmetry"}},
        {{"body", "lower"}, {"on", "outer"}, {"type", "symmetry"}},
        {{"body", "upper"}, {"on", "outer"}, {"type", "symmetry"}},
        {{"body", "upper"}, {"on", "top"}, {"type", "velocity"}, {"velocity", {0, 0, -v}}}}},
      {"interactions",
       {{{"type", "contact"}, {"master", "lower"}, {"slave", "upper"}, {"two_pass", two_pass}}}},
      {"time", {{"end_time", t_end}}}};
  const LoadedScene loaded = read_scene(doc);
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const RunSummary s = sim.run();
  EXPECT_EQ(s.outcome, RunOutcome::finished) << s.reason;
  PatchResult r;
  r.exact = -M * v * t_end / 4e-3;
  r.lo = 1e300;
  r.hi = -1e300;
  double sum = 0.0;
  long long n = 0;
  for (const FeBody& b : sim.bodies()) {
    for (const PointState& st : b.state) {
      const double szz = st.cauchy()(1, 1);  // axisymmetric (r, z, theta): zz
      r.lo = std::min(r.lo, szz);
      r.hi = std::max(r.hi, szz);
      sum += szz;
      ++n;
    }
  }
  r.mean = sum / static_cast<double>(n);
  std::printf(
      "patch (lower %.2f mm, %s): sigma_zz mean %.5e Pa (exact %.5e), range [%.4e, %.4e], "
      "spread %.2e, max sweeps %d\n",
      lower_size * 1e3, two_pass ? "two passes" : "one pass", r.mean, r.exact, r.lo, r.hi,
      (r.hi - r.lo) / std::abs(r.exact), s.interfaces[0].max_solver_iterations);
  return r;
}

TEST(ContactImpact, pressed_blocks_patch_test) {
  const PatchResult same = pressed_blocks(0.25e-3, false);
  EXPECT_NEAR(same.lo, same.exact, 0.01 * std::abs(same.exact));
  EXPECT_NEAR(same.hi, same.exact, 0.01 * std::abs(same.exact));
  const PatchResult one = pressed_blocks(0.33e-3, false);
  EXPECT_NEAR(one.mean, one.exact, 0.005 * std::abs(one.exact));
  const PatchResult two = pressed_blocks(0.33e-3, true);
  EXPECT_NEAR(two.mean, two.exact, 0.005 * std::abs(two.exact));
  EXPECT_LT(two.hi - two.lo, one.hi - one.lo);  // two passes spread the stress less
  const PatchResult two_same = pressed_blocks(0.25e-3, true);
  EXPECT_NEAR(two_same.lo, two_same.exact, 0.01 * std::abs(two_same.exact));
  EXPECT_NEAR(two_same.hi, two_same.exact, 0.01 * std::abs(two_same.exact));
}

}  // namespace
}  // namespace splat
