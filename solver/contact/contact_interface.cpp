#include "solver/contact/contact_interface.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>

namespace splat {

ContactInterface::ContactInterface(std::string master_body, std::string slave_body,
                                   ContactSurface master, ContactSurface slave,
                                   ContactSettings settings, bool axisymmetric,
                                   std::size_t node_count)
    : master_body_(std::move(master_body)),
      slave_body_(std::move(slave_body)),
      master_(std::move(master)),
      slave_(std::move(slave)),
      settings_(std::move(settings)),
      axisymmetric_(axisymmetric),
      local_(node_count, -1),
      touched_(slave_.nodes.size(), 0),
      pressed_(slave_.nodes.size(), 0),
      link_state_(slave_.nodes.size(), LinkState::none),
      link_work_(slave_.nodes.size(), 0.0),
      link_area_(slave_.nodes.size(), 0.0),
      link_rate_(slave_.nodes.size(), 0.0),
      link_face_(slave_.nodes.size(), -1),
      link_damage_(slave_.nodes.size(), 0.0),
      link_flow_(slave_.nodes.size(), 1e30),
      link_touching_(slave_.nodes.size(), 0) {}

namespace {

// Existing penetration pushed out per step (positions only), fraction of the
// face size, -: a larger step distorts the elements behind the face.
constexpr double k_pushout_fraction = 0.02;

// The melting temperature of a body's material, K.
double melt_temperature(const Material& m) {
  return strength_references(m.strength).T_melt;
}

// Key of a pair for the warm start: its slave's global node and its face.
// A node is a slave in one pass only (master and slave bodies differ), so the
// key also tells the pass.
std::uint64_t pair_key(int node, int face) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(node)) << 32) |
         static_cast<std::uint32_t>(face);
}

