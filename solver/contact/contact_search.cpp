#include "solver/contact/contact_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

#include <Eigen/Eigenvalues>

#include "solver/common/parallel.hpp"

namespace splat {

ContactSurface make_contact_surface(DetectionKind kind, std::vector<std::array<int, 4>> faces) {
  ContactSurface s;
  s.kind = kind;
  s.faces = std::move(faces);
  const int npf = s.nodes_per_face();
  for (const auto& f : s.faces) s.nodes.insert(s.nodes.end(), f.begin(), f.begin() + npf);
  std::sort(s.nodes.begin(), s.nodes.end());
  s.nodes.erase(std::unique(s.nodes.begin(), s.nodes.end()), s.nodes.end());
  s.node_face_offsets.assign(s.nodes.size() + 1, 0);
  auto index_of = [&](int node) {
    return static_cast<int>(std::lower_bound(s.nodes.begin(), s.nodes.end(), node) -
                            s.nodes.begin());
  };
  for (const auto& f : s.faces) {
    for (int k = 0; k < npf; ++k) ++s.node_face_offsets[index_of(f[k]) + 1];
  }
  for (std::size_t k = 0; k < s.nodes.size(); ++k) {
    s.node_face_offsets[k + 1] += s.node_face_offsets[k];
  }
  s.node_face_entries.resize(s.node_face_offsets.back());
  std::vector<int> fill(s.node_face_offsets.begin(), s.node_face_offsets.end() - 1);
  for (std::size_t fi = 0; fi < s.faces.size(); ++fi) {
    for (int k = 0; k < npf; ++k) {
      s.node_face_entries[fill[index_of(s.faces[fi][k])]++] = static_cast<int>(fi);
    }
  }
  return s;
}

ContactSurface make_particle_surface(const std::vector<int>& particles,
                                     const std::vector<double>& radius) {
  std::vector<std::size_t> order(particles.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return particles[a] < particles[b]; });
  std::vector<std::array<int, 4>> faces;
  std::vector<double> r;
  for (std::size_t i : order) {
    faces.push_back({particles[i], -1, -1, -1});
    r.push_back(radius[i]);
  }
  ContactSurface s = make_contact_surface(DetectionKind::particle_pinball, std::move(faces));
  s.radius = std::move(r);  // nodes ascending = faces ascending (distinct particles)
  return s;
}

