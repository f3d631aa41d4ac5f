// Faults in the middle of a campaign of real two-mass jobs (issue 28):
// kill -9 of `splat sweep` and SIGTERM of `splat serve` while a refinement
// round's jobs are running, each resumed to the end with every job ended
// once and the windows of an uninterrupted run; and a splat rebuilt under a
// running server (a new file renamed over the one it started from), whose
// next campaign's jobs run the new file instead of failing.
//
// A job child killed by SIGKILL (kill -9, the OOM killer) is retried with the
// signal named: campaign_executor.crashes_timeouts_and_bad_output_are_-
// recorded_while_others_finish (tests/integration/test_campaign_executor.cpp).
//
// The refinement jobs are held while the fault is made: the job program is a
// script that runs splat, except that a job started after the grid's (a
// refinement round starts only once every grid job has ended) first waits
// for a gate file the test creates after the fault.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <tuple>

#include "campaign/manager.hpp"
#include "support/serve_process.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace splat::campaign;
using nlohmann::json;
namespace fs = std::filesystem;

using splat::test_support::ServeProcess;
using splat::test_support::TempDir;

constexpr int k_grid_jobs = 2 * 15;  // G_c 0.1 and 0.2 at 0.1, 0.2, ..., 1.5 m/s

// The two-mass scene inline (the API reads no file) over the grid above,
// each window edge bisected to 0.01 m/s.
json refined_campaign(const std::string& name) {
  const json scene =
      json::parse(std::ifstream(fs::path(SPLAT_SOURCE_DIR) / "scenes/verification/two_mass.json"));
  return {{"name", name},
          {"base_scene", scene},
          {"velocity", {{"range", {{"from", 0.1}, {"to", 1.5}, {"step", 0.1}}}}},
          {"G_c", {{"values", {0.1, 0.2}}}},
          {"refinement", {{"tolerance", 0.01}, {"max_extra_jobs", 100}}},
          {"job", {{"time_limit", 60}, {"retries", 1}}}};
}

// The job program that holds refinement jobs until `dir`/gate exists.
fs::path gated_splat(const fs::path& dir) {
  const fs::path script = dir / "gated_splat.sh";
  const std::string starts = (dir / "starts").string();
  std::ofstream(script) << "#!/bin/sh\n"
                        << "echo \"$$\" >> '" << starts << "'\n"
                        << "if [ \"$(wc -l < '" << starts << "')\" -gt " << k_grid_jobs
                        << " ]; then\n"
                        << "  while [ ! -e '" << (dir / "gate").string()
                        << "' ]; do sleep 0.02; done\n"
                        << "fi\n"
                        << "exec '" << SPLAT_BINARY << "' \"$@\"\n";
  fs::permissions(script, fs::perms::owner_all, fs::perm_options::add);
  return script;
}

void open_gate(const fs::path& dir) {
  std::ofstream(dir / "gate") << "open\n";
}

// What the store shows of its only campaign (nothing while it is being
// created).
struct Peek {
  std::optional<CampaignState> state;
  JobCounts counts;
  int refinement_running = 0;
};

Peek peek(const fs::path& db) {
  Peek out;
  try {
    Store store(db, Store::ReadOnly{});
    const auto cs = store.campaigns();
    if (cs.empty()) return out;
    for (const PointStatus& p : store.points(cs[0].id))
      out.refinement_running += p.point.origin == "refine" && p.state == JobState::running;
    out.counts = store.job_counts(cs[0].id);
    out.state = cs[0].state;
  } catch (const std::exception&) {
    // being created
  }
  return out;
}

