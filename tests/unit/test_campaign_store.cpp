// The campaign store on a real SQLite file (campaign/store.hpp): schema and
// migrations, WAL, round trips of every table, dedupe and cache reuse,
// orphaned jobs, cancellation, and concurrent writers that never see
// "database is locked".
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <span>
#include <thread>
#include <vector>

#include "campaign/process.hpp"
#include "campaign/sqlite.hpp"
#include "campaign/store.hpp"
#include "solver/io/result_file.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace splat::campaign;
namespace fs = std::filesystem;

using splat::test_support::TempDir;

CampaignRecord campaign_named(const std::string& name) {
  CampaignRecord c;
  c.name = name;
  c.spec_hash = "spec-" + name;
  c.spec = "{}";
  return c;
}

NewPoint point(const std::string& params, double v, const std::string& hash) {
  return {{params, params, v, hash, "grid"}, R"({"scene":")" + hash + "\"}", "v1"};
}

TEST(campaign_store, creates_schema_in_wal_mode_and_reopens) {
  TempDir t;
  const fs::path db = t.path / "c.db";
  {
    Store s(db);
    EXPECT_EQ(s.schema_version(), k_store_schema_version);
    Statement m = s.reader().prepare("PRAGMA journal_mode");
    ASSERT_TRUE(m.step());
    EXPECT_EQ(m.text(0), "wal");
    s.open_campaign(campaign_named("a"));
  }
  Store again(db);
  EXPECT_EQ(again.schema_version(), k_store_schema_version);
  ASSERT_EQ(again.campaigns().size(), 1u);
  EXPECT_EQ(again.campaigns()[0].name, "a");
}

TEST(campaign_store, a_copied_store_folder_keeps_every_jobs_histories) {
  TempDir t;
  const fs::path first = t.path / "first";
  const fs::path h5 = first / "c.db.jobs" / "h1" / "out" / "run.h5";
  fs::create_directories(h5.parent_path());
  {
    splat::ResultFile out(h5, {}, {{"time", "s"}});
    for (double time : {0.0, 1e-9, 2e-9}) out.append_history(std::span<const double>(&time, 1));
  }
  {
    Store s(first / "c.db");
    const auto c = s.open_campaign(campaign_named("one"));
    s.add_points(c, {point("{}", 1.0, "h1")}, false);
    ASSERT_TRUE(s.claim_next_job(c, this_process_owner(), "hostA"));
    // As the runner records it: the path the job printed.
    s.finish_job("h1", JobState::succeeded, "stick", 0.1, 1,
                 ResultRecord{"h1", "stick", "", "{}", h5.string(), 0.0});
    EXPECT_EQ(s.result("h1")->hdf5_path, h5.string());
    Statement raw = s.reader().prepare("SELECT hdf5_path FROM results");
    ASSERT_TRUE(raw.step());
    EXPECT_EQ(raw.text(0), "c.db.jobs/h1/out/run.h5");  // relative to the store's folder
  }
  const fs::path second = t.path / "second";
  fs::copy(first, second, fs::copy_options::recursive);
  fs::remove_all(first);
  Store copy(second / "c.db");
  const std::string moved = copy.result("h1")->hdf5_path;
  EXPECT_EQ(moved, (second / "c.db.jobs" / "h1" / "out" / "run.h5").string());
  EXPECT_EQ(splat::read_history(moved, "time"), (std::vector<double>{0.0, 1e-9, 2e-9}));
}

TEST(campaign_store, result_paths_outside_the_folder_and_old_absolute_ones_stay_absolute) {
  const fs::path folder = "/data/stores";
  EXPECT_EQ(stored_result_path(folder, "/data/stores/c.db.jobs/h/out/r.h5"),
            "c.db.jobs/h/out/r.h5");
  EXPECT_EQ(stored_result_path(folder, "/data/other/r.h5"), "/data/other/r.h5");
  EXPECT_EQ(stored_result_path(folder, "/data/stores/../x.h5"), "/data/x.h5");
  EXPECT_EQ(stored_result_path(folder, ""), "");
  EXPECT_EQ(result_path_from_store(folder, "c.db.jobs/h/out/r.h5"),
            "/data/stores/c.db.jobs/h/out/r.h5");
  EXPECT_EQ(result_path_from_store(folder, "/old/absolute/r.h5"), "/old/absolute/r.h5");
  EXPECT_EQ(result_path_from_store(folder, ""), "");
}

