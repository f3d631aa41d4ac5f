// The campaign manager's own cost per job (target: under 50 ms): a sweep of
// real two-mass jobs (`splat run`, milliseconds each) on one worker slot,
// minus the wall time of the child processes themselves (as the store
// records it, fork to reap). What is left is claiming, writing the job's
// folder, parsing and storing the summary, windows, and dispatch latency.
// Counters: jobs, child_ms (mean per job), overhead_ms (per job),
// sweep_ms (per job, both together).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "campaign/manager.hpp"

namespace {

using namespace splat::campaign;
namespace fs = std::filesystem;

void BM_manager_overhead_per_job(benchmark::State& state) {
  const int jobs = static_cast<int>(state.range(0));
  const int workers = static_cast<int>(state.range(1));
  std::vector<double> speeds;
  for (int i = 0; i < jobs; ++i) speeds.push_back(0.1 + 0.01 * i);
  const nlohmann::json doc = {
      {"name", "overhead"},
      {"base_scene", std::string(SPLAT_SOURCE_DIR) + "/scenes/verification/two_mass.json"},
      {"velocity", {{"values", speeds}}}};
  const CampaignSpec spec = read_campaign(doc);
  double overhead = 0.0, child = 0.0, total = 0.0;
  int n = 0;
  for (auto _ : state) {
    const fs::path dir = fs::temp_directory_path() / ("splat_bench_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    double child_sum = 0.0;
    double wall = 0.0;
    {
      Store store(dir / "b.db");
      ManagerOptions o;
      o.workers = workers;
      o.job_program = SPLAT_BINARY;
      const auto t0 = std::chrono::steady_clock::now();
      const SweepReport r = run_sweep(store, spec, o);
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      for (const PointStatus& p : store.points(r.campaign_id)) {
        child_sum += store.job(p.point.job_hash)->wall_seconds.value_or(0.0);
      }
      if (r.counts.succeeded != jobs) state.SkipWithError("not every job succeeded");
    }
    fs::remove_all(dir);
    // With w slots the children overlap: the manager's share is the wall
    // time not covered by children, per job.
    total += wall;
    child += child_sum;
    overhead += wall - child_sum / workers;
    n += jobs;
  }
  state.counters["jobs"] = jobs;
  state.counters["child_ms"] = 1e3 * child / n;
  state.counters["overhead_ms"] = 1e3 * overhead / n;
  state.counters["sweep_ms"] = 1e3 * total / n;
}

BENCHMARK(BM_manager_overhead_per_job)
    ->Args({100, 1})
    ->Args({100, 2})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
