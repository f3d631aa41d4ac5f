// Resolution ladders (campaign/ladders.hpp): windows of one parameter set at
// several resolutions read together; each edge gets a value and an error
// from resolution, checked against edges built from a known convergence law.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "campaign/ladders.hpp"
#include "campaign/windows.hpp"

namespace {

using namespace splat::campaign;
using nlohmann::json;

const std::string k_across = "/particle_impact/particle/elements_across";

// Edges of exact midpoint f and half-width w at each level.
std::vector<LevelEdge> edges(const std::vector<double>& f, double w) {
  std::vector<LevelEdge> out;
  for (double x : f) out.push_back({x, w});
  return out;
}

// A stored window whose critical velocity is bracketed by a rebound at
// `edge` - 5 and a stick at `edge` + 5 (m/s), on a 10 m/s grid 100-1000.
WindowRecord record(std::int64_t campaign, const json& params, double edge) {
  std::vector<Sample> samples;
  for (double v = edge - 95.0; v <= edge + 95.0; v += 10.0) {
    samples.push_back(
        {v, v < edge ? Verdict::rebound : Verdict::stick, v < edge ? "rebound" : "stick"});
  }
  const Window w = compute_window(samples);
  json doc = to_json(w);
  doc["params"] = params;
  return {campaign,           params.dump(), params.dump(), w.critical_velocity,
          w.maximum_velocity, doc.dump()};
}

}  // namespace

// f(n) = f* - C / n^2 at n = 8, 16, 32 (ratio 2, order 2): the estimate is f*
// and the error 1.25 |f* - f(32)| plus the finest half-width.
TEST(campaign_ladders, second_order_edges_extrapolate_to_the_limit) {
  const double limit = 800.0, C = 12800.0;
  std::vector<double> f;
  for (double n : {8.0, 16.0, 32.0}) f.push_back(limit - C / (n * n));
  const LadderEdge e = ladder_edge({8, 16, 32}, edges(f, 5.0));
  ASSERT_EQ(e.status, LadderStatus::extrapolated);
  EXPECT_NEAR(*e.value, limit, 1e-9);
  EXPECT_NEAR(*e.order, 2.0, 1e-9);
  EXPECT_NEAR(*e.error, 1.25 * (limit - f[2]) + 5.0, 1e-9);
}

// Edges whose moves barely shrink (884 / 828 / 775 m/s, moves 56 then 53,
// observed order 0.08) are not extrapolated (to -155 m/s): not-converged,
// the finest value with the last move as its error.
TEST(campaign_ladders, edges_that_barely_converge_are_not_extrapolated) {
  const LadderEdge e = ladder_edge({8, 16, 32}, edges({884, 828, 775}, 3.0));
  ASSERT_EQ(e.status, LadderStatus::not_converged);
  EXPECT_NEAR(*e.value, 775.0, 1e-9);
  EXPECT_NEAR(*e.error, 53.0 + 3.0, 1e-9);
}

// Edges that move back and forth (the FE Al/Al band 290 / 310 / 290 m/s)
// are not extrapolated: value the finest, error the last move plus the
// finest half-width.
TEST(campaign_ladders, edges_that_alternate_are_not_converged) {
  const LadderEdge e = ladder_edge({8, 16, 32}, edges({290, 310, 290}, 5.0));
  EXPECT_EQ(e.status, LadderStatus::not_converged);
  EXPECT_DOUBLE_EQ(*e.value, 290.0);
  EXPECT_DOUBLE_EQ(*e.error, 25.0);
  EXPECT_FALSE(e.order.has_value());
}

// Converging edges at ratios 1.5 and 1.33 (8, 12, 16): no constant ratio, so
// no Richardson estimate; two levels are never extrapolated either.
TEST(campaign_ladders, unequal_ratios_and_two_levels_give_the_spread) {
  const LadderEdge a = ladder_edge({8, 12, 16}, edges({600, 700, 740}, 5.0));
  EXPECT_EQ(a.status, LadderStatus::not_converged);
  EXPECT_DOUBLE_EQ(*a.error, 45.0);
  const LadderEdge b = ladder_edge({8, 16}, edges({600, 700}, 12.5));
  EXPECT_EQ(b.status, LadderStatus::not_converged);
  EXPECT_DOUBLE_EQ(*b.value, 700.0);
  EXPECT_DOUBLE_EQ(*b.error, 112.5);
}

