// The nonlocal interface average (solver/adhesion/interface_average.hpp)
// against closed forms of the hat-weighted mean: a band of softened material
// of fixed physical width converges to its exact average as the sampling is
// refined, a spike one sample wide fades as h / l, and a linear field is
// reproduced exactly away from the ends. The single-sample reading the
// activation used before (the peak) would give the band's own value at every
// resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/adhesion/interface_average.hpp"

namespace splat {
namespace {

// Samples at the midpoints of n cells of size h along x on [0, n h], each of
// area h (a strip of unit width), with yield ratio `field(x)`.
template <class Field>
std::vector<InterfaceSample> line(int n, double h, Field field) {
  std::vector<InterfaceSample> s(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * h;
    s[i].x = Vec3(x, 0.0, 0.0);
    s[i].area = h;
    s[i].slave.yield_ratio = field(x);
    s[i].master.damage = 1.0 - field(x);
  }
  return s;
}

// Hat-weighted mean of a band |x - x0| < b / 2 where the ratio is 1 - drop,
// 1 elsewhere, at x0: 1 - drop (b - b^2 / (4 l)) / l (the hat integrates to l).
double band_average_exact(double drop, double b, double l) {
  return 1.0 - drop * (b - b * b / (4.0 * l)) / l;
}

TEST(InterfaceAverage, band_of_fixed_width_converges_to_its_hat_mean) {
  const double l = 2.0e-6, b = 0.4 * l, x0 = 10.0e-6, drop = 0.5;
  const double exact = band_average_exact(drop, b, l);  // 0.82
  double previous_error = 1.0;
  for (const int per_l : {10, 20, 40, 80}) {
    const double h = l / per_l;
    const int n = static_cast<int>(std::lround(2.0 * x0 / h));
    const auto s =
        line(n, h, [&](double x) { return std::abs(x - x0) < 0.5 * b ? 1.0 - drop : 1.0; });
    const auto avg = average_interface(s, l);
    const std::size_t mid = static_cast<std::size_t>(n / 2);  // the sample at x0 + h / 2
    const double error = std::abs(avg[mid].slave.yield_ratio - exact);
    EXPECT_LT(error, previous_error + 1e-12) << "h = l / " << per_l;
    EXPECT_NEAR(avg[mid].master.damage, 1.0 - avg[mid].slave.yield_ratio, 1e-12);
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.01 * drop);
}

TEST(InterfaceAverage, one_sample_spike_fades_with_the_sample_size) {
  const double l = 2.0e-6;
  double previous = 0.0;
  for (const int per_l : {2, 4, 8, 16}) {
    const double h = l / per_l;
    const int n = 8 * per_l + 1;
    const int spike = n / 2;
    std::vector<InterfaceSample> s = line(n, h, [](double) { return 1.0; });
    s[spike].slave.yield_ratio = 0.0;
    const double r = average_interface(s, l)[spike].slave.yield_ratio;
    // The spike's weight h over the hat's discrete integral, about l: the
    // drop seen is about h / l.
    EXPECT_NEAR(1.0 - r, h / l, 0.25 * h / l) << "h = l / " << per_l;
    EXPECT_GT(r, previous);
    previous = r;
  }
}

TEST(InterfaceAverage, linear_field_is_kept_inside_and_own_state_without_a_length) {
  const double h = 0.25e-6, l = 1.0e-6;
  const auto s = line(40, h, [](double x) { return 1.0 - 0.3 * x / 10.0e-6; });
  const auto avg = average_interface(s, l);
  for (std::size_t i = 5; i + 5 < s.size(); ++i) {
    EXPECT_NEAR(avg[i].slave.yield_ratio, s[i].slave.yield_ratio, 1e-12);
  }
  // Near an end the hat is cut: the mean leans inwards (towards lower
  // ratios here).
  EXPECT_LT(avg[0].slave.yield_ratio, s[0].slave.yield_ratio);
  const auto own = average_interface(s, 0.0);
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(own[i].slave.yield_ratio, s[i].slave.yield_ratio);
  }
}

}  // namespace
}  // namespace splat
