// Structured mesh generators: orientation, quality, volumes and surface areas
// against the exact shapes (with the discretisation error shrinking under
// refinement), boundary tags against the geometry, closed boundaries, and
// node merging and boundary detection checked against slow all-pairs /
// face-counting versions.
//
// Quality thresholds asserted (measured values in the printout):
//   2D disc and cylinder section: min scaled Jacobian >= 0.75
//   3D sphere:                    min scaled Jacobian >= 0.6
//   sphere and disc:              longest / shortest edge < 3
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "solver/mesh/generators.hpp"

namespace splat {
namespace {

constexpr double pi = std::numbers::pi;
constexpr std::array<Sector, 3> all_sectors = {Sector::full, Sector::half, Sector::quarter};

double sector_fraction(Sector s) {
  return s == Sector::full ? 1.0 : s == Sector::half ? 0.5 : 0.25;
}

const char* sector_name(Sector s) {
  return s == Sector::full ? "full" : s == Sector::half ? "half" : "quarter";
}

// ---------------------------------------------------------------- 2D helpers

double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Scaled Jacobian at each corner: sine of the corner angle, > 0 if convex CCW.
double quad_min_scaled_jacobian(const AxisymMesh& m, const std::array<int, 4>& q) {
  double worst = 1.0;
  for (int v = 0; v < 4; ++v) {
    const Vec2 p = m.nodes[q[v]];
    const Vec2 a = m.nodes[q[(v + 1) % 4]] - p, b = m.nodes[q[(v + 3) % 4]] - p;
    worst = std::min(worst, cross2(a, b) / (a.norm() * b.norm()));
  }
  return worst;
}

// Area and area centroid of a straight-sided quad (shoelace); by Pappus the
// revolved volume of the quad is exactly 2 pi r_centroid area.
std::pair<double, Vec2> quad_area_centroid(const AxisymMesh& m, const std::array<int, 4>& q) {
  double area = 0.0;
  Vec2 moment = Vec2::Zero();
  for (int v = 0; v < 4; ++v) {
    const Vec2 a = m.nodes[q[v]], b = m.nodes[q[(v + 1) % 4]];
    const double w = cross2(a, b);
    area += 0.5 * w;
    moment += w * (a + b) / 6.0;
  }
  return {area, moment / area};
}

double revolved_volume(const AxisymMesh& m) {
  double v = 0.0;
  for (const auto& q : m.quads) {
    const auto [area, c] = quad_area_centroid(m, q);
    v += 2.0 * pi * c.x() * area;
  }
  return v;
}

double min_edge(const AxisymMesh& m) {
  double h = INFINITY;
  for (const auto& q : m.quads)
    for (int v = 0; v < 4; ++v) h = std::min(h, (m.nodes[q[v]] - m.nodes[q[(v + 1) % 4]]).norm());
  return h;
}

double edge_ratio(const AxisymMesh& m) {
  double lo = INFINITY, hi = 0.0;
  for (const auto& q : m.quads)
    for (int v = 0; v < 4; ++v) {
      const double l = (m.nodes[q[v]] - m.nodes[q[(v + 1) % 4]]).norm();
      lo = std::min(lo, l), hi = std::max(hi, l);
    }
  return hi / lo;
}

// Every quad convex and counter-clockwise; returns the min scaled Jacobian.
double check_quads(const AxisymMesh& m) {
  double worst = 1.0;
  for (const auto& q : m.quads) {
    for (int v : q) EXPECT_TRUE(v >= 0 && v < int(m.nodes.size()));
    const double sj = quad_min_scaled_jacobian(m, q);
    EXPECT_GT(sj, 0.0);
    EXPECT_GT(quad_area_centroid(m, q).first, 0.0);
    worst = std::min(worst, sj);
  }
  return worst;
}

// Boundary segments: tags shared by both nodes, every boundary edge found
// (against counting edge uses), one closed loop that runs counter-clockwise
// (its shoelace area is the mesh area, so the outside is on the right).
void check_boundary_loop(const AxisymMesh& m) {
  ASSERT_EQ(m.boundary_segments.size(), m.segment_boundary.size());
  std::map<std::pair<int, int>, int> uses;
  for (const auto& q : m.quads)
    for (int v = 0; v < 4; ++v) ++uses[std::minmax(q[v], q[(v + 1) % 4])];
  std::set<std::pair<int, int>> once;
  for (const auto& [e, n] : uses)
    if (n == 1) once.insert(e);
  std::set<std::pair<int, int>> tagged;
  for (std::size_t s = 0; s < m.boundary_segments.size(); ++s) {
    const auto [a, b] = m.boundary_segments[s];
    const std::uint32_t tag = m.segment_boundary[s];
    EXPECT_EQ(std::popcount(tag), 1);
    EXPECT_EQ(m.node_boundary[a] & tag, tag);
    EXPECT_EQ(m.node_boundary[b] & tag, tag);
    tagged.insert(std::minmax(a, b));
  }
  EXPECT_EQ(tagged, once);
  EXPECT_EQ(tagged.size(), m.boundary_segments.size());

  std::map<int, int> next;  // start node -> segment
  for (std::size_t s = 0; s < m.boundary_segments.size(); ++s)
    EXPECT_TRUE(next.emplace(m.boundary_segments[s][0], int(s)).second)
        << "node starts two segments";
  int s = 0, steps = 0;
  double loop_area = 0.0;
  do {
    const auto [a, b] = m.boundary_segments[s];
    loop_area += 0.5 * cross2(m.nodes[a], m.nodes[b]);
    ASSERT_TRUE(next.count(b)) << "open boundary at node " << b;
    s = next[b];
    ++steps;
  } while (s != 0 && steps <= int(m.boundary_segments.size()));
  EXPECT_EQ(steps, int(m.boundary_segments.size())) << "boundary is not one closed loop";
  double area = 0.0;
  for (const auto& q : m.quads) area += quad_area_centroid(m, q).first;
  EXPECT_NEAR(loop_area, area, 1e-12 * area);
}

// ---------------------------------------------------------------- 3D helpers

constexpr int cube_corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

int corner_at(int x, int y, int z) {
  return (y ? (x ? 2 : 3) : (x ? 1 : 0)) + 4 * z;
}

// Jacobian columns of the trilinear map at corner v: edges to the three
// neighbours, signed so that they point along +xi, +eta, +zeta.
Mat3 corner_jacobian(const HexMesh& m, const std::array<int, 8>& h, int v) {
  const int x = cube_corner[v][0], y = cube_corner[v][1], z = cube_corner[v][2];
  const Vec3 p = m.nodes[h[v]];
  Mat3 J;
  J.col(0) = (m.nodes[h[corner_at(1 - x, y, z)]] - p) * (x ? -1.0 : 1.0);
  J.col(1) = (m.nodes[h[corner_at(x, 1 - y, z)]] - p) * (y ? -1.0 : 1.0);
  J.col(2) = (m.nodes[h[corner_at(x, y, 1 - z)]] - p) * (z ? -1.0 : 1.0);
  return J;
}

double hex_min_scaled_jacobian(const HexMesh& m, const std::array<int, 8>& h) {
  double worst = 1.0;
  for (int v = 0; v < 8; ++v) {
    const Mat3 J = corner_jacobian(m, h, v);
    worst =
        std::min(worst, J.determinant() / (J.col(0).norm() * J.col(1).norm() * J.col(2).norm()));
  }
  return worst;
}

// Volume of the trilinear hexahedron; 2x2x2 Gauss is exact (det J has degree
// <= 2 in each reference coordinate).
double hex_volume(const HexMesh& m, const std::array<int, 8>& h) {
  const double g = 0.5 / std::sqrt(3.0);
  double vol = 0.0;
  for (int q = 0; q < 8; ++q) {
    const double xi[3] = {0.5 + (q & 1 ? g : -g), 0.5 + (q & 2 ? g : -g), 0.5 + (q & 4 ? g : -g)};
    Mat3 J = Mat3::Zero();
    for (int v = 0; v < 8; ++v) {
      double dN[3];
      for (int d = 0; d < 3; ++d) {
        dN[d] = 1.0;
        for (int e = 0; e < 3; ++e) {
          const double s = cube_corner[v][e] ? xi[e] : 1.0 - xi[e];
          dN[d] *= e == d ? (cube_corner[v][e] ? 1.0 : -1.0) : s;
        }
      }
      for (int d = 0; d < 3; ++d) J.col(d) += dN[d] * m.nodes[h[v]];
    }
    vol += J.determinant() / 8.0;
  }
  return vol;
}

double mesh_volume(const HexMesh& m) {
  double v = 0.0;
  for (const auto& h : m.hexes) v += hex_volume(m, h);
  return v;
}

// Exact vector area of a bilinear quad face: half the cross product of its
// diagonals. Its scalar area by 3x3 Gauss on |X_u x X_v|.
Vec3 face_vector_area(const HexMesh& m, const std::array<int, 4>& f) {
  return 0.5 * (m.nodes[f[2]] - m.nodes[f[0]]).cross(m.nodes[f[3]] - m.nodes[f[1]]);
}

double face_area(const HexMesh& m, const std::array<int, 4>& f) {
  const double gp[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
  const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  const Vec3 &x0 = m.nodes[f[0]], &x1 = m.nodes[f[1]], &x2 = m.nodes[f[2]], &x3 = m.nodes[f[3]];
  double a = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double u = gp[i], v = gp[j];
      const Vec3 xu = (1.0 - v) * (x1 - x0) + v * (x2 - x3);
      const Vec3 xv = (1.0 - u) * (x3 - x0) + u * (x2 - x1);
      a += gw[i] * gw[j] * xu.cross(xv).norm();
    }
  return a;
}

double min_edge(const HexMesh& m) {
  constexpr int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  double h = INFINITY;
  for (const auto& hx : m.hexes)
    for (const auto& e : edges) h = std::min(h, (m.nodes[hx[e[0]]] - m.nodes[hx[e[1]]]).norm());
  return h;
}

double edge_ratio(const HexMesh& m) {
  constexpr int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  double lo = INFINITY, hi = 0.0;
  for (const auto& hx : m.hexes)
    for (const auto& e : edges) {
      const double l = (m.nodes[hx[e[0]]] - m.nodes[hx[e[1]]]).norm();
      lo = std::min(lo, l), hi = std::max(hi, l);
    }
  return hi / lo;
}

// Positive Jacobian at all 8 corners of every hex; returns the min scaled one.
double check_hexes(const HexMesh& m) {
  double worst = 1.0;
  for (const auto& h : m.hexes) {
    for (int v : h) EXPECT_TRUE(v >= 0 && v < int(m.nodes.size()));
    for (int v = 0; v < 8; ++v) EXPECT_GT(corner_jacobian(m, h, v).determinant(), 0.0);
    worst = std::min(worst, hex_min_scaled_jacobian(m, h));
  }
  return worst;
}

// Boundary faces: exactly the faces used by one hex (counted the slow way),
// each with one tag its nodes share, and together a closed surface (the
// vector areas sum to zero). Returns the total area per tag.
std::map<std::uint32_t, double> check_boundary_faces(const HexMesh& m) {
  constexpr int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                               {2, 3, 7, 6}, {3, 0, 4, 7}, {1, 2, 6, 5}};
  std::map<std::array<int, 4>, int> uses;
  for (const auto& h : m.hexes)
    for (const auto& f : faces) {
      std::array<int, 4> key = {h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
      std::sort(key.begin(), key.end());
      ++uses[key];
    }
  std::set<std::array<int, 4>> once, tagged;
  for (const auto& [k, n] : uses) {
    EXPECT_LE(n, 2);
    if (n == 1) once.insert(k);
  }
  EXPECT_EQ(m.boundary_faces.size(), m.face_boundary.size());
  std::map<std::uint32_t, double> area;
  Vec3 closure = Vec3::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < m.boundary_faces.size(); ++i) {
    const auto& f = m.boundary_faces[i];
    const std::uint32_t tag = m.face_boundary[i];
    EXPECT_EQ(std::popcount(tag), 1);
    for (int v : f) EXPECT_EQ(m.node_boundary[v] & tag, tag);
    std::array<int, 4> key = f;
    std::sort(key.begin(), key.end());
    tagged.insert(key);
    closure += face_vector_area(m, f);
    const double a = face_area(m, f);
    area[tag] += a;
    total += a;
  }
  EXPECT_EQ(tagged, once);
  EXPECT_EQ(tagged.size(), m.boundary_faces.size());
  EXPECT_LT(closure.norm(), 1e-12 * total) << "boundary surface is not closed";
  // Nodes carry bits exactly when they lie on some boundary face.
  std::vector<char> on_face(m.nodes.size(), 0);
  for (const auto& f : m.boundary_faces)
    for (int v : f) on_face[v] = 1;
  for (std::size_t v = 0; v < m.nodes.size(); ++v)
    EXPECT_EQ(on_face[v] != 0, m.node_boundary[v] != 0) << "node " << v;
  return area;
}

// Every face on a plane tag lies in that plane and faces away from the body
// (its vector area points along the outward axis direction).
void check_plane_faces(const HexMesh& m, std::uint32_t tag, int axis, double value, double sign) {
  int n = 0;
  for (std::size_t i = 0; i < m.boundary_faces.size(); ++i) {
    if (m.face_boundary[i] != tag) continue;
    ++n;
    for (int v : m.boundary_faces[i]) EXPECT_EQ(m.nodes[v][axis], value);
    const Vec3 a = face_vector_area(m, m.boundary_faces[i]);
    EXPECT_GT(sign * a[axis], 0.0);
    EXPECT_NEAR(std::abs(a[axis]), a.norm(), 1e-12 * a.norm());
  }
  EXPECT_GT(n, 0) << "no face tagged " << tag;
}

// Slow all-pairs check that no two nodes coincide: every pair is further
// apart than a fraction of the shortest element edge.
template <class Mesh>
void check_no_duplicate_nodes(const Mesh& m) {
  const double h = min_edge(m);
  double closest = INFINITY;
  for (std::size_t a = 0; a < m.nodes.size(); ++a)
    for (std::size_t b = a + 1; b < m.nodes.size(); ++b)
      closest = std::min(closest, (m.nodes[a] - m.nodes[b]).norm());
  EXPECT_GT(closest, 0.5 * h);
}

// Every node is used by some element.
template <class Mesh, class Cells>
void check_all_nodes_used(const Mesh& m, const Cells& cells) {
  std::vector<char> used(m.nodes.size(), 0);
  for (const auto& c : cells)
    for (int v : c) used[v] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}

void expect_invalid(const std::function<void()>& f, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one naming '" << words << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------- graded_points

std::vector<double> sizes(const std::vector<double>& x) {
  std::vector<double> h;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) h.push_back(x[i + 1] - x[i]);
  return h;
}

TEST(MeshGenerators, graded_points_uniform_and_one_sided) {
  for (double scale : {1.0, 25e-6}) {
    const double a = -0.3 * scale, b = 1.7 * scale;
    const auto u = graded_points(a, b, 8, 0.0, 1.0);
    ASSERT_EQ(u.size(), 9u);
    EXPECT_EQ(u.front(), a);
    EXPECT_EQ(u.back(), b);
    for (double h : sizes(u)) EXPECT_NEAR(h, (b - a) / 8.0, 1e-14 * scale);

    for (double ratio : {1.05, 1.3, 2.0}) {
      const auto lo = graded_points(a, b, 12, a - scale, ratio);  // focus below a: clamped
      const auto hi = graded_points(a, b, 12, b, ratio);
      EXPECT_EQ(lo.front(), a);
      EXPECT_EQ(lo.back(), b);
      EXPECT_EQ(hi.front(), a);
      EXPECT_EQ(hi.back(), b);
      const auto hl = sizes(lo), hh = sizes(hi);
      for (std::size_t i = 0; i + 1 < hl.size(); ++i) {
        EXPECT_GT(hl[i], 0.0);
        EXPECT_NEAR(hl[i + 1] / hl[i], ratio, 1e-12) << "ratio " << ratio << " i " << i;
        EXPECT_NEAR(hh[i] / hh[i + 1], ratio, 1e-12) << "ratio " << ratio << " i " << i;
      }
    }
  }
}

TEST(MeshGenerators, graded_points_focus_inside_grows_both_ways) {
  const double ratio = 1.15, focus = 0.3;
  const auto x = graded_points(0.0, 1.0, 20, focus, ratio);
  ASSERT_EQ(x.size(), 21u);
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_EQ(x.back(), 1.0);
  const auto it = std::find(x.begin(), x.end(), focus);
  ASSERT_NE(it, x.end()) << "focus is not a node";
  const std::size_t k = std::size_t(it - x.begin());
  EXPECT_GT(k, 1u);
  EXPECT_LT(k, 19u);
  const auto h = sizes(x);
  for (std::size_t i = 0; i + 1 < h.size(); ++i) {
    EXPECT_GT(h[i], 0.0);
    if (i + 1 < k) {  // left of the focus
      EXPECT_NEAR(h[i] / h[i + 1], ratio, 1e-12) << i;
    }
    if (i >= k) {  // right of the focus
      EXPECT_NEAR(h[i + 1] / h[i], ratio, 1e-12) << i;
    }
  }
  // The two cells touching the focus differ by less than 2 ratio + 1.
  const double jump = std::max(h[k - 1] / h[k], h[k] / h[k - 1]);
  EXPECT_LT(jump, 2.0 * ratio + 1.0);
  std::printf("focus 0.3, n 20, ratio 1.15: %zu cells left, size jump at focus %.3f\n", k, jump);
}

TEST(MeshGenerators, graded_points_focus_near_an_end_snaps_instead_of_a_sliver) {
  const auto end = graded_points(0.0, 1.0, 10, 0.0, 1.2);
  for (double focus : {1e-9, 0.01}) {
    const auto x = graded_points(0.0, 1.0, 10, focus, 1.2);
    EXPECT_EQ(x, end) << "focus " << focus;
  }
  const auto far = graded_points(0.0, 1.0, 10, 1.0 - 1e-9, 1.2);
  EXPECT_EQ(far, graded_points(0.0, 1.0, 10, 1.0, 1.2));
  // Focus further in: a node, and no cell below half the one-sided smallest.
  const auto mid = graded_points(0.0, 1.0, 10, 0.05, 1.2);
  for (double h : sizes(mid)) EXPECT_GT(h, 0.5 * end[1]);
}

TEST(MeshGenerators, graded_points_many_cells_strong_grading_stay_finite) {
  const auto x = graded_points(0.0, 1.0, 4000, 0.5, 1.5);
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_EQ(x.back(), 1.0);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    ASSERT_TRUE(std::isfinite(x[i]));
    ASSERT_LE(x[i], x[i + 1]);
  }
  const auto one = graded_points(2.0, 3.0, 1, 2.5, 1.5);
  EXPECT_EQ(one, (std::vector<double>{2.0, 3.0}));
}

