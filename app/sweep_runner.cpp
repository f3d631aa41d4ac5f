#include "app/sweep_runner.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

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
      std::fprintf(stderr, "\r[%s%s] %d/%d jobs, %d running, %d failed, refinement +%d%s   ",
                   std::string(static_cast<std::size_t>(filled), '#').c_str(),
                   std::string(static_cast<std::size_t>(k_width - filled), ' ').c_str(), done,
                   total, p.counts.running, p.counts.failed + p.counts.timed_out, p.refinement_jobs,
                   time_left(p).c_str());
      std::fflush(stderr);
      drawn_ = true;
      return;
    }
    if (done == last_done_ && total == last_total_) return;
    if (done != total && now - last_line_ < std::chrono::seconds(1)) return;
    std::fprintf(stderr, "progress: %d/%d jobs finished (%d failed or timed out), round %d%s\n",
                 done, total, p.counts.failed + p.counts.timed_out, p.round, time_left(p).c_str());
    last_done_ = done;
    last_total_ = total;
    last_line_ = now;
  }
  void finish() {
    if (drawn_) std::fputc('\n', stderr);
  }

 private:
  // ", about 40 s left": the jobs queued or running, each charged what the
  // jobs of its parameter set and resolution took (campaign/progress.hpp).
  static std::string time_left(const campaign::Progress& p) {
    if (!p.seconds_left || p.counts.finished() >= p.counts.total()) return {};
    return ", about " + std::to_string(static_cast<long long>(*p.seconds_left + 0.5)) + " s left";
  }

  bool tty_;
  bool drawn_ = false;
  int last_done_ = -1;
  int last_total_ = -1;
  std::chrono::steady_clock::time_point last_line_{};
};

}  // namespace

int run_and_print(campaign::CampaignSpec spec, const SweepRun& o) {
  if (const auto executor = parse<campaign::ExecutorKind>(o.executor)) spec.executor = *executor;
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
  const auto start = std::chrono::steady_clock::now();
  const campaign::SweepReport r = campaign::run_sweep(store, spec, mo);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printer->finish();
  std::fprintf(stderr,
               "campaign %lld %s: %s; %d started here, %d reused from the store, %d refinement "
               "jobs; wall %.1f s on %d workers\n",
               static_cast<long long>(r.campaign_id), campaign::to_string(r.state),
               counts_text(r.counts).c_str(), r.jobs_started, r.grid.jobs_reused, r.refinement_jobs,
               wall, mo.workers);
  if (o.format == "json") {
    std::printf("%s\n", windows_json(r.windows).dump(2).c_str());
  } else {
    print_windows_table(stdout, r.windows);
    print_ladders_table(stdout,
                        campaign::resolution_ladders(
                            r.windows, campaign::cost_by_parameter_set(store, r.campaign_id)),
                        ladder_grid(spec));
  }
  return r.state == campaign::CampaignState::finished ? 0 : 3;
}

}  // namespace splat::app
