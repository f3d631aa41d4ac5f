// update_points (SIMD lanes of points) against update_point (one point at a
// time): every field of every state and every result must be the same to the
// bit, over random states and the edge cases of the return mapping, both
// equations of state, damage on and off and every block size.
// The test runs the variant the CPU selects (AVX-512 on the development
// machine). To check the others by hand, build point_update_batch.cpp alone
// with -DSPLAT_BATCH_SINGLE_TARGET and -mno-avx (SSE2) or -mavx2 and link it
// before libsplat_solver.a with this test's object (done for this commit:
// both pass).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "solver/input/material_io.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update.hpp"
#include "solver/material/point_update_batch.hpp"
#include "tests/support/materials.hpp"

namespace {

using namespace splat;

constexpr int W = 8;  // lanes of update_points (point_update_batch.cpp)

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Counts the fields that differ (and reports them); 0 when bit-identical.
int compare_states(const PointState& a, const PointState& b, const std::string& where) {
  int bad = 0;
  auto check = [&](double x, double y, const char* name) {
    if (!same_bits(x, y)) {
      ++bad;
      ADD_FAILURE() << where << " " << name << ": update_point " << x << " vs update_points " << y;
    }
  };
  for (int i = 0; i < 9; ++i) check(a.s.data()[i], b.s.data()[i], "s");
  check(a.p, b.p, "p");
  check(a.J, b.J, "J");
  check(a.e, b.e, "e");
  check(a.eps_p, b.eps_p, "eps_p");
  check(a.eps_dot_p, b.eps_dot_p, "eps_dot_p");
  check(a.T, b.T, "T");
  check(a.D, b.D, "D");
  check(a.omega, b.omega, "omega");
  check(a.eps_p_init, b.eps_p_init, "eps_p_init");
  check(a.sigma_y, b.sigma_y, "sigma_y");
  check(a.sigma_y_static, b.sigma_y_static, "sigma_y_static");
  check(a.hardening, b.hardening, "hardening");
  check(a.strength_scale, b.strength_scale, "strength_scale");
  check(a.sigma_y_peak, b.sigma_y_peak, "sigma_y_peak");
  check(a.plastic_work, b.plastic_work, "plastic_work");
  check(a.sigma_y_static_peak, b.sigma_y_static_peak, "sigma_y_static_peak");
  return bad;
}

Mat3 random_strain(std::mt19937_64& rng, double magnitude) {
  std::normal_distribution<double> nd(0.0, 1.0);
  Mat3 a;
  for (int i = 0; i < 9; ++i) a.data()[i] = nd(rng);
  return magnitude * 0.5 * (a + a.transpose());
}

// A state reached by a random loading history (so the cached fields are
// consistent), then one of the edge cases.
enum class Edge { none, virgin, near_melt, molten, near_D_max, near_initiation };

PointState make_state(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                      std::mt19937_64& rng, Edge edge, double dt) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointState st = initial_point_state(m, sw, 300.0 + 200.0 * u(rng), 0.0);
  if (edge == Edge::virgin) return st;
  const int steps = static_cast<int>(6 * u(rng));
  for (int i = 0; i < steps; ++i) {
    const Mat3 d = random_strain(rng, std::pow(10.0, -5.0 + 3.0 * u(rng)));
    update_point(m, mc, sw, st, d, st.J * (1.0 + d.trace()), dt, 1e-5);
  }
  const JohnsonCookParams& jc = m.strength;
  if (edge == Edge::near_melt || edge == Edge::molten) {
    st.T = edge == Edge::molten ? jc.T_melt + 10.0 * u(rng) : jc.T_melt - 2.0 * u(rng);
    st.strength_scale = (1.0 - st.D) * jc_thermal_factor(jc, sw.thermal_softening, st.T);
    st.sigma_y_static = st.strength_scale * st.hardening;
  }
  if (edge == Edge::near_D_max && sw.damage) {
    st.D = m.damage.D_max * (1.0 - 1e-3 * u(rng));
    st.omega = 1.0;
    st.eps_p_init = st.eps_p;
    st.strength_scale = (1.0 - st.D) * jc_thermal_factor(jc, sw.thermal_softening, st.T);
    st.sigma_y_static = st.strength_scale * st.hardening;
  }
  if (edge == Edge::near_initiation && st.eps_p_init < 0.0) st.omega = 1.0 - 1e-4 * u(rng);
  return st;
}

struct Case {
  Material m;
  ModelSwitches sw;
  std::string name;
};

std::vector<Case> cases() {
  std::vector<Case> c;
  const Material cu = load_material("cu-thesis");  // JC damage initiation, plastic-strain evolution
  const Material al = load_material("al-thesis");  // shear damage initiation
  Material cu_mg = cu;
  cu_mg.eos.model = EosModel::mie_gruneisen;
  Material cu_instant = cu;
  cu_instant.damage.evolution = DamageEvolution::instant;
  Material al_energy = al;
  al_energy.damage.evolution = DamageEvolution::fracture_energy;
  al_energy.damage.G_f = 1e3;
  al_energy.eos.model = EosModel::mie_gruneisen;
  ModelSwitches all, off;
  off.damage = off.thermal_softening = off.rate_hardening = off.adiabatic_heating = false;
  ModelSwitches no_rate = all;
  no_rate.rate_hardening = false;
  c.push_back({test_support::jc_copper(), test_support::no_damage(), "copper, no damage"});
  c.push_back({cu, all, "cu-thesis, JC damage"});
  c.push_back({cu_mg, all, "cu-thesis, Mie-Grueneisen"});
  c.push_back({cu_mg, test_support::no_damage(), "cu-thesis, Mie-Grueneisen, no damage"});
  c.push_back({cu_instant, all, "cu-thesis, instant damage"});
  c.push_back({al, all, "al-thesis, shear damage"});
  c.push_back({al_energy, all, "al, fracture energy, Mie-Grueneisen"});
  c.push_back({cu, off, "cu-thesis, all switches off"});
  c.push_back({cu, no_rate, "cu-thesis, no rate term"});
  return c;
}