TEST(MeshGenerators, graded_points_rejects_bad_arguments) {
  expect_invalid([] { graded_points(0.0, 1.0, 0, 0.0, 1.0); }, "n must be >= 1");
  expect_invalid([] { graded_points(1.0, 1.0, 4, 0.0, 1.0); }, "b must be > a");
  expect_invalid([] { graded_points(0.0, 1.0, 4, 0.0, 0.9); }, "ratio must be");
  expect_invalid([] { graded_points(0.0, NAN, 4, 0.0, 1.0); }, "b must be finite");
  expect_invalid([] { graded_points(0.0, 1.0, 4, NAN, 1.0); }, "focus");
}

// ---------------------------------------------------------------- axis_points

TEST(MeshGenerators, axis_points_without_uniform_zone_sizes_the_focus_cell_to_h) {
  const double h = 0.01, ratio = 1.15;
  for (double focus : {0.0, 0.3, 1.0}) {
    const auto x = axis_points(0.0, 1.0, h, focus, ratio, 0.0);
    EXPECT_EQ(x, graded_points(0.0, 1.0, int(x.size()) - 1, focus, ratio)) << focus;
    const auto s = sizes(x);
    const auto it = std::lower_bound(x.begin(), x.end(), focus);
    const std::size_t k = std::min<std::size_t>(std::size_t(it - x.begin()), s.size() - 1);
    // The cell at the focus is within one growth step of h.
    EXPECT_LT(s[k], h * ratio * (1.0 + 1e-9)) << focus;
    EXPECT_GT(s[k], h / (2.0 * ratio + 1.0)) << focus;
  }
  const auto u = axis_points(0.0, 1.0, 0.1, 0.5, 1.0, 0.0);
  ASSERT_EQ(u.size(), 11u);
  for (double c : sizes(u)) EXPECT_NEAR(c, 0.1, 1e-12);
}

