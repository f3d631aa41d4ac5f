#include "solver/fe/fe_body.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "solver/common/isa.hpp"
#include "solver/common/simd_lanes.hpp"
#include "solver/fe/bulk_viscosity.hpp"
#include "solver/fe/fe_block.hpp"
#include "solver/fe/heat_conduction.hpp"
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

using fe_block::block_size;
using fe_block::BlockSums;

constexpr double infinity = std::numeric_limits<double>::infinity();
// Smaller loops run on one thread: forking costs more than they take.
constexpr long long min_parallel_blocks = 4;

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
// then the CSR node -> (element * 8 + local node) adjacency, in element order
// (solver/contact reads it too).
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
  body.hg_kappa.assign(ne, 0.0);
  body.active.assign(ne, 1);
  const std::size_t records = (ne + fe_force_lanes - 1) / fe_force_lanes;
  body.elem_force.assign(records * fe_force_lanes * static_cast<std::size_t>(npe) *
                             static_cast<std::size_t>(body.force_components()),
                         0.0);
  body.node_run.assign(ne, 0);
  for (std::size_t e = 0; e + fe_force_lanes <= ne; e += fe_force_lanes) {
    bool run = true;
    for (std::size_t l = 1; l < fe_force_lanes && run; ++l)
      for (int a = 0; a < npe; ++a)
        run = run && body.conn[e + l][a] == body.conn[e][a] + static_cast<int>(l);
    body.node_run[e] = run ? 1 : 0;
  }

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
  if (body.elem_force.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("body '" + body.name + "': " + std::to_string(ne) +
                                " elements are more than one body can hold");
  }
  body.node_force_offsets.assign(body.node_elem_entries.size(), 0);
  for (std::size_t e = 0; e < ne; ++e) {
    for (int a = 0; a < npe; ++a) {
      const std::size_t local = static_cast<std::size_t>(body.conn[e][a]) - body.node_begin;
      const std::size_t k = static_cast<std::size_t>(fill[local]++);
      body.node_elem_entries[k] = static_cast<int>(e) * 8 + a;
      body.node_force_offsets[k] = static_cast<std::uint32_t>(body.force_index(e, a, 0));
    }
  }
  build_heat_faces(body);
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

// The scalar form of rotate_symmetric_cm (simd_lanes.hpp) for an Eigen matrix.
inline void rotate_symmetric_mat3(const double Q[3][3], Mat3& s) {
  double S[3][3];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) S[i][j] = s(i, j);
  rotate_symmetric_cm(Q, S);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) s(i, j) = S[i][j];
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
    // Jaumann rotation of the deviator (jaumann_rotate's rotation, closed
    // form), in scalars: see hughes_winget_rotation_cm.
    double Q[3][3];
    hughes_winget_rotation_cm(0.5 * (L(2, 1) - L(1, 2)), 0.5 * (L(0, 2) - L(2, 0)),
                              0.5 * (L(1, 0) - L(0, 1)), dt, Q);
    rotate_symmetric_mat3(Q, st.s);
    ms.R << Q[0][0], Q[0][1], Q[0][2], Q[1][0], Q[1][1], Q[1][2], Q[2][0], Q[2][1], Q[2][2];
    const Mat3 D = 0.5 * (L + L.transpose());
    const PointUpdateResult r =
        update_point(body.material, body.constants, body.switches, st, dt * D,
                     volume_ratio_after(st.J, dt * D.trace()), dt, L_c);
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

// Element e's force on its local node a: components 0 .. force_components() - 1
// of f (the axisymmetric z entry, always 0, is not stored).
inline void store_element_force(FeBody& body, std::size_t e, int a, double f0, double f1,
                                double f2) {
  body.elem_force[body.force_index(e, a, 0)] = f0;
  body.elem_force[body.force_index(e, a, 1)] = f1;
  if (body.kind == ElementKind::hex8) body.elem_force[body.force_index(e, a, 2)] = f2;
}
}  // namespace

void fe_block::zero_forces(FeBody& body, std::size_t e) {
  for (int a = 0; a < body.nodes_per_element(); ++a) store_element_force(body, e, a, 0, 0, 0);
}

