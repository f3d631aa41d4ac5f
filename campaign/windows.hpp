// Deposition windows: pure functions over the stick/rebound sequence of one
// parameter set along impact velocity. No store, no processes.
//
// The sticking intervals are the maximal runs of `stick` among the
// classified samples (stick or rebound) sorted by velocity. Each interval
// has a lower and an upper edge, bracketed by the nearest rebound and stick
// samples; an edge with no rebound beyond it is open (the interval reaches
// the end of the swept range). Samples that are neither stick nor rebound
// (unstable, error, failed, timed-out, cancelled, ...) never count as
// either: they are listed inside the bracket or interval they fall in.
// Between two sticks they do not split the interval (nothing says the
// particle rebounds there) but are listed in the interval's `unclassified`.
//
// critical velocity = estimate of the lower edge of the first interval,
// maximum velocity  = estimate of the upper edge of the last interval;
// each estimate is the bracket's midpoint (error at most half its width) and
// is empty when the edge is open. A stick island narrower than the sampling
// and lying between two rebound samples cannot be seen unless refinement
// samples the guard band around each edge (refinement_points).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

namespace splat::campaign {

enum class Verdict { stick, rebound, other };

struct Sample {
  double velocity = 0.0;  // m/s
  Verdict verdict = Verdict::other;
  std::string label;  // what happened: the outcome ("stick", "unstable", ...) or the job state
};

struct Edge {
  std::optional<double> rebound_velocity;  // m/s; empty = open (no rebound beyond the stick)
  double stick_velocity = 0.0;             // m/s; the stick sample nearest the edge
  std::vector<Sample> unclassified;        // samples strictly inside the bracket
  bool closed() const { return rebound_velocity.has_value(); }
  std::optional<double> width() const;     // m/s, |rebound - stick| when closed
  std::optional<double> estimate() const;  // m/s, bracket midpoint when closed
};

struct StickInterval {
  Edge lower;
  Edge upper;
  std::vector<Sample> unclassified;  // neither stick nor rebound, between the interval's sticks
};

struct Window {
  std::vector<StickInterval> intervals;
  std::optional<double> critical_velocity;  // m/s
  std::optional<double> maximum_velocity;   // m/s
  int sticks = 0;
  int rebounds = 0;
  std::vector<Sample> unclassified;  // every sample that is neither
  double min_velocity = 0.0;         // swept range, m/s
  double max_velocity = 0.0;
  std::vector<double> sampled;  // every sample's velocity, ascending, m/s
};

// The window of one parameter set. `samples` need not be sorted.
Window compute_window(std::vector<Sample> samples);

// How refinement samples a window: the bracket width at which an edge counts
// as found, the band about each edge sampled to that width too, and how many
// new velocities a round may spread over the brackets of one window.
struct RefinementRule {
  double tolerance = 0.0;    // m/s
  double guard_band = 0.0;   // m/s; 0 = the brackets only
  int points_per_round = 1;  // 1 = bisection
};

// Velocities to run next to sharpen the window's closed edges. For each edge
// whose bracket is wider than `tolerance`, the midpoint of the largest gap
// between the bracket's ends and the unclassified samples inside it (so an
// unstable job at a midpoint does not stall the bisection). With
// `points_per_round` k > 1 the round has up to k such points in all (at
// least the one per bracket): each further point goes to the gap of an open
// bracket whose parts are widest, a gap given m points is split into m + 1
// equal parts, and no gap gets more than ceil(gap / tolerance) - 1 (parts
// no narrower than needed); ties go to the lower velocity. With a
// `guard_band`, also the midpoint of every gap wider than `tolerance`
// between samples within guard_band of a closed edge's bracket: stick and
// rebound alternate near an edge (an island narrower than the grid hides
// between two samples of the same verdict), so the band around each edge is
// sampled to the tolerance too, and an island found there becomes an
// interval of its own; a bracket gap that is split has its split points
// instead of that midpoint. Ascending; empty when nothing is left to sample.
std::vector<double> refinement_points(const Window& window, const RefinementRule& rule);

nlohmann::json to_json(const Sample& s);
nlohmann::json to_json(const Edge& e);
nlohmann::json to_json(const Window& w);

const char* to_string(Verdict v);

}  // namespace splat::campaign
