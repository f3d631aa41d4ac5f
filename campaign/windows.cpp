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

// Midpoints of the parts inside (lo - band, hi + band) of the gaps between
// consecutive sampled velocities, where such a part is wider than
// `tolerance`.
void guard_band_points(const Window& w, double lo, double hi, double band, double tolerance,
                       std::vector<double>& out) {
  const std::vector<double>& v = w.sampled;
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    // The part of the gap inside the band: a long gap that only reaches into
    // the band is split there, not at its far-away midpoint.
    const double a = std::max(v[i], lo - band), b = std::min(v[i + 1], hi + band);
    if (b - a > tolerance) out.push_back(0.5 * (a + b));
  }
}

}  // namespace

std::vector<double> refinement_points(const Window& window, double tolerance, double guard_band) {
  std::vector<double> out;
  auto refine = [&](const Edge& e) {
    if (!e.closed() || *e.width() <= tolerance) return;
    std::vector<double> v{*e.rebound_velocity, e.stick_velocity};
    for (const Sample& s : e.unclassified) v.push_back(s.velocity);
    std::sort(v.begin(), v.end());
    double best_gap = 0.0;
    double best_mid = 0.0;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
      const double gap = v[i + 1] - v[i];
      if (gap > best_gap) {
        best_gap = gap;
        best_mid = 0.5 * (v[i] + v[i + 1]);
      }
    }
    if (best_gap > tolerance) out.push_back(best_mid);
  };
  for (const StickInterval& iv : window.intervals) {
    refine(iv.lower);
    refine(iv.upper);
    for (const Edge* e : {&iv.lower, &iv.upper}) {
      if (!(guard_band > 0.0) || !e->closed()) continue;
      const double a = std::min(*e->rebound_velocity, e->stick_velocity);
      const double b = std::max(*e->rebound_velocity, e->stick_velocity);
      guard_band_points(window, a, b, guard_band, tolerance, out);
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
