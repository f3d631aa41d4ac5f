// The Slurm executor against a real one-node Slurm cluster that this test
// starts itself (tests/slurm/cluster.sh: munged, slurmctld, slurmd in a
// temporary directory) and stops at the end (exactly those daemons). ctest
// label `slurm`; needs slurm-wlm and munge (`tests/slurm/cluster.sh install`)
// and fails clearly without them. Jobs: tests/fake_job for crashes and time
// limits, and real two-mass `splat run` jobs for a window.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "campaign/manager.hpp"

namespace {

using namespace splat::campaign;
using nlohmann::json;
namespace fs = std::filesystem;

const fs::path k_source = SPLAT_SOURCE_DIR;

int shell(const std::string& cmd, std::string* out = nullptr) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  std::array<char, 4096> buf{};
  std::string text;
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) text.append(buf.data(), n);
  const int status = pclose(p);
  if (out) *out = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class SlurmCluster : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("splat_slurm_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    std::string out;
    const int code =
        shell((k_source / "tests/slurm/cluster.sh").string() + " start " + dir_.string(), &out);
    started_ = code == 0;
    start_log_ = out;
    if (started_) setenv("SLURM_CONF", (dir_ / "slurm.conf").c_str(), 1);
  }
  static void TearDownTestSuite() {
    shell((k_source / "tests/slurm/cluster.sh").string() + " stop " + dir_.string());
    fs::remove_all(dir_);
  }
  void SetUp() override {
    ASSERT_TRUE(started_) << "could not start the Slurm test cluster:\n" << start_log_;
    work_ = dir_ / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(work_);
  }

  ManagerOptions slurm_options(const char* program) {
    ManagerOptions o;
    o.executor = ExecutorKind::slurm;
    o.job_program = program;
    o.jobs_dir = work_ / "jobs";
    o.slurm.poll_seconds = 0.2;
    o.poll_seconds = 0.05;
    return o;
  }

  static inline fs::path dir_;
  static inline bool started_ = false;
  static inline std::string start_log_;
  fs::path work_;
};

const SceneResolver identity = [](const json& scene, const fs::path&) { return scene; };

TEST_F(SlurmCluster, packed_array_records_crashes_time_limits_and_results) {
  Store store(work_ / "c.db");
  const std::vector<json> fakes = {json::object({{"threshold", 2.5}}),
                                   json::object({{"segfault", true}}),
                                   json::object({{"sleep", 30}})};
  const json doc = {{"name", "slurm-fake"},
                    {"executor", "slurm"},
                    {"base_scene", {{"name", "fake"}, {"V0", 0.0}, {"fake", json::object()}}},
                    {"velocity", {{"pointer", "/V0"}, {"values", {1.0, 2.0, 3.0, 4.0}}}},
                    {"fields", {{{"pointer", "/fake"}, {"unit", "-"}, {"values", fakes}}}},
                    {"job", {{"time_limit", 1.0}, {"retries", 0}}}};
  ManagerOptions o = slurm_options(SPLAT_FAKE_JOB);
  o.resolver = identity;
  o.solver_version = "fake-slurm";
  o.slurm.max_array_size = 5;  // 12 jobs -> 3 per task, 4 tasks
  o.slurm.throttle = 2;
  const SweepReport r = run_sweep(store, read_campaign(doc), o);
  EXPECT_EQ(r.state, CampaignState::finished);
  EXPECT_EQ(r.jobs_started, 12);
  EXPECT_EQ(r.counts.succeeded, 4);
  EXPECT_EQ(r.counts.failed, 4);
  EXPECT_EQ(r.counts.timed_out, 4);
  for (const PointStatus& p : store.points(r.campaign_id)) {
    const JobRecord j = *store.job(p.point.job_hash);
    const json fake = json::parse(p.point.params).at("/fake");
    if (fake.contains("segfault")) {
      EXPECT_NE(j.exit_reason.find("exit code 139"), std::string::npos) << j.exit_reason;
    } else if (fake.contains("sleep")) {
      EXPECT_NE(j.exit_reason.find("time limit"), std::string::npos) << j.exit_reason;
    } else {
      EXPECT_NE(j.exit_reason.find("(Slurm "), std::string::npos) << j.exit_reason;
    }
  }
  for (const WindowRecord& w : r.windows) {
    if (json::parse(w.params).at("/fake").contains("threshold")) {
      EXPECT_EQ(*w.maximum_velocity, 2.5);
    }
  }
}

TEST_F(SlurmCluster, two_mass_window_through_slurm) {
  Store store(work_ / "c.db");
  const json doc = {{"name", "slurm-two-mass"},
                    {"executor", "slurm"},
                    {"base_scene", (k_source / "scenes/verification/two_mass.json").string()},
                    {"velocity", {{"range", {{"from", 0.2}, {"to", 1.4}, {"step", 0.2}}}}},
                    {"refinement", {{"tolerance", 0.02}, {"max_extra_jobs", 20}}}};
  const SweepReport r = run_sweep(store, read_campaign(doc), slurm_options(SPLAT_BINARY));
  ASSERT_EQ(r.state, CampaignState::finished);
  EXPECT_EQ(r.counts.succeeded, r.counts.total());
  ASSERT_EQ(r.windows.size(), 1u);
  // k = 0: sticks below sqrt(2 G_c A (M + m) / (M m)) = sqrt(0.6) m/s.
  ASSERT_TRUE(r.windows[0].maximum_velocity);
  EXPECT_NEAR(*r.windows[0].maximum_velocity, std::sqrt(0.6), 0.01);
  EXPECT_GT(r.refinement_jobs, 0);
}

TEST_F(SlurmCluster, cancellation_scancels_and_records_every_job) {
  Store store(work_ / "c.db");
  const json doc = {{"name", "slurm-cancel"},
                    {"executor", "slurm"},
                    {"base_scene", {{"name", "fake"}, {"V0", 0.0}, {"fake", {{"sleep", 60}}}}},
                    {"velocity", {{"pointer", "/V0"}, {"values", {1, 2, 3, 4, 5, 6}}}},
                    {"job", {{"time_limit", 120}}}};
  std::atomic<bool> interrupt{false};
  ManagerOptions o = slurm_options(SPLAT_FAKE_JOB);
  o.resolver = identity;
  o.solver_version = "fake-slurm";
  o.slurm.throttle = 2;
  o.interrupt = &interrupt;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::seconds(3));
    interrupt = true;
  });
  const SweepReport r = run_sweep(store, read_campaign(doc), o);
  stopper.join();
  EXPECT_EQ(r.state, CampaignState::cancelled);
  EXPECT_EQ(r.counts.cancelled, 6);
  std::string q;
  shell("squeue --noheader --name=splat-c" + std::to_string(r.campaign_id) +
            " --states=PENDING,RUNNING",
        &q);
  EXPECT_EQ(q.find("splat"), std::string::npos) << q;
}

}  // namespace
