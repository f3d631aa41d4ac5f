// splat sweep CAMPAIGN.json [--db FILE] [--workers N] [--executor local|slurm] [--rerun]
// Runs (or resumes) a campaign (schemas/campaign.schema.json): expands it
// into jobs, runs each as a child `splat run` on N local worker slots (or as
// Slurm job arrays, campaign/slurm.hpp; the jobs folder must be shared),
// refines the window edges if asked, and stores everything in the SQLite
// file. Shows a progress bar on a terminal (plain lines otherwise) and ends
// with the window table. Ctrl-C (SIGINT) or SIGTERM cancels: running jobs
// are stopped, queued ones never start; run the same command to resume.
// Exit code: 0 the campaign finished (failed jobs are in the table), 3 it
// was cancelled, 2 bad input.
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/sweep_runner.hpp"
#include "campaign/spec.hpp"

namespace splat::app {

namespace {

struct SweepOptions {
  std::string campaign;
  SweepRun run;
};

int run_sweep_command(const SweepOptions& o) {
  return run_and_print(campaign::load_campaign(o.campaign), o.run);
}

}  // namespace

void register_sweep(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub = app.add_subcommand("sweep", "Run or resume a campaign and print its windows");
  sub->add_option("campaign", o->campaign, "Campaign JSON file")->required();
  sub->add_option("--db", o->run.db, "SQLite store")->capture_default_str();
  sub->add_option("--workers", o->run.workers, "Jobs run at once")->capture_default_str();
  sub->add_option("--executor", o->run.executor, "local or slurm (default: the campaign's)")
      ->check(CLI::IsMember(all_names<campaign::ExecutorKind>()));
  sub->add_flag("--rerun", o->run.rerun, "Recompute jobs even when results are stored");
  sub->add_option("--job-program", o->run.job_program,
                  "Program run for each job (default: this splat)");
  sub->add_option("--slurm-throttle", o->run.slurm_throttle, "Slurm: array tasks running at once")
      ->capture_default_str();
  sub->add_option("--slurm-max-array", o->run.slurm_max_array,
                  "Slurm: tasks per array (more jobs are packed per task)")
      ->capture_default_str();
  sub->add_option("--sbatch-arg", o->run.sbatch_args,
                  "Slurm: extra sbatch argument, e.g. --sbatch-arg=--partition=debug");
  sub->add_option("--format", o->run.format, "Window output: table or json")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  commands.emplace_back(sub, [o] { return run_sweep_command(*o); });
}

}  // namespace splat::app
