// Stick or rebound: the verdict of a particle impact and the adaptive end
// time that stops a run once the verdict is decided and settled.
//
// Quantities (n = +z, the substrate normal pointing away from it):
//   v_n      normal velocity of the particle's centre of mass relative to the
//            substrate's, positive away from the substrate (m/s)
//   K_rel    kinetic energy of the particle's motion relative to the
//            substrate's centre of mass, 1/2 M |v_p - v_s|^2 (J)
//   K_0      K_rel at impact
// Decided and settled (checked at every history row):
//   rebound  no active link, no pair carrying a force, and v_n > 0, all held
//            for `hold_time`: nothing can pull the particle back;
//   stick    at least one active link and v_n <= 0.02 |v_impact| (not
//            leaving), no link lost, bonded area steady (within 1 %) for
//            `hold_time`, and K_rel <= settle_fraction K_0: the particle is
//            held and its motion has died down.
// At the maximum time without a settled verdict: stick if links are active
// and v_n <= 0.02 |v_impact| (still held, not flying off), otherwise rebound;
// the reason then says the state was not settled.
#pragma once

#include <optional>
#include <string>

namespace splat {

struct ImpactSample {
  double time = 0.0;         // s
  double v_normal = 0.0;     // v_n, m/s
  double kinetic_rel = 0.0;  // K_rel, J
  long long links_active = 0;
  long long pairs_in_contact = 0;  // pairs carrying a compressive force
  double bonded_area = 0.0;        // m^2
};

struct VerdictSettings {
  double settle_fraction = 0.01;  // K_rel / K_0 below which a held particle is settled, -
  double hold_time = 0.0;         // s, how long a verdict must hold before the run stops
  double impact_speed = 0.0;      // |v_impact|, m/s
};

enum class ImpactVerdict { stick, rebound };

struct VerdictDecision {
  ImpactVerdict verdict = ImpactVerdict::rebound;
  bool settled = false;  // false: forced at the maximum time
  std::string reason;
};

// Follows the samples of one run; decide() says when the verdict is settled.
class ImpactMonitor {
 public:
  explicit ImpactMonitor(VerdictSettings settings) : settings_(settings) {}

  // Feeds one sample; returns the decision once one is settled.
  std::optional<VerdictDecision> update(const ImpactSample& s);
  // The verdict at the end of a run that was not settled (maximum time).
  VerdictDecision at_end(const ImpactSample& s) const;

 private:
  VerdictSettings settings_;
  double kinetic_0_ = -1.0;
  // Start of the current candidate window, or < 0 when none.
  double rebound_since_ = -1.0;
  double stick_since_ = -1.0;
  long long stick_links_ = 0;
  double stick_area_ = 0.0;
};

}  // namespace splat
