// Resolution ladders: a campaign's windows at several resolutions of the same
// parameter set, read together so each edge comes with its error from
// resolution. Pure functions over WindowRecords; no store, no processes.
//
// A ladder is a group of parameter sets that differ only in the value of one
// resolution field (k_resolution_pointers, e.g. elements_across 8, 12, 16).
// Per level it lists each edge's bracket midpoint and half-width, and the
// cost of the level. Each edge then gets a value and an error:
// - extrapolated: the three finest levels at a constant ratio r (to 1 %)
//   converge monotonically (Richardson, solver/core/richardson.hpp, observed
//   order p >= 0.5); value f*, error = 1.25 |f* - f_finest| (Roache's grid
//   convergence index with safety factor 1.25, "Verification and Validation
//   in Computational Science and Engineering", 1998, ch. 5) plus the finest
//   bracket's half-width;
// - not-converged: otherwise (two levels, ratios not constant, edges that
//   move back and forth or apart); value the finest level's, error the move
//   between the finest two plus the finest bracket's half-width;
// - single-level: one level only; value its midpoint, error its half-width;
// - open: the edge is open (or missing) at some level; no value.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "campaign/store.hpp"
#include "campaign/windows.hpp"

namespace splat::campaign {

// Fields read as resolution levels (JSON pointers of `fields` axes).
inline const std::vector<std::string> k_resolution_pointers = {
    "/particle_impact/particle/elements_across"};

enum class LadderStatus { extrapolated, not_converged, single_level, open };

const char* to_string(LadderStatus s);

// One edge at one level: bracket midpoint and half-width, m/s; empty = open.
struct LevelEdge {
  std::optional<double> estimate;
  std::optional<double> half_width;
};

struct LadderEdge {
  std::vector<LevelEdge> levels;  // one per ladder level, coarse to fine
  LadderStatus status = LadderStatus::open;
  std::optional<double> value;  // m/s
  std::optional<double> error;  // m/s
  std::optional<double> order;  // observed order of convergence, - (extrapolated only)
};

// Jobs of one level and the sum of their wall times.
struct LevelCost {
  int jobs = 0;
  double job_seconds = 0.0;  // s
};

struct Ladder {
  std::int64_t campaign_id = 0;
  std::string pointer;         // the resolution field
  nlohmann::json params;       // the parameter set without the resolution field
  std::vector<double> levels;  // resolution values, coarse to fine (ascending)
  std::vector<LevelCost> cost;
  LadderEdge critical;
  LadderEdge maximum;
};

// Estimate of one edge from its levels (see the header comment).
LadderEdge ladder_edge(const std::vector<double>& levels, const std::vector<LevelEdge>& edges);

// The ladders of a set of windows: one per group of parameter sets that differ
// only in a resolution field and have at least two levels. `cost` maps a
// parameter set's params_key to its cost (missing: zero).
std::vector<Ladder> resolution_ladders(const std::vector<WindowRecord>& windows,
                                       const std::map<std::string, LevelCost>& cost = {});

// Coarse to fine: the finer levels of a ladder run only near the edges the
// next coarser level found. `coarse` and `fine` are the samples of two
// neighbouring levels (same parameters otherwise); the coarse velocities are
// the candidates. For each edge of the coarse window:
// - its bracket's two ends, where the fine level has not run them;
// - once those ran: the fine sample nearest the bracket is followed through
//   samples of its verdict away from it until the opposite verdict turns up
//   (the fine edge); if it does not, a velocity at twice the distance
//   covered from the bracket (the edge moved under refinement);
// - once the fine edge is bracketed: island probes on the coarse edge's
//   rebound side, spaced from half the coarse grid step or `guard_band`
//   (m/s), whichever is wider.
// An open coarse edge gets the swept range's end on its side and the coarse
// level's outermost stick there; an edge open at the fine level while coarse
// samples lie beyond it gets the nearest of them, or, with none there, the
// nearest of `coarser` (the velocities every coarser level ran: an edge
// that moved past the coarse level's samples under refinement). Empty: the
// fine level has every edge of the coarse one bracketed (bisection, guard
// bands and islands are then refinement_points' work on the fine window).
std::vector<double> level_seeds(const std::vector<Sample>& coarse, const std::vector<Sample>& fine,
                                double guard_band, const std::vector<double>& coarser = {});

// What a ladder runs next: the coarsest level whose refinement is not done
// (refinement_points of its window under `rule`, the guard band at the
// finest level only, or, above the coarsest, level_seeds from the level
// below with the rule's guard band), with its velocities. Empty velocities:
// every level done.
struct LadderStep {
  std::size_t level = 0;  // index into the levels, coarse to fine
  std::vector<double> velocities;
};
LadderStep coarse_to_fine_step(const std::vector<std::vector<Sample>>& levels,
                               const RefinementRule& rule);

nlohmann::json to_json(const Ladder& l);

// One CSV line per ladder and level, with the edge estimates of the ladder on
// every line; units in the header.
std::string ladders_csv(const std::vector<Ladder>& ladders);

}  // namespace splat::campaign
