// The element loop (fe_internal_forces) runs each block of elements in
// phases, W elements per vector lane group (simd_lanes.hpp). Checked against
// the slow obvious assembly: each element on its own through the Eigen-form
// kernels (hex8.hpp, quad4_axisym.hpp), summed into the nodes in element
// order; with material updates (dt > 0), against the one-element path
// (fe_internal_forces_one_by_one) to the bit, and against the same body whose
// lane groups are shifted by one element.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "solver/fe/fe_body.hpp"
#include "solver/fe/hex8.hpp"
#include "solver/fe/quad4_axisym.hpp"
#include "solver/mesh/generators.hpp"
#include "support/isa.hpp"
#include "support/materials.hpp"

namespace splat {
namespace {

using test_support::jc_copper;
using test_support::no_damage;

Vec3 random_vec(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Vec3(u(rng), u(rng), u(rng));
}

// nx x ny x nz box of side h with interior nodes moved by up to jitter h.
HexMesh jittered_box(int nx, int ny, int nz, double h, double jitter, std::mt19937_64& rng) {
  HexMesh m;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        m.nodes.push_back(h * Vec3(i, j, k) + random_vec(rng, jitter * h));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                           id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                           id(i, j + 1, k + 1)});
  return m;
}

AxisymMesh jittered_rectangle(int nr, int nz, double h, double jitter, std::mt19937_64& rng) {
  AxisymMesh m;
  auto id = [&](int i, int j) { return i + (nr + 1) * j; };
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i <= nr; ++i) {
      Vec2 p(h * i, h * j);
      if (i > 0) p += random_vec(rng, jitter * h).head<2>();
      m.nodes.push_back(p);
    }
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < nr; ++i)
      m.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

// A random symmetric stress (deviator and pressure) in every element, random
// nodal velocities (axisymmetric: in the plane, and no r-theta or z-theta
// stress, which a torsion-free axisymmetric state never has).
void randomise(FeBody& body, NodeSet& nodes, std::mt19937_64& rng) {
  const bool axisymmetric = body.kind == ElementKind::quad4_axisym;
  for (PointState& st : body.state) {
    Mat3 s;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i <= j; ++i) s(i, j) = s(j, i) = random_vec(rng, 1e8).x();
    if (axisymmetric) s(0, 2) = s(2, 0) = s(1, 2) = s(2, 1) = 0.0;
    st.s = s - (s.trace() / 3.0) * Mat3::Identity();
    st.p = random_vec(rng, 1e8).x();
  }
  for (Vec3& v : nodes.v) {
    v = random_vec(rng, 30.0);
    if (axisymmetric) v.z() = 0.0;
  }
}

// Nodal forces of the active elements, each evaluated on its own with the
// Eigen-form kernels at dt = 0 (no material update, no bulk viscosity: the
// stress is the state's, the hourglass forces the viscous ones).
std::vector<Vec3> reference_forces(const FeBody& body, const NodeSet& nodes) {
  std::vector<Vec3> f(nodes.size(), Vec3::Zero());
  const double c_hg = body.settings.hourglass_coefficient;
  const double c = body.constants.wave_speed;
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    if (!body.active[e]) continue;
    const Mat3 sigma = body.state[e].cauchy();
    if (body.kind == ElementKind::hex8) {
      Hex8Vectors x, v;
      for (int a = 0; a < 8; ++a) {
        x[a] = nodes.x[body.conn[e][a]];
        v[a] = nodes.v[body.conn[e][a]];
      }
      const Hex8Modes xm = hex8_modes(x), w = hex8_modes(v);
      const Hex8Geometry g = hex8_geometry(xm);
      const std::array<Vec3, 4> qdot = hex8_hourglass_rates(w, xm, hex8_velocity_gradient(w, g));
      const double rho = body.element_mass[e] / g.volume;
      std::array<Vec3, 4> Q;
      hex8_hourglass_viscous(qdot, hex8_viscous_hourglass_coefficient(c_hg, rho, c, g.volume), Q);
      const Hex8Vectors fe = hex8_forces(sigma, g, xm, Q);
      for (int a = 0; a < 8; ++a) f[body.conn[e][a]] += fe[a];
    } else {
      Quad4Vectors x, v, fe;
      for (int a = 0; a < 4; ++a) {
        x[a] = nodes.x[body.conn[e][a]].head<2>();
        v[a] = nodes.v[body.conn[e][a]].head<2>();
      }
      const Quad4Gradient g = quad4_axisym_gradient(x);
      quad4_axisym_stress_forces(sigma, g, fe);
      const double rho = body.element_mass[e] / g.volume;
      quad4_axisym_hourglass_viscous(quad4_axisym_hourglass_vector(x, g), v,
                                     quad4_axisym_viscous_hourglass_coefficient(c_hg, rho, c, g),
                                     fe);
      for (int a = 0; a < 4; ++a) f[body.conn[e][a]] += Vec3(fe[a].x(), fe[a].y(), 0.0);
    }
  }
  return f;
}