// Polls the store every 20 ms until `done` holds (false after a minute).
bool wait_until(const fs::path& db, const std::function<bool(const Peek&)>& done) {
  for (int i = 0; i < 3000; ++i) {
    if (done(peek(db))) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

bool refinement_running(const Peek& p) {
  return p.refinement_running > 0;
}

// The campaign run without a fault, in a store of its own.
struct CleanRun {
  std::vector<PointStatus> points;
  std::vector<WindowRecord> windows;
};

CleanRun clean_run(const fs::path& dir, const json& doc) {
  Store store(dir / "clean.db");
  ManagerOptions o;
  o.workers = 2;
  o.job_program = SPLAT_BINARY;
  o.poll_seconds = 0.05;
  const SweepReport r = run_sweep(store, read_campaign(doc), o);
  EXPECT_EQ(r.state, CampaignState::finished);
  EXPECT_EQ(r.counts.succeeded, r.counts.total());
  EXPECT_GT(r.refinement_jobs, 0);
  return {store.points(r.campaign_id), store.windows(r.campaign_id)};
}

using PointKey = std::tuple<std::string, double, std::string>;  // params, velocity, origin

std::set<PointKey> point_keys(const std::vector<PointStatus>& points) {
  std::set<PointKey> keys;
  for (const PointStatus& p : points)
    keys.insert({p.point.params_key, p.point.velocity, p.point.origin});
  return keys;
}

// The resumed campaign against the clean run: finished, every job of every
// point (refinement included) succeeded once, no point lost or added twice,
// the same windows.
void expect_like_the_clean_run(const fs::path& db, const CleanRun& clean) {
  Store store(db, Store::ReadOnly{});
  const CampaignRecord c = store.campaigns().at(0);
  EXPECT_EQ(c.state, CampaignState::finished);
  const std::vector<PointStatus> points = store.points(c.id);
  std::set<std::string> hashes;
  for (const PointStatus& p : points) {
    hashes.insert(p.point.job_hash);
    EXPECT_EQ(p.state, JobState::succeeded)
        << p.point.origin << " " << p.point.velocity << ": " << p.exit_reason;
  }
  EXPECT_EQ(hashes.size(), points.size()) << "a job is shared by two points";
  EXPECT_EQ(store.job_counts(c.id).total(), static_cast<int>(points.size()));
  EXPECT_EQ(point_keys(points), point_keys(clean.points));
  std::printf("%zu points (%d refinement); the run without a fault: %zu\n", points.size(),
              store.refinement_points_count(c.id), clean.points.size());
  const std::vector<WindowRecord> windows = store.windows(c.id);
  ASSERT_EQ(windows.size(), clean.windows.size());
  for (std::size_t i = 0; i < windows.size(); ++i) {
    EXPECT_EQ(windows[i].params_key, clean.windows[i].params_key);
    EXPECT_EQ(json::parse(windows[i].window), json::parse(clean.windows[i].window))
        << windows[i].params;
  }
}

// `splat ARGS...` as a child process with its output dropped.
pid_t start_splat(const std::vector<std::string>& args) {
  const pid_t child = fork();
  if (child == 0) {
    const int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, STDOUT_FILENO);
    dup2(devnull, STDERR_FILENO);
    std::vector<char*> argv{const_cast<char*>(SPLAT_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(SPLAT_BINARY, argv.data());
    _exit(127);
  }
  return child;
}

// The exit code of a child, killed (-1) if it has not ended in two minutes.
int exit_code(pid_t child) {
  int status = 0;
  for (int i = 0; i < 6000; ++i) {
    if (waitpid(child, &status, WNOHANG) == child)
      return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(child, SIGKILL);
  waitpid(child, &status, 0);
  return -1;
}

TEST(campaign_faults, kill_minus_nine_of_the_sweep_during_refinement_resumes_it) {
  TempDir t;
  const json doc = refined_campaign("kill9-refine");
  const fs::path spec = t.path / "c.json";
  std::ofstream(spec) << doc.dump(2);
  const fs::path db = t.path / "c.db";
  const std::vector<std::string> sweep_args = {
      "sweep", spec.string(), "--db", db.string(), "--job-program", gated_splat(t.path).string()};
  const pid_t sweep = start_splat(sweep_args);
  const bool refining = wait_until(db, refinement_running);
  const Peek at_kill = peek(db);
  ASSERT_EQ(kill(sweep, SIGKILL), 0);
  int status = 0;
  waitpid(sweep, &status, 0);
  ASSERT_TRUE(refining) << "no refinement job ran";
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(peek(db).state, CampaignState::active);
  std::printf("killed with %d refinement job(s) running, %d job(s) queued\n",
              at_kill.refinement_running, at_kill.counts.queued);

  open_gate(t.path);
  EXPECT_EQ(exit_code(start_splat(sweep_args)), 0);
  expect_like_the_clean_run(db, clean_run(t.path, doc));
}

TEST(campaign_faults, sigterm_of_the_server_during_refinement_resumes_it) {
  TempDir t;
  const json doc = refined_campaign("sigterm-refine");
  const fs::path db = t.path / "store.db";
  const std::vector<std::string> serve = {"--db", db.string(),     "--port",
                                          "0",    "--job-program", gated_splat(t.path).string()};
  {
    ServeProcess p(serve);
    ASSERT_GT(p.port(), 0);
    httplib::Client c("127.0.0.1", p.port());
    auto r = c.Post("/api/v1/campaigns", doc.dump(), "application/json");
    ASSERT_TRUE(r && r->status == 202) << (r ? r->body : "no response");
    ASSERT_TRUE(wait_until(db, refinement_running)) << "no refinement job ran";
    EXPECT_EQ(p.stop(SIGTERM, 30), 0);
  }
  {
    Store store(db, Store::ReadOnly{});
    const CampaignRecord c = store.campaigns().at(0);
    EXPECT_EQ(c.state, CampaignState::active);
    int stopped = 0;
    for (const PointStatus& ps : store.points(c.id))
      stopped += ps.point.origin == "refine" && ps.state != JobState::succeeded;
    EXPECT_GT(stopped, 0) << "no refinement job was left to resume";
    std::printf("stopped with %d refinement job(s) not run\n", stopped);
  }
  open_gate(t.path);
  {
    ServeProcess p(serve);
    ASSERT_GT(p.port(), 0);
    EXPECT_TRUE(wait_until(db, [](const Peek& s) { return s.state != CampaignState::active; }));
    EXPECT_EQ(p.stop(SIGINT, 30), 0);
  }
  expect_like_the_clean_run(db, clean_run(t.path, doc));
}

// The splat a server started from is replaced by a new file renamed over it
// (what a rebuild does), then a campaign is submitted: its jobs run the new
// file (before: every one failed with "cannot execute '.../splat (deleted)'").
TEST(campaign_faults, a_splat_replaced_under_a_running_server_runs_the_next_campaign) {
  TempDir t;
  const fs::path bin = t.path / "bin";
  fs::create_directories(bin);
  fs::copy_file(SPLAT_BINARY, bin / "splat");
  json doc = refined_campaign("replaced");
  doc.erase("refinement");
  doc["velocity"] = {{"values", {0.2, 0.4, 0.6, 0.8, 1.0}}};
  const fs::path db = t.path / "store.db";
  ServeProcess p({"--db", db.string(), "--port", "0"}, (bin / "splat").string());
  ASSERT_GT(p.port(), 0);
  fs::copy_file(SPLAT_BINARY, bin / "splat.new");
  fs::rename(bin / "splat.new", bin / "splat");
  httplib::Client c("127.0.0.1", p.port());
  auto r = c.Post("/api/v1/campaigns", doc.dump(), "application/json");
  ASSERT_TRUE(r && r->status == 202) << (r ? r->body : "no response");
  EXPECT_TRUE(wait_until(db, [](const Peek& s) { return s.state == CampaignState::finished; }));
  EXPECT_EQ(p.stop(SIGINT, 30), 0);
  Store store(db, Store::ReadOnly{});
  const std::int64_t cid = store.campaigns().at(0).id;
  EXPECT_EQ(store.job_counts(cid).succeeded, 10);
  for (const PointStatus& ps : store.points(cid)) {
    EXPECT_EQ(ps.state, JobState::succeeded) << ps.point.velocity << ": " << ps.exit_reason;
  }
}

}  // namespace
