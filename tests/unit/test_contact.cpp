// Contact building blocks: pair geometry against hand values and the
// closest-point property, the bucket search against all pairs, the PGS
// solver against the active-set (direct) solver, friction against the
// closed form of one node on a rigid segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "solver/contact/contact_geometry.hpp"
#include "solver/contact/contact_search.hpp"
#include "solver/contact/contact_solver.hpp"
#include "solver/mesh/generators.hpp"

namespace splat {
namespace {

TEST(ContactGeometry, point_on_segment) {
  // Segment from (1, 0) to (0, 0): outward normal on the right is +z (+y here).
  const Vec3 a(1, 0, 0), b(0, 0, 0);
  const PairGeometry g = project_on_segment(Vec3(0.25, -0.1, 0), a, b);
  ASSERT_TRUE(g.valid);
  EXPECT_NEAR(g.normal.y(), 1.0, 1e-15);
  EXPECT_NEAR(g.gap, -0.1, 1e-15);
  EXPECT_NEAR(g.xi, 0.75, 1e-15);
  EXPECT_NEAR(g.weights[0], 0.25, 1e-15);
  EXPECT_NEAR(g.weights[1], 0.75, 1e-15);
  EXPECT_EQ(g.distance_outside, 0.0);
  const PairGeometry out = project_on_segment(Vec3(-0.5, 0.2, 0), a, b);
  EXPECT_NEAR(out.distance_outside, 0.5, 1e-15);
  EXPECT_EQ(out.weights[1], 1.0);
}

TEST(ContactGeometry, point_on_flat_quad) {
  // Unit square in z = 0, counter-clockwise seen from +z: normal +z.
  const std::array<Vec3, 4> x = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  const PairGeometry g = project_on_quad(Vec3(0.3, 0.6, -0.1), x);
  ASSERT_TRUE(g.valid);
  EXPECT_NEAR(g.gap, -0.1, 1e-14);
  EXPECT_NEAR(g.normal.z(), 1.0, 1e-14);
  // Bilinear weights at (0.3, 0.6).
  EXPECT_NEAR(g.weights[0], 0.7 * 0.4, 1e-13);
  EXPECT_NEAR(g.weights[1], 0.3 * 0.4, 1e-13);
  EXPECT_NEAR(g.weights[2], 0.3 * 0.6, 1e-13);
  EXPECT_NEAR(g.weights[3], 0.7 * 0.6, 1e-13);
  EXPECT_NEAR(g.tangent1.dot(g.normal), 0.0, 1e-14);
  EXPECT_NEAR(g.tangent2.dot(g.normal), 0.0, 1e-14);
}

TEST(ContactGeometry, warped_quad_projection_is_the_closest_point) {
  const std::array<Vec3, 4> x = {Vec3(0, 0, 0), Vec3(1.1, 0, 0.1), Vec3(1, 0.9, -0.05),
                                 Vec3(-0.1, 1, 0.2)};
  const Vec3 p(0.4, 0.45, 0.3);
  const PairGeometry g = project_on_quad(p, x);
  ASSERT_TRUE(g.valid);
  EXPECT_EQ(g.distance_outside, 0.0);
  Vec3 q = Vec3::Zero();
  for (int k = 0; k < 4; ++k) q += g.weights[k] * x[k];
  // p - q is along the normal (orthogonal to the surface) and |gap| = |p - q|.
  EXPECT_NEAR((p - q).cross(g.normal).norm(), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(g.gap), (p - q).norm(), 1e-12);
  // No point of the face on a fine grid is closer.
  double best = 1e300;
  for (int i = 0; i <= 200; ++i) {
    for (int j = 0; j <= 200; ++j) {
      const double xi = -1 + i / 100.0, eta = -1 + j / 100.0;
      const Vec3 y = 0.25 * ((1 - xi) * (1 - eta) * x[0] + (1 + xi) * (1 - eta) * x[1] +
                             (1 + xi) * (1 + eta) * x[2] + (1 - xi) * (1 + eta) * x[3]);
      best = std::min(best, (p - y).norm());
    }
  }
  EXPECT_LE(std::abs(g.gap), best + 1e-12);
  EXPECT_GT(std::abs(g.gap), best - 1e-4);
}

// Positions of two meshes in one array, with surfaces of each.
struct TwoSurfaces {
  std::vector<Vec3> x;
  ContactSurface master, slave;
};

TwoSurfaces axisym_pair(double overlap, unsigned seed, int fine = 1) {
  TwoSurfaces t;
  const AxisymMesh block = axisym_rectangle(30e-6, -20e-6, 0.0, 17 * fine, 11 * fine, Grading{});
  const AxisymMesh ball = axisym_half_disc(10e-6, 10e-6 - overlap, 10 * fine);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2e-6 / fine, 0.2e-6 / fine);
  for (const Vec2& p : block.nodes) t.x.emplace_back(p.x(), p.y() + jitter(rng), 0.0);
  const int off = static_cast<int>(t.x.size());
  for (const Vec2& p : ball.nodes) t.x.emplace_back(p.x(), p.y() + jitter(rng), 0.0);
  std::vector<std::array<int, 4>> mf, sf;
  for (std::size_t k = 0; k < block.boundary_segments.size(); ++k) {
    if (block.segment_boundary[k] & boundary_x_min) continue;
    mf.push_back({block.boundary_segments[k][0], block.boundary_segments[k][1], 0, 0});
  }
  for (std::size_t k = 0; k < ball.boundary_segments.size(); ++k) {
    if (ball.segment_boundary[k] & boundary_x_min) continue;
    sf.push_back({ball.boundary_segments[k][0] + off, ball.boundary_segments[k][1] + off, 0, 0});
  }
  t.master = make_contact_surface(DetectionKind::node_on_segment, mf);
  t.slave = make_contact_surface(DetectionKind::node_on_segment, sf);
  return t;
}

TwoSurfaces hex_pair(double overlap, unsigned seed, int fine = 1) {
  TwoSurfaces t;
  const HexMesh block =
      hex_box(Vec3(0, 0, -10e-6), Vec3(15e-6, 15e-6, 0), 9 * fine, 9 * fine, 6 * fine, Grading{});
  const HexMesh ball = hex_sphere(10e-6, Vec3(0, 0, 10e-6 - overlap), 6 * fine, Sector::quarter);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2e-6 / fine, 0.2e-6 / fine);
  for (const Vec3& p : block.nodes) t.x.push_back(p + Vec3(0, 0, jitter(rng)));
  const int off = static_cast<int>(t.x.size());
  for (const Vec3& p : ball.nodes) t.x.push_back(p + Vec3(0, 0, jitter(rng)));
  std::vector<std::array<int, 4>> mf = block.boundary_faces, sf;
  for (std::size_t k = 0; k < ball.boundary_faces.size(); ++k) {
    if (!(ball.face_boundary[k] & boundary_curved)) continue;
    std::array<int, 4> f = ball.boundary_faces[k];
    for (int& id : f) id += off;
    sf.push_back(f);
  }
  t.master = make_contact_surface(DetectionKind::node_on_quad, mf);
  t.slave = make_contact_surface(DetectionKind::node_on_quad, sf);
  return t;
}