template <class Mesh>
void check_against_reference(const Mesh& mesh) {
  std::mt19937_64 rng(41);
  NodeSet nodes;
  FeBody body = make_fe_body("b", mesh, jc_copper(), no_damage(), FeSettings{}, Vec3::Zero(), 300.0,
                             1, nodes);
  randomise(body, nodes, rng);
  // An inactive element splits the pairs: its neighbours run one at a time.
  // It is eroded after a step, so it had forces: the gather must not add them.
  fe_internal_forces(body, nodes, 0.0);
  for (Vec3& f : nodes.f) f.setZero();
  erode_element(body, nodes, 7);
  fe_internal_forces(body, nodes, 0.0);
  const std::vector<Vec3> ref = reference_forces(body, nodes);
  double scale = 0.0;
  for (const Vec3& fi : ref) scale = std::max(scale, fi.norm());
  ASSERT_GT(scale, 0.0);
  for (std::size_t n = 0; n < nodes.size(); ++n)
    ASSERT_LE((nodes.f[n] - ref[n]).norm(), 1e-13 * scale) << "node " << n;
}

TEST(fe_element_lanes, hex_forces_match_element_by_element_assembly) {
  std::mt19937_64 rng(42);
  check_against_reference(jittered_box(5, 4, 3, 1e-4, 0.15, rng));  // 60 elements, one block
}

TEST(fe_element_lanes, quad_forces_match_element_by_element_assembly) {
  std::mt19937_64 rng(43);
  check_against_reference(jittered_rectangle(9, 7, 1e-4, 0.2, rng));  // 63 elements
}

// Steps with material updates; body B has element 0 removed, so every pair of
// B is shifted by one element against A. Every other element must come out
// the same to the bit.
template <class Mesh>
void check_pairing_shift(const Mesh& mesh) {
  std::array<NodeSet, 2> nodes;
  std::array<FeBody, 2> body;
  for (int b = 0; b < 2; ++b) {
    std::mt19937_64 rng(44);
    body[b] = make_fe_body("b", mesh, jc_copper(), no_damage(), FeSettings{}, Vec3::Zero(), 300.0,
                           1, nodes[b]);
    randomise(body[b], nodes[b], rng);
    for (Vec3& v : nodes[b].v) v *= 1e2;  // large enough to yield
    if (b == 1) erode_element(body[b], nodes[b], 0);
    const double dt = 1e-9;
    for (int step = 0; step < 4; ++step) {
      for (std::size_t n = 0; n < nodes[b].size(); ++n) nodes[b].x[n] += dt * nodes[b].v[n];
      const FeStepResult r = fe_internal_forces(body[b], nodes[b], dt);
      ASSERT_FALSE(r.return_failed);
    }
  }
  int plastic = 0;
  for (std::size_t e = 1; e < body[0].num_elements(); ++e) {
    for (int a = 0; a < body[0].nodes_per_element(); ++a)
      ASSERT_EQ(body[0].element_force(e, a), body[1].element_force(e, a)) << "element " << e;
    ASSERT_EQ(body[0].state[e].s, body[1].state[e].s) << "element " << e;
    ASSERT_EQ(body[0].state[e].p, body[1].state[e].p) << "element " << e;
    ASSERT_EQ(body[0].state[e].eps_p, body[1].state[e].eps_p) << "element " << e;
    ASSERT_EQ(body[0].volume[e], body[1].volume[e]) << "element " << e;
    ASSERT_EQ(body[0].char_length[e], body[1].char_length[e]) << "element " << e;
    plastic += body[0].state[e].eps_p > 0.0;
  }
  EXPECT_GT(plastic, 0);  // the return mapping ran in the lanes too
}

TEST(fe_element_lanes, hex_results_do_not_depend_on_the_pairing) {
  std::mt19937_64 rng(45);
  check_pairing_shift(jittered_box(5, 4, 3, 1e-4, 0.15, rng));
}

TEST(fe_element_lanes, quad_results_do_not_depend_on_the_pairing) {
  std::mt19937_64 rng(46);
  check_pairing_shift(jittered_rectangle(9, 7, 1e-4, 0.2, rng));
}

