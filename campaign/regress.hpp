// Regression runs: a campaign's windows compared with a stored baseline.
//
// Baseline file (JSON, written by `splat regress --update`):
//   {"campaign": NAME, "solver_version": "...", "created": "unix time",
//    "tolerances": {"velocity": 0.01},          // m/s, for window edges
//    "windows": [{"params": {...}, "critical_velocity": x | null,
//                 "maximum_velocity": y | null, "intervals": n,
//                 "sticks": n, "rebounds": n, "unclassified": n}, ...],
//    "ladders": [{"params": {...}, "pointer": "/particle_impact/...",
//                 "levels": [8, 16],
//                 "critical": {"status": "not-converged", "value": x | null,
//                              "error": e | null},
//                 "maximum": {...}}, ...]}      // only where the windows form
//                                                // resolution ladders
// A parameter set drifts when it is missing, when an edge appears,
// disappears or moves by more than the velocity tolerance, when the number
// of sticking intervals changes, or when the number of jobs that are neither
// stick nor rebound changes (a newly unstable job is a regression). A
// resolution ladder (campaign/ladders.hpp) drifts when it is missing, when
// an edge's status changes, or when its value or its error from resolution
// appears, disappears or moves by more than the velocity tolerance.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "campaign/store.hpp"

namespace splat::campaign {

struct RegressionCheck {
  std::string params;  // canonical JSON of the parameter set
  std::string figure;  // critical_velocity, maximum_velocity, intervals, unclassified, present
  std::string baseline;
  std::string current;
  bool ok = true;
};

struct RegressionReport {
  std::vector<RegressionCheck> checks;
  bool drift() const;
};

nlohmann::json make_baseline(const std::string& campaign_name,
                             const std::vector<WindowRecord>& windows, double velocity_tolerance);

// Throws std::invalid_argument naming the field when the baseline is malformed.
RegressionReport compare_to_baseline(const nlohmann::json& baseline,
                                     const std::vector<WindowRecord>& windows);

}  // namespace splat::campaign