// Elements of `body` that contain global node g (ascending).
std::vector<int> elements_of_node(const FeBody& body, int g) {
  std::vector<int> out;
  const std::size_t local = static_cast<std::size_t>(g) - body.node_begin;
  for (int k = body.node_elem_offsets[local]; k < body.node_elem_offsets[local + 1]; ++k) {
    out.push_back(body.node_elem_entries[static_cast<std::size_t>(k)] / 8);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Sets the deformed pinballs of SPH surface s from its body's deformation
// gradients (set_pinball_shape, ContactSurface::radius_along).
void follow_particle_shapes(ContactSurface& s, const SphBody& body) {
  for (std::size_t k = 0; k < s.nodes.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(s.nodes[k]) - body.node_begin;
    set_pinball_shape(s, static_cast<int>(k), body.F[i] * body.F_ref[i]);
  }
}

// Particle k of particle surface s: its share of its body's surface now
// (sph_surface_area), or pi R^2 of its pinball without a body (`body` null).
double particle_area(const ContactSurface& s, int k, const SphBody* body) {
  if (body == nullptr) {
    const double R = s.node_radius(k);
    return std::numbers::pi * R * R;
  }
  return sph_surface_area(*body, static_cast<std::size_t>(s.nodes[k]) - body->node_begin);
}

// Sets the cap normals of SPH master surface s: each particle's outward
// surface normal (sph_surface_normal; zero inside the body).
void follow_cap_normals(ContactSurface& s, const SphBody& body) {
  s.cap_normal.resize(s.nodes.size());
  for (std::size_t k = 0; k < s.nodes.size(); ++k) {
    s.cap_normal[k] =
        sph_surface_normal(body, static_cast<std::size_t>(s.nodes[k]) - body.node_begin);
  }
}

// A face's nodes, ascending (segments padded with -1): the same key for
// the face seen from either of its elements.
using FaceKey = std::array<int, 4>;
FaceKey face_key(const std::array<int, 4>& f, int nodes_per_face) {
  FaceKey k = f;
  if (nodes_per_face == 2) k[2] = k[3] = -1;
  std::sort(k.begin(), k.end());
  return k;
}

// Faces of element e, outward: the 4 segments of a quadrilateral (outward
// normal on the right) or the 6 quadrilaterals of a hexahedron.
std::vector<std::array<int, 4>> element_faces(const FeBody& body, std::size_t e, bool axisym) {
  const auto& c = body.conn[e];
  std::vector<std::array<int, 4>> out;
  if (axisym) {
    for (int a = 0; a < 4; ++a) out.push_back({c[a], c[(a + 1) % 4], -1, -1});
    return out;
  }
  for (const auto& f : k_hex_faces) out.push_back({c[f[0]], c[f[1]], c[f[2]], c[f[3]]});
  return out;
}

// Faces on the boundary of the active elements of a body, each with its
// element, in element order, leaving out the faces whose keys are in
// `excluded` (sorted).
std::vector<std::pair<std::array<int, 4>, int>> active_boundary_faces(
    const FeBody& body, bool axisym, const std::vector<FaceKey>& excluded) {
  const int npf = axisym ? 2 : 4;
  std::vector<std::pair<std::array<int, 4>, int>> all;
  std::vector<FaceKey> keys;
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    if (!body.active[e]) continue;
    for (const auto& f : element_faces(body, e, axisym)) {
      all.push_back({f, static_cast<int>(e)});
      keys.push_back(face_key(f, npf));
    }
  }
  std::vector<std::size_t> order(all.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  std::vector<std::uint8_t> shared(all.size(), 0);
  for (std::size_t k = 0; k + 1 < order.size(); ++k) {
    if (keys[order[k]] == keys[order[k + 1]]) shared[order[k]] = shared[order[k + 1]] = 1;
  }
  std::vector<std::pair<std::array<int, 4>, int>> out;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (shared[k] || std::binary_search(excluded.begin(), excluded.end(), keys[k])) continue;
    out.push_back(all[k]);
  }
  return out;
}

// The body's initial boundary faces that `surface` leaves out (symmetry
// planes, the axis, supported faces), sorted: they never become contact
// faces; a face that erosion exposes is never one of them.
std::vector<FaceKey> faces_left_out(const FeBody& body, bool axisym,
                                    const ContactSurface& surface) {
  const int npf = axisym ? 2 : 4;
  std::vector<FaceKey> in;
  for (const auto& f : surface.faces) in.push_back(face_key(f, npf));
  std::sort(in.begin(), in.end());
  std::vector<FaceKey> out;
  for (const auto& [f, e] : active_boundary_faces(body, axisym, {})) {
    const FaceKey k = face_key(f, npf);
    if (!std::binary_search(in.begin(), in.end(), k)) out.push_back(k);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

void ContactInterface::attach_bodies(const std::vector<FeBody>& bodies, std::size_t mb,
                                     std::size_t sb) {
  master_index_ = mb;
  slave_index_ = sb;
  const FeBody& master = bodies[mb];
  const FeBody& slave = bodies[sb];
  slave_elem_offsets_.assign(1, 0);
  slave_elem_entries_.clear();
  for (int g : slave_.nodes) {
    const std::vector<int> e = elements_of_node(slave, g);
    slave_elem_entries_.insert(slave_elem_entries_.end(), e.begin(), e.end());
    slave_elem_offsets_.push_back(static_cast<int>(slave_elem_entries_.size()));
  }
  const int npf = master_.nodes_per_face();
  master_face_element_.assign(master_.faces.size(), -1);
  for (std::size_t f = 0; f < master_.faces.size(); ++f) {
    std::vector<int> common = elements_of_node(master, master_.faces[f][0]);
    for (int k = 1; k < npf; ++k) {
      const std::vector<int> e = elements_of_node(master, master_.faces[f][k]);
      std::vector<int> both;
      std::set_intersection(common.begin(), common.end(), e.begin(), e.end(),
                            std::back_inserter(both));
      common = std::move(both);
    }
    if (!common.empty()) master_face_element_[f] = common.front();
  }
  master_left_out_ = faces_left_out(master, axisymmetric_, master_);
  slave_left_out_ = faces_left_out(slave, axisymmetric_, slave_);
}

void ContactInterface::attach_bodies(const std::vector<FeBody>& fe, const std::vector<SphBody>& sph,
                                     bool master_is_sph, std::size_t master, bool slave_is_sph,
                                     std::size_t slave) {
  if (!master_is_sph && !slave_is_sph) {
    attach_bodies(fe, master, slave);
    return;
  }
  (void)sph;
  master_index_ = master;
  slave_index_ = slave;
  master_sph_ = master_is_sph;
  slave_sph_ = slave_is_sph;
  // FE side of a mixed pair: its elements, as above.
  if (!slave_is_sph) {
    const FeBody& b = fe[slave];
    slave_elem_offsets_.assign(1, 0);
    slave_elem_entries_.clear();
    for (int g : slave_.nodes) {
      const std::vector<int> e = elements_of_node(b, g);
      slave_elem_entries_.insert(slave_elem_entries_.end(), e.begin(), e.end());
      slave_elem_offsets_.push_back(static_cast<int>(slave_elem_entries_.size()));
    }
  }
  if (!master_is_sph) {
    const FeBody& b = fe[master];
    const int npf = master_.nodes_per_face();
    master_face_element_.assign(master_.faces.size(), -1);
    for (std::size_t f = 0; f < master_.faces.size(); ++f) {
      std::vector<int> common = elements_of_node(b, master_.faces[f][0]);
      for (int k = 1; k < npf; ++k) {
        const std::vector<int> e = elements_of_node(b, master_.faces[f][k]);
        std::vector<int> both;
        std::set_intersection(common.begin(), common.end(), e.begin(), e.end(),
                              std::back_inserter(both));
        common = std::move(both);
      }
      if (!common.empty()) master_face_element_[f] = common.front();
    }
  }
}

void ContactInterface::follow_erosion(const std::vector<FeBody>& bodies) {
  if (master_sph_ || slave_sph_ || master_index_ >= bodies.size() ||
      slave_index_ >= bodies.size() || master_face_element_.empty()) {
    return;
  }
  const int npf = master_.nodes_per_face();
  // Master: mark the faces of eroded elements, append the exposed ones.
  const FeBody& mb = bodies[master_index_];
  master_face_dead_.resize(master_.faces.size(), 0);
  for (std::size_t f = 0; f < master_.faces.size(); ++f) {
    const int e = master_face_element_[f];
    if (e >= 0 && !mb.active[e]) master_face_dead_[f] = 1;
  }
  std::vector<FaceKey> known;
  for (const auto& f : master_.faces) known.push_back(face_key(f, npf));
  std::sort(known.begin(), known.end());
  std::vector<std::array<int, 4>> faces = master_.faces;
  for (const auto& [f, e] : active_boundary_faces(mb, axisymmetric_, master_left_out_)) {
    if (std::binary_search(known.begin(), known.end(), face_key(f, npf))) continue;
    faces.push_back(f);
    master_face_element_.push_back(e);
    master_face_dead_.push_back(0);
  }
  if (faces.size() != master_.faces.size()) {
    master_ = make_contact_surface(master_.kind, std::move(faces));
  }
  // Slave: the boundary of its active elements; per-node records by node id.
  const FeBody& sb = bodies[slave_index_];
  std::vector<std::array<int, 4>> slave_faces;
  for (const auto& fe : active_boundary_faces(sb, axisymmetric_, slave_left_out_)) {
    slave_faces.push_back(fe.first);
  }
  ContactSurface slave = make_contact_surface(slave_.kind, std::move(slave_faces));
  if (slave.nodes == slave_.nodes && slave.faces.size() == slave_.faces.size()) return;
  const std::size_t n = slave.nodes.size();
  std::vector<std::uint8_t> touched(n, 0), touching(n, 0), pressed(n, 0);
  std::vector<LinkState> state(n, LinkState::none);
  std::vector<double> work(n, 0.0), area(n, 0.0), rate(n, 0.0), damage(n, 0.0), flow(n, 1e30);
  std::vector<int> face(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    const auto it = std::lower_bound(slave_.nodes.begin(), slave_.nodes.end(), slave.nodes[k]);
    if (it == slave_.nodes.end() || *it != slave.nodes[k]) continue;
    const std::size_t o = static_cast<std::size_t>(it - slave_.nodes.begin());
    touched[k] = touched_[o];
    pressed[k] = pressed_[o];
    touching[k] = link_touching_[o];
    state[k] = link_state_[o];
    work[k] = link_work_[o];
    area[k] = link_area_[o];
    rate[k] = link_rate_[o];
    face[k] = link_face_[o];
    damage[k] = link_damage_[o];
    flow[k] = link_flow_[o];
  }
  // Links on nodes that left the surface (all their elements eroded) are
  // counted as eroded links.
  for (std::size_t o = 0; o < slave_.nodes.size(); ++o) {
    if (link_state_[o] != LinkState::active) continue;
    if (!std::binary_search(slave.nodes.begin(), slave.nodes.end(), slave_.nodes[o])) {
      ++stats_.links_eroded;
    }
  }
  slave_ = std::move(slave);
  last_multiplier_.clear();  // keyed by slave face indices, which changed
  touched_ = std::move(touched);
  pressed_ = std::move(pressed);
  link_touching_ = std::move(touching);
  link_state_ = std::move(state);
  link_work_ = std::move(work);
  link_area_ = std::move(area);
  link_rate_ = std::move(rate);
  link_face_ = std::move(face);
  link_damage_ = std::move(damage);
  link_flow_ = std::move(flow);
  slave_elem_offsets_.assign(1, 0);
  slave_elem_entries_.clear();
  for (int g : slave_.nodes) {
    const std::vector<int> e = elements_of_node(sb, g);
    slave_elem_entries_.insert(slave_elem_entries_.end(), e.begin(), e.end());
    slave_elem_offsets_.push_back(static_cast<int>(slave_elem_entries_.size()));
  }
}

double ContactInterface::scale() const {
  return axisymmetric_ ? 2.0 * std::numbers::pi : 1.0;
}

void ContactInterface::release_local_nodes() {
  for (int g : local_nodes_) local_[g] = -1;
  local_nodes_.clear();
}

std::vector<DetectedPair> ContactInterface::open_link_pairs(
    const std::vector<Vec3>& x, const std::vector<DetectedPair>& found) const {
  std::vector<std::uint8_t> paired(slave_.nodes.size(), 0);
  for (const DetectedPair& p : found) paired[p.slave] = 1;
  std::vector<DetectedPair> out;
  for (std::size_t k = 0; k < slave_.nodes.size(); ++k) {
    const int f = link_face_[k];
    if (link_state_[k] != LinkState::active || paired[k] || f < 0) continue;
    // A link with nothing left to spend (a node on the axis bonds no area)
    // holds nothing: it goes with its pair.
    if (!(work_budget(*settings_.adhesion, link_area_[k]) > link_work_[k])) continue;
    const int ki = static_cast<int>(k);
    const std::optional<double> strength = link_params(ki).sigma_c;
    const double size = face_size(master_, f, x);
    const double reach =
        strength && *strength > 0.0 ? 2.0 * settings_.adhesion->G_c / *strength : size;
    const double max_gap = std::max(reach, settings_.search.search_margin * size);
    if (const auto p = pair_on_face(master_, f, slave_, ki, x, settings_.search, max_gap)) {
      out.push_back(*p);
    }
  }
  return out;
}

std::vector<DetectedPair> ContactInterface::detect(const NodeSet& nodes) {
  const std::vector<Vec3>& x = nodes.x;
  auto live = [&](const ContactSurface& sl, const ContactSurface& ma, const DetectedPair& p) {
    if (!(nodes.mass[sl.nodes[p.slave]] > 0.0)) return false;
    if (&ma == &master_ && static_cast<std::size_t>(p.face) < master_face_dead_.size() &&
        master_face_dead_[p.face]) {
      return false;
    }
    for (int k = 0; k < ma.nodes_per_face(); ++k) {
      if (!(nodes.mass[ma.faces[p.face][k]] > 0.0)) return false;
    }
    return true;
  };
  std::vector<DetectedPair> pairs;
  for (const DetectedPair& p : find_pairs_buckets(master_, slave_, x, settings_.search)) {
    if (live(slave_, master_, p)) pairs.push_back(p);
  }
  if (settings_.adhesion) {
    for (const DetectedPair& p : open_link_pairs(x, pairs)) {
      if (live(slave_, master_, p)) pairs.push_back(p);
    }
    std::stable_sort(pairs.begin(), pairs.end(), [](const DetectedPair& a, const DetectedPair& b) {
      return a.slave < b.slave;
    });
  }
  first_pass_pairs_ = pairs.size();
  if (settings_.two_pass) {
    for (const DetectedPair& p : find_pairs_buckets(slave_, master_, x, settings_.search)) {
      if (live(master_, slave_, p)) pairs.push_back(p);
    }
  }
  return pairs;
}

void ContactInterface::build_problem(const NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                     const std::vector<DetectedPair>& pairs, double dt) {
  problem_.clear_pairs();
  start_gap_.clear();
  pushout_.clear();
  problem_.inv_mass.clear();
  problem_.velocity.clear();
  release_local_nodes();
  const int dims = axisymmetric_ ? 2 : 3;
  auto local = [&](int g) {
    if (local_[g] < 0) {
      local_[g] = static_cast<int>(local_nodes_.size());
      local_nodes_.push_back(g);
      Vec3 inv = Vec3::Zero();
      const double m = nodes.mass[g];
      if (m > 0.0) {
        for (int c = 0; c < dims; ++c) {
          if (!(mask[g] & (1u << c))) inv[c] = 1.0 / m;
        }
      }
      problem_.inv_mass.push_back(inv);
      problem_.velocity.push_back(nodes.v[g]);
    }
    return local_[g];
  };
  const int npf = master_.nodes_per_face();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const DetectedPair& dp = pairs[i];
    const bool second = i >= first_pass_pairs_;
    const ContactSurface& sl = second ? master_ : slave_;
    const ContactSurface& ma = second ? slave_ : master_;
    std::array<int, 5> ids{-1, -1, -1, -1, -1};
    std::array<double, 5> coef{};
    ids[0] = local(sl.nodes[dp.slave]);
    coef[0] = 1.0;
    for (int k = 0; k < npf; ++k) {
      ids[k + 1] = local(ma.faces[dp.face][k]);
      coef[k + 1] = -dp.geometry.weights[k];
    }
    problem_.node.push_back(ids);
    problem_.coef.push_back(coef);
    problem_.normal.push_back(dp.geometry.normal);
    problem_.tangent1.push_back(dp.geometry.tangent1);
    problem_.tangent2.push_back(dp.geometry.tangent2);
    // Split impulse: the velocity rows only stop further penetration. A pair
    // already behind its face at x_n (a fold, or a pair first found behind
    // its face) gets b = -C v (no approach), not -g / dt: pushing it out
    // through the velocity gives the node a speed of up to g_n / dt, the
    // order of the wave speed at the steps of a fast impact, and injects
    // kinetic energy. Its penetration is removed by the position-only pass
    // (correct_positions), at most k_pushout_fraction of the face size per
    // step.
    double b = -dp.geometry.gap / dt;
    double g_n = 0.0;
    {
      double vn = 0.0;  // C v, normal rate of the pair (positive opening)
      for (int k = 0; k < npf + 1; ++k) {
        const int g = k == 0 ? sl.nodes[dp.slave] : ma.faces[dp.face][k - 1];
        vn += coef[k] * nodes.v[g].dot(dp.geometry.normal);
      }
      g_n = dp.geometry.gap - dt * vn;
      if (g_n < 0.0) b = -vn;
    }
    const double allowed = k_pushout_fraction * face_size(ma, dp.face, nodes.x);
    start_gap_.push_back(g_n);
    pushout_.push_back(g_n < 0.0 ? std::min(-g_n, allowed) : 0.0);
    problem_.b.push_back(b);
    problem_.lo.push_back(0.0);
    problem_.b_hold.push_back(problem_.b.back());
    problem_.mu.push_back(settings_.friction);
  }
}

void ContactInterface::drop_repeated_rows(const NodeSet& nodes,
                                          const std::vector<std::uint8_t>& mask,
                                          std::vector<DetectedPair>& pairs, double dt) {
  if (pairs.size() <= first_pass_pairs_) return;
  // An active link holds its pair's gap both ways; a compressive
  // second-pass row nearly parallel to it could cancel the link's tension
  // with an equal push, so that the link is charged work it never does
  // (the elastic sphere with sigma_c large exhausted its links while
  // rebounding at the free speed): such rows go from a lower correlation.
  std::vector<double> threshold(first_pass_pairs_, settings_.max_row_correlation);
  if (settings_.adhesion) {
    for (std::size_t i = 0; i < first_pass_pairs_; ++i) {
      if (pairs[i].primary && link_state_[pairs[i].slave] == LinkState::active) {
        threshold[i] = settings_.max_bonded_row_correlation;
      }
    }
  }
  std::vector<std::uint8_t> repeated = repeated_rows(problem_, first_pass_pairs_, threshold);
  if (std::none_of(repeated.begin(), repeated.end(), [](std::uint8_t r) { return r != 0; })) {
    return;
  }
  std::vector<DetectedPair> kept;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!repeated[i]) kept.push_back(pairs[i]);
  }
  pairs = std::move(kept);
  build_problem(nodes, mask, pairs, dt);
}

