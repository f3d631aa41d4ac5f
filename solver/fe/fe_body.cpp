#include "solver/fe/fe_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "solver/fe/bulk_viscosity.hpp"
#include "solver/fe/hex8.hpp"
#include "solver/fe/quad4_axisym.hpp"
#include "solver/material/damage.hpp"

#ifdef _OPENMP
#include <omp.h>
#define SPLAT_OMP(directive) _Pragma(#directive)
#else
#define SPLAT_OMP(directive)
#endif

namespace splat {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Elements per reduction block: partial sums are taken over fixed blocks and
// combined in block order, so they do not depend on the thread count.
constexpr std::size_t block_size = 64;
// Smaller loops run on one thread: forking costs more than they take.
constexpr long long min_parallel_blocks = 4;
constexpr long long min_parallel_nodes = 512;

int thread_id() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Reductions of one block of elements.
struct BlockSums {
  double dt_min = infinity;
  double hourglass_power = 0.0;
  double viscosity_power = 0.0;
  int max_iterations = 0;
  bool failed = false;
  long long inverted = 0;
};

// Common setup of a new body: material data and the node range.
FeBody start_body(const std::string& name, ElementKind kind, const Material& material,
                  const ModelSwitches& switches, const FeSettings& settings, std::size_t num_nodes,
                  NodeSet& nodes) {
  FeBody body;
  body.name = name;
  body.kind = kind;
  body.material = material;
  body.constants = derive_constants(material);
  body.switches = switches;
  body.settings = settings;
  body.node_begin = nodes.size();
  body.node_end = body.node_begin + num_nodes;
  const std::size_t n = body.node_end;
  nodes.x0.resize(n, Vec3::Zero());
  nodes.x.resize(n, Vec3::Zero());
  nodes.v.resize(n, Vec3::Zero());
  nodes.f.resize(n, Vec3::Zero());
  nodes.mass.resize(n, 0.0);
  nodes.boundary.resize(n, boundary_none);
  return body;
}

// Per-element arrays sized and initialised once the connectivity is known;
// then the CSR node -> (element * 8 + local node) adjacency, in element order.
void finish_body(FeBody& body, NodeSet& nodes, double temperature, unsigned long long seed) {
  const std::size_t ne = body.num_elements();
  const int npe = body.nodes_per_element();
  const Material& m = body.material;
  body.state.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const double D0 = body.switches.damage && m.damage.initial_random_max > 0.0
                          ? initial_random_damage(seed, e, m.damage.initial_random_max)
                          : 0.0;
    body.state[e] = initial_point_state(m, body.switches, temperature, D0);
  }
  body.q.assign(ne, 0.0);
  body.hg.assign(ne, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  body.active.assign(ne, 1);
  std::array<Vec3, 8> zero;
  zero.fill(Vec3::Zero());
  body.elem_force.assign(ne, zero);

  const std::size_t nn = body.node_end - body.node_begin;
  body.node_elem_offsets.assign(nn + 1, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    for (int a = 0; a < npe; ++a) {
      const std::size_t local = static_cast<std::size_t>(body.conn[e][a]) - body.node_begin;
      ++body.node_elem_offsets[local + 1];
      nodes.mass[body.conn[e][a]] += body.element_mass[e] / npe;
    }
  }
  for (std::size_t i = 0; i < nn; ++i) body.node_elem_offsets[i + 1] += body.node_elem_offsets[i];
  body.node_elem_entries.assign(static_cast<std::size_t>(body.node_elem_offsets[nn]), 0);
  std::vector<int> fill(body.node_elem_offsets.begin(), body.node_elem_offsets.end() - 1);
  for (std::size_t e = 0; e < ne; ++e) {
    for (int a = 0; a < npe; ++a) {
      const std::size_t local = static_cast<std::size_t>(body.conn[e][a]) - body.node_begin;
      body.node_elem_entries[static_cast<std::size_t>(fill[local]++)] = static_cast<int>(e) * 8 + a;
    }
  }
}

// Global id of local mesh node `local`, checked against the mesh's node count.
int global_node(const std::string& name, std::size_t e, int local, std::size_t num_nodes,
                std::size_t node_begin) {
  if (local < 0 || static_cast<std::size_t>(local) >= num_nodes) {
    throw std::invalid_argument("body '" + name + "': element " + std::to_string(e) +
                                " refers to node " + std::to_string(local) + " of " +
                                std::to_string(num_nodes));
  }
  return static_cast<int>(node_begin) + local;
}

[[noreturn]] void throw_bad_element(const std::string& name, std::size_t e, double volume) {
  throw std::invalid_argument("body '" + name + "': element " + std::to_string(e) +
                              " has non-positive volume " + std::to_string(volume));
}

// Result of the material part of one element step.
struct MaterialStep {
  Mat3 sigma;            // Cauchy stress minus bulk viscosity, Pa
  Mat3 R;                // incremental Hughes-Winget rotation
  double q = 0.0;        // bulk viscosity, Pa
  double c = 0.0;        // wave speed, m/s
  double dt_e = 0.0;     // CFL bound of the element, s
  double q_power = 0.0;  // power absorbed by the bulk viscosity, -q V tr(D), W
};

// Stress update of element e over dt (skipped for dt = 0): Jaumann rotation,
// material kernel, bulk viscosity, time-step bound.
inline MaterialStep material_step(FeBody& body, std::size_t e, const Mat3& L, double dt, double V,
                                  double L_c, BlockSums& sums) {
  MaterialStep ms;
  ms.R.setIdentity();
  ms.c = body.constants.wave_speed;
  PointState& st = body.state[e];
  double trD = 0.0;
  if (dt > 0.0) {
    const Mat3 D = 0.5 * (L + L.transpose());
    const Mat3 W = 0.5 * (L - L.transpose());
    // Jaumann rotation of the deviator (jaumann_rotate's rotation, closed form).
    ms.R = hughes_winget_rotation(W, dt);
    st.s = rotate_symmetric(ms.R, st.s);
    const PointUpdateResult r = update_point(body.material, body.constants, body.switches, st,
                                             dt * D, V / body.volume0[e], dt, L_c);
    sums.max_iterations = std::max(sums.max_iterations, r.iterations);
    sums.failed = sums.failed || !r.converged;
    trD = D.trace();
  }
  const double rho = body.element_mass[e] / V;
  const BulkViscosityCoefficients k{body.settings.q_linear, body.settings.q_quadratic};
  ms.q = bulk_viscosity_pressure(k, rho, L_c, ms.c, trD);
  body.q[e] = ms.q;
  ms.sigma = st.cauchy();
  ms.sigma.diagonal().array() -= ms.q;
  ms.dt_e = stable_time_step(L_c, ms.c, bulk_viscosity_speed(k, L_c, ms.c, trD));
  ms.q_power = -ms.q * V * trD;
  return ms;
}

// True if the element meets an erosion criterion (settings.erosion): damage at
// its cap, non-positive volume, or a CFL bound below erosion_min_time_step.
// Without erosion a non-positive volume is counted as inverted.
inline bool to_be_eroded(const FeBody& body, std::size_t e, double V, double dt_e,
                         BlockSums& sums) {
  const FeSettings& s = body.settings;
  if (!s.erosion) {
    if (!(V > 0.0)) ++sums.inverted;
    return false;
  }
  if (!(V > 0.0)) return true;
  const DamageParams& dm = body.material.damage;
  if (body.switches.damage && dm.initiation != DamageInitiation::none &&
      body.state[e].D >= dm.D_max - 1e-12) {
    return true;
  }
  return s.erosion_min_time_step > 0.0 && dt_e < s.erosion_min_time_step;
}

// Books an element's step: an element flagged for erosion exerts no force and
// sets no time-step bound (it is removed before the next step).
template <class Forces>
inline void finish_element(FeBody& body, std::size_t e, double V, const MaterialStep& ms,
                           double hourglass_power, const Forces& f, BlockSums& sums,
                           std::vector<int>& erode) {
  std::array<Vec3, 8>& out = body.elem_force[e];
  if (to_be_eroded(body, e, V, ms.dt_e, sums)) {
    out.fill(Vec3::Zero());
    erode.push_back(static_cast<int>(e));
    return;
  }
  for (std::size_t a = 0; a < f.size(); ++a) {
    if constexpr (std::is_same_v<Forces, Quad4Vectors>) {
      out[a] = Vec3(f[a].x(), f[a].y(), 0.0);
    } else {
      out[a] = f[a];
    }
  }
  sums.dt_min = std::min(sums.dt_min, ms.dt_e);
  sums.hourglass_power += hourglass_power;
  sums.viscosity_power += ms.q_power;
}

// An element with non-positive volume: no force, no material update.
inline void inverted_element(FeBody& body, std::size_t e, BlockSums& sums,
                             std::vector<int>& erode) {
  body.elem_force[e].fill(Vec3::Zero());
  if (to_be_eroded(body, e, 0.0, infinity, sums)) erode.push_back(static_cast<int>(e));
}

void hex_element(FeBody& body, const NodeSet& nodes, std::size_t e, double dt, BlockSums& sums,
                 std::vector<int>& erode) {
  const std::array<int, 8>& cn = body.conn[e];
  Hex8Vectors x, v;
  for (int a = 0; a < 8; ++a) {
    x[a] = nodes.x[cn[a]];
    v[a] = nodes.v[cn[a]];
  }
  const Hex8Modes xm = hex8_modes(x);
  const Hex8Geometry g = hex8_geometry(xm);
  const double V = g.volume;
  body.volume[e] = V;
  if (!(V > 0.0)) return inverted_element(body, e, sums, erode);
  const double L_c = hex8_characteristic_length(x, V);
  body.char_length[e] = L_c;
  const Hex8Modes w = hex8_modes(v);

  Mat3 L = Mat3::Zero();
  if (dt > 0.0) {
    Hex8Modes mid;  // x_{n+1/2} = x - dt/2 v, mode by mode
    for (int u = 0; u < 8; ++u) mid.c[u] = xm.c[u] - (0.5 * dt) * w.c[u];
    L = hex8_velocity_gradient(w, hex8_geometry(mid));
  }
  const MaterialStep ms = material_step(body, e, L, dt, V, L_c, sums);

  const std::array<Vec3, 4> qdot = hex8_hourglass_rates(w, xm, hex8_velocity_gradient(w, g));
  const double c_hg = body.settings.hourglass_coefficient;
  double hg_power = 0.0;
  std::array<Vec3, 4> Q;
  if (body.settings.stiffness_hourglass) {
    const double G_d = (1.0 - body.state[e].D) * body.constants.G;
    const double kappa = hex8_stiffness_hourglass_coefficient(c_hg, G_d, V);
    hg_power = hex8_hourglass_stiffness(qdot, kappa, dt, ms.R, body.hg[e]);
    Q = body.hg[e];
  } else {
    const double rho = body.element_mass[e] / V;
    const double a_h = hex8_viscous_hourglass_coefficient(c_hg, rho, ms.c, V);
    hg_power = hex8_hourglass_viscous(qdot, a_h, Q);
  }
  finish_element(body, e, V, ms, hg_power, hex8_forces(ms.sigma, g, xm, Q), sums, erode);
}

void quad_element(FeBody& body, const NodeSet& nodes, std::size_t e, double dt, BlockSums& sums,
                  std::vector<int>& erode) {
  const std::array<int, 8>& cn = body.conn[e];
  Quad4Vectors x, v;
  for (int a = 0; a < 4; ++a) {
    x[a] = nodes.x[cn[a]].head<2>();
    v[a] = nodes.v[cn[a]].head<2>();
  }
  const Quad4Gradient g = quad4_axisym_gradient(x);
  const double V = g.volume;
  body.volume[e] = V;
  if (!(g.area > 0.0) || !(V > 0.0)) return inverted_element(body, e, sums, erode);
  const double L_c = quad4_axisym_characteristic_length(x, g.area);
  body.char_length[e] = L_c;

  Mat3 L = Mat3::Zero();
  if (dt > 0.0) {
    Quad4Vectors xm;
    for (int a = 0; a < 4; ++a) xm[a] = x[a] - (0.5 * dt) * v[a];
    L = quad4_axisym_velocity_gradient(v, quad4_axisym_gradient(xm));
  }
  const MaterialStep ms = material_step(body, e, L, dt, V, L_c, sums);

  Quad4Vectors f;
  quad4_axisym_stress_forces(ms.sigma, g, f);
  const std::array<double, 4> gamma = quad4_axisym_hourglass_vector(x, g);
  const double c_hg = body.settings.hourglass_coefficient;
  double hg_power = 0.0;
  if (body.settings.stiffness_hourglass) {
    const double G_d = (1.0 - body.state[e].D) * body.constants.G;
    const double kappa = quad4_axisym_stiffness_hourglass_coefficient(c_hg, G_d, g);
    Vec2 Q = body.hg[e][0].head<2>();
    const Mat2 R = ms.R.topLeftCorner<2, 2>();
    hg_power = quad4_axisym_hourglass_stiffness(gamma, v, kappa, dt, R, Q, f);
    body.hg[e][0] = Vec3(Q.x(), Q.y(), 0.0);
  } else {
    const double rho = body.element_mass[e] / V;
    const double a_h = quad4_axisym_viscous_hourglass_coefficient(c_hg, rho, ms.c, g);
    hg_power = quad4_axisym_hourglass_viscous(gamma, v, a_h, f);
  }
  finish_element(body, e, V, ms, hg_power, f, sums, erode);
}

}  // namespace

