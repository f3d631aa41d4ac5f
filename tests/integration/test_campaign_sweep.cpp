// Campaigns of real splat jobs: the two-mass adhesion model
// (scenes/verification/two_mass.json), run by `splat run` in child
// processes. For k = 0 the masses stick below
//   V0* = sqrt(2 G_c A (M + m) / (M m))
// (momentum and energy: the relative kinetic energy after the elastic
// collision must exceed the adhesion budget G_c A), an independent closed
// form the window edge is checked against. Also: refinement finds the same
// edge as a fine uniform grid with fewer jobs, and the sweep / windows /
// regress commands as users call them.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "campaign/manager.hpp"
#include "support/scene_runs.hpp"
#include "support/temp_dir.hpp"

namespace {

using splat::test_support::run_splat;

using namespace splat::campaign;
using nlohmann::json;
namespace fs = std::filesystem;

using splat::test_support::TempDir;

const fs::path k_source = SPLAT_SOURCE_DIR;

// The closed-form sticking threshold of the k = 0 two-mass problem, m/s.
double two_mass_threshold(double G_c, double area, double M, double m) {
  return std::sqrt(2.0 * G_c * area * (M + m) / (M * m));
}

json two_mass_campaign(const std::string& name, double step, std::optional<double> tolerance) {
  json doc = {{"name", name},
              {"base_scene", (k_source / "scenes/verification/two_mass.json").string()},
              {"velocity", {{"range", {{"from", 0.1}, {"to", 1.5}, {"step", step}}}}},
              {"G_c", {{"values", {0.1, 0.2}}}},
              {"job", {{"time_limit", 60}}}};
  if (tolerance) doc["refinement"] = {{"tolerance", *tolerance}, {"max_extra_jobs", 100}};
  return doc;
}

ManagerOptions splat_options() {
  ManagerOptions o;
  o.workers = 2;
  o.job_program = SPLAT_BINARY;
  o.poll_seconds = 0.05;
  return o;
}

TEST(campaign_sweep, refinement_finds_the_fine_grid_window_with_fewer_jobs) {
  TempDir t;
  const double tol = 0.01;  // m/s
  Store coarse_store(t.path / "refine.db");
  const CampaignSpec refine = read_campaign(two_mass_campaign("refine", 0.1, tol));
  const SweepReport r = run_sweep(coarse_store, refine, splat_options());
  ASSERT_EQ(r.state, CampaignState::finished);
  EXPECT_EQ(r.counts.failed + r.counts.timed_out, 0);

  Store fine_store(t.path / "fine.db");
  const CampaignSpec fine = read_campaign(two_mass_campaign("fine", tol, std::nullopt));
  const SweepReport f = run_sweep(fine_store, fine, splat_options());
  ASSERT_EQ(f.state, CampaignState::finished);

  ASSERT_EQ(r.windows.size(), 2u);
  ASSERT_EQ(f.windows.size(), 2u);
  const json scene = json::parse(std::ifstream(k_source / "scenes/verification/two_mass.json"));
  const json& tm = scene.at("two_mass");
  for (std::size_t i = 0; i < 2; ++i) {
    const json rw = json::parse(r.windows[i].window);
    const json fw = json::parse(f.windows[i].window);
    EXPECT_EQ(rw.at("params"), fw.at("params"));
    // Sticks from the lowest speed, rebounds above one edge: one interval.
    ASSERT_EQ(rw.at("intervals").size(), 1u);
    ASSERT_EQ(fw.at("intervals").size(), 1u);
    EXPECT_TRUE(rw.at("critical_velocity").is_null());
    const double v_refine = rw.at("maximum_velocity").get<double>();
    const double v_fine = fw.at("maximum_velocity").get<double>();
    EXPECT_LE(rw.at("maximum_bracket").at("width").get<double>(), tol + 1e-12);
    EXPECT_NEAR(v_refine, v_fine, tol);
    const double v_exact =
        two_mass_threshold(rw.at("params").at("G_c").get<double>(), tm.at("area").get<double>(),
                           tm.at("M").get<double>(), tm.at("m").get<double>());
    EXPECT_NEAR(v_refine, v_exact, tol / 2 + 1e-12) << "G_c " << rw.at("params");
    EXPECT_NEAR(v_fine, v_exact, tol / 2 + 1e-12);
  }
  const int refine_jobs = r.counts.total();
  const int fine_jobs = f.counts.total();
  std::printf("refinement: %d jobs, uniform grid at %g m/s: %d jobs (%.1f %%)\n", refine_jobs, tol,
              fine_jobs, 100.0 * refine_jobs / fine_jobs);
  EXPECT_LE(refine_jobs, 0.4 * fine_jobs);
}

TEST(campaign_sweep, sweep_and_windows_commands) {
  TempDir t;
  const fs::path spec = t.path / "c.json";
  std::ofstream(spec) << two_mass_campaign("cli", 0.1, 0.01).dump(2);
  const std::string db = (t.path / "c.db").string();
  auto o = run_splat("sweep " + spec.string() + " --db " + db + " --workers 2");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("critical velocity m/s"), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("below 0.1"), std::string::npos)
      << o.stdout_text;  // open lower edge
  // Again: everything comes from the store.
  o = run_splat("sweep " + spec.string() + " --db " + db);
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("0 started here"), std::string::npos) << o.stdout_text;

  o = run_splat("windows --db " + db + " --format json");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const json rows = json::parse(o.stdout_text);
  ASSERT_EQ(rows.size(), 2u);
  for (const json& row : rows) {
    EXPECT_TRUE(row.contains("params"));
    EXPECT_TRUE(row.at("critical_velocity").is_null());
    EXPECT_TRUE(row.at("maximum_velocity").is_number());
    EXPECT_TRUE(row.at("maximum_bracket").at("width").get<double>() <= 0.01);
    EXPECT_EQ(row.at("intervals").size(), 1u);
  }
  o = run_splat("windows --db " + db + " --format csv");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_EQ(o.stdout_text.rfind("campaign_id,params,critical_velocity", 0), 0u) << o.stdout_text;
  o = run_splat("windows --db " + db + " --campaign 99");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.stdout_text.find("--campaign: no campaign 99"), std::string::npos) << o.stdout_text;

  // Bad input names the field.
  std::ofstream(spec) << R"({"name": "bad", "base_scene": "x.json", "velocity": {"values": [-1]}})";
  o = run_splat("sweep " + spec.string() + " --db " + db);
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.stdout_text.find("/velocity/values/0: must be >= 0 (m/s)"), std::string::npos)
      << o.stdout_text;
}

