// volume_ratio_after (solver/material/point_update.hpp): the volume ratio a
// point reaches from its own strain increments. Exact references: J_mid tr
// equals the change of J in every step (so the trapezoidal pressure work is
// -p dJ), and a constant rate tr(D) = k integrates to J = exp(k t).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/material/point_update.hpp"

namespace splat {
namespace {

TEST(volume_ratio, mid_step_ratio_times_the_trace_is_the_change_of_j) {
  for (double J_old : {0.3, 0.97, 1.0, 1.4}) {
    for (double tr : {-0.2, -1e-4, 0.0, 3e-5, 0.15}) {
      const double J_new = volume_ratio_after(J_old, tr);
      EXPECT_NEAR(0.5 * (J_old + J_new) * tr, J_new - J_old, 1e-15 * J_old) << J_old << " " << tr;
      EXPECT_GT(J_new, 0.0);
    }
  }
}

TEST(volume_ratio, a_constant_rate_integrates_to_the_exponential) {
  const double k = -2e6, t_end = 1e-7;  // 1/s, s: J = exp(-0.2)
  for (int steps : {100, 1000}) {
    const double dt = t_end / steps;
    double J = 1.0;
    for (int i = 0; i < steps; ++i) J = volume_ratio_after(J, k * dt);
    // The (2 + x) / (2 - x) step is exp(x) to third order: error ~ t x^2 / 12.
    const double exact = std::exp(k * t_end);
    EXPECT_NEAR(J, exact, 2.0 * std::abs(k * t_end) * std::pow(k * dt, 2) / 12.0) << steps;
  }
}

}  // namespace
}  // namespace splat