// Runs n points of a case through both paths; index has holes (every other
// state of a larger, shuffled array). Returns the number of differing fields.
int run_case(const Case& c, std::size_t n, std::uint64_t seed, double dt, Edge edge_every) {
  const MaterialConstants mc = derive_constants(c.m);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PointState> states(2 * n + 3);
  for (std::size_t i = 0; i < states.size(); ++i) {
    const Edge edge = (edge_every != Edge::none && i % 3 == 0) ? edge_every : Edge::none;
    states[i] = make_state(c.m, mc, c.sw, rng, edge, dt);
  }
  std::vector<int> index(n);
  for (std::size_t k = 0; k < n; ++k) index[k] = static_cast<int>(2 * k + 1);
  std::shuffle(index.begin(), index.end(), rng);
  std::vector<Mat3> d(n);
  std::vector<double> J_new(n), length(n);
  for (std::size_t k = 0; k < n; ++k) {
    // Elastic (1e-6) to strongly plastic (1e-2) increments.
    d[k] = random_strain(rng, std::pow(10.0, -6.0 + 4.0 * u(rng)));
    J_new[k] = states[index[k]].J * (1.0 + d[k].trace());
    length[k] = 1e-6 + 1e-4 * u(rng);
  }
  std::vector<PointState> ref = states;
  std::vector<PointUpdateResult> r_ref(n), r_batch(n);
  for (std::size_t k = 0; k < n; ++k)
    r_ref[k] = update_point(c.m, mc, c.sw, ref[index[k]], d[k], J_new[k], dt, length[k]);
  update_points(c.m, mc, c.sw, states.data(), index.data(), n, d.data(), J_new.data(), dt,
                length.data(), r_batch.data());
  int bad = 0;
  for (std::size_t i = 0; i < states.size(); ++i)
    bad += compare_states(ref[i], states[i], c.name + ", state " + std::to_string(i));
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_EQ(r_ref[k].iterations, r_batch[k].iterations) << c.name << ", point " << k;
    EXPECT_EQ(r_ref[k].converged, r_batch[k].converged) << c.name << ", point " << k;
    bad += r_ref[k].iterations != r_batch[k].iterations;
  }
  return bad;
}

TEST(update_points, bit_identical_to_update_point_for_every_block_size) {
  for (const Case& c : cases()) {
    for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{W - 1}, std::size_t{W},
                          std::size_t{3 * W + 1}, std::size_t{257}}) {
      EXPECT_EQ(run_case(c, n, 17 + n, 1e-9, Edge::none), 0) << c.name << ", n = " << n;
    }
  }
}

TEST(update_points, bit_identical_at_the_edges_of_the_return_mapping) {
  const Edge edges[] = {Edge::virgin, Edge::near_melt, Edge::molten, Edge::near_D_max,
                        Edge::near_initiation};
  const char* names[] = {"first yield from eps_p = 0", "T near T_melt", "T above T_melt",
                         "D near D_max", "damage initiation in the step"};
  for (const Case& c : cases()) {
    for (int e = 0; e < 5; ++e) {
      // dt = 1e-9: plastic rates far above eps_dot_0; dt = 10 s: below it.
      for (double dt : {1e-9, 10.0}) {
        EXPECT_EQ(run_case(c, 64, 100 + static_cast<std::uint64_t>(e), dt, edges[e]), 0)
            << c.name << ", " << names[e] << ", dt = " << dt;
      }
    }
  }
}

// The lanes must not only agree with update_point but also go through the
// plastic path: a sanity check that the cases above are not all elastic.
TEST(update_points, cases_include_plastic_and_elastic_points) {
  const Case c = cases()[1];
  const MaterialConstants mc = derive_constants(c.m);
  std::mt19937_64 rng(5);
  const std::size_t n = 256;
  std::vector<PointState> states(n);
  std::vector<int> index(n);
  std::vector<Mat3> d(n);
  std::vector<double> J_new(n), length(n, 1e-5);
  for (std::size_t k = 0; k < n; ++k) {
    states[k] = make_state(c.m, mc, c.sw, rng, Edge::none, 1e-9);
    index[k] = static_cast<int>(k);
    d[k] = random_strain(rng, k % 2 ? 1e-6 : 1e-2);
    J_new[k] = states[k].J * (1.0 + d[k].trace());
  }
  std::vector<PointUpdateResult> r(n);
  update_points(c.m, mc, c.sw, states.data(), index.data(), n, d.data(), J_new.data(), 1e-9,
                length.data(), r.data());
  int plastic = 0;
  for (const PointUpdateResult& ri : r) plastic += ri.iterations > 0;
  EXPECT_GT(plastic, 64);
  EXPECT_LT(plastic, 256);
}

}  // namespace
