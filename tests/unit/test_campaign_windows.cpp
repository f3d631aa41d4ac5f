// Deposition windows as a pure function of a stick/rebound sequence
// (campaign/windows.hpp): intervals, edge brackets, unclassified samples
// shown and never counted, and the bisection points of refinement.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>

#include "campaign/windows.hpp"

namespace {

using namespace splat::campaign;

// Samples from a pattern, one character per velocity v0 + i*dv:
// s = stick, r = rebound, u = unstable, f = failed.
std::vector<Sample> pattern(const std::string& p, double v0 = 100.0, double dv = 100.0) {
  std::vector<Sample> out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    Sample s;
    s.velocity = v0 + dv * static_cast<double>(i);
    switch (p[i]) {
      case 's':
        s.verdict = Verdict::stick;
        s.label = "stick";
        break;
      case 'r':
        s.verdict = Verdict::rebound;
        s.label = "rebound";
        break;
      case 'u':
        s.label = "unstable";
        break;
      default:
        s.label = "failed";
        break;
    }
    out.push_back(s);
  }
  return out;
}

TEST(campaign_windows, empty_and_all_rebound_have_no_interval) {
  EXPECT_TRUE(compute_window({}).intervals.empty());
  const Window w = compute_window(pattern("rrrr"));
  EXPECT_TRUE(w.intervals.empty());
  EXPECT_FALSE(w.critical_velocity);
  EXPECT_FALSE(w.maximum_velocity);
  EXPECT_EQ(w.rebounds, 4);
}

TEST(campaign_windows, one_interval_both_edges_closed) {
  // 100 r, 200 r, 300 s, 400 s, 500 s, 600 r
  const Window w = compute_window(pattern("rrsssr"));
  ASSERT_EQ(w.intervals.size(), 1u);
  const StickInterval& iv = w.intervals[0];
  EXPECT_EQ(*iv.lower.rebound_velocity, 200.0);
  EXPECT_EQ(iv.lower.stick_velocity, 300.0);
  EXPECT_EQ(iv.upper.stick_velocity, 500.0);
  EXPECT_EQ(*iv.upper.rebound_velocity, 600.0);
  EXPECT_EQ(*w.critical_velocity, 250.0);
  EXPECT_EQ(*w.maximum_velocity, 550.0);
  EXPECT_EQ(*iv.lower.width(), 100.0);
}

TEST(campaign_windows, open_edges_when_the_range_ends_inside_the_window) {
  // Sticks from the lowest speed: the lower edge lies below the range.
  Window w = compute_window(pattern("sssrr"));
  ASSERT_EQ(w.intervals.size(), 1u);
  EXPECT_FALSE(w.intervals[0].lower.closed());
  EXPECT_FALSE(w.critical_velocity);
  EXPECT_EQ(*w.maximum_velocity, 350.0);
  // Sticks up to the highest speed: the window does not close.
  w = compute_window(pattern("rrsss"));
  EXPECT_EQ(*w.critical_velocity, 250.0);
  EXPECT_FALSE(w.maximum_velocity);
  EXPECT_FALSE(w.intervals[0].upper.closed());
}

TEST(campaign_windows, several_intervals_are_reported_not_smoothed) {
  // Thesis: a second sticking range at very high speed.
  const Window w = compute_window(pattern("rssrrrssr"));
  ASSERT_EQ(w.intervals.size(), 2u);
  EXPECT_EQ(*w.critical_velocity, 150.0);  // first interval's lower edge
  EXPECT_EQ(*w.maximum_velocity, 850.0);   // last interval's upper edge
  EXPECT_EQ(*w.intervals[0].upper.estimate(), 350.0);
  EXPECT_EQ(*w.intervals[1].lower.estimate(), 650.0);
  const nlohmann::json j = to_json(w);
  EXPECT_EQ(j.at("intervals").size(), 2u);
  EXPECT_EQ(j.at("critical_velocity"), 150.0);
  EXPECT_EQ(j.at("maximum_velocity"), 850.0);
}

