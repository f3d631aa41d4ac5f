#include "app/window_table.hpp"

#include <algorithm>
#include <cmath>

#include "campaign/window_rows.hpp"

namespace splat::app {

using nlohmann::json;

namespace {

std::string number(const json& x, const char* fmt = "%.6g") {
  if (!x.is_number()) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, x.get<double>());
  return buf;
}

// "0.775 [0.77, 0.78]" for a closed edge; an open edge says how far the
// sticks reach ("above 800": the last stick; samples beyond it unclassified
// are listed in the last column), or the swept range's end without a stick.
std::string edge_text(const json& edge, bool lower, const json& range) {
  if (edge.is_null()) return "-";
  if (edge.at("estimate").is_null()) {
    const json& stick = edge.at("stick_velocity");
    const json& bound = stick.is_number() ? stick : range.at(lower ? 0 : 1);
    return (lower ? "below " : "above ") + number(bound);
  }
  const double a = edge.at("rebound_velocity").get<double>();
  const double b = edge.at("stick_velocity").get<double>();
  std::string s = number(edge.at("estimate")) + " [" + number(json(std::min(a, b))) + ", " +
                  number(json(std::max(a, b))) + "]";
  if (!edge.at("unclassified").empty()) {
    s += " (" + std::to_string(edge.at("unclassified").size()) + " unclassified inside)";
  }
  return s;
}

std::string unclassified_text(const json& list) {
  std::string s;
  for (const json& u : list) {
    if (!s.empty()) s += ", ";
    s += u.at("label").get<std::string>() + "@" + number(u.at("velocity"));
  }
  return s.empty() ? "-" : s;
}

}  // namespace

json windows_json(const std::vector<campaign::WindowRecord>& windows) {
  return campaign::window_rows(windows);
}

void print_windows_table(std::FILE* out, const std::vector<campaign::WindowRecord>& windows) {
  std::fprintf(out, "%-48s %-34s %-34s %9s  %s\n", "parameters", "critical velocity m/s",
               "maximum velocity m/s", "intervals", "not stick/rebound");
  for (const json& row : windows_json(windows)) {
    const json& range = row.at("swept_range");
    std::string params = row.at("params").dump();
    if (params == "{}") params = "(base scene)";
    std::fprintf(out, "%-48s %-34s %-34s %9zu  %s\n", params.c_str(),
                 edge_text(row.at("critical_bracket"), true, range).c_str(),
                 edge_text(row.at("maximum_bracket"), false, range).c_str(),
                 row.at("intervals").size(), unclassified_text(row.at("unclassified")).c_str());
    if (row.at("intervals").size() > 1) {
      for (const json& iv : row.at("intervals")) {
        std::fprintf(out, "%-48s   interval %s .. %s\n", "",
                     edge_text(iv.at("lower"), true, range).c_str(),
                     edge_text(iv.at("upper"), false, range).c_str());
      }
    }
  }
}

void print_windows_csv(std::FILE* out, const std::vector<campaign::WindowRecord>& windows) {
  std::fputs(campaign::window_rows_csv(windows).c_str(), out);
}

namespace {

std::string level_text(const campaign::LevelEdge& e) {
  if (!e.estimate) return "open";
  return number(json(*e.estimate)) + " +- " + number(json(e.half_width.value_or(0.0)));
}

std::string ladder_edge_text(const campaign::LadderEdge& e) {
  if (!e.value) return "open at some level (no value)";
  std::string s = number(json(*e.value)) + " +- " + number(json(e.error.value_or(0.0))) + " (" +
                  to_string(e.status);
  if (e.order) s += ", observed order " + number(json(*e.order), "%.2f");
  return s + ")";
}

// The ladder's jobs against every level gridded: at the tolerance over the
// grid's range, and on the campaign's grid (at least the grid at every
// level, about the coarsest level's jobs at every level).
void print_ladder_saving(std::FILE* out, const campaign::Ladder& l, const LadderGrid& grid) {
  if (grid.velocities == 0 || l.cost.empty()) return;
  int jobs = 0;
  for (const campaign::LevelCost& c : l.cost) jobs += c.jobs;
  const double levels = static_cast<double>(l.levels.size());
  std::fprintf(out, "  jobs %d; every level gridded:", jobs);
  if (grid.tolerance > 0.0 && grid.to > grid.from) {
    const double per_level = std::floor((grid.to - grid.from) / grid.tolerance + 1e-9) + 1.0;
    std::fprintf(out, " at the %s m/s tolerance over %s-%s m/s %.0f (this ladder %.0f %%);",
                 number(json(grid.tolerance)).c_str(), number(json(grid.from)).c_str(),
                 number(json(grid.to)).c_str(), per_level * levels,
                 100.0 * jobs / (per_level * levels));
  }
  const double grid_only = static_cast<double>(grid.velocities) * levels;
  const double as_coarsest = std::max(grid_only, l.cost.front().jobs * levels);
  std::fprintf(out,
               " on the %zu velocities at least %.0f, about %.0f refined as the coarsest "
               "(this ladder %.0f %%)\n",
               grid.velocities, grid_only, as_coarsest, 100.0 * jobs / as_coarsest);
}

}  // namespace

LadderGrid ladder_grid(const campaign::CampaignSpec& spec) {
  LadderGrid g;
  g.velocities = spec.velocities.size();
  if (spec.velocities.empty()) return g;
  const auto [lo, hi] = std::minmax_element(spec.velocities.begin(), spec.velocities.end());
  g.from = *lo;
  g.to = *hi;
  if (spec.refinement) g.tolerance = spec.refinement->tolerance;
  return g;
}

void print_ladders_table(std::FILE* out, const std::vector<campaign::Ladder>& ladders,
                         const LadderGrid& grid) {
  for (const campaign::Ladder& l : ladders) {
    std::string params = l.params.dump();
    if (params == "{}") params = "(base scene)";
    std::fprintf(out, "\nresolution ladder %s, parameters %s\n", l.pointer.c_str(), params.c_str());
    std::fprintf(out, "  %-8s %-24s %-24s %6s %10s\n", "level", "critical m/s", "maximum m/s",
                 "jobs", "job s");
    for (std::size_t i = 0; i < l.levels.size(); ++i) {
      std::fprintf(out, "  %-8s %-24s %-24s %6d %10.1f\n", number(json(l.levels[i])).c_str(),
                   level_text(l.critical.levels[i]).c_str(),
                   level_text(l.maximum.levels[i]).c_str(), l.cost[i].jobs, l.cost[i].job_seconds);
    }
    std::fprintf(out, "  critical velocity %s\n", ladder_edge_text(l.critical).c_str());
    std::fprintf(out, "  maximum velocity  %s\n", ladder_edge_text(l.maximum).c_str());
    print_ladder_saving(out, l, grid);
  }
}

std::string counts_text(const campaign::JobCounts& c) {
  std::string s = std::to_string(c.total()) + " jobs:";
  bool first = true;
  auto part = [&](int n, const char* what) {
    if (n == 0) return;
    s += (first ? " " : ", ") + std::to_string(n) + " " + what;
    first = false;
  };
  part(c.succeeded, "succeeded");
  part(c.failed, "failed");
  part(c.timed_out, "timed-out");
  part(c.cancelled, "cancelled");
  part(c.running, "running");
  part(c.queued, "queued");
  return s;
}

}  // namespace splat::app
