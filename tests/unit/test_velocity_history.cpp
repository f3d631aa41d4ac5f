// The tabulated velocity of a boundary condition
// (solver/scene/velocity_history.hpp): values at and between the points, the
// holds outside, and the displacement against a numerical quadrature of the
// values (composite Boole rule, exact for polynomials up to degree 5, so for
// the smooth step's quintic, when the points are among its nodes).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/scene/velocity_history.hpp"

namespace splat {
namespace {

VelocityHistory ramp(HistoryInterpolation kind) {
  VelocityHistory h;
  h.time = {0.5, 1.5, 3.0};
  h.velocity = {Vec3(1.0, 0.0, -2.0), Vec3(3.0, 0.0, 4.0), Vec3(3.0, 1.0, 4.0)};
  h.interpolation = kind;
  return h;
}

// Boole's rule over [0, t] on steps of 1/600 (t a multiple of it), the
// points among the nodes.
Vec3 boole(const VelocityHistory& h, double t) {
  const int n = 4 * static_cast<int>(std::lround(150.0 * t));
  const double dt = t / n;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < n; k += 4) {
    const auto v = [&](int j) { return history_velocity(h, (k + j) * dt); };
    sum += 7.0 * v(0) + 32.0 * v(1) + 12.0 * v(2) + 32.0 * v(3) + 7.0 * v(4);
  }
  return sum * 2.0 * dt / 45.0;
}

TEST(velocity_history, linear_values_and_holds) {
  const VelocityHistory h = ramp(HistoryInterpolation::linear);
  EXPECT_EQ(history_velocity(h, 0.0), Vec3(1.0, 0.0, -2.0));  // before the first point
  EXPECT_EQ(history_velocity(h, 0.5), Vec3(1.0, 0.0, -2.0));
  EXPECT_TRUE(history_velocity(h, 1.0).isApprox(Vec3(2.0, 0.0, 1.0), 1e-15));
  EXPECT_TRUE(history_velocity(h, 2.25).isApprox(Vec3(3.0, 0.5, 4.0), 1e-15));
  EXPECT_EQ(history_velocity(h, 10.0), Vec3(3.0, 1.0, 4.0));  // after the last point
}

TEST(velocity_history, smooth_step_has_zero_slope_at_the_points) {
  const VelocityHistory h = ramp(HistoryInterpolation::smooth_step);
  // Half-way the smooth step is half-way; a quarter in, 0.103515625 of the jump.
  EXPECT_TRUE(history_velocity(h, 1.0).isApprox(Vec3(2.0, 0.0, 1.0), 1e-15));
  EXPECT_NEAR(history_velocity(h, 0.75).x(), 1.0 + 2.0 * 0.103515625, 1e-15);
  const double e = 1e-6;
  for (const double t : {0.5, 1.5}) {
    const Vec3 slope_after = (history_velocity(h, t + e) - history_velocity(h, t)) / e;
    EXPECT_LT(slope_after.norm(), 1e-9) << t;
  }
}

TEST(velocity_history, displacement_is_the_integral_of_the_velocity) {
  for (const HistoryInterpolation kind :
       {HistoryInterpolation::linear, HistoryInterpolation::smooth_step}) {
    const VelocityHistory h = ramp(kind);
    EXPECT_EQ(history_displacement(h, 0.0), Vec3::Zero());
    for (const double t : {0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.5}) {
      const Vec3 d = history_displacement(h, t);
      const Vec3 q = boole(h, t);
      EXPECT_LT((d - q).norm(), 1e-12 * (1.0 + q.norm())) << t;
    }
    // Whole segments: the smooth step moves as far as the linear ramp.
    EXPECT_TRUE(history_displacement(h, 1.5).isApprox(Vec3(0.5 + 2.0, 0.0, -1.0 + 1.0), 1e-14));
  }
}

TEST(velocity_history, mean_velocity_over_a_step) {
  const VelocityHistory h = ramp(HistoryInterpolation::smooth_step);
  const double t = 0.9, dt = 0.2;
  const Vec3 mean = history_mean_velocity(h, t, dt);
  EXPECT_TRUE(
      (history_displacement(h, t) + dt * mean).isApprox(history_displacement(h, t + dt), 1e-14));
  EXPECT_EQ(history_mean_velocity(h, t, 0.0), history_velocity(h, t));
}

}  // namespace
}  // namespace splat
