// The explicit time loop: builds bodies from a Scene, advances them by
// central differences and ends every run with an outcome and a reason.
//
// Stages of one step (docs/design.md "Stages of a time step"):
//   1. update       a_n = f_n / m; v_{n+1/2} = v_{n-1/2} + dt_n a_n (absorbing
//                   dashpots at the mid-point); velocity constraints (fixed,
//                   symmetry, axis, prescribed); rigid walls
//   2. predict      x_{n+1} = x_n + dt_{n+1/2} v_{n+1/2}
//   3. contact      Lagrange-multiplier contact on the predicted positions:
//                   v_{n+1/2} and x_{n+1} corrected so x_{n+1} does not penetrate
//   4. internal     element loop: velocity gradient, material update, bulk
//      forces       viscosity, hourglass control, nodal forces, CFL bound
//   5. boundary     penalty contact forces; dashpot matrices of the absorbing
//      forces       faces at x_{n+1}
//   6. diagnostics  energies, histories, snapshots, stop checks; next dt
#pragma once

#include <atomic>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/core/run_summary.hpp"
#include "solver/core/thread_governor.hpp"
#include "solver/fe/fe_body.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sph/sph_body.hpp"

namespace splat {

struct SimulationOptions {
  std::filesystem::path output_dir;                     // empty: no result file
  int threads = 0;                                      // the team; 0: OpenMP default
  ThreadPolicy thread_policy = ThreadPolicy::adaptive;  // thread_governor.hpp
  ThreadGovernorSettings thread_governor;
  const std::atomic<bool>* cancel = nullptr;
  bool quiet = true;  // no progress lines on stderr
};

class Simulation {
 public:
  // Builds the model; throws InputError when the scene cannot be modelled.
  Simulation(const Scene& scene, nlohmann::json resolved_scene, SimulationOptions options);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Runs to the end time or to the first stop condition. Never throws.
  RunSummary run();

  const NodeSet& nodes() const;
  const std::vector<FeBody>& bodies() const;       // FE bodies
  const std::vector<SphBody>& sph_bodies() const;  // SPH bodies
  bool axisymmetric() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace splat
