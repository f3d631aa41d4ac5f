#include "campaign/windows.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace splat::campaign {

using nlohmann::json;

std::optional<double> Edge::width() const {
  if (!rebound_velocity) return std::nullopt;
  return std::abs(*rebound_velocity - stick_velocity);
}

std::optional<double> Edge::estimate() const {
  if (!rebound_velocity) return std::nullopt;
  return 0.5 * (*rebound_velocity + stick_velocity);
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::stick:
      return "stick";
    case Verdict::rebound:
      return "rebound";
    case Verdict::other:
      return "other";
  }
  return "other";
}

Window compute_window(std::vector<Sample> samples) {
  std::stable_sort(samples.begin(), samples.end(),
                   [](const Sample& a, const Sample& b) { return a.velocity < b.velocity; });
  Window w;
  if (samples.empty()) return w;
  w.min_velocity = samples.front().velocity;
  w.max_velocity = samples.back().velocity;
  for (const Sample& s : samples) w.sampled.push_back(s.velocity);
  std::vector<std::size_t> classified;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    if (s.verdict == Verdict::stick) ++w.sticks;
    if (s.verdict == Verdict::rebound) ++w.rebounds;
    if (s.verdict == Verdict::other) {
      w.unclassified.push_back(s);
    } else {
      classified.push_back(i);
    }
  }
  auto others_between = [&](std::size_t lo, std::size_t hi) {  // exclusive indices
    std::vector<Sample> out;
    for (std::size_t i = lo; i < hi; ++i) {
      if (samples[i].verdict == Verdict::other) out.push_back(samples[i]);
    }
    return out;
  };

  for (std::size_t c = 0; c < classified.size();) {
    if (samples[classified[c]].verdict != Verdict::stick) {
      ++c;
      continue;
    }
    std::size_t e = c;  // last classified stick of this run
    while (e + 1 < classified.size() && samples[classified[e + 1]].verdict == Verdict::stick) ++e;
    const std::size_t first = classified[c];
    const std::size_t last = classified[e];
    StickInterval iv;
    iv.lower.stick_velocity = samples[first].velocity;
    if (c > 0) {
      const std::size_t r = classified[c - 1];
      iv.lower.rebound_velocity = samples[r].velocity;
      iv.lower.unclassified = others_between(r + 1, first);
    } else {
      iv.lower.unclassified = others_between(0, first);
    }
    iv.upper.stick_velocity = samples[last].velocity;
    if (e + 1 < classified.size()) {
      const std::size_t r = classified[e + 1];
      iv.upper.rebound_velocity = samples[r].velocity;
      iv.upper.unclassified = others_between(last + 1, r);
    } else {
      iv.upper.unclassified = others_between(last + 1, samples.size());
    }
    iv.unclassified = others_between(first + 1, last);
    w.intervals.push_back(std::move(iv));
    c = e + 1;
  }
  if (!w.intervals.empty()) {
    w.critical_velocity = w.intervals.front().lower.estimate();
    w.maximum_velocity = w.intervals.back().upper.estimate();
  }
  return w;
}

namespace {

// A gap between neighbouring samples of an open bracket (m/s) and the points
// this round puts into it, at most `cap`.
struct Gap {
  double lo = 0.0;
  double hi = 0.0;
  int points = 0;
  int cap = 1;
  double part() const { return (hi - lo) / (points + 1); }
};

// The gaps wider than `tolerance` of every closed edge's bracket wider than
// it, ascending; each bracket's widest gap (the first of equals) holds its
// bisection point.
std::vector<Gap> bracket_gaps(const Window& w, double tolerance) {
  std::vector<Gap> out;
  auto add = [&](const Edge& e) {
    if (!e.closed() || *e.width() <= tolerance) return;
    std::vector<double> v{*e.rebound_velocity, e.stick_velocity};
    for (const Sample& s : e.unclassified) v.push_back(s.velocity);
    std::sort(v.begin(), v.end());
    std::optional<std::size_t> widest;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
      const double width = v[i + 1] - v[i];
      if (!(width > tolerance)) continue;
      const int cap = std::max(1, static_cast<int>(std::ceil(width / tolerance)) - 1);
      out.push_back({v[i], v[i + 1], 0, cap});
      if (!widest || width > out[*widest].hi - out[*widest].lo) widest = out.size() - 1;
    }
    if (widest) out[*widest].points = 1;
  };
  for (const StickInterval& iv : w.intervals) {
    add(iv.lower);
    add(iv.upper);
  }
  return out;
}

