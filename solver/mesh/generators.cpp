#include "solver/mesh/generators.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace splat {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

[[noreturn]] void fail(const char* where, const std::string& rule) {
  throw std::invalid_argument(std::string(where) + ": " + rule);
}

void require_positive(const char* where, const char* name, double v) {
  if (!(v > 0.0) || !std::isfinite(v))
    fail(where, std::string(name) + " must be finite and > 0 (got " + num(v) + ")");
}

void require_finite(const char* where, const char* name, double v) {
  if (!std::isfinite(v)) fail(where, std::string(name) + " must be finite (got " + num(v) + ")");
}

void require_count(const char* where, const char* name, int v, int min) {
  if (v < min)
    fail(where, std::string(name) + " must be >= " + std::to_string(min) + " (got " +
                    std::to_string(v) + ")");
}

void require_interval(const char* where, const char* lo_name, double lo, const char* hi_name,
                      double hi) {
  require_finite(where, lo_name, lo);
  require_finite(where, hi_name, hi);
  if (!(hi > lo))
    fail(where, std::string(hi_name) + " must be > " + lo_name + " (got " + num(hi) +
                    " <= " + num(lo) + ")");
}

void require_grading(const char* where, const Grading& g) {
  if (!g.enabled) return;
  if (!(g.ratio >= 1.0) || !std::isfinite(g.ratio))
    fail(where, "grading.ratio must be finite and >= 1 (got " + num(g.ratio) + ")");
  if (!g.focus.allFinite()) fail(where, "grading.focus must be finite");
}

// log(e^x - 1) for x > 0 without overflow.
double log_expm1(double x) {
  return x > 30.0 ? x + std::log1p(-std::exp(-x)) : std::log(std::expm1(x));
}

// log of 1 + r + ... + r^(n-1) = (r^n - 1) / (r - 1), r = e^lr: the length of
// n geometrically growing cells in units of the first.
double log_series(int n, double lr) {
  return lr == 0.0 ? std::log(double(n)) : log_expm1(n * lr) - log_expm1(lr);
}

// Fraction (r^i - 1) / (r^n - 1) of an interval covered by the first i of n
// cells growing by r = e^lr, written so that large n lr cannot overflow.
double geometric_fraction(int i, int n, double lr) {
  if (i >= n) return 1.0;
  if (lr == 0.0) return double(i) / double(n);
  return std::exp(double(i - n) * lr) * std::expm1(-double(i) * lr) / std::expm1(-double(n) * lr);
}

std::vector<double> uniform_or_graded(double a, double b, int n, bool enabled, double focus,
                                      double ratio) {
  return graded_points(a, b, n, enabled ? focus : a, enabled ? ratio : 1.0);
}

// Boundary segments of a mesh whose node_boundary is set: an edge whose two
// nodes share a bit lies on that boundary (true for the convex, structured
// primitives built here: no boundary-to-boundary chords). Keeping the CCW
// quad's own node order puts the outward normal on the right.
void add_boundary_segments(AxisymMesh& m) {
  m.boundary_segments.clear();
  m.segment_boundary.clear();
  for (const auto& q : m.quads) {
    for (int e = 0; e < 4; ++e) {
      const int a = q[e], b = q[(e + 1) % 4];
      const std::uint32_t bits = m.node_boundary[a] & m.node_boundary[b];
      if (bits == 0) continue;
      if (std::popcount(bits) != 1)
        throw std::logic_error("add_boundary_segments: segment on two boundaries");
      m.boundary_segments.push_back({a, b});
      m.segment_boundary.push_back(bits);
    }
  }
}

// As add_boundary_segments, for hexahedron faces whose four nodes share a bit.
void add_boundary_faces(HexMesh& m) {
  m.boundary_faces.clear();
  m.face_boundary.clear();
  for (const auto& h : m.hexes) {
    for (const auto& f : k_hex_faces) {
      const std::uint32_t bits = m.node_boundary[h[f[0]]] & m.node_boundary[h[f[1]]] &
                                 m.node_boundary[h[f[2]]] & m.node_boundary[h[f[3]]];
      if (bits == 0) continue;
      if (std::popcount(bits) != 1)
        throw std::logic_error("add_boundary_faces: face on two boundaries");
      m.boundary_faces.push_back({h[f[0]], h[f[1]], h[f[2]], h[f[3]]});
      m.face_boundary.push_back(bits);
    }
  }
}

