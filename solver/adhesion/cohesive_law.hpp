// The cohesive adhesion law of one contact pair (thesis 1.4.4 and 2.2):
// energy exhaustion (Griffith, G_c per bonded area), optional tensile stress
// cap (Dugdale-Barenblatt, sigma_c, or the flow stress of the weaker side),
// activation on a yield-stress drop or on the interface temperature, and
// erosion on damage. Pointwise: every
// function here acts on ONE pair; the loop over pairs and the
// Lagrange-multiplier solve live in the contact stage, which feeds the
// activation and erosion tests and the flow-stress cap with the interface
// state of the material within AdhesionParams::averaging_length of the
// contact point (interface_average.hpp), not with the state of one element.
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
//   g_prev  the pair's separation rate at the start of the step (m/s),
//   g_free  the rate it would have at the end of the step without this
//           link's impulse (m/s),
//   h       the pair's effective inverse mass along n, h = H_ii = C_i M^-1 C_i^T
//           (1/kg; for two point masses h = 1/m_1 + 1/m_2),
//   I       the link impulse, 0 <= I <= I_hold = g_free / h (I_hold stops the
//           opening exactly; more would pull the pair together),
//   g_after = g_free - h I, the rate at the end of the step.
// The work the link force does on the opening during the step is, exactly
// for the central-difference (leapfrog) update that moves the rate from
// g_prev to g_after,
//   dW = I (g_prev + g_after) / 2                                  (J)
// (for one mass, 1/2 m (v+^2 - v-^2) = F dt (v- + v+) / 2), clamped at 0 for
// the budget. A link that holds its pair (g_prev = g_after = 0) does no work,
// whatever the step, so the budget no longer depends on dt under smooth
// loading (the thesis's eq. 1.19); a link that catches a pair arriving with
// g_prev > 0 is charged the kinetic energy it takes out (g_prev^2 / (2h) when
// nothing else acts, which gives the two-mass closed form for any dt); a
// capped link that opens at sigma_c is charged sigma_c A times the opening
// (Dugdale-Barenblatt, eq. 1.28 in the continuous limit).
//
// Energy stored by the link force (Griffith form). A rigid link can hold any
// force without doing work, so the work alone would let an uncapped link hold
// for ever under a steady pull. The link force F = I / dt also strains the
// material on both sides; releasing the link would give back
//   U = c F^2 / 2,  c = compliance of the two sides along n (m/N),
// the virtual-crack-closure estimate of the energy a debond of this link's
// area releases (c = h_e / (M A) per side for an element of thickness h_e
// and P-wave modulus M = K + 4G/3 under the area A). The link breaks when
//   W + dW + U >= G_c A,
// i.e. when the work done on it plus what its release would set free covers
// the budget. Both terms are state functions of the motion, so the verdict
// converges as dt -> 0. Like the thesis's per-link budget (G_c pi R_SPH^2)
// the criterion depends on the mesh through c and A: it is a nodal Griffith
// criterion whose flaw size is the element size. With c = 0 (rigid bodies,
// the two-mass model) only the work counts.
// When the budget is reached during a step the impulse is reduced to the
// largest I with W + dW(I) + U(I) <= G_c A (bisection), the step's charge is
// exactly the remaining budget W_rem = G_c A - W, and the link is exhausted.
// The tension cap limits I <= sigma_c A dt. Without a cap (Griffith form)
// the multiplier itself holds the pair: I = I_hold until the budget is spent.
//
// Several pairs (the contact solver): H couples the pairs, so "g_free" of one
// pair depends on the impulses of its neighbours. The contact stage uses the
// diagonal (projected Gauss-Seidel) approximation: for pair i, g_free is the
// rate with every other pair's current impulse applied and h = H_ii.
//
// Deviations from the thesis:
//  - eq. 1.19 takes the work of a step as dt lambda g_dot(n+1), the rate after
//    the force only; a velocity jump stopped in one step would then never be
//    charged. The average of the rates before and after is the exact discrete
//    work of the update. The stored-energy term U is ours: without it an
//    uncapped link is exhausted only by jumps (or, with eq. 1.21's n+3/2
//    rates, by a charge that shrinks with dt).
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

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>

#include "solver/adhesion/interface_average.hpp"
#include "solver/common/enum_names.hpp"