// A diverging sequence (the moves grow) has a negative observed order: the
// spread, never an extrapolation away from the data.
TEST(campaign_ladders, diverging_edges_are_not_extrapolated) {
  const LadderEdge e = ladder_edge({8, 16, 32}, edges({700, 680, 600}, 5.0));
  EXPECT_EQ(e.status, LadderStatus::not_converged);
  EXPECT_DOUBLE_EQ(*e.error, 85.0);
}

TEST(campaign_ladders, an_edge_open_at_one_level_has_no_value) {
  std::vector<LevelEdge> e = edges({600, 700, 740}, 5.0);
  e[1] = {};
  const LadderEdge l = ladder_edge({8, 16, 32}, e);
  EXPECT_EQ(l.status, LadderStatus::open);
  EXPECT_FALSE(l.value.has_value());
  EXPECT_FALSE(l.error.has_value());
}

// Windows group into ladders by the parameters other than the resolution
// field; a set with one level and sets of another campaign stay apart, and
// the levels come out coarse to fine whatever the stored order.
TEST(campaign_ladders, windows_group_by_the_other_parameters) {
  auto params = [](double gc, double n) { return json{{"G_c", gc}, {k_across, n}}; };
  const std::vector<WindowRecord> w = {
      record(1, params(30, 32), 795), record(1, params(30, 8), 605), record(1, params(30, 16), 755),
      record(1, params(15, 8), 505), record(2, params(30, 8), 405)};
  std::map<std::string, LevelCost> cost;
  cost[params(30, 8).dump()] = {20, 10.0};
  cost[params(30, 32).dump()] = {12, 400.0};
  const std::vector<Ladder> ladders = resolution_ladders(w, cost);
  ASSERT_EQ(ladders.size(), 1u);
  const Ladder& l = ladders[0];
  EXPECT_EQ(l.pointer, k_across);
  EXPECT_EQ(l.params, json({{"G_c", 30}}));
  EXPECT_EQ(l.levels, (std::vector<double>{8, 16, 32}));
  EXPECT_EQ(l.cost[0].jobs, 20);
  EXPECT_EQ(l.cost[1].jobs, 0);
  EXPECT_DOUBLE_EQ(l.cost[2].job_seconds, 400.0);
  // Critical edges 605, 755, 795 m/s: moves 150 then 40, order log2(3.75).
  ASSERT_EQ(l.critical.status, LadderStatus::extrapolated);
  EXPECT_NEAR(*l.critical.order, std::log2(150.0 / 40.0), 1e-9);
  EXPECT_NEAR(*l.critical.value, 795.0 + 40.0 / (150.0 / 40.0 - 1.0), 1e-9);
  EXPECT_EQ(l.maximum.status, LadderStatus::open);  // every stick reaches the range's end

  const json doc = to_json(l);
  EXPECT_EQ(doc.at("critical").at("status"), "extrapolated");
  EXPECT_EQ(doc.at("critical").at("levels").size(), 3u);
  const std::string csv = ladders_csv(ladders);
  EXPECT_EQ(csv.rfind("campaign_id,params,pointer,level,jobs,job_seconds [s],", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);  // header + 3 levels
}

namespace {

// A level whose particle sticks in [lower, upper) m/s.
struct TrueWindow {
  double lower;
  double upper;
  Sample at(double v) const {
    const bool stick = v >= lower && v < upper;
    return {v, stick ? Verdict::stick : Verdict::rebound, stick ? "stick" : "rebound"};
  }
};

// The samples of each level and the rounds coarse_to_fine_step took.
struct LadderRun {
  std::vector<std::vector<Sample>> levels;
  int rounds = 0;
};

// Runs coarse_to_fine_step to the end: the coarsest level starts on the
// grid, the finer ones empty.
LadderRun run_ladder_rounds(const std::vector<TrueWindow>& truth, const std::vector<double>& grid,
                            const RefinementRule& rule) {
  LadderRun run{std::vector<std::vector<Sample>>(truth.size()), 0};
  for (double v : grid) run.levels[0].push_back(truth[0].at(v));
  for (; run.rounds < 200; ++run.rounds) {
    const LadderStep step = coarse_to_fine_step(run.levels, rule);
    if (step.velocities.empty()) return run;
    for (double v : step.velocities) run.levels[step.level].push_back(truth[step.level].at(v));
  }
  ADD_FAILURE() << "no end after 200 rounds";
  return run;
}

// Each level's samples of run_ladder_rounds with bisection.
std::vector<std::vector<Sample>> run_ladder(const std::vector<TrueWindow>& truth,
                                            const std::vector<double>& grid, double tolerance,
                                            double band) {
  return run_ladder_rounds(truth, grid, {tolerance, band}).levels;
}

// A level whose particle sticks in [lower, upper) m/s and in an island
// [island_lower, island_upper) below it.
struct IslandWindow {
  TrueWindow main;
  TrueWindow island;
  Sample at(double v) const {
    return island.at(v).verdict == Verdict::stick ? island.at(v) : main.at(v);
  }
};

std::vector<double> grid_200_to_1000() {
  std::vector<double> g;
  for (double v = 200; v <= 1000; v += 100) g.push_back(v);
  return g;
}

}  // namespace

// An edge that moves down past every sample of the middle level (778 ->
// 772 -> 730 m/s, the FE Al/Al ladder of 8, 16, 32 elements across): the
// middle level ran only near its bracket (756-781), so the finest one sticks
// at all of those; the coarsest level's samples below (750, 725, ...) are
// tried until it rebounds. Without them the finest edge stays open.
TEST(campaign_ladders, an_edge_that_moves_past_the_middle_level_is_found_below_it) {
  const std::vector<TrueWindow> truth = {{778, 1250}, {772, 1250}, {730, 1250}};
  std::vector<double> grid;
  for (double v = 200; v <= 1400; v += 100) grid.push_back(v);
  const auto levels = run_ladder(truth, grid, 10.0, 20.0);
  const Window w = compute_window(levels[2]);
  ASSERT_FALSE(w.intervals.empty());
  ASSERT_TRUE(w.intervals.front().lower.closed());
  EXPECT_NEAR(*w.critical_velocity, 730.0, 10.0);
}

// A refined level that sticks in an island well below the coarse edge, with
// rebounds between (FE Al/Al: 8 across sticks from 884 m/s; 16 across
// sticks at 775 and 800 m/s and rebounds from 825 to 875): the walk from
// the coarse bracket stops at the first rebound, the probes at the 1st,
// 2nd, 4th, ... coarse velocity below it find the island, and the fine
// level's critical edge is the island's. Both levels ran on a 50 m/s grid.
TEST(campaign_ladders, coarse_to_fine_finds_a_stick_island_below_the_coarse_edge) {
  std::vector<double> grid;
  for (double v = 100; v <= 1400; v += 50) grid.push_back(v);
  const TrueWindow coarse{884, 1300};
  const IslandWindow fine{{880, 1300}, {770, 810}};
  std::vector<std::vector<Sample>> levels(2);
  for (double v : grid) levels[0].push_back(coarse.at(v));
  int round = 0;
  for (; round < 200; ++round) {
    const LadderStep step = coarse_to_fine_step(levels, {10.0, 20.0});
    if (step.velocities.empty()) break;
    for (double v : step.velocities) {
      levels[step.level].push_back(step.level == 0 ? coarse.at(v) : fine.at(v));
    }
  }
  ASSERT_LT(round, 200);
  const Window w = compute_window(levels[1]);
  ASSERT_TRUE(w.critical_velocity.has_value());
  EXPECT_NEAR(*w.critical_velocity, 770.0, 10.0);
  EXPECT_EQ(w.intervals.size(), 2u);
  // Cheaper than running the fine level like the coarse one (grid,
  // bisection and guard bands).
  EXPECT_LT(levels[1].size(), levels[0].size());
  std::printf("  coarse %zu jobs, fine %zu jobs (grid %zu)\n", levels[0].size(), levels[1].size(),
              grid.size());
}

// Edges that move with the level (300 -> 340 -> 352 m/s lower, 820 -> 790 ->
// 784 upper): every level brackets both to the tolerance, and the finer
// levels run fewer jobs than the coarse one.
TEST(campaign_ladders, coarse_to_fine_brackets_every_level_with_fewer_jobs) {
  const std::vector<TrueWindow> truth = {{300, 820}, {340, 790}, {352, 784}};
  const auto levels = run_ladder(truth, grid_200_to_1000(), 10.0, 0.0);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Window w = compute_window(levels[i]);
    ASSERT_EQ(w.intervals.size(), 1u) << "level " << i;
    EXPECT_NEAR(*w.critical_velocity, truth[i].lower, 10.0) << "level " << i;
    EXPECT_NEAR(*w.maximum_velocity, truth[i].upper, 10.0) << "level " << i;
    EXPECT_LE(*w.intervals[0].lower.width(), 10.0);
    std::printf("  level %zu: %zu jobs\n", i, levels[i].size());
  }
  // The finer levels, island probes included, take fewer jobs together than
  // running both like the coarse one.
  EXPECT_LE(levels[1].size(), levels[0].size());
  EXPECT_LT(levels[1].size() + levels[2].size(), 2 * levels[0].size());
}

