// The Slurm executor: one round of a campaign's queued jobs as one Slurm job
// array submitted with `sbatch` (argument vector, no shell), at most
// `max_array_size` tasks (jobs packed several per task when there are more),
// at most `throttle` running at once. Each task runs its jobs one after
// another under `timeout` (the per-job time limit) and leaves, per job, the
// usual stdout.json / stderr.txt and an `exit_code` file ("CODE START END")
// in the job's folder under the shared jobs directory; the manager ingests
// those files as they appear. A task Slurm ended without a job's exit_code
// file gives the job its state from Slurm's task state (TIMEOUT -> timed-out,
// CANCELLED -> cancelled, anything else -> failed): a timed-out task reports
// exit code 0, so the state, not the exit code, decides. Cancellation runs
// `scancel` on the array and records the cancelled jobs ourselves, since
// Slurm keeps no trace of a pending task it cancelled.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "campaign/slurm_options.hpp"
#include "campaign/spec.hpp"
#include "campaign/store.hpp"

namespace splat::campaign {

struct SlurmRound {
  Store& store;
  std::int64_t campaign_id;
  const CampaignSpec& spec;
  std::filesystem::path program;   // job program, on a path the nodes see
  std::filesystem::path jobs_dir;  // shared directory
  SlurmOptions options;
  std::string owner;
  std::function<bool()> cancel_requested;
  std::function<void()> on_job_end;
};

struct SlurmRoundResult {
  int jobs_submitted = 0;
  bool cancelled = false;
};

// Claims every queued job of the campaign, submits them, and returns when
// each has ended (or the campaign was cancelled). Submission failures end
// the jobs as failed with sbatch's message.
SlurmRoundResult run_slurm_round(SlurmRound& round);

}  // namespace splat::campaign