// scenes/impact_al_al.json with the thesis's aluminium (al-thesis: links
// activate from about 300 m/s at 8 to 12 elements across), written to `dir`:
// a window low enough in speed for short jobs.
fs::path al_thesis_scene(const fs::path& dir) {
  json scene = json::parse(std::ifstream(k_source / "scenes/impact_al_al.json"));
  scene["particle_impact"]["particle"]["material"] = "al-thesis";
  const fs::path path = dir / "impact_al_al_thesis_material.json";
  std::ofstream(path) << scene.dump(2);
  return path;
}

// A campaign over the particle_impact example (scenes/impact_al_al.json):
// the axes default to the impact block's fields and the jobs are classified
// by the same stick / rebound outcome as two-mass jobs, so the window has a
// critical velocity (rebound at 200 m/s, stick at 500 m/s at 8 elements
// across; docs/verification.md "FE impact robustness").
TEST(campaign_sweep, impact_jobs_classify_like_two_mass_jobs) {
  TempDir t;
  const fs::path spec = t.path / "impact.json";
  std::ofstream(spec) << json{{"name", "impact"},
                              {"base_scene", al_thesis_scene(t.path).string()},
                              {"velocity", {{"values", {200, 500}}}},
                              {"G_c", {{"values", {30}}}},
                              {"job", {{"time_limit", 120}}}}
                             .dump(2);
  const std::string db = (t.path / "c.db").string();
  auto o = run_splat("sweep " + spec.string() + " --db " + db + " --workers 2");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  o = run_splat("windows --db " + db + " --format json");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const json rows = json::parse(o.stdout_text);
  ASSERT_EQ(rows.size(), 1u) << o.stdout_text;
  EXPECT_EQ(rows[0].at("params"), json::parse(R"({"G_c": 30})"));
  ASSERT_TRUE(rows[0].at("critical_velocity").is_number()) << rows[0].dump(2);
  EXPECT_GT(rows[0].at("critical_velocity").get<double>(), 200.0);
  EXPECT_LT(rows[0].at("critical_velocity").get<double>(), 500.0);
}