double ContactInterface::adhesive_area(int k, int f, const std::vector<Vec3>& x,
                                       const std::vector<SphBody>& sph) const {
  const SphBody* slave_body =
      slave_sph_ && slave_index_ < sph.size() ? &sph[slave_index_] : nullptr;
  const SphBody* master_body =
      master_sph_ && master_index_ < sph.size() ? &sph[master_index_] : nullptr;
  // Thesis 2.2.4 gives SPH links pi R^2, which on a lattice adds up to
  // 0.56-0.93 of the surface; here each particle bonds its share of its
  // body's surface as it is now (sph_surface_area: stretched as an FE face
  // follows its nodes), the smaller side's share, as on FE faces (below).
  if (master_.kind == DetectionKind::particle_pinball && f >= 0) {
    return std::min(particle_area(slave_, k, slave_body), particle_area(master_, f, master_body));
  }
  const double own =
      slave_.radius.empty() ? slave_node_area(slave_, k, x) : particle_area(slave_, k, slave_body);
  if (master_.kind == DetectionKind::node_on_segment || f < 0) return own;
  const auto& ids = master_.faces[f];
  return std::min(own, quad_area({x[ids[0]], x[ids[1]], x[ids[2]], x[ids[3]]}));
}

// The state of slave node k's side read from its own live elements,
// weighted by their volume: the fallback of average_around where no
// material point lies within averaging_length (interface_states).
InterfaceSideState ContactInterface::slave_side_state(const FeBody& slave, int k) const {
  const double T_melt = melt_temperature(slave.material);
  InterfaceSideState sum{0.0, 0.0, 0.0, 0.0};
  double w_sum = 0.0;
  for (int j = slave_elem_offsets_[k]; j < slave_elem_offsets_[k + 1]; ++j) {
    const int e = slave_elem_entries_[j];
    if (!slave.active[e]) continue;
    const double w = slave.volume[e];
    if (!(w > 0.0)) continue;
    accumulate(sum, w, side_state(slave.state[e], T_melt));
    w_sum += w;
  }
  if (!(w_sum > 0.0)) return {};
  return divided(sum, w_sum);
}

