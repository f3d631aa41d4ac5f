// The local executor and manager with real child processes and a real SQLite
// file. Jobs here are tests/fake_job (a stand-in program that sleeps,
// crashes, hangs or prints a canned summary on command), so these tests are
// about the executor, not physics: crashes and time limits recorded with
// their reason while the other jobs finish, transient retries, cancellation,
// kill -9 of the manager and resume with every job ending exactly once, and
// cache reuse.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <utility>

#include "campaign/manager.hpp"
#include "campaign/sqlite.hpp"
#include "support/small_tmpfs.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace splat::campaign;
using nlohmann::json;
namespace fs = std::filesystem;

using splat::test_support::SmallTmpfs;
using splat::test_support::TempDir;

const SceneResolver identity = [](const json& scene, const fs::path&) { return scene; };

// A campaign over fake jobs: one parameter set per entry of `fakes` (the
// job's "fake" block), at each of `speeds`.
CampaignSpec fake_campaign(const std::string& name, const std::vector<json>& fakes,
                           const std::vector<double>& speeds, double time_limit = 30.0) {
  json doc = {{"name", name},
              {"base_scene", {{"name", "fake"}, {"V0", 0.0}, {"fake", json::object()}}},
              {"velocity", {{"pointer", "/V0"}, {"values", speeds}}},
              {"fields", {{{"pointer", "/fake"}, {"unit", "-"}, {"values", fakes}}}},
              {"job", {{"time_limit", time_limit}, {"retries", 1}}}};
  return read_campaign(doc);
}

ManagerOptions fake_options(int workers = 2) {
  ManagerOptions o;
  o.workers = workers;
  o.job_program = SPLAT_FAKE_JOB;
  o.resolver = identity;
  o.solver_version = "fake-1";
  o.poll_seconds = 0.02;
  return o;
}

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream f(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(f, l);) out.push_back(l);
  return out;
}

// The state and reason of the job of each parameter set (single speed).
std::map<std::string, JobRecord> jobs_by_fake(Store& s, std::int64_t cid) {
  std::map<std::string, JobRecord> out;
  for (const PointStatus& p : s.points(cid)) {
    const json params = json::parse(p.point.params);
    out[params.at("/fake").dump()] = *s.job(p.point.job_hash);
  }
  return out;
}

