// Richardson extrapolation (solver/core/richardson.hpp) on sequences with a
// known limit and order: f(h) = f* + C h^p.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/core/richardson.hpp"

namespace splat {
namespace {

TEST(richardson, recovers_order_and_limit_of_a_power_law_sequence) {
  for (double p : {1.0, 2.0, 0.6}) {
    auto f = [&](double h) { return 3.0 + 0.7 * std::pow(h, p); };
    const auto r = richardson(f(0.4), f(0.2), f(0.1), 2.0);
    ASSERT_TRUE(r);
    EXPECT_NEAR(r->order, p, 1e-10);
    EXPECT_NEAR(r->estimate, 3.0, 1e-10);
  }
  // Ratio 3, decreasing from below.
  auto g = [](double h) { return -1.0 - 2.0 * h * h; };
  const auto r = richardson(g(0.9), g(0.3), g(0.1), 3.0);
  ASSERT_TRUE(r);
  EXPECT_NEAR(r->order, 2.0, 1e-10);
  EXPECT_NEAR(r->estimate, -1.0, 1e-10);
}

TEST(richardson, oscillating_or_stalled_sequences_have_no_estimate) {
  EXPECT_FALSE(richardson(1.0, 2.0, 1.5, 2.0));   // oscillates
  EXPECT_FALSE(richardson(1.0, 1.0, 1.0, 2.0));   // no change
  EXPECT_FALSE(richardson(1.0, 0.5, 0.25, 1.0));  // no refinement
  EXPECT_FALSE(richardson(1.0, 0.9, 0.5, 2.0));   // differences grow: diverges
  // Differences that barely shrink (p = 0.08): 884, 828, 775 would
  // extrapolate to -155; below k_min_observed_order there is no estimate.
  EXPECT_FALSE(richardson(884.0, 828.0, 775.0, 2.0));
  auto slow = [](double h) { return 3.0 + 0.7 * std::pow(h, 0.3); };
  EXPECT_FALSE(richardson(slow(0.4), slow(0.2), slow(0.1), 2.0));
}

}  // namespace
}  // namespace splat
