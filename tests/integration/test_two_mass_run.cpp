// `splat run` of the two-mass scene as the campaign manager calls it: exit
// code, --json summary valid against schemas/result.schema.json, HDF5
// histories that read back to the summary's figures, and clear outcomes at
// the bounds of the inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/input/schema.hpp"
#include "solver/io/result_file.hpp"
#include "support/scene_runs.hpp"

namespace splat {
namespace {

using splat::test_support::run_splat;

using nlohmann::json;

const std::string scene = std::string(SPLAT_SOURCE_DIR) + "/scenes/verification/two_mass.json";

TEST(two_mass_run, summary_and_histories_of_the_thesis_case) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("splat_two_mass_" + std::to_string(getpid()));
  const auto o = run_splat("run " + scene + " --json --out " + dir.string(), false);
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const json s = json::parse(o.stdout_text);
  EXPECT_TRUE(validate("result", s).empty()) << s.dump(2);
  EXPECT_EQ(s["outcome"], "rebound");
  // 1/3 - (2/3) sqrt(0.4), the k = 0 closed form, away from m.
  const double expected = -(1.0 / 3.0 - 2.0 / 3.0 * std::sqrt(0.4));
  EXPECT_NEAR(s["separation_velocity"].get<double>(), expected, 1e-12);
  EXPECT_EQ(s["two_mass"]["link_state"], "exhausted");
  EXPECT_DOUBLE_EQ(s["two_mass"]["link_work"].get<double>(), 0.2);

  const std::filesystem::path h5 = s["output"]["hdf5"].get<std::string>();
  const ResultSummary r = read_result_summary(h5);
  EXPECT_EQ(r.text_attributes.at("outcome"), "rebound");
  EXPECT_EQ(r.history_rows, static_cast<std::size_t>(s["steps"].get<long long>() + 1));
  EXPECT_EQ(read_unit(h5, "/history/v_M"), "m/s");
  EXPECT_EQ(read_unit(h5, "/history/link_force"), "N");
  EXPECT_DOUBLE_EQ(read_history(h5, "v_M").back(), s["two_mass"]["final_velocity_M"].get<double>());
  EXPECT_DOUBLE_EQ(read_history(h5, "link_work").back(), 0.2);
  EXPECT_DOUBLE_EQ(read_history(h5, "v_M").front(), 1.0);  // V0 before the impact
  std::filesystem::remove_all(dir);
}

// Bounds the campaign may send: each gives a verdict or a clear input error,
// in milliseconds.
TEST(two_mass_run, bounds_give_a_verdict_or_an_input_error) {
  struct Case {
    std::string set;
    int code;
    std::string outcome_or_message;
  };
  const Case cases[] = {
      {"--set /two_mass/V0=0", 0, "stick"},
      {"--set /two_mass/adhesion/G_c=0", 0, "rebound"},
      {"--set /two_mass/area=1e-300", 0, "rebound"},
      {"--set /two_mass/adhesion/sigma_c=1e-300", 0, "rebound"},  // predicted at the end time
      {"--set /two_mass/adhesion/sigma_c=null --set /two_mass/adhesion/G_c=1", 0, "stick"},
      {"--set /two_mass/k=1e6 --set /two_mass/adhesion/G_c=10", 0, "stick"},
      {"--set /two_mass/k=1e6", 0, "rebound"},
      {"--set /two_mass/k=0.5 --set /time/max_steps=10", 3, "timed-out"},
      {"--set /two_mass/k=1e6 --set /time/dt=0.01", 2, "/time/dt: must be < 2 sqrt(m / k)"},
      {"--set /two_mass/adhesion/activation/rule=yield-drop "
       "--set /two_mass/adhesion/activation/drop_percent=30",
       2, "/two_mass/adhesion/activation/rule: must be \"none\""},
      {"--set /two_mass/M=0", 2, "/two_mass/M: must be > 0 (kg)"},
      {"--set /two_mass/adhesion/sigma_c=0", 2, "/two_mass/adhesion/sigma_c: must be > 0 (Pa)"},
  };
  for (const Case& c : cases) {
    const auto o = run_splat("run " + scene + " --json --out '' " + c.set, false);
    EXPECT_EQ(o.code, c.code) << c.set << "\n" << o.stdout_text;
    if (c.code == 2) continue;  // the message goes to stderr; checked below
    const json s = json::parse(o.stdout_text);
    EXPECT_EQ(s["outcome"], c.outcome_or_message) << c.set << ": " << s["reason"];
    EXPECT_LT(s["wall_seconds"].get<double>(), 1.0) << c.set;
  }
  for (const Case& c : cases) {
    if (c.code != 2) continue;
    const std::string text = run_splat("run " + scene + " " + c.set).stdout_text;
    EXPECT_NE(text.find(c.outcome_or_message), std::string::npos) << c.set << "\n" << text;
  }
}

}  // namespace
}  // namespace splat
