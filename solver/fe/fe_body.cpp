#include "solver/fe/fe_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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
  body.hg_kappa.assign(ne, 0.0);
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

// hughes_winget_rotation and rotate_symmetric (fe_body.hpp), same arithmetic,
// in scalars for the element loop: Eigen's comma initialiser and 3x3 products
// mixed scalar stores with packet loads of the same memory here
// (store-forwarding stalls). (w21, w02, w10) are W(2,1), W(0,2), W(1,0).
inline void hughes_winget_rotation_cm(double w21, double w02, double w10, double dt,
                                      double Q[3][3]) {
  const double h = 0.5 * dt;
  const double a0 = h * w21, a1 = h * w02, a2 = h * w10;
  const double a_sq = a0 * a0 + a1 * a1 + a2 * a2;
  const double c = 2.0 / (1.0 + a_sq);
  const double d = 1.0 - c * a_sq;
  Q[0][0] = d + c * a0 * a0, Q[0][1] = c * (a0 * a1 - a2), Q[0][2] = c * (a0 * a2 + a1);
  Q[1][0] = c * (a0 * a1 + a2), Q[1][1] = d + c * a1 * a1, Q[1][2] = c * (a1 * a2 - a0);
  Q[2][0] = c * (a0 * a2 - a1), Q[2][1] = c * (a1 * a2 + a0), Q[2][2] = d + c * a2 * a2;
}

// s <- Q s Q^T for a symmetric s (the six distinct entries, exactly symmetric).
inline void rotate_symmetric_cm(const double Q[3][3], Mat3& s) {
  double S[3][3], T[3][3];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) S[i][j] = s(i, j);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) T[i][k] = Q[i][0] * S[0][k] + Q[i][1] * S[1][k] + Q[i][2] * S[2][k];
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      const double r = T[i][0] * Q[j][0] + T[i][1] * Q[j][1] + T[i][2] * Q[j][2];
      s(i, j) = r;
      s(j, i) = r;
    }
  }
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
    rotate_symmetric_cm(Q, st.s);
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