void expect_same_pairs(const TwoSurfaces& t, std::size_t at_least) {
  const SearchSettings st;
  const auto fast = find_pairs_buckets(t.master, t.slave, t.x, st);
  const auto slow = find_pairs_all_pairs(t.master, t.slave, t.x, st);
  ASSERT_EQ(fast.size(), slow.size());
  EXPECT_GE(fast.size(), at_least);
  for (std::size_t i = 0; i < fast.size(); ++i) {
    EXPECT_EQ(fast[i].slave, slow[i].slave) << i;
    EXPECT_EQ(fast[i].face, slow[i].face) << i;
    EXPECT_EQ(fast[i].geometry.gap, slow[i].geometry.gap) << i;
  }
}

TEST(ContactSearch, buckets_match_all_pairs_axisymmetric) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (double overlap : {-0.5e-6, 0.3e-6, 0.8e-6}) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " overlap " << overlap);
      expect_same_pairs(axisym_pair(overlap, seed, 2), overlap > 0.0 ? 1 : 0);
    }
  }
}

TEST(ContactSearch, buckets_match_all_pairs_hexahedra) {
  for (unsigned seed : {1u, 2u}) {
    for (double overlap : {0.3e-6, 0.8e-6}) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " overlap " << overlap);
      expect_same_pairs(hex_pair(overlap, seed), overlap > 0.5e-6 ? 4 : 1);
    }
  }
}

TEST(ContactSearch, slave_areas_add_up_to_the_surface) {
  // Axisymmetric: the ring areas of a half-disc's arc nodes add up to the
  // sphere's area (per radian, 2 R^2) to the chord error of the polygon.
  const AxisymMesh ball = axisym_half_disc(1.0, 0.0, 16);
  std::vector<Vec3> x;
  for (const Vec2& p : ball.nodes) x.emplace_back(p.x(), p.y(), 0.0);
  std::vector<std::array<int, 4>> sf;
  for (std::size_t k = 0; k < ball.boundary_segments.size(); ++k) {
    if (ball.segment_boundary[k] & boundary_curved) {
      sf.push_back({ball.boundary_segments[k][0], ball.boundary_segments[k][1], 0, 0});
    }
  }
  const ContactSurface s = make_contact_surface(DetectionKind::node_on_segment, sf);
  double area = 0.0;
  for (std::size_t k = 0; k < s.nodes.size(); ++k) {
    area += slave_node_area(s, static_cast<int>(k), x);
  }
  EXPECT_NEAR(area, 2.0, 2.0 * 0.01);
}