// Steps with material updates, an eroded element and elements inverted by a
// node pushed through them, through the lane loop (body 0) and the
// one-element path (body 1): forces, states, held hourglass forces and every
// reduction the same to the bit.
template <class Mesh>
void check_active_lanes_against_one_by_one(const Mesh& mesh, const FeSettings& settings) {
  std::array<NodeSet, 2> nodes;
  std::array<FeBody, 2> body;
  std::array<std::vector<FeStepResult>, 2> results;
  for (int b = 0; b < 2; ++b) {
    std::mt19937_64 rng(47);
    body[b] = make_fe_body("b", mesh, jc_copper(), no_damage(), settings, Vec3::Zero(), 300.0, 1,
                           nodes[b]);
    randomise(body[b], nodes[b], rng);
    for (Vec3& v : nodes[b].v) v *= 1e2;  // large enough to yield
    erode_element(body[b], nodes[b], 5);
    // Push the far corner of element 70 through its near corner.
    const std::array<int, 8>& cn = body[b].conn[70];
    const int far = body[b].kind == ElementKind::hex8 ? 6 : 2;
    nodes[b].x[cn[far]] = nodes[b].x[cn[0]] - 0.5 * (nodes[b].x[cn[far]] - nodes[b].x[cn[0]]);
    const double dt = 1e-9;
    for (int step = 0; step < 4; ++step) {
      for (std::size_t n = 0; n < nodes[b].size(); ++n) nodes[b].x[n] += dt * nodes[b].v[n];
      for (Vec3& f : nodes[b].f) f.setZero();
      results[b].push_back(b == 0 ? fe_internal_forces(body[b], nodes[b], dt)
                                  : fe_internal_forces_one_by_one(body[b], nodes[b], dt));
    }
  }
  for (std::size_t n = 0; n < nodes[0].size(); ++n)
    ASSERT_EQ(nodes[0].f[n], nodes[1].f[n]) << "node " << n;
  int plastic = 0;
  for (std::size_t e = 0; e < body[0].num_elements(); ++e) {
    const PointState &a = body[0].state[e], &b = body[1].state[e];
    ASSERT_EQ(a.s, b.s) << "element " << e;
    ASSERT_EQ(a.p, b.p) << "element " << e;
    ASSERT_EQ(a.e, b.e) << "element " << e;
    ASSERT_EQ(a.eps_p, b.eps_p) << "element " << e;
    ASSERT_EQ(a.T, b.T) << "element " << e;
    ASSERT_EQ(body[0].hg[e], body[1].hg[e]) << "element " << e;
    ASSERT_EQ(body[0].hg_kappa[e], body[1].hg_kappa[e]) << "element " << e;
    ASSERT_EQ(body[0].q[e], body[1].q[e]) << "element " << e;
    ASSERT_EQ(body[0].volume[e], body[1].volume[e]) << "element " << e;
    ASSERT_EQ(body[0].char_length[e], body[1].char_length[e]) << "element " << e;
    for (int node = 0; node < body[0].nodes_per_element(); ++node)
      ASSERT_EQ(body[0].element_force(e, node), body[1].element_force(e, node)) << "element " << e;
    plastic += a.eps_p > 0.0;
  }
  EXPECT_GT(plastic, 0);
  for (std::size_t k = 0; k < results[0].size(); ++k) {
    const FeStepResult &a = results[0][k], &b = results[1][k];
    ASSERT_EQ(a.dt_stable, b.dt_stable) << "step " << k;
    ASSERT_EQ(a.hourglass_power, b.hourglass_power) << "step " << k;
    ASSERT_EQ(a.viscosity_power, b.viscosity_power) << "step " << k;
    ASSERT_EQ(a.max_return_iterations, b.max_return_iterations) << "step " << k;
    ASSERT_EQ(a.return_failed, b.return_failed) << "step " << k;
    ASSERT_EQ(a.inverted, b.inverted) << "step " << k;
    ASSERT_EQ(a.to_erode, b.to_erode) << "step " << k;
    EXPECT_GT(a.viscosity_power, 0.0);
    EXPECT_TRUE(a.inverted > 0 || !a.to_erode.empty());  // the inverted path ran
  }
}

// The above for the lane loops of every instruction set this CPU supports.
template <class Mesh>
void check_lanes_against_one_by_one(const Mesh& mesh, const FeSettings& settings) {
  test_support::for_each_isa([&] { check_active_lanes_against_one_by_one(mesh, settings); });
}

FeSettings stiffness_form() {
  FeSettings s;
  s.stiffness_hourglass = true;
  return s;
}

FeSettings with_erosion() {
  FeSettings s;
  s.erosion = true;
  return s;
}