FeBody make_fe_body(const std::string& name, const HexMesh& mesh, const Material& material,
                    const ModelSwitches& switches, const FeSettings& settings, const Vec3& velocity,
                    double temperature, unsigned long long seed, NodeSet& nodes) {
  FeBody body =
      start_body(name, ElementKind::hex8, material, switches, settings, mesh.nodes.size(), nodes);
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const std::size_t n = body.node_begin + i;
    nodes.x0[n] = nodes.x[n] = mesh.nodes[i];
    nodes.v[n] = velocity;
    if (i < mesh.node_boundary.size()) nodes.boundary[n] = mesh.node_boundary[i];
  }
  const std::size_t ne = mesh.hexes.size();
  body.conn.resize(ne);
  body.volume0.resize(ne);
  body.element_mass.resize(ne);
  body.volume.resize(ne);
  body.char_length.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    Hex8Vectors x;
    for (int a = 0; a < 8; ++a) {
      body.conn[e][a] = global_node(name, e, mesh.hexes[e][a], mesh.nodes.size(), body.node_begin);
      x[a] = nodes.x[body.conn[e][a]];
    }
    const double V = hex8_geometry(hex8_modes(x)).volume;
    if (!(V > 0.0)) throw_bad_element(name, e, V);
    body.volume0[e] = body.volume[e] = V;
    body.element_mass[e] = material.density * V;
    body.char_length[e] = hex8_characteristic_length(x, V);
  }
  finish_body(body, nodes, temperature, seed);
  return body;
}

