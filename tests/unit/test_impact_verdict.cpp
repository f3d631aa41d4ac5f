// The impact verdict on synthetic histories: when a rebound or a stick is
// settled, and what the maximum time forces.
#include <gtest/gtest.h>

#include "solver/core/impact_verdict.hpp"

namespace splat {
namespace {

VerdictSettings settings() {
  VerdictSettings s;
  s.settle_fraction = 0.01;
  s.hold_time = 1e-9;
  s.impact_speed = 500.0;
  return s;
}

ImpactSample sample(double t, double v_n, double kinetic, long long links, long long contact,
                    double area) {
  return {t, v_n, kinetic, links, contact, area};
}

TEST(ImpactVerdict, rebound_is_settled_after_the_hold_time_without_links_or_contact) {
  ImpactMonitor m(settings());
  EXPECT_FALSE(m.update(sample(0.0, -500.0, 1.0, 0, 0, 0.0)));   // approaching
  EXPECT_FALSE(m.update(sample(1e-9, -10.0, 0.5, 0, 30, 0.0)));  // in contact
  EXPECT_FALSE(m.update(sample(2e-9, 20.0, 0.1, 0, 0, 0.0)));    // leaving: window opens
  EXPECT_FALSE(m.update(sample(2.5e-9, 20.0, 0.1, 0, 0, 0.0)));
  const auto d = m.update(sample(3.1e-9, 20.0, 0.1, 0, 0, 0.0));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->verdict, ImpactVerdict::rebound);
  EXPECT_TRUE(d->settled);
}

TEST(ImpactVerdict, touching_again_restarts_the_rebound_window) {
  ImpactMonitor m(settings());
  m.update(sample(0.0, -500.0, 1.0, 0, 0, 0.0));
  EXPECT_FALSE(m.update(sample(1e-9, 5.0, 0.1, 0, 0, 0.0)));
  EXPECT_FALSE(m.update(sample(1.5e-9, 5.0, 0.1, 0, 2, 0.0)));  // contact again
  EXPECT_FALSE(m.update(sample(2.2e-9, 5.0, 0.1, 0, 0, 0.0)));
  EXPECT_TRUE(m.update(sample(3.2e-9, 5.0, 0.1, 0, 0, 0.0)));
}

TEST(ImpactVerdict, stick_is_settled_once_held_calm_for_the_hold_time) {
  ImpactMonitor m(settings());
  m.update(sample(0.0, -500.0, 1.0, 0, 0, 0.0));
  EXPECT_FALSE(m.update(sample(1e-9, -5.0, 0.005, 20, 20, 2e-10)));  // window opens
  EXPECT_FALSE(m.update(sample(1.5e-9, 0.0, 0.005, 20, 20, 2e-10)));
  // Losing a link restarts the window.
  EXPECT_FALSE(m.update(sample(1.8e-9, 0.0, 0.005, 19, 20, 1.9e-10)));
  EXPECT_FALSE(m.update(sample(2.5e-9, 0.0, 0.005, 19, 20, 1.9e-10)));
  const auto d = m.update(sample(2.9e-9, 0.0, 0.005, 19, 20, 1.9e-10));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->verdict, ImpactVerdict::stick);
  // Still moving at 5 % of K_0: never settled.
  ImpactMonitor busy(settings());
  busy.update(sample(0.0, -500.0, 1.0, 0, 0, 0.0));
  for (double t = 1e-9; t < 1e-8; t += 1e-10) {
    EXPECT_FALSE(busy.update(sample(t, 0.0, 0.05, 20, 20, 2e-10)));
  }
}

TEST(ImpactVerdict, maximum_time_forces_a_verdict_from_links_and_motion) {
  ImpactMonitor m(settings());
  m.update(sample(0.0, -500.0, 1.0, 0, 0, 0.0));
  const VerdictDecision held = m.at_end(sample(1e-8, 1.0, 0.05, 5, 5, 1e-11));
  EXPECT_EQ(held.verdict, ImpactVerdict::stick);
  EXPECT_FALSE(held.settled);
  EXPECT_NE(held.reason.find("not settled"), std::string::npos);
  const VerdictDecision flying = m.at_end(sample(1e-8, 100.0, 0.05, 5, 0, 1e-11));
  EXPECT_EQ(flying.verdict, ImpactVerdict::rebound);
  const VerdictDecision unbonded = m.at_end(sample(1e-8, -1.0, 0.05, 0, 5, 0.0));
  EXPECT_EQ(unbonded.verdict, ImpactVerdict::rebound);
}

}  // namespace
}  // namespace splat
