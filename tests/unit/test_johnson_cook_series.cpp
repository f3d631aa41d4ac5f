// The series shortcuts of the Johnson-Cook law (johnson_cook.cpp) against the
// law evaluated directly with exp and log:
//   - the thermal factor carried over small heating steps,
//     jc_thermal_factor_after_heating, one step and 100,000 steps in a row;
//   - the return of a step that continues plastic flow (the terms at the
//     guess from the cached hardening and the previous rate factor).
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

TEST(johnson_cook_series, thermal_factor_after_one_heating_step) {
  JohnsonCookParams j = copper();
  for (double m : {0.5, 1.09, 1.7, 3.0}) {
    j.m = m;
    for (double T_old : {299.0, 300.0, 300.5, 310.0, 600.0, 1000.0, 1350.0}) {
      for (double dT : {0.0, 1e-6, 1e-3, 0.05, 1.0, 20.0}) {
        const double theta_old = jc_thermal_factor(j, true, T_old);
        const double got =
            jc_thermal_factor_after_heating(j, jc_thermal_series(j), theta_old, T_old, T_old + dT);
        const double want = jc_thermal_factor(j, true, T_old + dT);
        EXPECT_NEAR(got, want, 4e-16) << "m " << m << " T " << T_old << " dT " << dT;
      }
    }
  }
}

// 100,000 heating steps of 0.005 K from 310 K: each step rounds anew, the
// error grows no faster than the step count times the rounding (1e-16).
TEST(johnson_cook_series, thermal_factor_over_many_heating_steps) {
  const JohnsonCookParams j = copper();
  double T = 310.0;
  double theta = jc_thermal_factor(j, true, T);
  for (int k = 0; k < 100000; ++k) {
    const double T_new = T + 0.005;
    theta = jc_thermal_factor_after_heating(j, jc_thermal_series(j), theta, T, T_new);
    T = T_new;
  }
  const double want = jc_thermal_factor(j, true, T);
  EXPECT_NEAR(theta, want, 1e-11);
  std::printf("thermal factor after 100000 steps: %.17g, direct %.17g, difference %.2g\n", theta,
              want, theta - want);
}

// A step that continues plastic flow: the guess is the previous increment and
// rate_guess its rate factor. The return must give the increment of the
// general iteration (no rate_guess) and the terms of the law at it.
TEST(johnson_cook_series, continued_flow_return_matches_the_law) {
  const JohnsonCookParams j = copper();
  const double G = 46.3e9;
  for (double eps_p : {1e-4, 0.01, 0.3, 3.0}) {
    for (double rate : {1e3, 1e5, 1e8}) {
      for (double change : {1.0, 1.001, 0.9, 1.5}) {
        const double dt = 1e-4 / rate;  // plastic strain 1e-4 per step
        const double dp_prev = rate * dt;
        const double dp_target = change * dp_prev;
        const double hard0 = jc_hardening(j, eps_p);
        const double q_trial = 3.0 * G * dp_target + jc_hardening(j, eps_p + dp_target) *
                                                         jc_rate_factor(j, true, dp_target / dt);
        const ReturnMapResult plain =
            johnson_cook_return(j, true, q_trial, G, eps_p, dt, 1.0, hard0, dp_prev);
        const ReturnMapResult r = johnson_cook_return(j, true, q_trial, G, eps_p, dt, 1.0, hard0,
                                                      dp_prev, jc_rate_factor(j, true, rate));
        ASSERT_TRUE(plain.converged);
        ASSERT_TRUE(r.converged);
        const double dp = r.delta_eps_p;
        EXPECT_NEAR(dp, dp_target, 1e-9 * dp_target) << eps_p << " " << rate << " " << change;
        EXPECT_NEAR(dp, plain.delta_eps_p, 1e-9 * dp_target);
        const double hard = jc_hardening(j, eps_p + dp);
        const double rf = jc_rate_factor(j, true, dp / dt);
        EXPECT_NEAR(r.hard, hard, 1e-14 * hard) << eps_p << " " << rate << " " << change;
        EXPECT_NEAR(r.rate, rf, 1e-14 * rf) << eps_p << " " << rate << " " << change;
        EXPECT_NEAR(r.hard_rate, hard * rf, 1e-14 * hard * rf);
      }
    }
  }
}

}  // namespace
}  // namespace splat
