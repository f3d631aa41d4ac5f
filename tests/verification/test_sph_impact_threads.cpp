// sph_impact_threads: the thesis's full SPH Al/Al impact (743-particle ball on
// an 11,000-particle block, 600 m/s, pinball Lagrange contact with adhesion,
// absorbing layers) run for 60 steps on one and on two threads ends with the
// same bits: energies, the contact and absorbed work, every body's centroid
// velocity and extent. The scene is big enough for every parallel loop of
// the step to run in parallel (node loops from 4,096 nodes, the contact
// search from 256 slave nodes and 2,048 faces, the absorbing layers from
// 1,024 entries), so a loop whose result depends on how the work is split
// between threads fails here.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"

namespace splat {
namespace {

RunSummary run_on(int threads) {
  const LoadedScene loaded =
      load_scene(std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes" / "impact_al_al_sph.json",
                 {"/particle_impact/fidelity=sph-3d-full", R"(/time={"max_steps": 60})"});
  SimulationOptions options;
  options.threads = threads;
  options.quiet = true;
  Simulation sim(loaded.scene, loaded.resolved, options);
  return sim.run();
}

TEST(sph_impact_threads, one_and_two_threads_give_the_same_bits) {
#ifdef _OPENMP
  const RunSummary a = run_on(1);
  const RunSummary b = run_on(2);
  ASSERT_EQ(a.steps, 60) << a.reason;
  ASSERT_EQ(b.steps, 60) << b.reason;
  EXPECT_EQ(a.threads, 1);
  EXPECT_EQ(b.threads, 2);
  // The particle is in contact and the run has moved energy around.
  EXPECT_LT(a.energy.contact_work, 0.0);
  EXPECT_GT(a.energy.internal, 0.0);
  EXPECT_EQ(a.energy.kinetic, b.energy.kinetic);
  EXPECT_EQ(a.energy.internal, b.energy.internal);
  EXPECT_EQ(a.energy.plastic_work, b.energy.plastic_work);
  EXPECT_EQ(a.energy.hourglass, b.energy.hourglass);
  EXPECT_EQ(a.energy.artificial_viscosity, b.energy.artificial_viscosity);
  EXPECT_EQ(a.energy.contact_work, b.energy.contact_work);
  EXPECT_EQ(a.energy.absorbed, b.energy.absorbed);
  EXPECT_EQ(a.energy.balance_error, b.energy.balance_error);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t k = 0; k < a.bodies.size(); ++k) {
    EXPECT_EQ(a.bodies[k].centroid_velocity, b.bodies[k].centroid_velocity) << a.bodies[k].name;
    EXPECT_EQ(a.bodies[k].extent_min, b.bodies[k].extent_min) << a.bodies[k].name;
    EXPECT_EQ(a.bodies[k].extent_max, b.bodies[k].extent_max) << a.bodies[k].name;
  }
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

}  // namespace
}  // namespace splat