InterfaceSideState ContactInterface::master_side_state(const FeBody& master, int f) const {
  const int e = f >= 0 ? master_face_element_[f] : -1;
  if (e < 0 || !master.active[e]) return {};  // never drops
  return side_state(master.state[e], melt_temperature(master.material));
}

AdhesionParams ContactInterface::link_params(int k) const {
  AdhesionParams p = *settings_.adhesion;
  p.sigma_c = link_strength(p, link_flow_[k]);
  p.cap_at_flow_stress = false;
  return p;
}

double ContactInterface::link_compliance(int k, int f, const std::vector<FeBody>& bodies,
                                         const std::vector<SphBody>& sph) const {
  const double A = link_area_[k];
  if (!(A > 0.0)) return 0.0;
  // h_e / (M A) for one side of thickness h_e (m) and P-wave modulus
  // M = K + 4G/3 (Pa); 0 for a side without material.
  const auto side = [A](double h_e, const MaterialConstants& c) {
    const double M = c.K + 4.0 / 3.0 * c.G;
    return M > 0.0 && h_e > 0.0 ? h_e / (M * A) : 0.0;
  };
  double c = 0.0;
  // Slave: an SPH particle's spacing, or the mean size of the node's elements.
  if (slave_sph_) {
    if (slave_index_ < sph.size())
      c += side(sph[slave_index_].spacing, sph[slave_index_].constants);
  } else if (slave_index_ < bodies.size() && !slave_elem_offsets_.empty()) {
    const FeBody& slave = bodies[slave_index_];
    double h_sum = 0.0;
    int n = 0;
    for (int j = slave_elem_offsets_[k]; j < slave_elem_offsets_[k + 1]; ++j) {
      const int e = slave_elem_entries_[j];
      if (!slave.active[e]) continue;
      h_sum += slave.char_length[e];
      ++n;
    }
    if (n > 0) c += side(h_sum / n, slave.constants);
  }
  // Master: the SPH particle's spacing, or the size of the face's element.
  if (master_sph_) {
    if (master_index_ < sph.size()) {
      c += side(sph[master_index_].spacing, sph[master_index_].constants);
    }
  } else if (master_index_ < bodies.size() && f >= 0 &&
             static_cast<std::size_t>(f) < master_face_element_.size()) {
    const FeBody& master = bodies[master_index_];
    const int e = master_face_element_[f];
    if (e >= 0 && master.active[e]) c += side(master.char_length[e], master.constants);
  }
  return c;
}

namespace {

// The state of an SPH particle (global node g of body b), or a fresh
// state for a deactivated one.
InterfaceSideState particle_state(const SphBody& b, int g) {
  const std::size_t i = static_cast<std::size_t>(g) - b.node_begin;
  if (!b.active[i]) return InterfaceSideState{};
  return side_state(b.state[i], melt_temperature(b.material));
}

// The live material points of one body inside the box [lo, hi]: element
// centres weighted by their volume (FE), or particles weighted by their
// initial volume (SPH).
std::vector<MaterialSample> fe_samples(const FeBody& b, const NodeSet& nodes, const Vec3& lo,
                                       const Vec3& hi) {
  std::vector<MaterialSample> out;
  const double T_melt = melt_temperature(b.material);
  const int npe = b.nodes_per_element();
  for (std::size_t e = 0; e < b.num_elements(); ++e) {
    if (!b.active[e]) continue;
    Vec3 c = Vec3::Zero();
    for (int a = 0; a < npe; ++a) c += nodes.x[b.conn[e][a]];
    c /= npe;
    if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) continue;
    out.push_back({c, b.volume[e], side_state(b.state[e], T_melt)});
  }
  return out;
}