namespace splat {

// What turns a pair in contact into a bond (thesis 2.2.2; 5.3.2 names the
// temperature among the criteria worth trying): each rule is one case of
// side_activated below, reading the averaged InterfaceSideState.
// surface_expansion is the film theory of cold welding (Bay 1979, J. Eng.
// Ind. 101(2) 121-127; Bay 1983, Welding J. 62, 137s-142s): the oxide and
// contaminant film cracks once the surface has grown by a threshold, and
// metal meets metal through the cracks; each side's own film must crack.
enum class ActivationRule { none, yield_drop, temperature, surface_expansion };
inline constexpr NameTable<ActivationRule, 4> k_activation_rule_names{{
    {ActivationRule::none, "none"},
    {ActivationRule::yield_drop, "yield-drop"},
    {ActivationRule::temperature, "temperature"},
    {ActivationRule::surface_expansion, "surface-expansion"},
}};
static_assert(names_in_order(k_activation_rule_names));
constexpr const auto& names_of(ActivationRule) {
  return k_activation_rule_names;
}

// Default averaging length of the interface state, m: the order of the heat
// diffusion length sqrt(kappa t) of the interface over an impact, with the
// thermal diffusivity of aluminium and copper, kappa ~ 1e-4 m^2/s (9.7e-5 and
// 1.1e-4 m^2/s at 300 K, Incropera and DeWitt, Fundamentals of Heat and Mass
// Transfer, table A.1), and t ~ 40 ns, the jetting phase of a 10-50 um
// particle at 300-1000 m/s (contact time ~ 2 R / V). A model parameter, not a
// numerical one: the averaged state converges once the mesh resolves it.
inline constexpr double k_default_averaging_length = 2.0e-6;
enum class ActivationSides { either, both };

// How much of a link's area bonds once it is active. full: all of it.
// film-cracks (surface_expansion only): the metal exposed through the
// cracked films, Bay's fraction (Y - Y') / (1 - Y') of the area (Bay 1983,
// Welding J. 62, 137s: the bond strength of cold pressure welds rises
// linearly from 0 at the threshold Y' to the parent metal's at Y = 1),
// growing while the pair is pressed together.
enum class BondedFraction { full, film_cracks };
inline constexpr NameTable<BondedFraction, 2> k_bonded_fraction_names{{
    {BondedFraction::full, "full"},
    {BondedFraction::film_cracks, "film-cracks"},
}};
static_assert(names_in_order(k_bonded_fraction_names));
constexpr const auto& names_of(BondedFraction) {
  return k_bonded_fraction_names;
}

struct AdhesionParams {
  double G_c = 0.0;               // J/m^2, adhesion energy per bonded area
  std::optional<double> sigma_c;  // Pa, tensile stress cap; empty = no fixed cap
  // Cap each link at the current rate-free yield stress of the weaker side
  // of the interface (averaged like activation): a bond between metals
  // cannot pull harder than the metal beside it can carry. With sigma_c
  // too, the smaller cap holds. Neither: no cap (Griffith form: the
  // multiplier itself holds the pair).
  bool cap_at_flow_stress = false;
  ActivationRule activation = ActivationRule::none;
  double yield_drop = 0.0;  // fraction in [0,1): activation when sigma_y <= (1-x)*peak
  // Rule temperature: activation when T / T_melt of a side reaches this, -.
  double homologous_temperature = 1.0;
  // Rule surface_expansion: activation when Bay's surface expansion
  // Y = (A - A0) / A of a side's surface reaches this threshold Y', -.
  double surface_expansion = 1.0;
  ActivationSides sides = ActivationSides::either;
  BondedFraction bonded_fraction = BondedFraction::full;
  std::optional<double> D_adh_max;  // damage at which a link erodes; empty = never
  // Radius of the material around a contact point over which activation,
  // erosion and the flow-stress cap average each side's state
  // (interface_average.hpp), m; 0 = each node's own elements.
  double averaging_length = k_default_averaging_length;
};

enum class LinkState : std::uint8_t { none, contact, active, exhausted, eroded };

const char* to_string(LinkState s);

// One side of a pair meets the activation rule: for yield_drop its rate-free
// yield stress has fallen yield_drop below the largest value seen there
// (yield_ratio <= 1 - yield_drop); for temperature it has reached
// homologous_temperature; for surface_expansion its surface has grown to
// Bay's expansion surface_expansion. A side without material
// (InterfaceSideState{}) never meets any.
inline bool side_activated(const AdhesionParams& p, const InterfaceSideState& s) {
  switch (p.activation) {
    case ActivationRule::none:
      return true;
    case ActivationRule::yield_drop:
      return s.yield_ratio <= 1.0 - p.yield_drop;
    case ActivationRule::temperature:
      return s.homologous_temperature >= p.homologous_temperature;
    case ActivationRule::surface_expansion:
      return s.surface_expansion >= p.surface_expansion;
  }
  return false;
}

// Activation test of thesis 2.2.2 for a pair with sides a and b: always true
// for ActivationRule::none; otherwise the rule met on either side or on both
// (ActivationSides).
inline bool activation_met(const AdhesionParams& p, const InterfaceSideState& a,
                           const InterfaceSideState& b) {
  if (p.activation == ActivationRule::none) return true;
  const bool da = side_activated(p, a);
  const bool db = side_activated(p, b);
  return p.sides == ActivationSides::both ? (da && db) : (da || db);
}

// The fraction of an active link's area that bonds with sides a and b
// (BondedFraction): 1 for full or a rule other than surface_expansion; else
// (Y - Y') / (1 - Y') in [0, 1], Y the expansion of the side the rule reads
// (the smaller with both, the larger with either).
inline double bonded_fraction(const AdhesionParams& p, const InterfaceSideState& a,
                              const InterfaceSideState& b) {
  if (p.bonded_fraction == BondedFraction::full ||
      p.activation != ActivationRule::surface_expansion) {
    return 1.0;
  }
  const double y = p.sides == ActivationSides::both
                       ? std::min(a.surface_expansion, b.surface_expansion)
                       : std::max(a.surface_expansion, b.surface_expansion);
  return std::clamp((y - p.surface_expansion) / (1.0 - p.surface_expansion), 0.0, 1.0);
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

// The tensile strength of one link, Pa: the smaller of sigma_c and, with
// cap_at_flow_stress, the weaker side's flow stress `flow_stress` (Pa);
// empty when neither caps it.
inline std::optional<double> link_strength(const AdhesionParams& p, double flow_stress) {
  if (!p.cap_at_flow_stress) return p.sigma_c;
  return p.sigma_c ? std::min(*p.sigma_c, flow_stress) : flow_stress;
}

// Work budget of a link: G_c * area (J).
inline double work_budget(const AdhesionParams& p, double area) {
  return p.G_c * area;
}

// Length of the process zone of this law, a Dugdale-Barenblatt interface
// (traction sigma_c over an opening G_c / sigma_c), at the tip of a crack
// between two elastic sides (Rice 1968, Dugdale strip-yield model):
//   l_cz = (pi / 8) E' G_c / sigma_c^2,  2 / E' = 1 / E'_1 + 1 / E'_2,
//   E'_i = E_i / (1 - nu_i^2) (plane strain), m.
// An interface resolves its process zone with l_cz / h elements of size h
// (Turon et al. 2007 ask for a few). Without a cap (sigma_c absent) the links
// are rigid until their budget is spent: a zone of zero length (0 here),
// which no mesh resolves.
inline double cohesive_zone_length(const AdhesionParams& p, double E1, double nu1, double E2,
                                   double nu2) {
  if (!p.sigma_c || !(*p.sigma_c > 0.0)) return 0.0;
  const double E_plane = 2.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
  return 0.125 * 3.14159265358979323846 * E_plane * p.G_c / (*p.sigma_c * *p.sigma_c);
}

// The motion of one pair in one step, as cohesive_step needs it.
struct LinkKinematics {
  double g_prev = 0.0;      // separation rate at the start of the step, m/s
  double g_free = 0.0;      // rate at the end of the step without this link's impulse, m/s
  double h = 0.0;           // effective inverse mass along the normal, 1/kg
  double compliance = 0.0;  // c, compliance of both sides along the normal, m/N (0: rigid)
};

// Result of one step of an active link.
struct CohesiveStep {
  double impulse = 0.0;    // I = lambda dt >= 0, tension impulse to apply (N s)
  double work = 0.0;       // budget charged this step (J): dW, or W_rem when exhausted
  double stored = 0.0;     // U = c (I/dt)^2 / 2 with the impulse applied, J
  bool exhausted = false;  // W + dW + U reached G_c A this step: the link breaks
};

// One step of an active link (see the header comment for the definitions):
//   area       adhesive area of the pair, m^2
//   work_done  W, work already charged to this link's budget, J
//   k          the pair's rates, inverse mass and compliance
//   dt         time step, s
//   wanted     the tension impulse the solver asks for, N s; default: hold
//              (I_hold = g_free / h). Clamped to [0, min(I_hold, sigma_c A dt)].
// A closing or resting pair (g_free <= 0) or h <= 0 gets no tension and no work.
CohesiveStep cohesive_step(const AdhesionParams& p, double area, double work_done,
                           const LinkKinematics& k, double dt,
                           double wanted = std::numeric_limits<double>::infinity());

}  // namespace splat
