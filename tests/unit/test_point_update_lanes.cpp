// update_points (groups of 8 points in SIMD lanes through point_update_fast,
// the rest through update_point) against update_point called point by point:
// the same bits in every field of every point, for elastic steps, steps that
// continue plastic flow, the onset of yield, tension, both EOS, every model
// switch, and damage. And point_update_fast itself: it must cover most steps
// of continued plastic flow (else the lanes would buy nothing), and where it
// covers one, give what the general path gives to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "solver/material/point_update.hpp"
#include "solver/material/point_update_fast.hpp"
#include "tests/support/isa.hpp"
#include "tests/support/materials.hpp"

namespace splat {
namespace {

constexpr double dt = 2e-9;  // s

Material copper_mg() {
  Material m = test_support::jc_copper();
  m.eos.model = EosModel::mie_gruneisen;
  m.eos.mie_gruneisen = MieGruneisenParams{3940.0, 1.49, 2.02};
  return m;
}

Material copper_damage() {
  Material m = test_support::jc_copper();
  m.damage.initiation = DamageInitiation::johnson_cook;
  m.damage.jc = {0.54, 4.89, -3.03, 0.014, 1.12};
  m.damage.evolution = DamageEvolution::plastic_strain;
  m.damage.eps_p_max = 0.5;
  return m;
}

// A symmetric strain increment: uniaxial compression at `rate` plus a random
// part of relative size `noise`.
Mat3 strain_increment(std::mt19937_64& rng, double rate, double noise) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat3 d = Mat3::Zero();
  d(0, 0) = -rate * dt;
  d(1, 1) = d(2, 2) = 0.3 * rate * dt;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      d(i, j) += noise * rate * dt * u(rng);
      d(j, i) = d(i, j);
    }
  return d;
}

bool same_bits(const PointState& a, const PointState& b) {
  static constexpr double PointState::*fields[] = {&PointState::p,
                                                   &PointState::J,
                                                   &PointState::e,
                                                   &PointState::eps_p,
                                                   &PointState::eps_dot_p,
                                                   &PointState::T,
                                                   &PointState::D,
                                                   &PointState::omega,
                                                   &PointState::eps_p_init,
                                                   &PointState::sigma_y,
                                                   &PointState::sigma_y_static,
                                                   &PointState::hardening,
                                                   &PointState::strength_scale,
                                                   &PointState::sigma_y_peak,
                                                   &PointState::plastic_work,
                                                   &PointState::sigma_y_static_peak};
  bool same = std::memcmp(a.s.data(), b.s.data(), sizeof(double) * 9) == 0;
  for (auto field : fields)
    same = same && std::memcmp(&(a.*field), &(b.*field), sizeof(double)) == 0;
  return same;
}

// n points, each with its own loading history (rates from elastic to far
// past yield, some reversed), advanced `steps` steps both ways.
void expect_active_lanes_match_points(const Material& m, const ModelSwitches& sw, int steps,
                                      unsigned seed) {
  const MaterialConstants mc = derive_constants(m);
  constexpr int n = 61;  // 7 whole groups of 8 and a remainder of 5
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PointState> a(n, initial_point_state(m, sw, 300.0, 0.0));
  std::vector<double> rate(n);
  std::vector<int> index(n);
  for (int k = 0; k < n; ++k) {
    rate[k] = std::pow(10.0, 2.0 + 6.0 * u(rng)) * (u(rng) < 0.2 ? -1.0 : 1.0);  // 1/s
    index[k] = (k * 17) % n;  // not in storage order
  }
  std::vector<PointState> b = a;
  std::vector<Mat3> d_eps(n);
  std::vector<double> J_new(n), length(n, 1e-5);
  std::vector<PointUpdateResult> out(n);
  for (int step = 0; step < steps; ++step) {
    for (int k = 0; k < n; ++k) {
      const int i = index[k];
      // Reverse the load of some points now and then (unloading, reloading).
      const double r = (step / 50) % 3 == 2 && i % 2 == 0 ? -rate[i] : rate[i];
      d_eps[k] = strain_increment(rng, r, 0.2);
      J_new[k] = a[i].J * std::exp(d_eps[k].trace());
    }
    update_points(m, mc, sw, a.data(), index.data(), n, d_eps.data(), J_new.data(), dt,
                  length.data(), out.data());
    for (int k = 0; k < n; ++k) {
      const int i = index[k];
      const PointUpdateResult r = update_point(m, mc, sw, b[i], d_eps[k], J_new[k], dt, length[k]);
      ASSERT_TRUE(same_bits(a[i], b[i])) << "point " << i << " step " << step;
      ASSERT_EQ(out[k].iterations, r.iterations);
      ASSERT_EQ(out[k].converged, r.converged);
    }
  }
}

// The above for the lane loops of every instruction set this CPU supports.
void expect_lanes_match_points(const Material& m, const ModelSwitches& sw, int steps,
                               unsigned seed) {
  test_support::for_each_isa([&] { expect_active_lanes_match_points(m, sw, steps, seed); });
}

TEST(point_update_lanes, match_update_point_linear_eos) {
  expect_lanes_match_points(test_support::jc_copper(), test_support::no_damage(), 400, 1);
}

TEST(point_update_lanes, match_update_point_mie_gruneisen) {
  expect_lanes_match_points(copper_mg(), test_support::no_damage(), 400, 2);
}