std::vector<MaterialSample> sph_samples(const SphBody& b, const NodeSet& nodes, const Vec3& lo,
                                        const Vec3& hi) {
  std::vector<MaterialSample> out;
  const double T_melt = melt_temperature(b.material);
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Vec3& x = nodes.x[b.node_begin + i];
    if (!b.active[i] || (x.array() < lo.array()).any() || (x.array() > hi.array()).any()) {
      continue;
    }
    out.push_back({x, b.volume0[i], side_state(b.state[i], T_melt)});
  }
  return out;
}

}  // namespace

InterfaceStates ContactInterface::interface_states(const NodeSet& nodes,
                                                   const std::vector<int>& ids,
                                                   const std::vector<FeBody>& bodies,
                                                   const std::vector<SphBody>& sph) const {
  const double l = settings_.adhesion->averaging_length;
  InterfaceStates out;
  out.slave.resize(ids.size());
  out.master.resize(ids.size());
  std::vector<Vec3> centres(ids.size());
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  // Each side's own state at the contact point (the node's elements, the
  // face's element, the particle) is the fallback. Sides whose bodies were
  // not attached (unit tests of the detection alone) never drop and carry
  // no damage.
  const bool slave_fe = !slave_sph_ && slave_index_ < bodies.size() && !slave_elem_offsets_.empty();
  const bool master_fe =
      !master_sph_ && master_index_ < bodies.size() && !master_face_element_.empty();
  const bool slave_p = slave_sph_ && slave_index_ < sph.size();
  const bool master_p = master_sph_ && master_index_ < sph.size();
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const int k = ids[n];
    centres[n] = nodes.x[slave_.nodes[k]];
    lo = lo.cwiseMin(centres[n]);
    hi = hi.cwiseMax(centres[n]);
    if (slave_p) out.slave[n] = particle_state(sph[slave_index_], slave_.nodes[k]);
    if (slave_fe) out.slave[n] = slave_side_state(bodies[slave_index_], k);
    if (master_p && link_face_[k] >= 0) {
      out.master[n] = particle_state(sph[master_index_], master_.faces[link_face_[k]][0]);
    }
    if (master_fe) out.master[n] = master_side_state(bodies[master_index_], link_face_[k]);
  }
  if (!ids.empty() && l > 0.0) {
    lo.array() -= l;
    hi.array() += l;
    const auto side = [&](bool fe, bool p, std::size_t index) {
      if (fe) return fe_samples(bodies[index], nodes, lo, hi);
      if (p) return sph_samples(sph[index], nodes, lo, hi);
      return std::vector<MaterialSample>{};
    };
    out.slave = average_around(side(slave_fe, slave_p, slave_index_), centres, l, out.slave);
    out.master = average_around(side(master_fe, master_p, master_index_), centres, l, out.master);
  }
  if (settings_.adhesion->activation == ActivationRule::surface_expansion) {
    set_surface_expansion(out, nodes, ids, sph);
  }
  return out;
}

namespace {

// Y = 1 - 1 / (A / A0) of an SPH particle's share of its body's surface
// (sph_surface_stretch: A / A0 by Nanson's rule), global node g; 0 where the
// share has not grown.
double particle_surface_expansion(const SphBody& b, int g) {
  const double stretch = sph_surface_stretch(b, static_cast<std::size_t>(g) - b.node_begin);
  return stretch > 1.0 && std::isfinite(stretch) ? 1.0 - 1.0 / stretch : 0.0;
}

}  // namespace

void ContactInterface::set_surface_expansion(InterfaceStates& out, const NodeSet& nodes,
                                             const std::vector<int>& ids,
                                             const std::vector<SphBody>& sph) const {
  const bool slave_p = slave_sph_ && slave_index_ < sph.size();
  const bool master_p = master_sph_ && master_index_ < sph.size();
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const int k = ids[n];
    const int f = link_face_[k];
    out.slave[n].surface_expansion =
        slave_p ? particle_surface_expansion(sph[slave_index_], slave_.nodes[k])
                : node_surface_expansion(slave_, k, nodes.x0, nodes.x);
    if (f < 0) continue;
    out.master[n].surface_expansion =
        master_p ? particle_surface_expansion(sph[master_index_], master_.faces[f][0])
                 : face_surface_expansion(master_, f, nodes.x0, nodes.x);
  }
}

// The bonded area of active link k: its adhesive area on activation, or,
// with a bonded fraction below one, the largest fraction of its area
// reached while its pair is pressed (metal extrudes through the cracked
// films only under pressure, Bay 1983).
void ContactInterface::grow_bond(int k, bool activated, bool pressed, const InterfaceSideState& a,
                                 const InterfaceSideState& b, const NodeSet& nodes,
                                 const std::vector<SphBody>& sph) {
  const AdhesionParams& ap = *settings_.adhesion;
  const bool partial = ap.bonded_fraction != BondedFraction::full;
  if (!activated && !(partial && pressed)) return;
  const double area = adhesive_area(k, link_face_[k], nodes.x, sph);
  if (!partial) {
    link_area_[k] = area;
    return;
  }
  const double bonded = pressed ? area * bonded_fraction(ap, a, b) : 0.0;
  link_area_[k] = activated ? bonded : std::max(link_area_[k], bonded);
}

void ContactInterface::update_links_before_solve(const NodeSet& nodes,
                                                 const std::vector<DetectedPair>& pairs,
                                                 const std::vector<FeBody>& bodies,
                                                 const std::vector<SphBody>& sph) {
  const AdhesionParams& ap = *settings_.adhesion;
  // The interface: slave nodes in a primary pair that touch or have touched.
  std::vector<int> ids;
  for (std::size_t i = 0; i < first_pass_pairs_; ++i) {
    const int k = pairs[i].slave;
    if (!pairs[i].primary) continue;
    if (link_state_[k] == LinkState::none && !link_touching_[k]) continue;
    ids.push_back(k);
  }
  const InterfaceStates avg = interface_states(nodes, ids, bodies, sph);
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const int k = ids[n];
    const InterfaceSideState& a = avg.slave[n];
    const InterfaceSideState& b = avg.master[n];
    link_damage_[k] = std::max(a.damage, b.damage);
    link_flow_[k] = std::min(a.flow_stress, b.flow_stress);
    const LinkState before = link_state_[k];
    LinkEvents ev;
    ev.touching = link_touching_[k] != 0;
    ev.activation_met = activation_met(ap, a, b);
    ev.erosion_met = erosion_met(ap, a.damage, b.damage);
    const LinkState after = next_link_state(before, ap.activation, ev);
    if (after == LinkState::active) grow_bond(k, before != after, ev.touching, a, b, nodes, sph);
    if (after == before) continue;
    link_state_[k] = after;
    if (after == LinkState::active) ++stats_.links_activated;
    if (after == LinkState::eroded) ++stats_.links_eroded;
  }
}

