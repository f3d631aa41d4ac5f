// Mesh refinement of the axisymmetric Taylor anvil test
// (scenes/taylor_copper_axisym.json): final length and footprint radius at 4,
// 8, 16 and 32 elements across the radius, with the cost of each run, so a
// user can see what each resolution buys. The changes between successive
// resolutions must shrink (the final length converges), and the finest runs
// must stay within 1.5 % of the published code benchmark (21.42-21.5 mm).
// Run with: ctest --test-dir build -L long -R taylor --output-on-failure
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"

namespace splat {
namespace {

struct Row {
  int across = 0;
  long long elements = 0, steps = 0;
  double length = 0.0, footprint = 0.0, cpu_seconds = 0.0;
};

Row run_at(int across) {
  const auto file = std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes/taylor_copper_axisym.json";
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
  r.across = across;
  r.elements = s.bodies.at(0).elements;
  r.steps = s.steps;
  r.length = s.bodies.at(0).extent_max.z() - s.bodies.at(0).extent_min.z();
  r.footprint = s.bodies.at(0).extent_max.x();
  return r;
}

TEST(taylor_anvil_refinement, final_length_converges) {
  std::vector<Row> rows;
  for (int across : {4, 8, 16, 32}) rows.push_back(run_at(across));
  std::printf(
      "| across | elements | steps | final length (mm) | footprint radius (mm) | CPU s |\n");
  std::printf("| --- | --- | --- | --- | --- | --- |\n");
  for (const Row& r : rows) {
    std::printf("| %d | %lld | %lld | %.3f | %.3f | %.1f |\n", r.across, r.elements, r.steps,
                r.length * 1e3, r.footprint * 1e3, r.cpu_seconds);
  }
  for (std::size_t i = 2; i < rows.size(); ++i) {
    const double before = std::abs(rows[i - 1].length - rows[i - 2].length);
    const double now = std::abs(rows[i].length - rows[i - 1].length);
    EXPECT_LT(now, before + 1e-6) << "at " << rows[i].across << " across";
  }
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_NEAR(rows[i].length / 21.46e-3, 1.0, 0.015) << rows[i].across << " across";
  }
}

}  // namespace
}  // namespace splat