TEST(MeshGenerators, axis_points_keep_h_in_the_uniform_zone_and_grow_beyond) {
  // Substrate-like: r from the axis, uniform out to 37.5 um, element 1.5625 um.
  const double h = 1.5625e-6, ratio = 1.15, a = 0.0, b = 200e-6, u = 37.5e-6;
  const auto x = axis_points(a, b, h, 0.0, ratio, u);
  EXPECT_EQ(x.front(), a);
  EXPECT_EQ(x.back(), b);
  const auto s = sizes(x);
  std::size_t core = 0;
  while (core < x.size() && x[core] < u - 1e-3 * h) ++core;
  ASSERT_GT(core, 20u);
  EXPECT_NEAR(x[core], u, 1e-12 * b) << "the zone ends on a node";
  for (std::size_t i = 0; i < core; ++i) EXPECT_NEAR(s[i], u / double(core), 1e-9 * h);
  EXPECT_NEAR(s[0], h, 0.5 * h / double(core));
  // Beyond: a first cell no larger than h, then growth by the ratio.
  EXPECT_LE(s[core], h * (1.0 + 1e-9));
  for (std::size_t i = core; i + 1 < s.size(); ++i) EXPECT_NEAR(s[i + 1] / s[i], ratio, 1e-9);
  // Both sides of an interior focus, the zone clipped at the ends.
  const auto y = axis_points(-1.0, 1.0, 0.05, 0.2, 1.2, 0.5);
  for (double c : sizes(y)) EXPECT_GT(c, 0.5 * 0.05);
  EXPECT_NE(std::find(y.begin(), y.end(), -0.3), y.end());
  const auto all = axis_points(0.0, 1.0, 0.1, 0.5, 1.2, 10.0);  // zone covers everything
  ASSERT_EQ(all.size(), 11u);
  for (double c : sizes(all)) EXPECT_NEAR(c, 0.1, 1e-12);
}