void ContactInterface::lagrange_step(NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                     double dt, const std::vector<FeBody>& bodies) {
  lagrange_step(nodes, mask, dt, bodies, {});
}

int ContactInterface::pair_slave_node(const std::vector<DetectedPair>& pairs, std::size_t i) const {
  const ContactSurface& sl = i < first_pass_pairs_ ? slave_ : master_;
  return sl.nodes[pairs[i].slave];
}

// Warm start: each pair starts from the multiplier it carried in the last
// step, so a pressed contact needs only the sweeps that follow its change
// over one step.
void ContactInterface::warm_start(const std::vector<DetectedPair>& pairs, double dt) {
  problem_.p_start.assign(pairs.size(), 0.0);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto it = last_multiplier_.find(pair_key(pair_slave_node(pairs, i), pairs[i].face));
    if (it != last_multiplier_.end()) problem_.p_start[i] = it->second * dt;
  }
}

std::vector<std::size_t> ContactInterface::link_rows(const std::vector<DetectedPair>& pairs,
                                                     double dt) {
  std::vector<std::size_t> links;
  for (std::size_t i = 0; i < first_pass_pairs_; ++i) {
    const int k = pairs[i].slave;
    if (!pairs[i].primary || link_state_[k] != LinkState::active) continue;
    const double rate = normal_rate(problem_, i, problem_.velocity);
    const double g_n = pairs[i].geometry.gap - dt * rate;
    problem_.lo[i] = -max_tension(link_params(k), link_area_[k]) * dt;
    problem_.b_hold[i] = problem_.b[i] + std::max(g_n, 0.0) / dt;
    links.push_back(i);
  }
  return links;
}

void ContactInterface::charge_links(const std::vector<DetectedPair>& pairs,
                                    const std::vector<std::size_t>& links, ContactSolution& sol,
                                    double dt, const std::vector<FeBody>& bodies,
                                    const std::vector<SphBody>& sph) {
  std::vector<std::uint8_t> exhausted(links.size(), 0);
  auto link_step = [&](std::size_t j, const ContactSolution& s) {
    const std::size_t i = links[j];
    const int k = pairs[i].slave;
    const double h = normal_inverse_mass(problem_, i);
    const double I = -s.p_n[i];
    const double g_free = normal_rate(problem_, i, s.dv) + h * I - problem_.b_hold[i];
    const LinkKinematics kin{link_rate_[k], g_free, h,
                             link_compliance(k, pairs[i].face, bodies, sph)};
    return cohesive_step(link_params(k), link_area_[k], link_work_[k], kin, dt, I);
  };
  bool resolve = false;
  for (std::size_t j = 0; j < links.size(); ++j) {
    if (!(sol.p_n[links[j]] < 0.0)) continue;
    const CohesiveStep c = link_step(j, sol);
    if (c.exhausted) {
      exhausted[j] = 1;
      problem_.lo[links[j]] = -c.impulse;
      resolve = true;
    }
  }
  if (resolve) {
    problem_.p_start = sol.p_n;
    sol = solve_contact(problem_, settings_.solver);
  }
  double adhesion_work = 0.0;
  for (std::size_t j = 0; j < links.size(); ++j) {
    const int k = pairs[links[j]].slave;
    if (sol.p_n[links[j]] < 0.0) {
      ++stats_.links_in_tension;
      const CohesiveStep c = link_step(j, sol);
      const double dW =
          exhausted[j]
              ? std::max(work_budget(*settings_.adhesion, link_area_[k]) - link_work_[k], 0.0)
              : c.work;
      link_work_[k] += dW;
      adhesion_work += dW;
      if (c.exhausted) exhausted[j] = 1;
    }
    if (exhausted[j]) {
      link_state_[k] = next_link_state(link_state_[k], settings_.adhesion->activation,
                                       {false, false, false, true});
      ++stats_.links_exhausted;
    }
  }
  stats_.adhesion_work += adhesion_work * scale();
}

void ContactInterface::apply_solution(NodeSet& nodes, const std::vector<DetectedPair>& pairs,
                                      const ContactSolution& sol, double dt) {
  stats_.max_iterations = std::max(stats_.max_iterations, sol.iterations);
  stats_.max_residual = std::max(stats_.max_residual, sol.residual);
  if (!sol.converged) ++stats_.unconverged;
  for (std::size_t l = 0; l < local_nodes_.size(); ++l) {
    const int g = local_nodes_[l];
    const Vec3& dv = sol.dv[l];
    if (dv.isZero(0.0)) continue;
    nodes.v[g] += dv;
    nodes.x[g] += dt * dv;
  }
  correct_positions(nodes, pairs, sol, dt);
  last_multiplier_.clear();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (sol.p_n[i] != 0.0)
      last_multiplier_[pair_key(pair_slave_node(pairs, i), pairs[i].face)] = sol.p_n[i] / dt;
  }
}

// Contact work: every impulse (compression, link tension, friction) times
// the corrected relative velocity (eq. 1.21), the work of a force held over
// the step on the displacement it drives. This, not the link's budget
// charge, is the work the energy balance sees.
//
// A slave node that carried no force in the last step (it lands on the face
// within this step, or is found already behind it: a node exposed by
// erosion, a fold) makes a node-level plastic impact: its impulse takes out
// the kinetic energy of its approach, booked as p (C v_before + C v_after) /
// 2 (the kinetic energy change of one row). Without it that energy (1500 m/s
// Al impact: 2-3 % of the initial energy) leaves outside the balance. Pairs
// that stay in contact keep p C v_after: their "penetration" at x_n is the
// linearised gap of a pressed contact, and the approach the force update
// gives them each step is taken back at once (header).
double ContactInterface::contact_work(const std::vector<DetectedPair>& pairs,
                                      const ContactSolution& sol,
                                      const std::vector<Vec3>& v_new) const {
  double work = 0.0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (sol.p_n[i] != 0.0) {
      const double after = normal_rate(problem_, i, v_new);
      const bool landing =
          i < first_pass_pairs_ && !pressed_[static_cast<std::size_t>(pairs[i].slave)];
      const double before = landing ? normal_rate(problem_, i, problem_.velocity) : after;
      work += sol.p_n[i] * 0.5 * (before + after);
    }
    if (problem_.mu[i] > 0.0) {
      double st1 = 0.0, st2 = 0.0;
      for (int k = 0; k < 5; ++k) {
        const int n = problem_.node[i][k];
        if (n < 0) continue;
        st1 += problem_.coef[i][k] * problem_.tangent1[i].dot(v_new[n]);
        st2 += problem_.coef[i][k] * problem_.tangent2[i].dot(v_new[n]);
      }
      work += sol.p_t[i].x() * st1 + sol.p_t[i].y() * st2;
    }
  }
  return work;
}

