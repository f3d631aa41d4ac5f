// Honest runs (issue 22): a run whose physics broke never reports a verdict or
// `finished`. Each test reproduces one way a run used to break and still end
// with a normal outcome, and checks the run now either stays sound (the
// conserved quantity within its tolerance) or ends `unstable` naming the check.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/input/schema.hpp"
#include "support/scene_runs.hpp"

namespace splat {
namespace {

using nlohmann::json;

// No result files (--out ''): tests running at once on the same scene would
// otherwise write the same out/SCENE.h5, and HDF5's lock fails the second.
json run(const std::string& scene, const std::string& sets = "") {
  const test_support::CommandOutput o = test_support::run_splat(
      "run " + std::string(SPLAT_SOURCE_DIR) + "/" + scene + " --json --threads 1 --out '' " + sets,
      false);
  json s = json::parse(o.stdout_text, nullptr, false);
  EXPECT_FALSE(s.is_discarded()) << o.stdout_text;
  if (s.is_discarded()) return json::object();
  for (const SchemaViolation& v : validate("result", s)) ADD_FAILURE() << to_string(v);
  // Exit 0 only with a verdict or at the end time (cmd_run.cpp).
  const std::string outcome = s.value("outcome", "");
  EXPECT_EQ(o.code == 0, outcome == "stick" || outcome == "rebound" || outcome == "finished")
      << outcome << " exit " << o.code;
  return s;
}

// Item 2: the thesis's 1 mm Cu/Cu shot at 457 m/s drove 38 particle nodes up
// to 3.2 element sizes deep into the substrate and ended `rebound`, exit 0.
// The guard measures each particle node inside a substrate element against
// the substrate surface (physics_guard.hpp). One-pass contact still lets the
// particle through at this resolution (two passes, the default, do not:
// rebound at 22 m/s, no node through): what is checked here is that a run
// with one pass says so.
TEST(honest_runs, interpenetration_is_never_a_verdict) {
  const json s =
      run("scenes/verification/cu_1mm_457.json", "--set /particle_impact/two_pass_contact=false");
  const json& g = s["guard"];
  ASSERT_TRUE(g["interpenetration_checked"].get<bool>());
  EXPECT_EQ(s["outcome"], "unstable");
  EXPECT_EQ(s["stop_reason"], "interpenetration") << s["reason"];
  EXPECT_EQ(s["verdict"], "none");
  EXPECT_GT(g["nodes_through"].get<long long>(), 0);
  EXPECT_GT(g["interpenetration_ratio"].get<double>(), 0.5);
}

// The same guard passes a sound run: the thesis Al/Al scene at 500 m/s has
// no particle node inside the substrate.
TEST(honest_runs, sound_impact_passes_the_guard) {
  const json s = run("scenes/impact_al_al.json");
  EXPECT_EQ(s["guard"]["failed"], "") << s["reason"];
  EXPECT_EQ(s["guard"]["nodes_through"].get<long long>(), 0);
  EXPECT_LE(s["guard"]["interpenetration_ratio"].get<double>(), 0.5);
}

// Item 3: after the bounce the sphere flies freely, yet the booked stiffness
// hourglass energy grew by 4 % per 180 ns and the run ended `unstable`
// (energy balance) at 248 ns. Mid-point booking keeps the hourglass work
// equal to the stored energy: the balance stays within 1 % at 600 ns.
TEST(honest_runs, stiffness_hourglass_energy_does_not_drift) {
  const json s = run("scenes/elastic_sphere_bounce_3d.json", "--set /time/end_time=6e-7");
  EXPECT_EQ(s["outcome"], "finished") << s["reason"];
  const json& e = s["energy"];
  const double E0 = e["initial_total"].get<double>();
  EXPECT_LT(std::abs(e["balance_error"].get<double>()), 0.01);
  EXPECT_LT(std::abs(e["hourglass"].get<double>()) / E0, 0.01);
}

}  // namespace
}  // namespace splat

namespace splat {
namespace {

// Item 5: a uniform 3D hexahedral block driven from rest into absorbing
// faces blew up at the default stability coefficient (dashpot force on the
// old velocity: stable only for dt C / m < 2, less with the element
// stiffness) and, having no initial energy, was never checked. The dashpots
// now act at the mid-point of the update; the run stays sound: the energy
// balance closes within 0.5 % of the work put in, and the absorbing faces
// take out most of that work (the wave the driven face sends in leaves
// through them; the rest is the plastic work and the wave in flight).
TEST(honest_runs, absorbing_faces_stay_stable_at_the_default_step) {
  const json s = run("scenes/verification/absorbing_block_3d.json");
  EXPECT_EQ(s["outcome"], "finished") << s["reason"];
  const json& e = s["energy"];
  const double work = e["external_work"].get<double>();
  ASSERT_GT(work, 0.0);
  EXPECT_LT(std::abs(e["balance_error"].get<double>()), 0.005);
  EXPECT_GT(e["absorbed"].get<double>(), 0.8 * work);
  EXPECT_LT(e["absorbed"].get<double>(), work);
}

}  // namespace
}  // namespace splat

