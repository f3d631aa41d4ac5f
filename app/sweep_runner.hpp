// Running a campaign from the command line: the progress display, Ctrl-C
// and SIGTERM as cancel, and the window table at the end; shared by
// `splat sweep` (a campaign file) and `splat window` (a campaign it builds).
#pragma once

#include <string>
#include <vector>

#include "campaign/spec.hpp"

namespace splat::app {

struct SweepRun {
  std::string db = "splat.db";
  int workers = 2;
  std::string executor;  // local or slurm; empty: the campaign's
  bool rerun = false;
  std::string job_program;
  std::string format = "table";  // table or json
  int slurm_throttle = 8;
  int slurm_max_array = 1000;
  std::vector<std::string> sbatch_args;
};

// Runs (or resumes) the campaign in the store o.db and prints its windows
// (table with the resolution ladders, or JSON). Exit code: 0 the campaign
// finished, 3 it was cancelled.
int run_and_print(campaign::CampaignSpec spec, const SweepRun& o);

}  // namespace splat::app
