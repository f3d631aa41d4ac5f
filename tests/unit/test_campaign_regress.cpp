// Regression comparison (campaign/regress.hpp): a baseline written from
// windows compares clean with itself, and each kind of drift is caught.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "campaign/ladders.hpp"
#include "campaign/regress.hpp"
#include "campaign/windows.hpp"

namespace {

using namespace splat::campaign;
using nlohmann::json;

WindowRecord record(const std::string& params, const std::string& pattern, double dv = 0.1) {
  std::vector<Sample> s;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    Sample x;
    x.velocity = 0.1 + dv * static_cast<double>(i);
    x.verdict = pattern[i] == 's'   ? Verdict::stick
                : pattern[i] == 'r' ? Verdict::rebound
                                    : Verdict::other;
    x.label = pattern[i] == 'u' ? "unstable" : "";
    s.push_back(x);
  }
  const Window w = compute_window(s);
  json doc = to_json(w);
  doc["params"] = json::parse(params);
  return {1, params, params, w.critical_velocity, w.maximum_velocity, doc.dump()};
}

int drifts(const RegressionReport& r) {
  int n = 0;
  for (const RegressionCheck& c : r.checks) n += !c.ok;
  return n;
}

TEST(campaign_regress, baseline_matches_itself_and_catches_each_drift) {
  const std::vector<WindowRecord> now = {record(R"({"G_c":0.1})", "rsssrr"),
                                         record(R"({"G_c":0.2})", "sssrrr")};
  const json base = make_baseline("c", now, 0.05);
  EXPECT_EQ(base.at("tolerances").at("velocity"), 0.05);
  EXPECT_FALSE(compare_to_baseline(base, now).drift());

  // An edge moved by one step (0.1 m/s > 0.05): drift on that figure only.
  RegressionReport r = compare_to_baseline(base, {record(R"({"G_c":0.1})", "rrssrr"), now[1]});
  EXPECT_TRUE(r.drift());
  EXPECT_EQ(drifts(r), 1);
  // Within tolerance when the baseline allows it.
  json loose = base;
  loose["tolerances"]["velocity"] = 0.11;
  EXPECT_FALSE(compare_to_baseline(loose, {record(R"({"G_c":0.1})", "rrssrr"), now[1]}).drift());
  // A window that now closes where it did not, a new interval, a new unstable job.
  EXPECT_TRUE(compare_to_baseline(base, {now[0], record(R"({"G_c":0.2})", "rsssrr")}).drift());
  EXPECT_TRUE(compare_to_baseline(base, {record(R"({"G_c":0.1})", "rsrsrr"), now[1]}).drift());
  EXPECT_TRUE(compare_to_baseline(base, {record(R"({"G_c":0.1})", "rsssru"), now[1]}).drift());
  // A missing or an extra parameter set.
  EXPECT_TRUE(compare_to_baseline(base, {now[0]}).drift());
  EXPECT_TRUE(compare_to_baseline(base, {now[0], now[1], record(R"({"G_c":0.3})", "rrr")}).drift());
  // A malformed baseline names the field.
  json bad = base;
  bad["tolerances"]["velocity"] = "x";
  EXPECT_THROW(compare_to_baseline(bad, now), std::invalid_argument);
}

// The same window at elements_across 8 and 16 (a resolution ladder) whose
// critical velocity moves from the third to the `fine`-th sample at 16.
std::vector<WindowRecord> ladder_windows(const std::string& fine) {
  const std::string k = R"("/particle_impact/particle/elements_across")";
  return {record("{" + k + ":8}", "rrssss", 100.0), record("{" + k + ":16}", fine, 100.0)};
}

// A baseline of a campaign whose windows form a resolution ladder also holds
// each edge's status, value and error from resolution; a finer level whose
// edge moved changes the error (and the value) and is caught, within the
// tolerance it is not.
TEST(campaign_regress, a_resolution_ladder_drifts_with_its_error_bar) {
  const std::vector<WindowRecord> now = ladder_windows("rrrsss");
  const json base = make_baseline("c", now, 5.0);
  ASSERT_EQ(base.at("ladders").size(), 1u) << base.dump(2);
  const json& critical = base.at("ladders")[0].at("critical");
  EXPECT_EQ(critical.at("status"), "not-converged");
  // Edges 150.1 and 250.1 m/s (brackets of 100): value 250.1, error the
  // move plus the finest half-width, 100 + 50.
  EXPECT_NEAR(critical.at("value").get<double>(), 250.1, 1e-9);
  EXPECT_NEAR(critical.at("error").get<double>(), 150.0, 1e-9);
  EXPECT_FALSE(compare_to_baseline(base, now).drift());
  // Both windows unchanged but the finer one's edge one sample higher: its
  // window edge, the ladder's value and its error drift.
  const RegressionReport r = compare_to_baseline(base, ladder_windows("rrrrss"));
  int ladder_drifts = 0;
  for (const RegressionCheck& c : r.checks)
    ladder_drifts += !c.ok && c.figure.rfind("ladder", 0) == 0;
  EXPECT_EQ(ladder_drifts, 2);  // value and error; the status is the same
  // A baseline ladder the windows no longer form.
  EXPECT_TRUE(compare_to_baseline(base, {now[0]}).drift());
  json bad = base;
  bad["ladders"] = 3;
  EXPECT_THROW(compare_to_baseline(bad, now), std::invalid_argument);
}

}  // namespace