TEST(MeshGenerators, axis_points_join_a_short_outer_part_instead_of_a_sliver) {
  const double h = 0.1;
  // The zone stops 0.03 (< h / 2) short of b: no cell of 0.03 at the end.
  const auto x = axis_points(0.0, 1.0, h, 0.0, 1.2, 0.97);
  EXPECT_EQ(x.back(), 1.0);
  for (double c : sizes(x)) EXPECT_GT(c, 0.5 * h);
  const auto y = axis_points(0.0, 1.0, h, 0.5, 1.2, 0.46);
  for (double c : sizes(y)) EXPECT_GT(c, 0.5 * h);
}

TEST(MeshGenerators, axis_points_rejects_bad_arguments) {
  expect_invalid([] { axis_points(1.0, 0.0, 0.1, 0.0, 1.1, 0.0); }, "b must be > a");
  expect_invalid([] { axis_points(0.0, 1.0, 0.0, 0.0, 1.1, 0.0); }, "h must be");
  expect_invalid([] { axis_points(0.0, 1.0, 0.1, 0.0, 0.9, 0.0); }, "ratio must be");
  expect_invalid([] { axis_points(0.0, 1.0, 0.1, NAN, 1.1, 0.0); }, "focus");
  expect_invalid([] { axis_points(0.0, 1.0, 0.1, 0.0, 1.1, -1.0); }, "uniform must be");
  expect_invalid([] { axis_points(0.0, 1.0, 0.1, 0.0, 1.1, INFINITY); }, "uniform must be");
}

