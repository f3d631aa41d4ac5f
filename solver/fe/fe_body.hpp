// Finite-element body state and its per-step internal-force computation.
//
// Nodes of every body live in one NodeSet (each body owns a contiguous
// range); a body's elements reference global node indices. 2D axisymmetric
// bodies use components (0, 1) = (r, z) of the Vec3 node fields (component 2
// stays 0) and carry masses and forces per radian; 3D bodies use (x, y, z).
//
// Material-point state is an array of PointState structs (one per element,
// one integration point each) rather than one array per field: the kernel
// reads and writes the whole struct every step, so keeping it contiguous is
// simpler and no slower than twenty-two separate arrays. (Measured: one array
// per field, with whole-vector loads and stores in the element loop and the
// arrays staggered by cache lines, ran 2-4 % slower; with both layouts' lane
// lambdas forced inline, hex8 plastic 3 % faster and elastic 6 % slower;
// branch soa-point-states.)
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/common/types.hpp"
#include "solver/material/material.hpp"
#include "solver/material/point_update.hpp"
#include "solver/mesh/mesh.hpp"

namespace splat {

struct NodeSet {
  std::vector<Vec3> x0;                 // reference position, m (set once)
  std::vector<Vec3> x;                  // current position, m (every step)
  std::vector<Vec3> v;                  // velocity at t_{n+1/2}, m/s (every step)
  std::vector<Vec3> f;                  // total force at t_n, N (every step; per radian in 2D)
  std::vector<double> mass;             // lumped mass, kg (per radian in 2D; erosion reduces it)
  std::vector<std::uint32_t> boundary;  // BoundaryBit mask (set once)

  std::size_t size() const { return x.size(); }
};

enum class ElementKind { quad4_axisym, hex8 };

// Elements whose forces share one lane-order record (FeBody::force_index),
// and the length of a node run (FeBody::node_run).
inline constexpr std::size_t fe_force_lanes = 8;

struct FeSettings {
  bool stiffness_hourglass = false;    // Flanagan-Belytschko stiffness form, else viscous
  double hourglass_coefficient = 0.1;  // -
  double q_linear = 0.06;              // bulk viscosity, linear coefficient, -
  double q_quadratic = 1.5;            // bulk viscosity, quadratic coefficient, -
  bool erosion = false;
  double erosion_min_time_step = 0.0;  // s; 0 = off
  bool erosion_on_damage = true;       // erosion also at the damage cap (else only geometric)
};

// A face element e shares with element `neighbour` of the same body: its
// nodes in the cyclic order of the element that lists it first (quads use
// the first 2), the same array on both sides so that both compute the same
// conductance.
struct HeatFace {
  int neighbour = 0;
  std::array<int, 4> nodes{};
};

struct FeBody {
  std::string name;
  ElementKind kind = ElementKind::hex8;
  Material material;
  MaterialConstants constants;
  ModelSwitches switches;
  FeSettings settings;
  std::size_t node_begin = 0, node_end = 0;  // this body's range in the NodeSet

  // Set once.
  std::vector<std::array<int, 8>> conn;  // global node ids; quads use the first 4
  std::vector<double> volume0;           // reference volume, m^3 (2D: per radian, r A)
  std::vector<double> element_mass;      // kg (2D: per radian)
  std::vector<int> node_elem_offsets;    // CSR node -> (element * 8 + local node), local to
  std::vector<int> node_elem_entries;    //   the body's node range, for a deterministic gather
  std::vector<std::uint32_t> node_force_offsets;  // per CSR entry: force_index(e, a, 0)
  // 1 at an element e (e a multiple of fe_force_lanes) that starts a run:
  // elements e .. e + 7 all exist and each local node a of element e + l is
  // node conn[e][a] + l. The element loop loads such a run's node positions
  // and velocities as whole vectors (structured meshes are mostly runs).
  std::vector<std::uint8_t> node_run;
  // Heat conduction (heat_conduction.hpp): element e's faces shared with
  // another element are heat_faces[heat_offsets[e] .. heat_offsets[e + 1]);
  // both empty when the body conducts no heat.
  std::vector<int> heat_offsets;
  std::vector<HeatFace> heat_faces;

