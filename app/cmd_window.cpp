// splat window --particle MATERIAL [--substrate MATERIAL] [--radius R]
//              [--velocity FROM:TO[:STEP]] [--accuracy fast|converged] [--G_c G]
//              [--db FILE] [--workers N]
// One command from a material pair to a deposition window: builds the
// campaign (axisymmetric FE impact with splat's bonding model, the
// velocity grid, refinement of the edges and, for `converged`, a resolution
// ladder of campaign::k_converged_ladder refined coarse to fine), runs it
// like `splat sweep` (resumable: the same command continues it) and prints
// the window with its error from resolution and where everything is stored.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "app/commands.hpp"
#include "app/sweep_runner.hpp"
#include "campaign/window_request.hpp"
#include "solver/input/schema.hpp"

namespace splat::app {

namespace {

struct WindowOptions {
  campaign::WindowRequest request;
  std::string velocity = "100:1200:100";
  SweepRun run;
};

int run_window(WindowOptions o) {
  o.request.velocity = campaign::parse_velocity_range(o.velocity);
  const nlohmann::json doc = campaign::window_campaign(o.request);
  o.run.workers = o.request.workers;
  const campaign::CampaignSpec spec = campaign::read_campaign(doc, std::filesystem::current_path());
  std::fprintf(stderr, "%s\n", spec.description.c_str());
  const int code = run_and_print(spec, o.run);
  if (o.request.accuracy == "fast") {
    std::printf(
        "\nerror bars: the brackets only (16 elements across); --accuracy converged adds "
        "the error from resolution (%s elements across, coarse to fine, the edges "
        "extrapolated).\n",
        campaign::converged_ladder_text().c_str());
  }
  std::printf(
      "\nstored in %s (job results under %s.jobs/): `splat windows --db %s --format "
      "ladders-csv` prints the edges again, `splat serve --db %s` shows them in the "
      "dashboard; the same command resumes an interrupted window.\n",
      o.run.db.c_str(), o.run.db.c_str(), o.run.db.c_str(), o.run.db.c_str());
  return code;
}

}  // namespace

void register_window(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<WindowOptions>();
  o->run.db = "window.db";
  o->request.workers = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  CLI::App* sub = app.add_subcommand(
      "window", "Deposition window of a material pair, with its error from resolution");
  sub->add_option("--particle", o->request.particle,
                  "Particle material: a library name (`splat materials`) or a material file")
      ->required();
  sub->add_option("--substrate", o->request.substrate,
                  "Substrate material (default: the particle's)");
  sub->add_option("--radius", o->request.radius, "Particle radius, m")->capture_default_str();
  sub->add_option("--velocity", o->velocity, "Impact speeds FROM:TO[:STEP], m/s")
      ->capture_default_str();
  sub->add_option("--accuracy", o->request.accuracy,
                  "fast (16 elements across) or converged (" + campaign::converged_ladder_text() +
                      " across, coarse to fine)")
      ->check(CLI::IsMember({"fast", "converged"}))
      ->capture_default_str();
  sub->add_option("--G_c", o->request.G_c, "Adhesion energy, J/m^2")->capture_default_str();
  sub->add_option("--db", o->run.db, "SQLite store")->capture_default_str();
  sub->add_option("--workers", o->request.workers,
                  "Jobs run at once; each refinement round runs as many new speeds (at most " +
                      std::to_string(campaign::k_max_points_per_round) + ")")
      ->capture_default_str();
  commands.emplace_back(sub, [o] { return run_window(*o); });
}

}  // namespace splat::app
