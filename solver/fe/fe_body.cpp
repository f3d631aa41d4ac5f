// The lane kernels (Lane<8> = 64-byte vectors) are forced inline into the
// target_clones block loops below, so GCC's note that returning such vectors
// by value changes the ABI between the baseline and AVX-512 code does not
// apply to them and is silenced here. A function that is NOT inlined (a
// lambda returning a lane vector was one, in the sanitizer build) is reported
// without a source location, which this pragma does not silence: the build
// fails instead of miscompiling.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "solver/fe/fe_body.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "solver/common/simd_lanes.hpp"
#include "solver/fe/bulk_viscosity.hpp"
#include "solver/fe/hex8.hpp"
#include "solver/fe/quad4_axisym.hpp"
#include "solver/material/damage.hpp"
#include "solver/material/point_update_fast.hpp"

#ifdef _OPENMP
#include <omp.h>
#define SPLAT_OMP(directive) _Pragma(#directive)
#else
#define SPLAT_OMP(directive)
#endif

#ifndef SPLAT_FE_LANE_WIDTH
#define SPLAT_FE_LANE_WIDTH 8
#endif

namespace splat {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Elements per reduction block: partial sums are taken over fixed blocks and
// combined in block order, so they do not depend on the thread count.
constexpr std::size_t block_size = 64;
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
// its cap (if erosion_on_damage), non-positive volume, or a CFL bound below
// erosion_min_time_step.
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
  if (s.erosion_on_damage && body.switches.damage && dm.initiation != DamageInitiation::none &&
      body.state[e].D >= dm.D_max - 1e-12) {
    return true;
  }
  return s.erosion_min_time_step > 0.0 && dt_e < s.erosion_min_time_step;
}

// Element e's force on its local node a: components 0 .. force_components() - 1
// of f (the axisymmetric z entry, always 0, is not stored).
inline void store_element_force(FeBody& body, std::size_t e, int a, double f0, double f1,
                                double f2) {
  body.elem_force[body.force_index(e, a, 0)] = f0;
  body.elem_force[body.force_index(e, a, 1)] = f1;
  if (body.kind == ElementKind::hex8) body.elem_force[body.force_index(e, a, 2)] = f2;
}
inline void zero_forces(FeBody& body, std::size_t e) {
  for (int a = 0; a < body.nodes_per_element(); ++a) store_element_force(body, e, a, 0, 0, 0);
}

// Books an element's step whose forces the caller has written to
// elem_force[e]: an element flagged for erosion exerts no force (they are
// zeroed) and sets no time-step bound (it is removed before the next step).
inline void finish_element(FeBody& body, std::size_t e, double V, double dt_e, double q_power,
                           double hourglass_power, BlockSums& sums, std::vector<int>& erode) {
  if (to_be_eroded(body, e, V, dt_e, sums)) {
    zero_forces(body, e);
    erode.push_back(static_cast<int>(e));
    return;
  }
  sums.dt_min = std::min(sums.dt_min, dt_e);
  sums.hourglass_power += hourglass_power;
  sums.viscosity_power += q_power;
}
inline void finish_element(FeBody& body, std::size_t e, double V, const MaterialStep& ms,
                           double hourglass_power, BlockSums& sums, std::vector<int>& erode) {
  finish_element(body, e, V, ms.dt_e, ms.q_power, hourglass_power, sums, erode);
}

// An element with non-positive volume: no force, no material update.
inline void inverted_element(FeBody& body, std::size_t e, BlockSums& sums,
                             std::vector<int>& erode) {
  zero_forces(body, e);
  if (to_be_eroded(body, e, 0.0, infinity, sums)) erode.push_back(static_cast<int>(e));
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

// Elements per lane group (4 or 8 doubles per vector, simd_lanes.hpp).
constexpr int lane_width = SPLAT_FE_LANE_WIDTH;
static_assert(block_size % lane_width == 0);

// Lane l of the result is f(l).
template <int W, class F>
SPLAT_LANE_INLINE Lane<W> lanes_of(F&& f) {
  if constexpr (W == 4) {
    return Lane<4>{f(0), f(1), f(2), f(3)};
  } else {
    static_assert(W == 8);
    return Lane<8>{f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7)};
  }
}

// Lane indices of a two-source permute of Lane<8> vectors (__builtin_shuffle:
// 0-7 pick from the first source, 8-15 from the second).
using LaneIndex8 = long long __attribute__((vector_size(64)));

