// How a run ended and the figures behind it: the document `splat run --json`
// prints (schemas/result.schema.json) and the attributes of the result file.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "solver/common/types.hpp"

namespace splat {

enum class RunOutcome {
  finished,   // reached the end time
  unstable,   // a numerical check failed (see reason)
  timed_out,  // wall-clock or step limit
  cancelled,  // stopped from outside
  error,      // could not run or write its output (see reason)
  stick,      // two-mass scene: the link held (settled, or still active at the end time)
  rebound,    // two-mass scene: the link let go (exhausted)
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
  double balance_error = 0.0;   // (total now - initial - external - wall - contact) / initial, -
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

struct RunSummary {
  std::string scene;
  RunOutcome outcome = RunOutcome::finished;
  std::string reason;       // why it ended this way, for people
  std::string stop_reason;  // short machine-readable cause: end-time, energy-balance, ...
  long long steps = 0;
  double end_time = 0.0;      // s
  double wall_seconds = 0.0;  // s
  int threads = 1;
  EnergyBudget energy;
  std::vector<BodySummary> bodies;
  std::vector<InterfaceSummary> interfaces;
  std::optional<TwoMassSummary> two_mass;  // two-mass scenes only
  std::string hdf5_path;                   // empty when no file was written
  std::string xdmf_path;
};

nlohmann::json to_json(const RunSummary& summary);

}  // namespace splat