// Books an element's step whose forces the caller has written to
// elem_force[e]: an element flagged for erosion exerts no force (they are
// zeroed) and sets no time-step bound (it is removed before the next step).
inline void finish_element(FeBody& body, std::size_t e, double V, const MaterialStep& ms,
                           double hourglass_power, BlockSums& sums, std::vector<int>& erode) {
  if (to_be_eroded(body, e, V, ms.dt_e, sums)) {
    body.elem_force[e].fill(Vec3::Zero());
    erode.push_back(static_cast<int>(e));
    return;
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
  std::array<Vec3, 8>& out = body.elem_force[e];
  for (int a = 0; a < 8; ++a) out[a] = Vec3(f.u[0][a], f.u[1][a], f.u[2][a]);
  finish_element(body, e, V, ms, hg_power, sums, erode);
}

// Two neighbouring elements at once, lane l = element e + l: the geometry,
// gradient and force kernels run on Pair (hex8.hpp), two elements per SSE2
// instruction, lane by lane the arithmetic of hex_element, so the results are
// the same to the bit; the material update and hourglass forces run element by
// element, and the sums are booked in element order. Falls back to
// hex_element for each element when either is inverted.
void hex_element_pair(FeBody& body, const NodeSet& nodes, std::size_t e, double dt, BlockSums& sums,
                      std::vector<int>& erode) {
  const std::array<int, 8>& c0 = body.conn[e];
  const std::array<int, 8>& c1 = body.conn[e + 1];
  Hex8FieldT<Pair> x, v;
  for (int a = 0; a < 8; ++a) {
    const Vec3& x0 = nodes.x[c0[a]];
    const Vec3& x1 = nodes.x[c1[a]];
    const Vec3& v0 = nodes.v[c0[a]];
    const Vec3& v1 = nodes.v[c1[a]];
    for (int i = 0; i < 3; ++i) {
      x.u[i][a] = make_pair(x0[i], x1[i]);
      v.u[i][a] = make_pair(v0[i], v1[i]);
    }
  }
  const Hex8FieldT<Pair> xm = hex8_modes_cm(x);
  const Hex8GeometryCmT<Pair> g = hex8_geometry_cm(xm);
  const double V[2] = {g.volume[0], g.volume[1]};
  if (!(V[0] > 0.0) || !(V[1] > 0.0)) {
    hex_element(body, nodes, e, dt, sums, erode);
    hex_element(body, nodes, e + 1, dt, sums, erode);
    return;
  }
  const Pair max_area2 = hex8_max_face_area2_cm(x);
  const Pair lc = 2.0 * g.volume / lane_sqrt(max_area2);
  double L_c[2];
  for (int l = 0; l < 2; ++l) {
    L_c[l] = max_area2[l] > 0.0 ? lc[l] : 0.0;
    body.volume[e + l] = V[l];
    body.char_length[e + l] = L_c[l];
  }
  const Hex8FieldT<Pair> w = hex8_modes_cm(v);

  Pair L[3][3];
  if (dt > 0.0) {
    Hex8FieldT<Pair> mid;  // x_{n+1/2} = x - dt/2 v, mode by mode
    for (int i = 0; i < 3; ++i)
      for (int u = 0; u < 8; ++u) mid.u[i][u] = xm.u[i][u] - (0.5 * dt) * w.u[i][u];
    hex8_velocity_gradient_cm(w, hex8_geometry_cm(mid), L);
  } else {
    for (auto& row : L)
      for (Pair& c : row) c = Pair{};
  }
  MaterialStep ms[2];
  for (int l = 0; l < 2; ++l) {
    Mat3 Ll;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) Ll(i, j) = L[i][j][l];
    ms[l] = material_step(body, e + l, Ll, dt, V[l], L_c[l], sums);
  }

  Pair L_end[3][3], qdot[4][3];
  hex8_velocity_gradient_cm(w, g, L_end);
  hex8_hourglass_rates_cm(w, xm, L_end, qdot);
  const double c_hg = body.settings.hourglass_coefficient;
  double hg_power[2];
  std::array<Vec3, 4> Q[2];
  for (int l = 0; l < 2; ++l) {
    const std::size_t el = e + static_cast<std::size_t>(l);
    std::array<Vec3, 4> q;
    for (int k = 0; k < 4; ++k) q[k] = Vec3(qdot[k][0][l], qdot[k][1][l], qdot[k][2][l]);
    if (body.settings.stiffness_hourglass) {
      const double G_d = (1.0 - body.state[el].D) * body.constants.G;
      const double kappa = hex8_stiffness_hourglass_coefficient(c_hg, G_d, V[l]);
      soften_held_hourglass(body.hg_kappa[el], kappa, body.hg[el].data(), 4);
      hg_power[l] = hex8_hourglass_stiffness(q, kappa, dt, ms[l].R, body.hg[el]);
      Q[l] = body.hg[el];
    } else {
      const double rho = body.element_mass[el] / V[l];
      const double a_h = hex8_viscous_hourglass_coefficient(c_hg, rho, ms[l].c, V[l]);
      hg_power[l] = hex8_hourglass_viscous(q, a_h, Q[l]);
    }
  }
  Pair sigma[3][3], Qp[4][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) sigma[i][j] = make_pair(ms[0].sigma(i, j), ms[1].sigma(i, j));
    for (int k = 0; k < 4; ++k) Qp[k][i] = make_pair(Q[0][k][i], Q[1][k][i]);
  }
  const Hex8FieldT<Pair> f = hex8_forces_cm(sigma, g, xm, Qp);
  for (int l = 0; l < 2; ++l) {
    std::array<Vec3, 8>& out = body.elem_force[e + l];
    for (int a = 0; a < 8; ++a) out[a] = Vec3(f.u[0][a][l], f.u[1][a][l], f.u[2][a][l]);
    finish_element(body, e + l, V[l], ms[l], hg_power[l], sums, erode);
  }
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
  std::array<Vec3, 8>& out = body.elem_force[e];
  for (int a = 0; a < 4; ++a) out[a] = Vec3(f.u[0][a], f.u[1][a], 0.0);
  finish_element(body, e, V, ms, hg_power, sums, erode);
}

