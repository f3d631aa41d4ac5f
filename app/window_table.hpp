// Printing deposition windows (stored WindowRecords) as a table, JSON or CSV;
// shared by `splat sweep`, `splat windows` and `splat regress`.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "campaign/ladders.hpp"
#include "campaign/store.hpp"

namespace splat::app {

// One JSON row per parameter set: `params`, `critical_velocity`,
// `maximum_velocity` (null when the edge lies outside the swept range),
// each edge's bracket, the sticking `intervals` and the unclassified jobs.
nlohmann::json windows_json(const std::vector<campaign::WindowRecord>& windows);

void print_windows_table(std::FILE* out, const std::vector<campaign::WindowRecord>& windows);
void print_windows_csv(std::FILE* out, const std::vector<campaign::WindowRecord>& windows);

// The resolution ladders (campaign/ladders.hpp): per ladder, each level's
// edges and cost, then each edge's value, error and status, and with
// `grid_velocities` (the campaign's velocity grid; 0: not known) the jobs of
// the ladder against two estimates of gridding every level: the grid alone
// (a lower bound) and the coarsest level's jobs at every level.
// Nothing when the windows hold no ladder.
void print_ladders_table(std::FILE* out, const std::vector<campaign::Ladder>& ladders,
                         std::size_t grid_velocities = 0);

// "12 jobs: 10 succeeded, 1 failed, 1 timed-out"
std::string counts_text(const campaign::JobCounts& c);

}  // namespace splat::app
