// sph_quarter_impact_matches_full: the quarter SPH impact model (two
// mirrored-ghost symmetry planes, a quarter of the particles) against the
// full model of the same scene, which is the reference: an al-thesis ball
// (R 12.5 um, 3 spacings across R, cubic lattice in both so the particle
// sets are the same up to the mirror images) hitting an SPH al-thesis block
// at 50 m/s, run to the rebound verdict.
//
//        ( ball )  50 m/s            quarter: x >= 0, y >= 0, ghosts across
//   ======|======== SPH block         x = 0 and y = 0; absorbing far faces
//
// The mirrored ghosts must reproduce the missing three quarters: the rebound
// velocity agrees within 1 % of the full model's (measured: 21.64 and
// 21.64 m/s), the plastic work within 2 % (per quarter), the verdict is the
// same, and the full model's centre of mass stays on the axis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"

namespace splat {
namespace {

RunSummary run_level(const std::string& level) {
  const LoadedScene loaded = load_scene(
      std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes" / "impact_al_al_sph.json",
      {"/particle_impact/fidelity=" + level, "/particle_impact/velocity=50",
       "/particle_impact/particle/elements_across=3", "/particle_impact/sph/lattice=cubic"});
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  return sim.run();
}

TEST(sph_quarter_impact_matches_full, rebound_velocity_and_plastic_work_at_50_m_s) {
  const RunSummary q = run_level("sph-3d-quarter");
  const RunSummary f = run_level("sph-3d-full");
  ASSERT_TRUE(q.impact && f.impact);
  std::printf("quarter: %s, rebound %.4f m/s, plastic work %.4e J (x4), %lld steps\n",
              to_string(q.outcome), q.impact->rebound_velocity, 4.0 * q.energy.plastic_work,
              q.steps);
  std::printf("full:    %s, rebound %.4f m/s, plastic work %.4e J, %lld steps\n",
              to_string(f.outcome), f.impact->rebound_velocity, f.energy.plastic_work, f.steps);
  EXPECT_EQ(std::string(to_string(f.outcome)), "rebound") << f.reason;
  EXPECT_EQ(std::string(to_string(q.outcome)), std::string(to_string(f.outcome))) << q.reason;
  EXPECT_GT(f.impact->rebound_velocity, 0.0);
  EXPECT_NEAR(q.impact->rebound_velocity, f.impact->rebound_velocity,
              0.01 * f.impact->rebound_velocity);
  EXPECT_NEAR(4.0 * q.energy.plastic_work, f.energy.plastic_work, 0.02 * f.energy.plastic_work);
  // Full model: the particle's centre of mass stays on the axis.
  EXPECT_LT(std::hypot(f.bodies[0].centroid_velocity.x(), f.bodies[0].centroid_velocity.y()),
            1e-3 * f.impact->rebound_velocity);
}

}  // namespace
}  // namespace splat