TEST(campaign_store, refuses_a_newer_schema) {
  TempDir t;
  const fs::path db = t.path / "c.db";
  {
    Database raw(db);
    raw.exec("PRAGMA user_version = 99");
  }
  try {
    Store s(db);
    FAIL() << "opened a newer store";
  } catch (const SqliteError& e) {
    EXPECT_NE(std::string(e.what()).find("schema version 99"), std::string::npos) << e.what();
  }
}

TEST(campaign_store, same_spec_is_the_same_campaign) {
  TempDir t;
  Store s(t.path / "c.db");
  const auto a = s.open_campaign(campaign_named("a"));
  const auto b = s.open_campaign(campaign_named("b"));
  EXPECT_NE(a, b);
  s.set_campaign_state(a, CampaignState::finished);
  EXPECT_EQ(s.open_campaign(campaign_named("a")), a);
  EXPECT_EQ(s.campaign(a)->state, CampaignState::active);
}

TEST(campaign_store, jobs_round_trip_with_dedupe_and_cache_reuse) {
  TempDir t;
  Store s(t.path / "c.db");
  const auto c1 = s.open_campaign(campaign_named("one"));
  // Two points share job h1 (same resolved scene): one job.
  AddPointsStats st = s.add_points(
      c1, {point("{}", 1.0, "h1"), point("{\"x\":1}", 1.0, "h1"), point("{}", 2.0, "h2")}, false);
  EXPECT_EQ(st.points_added, 3);
  EXPECT_EQ(st.jobs_created, 2);
  EXPECT_EQ(s.job_counts(c1).queued, 2);
  // Adding the same points again changes nothing.
  st = s.add_points(c1, {point("{}", 1.0, "h1")}, false);
  EXPECT_EQ(st.points_added, 0);
  EXPECT_EQ(st.jobs_created, 0);

  const std::string owner = this_process_owner();
  auto j = s.claim_next_job(c1, owner, "hostA");
  ASSERT_TRUE(j);
  EXPECT_EQ(j->hash, "h1");
  EXPECT_EQ(j->state, JobState::running);
  EXPECT_EQ(j->attempts, 1);
  EXPECT_EQ(j->scene, R"({"scene":"h1"})");
  ResultRecord r{"h1", "stick", "bonded", R"({"outcome":"stick"})", "/x/a.h5", 0.0};
  s.finish_job("h1", JobState::succeeded, "stick: bonded", 0.25, 2, r);
  const auto back = s.job("h1");
  EXPECT_EQ(back->state, JobState::succeeded);
  EXPECT_EQ(*back->wall_seconds, 0.25);
  EXPECT_EQ(*back->threads, 2);
  EXPECT_EQ(back->host, "hostA");
  EXPECT_TRUE(back->finished_at);
  const auto res = s.result("h1");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->outcome, "stick");
  EXPECT_EQ(res->hdf5_path, "/x/a.h5");

  // Another campaign with job h1: reused from the store, not queued again.
  const auto c2 = s.open_campaign(campaign_named("two"));
  st = s.add_points(c2, {point("{}", 1.0, "h1"), point("{}", 3.0, "h3")}, false);
  EXPECT_EQ(st.jobs_reused, 1);
  EXPECT_EQ(st.jobs_created, 1);
  EXPECT_EQ(s.job_counts(c2).succeeded, 1);
  EXPECT_EQ(s.job_counts(c2).queued, 1);
  // Unless a rerun is asked for: queued again, the old result dropped.
  st = s.add_points(c2, {point("{}", 1.0, "h1")}, true);
  EXPECT_EQ(st.jobs_requeued, 1);
  EXPECT_EQ(s.job("h1")->state, JobState::queued);
  EXPECT_FALSE(s.result("h1"));

  const std::vector<PointStatus> pts = s.points(c1);
  ASSERT_EQ(pts.size(), 3u);
}