TEST(MeshGenerators, point_list_blocks_reject_lists_that_do_not_increase) {
  const std::vector<double> good{0.0, 0.5, 1.0};
  expect_invalid([&] { axisym_rectangle({0.0, 0.5, 0.5}, good); }, "r must increase");
  expect_invalid([&] { axisym_rectangle({0.1, 0.5, 1.0}, good); }, "r must start on the axis");
  expect_invalid([&] { axisym_rectangle(good, {0.0}); }, "z needs at least 2 points");
  expect_invalid([&] { hex_box(good, good, {0.0, NAN}); }, "z must be finite");
  expect_invalid([&] { hex_box(good, {1.0, 0.0}, good); }, "y must increase");
  const HexMesh m = hex_box(good, {0.0, 0.2, 0.3, 1.0}, good);
  EXPECT_EQ(m.hexes.size(), 12u);
  const AxisymMesh r = axisym_rectangle(good, {-1.0, 0.0});
  EXPECT_EQ(r.quads.size(), 2u);
  EXPECT_NEAR(revolved_volume(r), pi, 1e-12);
}

// ---------------------------------------------------------------- 2D meshes

TEST(MeshGenerators, half_disc_orientation_tags_and_quality) {
  const double R = 20e-6, zc = 3e-6;
  for (int n : {2, 3, 4, 7, 10, 20}) {
    SCOPED_TRACE("elements_across_radius " + std::to_string(n));
    const AxisymMesh m = axisym_half_disc(R, zc, n);
    ASSERT_EQ(m.node_boundary.size(), m.nodes.size());
    const double sj = check_quads(m);
    const double er = edge_ratio(m);
    EXPECT_GE(sj, 0.75);
    EXPECT_LT(er, 3.0);
    check_all_nodes_used(m, m.quads);
    check_boundary_loop(m);
    for (std::size_t v = 0; v < m.nodes.size(); ++v) {
      const Vec2 p = m.nodes[v];
      EXPECT_GE(p.x(), 0.0);
      const bool on_axis = p.x() == 0.0;
      const bool on_arc = std::abs((p - Vec2(0.0, zc)).norm() - R) < 1e-12 * R;
      const std::uint32_t want = (on_axis ? boundary_x_min : 0u) | (on_arc ? boundary_curved : 0u);
      EXPECT_EQ(m.node_boundary[v], want) << "node " << v << " at " << p.transpose();
      EXPECT_LE((p - Vec2(0.0, zc)).norm(), R * (1.0 + 1e-12));
    }
    double arc = 0.0, axis = 0.0;
    for (std::size_t s = 0; s < m.boundary_segments.size(); ++s) {
      const auto [a, b] = m.boundary_segments[s];
      const double l = (m.nodes[b] - m.nodes[a]).norm();
      if (m.segment_boundary[s] == boundary_curved) arc += l;
      if (m.segment_boundary[s] == boundary_x_min) {
        axis += l;
        EXPECT_LT(m.nodes[b].y(), m.nodes[a].y()) << "axis walked upwards: normal not outward";
      }
    }
    EXPECT_NEAR(axis, 2.0 * R, 1e-12 * R);
    EXPECT_NEAR(arc, pi * R, 0.1 * pi * R);
    std::printf("half disc n=%2d: %4zu quads, min scaled Jacobian %.3f, edge ratio %.2f\n", n,
                m.quads.size(), sj, er);
  }
  EXPECT_EQ(axisym_half_disc(1.0, 0.0, 10).quads.size(), 168u);
}

TEST(MeshGenerators, half_disc_volume_converges_to_sphere) {
  const double R = 10e-6, exact = 4.0 / 3.0 * pi * R * R * R;
  double previous = INFINITY;
  int prev_n = 0;
  for (int n : {5, 10, 20, 40, 80}) {
    const double err = std::abs(revolved_volume(axisym_half_disc(R, -R, n)) - exact) / exact;
    EXPECT_LT(err, previous) << "n " << n;
    if (prev_n) {
      const double order = std::log(previous / err) / std::log(double(n) / prev_n);
      std::printf("half disc volume: n=%2d rel. error %.3e, observed order %.2f\n", n, err, order);
      EXPECT_GT(order, 1.5);
    } else {
      std::printf("half disc volume: n=%2d rel. error %.3e\n", n, err);
    }
    previous = err, prev_n = n;
  }
  EXPECT_LT(previous, 1e-3);
}

