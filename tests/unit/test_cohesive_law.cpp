// The cohesive law of one pair (solver/adhesion/cohesive_law.hpp): every
// link-state transition on a two-pair toy, the activation and erosion tests,
// and the energy bookkeeping of one step against the kinetic energy of two
// point masses computed independently.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solver/adhesion/cohesive_law.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update.hpp"

namespace splat {
namespace {

// A side whose rate-free yield stress is sigma of a peak `peak` (Pa).
InterfaceSideState yielded(double sigma, double peak) {
  InterfaceSideState s;
  s.yield_ratio = sigma / peak;
  return s;
}

AdhesionParams yield_drop_params(double drop, ActivationSides sides) {
  AdhesionParams p;
  p.G_c = 0.2;
  p.activation = ActivationRule::yield_drop;
  p.yield_drop = drop;
  p.sides = sides;
  p.D_adh_max = 0.5;
  return p;
}

// Two point masses on a line, the pair normal along +x from 1 to 2: the
// separation rate is v2 - v1; a tension impulse I lowers it (v1 += I/m1,
// v2 -= I/m2). Kinetic energy computed from the velocities, not from dW.
struct TwoMasses {
  double m1, m2, v1, v2;
  double rate() const { return v2 - v1; }
  double h() const { return 1.0 / m1 + 1.0 / m2; }
  double kinetic() const { return 0.5 * m1 * v1 * v1 + 0.5 * m2 * v2 * v2; }
  void apply_tension(double I) {
    v1 += I / m1;
    v2 -= I / m2;
  }
  // Nothing else acts in the step: the rate at its start is the free rate.
  LinkKinematics free_flight(double compliance = 0.0) const {
    return {rate(), rate(), h(), compliance};
  }
};

TEST(cohesive_law, activation_either_and_both_sides) {
  const InterfaceSideState dropped = yielded(69.0e6, 100.0e6);  // 31 % below its peak
  const InterfaceSideState steady = yielded(95.0e6, 100.0e6);   // 5 % below
  AdhesionParams either = yield_drop_params(0.30, ActivationSides::either);
  AdhesionParams both = yield_drop_params(0.30, ActivationSides::both);
  EXPECT_TRUE(activation_met(either, dropped, steady));
  EXPECT_TRUE(activation_met(either, steady, dropped));
  EXPECT_FALSE(activation_met(either, steady, steady));
  EXPECT_FALSE(activation_met(both, dropped, steady));
  EXPECT_FALSE(activation_met(both, steady, dropped));
  EXPECT_TRUE(activation_met(both, dropped, dropped));
  // The threshold itself counts as a drop: sigma_y <= (1 - x) peak.
  EXPECT_TRUE(side_activated(either, yielded(70.0e6, 100.0e6)));
  EXPECT_FALSE(side_activated(either, yielded(70.1e6, 100.0e6)));
  // A rigid side never drops: `either` rests on the other side, `both` never holds.
  EXPECT_TRUE(activation_met(either, InterfaceSideState{}, dropped));
  EXPECT_FALSE(activation_met(both, InterfaceSideState{}, dropped));
  // Rule none: always met, whatever the yield stresses.
  AdhesionParams none;
  EXPECT_TRUE(activation_met(none, steady, steady));
}

// The sides rule for a side state `met` that meets p's activation rule and
// one, `unmet`, that does not: either side suffices with `either`, both are
// needed with `both`.
void expect_sides_rule(AdhesionParams p, const InterfaceSideState& met,
                       const InterfaceSideState& unmet) {
  p.sides = ActivationSides::either;
  EXPECT_FALSE(activation_met(p, unmet, unmet));
  EXPECT_TRUE(activation_met(p, met, unmet));
  EXPECT_TRUE(activation_met(p, unmet, met));
  p.sides = ActivationSides::both;
  EXPECT_FALSE(activation_met(p, met, unmet));
  EXPECT_FALSE(activation_met(p, unmet, met));
  EXPECT_TRUE(activation_met(p, met, met));
}

TEST(cohesive_law, activation_on_the_interface_temperature) {
  AdhesionParams p;
  p.activation = ActivationRule::temperature;
  p.homologous_temperature = 0.6;
  InterfaceSideState cool, hot;
  cool.homologous_temperature = 0.59;
  hot.homologous_temperature = 0.6;  // the threshold itself activates
  expect_sides_rule(p, hot, cool);
  p.sides = ActivationSides::both;
  // A side without material never heats; a softened but cool side does not
  // activate on temperature.
  EXPECT_FALSE(activation_met(p, InterfaceSideState{}, hot));
  p.sides = ActivationSides::either;
  EXPECT_FALSE(activation_met(p, yielded(10e6, 100e6), cool));
}

TEST(cohesive_law, activation_on_the_surface_expansion) {
  AdhesionParams p;
  p.activation = ActivationRule::surface_expansion;
  p.surface_expansion = 0.3;
  InterfaceSideState film, cracked, hot;
  film.surface_expansion = 0.29;
  cracked.surface_expansion = 0.3;  // the threshold itself activates
  hot.homologous_temperature = 0.99;
  hot.yield_ratio = 0.1;
  // With `both`, each side's film must crack: one grown surface is not enough.
  expect_sides_rule(p, cracked, film);
  // Heat and softening do not crack a film that has not grown.
  p.sides = ActivationSides::either;
  EXPECT_FALSE(activation_met(p, hot, film));
}

// Bay's film theory (1983): the metal exposed through the cracked films,
// and with it the bond, rises linearly from none at the threshold Y' to the
// whole area at Y = 1; each side's own film must crack with `both`.
TEST(cohesive_law, bonded_fraction_of_the_cracked_films) {
  AdhesionParams p;
  p.activation = ActivationRule::surface_expansion;
  p.surface_expansion = 0.3;
  InterfaceSideState a, b;
  a.surface_expansion = 0.65;
  b.surface_expansion = 0.475;
  EXPECT_EQ(bonded_fraction(p, a, b), 1.0);  // full: the whole area bonds
  p.bonded_fraction = BondedFraction::film_cracks;
  p.sides = ActivationSides::both;
  EXPECT_NEAR(bonded_fraction(p, a, b), 0.25, 1e-12);  // (0.475 - 0.3) / 0.7
  p.sides = ActivationSides::either;
  EXPECT_NEAR(bonded_fraction(p, a, b), 0.5, 1e-12);  // (0.65 - 0.3) / 0.7
  b.surface_expansion = 0.0;
  a.surface_expansion = 0.2;
  EXPECT_EQ(bonded_fraction(p, a, b), 0.0);  // below the threshold: no bond
  a.surface_expansion = 1.0;
  EXPECT_EQ(bonded_fraction(p, a, b), 1.0);
  p.activation = ActivationRule::temperature;  // a rule without films
  EXPECT_EQ(bonded_fraction(p, b, b), 1.0);
}

TEST(cohesive_law, erosion_on_either_side_only_with_a_limit) {
  AdhesionParams p;
  EXPECT_FALSE(erosion_met(p, 1.0, 1.0));  // no D_adh_max: never
  p.D_adh_max = 0.5;
  EXPECT_FALSE(erosion_met(p, 0.49, 0.0));
  EXPECT_TRUE(erosion_met(p, 0.5, 0.0));
  EXPECT_TRUE(erosion_met(p, 0.0, 0.7));
}

// The rate-free yield stress is what activation must watch: a point that
// hardens at a high rate and then unloads keeps its static peak, while the
// rate-dependent sigma_y falls back by the rate factor. Checked on the
// material point update that fills PointState.
TEST(cohesive_law, static_peak_does_not_see_the_rate_factor) {
  Material m;
  m.strength = JohnsonCookParams{.A = 90e6,
                                 .B = 292e6,
                                 .n = 0.31,
                                 .C = 0.025,
                                 .eps_dot_0 = 1.0,
                                 .m = 1.09,
                                 .T_ref = 300.0,
                                 .T_melt = 1356.0};
  m.elastic.E = 124e9, m.elastic.nu = 0.34, m.density = 8960.0;
  m.thermal.c_p = 385.0;
  ModelSwitches sw;
  sw.damage = false;
  sw.thermal_softening = false;
  sw.adiabatic_heating = false;
  const MaterialConstants mc = derive_constants(m);
  PointState st = initial_point_state(m, sw, 300.0, 0.0);
  Mat3 d = Mat3::Zero();
  d(0, 1) = d(1, 0) = 1e-3;  // shear at 1e7 /s with dt = 1e-10 s
  for (int i = 0; i < 20; ++i) update_point(m, mc, sw, st, d, 1.0, 1e-10, 1e-3);
  ASSERT_GT(st.sigma_y_peak, 1.3 * st.sigma_y_static);  // rate factor ~ 1.4
  update_point(m, mc, sw, st, -d, 1.0, 1e-10, 1e-3);    // elastic unloading
  const AdhesionParams p = yield_drop_params(0.2, ActivationSides::either);
  EXPECT_DOUBLE_EQ(st.sigma_y_static_peak, st.sigma_y_static);  // hardening only, no drop
  EXPECT_FALSE(side_activated(p, yielded(st.sigma_y_static, st.sigma_y_static_peak)));
  // The rate-dependent peak would have faked a > 20 % drop.
  EXPECT_TRUE(side_activated(p, yielded(st.sigma_y_static, st.sigma_y_peak)));
}

// Two pairs through every transition. Pair A (yield-drop, either side):
// none -> contact -> active (after separating, on a later drop) -> exhausted.
// Pair B: none -> contact -> active -> eroded. Pair C (rule none): active on
// first touch. Pair D: damaged before it activates: contact -> eroded.
TEST(cohesive_law, link_state_transitions_on_a_two_pair_toy) {
  const AdhesionParams p = yield_drop_params(0.3, ActivationSides::either);
  const double area = 1.0;  // m^2: budget 0.2 J
  struct Pair {
    LinkState state = LinkState::none;
    double work = 0.0;
  };
  Pair a, b;
  const InterfaceSideState fresh = yielded(100e6, 100e6), soft = yielded(60e6, 100e6);

  // Step 1: neither touches.
  a.state = next_link_state(a.state, p.activation, {false, false, false, false});
  b.state = next_link_state(b.state, p.activation, {false, false, false, false});
  EXPECT_EQ(a.state, LinkState::none);
  EXPECT_EQ(b.state, LinkState::none);
  // An untouched pair ignores activation and damage.
  EXPECT_EQ(next_link_state(LinkState::none, p.activation, {false, true, true, false}),
            LinkState::none);

  // Step 2: both touch, nothing has softened yet.
  a.state = next_link_state(a.state, p.activation,
                            {true, activation_met(p, fresh, fresh), erosion_met(p, 0, 0), false});
  b.state = next_link_state(b.state, p.activation,
                            {true, activation_met(p, fresh, fresh), erosion_met(p, 0, 0), false});
  EXPECT_EQ(a.state, LinkState::contact);
  EXPECT_EQ(b.state, LinkState::contact);

  // Step 3: A has separated (not touching) when its side softens: it still
  // activates ("while in contact or later"). B softens while touching.
  a.state = next_link_state(a.state, p.activation,
                            {false, activation_met(p, soft, fresh), erosion_met(p, 0, 0), false});
  b.state = next_link_state(b.state, p.activation,
                            {true, activation_met(p, fresh, soft), erosion_met(p, 0, 0), false});
  EXPECT_EQ(a.state, LinkState::active);
  EXPECT_EQ(b.state, LinkState::active);

  // Step 4: A opens fast enough to spend its budget in one step (relative
  // kinetic energy 0.5 * 2/3 * 1^2 = 1/3 J > 0.2 J); B opens slowly.
  TwoMasses ma{1.0, 2.0, -1.0 / 3.0, 2.0 / 3.0};
  const CohesiveStep sa = cohesive_step(p, area, a.work, ma.free_flight(), 1e-3);
  a.work += sa.work;
  a.state = next_link_state(a.state, p.activation, {false, true, false, sa.exhausted});
  EXPECT_TRUE(sa.exhausted);
  EXPECT_EQ(a.state, LinkState::exhausted);
  EXPECT_DOUBLE_EQ(a.work, 0.2);
  TwoMasses mb{1.0, 2.0, 0.0, 0.01};
  const CohesiveStep sb = cohesive_step(p, area, b.work, mb.free_flight(), 1e-3);
  b.work += sb.work;
  b.state = next_link_state(b.state, p.activation, {true, true, false, sb.exhausted});
  EXPECT_FALSE(sb.exhausted);
  EXPECT_EQ(b.state, LinkState::active);

  // Step 5: damage on B's second side reaches D_adh_max.
  b.state = next_link_state(b.state, p.activation, {true, true, erosion_met(p, 0.1, 0.5), false});
  EXPECT_EQ(b.state, LinkState::eroded);

  // Final states stay final whatever happens next.
  for (LinkState s : {LinkState::exhausted, LinkState::eroded}) {
    EXPECT_EQ(next_link_state(s, p.activation, {true, true, false, false}), s);
    EXPECT_EQ(next_link_state(s, p.activation, {true, true, true, true}), s);
  }
  // Erosion wins over exhaustion in the same step.
  EXPECT_EQ(next_link_state(LinkState::active, p.activation, {true, true, true, true}),
            LinkState::eroded);
  // Rule none: active on first touch; activation flag irrelevant.
  EXPECT_EQ(next_link_state(LinkState::none, ActivationRule::none, {true, false, false, false}),
            LinkState::active);
  // Damaged before activation: the pair can no longer bond.
  EXPECT_EQ(next_link_state(LinkState::contact, p.activation, {true, false, true, false}),
            LinkState::eroded);
  // A contact link cannot be exhausted (it carries no tension).
  EXPECT_EQ(next_link_state(LinkState::contact, p.activation, {true, false, false, true}),
            LinkState::contact);
  EXPECT_STREQ(to_string(LinkState::exhausted), "exhausted");
}

TEST(cohesive_law, tension_cap) {
  AdhesionParams p;
  EXPECT_EQ(max_tension(p, 2.0), std::numeric_limits<double>::infinity());
  p.sigma_c = 3.0e6;
  EXPECT_DOUBLE_EQ(max_tension(p, 2.0e-12), 6.0e-6);
}

// Griffith form (no cap): the impulse holds the pair, the work is the whole
// relative kinetic energy, and the kinetic energy lost equals dW exactly.
TEST(cohesive_law, griffith_step_holds_the_pair_and_charges_the_kinetic_energy) {
  AdhesionParams p;
  p.G_c = 10.0;
  TwoMasses m{1.5, 0.5, -0.2, 0.7};
  const double K0 = m.kinetic();
  const CohesiveStep s = cohesive_step(p, 1.0, 0.0, m.free_flight(), 1e-3);
  m.apply_tension(s.impulse);
  EXPECT_FALSE(s.exhausted);
  EXPECT_NEAR(m.rate(), 0.0, 1e-15);
  const double mu = 1.5 * 0.5 / 2.0;
  EXPECT_NEAR(s.work, 0.5 * mu * 0.9 * 0.9, 1e-15);
  EXPECT_NEAR(K0 - m.kinetic(), s.work, 1e-15);
}

// With a cap, the impulse is sigma_c A dt and the kinetic energy lost is dW,
// for any dt (one step, no approximation in time).
TEST(cohesive_law, capped_step_work_equals_kinetic_energy_lost) {
  AdhesionParams p;
  p.G_c = 10.0;
  p.sigma_c = 40.0;
  const double area = 0.25;  // cap 10 N
  for (double dt : {1e-4, 1e-2, 0.05}) {
    TwoMasses m{1.0, 3.0, 0.1, 0.9};
    const double K0 = m.kinetic();
    const CohesiveStep s = cohesive_step(p, area, 0.0, m.free_flight(), dt);
    m.apply_tension(s.impulse);
    EXPECT_DOUBLE_EQ(s.impulse, 10.0 * dt);
    EXPECT_GT(m.rate(), 0.0);
    EXPECT_NEAR(K0 - m.kinetic(), s.work, 1e-15 * K0) << dt;
    EXPECT_GT(s.work, 0.0);
  }
  // Above the holding impulse the cap does not bind: the pair is held, not pulled back.
  TwoMasses m{1.0, 3.0, 0.1, 0.1001};
  const CohesiveStep s = cohesive_step(p, area, 0.0, m.free_flight(), 0.05);
  m.apply_tension(s.impulse);
  EXPECT_NEAR(m.rate(), 0.0, 1e-15);
  // The solver may ask for less than the hold; never for more, never negative.
  EXPECT_DOUBLE_EQ(cohesive_step(p, area, 0.0, {0.8, 0.8, 4.0 / 3.0, 0.0}, 0.05, 0.1).impulse, 0.1);
  EXPECT_DOUBLE_EQ(cohesive_step(p, area, 0.0, {0.8, 0.8, 4.0 / 3.0, 0.0}, 0.05, -1.0).impulse,
                   0.0);
}

// The step that spends the budget: work exactly W_rem, kinetic energy lost
// exactly W_rem, and the impulse smaller than the one asked for.
TEST(cohesive_law, exhausting_step_spends_exactly_the_remaining_budget) {
  for (bool capped : {false, true}) {
    AdhesionParams p;
    p.G_c = 0.2;
    if (capped) p.sigma_c = 5.0;
    const double area = 1.0, dt = 0.1, W = 0.15;  // W_rem = 0.05 J
    TwoMasses m{1.0, 2.0, -1.0 / 3.0, 2.0 / 3.0};
    const double K0 = m.kinetic();
    const CohesiveStep s = cohesive_step(p, area, W, m.free_flight(), dt);
    m.apply_tension(s.impulse);
    EXPECT_TRUE(s.exhausted) << capped;
    EXPECT_DOUBLE_EQ(s.work, 0.05);
    EXPECT_NEAR(K0 - m.kinetic(), 0.05, 1e-15) << capped;
    EXPECT_LT(s.impulse, capped ? 5.0 * dt : 1.0 / m.h());
    EXPECT_GT(m.rate(), 0.0);
  }
  // G_c = 0: the first opening step exhausts the link with no impulse.
  AdhesionParams p0;
  const CohesiveStep s0 = cohesive_step(p0, 1.0, 0.0, {1.0, 1.0, 1.5, 0.0}, 1e-3);
  EXPECT_TRUE(s0.exhausted);
  EXPECT_EQ(s0.impulse, 0.0);
  EXPECT_EQ(s0.work, 0.0);
}

TEST(cohesive_law, closing_pairs_carry_no_tension) {
  AdhesionParams p;
  p.G_c = 1.0;
  for (double g : {-1.0, 0.0}) {
    const CohesiveStep s = cohesive_step(p, 1.0, 0.0, {g, g, 1.5, 0.0}, 1e-3);
    EXPECT_EQ(s.impulse, 0.0);
    EXPECT_EQ(s.work, 0.0);
    EXPECT_FALSE(s.exhausted);
  }
  EXPECT_EQ(cohesive_step(p, 1.0, 0.0, {1.0, 1.0, 0.0, 0.0}, 1e-3).impulse, 0.0);  // immovable pair
}

// Many capped steps: the work sums to the budget and never beyond, and the
// kinetic energy lost matches the work summed step by step.
TEST(cohesive_law, work_never_exceeds_the_budget) {
  AdhesionParams p;
  p.G_c = 0.2;
  p.sigma_c = 0.5;
  TwoMasses m{1.0, 2.0, -1.0 / 3.0, 2.0 / 3.0};
  const double K0 = m.kinetic();
  double W = 0.0;
  bool exhausted = false;
  int steps = 0;
  while (!exhausted && steps < 100000) {
    const CohesiveStep s = cohesive_step(p, 1.0, W, m.free_flight(), 1e-3);
    m.apply_tension(s.impulse);
    W += s.work;
    exhausted = s.exhausted;
    ++steps;
    ASSERT_LE(W, 0.2);
  }
  EXPECT_TRUE(exhausted);
  EXPECT_DOUBLE_EQ(W, 0.2);
  EXPECT_NEAR(K0 - m.kinetic(), W, 1e-13);
}

// A steady pull held by an uncapped link: two masses, a force f(t) = f_dot t
// pulls mass 2 away; the link holds the pair (rate 0 before and after every
// step), so its work is exactly zero for any dt, and it lets go when the
// energy its force stores in the compliance c, c F^2 / 2, reaches G_c A:
// at F_break = sqrt(2 G_c A / c), whatever the step. (The previous rule
// charged the kinetic energy of each step's virtual opening, h (F dt)^2 / 2,
// so the link broke later and later as dt shrank.)
TEST(cohesive_law, steady_pull_breaks_at_the_griffith_force_for_any_dt) {
  AdhesionParams p;
  p.G_c = 0.5;
  const double area = 2.0, c = 1e-3, f_dot = 1e4;            // m^2, m/N, N/s
  const double F_break = std::sqrt(2.0 * p.G_c * area / c);  // 44.72 N
  for (double dt : {1e-4, 1e-5, 1e-6}) {
    TwoMasses m{1.0, 2.0, 0.0, 0.0};
    double W = 0.0, t = 0.0, F_last = 0.0;
    bool exhausted = false;
    while (!exhausted && t < 1.0) {
      const double g_prev = m.rate();
      t += dt;
      m.v2 += dt * f_dot * t / m.m2;  // the pull, before the link
      const CohesiveStep s = cohesive_step(p, area, W, {g_prev, m.rate(), m.h(), c}, dt);
      m.apply_tension(s.impulse);
      if (!s.exhausted) {
        EXPECT_LE(s.work, 1e-12 * p.G_c * area) << dt;
      }
      W += s.work;
      exhausted = s.exhausted;
      F_last = s.impulse / dt;
    }
    ASSERT_TRUE(exhausted) << dt;
    EXPECT_DOUBLE_EQ(W, p.G_c * area);
    // The link force tracks m1's share of the pull, f t m1 / (m1 + m2); it
    // breaks within one step's load increment of F_break.
    EXPECT_NEAR(F_last, F_break, 1e-9 * F_break + f_dot * dt) << dt;
    EXPECT_NEAR(t * f_dot / 3.0, F_break, 2.0 * f_dot * dt) << dt;
  }
}

// The work charged is the exact work of the link force in the leapfrog
// update, whatever else acts in the step: with an external force on mass 2,
// kinetic energy change = external work + link work, each force's work being
// F dt (v_before + v_after) / 2 (1/2 m (v+^2 - v-^2) = m (v+ - v-)(v+ + v-) / 2).
TEST(cohesive_law, capped_work_is_the_exact_discrete_work) {
  AdhesionParams p;
  p.G_c = 100.0;
  p.sigma_c = 2.0;
  const double area = 1.0, dt = 0.05, f = 30.0;  // cap 2 N, pull 30 N
  TwoMasses m{1.0, 2.0, -0.1, 0.4};
  for (int step = 0; step < 20; ++step) {
    const double K0 = m.kinetic();
    const double v2_before = m.v2, g_prev = m.rate();
    m.v2 += dt * f / m.m2;
    const CohesiveStep s = cohesive_step(p, area, 0.0, {g_prev, m.rate(), m.h(), 0.0}, dt);
    m.apply_tension(s.impulse);
    ASSERT_DOUBLE_EQ(s.impulse, 2.0 * dt);  // the cap binds: the pair opens
    const double W_ext = f * dt * 0.5 * (v2_before + m.v2);
    EXPECT_NEAR(m.kinetic() - K0, W_ext - s.work, 1e-12 * m.kinetic()) << step;
    EXPECT_NEAR(s.work, 2.0 * dt * 0.5 * (g_prev + m.rate()), 1e-15) << step;
  }
}

}  // namespace
}  // namespace splat

