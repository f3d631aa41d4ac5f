#include "campaign/progress.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace splat::campaign {

namespace {

using nlohmann::json;

struct Level {
  double n = 0.0;     // resolution of the level
  double cost = 0.0;  // s, mean wall time of its finished jobs
};

std::optional<double> level_of(const json& params, const ParameterAxis* ladder) {
  if (!ladder || !params.is_object()) return std::nullopt;
  const auto it = params.find(ladder->name);
  if (it == params.end() || !it->is_number() || !(it->get<double>() > 0.0)) return std::nullopt;
  return it->get<double>();
}

// The parameters without the ladder's: the levels of one family share it.
std::string family_of(const json& params, const ParameterAxis* ladder) {
  json rest = params;
  if (ladder && rest.is_object()) rest.erase(ladder->name);
  return canonical_text(rest);
}

// Cost at resolution n from a family's measured levels (sorted by n, not
// empty): the nearest measured level below n (else the coarsest) scaled by
// (n / n_ref)^p, p from the two finest measured levels.
double scaled_cost(const std::vector<Level>& measured, double n) {
  double p = k_default_cost_exponent;
  if (measured.size() >= 2) {
    const Level& a = measured[measured.size() - 2];
    const Level& b = measured.back();
    if (a.cost > 0.0 && b.cost > 0.0)
      p = std::clamp(std::log(b.cost / a.cost) / std::log(b.n / a.n), 1.0, 6.0);
  }
  const Level* ref = &measured.front();
  for (const Level& l : measured) {
    if (l.n <= n) ref = &l;
  }
  return ref->cost * std::pow(n / ref->n, p);
}

}  // namespace

std::optional<WorkLeft> work_left(const std::vector<ParameterSetLoad>& sets,
                                  const ParameterAxis* ladder) {
  int finished = 0, pending = 0;
  double wall = 0.0;
  std::vector<json> params(sets.size());
  std::map<std::string, std::vector<Level>> families;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const ParameterSetLoad& s = sets[k];
    finished += s.finished;
    pending += s.pending;
    wall += s.wall_seconds;
    params[k] = json::parse(s.params, nullptr, false);
    const auto n = level_of(params[k], ladder);
    if (s.finished > 0 && n) {
      families[family_of(params[k], ladder)].push_back({*n, s.wall_seconds / s.finished});
    }
  }
  if (finished == 0 || pending == 0) return std::nullopt;
  for (auto& [key, levels] : families) {
    std::sort(levels.begin(), levels.end(),
              [](const Level& a, const Level& b) { return a.n < b.n; });
  }
  const double overall = wall / finished;
  WorkLeft w;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const ParameterSetLoad& s = sets[k];
    if (s.pending == 0) continue;
    double cost = overall;
    const auto n = level_of(params[k], ladder);
    const auto family = n ? families.find(family_of(params[k], ladder)) : families.end();
    if (s.finished > 0) {
      cost = s.wall_seconds / s.finished;
    } else if (family != families.end()) {
      cost = scaled_cost(family->second, *n);
    }
    w.job_seconds += s.pending * cost;
    w.longest_job = std::max(w.longest_job, cost);
  }
  return w;
}

double seconds_left(const WorkLeft& w, int workers) {
  return std::max(w.job_seconds / std::max(1, workers), w.longest_job);
}

}  // namespace splat::campaign