// Components (x, y, z) of the 8 consecutive Vec3 at p as three lanes: three
// whole-vector loads and two two-source permutes per component, in place of
// 24 single loads and lane inserts.
SPLAT_LANE_INLINE void load_vec3_run(const Vec3* p, Lane<8> out[3]) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  const char* bytes = reinterpret_cast<const char*>(p);
  Lane<8> A, B, C;
  std::memcpy(&A, bytes, sizeof A);
  std::memcpy(&B, bytes + sizeof A, sizeof B);
  std::memcpy(&C, bytes + 2 * sizeof A, sizeof C);
  // Component c of node l is double 3 l + c of the 24.
  out[0] = __builtin_shuffle(__builtin_shuffle(A, B, LaneIndex8{0, 3, 6, 9, 12, 15, 0, 0}), C,
                             LaneIndex8{0, 1, 2, 3, 4, 5, 10, 13});
  out[1] = __builtin_shuffle(__builtin_shuffle(A, B, LaneIndex8{1, 4, 7, 10, 13, 0, 0, 0}), C,
                             LaneIndex8{0, 1, 2, 3, 4, 8, 11, 14});
  out[2] = __builtin_shuffle(__builtin_shuffle(A, B, LaneIndex8{2, 5, 8, 11, 14, 0, 0, 0}), C,
                             LaneIndex8{0, 1, 2, 3, 4, 9, 12, 15});
}

// Block-local data of the phased element loop, one entry per position p of
// the block's active elements (element order), lanes grouped W at a time.
template <int W, int NodesPerElement>
struct BlockScratch {
  static constexpr int groups = static_cast<int>(block_size) / W;
  // Axisymmetric quads: L, D, the rotation and the stress deviator have no
  // r-theta or z-theta terms (they stay exactly zero), so only the r-z block
  // and the hoop entry are loaded and stored.
  static constexpr bool axisymmetric = NodesPerElement == 4;
  int count = 0;            // active elements of the block
  int element[block_size];  // element id at position p
  bool valid[block_size];   // not inverted: runs the material update and forces
  Lane<W> L_c[groups];      // characteristic length, m
  Lane<W> tr_D[groups];     // tr(D) at mid-step, 1/s (0 for dt = 0)
  Lane<W> R[groups][3][3];  // incremental rotation (I for dt = 0)
  bool run[groups];         // the group's lanes are one node run (FeBody::node_run)
  // The new deviator (xx, yy, zz, xy, yz, xz) and pressure of groups whose
  // lanes phase (a) all advanced (lanes_done): phase (c) takes them from here
  // instead of loading them back from the states.
  bool lanes_done[groups];
  Lane<W> s_new[groups][6];
  Lane<W> p_new[groups];
  double dt_e[block_size];      // CFL bound, s
  double q_power[block_size];   // bulk-viscosity power, W
  double hg_power[block_size];  // hourglass power, W
  // Largest return-mapping iteration count of the points the lanes advanced.
  int lane_iterations = 0;
  // Inputs of the general material update of the points the lanes left.
  int mat_count = 0;
  int mat_index[block_size];
  Mat3 d_eps[block_size];
  double J_new[block_size];
  double length[block_size];

  // Element of lane l of group g (the last one repeated past the end).
  int lane_element(int g, int l) const { return element[std::min(g * W + l, count - 1)]; }
  bool real(int g, int l) const { return g * W + l < count && valid[g * W + l]; }
  // Every lane of group g is a valid element.
  bool full(int g) const {
    if (g * W + W > count) return false;
    for (int l = 0; l < W; ++l)
      if (!valid[g * W + l]) return false;
    return true;
  }
};

// A per-element field (volume0, element_mass) over lane group g: one
// whole-vector load when the group's elements are consecutive (the active
// elements are listed in increasing order), else lane by lane.
template <int W, class Scratch>
SPLAT_LANE_INLINE Lane<W> element_lanes(const std::vector<double>& field, const Scratch& s, int g) {
  const int p = g * W;
  if (p + W <= s.count && s.element[p + W - 1] == s.element[p] + W - 1) {
    Lane<W> v;
    std::memcpy(&v, &field[std::size_t(s.element[p])], sizeof v);
    return v;
  }
  return lanes_of<W>([&](int l)
                         SPLAT_LANE_LAMBDA { return field[std::size_t(s.lane_element(g, l))]; });
}

