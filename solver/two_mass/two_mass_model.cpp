#include "solver/two_mass/two_mass_model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/adhesion/cohesive_law.hpp"
#include "solver/build_info.hpp"
#include "solver/io/result_file.hpp"

namespace splat {

namespace {

constexpr double k_pi = 3.14159265358979323846;
constexpr double k_restitution = 1.0;  // elastic rigid collision (thesis eq. 3.1), -
constexpr double k_steps_per_scale = 2000.0;

std::string seconds_text(double t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g s", t);
  return buf;
}

// The leapfrog integration of the two masses (see the header): state at t,
// velocities over the last step (v_{n-1/2}), the link's state and work, and
// the run's figures as they build up.
class TwoMassIntegrator {
 public:
  TwoMassIntegrator(const TwoMassSpec& s, const TimeSpec& time)
      : s_(s),
        time_(time),
        dt_fixed_(time.dt > 0.0 ? time.dt : two_mass_default_dt(s, time.end_time)),
        h_(1.0 / s.M + 1.0 / s.m),
        F_cap_(max_tension(s.adhesion, s.area)),
        E0_(0.5 * s.M * s.V0 * s.V0),
        V_(s.V0) {
    run_.figures.work_budget = work_budget(s.adhesion, s.area);
    run_.figures.dt = dt_fixed_;
  }

  // One step of stages 1-4; the row gets the state after it.
  void step() {
    const double dt = std::min(dt_fixed_, time_.end_time - t_);
    dt_ = dt;
    TwoMassSummary& fig = run_.figures;
    // 1. update: spring force on m.
    const double g_prev = v_ - V_;
    double V_new = V_;
    double v_new = v_ - dt * s_.k * x_ / s_.m;
    // 2. contact: no penetration, elastic impact on the rate at the step start.
    const double g_n = x_ - X_;
    const double g_free = v_new - V_new;
    const bool touching = g_n + dt * g_free <= 0.0;
    double P = 0.0;  // compressive impulse, N s
    if (touching) {
      const double target = std::max(-g_n / dt, g_prev < 0.0 ? -k_restitution * g_prev : 0.0);
      if (g_free < target) {
        P = (target - g_free) / h_;
        V_new -= P / s_.M;
        v_new += P / s_.m;
      }
    }
    // 3. link: rigid masses never damage, activation is `none` (scene_io).
    const LinkEvents events{touching, true, erosion_met(s_.adhesion, 0.0, 0.0), false};
    link_ = next_link_state(link_, s_.adhesion.activation, events);
    double I = 0.0;  // tension impulse, N s
    bool released = false;
    if (link_ == LinkState::active) {
      // The link starts from the rate at the step start, or from the rate
      // the contact impulse of this step left (an impact inside the step).
      const double g_start = P > 0.0 ? v_new - V_new : g_prev;
      const CohesiveStep c = cohesive_step(s_.adhesion, s_.area, W_,
                                           LinkKinematics{g_start, v_new - V_new, h_, 0.0}, dt);
      I = c.impulse;
      V_new += I / s_.M;
      v_new -= I / s_.m;
      W_ += c.work;
      if (c.exhausted) {
        LinkEvents spent = events;
        spent.budget_spent = true;
        link_ = next_link_state(link_, s_.adhesion.activation, spent);
        released = true;
      }
    } else if (link_ == LinkState::eroded && !fig.release_time) {
      released = true;
    }
    // 4. predict.
    V_ = V_new;
    v_ = v_new;
    X_ += dt * V_;
    x_ += dt * v_;
    t_ += dt;
    ++run_.steps;
    if (released) {
      fig.release_time = t_;
      fig.separation_velocity = -V_;
    }
    fig.max_link_force = std::max(fig.max_link_force, I / dt);
    fill_row(I / dt, P / dt);
  }

  void fill_row(double link_force, double contact_force) {
    row_.t = t_;
    row_.x_M = X_;
    row_.x_m = x_;
    row_.v_M = V_;
    row_.v_m = v_;
    row_.gap = x_ - X_;
    row_.link_force = link_force;
    row_.contact_force = contact_force;
    row_.link_work = W_;
    row_.kinetic = 0.5 * s_.M * V_ * V_ + 0.5 * s_.m * v_ * v_;
    row_.spring = 0.5 * s_.k * x_ * x_;
    row_.balance_error = E0_ > 0.0 ? (row_.kinetic + row_.spring + W_ - E0_) / E0_ : 0.0;
    row_.link_state = static_cast<int>(link_);
  }

