// How a run ended and the figures behind it: the document `splat run --json`
// prints (schemas/result.schema.json) and the attributes of the result file.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "solver/common/types.hpp"
#include "solver/core/stop_reason.hpp"
#include "solver/core/thread_governor.hpp"
#include "solver/scene/fidelity.hpp"

namespace splat {

enum class RunOutcome {
  finished,   // reached the end time
  unstable,   // a numerical check failed (see reason)
  timed_out,  // wall-clock or step limit
  cancelled,  // stopped from outside
  error,      // could not run or write its output (see reason)
  stick,      // two-mass or impact scene: the particle is held (impact_verdict.hpp)
  rebound,    // two-mass or impact scene: the link let go / the particle left
};

const char* to_string(RunOutcome outcome);

// Energy terms, J (axisymmetric runs are integrated over the full 2 pi).
struct EnergyBudget {
  double initial_total = 0.0;
  double kinetic = 0.0;
  double internal = 0.0;              // elastic + plastic, from the material states
  double plastic_work = 0.0;          // part of `internal`
  double hourglass = 0.0;             // work of the hourglass forces
  double artificial_viscosity = 0.0;  // work of the bulk viscosity
  double absorbed = 0.0;              // taken out by absorbing boundaries
  double eroded = 0.0;                // kinetic + internal energy of eroded elements
  double wall_work = 0.0;             // work of rigid walls on the bodies (<= 0)
  double external_work = 0.0;         // work of prescribed velocities and other constraints
  double contact_work = 0.0;    // work of contact forces on the bodies (<= 0 without adhesion)
  double contact_stored = 0.0;  // energy in penalty contact springs now (part of -contact_work)
  double adhesion = 0.0;        // charged to the links' budgets G_c A (cohesive_law.hpp), >= 0; the
                                // links' mechanical work is part of contact_work (see interface)
  double balance_error = 0.0;   // (total now - initial - external - wall - contact) /
                                // (initial + max(external, 0)), -
};

struct BodySummary {
  std::string name;
  long long elements = 0;
  long long nodes = 0;
  double mass = 0.0;                      // kg
  Vec3 centroid_velocity = Vec3::Zero();  // m/s
  double kinetic_energy = 0.0;            // J
  long long eroded_elements = 0;
  double max_plastic_strain = 0.0;  // -
  double max_temperature = 0.0;     // K
  Vec3 extent_min = Vec3::Zero();   // m
  Vec3 extent_max = Vec3::Zero();   // m
};

// One contact interface (solver/contact/contact_interface.hpp).
struct InterfaceSummary {
  std::string master, slave;
  std::string method;  // lagrange | penalty
  double friction = 0.0;
  double work = 0.0;                   // J, work of the contact forces on the bodies
  double stored = 0.0;                 // J, penalty springs at the end
  double dissipated = 0.0;             // J, -work - stored
  long long pairs_in_contact = 0;      // at the end
  long long max_pairs_in_contact = 0;  // over the run
  long long nodes_ever_in_contact = 0;
  int max_solver_iterations = 0;
  double max_solver_residual = 0.0;  // m/s
  long long unconverged_solves = 0;
  double max_penetration = 0.0;  // m
  // Adhesion (thesis 3.5.3); areas of the full body of revolution in 2D.
  bool adhesion = false;
  double adhesion_work = 0.0;      // J, dissipated by the links
  long long links_activated = 0;   // links that became active
  long long links_exhausted = 0;   // budget G_c A spent
  long long links_eroded = 0;      // broken by damage
  long long links_active = 0;      // active at the end (thesis: "at least one active link")
  long long max_links_active = 0;  // most links active at one time ("stuck" at most)
  double bonded_area = 0.0;        // m^2, area of the active links at the end
  double max_bonded_area = 0.0;    // m^2
};

// Figures of a two-mass run (solver/two_mass/two_mass_model.hpp). Velocities
// are along +x, the direction in which M first moved towards m.
struct TwoMassSummary {
  // Velocity of M when the link let go, positive away from m (= -V_M), m/s;
  // empty when the link never let go.
  std::optional<double> separation_velocity;
  std::optional<double> release_time;  // s, when the link let go
  double final_velocity_M = 0.0;       // m/s, V_M at the end of the run
  double final_velocity_m = 0.0;       // m/s, v_m at the end of the run
  double final_gap = 0.0;              // m, x_m - x_M at the end of the run
  std::string link_state;              // none | contact | active | exhausted | eroded
  double link_work = 0.0;              // J, work done against separation
  double work_budget = 0.0;            // J, G_c * area
  double max_link_force = 0.0;         // N, largest link tension
  double dt = 0.0;                     // s, time step used
};

// The physics checks of an impact run (solver/core/physics_guard.hpp), kept
// whether they passed or not so that a campaign can show them.
struct GuardFigures {
  bool interpenetration_checked = false;  // false: a rigid wall
  double max_interpenetration = 0.0;      // m, deepest particle node inside the substrate
                                          //   (SPH substrate: deepest pinball overlap)
  double interpenetration_ratio = 0.0;    // -, that depth over the local element size
                                          //   (SPH: over the substrate spacing)
  long long nodes_through = 0;            // nodes deeper than the limit
  double eroded_energy_fraction = 0.0;    // -, eroded energy over the reference energy
  double internal_energy_fraction = 0.0;  // -, internal energy over the reference energy
  double plastic_work_excess = 0.0;       // -, (plastic work - internal - eroded energy) over
                                          //   the reference energy (physics_guard.hpp)
  std::optional<StopReason> failed;       // the failed check, none when all passed
};

// Figures of a particle_impact run (solver/core/impact_run.hpp says how each
// is measured). Velocities along the substrate normal +z, positive away from
// the substrate. Areas of the full body of revolution in axisymmetric runs.
struct ImpactSummary {
  std::string verdict;                    // stick | rebound | none (the run ended before a verdict)
  bool settled = false;                   // the verdict held for the hold time before the end
  double impact_velocity = 0.0;           // m/s
  double rebound_velocity = 0.0;          // m/s, particle relative to substrate, at the end
  double coefficient_of_restitution = 0;  // max(rebound_velocity, 0) / impact_velocity, -
  double bonded_area = 0.0;               // m^2, active links at the end
  double contact_area = 0.0;              // m^2, particle surface that ever touched
  double bonded_fraction = 0.0;           // bonded_area / contact_area, -
  long long links_contact = 0;            // particle surface nodes that ever touched
  long long links_activated = 0, links_exhausted = 0, links_eroded = 0, links_active = 0;
  long long max_links_active = 0;
  // Thesis 3.5.3 stick criteria, reported for comparison.
  bool thesis_active_link = false;      // at least one active link at the end
  bool thesis_one_percent = false;      // active links > 1 % of the most ever active
  double initial_kinetic = 0.0;         // J, particle at impact
  double final_particle_kinetic = 0.0;  // J, particle (all its motion) at the end
  double adhesion_dissipated = 0.0;     // J, charged to the links' budgets
  double max_temperature = 0.0;         // K, both bodies
  double max_plastic_strain = 0.0;      // -, both bodies
  double flattening_ratio = 0.0;        // final particle diameter / 2R, -
  double penetration_depth = 0.0;       // m, lowest particle point below z = 0
  double hold_time = 0.0;               // s
  double max_time = 0.0;                // s
  bool adaptive = true;
  std::optional<Fidelity> model;  // the impact spec's
  std::string why;
  GuardFigures guard;
  // Adhesion: the interface law's process zone (cohesive_law.hpp) against the
  // size of the particle's surface elements (SPH: the spacing) where it
  // touched; 0 without a stress cap (no zone) or without adhesion.
  double cohesive_zone_length = 0.0;    // m
  double interface_element_size = 0.0;  // m
  double cohesive_zone_elements = 0.0;  // -, cohesive_zone_length / interface_element_size
  double bond_energy = 0.0;             // J, budget the active links have left at the end
  double separating_kinetic = 0.0;      // J, K_sep at the end (impact_verdict.hpp)
};

struct RunSummary {
  std::string scene;
  RunOutcome outcome = RunOutcome::finished;
  std::string reason;                     // why it ended this way, for people
  std::optional<StopReason> stop_reason;  // machine-readable cause, none until the run stops
  long long steps = 0;
  double end_time = 0.0;      // s
  double wall_seconds = 0.0;  // s
  ThreadUse threads;          // the team and the steps run on it and on one thread
  EnergyBudget energy;
  std::vector<BodySummary> bodies;
  std::vector<InterfaceSummary> interfaces;
  std::optional<TwoMassSummary> two_mass;  // two-mass scenes only
  std::optional<ImpactSummary> impact;     // particle_impact scenes (FE) only
  std::string hdf5_path;                   // empty when no file was written
  std::string xdmf_path;
};

nlohmann::json to_json(const RunSummary& summary);

}  // namespace splat