FeBody make_fe_body(const std::string& name, const AxisymMesh& mesh, const Material& material,
                    const ModelSwitches& switches, const FeSettings& settings, const Vec3& velocity,
                    double temperature, unsigned long long seed, NodeSet& nodes) {
  FeBody body = start_body(name, ElementKind::quad4_axisym, material, switches, settings,
                           mesh.nodes.size(), nodes);
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const std::size_t n = body.node_begin + i;
    nodes.x0[n] = nodes.x[n] = Vec3(mesh.nodes[i].x(), mesh.nodes[i].y(), 0.0);
    nodes.v[n] = Vec3(0.0, velocity.z(), 0.0);
    if (i < mesh.node_boundary.size()) nodes.boundary[n] = mesh.node_boundary[i];
  }
  const std::size_t ne = mesh.quads.size();
  body.conn.resize(ne);
  body.volume0.resize(ne);
  body.element_mass.resize(ne);
  body.volume.resize(ne);
  body.char_length.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    Quad4Vectors x;
    body.conn[e].fill(-1);
    for (int a = 0; a < 4; ++a) {
      body.conn[e][a] = global_node(name, e, mesh.quads[e][a], mesh.nodes.size(), body.node_begin);
      x[a] = nodes.x[body.conn[e][a]].head<2>();
    }
    const Quad4Gradient g = quad4_axisym_gradient(x);
    if (!(g.area > 0.0) || !(g.volume > 0.0)) throw_bad_element(name, e, g.volume);
    body.volume0[e] = body.volume[e] = g.volume;
    body.element_mass[e] = material.density * g.volume;
    body.char_length[e] = quad4_axisym_characteristic_length(x, g.area);
  }
  finish_body(body, nodes, temperature, seed);
  return body;
}

