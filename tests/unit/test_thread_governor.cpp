// The thread governor (solver/core/thread_governor.hpp) fed step times from
// a machine model: on an idle machine two threads take 0.66 of one thread's
// step time, beside a busy process 1.08 (the SPH impact benchmark's 1.51x
// and 0.93x, docs/performance.md). It must run most steps on the faster
// count, follow a change of load within a bounded number of windows, keep
// two threads only when they gain more than the margin, and not flip on
// noise.
#include <gtest/gtest.h>

#include <functional>

#include "solver/core/thread_governor.hpp"

namespace splat {
namespace {

constexpr double k_step = 1e-3;  // s, one thread's step

// Runs `steps` steps; cost(threads, step) is the wall time of that step.
ThreadUse drive(ThreadGovernor& g, long long steps,
                const std::function<double(int, long long)>& cost) {
  for (long long k = 0; k < steps; ++k) g.step_done(cost(g.threads(), k));
  return g.use();
}

double idle(int threads, long long) {
  return threads == 1 ? k_step : 0.66 * k_step;
}
double busy(int threads, long long) {
  return threads == 1 ? k_step : 1.08 * k_step;
}

TEST(ThreadGovernor, a_fixed_policy_runs_every_step_on_the_team) {
  ThreadGovernor g(2, ThreadPolicy::fixed);
  const ThreadUse u = drive(g, 10000, busy);
  EXPECT_EQ(u.steps_on_team, 10000);
  EXPECT_EQ(u.steps_on_one, 0);
  EXPECT_EQ(u.switches, 0);
}

TEST(ThreadGovernor, a_team_of_one_is_fixed) {
  ThreadGovernor g(1, ThreadPolicy::adaptive);
  const ThreadUse u = drive(g, 1000, busy);
  EXPECT_EQ(u.policy, ThreadPolicy::fixed);
  EXPECT_EQ(u.steps_on_team, 1000);
  EXPECT_EQ(g.threads(), 1);
}

TEST(ThreadGovernor, an_idle_machine_keeps_the_team) {
  ThreadGovernor g(2, ThreadPolicy::adaptive);
  // 100,000 steps of 0.66 ms, about 66 s: probes of one thread are rare.
  const ThreadUse u = drive(g, 100000, idle);
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(u.switches, 0);
  EXPECT_LT(static_cast<double>(u.steps_on_one) / 100000.0, 0.03);
}

TEST(ThreadGovernor, a_busy_neighbour_moves_the_run_to_one_thread) {
  ThreadGovernor g(2, ThreadPolicy::adaptive);
  const ThreadUse u = drive(g, 100000, busy);
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(u.switches, 1);
  EXPECT_LT(static_cast<double>(u.steps_on_team) / 100000.0, 0.03);
}

TEST(ThreadGovernor, a_change_of_load_is_followed) {
  ThreadGovernor g(2, ThreadPolicy::adaptive);
  const ThreadGovernorSettings s;
  drive(g, 100000, idle);
  ASSERT_EQ(g.threads(), 2);
  // The load arrives: the team is left within the longest settling period
  // and a probe (64 + 2 windows of at least 25 ms).
  const double bound_seconds = (s.max_settle_windows + 2) * s.window_seconds * 1.1;
  const long long bound_steps = static_cast<long long>(bound_seconds / (1.08 * k_step)) + 10;
  drive(g, bound_steps, busy);
  EXPECT_EQ(g.threads(), 1);
  // And leaves again: back to the team.
  drive(g, bound_steps, idle);
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(g.use().switches, 2);
}

TEST(ThreadGovernor, a_team_faster_by_less_than_the_margin_leaves_one_thread) {
  ThreadGovernor g(2, ThreadPolicy::adaptive);
  // Two threads 2 % faster than one, with an alternating 1 % jitter on every
  // step: one thread is chosen at the first comparison and kept.
  const ThreadUse u = drive(g, 100000, [](int threads, long long k) {
    const double jitter = (k % 2 == 0 ? 1.01 : 0.99);
    return jitter * (threads == 1 ? k_step : 0.98 * k_step);
  });
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(u.switches, 1);
  EXPECT_LT(static_cast<double>(u.steps_on_team) / 100000.0, 0.03);
}

TEST(ThreadGovernor, a_team_faster_by_more_than_the_margin_is_kept) {
  ThreadGovernor g(2, ThreadPolicy::adaptive);
  const ThreadUse u = drive(g, 100000, [](int threads, long long k) {
    const double jitter = (k % 2 == 0 ? 1.01 : 0.99);
    return jitter * (threads == 1 ? k_step : 0.95 * k_step);
  });
  EXPECT_EQ(u.switches, 0);
  EXPECT_LT(static_cast<double>(u.steps_on_one) / 100000.0, 0.03);
}

TEST(ThreadGovernor, a_window_needs_its_time_and_its_steps) {
  ThreadGovernorSettings s;
  s.window_seconds = 0.01;
  s.window_steps = 3;
  ThreadGovernor g(2, ThreadPolicy::adaptive, s);
  // Two steps of 20 ms: time enough, steps not yet.
  g.step_done(0.02);
  g.step_done(0.02);
  EXPECT_EQ(g.threads(), 2);
  g.step_done(0.02);
  EXPECT_EQ(g.threads(), 1) << "the first window ends, one thread is measured next";
  // Three steps of 1 ms: steps enough, time not yet.
  for (int k = 0; k < 3; ++k) g.step_done(0.001);
  EXPECT_EQ(g.threads(), 1);
}

}  // namespace
}  // namespace splat