  // Every step.
  std::vector<PointState> state;        // material state at the element centre
  std::vector<double> volume;           // current volume, m^3 (2D: per radian)
  std::vector<double> char_length;      // characteristic length for the time step, m
  std::vector<double> q;                // bulk-viscosity pressure, Pa
  std::vector<std::array<Vec3, 4>> hg;  // stiffness-form hourglass generalised forces
  std::vector<double> hg_kappa;         // stiffness-form kappa that hg was built with
  std::vector<std::uint8_t> active;     // 0 once eroded
  std::vector<double> heat_in;          // scratch: heat an element receives in a step, J
                                        //   (2D: per radian)
  std::vector<double> elem_force;       // scratch: element nodal forces, N, in lane order
                                        //   (component i of element e's node a at
                                        //   force_index(e, a, i)); an eroded element's are 0

  std::size_t num_elements() const { return conn.size(); }
  int nodes_per_element() const { return kind == ElementKind::hex8 ? 8 : 4; }
  // Force components stored per node: (x, y, z) in 3D, (r, z) axisymmetric.
  int force_components() const { return kind == ElementKind::hex8 ? 3 : 2; }
  // Element forces are stored in records of fe_force_lanes elements: the
  // record of elements 8k .. 8k + 7 holds, for each local node a and
  // component i, the 8 elements' values side by side, so the element loop
  // stores a group's forces as whole vectors.
  std::size_t force_index(std::size_t e, int a, int i) const {
    const std::size_t record = e / fe_force_lanes;
    const std::size_t row =
        (record * static_cast<std::size_t>(nodes_per_element()) + static_cast<std::size_t>(a)) *
            static_cast<std::size_t>(force_components()) +
        static_cast<std::size_t>(i);
    return row * fe_force_lanes + e % fe_force_lanes;
  }
  // Element e's force on its local node a (component 2 is 0 axisymmetric), N.
  Vec3 element_force(std::size_t e, int a) const {
    Vec3 f = Vec3::Zero();
    for (int i = 0; i < force_components(); ++i) f[i] = elem_force[force_index(e, a, i)];
    return f;
  }
};

// Reductions over one body for one step.
struct FeStepResult {
  double dt_stable = 0.0;        // min over active elements of the CFL bound, s
  double hourglass_power = 0.0;  // power absorbed by the hourglass forces, -sum f_hg . v, W
                                 //   (>= 0 for the viscous form; 2D: per radian)
  double viscosity_power = 0.0;  // power absorbed by the bulk viscosity, -q V tr(D) >= 0, W
                                 //   (2D: per radian)
  int max_return_iterations = 0;
  bool return_failed = false;  // a return mapping did not converge
  long long inverted = 0;      // active elements with non-positive volume (not eroded)
  std::vector<int> to_erode;   // elements that met an erosion criterion this step
};

// Stiffness-form hourglass control (Flanagan-Belytschko) holds its
// generalised forces Q across steps, Q += kappa dt qdot: a spring of
// displacement Q / kappa and stored energy |Q|^2 / (2 kappa). When kappa
// falls (damage softens G_d = (1 - D) G, the element shrinks), a held Q would
// give back |Q|^2 / (2 kappa_new), more than was stored: the booked hourglass
// work turns negative, energy made from nothing. Q is scaled by
// kappa / kappa_held, keeping the displacement: the stored energy falls by the
// same factor and the difference stays in the hourglass work (dissipated).
// A stiffening kappa keeps Q (the stored energy falls, nothing is made).
// kappa_held is set to kappa for the next step; 0 = nothing held yet.
inline void soften_held_hourglass(double& kappa_held, double kappa, Vec3* Q, int n) {
  if (kappa_held > 0.0 && kappa < kappa_held) {
    const double s = std::max(kappa, 0.0) / kappa_held;
    for (int i = 0; i < n; ++i) Q[i] *= s;
  }
  kappa_held = kappa;
}

// Hughes-Winget incremental rotation Q = (I - A)^{-1} (I + A), A = W dt / 2,
// of the spin W over dt (the rotation jaumann_rotate applies), in the closed
// form of the Cayley transform of a skew matrix with axial vector a
// (A v = a x v, A^2 = a a^T - |a|^2 I):
//   Q = I + 2 (A + A^2) / (1 + |a|^2),
// a fraction of the cost of the general 3x3 inverse. W must be skew.
inline Mat3 hughes_winget_rotation(const Mat3& W, double dt) {
  const double h = 0.5 * dt;
  const double a0 = h * W(2, 1), a1 = h * W(0, 2), a2 = h * W(1, 0);
  const double a_sq = a0 * a0 + a1 * a1 + a2 * a2;
  const double c = 2.0 / (1.0 + a_sq);
  const double d = 1.0 - c * a_sq;
  Mat3 Q;
  Q << d + c * a0 * a0, c * (a0 * a1 - a2), c * (a0 * a2 + a1),  //
      c * (a0 * a1 + a2), d + c * a1 * a1, c * (a1 * a2 - a0),   //
      c * (a0 * a2 - a1), c * (a1 * a2 + a0), d + c * a2 * a2;
  return Q;
}

// Q s Q^T of a symmetric s, computing the six distinct entries only (the
// result is exactly symmetric).
inline Mat3 rotate_symmetric(const Mat3& Q, const Mat3& s) {
  const Mat3 T = Q * s;
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) r(i, j) = r(j, i) = T.row(i).dot(Q.row(j));
  }
  return r;
}