void set_pinball_shape(ContactSurface& s, int k, const Mat3& F) {
  const std::size_t n = s.nodes.size();
  if (s.inverse_stretch.size() != n) s.inverse_stretch.assign(n, Mat3::Identity());
  if (s.reach.size() != n) s.reach = s.radius;
  const std::size_t kk = static_cast<std::size_t>(k);
  const double R = s.radius[kk];
  const double deformation = (F - Mat3::Identity()).norm();
  if (!(deformation > k_round_pinball_deformation) || !(F.determinant() > 0.0)) {
    s.inverse_stretch[kk] = Mat3::Identity();
    s.reach[kk] = R;
    return;
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(F.transpose() * F, Eigen::EigenvaluesOnly);
  const double largest_stretch = std::sqrt(std::max(eig.eigenvalues()(2), 0.0));
  s.inverse_stretch[kk] = F.inverse();
  s.reach[kk] = R * std::clamp(largest_stretch, 1.0, k_max_pinball_stretch);
}

namespace {

// Slave nodes per chunk of the bucket search, and the face and slave counts
// from which its loops run in parallel (a slave node tests tens of faces, a
// face only computes its box).
constexpr std::size_t search_chunk = 64;
constexpr std::size_t min_parallel_slaves = 128;
constexpr std::size_t min_parallel_faces = 512;

// Curvature radius R_c of master particle f's cap (at least its pinball's
// reach), m; 0 without a cap.
double cap_radius(const ContactSurface& s, int f) {
  if (s.cap_normal.empty() || s.cap_normal[static_cast<std::size_t>(f)].squaredNorm() == 0.0) {
    return 0.0;
  }
  return std::max(k_cap_curvature * s.node_radius(f), s.node_reach(f));
}

// Geometry of point p against master particle f of surface s: its cap when
// it has one and p is outside its tangent plane, else its pinball (header).
PairGeometry project_on_particle(const Vec3& p, const ContactSurface& s, int f,
                                 const std::vector<Vec3>& x) {
  PairGeometry g;
  const Vec3 d = p - x[s.faces[f][0]];
  const double dist = d.norm();
  if (!(dist > 0.0)) return g;
  g.valid = true;
  const Vec3 n = s.cap_normal.empty() ? Vec3::Zero() : s.cap_normal[static_cast<std::size_t>(f)];
  const double along = d.dot(n);
  if (along > 0.0) {
    // The cap: a sphere of radius R_c through the pinball's top along n.
    const double top = s.radius_along(f, n);
    const double curvature_radius = cap_radius(s, f);
    const Vec3 e = d + (curvature_radius - top) * n;
    const double e_norm = e.norm();
    g.normal = e / e_norm;
    g.gap = e_norm - curvature_radius;
  } else {
    g.normal = d / dist;
    g.gap = dist - s.radius_along(f, g.normal);
  }
  // Any unit vector normal to n, then the third of the triad.
  const Vec3 a = std::abs(g.normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  g.tangent1 = g.normal.cross(a).normalized();
  g.tangent2 = g.normal.cross(g.tangent1);
  g.weights = {1.0, 0.0, 0.0, 0.0};
  return g;
}

std::array<Vec3, 4> face_points(const ContactSurface& s, int f, const std::vector<Vec3>& x) {
  const auto& ids = s.faces[f];
  if (s.kind == DetectionKind::particle_pinball)
    return {x[ids[0]], x[ids[0]], x[ids[0]], x[ids[0]]};
  if (s.kind == DetectionKind::node_on_segment) return {x[ids[0]], x[ids[1]], x[ids[1]], x[ids[1]]};
  return {x[ids[0]], x[ids[1]], x[ids[2]], x[ids[3]]};
}

PairGeometry project(const ContactSurface& s, int f, const Vec3& p, const std::vector<Vec3>& x) {
  if (s.kind == DetectionKind::particle_pinball) {
    return project_on_particle(p, s, f, x);
  }
  const auto pts = face_points(s, f, x);
  if (s.kind == DetectionKind::node_on_segment) return project_on_segment(p, pts[0], pts[1]);
  return project_on_quad(p, pts);
}

// Whether candidate a is better than b for the same slave node: a projection
// inside the face first, then the smaller |gap|, then the lower face index
// (so that the choice does not depend on the order faces are tested in).
bool better(const DetectedPair& a, const DetectedPair& b) {
  const bool ina = a.geometry.distance_outside <= 1e-9;
  const bool inb = b.geometry.distance_outside <= 1e-9;
  if (ina != inb) return ina;
  const double ga = std::abs(a.geometry.gap), gb = std::abs(b.geometry.gap);
  if (ga != gb) return ga < gb;
  return a.face < b.face;
}

// Tests slave node k against face f and keeps the better pair in `best`, or,
// with `all`, appends every pair in range to it.
void consider(const ContactSurface& master, int f, const ContactSurface& slave, int k,
              const std::vector<Vec3>& x, const SearchSettings& st, double size, DetectedPair& best,
              bool& found, std::vector<DetectedPair>* all) {
  DetectedPair c;
  c.slave = k;
  c.face = f;
  c.geometry = project(master, f, x[slave.nodes[k]], x);
  if (!c.geometry.valid) return;
  c.geometry.gap -= slave.radius_along(k, c.geometry.normal);
  if (c.geometry.distance_outside > st.outside_tolerance) return;
  if (c.geometry.gap > st.search_margin * size || c.geometry.gap < -st.capture_depth * size) return;
  if (all) {
    all->push_back(c);
    return;
  }
  if (!found || better(c, best)) {
    best = c;
    found = true;
  }
}

// Pinball master: all candidates of one slave, smallest gap (then face) first.
void append_all(std::vector<DetectedPair>& all, std::vector<DetectedPair>& out) {
  std::sort(all.begin(), all.end(), [](const DetectedPair& a, const DetectedPair& b) {
    if (a.geometry.gap != b.geometry.gap) return a.geometry.gap < b.geometry.gap;
    return a.face < b.face;
  });
  for (std::size_t i = 0; i < all.size(); ++i) {
    all[i].primary = i == 0;
    out.push_back(all[i]);
  }
  all.clear();
}

}  // namespace

double face_size(const ContactSurface& s, int f, const std::vector<Vec3>& x) {
  if (s.kind == DetectionKind::particle_pinball) return 2.0 * s.node_reach(f);
  const auto pts = face_points(s, f, x);
  if (s.kind == DetectionKind::node_on_segment) return (pts[1] - pts[0]).norm();
  return std::sqrt(quad_area(pts));
}

double slave_node_area(const ContactSurface& s, int k, const std::vector<Vec3>& x) {
  if (!s.radius.empty()) return std::numbers::pi * s.radius[k] * s.radius[k];
  double area = 0.0;
  for (int e = s.node_face_offsets[k]; e < s.node_face_offsets[k + 1]; ++e) {
    const auto pts = face_points(s, s.node_face_entries[e], x);
    if (s.kind == DetectionKind::node_on_segment) {
      area += 0.5 * (pts[1] - pts[0]).norm();
    } else {
      area += 0.25 * quad_area(pts);
    }
  }
  if (s.kind == DetectionKind::node_on_segment) area *= x[s.nodes[k]].x();  // r, per radian
  return area;
}

std::optional<DetectedPair> pair_on_face(const ContactSurface& master, int f,
                                         const ContactSurface& slave, int k,
                                         const std::vector<Vec3>& x, const SearchSettings& st,
                                         double max_gap) {
  DetectedPair c;
  c.slave = k;
  c.face = f;
  c.geometry = project(master, f, x[slave.nodes[k]], x);
  if (!c.geometry.valid) return std::nullopt;
  c.geometry.gap -= slave.radius_along(k, c.geometry.normal);
  const double size = face_size(master, f, x);
  if (c.geometry.distance_outside > st.outside_tolerance) return std::nullopt;
  if (c.geometry.gap > max_gap || c.geometry.gap < -st.capture_depth * size) return std::nullopt;
  return c;
}

double face_area(const ContactSurface& s, int f, const std::vector<Vec3>& x) {
  const auto pts = face_points(s, f, x);
  if (s.kind == DetectionKind::node_on_segment) {
    return (pts[1] - pts[0]).norm() * 0.5 * (pts[0].x() + pts[1].x());
  }
  return quad_area(pts);
}

namespace {

// Y = 1 - A0 / A, 0 where the surface has not grown (or has no area).
double expansion(double A0, double A) {
  return A > A0 && A0 > 0.0 && std::isfinite(A) ? 1.0 - A0 / A : 0.0;
}

}  // namespace

double face_surface_expansion(const ContactSurface& s, int f, const std::vector<Vec3>& x0,
                              const std::vector<Vec3>& x) {
  if (s.kind == DetectionKind::particle_pinball || f < 0) return 0.0;
  return expansion(face_area(s, f, x0), face_area(s, f, x));
}

double node_surface_expansion(const ContactSurface& s, int k, const std::vector<Vec3>& x0,
                              const std::vector<Vec3>& x) {
  if (s.kind == DetectionKind::particle_pinball || !s.radius.empty()) return 0.0;
  double A0 = 0.0, A = 0.0;
  for (int e = s.node_face_offsets[k]; e < s.node_face_offsets[k + 1]; ++e) {
    A0 += face_area(s, s.node_face_entries[e], x0);
    A += face_area(s, s.node_face_entries[e], x);
  }
  return expansion(A0, A);
}

std::vector<DetectedPair> find_pairs_all_pairs(const ContactSurface& master,
                                               const ContactSurface& slave,
                                               const std::vector<Vec3>& x,
                                               const SearchSettings& st) {
  std::vector<DetectedPair> out;
  std::vector<double> sizes(master.faces.size());
  for (std::size_t f = 0; f < sizes.size(); ++f)
    sizes[f] = face_size(master, static_cast<int>(f), x);
  const bool pinball = master.kind == DetectionKind::particle_pinball;
  std::vector<DetectedPair> all;
  for (std::size_t k = 0; k < slave.nodes.size(); ++k) {
    DetectedPair best;
    bool found = false;
    for (std::size_t f = 0; f < master.faces.size(); ++f) {
      consider(master, static_cast<int>(f), slave, static_cast<int>(k), x, st, sizes[f], best,
               found, pinball ? &all : nullptr);
    }
    if (pinball) append_all(all, out);
    if (found) out.push_back(best);
  }
  return out;
}

std::vector<DetectedPair> find_pairs_buckets(const ContactSurface& master,
                                             const ContactSurface& slave,
                                             const std::vector<Vec3>& x, const SearchSettings& st) {
  std::vector<DetectedPair> out;
  const std::size_t nf = master.faces.size();
  if (nf == 0 || slave.nodes.empty()) return out;
  const int npf = master.nodes_per_face();
  const double pinball = master.kind == DetectionKind::particle_pinball ? 1.0 : 0.0;
  double slave_reach = 0.0;
  for (std::size_t k = 0; k < slave.nodes.size(); ++k) {
    slave_reach = std::max(slave_reach, slave.node_reach(static_cast<int>(k)));
  }
  // Face bounding boxes grown by the capture range (the projection tolerance
  // included), so a slave node within range of a face lies inside its box.
  std::vector<Vec3> lo(nf), hi(nf);
  std::vector<double> sizes(nf);
  double cell = 0.0;
  // Only faces whose grown box meets the slave nodes' bounding box can pair
  // with any of them: the others stay out of the grid (an SPH block's
  // thousands of particle "faces" far from the ball cost most of the search).
  Vec3 slave_lo = x[slave.nodes[0]], slave_hi = slave_lo;
  for (int n : slave.nodes) {
    slave_lo = slave_lo.cwiseMin(x[n]);
    slave_hi = slave_hi.cwiseMax(x[n]);
  }
  std::vector<std::uint8_t> near(nf, 0);
  const double reach =
      std::max(st.capture_depth, st.search_margin) + 2.0 * st.outside_tolerance + 1e-6;
  // Faces are independent; max and || do not depend on the order.
  const long long nfl = static_cast<long long>(nf);
  const bool parallel_faces = nf >= min_parallel_faces;
  SPLAT_PARALLEL_PRAGMA(omp parallel for schedule(static) reduction(max : cell) if (parallel_faces))
  for (long long fl = 0; fl < nfl; ++fl) {
    const std::size_t f = static_cast<std::size_t>(fl);
    sizes[f] = face_size(master, static_cast<int>(f), x);
    Vec3 a = x[master.faces[f][0]], b = a;
    for (int k = 1; k < npf; ++k) {
      a = a.cwiseMin(x[master.faces[f][k]]);
      b = b.cwiseMax(x[master.faces[f][k]]);
    }
    // The projection tolerance is in local units: a fraction of the largest
    // edge; a master pinball reaches its radius further (a cap its curvature
    // radius: the points within a gap G of a cap lie within R_c + G of its
    // particle), a slave pinball its own.
    const double own_reach = std::max(0.5 * sizes[f], cap_radius(master, static_cast<int>(f)));
    const double grow =
        reach * std::max(sizes[f], (b - a).maxCoeff()) + own_reach * pinball + slave_reach;
    lo[f] = a - Vec3::Constant(grow);
    hi[f] = b + Vec3::Constant(grow);
    near[f] =
        (lo[f].array() <= slave_hi.array()).all() && (hi[f].array() >= slave_lo.array()).all();
    if (near[f]) cell = std::max(cell, (hi[f] - lo[f]).maxCoeff());
  }
  if (std::none_of(near.begin(), near.end(), [](std::uint8_t b) { return b != 0; })) return out;
  if (!(cell > 0.0) || !std::isfinite(cell)) return find_pairs_all_pairs(master, slave, x, st);
  const bool planar = master.kind == DetectionKind::node_on_segment;
  auto cell_of = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    constexpr std::int64_t off = 1 << 20, mask = (1 << 21) - 1;
    return ((i + off) & mask) | (((j + off) & mask) << 21) | (((k + off) & mask) << 42);
  };
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  grid.reserve(2 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    if (!near[f]) continue;
    const std::int64_t i0 = cell_of(lo[f].x()), i1 = cell_of(hi[f].x());
    const std::int64_t j0 = cell_of(lo[f].y()), j1 = cell_of(hi[f].y());
    const std::int64_t k0 = planar ? 0 : cell_of(lo[f].z()), k1 = planar ? 0 : cell_of(hi[f].z());
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t k = k0; k <= k1; ++k) grid[key(i, j, k)].push_back(static_cast<int>(f));
  }
  // Slave nodes in fixed chunks, in parallel; the chunks' pairs are joined in
  // chunk order, so the list is the same for any thread count.
  const std::size_t ns = slave.nodes.size();
  std::vector<std::vector<DetectedPair>> chunk_pairs((ns + search_chunk - 1) / search_chunk);
  for_each_block(ns, search_chunk, min_parallel_slaves, [&](std::size_t first, std::size_t last) {
    std::vector<DetectedPair>& part = chunk_pairs[first / search_chunk];
    std::vector<DetectedPair> all;
    for (std::size_t s = first; s < last; ++s) {
      const Vec3& p = x[slave.nodes[s]];
      const auto it = grid.find(key(cell_of(p.x()), cell_of(p.y()), planar ? 0 : cell_of(p.z())));
      if (it == grid.end()) continue;
      DetectedPair best;
      bool found = false;
      for (int f : it->second) {
        if ((p.array() < lo[f].array()).any() || (p.array() > hi[f].array()).any()) continue;
        consider(master, f, slave, static_cast<int>(s), x, st, sizes[f], best, found,
                 pinball > 0.0 ? &all : nullptr);
      }
      if (pinball > 0.0) append_all(all, part);
      if (found) part.push_back(best);
    }
  });
  for (const std::vector<DetectedPair>& part : chunk_pairs) {
    out.insert(out.end(), part.begin(), part.end());
  }
  return out;
}

}  // namespace splat
