#include "solver/two_mass/two_mass_model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
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
  TwoMassRun run;
  const double dt_fixed = time.dt > 0.0 ? time.dt : two_mass_default_dt(s, time.end_time);
  const double h = 1.0 / s.M + 1.0 / s.m;  // inverse effective mass of the pair, 1/kg
  const double F_cap = max_tension(s.adhesion, s.area);
  const double E0 = 0.5 * s.M * s.V0 * s.V0;

  // State: positions at t, velocities over the last step (v_{n-1/2}).
  double t = 0.0, X = 0.0, x = 0.0, V = s.V0, v = 0.0, W = 0.0;
  LinkState link = LinkState::none;
  TwoMassSummary& fig = run.figures;
  fig.work_budget = work_budget(s.adhesion, s.area);
  fig.dt = dt_fixed;

  TwoMassRow row;
  const auto fill_row = [&](double link_force, double contact_force) {
    row.t = t;
    row.x_M = X;
    row.x_m = x;
    row.v_M = V;
    row.v_m = v;
    row.gap = x - X;
    row.link_force = link_force;
    row.contact_force = contact_force;
    row.link_work = W;
    row.kinetic = 0.5 * s.M * V * V + 0.5 * s.m * v * v;
    row.spring = 0.5 * s.k * x * x;
    row.balance_error = E0 > 0.0 ? (row.kinetic + row.spring + W - E0) / E0 : 0.0;
    row.link_state = static_cast<int>(link);
  };
  fill_row(0.0, 0.0);
  if (record) record(row);

  bool decided = false;
  while (!decided) {
    const double dt = std::min(dt_fixed, time.end_time - t);
    // 1. update: spring force on m.
    const double g_prev = v - V;
    double V_new = V;
    double v_new = v - dt * s.k * x / s.m;
    // 2. contact: no penetration, elastic impact on the rate at the step start.
    const double g_n = x - X;
    const double g_free = v_new - V_new;
    const bool touching = g_n + dt * g_free <= 0.0;
    double P = 0.0;  // compressive impulse, N s
    if (touching) {
      const double target = std::max(-g_n / dt, g_prev < 0.0 ? -k_restitution * g_prev : 0.0);
      if (g_free < target) {
        P = (target - g_free) / h;
        V_new -= P / s.M;
        v_new += P / s.m;
      }
    }
    // 3. link: rigid masses never damage, activation is `none` (scene_io).
    const LinkEvents events{touching, true, erosion_met(s.adhesion, 0.0, 0.0), false};
    link = next_link_state(link, s.adhesion.activation, events);
    double I = 0.0;  // tension impulse, N s
    bool released = false;
    if (link == LinkState::active) {
      // The link starts from the rate at the step start, or from the rate
      // the contact impulse of this step left (an impact inside the step).
      const double g_start = P > 0.0 ? v_new - V_new : g_prev;
      const CohesiveStep c =
          cohesive_step(s.adhesion, s.area, W, LinkKinematics{g_start, v_new - V_new, h, 0.0}, dt);
      I = c.impulse;
      V_new += I / s.M;
      v_new -= I / s.m;
      W += c.work;
      if (c.exhausted) {
        LinkEvents spent = events;
        spent.budget_spent = true;
        link = next_link_state(link, s.adhesion.activation, spent);
        released = true;
      }
    } else if (link == LinkState::eroded && !fig.release_time) {
      released = true;
    }
    // 4. predict.
    V = V_new;
    v = v_new;
    X += dt * V;
    x += dt * v;
    t += dt;
    ++run.steps;
    if (released) {
      fig.release_time = t;
      fig.separation_velocity = -V;
    }
    fig.max_link_force = std::max(fig.max_link_force, I / dt);
    fill_row(I / dt, P / dt);
    if (record) record(row);

    // 5. decide, then the checks every run has.
    const double g_dot = v - V;
    const double gap = x - X;
    if (!std::isfinite(X + x + V + v + W)) {
      run.outcome = RunOutcome::unstable;
      run.stop_reason = StopReason::non_finite;
      run.reason = "a position or velocity became non-finite at t = " + seconds_text(t);
      break;
    }
    if (link == LinkState::exhausted || link == LinkState::eroded) {
      bool apart = false;
      if (s.k == 0.0) {
        apart = g_dot >= 0.0;  // no force acts any more: they never meet again
      } else {
        const double reach = std::sqrt(x * x + v * v * s.m / s.k);  // m's amplitude
        apart = V <= 0.0 && X < -reach;
      }
      if (apart) {
        run.outcome = RunOutcome::rebound;
        run.stop_reason = StopReason::separated;
        run.reason = "the link let go at t = " + seconds_text(*fig.release_time) +
                     " and the masses can no longer meet";
        decided = true;
      }
    } else if (link == LinkState::active) {
      // With k > 0 the link's work is taken from the mechanical energy (the
      // spring couples M to the frame, so all of it may be converted); a
      // remaining budget above it can never be spent: the link holds for
      // good, though the masses may chatter for a long time before they
      // settle. (k = 0 settles within mu V0 / F_cap, below.)
      const double convertible = row.kinetic + row.spring;
      if (s.k > 0.0 && fig.work_budget - W > convertible * (1.0 + 1e-6)) {
        run.outcome = RunOutcome::stick;
        run.stop_reason = StopReason::budget_exceeds_energy;
        run.reason =
            "the link's remaining adhesion budget exceeds the mechanical energy left: it "
            "can never let go";
        decided = true;
      }
      const double eps_v = 1e-12 * (s.V0 + std::abs(V) + std::abs(v));
      const double eps_x = 1e-9 * (std::abs(X) + std::abs(x) + s.V0 * dt);
      // k = 0: nothing acts on a held pair, whatever its gap; k > 0: the
      // joint oscillation needs compression half the time, which only the
      // contact (gap 0) can carry.
      if (std::abs(g_dot) <= eps_v && (s.k == 0.0 || std::abs(gap) <= eps_x)) {
        bool settled = s.k == 0.0;
        if (!settled) {
          // Joint oscillation of M + m on the spring: the link must pull M
          // with M k A / (M + m) at the extreme x = -A.
          const double v_joint = (s.M * V + s.m * v) / (s.M + s.m);
          const double A = std::sqrt(x * x + v_joint * v_joint * (s.M + s.m) / s.k);
          settled = s.M * s.k * A / (s.M + s.m) <= F_cap * (1.0 - 1e-9);
        }
        if (settled && !decided) {
          run.outcome = RunOutcome::stick;
          run.stop_reason = StopReason::settled;
          run.reason =
              "the link holds the masses together and can carry every tension the "
              "remaining motion needs";
          decided = true;
        }
      }
    }
    if (decided) break;
    if (E0 > 0.0 && std::abs(row.balance_error) > time.energy_balance_limit) {
      run.outcome = RunOutcome::unstable;
      run.stop_reason = StopReason::energy_balance;
      run.reason = "energy balance error above its limit at t = " + seconds_text(t) +
                   " (time step too large?)";
      break;
    }
    if (t >= time.end_time * (1.0 - 1e-12)) {
      const bool broken = link == LinkState::exhausted || link == LinkState::eroded;
      run.outcome = broken ? RunOutcome::rebound : RunOutcome::stick;
      run.stop_reason = StopReason::end_time;
      const double K_rel = 0.5 * g_dot * g_dot / h;  // relative kinetic energy, J
      const double W_rem = fig.work_budget - W;
      if (broken) {
        run.reason = "reached the end time after the link let go (the masses may still meet again)";
      } else if (s.k == 0.0 && g_dot > 0.0 && K_rel > W_rem) {
        // Free masses still opening with more relative kinetic energy than
        // the link can take: it will let go, at the velocity momentum and
        // energy give (the closed form of the k = 0 problem).
        const double g_final = std::sqrt(g_dot * g_dot - 2.0 * h * W_rem);
        const double u = (s.M * V + s.m * v) / (s.M + s.m);
        run.outcome = RunOutcome::rebound;
        run.stop_reason = StopReason::end_time_predicted;
        fig.separation_velocity = -(u - s.m / (s.M + s.m) * g_final);
        run.reason =
            "reached the end time before the link let go; with k = 0 it will (relative "
            "kinetic energy " +
            std::to_string(K_rel) + " J > remaining budget " + std::to_string(W_rem) +
            " J): separation velocity from momentum and energy, release time unknown";
      } else {
        char buf[160];
        std::snprintf(buf, sizeof buf, " (not settled: gap %.3e m, opening at %.3e m/s)", gap,
                      g_dot);
        run.reason =
            "reached the end time with the link still " + std::string(to_string(link)) + buf;
      }
      break;
    }
    if (run.steps >= time.max_steps) {
      run.outcome = RunOutcome::timed_out;
      run.stop_reason = StopReason::step_limit;
      run.reason = "step limit of " + std::to_string(time.max_steps) +
                   " steps reached at t = " + seconds_text(t) +
                   " with dt = " + seconds_text(dt_fixed) +
                   " (the step resolves the spring period 2 pi sqrt(m/k) and the opening time)";
      break;
    }
    if ((run.steps & 4095) == 0) {
      if (cancel != nullptr && cancel->load()) {
        run.outcome = RunOutcome::cancelled;
        run.stop_reason = StopReason::cancelled;
        run.reason = "cancelled at t = " + seconds_text(t);
        break;
      }
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (time.wall_clock_limit > 0.0 && wall > time.wall_clock_limit) {
        run.outcome = RunOutcome::timed_out;
        run.stop_reason = StopReason::wall_clock_limit;
        run.reason = "wall-clock limit reached at t = " + seconds_text(t);
        break;
      }
    }
  }

  run.time = t;
  fig.final_velocity_M = V;
  fig.final_velocity_m = v;
  fig.final_gap = x - X;
  fig.link_state = to_string(link);
  fig.link_work = W;
  EnergyBudget& e = run.energy;
  e.initial_total = E0;
  e.kinetic = row.kinetic;
  e.internal = row.spring;
  e.external_work = -W;  // taken out by the link (adhesion energy)
  e.balance_error = row.balance_error;
  return run;
}

RunSummary run_two_mass(const Scene& scene, const nlohmann::json& resolved,
                        const SimulationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  RunSummary summary;
  summary.scene = scene.name;
  summary.threads = 1;
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