// The material states of lane group g (the block's last element repeated in
// the lanes past its end).
template <int W, class Scratch>
SPLAT_LANE_INLINE void group_states(FeBody& body, const Scratch& s, int g, PointState* st[W]) {
  for (int l = 0; l < W; ++l) st[l] = &body.state[std::size_t(s.lane_element(g, l))];
}

// One field, or one stress entry, of those states. Plain loops, not lanes_of:
// in the large block loops GCC left the lambda of a pointer-to-member load out
// of line, compiled for the baseline instruction set and called lane by lane.
template <int W>
SPLAT_LANE_INLINE Lane<W> state_lanes(PointState* const st[W], double PointState::*field) {
  Lane<W> v;
  for (int l = 0; l < W; ++l) v[l] = st[l]->*field;
  return v;
}
template <int W>
SPLAT_LANE_INLINE Lane<W> stress_entry_lanes(PointState* const st[W], int i, int j) {
  Lane<W> v;
  for (int l = 0; l < W; ++l) v[l] = st[l]->s(i, j);
  return v;
}

// Positions and velocities of the nodes of lane group g (components 0 .. C - 1
// of local nodes 0 .. N - 1): whole-vector loads when the group's elements
// are one node run (sets s.run[g]), else lane by lane.
template <int W, int C, int N, class Field, class Scratch>
SPLAT_LANE_INLINE void load_group_nodes(const FeBody& body, const NodeSet& nodes, int g, Scratch& s,
                                        Field& x, Field& v) {
  const int p = g * W;
  s.run[g] = false;
  if constexpr (W == static_cast<int>(fe_force_lanes)) {
    const int e0 = s.element[p];
    // The active elements are listed in increasing order, so W of them
    // spanning W ids are consecutive.
    s.run[g] = p + W <= s.count && s.element[p + W - 1] == e0 + W - 1 && e0 % W == 0 &&
               body.node_run[std::size_t(e0)] != 0;
    if (s.run[g]) {
      const std::array<int, 8>& cn = body.conn[std::size_t(e0)];
      for (int a = 0; a < N; ++a) {
        Lane<W> xa[3], va[3];
        load_vec3_run(&nodes.x[std::size_t(cn[a])], xa);
        load_vec3_run(&nodes.v[std::size_t(cn[a])], va);
        for (int i = 0; i < C; ++i) {
          x.u[i][a] = xa[i];
          v.u[i][a] = va[i];
        }
      }
      return;
    }
  }
  const std::array<int, 8>* cn[W];
  for (int l = 0; l < W; ++l) cn[l] = &body.conn[std::size_t(s.lane_element(g, l))];
  for (int a = 0; a < N; ++a)
    for (int i = 0; i < C; ++i) {
      x.u[i][a] = lanes_of<W>(
          [&](int l) SPLAT_LANE_LAMBDA { return nodes.x[std::size_t((*cn[l])[a])][i]; });
      v.u[i][a] = lanes_of<W>(
          [&](int l) SPLAT_LANE_LAMBDA { return nodes.v[std::size_t((*cn[l])[a])][i]; });
    }
}

// Element forces of lane group g (components 0 .. C - 1 of local nodes
// 0 .. N - 1) into FeBody::elem_force: whole-vector stores when the group is a
// node run of valid elements (its lanes are one lane-order record), else lane
// by lane for the valid lanes.
template <int W, int C, int N, class Field, class Scratch>
SPLAT_LANE_INLINE void store_group_forces(FeBody& body, int g, const Scratch& s, const Field& f) {
  if (s.run[g] && s.full(g)) {
    // The record's rows follow one another: node a's component i is row a C + i.
    double* record = &body.elem_force[body.force_index(std::size_t(s.element[g * W]), 0, 0)];
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < C; ++i)
        std::memcpy(record + (a * C + i) * W, &f.u[i][a], sizeof(Lane<W>));
    return;
  }
  for (int l = 0; l < W; ++l) {
    if (!s.real(g, l)) continue;
    const std::size_t e = std::size_t(s.element[g * W + l]);
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < C; ++i) body.elem_force[body.force_index(e, a, i)] = f.u[i][a][l];
  }
}