TEST(campaign_executor, crashes_timeouts_and_bad_output_are_recorded_while_others_finish) {
  TempDir t;
  Store store(t.path / "c.db");
  const std::vector<json> fakes = {
      json::object({{"threshold", 5}}),
      json::object({{"segfault", true}}),
      json::object({{"sleep", 30}}),
      json::object({{"sleep", 30}, {"ignore_term", true}}),
      json::object({{"garbage", true}}),
      json::object({{"exit", 9}}),
      json::object({{"exit", 2}}),
      json::object({{"outcome", "unstable"}}),
      json::object({{"transient_failures", 1}, {"threshold", 5}}),
      json::object({{"transient_failures", 5}}),
      json::object({{"killed_attempts", 1}, {"threshold", 5}}),
      json::object({{"killed_attempts", 5}}),
  };
  const CampaignSpec spec = fake_campaign("crashes", fakes, {1.0}, 0.5);
  const SweepReport r = run_sweep(store, spec, fake_options(3));
  EXPECT_EQ(r.state, CampaignState::finished);
  auto jobs = jobs_by_fake(store, r.campaign_id);
  auto job = [&](const json& f) { return jobs.at(f.dump()); };

  EXPECT_EQ(job(fakes[0]).state, JobState::succeeded);
  EXPECT_EQ(store.result(job(fakes[0]).hash)->outcome, "stick");

  // A signal death is retried like a transient failure, then recorded with the signal.
  EXPECT_EQ(job(fakes[1]).state, JobState::failed);
  EXPECT_EQ(job(fakes[1]).attempts, 2);
  EXPECT_NE(job(fakes[1]).exit_reason.find("killed by signal 11"), std::string::npos)
      << job(fakes[1]).exit_reason;
  EXPECT_FALSE(store.result(job(fakes[1]).hash));

  for (int i : {2, 3}) {  // the second ignores SIGTERM and needs SIGKILL
    EXPECT_EQ(job(fakes[i]).state, JobState::timed_out) << i;
    EXPECT_NE(job(fakes[i]).exit_reason.find("time limit of 0.5"), std::string::npos)
        << job(fakes[i]).exit_reason;
    EXPECT_LT(*job(fakes[i]).wall_seconds, 5.0) << i;
  }
  EXPECT_EQ(job(fakes[4]).state, JobState::failed);
  EXPECT_NE(job(fakes[4]).exit_reason.find("without a JSON summary"), std::string::npos);
  EXPECT_EQ(job(fakes[5]).state, JobState::failed);
  EXPECT_NE(job(fakes[5]).exit_reason.find("exit code 9: fake_job: told to exit 9"),
            std::string::npos)
      << job(fakes[5]).exit_reason;
  EXPECT_NE(job(fakes[6]).exit_reason.find("bad input (exit code 2)"), std::string::npos);
  // A job that ran but ended unstable succeeded as a job; its outcome is kept.
  EXPECT_EQ(job(fakes[7]).state, JobState::succeeded);
  EXPECT_EQ(store.result(job(fakes[7]).hash)->outcome, "unstable");
  // One transient failure, one retry allowed: succeeds on attempt 2.
  EXPECT_EQ(job(fakes[8]).state, JobState::succeeded);
  EXPECT_EQ(job(fakes[8]).attempts, 2);
  // Five transient failures: fails after 1 + 1 attempts, saying why.
  EXPECT_EQ(job(fakes[9]).state, JobState::failed);
  EXPECT_EQ(job(fakes[9]).attempts, 2);
  EXPECT_NE(job(fakes[9]).exit_reason.find("no retries left"), std::string::npos);
  // Killed by SIGKILL (kill -9, the OOM killer) once: the retry succeeds.
  EXPECT_EQ(job(fakes[10]).state, JobState::succeeded);
  EXPECT_EQ(job(fakes[10]).attempts, 2);
  // Killed on every attempt: fails after 1 + 1 attempts, naming the signal.
  EXPECT_EQ(job(fakes[11]).state, JobState::failed);
  EXPECT_EQ(job(fakes[11]).attempts, 2);
  EXPECT_NE(job(fakes[11]).exit_reason.find("killed by signal 9"), std::string::npos)
      << job(fakes[11]).exit_reason;
  EXPECT_NE(job(fakes[11]).exit_reason.find("no retries left"), std::string::npos)
      << job(fakes[11]).exit_reason;

  // The windows show the failures as neither stick nor rebound.
  // Only the two jobs that stuck count; every other one is unclassified.
  for (const WindowRecord& w : r.windows) {
    const json doc = json::parse(w.window);
    const json fake = json::parse(w.params).at("/fake");
    const bool sticks = fake == fakes[0] || fake == fakes[8] || fake == fakes[10];
    EXPECT_EQ(doc.at("sticks"), sticks ? 1 : 0) << fake;
    EXPECT_EQ(doc.at("rebounds"), 0) << fake;
    EXPECT_EQ(doc.at("unclassified").size(), sticks ? 0u : 1u) << fake;
  }
}

