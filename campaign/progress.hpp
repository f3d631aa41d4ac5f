// How long a campaign still has to run, from what its jobs took so far.
//
// Jobs of one parameter set cost about the same, but jobs of a finer
// resolution level cost far more (an axisymmetric FE job at 32 elements
// across about 10x one at 16: elements x steps grow as N^3). So each
// parameter set's pending jobs are charged the mean wall time of its own
// finished jobs; a set none of whose jobs has finished yet is charged from
// the nearest level of the same parameters that has, scaled by
// (N / N_ref)^p, with p observed between two finished levels of those
// parameters (clamped to [1, 6]) or k_default_cost_exponent before two have
// finished; a set with neither is charged the mean of all finished jobs.
#pragma once

#include <optional>
#include <vector>

#include "campaign/spec.hpp"
#include "campaign/store.hpp"

namespace splat::campaign {

// Cost of a job against the resolution N (elements or spacings across the
// particle radius) before two levels have been measured: an axisymmetric
// model has N^2 elements and takes N steps (CFL), so N^3.
constexpr double k_default_cost_exponent = 3.0;

struct WorkLeft {
  double job_seconds = 0.0;  // s, the pending jobs' estimated wall times added
  double longest_job = 0.0;  // s, the longest of them
};

// The pending jobs' estimated wall times (above); nullopt while no job has
// finished (nothing to estimate from) or none is pending. `ladder` is the
// campaign's resolution ladder axis, or null.
std::optional<WorkLeft> work_left(const std::vector<ParameterSetLoad>& sets,
                                  const ParameterAxis* ladder);

// Wall time left with `workers` jobs side by side: the job seconds shared
// among the workers, but never less than the longest job.
double seconds_left(const WorkLeft& w, int workers);

}  // namespace splat::campaign
