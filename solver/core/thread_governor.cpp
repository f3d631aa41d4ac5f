#include "solver/core/thread_governor.hpp"

#include <algorithm>

namespace splat {

ThreadGovernor::ThreadGovernor(int team, ThreadPolicy policy, ThreadGovernorSettings settings)
    : settings_(settings) {
  use_.team = std::max(1, team);
  use_.policy = use_.team > 1 ? policy : ThreadPolicy::fixed;
  current_ = use_.team;
  settle_ = settings_.min_settle_windows;
}

int ThreadGovernor::step_done(double seconds) {
  (current_ == use_.team ? use_.steps_on_team : use_.steps_on_one) += 1;
  if (use_.policy == ThreadPolicy::fixed) return current_;
  window_seconds_ += seconds;
  window_steps_ += 1;
  if (window_seconds_ >= settings_.window_seconds && window_steps_ >= settings_.window_steps) {
    const double cost = window_seconds_ / static_cast<double>(window_steps_);
    window_seconds_ = 0.0;
    window_steps_ = 0;
    window_done(cost);
  }
  return current_;
}

void ThreadGovernor::window_done(double cost) {
  switch (phase_) {
    case Phase::first_team:
      chosen_cost_ = cost;
      current_ = 1;
      phase_ = Phase::first_one;
      return;
    case Phase::first_one:
    case Phase::probing: {
      // cost is the other count's, chosen_cost_ the chosen one's.
      const double team_cost = current_ == use_.team ? cost : chosen_cost_;
      const double one_cost = current_ == use_.team ? chosen_cost_ : cost;
      const int faster = team_cost < one_cost * (1.0 - settings_.margin) ? use_.team : 1;
      const int before = phase_ == Phase::first_one ? use_.team : other();
      if (faster != before) {
        settle_ = settings_.min_settle_windows;
        ++use_.switches;
      } else {
        settle_ = phase_ == Phase::probing ? std::min(2 * settle_, settings_.max_settle_windows)
                                           : settings_.min_settle_windows;
      }
      chosen_cost_ = faster == current_ ? cost : chosen_cost_;
      current_ = faster;
      settle_left_ = settle_;
      phase_ = Phase::settled;
      return;
    }
    case Phase::settled:
      chosen_cost_ = cost;
      if (--settle_left_ > 0) return;
      current_ = other();
      phase_ = Phase::probing;
      return;
  }
}

}  // namespace splat
