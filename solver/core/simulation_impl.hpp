// Private state of Simulation, shared by simulation.cpp (time loop) and
// simulation_output.cpp (result file). Not part of the solver's interface.
#pragma once

#include <array>
#include <chrono>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "solver/core/impact_run.hpp"
#include "solver/core/model_builder.hpp"
#include "solver/core/simulation.hpp"
#include "solver/io/result_file.hpp"

namespace splat {

// Dashpot matrix of one absorbing face on each of its nodes (equal shares):
// C = (A / count) (rho c_p n n^T + rho c_s (I - n n^T)), kg/s (per radian in
// 2D), on the face's current area A and normal n (Lysmer & Kuhlemeyer 1969);
// live = false for a face collapsed to zero area.
struct FaceDamping {
  Mat3 c = Mat3::Zero();
  bool live = false;
};
FaceDamping absorbing_face_damping(const AbsorbingFace& face, const NodeSet& n);

struct Simulation::Impl {
  Scene scene;
  nlohmann::json resolved;
  SimulationOptions options;
  Model model;

  // Running state.
  double time = 0.0;
  long long step = 0;
  double dt_half = 0.0;        // dt_{n+1/2}, s
  double dt_half_prev = 0.0;   // dt_{n-1/2}, s
  double dt_stable = 0.0;      // last CFL bound over all bodies, s
  double dt_first = 0.0;       // first step, s
  double closing_speed = 0.0;  // largest initial closing speed, m/s (model_builder.hpp)
  EnergyBudget energy;
  int max_return_iterations = 0;
  std::size_t next_snapshot = 0;
  std::size_t snapshots_written = 0;  // field snapshots in the result file
  double next_history_time = 0.0;
  std::unique_ptr<ResultFile> file;
  std::filesystem::path h5_path;
  // particle_impact scenes: the verdict monitor and the latest settled verdict.
  std::optional<ImpactRun> impact;
  std::optional<VerdictDecision> verdict;
  // Absorbing faces: per node, the slot of its dashpot matrix (-1: none; set
  // once), and the matrices, summed over the node's faces at the positions of
  // the last stage 5; face_damping is the per-face scratch.
  std::vector<int> damped_slot;
  std::vector<Mat3> node_damping;
  std::vector<FaceDamping> face_damping;

  // Energy factor: axisymmetric quantities are per radian.
  double scale() const { return model.axisymmetric ? 2.0 * std::numbers::pi : 1.0; }

  void set_driven_velocities();
  void update_velocities(bool first);
  void predict_positions();
  void contact_constraints();
  bool internal_forces(RunSummary& s);
  void boundary_forces();
  void setup_absorbing();
  void absorbing_damping();
  void compute_energies();
  std::optional<std::pair<RunOutcome, std::string>> checks(
      const std::chrono::steady_clock::time_point& start, std::optional<StopReason>& stop_reason);
  void open_output();
  void write_history();
  void write_snapshot(bool final_state = false);
  bool final_energy_check(RunSummary& s) const;
  void fill_summary(RunSummary& s) const;
  // SPH bodies (simulation_sph.cpp).
  bool sph_internal_forces_all(RunSummary& s);
  void sph_boundary_forces();
  Vec3 sph_dissipative_power() const;  // (viscosity, hourglass) -sum f . v, W
  void book_sph_dissipation(const Vec3& power_before, double dt_v);
  void sph_energies(double& internal, double& plastic) const;
  void sph_summaries(RunSummary& s) const;
};

}  // namespace splat
