// traction_cylinder: the traction test of thesis section 3.2
// (scenes/thesis/traction_cylinder_axisym.json), an aluminium cylinder 40 mm
// across and 120 mm long, held axially at its bottom end and pulled at its
// top end to 2.4 m/s through a smooth-step ramp of 1 ms, both ends free to
// contract radially. Until it necks the bar is uniform, and its force is the
// closed form of tests/exact/uniform_bar_tension.hpp for the material's own
// Johnson-Cook law (E A0 eps while elastic; sigma_y(eps_p, eps_dot, T) A0
// exp(-eps) once plastic, T adiabatic).
//
// Checked, on the histories of the result file (pulled_end_reaction_z
// against pulled_end_displacement_z):
//   - the pulled end sits where the velocity table puts it (its exact
//     integral), to 1e-9 of the elongation;
//   - elastic part, eps from 0.25 to 0.75 of the yield strain: within 2 % of
//     E A0 eps (the ramp's inertial force, about 1 % there, see the scene;
//     measured 0.9 %);
//   - plastic part, eps from 3 yield strains to 0.9 of the closed form's
//     necking strain: within 0.1 % of the closed form, half its smallest
//     term (the elastic volume change, 0.23 %; the rate term is 0.30 %), so
//     that a term missing from the solver fails; at 5 and at 10 elements
//     across the radius, which agree to 0.1 % (a uniform bar is represented
//     exactly by either mesh; measured: 0.054 % from the closed form, 0.002 %
//     between the meshes);
//   - the fixed end carries the opposite force, within 0.1 % after the ramp
//     (the bar's inertia; measured 0.007 %);
//   - thermal softening on lies below thermal softening off over the whole
//     plastic range checked, and the gap at 0.9 of the necking strain is the
//     closed form's (2.26 % of the force) within 0.1 % of the force.
// Runs end at 7 ms (elongation 15.6 mm, true strain 0.122): past both
// closed-form necking strains (0.089 softened, 0.116 not). About 3 s for the
// three runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "exact/uniform_bar_tension.hpp"
#include "solver/core/simulation.hpp"
#include "solver/input/material_io.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/io/result_file.hpp"
#include "solver/scene/velocity_history.hpp"
#include "support/temp_dir.hpp"

namespace splat {
namespace {

const std::filesystem::path scene_file =
    std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes/thesis/traction_cylinder_axisym.json";
constexpr double end_time = 7e-3;  // s

struct Curve {
  std::string outcome, reason;
  std::vector<double> time, u, force, fixed_force;  // s, m, N, N
  std::string force_unit, displacement_unit;
  VelocityHistory table;  // the pulled end's, user frame
};

Curve run(int elements_across, bool thermal_softening) {
  test_support::TempDir dir("traction");
  const LoadedScene loaded = load_scene(
      scene_file, {"/bodies/0/discretization/elements_across=" + std::to_string(elements_across),
                   std::string("/bodies/0/switches/thermal_softening=") +
                       (thermal_softening ? "true" : "false"),
                   "/time/end_time=" + std::to_string(end_time), "/output/snapshot_count=0"});
  SimulationOptions options;
  options.threads = 1;
  options.quiet = true;
  options.output_dir = dir.path;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const RunSummary s = sim.run();
  Curve c;
  c.outcome = to_string(s.outcome);
  c.reason = s.reason;
  const std::filesystem::path h5 = dir.path / "traction_cylinder_axisym.h5";
  c.time = read_history(h5, "time");
  c.u = read_history(h5, "pulled_end_displacement_z");
  c.force = read_history(h5, "pulled_end_reaction_z");
  c.fixed_force = read_history(h5, "fixed_end_reaction_z");
  c.force_unit = read_unit(h5, "/history/pulled_end_reaction_z");
  c.displacement_unit = read_unit(h5, "/history/pulled_end_displacement_z");
  for (const BoundarySpec& bc : loaded.scene.boundaries) {
    if (bc.name == "pulled_end" && bc.history) c.table = *bc.history;
  }
  return c;
}

// The scene's bar and material (from the library document the scene names).
exact::UniformBar bar(bool thermal_softening) {
  const nlohmann::json m = material_document("al-thesis");
  const nlohmann::json& st = m.at("strength");
  exact::UniformBar b;
  b.law = {st.at("A"),         st.at("B"), st.at("n"),     st.at("C"),
           st.at("eps_dot_0"), st.at("m"), st.at("T_ref"), st.at("T_melt")};
  b.E = m.at("elastic").at("E");
  b.nu = m.at("elastic").at("nu");
  b.length = 0.12;
  b.area = std::numbers::pi * 0.02 * 0.02;
  b.T0 = 300.0;
  b.heating = m.at("thermal").at("heat_fraction").get<double>() /
              (m.at("density").get<double>() * m.at("thermal").at("c_p").get<double>());
  b.thermal_softening = thermal_softening;
  return b;
}

double true_strain(double u) {
  return std::log1p(u / 0.12);
}
double yield_strain(const exact::UniformBar& b) {
  return b.law.A / b.E;
}

// The closed form's necking (Considere) strain: its force maximum.
double necking_strain(const exact::UniformBar& b, double v) {
  double best_force = 0.0, best_eps = 0.0;
  for (int k = 1; k <= 400; ++k) {
    const double u = 0.12 * (std::exp(0.2 * k / 400.0) - 1.0);
    const double f = exact::uniform_bar_tension(b, u, v, 1000).force;
    if (f > best_force) {
      best_force = f;
      best_eps = true_strain(u);
    }
  }
  return best_eps;
}

// The pulled end's speed at time t (for the closed form's strain rate).
double pull_speed(const Curve& c, double t) {
  return history_velocity(c.table, t).z();
}

// Linear interpolation of y(x) on increasing x.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  const auto it = std::lower_bound(x.begin(), x.end(), at);
  if (it == x.begin()) return y.front();
  if (it == x.end()) return y.back();
  const std::size_t k = static_cast<std::size_t>(it - x.begin());
  const double w = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

class TractionCylinder : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    runs = new std::map<std::string, Curve>{
        {"coarse", run(5, true)}, {"fine", run(10, true)}, {"coarse_no_softening", run(5, false)}};
  }
  static void TearDownTestSuite() {
    delete runs;
    runs = nullptr;
  }
  static const Curve& curve(const std::string& name) { return runs->at(name); }
  static std::map<std::string, Curve>* runs;
};
std::map<std::string, Curve>* TractionCylinder::runs = nullptr;