// Builds a body from a mesh and appends its nodes to `nodes`: positions
// (axisymmetric: (r, z, 0)), the initial velocity, boundary bits, lumped masses
// (element mass / nodes per element; axisymmetric per radian, rho0 rbar A / 4
// per node), reference volumes, the initial material state at `temperature`
// (K) with, when damage is on, the reproducible random initial damage
// initial_random_damage(seed, element, initial_random_max), and the CSR
// node -> element adjacency. `velocity` (m/s) is in the user frame: 3D bodies
// take it as is, axisymmetric bodies only its z component (into component 1).
// Throws std::invalid_argument if an element has non-positive volume or
// refers to a node the mesh does not have.
FeBody make_fe_body(const std::string& name, const HexMesh& mesh, const Material& material,
                    const ModelSwitches& switches, const FeSettings& settings, const Vec3& velocity,
                    double temperature, unsigned long long seed, NodeSet& nodes);
FeBody make_fe_body(const std::string& name, const AxisymMesh& mesh, const Material& material,
                    const ModelSwitches& switches, const FeSettings& settings, const Vec3& velocity,
                    double temperature, unsigned long long seed, NodeSet& nodes);

// Internal forces of one body, called once per step after the nodes moved to
// x_{n+1} with velocity v_{n+1/2}. Per active element: L on the mid-step
// geometry x - dt/2 v; Jaumann rotation and material update with
// d_eps = sym(L) dt, J = V_{n+1} / V0 and the characteristic length L_c;
// bulk viscosity q; forces on the end geometry from sigma - q I plus hourglass
// forces; the CFL bound; erosion flags. An element flagged for erosion (listed
// in to_erode, still active: the caller removes it with erode_element) exerts
// no force and sets no time-step bound this step. The element forces are then
// ADDED to nodes.f through the node -> element adjacency in a fixed order. dt = 0
// (the force evaluation before the first step) leaves the material state
// unchanged. Results do not depend on the number of OpenMP threads (sums are
// taken over fixed blocks of elements combined in block order).
FeStepResult fe_internal_forces(FeBody& body, NodeSet& nodes, double dt);

// The same step with every element on its own (one element, one
// update_point call at a time): the slow obvious reference that the phased,
// lane-wide loop of fe_internal_forces must match to the bit.
FeStepResult fe_internal_forces_one_by_one(FeBody& body, NodeSet& nodes, double dt);

// What removing one element takes out of the energy budget (2D: per radian).
struct ErodedEnergy {
  double internal = 0.0;  // V0 e, J
  double kinetic = 0.0;   // 0.5 m v^2 of the element's share of its nodes' mass, J
  double mass = 0.0;      // element mass, kg
};

// Smallest characteristic length (the time step's, m) of the active elements
// holding global node n of `body`; +infinity when none holds it.
double node_element_length(const FeBody& body, std::size_t n);

// Deactivates element e; a node no active element holds any more leaves the
// model with its mass (nodes still held keep their whole mass).
ErodedEnergy erode_element(FeBody& body, NodeSet& nodes, int e);

// Sum over active elements of V0 e, J (2D: per radian).
double fe_internal_energy(const FeBody& body);

// Sum over active elements of the element mass, kg (2D: per radian).
double fe_body_mass(const FeBody& body);

}  // namespace splat