namespace splat {
namespace {

// Dugdale-Barenblatt process zone, l = (pi/8) E' G_c / sigma_c^2 (Rice 1968):
// aluminium on aluminium (E 70 GPa, nu 0.3: E' = 76.92 GPa), G_c 30 J/m^2,
// sigma_c 100 MPa: l = 0.3927 x 76.92e9 x 30 / 1e16 = 90.6 um, larger than a
// 12.5 um particle (the whole bond is in its process zone). Copper on
// aluminium (E 124 GPa, nu 0.34) takes the harmonic mean of the two plane-strain
// moduli, either way round; without a cap there is no zone.
TEST(cohesive_law, cohesive_zone_length_of_the_dugdale_law) {
  AdhesionParams p;
  p.G_c = 30.0;
  p.sigma_c = 100e6;
  EXPECT_NEAR(cohesive_zone_length(p, 70e9, 0.3, 70e9, 0.3), 9.062e-5, 0.001e-5);
  const double E_al = 70e9 / (1.0 - 0.09), E_cu = 124e9 / (1.0 - 0.34 * 0.34);
  const double mixed = 0.125 * 3.141592653589793 * (2.0 / (1.0 / E_al + 1.0 / E_cu)) * 30.0 / 1e16;
  EXPECT_NEAR(cohesive_zone_length(p, 70e9, 0.3, 124e9, 0.34), mixed, 1e-12 * mixed);
  EXPECT_DOUBLE_EQ(cohesive_zone_length(p, 124e9, 0.34, 70e9, 0.3),
                   cohesive_zone_length(p, 70e9, 0.3, 124e9, 0.34));
  p.sigma_c.reset();
  EXPECT_EQ(cohesive_zone_length(p, 70e9, 0.3, 70e9, 0.3), 0.0);
}

}  // namespace
}  // namespace splat