TEST(ContactSearch, surface_expansion_of_stretched_rotated_and_compressed_surfaces) {
  // Axisymmetric: a flat annulus from the axis to r = 2 (three segments in z
  // = 0) stretched radially by s grows its ring areas by s^2 (length s,
  // mean radius s): Bay's Y = (A - A0) / A = 1 - 1 / s^2 at every node, the
  // node on the axis included; a rigid shift along the axis leaves Y = 0,
  // and a radial compression too (the film does not crack where the surface
  // shrinks).
  const std::vector<Vec3> x0{{0.0, 0.0, 0.0}, {0.5, 0.0, 0.0}, {1.2, 0.0, 0.0}, {2.0, 0.0, 0.0}};
  const ContactSurface ring = make_contact_surface(DetectionKind::node_on_segment,
                                                   {{0, 1, 0, 0}, {1, 2, 0, 0}, {2, 3, 0, 0}});
  const auto mapped = [&](double s, double dz) {
    std::vector<Vec3> x;
    for (const Vec3& p : x0) x.emplace_back(s * p.x(), p.y() + dz, 0.0);
    return x;
  };
  for (double s : {1.2, 2.0}) {
    const auto x = mapped(s, 3.0);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(node_surface_expansion(ring, k, x0, x), 1.0 - 1.0 / (s * s), 1e-12) << k;
    }
    for (int f = 0; f < 3; ++f) {
      EXPECT_NEAR(face_surface_expansion(ring, f, x0, x), 1.0 - 1.0 / (s * s), 1e-12) << f;
    }
  }
  EXPECT_EQ(node_surface_expansion(ring, 2, x0, mapped(1.0, 3.0)), 0.0);
  EXPECT_EQ(node_surface_expansion(ring, 2, x0, mapped(0.8, 0.0)), 0.0);
  // 3D: a unit square stretched by 1.5 and 2 in its plane, then rotated
  // about an axis in its plane, has 3 times its area: Y = 2/3.
  const std::vector<Vec3> q0{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const ContactSurface quad = make_contact_surface(DetectionKind::node_on_quad, {{0, 1, 2, 3}});
  const double c = std::cos(0.7), sn = std::sin(0.7);
  std::vector<Vec3> q;
  for (const Vec3& p : q0) q.emplace_back(1.5 * p.x(), c * 2.0 * p.y(), sn * 2.0 * p.y());
  EXPECT_NEAR(face_surface_expansion(quad, 0, q0, q), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(node_surface_expansion(quad, 1, q0, q), 2.0 / 3.0, 1e-12);
}

// Contact problem of two surfaces: every detected pair, random lumped masses.
ContactProblem problem_of(const TwoSurfaces& t, double dt, unsigned seed) {
  const auto pairs = find_pairs_all_pairs(t.master, t.slave, t.x, SearchSettings{});
  ContactProblem P;
  std::vector<int> local(t.x.size(), -1);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> mass(0.5, 2.0);
  auto loc = [&](int g) {
    if (local[g] < 0) {
      local[g] = static_cast<int>(P.inv_mass.size());
      P.inv_mass.push_back(Vec3::Constant(1.0 / mass(rng)));
      P.velocity.push_back(Vec3::Zero());
    }
    return local[g];
  };
  const int npf = t.master.nodes_per_face();
  for (const DetectedPair& d : pairs) {
    std::array<int, 5> ids{-1, -1, -1, -1, -1};
    std::array<double, 5> c{};
    ids[0] = loc(t.slave.nodes[d.slave]);
    c[0] = 1.0;
    for (int k = 0; k < npf; ++k) {
      ids[k + 1] = loc(t.master.faces[d.face][k]);
      c[k + 1] = -d.geometry.weights[k];
    }
    P.node.push_back(ids);
    P.coef.push_back(c);
    P.normal.push_back(d.geometry.normal);
    P.tangent1.push_back(d.geometry.tangent1);
    P.tangent2.push_back(d.geometry.tangent2);
    P.b.push_back(-d.geometry.gap / dt);
    P.lo.push_back(0.0);
    P.b_hold.push_back(P.b.back());
    P.mu.push_back(0.0);
  }
  return P;
}

void expect_solvers_agree(const ContactProblem& P) {
  ContactSolverSettings pgs, direct;
  direct.kind = ContactSolverKind::active_set;
  const ContactSolution a = solve_contact(P, pgs);
  const ContactSolution b = solve_contact(P, direct);
  ASSERT_TRUE(a.converged);
  ASSERT_TRUE(b.converged);
  double scale = 0.0, bscale = 0.0;
  for (double p : b.p_n) scale = std::max(scale, std::abs(p));
  for (double v : P.b) bscale = std::max(bscale, std::abs(v));
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = 0; i < P.pairs(); ++i) EXPECT_NEAR(a.p_n[i], b.p_n[i], 1e-6 * scale) << i;
  EXPECT_LE(a.residual, 1e-7 * bscale);
  EXPECT_LE(b.residual, 1e-9 * bscale);
  // Unilateral: no tension.
  for (double p : a.p_n) EXPECT_GE(p, 0.0);
  std::printf(
      "pairs %zu: pgs %d sweeps (violation %.2e), active set %d passes (%.2e) of %.2e m/s\n",
      P.pairs(), a.iterations, a.residual, b.iterations, b.residual, bscale);
}