// After the solve: each slave node's opening rate (the rate a link starts
// the next step from, 0 for nodes in no pair), which nodes carried a force,
// and the contact counts.
void ContactInterface::record_pair_states(const std::vector<DetectedPair>& pairs,
                                          const ContactSolution& sol,
                                          const std::vector<Vec3>& v_new) {
  const bool adhesive = settings_.adhesion.has_value();
  if (adhesive) {
    std::fill(link_rate_.begin(), link_rate_.end(), 0.0);
    for (std::size_t i = 0; i < first_pass_pairs_; ++i) {
      if (pairs[i].primary) link_rate_[pairs[i].slave] = normal_rate(problem_, i, v_new);
    }
  }
  std::fill(pressed_.begin(), pressed_.end(), 0);
  for (std::size_t i = 0; i < first_pass_pairs_; ++i) {
    if (sol.p_n[i] != 0.0) pressed_[pairs[i].slave] = 1;  // compression or link tension
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!(sol.p_n[i] > 0.0)) continue;
    ++stats_.in_contact;
    if (i >= first_pass_pairs_) continue;
    if (!touched_[pairs[i].slave]) {
      touched_[pairs[i].slave] = 1;
      ++stats_.ever_in_contact;
    }
    if (adhesive) link_touching_[pairs[i].slave] = 1;
  }
  stats_.max_in_contact = std::max(stats_.max_in_contact, stats_.in_contact);
}

void ContactInterface::solve_pairs(NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                   std::vector<DetectedPair>& pairs, double dt,
                                   const std::vector<FeBody>& bodies,
                                   const std::vector<SphBody>& sph) {
  for (const DetectedPair& p : pairs) {
    stats_.max_penetration = std::max(stats_.max_penetration, -p.geometry.gap);
  }
  build_problem(nodes, mask, pairs, dt);
  drop_repeated_rows(nodes, mask, pairs, dt);
  limit_pushout(bodies);
  warm_start(pairs, dt);
  // Active links: tension allowed down to the cap, holding the opening the
  // pair has at the start of the step, g_n = g_{n+1} - dt C v_{n+1/2}.
  const std::vector<std::size_t> links =
      settings_.adhesion ? link_rows(pairs, dt) : std::vector<std::size_t>{};
  ContactSolution sol = solve_contact(problem_, settings_.solver);
  if (!links.empty()) charge_links(pairs, links, sol, dt, bodies, sph);
  apply_solution(nodes, pairs, sol, dt);
  std::vector<Vec3> v_new(local_nodes_.size());
  for (std::size_t l = 0; l < local_nodes_.size(); ++l) v_new[l] = nodes.v[local_nodes_[l]];
  stats_.work += contact_work(pairs, sol, v_new) * scale();
  record_pair_states(pairs, sol, v_new);
}

void ContactInterface::summarise_links(const std::vector<DetectedPair>& pairs) {
  // An active link whose pair opened beyond the search range (possible
  // only with a stress cap) has let go: it counts as exhausted.
  std::vector<std::uint8_t> seen(slave_.nodes.size(), 0);
  for (std::size_t i = 0; i < first_pass_pairs_; ++i) seen[pairs[i].slave] = 1;
  for (std::size_t k = 0; k < slave_.nodes.size(); ++k) {
    if (link_state_[k] == LinkState::active && !seen[k]) {
      link_state_[k] = next_link_state(link_state_[k], settings_.adhesion->activation,
                                       {false, false, false, true});
      ++stats_.links_exhausted;
    }
  }
  stats_.links_active = 0;
  double area = 0.0, remaining = 0.0;
  stats_.bond_damage = 0.0;
  double strength_area = 0.0, force_cap = 0.0;
  for (std::size_t k = 0; k < slave_.nodes.size(); ++k) {
    if (link_state_[k] != LinkState::active) continue;
    ++stats_.links_active;
    const std::optional<double> sc = link_params(static_cast<int>(k)).sigma_c;
    strength_area += (sc ? *sc : 0.0) * link_area_[k];
    force_cap += sc ? *sc * link_area_[k] : std::numeric_limits<double>::infinity();
    if (settings_.adhesion->D_adh_max) {
      stats_.bond_damage =
          std::max(stats_.bond_damage, link_damage_[k] / *settings_.adhesion->D_adh_max);
    }
    area += link_area_[k];
    remaining += std::max(work_budget(*settings_.adhesion, link_area_[k]) - link_work_[k], 0.0);
  }
  stats_.bonded_area = area * scale();
  stats_.bond_strength = area > 0.0 ? strength_area / area : 0.0;
  stats_.bond_force = force_cap * scale();
  stats_.bond_energy = remaining * scale();
  stats_.max_bonded_area = std::max(stats_.max_bonded_area, stats_.bonded_area);
  stats_.max_links_active = std::max(stats_.max_links_active, stats_.links_active);
}

void ContactInterface::lagrange_step(NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                     double dt, const std::vector<FeBody>& bodies,
                                     const std::vector<SphBody>& sph) {
  if (!(dt > 0.0)) return;
  const bool adhesive = settings_.adhesion.has_value();
  if (master_sph_ && master_index_ < sph.size()) {
    follow_particle_shapes(master_, sph[master_index_]);
    follow_cap_normals(master_, sph[master_index_]);
  }
  if (slave_sph_ && slave_index_ < sph.size()) follow_particle_shapes(slave_, sph[slave_index_]);
  std::vector<DetectedPair> pairs = detect(nodes);
  stats_.pairs = static_cast<long long>(pairs.size());
  stats_.in_contact = 0;
  stats_.links_in_tension = 0;
  if (adhesive) {
    for (std::size_t i = 0; i < first_pass_pairs_; ++i) {
      if (pairs[i].primary) link_face_[pairs[i].slave] = pairs[i].face;
    }
    update_links_before_solve(nodes, pairs, bodies, sph);
    std::fill(link_touching_.begin(), link_touching_.end(), 0);
  }
  if (pairs.empty()) last_multiplier_.clear();
  if (!pairs.empty()) solve_pairs(nodes, mask, pairs, dt, bodies, sph);
  if (adhesive) summarise_links(pairs);
}

