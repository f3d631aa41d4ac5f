// Jobs adaptive refinement needs against a uniform grid that finds the same
// window edges to the same width (the target: at most 40 %).
// The classifier is a known window [v_lo, v_hi] (stick inside, rebound
// outside), so the counts are those of any physics with one window; the
// integration test campaign_sweep.* checks the same on real two-mass jobs.
// Counters printed per case: refine_jobs (coarse grid + bisections),
// uniform_jobs (grid at step = tolerance over the same range), ratio.
#include <benchmark/benchmark.h>

#include <cmath>

#include "campaign/windows.hpp"

namespace {

using namespace splat::campaign;

struct Case {
  double v_min, v_max, coarse_step, tolerance, v_lo, v_hi;
};

Sample truth(double v, const Case& c) {
  Sample s;
  s.velocity = v;
  s.verdict = (v >= c.v_lo && v <= c.v_hi) ? Verdict::stick : Verdict::rebound;
  return s;
}

int refine_jobs(const Case& c) {
  std::vector<Sample> samples;
  for (int i = 0;; ++i) {
    const double v = c.v_min + i * c.coarse_step;
    if (v > c.v_max + 1e-9) break;
    samples.push_back(truth(v, c));
  }
  for (;;) {
    const std::vector<double> next = refinement_points(compute_window(samples), c.tolerance);
    if (next.empty()) break;
    for (double v : next) samples.push_back(truth(v, c));
  }
  return static_cast<int>(samples.size());
}

void run_case(benchmark::State& state, const Case& c) {
  int jobs = 0;
  for (auto _ : state) {
    jobs = refine_jobs(c);
    benchmark::DoNotOptimize(jobs);
  }
  const int uniform = static_cast<int>(std::floor((c.v_max - c.v_min) / c.tolerance)) + 1;
  state.counters["refine_jobs"] = jobs;
  state.counters["uniform_jobs"] = uniform;
  state.counters["ratio"] = static_cast<double>(jobs) / uniform;
}

// Cold-spray scale: 100-1200 m/s, coarse 100 m/s, edges to 1 m/s.
void BM_refine_cold_spray_1ms(benchmark::State& s) {
  run_case(s, {100, 1200, 100, 1.0, 437.3, 812.9});
}
// Coarser tolerance: 10 m/s.
void BM_refine_cold_spray_10ms(benchmark::State& s) {
  run_case(s, {100, 1200, 100, 10.0, 437.3, 812.9});
}
// Two-mass scale (the demo campaign): 0.1-2 m/s, coarse 0.1, edge to 0.001.
void BM_refine_two_mass_1mms(benchmark::State& s) {
  run_case(s, {0.1, 2.0, 0.1, 0.001, 0.0, 0.7746});
}

BENCHMARK(BM_refine_cold_spray_1ms);
BENCHMARK(BM_refine_cold_spray_10ms);
BENCHMARK(BM_refine_two_mass_1mms);

}  // namespace

BENCHMARK_MAIN();
