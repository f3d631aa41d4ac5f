// Options of the Slurm executor (campaign/slurm.hpp).
#pragma once

#include <string>
#include <vector>

namespace splat::campaign {

struct SlurmOptions {
  int throttle = 8;                      // array tasks running at once (--array=...%throttle)
  int max_array_size = 1000;             // tasks per array; more jobs are packed several per task
  double poll_seconds = 0.5;             // how often squeue and the result files are looked at
  std::vector<std::string> sbatch_args;  // extra sbatch arguments, e.g. --partition=debug
};

}  // namespace splat::campaign
