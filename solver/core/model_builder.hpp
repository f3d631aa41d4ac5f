// Turns a Scene into the solver's state: meshes each body, builds the finite
// element bodies in one NodeSet, and resolves boundary conditions and rigid
// walls into per-node constraints and face lists.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/contact/contact_interface.hpp"
#include "solver/fe/fe_body.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sph/sph_body.hpp"
#include "solver/sph/sph_boundary.hpp"

namespace splat {

struct RigidWall {
  Vec3 point = Vec3::Zero();       // internal frame, m
  Vec3 normal = Vec3::UnitZ();     // internal frame, unit, into the allowed side
  std::vector<int> nodes;          // nodes the wall acts on
  std::vector<std::uint8_t> held;  // per node of `nodes`: stopped by the wall in the last step
};

// A boundary face (3D quad) or segment (axisymmetric, count 2) with the
// impedances of its body's material, for viscous absorbing boundaries.
struct AbsorbingFace {
  std::array<int, 4> nodes{};
  int count = 4;
  double rho_cp = 0.0;  // rho0 c_p (P wave), kg/(m^2 s)
  double rho_cs = 0.0;  // rho0 c_s (S wave), kg/(m^2 s)
};

// Connectivity of one body for the result file (fixed for the run).
struct BodyMeshInfo {
  std::vector<int> connectivity;  // flattened, local node ids, 4 or 8 per cell
};

// Where scene body k lives: model.bodies[index] (FE) or model.sph_bodies[index].
struct BodyRef {
  bool sph = false;
  std::size_t index = 0;
};

// Nodes whose prescribed velocity follows a table (a velocity condition with
// a history): before each step's velocity update the time loop sets their
// constraint_value components in `mask` to the table's mean over the step.
struct DrivenSet {
  std::vector<int> nodes;
  std::uint8_t mask = 0;    // bit c = internal component c prescribed
  VelocityHistory history;  // internal frame (axisymmetric: (vr, vz, 0))
};

// The nodes of a named boundary condition, whose reaction force and mean
// displacement the result file records (simulation_output.cpp).
struct ReactionSet {
  std::string name;
  std::vector<int> nodes;
  Vec3 initial_mean = Vec3::Zero();  // mean initial position, internal frame, m (set once)
};

struct Model {
  bool axisymmetric = false;
  NodeSet nodes;
  std::vector<FeBody> bodies;                 // the FE bodies, scene order
  std::vector<SphBody> sph_bodies;            // the SPH bodies, scene order
  std::vector<BodyRef> body_refs;             // one per scene body
  std::vector<SphAbsorbing> sph_absorbing;    // absorbing layers of SPH bodies
  std::vector<BodyMeshInfo> meshes;           // one per FE body
  std::vector<std::uint8_t> constraint_mask;  // per node: bit c = component c prescribed
  std::vector<Vec3> constraint_value;         // per node: prescribed velocity, m/s (driven
                                              // sets: every step)
  std::vector<DrivenSet> driven;              // tabulated prescribed velocities
  std::vector<ReactionSet> reaction_sets;     // named boundary conditions, scene order
  std::vector<RigidWall> walls;
  std::vector<AbsorbingFace> absorbing;
  std::vector<ContactInterface> contacts;  // scene order of the contact interactions
};

// Throws InputError (solver/input/schema.hpp) naming the scene field when the
// scene cannot be modelled.
Model build_model(const Scene& scene);

// Conservative CFL bound before the first force evaluation: shortest element
// edge over the undamaged P-wave speed, s.
double initial_time_step_bound(const Model& model);

// Largest closing speed of the initial state, m/s: the largest difference of
// two bodies' mean velocities and, with rigid walls, the largest body speed.
// A contact or a wall arrests a node at up to this speed within one step.
double initial_closing_speed(const Model& model);

// Time-step bound of a velocity jump dv (m/s) arriving at any element, s:
// min over elements of L_c / (Qv + sqrt(Qv^2 + c^2)) with the bulk-viscosity
// speed Qv = Q1 c + Q2 dv the element will have once the jump compresses it
// (bulk_viscosity.hpp, tr(D) ~ -dv / L_c). Without it the step before an
// arrest is the elastic one, and at dv comparable to c a node arrested in
// that step compresses its element by ~dv dt / L_c ~ 0.5 in one increment:
// the Taylor bar at 3000 m/s gained 5.6 % energy in its first step. Infinite
// for dv = 0. Uses L_c of the last force evaluation (the initial edge length
// before the first).
double closing_speed_time_step_bound(const Model& model, double dv);
// Node (particle) range [begin, end) of scene body `scene_index`.
std::size_t body_node_begin(const Model& model, std::size_t scene_index);
std::size_t body_node_end(const Model& model, std::size_t scene_index);

// Internal frame -> user frame: axisymmetric (r, z, 0) -> (r, 0, z).
Vec3 to_user_frame(const Model& model, const Vec3& v);
// Centre-of-mass velocity in the user frame from a body's momentum and mass
// (axisymmetric: only the axial component; the radial one averages to zero).
Vec3 centroid_velocity(const Model& model, const Vec3& momentum, double mass);
// The reaction force on a named node set and the set's mean displacement,
// user frame. force: what the constraints apply to the body, -sum f over the
// set's nodes (the nodal forces of the last force evaluation; the nodes'
// inertia m a is left out, exact for nodes held at a constant velocity), N;
// axisymmetric: over the whole ring, axial only (the radial forces of a ring
// have no resultant). displacement: mean of the nodes' displacements, m
// (axisymmetric: x radial, z axial).
struct ReactionHistory {
  Vec3 force = Vec3::Zero();         // N
  Vec3 displacement = Vec3::Zero();  // m
};
ReactionHistory reaction_history(const Model& model, const ReactionSet& set);
// User frame -> internal frame: axisymmetric (x, y, z) -> (hypot(x, y), z, 0).
Vec3 to_internal_frame(const Model& model, const Vec3& v);

}  // namespace splat