  const TwoMassRow& row() const { return row_; }

  // Stage 5: whether the run ends after this step (outcome and reason set).
  bool stops(std::chrono::steady_clock::time_point start, const std::atomic<bool>* cancel) {
    if (!std::isfinite(X_ + x_ + V_ + v_ + W_)) {
      return stop(RunOutcome::unstable, StopReason::non_finite,
                  "a position or velocity became non-finite at t = " + seconds_text(t_));
    }
    if (decided()) return true;
    if (E0_ > 0.0 && std::abs(row_.balance_error) > time_.energy_balance_limit) {
      return stop(RunOutcome::unstable, StopReason::energy_balance,
                  "energy balance error above its limit at t = " + seconds_text(t_) +
                      " (time step too large?)");
    }
    if (t_ >= time_.end_time * (1.0 - 1e-12)) {
      at_end_time();
      return true;
    }
    if (run_.steps >= time_.max_steps) {
      return stop(RunOutcome::timed_out, StopReason::step_limit,
                  "step limit of " + std::to_string(time_.max_steps) + " steps reached at t = " +
                      seconds_text(t_) + " with dt = " + seconds_text(dt_fixed_) +
                      " (the step resolves the spring period 2 pi sqrt(m/k) and the opening "
                      "time)");
    }
    if ((run_.steps & 4095) != 0) return false;
    if (cancel != nullptr && cancel->load()) {
      return stop(RunOutcome::cancelled, StopReason::cancelled,
                  "cancelled at t = " + seconds_text(t_));
    }
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (time_.wall_clock_limit > 0.0 && wall > time_.wall_clock_limit) {
      return stop(RunOutcome::timed_out, StopReason::wall_clock_limit,
                  "wall-clock limit reached at t = " + seconds_text(t_));
    }
    return false;
  }

  TwoMassRun finish() {
    TwoMassSummary& fig = run_.figures;
    run_.time = t_;
    fig.final_velocity_M = V_;
    fig.final_velocity_m = v_;
    fig.final_gap = x_ - X_;
    fig.link_state = to_string(link_);
    fig.link_work = W_;
    EnergyBudget& e = run_.energy;
    e.initial_total = E0_;
    e.kinetic = row_.kinetic;
    e.internal = row_.spring;
    e.external_work = -W_;  // taken out by the link (adhesion energy)
    e.balance_error = row_.balance_error;
    return run_;
  }

 private:
  bool stop(RunOutcome outcome, StopReason reason, std::string text) {
    run_.outcome = outcome;
    run_.stop_reason = reason;
    run_.reason = std::move(text);
    return true;
  }

  bool broken() const { return link_ == LinkState::exhausted || link_ == LinkState::eroded; }

  // A verdict from the link: let go and apart for good (rebound), or holding
  // what the remaining motion needs (stick).
  bool decided() {
    if (broken()) {
      bool apart = false;
      if (s_.k == 0.0) {
        apart = v_ - V_ >= 0.0;  // no force acts any more: they never meet again
      } else {
        const double reach = std::sqrt(x_ * x_ + v_ * v_ * s_.m / s_.k);  // m's amplitude
        apart = V_ <= 0.0 && X_ < -reach;
      }
      if (!apart) return false;
      return stop(RunOutcome::rebound, StopReason::separated,
                  "the link let go at t = " + seconds_text(*run_.figures.release_time) +
                      " and the masses can no longer meet");
    }
    if (link_ != LinkState::active) return false;
    // With k > 0 the link's work is taken from the mechanical energy (the
    // spring couples M to the frame, so all of it may be converted); a
    // remaining budget above it can never be spent: the link holds for
    // good, though the masses may chatter for a long time before they
    // settle. (k = 0 settles within mu V0 / F_cap, below.)
    const double convertible = row_.kinetic + row_.spring;
    if (s_.k > 0.0 && run_.figures.work_budget - W_ > convertible * (1.0 + 1e-6)) {
      return stop(RunOutcome::stick, StopReason::budget_exceeds_energy,
                  "the link's remaining adhesion budget exceeds the mechanical energy left: it "
                  "can never let go");
    }
    if (!held_at_rest()) return false;
    return stop(RunOutcome::stick, StopReason::settled,
                "the link holds the masses together and can carry every tension the "
                "remaining motion needs");
  }