TEST(campaign_windows, unstable_jobs_inside_a_bracket_are_shown_not_counted) {
  // 100 r, 200 u, 300 f, 400 s, 500 s, 600 u, 700 r
  const Window w = compute_window(pattern("rufssur"));
  ASSERT_EQ(w.intervals.size(), 1u);
  const StickInterval& iv = w.intervals[0];
  // The bracket stays between the nearest rebound and stick: [100, 400].
  EXPECT_EQ(*iv.lower.rebound_velocity, 100.0);
  EXPECT_EQ(iv.lower.stick_velocity, 400.0);
  ASSERT_EQ(iv.lower.unclassified.size(), 2u);
  EXPECT_EQ(iv.lower.unclassified[0].label, "unstable");
  EXPECT_EQ(iv.lower.unclassified[1].label, "failed");
  EXPECT_EQ(*iv.upper.rebound_velocity, 700.0);
  ASSERT_EQ(iv.upper.unclassified.size(), 1u);
  EXPECT_EQ(iv.upper.unclassified[0].velocity, 600.0);
  EXPECT_EQ(w.sticks, 2);
  EXPECT_EQ(w.rebounds, 2);
  EXPECT_EQ(w.unclassified.size(), 3u);
  // The JSON shows them too.
  const nlohmann::json j = to_json(w);
  EXPECT_EQ(j.at("critical_bracket").at("unclassified").size(), 2u);
  EXPECT_EQ(j.at("critical_bracket").at("unclassified")[0].at("label"), "unstable");
}

TEST(campaign_windows, unstable_between_sticks_stays_inside_the_interval) {
  const Window w = compute_window(pattern("rsusr"));
  ASSERT_EQ(w.intervals.size(), 1u);
  ASSERT_EQ(w.intervals[0].unclassified.size(), 1u);
  EXPECT_EQ(w.intervals[0].unclassified[0].velocity, 300.0);
  EXPECT_TRUE(w.intervals[0].lower.unclassified.empty());
}

TEST(campaign_windows, only_unclassified_gives_no_interval) {
  const Window w = compute_window(pattern("uuf"));
  EXPECT_TRUE(w.intervals.empty());
  EXPECT_EQ(w.unclassified.size(), 3u);
}

TEST(campaign_windows, unsorted_input_is_sorted) {
  std::vector<Sample> s = pattern("rssr");
  std::swap(s[0], s[3]);
  std::swap(s[1], s[2]);
  const Window w = compute_window(s);
  ASSERT_EQ(w.intervals.size(), 1u);
  EXPECT_EQ(*w.critical_velocity, 150.0);
  EXPECT_EQ(*w.maximum_velocity, 350.0);
}

TEST(campaign_windows, refinement_bisects_each_wide_closed_edge) {
  const Window w = compute_window(pattern("rrsssr"));
  EXPECT_EQ(refinement_points(w, {10.0}), (std::vector<double>{250.0, 550.0}));
  EXPECT_TRUE(refinement_points(w, {100.0}).empty());  // width 100 is within tolerance
  // Open edges cannot be refined.
  EXPECT_EQ(refinement_points(compute_window(pattern("ssr")), {1.0}), std::vector<double>{250.0});
}

TEST(campaign_windows, refinement_steps_around_an_unstable_midpoint) {
  // Bracket [100, 300] with an unstable sample at 200: bisect a half, not 200 again.
  const Window w = compute_window(pattern("rus"));
  const std::vector<double> p = refinement_points(w, {10.0});
  ASSERT_EQ(p.size(), 1u);
  EXPECT_TRUE(p[0] == 150.0 || p[0] == 250.0) << p[0];
}

// Samples at the given velocities with the given verdicts (s, r, u as in
// pattern()).
std::vector<Sample> at(const std::vector<double>& v, const std::string& p) {
  std::vector<Sample> out = pattern(p);
  for (std::size_t i = 0; i < out.size(); ++i) out[i].velocity = v[i];
  return out;
}

