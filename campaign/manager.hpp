// Running a campaign: the grid's jobs, then refinement rounds, on a pool of
// local worker slots, everything recorded in the store as it happens.
//
// The job contract: a job is a fully resolved scene; running it is the child
// process `PROGRAM run DIR/scene.json --json --out DIR/out --threads T`
// (argument vector, no shell) whose stdout is the result summary
// (schemas/result.schema.json). Exit code 0 finished, 3 ended otherwise
// (the summary's outcome says why), 2 bad input, 75 transient failure
// (EX_TEMPFAIL). Exit 75 and death by a signal (kill -9, the OOM killer) are
// retried up to `retries` times; any other exit code or no summary is a
// failure. A job that outlives its time limit is stopped and recorded
// timed-out.
//
// Resume: jobs a dead manager left running go back to the queue at start;
// finished jobs are never redone (unless a rerun is asked for); a job is
// stored only when it has ended, so a killed manager loses nothing stored.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "campaign/slurm_options.hpp"
#include "campaign/spec.hpp"
#include "campaign/store.hpp"
#include "campaign/windows.hpp"

namespace splat::campaign {

struct Progress {
  std::int64_t campaign_id = 0;
  JobCounts counts;
  int refinement_jobs = 0;  // points refinement has added so far
  int round = 0;            // 0 = the grid, then one per refinement round
  // s, the jobs queued or running now, estimated from those that ran, finer
  // resolution levels charged more (campaign/progress.hpp); none before a
  // job has finished. Refinement may add jobs.
  std::optional<double> seconds_left;
};

struct ManagerOptions {
  int workers = 2;
  std::filesystem::path job_program;             // empty = this executable, found at each launch
  std::filesystem::path jobs_dir;                // empty = "<db file>.jobs"
  std::string solver_version;                    // empty = solver_version_string()
  SceneResolver resolver;                        // empty = splat_scene_resolver()
  bool rerun = false;                            // recompute even jobs with stored results
  const std::atomic<bool>* interrupt = nullptr;  // set (e.g. by SIGINT) to cancel
  std::function<void(const Progress&)> on_progress;
  double poll_seconds = 0.1;  // how often the campaign's state is checked for a cancel request
  std::optional<ExecutorKind> executor;  // overrides the spec's executor
  SlurmOptions slurm;
};

struct SweepReport {
  std::int64_t campaign_id = 0;
  CampaignState state = CampaignState::active;
  JobCounts counts;
  AddPointsStats grid;       // what adding the grid did (created / reused / requeued)
  int refinement_jobs = 0;   // refinement points of the campaign
  int jobs_started = 0;      // child processes this manager started
  int orphans_requeued = 0;  // jobs a dead manager had left running
  std::vector<WindowRecord> windows;
};

// A run ended by a fault of the host or the store (a full disk: a job's
// output or the store could not be written). The jobs stored so far are
// kept, the unfinished ones are queued again (or requeued by the next
// manager of this host) and the campaign stays `active`, to be resumed.
class RunStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs (or resumes) the campaign to its end or to cancellation. Throws
// RunStopped or SqliteError when the host or the store fails under it,
// having stopped and joined its workers first.
SweepReport run_sweep(Store& store, const CampaignSpec& spec, const ManagerOptions& options);

// Classification of one stored point for windows: stick / rebound from the
// summary's outcome of a succeeded job, anything else `other` with the
// outcome or job state as its label.
Sample classify(const PointStatus& p);

// The window of every parameter set of the campaign from what is stored.
std::vector<WindowRecord> compute_windows(Store& store, std::int64_t campaign_id);

}  // namespace splat::campaign
