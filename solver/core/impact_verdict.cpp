#include "solver/core/impact_verdict.hpp"

#include <cmath>
#include <cstdio>

namespace splat {
namespace {

constexpr double k_area_steadiness = 0.01;  // relative bonded-area change allowed, -

std::string format(const char* fmt, double a, double b, double c = 0.0) {
  char buf[240];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

}  // namespace

const char* to_string(ImpactVerdict v) {
  switch (v) {
    case ImpactVerdict::stick:
      return "stick";
    case ImpactVerdict::rebound:
      return "rebound";
    case ImpactVerdict::undecided:
      return "undecided";
  }
  return "undecided";
}

bool ImpactMonitor::tearing(const ImpactSample& s) {
  if (s.links_active == 0) {
    linked_ = false;
    return false;
  }
  // d is measured from the mean height of the active links: a change of
  // that set moves it without any motion, so the watch restarts.
  if (!linked_ || s.links_active != offset_links_ || s.bond_offset < min_offset_) {
    min_offset_ = s.bond_offset;
  }
  offset_links_ = s.links_active;
  linked_ = true;
  return s.bond_offset - min_offset_ > k_tear_fraction * settings_.radius;
}

bool ImpactMonitor::too_weak_to_stop(const ImpactSample& s) const {
  // Uncapped links stop the particle within any opening.
  return s.links_active > 0 && !std::isinf(s.bond_force) &&
         s.kinetic_leaving > s.bond_force * k_tear_fraction * settings_.radius;
}

bool ImpactMonitor::held(const ImpactSample& s) {
  const bool torn = tearing(s);
  return s.links_active > 0 && s.kinetic_leaving <= s.bond_energy && !too_weak_to_stop(s) && !torn;
}

std::optional<VerdictDecision> ImpactMonitor::update(const ImpactSample& s) {
  if (kinetic_0_ < 0.0) kinetic_0_ = s.kinetic_rel;
  if (s.v_normal > 0.0 && !sprung_back_) {
    sprung_back_ = true;
    stick_stopped_ = false;  // it must stop again, now against its bond
  }

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

  const bool holding = held(s);
  const bool steady = holding && s.links_active >= stick_links_ &&
                      std::abs(s.bonded_area - stick_area_) <= k_area_steadiness * stick_area_ &&
                      s.bond_damage - stick_damage_ <= k_damage_steadiness;
  if (!holding || !steady || stick_since_ < 0.0) {
    stick_since_ = holding ? s.time : -1.0;
    stick_links_ = s.links_active;
    stick_area_ = s.bonded_area;
    stick_damage_ = s.bond_damage;
    stick_stopped_ = false;
  }
  // A held particle stops receding within the window (it rings about its
  // bonded position); one still receding is loading a bond that may yet
  // break. One that never receded has not yet sprung back: the elastic
  // energy of the impact has not loaded its bond.
  if (holding && s.v_normal <= 0.0) stick_stopped_ = true;
  const bool calm = s.kinetic_rel <= settings_.settle_fraction * kinetic_0_;
  if (holding && stick_since_ >= 0.0 && calm && stick_stopped_ && sprung_back_ &&
      s.time - stick_since_ >= settings_.hold_time) {
    return VerdictDecision{
        ImpactVerdict::stick, true,
        format("stick: active links steady since t = %.4g s, the relative kinetic energy down "
               "to %.3g of its initial value and the bond's remaining energy %.3g J above the "
               "separating kinetic energy",
               stick_since_, kinetic_0_ > 0.0 ? s.kinetic_rel / kinetic_0_ : 0.0,
               s.bond_energy - s.kinetic_leaving)};
  }
  return std::nullopt;
}

VerdictDecision ImpactMonitor::at_end(const ImpactSample& s) {
  if (tearing(s)) {
    return {ImpactVerdict::undecided, false,
            format("undecided at the maximum time: the particle's centre moved %.3g m (%.3g R) "
                   "away from its %.0f bonded nodes; the particle is tearing off its bond",
                   s.bond_offset - min_offset_, (s.bond_offset - min_offset_) / settings_.radius,
                   static_cast<double>(s.links_active))};
  }
  const bool calm = s.kinetic_rel <= settings_.settle_fraction * kinetic_0_;
  if (s.v_normal < 0.0 && !calm) {
    return {ImpactVerdict::undecided, false,
            format("undecided at the maximum time: the particle still moves into the substrate "
                   "at %.4g m/s (%.4g m/s across it), with %.0f links active",
                   -s.v_normal, s.v_tangential, static_cast<double>(s.links_active))};
  }
  if (held(s)) {
    return {ImpactVerdict::stick, false,
            format("stick (not settled at the maximum time): %.0f links active hold %.3g J "
                   "against a separating kinetic energy of %.3g J",
                   static_cast<double>(s.links_active), s.bond_energy, s.kinetic_leaving)};
  }
  if (s.links_active == 0 && s.v_normal > 0.0) {
    return {ImpactVerdict::rebound, false,
            format("rebound (not settled at the maximum time): no active link, particle moving "
                   "at %.4g m/s away from the substrate",
                   s.v_normal, 0.0)};
  }
  if (too_weak_to_stop(s) && s.v_normal > 0.0) {
    return {ImpactVerdict::rebound, false,
            format("rebound (not settled at the maximum time): the particle leaves at %.4g m/s; "
                   "its active links carry %.3g N in all and would stop it only after %.3g m "
                   "of opening",
                   s.v_normal, s.bond_force, s.kinetic_leaving / s.bond_force)};
  }
  if (s.links_active > 0) {
    return {ImpactVerdict::undecided, false,
            format("undecided at the maximum time: %.0f links active hold %.3g J but the "
                   "particle carries %.3g J of separating kinetic energy (sliding or leaving)",
                   static_cast<double>(s.links_active), s.bond_energy, s.kinetic_leaving)};
  }
  return {ImpactVerdict::undecided, false,
          format("undecided at the maximum time: no active link and the particle at rest "
                 "against the substrate (%.4g m/s along the normal, %.4g m/s across it)",
                 s.v_normal, s.v_tangential)};
}

}  // namespace splat
