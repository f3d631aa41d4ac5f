// The nonlocal average of the material state around contact points
// (solver/adhesion/interface_average.hpp) against closed forms of the
// hat-weighted mean: a band of softened material of fixed physical width
// converges to its exact average as the sampling is refined, a spike one
// sample wide fades as h / l, a softened layer one sample thick under the
// surface fades as h / l too (the node's own elements, the fallback, would
// read the layer's value at every resolution), and a linear field is kept
// away from the ends.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/adhesion/interface_average.hpp"

namespace splat {
namespace {

// Samples at the midpoints of n cells of size h along x on [0, n h], each of
// weight h (a strip of unit section), with yield ratio `field(x)` and damage
// 1 - field(x).
template <class Field>
std::vector<MaterialSample> line(int n, double h, Field field) {
  std::vector<MaterialSample> s(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * h;
    s[i].x = Vec3(x, 0.0, 0.0);
    s[i].weight = h;
    s[i].state.yield_ratio = field(x);
    s[i].state.damage = 1.0 - field(x);
  }
  return s;
}

std::vector<InterfaceSideState> fresh(std::size_t n) {
  return std::vector<InterfaceSideState>(n);
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
    const Vec3 centre(x0 + 0.5 * h, 0.0, 0.0);
    const InterfaceSideState avg = average_around(s, {centre}, l, fresh(1))[0];
    const double error = std::abs(avg.yield_ratio - exact);
    EXPECT_LT(error, previous_error + 1e-12) << "h = l / " << per_l;
    EXPECT_NEAR(avg.damage, 1.0 - avg.yield_ratio, 1e-12);
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
    std::vector<MaterialSample> s = line(n, h, [](double) { return 1.0; });
    s[spike].state.yield_ratio = 0.0;
    const double r = average_around(s, {s[spike].x}, l, fresh(1))[0].yield_ratio;
    // The spike's weight h over the hat's discrete integral, about l: the
    // drop seen is about h / l.
    EXPECT_NEAR(1.0 - r, h / l, 0.25 * h / l) << "h = l / " << per_l;
    EXPECT_GT(r, previous);
    previous = r;
  }
}

// A half-plane z < 0 sampled on a square grid of spacing h; the first row
// under the surface (a layer one sample thick, like the adiabatic shear band
// an element wide at a contact interface) has lost half its yield stress.
// Around a surface point the hat covers a half disc of area pi l^2 / 2 with
// weight integral pi l^2 / 6; the layer's share is about 2 l h / 2 over that,
// 6 h / (pi l): the drop seen fades with h.
TEST(InterfaceAverage, softened_surface_layer_one_sample_thick_fades_with_the_sample_size) {
  const double l = 2.0e-6;
  double previous_drop = 1.0;
  for (const int per_l : {4, 8, 16, 32}) {
    const double h = l / per_l;
    std::vector<MaterialSample> s;
    const int nx = 2 * per_l + 2, nz = per_l + 2;
    for (int i = -nx; i < nx; ++i) {
      for (int j = 0; j < nz; ++j) {
        MaterialSample p;
        p.x = Vec3((i + 0.5) * h, 0.0, -(j + 0.5) * h);
        p.weight = h * h;
        p.state.yield_ratio = j == 0 ? 0.5 : 1.0;
        s.push_back(p);
      }
    }
    const std::vector<InterfaceSideState> own{{0.5, 0.0, 1e30}};  // the node's elements
    const double drop = 1.0 - average_around(s, {Vec3::Zero()}, l, own)[0].yield_ratio;
    EXPECT_NEAR(drop, 0.5 * 6.0 * h / (3.14159265358979 * l), 0.3 * 0.5 * 6.0 * h / (3.14159 * l))
        << "h = l / " << per_l;
    EXPECT_LT(drop, previous_drop);
    previous_drop = drop;
  }
  EXPECT_LT(previous_drop, 0.05);
}

TEST(InterfaceAverage, linear_field_is_kept_inside_and_fallback_without_a_length) {
  const double h = 0.25e-6, l = 1.0e-6;
  const auto s = line(40, h, [](double x) { return 1.0 - 0.3 * x / 10.0e-6; });
  std::vector<Vec3> centres;
  std::vector<InterfaceSideState> own;
  for (const MaterialSample& p : s) {
    centres.push_back(p.x);
    own.push_back(p.state);
  }
  const auto avg = average_around(s, centres, l, own);
  for (std::size_t i = 5; i + 5 < s.size(); ++i) {
    EXPECT_NEAR(avg[i].yield_ratio, s[i].state.yield_ratio, 1e-12);
  }
  // Near an end the hat is cut: the mean leans inwards (towards lower
  // ratios here).
  EXPECT_LT(avg[0].yield_ratio, s[0].state.yield_ratio);
  // No length, or no sample within it: the fallback.
  const auto none = average_around(s, centres, 0.0, own);
  const auto far = average_around(s, {Vec3(1.0, 0.0, 0.0)}, l, {InterfaceSideState{0.3, 0.2, 5.0}});
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(none[i].yield_ratio, s[i].state.yield_ratio);
  }
  EXPECT_EQ(far[0].yield_ratio, 0.3);
  EXPECT_EQ(far[0].flow_stress, 5.0);
}

}  // namespace
}  // namespace splat