void ContactInterface::limit_pushout(const std::vector<FeBody>& bodies) {
  const auto length_at = [&](int g) {
    const std::size_t n = static_cast<std::size_t>(g);
    for (const FeBody& b : bodies) {
      if (n >= b.node_begin && n < b.node_end) return node_element_length(b, n);
    }
    return std::numeric_limits<double>::infinity();
  };
  for (std::size_t i = 0; i < pushout_.size(); ++i) {
    if (!(pushout_[i] > 0.0)) continue;
    double length = std::numeric_limits<double>::infinity();
    for (int id : problem_.node[i]) {
      if (id >= 0) length = std::min(length, length_at(local_nodes_[static_cast<std::size_t>(id)]));
    }
    pushout_[i] = std::min(pushout_[i], k_pushout_fraction * length);
  }
}

void ContactInterface::correct_positions(NodeSet& nodes, const std::vector<DetectedPair>& pairs,
                                         const ContactSolution& sol, double dt) {
  if (std::none_of(pushout_.begin(), pushout_.end(), [](double p) { return p > 0.0; })) return;
  // Pseudo-velocities w with C w >= b on the same rows and masses: a pushed
  // pair reaches g_n + pushout, every other pair may close to contact but not
  // beyond. Plain contact rows (no tension, no friction); x += dt w, v kept.
  ContactProblem pos = problem_;
  pos.p_start.clear();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const double g_after = pairs[i].geometry.gap + dt * normal_rate(problem_, i, sol.dv);
    const double target = pushout_[i] > 0.0 ? start_gap_[i] + pushout_[i] : 0.0;
    pos.b[i] = (target - g_after) / dt;
    pos.b_hold[i] = pos.b[i];
    pos.lo[i] = 0.0;
    pos.mu[i] = 0.0;
  }
  std::fill(pos.velocity.begin(), pos.velocity.end(), Vec3::Zero());
  const ContactSolution w = solve_contact(pos, settings_.solver);
  if (!w.converged) ++stats_.unconverged;
  double moved = 0.0;
  for (std::size_t l = 0; l < local_nodes_.size(); ++l) {
    if (w.dv[l].isZero(0.0)) continue;
    nodes.x[local_nodes_[l]] += dt * w.dv[l];
    moved = std::max(moved, dt * w.dv[l].norm());
  }
  stats_.max_position_correction = std::max(stats_.max_position_correction, moved);
}

double ContactInterface::soft_penalty_stiffness(std::size_t i, const Vec3& normal,
                                                double dt) const {
  if (!(settings_.penalty_mass_scale > 0.0) || !(dt > 0.0)) return 0.0;
  double h = 0.0;  // 1/kg
  for (int s = 0; s < 5; ++s) {
    const int id = problem_.node[i][s];
    if (id < 0) continue;
    const double c = problem_.coef[i][s];
    h += c * c * normal.dot(problem_.inv_mass[id].cwiseProduct(normal));
  }
  return h > 0.0 ? settings_.penalty_mass_scale / (h * dt * dt) : 0.0;
}

void ContactInterface::penalty_forces(NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                      double dt) {
  penalty_nodes_.clear();
  penalty_force_.clear();
  penalty_v_old_.clear();
  const std::vector<DetectedPair> pairs = detect(nodes);
  stats_.pairs = static_cast<long long>(pairs.size());
  stats_.in_contact = 0;
  stats_.stored = 0.0;
  if (pairs.empty()) return;
  build_problem(nodes, mask, pairs, dt);
  std::vector<Vec3> force(local_nodes_.size(), Vec3::Zero());
  const int npf = master_.nodes_per_face();
  double stored = 0.0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const PairGeometry& g = pairs[i].geometry;
    if (g.gap >= 0.0) continue;
    const bool second = i >= first_pass_pairs_;
    const double area = slave_node_area(second ? master_ : slave_, pairs[i].slave, nodes.x);
    const double k = std::max(settings_.penalty_stiffness * area,
                              soft_penalty_stiffness(i, g.normal, dt));  // N/m (per radian in 2D)
    const double fn = -k * g.gap;
    stored += 0.5 * k * g.gap * g.gap;
    stats_.max_penetration = std::max(stats_.max_penetration, -g.gap);
    Vec3 f = fn * g.normal;
    if (settings_.friction > 0.0) {
      // Slip velocity and the tangential force that would stop it in one
      // step; Coulomb's limit mu fn caps it.
      const auto& ids = problem_.node[i];
      const auto& cf = problem_.coef[i];
      Vec3 slip = Vec3::Zero();
      double h = 0.0;
      for (int s = 0; s < 5; ++s) {
        if (ids[s] < 0) continue;
        slip += cf[s] * problem_.velocity[ids[s]];
        h += cf[s] * cf[s] * problem_.inv_mass[ids[s]].maxCoeff();
      }
      slip -= slip.dot(g.normal) * g.normal;
      const double vs = slip.norm();
      if (vs > 0.0 && h > 0.0) {
        const double ft = std::min(settings_.friction * fn, vs / (h * dt));
        f -= ft * slip / vs;
      }
    }
    const auto& ids = problem_.node[i];
    const auto& cf = problem_.coef[i];
    for (int s = 0; s <= npf; ++s) force[ids[s]] += cf[s] * f;
    ++stats_.in_contact;
    if (!second && !touched_[pairs[i].slave]) {
      touched_[pairs[i].slave] = 1;
      ++stats_.ever_in_contact;
    }
  }
  stats_.stored = stored * scale();
  stats_.max_in_contact = std::max(stats_.max_in_contact, stats_.in_contact);
  for (std::size_t l = 0; l < local_nodes_.size(); ++l) {
    if (force[l].isZero(0.0)) continue;
    const int g = local_nodes_[l];
    nodes.f[g] += force[l];
    penalty_nodes_.push_back(g);
    penalty_force_.push_back(force[l]);
    penalty_v_old_.push_back(nodes.v[g]);
  }
}

void ContactInterface::book_penalty_work(const NodeSet& nodes, double dt_v) {
  double work = 0.0;
  for (std::size_t k = 0; k < penalty_nodes_.size(); ++k) {
    const Vec3 v_mean = 0.5 * (penalty_v_old_[k] + nodes.v[penalty_nodes_[k]]);
    work += penalty_force_[k].dot(v_mean) * dt_v;
  }
  stats_.work += work * scale();
}

}  // namespace splat