TEST(fe_element_lanes, hex_lanes_match_one_element_path_viscous_hourglass) {
  std::mt19937_64 rng(48);
  check_lanes_against_one_by_one(jittered_box(7, 6, 5, 1e-4, 0.15, rng), FeSettings{});
}

TEST(fe_element_lanes, hex_lanes_match_one_element_path_stiffness_hourglass) {
  std::mt19937_64 rng(49);
  check_lanes_against_one_by_one(jittered_box(7, 6, 5, 1e-4, 0.15, rng), stiffness_form());
}

TEST(fe_element_lanes, hex_lanes_match_one_element_path_with_erosion) {
  std::mt19937_64 rng(50);
  check_lanes_against_one_by_one(jittered_box(7, 6, 5, 1e-4, 0.15, rng), with_erosion());
}

TEST(fe_element_lanes, quad_lanes_match_one_element_path_viscous_hourglass) {
  std::mt19937_64 rng(51);
  check_lanes_against_one_by_one(jittered_rectangle(19, 13, 1e-4, 0.2, rng), FeSettings{});
}

TEST(fe_element_lanes, quad_lanes_match_one_element_path_stiffness_hourglass) {
  std::mt19937_64 rng(52);
  check_lanes_against_one_by_one(jittered_rectangle(19, 13, 1e-4, 0.2, rng), stiffness_form());
}

TEST(fe_element_lanes, quad_lanes_match_one_element_path_with_erosion) {
  std::mt19937_64 rng(53);
  check_lanes_against_one_by_one(jittered_rectangle(19, 13, 1e-4, 0.2, rng), with_erosion());
}

// Rows of 16 hexahedra and of 19 quads: most lane groups are node runs
// (whole-vector node loads and force stores), some are not (a row ends inside
// them, or the eroded element 5 shifts block 0's groups), and the inverted
// element 70 sits in a run.
TEST(fe_element_lanes, hex_node_runs_match_one_element_path) {
  std::mt19937_64 rng(54);
  const HexMesh mesh = jittered_box(16, 3, 3, 1e-4, 0.15, rng);
  check_lanes_against_one_by_one(mesh, FeSettings{});
  check_lanes_against_one_by_one(mesh, stiffness_form());
  check_lanes_against_one_by_one(mesh, with_erosion());
}

// FeBody::node_run against a count from the mesh's rows: a record of 8
// elements starting at e is a run exactly when its elements share one row.
TEST(fe_element_lanes, node_runs_are_the_records_within_one_row) {
  std::mt19937_64 rng(55);
  auto expected = [](std::size_t elements, std::size_t row) {
    int runs = 0;
    for (std::size_t e = 0; e + 8 <= elements; e += 8) runs += e % row + 8 <= row;
    return runs;
  };
  auto count = [](const FeBody& b) {
    return static_cast<int>(std::count(b.node_run.begin(), b.node_run.end(), 1));
  };
  NodeSet nodes;
  const FeBody hex = make_fe_body("h", jittered_box(16, 3, 3, 1e-4, 0.15, rng), jc_copper(),
                                  no_damage(), FeSettings{}, Vec3::Zero(), 300.0, 1, nodes);
  EXPECT_EQ(count(hex), 18);
  EXPECT_EQ(count(hex), expected(hex.num_elements(), 16));
  const FeBody odd = make_fe_body("o", jittered_box(7, 6, 5, 1e-4, 0.15, rng), jc_copper(),
                                  no_damage(), FeSettings{}, Vec3::Zero(), 300.0, 1, nodes);
  EXPECT_EQ(count(odd), 0);
  const FeBody quad = make_fe_body("q", jittered_rectangle(19, 13, 1e-4, 0.2, rng), jc_copper(),
                                   no_damage(), FeSettings{}, Vec3::Zero(), 300.0, 1, nodes);
  EXPECT_GT(count(quad), 0);
  EXPECT_EQ(count(quad), expected(quad.num_elements(), 19));
  // hex_cylinder is numbered along the axis first: its columns of 16 elements
  // are the rows here.
  const HexMesh cylinder_mesh = hex_cylinder(1e-3, 0.0, 4e-3, 4, 16, Sector::quarter, Grading{});
  const FeBody cylinder = make_fe_body("c", cylinder_mesh, jc_copper(), no_damage(), FeSettings{},
                                       Vec3::Zero(), 300.0, 1, nodes);
  EXPECT_GT(count(cylinder), 0);
  EXPECT_EQ(count(cylinder), expected(cylinder.num_elements(), 16));
}

}  // namespace
}  // namespace splat
