#include "solver/scene/velocity_history.hpp"

#include <algorithm>
#include <cstddef>

namespace splat {
namespace {

// The shape of a segment at xi in [0, 1] and its integral from 0 to xi.
double shape(HistoryInterpolation kind, double xi) {
  if (kind == HistoryInterpolation::linear) return xi;
  return xi * xi * xi * (10.0 + xi * (-15.0 + 6.0 * xi));
}
double shape_integral(HistoryInterpolation kind, double xi) {
  if (kind == HistoryInterpolation::linear) return 0.5 * xi * xi;
  const double xi2 = xi * xi;
  return xi2 * xi2 * (2.5 + xi * (-3.0 + xi));
}

}  // namespace

Vec3 history_velocity(const VelocityHistory& h, double t) {
  const std::size_t n = h.time.size();
  if (n == 0) return Vec3::Zero();
  if (t <= h.time.front()) return h.velocity.front();
  if (t >= h.time.back()) return h.velocity.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(h.time.begin(), h.time.end(), t) -
                                                 h.time.begin() - 1);
  const double xi = (t - h.time[k]) / (h.time[k + 1] - h.time[k]);
  return h.velocity[k] + shape(h.interpolation, xi) * (h.velocity[k + 1] - h.velocity[k]);
}

Vec3 history_displacement(const VelocityHistory& h, double t) {
  const std::size_t n = h.time.size();
  if (n == 0 || t <= 0.0) return Vec3::Zero();
  // Before the first point: the first velocity, from 0 to min(t, t_0).
  Vec3 d = std::clamp(h.time.front(), 0.0, t) * h.velocity.front();
  for (std::size_t k = 0; k + 1 < n && h.time[k] < t; ++k) {
    const double span = h.time[k + 1] - h.time[k];
    const double xi = std::min((t - h.time[k]) / span, 1.0);  // the part of the segment in [0, t]
    d += span * (xi * h.velocity[k] +
                 shape_integral(h.interpolation, xi) * (h.velocity[k + 1] - h.velocity[k]));
  }
  // After the last point: the last velocity.
  if (t > h.time.back()) d += (t - h.time.back()) * h.velocity.back();
  return d;
}

Vec3 history_mean_velocity(const VelocityHistory& h, double t, double dt) {
  if (!(dt > 0.0)) return history_velocity(h, t);
  return (history_displacement(h, t + dt) - history_displacement(h, t)) / dt;
}

}  // namespace splat