TEST(campaign_store, orphaned_running_jobs_return_to_the_queue) {
  TempDir t;
  Store s(t.path / "c.db");
  const auto c = s.open_campaign(campaign_named("c"));
  s.add_points(c, {point("{}", 1.0, "h1"), point("{}", 2.0, "h2")}, false);
  // h1 claimed by a process that has exited, h2 by this (live) process.
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  const std::string host = host_name();
  const std::string dead = host + ":" + std::to_string(child) + ":12345";
  ASSERT_TRUE(s.claim_next_job(c, dead, host));
  ASSERT_TRUE(s.claim_next_job(c, this_process_owner(), host));
  EXPECT_FALSE(owner_alive(dead));
  EXPECT_TRUE(owner_alive(this_process_owner()));
  EXPECT_EQ(s.job("h1")->attempts, 1);
  EXPECT_EQ(s.recover_orphaned_jobs(host), 1);
  EXPECT_EQ(s.job("h1")->state, JobState::queued);
  EXPECT_EQ(s.job("h1")->exit_reason, "requeued: its manager stopped while it ran");
  EXPECT_EQ(s.job("h1")->attempts, 0);  // the job did not fail: its retries are intact
  EXPECT_EQ(s.job("h2")->state, JobState::running);
  EXPECT_EQ(s.job("h2")->attempts, 1);
}

TEST(campaign_store, cancellation_marks_queued_jobs_and_the_campaign) {
  TempDir t;
  Store s(t.path / "c.db");
  const auto c = s.open_campaign(campaign_named("c"));
  s.add_points(c, {point("{}", 1.0, "h1"), point("{}", 2.0, "h2"), point("{}", 3.0, "h3")}, false);
  ASSERT_TRUE(s.claim_next_job(c, this_process_owner(), host_name()));
  s.request_cancel(c);
  EXPECT_EQ(s.campaign(c)->state, CampaignState::cancelling);
  EXPECT_EQ(s.cancel_queued_jobs(c, "cancelled"), 2);
  const JobCounts n = s.job_counts(c);
  EXPECT_EQ(n.cancelled, 2);
  EXPECT_EQ(n.running, 1);
  // Cancelled jobs run again when the campaign is started again.
  const AddPointsStats st = s.add_points(c, {point("{}", 2.0, "h2")}, false);
  EXPECT_EQ(st.jobs_requeued, 1);
}

// A graceful stop during a refinement round cancels refinement jobs too;
// opening the campaign again queues every one of them, not just the grid's.
TEST(campaign_store, reopening_requeues_cancelled_refinement_jobs) {
  TempDir t;
  Store s(t.path / "c.db");
  const std::vector<NewPoint> grid = {point("{}", 1.0, "h1"), point("{}", 2.0, "h2")};
  const auto c = s.open_campaign(campaign_named("c"), grid, false).id;
  NewPoint refine = point("{}", 1.5, "h3");
  refine.point.origin = "refine";
  s.add_points(c, {refine}, false);
  EXPECT_EQ(s.cancel_queued_jobs(c, "stopped"), 3);
  const OpenedCampaign again = s.open_campaign(campaign_named("c"), grid, false);
  EXPECT_EQ(again.id, c);
  EXPECT_EQ(again.points.jobs_requeued, 3);
  EXPECT_EQ(s.job_counts(c).queued, 3);
  EXPECT_EQ(s.job("h3")->state, JobState::queued);
  EXPECT_EQ(s.job("h3")->exit_reason, "requeued after cancellation");
}

