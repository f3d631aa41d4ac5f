// The cohesive adhesion law of one contact pair (thesis 1.4.4 and 2.2):
// energy exhaustion (Griffith, G_c per bonded area), optional tensile stress
// cap (Dugdale-Barenblatt, sigma_c), activation on a yield-stress drop, and
// erosion on damage. Pointwise: every function here acts on ONE pair; the
// loop over pairs and the Lagrange-multiplier solve live in the contact stage.
//
// Sign conventions. n is the pair normal; the separation rate g_dot >= 0
// means the pair opens (the thesis's (V1 - V2).n12 with the opposite sign).
// A link impulse I = lambda dt >= 0 is TENSION: it pulls the two sides
// together, i.e. it lowers g_dot.
//
// Life of a link (next_link_state):
//
//   none --touch--> contact --activation--> active --work = G_c A--> exhausted
//                      |                       |
//                      +------- damage --------+-----> eroded
//
// exhausted and eroded are final. With ActivationRule::none the link is
// active on first touch (none -> active in one step). Activation may come
// while in contact or later (the pair need not touch at that step), as in
// thesis 2.2.2. A pair whose side reaches D_adh_max before it activated can no
// longer bond (contact -> eroded): damaged material is a third body.
//
// Work against separation, per step (cohesive_step). Let
//   g_free  the separation rate the pair would have at the end of the step
//           without this link's impulse (m/s),
//   h       the pair's effective inverse mass along n, h = H_ii = C_i M^-1 C_i^T
//           (1/kg; for two point masses h = 1/m_1 + 1/m_2),
//   I       the link impulse, 0 <= I <= I_hold = g_free / h (I_hold stops the
//           opening exactly; more would pull the pair together),
//   g_after = g_free - h I.
// The discrete work done against the separation is
//   dW = I (g_free + g_after) / 2 = I g_free - h I^2 / 2          (J)
// which is exactly the relative kinetic energy the impulse removes,
// (g_free^2 - g_after^2) / (2 h): for one pair the energy bookkeeping is exact
// for any dt, and dW >= 0 on the allowed range of I. The accumulated work W
// never exceeds the budget G_c A: if dW would pass the remaining budget
// W_rem = G_c A - W, the impulse is reduced to the root of
//   I g_free - h I^2 / 2 = W_rem,  I = 2 W_rem / (g_free + sqrt(g_free^2 - 2 h W_rem)),
// (the smaller root; it exists because dW(I) < dW(I_hold) = g_free^2 / (2h)),
// the work of the step is exactly W_rem, and the link is exhausted.
// The tension cap limits I <= sigma_c A dt. Without a cap (Griffith form)
// the multiplier itself holds the pair: I = I_hold.
//
// Griffith form under smooth loading: a holding impulse that only cancels
// the opening one step of smooth forces would produce is charged
// dW = g_free^2 / (2h) = O(dt^2) per step, so a held link under a steady pull
// spends its budget at a rate O(dt) that vanishes as dt -> 0 (a rigid holding
// constraint does no work). In the limit the uncapped link dissipates only on
// velocity jumps (impacts); the two-mass model shows it (k > 0, no cap:
// the answer is the free-mass one).
//
// Several pairs (the contact solver): H couples the pairs, so "g_free" of one
// pair depends on the impulses of its neighbours. The contact stage uses the
// diagonal (projected Gauss-Seidel) approximation: for pair i, g_free is the
// rate with every other pair's current impulse applied and h = H_ii; the sum
// of the pairs' dW is then the kinetic energy removed only up to the
// off-diagonal terms of H (exact when no two links share a node).
//
// Deviations from the thesis:
//  - eq. 1.19 takes the work of a step as dt lambda g_dot(n+1), the rate after
//    the force; a link that holds the pair (g_after = 0) would then do no work
//    at all, and a velocity jump would never be charged to the budget. The
//    trapezoid above charges exactly the kinetic energy taken out.
//  - eq. 1.21 uses the velocity at n+3/2 for unilateral contact; that is a
//    contact (not a cohesive) choice and is left to the contact stage.
//  - With a cap, eq. 1.28 (G_c = sigma_c gap_c) is the continuous limit of
//    this rule for a constant force: W = sigma_c A * (opening).
//  - Activation compares the rate-free static yield stress with the largest
//    static yield stress seen (PointState::sigma_y_static and
//    sigma_y_static_peak). PointState::sigma_y_peak tracks the RATE-DEPENDENT
//    sigma_y and must not be used: the rate factor falls as soon as a point
//    unloads, which would read as a yield drop and fake an instability.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