// The ladder above with four points per round: every level bracketed to the
// tolerance as with bisection, the finest with its guard band, in fewer
// rounds.
TEST(campaign_ladders, four_points_per_round_bracket_the_ladder_in_fewer_rounds) {
  const std::vector<TrueWindow> truth = {{300, 820}, {340, 790}, {352, 784}};
  std::map<int, LadderRun> runs;
  for (int k : {1, 4}) {
    runs[k] = run_ladder_rounds(truth, grid_200_to_1000(), {10.0, 20.0, k});
    std::size_t jobs = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const Window w = compute_window(runs[k].levels[i]);
      ASSERT_EQ(w.intervals.size(), 1u) << k << " points, level " << i;
      EXPECT_NEAR(*w.critical_velocity, truth[i].lower, 10.0) << k << " points, level " << i;
      EXPECT_NEAR(*w.maximum_velocity, truth[i].upper, 10.0) << k << " points, level " << i;
      EXPECT_LE(*w.intervals[0].lower.width(), 10.0);
      EXPECT_LE(*w.intervals[0].upper.width(), 10.0);
      jobs += runs[k].levels[i].size();
    }
    std::printf("  %d point(s) per round: %d rounds, %zu jobs\n", k, runs[k].rounds, jobs);
  }
  EXPECT_LT(runs[4].rounds, runs[1].rounds);
}

