// Stick or rebound: the verdict of a particle impact and the adaptive end
// time that stops a run once the verdict is decided and settled.
//
// Quantities (n = +z, the substrate normal pointing away from it):
//   v_n      normal velocity of the particle's centre of mass relative to the
//            substrate's, positive away from the substrate (m/s)
//   v_t      tangential speed of that relative motion (m/s)
//   K_rel    kinetic energy of the particle's motion relative to the
//            substrate's centre of mass, 1/2 M |v_p - v_s|^2 (J)
//   K_sep    the part of K_rel that can load the bond: 1/2 M (max(v_n, 0)^2
//            + v_t^2) (J); motion into the substrate does not pull on it
//   E_bond   budget the active links have left, sum of G_c A - W (J)
//   F_bond   the most tension the active links can carry together, sum of
//            their strength times area (N)
//   d        height of the particle's centre of mass above the mean height of
//            its bonded nodes (m); it shrinks while the particle flattens and
//            recovers only elastically once it is held
//   K_0      K_rel at impact
// A particle is held when links are active, K_sep <= E_bond (the bond can
// take all the separating energy the particle still has, whatever the impact
// speed), K_sep <= F_bond k_tear_fraction R (pulling at most F_bond, the
// bond stops the particle before it has opened k_tear_fraction R: weak links
// with a large budget would only stop it far away) and it is not tearing off
// its bonded nodes: d has not grown by more
// than k_tear_fraction R above its smallest value since the number of active
// links last changed
// (elastic recovery is a fraction of a percent of R; a particle whose bulk
// leaves while the bonded surface stays behind grows d without bound).
// Decided and settled (checked at every history row):
//   rebound  no active link, no pair carrying a force, and v_n > 0, all held
//            for `hold_time`: nothing can pull the particle back;
//   stick    held, no link lost, bonded area steady (within 1 %) for
//            `hold_time`, the particle receded (v_n > 0) at least once
//            since the impact and stopped receding (v_n <= 0) at least once
//            in that window, and K_rel <= settle_fraction K_0: the particle
//            sprang back, is held and its motion has died down. A particle
//            at rest at the bottom of its crater has not yet given back the
//            elastic energy that loads its bond (K_sep is then zero,
//            whatever that energy).
// At the maximum time without a settled verdict: undecided while the particle
// still moves into the substrate with more than settle_fraction K_0 (the
// impact is not over); else stick if held, rebound if the particle leaves
// (v_n > 0) with no active link or with links too weak to stop it within
// k_tear_fraction R of opening, otherwise undecided: at rest without a
// bond, or links active while the particle carries more separating energy
// than they can take or tears off them. The reason says the state was not
// settled.
#pragma once

#include <optional>
#include <string>

namespace splat {

struct ImpactSample {
  double time = 0.0;             // s
  double v_normal = 0.0;         // v_n, m/s
  double v_tangential = 0.0;     // v_t, m/s
  double kinetic_rel = 0.0;      // K_rel, J
  double kinetic_leaving = 0.0;  // K_sep, J
  long long links_active = 0;
  long long pairs_in_contact = 0;  // pairs carrying a compressive force
  double bonded_area = 0.0;        // m^2
  double bond_energy = 0.0;        // E_bond, J
  double bond_offset = 0.0;        // d, m (0 without links)
  double bond_damage = 0.0;        // largest averaged damage of an active link over D_adh_max, -
  double bond_force = 0.0;         // F_bond, N (+infinity when a link is uncapped)
};

// Growth of d above its smallest value since the links formed, over R, above
// which the particle is tearing off its bond, -.
inline constexpr double k_tear_fraction = 0.05;

// Growth of the bond's damage (over D_adh_max) within the hold window above
// which the bond is still being eaten away and a stick is not settled, -.
inline constexpr double k_damage_steadiness = 0.02;

struct VerdictSettings {
  double settle_fraction = 0.01;  // K_rel / K_0 below which a held particle is settled, -
  double hold_time = 0.0;         // s, how long a verdict must hold before the run stops
  double radius = 0.0;            // R, the particle's initial radius, m
};

enum class ImpactVerdict { stick, rebound, undecided };

const char* to_string(ImpactVerdict v);

struct VerdictDecision {
  ImpactVerdict verdict = ImpactVerdict::undecided;
  bool settled = false;  // false: forced at the maximum time
  std::string reason;
};

// Follows the samples of one run; decide() says when the verdict is settled.
class ImpactMonitor {
 public:
  explicit ImpactMonitor(VerdictSettings settings) : settings_(settings) {}

  // Feeds one sample; returns the decision once one is settled (stick or
  // rebound, never undecided).
  std::optional<VerdictDecision> update(const ImpactSample& s);
  // The verdict at the end of a run that was not settled (maximum time).
  VerdictDecision at_end(const ImpactSample& s);

 private:
  // Follows d; true when the particle tears off its bond (above).
  bool tearing(const ImpactSample& s);
  // Links active whose total strength would stop the particle only beyond
  // k_tear_fraction R of opening.
  bool too_weak_to_stop(const ImpactSample& s) const;
  // Links active, the separating energy within what they can take, not tearing.
  bool held(const ImpactSample& s);

  VerdictSettings settings_;
  double kinetic_0_ = -1.0;
  // Start of the current candidate window, or < 0 when none.
  double rebound_since_ = -1.0;
  double stick_since_ = -1.0;
  long long stick_links_ = 0;
  double stick_area_ = 0.0;
  double stick_damage_ = 0.0;   // bond_damage at the start of the stick window
  bool stick_stopped_ = false;  // v_n <= 0 at a sample of the current stick window
  bool sprung_back_ = false;    // v_n > 0 at a sample: the spring-back has begun
  double min_offset_ = 0.0;     // smallest d since the set of active links last changed, m
  long long offset_links_ = 0;  // active links when min_offset_ was last reset
  bool linked_ = false;         // links were active at the last sample
};

}  // namespace splat
