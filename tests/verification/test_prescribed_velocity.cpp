// prescribed_velocity: a steel bar at rest whose end face is driven at a
// prescribed velocity V. The energy put in is the work of the constraint's
// reactions (external_work), and the bar's kinetic plus internal energy must
// match it.
//
//   V = 1 m/s -> |=========== bar 1 x 1 x 10 mm, elastic (39 MPa << yield) ===|
//
// The first step sets the driven nodes' velocity from 0 to V: the
// constraint's impulse gives them the kinetic energy m V^2 / 2, and that is
// what is booked. Booking the reaction's work over the coming displacement
// instead (right for a node held since the last step) gives 2 m V^2 on the
// first step; this test then fails (measured: stored energy 2.3 % below the
// booked work, against 0.135 % now).
//
// The run uses a stability coefficient of 0.1: the kinetic energy of the
// half-step velocities lags the work by about P dt / 2 (P the power put in),
// a constant offset that at the default 0.9 is 1.6 % of the work put in over
// 1.5 us (36 steps) and shrinks with dt, while the first-step error does not.
// Tolerance 0.2 % of the work.
//
// Reference in closed form too: a 1D bar wave driven at V takes the power
// rho c A V^2, c = sqrt(E / rho). The 3D bar with free sides is not a 1D bar
// at its driven end (the face is held laterally), so the work agrees with
// rho c A V^2 t only within 10 % (measured: 0.6 % below).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"
#include "support/materials.hpp"

namespace splat {
namespace {

constexpr double rho = test_support::steel_rho, E = test_support::steel_E, V = 1.0;
constexpr double width = 1e-3, length = 10e-3, end_time = 1.5e-6;

nlohmann::json driven_bar(double coefficient) {
  using nlohmann::json;
  const json material = test_support::elastic_steel_json();
  const json bar = {
      {"name", "bar"},
      {"material", material},
      {"geometry", {{"type", "box"}, {"min", {0.0, 0.0, 0.0}}, {"max", {width, width, length}}}},
      {"discretization", {{"type", "fe-hex"}, {"element_size", 0.25e-3}}}};
  return {{"name", "driven_bar"},
          {"bodies", {bar}},
          {"boundary_conditions",
           {{{"body", "bar"}, {"on", "z_min"}, {"type", "velocity"}, {"velocity", {0, 0, V}}}}},
          {"time", {{"end_time", end_time}, {"stability_coefficient", coefficient}}}};
}

TEST(prescribed_velocity, driven_bar_books_the_energy_put_in) {
  const LoadedScene loaded = read_scene(driven_bar(0.1));
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const RunSummary s = sim.run();
  ASSERT_EQ(std::string(to_string(s.outcome)), "finished") << s.reason;
  const EnergyBudget& e = s.energy;
  const double stored = e.kinetic + e.internal + e.hourglass + e.artificial_viscosity;
  const double closed_form = rho * std::sqrt(E / rho) * width * width * V * V * end_time;
  std::printf(
      "external work %.6e J, kinetic + internal + hourglass + viscosity %.6e J "
      "(kinetic %.4e, internal %.4e), rho c A V^2 t %.6e J, balance error %.3e\n",
      e.external_work, stored, e.kinetic, e.internal, closed_form, e.balance_error);
  EXPECT_GT(e.external_work, 0.0);
  EXPECT_NEAR(stored, e.external_work, 2e-3 * e.external_work);
  EXPECT_NEAR(e.external_work, closed_form, 0.1 * closed_form);
  // Started at rest: the balance is relative to the energy put in.
  EXPECT_LT(std::abs(e.balance_error), 2e-3);
}

}  // namespace
}  // namespace splat
