// SPH Taylor anvil test against the FE result of the same scene
// (scenes/taylor_copper_sph.json vs scenes/taylor_copper_axisym.json): the
// rod as total-Lagrangian SPH particles (quarter rod with mirrored-ghost
// symmetry planes) at 4, 6 and 8 particle spacings across the radius, with
// the final length and footprint radius of each and its cost, against the FE
// reference of the Taylor refinement study (axisymmetric, 32 elements
// across: 21.467 mm, 7.354 mm). The thesis (2.1.3) found its SPH a few
// percent softer than FE; ours is a few percent stiffer, converging towards
// FE as the spacing shrinks (docs/verification.md "SPH"). Particle centres lie
// inside the body, so the
// extent of the rod is that of the centres plus half a spacing on each free
// side (the wall stops the centres at z = 0, so only the top and the rim
// get the half spacing).
// Run with: ctest --test-dir build -L long -R sph_taylor --output-on-failure
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"

namespace splat {
namespace {

constexpr double fe_length = 21.467e-3;    // m, taylor_anvil_refinement, axisymmetric FE 32 across
constexpr double fe_footprint = 7.354e-3;  // m

struct Row {
  int across = 0;
  long long particles = 0, steps = 0, updates = 0;
  double length = 0.0, footprint = 0.0, cpu_seconds = 0.0, balance = 0.0;
};

Row run_at(int across) {
  const auto file = std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes/taylor_copper_sph.json";
  const LoadedScene loaded =
      load_scene(file, {"/bodies/0/discretization/elements_across=" + std::to_string(across)});
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const std::clock_t c0 = std::clock();
  const RunSummary s = sim.run();
  Row r;
  r.cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  EXPECT_EQ(s.outcome, RunOutcome::finished) << s.reason;
  const double half = 0.5 * 3.2e-3 / across;
  r.across = across;
  r.particles = s.bodies[0].elements;
  r.steps = s.steps;
  r.updates = sim.sph_bodies()[0].reference_updates;
  r.length = s.bodies[0].extent_max.z() + half;
  r.footprint = std::max(s.bodies[0].extent_max.x(), s.bodies[0].extent_max.y()) + half;
  r.balance = s.energy.balance_error;
  return r;
}

TEST(SphTaylor, sph_taylor_against_fe) {
  std::vector<Row> rows;
  for (int across : {4, 6, 8}) rows.push_back(run_at(across));
  std::printf(
      "| spacings across | particles | steps | reference updates | final length (mm) | "
      "vs FE | footprint radius (mm) | vs FE | energy balance | CPU s |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const Row& r : rows) {
    std::printf("| %d | %lld | %lld | %lld | %.3f | %+.1f %% | %.3f | %+.1f %% | %.2e | %.1f |\n",
                r.across, r.particles, r.steps, r.updates, r.length * 1e3,
                100.0 * (r.length / fe_length - 1.0), r.footprint * 1e3,
                100.0 * (r.footprint / fe_footprint - 1.0), r.balance, r.cpu_seconds);
  }
  // Measured (docs/verification.md): SPH is stiffer than FE here (longer rod, smaller
  // footprint; the thesis found its SPH softer), and the gap to FE closes as
  // the spacing shrinks. Asserted: both gaps shrink with each refinement, the
  // finest length is within 5 % of FE, and its energy balance within 2 %
  // (the loss is the wall landing the arriving particle centres).
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_LT(std::abs(rows[k].length / fe_length - 1.0),
              std::abs(rows[k - 1].length / fe_length - 1.0));
    EXPECT_LT(std::abs(rows[k].footprint / fe_footprint - 1.0),
              std::abs(rows[k - 1].footprint / fe_footprint - 1.0));
  }
  const Row& fine = rows.back();
  EXPECT_LT(std::abs(fine.length / fe_length - 1.0), 0.05);
  EXPECT_LT(std::abs(fine.balance), 0.02);
}

}  // namespace
}  // namespace splat
