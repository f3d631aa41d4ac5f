#include "solver/core/physics_guard.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <unordered_map>
#include <vector>

#include "solver/mesh/mesh.hpp"

namespace splat {
namespace {

struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -Vec3::Constant(std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool contains(const Vec3& p) const {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  }
};

// Crossing-number test of (r, z) point p in the quadrilateral x[0..3].
bool inside_quad(const Vec3& p, const std::array<Vec3, 4>& x) {
  bool in = false;
  for (int a = 0, b = 3; a < 4; b = a++) {
    const double ya = x[a].y(), yb = x[b].y();
    if ((ya > p.y()) != (yb > p.y())) {
      const double r = x[a].x() + (p.y() - ya) / (yb - ya) * (x[b].x() - x[a].x());
      if (p.x() < r) in = !in;
    }
  }
  return in;
}

// Whether a ray from p along d crosses triangle (a, b, c) (Moeller-Trumbore).
bool ray_crosses(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 q = d.cross(e2);
  const double det = e1.dot(q);
  if (std::abs(det) < 1e-300) return false;
  const Vec3 s = p - a;
  const double u = s.dot(q) / det;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 r = s.cross(e1);
  const double v = d.dot(r) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  return e2.dot(r) / det > 0.0;
}

// Crossing-number test of p in the hexahedron x[0..7], faces split in two
// triangles; the ray direction is skewed off the mesh axes.
bool inside_hex(const Vec3& p, const std::array<Vec3, 8>& x) {
  const Vec3 d = Vec3(1.0, 0.3127, 0.1713).normalized();
  int crossings = 0;
  for (const auto& f : k_hex_faces) {
    crossings += ray_crosses(p, d, x[f[0]], x[f[1]], x[f[2]]);
    crossings += ray_crosses(p, d, x[f[0]], x[f[2]], x[f[3]]);
  }
  return crossings % 2 == 1;
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Distance from p to triangle (a, b, c) (closest point by region, Ericson 2005, 5.1.5).
double triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (n2 > 0.0) {
    const Vec3 q = p - n * ((p - a).dot(n) / n2);
    const double w_a = (b - q).cross(c - q).dot(n), w_b = (c - q).cross(a - q).dot(n),
                 w_c = (a - q).cross(b - q).dot(n);
    if (w_a >= 0.0 && w_b >= 0.0 && w_c >= 0.0) return (p - q).norm();
  }
  return std::min(
      {segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

// Cell (i, j, l) of point p on a grid of cube cells of size `cell`, and the
// hash of a cell (distinct cells may share one).
std::array<long long, 3> cell_of(const Vec3& p, double cell) {
  return {static_cast<long long>(std::floor(p.x() / cell)),
          static_cast<long long>(std::floor(p.y() / cell)),
          static_cast<long long>(std::floor(p.z() / cell))};
}
long long cell_hash(long long i, long long j, long long l) {
  return (i * 73856093LL) ^ (j * 19349663LL) ^ (l * 83492791LL);
}

// Uniform grid of element bounding boxes.
class ElementGrid {
 public:
  // Boxes spanning more than k_max_span cells along an axis (an element
  // stretched far beyond the mean) are kept apart and tested for every point.
  static constexpr long long k_max_span = 8;

  ElementGrid(const std::vector<Box>& boxes, const std::vector<int>& ids, double cell)
      : cell_(cell) {
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const auto lo = key3(boxes[k].lo), hi = key3(boxes[k].hi);
      if (hi[0] - lo[0] > k_max_span || hi[1] - lo[1] > k_max_span || hi[2] - lo[2] > k_max_span) {
        large_.push_back(ids[k]);
        continue;
      }
      for (long long i = lo[0]; i <= hi[0]; ++i)
        for (long long j = lo[1]; j <= hi[1]; ++j)
          for (long long l = lo[2]; l <= hi[2]; ++l) cells_[hash(i, j, l)].push_back(ids[k]);
    }
  }
  // The elements whose box may hold p: its cell's and the large ones.
  void candidates(const Vec3& p, std::vector<int>& out) const {
    out = large_;
    const auto k = key3(p);
    const auto it = cells_.find(hash(k[0], k[1], k[2]));
    if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
  }

 private:
  std::array<long long, 3> key3(const Vec3& p) const { return cell_of(p, cell_); }
  static long long hash(long long i, long long j, long long l) { return cell_hash(i, j, l); }
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;
  std::vector<int> large_;
};

bool node_live(const Model& model, std::size_t i) {
  return model.nodes.mass[i] > 0.0;
}

// Distance from p to the live master faces of interface c.
double surface_distance(const Model& model, const ContactInterface& c, const Vec3& p) {
  const ContactSurface& s = c.master_surface();
  const std::vector<Vec3>& x = model.nodes.x;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (!c.master_face_live(f)) continue;
    const auto& ids = s.faces[f];
    if (s.kind == DetectionKind::node_on_segment) {
      if (!node_live(model, ids[0]) || !node_live(model, ids[1])) continue;
      best = std::min(best, segment_distance(p, x[ids[0]], x[ids[1]]));
    } else if (s.kind == DetectionKind::node_on_quad) {
      if (!node_live(model, ids[0]) || !node_live(model, ids[1]) || !node_live(model, ids[2]) ||
          !node_live(model, ids[3]))
        continue;
      best = std::min({best, triangle_distance(p, x[ids[0]], x[ids[1]], x[ids[2]]),
                       triangle_distance(p, x[ids[0]], x[ids[2]], x[ids[3]])});
    }
  }
  return best;
}

// A live particle of an SPH body: with mass and not deactivated.
bool sph_live(const Model& model, const SphBody& body, std::size_t i) {
  return node_live(model, i) && body.active[i - body.node_begin] != 0;
}

// Live particles of an SPH body near `region`, with their mirror images
// across the body's symmetry planes, hashed in cells of size `reach`.
class ParticleGrid {
 public:
  ParticleGrid(const Model& model, const SphBody& body, const Box& region, double reach)
      : cell_(reach) {
    const auto ops = static_cast<std::uint8_t>(1u << body.planes.size());
    for (std::size_t j = body.node_begin; j < body.node_end; ++j) {
      if (!sph_live(model, body, j) || !model.nodes.x[j].allFinite()) continue;
      for (std::uint8_t op = 0; op < ops; ++op) {
        const Vec3 p = mirror_point(body.planes, op, model.nodes.x[j]);
        if ((p.array() < region.lo.array() - reach).any() ||
            (p.array() > region.hi.array() + reach).any())
          continue;
        const auto k = key3(p);
        cells_[hash(k[0], k[1], k[2])].push_back(p);
      }
    }
  }
  // Calls f(q, distance) for each point q within `reach` of p (once: two
  // of the 27 cells around p may share a hash bucket).
  template <class F>
  void for_each_near(const Vec3& p, F&& f) const {
    const auto k = key3(p);
    std::array<long long, 27> keys{};
    std::size_t n = 0;
    for (long long i = k[0] - 1; i <= k[0] + 1; ++i)
      for (long long j = k[1] - 1; j <= k[1] + 1; ++j)
        for (long long l = k[2] - 1; l <= k[2] + 1; ++l) keys[n++] = hash(i, j, l);
    std::sort(keys.begin(), keys.end());
    for (std::size_t c = 0; c < keys.size(); ++c) {
      if (c > 0 && keys[c] == keys[c - 1]) continue;
      const auto it = cells_.find(keys[c]);
      if (it == cells_.end()) continue;
      for (const Vec3& q : it->second) {
        const double r = (q - p).norm();
        if (r <= cell_) f(q, r);
      }
    }
  }

 private:
  std::array<long long, 3> key3(const Vec3& p) const { return cell_of(p, cell_); }
  static long long hash(long long i, long long j, long long l) { return cell_hash(i, j, l); }
  double cell_;
  std::unordered_map<long long, std::vector<Vec3>> cells_;
};

// SPH substrate (the particle is then SPH too): pinball overlap and
// enclosure of each live particle of the impacting body (physics_guard.hpp).
Interpenetration measure_sph_interpenetration(const Model& model, const GuardInput& in) {
  Interpenetration out;
  out.checked = true;
  out.sph = true;
  const std::vector<Vec3>& x = model.nodes.x;
  const SphBody& sub =
      model.sph_bodies[model.body_refs[static_cast<std::size_t>(in.substrate)].index];
  const BodyRef& p_ref = model.body_refs[static_cast<std::size_t>(in.particle)];
  const SphBody* ball = p_ref.sph ? &model.sph_bodies[p_ref.index] : nullptr;
  auto live = [&](std::size_t i) {
    return (ball ? sph_live(model, *ball, i) : node_live(model, i)) && x[i].allFinite();
  };
  const double d_s = sub.spacing;
  const double touch = 0.5 * d_s + (ball ? 0.5 * ball->spacing : 0.0);
  const double reach = std::max(k_enclosure_radius * d_s, touch);
  const std::size_t p_begin = body_node_begin(model, static_cast<std::size_t>(in.particle));
  const std::size_t p_end = body_node_end(model, static_cast<std::size_t>(in.particle));
  Box particle_box;
  for (std::size_t i = p_begin; i < p_end; ++i) {
    if (live(i)) particle_box.add(x[i]);
  }
  if (!(d_s > 0.0) || !particle_box.lo.allFinite() || !particle_box.hi.allFinite()) return out;
  const ParticleGrid grid(model, sub, particle_box, reach);
  for (std::size_t i = p_begin; i < p_end; ++i) {
    if (!live(i)) continue;
    double nearest = std::numeric_limits<double>::infinity();
    Vec3 direction_sum = Vec3::Zero();
    int around = 0;
    grid.for_each_near(x[i], [&](const Vec3& q, double r) {
      nearest = std::min(nearest, r);
      if (r > 0.0) direction_sum += (q - x[i]) / r;
      ++around;
    });
    const double overlap = std::max(touch - nearest, 0.0);
    const bool enclosed =
        around >= k_enclosure_neighbours && direction_sum.norm() < k_enclosure_balance * around;
    out.max_depth = std::max(out.max_depth, overlap);
    out.max_ratio = std::max(out.max_ratio, overlap / d_s);
    if (overlap > k_interpenetration_limit * d_s || enclosed) ++out.nodes_through;
  }
  return out;
}

}  // namespace

Interpenetration measure_interpenetration(const Model& model, const GuardInput& in) {
  Interpenetration out;
  if (in.particle < 0 || in.substrate < 0) return out;
  const BodyRef& sub_ref = model.body_refs[static_cast<std::size_t>(in.substrate)];
  if (sub_ref.sph) return measure_sph_interpenetration(model, in);
  if (in.contact < 0) return out;
  const ContactInterface& contact = model.contacts[static_cast<std::size_t>(in.contact)];
  if (contact.master_surface().kind == DetectionKind::particle_pinball) return out;
  out.checked = true;
  const FeBody& sub = model.bodies[sub_ref.index];
  const std::size_t p_begin = body_node_begin(model, static_cast<std::size_t>(in.particle));
  const std::size_t p_end = body_node_end(model, static_cast<std::size_t>(in.particle));
  const std::vector<Vec3>& x = model.nodes.x;
  Box particle_box;
  for (std::size_t i = p_begin; i < p_end; ++i) {
    if (node_live(model, i) && x[i].allFinite()) particle_box.add(x[i]);
  }
  if (!particle_box.lo.allFinite() || !particle_box.hi.allFinite()) return out;
  // Live substrate elements that overlap the particle's box.
  const int npe = sub.nodes_per_element();
  std::vector<Box> boxes;
  std::vector<int> ids;
  double size_sum = 0.0;
  for (std::size_t e = 0; e < sub.num_elements(); ++e) {
    if (!sub.active[e]) continue;
    Box b;
    for (int a = 0; a < npe; ++a) b.add(x[sub.conn[e][a]]);
    if (!b.lo.allFinite() || !b.hi.allFinite()) continue;
    if ((b.hi.array() < particle_box.lo.array()).any() ||
        (b.lo.array() > particle_box.hi.array()).any())
      continue;
    boxes.push_back(b);
    ids.push_back(static_cast<int>(e));
    size_sum += (b.hi - b.lo).maxCoeff();
  }
  const double cell = ids.empty() ? 0.0 : size_sum / static_cast<double>(ids.size());
  if (!(cell > 0.0) || !std::isfinite(cell)) return out;
  const ElementGrid grid(boxes, ids, cell);
  std::vector<Box> box_of(sub.num_elements());
  for (std::size_t k = 0; k < ids.size(); ++k) box_of[ids[k]] = boxes[k];
  std::vector<int> candidates;
  for (std::size_t i = p_begin; i < p_end; ++i) {
    if (!node_live(model, i) || !x[i].allFinite()) continue;
    grid.candidates(x[i], candidates);
    for (int e : candidates) {
      if (!box_of[e].contains(x[i])) continue;
      bool inside = false;
      if (sub.kind == ElementKind::quad4_axisym) {
        inside = inside_quad(
            x[i], {x[sub.conn[e][0]], x[sub.conn[e][1]], x[sub.conn[e][2]], x[sub.conn[e][3]]});
      } else {
        std::array<Vec3, 8> xe;
        for (int a = 0; a < 8; ++a) xe[a] = x[sub.conn[e][a]];
        inside = inside_hex(x[i], xe);
      }
      if (!inside) continue;
      const double depth = surface_distance(model, contact, x[i]);
      if (!std::isfinite(depth)) break;
      const double h = std::max(sub.char_length[e], 1e-300);
      out.max_depth = std::max(out.max_depth, depth);
      out.max_ratio = std::max(out.max_ratio, depth / h);
      if (depth > k_interpenetration_limit * h) ++out.nodes_through;
      break;
    }
  }
  return out;
}

Interpenetration worse(const Interpenetration& a, const Interpenetration& b) {
  if (a.nodes_through != b.nodes_through) return a.nodes_through > b.nodes_through ? a : b;
  return b.max_ratio > a.max_ratio ? b : a;
}

std::optional<StopReason> check_physics(const Model& model, const EnergyBudget& energy,
                                        const GuardInput& in, GuardFigures& figures,
                                        std::string& reason, const Interpenetration& during) {
  Interpenetration p = worse(measure_interpenetration(model, in), during);
  p.checked = p.checked || during.checked;
  figures.interpenetration_checked = p.checked;
  figures.max_interpenetration = p.max_depth;
  figures.interpenetration_ratio = p.max_ratio;
  figures.nodes_through = p.nodes_through;
  const double reference =
      std::max(energy.initial_total + std::max(energy.external_work, 0.0), 1e-300);
  figures.eroded_energy_fraction = energy.eroded / reference;
  figures.internal_energy_fraction = energy.internal / reference;
  figures.plastic_work_excess =
      (energy.plastic_work - energy.internal - std::max(energy.eroded, 0.0)) / reference;
  char buf[320];
  if (p.nodes_through > 0) {
    const char* format =
        p.sph ? "interpenetration: %lld particle(s) through the SPH substrate (pinballs "
                "overlapping by more than %.2g spacing, or enclosed by substrate particles; "
                "deepest overlap %.3g m, %.2f spacings); the contact let the particle through"
              : "interpenetration: %lld particle node(s) inside the substrate deeper than %.2g "
                "of the local element size (deepest %.3g m, %.2f element sizes); the contact "
                "let the particle through";
    std::snprintf(buf, sizeof buf, format, p.nodes_through, k_interpenetration_limit, p.max_depth,
                  p.max_ratio);
    reason = buf;
    if (p.time >= 0.0) {
      std::snprintf(buf, sizeof buf, " (at t = %.4g s)", p.time);
      reason += buf;
    }
    return figures.failed = StopReason::interpenetration;
  }
  if (energy.eroded < -in.energy_limit * reference) {
    std::snprintf(buf, sizeof buf,
                  "negative eroded energy: %.3g of the reference energy (limit -%.3g); the "
                  "erosion bookkeeping broke",
                  figures.eroded_energy_fraction, in.energy_limit);
    reason = buf;
    return figures.failed = StopReason::negative_eroded_energy;
  }
  if (energy.internal < -in.energy_limit * reference) {
    std::snprintf(buf, sizeof buf,
                  "negative internal energy: %.3g of the reference energy (limit -%.3g)",
                  figures.internal_energy_fraction, in.energy_limit);
    reason = buf;
    return figures.failed = StopReason::negative_internal_energy;
  }
  if (figures.plastic_work_excess > in.energy_limit) {
    std::snprintf(buf, sizeof buf,
                  "plastic work exceeds the internal energy by %.3g of the reference energy "
                  "(limit %.3g): the strength law booked more plastic work and heat than the "
                  "stresses received (strain increments that reverse from step to step, or far "
                  "larger than the yield strain)",
                  figures.plastic_work_excess, in.energy_limit);
    reason = buf;
    return figures.failed = StopReason::plastic_work_excess;
  }
  figures.failed.reset();
  return std::nullopt;
}

}  // namespace splat
