// How many OpenMP threads the next time step uses, chosen by measuring.
//
// On an idle machine a run's threads speed it up; on a shared one (a busy
// process beside it, campaign jobs side by side, a Slurm node) the threads
// wait for each other at every parallel region of a step and two can be
// slower than one (issue 28). The governor times the steps in windows of
// at least `window_seconds` and `window_steps` steps, with the whole team
// (`team` threads) or with one thread, and keeps the faster:
//   - the run starts with the team; one window at the team, one at one
//     thread, then the faster count runs for `settle` windows;
//   - after those, one probe window at the other count compares with the
//     last window at the chosen count;
//   - the team is chosen only when it is faster than one thread by more
//     than `margin`: a second thread must earn its keep, a near tie (two
//     threads beside a busy process) goes to one thread, which also leaves
//     the other core to the neighbour, and noise does not flip the choice;
//   - a probe that confirms the choice doubles `settle` (up to
//     `max_settle_windows`), one that changes it starts again from
//     `min_settle_windows`: a steady machine is probed rarely, a changing
//     one often.
// Every parallel loop of a step sums in fixed blocks whatever the thread
// count (solver/common/parallel.hpp), so a run's results have the same bits
// whichever counts the governor picks. Only the time spent inside steps is
// measured (the caller leaves output out of it).
#pragma once

#include "solver/common/enum_names.hpp"

namespace splat {

enum class ThreadPolicy {
  adaptive,  // the governor picks one thread or the whole team as it measures
  fixed,     // the whole team for every step
};

inline constexpr NameTable<ThreadPolicy, 2> k_thread_policy_names{{
    {ThreadPolicy::adaptive, "adaptive"},
    {ThreadPolicy::fixed, "fixed"},
}};
static_assert(names_in_order(k_thread_policy_names));
constexpr const auto& names_of(ThreadPolicy) {
  return k_thread_policy_names;
}

struct ThreadGovernorSettings {
  double window_seconds = 0.025;  // s, the shortest window measured
  long long window_steps = 3;     // the fewest steps in a window
  int min_settle_windows = 4;
  int max_settle_windows = 64;
  double margin = 0.03;  // relative speed the team must gain over one thread
};

// Steps run with the team and with one thread.
struct ThreadUse {
  int team = 1;  // threads of the whole team
  ThreadPolicy policy = ThreadPolicy::fixed;
  long long steps_on_team = 0;
  long long steps_on_one = 0;
  int switches = 0;  // changes of the chosen count (probes not counted)
};

class ThreadGovernor {
 public:
  ThreadGovernor(int team, ThreadPolicy policy, ThreadGovernorSettings settings = {});

  // The thread count for the next step.
  int threads() const { return current_; }

  // A step of `seconds` (wall clock) ran with threads(); returns the count
  // for the next step.
  int step_done(double seconds);

  const ThreadUse& use() const { return use_; }

 private:
  enum class Phase { first_team, first_one, settled, probing };
  int other() const { return current_ == use_.team ? 1 : use_.team; }
  void window_done(double seconds_per_step);

  ThreadGovernorSettings settings_;
  ThreadUse use_;
  int current_ = 1;
  Phase phase_ = Phase::first_team;
  int settle_ = 0;            // windows the chosen count runs between probes
  int settle_left_ = 0;       // of those, still to run
  double chosen_cost_ = 0.0;  // s per step of the last window at the chosen count
  double window_seconds_ = 0.0;
  long long window_steps_ = 0;
};

}  // namespace splat
