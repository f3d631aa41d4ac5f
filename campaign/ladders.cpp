#include "campaign/ladders.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "solver/core/richardson.hpp"

namespace splat::campaign {

using nlohmann::json;

namespace {

// Safety factor of the grid convergence index for a three-level study.
constexpr double k_gci_safety = 1.25;
// Largest relative difference of two refinement ratios still called constant.
constexpr double k_ratio_tolerance = 0.01;

LevelEdge level_edge(const json& bracket) {
  if (bracket.is_null() || !bracket.at("estimate").is_number()) return {};
  return {bracket.at("estimate").get<double>(), 0.5 * bracket.at("width").get<double>()};
}

std::optional<double> extrapolated(const std::vector<double>& levels,
                                   const std::vector<double>& f) {
  const std::size_t n = levels.size();
  if (n < 3 || !(levels[n - 3] > 0.0)) return std::nullopt;
  const double r1 = levels[n - 2] / levels[n - 3], r2 = levels[n - 1] / levels[n - 2];
  if (std::abs(r1 - r2) > k_ratio_tolerance * r2) return std::nullopt;
  const auto est = richardson(f[n - 3], f[n - 2], f[n - 1], r2);
  if (!est) return std::nullopt;
  return est->estimate;
}

// Richardson's observed order for the same three levels (only called after
// extrapolated() succeeded).
double observed_order(const std::vector<double>& levels, const std::vector<double>& f) {
  const std::size_t n = levels.size();
  return richardson(f[n - 3], f[n - 2], f[n - 1], levels[n - 1] / levels[n - 2])->order;
}

json optional_number(const std::optional<double>& x) {
  return x ? json(*x) : json(nullptr);
}

json edge_json(const LadderEdge& e) {
  json levels = json::array();
  for (const LevelEdge& l : e.levels) {
    levels.push_back(
        {{"estimate", optional_number(l.estimate)}, {"half_width", optional_number(l.half_width)}});
  }
  return {{"status", to_string(e.status)},
          {"value", optional_number(e.value)},
          {"error", optional_number(e.error)},
          {"order", optional_number(e.order)},
          {"levels", levels}};
}

std::string number(const std::optional<double>& x) {
  if (!x) return {};
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", *x);
  return buf;
}

std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

struct Classified {
  double velocity = 0.0;
  Verdict verdict = Verdict::other;
};

std::vector<Classified> classified(const std::vector<Sample>& samples) {
  std::vector<Classified> out;
  for (const Sample& s : samples) {
    if (s.verdict != Verdict::other) out.push_back({s.velocity, s.verdict});
  }
  std::sort(out.begin(), out.end(),
            [](const Classified& a, const Classified& b) { return a.velocity < b.velocity; });
  return out;
}

// What one level knows of the next coarser one: its velocities (ascending)
// and the velocities the fine level already ran.
struct SeedContext {
  std::vector<double> coarse;
  std::set<double> fine_run;
  std::vector<Classified> fine;
  bool run(double v) const { return fine_run.count(v) > 0; }
};

// The velocity of `candidates` nearest beyond v (above when `up`) that the
// fine level has not run.
std::optional<double> nearest_beyond(const SeedContext& c, const std::vector<double>& candidates,
                                     double v, bool up) {
  std::optional<double> best;
  for (double x : candidates) {
    if ((up ? x > v : x < v) && !c.run(x) && (!best || std::abs(x - v) < std::abs(*best - v)))
      best = x;
  }
  return best;
}

// Seeds of one closed coarse edge with bracket [lo, hi]; `below` is the
// verdict on its low side (rebound for a lower edge, stick for an upper one).
// The fine level runs the bracket's two ends; the guard band about its own
// edge comes from its own refinement, once that edge is bracketed.
std::vector<double> edge_seeds(const SeedContext& c, double lo, double hi, Verdict below) {
  std::vector<double> out;
  for (double v : {lo, hi}) {
    if (!c.run(v)) out.push_back(v);
  }
  if (!out.empty() || c.fine.empty()) return out;
  const double mid = 0.5 * (lo + hi);
  std::size_t k = 0;
  for (std::size_t i = 1; i < c.fine.size(); ++i) {
    if (std::abs(c.fine[i].velocity - mid) < std::abs(c.fine[k].velocity - mid)) k = i;
  }
  // Up from a `below` sample, down from the other, through fine samples of
  // the same verdict until the verdict changes. Past the bracket the walk
  // doubles its reach from the bracket's end (twice the bracket's width,
  // then twice the distance covered): where the next fine sample lies beyond
  // that reach, the reach is sampled (within the swept range).
  const Verdict start = c.fine[k].verdict;
  const bool up = start == below;
  const double anchor = up ? hi : lo, width = hi - lo;
  std::optional<double> next;
  for (std::size_t j = k;;) {
    const double reach = std::max(2.0 * std::abs(c.fine[j].velocity - anchor), 2.0 * width);
    const double target =
        std::clamp(up ? anchor + reach : anchor - reach, c.coarse.front(), c.coarse.back());
    const bool last = up ? j + 1 == c.fine.size() : j == 0;
    const std::size_t n = last ? j : (up ? j + 1 : j - 1);
    if (last || (up ? c.fine[n].velocity > target : c.fine[n].velocity < target)) {
      if (!c.run(target)) next = target;
      break;
    }
    if (c.fine[n].verdict != start) break;  // the fine edge is bracketed
    j = n;
  }
  if (next) out.push_back(*next);
  return out;
}

// Probes for a stick island the coarse level could not see on the rebound
// side of a closed coarse edge [lo, hi] (`below`: the verdict on its low
// side): the coarse velocities nearest to 2, 4, 8, 16, ... times `unit` (m/s)
// beyond the bracket on that side, up to the next coarse stick (another
// interval's territory), those the fine level has not run. A refined mesh
// can stick well below a coarse edge with rebounds in between (a measured
// case: docs/design.md, "Resolution ladders"): following the edge from the
// bracket stops at the first rebound.
std::vector<double> island_probes(const SeedContext& c, double lo, double hi, Verdict below,
                                  const std::vector<Classified>& coarse, double unit) {
  const bool down = below == Verdict::rebound;  // the rebound side is below a lower edge
  std::vector<double> side;                     // coarse velocities beyond, nearest first
  for (std::size_t i = 0; i < coarse.size(); ++i) {
    const Classified& s = coarse[down ? coarse.size() - 1 - i : i];
    if (down ? s.velocity >= lo : s.velocity <= hi) continue;
    if (s.verdict == Verdict::stick) break;
    side.push_back(s.velocity);
  }
  std::set<double> out;
  const double end = down ? lo : hi;
  for (double reach = 2.0 * unit; !side.empty() && unit > 0.0; reach *= 2.0) {
    const double target = down ? end - reach : end + reach;
    const auto nearest = std::min_element(side.begin(), side.end(), [&](double a, double b) {
      return std::abs(a - target) < std::abs(b - target);
    });
    if (!c.run(*nearest)) out.insert(*nearest);
    if (std::abs(side.back() - end) < reach) break;  // past the farthest candidate
  }
  return {out.begin(), out.end()};
}

}  // namespace

std::vector<double> level_seeds(const std::vector<Sample>& coarse, const std::vector<Sample>& fine,
                                double guard_band, const std::vector<double>& coarser) {
  SeedContext c;
  for (const Sample& s : coarse) c.coarse.push_back(s.velocity);
  std::sort(c.coarse.begin(), c.coarse.end());
  c.coarse.erase(std::unique(c.coarse.begin(), c.coarse.end()), c.coarse.end());
  if (c.coarse.empty()) return {};
  for (const Sample& s : fine) c.fine_run.insert(s.velocity);
  c.fine = classified(fine);
  const Window w = compute_window(coarse);
  const std::vector<Classified> coarse_classified = classified(coarse);
  // Half the coarse level's widest gap (its grid step), at least the band.
  double probe_unit = guard_band;
  for (std::size_t i = 1; i < c.coarse.size(); ++i) {
    probe_unit = std::max(probe_unit, 0.5 * (c.coarse[i] - c.coarse[i - 1]));
  }
  std::set<double> out;
  auto add = [&](const std::vector<double>& v) { out.insert(v.begin(), v.end()); };
  auto add_end = [&](double v) {
    if (!c.run(v)) out.insert(v);
  };
  if (w.intervals.empty()) {
    add_end(c.coarse.front());
    add_end(c.coarse.back());
  }
  for (const StickInterval& iv : w.intervals) {
    for (const auto& [edge, below] :
         {std::pair{&iv.lower, Verdict::rebound}, std::pair{&iv.upper, Verdict::stick}}) {
      if (!edge->closed()) {
        add_end(below == Verdict::rebound ? c.coarse.front() : c.coarse.back());
        add_end(edge->stick_velocity);
        continue;
      }
      const double a = *edge->rebound_velocity, b = edge->stick_velocity;
      const double lo = std::min(a, b), hi = std::max(a, b);
      const std::vector<double> walk = edge_seeds(c, lo, hi, below);
      add(walk.empty() ? island_probes(c, lo, hi, below, coarse_classified, probe_unit) : walk);
    }
  }
  // The fine level's own open edges (a stick at its outermost sample on
  // that side, inside the coarse range): the next coarse velocity beyond.
  const Window fw = compute_window(fine);
  // None there: the nearest velocity a coarser level ran beyond it.
  auto beyond = [&](double v, bool up) {
    if (const auto x = nearest_beyond(c, c.coarse, v, up)) return x;
    return nearest_beyond(c, coarser, v, up);
  };
  if (!fw.intervals.empty()) {
    if (!fw.intervals.front().lower.closed()) {
      if (const auto v = beyond(fw.intervals.front().lower.stick_velocity, false)) out.insert(*v);
    }
    if (!fw.intervals.back().upper.closed()) {
      if (const auto v = beyond(fw.intervals.back().upper.stick_velocity, true)) out.insert(*v);
    }
  }
  return {out.begin(), out.end()};
}

LadderStep coarse_to_fine_step(const std::vector<std::vector<Sample>>& levels,
                               const RefinementRule& rule) {
  for (std::size_t i = 0; i < levels.size(); ++i) {
    if (i > 0) {
      std::vector<double> coarser;
      for (std::size_t j = 0; j < i; ++j) {
        for (const Sample& s : levels[j]) coarser.push_back(s.velocity);
      }
      std::vector<double> seeds = level_seeds(levels[i - 1], levels[i], rule.guard_band, coarser);
      if (!seeds.empty()) return {i, std::move(seeds)};
    }
    // The guard band is sampled at the finest level only: an island a
    // coarser mesh shows beside its edge would only be followed, at every
    // finer level, by edges that mesh does not have.
    RefinementRule level_rule = rule;
    if (i + 1 < levels.size()) level_rule.guard_band = 0.0;
    std::vector<double> points = refinement_points(compute_window(levels[i]), level_rule);
    if (!points.empty()) return {i, std::move(points)};
  }
  return {};
}

const char* to_string(LadderStatus s) {
  switch (s) {
    case LadderStatus::extrapolated:
      return "extrapolated";
    case LadderStatus::not_converged:
      return "not-converged";
    case LadderStatus::single_level:
      return "single-level";
    case LadderStatus::open:
      return "open";
  }
  return "open";
}

LadderEdge ladder_edge(const std::vector<double>& levels, const std::vector<LevelEdge>& edges) {
  LadderEdge out;
  out.levels = edges;
  const std::size_t n = edges.size();
  if (n == 0 || n != levels.size()) return out;
  std::vector<double> f;
  for (const LevelEdge& e : edges) {
    if (!e.estimate) return out;  // open at some level
    f.push_back(*e.estimate);
  }
  const double w = edges.back().half_width.value_or(0.0);
  if (n == 1) {
    out.status = LadderStatus::single_level;
    out.value = f[0];
    out.error = w;
    return out;
  }
  if (const auto star = extrapolated(levels, f)) {
    out.status = LadderStatus::extrapolated;
    out.value = *star;
    out.error = k_gci_safety * std::abs(*star - f[n - 1]) + w;
    out.order = observed_order(levels, f);
    return out;
  }
  out.status = LadderStatus::not_converged;
  out.value = f[n - 1];
  out.error = std::abs(f[n - 1] - f[n - 2]) + w;
  return out;
}

std::vector<Ladder> resolution_ladders(const std::vector<WindowRecord>& windows,
                                       const std::map<std::string, LevelCost>& cost) {
  struct Member {
    double level;
    const WindowRecord* record;
  };
  // (campaign, pointer, params without it) -> members
  std::map<std::tuple<std::int64_t, std::string, std::string>, std::vector<Member>> groups;
  for (const WindowRecord& w : windows) {
    json params = json::parse(w.params);
    for (const std::string& p : k_resolution_pointers) {
      if (!params.is_object() || !params.contains(p) || !params.at(p).is_number()) continue;
      const double level = params.at(p).get<double>();
      params.erase(p);
      groups[{w.campaign_id, p, params.dump()}].push_back({level, &w});
      break;
    }
  }
  std::vector<Ladder> out;
  for (auto& [key, members] : groups) {
    if (members.size() < 2) continue;
    std::sort(members.begin(), members.end(),
              [](const Member& a, const Member& b) { return a.level < b.level; });
    Ladder l;
    l.campaign_id = std::get<0>(key);
    l.pointer = std::get<1>(key);
    l.params = json::parse(std::get<2>(key));
    std::vector<LevelEdge> lower, upper;
    for (const Member& m : members) {
      l.levels.push_back(m.level);
      const auto c = cost.find(m.record->params_key);
      l.cost.push_back(c == cost.end() ? LevelCost{} : c->second);
      const json doc = json::parse(m.record->window);
      lower.push_back(level_edge(doc.at("critical_bracket")));
      upper.push_back(level_edge(doc.at("maximum_bracket")));
    }
    l.critical = ladder_edge(l.levels, lower);
    l.maximum = ladder_edge(l.levels, upper);
    out.push_back(std::move(l));
  }
  return out;
}

json to_json(const Ladder& l) {
  json cost = json::array();
  for (const LevelCost& c : l.cost)
    cost.push_back({{"jobs", c.jobs}, {"job_seconds", c.job_seconds}});
  return {{"campaign_id", l.campaign_id},
          {"pointer", l.pointer},
          {"params", l.params},
          {"levels", l.levels},
          {"cost", cost},
          {"critical", edge_json(l.critical)},
          {"maximum", edge_json(l.maximum)}};
}

std::string ladders_csv(const std::vector<Ladder>& ladders) {
  std::string out =
      "campaign_id,params,pointer,level,jobs,job_seconds [s],critical_level [m/s],"
      "critical_half_width [m/s],maximum_level [m/s],maximum_half_width [m/s],"
      "critical_status,critical_value [m/s],critical_error [m/s],maximum_status,"
      "maximum_value [m/s],maximum_error [m/s]\n";
  for (const Ladder& l : ladders) {
    for (std::size_t i = 0; i < l.levels.size(); ++i) {
      const LevelEdge& lo = l.critical.levels[i];
      const LevelEdge& hi = l.maximum.levels[i];
      out += std::to_string(l.campaign_id) + "," + quoted(l.params.dump()) + "," + l.pointer + "," +
             number(l.levels[i]) + "," + std::to_string(l.cost[i].jobs) + "," +
             number(l.cost[i].job_seconds) + "," + number(lo.estimate) + "," +
             number(lo.half_width) + "," + number(hi.estimate) + "," + number(hi.half_width) + "," +
             to_string(l.critical.status) + "," + number(l.critical.value) + "," +
             number(l.critical.error) + "," + to_string(l.maximum.status) + "," +
             number(l.maximum.value) + "," + number(l.maximum.error) + "\n";
    }
  }
  return out;
}

}  // namespace splat::campaign
