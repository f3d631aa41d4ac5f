#include "solver/core/impact_verdict.hpp"

#include <cmath>
#include <cstdio>

namespace splat {
namespace {

constexpr double k_area_steadiness = 0.01;  // relative bonded-area change allowed, -
// v_n / v_impact above which a particle counts as leaving even with links
// active (a link with a tiny sigma_c stays active over an opening of
// G_c / sigma_c while the particle flies off), -
constexpr double k_held_speed = 0.02;

std::string format(const char* fmt, double a, double b) {
  char buf[200];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

}  // namespace

std::optional<VerdictDecision> ImpactMonitor::update(const ImpactSample& s) {
  if (kinetic_0_ < 0.0) kinetic_0_ = s.kinetic_rel;

  const bool rebounding = s.links_active == 0 && s.pairs_in_contact == 0 && s.v_normal > 0.0;
  if (!rebounding) {
    rebound_since_ = -1.0;
  } else if (rebound_since_ < 0.0) {
    rebound_since_ = s.time;
  }
  if (rebounding && s.time - rebound_since_ >= settings_.hold_time) {
    return VerdictDecision{
        ImpactVerdict::rebound, true,
        format("rebound: no active link and no contact force since t = %.4g s; the particle "
               "leaves at %.4g m/s",
               rebound_since_, s.v_normal)};
  }

  const bool holding = s.links_active > 0 && s.v_normal <= k_held_speed * settings_.impact_speed;
  const bool steady = holding && s.links_active >= stick_links_ &&
                      std::abs(s.bonded_area - stick_area_) <= k_area_steadiness * stick_area_;
  if (!holding || !steady || stick_since_ < 0.0) {
    stick_since_ = holding ? s.time : -1.0;
    stick_links_ = s.links_active;
    stick_area_ = s.bonded_area;
  }
  const bool calm = s.kinetic_rel <= settings_.settle_fraction * kinetic_0_;
  if (holding && stick_since_ >= 0.0 && calm && s.time - stick_since_ >= settings_.hold_time) {
    return VerdictDecision{
        ImpactVerdict::stick, true,
        format("stick: active links steady since t = %.4g s and the relative kinetic energy "
               "down to %.3g of its initial value",
               stick_since_, kinetic_0_ > 0.0 ? s.kinetic_rel / kinetic_0_ : 0.0)};
  }
  return std::nullopt;
}

VerdictDecision ImpactMonitor::at_end(const ImpactSample& s) const {
  const bool held = s.links_active > 0 && s.v_normal <= k_held_speed * settings_.impact_speed;
  if (held) {
    return {ImpactVerdict::stick, false,
            format("stick (not settled at the maximum time): links active, particle moving at "
                   "%.4g m/s relative to the substrate, relative kinetic energy %.3g of initial",
                   s.v_normal, kinetic_0_ > 0.0 ? s.kinetic_rel / kinetic_0_ : 0.0)};
  }
  return {ImpactVerdict::rebound, false,
          format("rebound (not settled at the maximum time): particle moving at %.4g m/s away "
                 "from the substrate with %.0f active links",
                 s.v_normal, static_cast<double>(s.links_active))};
}

}  // namespace splat