  // The pair at rest relative to each other, and the link strong enough for
  // what remains. k = 0: nothing acts on a held pair, whatever its gap;
  // k > 0: the joint oscillation needs compression half the time, which
  // only the contact (gap 0) can carry.
  bool held_at_rest() const {
    const double g_dot = v_ - V_, gap = x_ - X_;
    const double eps_v = 1e-12 * (s_.V0 + std::abs(V_) + std::abs(v_));
    const double eps_x = 1e-9 * (std::abs(X_) + std::abs(x_) + s_.V0 * dt_);
    if (!(std::abs(g_dot) <= eps_v && (s_.k == 0.0 || std::abs(gap) <= eps_x))) return false;
    if (s_.k == 0.0) return true;
    // Joint oscillation of M + m on the spring: the link must pull M with
    // M k A / (M + m) at the extreme x = -A.
    const double v_joint = (s_.M * V_ + s_.m * v_) / (s_.M + s_.m);
    const double A = std::sqrt(x_ * x_ + v_joint * v_joint * (s_.M + s_.m) / s_.k);
    return s_.M * s_.k * A / (s_.M + s_.m) <= F_cap_ * (1.0 - 1e-9);
  }

  void at_end_time() {
    const double g_dot = v_ - V_, gap = x_ - X_;
    run_.outcome = broken() ? RunOutcome::rebound : RunOutcome::stick;
    run_.stop_reason = StopReason::end_time;
    const double K_rel = 0.5 * g_dot * g_dot / h_;  // relative kinetic energy, J
    const double W_rem = run_.figures.work_budget - W_;
    if (broken()) {
      run_.reason = "reached the end time after the link let go (the masses may still meet again)";
    } else if (s_.k == 0.0 && g_dot > 0.0 && K_rel > W_rem) {
      // Free masses still opening with more relative kinetic energy than
      // the link can take: it will let go, at the velocity momentum and
      // energy give (the closed form of the k = 0 problem).
      const double g_final = std::sqrt(g_dot * g_dot - 2.0 * h_ * W_rem);
      const double u = (s_.M * V_ + s_.m * v_) / (s_.M + s_.m);
      run_.outcome = RunOutcome::rebound;
      run_.stop_reason = StopReason::end_time_predicted;
      run_.figures.separation_velocity = -(u - s_.m / (s_.M + s_.m) * g_final);
      run_.reason =
          "reached the end time before the link let go; with k = 0 it will (relative "
          "kinetic energy " +
          std::to_string(K_rel) + " J > remaining budget " + std::to_string(W_rem) +
          " J): separation velocity from momentum and energy, release time unknown";
    } else {
      char buf[160];
      std::snprintf(buf, sizeof buf, " (not settled: gap %.3e m, opening at %.3e m/s)", gap, g_dot);
      run_.reason =
          "reached the end time with the link still " + std::string(to_string(link_)) + buf;
    }
  }