// The same campaign at two resolutions: `splat windows` reads the two
// parameter sets that differ only in elements_across as one ladder, whose
// critical velocity is the finer level's with the move between the levels
// as its error (campaign/ladders.hpp).
TEST(campaign_sweep, a_resolution_field_gives_a_ladder) {
  TempDir t;
  const fs::path spec = t.path / "ladder.json";
  const json field = {
      {"pointer", "/particle_impact/particle/elements_across"}, {"unit", "-"}, {"values", {8, 12}}};
  std::ofstream(spec) << json{{"name", "ladder"},
                              {"base_scene", al_thesis_scene(t.path).string()},
                              {"velocity", {{"values", {200, 500}}}},
                              {"fields", {field}},
                              {"job", {{"time_limit", 120}}}}
                             .dump(2);
  const std::string db = (t.path / "c.db").string();
  auto o = run_splat("sweep " + spec.string() + " --db " + db + " --workers 2");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("resolution ladder /particle_impact/particle/elements_across"),
            std::string::npos)
      << o.stdout_text;
  // Its cost against every level run on the grid (2 velocities x 2 levels,
  // no refinement): the sweep knows the grid, `windows` reads it back from
  // the stored spec.
  const std::string cost =
      "jobs 4; every level gridded: on the 2 velocities at least 4, about 4 refined as the "
      "coarsest (this ladder 100 %)";
  EXPECT_NE(o.stdout_text.find(cost), std::string::npos) << o.stdout_text;
  EXPECT_NE(run_splat("windows --db " + db).stdout_text.find(cost), std::string::npos);
  o = run_splat("windows --db " + db + " --format ladders");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const json ladders = json::parse(o.stdout_text);
  ASSERT_EQ(ladders.size(), 1u) << o.stdout_text;
  const json& l = ladders[0];
  EXPECT_EQ(l.at("levels"), json({8, 12}));
  EXPECT_EQ(l.at("cost")[1].at("jobs"), 2);
  const json& c = l.at("critical");
  ASSERT_EQ(c.at("status"), "not-converged") << l.dump(2);
  const double f8 = c.at("levels")[0].at("estimate").get<double>();
  const double f12 = c.at("levels")[1].at("estimate").get<double>();
  EXPECT_DOUBLE_EQ(c.at("value").get<double>(), f12);
  EXPECT_DOUBLE_EQ(c.at("error").get<double>(),
                   std::abs(f12 - f8) + c.at("levels")[1].at("half_width").get<double>());
  o = run_splat("windows --db " + db + " --format ladders-csv");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_EQ(o.stdout_text.rfind("campaign_id,params,pointer,level,jobs,job_seconds [s]", 0), 0u)
      << o.stdout_text;
}

// Coarse to fine: the finer level starts from the coarse level's edges and
// brackets its own critical velocity to the tolerance. Its cost is printed,
// not asserted: al-thesis's edge moves from 325-350 m/s (8 across) to
// 400-425 m/s (12 across), so the finer level walks to it and its island
// probes run as many jobs as a level run on its own (8 and 8); the saving
// needs edges that move less than a grid step (test_campaign_ladders.cpp).
TEST(campaign_sweep, coarse_to_fine_runs_the_finer_level_near_the_edges) {
  TempDir t;
  const fs::path spec = t.path / "c2f.json";
  const json field = {
      {"pointer", "/particle_impact/particle/elements_across"}, {"unit", "-"}, {"values", {8, 12}}};
  std::ofstream(spec) << json{
      {"name", "c2f"},
      {"base_scene", al_thesis_scene(t.path).string()},
      {"velocity", {{"range", {{"from", 100}, {"to", 600}, {"step", 100}}}}},
      {"fields", {field}},
      {"refinement", {{"tolerance", 25}, {"coarse_to_fine", true}}},
      {"job",
       {{"time_limit",
         120}}}}.dump(2);
  const std::string db = (t.path / "c.db").string();
  auto o = run_splat("sweep " + spec.string() + " --db " + db + " --workers 2");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  o = run_splat("windows --db " + db + " --format ladders");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const json ladders = json::parse(o.stdout_text);
  ASSERT_EQ(ladders.size(), 1u) << o.stdout_text;
  const json& l = ladders[0];
  std::printf("jobs per level: %d, %d\n", l.at("cost")[0].at("jobs").get<int>(),
              l.at("cost")[1].at("jobs").get<int>());
  for (const json& level : l.at("critical").at("levels")) {
    ASSERT_TRUE(level.at("estimate").is_number()) << l.dump(2);
    EXPECT_LE(level.at("half_width").get<double>(), 12.5);
  }
  // Against both levels on a grid at the tolerance: 21 velocities from 100
  // to 600 m/s at 25 m/s, times 2 levels.
  const int jobs = l.at("cost")[0].at("jobs").get<int>() + l.at("cost")[1].at("jobs").get<int>();
  char line[128];
  std::snprintf(line, sizeof line,
                "jobs %d; every level gridded: at the 25 m/s tolerance over 100-600 m/s 42 "
                "(this ladder %.0f %%)",
                jobs, 100.0 * jobs / 42.0);
  EXPECT_NE(run_splat("windows --db " + db).stdout_text.find(line), std::string::npos) << line;
}

