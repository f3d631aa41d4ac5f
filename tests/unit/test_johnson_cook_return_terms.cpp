// The hardening and rate terms the Johnson-Cook return hands back (cached in
// the point state by update_point) are those of the law at the returned
// plastic increment, whether the return ended on an evaluation or on a
// Taylor-expanded last step (johnson_cook.cpp): checked against
// jc_hardening and jc_rate_factor evaluated directly.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/material/johnson_cook.hpp"

namespace splat {
namespace {

TEST(johnson_cook_return, returned_terms_are_the_law_at_the_returned_increment) {
  JohnsonCookParams j;
  j.A = 90e6, j.B = 292e6, j.n = 0.31, j.C = 0.025, j.eps_dot_0 = 1.0, j.m = 1.09;
  j.T_ref = 300.0, j.T_melt = 1356.0;
  const double G = 46.3e9;
  int taylor_like = 0;  // returns that ended after a single evaluation
  for (double eps_p : {1e-6, 1e-3, 0.3, 2.0}) {
    for (double rate : {0.5, 1e3, 1e6}) {
      for (double rel_guess_error : {0.0, 1e-6, 1e-4, 1e-2}) {
        const double dt = 1e-9 * (rate > 1e5 ? 1.0 : 1e3);
        // A trial stress whose return gives about `rate`: solve once, then
        // seed a second return with the answer perturbed by rel_guess_error.
        const double hard0 = jc_hardening(j, eps_p);
        const double dp_target = rate * dt;
        const double q_trial = 3.0 * G * dp_target + hard0 * jc_rate_factor(j, true, rate);
        const ReturnMapResult first =
            johnson_cook_return(j, true, q_trial, G, eps_p, dt, 1.0, hard0);
        ASSERT_TRUE(first.converged);
        const ReturnMapResult r = johnson_cook_return(j, true, q_trial, G, eps_p, dt, 1.0, hard0,
                                                      first.delta_eps_p * (1.0 + rel_guess_error));
        ASSERT_TRUE(r.converged);
        if (r.iterations == 1) ++taylor_like;
        const double dp = r.delta_eps_p;
        const double hard = jc_hardening(j, eps_p + dp);
        const double rf = jc_rate_factor(j, true, dp / dt);
        EXPECT_NEAR(r.hard, hard, 1e-14 * hard) << eps_p << " " << rate << " " << rel_guess_error;
        EXPECT_NEAR(r.rate, rf, 1e-14 * rf) << eps_p << " " << rate << " " << rel_guess_error;
        EXPECT_NEAR(r.hard_rate, hard * rf, 1e-14 * hard * rf);
        EXPECT_NEAR(r.delta_eps_p, first.delta_eps_p, 1e-9 * first.delta_eps_p);
      }
    }
  }
  std::printf("returns that ended after one evaluation: %d of 48\n", taylor_like);
}

}  // namespace
}  // namespace splat