// A program that cannot be started (missing, or a file that is not
// executable and was not written for a minute) is the host's fault: each
// job is tried again a few times (whatever its retries, 1 here) before it
// fails.
TEST(campaign_executor, a_missing_job_program_fails_each_job_clearly) {
  TempDir t;
  const fs::path not_a_program = t.path / "notes.txt";
  std::ofstream(not_a_program) << "not a program\n";
  fs::last_write_time(not_a_program, fs::file_time_type::clock::now() - std::chrono::minutes(2));
  for (const fs::path& program : {t.path / "no-such-program", not_a_program}) {
    Store store(t.path / (program.filename().string() + ".db"));
    ManagerOptions o = fake_options();
    o.job_program = program;
    const SweepReport r =
        run_sweep(store, fake_campaign("missing", {json::object()}, {1.0, 2.0}), o);
    EXPECT_EQ(r.counts.failed, 2);
    for (const PointStatus& p : store.points(r.campaign_id)) {
      EXPECT_NE(p.exit_reason.find("could not start: cannot execute"), std::string::npos)
          << p.exit_reason;
      EXPECT_NE(p.exit_reason.find("on attempt 4, no retries left"), std::string::npos)
          << p.exit_reason;
    }
  }
}

// Whether a job under `jobs_dir` could not start its program.
bool a_job_could_not_start(const fs::path& jobs_dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(jobs_dir, ec)) {
    for (const std::string& l : lines_of(e.path() / "stderr.txt"))
      if (l.find("cannot execute") != std::string::npos) return true;
  }
  return false;
}