// `splat window`: from a material pair to a window in one command; the same
// command again reuses every stored job; a bad option names itself.
TEST(campaign_sweep, window_command_from_a_material_pair) {
  TempDir t;
  const std::string db = (t.path / "w.db").string();
  const std::string cmd =
      "window --particle al-thesis --velocity 300:700:100 --workers 2 --db " + db;
  auto o = run_splat(cmd);
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("critical velocity m/s"), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("stored in " + db), std::string::npos) << o.stdout_text;
  o = run_splat("windows --db " + db + " --format json");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const json rows = json::parse(o.stdout_text);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].at("critical_velocity").is_number()) << rows[0].dump(2);
  o = run_splat(cmd);
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("0 started here"), std::string::npos) << o.stdout_text;
  o = run_splat("window --particle al-thesis --velocity 500:200 --db " + db);
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.stdout_text.find("--velocity: needs 0 < FROM < TO"), std::string::npos)
      << o.stdout_text;
}

// `splat sweep` as users run it, killed with SIGKILL in the middle and run
// again: the second run finishes the campaign, reusing what was stored.
TEST(campaign_sweep, sweep_command_survives_kill_minus_nine) {
  TempDir t;
  const fs::path spec = t.path / "c.json";
  json doc = two_mass_campaign("kill", 0.01, std::nullopt);  // 2 x 141 jobs
  std::ofstream(spec) << doc.dump(2);
  const fs::path db = t.path / "c.db";
  const pid_t child = fork();
  if (child == 0) {
    const int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, STDOUT_FILENO);
    dup2(devnull, STDERR_FILENO);
    execl(SPLAT_BINARY, SPLAT_BINARY, "sweep", spec.c_str(), "--db", db.c_str(), "--workers", "2",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Kill once some jobs have been stored.
  for (int i = 0; i < 600; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!fs::exists(db)) continue;
    try {
      Store peek(db);
      const auto cs = peek.campaigns();
      if (!cs.empty() && peek.job_counts(cs[0].id).succeeded >= 20) break;
    } catch (const std::exception&) {
      // the file is being created
    }
  }
  ASSERT_EQ(kill(child, SIGKILL), 0);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  int stored = 0;
  {
    Store peek(db);
    const JobCounts c = peek.job_counts(peek.campaigns().at(0).id);
    stored = c.succeeded;
    EXPECT_LT(stored, 282) << "the sweep ended before the kill; nothing tested";
  }
  const auto o = run_splat("sweep " + spec.string() + " --db " + db.string());
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("282 jobs: 282 succeeded; " + std::to_string(282 - stored) +
                               " started here"),
            std::string::npos)
      << o.stdout_text;
}

TEST(campaign_sweep, regress_passes_on_its_baseline_and_fails_on_drift) {
  TempDir t;
  const fs::path campaign = k_source / "campaigns/regress_two_mass.json";
  const fs::path baseline = k_source / "campaigns/regress_two_mass.baseline.json";
  const std::string db = (t.path / "r.db").string();
  auto o = run_splat("regress " + campaign.string() + " --baseline " + baseline.string() +
                     " --db " + db);
  EXPECT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("no drift"), std::string::npos) << o.stdout_text;

  // Move one edge of the baseline by 0.1 m/s: drift, exit 1, named.
  json b = json::parse(std::ifstream(baseline));
  for (json& w : b.at("windows")) {
    if (w.at("maximum_velocity").is_number()) {
      w["maximum_velocity"] = w["maximum_velocity"].get<double>() + 0.1;
      break;
    }
  }
  const fs::path drifted = t.path / "drifted.json";
  std::ofstream(drifted) << b.dump(2);
  o = run_splat("regress " + campaign.string() + " --baseline " + drifted.string() + " --db " + db);
  EXPECT_EQ(o.code, 1) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("DRIFT"), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("0 run"), std::string::npos)
      << o.stdout_text;  // cached results reused
}

}  // namespace