TEST_F(TractionCylinder, runs_finish_and_write_their_histories_with_units) {
  for (const auto& [name, c] : *runs) {
    EXPECT_EQ(c.outcome, "finished") << name << ": " << c.reason;
    EXPECT_EQ(c.force_unit, "N") << name;
    EXPECT_EQ(c.displacement_unit, "m") << name;
    ASSERT_GT(c.time.size(), 300u) << name;
    EXPECT_NEAR(c.time.back(), end_time, 1e-12) << name;
  }
}

TEST_F(TractionCylinder, pulled_end_sits_where_the_table_puts_it) {
  for (const auto& [name, c] : *runs) {
    double worst = 0.0;
    for (std::size_t k = 0; k < c.time.size(); ++k) {
      const double expected = history_displacement(c.table, c.time[k]).z();
      worst = std::max(worst, std::abs(c.u[k] - expected));
    }
    const double final_u = history_displacement(c.table, end_time).z();
    std::printf("%s: final elongation %.6e m (table %.6e m), largest departure %.3e m\n",
                name.c_str(), c.u.back(), final_u, worst);
    EXPECT_LT(worst, 1e-9 * final_u) << name;
  }
}

TEST_F(TractionCylinder, elastic_force_is_E_A0_eps) {
  const exact::UniformBar b = bar(true);
  for (const auto& [name, c] : *runs) {
    double worst = 0.0;
    int rows = 0;
    for (std::size_t k = 0; k < c.time.size(); ++k) {
      const double eps = true_strain(c.u[k]);
      if (eps < 0.25 * yield_strain(b) || eps > 0.75 * yield_strain(b)) continue;
      const double reference = b.E * b.area * eps;
      worst = std::max(worst, std::abs(c.force[k] / reference - 1.0));
      ++rows;
    }
    std::printf("%s: elastic part, %d rows, largest |F / (E A0 eps) - 1| = %.4f\n", name.c_str(),
                rows, worst);
    EXPECT_GE(rows, 3) << name;
    EXPECT_LT(worst, 0.02) << name;
  }
}