  const TwoMassSpec& s_;
  const TimeSpec& time_;
  const double dt_fixed_;  // s
  const double h_;         // inverse effective mass of the pair, 1/kg
  const double F_cap_;     // N, the link's largest tension
  const double E0_;        // J, initial kinetic energy
  double dt_ = 0.0;        // s, of the last step
  double t_ = 0.0, X_ = 0.0, x_ = 0.0, V_ = 0.0, v_ = 0.0, W_ = 0.0;
  LinkState link_ = LinkState::none;
  TwoMassRow row_;
  TwoMassRun run_;
};

}  // namespace

double two_mass_default_dt(const TwoMassSpec& s, double end_time) {
  double scale = end_time;
  if (s.k > 0.0) scale = std::min(scale, 2.0 * k_pi * std::sqrt(s.m / s.k));
  const double cap = max_tension(s.adhesion, s.area);
  if (std::isfinite(cap) && cap > 0.0 && s.V0 > 0.0) {
    const double mu = s.M * s.m / (s.M + s.m);
    scale = std::min(scale, mu * s.V0 / cap);
  }
  return scale / k_steps_per_scale;
}

TwoMassRun integrate_two_mass(const TwoMassSpec& s, const TimeSpec& time,
                              const std::function<void(const TwoMassRow&)>& record,
                              const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  TwoMassIntegrator it(s, time);
  it.fill_row(0.0, 0.0);
  if (record) record(it.row());
  do {
    it.step();
    if (record) record(it.row());
  } while (!it.stops(start, cancel));
  return it.finish();
}

RunSummary run_two_mass(const Scene& scene, const nlohmann::json& resolved,
                        const SimulationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  RunSummary summary;
  summary.scene = scene.name;
  try {
    std::unique_ptr<ResultFile> file;
    const std::vector<std::pair<std::string, std::string>> columns = {
        {"time", "s"},      {"x_M", "m"},     {"x_m", "m"},        {"v_M", "m/s"},
        {"v_m", "m/s"},     {"gap", "m"},     {"link_force", "N"}, {"contact_force", "N"},
        {"link_work", "J"}, {"kinetic", "J"}, {"spring", "J"},     {"balance_error", "-"},
        {"link_state", "-"}};
    if (!options.output_dir.empty()) {
      std::filesystem::create_directories(options.output_dir);
      file = std::make_unique<ResultFile>(options.output_dir / (scene.name + ".h5"),
                                          std::vector<BodyTopology>{}, columns);
      file->set_attribute("solver_version", std::string(version()));
      file->set_attribute("git_commit", std::string(git_commit()));
      file->set_attribute("scene_name", scene.name);
      file->set_attribute("scene", resolved.dump());
      file->set_attribute("frame",
                          "two-mass: positions and velocities along +x, the direction in which M "
                          "first moved towards m; link_state 0 none, 1 contact, 2 active, "
                          "3 exhausted, 4 eroded");
    }
    const double interval = scene.output.history_interval;
    double next_time = 0.0;
    bool last_written = false;
    TwoMassRow last;
    const auto record = [&](const TwoMassRow& r) {
      last = r;
      last_written = false;
      if (!file || r.t < next_time) return;
      if (interval > 0.0) {
        while (next_time <= r.t) next_time += interval;
      }
      const double values[] = {r.t,
                               r.x_M,
                               r.x_m,
                               r.v_M,
                               r.v_m,
                               r.gap,
                               r.link_force,
                               r.contact_force,
                               r.link_work,
                               r.kinetic,
                               r.spring,
                               r.balance_error,
                               static_cast<double>(r.link_state)};
      file->append_history(values);
      last_written = true;
    };
    const TwoMassRun run = integrate_two_mass(*scene.two_mass, scene.time, record, options.cancel);
    if (file && !last_written) {
      next_time = -1.0;
      record(last);
    }
    summary.outcome = run.outcome;
    summary.reason = run.reason;
    summary.stop_reason = run.stop_reason;
    summary.steps = run.steps;
    summary.end_time = run.time;
    summary.energy = run.energy;
    summary.two_mass = run.figures;
    if (file) {
      file->set_attribute("outcome", to_string(summary.outcome));
      file->set_attribute("reason", summary.reason);
      file->set_attribute("stop_reason", name_or_empty(summary.stop_reason));
      file->set_attribute("steps", summary.steps);
      file->set_attribute("end_time", summary.end_time, "s");
      file->set_attribute("link_work", run.figures.link_work, "J");
      if (run.figures.separation_velocity) {
        file->set_attribute("separation_velocity", *run.figures.separation_velocity, "m/s");
      }
      summary.hdf5_path = file->h5_path().string();
      summary.xdmf_path = file->xmf_path().string();
      file->close();
    }
  } catch (const std::exception& e) {
    summary.outcome = RunOutcome::error;
    summary.stop_reason = StopReason::error;
    summary.reason = e.what();
  }
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace splat
