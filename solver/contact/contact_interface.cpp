#include "solver/contact/contact_interface.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
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
      touched_(slave_.nodes.size(), 0) {}

namespace {

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

}  // namespace

void ContactInterface::attach_bodies(const FeBody& master, const FeBody& slave) {
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
}

double ContactInterface::scale() const {
  return axisymmetric_ ? 2.0 * std::numbers::pi : 1.0;
}

void ContactInterface::release_local_nodes() {
  for (int g : local_nodes_) local_[g] = -1;
  local_nodes_.clear();
}

std::vector<DetectedPair> ContactInterface::detect(const std::vector<Vec3>& x) {
  std::vector<DetectedPair> pairs = find_pairs_buckets(master_, slave_, x, settings_.search);
  first_pass_pairs_ = pairs.size();
  if (settings_.two_pass) {
    const std::vector<DetectedPair> back = find_pairs_buckets(slave_, master_, x, settings_.search);
    pairs.insert(pairs.end(), back.begin(), back.end());
  }
  return pairs;
}

void ContactInterface::build_problem(const NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                     const std::vector<DetectedPair>& pairs, double dt) {
  problem_.clear_pairs();
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
    problem_.b.push_back(-dp.geometry.gap / dt);
    problem_.lo.push_back(0.0);
    problem_.b_hold.push_back(problem_.b.back());
    problem_.mu.push_back(settings_.friction);
  }
}

void ContactInterface::lagrange_step(NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                     double dt) {
  if (!(dt > 0.0)) return;
  const std::vector<DetectedPair> pairs = detect(nodes.x);
  stats_.pairs = static_cast<long long>(pairs.size());
  stats_.in_contact = 0;
  if (pairs.empty()) return;
  for (const DetectedPair& p : pairs) {
    stats_.max_penetration = std::max(stats_.max_penetration, -p.geometry.gap);
  }
  build_problem(nodes, mask, pairs, dt);
  const ContactSolution sol = solve_contact(problem_, settings_.solver);
  stats_.max_iterations = std::max(stats_.max_iterations, sol.iterations);
  stats_.max_residual = std::max(stats_.max_residual, sol.residual);
  if (!sol.converged) ++stats_.unconverged;
  double work = 0.0;
  for (std::size_t l = 0; l < local_nodes_.size(); ++l) {
    const int g = local_nodes_[l];
    const Vec3& dv = sol.dv[l];
    if (dv.isZero(0.0)) continue;
    nodes.v[g] += dv;
    nodes.x[g] += dt * dv;
    work += nodes.mass[g] * dv.dot(nodes.v[g]);
  }
  stats_.work += work * scale();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (sol.p_n[i] > 0.0) {
      ++stats_.in_contact;
      if (i < first_pass_pairs_ && !touched_[pairs[i].slave]) {
        touched_[pairs[i].slave] = 1;
        ++stats_.ever_in_contact;
      }
    }
  }
  stats_.max_in_contact = std::max(stats_.max_in_contact, stats_.in_contact);
}

void ContactInterface::penalty_forces(NodeSet& nodes, const std::vector<std::uint8_t>& mask,
                                      double dt) {
  penalty_nodes_.clear();
  penalty_force_.clear();
  penalty_v_old_.clear();
  const std::vector<DetectedPair> pairs = detect(nodes.x);
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
    const double k = settings_.penalty_stiffness * area;  // N/m (per radian in 2D)
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