TEST(point_update_lanes, match_update_point_with_each_switch_off) {
  for (int off = 0; off < 3; ++off) {
    ModelSwitches sw = test_support::no_damage();
    if (off == 0) sw.thermal_softening = false;
    if (off == 1) sw.rate_hardening = false;
    if (off == 2) sw.adiabatic_heating = false;
    SCOPED_TRACE(off);
    expect_lanes_match_points(copper_mg(), sw, 200, 3 + unsigned(off));
  }
}

TEST(point_update_lanes, match_update_point_with_damage) {
  expect_lanes_match_points(copper_damage(), ModelSwitches{}, 400, 7);
}

// A law the lanes do not accelerate (Zerilli-Armstrong): every point takes
// the general path, with the same bits as update_point.
TEST(point_update_lanes, match_update_point_for_a_law_without_lanes) {
  Material m = test_support::jc_copper();
  m.strength = ZerilliArmstrongParams{.C0 = 46.5e6,
                                      .C2 = 890e6,
                                      .C3 = 0.0028,
                                      .C4 = 0.000115,
                                      .eps_dot_0 = 1.0,
                                      .T_ref = 300.0,
                                      .T_melt = 1356.0};
  expect_lanes_match_points(m, test_support::no_damage(), 400, 11);
}

// Plastic flow at 1e5 /s whose increments vary from step to step by
// `noise` (relative): the fast path's cover of the plastic steps after the
// onset, and the steps it ended in its second evaluation. Where it covers a
// step, its result must equal the general path's (the same point advanced by
// johnson_cook_return with its full iteration) within the return's
// tolerance, 1e-11 of the trial stress.
struct Coverage {
  int plastic_steps = 0, covered = 0, second = 0;
};

Coverage fast_path_coverage(double noise) {
  const Material m = copper_mg();
  const ModelSwitches sw = test_support::no_damage();
  const MaterialConstants mc = derive_constants(m);
  PointState st = initial_point_state(m, sw, 300.0, 0.0);
  std::mt19937_64 rng(11);
  Coverage c;
  for (int step = 0; step < 2000; ++step) {
    const Mat3 d = strain_increment(rng, 1e5, noise);
    const double J_new = st.J * std::exp(d.trace());
    PointFields<double> f;
    for (int k = 0; k < 6; ++k) f.s[k] = st.s(sym_row[k], sym_col[k]);
    for_each_point_field(f, [&](double& v, double PointState::*field) { v = st.*field; });
    double de[6];
    for (int k = 0; k < 6; ++k) de[k] = d(sym_row[k], sym_col[k]);
    double evaluations = 0.0;
    const bool done = point_update_fast(m, mc, sw, f, de, J_new, dt, evaluations);
    // The general path, started from the return's linearised guess instead
    // of the previous increment (no series, no cached rate factor).
    PointState general = st;
    general.eps_dot_p = 0.0;
    const PointUpdateResult rg = update_point_general(m, mc, sw, general, d, J_new, dt, 1e-5);
    const double eps_p_old = st.eps_p;
    update_point(m, mc, sw, st, d, J_new, dt, 1e-5);
    if (rg.iterations == 0) continue;
    ++c.plastic_steps;
    if (!done) continue;
    ++c.covered;
    if (evaluations == 2.0) ++c.second;
    // Both returns end with |g| <= 1e-11 q_trial and g' <= -3G, so their
    // increments differ by at most 2e-11 q_trial / 3G, and the deviators by
    // at most 2e-11 of the trial deviator.
    const double three_g = 3.0 * mc.G;
    const double dp = general.eps_p - eps_p_old;
    const double q_trial = std::sqrt(1.5 * general.s.squaredNorm()) + three_g * dp;
    EXPECT_NEAR(f.eps_p, general.eps_p, 2e-11 * q_trial / three_g) << step;
    EXPECT_NEAR(f.s[0], general.s(0, 0), 2e-11 * q_trial) << step;
    EXPECT_NEAR(f.temp, general.T, 1e-12 * general.T) << step;
    EXPECT_NEAR(f.sigma_y, general.sigma_y, 1e-11 * general.sigma_y) << step;
  }
  std::printf("noise %g: fast path covered %d of %d plastic steps, %d in its second evaluation\n",
              noise, c.covered, c.plastic_steps, c.second);
  return c;
}

// Steady flow (increments that vary by 0.05 %): nearly every step ends in the
// first evaluation.
TEST(point_update_lanes, fast_path_covers_continued_plastic_flow) {
  const Coverage c = fast_path_coverage(0.0005);
  EXPECT_GT(c.plastic_steps, 1900);
  EXPECT_GT(c.covered, c.plastic_steps * 9 / 10);
}

// Increments that vary by a few per cent per step, as in an impact: the rate
// term's Taylor bound fails after the first evaluation, and the second
// evaluation ends most steps.
TEST(point_update_lanes, fast_path_second_evaluation_covers_varying_flow) {
  const Coverage c = fast_path_coverage(0.02);
  EXPECT_GT(c.plastic_steps, 1900);
  EXPECT_GT(c.covered, c.plastic_steps * 9 / 10);
  EXPECT_GT(c.second, c.plastic_steps / 2);
}

}  // namespace
}  // namespace splat
