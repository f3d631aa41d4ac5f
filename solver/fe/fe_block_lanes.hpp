// The phased block loops of the FE element loop on lanes of W elements
// (fe_body.cpp calls them through fe_block.hpp). Included only by
// fe_blocks_isa.cpp, which CMake compiles once per instruction set with its
// -march: everything here is in an unnamed namespace, so each of those
// translation units has its own copy, built for its set throughout.
//
// Not target_clones: GCC 12 gives the comparisons and masks of lane vectors
// in an always-inline helper the baseline's vector-boolean type before the
// helper is inlined into a clone, and the AVX-512 clone then ran every mask
// operation (&&, ||, !, and the selects on their results) lane by lane in
// scalar code (vcomisd, seta, branches): the plastic return, which is mostly
// masks, cost twice its arithmetic.
#pragma once

// The lane kernels (Lane<8> = 64-byte vectors) are forced inline into the
// block loops, so GCC's note that returning such vectors by value changes the
// ABI between the baseline and AVX-512 code does not apply to them and is
// silenced here. A function that is NOT inlined (a lambda returning a lane
// vector was one, in the sanitizer build) is reported without a source
// location, which this pragma does not silence: the build fails instead of
// miscompiling.
#pragma GCC diagnostic ignored "-Wpsabi"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "solver/common/simd_lanes.hpp"
#include "solver/fe/bulk_viscosity.hpp"
#include "solver/fe/fe_block.hpp"
#include "solver/fe/hex8.hpp"
#include "solver/fe/quad4_axisym.hpp"
#include "solver/material/point_update_fast.hpp"

#ifndef SPLAT_FE_LANE_WIDTH
#define SPLAT_FE_LANE_WIDTH 8
#endif

namespace splat::fe_block {

namespace {

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

// Asks for the states of the W elements after group g's last one (the next
// group's, in a block without eroded elements) while g computes.
template <int W, class Scratch>
SPLAT_LANE_INLINE void prefetch_next_states(const FeBody& body, const Scratch& s, int g) {
  const std::size_t next = std::size_t(s.lane_element(g, W - 1)) + 1;
  if (next + W > body.state.size()) return;
  const char* p = reinterpret_cast<const char*>(&body.state[next]);
  for (std::size_t b = 0; b < W * sizeof(PointState); b += 64) __builtin_prefetch(p + b);
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
// d_eps = sym(L) dt, J from tr(d_eps) (volume_ratio_after), L_c of the
// group's valid lanes; for dt = 0 R = I and tr(D) = 0 (no material update).
template <int W, class Scratch>
SPLAT_LANE_INLINE void kinematics_lanes(FeBody& body, int g, const Lane<W> L[3][3], double dt,
                                        Scratch& s) {
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
  prefetch_next_states<W>(body, s, g);
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
  const V J_new = volume_ratio_after(state_lanes<W>(st, &PointState::J), dt * s.tr_D[g]);
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
  // A local copy stays in registers: through the reference every element's
  // sums were a load and a store on the additions' dependency chains (the
  // same additions in the same order).
  BlockSums local = sums;
  for (int p = 0; p < s.count; ++p) {
    if (!s.valid[p]) continue;
    const std::size_t e = std::size_t(s.element[p]);
    finish_element(body, e, body.volume[e], s.dt_e[p], s.q_power[p], s.hg_power[p], local, erode);
  }
  sums = local;
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
    kinematics_lanes<W>(body, g, L, dt, s);
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
        V rotated[3];
        for (int i = 0; i < 2; ++i)
          rotated[i] = (R[i][0] * Qk[0] + R[i][1] * Qk[1]) + R[i][2] * Qk[2];
        rotated[2] = R[2][0] * Qk[0] + (R[2][1] * Qk[1] + R[2][2] * Qk[2]);
        V mid[3];
        for (int i = 0; i < 3; ++i) {
          Q[k][i] = rotated[i] + (coefficient * dt) * qdot[k][i];
          mid[i] = 0.5 * (rotated[i] + Q[k][i]);
        }
        power += (mid[0] * qdot[k][0] + mid[1] * qdot[k][1]) + mid[2] * qdot[k][2];
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
    kinematics_lanes<W>(body, g, L, dt, s);
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

}  // namespace

}  // namespace splat::fe_block
