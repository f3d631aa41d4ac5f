// The time a campaign has left (campaign/progress.hpp): pending jobs charged
// what their parameter set's finished jobs took, a resolution level none of
// whose jobs has finished charged from the coarser levels of the same
// parameters by the cost's observed power of the resolution, the wall time
// shared among the workers but never below the longest job. Expected
// values worked out by hand from the loads given.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "campaign/progress.hpp"

namespace splat::campaign {
namespace {

const char* const k_n = "/particle_impact/particle/elements_across";

ParameterAxis ladder() {
  ParameterAxis a;
  a.name = k_n;
  a.pointer = k_n;
  a.is_field = true;
  a.values = {8, 16, 32};
  return a;
}

// A parameter set {G_c, N} with its pending and finished jobs.
ParameterSetLoad load(double G_c, int n, int pending, int finished, double wall) {
  nlohmann::json params = {{"G_c", G_c}, {k_n, n}};
  return {params.dump(), pending, finished, wall};
}

TEST(CampaignProgress, nothing_to_estimate_before_a_job_has_finished) {
  const ParameterAxis a = ladder();
  EXPECT_FALSE(work_left({load(30, 8, 12, 0, 0.0)}, &a));
  EXPECT_FALSE(work_left({load(30, 8, 0, 12, 6.0)}, &a)) << "nothing pending";
}

TEST(CampaignProgress, pending_jobs_cost_what_their_set_took) {
  const ParameterAxis a = ladder();
  // 5 finished in 10 s: 2 s each, 10 pending.
  const auto w = work_left({load(30, 8, 10, 5, 10.0)}, &a);
  ASSERT_TRUE(w);
  EXPECT_DOUBLE_EQ(w->job_seconds, 20.0);
  EXPECT_DOUBLE_EQ(w->longest_job, 2.0);
  EXPECT_DOUBLE_EQ(seconds_left(*w, 2), 10.0);
}

TEST(CampaignProgress, a_finer_level_is_charged_by_the_observed_power) {
  const ParameterAxis a = ladder();
  // 1 s at 8 across, 8 s at 16: cost ~ N^3, so 64 s at 32 across.
  const auto w =
      work_left({load(30, 8, 0, 10, 10.0), load(30, 16, 0, 5, 40.0), load(30, 32, 4, 0, 0.0)}, &a);
  ASSERT_TRUE(w);
  EXPECT_NEAR(w->job_seconds, 4 * 64.0, 1e-9);
  EXPECT_NEAR(w->longest_job, 64.0, 1e-12);
  EXPECT_NEAR(seconds_left(*w, 2), 128.0, 1e-9);
  // 1 s and 4 s: N^2, 16 s at 32.
  const auto v =
      work_left({load(30, 8, 0, 10, 10.0), load(30, 16, 0, 5, 20.0), load(30, 32, 1, 0, 0.0)}, &a);
  ASSERT_TRUE(v);
  EXPECT_NEAR(v->job_seconds, 16.0, 1e-9);
}

TEST(CampaignProgress, one_measured_level_takes_the_default_power) {
  const ParameterAxis a = ladder();
  const auto w = work_left({load(30, 8, 0, 4, 2.0), load(30, 16, 3, 0, 0.0)}, &a);
  ASSERT_TRUE(w);
  EXPECT_NEAR(w->job_seconds, 3 * 0.5 * 8.0, 1e-12);  // 0.5 s x 2^3
}

TEST(CampaignProgress, the_power_is_clamped_and_other_parameters_do_not_count) {
  const ParameterAxis a = ladder();
  // G_c 30: finer was cheaper (noise): the power is clamped to 1, 2 x 2 s.
  // G_c 15: only 8 across measured, 1 s; its 16 charged 2^3, not G_c 30's.
  const auto w =
      work_left({load(30, 8, 0, 2, 6.0), load(30, 16, 0, 2, 4.0), load(30, 32, 1, 0, 0.0),
                 load(15, 8, 0, 1, 1.0), load(15, 16, 1, 0, 0.0)},
                &a);
  ASSERT_TRUE(w);
  EXPECT_NEAR(w->job_seconds, 4.0 + 8.0, 1e-12);
  EXPECT_NEAR(w->longest_job, 8.0, 1e-12);
}

TEST(CampaignProgress, without_a_ladder_a_new_set_costs_the_mean_of_all) {
  // 3 jobs in 9 s over the other sets: 3 s each for the 5 of the new set.
  const std::vector<ParameterSetLoad> sets = {
      {R"({"G_c":30})", 0, 2, 4.0}, {R"({"G_c":15})", 0, 1, 5.0}, {R"({"G_c":5})", 5, 0, 0.0}};
  const auto w = work_left(sets, nullptr);
  ASSERT_TRUE(w);
  EXPECT_NEAR(w->job_seconds, 15.0, 1e-12);
}

TEST(CampaignProgress, the_wall_time_is_never_below_the_longest_job) {
  const ParameterAxis a = ladder();
  const auto w = work_left({load(30, 8, 0, 1, 1.0), load(30, 32, 1, 0, 0.0)}, &a);
  ASSERT_TRUE(w);
  EXPECT_NEAR(seconds_left(*w, 8), 64.0, 1e-9);
}

}  // namespace
}  // namespace splat::campaign