// Renumber so that only nodes used by `cells` remain, in their original order.
template <class Point, std::size_t K>
void drop_unused_nodes(std::vector<Point>& nodes, std::vector<std::uint32_t>& bits,
                       std::vector<std::array<int, K>>& cells) {
  std::vector<int> new_id(nodes.size(), -1);
  for (const auto& c : cells)
    for (int v : c) new_id[v] = 0;
  int next = 0;
  for (std::size_t v = 0; v < nodes.size(); ++v) {
    if (new_id[v] < 0) continue;
    new_id[v] = next;
    nodes[next] = nodes[v];
    bits[next] = bits[v];
    ++next;
  }
  nodes.resize(next);
  bits.resize(next);
  for (auto& c : cells)
    for (int& v : c) v = new_id[v];
}

// Layout of an O-grid with n elements along a radius: n_core cells from the
// centre to a core face, then n_shell layers out to the surface. The core is
// the lattice [-n_core, n_core]^d scaled to half-width core_fraction * radius
// and rounded by `bulge` towards the inscribed ball, so that the cells where
// core and shell blocks meet have angles near 120 degrees instead of 90/135.
// The numbers were tuned (over n = 2..40) for the largest minimum scaled
// Jacobian while keeping longest / shortest edge below 2.6.
struct OGridShape {
  int n_core = 1;
  int n_shell = 1;
  double core_fraction = 0.5;  // core half-width / radius, -
  double bulge = 0.0;          // 0 = cube core, 1 = ball core, -
};

OGridShape ogrid_shape(int n_across_radius, int dim) {
  OGridShape s;
  s.n_core = std::clamp(int(std::lround(0.6 * n_across_radius)), 1, n_across_radius - 1);
  s.n_shell = n_across_radius - s.n_core;
  s.core_fraction = 0.5;
  s.bulge = dim == 2 ? 0.4 : 0.5;
  return s;
}

// Smooth maps of the square (cube) [-1, 1]^d onto the unit disc (ball) that
// keep the coordinate planes and send the boundary onto the circle (sphere).
Vec2 square_to_disc(const Vec2& p) {
  return {p.x() * std::sqrt(1.0 - 0.5 * p.y() * p.y()),
          p.y() * std::sqrt(1.0 - 0.5 * p.x() * p.x())};
}

Vec3 cube_to_ball(const Vec3& p) {
  const double x2 = p.x() * p.x(), y2 = p.y() * p.y(), z2 = p.z() * p.z();
  return {p.x() * std::sqrt(1.0 - 0.5 * (y2 + z2) + y2 * z2 / 3.0),
          p.y() * std::sqrt(1.0 - 0.5 * (z2 + x2) + z2 * x2 / 3.0),
          p.z() * std::sqrt(1.0 - 0.5 * (x2 + y2) + x2 * y2 / 3.0)};
}

// Position along a core face of lattice index i in [-n, n] on the surface:
// equiangular, tan(pi/4 i/n), exactly 0 and +-1 at the middle and the ends.
double equiangular(int i, int n) {
  const int k = std::abs(i);
  const double t = k == n ? 1.0 : std::tan(0.25 * std::numbers::pi * double(k) / double(n));
  return i < 0 ? -t : t;
}

// 2D O-grid of the disc of `radius` about the origin, optionally only x >= 0
// and/or y >= 0, with x_min / y_min on the kept cut lines and curved on the rim.
struct DiscSection {
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 4>> quads;  // counter-clockwise
  std::vector<std::uint32_t> bits;
};