// Another connection holds the write lock longer than one attempt waits
// (the busy timeout): the finished job's result is written once the lock is
// free, never dropped.
TEST(campaign_store, a_write_lock_held_past_the_busy_timeout_is_waited_out) {
  TempDir t;
  Store s(t.path / "c.db", 50);
  const auto c = s.open_campaign(campaign_named("c"));
  s.add_points(c, {point("{}", 1.0, "h1")}, false);
  ASSERT_TRUE(s.claim_next_job(c, this_process_owner(), host_name()));
  Database other(t.path / "c.db");
  other.exec("BEGIN IMMEDIATE");
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    other.exec("COMMIT");
  });
  const ResultRecord r{"h1", "stick", "canned", "{}", "", 0.0};
  EXPECT_NO_THROW(s.finish_job("h1", JobState::succeeded, "stick: canned", 1.0, 1, r));
  release.join();
  EXPECT_EQ(s.job("h1")->state, JobState::succeeded);
  ASSERT_TRUE(s.result("h1"));
  EXPECT_EQ(s.result("h1")->outcome, "stick");
}

TEST(campaign_store, windows_round_trip) {
  TempDir t;
  Store s(t.path / "c.db");
  const auto c = s.open_campaign(campaign_named("c"));
  s.store_windows(c, {{c, "{\"G_c\":1}", "{\"G_c\":1}", 250.0, std::nullopt, "{}"}});
  auto w = s.windows(c);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(*w[0].critical_velocity, 250.0);
  EXPECT_FALSE(w[0].maximum_velocity);
  s.store_windows(c, {});
  EXPECT_TRUE(s.windows(c).empty());
}

// A campaign and its points are one write: a point the schema refuses (an
// unknown origin) leaves neither the campaign nor any job behind.
TEST(campaign_store, campaign_and_points_are_stored_together_or_not_at_all) {
  TempDir t;
  Store s(t.path / "c.db");
  NewPoint bad = point("{}", 3.0, "h3");
  bad.point.origin = "elsewhere";
  EXPECT_THROW(s.open_campaign(campaign_named("x"), {point("{}", 1.0, "h1"), bad}, false),
               SqliteError);
  EXPECT_TRUE(s.campaigns().empty());
  EXPECT_FALSE(s.job("h1"));
  const OpenedCampaign ok =
      s.open_campaign(campaign_named("x"), {point("{}", 1.0, "h1"), point("{}", 2.0, "h2")}, false);
  EXPECT_FALSE(ok.replayed);
  EXPECT_EQ(ok.points.jobs_created, 2);
  EXPECT_EQ(s.job_counts(ok.id).total(), 2);
}

// Submission keys: a retry with the same body gets the first campaign and
// writes nothing; another body under the key is refused; the key survives a
// restart and is forgotten after k_submission_key_seconds.
TEST(campaign_store, submission_keys_replay_refuse_persist_and_expire) {
  TempDir t;
  const fs::path db = t.path / "c.db";
  std::int64_t first = 0;
  {
    Store s(db);
    const OpenedCampaign a = s.open_campaign(campaign_named("a"), {point("{}", 1.0, "h1")}, false,
                                             SubmissionKey{"k1", "body-a"});
    first = a.id;
    const OpenedCampaign again = s.open_campaign(campaign_named("a"), {point("{}", 1.0, "h1")},
                                                 false, SubmissionKey{"k1", "body-a"});
    EXPECT_TRUE(again.replayed);
    EXPECT_EQ(again.id, first);
    EXPECT_THROW(s.open_campaign(campaign_named("b"), {point("{}", 2.0, "h2")}, false,
                                 SubmissionKey{"k1", "body-b"}),
                 SubmissionKeyReused);
    EXPECT_EQ(s.campaigns().size(), 1u);
    EXPECT_FALSE(s.job("h2"));
  }
  Store s(db);
  ASSERT_TRUE(s.submission("k1"));
  EXPECT_EQ(s.submission("k1")->campaign_id, first);
  EXPECT_EQ(s.submission("k1")->body_hash, "body-a");
  EXPECT_FALSE(s.submission("k2"));
  // A day and a bit later the key is free again.
  s.write([](Database& d) {
    d.prepare("UPDATE submissions SET created_at = created_at - ?")
        .bind(1, k_submission_key_seconds + 60.0)
        .run();
  });
  EXPECT_FALSE(s.submission("k1"));
  const OpenedCampaign b = s.open_campaign(campaign_named("b"), {point("{}", 2.0, "h2")}, false,
                                           SubmissionKey{"k1", "body-b"});
  EXPECT_FALSE(b.replayed);
  EXPECT_NE(b.id, first);
  EXPECT_EQ(s.submission("k1")->campaign_id, b.id);
}

