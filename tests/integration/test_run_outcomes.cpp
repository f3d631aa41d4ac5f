// Every way a `splat run` can end leaves the same evidence behind: a summary
// that validates against schemas/result.schema.json (on stdout with --json
// and in DIR/<scene>.summary.json), an HDF5 file whose histories and final
// snapshot read back, and the documented exit code.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include <unistd.h>

#include "solver/input/schema.hpp"
#include "solver/io/result_file.hpp"
#include "support/scene_runs.hpp"

namespace splat {
namespace {

using Output = test_support::CommandOutput;

Output run(const std::string& args) {
  return test_support::run_command(std::string(SPLAT_BINARY) + " " + args + " 2>/dev/null");
}

const std::string taylor = std::string(SPLAT_SOURCE_DIR) + "/scenes/taylor_copper_axisym.json";

// Runs the axisymmetric Taylor scene with `sets` and checks the evidence.
nlohmann::json check_run(const std::string& name, const std::string& sets, int expected_code,
                         const std::string& expected_outcome,
                         const std::string& expected_stop_reason) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("splat_outcome_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  const Output o = run("run " + taylor + " --json --out " + dir.string() + " " + sets);
  EXPECT_EQ(o.code, expected_code) << o.stdout_text;
  const nlohmann::json printed = nlohmann::json::parse(o.stdout_text, nullptr, false);
  EXPECT_FALSE(printed.is_discarded()) << o.stdout_text;
  if (printed.is_discarded()) return {};
  for (const SchemaViolation& v : validate("result", printed)) ADD_FAILURE() << to_string(v);
  EXPECT_EQ(printed.value("outcome", ""), expected_outcome) << printed.dump(2);
  EXPECT_EQ(printed.value("stop_reason", ""), expected_stop_reason) << printed.dump(2);
  EXPECT_FALSE(printed.value("reason", "").empty());

  const auto summary_file = dir / "taylor_copper_axisym.summary.json";
  EXPECT_TRUE(std::filesystem::exists(summary_file));
  std::ifstream in(summary_file);
  const nlohmann::json stored = nlohmann::json::parse(in, nullptr, false);
  EXPECT_EQ(stored, printed);

  const auto h5 = dir / "taylor_copper_axisym.h5";
  const ResultSummary rs = read_result_summary(h5);
  EXPECT_GT(rs.history_rows, 0u);
  EXPECT_GE(rs.snapshots, 1u);
  const std::vector<double> t = read_history(h5, "time");
  EXPECT_EQ(t.size(), rs.history_rows);
  // The last snapshot is the state the run ended in.
  const double t_last = read_snapshot_time(h5, rs.snapshots - 1);
  EXPECT_NEAR(t_last, printed.value("end_time", -1.0), 1e-12);
  EXPECT_FALSE(read_snapshot_field(h5, rs.snapshots - 1, "rod", "coordinates").empty());
  EXPECT_TRUE(std::filesystem::exists(dir / "taylor_copper_axisym.xmf"));
  return printed;
}

TEST(run_outcomes, finished_at_end_time) {
  check_run("finished", "--set /time/end_time=2e-6", 0, "finished", "end-time");
}

TEST(run_outcomes, energy_balance_limit_ends_unstable) {
  check_run("energy", "--set /time/energy_balance_limit=1e-12", 3, "unstable", "energy-balance");
}

TEST(run_outcomes, step_limit_ends_timed_out) {
  check_run("steps", "--set /time/max_steps=7", 3, "timed-out", "step-limit");
}

TEST(run_outcomes, time_step_floor_ends_unstable) {
  check_run("dt_floor", "--set /time/min_time_step=1e-3", 3, "unstable", "time-step-collapse");
}

// At 3000 m/s the rod's impact face is crushed: without erosion its time
// step falls below the default floor (1e-3 of the first step).
TEST(run_outcomes, crushed_mesh_ends_unstable_with_time_step_collapse) {
  const nlohmann::json s = check_run("crushed",
                                     "--set /bodies/0/initial/velocity=[0,0,-3000] "
                                     "--set /bodies/0/discretization/elements_across=3",
                                     3, "unstable", "time-step-collapse");
  EXPECT_NE(s.value("reason", "").find("time step collapsed"), std::string::npos) << s.dump(2);
}

}  // namespace
}  // namespace splat