void fe_block::flag_for_erosion(FeBody& body, std::size_t e, std::vector<int>& erode) {
  zero_forces(body, e);
  erode.push_back(static_cast<int>(e));
}

namespace {

using fe_block::finish_element;
using fe_block::inverted_element;
using fe_block::zero_forces;

inline void finish_element(FeBody& body, std::size_t e, double V, const MaterialStep& ms,
                           double hourglass_power, BlockSums& sums, std::vector<int>& erode) {
  finish_element(body, e, V, ms.dt_e, ms.q_power, hourglass_power, sums, erode);
}

void hex_element(FeBody& body, const NodeSet& nodes, std::size_t e, double dt, BlockSums& sums,
                 std::vector<int>& erode) {
  const std::array<int, 8>& cn = body.conn[e];
  Hex8Field x, v;
  for (int a = 0; a < 8; ++a) {
    const Vec3& xa = nodes.x[cn[a]];
    const Vec3& va = nodes.v[cn[a]];
    for (int i = 0; i < 3; ++i) {
      x.u[i][a] = xa[i];
      v.u[i][a] = va[i];
    }
  }
  const Hex8Field xm = hex8_modes_cm(x);
  const Hex8GeometryCm g = hex8_geometry_cm(xm);
  const double V = g.volume;
  body.volume[e] = V;
  if (!(V > 0.0)) return inverted_element(body, e, sums, erode);
  const double L_c = hex8_characteristic_length_cm(x, V);
  body.char_length[e] = L_c;
  const Hex8Field w = hex8_modes_cm(v);

  Mat3 L = Mat3::Zero();
  if (dt > 0.0) {
    Hex8Field mid;  // x_{n+1/2} = x - dt/2 v, mode by mode
    for (int i = 0; i < 3; ++i)
      for (int u = 0; u < 8; ++u) mid.u[i][u] = xm.u[i][u] - (0.5 * dt) * w.u[i][u];
    L = hex8_velocity_gradient_cm(w, hex8_geometry_cm(mid));
  }
  const MaterialStep ms = material_step(body, e, L, dt, V, L_c, sums);

  const std::array<Vec3, 4> qdot = hex8_hourglass_rates_cm(w, xm, hex8_velocity_gradient_cm(w, g));
  const double c_hg = body.settings.hourglass_coefficient;
  double hg_power = 0.0;
  std::array<Vec3, 4> Q;
  if (body.settings.stiffness_hourglass) {
    const double G_d = (1.0 - body.state[e].D) * body.constants.G;
    const double kappa = hex8_stiffness_hourglass_coefficient(c_hg, G_d, V);
    soften_held_hourglass(body.hg_kappa[e], kappa, body.hg[e].data(), 4);
    hg_power = hex8_hourglass_stiffness(qdot, kappa, dt, ms.R, body.hg[e]);
    Q = body.hg[e];
  } else {
    const double rho = body.element_mass[e] / V;
    const double a_h = hex8_viscous_hourglass_coefficient(c_hg, rho, ms.c, V);
    hg_power = hex8_hourglass_viscous(qdot, a_h, Q);
  }
  const Hex8Field f = hex8_forces_cm(ms.sigma, g, xm, Q);
  for (int a = 0; a < 8; ++a) store_element_force(body, e, a, f.u[0][a], f.u[1][a], f.u[2][a]);
  finish_element(body, e, V, ms, hg_power, sums, erode);
}

void quad_element(FeBody& body, const NodeSet& nodes, std::size_t e, double dt, BlockSums& sums,
                  std::vector<int>& erode) {
  const std::array<int, 8>& cn = body.conn[e];
  Quad4Field x, v;
  for (int a = 0; a < 4; ++a) {
    const Vec3& xa = nodes.x[cn[a]];
    const Vec3& va = nodes.v[cn[a]];
    for (int i = 0; i < 2; ++i) {
      x.u[i][a] = xa[i];
      v.u[i][a] = va[i];
    }
  }
  const Quad4GradientCm g = quad4_axisym_gradient_cm(x);
  const double V = g.volume;
  body.volume[e] = V;
  if (!(g.area > 0.0) || !(V > 0.0)) return inverted_element(body, e, sums, erode);
  const double L_c = quad4_axisym_characteristic_length_cm(x, g.area);
  body.char_length[e] = L_c;

  Mat3 L = Mat3::Zero();
  if (dt > 0.0) {
    Quad4Field xm;
    for (int i = 0; i < 2; ++i)
      for (int a = 0; a < 4; ++a) xm.u[i][a] = x.u[i][a] - (0.5 * dt) * v.u[i][a];
    L = quad4_axisym_velocity_gradient_cm(v, quad4_axisym_gradient_cm(xm));
  }
  const MaterialStep ms = material_step(body, e, L, dt, V, L_c, sums);

  Quad4Field f;
  quad4_axisym_stress_forces_cm(ms.sigma, g, f);
  const std::array<double, 4> gamma = quad4_axisym_hourglass_vector_cm(x, g);
  const double c_hg = body.settings.hourglass_coefficient;
  double hg_power = 0.0;
  if (body.settings.stiffness_hourglass) {
    const double G_d = (1.0 - body.state[e].D) * body.constants.G;
    const double kappa = quad4_axisym_stiffness_hourglass_coefficient(c_hg, G_d, g.rbar);
    soften_held_hourglass(body.hg_kappa[e], kappa, body.hg[e].data(), 1);
    Vec3& Q = body.hg[e][0];
    double q[2] = {Q.x(), Q.y()};
    hg_power = quad4_axisym_hourglass_stiffness_cm(gamma, v, kappa, dt, ms.R, q, f);
    Q = Vec3(q[0], q[1], 0.0);
  } else {
    const double rho = body.element_mass[e] / V;
    const double a_h = quad4_axisym_viscous_hourglass_coefficient(c_hg, rho, ms.c, g.rbar, g.area);
    hg_power = quad4_axisym_hourglass_viscous_cm(gamma, v, a_h, f);
  }
  for (int a = 0; a < 4; ++a) store_element_force(body, e, a, f.u[0][a], f.u[1][a], 0.0);
  finish_element(body, e, V, ms, hg_power, sums, erode);
}

// One element at a time through hex_element / quad_element (the slow
// obvious path, fe_internal_forces_one_by_one).
void one_by_one_block(FeBody& body, const NodeSet& nodes, std::size_t begin, std::size_t end,
                      double dt, BlockSums& sums, std::vector<int>& erode) {
  for (std::size_t e = begin; e < end; ++e) {
    if (!body.active[e]) continue;
    if (body.kind == ElementKind::hex8) {
      hex_element(body, nodes, e, dt, sums, erode);
    } else {
      quad_element(body, nodes, e, dt, sums, erode);
    }
  }
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

namespace {

// The phased block loops compiled for `isa` (fe_blocks_isa.cpp).
fe_block::BlockLoops block_loops(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v4:
      return fe_block::isa_v4::block_loops();
    case Isa::x86_64_v3:
      return fe_block::isa_v3::block_loops();
    case Isa::baseline:
      break;
  }
  return fe_block::isa_baseline::block_loops();
}

// The element loop over blocks, either phased in lanes (the block loops of
// fe_block_lanes.hpp) or one element at a time, then the node gather.
FeStepResult internal_forces(FeBody& body, NodeSet& nodes, double dt, bool lanes) {
  FeStepResult result;
  result.dt_stable = infinity;
  const std::size_t ne = body.num_elements();
  const std::size_t num_blocks = (ne + block_size - 1) / block_size;
  std::vector<BlockSums> blocks(num_blocks);
  std::vector<std::vector<int>> erode(static_cast<std::size_t>(max_threads()));
  const bool hex = body.kind == ElementKind::hex8;
  const fe_block::BlockLoops loops = block_loops(active_isa());
  const long long nb = static_cast<long long>(num_blocks);

  const long long first = static_cast<long long>(body.node_begin);
  const long long last = static_cast<long long>(body.node_end);

  // One parallel region (one fork and join per step) for the element loop
  // and the node gather, which waits for it at the implicit barrier.
  SPLAT_OMP(omp parallel if (nb >= min_parallel_blocks)) {
    SPLAT_OMP(omp for schedule(static))
    for (long long bk = 0; bk < nb; ++bk) {
      const std::size_t k = static_cast<std::size_t>(bk);
      BlockSums& sums = blocks[k];
      std::vector<int>& my_erode = erode[static_cast<std::size_t>(thread_id())];
      const std::size_t begin = k * block_size, end = std::min(ne, (k + 1) * block_size);
      if (!lanes) {
        one_by_one_block(body, nodes, begin, end, dt, sums, my_erode);
      } else {
        (hex ? loops.hex : loops.quad)(body, nodes, begin, end, dt, sums, my_erode);
      }
    }

    // Deterministic gather: each node sums its elements' contributions in CSR
    // order. An eroded element's forces were zeroed when it was removed
    // (erode_element) and are never written again, so no activity test.
    SPLAT_OMP(omp for schedule(static))
    for (long long n = first; n < last; ++n) {
      const std::size_t local = static_cast<std::size_t>(n - first);
      const int begin = body.node_elem_offsets[local];
      const int end = body.node_elem_offsets[local + 1];
      Vec3 sum = Vec3::Zero();
      for (int k = begin; k < end; ++k) {
        const double* fa = &body.elem_force[body.node_force_offsets[static_cast<std::size_t>(k)]];
        sum.x() += fa[0];
        sum.y() += fa[fe_force_lanes];
        if (hex) sum.z() += fa[2 * fe_force_lanes];
      }
      nodes.f[static_cast<std::size_t>(n)] += sum;
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
  return result;
}

}  // namespace

FeStepResult fe_internal_forces(FeBody& body, NodeSet& nodes, double dt) {
  return internal_forces(body, nodes, dt, true);
}

FeStepResult fe_internal_forces_one_by_one(FeBody& body, NodeSet& nodes, double dt) {
  return internal_forces(body, nodes, dt, false);
}

namespace {

// Whether global node n still belongs to an active element of `body`.
bool node_in_active_element(const FeBody& body, std::size_t n) {
  const std::size_t local = n - body.node_begin;
  for (int k = body.node_elem_offsets[local]; k < body.node_elem_offsets[local + 1]; ++k) {
    if (body.active[static_cast<std::size_t>(body.node_elem_entries[k] / 8)]) return true;
  }
  return false;
}

}  // namespace

double node_element_length(const FeBody& body, std::size_t n) {
  double length = std::numeric_limits<double>::infinity();
  const std::size_t local = n - body.node_begin;
  for (int k = body.node_elem_offsets[local]; k < body.node_elem_offsets[local + 1]; ++k) {
    const std::size_t e = static_cast<std::size_t>(body.node_elem_entries[k] / 8);
    if (body.active[e]) length = std::min(length, body.char_length[e]);
  }
  return length;
}

ErodedEnergy erode_element(FeBody& body, NodeSet& nodes, int e) {
  ErodedEnergy out;
  const std::size_t k = static_cast<std::size_t>(e);
  if (!body.active[k]) return out;
  body.active[k] = 0;
  const int npe = body.nodes_per_element();
  // A node keeps its whole mass while an active element still holds it (as
  // explicit codes do: removing the eroded element's share would leave the
  // neighbours of an eroded rim on nodes of a sliver's mass, which the next
  // contact or element force flings off); a node left without an active
  // element leaves the model with all its mass and kinetic energy.
  for (int a = 0; a < npe; ++a) {
    const std::size_t n = static_cast<std::size_t>(body.conn[k][a]);
    if (node_in_active_element(body, n)) continue;
    out.kinetic += 0.5 * nodes.mass[n] * nodes.v[n].squaredNorm();
    nodes.mass[n] = 0.0;
  }
  out.internal = body.volume0[k] * body.state[k].e;
  out.mass = body.element_mass[k];
  zero_forces(body, k);
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