// Two neighbouring quads at once in the lanes of Pair, as hex_element_pair:
// lane by lane the arithmetic of quad_element (viscous hourglass control
// only), so the same results to the bit. Falls back to quad_element for each
// element when either is inverted.
void quad_element_pair(FeBody& body, const NodeSet& nodes, std::size_t e, double dt,
                       BlockSums& sums, std::vector<int>& erode) {
  const std::array<int, 8>& c0 = body.conn[e];
  const std::array<int, 8>& c1 = body.conn[e + 1];
  Quad4FieldT<Pair> x, v;
  for (int a = 0; a < 4; ++a) {
    const Vec3& x0 = nodes.x[c0[a]];
    const Vec3& x1 = nodes.x[c1[a]];
    const Vec3& v0 = nodes.v[c0[a]];
    const Vec3& v1 = nodes.v[c1[a]];
    for (int i = 0; i < 2; ++i) {
      x.u[i][a] = make_pair(x0[i], x1[i]);
      v.u[i][a] = make_pair(v0[i], v1[i]);
    }
  }
  const Quad4GradientCmT<Pair> g = quad4_axisym_gradient_cm(x);
  const double V[2] = {g.volume[0], g.volume[1]};
  if (!(g.area[0] > 0.0) || !(V[0] > 0.0) || !(g.area[1] > 0.0) || !(V[1] > 0.0)) {
    quad_element(body, nodes, e, dt, sums, erode);
    quad_element(body, nodes, e + 1, dt, sums, erode);
    return;
  }
  const Pair lc = quad4_axisym_characteristic_length_cm(x, g.area);
  const double L_c[2] = {lc[0], lc[1]};
  for (int l = 0; l < 2; ++l) {
    body.volume[e + l] = V[l];
    body.char_length[e + l] = L_c[l];
  }

  Pair L2[2][2], L_thth;
  if (dt > 0.0) {
    Quad4FieldT<Pair> xm;
    for (int i = 0; i < 2; ++i)
      for (int a = 0; a < 4; ++a) xm.u[i][a] = x.u[i][a] - (0.5 * dt) * v.u[i][a];
    quad4_axisym_velocity_gradient_cm(v, quad4_axisym_gradient_cm(xm), L2, L_thth);
  } else {
    L2[0][0] = L2[0][1] = L2[1][0] = L2[1][1] = L_thth = Pair{};
  }
  MaterialStep ms[2];
  for (int l = 0; l < 2; ++l) {
    Mat3 L;
    L << L2[0][0][l], L2[0][1][l], 0.0,  //
        L2[1][0][l], L2[1][1][l], 0.0,   //
        0.0, 0.0, L_thth[l];
    ms[l] = material_step(body, e + l, L, dt, V[l], L_c[l], sums);
  }

  Quad4FieldT<Pair> f;
  auto sigma = [&ms](int i, int j) { return make_pair(ms[0].sigma(i, j), ms[1].sigma(i, j)); };
  quad4_axisym_stress_forces_cm(sigma(0, 0), sigma(0, 1), sigma(1, 0), sigma(1, 1), sigma(2, 2), g,
                                f);
  const std::array<Pair, 4> gamma = quad4_axisym_hourglass_vector_cm(x, g);
  const double c_hg = body.settings.hourglass_coefficient;
  double a_h[2];
  for (int l = 0; l < 2; ++l) {
    const double rho = body.element_mass[e + l] / V[l];
    a_h[l] = quad4_axisym_viscous_hourglass_coefficient(c_hg, rho, ms[l].c, g.rbar[l], g.area[l]);
  }
  const Pair hg_power = quad4_axisym_hourglass_viscous_cm(gamma, v, make_pair(a_h[0], a_h[1]), f);
  for (int l = 0; l < 2; ++l) {
    std::array<Vec3, 8>& out = body.elem_force[e + l];
    for (int a = 0; a < 4; ++a) out[a] = Vec3(f.u[0][a][l], f.u[1][a][l], 0.0);
    finish_element(body, e + l, V[l], ms[l], hg_power[l], sums, erode);
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

FeStepResult fe_internal_forces(FeBody& body, NodeSet& nodes, double dt) {
  FeStepResult result;
  result.dt_stable = infinity;
  const std::size_t ne = body.num_elements();
  const std::size_t num_blocks = (ne + block_size - 1) / block_size;
  std::vector<BlockSums> blocks(num_blocks);
  std::vector<std::vector<int>> erode(static_cast<std::size_t>(max_threads()));
  const bool hex = body.kind == ElementKind::hex8;
  const bool pair_quads = !body.settings.stiffness_hourglass;  // quad pairs: viscous form only
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
      const std::size_t end = std::min(ne, (k + 1) * block_size);
      for (std::size_t e = k * block_size; e < end; ++e) {
        if (!body.active[e]) continue;
        if (hex) {
          if (e + 1 < end && body.active[e + 1]) {
            hex_element_pair(body, nodes, e, dt, sums, my_erode);
            ++e;
          } else {
            hex_element(body, nodes, e, dt, sums, my_erode);
          }
        } else if (pair_quads && e + 1 < end && body.active[e + 1]) {
          quad_element_pair(body, nodes, e, dt, sums, my_erode);
          ++e;
        } else {
          quad_element(body, nodes, e, dt, sums, my_erode);
        }
      }
    }

    // Deterministic gather: each node sums its elements' contributions in CSR order.
    SPLAT_OMP(omp for schedule(static))
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