TEST(MeshGenerators, rectangle_graded_volume_and_tags) {
  Grading g;
  g.enabled = true;
  g.focus = Vec3(0.0, 40e-6, 0.0);  // (r, z): the impact point on the top face
  g.ratio = 1.1;
  const double r_max = 100e-6, z_min = -60e-6, z_max = 40e-6;
  const AxisymMesh m = axisym_rectangle(r_max, z_min, z_max, 12, 9, g);
  ASSERT_EQ(m.quads.size(), 108u);
  check_quads(m);
  check_all_nodes_used(m, m.quads);
  check_boundary_loop(m);
  const auto r = graded_points(0.0, r_max, 12, 0.0, 1.1);
  const auto z = graded_points(z_min, z_max, 9, z_max, 1.1);
  std::set<double> rs(r.begin(), r.end()), zs(z.begin(), z.end());
  for (std::size_t v = 0; v < m.nodes.size(); ++v) {
    const Vec2 p = m.nodes[v];
    EXPECT_TRUE(rs.count(p.x()) && zs.count(p.y()));
    const std::uint32_t want =
        (p.x() == 0.0 ? boundary_x_min : 0u) | (p.x() == r_max ? boundary_x_max : 0u) |
        (p.y() == z_min ? boundary_y_min : 0u) | (p.y() == z_max ? boundary_y_max : 0u);
    EXPECT_EQ(m.node_boundary[v], want);
  }
  std::map<std::uint32_t, int> count;
  for (auto t : m.segment_boundary) ++count[t];
  EXPECT_EQ(count[boundary_x_min], 9);
  EXPECT_EQ(count[boundary_x_max], 9);
  EXPECT_EQ(count[boundary_y_min], 12);
  EXPECT_EQ(count[boundary_y_max], 12);
  // Pappus is exact for straight-sided cells: the cylinder volume.
  const double exact = pi * r_max * r_max * (z_max - z_min);
  EXPECT_NEAR(revolved_volume(m), exact, 1e-12 * exact);
  // Without grading: uniform.
  const AxisymMesh u = axisym_rectangle(1.0, 0.0, 2.0, 4, 4, Grading{});
  EXPECT_NEAR(edge_ratio(u), 2.0, 1e-12);
}

TEST(MeshGenerators, axisymmetric_generators_reject_bad_arguments) {
  expect_invalid([] { axisym_half_disc(0.0, 0.0, 4); }, "radius must be");
  expect_invalid([] { axisym_half_disc(1.0, 0.0, 1); }, "elements_across_radius must be >= 2");
  expect_invalid([] { axisym_half_disc(1.0, INFINITY, 4); }, "z_centre must be finite");
  expect_invalid([] { axisym_rectangle(-1.0, 0.0, 1.0, 2, 2, {}); }, "r_max must be");
  expect_invalid([] { axisym_rectangle(1.0, 1.0, 0.0, 2, 2, {}); }, "z_max must be > z_min");
  expect_invalid([] { axisym_rectangle(1.0, 0.0, 1.0, 0, 2, {}); }, "n_r must be >= 1");
  expect_invalid([] { axisym_rectangle(1.0, 0.0, 1.0, 2, 0, {}); }, "n_z must be >= 1");
  Grading g;
  g.enabled = true;
  g.ratio = 0.5;
  expect_invalid([&] { axisym_rectangle(1.0, 0.0, 1.0, 2, 2, g); }, "grading.ratio");
}

// ---------------------------------------------------------------- 3D meshes

TEST(MeshGenerators, hex_sphere_orientation_tags_and_quality) {
  const double R = 15e-6;
  const Vec3 c(2e-6, -1e-6, 30e-6);
  for (Sector s : all_sectors) {
    for (int n : {2, 3, 5, 8}) {
      SCOPED_TRACE(std::string(sector_name(s)) + " n " + std::to_string(n));
      const HexMesh m = hex_sphere(R, c, n, s);
      ASSERT_EQ(m.node_boundary.size(), m.nodes.size());
      const double sj = check_hexes(m);
      const double er = edge_ratio(m);
      EXPECT_GE(sj, 0.6);
      EXPECT_LT(er, 3.0);
      check_all_nodes_used(m, m.hexes);
      const auto area = check_boundary_faces(m);
      const bool quarter = s == Sector::quarter, cut = s != Sector::full;
      for (std::size_t v = 0; v < m.nodes.size(); ++v) {
        const Vec3 p = m.nodes[v];
        const bool on_sphere = std::abs((p - c).norm() - R) < 1e-12 * R;
        const std::uint32_t want = (on_sphere ? boundary_curved : 0u) |
                                   (quarter && p.x() == c.x() ? boundary_x_min : 0u) |
                                   (cut && p.y() == c.y() ? boundary_y_min : 0u);
        EXPECT_EQ(m.node_boundary[v], want) << "node " << v;
        if (quarter) {
          EXPECT_GE(p.x(), c.x());
        }
        if (cut) {
          EXPECT_GE(p.y(), c.y());
        }
      }
      if (quarter) check_plane_faces(m, boundary_x_min, 0, c.x(), -1.0);
      if (cut) check_plane_faces(m, boundary_y_min, 1, c.y(), -1.0);
      for (std::size_t i = 0; i < m.boundary_faces.size(); ++i)
        if (m.face_boundary[i] == boundary_curved) {
          Vec3 mid = Vec3::Zero();
          for (int v : m.boundary_faces[i]) mid += 0.25 * m.nodes[v];
          EXPECT_GT(face_vector_area(m, m.boundary_faces[i]).dot(mid - c), 0.0);
        }
      EXPECT_EQ(area.count(boundary_curved), 1u);
      if (s == Sector::full) {
        EXPECT_EQ(area.size(), 1u);
      }
      if (n == 8 || n == 2)
        std::printf("hex sphere %-7s n=%d: %5zu hexes, min scaled Jacobian %.3f, edge ratio %.2f\n",
                    sector_name(s), n, m.hexes.size(), sj, er);
    }
  }
  EXPECT_EQ(hex_sphere(1.0, Vec3::Zero(), 10, Sector::full).hexes.size(), 5184u);
}