FeStepResult fe_internal_forces(FeBody& body, NodeSet& nodes, double dt) {
  FeStepResult result;
  result.dt_stable = infinity;
  const std::size_t ne = body.num_elements();
  const std::size_t num_blocks = (ne + block_size - 1) / block_size;
  std::vector<BlockSums> blocks(num_blocks);
  std::vector<std::vector<int>> erode(static_cast<std::size_t>(max_threads()));
  const bool hex = body.kind == ElementKind::hex8;
  const long long nb = static_cast<long long>(num_blocks);

  SPLAT_OMP(omp parallel for schedule(static) if (nb >= min_parallel_blocks))
  for (long long bk = 0; bk < nb; ++bk) {
    const std::size_t k = static_cast<std::size_t>(bk);
    BlockSums& sums = blocks[k];
    std::vector<int>& my_erode = erode[static_cast<std::size_t>(thread_id())];
    const std::size_t end = std::min(ne, (k + 1) * block_size);
    for (std::size_t e = k * block_size; e < end; ++e) {
      if (!body.active[e]) continue;
      if (hex) {
        hex_element(body, nodes, e, dt, sums, my_erode);
      } else {
        quad_element(body, nodes, e, dt, sums, my_erode);
      }
    }
  }

  for (const BlockSums& s : blocks) {
    result.dt_stable = std::min(result.dt_stable, s.dt_min);
    result.hourglass_power += s.hourglass_power;
    result.viscosity_power += s.viscosity_power;
    result.max_return_iterations = std::max(result.max_return_iterations, s.max_iterations);
    result.return_failed = result.return_failed || s.failed;
    result.inverted += s.inverted;
  }
  for (const auto& list : erode)
    result.to_erode.insert(result.to_erode.end(), list.begin(), list.end());
  std::sort(result.to_erode.begin(), result.to_erode.end());

  // Deterministic gather: each node sums its elements' contributions in CSR order.
  const long long first = static_cast<long long>(body.node_begin);
  const long long last = static_cast<long long>(body.node_end);
  SPLAT_OMP(omp parallel for schedule(static) if (last - first >= min_parallel_nodes))
  for (long long n = first; n < last; ++n) {
    const std::size_t local = static_cast<std::size_t>(n - first);
    const int begin = body.node_elem_offsets[local];
    const int end = body.node_elem_offsets[local + 1];
    Vec3 sum = Vec3::Zero();
    for (int k = begin; k < end; ++k) {
      const int entry = body.node_elem_entries[static_cast<std::size_t>(k)];
      const std::size_t e = static_cast<std::size_t>(entry >> 3);
      if (body.active[e]) sum += body.elem_force[e][static_cast<std::size_t>(entry & 7)];
    }
    nodes.f[static_cast<std::size_t>(n)] += sum;
  }
  return result;
}

ErodedEnergy erode_element(FeBody& body, NodeSet& nodes, int e) {
  ErodedEnergy out;
  const std::size_t k = static_cast<std::size_t>(e);
  if (!body.active[k]) return out;
  body.active[k] = 0;
  const int npe = body.nodes_per_element();
  const double share = body.element_mass[k] / npe;
  for (int a = 0; a < npe; ++a) {
    const std::size_t n = static_cast<std::size_t>(body.conn[k][a]);
    const double m = std::min(share, nodes.mass[n]);
    out.kinetic += 0.5 * m * nodes.v[n].squaredNorm();
    nodes.mass[n] = std::max(nodes.mass[n] - share, 0.0);
  }
  out.internal = body.volume0[k] * body.state[k].e;
  out.mass = body.element_mass[k];
  body.elem_force[k].fill(Vec3::Zero());
  body.q[k] = 0.0;
  return out;
}

double fe_internal_energy(const FeBody& body) {
  double sum = 0.0;
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    if (body.active[e]) sum += body.volume0[e] * body.state[e].e;
  }
  return sum;
}

double fe_body_mass(const FeBody& body) {
  double sum = 0.0;
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    if (body.active[e]) sum += body.element_mass[e];
  }
  return sum;
}

}  // namespace splat