namespace splat {
namespace {

double sphere_speed(const json& s) {
  return s["bodies"][0]["centroid_velocity"][2].get<double>();  // up, after the bounce
}

// FE Cu/Cu at 700 m/s: an eroded rim element exposed a particle node about
// 2 um inside the substrate, and the position push-out (2 % of the large
// substrate face per step, 76 nm) crushed the 0.14 um thin element behind it
// to J = 0.29 in four steps; its pressure, read from the volume, did work
// no strain rate booked, and the run ended `unstable` (energy balance,
// negative eroded energy) at 12 and 16 elements across. The push-out is now
// capped by the elements behind the pair: the runs end with a verdict and
// close their balance.
TEST(honest_runs, an_exposed_node_is_pushed_out_without_crushing_its_element) {
  for (const char* across : {"12", "16"}) {
    const json s = run("scenes/impact_al_al.json",
                       "--set /particle_impact/particle/material=cu-thesis "
                       "--set /particle_impact/velocity=700 "
                       "--set /particle_impact/particle/elements_across=" +
                           std::string(across));
    const std::string outcome = s.value("outcome", "");
    EXPECT_TRUE(outcome == "stick" || outcome == "rebound")
        << across << " across: " << outcome << " (" << s.value("reason", "") << ")";
    EXPECT_LT(std::abs(s["energy"]["balance_error"].get<double>()), 0.05) << across;
    EXPECT_GT(s["guard"]["eroded_energy_fraction"].get<double>(), 0.0) << across;
  }
}

// Item 4: penalty contact with its default stiffness (0.1 K / h) let the
// elastic sphere of scenes/elastic_sphere_bounce_axisym.json, dropped at
// 100 m/s, sink into the block and took 68 % of its energy as contact work
// (unstable). The default spring is now also at least 0.1 m_eff / dt^2 per
// pair: an elastic bounce must give back the energy (contact work under 1 %
// of it) and leave at the speed the Lagrange contact gives on the same mesh
// (within 2 %).
TEST(honest_runs, default_penalty_contact_holds_an_elastic_impact) {
  const std::string sets = "--set /bodies/0/initial/velocity=[0,0,-100]";
  const json lagrange = run("scenes/elastic_sphere_bounce_axisym.json", sets);
  const json penalty = run("scenes/elastic_sphere_bounce_axisym.json",
                           sets + " --set /interactions/0/method=penalty");
  ASSERT_EQ(lagrange["outcome"], "finished") << lagrange["reason"];
  EXPECT_EQ(penalty["outcome"], "finished") << penalty["reason"];
  const json& e = penalty["energy"];
  EXPECT_LT(std::abs(e["contact_work"].get<double>()) / e["initial_total"].get<double>(), 0.01);
  EXPECT_NEAR(sphere_speed(penalty), sphere_speed(lagrange), 0.02 * sphere_speed(lagrange));
}

}  // namespace
}  // namespace splat

namespace splat {
namespace {

// Item 10: in the SPH scene, G_c = 1e6 J/m^2 "rebounded" at the 22.58 m/s of
// G_c = 30 with three links still active: a verdict forced at the maximum
// time while the links were pulling the particle back (a fixed 150 ns run
// ends at -9 m/s, held). A rebound now needs no active link (or links too
// weak to stop the particle, which uncapped links never are); the strong
// bond sticks.
TEST(honest_runs, no_rebound_with_active_links) {
  const json strong =
      run("scenes/impact_al_al_sph.json", "--set /particle_impact/adhesion/G_c=1e6");
  EXPECT_EQ(strong["outcome"], "stick") << strong["reason"];
  // The thesis bond at 600 m/s: whatever its outcome, a rebound comes with
  // no uncapped link active (its links are uncapped: none can be too weak).
  const json thesis = run("scenes/impact_al_al_sph.json");
  if (thesis["outcome"] == "rebound") {
    EXPECT_EQ(thesis["links"]["active"].get<long long>(), 0) << thesis["reason"];
  }
}

}  // namespace
}  // namespace splat