// A version-1 file (before submission keys) gains the table and keeps its data.
TEST(campaign_store, migrates_a_version_1_file) {
  TempDir t;
  const fs::path db = t.path / "c.db";
  {
    Store s(db);
    s.open_campaign(campaign_named("old"));
    s.write([](Database& d) {
      d.exec("DROP TABLE submissions");
      d.exec("PRAGMA user_version = 1");
    });
  }
  Store s(db);
  EXPECT_EQ(s.schema_version(), 2);
  ASSERT_EQ(s.campaigns().size(), 1u);
  EXPECT_FALSE(s.submission("k"));
}

// Several Stores (each with its own writer thread and connections, as
// separate managers or an API server would have) hammer one file while
// readers read: every write commits, none fails with "database is locked".
TEST(campaign_store, concurrent_writers_never_hit_database_is_locked) {
  TempDir t;
  const fs::path db = t.path / "c.db";
  constexpr int k_writers = 4;
  constexpr int k_jobs_each = 150;
  std::atomic<int> errors{0};
  std::string first_error;
  std::mutex err_mutex;
  {
    Store init(db);  // creates the schema once
  }
  // Another process writes to the same file at the same time (forked before
  // any thread starts, so the child inherits no held lock).
  const pid_t child = fork();
  if (child == 0) {
    int code = 0;
    try {
      Store s(db);
      const auto c = s.open_campaign(campaign_named("proc"));
      for (int i = 0; i < k_jobs_each; ++i) {
        s.add_points(c, {point("{}", i, "p-" + std::to_string(i))}, false);
      }
    } catch (...) {
      code = 1;
    }
    _exit(code);
  }
  std::vector<std::thread> threads;
  for (int w = 0; w < k_writers; ++w) {
    threads.emplace_back([&, w] {
      try {
        Store s(db);
        const auto c = s.open_campaign(campaign_named("w" + std::to_string(w)));
        for (int i = 0; i < k_jobs_each; ++i) {
          std::string h = std::to_string(w);
          h.append("-").append(std::to_string(i));
          s.add_points(c, {point("{}", i, h)}, false);
          auto j = s.claim_next_job(c, this_process_owner(), "host");
          if (!j) throw std::runtime_error("nothing to claim");
          s.finish_job(j->hash, JobState::succeeded, "ok", 0.0, 1,
                       ResultRecord{j->hash, "stick", "", "{}", "", 0.0});
          (void)s.job_counts(c);  // a read between writes
        }
      } catch (const std::exception& e) {
        ++errors;
        std::lock_guard lock(err_mutex);
        first_error = e.what();
      }
    });
  }
  for (std::thread& th : threads) th.join();
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(errors.load(), 0) << first_error;
  Store s(db);
  for (const CampaignRecord& c : s.campaigns()) {
    const JobCounts n = s.job_counts(c.id);
    EXPECT_EQ(n.total(), k_jobs_each) << c.name;
    if (c.name != "proc") {
      EXPECT_EQ(n.succeeded, k_jobs_each) << c.name;
    }
  }
  EXPECT_EQ(s.campaigns().size(), static_cast<std::size_t>(k_writers + 1));
}

}  // namespace
