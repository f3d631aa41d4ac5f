// Read-only queries the API server needs beyond store.hpp: paged job lists of
// a campaign, the campaigns a job belongs to, timing figures for time-left
// estimates, and store-wide job statistics for /metrics. They read through
// the Store's per-thread reader connection and write nothing.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "campaign/ladders.hpp"
#include "campaign/store.hpp"

namespace splat::campaign {

// One point of a campaign with its job's figures.
struct CampaignJobRow {
  CampaignPoint point;
  JobState state = JobState::queued;
  int attempts = 0;
  std::optional<double> started_at;    // unix time, s
  std::optional<double> finished_at;   // unix time, s
  std::optional<double> wall_seconds;  // s
  std::string exit_reason;
  std::optional<std::string> outcome;  // the result's outcome, when there is one
  // What the job's scene expanded into (set at submission, so also for
  // queued jobs): the model (particle_impact.model.name, "two-mass" for a
  // two-mass scene) and the particle body's resolution, elements across its
  // radius (FE) or particle spacing (SPH).
  std::optional<std::string> model;
  std::optional<std::int64_t> elements_across;  // -
  std::optional<double> spacing;                // m
};

// The campaign's points ordered by (parameter set, velocity), optionally only
// those whose job is in `state`, skipping `offset` and returning at most `limit`.
std::vector<CampaignJobRow> campaign_jobs(Store& store, std::int64_t campaign_id,
                                          std::optional<JobState> state, std::int64_t offset,
                                          std::int64_t limit);

// The points (of any campaign) that use this job, with their campaign ids.
struct JobUse {
  std::int64_t campaign_id = 0;
  CampaignPoint point;
};
std::vector<JobUse> job_uses(Store& store, const std::string& job_hash);

// Wall-time figures of a campaign's finished jobs (for a time-left estimate).
struct CampaignTiming {
  int timed_jobs = 0;         // finished jobs with a wall time
  double wall_seconds = 0.0;  // their summed wall time, s
};
CampaignTiming campaign_timing(Store& store, std::int64_t campaign_id);

// Per parameter set (params_key) of a campaign: its points and the summed
// wall time of their jobs (a job shared by two points counts twice).
std::map<std::string, LevelCost> cost_by_parameter_set(Store& store, std::int64_t campaign_id);

// Store-wide: jobs by state, and the wall times of every finished job (s).
JobCounts all_job_counts(Store& store);
std::vector<double> all_wall_seconds(Store& store);

// Campaigns ordered by id descending, ids below `before_id` (0 = no bound),
// at most `limit`.
std::vector<CampaignRecord> campaigns_page(Store& store, std::int64_t before_id,
                                           std::int64_t limit);

}  // namespace splat::campaign
