// splat::simd::exp and log (solver/common/simd_math.hpp) against the long
// double (64-bit mantissa) libm over the whole double range, their special
// values, and the identity of every vector lane with the scalar instantiation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "solver/common/simd_math.hpp"

// The vector types are passed by value inside this file only.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace {

using splat::simd::v4d;
using splat::simd::v8d;

// Error of `got` in units of the last place of the exact value (a long double).
double ulp_error(double got, long double exact) {
  const double e = static_cast<double>(exact);
  if (std::isinf(e) || e == 0.0) return got == e ? 0.0 : std::numeric_limits<double>::infinity();
  const int ex = std::max(std::ilogb(e), -1022);
  const long double ulp = std::ldexp(1.0L, ex - 52);
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / ulp);
}

TEST(simd_math, exp_within_1_5_ulp_from_underflow_to_overflow) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-745.0, 709.7);
  std::uniform_real_distribution<double> small(-1.0, 1.0);
  double worst = 0.0, worst_x = 0.0;
  for (int i = 0; i < 2000000; ++i) {
    // Half over the whole range, half over decades of small |x| (1e-20 .. 1).
    const double x = i % 2 ? u(rng) : small(rng) * std::pow(10.0, -20.0 * std::fabs(small(rng)));
    const double err = ulp_error(splat::simd::exp(x), std::exp(static_cast<long double>(x)));
    if (err > worst) worst = err, worst_x = x;
  }
  std::printf("exp: max error %.3f ulp at x = %a\n", worst, worst_x);
  EXPECT_LE(worst, 1.5);
}

TEST(simd_math, log_within_1_5_ulp_over_all_binades) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> mant(1.0, 2.0);
  std::uniform_int_distribution<int> ex(-1074, 1023);
  std::uniform_real_distribution<double> near1(-1e-3, 1e-3);
  double worst = 0.0, worst_x = 0.0;
  for (int i = 0; i < 2000000; ++i) {
    // Every binade incl. the subnormals, and values near 1 (the largest
    // relative cancellation).
    const double x = i % 2 ? std::ldexp(mant(rng), ex(rng)) : 1.0 + near1(rng);
    if (x == 0.0) continue;
    const double err = ulp_error(splat::simd::log(x), std::log(static_cast<long double>(x)));
    if (err > worst) worst = err, worst_x = x;
  }
  std::printf("log: max error %.3f ulp at x = %a\n", worst, worst_x);
  EXPECT_LE(worst, 1.5);
}

TEST(simd_math, special_values) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double dmin = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(splat::simd::exp(0.0), 1.0);
  EXPECT_EQ(splat::simd::exp(-0.0), 1.0);
  EXPECT_EQ(splat::simd::exp(inf), inf);
  EXPECT_EQ(splat::simd::exp(-inf), 0.0);
  EXPECT_TRUE(std::isnan(splat::simd::exp(nan)));
  EXPECT_EQ(splat::simd::exp(709.79), inf);
  EXPECT_EQ(splat::simd::exp(-745.2), 0.0);
  EXPECT_EQ(splat::simd::exp(-745.0), std::exp(-745.0));  // denorm_min territory
  EXPECT_EQ(splat::simd::exp(709.78), std::exp(709.78));
  EXPECT_EQ(splat::simd::log(1.0), 0.0);
  EXPECT_EQ(splat::simd::log(0.0), -inf);
  EXPECT_EQ(splat::simd::log(-0.0), -inf);
  EXPECT_EQ(splat::simd::log(inf), inf);
  EXPECT_TRUE(std::isnan(splat::simd::log(-1.0)));
  EXPECT_TRUE(std::isnan(splat::simd::log(-inf)));
  EXPECT_TRUE(std::isnan(splat::simd::log(nan)));
  EXPECT_EQ(splat::simd::log(dmin), std::log(dmin));
  EXPECT_EQ(splat::simd::log(std::numeric_limits<double>::max()),
            std::log(std::numeric_limits<double>::max()));
  EXPECT_EQ(splat::simd::log(2.0), std::log(2.0));
  EXPECT_NEAR(splat::simd::pow(8.0, 1.0 / 3.0), 2.0, 4e-16);
}

template <class V>
void expect_lanes_equal_scalar() {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-800.0, 800.0);
  std::uniform_int_distribution<int> ex(-1074, 1023);
  const double specials[] = {0.0,
                             -0.0,
                             1.0,
                             -1.0,
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN(),
                             4.9e-324,
                             1e-310};
  constexpr int W = splat::simd::lanes<V>;
  for (int i = 0; i < 20000; ++i) {
    V x, y;
    for (int l = 0; l < W; ++l) {
      x[l] = i < 3 ? specials[(i * W + l) % 9] : u(rng);
      y[l] = i < 3 ? specials[(i * W + l) % 9]
                   : std::ldexp(1.5 + 0.25 * std::fabs(u(rng)) / 800, ex(rng));
    }
    const V ex_v = splat::simd::exp(x);
    const V lg_v = splat::simd::log(y);
    for (int l = 0; l < W; ++l) {
      const double e = splat::simd::exp(x[l]), g = splat::simd::log(y[l]);
      // Same bits (NaN compared as NaN).
      EXPECT_TRUE((std::isnan(e) && std::isnan(ex_v[l])) || e == ex_v[l]) << x[l];
      EXPECT_TRUE((std::isnan(g) && std::isnan(lg_v[l])) || g == lg_v[l]) << y[l];
    }
  }
}

TEST(simd_math, vector_lanes_equal_scalar) {
  expect_lanes_equal_scalar<v4d>();
  expect_lanes_equal_scalar<v8d>();
}

}  // namespace