// A job program being written (ld writes its output in place and makes it
// executable at the end: a rebuild under a running campaign): a job that
// could not start it waits until it is executable before going back to the
// queue, instead of using up its attempts at once.
TEST(campaign_executor, a_job_program_being_written_is_waited_for) {
  TempDir t;
  const fs::path program = t.path / "job";
  fs::copy_file(SPLAT_FAKE_JOB, program);
  const auto exec = fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec;
  fs::permissions(program, exec, fs::perm_options::remove);
  ManagerOptions o = fake_options(1);
  o.job_program = program;
  Store store(t.path / "c.db");
  // The "link" ends a second after a job first could not start, or at once
  // when a job failed.
  std::thread linker([&] {
    for (int i = 0; i < 3000 && !a_job_could_not_start(t.path / "c.db.jobs"); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    for (int i = 0; i < 100; ++i) {
      const auto cs = store.campaigns();
      if (!cs.empty() && store.job_counts(cs[0].id).failed > 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    fs::permissions(program, fs::perms::owner_exec, fs::perm_options::add);
  });
  const SweepReport r = run_sweep(
      store, fake_campaign("being-written", {json::object({{"threshold", 5}})}, {1.0, 2.0}), o);
  linker.join();
  EXPECT_EQ(r.counts.succeeded, 2);
  for (const PointStatus& p : store.points(r.campaign_id)) {
    EXPECT_EQ(p.state, JobState::succeeded) << p.point.velocity << ": " << p.exit_reason;
  }
}

TEST(campaign_executor, cancellation_stops_running_jobs_and_queued_ones_never_start) {
  TempDir t;
  const fs::path db = t.path / "c.db";
  const fs::path log = t.path / "jobs.log";
  Store store(db);
  std::vector<double> speeds;
  for (int i = 0; i < 10; ++i) speeds.push_back(i);
  const CampaignSpec spec =
      fake_campaign("cancel", {json::object({{"sleep", 30}, {"log", log.string()}})}, speeds);
  // Someone else (another connection, as the API server would) cancels the
  // campaign once its first jobs are running.
  std::thread canceller([&] {
    Store other(db);
    for (int i = 0; i < 3000 && lines_of(log).size() < 2; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    other.request_cancel(other.campaigns().at(0).id);
  });
  const auto t0 = std::chrono::steady_clock::now();
  const SweepReport r = run_sweep(store, spec, fake_options(2));
  canceller.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 20.0);
  EXPECT_EQ(r.state, CampaignState::cancelled);
  EXPECT_EQ(store.campaign(r.campaign_id)->state, CampaignState::cancelled);
  EXPECT_EQ(r.counts.cancelled, 10);
  EXPECT_EQ(r.counts.total(), 10);
  EXPECT_EQ(r.jobs_started, 2);
  EXPECT_EQ(lines_of(log).size(), 2u);  // only the two running jobs ever started
  int stopped = 0;
  for (const PointStatus& p : store.points(r.campaign_id)) {
    stopped += p.exit_reason == "cancelled while running";
  }
  EXPECT_EQ(stopped, 2);
}

TEST(campaign_executor, interrupt_flag_cancels_like_a_request) {
  TempDir t;
  Store store(t.path / "c.db");
  std::atomic<bool> interrupt{false};
  ManagerOptions o = fake_options(1);
  o.interrupt = &interrupt;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    interrupt = true;
  });
  const SweepReport r =
      run_sweep(store, fake_campaign("sigint", {json::object({{"sleep", 30}})}, {1, 2, 3}), o);
  stopper.join();
  EXPECT_EQ(r.state, CampaignState::cancelled);
  EXPECT_EQ(r.counts.cancelled, 3);
}

// A graceful stop (SIGTERM of the server, Ctrl-C of `splat sweep`) right
// after a refinement round was added cancels its jobs; the resumed campaign
// runs them instead of ending with them unclassified.
TEST(campaign_executor, a_stop_during_refinement_resumes_the_refinement_jobs) {
  TempDir t;
  Store store(t.path / "c.db");
  CampaignSpec spec = fake_campaign("refine-stop", {json::object({{"threshold", 2.5}})}, {2, 3});
  spec.refinement = RefinementOptions{0.1, 1, 0.0};
  std::atomic<bool> interrupt{false};
  ManagerOptions o = fake_options(1);
  o.interrupt = &interrupt;
  o.on_progress = [&](const Progress& p) {
    if (p.round >= 1) interrupt = true;
  };
  const SweepReport stopped = run_sweep(store, spec, o);
  ASSERT_EQ(stopped.state, CampaignState::cancelled);
  ASSERT_EQ(stopped.refinement_jobs, 1);
  ASSERT_EQ(stopped.counts.cancelled, 1);

  const SweepReport resumed = run_sweep(store, spec, fake_options(1));
  EXPECT_EQ(resumed.state, CampaignState::finished);
  EXPECT_EQ(resumed.counts.cancelled, 0);
  EXPECT_EQ(resumed.counts.succeeded, 3);
  for (const PointStatus& p : store.points(resumed.campaign_id)) {
    EXPECT_EQ(p.state, JobState::succeeded) << p.point.velocity << " " << p.point.origin;
  }
}

// Refinement of a closed-form edge (fake jobs stick below V0 = 2.537) from
// a bracket [2, 3] to 0.01: two points per round, on two workers, need fewer
// rounds than bisection (5 against 7) for a few more jobs, and find the
// same edge.
TEST(campaign_executor, two_points_per_round_find_the_edge_in_fewer_rounds) {
  TempDir t;
  const double threshold = 2.537, tol = 0.01;
  std::map<int, std::pair<int, int>> rounds_jobs;
  for (int k : {1, 2}) {
    Store store(t.path / ("k" + std::to_string(k) + ".db"));
    CampaignSpec spec = fake_campaign("split-" + std::to_string(k),
                                      {json::object({{"threshold", threshold}})}, {1, 2, 3, 4});
    spec.refinement = RefinementOptions{tol, 100, 0.0, false, k};
    std::atomic<int> rounds{0};
    ManagerOptions o = fake_options(2);
    o.on_progress = [&](const Progress& p) { rounds = std::max(rounds.load(), p.round); };
    const SweepReport r = run_sweep(store, spec, o);
    ASSERT_EQ(r.state, CampaignState::finished);
    ASSERT_EQ(r.windows.size(), 1u);
    const json w = json::parse(r.windows[0].window);
    EXPECT_LE(w.at("maximum_bracket").at("width").get<double>(), tol + 1e-12) << k;
    EXPECT_NEAR(w.at("maximum_velocity").get<double>(), threshold, tol / 2) << k;
    rounds_jobs[k] = {rounds.load(), r.counts.total()};
    std::printf("  %d point(s) per round: %d rounds, %d jobs\n", k, rounds.load(),
                r.counts.total());
  }
  EXPECT_EQ(rounds_jobs[1], (std::pair{7, 11}));
  EXPECT_EQ(rounds_jobs[2], (std::pair{5, 13}));
}

// A store that refuses a write in the middle of a run (a full disk; here a
// trigger refuses a second job going `running`): the run ends with the
// store's error, its workers stopped and joined, no job left running; the
// next run finishes the campaign.
TEST(campaign_executor, a_store_error_ends_the_run_with_the_error_and_loses_no_job) {
  TempDir t;
  Store store(t.path / "c.db");
  const CampaignSpec spec =
      fake_campaign("store-error", {json::object({{"sleep", 0.3}})}, {1, 2, 3, 4});
  Database other(t.path / "c.db");
  other.exec(
      "CREATE TRIGGER full_disk BEFORE UPDATE OF state ON jobs WHEN NEW.state = 'running' "
      "AND (SELECT COUNT(*) FROM jobs WHERE state = 'running') >= 1 "
      "BEGIN SELECT RAISE(ABORT, 'database or disk is full'); END");
  EXPECT_THROW(run_sweep(store, spec, fake_options(2)), SqliteError);
  other.exec("DROP TRIGGER full_disk");
  const std::int64_t cid = store.campaigns().at(0).id;
  EXPECT_EQ(store.job_counts(cid).running, 0);

  const SweepReport r = run_sweep(store, spec, fake_options(2));
  EXPECT_EQ(r.state, CampaignState::finished);
  EXPECT_EQ(r.counts.succeeded, 4);
}

// The store and the jobs' folders on a small tmpfs that fills up while the
// campaign runs (issue 28 item 4): the run ends with an error that says the
// disk is full, the process lives on, every result stored before is kept,
// no job is blamed (`failed`) for the host's fault, the campaign stays
// `active`, and once there is room again the same run finishes it.
TEST(campaign_executor, a_full_disk_ends_the_run_clearly_and_loses_nothing) {
  TempDir t;
  const fs::path disk = t.path / "disk";
  SmallTmpfs tmpfs(disk, 4L << 20);
  if (!tmpfs.mounted()) GTEST_SKIP() << tmpfs.why_not();
  const fs::path log = t.path / "jobs.log";  // off the small disk
  std::vector<double> speeds;
  for (int i = 0; i < 12; ++i) speeds.push_back(i);
  const CampaignSpec spec = fake_campaign(
      "full-disk",
      {json::object(
          {{"sleep", 0.2}, {"threshold", 6}, {"write_bytes", 64 * 1024}, {"log", log.string()}})},
      speeds);

  Store store(disk / "c.db");
  std::map<std::string, std::string> stored_before;  // job hash -> outcome at the fill
  bool filled = false;
  ManagerOptions o = fake_options(2);
  o.on_progress = [&](const Progress& p) {
    if (filled || p.counts.succeeded < 4) return;
    for (const PointStatus& s : store.points(p.campaign_id)) {
      if (s.state == JobState::succeeded) stored_before[s.point.job_hash] = *s.outcome;
    }
    filled = SmallTmpfs::fill(disk / "filler");
  };
  std::string error;
  try {
    run_sweep(store, spec, o);
  } catch (const std::exception& e) {
    error = e.what();
  }
  ASSERT_TRUE(filled);
  EXPECT_TRUE(error.find("No space left on device") != std::string::npos ||
              error.find("database or disk is full") != std::string::npos)
      << "the error does not say the disk is full: '" << error << "'";

  fs::remove(disk / "filler");
  const std::int64_t cid = store.campaigns().at(0).id;
  EXPECT_EQ(store.campaign(cid)->state, CampaignState::active);
  const JobCounts after = store.job_counts(cid);
  EXPECT_EQ(after.failed, 0) << "a job was blamed for the full disk";
  ASSERT_GE(stored_before.size(), 4u);
  for (const auto& [hash, outcome] : stored_before) {
    const auto job = store.job(hash);
    ASSERT_TRUE(job) << hash;
    EXPECT_EQ(job->state, JobState::succeeded) << hash;
    ASSERT_TRUE(store.result(hash)) << hash;
    EXPECT_EQ(store.result(hash)->outcome, outcome) << hash;
  }

  const SweepReport r = run_sweep(store, spec, fake_options(2));
  EXPECT_EQ(r.state, CampaignState::finished);
  EXPECT_EQ(r.counts.succeeded, 12);
  EXPECT_EQ(r.counts.failed, 0);
  ASSERT_EQ(r.windows.size(), 1u);
  EXPECT_EQ(*r.windows[0].maximum_velocity, 5.5);
}

TEST(campaign_executor, finished_jobs_are_reused_and_rerun_on_request) {
  TempDir t;
  Store store(t.path / "c.db");
  const CampaignSpec spec =
      fake_campaign("cache", {json::object({{"threshold", 2.5}})}, {1.0, 2.0, 3.0, 4.0});
  SweepReport r = run_sweep(store, spec, fake_options());
  EXPECT_EQ(r.jobs_started, 4);
  EXPECT_EQ(r.counts.succeeded, 4);
  // The same campaign again: nothing recomputed.
  r = run_sweep(store, spec, fake_options());
  EXPECT_EQ(r.jobs_started, 0);
  EXPECT_EQ(r.counts.succeeded, 4);
  // Another campaign sharing two of the jobs: only the new ones run.
  const CampaignSpec other =
      fake_campaign("cache2", {json::object({{"threshold", 2.5}})}, {3.0, 4.0, 5.0});
  r = run_sweep(store, other, fake_options());
  EXPECT_EQ(r.grid.jobs_reused, 2);
  EXPECT_EQ(r.jobs_started, 1);
  // A rerun recomputes everything.
  ManagerOptions again = fake_options();
  again.rerun = true;
  r = run_sweep(store, spec, again);
  EXPECT_EQ(r.jobs_started, 4);
  EXPECT_EQ(r.windows.size(), 1u);
  EXPECT_EQ(*r.windows[0].maximum_velocity, 2.5);
}

// More job threads than cores (workers x threads): the jobs' OpenMP threads
// must wait passively, or the spinning ones take the cores the other jobs
// compute on; within the cores the wait policy is left alone.
TEST(campaign_executor, oversubscribed_jobs_wait_passively) {
  TempDir t;
  const char* saved = std::getenv("OMP_WAIT_POLICY");  // ctest sets it for every test
  const std::string saved_value = saved ? saved : "";
  unsetenv("OMP_WAIT_POLICY");
  cpu_set_t set;
  CPU_ZERO(&set);
  ASSERT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
  const int cores = CPU_COUNT(&set);
  auto env_lines = [&](const std::string& name, int workers, int threads) {
    const fs::path log = t.path / (name + ".log");
    const json fake = {{"threshold", 5}, {"log", log.string()}, {"log_env", "OMP_WAIT_POLICY"}};
    CampaignSpec spec = fake_campaign(name, {fake}, {1.0, 2.0});
    spec.job.threads = threads;
    Store store(t.path / (name + ".db"));
    const SweepReport r = run_sweep(store, spec, fake_options(workers));
    EXPECT_EQ(r.counts.succeeded, 2) << name;
    std::vector<std::string> env;
    for (const std::string& l : lines_of(log))
      if (l.rfind("env ", 0) == 0) env.push_back(l);
    return env;
  };
  // One more single-thread job than cores (job threads never exceed the cores).
  const std::vector<std::string> over = env_lines("over", cores + 1, 1);
  const std::vector<std::string> within = env_lines("within", 1, 1);
  if (saved) setenv("OMP_WAIT_POLICY", saved_value.c_str(), 1);
  EXPECT_EQ(over, std::vector<std::string>(2, "env OMP_WAIT_POLICY=passive"));
  EXPECT_EQ(within, std::vector<std::string>(2, "env OMP_WAIT_POLICY unset"));
}

// kill -9 of a running manager (a forked process running the sweep), then a
// restart: the jobs that had finished are not redone, the ones that were
// running run again, and every job ends exactly once with one result.
TEST(campaign_executor, kill_minus_nine_and_resume_end_every_job_exactly_once) {
  TempDir t;
  const fs::path db = t.path / "c.db";
  const fs::path log = t.path / "jobs.log";
  std::vector<double> speeds;
  for (int i = 0; i < 12; ++i) speeds.push_back(i);
  const CampaignSpec spec = fake_campaign(
      "kill9", {json::object({{"sleep", 0.3}, {"threshold", 6}, {"log", log.string()}})}, speeds);

  const pid_t manager = fork();  // before this process starts any thread
  if (manager == 0) {
    int code = 0;
    try {
      Store store(db);
      run_sweep(store, spec, fake_options(2));
    } catch (...) {
      code = 1;
    }
    _exit(code);
  }
  // Wait until some jobs have ended and others are running, then SIGKILL.
  auto count = [&](const std::string& what) {
    int n = 0;
    for (const std::string& l : lines_of(log)) n += l.rfind(what, 0) == 0;
    return n;
  };
  for (int i = 0; i < 4000 && !(count("end") >= 4 && count("start") > count("end")); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(kill(manager, SIGKILL), 0);
  int status = 0;
  waitpid(manager, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  const int ended_before = count("end");
  ASSERT_GE(ended_before, 4);
  ASSERT_LT(ended_before, 12);
  // Its children die with it (PR_SET_PDEATHSIG): no job finishes afterwards.
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  EXPECT_EQ(count("end"), ended_before);

  Store store(db);
  const std::int64_t cid = store.campaigns().at(0).id;
  JobCounts before = store.job_counts(cid);
  std::set<std::string> stored_before;
  for (const PointStatus& p : store.points(cid)) {
    if (p.state == JobState::succeeded) stored_before.insert(p.point.job_hash);
  }
  EXPECT_GE(before.succeeded, ended_before - 2);  // at most the in-flight records can lag
  EXPECT_GE(before.running, 1);                   // left behind by the dead manager

  const SweepReport r = run_sweep(store, spec, fake_options(2));
  EXPECT_EQ(r.state, CampaignState::finished);
  EXPECT_GE(r.orphans_requeued, 1);
  EXPECT_EQ(r.counts.succeeded, 12);
  EXPECT_EQ(r.counts.total(), 12);
  EXPECT_EQ(r.jobs_started, 12 - before.succeeded);

  // Exactly once in the store: the jobs stored before the kill never started
  // again; the others ran to an end (a job whose child had ended but whose
  // result the killed manager had not stored yet legitimately runs again).
  std::map<std::string, int> starts, ends;
  for (const std::string& l : lines_of(log)) {
    const auto sp = l.find(' ');
    (l.rfind("start", 0) == 0 ? starts : ends)[l.substr(sp + 1)]++;
  }
  EXPECT_EQ(ends.size(), 12u);
  for (const std::string& h : stored_before) {
    EXPECT_EQ(starts[(fs::path(db.string() + ".jobs") / h / "out").string()], 1) << h;
  }
  for (const auto& [dir, n] : ends) EXPECT_LE(n, 2) << dir;
  for (const PointStatus& p : store.points(cid)) {
    EXPECT_TRUE(store.result(p.point.job_hash)) << p.point.velocity;
  }
  // And the window is the fake threshold's.
  ASSERT_EQ(r.windows.size(), 1u);
  EXPECT_EQ(*r.windows[0].maximum_velocity, 5.5);
}

}  // namespace