TEST(MeshGenerators, hex_sphere_volume_and_area_converge) {
  const double R = 25e-6;
  const double V = 4.0 / 3.0 * pi * R * R * R, A = 4.0 * pi * R * R;
  for (Sector s : {Sector::full, Sector::quarter}) {
    double prev_v = INFINITY, prev_a = INFINITY;
    int prev_n = 0;
    for (int n : {5, 10, 20, 40}) {
      if (s == Sector::full && n == 40) break;  // the quarter reaches it 4x cheaper
      const HexMesh m = hex_sphere(R, Vec3(0.0, 0.0, R), n, s);
      const double f = sector_fraction(s);
      const double ev = std::abs(mesh_volume(m) - f * V) / (f * V);
      double curved = 0.0;
      for (std::size_t i = 0; i < m.boundary_faces.size(); ++i)
        if (m.face_boundary[i] == boundary_curved) curved += face_area(m, m.boundary_faces[i]);
      const double ea = std::abs(curved - f * A) / (f * A);
      EXPECT_LT(ev, prev_v) << "n " << n;
      EXPECT_LT(ea, prev_a) << "n " << n;
      if (prev_n) {
        const double step = std::log(double(n) / prev_n);
        const double pv = std::log(prev_v / ev) / step, pa = std::log(prev_a / ea) / step;
        std::printf(
            "hex sphere %-7s n=%2d: volume error %.3e (order %.2f), area error %.3e "
            "(order %.2f)\n",
            sector_name(s), n, ev, pv, ea, pa);
        EXPECT_GT(pv, 1.5);
        EXPECT_GT(pa, 1.5);
      } else {
        std::printf("hex sphere %-7s n=%2d: volume error %.3e, area error %.3e\n", sector_name(s),
                    n, ev, ea);
      }
      prev_v = ev, prev_a = ea, prev_n = n;
    }
    EXPECT_LT(prev_v, 5e-3);
  }
}

TEST(MeshGenerators, hex_box_volume_tags_and_grading) {
  const Vec3 lo(-50e-6, -50e-6, -80e-6), hi(50e-6, 50e-6, 0.0);
  Grading g;
  g.enabled = true;
  g.focus = Vec3(0.0, 0.0, 0.0);
  g.ratio = 1.12;
  const HexMesh m = hex_box(lo, hi, 6, 5, 7, g);
  ASSERT_EQ(m.hexes.size(), 210u);
  const double sj = check_hexes(m);
  EXPECT_NEAR(sj, 1.0, 1e-12);
  check_all_nodes_used(m, m.hexes);
  const auto area = check_boundary_faces(m);
  const Vec3 d = hi - lo;
  EXPECT_NEAR(mesh_volume(m), d.prod(), 1e-12 * d.prod());
  EXPECT_NEAR(area.at(boundary_x_min), d.y() * d.z(), 1e-12 * d.y() * d.z());
  EXPECT_NEAR(area.at(boundary_z_max), d.x() * d.y(), 1e-12 * d.x() * d.y());
  const std::uint32_t tags[6] = {boundary_x_min, boundary_x_max, boundary_y_min,
                                 boundary_y_max, boundary_z_min, boundary_z_max};
  for (int axis = 0; axis < 3; ++axis) {
    check_plane_faces(m, tags[2 * axis], axis, lo[axis], -1.0);
    check_plane_faces(m, tags[2 * axis + 1], axis, hi[axis], 1.0);
  }
  for (std::size_t v = 0; v < m.nodes.size(); ++v) {
    std::uint32_t want = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (m.nodes[v][axis] == lo[axis]) want |= tags[2 * axis];
      if (m.nodes[v][axis] == hi[axis]) want |= tags[2 * axis + 1];
    }
    EXPECT_EQ(m.node_boundary[v], want);
  }
  const auto zs = graded_points(lo.z(), hi.z(), 7, 0.0, 1.12);
  std::set<double> z(zs.begin(), zs.end());
  for (const Vec3& p : m.nodes) EXPECT_TRUE(z.count(p.z()));
}

TEST(MeshGenerators, hex_box_200k_cells_is_fast) {
  const auto t0 = std::chrono::steady_clock::now();
  const HexMesh m = hex_box(Vec3::Zero(), Vec3(1e-4, 1e-4, 1e-4), 60, 60, 56, Grading{});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(m.hexes.size(), 201600u);
  EXPECT_EQ(m.boundary_faces.size(), 2u * (60 * 60 + 60 * 56 + 60 * 56));
  std::printf("hex_box 60x60x56 = %zu hexes in %.3f s\n", m.hexes.size(), seconds);
#if defined(NDEBUG) && !defined(__SANITIZE_ADDRESS__)
  EXPECT_LT(seconds, 1.0);
#endif
}

