// The SPH time step through a high-speed impact: the quarter Al/Al SPH model
// of scenes/impact_al_al_sph.json at 1500 m/s and 6 spacings across R, run in
// process on one thread (about 8 s). Substrate particles flow onto the
// symmetry planes there and near their own mirror images while nothing is
// compressed; the step must follow the bound of sph_body.hpp and not the
// distance of a particle to its image down to the time-step floor (a bound
// on that distance ends this run `unstable` at 50 ns, the step at 3.2e-13 s,
// its mean 1.9e-11 s). The lattice step is Monaghan's signal-speed bound over
// the spacing, d / (c (1 + 1.2 alpha)), times the stability coefficient; the
// compressed particles under the impact take a fraction of it (the smallest
// principal stretch of F) and the approach speeds mu_ij raise the signal
// speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/material/point_update.hpp"

namespace splat {
namespace {

const std::string scene = std::string(SPLAT_SOURCE_DIR) + "/scenes/impact_al_al_sph.json";

TEST(sph_time_step, quarter_al_al_impact_at_1500_m_s_keeps_the_lattice_step) {
  const LoadedScene loaded = load_scene(
      scene, {"/particle_impact/velocity=1500", "/particle_impact/particle/elements_across=6",
              "/particle_impact/fidelity=sph-3d-quarter"});
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const RunSummary s = sim.run();

  // The lattice bound, smallest over the bodies (both SPH, spacing R / 6).
  double dt_lattice = std::numeric_limits<double>::infinity();
  for (const BodySpec& b : loaded.scene.bodies) {
    ASSERT_EQ(b.discretization, Discretization::sph) << b.name;
    ASSERT_GT(b.element_size, 0.0) << b.name;
    const double c = derive_constants(b.material).wave_speed;
    dt_lattice = std::min(dt_lattice, b.element_size / (c * (1.0 + 1.2 * b.sph.visc_linear)));
  }
  const TimeSpec& ts = loaded.scene.time;
  const double dt_mean = s.end_time / static_cast<double>(s.steps);
  std::printf(
      "Al/Al SPH 1500 m/s, 6 across: %s (%s) after %lld steps, %.3e s; mean step %.3e s, "
      "lattice step %.3e s; balance %.3f\n",
      to_string(s.outcome), name_or_empty(s.stop_reason).c_str(), s.steps, s.end_time, dt_mean,
      ts.stability_coefficient * dt_lattice, s.energy.balance_error);
  EXPECT_NE(s.stop_reason, StopReason::time_step_collapse) << s.reason;
  EXPECT_GT(s.end_time, 50e-9) << s.reason;
  // Measured: mean 0.61 of the lattice step (the compressed particles under
  // the impact set it); a step that follows a shrinking distance falls to
  // 0.12.
  EXPECT_GT(dt_mean, 0.25 * ts.stability_coefficient * dt_lattice);
  EXPECT_LT(std::abs(s.energy.balance_error), ts.energy_balance_limit);
}

}  // namespace
}  // namespace splat