// A fine level whose edge moved by more than a grid step (300 -> 480 m/s):
// the search walks out along the coarse velocities until it finds it.
TEST(campaign_ladders, coarse_to_fine_follows_an_edge_that_moved_far) {
  const std::vector<TrueWindow> truth = {{300, 2000}, {480, 2000}};
  const auto levels = run_ladder(truth, grid_200_to_1000(), 10.0, 0.0);
  const Window w = compute_window(levels[1]);
  ASSERT_TRUE(w.critical_velocity.has_value());
  EXPECT_NEAR(*w.critical_velocity, 480.0, 10.0);
  EXPECT_FALSE(w.maximum_velocity.has_value());  // open at both levels
}

// An edge open at the coarse level (sticks to the range's end) is checked at
// the fine level at the range's end; a fine level that loses the window
// keeps it open, not invented.
TEST(campaign_ladders, coarse_to_fine_checks_open_edges_at_the_range_end) {
  const std::vector<TrueWindow> truth = {{300, 2000}, {1500, 2000}};
  const auto levels = run_ladder(truth, grid_200_to_1000(), 10.0, 0.0);
  const Window w = compute_window(levels[1]);
  EXPECT_TRUE(w.intervals.empty());
  EXPECT_EQ(w.rebounds, static_cast<int>(levels[1].size()));
}

// The guard band is sampled at the finest level only. Both levels stick in
// [340, 790) m/s and in an island [324, 331) beside the lower edge, on a
// 100 m/s grid 200-1000, tolerance 10, band 20: the coarse level runs its
// grid and the bisection of its two edges (4 halvings of 100 m/s each), the
// finest level splits the band about its edges to the tolerance and finds
// the island.
TEST(campaign_ladders, the_guard_band_is_sampled_at_the_finest_level_only) {
  const IslandWindow truth{{340, 790}, {324, 331}};
  std::vector<std::vector<Sample>> levels(2);
  for (double v : grid_200_to_1000()) levels[0].push_back(truth.at(v));
  int round = 0;
  for (; round < 200; ++round) {
    const LadderStep step = coarse_to_fine_step(levels, {10.0, 20.0});
    if (step.velocities.empty()) break;
    for (double v : step.velocities) levels[step.level].push_back(truth.at(v));
  }
  ASSERT_LT(round, 200);
  EXPECT_EQ(levels[0].size(), grid_200_to_1000().size() + 2 * 4);
  const Window fine = compute_window(levels[1]);
  ASSERT_EQ(fine.intervals.size(), 2u);
  EXPECT_NEAR(*fine.critical_velocity, 324.0, 10.0);
  std::printf("  coarse %zu jobs, fine %zu jobs\n", levels[0].size(), levels[1].size());
}