TEST(MeshGenerators, hex_cylinder_orientation_tags_volume) {
  const double R = 3e-3, z_min = 0.0, z_max = 15e-3;
  Grading axial;
  axial.enabled = true;
  axial.focus = Vec3(0.0, 0.0, z_min);  // the anvil contact end
  axial.ratio = 1.08;
  for (Sector s : all_sectors) {
    for (int n : {2, 3, 6}) {
      SCOPED_TRACE(std::string(sector_name(s)) + " n " + std::to_string(n));
      const HexMesh m = hex_cylinder(R, z_min, z_max, n, 2 * n, s, axial);
      const double sj = check_hexes(m);
      EXPECT_GE(sj, 0.75);
      check_all_nodes_used(m, m.hexes);
      const auto area = check_boundary_faces(m);
      const bool quarter = s == Sector::quarter, cut = s != Sector::full;
      for (std::size_t v = 0; v < m.nodes.size(); ++v) {
        const Vec3 p = m.nodes[v];
        const bool on_mantle = std::abs(std::hypot(p.x(), p.y()) - R) < 1e-12 * R;
        const std::uint32_t want =
            (on_mantle ? boundary_curved : 0u) | (quarter && p.x() == 0.0 ? boundary_x_min : 0u) |
            (cut && p.y() == 0.0 ? boundary_y_min : 0u) | (p.z() == z_min ? boundary_z_min : 0u) |
            (p.z() == z_max ? boundary_z_max : 0u);
        EXPECT_EQ(m.node_boundary[v], want) << "node " << v;
      }
      check_plane_faces(m, boundary_z_min, 2, z_min, -1.0);
      check_plane_faces(m, boundary_z_max, 2, z_max, 1.0);
      if (quarter) check_plane_faces(m, boundary_x_min, 0, 0.0, -1.0);
      if (cut) check_plane_faces(m, boundary_y_min, 1, 0.0, -1.0);
      // The section is the polygon through the equiangular rim nodes: its
      // k segments per layer span f 2 pi, and extrusion is exact.
      const double f = sector_fraction(s);
      int k = 0;
      for (auto t : m.face_boundary) k += t == boundary_curved;
      ASSERT_EQ(k % (2 * n), 0);
      k /= 2 * n;
      const double V = 0.5 * k * R * R * std::sin(f * 2.0 * pi / k) * (z_max - z_min);
      EXPECT_NEAR(mesh_volume(m), V, 1e-12 * V);
      // Flat ends: the polygonal section's area, the same at both ends.
      EXPECT_NEAR(area.at(boundary_z_min), area.at(boundary_z_max), 1e-12 * R * R);
      if (n == 6)
        std::printf("hex cylinder %-7s n=%d: %5zu hexes, min scaled Jacobian %.3f\n",
                    sector_name(s), n, m.hexes.size(), sj);
    }
  }
  double prev = INFINITY;
  for (int n : {5, 10, 20, 40}) {
    const HexMesh m = hex_cylinder(R, z_min, z_max, n, 2, Sector::quarter, Grading{});
    const double V = 0.25 * pi * R * R * (z_max - z_min);
    const double err = std::abs(mesh_volume(m) - V) / V;
    EXPECT_LT(err, prev);
    std::printf("hex cylinder quarter n=%2d: volume error %.3e\n", n, err);
    prev = err;
  }
}

TEST(MeshGenerators, no_duplicate_nodes_all_pairs) {
  for (int n : {2, 3, 4}) {
    check_no_duplicate_nodes(axisym_half_disc(1e-5, 0.0, n));
    for (Sector s : all_sectors) {
      check_no_duplicate_nodes(hex_sphere(1e-5, Vec3(0.0, 0.0, 1e-5), n, s));
      check_no_duplicate_nodes(hex_cylinder(1e-5, -1e-5, 2e-5, n, 3, s, Grading{}));
    }
  }
  check_no_duplicate_nodes(axisym_rectangle(1.0, 0.0, 1.0, 5, 4, Grading{}));
  check_no_duplicate_nodes(hex_box(Vec3::Zero(), Vec3::Ones(), 3, 4, 5, Grading{}));
}

TEST(MeshGenerators, hex_generators_reject_bad_arguments) {
  expect_invalid([] { hex_sphere(-1.0, Vec3::Zero(), 4, Sector::full); }, "radius must be");
  expect_invalid([] { hex_sphere(1.0, Vec3::Zero(), 1, Sector::full); },
                 "elements_across_radius must be >= 2");
  expect_invalid([] { hex_sphere(1.0, Vec3(NAN, 0, 0), 4, Sector::full); }, "centre");
  expect_invalid([] { hex_box(Vec3::Zero(), Vec3(1, 0, 1), 2, 2, 2, {}); }, "hi.y must be > lo.y");
  expect_invalid([] { hex_box(Vec3::Zero(), Vec3::Ones(), 2, 0, 2, {}); }, "ny must be >= 1");
  Grading g;
  g.enabled = true;
  g.ratio = 0.99;
  expect_invalid([&] { hex_box(Vec3::Zero(), Vec3::Ones(), 2, 2, 2, g); }, "grading.ratio");
  expect_invalid([] { hex_cylinder(0.0, 0.0, 1.0, 4, 4, Sector::full, {}); }, "radius must be");
  expect_invalid([] { hex_cylinder(1.0, 1.0, 1.0, 4, 4, Sector::full, {}); },
                 "z_max must be > z_min");
  expect_invalid([] { hex_cylinder(1.0, 0.0, 1.0, 1, 4, Sector::full, {}); },
                 "elements_across_radius must be >= 2");
  expect_invalid([] { hex_cylinder(1.0, 0.0, 1.0, 4, 0, Sector::full, {}); }, "n_z must be >= 1");
}

}  // namespace
}  // namespace splat
