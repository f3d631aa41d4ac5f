// splat run SCENE.json [--set /json/pointer=VALUE ...] [--out DIR] [--json]
// Runs one scene. Writes DIR/<scene>.h5 (+ .xmf) and DIR/<scene>.summary.json
// and prints the summary (schemas/result.schema.json with --json).
// Exit code: 0 finished (two-mass and particle_impact scenes: stick or rebound), 3 ended otherwise
// (unstable, timed-out, error; the summary says why), 2 bad input, 74 the output could not be
// written, 75 out of memory (app/main.cpp).
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "app/commands.hpp"
#include "solver/common/parallel.hpp"
#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/two_mass/two_mass_model.hpp"

namespace splat::app {

namespace {

struct RunOptions {
  std::string scene;
  std::vector<std::string> overrides;
  std::string out = "out";
  bool json = false;
  bool progress = false;
  int threads = 0;
  ThreadPolicy thread_policy = ThreadPolicy::adaptive;
};

// "2 threads (adaptive: 812 steps on 2, 40 on 1)", "1 thread".
std::string thread_use_text(const ThreadUse& u) {
  std::string text = std::to_string(u.team) + (u.team == 1 ? " thread" : " threads");
  if (u.policy == ThreadPolicy::fixed) return text;
  return text + " (adaptive: " + std::to_string(u.steps_on_team) + " steps on " +
         std::to_string(u.team) + ", " + std::to_string(u.steps_on_one) + " on 1)";
}

void print_two_mass(const RunSummary& s) {
  const TwoMassSummary& t = *s.two_mass;
  std::printf("  steps %lld (dt %.4e s), end time %.4e s, wall %.3f s\n", s.steps, t.dt, s.end_time,
              s.wall_seconds);
  if (t.separation_velocity) {
    std::printf("  link let go at t = %.6e s; separation velocity %.6g m/s (away from m)\n",
                *t.release_time, *t.separation_velocity);
  }
  std::printf("  link %s, work %.6e of %.6e J, largest tension %.4e N\n", t.link_state.c_str(),
              t.link_work, t.work_budget, t.max_link_force);
  std::printf("  final velocities: M %.6g m/s, m %.6g m/s; gap %.4e m\n", t.final_velocity_M,
              t.final_velocity_m, t.final_gap);
  std::printf("  energy balance error %.3e of the initial energy\n", s.energy.balance_error);
  if (!s.hdf5_path.empty()) std::printf("  result %s\n", s.hdf5_path.c_str());
}

void print_human(const RunSummary& s) {
  std::printf("scene %s: %s (%s)\n", s.scene.c_str(), to_string(s.outcome), s.reason.c_str());
  if (s.two_mass) {
    print_two_mass(s);
    return;
  }
  std::printf("  steps %lld, end time %.4e s, wall %.2f s, %s\n", s.steps, s.end_time,
              s.wall_seconds, thread_use_text(s.threads).c_str());
  const EnergyBudget& e = s.energy;
  std::printf("  energy J: initial %.4e kinetic %.4e internal %.4e (plastic %.4e)\n",
              e.initial_total, e.kinetic, e.internal, e.plastic_work);
  std::printf("            hourglass %.3e viscosity %.3e absorbed %.3e eroded %.3e wall %.3e\n",
              e.hourglass, e.artificial_viscosity, e.absorbed, e.eroded, e.wall_work);
  std::printf("            balance error %.3e of the initial energy\n", e.balance_error);
  for (const BodySummary& b : s.bodies) {
    std::printf(
        "  body %s: %lld elements, v = (%.4g, %.4g, %.4g) m/s, max eps_p %.3f, max T %.1f K\n",
        b.name.c_str(), b.elements, b.centroid_velocity.x(), b.centroid_velocity.y(),
        b.centroid_velocity.z(), b.max_plastic_strain, b.max_temperature);
    std::printf("    extent (%.4e, %.4e, %.4e) .. (%.4e, %.4e, %.4e) m\n", b.extent_min.x(),
                b.extent_min.y(), b.extent_min.z(), b.extent_max.x(), b.extent_max.y(),
                b.extent_max.z());
  }
  if (s.impact) {
    const ImpactSummary& r = *s.impact;
    std::printf("  impact %s: verdict %s (%s), stop %s\n", name_or_empty(r.model).c_str(),
                r.verdict.c_str(), r.settled ? "settled" : "not settled",
                name_or_empty(s.stop_reason).c_str());
    std::printf(
        "    rebound velocity %.4g m/s (COR %.3f), bonded area %.4e m^2 (%.1f %% of %.4e)\n",
        r.rebound_velocity, r.coefficient_of_restitution, r.bonded_area, 100.0 * r.bonded_fraction,
        r.contact_area);
    std::printf("    links: contact %lld activated %lld exhausted %lld eroded %lld active %lld\n",
                r.links_contact, r.links_activated, r.links_exhausted, r.links_eroded,
                r.links_active);
    std::printf("    flattening %.3f, penetration %.4e m, max eps_p %.3f, max T %.1f K\n",
                r.flattening_ratio, r.penetration_depth, r.max_plastic_strain, r.max_temperature);
  }
  if (!s.hdf5_path.empty() && !s.xdmf_path.empty()) {
    std::printf("  result %s (ParaView: %s)\n", s.hdf5_path.c_str(), s.xdmf_path.c_str());
  } else if (!s.hdf5_path.empty()) {
    std::printf("  result %s (histories; no field snapshots)\n", s.hdf5_path.c_str());
  }
}

int run_scene(const RunOptions& o) {
  check_threads_option(o.threads);
  const LoadedScene loaded = load_scene(o.scene, o.overrides);
  SimulationOptions so;
  so.output_dir = o.out;
  so.threads = o.threads;
  so.thread_policy = o.thread_policy;
  so.quiet = !o.progress;
  RunSummary summary;
  if (loaded.scene.two_mass) {
    summary = run_two_mass(loaded.scene, loaded.resolved, so);
  } else {
    Simulation sim(loaded.scene, loaded.resolved, so);
    summary = sim.run();
  }
  const nlohmann::json doc = to_json(summary);
  if (!o.out.empty()) {
    const std::filesystem::path file =
        std::filesystem::path(o.out) / (loaded.scene.name + ".summary.json");
    std::ofstream f(file);
    f << doc.dump(2) << "\n";
    f.close();
    if (!f) {
      throw std::filesystem::filesystem_error("cannot write the summary", file,
                                              std::error_code(errno, std::generic_category()));
    }
  }
  if (o.json) {
    std::printf("%s\n", doc.dump(2).c_str());
  } else {
    print_human(summary);
  }
  const bool ran_to_a_verdict = summary.outcome == RunOutcome::finished ||
                                summary.outcome == RunOutcome::stick ||
                                summary.outcome == RunOutcome::rebound;
  return ran_to_a_verdict ? 0 : 3;
}

}  // namespace

void check_threads_option(int threads) {
  if (threads < 0 || threads > max_threads()) {
    throw std::invalid_argument("--threads " + std::to_string(threads) +
                                ": must be 0 (the default) to " + std::to_string(max_threads()) +
                                ", the cores of this machine");
  }
}

void add_thread_policy_option(CLI::App& sub, ThreadPolicy& policy) {
  std::vector<std::string> names;
  for (const auto& entry : k_thread_policy_names) names.emplace_back(entry.second);
  sub.add_option_function<std::string>(
         "--thread-policy",
         [&policy](const std::string& name) { policy = *parse<ThreadPolicy>(name); },
         "adaptive: the whole team only while the run measures it more than 3 % faster "
         "than one thread (not on a loaded machine); fixed: always the whole team")
      ->check(CLI::IsMember(names))
      ->default_str(std::string(to_string(policy)));
}

void register_run(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run", "Run one scene and print its result summary");
  sub->add_option("scene", o->scene, "Scene JSON file")->required();
  sub->add_option("--set", o->overrides,
                  "Override a scene field before validation: /json/pointer=VALUE (VALUE is JSON, "
                  "or a plain string); missing objects on the way are created");
  sub->add_option("--out", o->out, "Output directory for the HDF5/XDMF files and the summary")
      ->capture_default_str();
  sub->add_flag("--json", o->json, "Print the summary as JSON (schemas/result.schema.json)");
  sub->add_flag("--progress", o->progress, "Print progress lines on stderr");
  sub->add_option("--threads", o->threads, "OpenMP threads (0: default; at most the cores)")
      ->capture_default_str();
  add_thread_policy_option(*sub, o->thread_policy);
  commands.emplace_back(sub, [o] { return run_scene(*o); });
}

}  // namespace splat::app