namespace splat {
namespace {

// Item 1: the elastic sphere of scenes/elastic_sphere_bounce_3d.json at
// 100 m/s, 12 elements across its radius on a block of the same element
// size: with one-pass contact the sphere's pole node loaded a single block
// corner node, which hourglassed into the sphere, and the run ended
// `unstable` (energy balance) at 29 ns. Two-pass contact (the default for FE
// pairs) also keeps the block's nodes out of the sphere: the sphere bounces
// off and the balance stays within the scene's 5 % (measured 0.04 %).
TEST(honest_runs, hexahedral_contact_keeps_the_pole_out_of_the_block) {
  const json s = run("scenes/elastic_sphere_bounce_3d.json",
                     "--set /bodies/0/discretization/elements_across=12"
                     " --set /bodies/1/discretization/element_size=1.0416667e-6"
                     " --set /bodies/0/initial/velocity=[0,0,-100]");
  EXPECT_EQ(s["outcome"], "finished") << s["reason"];
  EXPECT_LT(std::abs(s["energy"]["balance_error"].get<double>()), 0.05);
  EXPECT_GT(sphere_speed(s), 90.0);  // up, m/s: an elastic bounce
  EXPECT_EQ(s["interfaces"][0]["unconverged_solves"].get<long long>(), 0);
}

// Item 2: Al/Al at 600 m/s without adhesion, 16 elements across: with
// one-pass contact a substrate node passed through the particle at the
// jetting lip and the run ended `unstable` (12 nodes through, energy
// balance -5 %). With two passes no node passes and the particle rebounds
// (20.4 m/s).
TEST(honest_runs, axisymmetric_contact_keeps_the_substrate_out_of_the_particle) {
  const json s = run("scenes/verification/al_al_600_no_adhesion.json");
  EXPECT_EQ(s["outcome"], "rebound") << s["reason"];
  EXPECT_EQ(s["guard"]["nodes_through"].get<long long>(), 0);
  EXPECT_LT(std::abs(s["energy"]["balance_error"].get<double>()), 0.05);
  EXPECT_GT(s["rebound_velocity"].get<double>(), 0.0);
  EXPECT_EQ(s["interfaces"][0]["unconverged_solves"].get<long long>(), 0);
}

// The SPH model of the same impact, at 6 and 8 spacings across the radius:
// on a layer of pinballs the particle's surface particles dropped into the
// hollows, landed in each and were caught: at 6 across the particle never
// left (undecided), and the plastic work of the kicked surface particles
// exceeded the internal energy by 7.1 % (6 across) and 5.9 % (8 across) of
// the impact energy, which no material can do (plastic work is part of the
// internal energy). On the caps of the substrate's surface particles
// (contact_search.hpp) the particle rebounds at 25.5 and 20.5 m/s (FE at 16
// across: 20.4), the plastic work stays below the internal energy and the
// balance closes to 2.3 and 2.0 %.
TEST(honest_runs, sph_particle_without_adhesion_rebounds_and_stores_its_plastic_work) {
  for (const char* across : {"6", "8"}) {
    SCOPED_TRACE(across);
    const json s = run("scenes/verification/al_al_600_no_adhesion.json",
                       "--set /particle_impact/particle/discretization=sph "
                       "--set /particle_impact/particle/elements_across=" +
                           std::string(across));
    EXPECT_EQ(s["outcome"], "rebound") << s["reason"];
    EXPECT_GT(s["rebound_velocity"].get<double>(), 5.0);
    EXPECT_LT(s["guard"]["plastic_work_excess"].get<double>(), 0.01);
    EXPECT_LT(std::abs(s["energy"]["balance_error"].get<double>()), 0.03);
  }
}
}  // namespace
}  // namespace splat

namespace splat {
namespace {

// FE Al/Al at 1100 m/s, 24 elements across: the contact's position-only
// push-out (contact_interface.hpp, correct_positions) compressed a substrate
// element under the sliding jet from J 0.99 to 0.78 over 900 steps while its
// velocities said it expanded. With J read from the element's volume its
// pressure rose to 15 GPa and did work on the nodes that nothing had paid
// for: its internal energy fell to -1.2e10 J/m^3, and the run ended
// `unstable` (negative eroded energy, -0.186 of the initial energy). J now
// follows the point's own strain increments (volume_ratio_after): the run
// ends with a verdict, a closed balance and a positive eroded energy.
TEST(honest_runs, a_contact_push_out_does_no_work_on_the_material) {
  const json s = run("scenes/impact_al_al.json",
                     "--set /particle_impact/velocity=1100 "
                     "--set /particle_impact/particle/elements_across=24");
  const std::string outcome = s.value("outcome", "");
  EXPECT_TRUE(outcome == "stick" || outcome == "rebound")
      << outcome << " (" << s.value("reason", "") << ")";
  EXPECT_LT(std::abs(s["energy"]["balance_error"].get<double>()), 0.02);
  EXPECT_GE(s["guard"]["eroded_energy_fraction"].get<double>(), 0.0);
  EXPECT_LT(s["energy"]["hourglass"].get<double>(),
            0.05 * s["energy"]["initial_total"].get<double>());
}

}  // namespace
}  // namespace splat
