// Richardson extrapolation of a quantity computed at three resolutions with
// a constant refinement ratio r (h1 = r h2 = r^2 h3, f3 the finest):
//   observed order  p  = ln((f1 - f2) / (f2 - f3)) / ln r
//   estimate        f* = f3 + (f3 - f2) / (r^p - 1)
// (Roache 1998, "Verification and Validation in Computational Science and
// Engineering", ch. 5). Defined only when the differences have the same sign
// and shrink fast enough, p >= k_min_observed_order, and r > 1; otherwise
// empty. A sequence whose differences grow diverges: no limit to extrapolate
// to. One whose differences barely shrink is not yet in its asymptotic range
// and the estimate would multiply the last move by 1 / (r^p - 1), more than
// 2.4 at r = 2 below p = 0.5 (FE Al/Al critical velocities 884, 828, 775
// m/s at 8, 16, 32 elements across, p = 0.08, extrapolate to -155 m/s).
#pragma once

#include <cmath>
#include <optional>

namespace splat {

// Smallest observed order from which a sequence is extrapolated, -.
inline constexpr double k_min_observed_order = 0.5;

struct RichardsonEstimate {
  double order = 0.0;     // observed order p, -
  double estimate = 0.0;  // extrapolated value f*, unit of f
};

inline std::optional<RichardsonEstimate> richardson(double f1, double f2, double f3, double r) {
  const double d12 = f1 - f2, d23 = f2 - f3;
  if (!(r > 1.0) || !(d12 * d23 > 0.0) || !std::isfinite(d12 / d23)) return std::nullopt;
  const double p = std::log(d12 / d23) / std::log(r);
  const double denominator = std::pow(r, p) - 1.0;
  if (!(p >= k_min_observed_order) || !(std::abs(denominator) > 0.0) || !std::isfinite(p)) {
    return std::nullopt;
  }
  return RichardsonEstimate{p, f3 + (f3 - f2) / denominator};
}

}  // namespace splat