TEST(ContactSolver, pgs_matches_active_set_axisymmetric) {
  expect_solvers_agree(problem_of(axisym_pair(0.1e-6, 4, 8), 1e-9, 5));
}

TEST(ContactSolver, pgs_matches_active_set_hexahedra) {
  expect_solvers_agree(problem_of(hex_pair(0.5e-6, 4, 2), 1e-9, 5));
}

// One node of mass m on a rigid segment (master nodes with zero inverse
// mass), approaching at b and sliding at u: p_n = m b; the friction impulse
// stops the slip if m u <= mu p_n, else it is mu p_n against the slip.
TEST(ContactSolver, coulomb_friction_on_a_rigid_segment) {
  const double m = 2.0, b = 3.0;
  for (double u : {0.5, 5.0}) {
    ContactProblem P;
    P.node.push_back({0, 1, 2, -1, -1});
    P.coef.push_back({1.0, -0.5, -0.5, 0.0, 0.0});
    P.normal.push_back(Vec3(0, 1, 0));
    P.tangent1.push_back(Vec3(1, 0, 0));
    P.tangent2.push_back(Vec3::Zero());
    P.b.push_back(b);
    P.lo.push_back(0.0);
    P.b_hold.push_back(P.b.back());
    P.mu.push_back(0.3);
    P.inv_mass = {Vec3(1 / m, 1 / m, 0), Vec3::Zero(), Vec3::Zero()};
    P.velocity = {Vec3(u, -b, 0), Vec3::Zero(), Vec3::Zero()};
    const ContactSolution s = solve_contact(P, ContactSolverSettings{});
    EXPECT_NEAR(s.p_n[0], m * b, 1e-12);
    const double expected = -std::min(m * u, 0.3 * m * b);
    EXPECT_NEAR(s.p_t[0].x(), expected, 1e-12) << "u = " << u;
  }
}

// A bonded row (one node of mass m on a rigid segment): opening at rate u
// from an open gap g_n it is held with tension -m u (no cap) or the cap; a
// pair closing at rate u from the same open gap gets no force until the
// gap would close.
TEST(ContactSolver, bonded_row_holds_or_caps_the_opening) {
  const double m = 2.0, dt = 1e-3, g_n = 1e-3;
  auto one = [&](double rate, double lo) {
    ContactProblem P;
    P.node.push_back({0, 1, 2, -1, -1});
    P.coef.push_back({1.0, -0.5, -0.5, 0.0, 0.0});
    P.normal.push_back(Vec3(0, 1, 0));
    P.tangent1.push_back(Vec3(1, 0, 0));
    P.tangent2.push_back(Vec3::Zero());
    const double g_pred = g_n + rate * dt;
    P.b.push_back(-g_pred / dt);
    P.b_hold.push_back(-(g_pred - g_n) / dt);
    P.lo.push_back(lo);
    P.mu.push_back(0.0);
    P.inv_mass = {Vec3(1 / m, 1 / m, 0), Vec3::Zero(), Vec3::Zero()};
    P.velocity = {Vec3(0, rate, 0), Vec3::Zero(), Vec3::Zero()};
    const ContactSolution s = solve_contact(P, ContactSolverSettings{});
    EXPECT_LE(s.residual, 1e-12);
    return s.p_n[0];
  };
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_NEAR(one(0.5, -inf), -m * 0.5, 1e-12);               // held
  EXPECT_NEAR(one(0.5, -0.25), -0.25, 1e-12);                 // capped
  EXPECT_EQ(one(-0.5, -inf), 0.0);                            // closing, still open at the end
  EXPECT_NEAR(one(-2.0, -inf), m * (2.0 - g_n / dt), 1e-12);  // would penetrate: pushed
  EXPECT_EQ(one(0.5, 0.0), 0.0);                              // not bonded: free to open
}

}  // namespace
}  // namespace splat
