// What the user asked for: a plain description read from a scene JSON
// document (schemas/scene.schema.json, parsed by solver/input/scene_io.hpp).
// The solver builds its own state from it and never changes it. SI units.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solver/adhesion/cohesive_law.hpp"
#include "solver/common/types.hpp"
#include "solver/contact/contact_types.hpp"
#include "solver/material/material.hpp"
#include "solver/scene/fidelity.hpp"
#include "solver/scene/velocity_history.hpp"
#include "solver/sph/sph_body.hpp"
#include "solver/sph/sph_particles.hpp"

namespace splat {

enum class GeometryType { sphere, cylinder, box, half_disc, rectangle };

// One primitive; which fields matter depends on the type.
//  sphere:    radius, centre                (fe-axisym: centre on the axis)
//  cylinder:  radius, z_min, z_max; axis z through x = y = 0
//  box:       lo, hi                        (fe-hex only)
//  half_disc: radius, centre.z()            (fe-axisym only)
//  rectangle: radius (= r_max), z_min, z_max (fe-axisym only)
struct Geometry {
  GeometryType type = GeometryType::sphere;
  double radius = 0.0;                        // m
  Vec3 centre = Vec3::Zero();                 // m
  double z_min = 0.0, z_max = 0.0;            // m
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // m
};

enum class Discretization { fe_axisym, fe_hex, sph };
enum class SectorKind { full, half, quarter };  // half: y >= 0; quarter: x >= 0, y >= 0

struct GradingSpec {
  bool enabled = false;
  Vec3 focus = Vec3::Zero();  // m, scene coordinates (axisymmetric: (r, 0, z))
  double ratio = 1.0;         // element size growth per element away from the focus, -
  // Half-widths about the focus within which elements keep the base size,
  // per axis, m (axisymmetric: (r, 0, z)); zero: growth from the focus.
  Vec3 uniform_extent = Vec3::Zero();
};

enum class HourglassType { viscous, stiffness };

struct BodySpec {
  std::string name;
  Material material;
  Geometry geometry;
  Discretization discretization = Discretization::fe_axisym;
  // Resolution: elements across the characteristic length (radius for
  // spheres, cylinders and half-discs; the smallest side for boxes and
  // rectangles) or, if > 0, the element size.
  int elements_across = 0;    // -
  double element_size = 0.0;  // m
  SectorKind sector = SectorKind::full;
  GradingSpec grading;
  Vec3 velocity = Vec3::Zero();          // initial velocity, m/s
  Vec3 angular_velocity = Vec3::Zero();  // initial spin about the centre of mass, rad/s (3D)
  double temperature = 300.0;            // initial temperature, K
  unsigned long long seed = 1;           // seed of the random initial damage
  ModelSwitches switches;
  HourglassType hourglass = HourglassType::viscous;
  double hourglass_coefficient = 0.1;  // -
  double q_linear = 0.06;              // bulk viscosity, linear coefficient, -
  double q_quadratic = 1.5;            // bulk viscosity, quadratic coefficient, -
  bool erosion = false;  // remove elements at D_max, on inversion, or below min_time_step
  double erosion_min_time_step = 0.0;  // s; 0 = off
  bool erosion_on_damage = true;       // also erode at the damage cap D_max
  // sph bodies only: the particle spacing is element_size, or the
  // characteristic length over elements_across.
  SphSettings sph;                 // kernel, viscosity, hourglass, reference update
  Lattice lattice = Lattice::hcp;  // particle lattice
  double sph_jitter = 0.0;         // random displacement, fraction of the spacing, -
  int sph_boundary_layers = 3;     // particle layers tagged per face, in spacings, -
};

enum class BoundaryType { fixed, symmetry, velocity, absorbing };

// A condition on the nodes of one body that carry a boundary bit (mesh.hpp):
// "x_min", "x_max", "y_min", "y_max", "z_min", "z_max", "curved"; in 2D
// "axis" = x_min, "outer" = x_max, "bottom" = y_min, "top" = y_max.
// Type velocity prescribes the `components` of the nodes' velocity: the
// constant `velocity`, or the tabulated `history` when it is set. A named
// condition's node set gets a reaction-force and displacement history in the
// result file (simulation_output.cpp).
struct BoundarySpec {
  std::string name;  // empty: no reaction history
  std::string body;
  std::uint32_t on = 0;  // BoundaryBit mask (any bit matches)
  BoundaryType type = BoundaryType::fixed;
  Vec3 velocity = Vec3::Zero();                      // m/s, for type velocity without a history
  std::optional<VelocityHistory> history;            // m/s against s, user frame
  std::array<bool, 3> components{true, true, true};  // x, y, z prescribed (type velocity)
};

enum class InteractionType { rigid_wall, contact };

struct InteractionSpec {
  InteractionType type = InteractionType::rigid_wall;
  // rigid-wall
  std::vector<std::string> bodies;  // empty = all bodies
  Vec3 point = Vec3::Zero();        // a point of the wall plane, m
  Vec3 normal = Vec3(0, 0, 1);      // unit normal pointing into the allowed side, -
  // contact: slave nodes of `slave` against the boundary faces of `master`
  std::string master, slave;
  ContactMethod method = ContactMethod::lagrange;
  double penalty_stiffness = 0.0;  // Pa/m; 0 = 0.1 K_min / h_min (see model_builder)
  double friction = 0.0;           // Coulomb coefficient, -
  ContactSolverKind solver = ContactSolverKind::pgs;
  bool two_pass = false;  // also master nodes on slave faces (default: FE-FE Lagrange pairs)
  std::optional<AdhesionParams> adhesion;  // cohesive law on the slave nodes' pairs
};

struct TimeSpec {
  double end_time = 0.0;               // s
  double dt = 0.0;                     // s; fixed time step of two-mass scenes; 0 = default
  double stability_coefficient = 0.9;  // fraction of the CFL bound, -
  long long max_steps = 10'000'000;    // -
  double min_time_step = 0.0;          // s; below it the run ends `unstable`; 0 = 1e-6 of the first
  double wall_clock_limit = 0.0;       // s; 0 = none
  double energy_balance_limit = 0.05;  // |balance error| above which the run ends unstable
                                       // (checked in runs that start with energy)
};

struct OutputSpec {
  std::vector<double> snapshot_times;  // s
  double history_interval = 0.0;       // s; 0 = every step
};

// The two-mass adhesion problem (thesis 3.5.1.1): a rigid mass M moving at V0
// along +x touches, at t = 0, a rigid mass m that rests on a spring of
// stiffness k (rest position x = 0); the collision is elastic and the pair
// is then joined by the cohesive law over `area`. Sketch:
//     M --V0-->  (touching at t = 0)  m --/\/\/\-- wall   (spring k)
struct TwoMassSpec {
  double M = 0.0;     // mass of the moving body, kg
  double m = 0.0;     // mass of the body on the spring, kg
  double k = 0.0;     // spring stiffness, N/m (0: free mass)
  double V0 = 0.0;    // speed of M towards m at first touch, m/s
  double area = 0.0;  // adhesive area of the link, m^2
  AdhesionParams adhesion;
};

// What a particle_impact block asked for and the model it expanded into
// (solver/input/impact_scene.hpp); the verdict of an impact run reads it.
struct ImpactSpec {
  std::string particle = "particle";  // body name
  std::string substrate;              // body name; empty = rigid wall
  double velocity = 0.0;              // impact speed, m/s
  double angle = 0.0;                 // from the substrate normal, deg
  bool adaptive_end = true;           // stop once the outcome is decided
  double max_eroded_fraction = 0.5;   // particle mass share erosion may take with a verdict, -
  std::optional<Fidelity> model;      // none: a block whose model names none
  std::string why;                    // why that model, for people
};

struct Scene {
  std::string name;
  std::string description;
  std::optional<TwoMassSpec> two_mass;  // set: a two-mass scene, no bodies
  std::optional<ImpactSpec> impact;     // set: expanded from a particle_impact block
  std::vector<BodySpec> bodies;
  std::vector<BoundarySpec> boundaries;
  std::vector<InteractionSpec> interactions;
  TimeSpec time;
  OutputSpec output;
};

}  // namespace splat
