// Radial return of the Johnson-Cook law: converges for every state, with the
// residual of the consistency condition at rounding level.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/material/johnson_cook.hpp"

namespace splat {
namespace {

JohnsonCookParams copper() {
  JohnsonCookParams j;
  j.A = 90e6, j.B = 292e6, j.n = 0.31, j.C = 0.025, j.eps_dot_0 = 1.0, j.m = 1.09;
  j.T_ref = 300.0, j.T_melt = 1356.0;
  return j;
}

double residual(const JohnsonCookParams& j, const ModelSwitches& sw, double q_trial, double G,
                double eps_p, double dt, double T, double D, double dp) {
  const double sy = johnson_cook_flow_stress(j, sw, eps_p + dp, dp / dt, T).value;
  return q_trial - 3.0 * G * dp - (1.0 - D) * sy;
}

TEST(johnson_cook_return, converges_over_rates_temperatures_and_trial_stresses) {
  const JohnsonCookParams j = copper();
  const ModelSwitches sw;
  const double G = 46.3e9;
  int worst_iterations = 0;
  for (double rate : {1e-3, 1.0, 1e3, 1e6, 1e8}) {
    for (double T : {300.0, 800.0, 1355.0, 1356.0 - 1e-9, 1356.0, 2000.0}) {
      for (double eps_p : {0.0, 1e-8, 0.3, 5.0}) {
        for (double overshoot : {1e-9, 1e-3, 1.0, 100.0}) {
          for (double D : {0.0, 0.5, 0.9}) {
            // dt chosen so that the trial overshoot corresponds to `rate`.
            const double sy0 = (1.0 - D) * johnson_cook_flow_stress(j, sw, eps_p, 0.0, T).value;
            const double q_trial = sy0 * (1.0 + overshoot) + 1.0;
            const double dt = (q_trial - sy0) / (3.0 * G * (1.0 - D)) / rate;
            const double scale = (1.0 - D) * jc_thermal_factor(j, true, T);
            const ReturnMapResult r = johnson_cook_return(j, true, q_trial, (1.0 - D) * G, eps_p,
                                                          dt, scale, jc_hardening(j, eps_p));
            ASSERT_TRUE(r.converged);
            ASSERT_TRUE(std::isfinite(r.delta_eps_p));
            ASSERT_GE(r.delta_eps_p, 0.0);
            ASSERT_LE(r.delta_eps_p, q_trial / (3.0 * (1.0 - D) * G));
            const double g =
                residual(j, sw, q_trial, (1.0 - D) * G, eps_p, dt, T, D, r.delta_eps_p);
            ASSERT_LE(std::abs(g), 1e-9 * q_trial)
                << "rate " << rate << " T " << T << " eps_p " << eps_p << " over " << overshoot;
            worst_iterations = std::max(worst_iterations, r.iterations);
          }
        }
      }
    }
  }
  EXPECT_LE(worst_iterations, 80);
  std::printf("worst-case return-mapping iterations: %d\n", worst_iterations);
}

TEST(johnson_cook_flow_stress, clamps_rate_and_temperature_terms) {
  const JohnsonCookParams j = copper();
  ModelSwitches sw;
  const double base = johnson_cook_flow_stress(j, sw, 0.1, 0.0, 300.0).value;
  EXPECT_DOUBLE_EQ(johnson_cook_flow_stress(j, sw, 0.1, 0.5, 300.0).value,
                   base);  // below eps_dot_0
  EXPECT_DOUBLE_EQ(johnson_cook_flow_stress(j, sw, 0.1, 0.0, 200.0).value, base);  // below T_ref
  EXPECT_EQ(johnson_cook_flow_stress(j, sw, 0.1, 0.0, 1356.0).value, 0.0);         // at melt
  EXPECT_EQ(johnson_cook_flow_stress(j, sw, 0.1, 0.0, 5000.0).value, 0.0);         // above melt
  EXPECT_GT(johnson_cook_flow_stress(j, sw, 0.1, 1e6, 300.0).value, base);
  sw.rate_hardening = false;
  EXPECT_DOUBLE_EQ(johnson_cook_flow_stress(j, sw, 0.1, 1e6, 300.0).value, base);
  sw.thermal_softening = false;
  EXPECT_DOUBLE_EQ(johnson_cook_flow_stress(j, sw, 0.1, 0.0, 1000.0).value, base);
}

}  // namespace
}  // namespace splat