// Gives points, up to `total` in all, one at a time to the gap whose parts
// are widest (the first of equals) among those below their cap.
void spread(std::vector<Gap>& gaps, int total) {
  int given = 0;
  for (const Gap& g : gaps) given += g.points;
  for (; given < total; ++given) {
    Gap* best = nullptr;
    for (Gap& g : gaps) {
      if (g.points < g.cap && (best == nullptr || g.part() > best->part())) best = &g;
    }
    if (best == nullptr) return;
    ++best->points;
  }
}

// The points that split a gap into points + 1 equal parts (one point: the
// midpoint, exactly 0.5 (lo + hi)).
void split_points(const Gap& g, std::vector<double>& out) {
  const int n = g.points + 1;
  for (int j = 1; j < n; ++j) out.push_back(((n - j) * g.lo + j * g.hi) / n);
}

bool is_split(const std::vector<Gap>& gaps, double lo, double hi) {
  return std::any_of(gaps.begin(), gaps.end(),
                     [&](const Gap& g) { return g.points > 0 && g.lo == lo && g.hi == hi; });
}

// Midpoints of the parts inside (lo - band, hi + band) of the gaps between
// consecutive sampled velocities, where such a part is wider than
// `tolerance` and is not a gap `split` already puts points into.
void guard_band_points(const Window& w, double lo, double hi, double band, double tolerance,
                       const std::vector<Gap>& split, std::vector<double>& out) {
  const std::vector<double>& v = w.sampled;
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    // The part of the gap inside the band: a long gap that only reaches into
    // the band is split there, not at its far-away midpoint.
    const double a = std::max(v[i], lo - band), b = std::min(v[i + 1], hi + band);
    if (b - a > tolerance && !is_split(split, a, b)) out.push_back(0.5 * (a + b));
  }
}

}  // namespace

std::vector<double> refinement_points(const Window& window, const RefinementRule& rule) {
  std::vector<Gap> gaps = bracket_gaps(window, rule.tolerance);
  spread(gaps, rule.points_per_round);
  std::vector<double> out;
  for (const Gap& g : gaps) split_points(g, out);
  for (const StickInterval& iv : window.intervals) {
    for (const Edge* e : {&iv.lower, &iv.upper}) {
      if (!(rule.guard_band > 0.0) || !e->closed()) continue;
      const double a = std::min(*e->rebound_velocity, e->stick_velocity);
      const double b = std::max(*e->rebound_velocity, e->stick_velocity);
      guard_band_points(window, a, b, rule.guard_band, rule.tolerance, gaps, out);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

json optional_number(const std::optional<double>& x) {
  return x ? json(*x) : json(nullptr);
}

json samples_json(const std::vector<Sample>& v) {
  json a = json::array();
  for (const Sample& s : v) a.push_back(to_json(s));
  return a;
}

}  // namespace

json to_json(const Sample& s) {
  return {{"velocity", s.velocity}, {"verdict", to_string(s.verdict)}, {"label", s.label}};
}

json to_json(const Edge& e) {
  return {{"estimate", optional_number(e.estimate())},
          {"rebound_velocity", optional_number(e.rebound_velocity)},
          {"stick_velocity", e.stick_velocity},
          {"width", optional_number(e.width())},
          {"unclassified", samples_json(e.unclassified)}};
}

json to_json(const Window& w) {
  json intervals = json::array();
  for (const StickInterval& iv : w.intervals) {
    intervals.push_back({{"lower", to_json(iv.lower)},
                         {"upper", to_json(iv.upper)},
                         {"unclassified", samples_json(iv.unclassified)}});
  }
  json out = {
      {"critical_velocity", optional_number(w.critical_velocity)},
      {"maximum_velocity", optional_number(w.maximum_velocity)},
      {"critical_bracket",
       w.intervals.empty() ? json(nullptr) : to_json(w.intervals.front().lower)},
      {"maximum_bracket", w.intervals.empty() ? json(nullptr) : to_json(w.intervals.back().upper)},
      {"intervals", intervals},
      {"sticks", w.sticks},
      {"rebounds", w.rebounds},
      {"unclassified", samples_json(w.unclassified)},
      {"swept_range", {w.min_velocity, w.max_velocity}}};
  return out;
}

}  // namespace splat::campaign
