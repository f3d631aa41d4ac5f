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
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/window_table.hpp"
#include "campaign/manager.hpp"
#include "campaign/queries.hpp"
#include "solver/input/schema.hpp"

namespace splat::app {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) {
  g_interrupted = true;
}

struct SweepOptions {
  std::string campaign;
  std::string db = "splat.db";
  int workers = 2;
  std::string executor;
  bool rerun = false;
  std::string job_program;
  std::string format = "table";
  int slurm_throttle = 8;
  int slurm_max_array = 1000;
  std::vector<std::string> sbatch_args;
};

void install_interrupt_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

// A progress bar on a terminal, a plain line at most once a second otherwise.
class ProgressPrinter {
 public:
  ProgressPrinter() : tty_(isatty(STDERR_FILENO) != 0) {}
  void operator()(const campaign::Progress& p) {
    const int done = p.counts.finished();
    const int total = p.counts.total();
    const auto now = std::chrono::steady_clock::now();
    if (tty_) {
      constexpr int k_width = 30;
      const int filled = total > 0 ? k_width * done / total : 0;
      std::fprintf(stderr, "\r[%s%s] %d/%d jobs, %d running, %d failed, refinement +%d   ",
                   std::string(static_cast<std::size_t>(filled), '#').c_str(),
                   std::string(static_cast<std::size_t>(k_width - filled), ' ').c_str(), done,
                   total, p.counts.running, p.counts.failed + p.counts.timed_out,
                   p.refinement_jobs);
      std::fflush(stderr);
      drawn_ = true;
      return;
    }
    if (done == last_done_ && total == last_total_) return;
    if (done != total && now - last_line_ < std::chrono::seconds(1)) return;
    std::fprintf(stderr, "progress: %d/%d jobs finished (%d failed or timed out), round %d\n", done,
                 total, p.counts.failed + p.counts.timed_out, p.round);
    last_done_ = done;
    last_total_ = total;
    last_line_ = now;
  }
  void finish() {
    if (drawn_) std::fputc('\n', stderr);
  }

 private:
  bool tty_;
  bool drawn_ = false;
  int last_done_ = -1;
  int last_total_ = -1;
  std::chrono::steady_clock::time_point last_line_{};
};

int run_sweep_command(const SweepOptions& o) {
  campaign::CampaignSpec spec = campaign::load_campaign(o.campaign);
  if (!o.executor.empty()) {
    spec.executor =
        o.executor == "slurm" ? campaign::ExecutorKind::slurm : campaign::ExecutorKind::local;
  }
  if (o.workers < 1) throw InputError(std::vector<SchemaViolation>{{"--workers", "must be >= 1"}});
  campaign::Store store(o.db);
  install_interrupt_handler();
  campaign::ManagerOptions mo;
  mo.workers = o.workers;
  mo.executor = spec.executor;
  mo.slurm.throttle = o.slurm_throttle;
  mo.slurm.max_array_size = o.slurm_max_array;
  mo.slurm.sbatch_args = o.sbatch_args;
  mo.rerun = o.rerun;
  mo.interrupt = &g_interrupted;
  if (!o.job_program.empty()) mo.job_program = o.job_program;
  auto printer = std::make_shared<ProgressPrinter>();
  mo.on_progress = [printer](const campaign::Progress& p) { (*printer)(p); };
  std::fprintf(stderr, "campaign '%s' in %s: %zu velocities x %zu parameter sets, %d workers\n",
               spec.name.c_str(), o.db.c_str(), spec.velocities.size(),
               campaign::parameter_sets(spec).size(), mo.workers);
  const campaign::SweepReport r = campaign::run_sweep(store, spec, mo);
  printer->finish();
  std::fprintf(stderr,
               "campaign %lld %s: %s; %d started here, %d reused from the store, %d refinement "
               "jobs\n",
               static_cast<long long>(r.campaign_id), campaign::to_string(r.state),
               counts_text(r.counts).c_str(), r.jobs_started, r.grid.jobs_reused,
               r.refinement_jobs);
  if (o.format == "json") {
    std::printf("%s\n", windows_json(r.windows).dump(2).c_str());
  } else {
    print_windows_table(stdout, r.windows);
    print_ladders_table(stdout,
                        campaign::resolution_ladders(
                            r.windows, campaign::cost_by_parameter_set(store, r.campaign_id)));
  }
  return r.state == campaign::CampaignState::finished ? 0 : 3;
}

}  // namespace

void register_sweep(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub = app.add_subcommand("sweep", "Run or resume a campaign and print its windows");
  sub->add_option("campaign", o->campaign, "Campaign JSON file")->required();
  sub->add_option("--db", o->db, "SQLite store")->capture_default_str();
  sub->add_option("--workers", o->workers, "Jobs run at once")->capture_default_str();
  sub->add_option("--executor", o->executor, "local or slurm (default: the campaign's)")
      ->check(CLI::IsMember({"local", "slurm"}));
  sub->add_flag("--rerun", o->rerun, "Recompute jobs even when results are stored");
  sub->add_option("--job-program", o->job_program,
                  "Program run for each job (default: this splat)");
  sub->add_option("--slurm-throttle", o->slurm_throttle, "Slurm: array tasks running at once")
      ->capture_default_str();
  sub->add_option("--slurm-max-array", o->slurm_max_array,
                  "Slurm: tasks per array (more jobs are packed per task)")
      ->capture_default_str();
  sub->add_option("--sbatch-arg", o->sbatch_args,
                  "Slurm: extra sbatch argument, e.g. --sbatch-arg=--partition=debug");
  sub->add_option("--format", o->format, "Window output: table or json")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
  commands.emplace_back(sub, [o] { return run_sweep_command(*o); });
}

}  // namespace splat::app