DiscSection ogrid_disc(double radius, int n_across_radius, bool keep_x_pos, bool keep_y_pos) {
  const OGridShape sh = ogrid_shape(n_across_radius, 2);
  const int c = sh.n_core, L = sh.n_shell, m = 2 * c + 1;
  const double a = sh.core_fraction * radius;
  auto core_id = [&](int i, int j) { return (i + c) + m * (j + c); };
  std::vector<int> surface_id(std::size_t(m) * m, -1);
  int n_surface = 0;
  for (int j = -c; j <= c; ++j)
    for (int i = -c; i <= c; ++i)
      if (std::max(std::abs(i), std::abs(j)) == c) surface_id[core_id(i, j)] = n_surface++;

  DiscSection s;
  const std::size_t n_nodes = std::size_t(m) * m + std::size_t(n_surface) * L;
  s.nodes.resize(n_nodes);
  s.bits.assign(n_nodes, boundary_none);
  auto cut_bits = [&](int i, int j) {
    return (keep_x_pos && i == 0 ? boundary_x_min : 0u) |
           (keep_y_pos && j == 0 ? boundary_y_min : 0u);
  };
  for (int j = -c; j <= c; ++j) {
    for (int i = -c; i <= c; ++i) {
      const Vec2 xi(double(i) / double(c), double(j) / double(c));
      const Vec2 p_core = a * ((1.0 - sh.bulge) * xi + sh.bulge * square_to_disc(xi));
      s.nodes[core_id(i, j)] = p_core;
      s.bits[core_id(i, j)] = cut_bits(i, j);
      const int sid = surface_id[core_id(i, j)];
      if (sid < 0) continue;
      const Vec2 q = radius * Vec2(equiangular(i, c), equiangular(j, c)).normalized();
      for (int l = 1; l <= L; ++l) {
        const std::size_t id = std::size_t(m) * m + std::size_t(sid) * L + (l - 1);
        s.nodes[id] = l == L ? q : Vec2(p_core + (q - p_core) * (double(l) / double(L)));
        s.bits[id] = cut_bits(i, j) | (l == L ? boundary_curved : 0u);
      }
    }
  }
  auto node = [&](int i, int j, int l) {
    return l == 0 ? core_id(i, j) : m * m + surface_id[core_id(i, j)] * L + (l - 1);
  };
  // Twice the lattice centroid decides which half-planes a cell is in.
  auto keep = [&](int x2, int y2) { return (!keep_x_pos || x2 > 0) && (!keep_y_pos || y2 > 0); };
  for (int j = -c; j < c; ++j)
    for (int i = -c; i < c; ++i)
      if (keep(2 * i + 1, 2 * j + 1))
        s.quads.push_back(
            {node(i, j, 0), node(i + 1, j, 0), node(i + 1, j + 1, 0), node(i, j + 1, 0)});
  // Shell block per core face with outward normal n; tangent e = n turned
  // clockwise, so (tangent, layer) is counter-clockwise.
  constexpr std::array<std::array<int, 2>, 4> normals = {{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
  for (const auto& n : normals) {
    const int ex = n[1], ey = -n[0];
    for (int t = -c; t < c; ++t) {
      if (!keep(2 * c * n[0] + (2 * t + 1) * ex, 2 * c * n[1] + (2 * t + 1) * ey)) continue;
      const int i0 = c * n[0] + t * ex, j0 = c * n[1] + t * ey;
      const int i1 = i0 + ex, j1 = j0 + ey;
      for (int l = 0; l < L; ++l)
        s.quads.push_back(
            {node(i0, j0, l), node(i1, j1, l), node(i1, j1, l + 1), node(i0, j0, l + 1)});
    }
  }
  drop_unused_nodes(s.nodes, s.bits, s.quads);
  return s;
}

}  // namespace

std::vector<double> graded_points(double a, double b, int n, double focus, double ratio) {
  const char* where = "graded_points";
  require_interval(where, "a", a, "b", b);
  require_count(where, "n", n, 1);
  if (!(ratio >= 1.0) || !std::isfinite(ratio))
    fail(where, "ratio must be finite and >= 1 (got " + num(ratio) + ")");
  if (std::isnan(focus)) fail(where, "focus must not be NaN");

  const double length = b - a;
  const double lr = std::log(ratio);
  double f = std::clamp(focus, a, b);
  if (lr > 0.0 && f > a && f < b) {
    const double h_end = length * std::exp(-log_series(n, lr));  // smallest one-sided cell
    if (n == 1 || f - a < 0.5 * h_end || b - f < 0.5 * h_end) f = (f - a <= b - f) ? a : b;
  }
  std::vector<double> x(std::size_t(n) + 1);
  if (lr == 0.0 || f == a) {
    for (int i = 0; i <= n; ++i) x[i] = a + length * geometric_fraction(i, n, lr);
  } else if (f == b) {
    for (int i = 0; i <= n; ++i) x[i] = b - length * geometric_fraction(n - i, n, lr);
  } else {
    // Focus inside: n_left cells on [a, f], n - n_left on [f, b], chosen so
    // that the two cells touching the focus are as alike as possible.
    const double left = f - a, right = b - f;
    int n_left = 1;
    double best = INFINITY;
    for (int k = 1; k < n; ++k) {
      const double mismatch =
          std::abs(std::log(left) - log_series(k, lr) - std::log(right) + log_series(n - k, lr));
      if (mismatch < best) best = mismatch, n_left = k;
    }
    const int n_right = n - n_left;
    for (int i = 0; i <= n_left; ++i) x[i] = f - left * geometric_fraction(n_left - i, n_left, lr);
    for (int i = 0; i <= n_right; ++i)
      x[n_left + i] = f + right * geometric_fraction(i, n_right, lr);
    x[n_left] = f;
  }
  x.front() = a;
  x.back() = b;
  return x;
}

namespace {

// Cells over a length l growing by `ratio` from a first cell of at most h
// (uniform cells of about h when ratio is 1).
int growing_cells(double l, double h, double ratio) {
  if (l <= 0.0) return 0;
  if (ratio <= 1.0 + 1e-12) return std::max(1, static_cast<int>(std::lround(l / h)));
  return std::max(1,
                  static_cast<int>(std::ceil(std::log1p(l * (ratio - 1.0) / h) / std::log(ratio))));
}

void require_increasing(const char* where, const char* name, const std::vector<double>& x) {
  if (x.size() < 2) fail(where, std::string(name) + " needs at least 2 points");
  for (std::size_t i = 0; i < x.size(); ++i) {
    require_finite(where, name, x[i]);
    if (i > 0 && !(x[i] > x[i - 1])) fail(where, std::string(name) + " must increase");
  }
}

}  // namespace

std::vector<double> axis_points(double a, double b, double h, double focus, double ratio,
                                double uniform) {
  const char* where = "axis_points";
  require_interval(where, "a", a, "b", b);
  require_positive(where, "h", h);
  if (!(ratio >= 1.0) || !std::isfinite(ratio))
    fail(where, "ratio must be finite and >= 1 (got " + num(ratio) + ")");
  if (std::isnan(focus)) fail(where, "focus must not be NaN");
  if (!(uniform >= 0.0) || !std::isfinite(uniform))
    fail(where, "uniform must be finite and >= 0 (got " + num(uniform) + ")");
  const double f = std::clamp(focus, a, b);
  if (uniform == 0.0) {
    const int n =
        ratio <= 1.0 + 1e-12
            ? growing_cells(b - a, h, 1.0)
            : std::max(1, growing_cells(f - a, h, ratio) + growing_cells(b - f, h, ratio));
    return graded_points(a, b, n, f, ratio);
  }
  double lo = std::max(a, f - uniform), hi = std::min(b, f + uniform);
  if (lo - a < 0.5 * h) lo = a;
  if (b - hi < 0.5 * h) hi = b;
  const double lr = std::log(ratio);
  std::vector<double> x;
  const int n_left = growing_cells(lo - a, h, ratio);
  for (int i = n_left; i > 0; --i) x.push_back(lo - (lo - a) * geometric_fraction(i, n_left, lr));
  const int n_core = std::max(1, static_cast<int>(std::lround((hi - lo) / h)));
  for (int i = 0; i < n_core; ++i) x.push_back(lo + (hi - lo) * double(i) / double(n_core));
  const int n_right = growing_cells(b - hi, h, ratio);
  for (int i = 0; i < n_right; ++i) x.push_back(hi + (b - hi) * geometric_fraction(i, n_right, lr));
  x.push_back(b);
  x.front() = a;
  return x;
}

AxisymMesh axisym_half_disc(double radius, double z_centre, int elements_across_radius) {
  const char* where = "axisym_half_disc";
  require_positive(where, "radius", radius);
  require_finite(where, "z_centre", z_centre);
  require_count(where, "elements_across_radius", elements_across_radius, 2);

  DiscSection s = ogrid_disc(radius, elements_across_radius, true, false);
  AxisymMesh m;
  m.nodes = std::move(s.nodes);
  for (Vec2& p : m.nodes) p.y() += z_centre;
  m.quads = std::move(s.quads);
  m.node_boundary = std::move(s.bits);
  add_boundary_segments(m);
  return m;
}

AxisymMesh axisym_rectangle(double r_max, double z_min, double z_max, int n_r, int n_z,
                            const Grading& grading) {
  const char* where = "axisym_rectangle";
  require_positive(where, "r_max", r_max);
  require_interval(where, "z_min", z_min, "z_max", z_max);
  require_count(where, "n_r", n_r, 1);
  require_count(where, "n_z", n_z, 1);
  require_grading(where, grading);

  const std::vector<double> r =
      uniform_or_graded(0.0, r_max, n_r, grading.enabled, grading.focus.x(), grading.ratio);
  const std::vector<double> z =
      uniform_or_graded(z_min, z_max, n_z, grading.enabled, grading.focus.y(), grading.ratio);
  return axisym_rectangle(r, z);
}

AxisymMesh axisym_rectangle(const std::vector<double>& r, const std::vector<double>& z) {
  const char* where = "axisym_rectangle";
  require_increasing(where, "r", r);
  require_increasing(where, "z", z);
  if (r.front() != 0.0) fail(where, "r must start on the axis (0)");
  const int n_r = int(r.size()) - 1, n_z = int(z.size()) - 1;
  AxisymMesh m;
  const int nr1 = n_r + 1;
  m.nodes.reserve(std::size_t(nr1) * (n_z + 1));
  m.node_boundary.reserve(m.nodes.capacity());
  for (int j = 0; j <= n_z; ++j) {
    for (int i = 0; i <= n_r; ++i) {
      m.nodes.emplace_back(r[i], z[j]);
      m.node_boundary.push_back((i == 0 ? boundary_x_min : 0u) | (i == n_r ? boundary_x_max : 0u) |
                                (j == 0 ? boundary_y_min : 0u) | (j == n_z ? boundary_y_max : 0u));
    }
  }
  m.quads.reserve(std::size_t(n_r) * n_z);
  for (int j = 0; j < n_z; ++j)
    for (int i = 0; i < n_r; ++i) {
      const int v = i + nr1 * j;
      m.quads.push_back({v, v + 1, v + 1 + nr1, v + nr1});
    }
  add_boundary_segments(m);
  return m;
}

HexMesh hex_sphere(double radius, Vec3 centre, int elements_across_radius, Sector sector) {
  const char* where = "hex_sphere";
  require_positive(where, "radius", radius);
  if (!centre.allFinite()) fail(where, "centre must be finite");
  require_count(where, "elements_across_radius", elements_across_radius, 2);

  const bool keep_y_pos = sector != Sector::full, keep_x_pos = sector == Sector::quarter;
  const OGridShape sh = ogrid_shape(elements_across_radius, 3);
  const int c = sh.n_core, L = sh.n_shell, m = 2 * c + 1;
  const double a = sh.core_fraction * radius;
  auto core_id = [&](int i, int j, int k) { return (i + c) + m * ((j + c) + m * (k + c)); };
  const std::size_t n_core_nodes = std::size_t(m) * m * m;
  std::vector<int> surface_id(n_core_nodes, -1);
  int n_surface = 0;
  for (int k = -c; k <= c; ++k)
    for (int j = -c; j <= c; ++j)
      for (int i = -c; i <= c; ++i)
        if (std::max({std::abs(i), std::abs(j), std::abs(k)}) == c)
          surface_id[core_id(i, j, k)] = n_surface++;

  HexMesh mesh;
  const std::size_t n_nodes = n_core_nodes + std::size_t(n_surface) * L;
  mesh.nodes.resize(n_nodes);
  mesh.node_boundary.assign(n_nodes, boundary_none);
  for (int k = -c; k <= c; ++k) {
    for (int j = -c; j <= c; ++j) {
      for (int i = -c; i <= c; ++i) {
        const int id0 = core_id(i, j, k);
        const Vec3 xi = Vec3(double(i), double(j), double(k)) / double(c);
        const Vec3 p_core = a * ((1.0 - sh.bulge) * xi + sh.bulge * cube_to_ball(xi));
        const std::uint32_t cut = (keep_x_pos && i == 0 ? boundary_x_min : 0u) |
                                  (keep_y_pos && j == 0 ? boundary_y_min : 0u);
        mesh.nodes[id0] = p_core;
        mesh.node_boundary[id0] = cut;
        const int sid = surface_id[id0];
        if (sid < 0) continue;
        const Vec3 q =
            radius * Vec3(equiangular(i, c), equiangular(j, c), equiangular(k, c)).normalized();
        for (int l = 1; l <= L; ++l) {
          const std::size_t id = n_core_nodes + std::size_t(sid) * L + (l - 1);
          mesh.nodes[id] = l == L ? q : Vec3(p_core + (q - p_core) * (double(l) / double(L)));
          mesh.node_boundary[id] = cut | (l == L ? boundary_curved : 0u);
        }
      }
    }
  }
  auto node = [&](const Eigen::Vector3i& p, int l) {
    const int id0 = core_id(p.x(), p.y(), p.z());
    return l == 0 ? id0 : int(n_core_nodes) + surface_id[id0] * L + (l - 1);
  };
  auto keep = [&](const Eigen::Vector3i& twice_centroid) {
    return (!keep_x_pos || twice_centroid.x() > 0) && (!keep_y_pos || twice_centroid.y() > 0);
  };
  for (int k = -c; k < c; ++k)
    for (int j = -c; j < c; ++j)
      for (int i = -c; i < c; ++i) {
        if (!keep(Eigen::Vector3i(2 * i + 1, 2 * j + 1, 2 * k + 1))) continue;
        const Eigen::Vector3i p(i, j, k);
        std::array<int, 8> h{};
        for (int v = 0; v < 8; ++v)
          h[v] = node(p + Eigen::Vector3i(((v + 1) >> 1) & 1, (v >> 1) & 1, v >> 2), 0);
        mesh.hexes.push_back(h);
      }
  // Shell block per core face: tangents (e1, e2) with e1 x e2 = outward n, so
  // (e1, e2, layer) is a right-handed unit cube.
  const Eigen::Vector3i X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  const std::array<std::array<Eigen::Vector3i, 3>, 6> frames = {
      {{X, Y, Z}, {Y, Z, X}, {Z, X, Y}, {Y, X, -Z}, {Z, Y, -X}, {X, Z, -Y}}};
  for (const auto& [e1, e2, n] : frames) {
    for (int t2 = -c; t2 < c; ++t2) {
      for (int t1 = -c; t1 < c; ++t1) {
        if (!keep(2 * c * n + (2 * t1 + 1) * e1 + (2 * t2 + 1) * e2)) continue;
        const Eigen::Vector3i p = c * n + t1 * e1 + t2 * e2;
        for (int l = 0; l < L; ++l) {
          std::array<int, 8> h{};
          for (int v = 0; v < 8; ++v)
            h[v] = node(p + (((v + 1) >> 1) & 1) * e1 + ((v >> 1) & 1) * e2, l + (v >> 2));
          mesh.hexes.push_back(h);
        }
      }
    }
  }
  drop_unused_nodes(mesh.nodes, mesh.node_boundary, mesh.hexes);
  for (Vec3& p : mesh.nodes) p += centre;
  add_boundary_faces(mesh);
  return mesh;
}

HexMesh hex_box(Vec3 lo, Vec3 hi, int nx, int ny, int nz, const Grading& grading) {
  const char* where = "hex_box";
  require_interval(where, "lo.x", lo.x(), "hi.x", hi.x());
  require_interval(where, "lo.y", lo.y(), "hi.y", hi.y());
  require_interval(where, "lo.z", lo.z(), "hi.z", hi.z());
  require_count(where, "nx", nx, 1);
  require_count(where, "ny", ny, 1);
  require_count(where, "nz", nz, 1);
  require_grading(where, grading);

  const bool g = grading.enabled;
  const std::vector<double> x =
      uniform_or_graded(lo.x(), hi.x(), nx, g, grading.focus.x(), grading.ratio);
  const std::vector<double> y =
      uniform_or_graded(lo.y(), hi.y(), ny, g, grading.focus.y(), grading.ratio);
  const std::vector<double> z =
      uniform_or_graded(lo.z(), hi.z(), nz, g, grading.focus.z(), grading.ratio);
  return hex_box(x, y, z);
}

HexMesh hex_box(const std::vector<double>& x, const std::vector<double>& y,
                const std::vector<double>& z) {
  const char* where = "hex_box";
  require_increasing(where, "x", x);
  require_increasing(where, "y", y);
  require_increasing(where, "z", z);
  const int nx = int(x.size()) - 1, ny = int(y.size()) - 1, nz = int(z.size()) - 1;
  HexMesh m;
  const std::size_t n_nodes = std::size_t(nx + 1) * (ny + 1) * (nz + 1);
  m.nodes.reserve(n_nodes);
  m.node_boundary.reserve(n_nodes);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        m.nodes.emplace_back(x[i], y[j], z[k]);
        m.node_boundary.push_back((i == 0 ? boundary_x_min : 0u) | (i == nx ? boundary_x_max : 0u) |
                                  (j == 0 ? boundary_y_min : 0u) | (j == ny ? boundary_y_max : 0u) |
                                  (k == 0 ? boundary_z_min : 0u) | (k == nz ? boundary_z_max : 0u));
      }
  const int sx = 1, sy = nx + 1, sz = (nx + 1) * (ny + 1);
  m.hexes.reserve(std::size_t(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int v = i * sx + j * sy + k * sz;
        m.hexes.push_back(
            {v, v + sx, v + sx + sy, v + sy, v + sz, v + sx + sz, v + sx + sy + sz, v + sy + sz});
      }
  add_boundary_faces(m);
  return m;
}

HexMesh hex_cylinder(double radius, double z_min, double z_max, int elements_across_radius, int n_z,
                     Sector sector, const Grading& axial) {
  const char* where = "hex_cylinder";
  require_positive(where, "radius", radius);
  require_interval(where, "z_min", z_min, "z_max", z_max);
  require_count(where, "elements_across_radius", elements_across_radius, 2);
  require_count(where, "n_z", n_z, 1);
  require_grading(where, axial);

  const DiscSection s =
      ogrid_disc(radius, elements_across_radius, sector == Sector::quarter, sector != Sector::full);
  const std::vector<double> z =
      uniform_or_graded(z_min, z_max, n_z, axial.enabled, axial.focus.z(), axial.ratio);
  // Numbered along the axis first (node (v, k) is v (n_z + 1) + k, element
  // (q, k) is q n_z + k): consecutive elements of a column have consecutive
  // nodes, the node runs the element loop loads as whole vectors
  // (FeBody::node_run); the O-grid's rows are too short for that.
  HexMesh m;
  const int n2 = int(s.nodes.size());
  m.nodes.reserve(std::size_t(n2) * (n_z + 1));
  m.node_boundary.reserve(m.nodes.capacity());
  for (int v = 0; v < n2; ++v)
    for (int k = 0; k <= n_z; ++k) {
      m.nodes.emplace_back(s.nodes[v].x(), s.nodes[v].y(), z[k]);
      m.node_boundary.push_back(s.bits[v] | (k == 0 ? boundary_z_min : 0u) |
                                (k == n_z ? boundary_z_max : 0u));
    }
  m.hexes.reserve(s.quads.size() * n_z);
  const int stride = n_z + 1;
  for (const auto& q : s.quads)
    for (int k = 0; k < n_z; ++k) {
      m.hexes.push_back({q[0] * stride + k, q[1] * stride + k, q[2] * stride + k, q[3] * stride + k,
                         q[0] * stride + k + 1, q[1] * stride + k + 1, q[2] * stride + k + 1,
                         q[3] * stride + k + 1});
    }
  add_boundary_faces(m);
  return m;
}

}  // namespace splat
