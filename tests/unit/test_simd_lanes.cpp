// The log of simd_lanes.hpp: log1p_series against std::log1p, and lane_log
// against std::log, in scalars and in lanes (the same bits either way).
// Lane vectors returned by value in a test built for the baseline: no ABI
// boundary here is crossed by other code.
#pragma GCC diagnostic ignored "-Wpsabi"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "solver/common/simd_lanes.hpp"

namespace splat {
namespace {

// Over |r| <= 1/16, to rounding (1e-15, a few units in the last place); the
// series refuses |r| > 1/16.
TEST(simd_lanes, log1p_series_is_log1p) {
  double worst = 0.0;
  for (int k = -1000; k <= 1000; ++k) {
    const double r = 0.0625 * k / 1000.0;
    bool ok = false;
    const double v = log1p_series(r, ok);
    ASSERT_TRUE(ok) << r;
    const double exact = std::log1p(r);
    EXPECT_NEAR(v, exact, 1e-15 * std::abs(exact)) << r;
    if (exact != 0.0) worst = std::max(worst, std::abs(v / exact - 1.0));
  }
  std::printf("log1p series: largest relative error %.2g over |r| <= 1/16\n", worst);
  bool ok = true;
  log1p_series(0.07, ok);
  EXPECT_FALSE(ok);
  log1p_series(-0.07, ok);
  EXPECT_FALSE(ok);
}

// lane_log from 0.3 to 3 (the series near 1, std::log elsewhere; a group of 8
// lanes mixes both), and at 0 and below: within 1e-15 of std::log, and the
// lanes give the scalar's bits.
TEST(simd_lanes, lane_log_is_log_in_scalars_and_lanes) {
  constexpr int n = 2001;
  for (int k0 = 0; k0 < n; k0 += 8) {
    Lane8 a{};
    for (int l = 0; l < 8; ++l) a[l] = 0.3 + 2.7 * std::min(k0 + l, n - 1) / (n - 1.0);
    const Lane8 v = lane_log(a);
    for (int l = 0; l < 8; ++l) {
      const double scalar = lane_log(a[l]);
      EXPECT_EQ(std::memcmp(&scalar, &v[l], sizeof scalar), 0) << a[l];
      EXPECT_NEAR(scalar, std::log(a[l]), 1e-15 * std::abs(std::log(a[l])) + 1e-300) << a[l];
    }
  }
  EXPECT_EQ(lane_log(1.0), 0.0);
  EXPECT_EQ(lane_log(0.0), -HUGE_VAL);
  EXPECT_TRUE(std::isnan(lane_log(-1.0)));
}

}  // namespace
}  // namespace splat