// Active elements of [begin, end) in order.
template <class Scratch>
SPLAT_LANE_INLINE void list_active(const FeBody& body, std::size_t begin, std::size_t end,
                                   Scratch& s) {
  s.count = 0;
  s.mat_count = 0;
  s.lane_iterations = 0;
  for (std::size_t e = begin; e < end; ++e)
    if (body.active[e]) s.element[s.count++] = static_cast<int>(e);
}

// Phase (a), after the geometry: with L at mid-step (dt > 0), the
// Hughes-Winget rotation of st.s, R, tr(D) and the material inputs
// d_eps = sym(L) dt, J = V / V0, L_c of the group's valid lanes; for dt = 0
// R = I and tr(D) = 0 (no material update).
template <int W, class Scratch>
SPLAT_LANE_INLINE void kinematics_lanes(FeBody& body, int g, const Lane<W> L[3][3],
                                        const Lane<W>& volume, double dt, Scratch& s) {
  using V = Lane<W>;
  if (!(dt > 0.0)) {
    s.lanes_done[g] = false;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s.R[g][i][j] = V{} + (i == j ? 1.0 : 0.0);
    s.tr_D[g] = V{};
    return;
  }
  V Q[3][3];
  hughes_winget_rotation_cm<V>(0.5 * (L[2][1] - L[1][2]), 0.5 * (L[0][2] - L[2][0]),
                               0.5 * (L[1][0] - L[0][1]), dt, Q);
  PointState* st[W];
  group_states<W>(body, s, g, st);
  V S[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      S[i][j] =
          Scratch::axisymmetric && (i == 2) != (j == 2) ? V{} : stress_entry_lanes<W>(st, i, j);
  rotate_symmetric_cm<V>(Q, S);
  V D[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      s.R[g][i][j] = Q[i][j];
      D[i][j] = 0.5 * (L[i][j] + L[j][i]);
    }
  s.tr_D[g] = D[0][0] + (D[1][1] + D[2][2]);  // Eigen's trace(): d0 + (d1 + d2)
  V d_eps[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d_eps[i][j] = dt * D[i][j];
  const V J_new = volume / element_lanes<W>(body.volume0, s, g);
  // The material update of the lanes point_update_fast covers, here; the
  // others are listed for update_point_general (phase b). Either way each
  // point gets update_point's bits.
  PointFields<V> f;
  V de[6];
  for (int k = 0; k < 6; ++k) {
    f.s[k] = S[sym_row[k]][sym_col[k]];
    de[k] = d_eps[sym_row[k]][sym_col[k]];
  }
  for_each_point_field(
      f, [&](V& v, double PointState::*field) SPLAT_LANE_LAMBDA { v = state_lanes<W>(st, field); });
  V evaluations;
  const LaneMask<V> done = point_update_fast(body.material, body.constants, body.switches, f, de,
                                             J_new, dt, evaluations);
  bool all_valid = true;
  for (int l = 0; l < W && g * W + l < s.count; ++l) all_valid = all_valid && s.valid[g * W + l];
  s.lanes_done[g] = all_valid && !lane_any(!done);
  if (s.lanes_done[g]) {
    for (int k = 0; k < 6; ++k) s.s_new[g][k] = f.s[k];
    s.p_new[g] = f.p;
  }
  for (int l = 0; l < W; ++l) {
    if (!s.real(g, l)) continue;
    const int e = s.element[g * W + l];
    PointState& point = body.state[static_cast<std::size_t>(e)];
    if (done[l]) {
      for (int k = 0; k < 6; ++k) {
        point.s(sym_row[k], sym_col[k]) = f.s[k][l];
        point.s(sym_col[k], sym_row[k]) = f.s[k][l];
      }
      for_each_point_field(
          f, [&](V& v, double PointState::*field) SPLAT_LANE_LAMBDA { point.*field = v[l]; });
      s.lane_iterations = std::max(s.lane_iterations, static_cast<int>(evaluations[l]));
      continue;
    }
    Mat3& de_l = s.d_eps[s.mat_count];
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        if (!Scratch::axisymmetric || (i == 2) == (j == 2)) point.s(i, j) = S[i][j][l];
        de_l(i, j) = d_eps[i][j][l];
      }
    s.mat_index[s.mat_count] = e;
    s.J_new[s.mat_count] = J_new[l];
    s.length[s.mat_count] = s.L_c[g][l];
    ++s.mat_count;
  }
}

// Phase (b): the material update of the block's elements that the lanes of
// phase (a) left (point_update_fast said "not done": the general path).
template <class Scratch>
SPLAT_LANE_INLINE void material_block(FeBody& body, double dt, Scratch& s, BlockSums& sums) {
  sums.max_iterations = std::max(sums.max_iterations, s.lane_iterations);
  if (!(dt > 0.0)) return;
  for (int k = 0; k < s.mat_count; ++k) {
    const PointUpdateResult r =
        update_point_general(body.material, body.constants, body.switches,
                             body.state[static_cast<std::size_t>(s.mat_index[k])], s.d_eps[k],
                             s.J_new[k], dt, s.length[k]);
    sums.max_iterations = std::max(sums.max_iterations, r.iterations);
    sums.failed = sums.failed || !r.converged;
  }
}

// Phase (c), stress part: bulk viscosity q (bulk_viscosity.hpp), sigma - q I,
// the CFL bound and the viscosity power of group g, as material_step.
template <int W, class Scratch>
SPLAT_LANE_INLINE void stress_lanes(FeBody& body, int g, const Lane<W>& volume, Scratch& s,
                                    Lane<W> sigma[3][3], Lane<W>& rho) {
  using V = Lane<W>;
  const double c = body.constants.wave_speed;
  const double Q1 = body.settings.q_linear, Q2 = body.settings.q_quadratic;
  rho = element_lanes<W>(body.element_mass, s, g) / volume;
  const V L_c = s.L_c[g], tr_D = s.tr_D[g];
  const V q_raw = rho * L_c * (Q2 * L_c * tr_D * tr_D - (Q1 * c) * tr_D);
  const V q = tr_D >= V{} ? V{} : q_raw;
  const V Qv = tr_D >= V{} ? V{} : (Q1 * c) - Q2 * L_c * tr_D;
  const V dt_e = L_c / (Qv + lane_sqrt(Qv * Qv + c * c));
  const V q_power = -q * volume * tr_D;
  // sigma = s - p I (off the diagonal s - 0 p = s: the same value).
  // The new stress from phase (a) where it advanced every lane, else from the
  // states (the general path of phase (b) wrote some of them).
  static constexpr int sym_index[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
  PointState* st[W];
  if (!s.lanes_done[g]) group_states<W>(body, s, g, st);
  const V pressure = s.lanes_done[g] ? s.p_new[g] : state_lanes<W>(st, &PointState::p);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (Scratch::axisymmetric && (i == 2) != (j == 2)) {
        sigma[i][j] = V{};
        continue;
      }
      sigma[i][j] = s.lanes_done[g] ? s.s_new[g][sym_index[i][j]] : stress_entry_lanes<W>(st, i, j);
      if (i == j) sigma[i][i] = sigma[i][i] - pressure;
    }
  for (int i = 0; i < 3; ++i) sigma[i][i] -= q;
  for (int l = 0; l < W; ++l) {
    if (!s.real(g, l)) continue;
    const int p = g * W + l;
    body.q[std::size_t(s.element[p])] = q[l];
    s.dt_e[p] = dt_e[l];
    s.q_power[p] = q_power[l];
  }
}

// Phase (d): bookkeeping in element order (sums, erosion flags).
template <class Scratch>
SPLAT_LANE_INLINE void finish_block(FeBody& body, const Scratch& s, BlockSums& sums,
                                    std::vector<int>& erode) {
  for (int p = 0; p < s.count; ++p) {
    if (!s.valid[p]) continue;
    const std::size_t e = std::size_t(s.element[p]);
    finish_element(body, e, body.volume[e], s.dt_e[p], s.q_power[p], s.hg_power[p], sums, erode);
  }
}

// One block of hexahedra in phases: (a) geometry, L and rotation in lanes of
// W elements, (b) one material call for the block, (c) bulk viscosity, CFL
// bound, hourglass (either form) and forces in lanes, (d) bookkeeping in
// element order. Lane by lane the arithmetic of hex_element, so the same
// results to the bit; an inverted element takes inverted_element's path.
template <int W>
SPLAT_LANE_INLINE void hex_block_lanes(FeBody& body, const NodeSet& nodes, std::size_t begin,
                                       std::size_t end, double dt, BlockSums& sums,
                                       std::vector<int>& erode) {
  using V = Lane<W>;
  using Scratch = BlockScratch<W, 8>;
  constexpr int G = Scratch::groups;
  Scratch s;
  list_active(body, begin, end, s);
  if (s.count == 0) return;
  const int groups = (s.count + W - 1) / W;
  Hex8FieldT<V> xm[G], w[G];
  Hex8GeometryCmT<V> geo[G];

  // (a) kinematics.
  for (int g = 0; g < groups; ++g) {
    Hex8FieldT<V> x, v;
    load_group_nodes<W, 3, 8>(body, nodes, g, s, x, v);
    xm[g] = hex8_modes_cm(x);
    geo[g] = hex8_geometry_cm(xm[g]);
    const V volume = geo[g].volume;
    const V max_area2 = hex8_max_face_area2_cm(x);
    s.L_c[g] = max_area2 > V{} ? 2.0 * volume / lane_sqrt(max_area2) : V{};
    w[g] = hex8_modes_cm(v);
    for (int l = 0; l < W && g * W + l < s.count; ++l) {
      const int p = g * W + l;
      const std::size_t e = std::size_t(s.element[p]);
      body.volume[e] = volume[l];
      s.valid[p] = volume[l] > 0.0;
      if (s.valid[p]) {
        body.char_length[e] = s.L_c[g][l];
      } else {
        inverted_element(body, e, sums, erode);
      }
    }
    V L[3][3];
    if (dt > 0.0) {
      Hex8FieldT<V> mid;  // x_{n+1/2} = x - dt/2 v, mode by mode
      for (int i = 0; i < 3; ++i)
        for (int u = 0; u < 8; ++u) mid.u[i][u] = xm[g].u[i][u] - (0.5 * dt) * w[g].u[i][u];
      hex8_velocity_gradient_cm(w[g], hex8_geometry_cm(mid), L);
    } else {
      for (auto& row : L)
        for (V& c : row) c = V{};
    }
    kinematics_lanes<W>(body, g, L, volume, dt, s);
  }

  // (b) material.
  material_block(body, dt, s, sums);

  // (c) bulk viscosity, time step, hourglass, forces.
  const double c_hg = body.settings.hourglass_coefficient;
  const bool stiffness = body.settings.stiffness_hourglass;
  for (int g = 0; g < groups; ++g) {
    const V volume = geo[g].volume;
    V sigma[3][3], rho;
    stress_lanes<W>(body, g, volume, s, sigma, rho);
    V L_end[3][3], qdot[4][3], Q[4][3];
    hex8_velocity_gradient_cm(w[g], geo[g], L_end);
    hex8_hourglass_rates_cm(w[g], xm[g], L_end, qdot);
    // kappa (stiffness) or a_h (viscous): hex8_*_hourglass_coefficient, the
    // same operations, with V^(1/3)'s estimate lane by lane and its Halley
    // steps and the viscous coefficient on whole lanes.
    const V h = cbrt_positive_refine(volume, lanes_of<W>([&](int l) SPLAT_LANE_LAMBDA {
                                       return cbrt_positive_estimate(volume[l]);
                                     }));
    V coefficient = stiffness ? V{}
                              : hex8_viscous_hourglass_coefficient_of_cbrt(
                                    c_hg, rho, body.constants.wave_speed, h);
    for (int l = 0; l < W; ++l) {
      const std::size_t e = std::size_t(s.lane_element(g, l));
      if (!s.real(g, l)) {
        coefficient[l] = 0.0;
      } else if (stiffness) {
        const double G_d = (1.0 - body.state[e].D) * body.constants.G;
        coefficient[l] = hex8_stiffness_hourglass_coefficient_of_cbrt(c_hg, G_d, h[l]);
        soften_held_hourglass(body.hg_kappa[e], coefficient[l], body.hg[e].data(), 4);
      }
    }
    V power = V{};
    if (stiffness) {
      const V(&R)[3][3] = s.R[g];
      for (int k = 0; k < 4; ++k) {
        V Qk[3];
        for (int i = 0; i < 3; ++i)
          Qk[i] = lanes_of<W>([&](int l) SPLAT_LANE_LAMBDA {
            return body.hg[std::size_t(s.lane_element(g, l))][k][i];
          });
        // R Q^k in the order Eigen's 3x3 product sums it (hex8_hourglass_stiffness):
        // rows 0 and 1 in one SSE2 packet, left to right; row 2 as an unrolled
        // reduction, r_0 + (r_1 + r_2).
        for (int i = 0; i < 2; ++i)
          Q[k][i] = ((R[i][0] * Qk[0] + R[i][1] * Qk[1]) + R[i][2] * Qk[2]) +
                    (coefficient * dt) * qdot[k][i];
        Q[k][2] = (R[2][0] * Qk[0] + (R[2][1] * Qk[1] + R[2][2] * Qk[2])) +
                  (coefficient * dt) * qdot[k][2];
        power += (Q[k][0] * qdot[k][0] + Q[k][1] * qdot[k][1]) + Q[k][2] * qdot[k][2];
      }
      for (int l = 0; l < W; ++l) {
        if (!s.real(g, l)) continue;
        std::array<Vec3, 4>& held = body.hg[std::size_t(s.element[g * W + l])];
        for (int k = 0; k < 4; ++k) held[k] = Vec3(Q[k][0][l], Q[k][1][l], Q[k][2][l]);
      }
    } else {
      for (int k = 0; k < 4; ++k) {
        for (int i = 0; i < 3; ++i) Q[k][i] = coefficient * qdot[k][i];
        power += (Q[k][0] * qdot[k][0] + Q[k][1] * qdot[k][1]) + Q[k][2] * qdot[k][2];
      }
    }
    const Hex8FieldT<V> f = hex8_forces_cm(sigma, geo[g], xm[g], Q);
    for (int l = 0; l < W; ++l)
      if (s.real(g, l)) s.hg_power[g * W + l] = power[l];
    store_group_forces<W, 3, 8>(body, g, s, f);
  }

  // (d) bookkeeping.
  finish_block(body, s, sums, erode);
}

// One block of axisymmetric quads in phases, as hex_block_lanes; lane by lane
// the arithmetic of quad_element.
template <int W>
SPLAT_LANE_INLINE void quad_block_lanes(FeBody& body, const NodeSet& nodes, std::size_t begin,
                                        std::size_t end, double dt, BlockSums& sums,
                                        std::vector<int>& erode) {
  using V = Lane<W>;
  using Scratch = BlockScratch<W, 4>;
  constexpr int G = Scratch::groups;
  Scratch s;
  list_active(body, begin, end, s);
  if (s.count == 0) return;
  const int groups = (s.count + W - 1) / W;
  Quad4FieldT<V> xs[G], vs[G];
  Quad4GradientCmT<V> grad[G];

  // (a) kinematics.
  for (int g = 0; g < groups; ++g) {
    Quad4FieldT<V>& x = xs[g];
    Quad4FieldT<V>& v = vs[g];
    load_group_nodes<W, 2, 4>(body, nodes, g, s, x, v);
    grad[g] = quad4_axisym_gradient_cm(x);
    const V volume = grad[g].volume;
    s.L_c[g] = quad4_axisym_characteristic_length_cm(x, grad[g].area);
    for (int l = 0; l < W && g * W + l < s.count; ++l) {
      const int p = g * W + l;
      const std::size_t e = std::size_t(s.element[p]);
      body.volume[e] = volume[l];
      s.valid[p] = grad[g].area[l] > 0.0 && volume[l] > 0.0;
      if (s.valid[p]) {
        body.char_length[e] = s.L_c[g][l];
      } else {
        inverted_element(body, e, sums, erode);
      }
    }
    V L[3][3];
    if (dt > 0.0) {
      Quad4FieldT<V> xm;
      for (int i = 0; i < 2; ++i)
        for (int a = 0; a < 4; ++a) xm.u[i][a] = x.u[i][a] - (0.5 * dt) * v.u[i][a];
      V L2[2][2], L_thth;
      quad4_axisym_velocity_gradient_cm(v, quad4_axisym_gradient_cm(xm), L2, L_thth);
      L[0][0] = L2[0][0], L[0][1] = L2[0][1], L[0][2] = V{};
      L[1][0] = L2[1][0], L[1][1] = L2[1][1], L[1][2] = V{};
      L[2][0] = V{}, L[2][1] = V{}, L[2][2] = L_thth;
    } else {
      for (auto& row : L)
        for (V& c : row) c = V{};
    }
    kinematics_lanes<W>(body, g, L, volume, dt, s);
  }

  // (b) material.
  material_block(body, dt, s, sums);

  // (c) bulk viscosity, time step, hourglass, forces.
  const double c_hg = body.settings.hourglass_coefficient;
  const bool stiffness = body.settings.stiffness_hourglass;
  for (int g = 0; g < groups; ++g) {
    const Quad4GradientCmT<V>& gr = grad[g];
    V sigma[3][3], rho;
    stress_lanes<W>(body, g, gr.volume, s, sigma, rho);
    Quad4FieldT<V> f;
    quad4_axisym_stress_forces_cm(sigma[0][0], sigma[0][1], sigma[1][0], sigma[1][1], sigma[2][2],
                                  gr, f);
    const std::array<V, 4> gamma = quad4_axisym_hourglass_vector_cm(xs[g], gr);
    // kappa (stiffness) or a_h (viscous): quad4_axisym_*_hourglass_coefficient,
    // the same operations, the viscous one on whole lanes.
    V coefficient = stiffness ? V{}
                              : quad4_axisym_viscous_hourglass_coefficient_t(
                                    c_hg, rho, body.constants.wave_speed, gr.rbar, gr.area);
    for (int l = 0; l < W; ++l) {
      const std::size_t e = std::size_t(s.lane_element(g, l));
      if (!s.real(g, l)) {
        coefficient[l] = 0.0;
      } else if (stiffness) {
        const double G_d = (1.0 - body.state[e].D) * body.constants.G;
        coefficient[l] = quad4_axisym_stiffness_hourglass_coefficient(c_hg, G_d, gr.rbar[l]);
        soften_held_hourglass(body.hg_kappa[e], coefficient[l], body.hg[e].data(), 1);
      }
    }
    V power;
    if (stiffness) {
      const V(&R)[3][3] = s.R[g];
      V Q[2];
      for (int i = 0; i < 2; ++i)
        Q[i] = lanes_of<W>([&](int l) SPLAT_LANE_LAMBDA {
          return body.hg[std::size_t(s.lane_element(g, l))][0][i];
        });
      power = quad4_axisym_hourglass_stiffness_cm(gamma, vs[g], coefficient, dt, R[0][0], R[0][1],
                                                  R[1][0], R[1][1], Q, f);
      for (int l = 0; l < W; ++l) {
        if (!s.real(g, l)) continue;
        body.hg[std::size_t(s.element[g * W + l])][0] = Vec3(Q[0][l], Q[1][l], 0.0);
      }
    } else {
      power = quad4_axisym_hourglass_viscous_cm(gamma, vs[g], coefficient, f);
    }
    for (int l = 0; l < W; ++l)
      if (s.real(g, l)) s.hg_power[g * W + l] = power[l];
    store_group_forces<W, 2, 4>(body, g, s, f);
  }

  // (d) bookkeeping.
  finish_block(body, s, sums, erode);
}

// The block loops, compiled for AVX-512, AVX2 and the x86-64 baseline and
// chosen at run time (never -march=native); the same results on each, as
// the build has -ffp-contract=off.
__attribute__((target_clones("avx512f", "avx2", "default"))) void hex_block(
    FeBody& body, const NodeSet& nodes, std::size_t begin, std::size_t end, double dt,
    BlockSums& sums, std::vector<int>& erode) {
  hex_block_lanes<lane_width>(body, nodes, begin, end, dt, sums, erode);
}

__attribute__((target_clones("avx512f", "avx2", "default"))) void quad_block(
    FeBody& body, const NodeSet& nodes, std::size_t begin, std::size_t end, double dt,
    BlockSums& sums, std::vector<int>& erode) {
  quad_block_lanes<lane_width>(body, nodes, begin, end, dt, sums, erode);
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

// The element loop over blocks, either phased in lanes (hex_block,
// quad_block) or one element at a time, then the node gather.
FeStepResult internal_forces(FeBody& body, NodeSet& nodes, double dt, bool lanes) {
  FeStepResult result;
  result.dt_stable = infinity;
  const std::size_t ne = body.num_elements();
  const std::size_t num_blocks = (ne + block_size - 1) / block_size;
  std::vector<BlockSums> blocks(num_blocks);
  std::vector<std::vector<int>> erode(static_cast<std::size_t>(max_threads()));
  const bool hex = body.kind == ElementKind::hex8;
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
      } else if (hex) {
        hex_block(body, nodes, begin, end, dt, sums, my_erode);
      } else {
        quad_block(body, nodes, begin, end, dt, sums, my_erode);
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
