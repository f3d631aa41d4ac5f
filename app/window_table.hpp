// Printing deposition windows (stored WindowRecords) as a table, JSON or CSV;
// shared by `splat sweep`, `splat windows` and `splat regress`.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "campaign/ladders.hpp"
#include "campaign/spec.hpp"
#include "campaign/store.hpp"

namespace splat::app {

// One JSON row per parameter set: `params`, `critical_velocity`,
// `maximum_velocity` (null when the edge lies outside the swept range),
// each edge's bracket, the sticking `intervals` and the unclassified jobs.
nlohmann::json windows_json(const std::vector<campaign::WindowRecord>& windows);

void print_windows_table(std::FILE* out, const std::vector<campaign::WindowRecord>& windows);
void print_windows_csv(std::FILE* out, const std::vector<campaign::WindowRecord>& windows);

// What a ladder's jobs are compared with: the campaign's velocity grid and
// its refinement tolerance.
struct LadderGrid {
  std::size_t velocities = 0;  // 0: not known (nothing is compared)
  double from = 0.0;           // m/s, the lowest grid velocity
  double to = 0.0;             // m/s, the highest
  double tolerance = 0.0;      // m/s; 0: no refinement
};
LadderGrid ladder_grid(const campaign::CampaignSpec& spec);

// The resolution ladders (campaign/ladders.hpp): per ladder, each level's
// edges and cost, then each edge's value, error and status, and with a known
// `grid` the jobs of the ladder against gridding every level: on a grid at
// the tolerance over the grid's range (the same bracket width without
// refinement), and on the campaign's grid, alone (a lower bound) and refined
// as the coarsest level was (its jobs at every level).
// Nothing when the windows hold no ladder.
void print_ladders_table(std::FILE* out, const std::vector<campaign::Ladder>& ladders,
                         const LadderGrid& grid = {});

// "12 jobs: 10 succeeded, 1 failed, 1 timed-out"
std::string counts_text(const campaign::JobCounts& c);

}  // namespace splat::app