namespace splat {

enum class ActivationRule { none, yield_drop };
enum class ActivationSides { either, both };

struct AdhesionParams {
  double G_c = 0.0;               // J/m^2, adhesion energy per bonded area
  std::optional<double> sigma_c;  // Pa, tensile stress cap; empty = no cap (Griffith form:
                                  // the multiplier itself holds the pair)
  ActivationRule activation = ActivationRule::none;
  double yield_drop = 0.0;  // fraction in [0,1): activation when sigma_y <= (1-x)*peak
  ActivationSides sides = ActivationSides::either;
  std::optional<double> D_adh_max;  // damage at which a link erodes; empty = never
};

enum class LinkState : std::uint8_t { none, contact, active, exhausted, eroded };

const char* to_string(LinkState s);

// The yield stresses of one side of a pair, as the activation test needs them.
struct SideYield {
  double sigma_y_static = 0.0;       // Pa, current rate-free yield stress
  double sigma_y_static_peak = 0.0;  // Pa, largest sigma_y_static seen at that point
};

// One side has dropped: sigma_y_static <= (1 - yield_drop) sigma_y_static_peak.
inline bool side_yield_dropped(const AdhesionParams& p, const SideYield& s) {
  return s.sigma_y_static <= (1.0 - p.yield_drop) * s.sigma_y_static_peak;
}

// A side without material (a rigid body): its yield stress never drops
// (for yield_drop > 0), so `both` can never activate against it.
inline constexpr SideYield rigid_side{1.0, 1.0};

// Activation test of thesis 2.2.2 for a pair with sides a and b: always true
// for ActivationRule::none; for yield_drop, the drop on either side or on both
// (ActivationSides).
inline bool activation_met(const AdhesionParams& p, const SideYield& a, const SideYield& b) {
  if (p.activation == ActivationRule::none) return true;
  const bool da = side_yield_dropped(p, a);
  const bool db = side_yield_dropped(p, b);
  return p.sides == ActivationSides::both ? (da && db) : (da || db);
}

// Erosion test of thesis 2.2.3: damage on either side >= D_adh_max.
inline bool erosion_met(const AdhesionParams& p, double D_a, double D_b) {
  return p.D_adh_max && (D_a >= *p.D_adh_max || D_b >= *p.D_adh_max);
}

// What happened to one pair in one step.
struct LinkEvents {
  bool touching = false;        // the pair is in contact (gap closed) this step
  bool activation_met = false;  // activation_met(...) this step (ignored for rule none)
  bool erosion_met = false;     // erosion_met(...) this step
  bool budget_spent = false;    // cohesive_step(...).exhausted this step
};

// The state after one step, applying in order: first touch (none -> contact),
// activation (contact -> active; on first touch already with rule none),
// erosion (contact or active -> eroded), exhaustion (active -> exhausted).
// Final states never change. Typical use in the contact stage:
//   s = next_link_state(s, rule, {touching, act, ero, false});
//   if (s == LinkState::active) { step = cohesive_step(...);
//     s = next_link_state(s, rule, {touching, act, ero, step.exhausted}); }
inline LinkState next_link_state(LinkState s, ActivationRule rule, const LinkEvents& e) {
  if (s == LinkState::exhausted || s == LinkState::eroded) return s;
  if (s == LinkState::none && e.touching) s = LinkState::contact;
  if (s == LinkState::contact && (rule == ActivationRule::none || e.activation_met)) {
    s = LinkState::active;
  }
  if (s != LinkState::none && e.erosion_met) return LinkState::eroded;
  if (s == LinkState::active && e.budget_spent) return LinkState::exhausted;
  return s;
}

// Largest tension a bonded pair of adhesive area `area` (m^2) may carry:
// sigma_c * area (N), or +infinity without a cap.
inline double max_tension(const AdhesionParams& p, double area) {
  return p.sigma_c ? *p.sigma_c * area : std::numeric_limits<double>::infinity();
}

// Work budget of a link: G_c * area (J).
inline double work_budget(const AdhesionParams& p, double area) {
  return p.G_c * area;
}

// Result of one step of an active link.
struct CohesiveStep {
  double impulse = 0.0;    // I = lambda dt >= 0, tension impulse to apply (N s)
  double work = 0.0;       // dW >= 0 done against the separation this step (J)
  bool exhausted = false;  // W + dW reached G_c A this step: the link breaks
};

// One step of an active link (see the header comment for the definitions):
//   area       adhesive area of the pair, m^2
//   work_done  W, work already done against separation by this link, J
//   g_free     separation rate without this link's impulse, m/s (> 0: opening)
//   h          effective inverse mass along the normal, 1/kg (> 0)
//   dt         time step, s
//   wanted     the tension impulse the solver asks for, N s; default: hold
//              (I_hold = g_free / h). Clamped to [0, min(I_hold, sigma_c A dt)].
// A closing or resting pair (g_free <= 0) or h <= 0 gets no tension and no work.
CohesiveStep cohesive_step(const AdhesionParams& p, double area, double work_done, double g_free,
                           double h, double dt,
                           double wanted = std::numeric_limits<double>::infinity());

}  // namespace splat
