// A small explicit time loop for SPH bodies, used by the tests and the
// benchmark until SPH bodies join solver/core's Simulation. It follows the
// stages of the time step (docs/design.md) on particles only:
//   1. update:  v(n+1/2) = v(n-1/2) + dt_v f / m (dt_v = the mean of the two
//               half-step sizes, dt/2 at the first step); prescribed velocity
//               components; a frictionless rigid plane (a particle that would
//               cross it lands on it).
//   2. predict: x(n+1) = x(n) + dt v(n+1/2).
//   4. internal forces: sph_internal_forces per body.
//   5. boundary forces: absorbing layers.
//   6. diagnostics: next dt = stability x min dt_i, stop checks.
// Energy terms are kept as in the Simulation: kinetic at the half step,
// internal at the full step, and the work of viscosity, hourglass forces,
// absorbing layers, prescribed velocities and the wall summed as power x dt.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solver/fe/fe_body.hpp"
#include "solver/sph/sph_body.hpp"
#include "solver/sph/sph_boundary.hpp"

namespace splat {

enum class SphOutcome { running, finished, unstable };

struct SphEnergy {
  double kinetic = 0.0;        // at t(n+1/2), J
  double internal = 0.0;       // at t(n+1), J
  double viscosity = 0.0;      // dissipated by artificial viscosity, J
  double hourglass = 0.0;      // work absorbed by hourglass forces, J
  double absorbed = 0.0;       // taken out by absorbing layers, J
  double external_work = 0.0;  // done on the bodies by prescribed velocities, J
  double wall_work = 0.0;      // done on the bodies by the rigid plane (<= 0), J
};

struct RigidPlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3(0, 0, 1);  // unit, into the allowed side
};

class SphDriver {
 public:
  NodeSet nodes;
  std::vector<SphBody> bodies;
  std::vector<SphAbsorbing> absorbing;
  std::optional<RigidPlane> wall;
  double stability = 0.5;  // fraction of the time-step bound, -
  double fixed_dt = 0.0;   // s; > 0 overrides the bound

  // Prescribes velocity components (bit c of `mask` = component c) of node g.
  void prescribe(std::size_t g, std::uint8_t mask, const Vec3& value);

  // Forces at t = 0 (dt = 0) and the first time step. Call once after adding bodies.
  SphOutcome start();
  // One step; ends `unstable` on a non-finite value or an inverted particle.
  SphOutcome step();
  // Steps until `end_time` (or max_steps); returns finished or unstable.
  SphOutcome run(double end_time, long long max_steps = 100'000'000);

  double time() const { return time_; }
  double dt() const { return dt_; }
  long long steps() const { return steps_; }
  const SphEnergy& energy() const { return energy_; }
  const std::string& reason() const { return reason_; }
  long long reference_updates() const;

 private:
  SphOutcome compute_forces(double dt);

  std::vector<std::uint8_t> mask_;
  std::vector<Vec3> value_;
  double time_ = 0.0, dt_ = 0.0, dt_prev_ = 0.0;
  long long steps_ = 0;
  SphEnergy energy_;
  std::string reason_;
};

}  // namespace splat
