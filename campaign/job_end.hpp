// What the end of one job's child process means for the job (shared by the
// local and Slurm executors; the table is in campaign/README.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "campaign/process.hpp"
#include "campaign/spec.hpp"
#include "campaign/store.hpp"

namespace splat::campaign {

struct JobEnd {
  JobState state = JobState::failed;
  std::string reason;
  bool retry = false;  // a transient failure with retries left: queue it again
  // The host could not hold the job's output (exit 74, EX_IOERR: a full
  // disk): no fault of the job. The local manager queues it again and ends
  // the run; Slurm rounds retry it like a transient failure.
  bool host_fault = false;
  std::optional<ResultRecord> result;
  std::optional<int> threads;
};

// `dir` holds the job's stdout.json and stderr.txt.
JobEnd interpret(const JobRecord& job, const ProcessResult& pr, const std::filesystem::path& dir,
                 const JobOptions& opts);

}  // namespace splat::campaign
