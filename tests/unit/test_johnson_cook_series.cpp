// The series shortcuts of the Johnson-Cook law (johnson_cook.cpp) against the
// law evaluated directly with exp and log:
//   - the thermal factor carried over small heating steps,
//     jc_thermal_factor_after_heating, one step and 100,000 steps in a row;
//   - the return of a step that continues plastic flow (the terms at the
//     guess from the cached hardening and the previous rate factor);
//   - both over 100,000 plastic steps of a point, where the cached terms
//     carry their rounding (and the Taylor-expanded ends' truncation) from
//     step to step.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update.hpp"
#include "tests/support/materials.hpp"

namespace splat {
namespace {

// The copper of the other tests (A 90 MPa, B 292 MPa, n 0.31, C 0.025,
// m 1.09, T_ref 300 K, T_melt 1356 K).
JohnsonCookParams copper() {
  return std::get<JohnsonCookParams>(test_support::jc_copper().strength);
}

TEST(johnson_cook_series, thermal_factor_after_one_heating_step) {
  JohnsonCookParams j = copper();
  for (double m : {0.5, 1.09, 1.7, 3.0}) {
    j.m = m;
    for (double T_old : {299.0, 300.0, 300.5, 310.0, 600.0, 1000.0, 1350.0}) {
      for (double dT : {0.0, 1e-6, 1e-3, 0.05, 1.0, 20.0}) {
        const double theta_old = jc_thermal_factor(j, true, T_old);
        const double got =
            jc_thermal_factor_after_heating(j, jc_series(j), theta_old, T_old, T_old + dT);
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
    theta = jc_thermal_factor_after_heating(j, jc_series(j), theta, T, T_new);
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
        const JcSeries series = jc_series(j);
        const ReturnMapResult r =
            johnson_cook_return(j, true, q_trial, G, eps_p, dt, 1.0, hard0, dp_prev,
                                jc_rate_factor(j, true, rate), &series);
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

// The binomial series of degree 12 against B (eps_p + dp)^n by pow, wherever
// it says it applies, to the rounding of pow and of the series (1e-15 of
// the hardening term);
// for copper's n it must apply up to u = dp / eps_p = 0.05 and not at 0.2.
TEST(johnson_cook_series, hardening_series_is_the_law_where_it_applies) {
  for (double n : {0.1, 0.31, 0.5, 1.0, 1.7}) {
    JohnsonCookParams j = copper();
    j.n = n;
    const JcSeries series = jc_series(j);
    for (double eps_p : {1e-4, 0.3, 3.0}) {
      const double P0 = j.B * std::pow(eps_p, n);
      int applies = 0;
      for (int k = 0; k <= 400; ++k) {
        const double u = 0.25 * k / 400.0;
        bool ok = false;
        const double series_value = jc_hardening_series(j, series, P0, u, ok);
        if (!ok) continue;
        ++applies;
        const double law = j.B * std::pow(eps_p * (1.0 + u), n);
        EXPECT_NEAR(j.A + series_value, j.A + law, 1e-15 * (j.A + law))
            << n << " " << eps_p << " " << u;
      }
      std::printf("n %.2f eps_p %g: the series applies at %d of 401 u in [0, 0.25]\n", n, eps_p,
                  applies);
    }
  }
  const JohnsonCookParams j = copper();
  const JcSeries series = jc_series(j);
  bool ok = false;
  jc_hardening_series(j, series, j.B * std::pow(0.1, j.n), 0.05, ok);
  EXPECT_TRUE(ok);
  jc_hardening_series(j, series, j.B * std::pow(0.1, j.n), 0.2, ok);
  EXPECT_FALSE(ok);
}

// 100,000 steps of adiabatic uniaxial compression at 1e5 /s (dt 1e-9 s, total
// plastic strain 10, heating to 1,190 K): every step after the first few
// continues plastic flow, so the cached hardening A + B eps_p^n and strength
// scale 1 - T*^m are carried over by the series and the Taylor-expanded ends.
// They must stay the law at the point's eps_p and T; the drift is printed.
TEST(johnson_cook_series, cached_terms_stay_the_law_over_many_plastic_steps) {
  const Material m = test_support::jc_copper();
  const ModelSwitches sw = test_support::no_damage();
  const MaterialConstants mc = derive_constants(m);
  PointState st = initial_point_state(m, sw, 300.0, 0.0);
  const double dt = 1e-9, rate = 1e5;
  // Volume-preserving uniaxial compression along z.
  Mat3 d_eps = Mat3::Zero();
  d_eps(2, 2) = -rate * dt;
  d_eps(0, 0) = d_eps(1, 1) = 0.5 * rate * dt;
  int one_step = 0;
  for (int k = 0; k < 100000; ++k) {
    const PointUpdateResult r = update_point(m, mc, sw, st, d_eps, 1.0, dt, 1e-6);
    ASSERT_TRUE(r.converged);
    one_step += r.iterations == 1;
  }
  const double hard = jc_hardening(std::get<JohnsonCookParams>(m.strength), st.eps_p);
  const double theta = jc_thermal_factor(std::get<JohnsonCookParams>(m.strength), true, st.T);
  std::printf("eps_p %.4f, T %.2f K, one-step returns %d; hardening drift %.2g, scale drift %.2g\n",
              st.eps_p, st.T, one_step, st.hardening / hard - 1.0, st.strength_scale - theta);
  EXPECT_GT(st.eps_p, 9.0);
  EXPECT_GT(st.T, 1000.0);
  EXPECT_GT(one_step, 90000);
  EXPECT_NEAR(st.hardening, hard, 1e-11 * hard);
  EXPECT_NEAR(st.strength_scale, theta, 1e-11);
}

// As above, with the strain rate varying by 2 % around 1e5 /s (period 44
// steps), so that most returns end in the fast path's second evaluation,
// which carries the rate factor over by the series of ln(1 + step / dp): the
// cached hardening, strength scale and rate factor sigma_y / sigma_y_static
// must stay the law at the point's eps_p, T and plastic rate.
TEST(johnson_cook_series, cached_terms_stay_the_law_when_the_rate_varies) {
  const Material m = test_support::jc_copper();
  const ModelSwitches sw = test_support::no_damage();
  const MaterialConstants mc = derive_constants(m);
  PointState st = initial_point_state(m, sw, 300.0, 0.0);
  const double dt = 1e-9;
  int two_evaluations = 0;
  for (int k = 0; k < 100000; ++k) {
    const double rate = 1e5 * (1.0 + 0.02 * std::sin(k / 7.0));
    Mat3 d_eps = Mat3::Zero();
    d_eps(2, 2) = -rate * dt;
    d_eps(0, 0) = d_eps(1, 1) = 0.5 * rate * dt;
    const PointUpdateResult r = update_point(m, mc, sw, st, d_eps, 1.0, dt, 1e-6);
    ASSERT_TRUE(r.converged);
    two_evaluations += r.iterations == 2;
  }
  const double hard = jc_hardening(std::get<JohnsonCookParams>(m.strength), st.eps_p);
  const double theta = jc_thermal_factor(std::get<JohnsonCookParams>(m.strength), true, st.T);
  const double rate_factor =
      jc_rate_factor(std::get<JohnsonCookParams>(m.strength), true, st.eps_dot_p);
  std::printf(
      "eps_p %.4f, T %.2f K, two-evaluation returns %d; drift: hardening %.2g, scale "
      "%.2g, rate factor %.2g\n",
      st.eps_p, st.T, two_evaluations, st.hardening / hard - 1.0, st.strength_scale - theta,
      st.sigma_y / st.sigma_y_static / rate_factor - 1.0);
  EXPECT_GT(st.eps_p, 9.0);
  EXPECT_GT(two_evaluations, 50000);
  EXPECT_NEAR(st.hardening, hard, 1e-11 * hard);
  EXPECT_NEAR(st.strength_scale, theta, 1e-11);
  EXPECT_NEAR(st.sigma_y / st.sigma_y_static, rate_factor, 1e-11 * rate_factor);
}

}  // namespace
}  // namespace splat