// The bisection of refinement as one obvious loop per edge and per band: the
// widest gap's midpoint of each bracket wider than the tolerance, and the
// midpoint of each gap's part within the band of a closed edge wider than
// the tolerance.
std::vector<double> bisection(const Window& w, double tol, double band) {
  std::vector<double> out;
  for (const StickInterval& iv : w.intervals) {
    for (const Edge* e : {&iv.lower, &iv.upper}) {
      if (!e->closed()) continue;
      const double lo = std::min(*e->rebound_velocity, e->stick_velocity);
      const double hi = std::max(*e->rebound_velocity, e->stick_velocity);
      std::vector<double> v{lo, hi};
      for (const Sample& s : e->unclassified) v.push_back(s.velocity);
      std::sort(v.begin(), v.end());
      double gap = 0.0, mid = 0.0;
      for (std::size_t i = 0; i + 1 < v.size(); ++i) {
        if (v[i + 1] - v[i] > gap) gap = v[i + 1] - v[i], mid = 0.5 * (v[i] + v[i + 1]);
      }
      if (hi - lo > tol && gap > tol) out.push_back(mid);
      for (std::size_t i = 0; band > 0.0 && i + 1 < w.sampled.size(); ++i) {
        const double a = std::max(w.sampled[i], lo - band);
        const double b = std::min(w.sampled[i + 1], hi + band);
        if (b - a > tol) out.push_back(0.5 * (a + b));
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// One bracket [100, 200] m/s: two points per round split it in thirds, one
// point bisects it.
TEST(campaign_windows, two_points_per_round_split_one_bracket_in_thirds) {
  const Window w = compute_window(pattern("rsss"));
  const std::vector<double> p = refinement_points(w, {10.0, 0.0, 2});
  ASSERT_EQ(p.size(), 2u);
  EXPECT_DOUBLE_EQ(p[0], 100.0 + 100.0 / 3.0);
  EXPECT_DOUBLE_EQ(p[1], 100.0 + 200.0 / 3.0);
  EXPECT_EQ(refinement_points(w, {10.0, 0.0, 1}), std::vector<double>{150.0});
}

// Brackets of 100 m/s (lower edge, [100, 200]) and 300 m/s (upper edge,
// [500, 800]): each gets its bisection point, the third point of a round
// goes to the wider one (split in thirds), a fourth to it again (quarters:
// its parts of 100 m/s are still wider than the narrow one's 50).
TEST(campaign_windows, points_spread_over_the_brackets_widest_first) {
  const Window w = compute_window(at({100, 200, 500, 800}, "rssr"));
  EXPECT_EQ(refinement_points(w, {10.0, 0.0, 2}), (std::vector<double>{150.0, 650.0}));
  EXPECT_EQ(refinement_points(w, {10.0, 0.0, 3}), (std::vector<double>{150.0, 600.0, 700.0}));
  EXPECT_EQ(refinement_points(w, {10.0, 0.0, 4}),
            (std::vector<double>{150.0, 575.0, 650.0, 725.0}));
}

// A gap of 30 m/s at a tolerance of 10 takes two points (parts of 10 m/s),
// one of 20 m/s one point, however many a round may have.
TEST(campaign_windows, points_stop_at_the_tolerance) {
  const Window one = compute_window(at({100, 130}, "rs"));
  EXPECT_EQ(refinement_points(one, {10.0, 0.0, 8}), (std::vector<double>{110.0, 120.0}));
  EXPECT_TRUE(refinement_points(compute_window(at({100, 110}, "rs")), {10.0, 0.0, 8}).empty());
  const Window two = compute_window(at({100, 130, 500, 520}, "rssr"));
  EXPECT_EQ(refinement_points(two, {10.0, 0.0, 8}), (std::vector<double>{110.0, 120.0, 510.0}));
}

// A bracket split in thirds has those points instead of its guard-band
// midpoint; the band beyond the bracket is sampled as with bisection.
TEST(campaign_windows, split_points_replace_the_guard_band_midpoint) {
  const Window w = compute_window(pattern("rss"));
  EXPECT_EQ(refinement_points(w, {5.0, 20.0, 1}), (std::vector<double>{150.0, 210.0}));
  const std::vector<double> p = refinement_points(w, {5.0, 20.0, 2});
  ASSERT_EQ(p.size(), 3u);
  EXPECT_DOUBLE_EQ(p[0], 100.0 + 100.0 / 3.0);
  EXPECT_DOUBLE_EQ(p[1], 100.0 + 200.0 / 3.0);
  EXPECT_EQ(p[2], 210.0);
}

// One point per round is bisection: round by round, with unclassified
// samples and a guard band, the same velocities, bit for bit, as the
// obvious loop above, until nothing is left to sample.
TEST(campaign_windows, one_point_per_round_is_plain_bisection) {
  auto truth = [](double v) {
    const bool stick = (v >= 300.0 && !(v >= 320.0 && v < 335.0)) || (v >= 262.0 && v < 274.0);
    const bool unstable = std::fmod(v, 150.0) == 0.0;
    return Sample{v, unstable ? Verdict::other : stick ? Verdict::stick : Verdict::rebound, ""};
  };
  for (const double band : {0.0, 50.0}) {
    std::vector<Sample> samples;
    for (double v = 100.0; v <= 1000.0; v += 50.0) samples.push_back(truth(v));
    int round = 0;
    for (; round < 50; ++round) {
      const Window w = compute_window(samples);
      const std::vector<double> next = refinement_points(w, {3.0, band, 1});
      ASSERT_EQ(next, bisection(w, 3.0, band)) << "band " << band << " round " << round;
      if (next.empty()) break;
      for (double v : next) samples.push_back(truth(v));
    }
    EXPECT_GT(round, 3) << band;
    EXPECT_LT(round, 50) << band;
  }
}

// Refinement driven to the end against a known threshold: the edge found is
// within tolerance of the truth, and it needs about log2(width/tol) jobs.
TEST(campaign_windows, refinement_converges_to_a_known_edge) {
  const double v_true = 437.3;  // stick below, rebound above
  auto truth = [&](double v) {
    Sample s;
    s.velocity = v;
    s.verdict = v < v_true ? Verdict::stick : Verdict::rebound;
    return s;
  };
  std::vector<Sample> samples;
  for (double v = 100.0; v <= 1000.0; v += 100.0) samples.push_back(truth(v));
  const double tol = 1.0;
  int extra = 0;
  for (;;) {
    const std::vector<double> next = refinement_points(compute_window(samples), {tol});
    if (next.empty()) break;
    for (double v : next) samples.push_back(truth(v));
    extra += static_cast<int>(next.size());
    ASSERT_LT(extra, 100);
  }
  const Window w = compute_window(samples);
  ASSERT_TRUE(w.maximum_velocity);
  EXPECT_LE(*w.intervals[0].upper.width(), tol);
  EXPECT_NEAR(*w.maximum_velocity, v_true, tol / 2);
  EXPECT_EQ(extra, static_cast<int>(std::ceil(std::log2(100.0 / tol))));
}

// A map like the FE Al/Al impacts near their critical velocity: stick from
// 300 m/s except a rebound island [320, 335), and a stick island [262, 274)
// below the edge. Bisection alone finds one edge near 300 m/s and neither
// island; a guard band of 50 m/s sampled to the 5 m/s tolerance finds both,
// each as a window interval of its own, and the critical velocity moves to
// the stick island's lower edge.
TEST(campaign_windows, guard_band_finds_islands_next_to_an_edge) {
  auto truth = [](double v) {
    Sample s;
    s.velocity = v;
    const bool stick = (v >= 300.0 && !(v >= 320.0 && v < 335.0)) || (v >= 262.0 && v < 274.0);
    s.verdict = stick ? Verdict::stick : Verdict::rebound;
    return s;
  };
  auto drive = [&](double band) {
    std::vector<Sample> samples;
    for (double v = 100.0; v <= 1000.0; v += 100.0) samples.push_back(truth(v));
    for (int round = 0; round < 50; ++round) {
      const std::vector<double> next = refinement_points(compute_window(samples), {5.0, band});
      if (next.empty()) break;
      for (double v : next) samples.push_back(truth(v));
    }
    return compute_window(samples);
  };
  const Window plain = drive(0.0);
  ASSERT_EQ(plain.intervals.size(), 1u);
  EXPECT_NEAR(*plain.critical_velocity, 300.0, 5.0);
  const Window guarded = drive(50.0);
  ASSERT_EQ(guarded.intervals.size(), 3u);
  EXPECT_NEAR(*guarded.critical_velocity, 262.0, 5.0);
  EXPECT_NEAR(*guarded.intervals[0].upper.estimate(), 274.0, 5.0);
  EXPECT_NEAR(*guarded.intervals[1].upper.estimate(), 320.0, 5.0);
  EXPECT_NEAR(*guarded.intervals[2].lower.estimate(), 335.0, 5.0);
}

}  // namespace