TEST_F(TractionCylinder, plastic_force_follows_the_uniform_bar_closed_form) {
  for (const auto& [name, c] : *runs) {
    const bool softening = name != "coarse_no_softening";
    const exact::UniformBar b = bar(softening);
    const double eps_neck = necking_strain(b, 2.4);
    double worst = 0.0, worst_eps = 0.0, peak = 0.0;
    int rows = 0;
    for (std::size_t k = 0; k < c.time.size(); ++k) {
      const double eps = true_strain(c.u[k]);
      if (eps < 3.0 * yield_strain(b) || eps > 0.9 * eps_neck) continue;
      const double reference =
          exact::uniform_bar_tension(b, c.u[k], pull_speed(c, c.time[k])).force;
      const double error = c.force[k] / reference - 1.0;
      if (std::abs(error) > std::abs(worst)) {
        worst = error;
        worst_eps = eps;
      }
      peak = std::max(peak, c.force[k]);
      ++rows;
    }
    std::printf(
        "%s: plastic part to 0.9 eps_neck = %.4f, %d rows, largest F / F_closed - 1 = %+.5f at "
        "eps %.4f; largest force %.5e N\n",
        name.c_str(), 0.9 * eps_neck, rows, worst, worst_eps, peak);
    EXPECT_GE(rows, 100) << name;
    EXPECT_LT(std::abs(worst), 0.001) << name;
  }
}

TEST_F(TractionCylinder, resolutions_agree) {
  const Curve& coarse = curve("coarse");
  const Curve& fine = curve("fine");
  const exact::UniformBar b = bar(true);
  const double eps_neck = necking_strain(b, 2.4);
  double worst = 0.0;
  for (std::size_t k = 0; k < fine.time.size(); ++k) {
    const double eps = true_strain(fine.u[k]);
    if (eps < 3.0 * yield_strain(b) || eps > 0.9 * eps_neck) continue;
    const double f_coarse = interpolate(coarse.u, coarse.force, fine.u[k]);
    worst = std::max(worst, std::abs(f_coarse / fine.force[k] - 1.0));
  }
  std::printf(
      "5 vs 10 elements across: largest |F_5 / F_10 - 1| = %.5f (plastic, to 0.9 eps_neck)\n",
      worst);
  EXPECT_LT(worst, 0.001);
}

TEST_F(TractionCylinder, fixed_end_carries_the_opposite_force) {
  for (const auto& [name, c] : *runs) {
    double worst = 0.0;
    for (std::size_t k = 0; k < c.time.size(); ++k) {
      if (c.time[k] < 1e-3) continue;  // after the ramp
      worst = std::max(worst, std::abs(c.fixed_force[k] + c.force[k]) / std::abs(c.force[k]));
    }
    std::printf("%s: after the ramp, largest |F_fixed + F_pulled| / |F_pulled| = %.5f\n",
                name.c_str(), worst);
    EXPECT_LT(worst, 0.001) << name;
  }
}

TEST_F(TractionCylinder, thermal_softening_lowers_the_curve) {
  const Curve& on = curve("coarse");
  const Curve& off = curve("coarse_no_softening");
  const exact::UniformBar b_on = bar(true), b_off = bar(false);
  const double eps_neck = necking_strain(b_on, 2.4);
  int above = 0, rows = 0;
  for (std::size_t k = 0; k < on.time.size(); ++k) {
    const double eps = true_strain(on.u[k]);
    if (eps < 3.0 * yield_strain(b_on) || eps > 0.9 * eps_neck) continue;
    ++rows;
    if (!(on.force[k] < interpolate(off.u, off.force, on.u[k]))) ++above;
  }
  // The gap at 0.9 of the necking strain against the closed form's.
  const double u_check = 0.12 * std::expm1(0.9 * eps_neck);
  const double f_on = interpolate(on.u, on.force, u_check);
  const double f_off = interpolate(off.u, off.force, u_check);
  const double v = 2.4;
  const double c_on = exact::uniform_bar_tension(b_on, u_check, v).force;
  const double c_off = exact::uniform_bar_tension(b_off, u_check, v).force;
  std::printf(
      "softening on below off at %d of %d rows; at eps %.4f: F_off - F_on = %.4e N (%.3f %% of "
      "F_off), closed form %.4e N (%.3f %%)\n",
      rows - above, rows, 0.9 * eps_neck, f_off - f_on, 100.0 * (f_off - f_on) / f_off,
      c_off - c_on, 100.0 * (c_off - c_on) / c_off);
  EXPECT_GE(rows, 100);
  EXPECT_EQ(above, 0);
  EXPECT_NEAR((f_off - f_on) / f_off, (c_off - c_on) / c_off, 0.001);
}

}  // namespace
}  // namespace splat
