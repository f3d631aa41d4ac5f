// Jobs adaptive refinement needs against a uniform grid that finds the same
// window edges to the same width (the target: at most 40 %), and the
// rounds it takes at 1, 2 and 4 points per round (the benchmark's argument:
// refinement.points_per_round, 1 = bisection).
// The classifier is a known window [v_lo, v_hi] (stick inside, rebound
// outside), so the counts are those of any physics with one window; the
// integration test campaign_sweep.* checks the same on real two-mass jobs.
// Counters printed per case: refine_jobs (coarse grid + refinement), rounds
// (refinement rounds), uniform_jobs (grid at step = tolerance over the same
// range), ratio.
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

struct Refined {
  int jobs = 0;
  int rounds = 0;
};

Refined refine(const Case& c, int points_per_round) {
  std::vector<Sample> samples;
  for (int i = 0;; ++i) {
    const double v = c.v_min + i * c.coarse_step;
    if (v > c.v_max + 1e-9) break;
    samples.push_back(truth(v, c));
  }
  const RefinementRule rule{c.tolerance, 0.0, points_per_round};
  int rounds = 0;
  for (;; ++rounds) {
    const std::vector<double> next = refinement_points(compute_window(samples), rule);
    if (next.empty()) break;
    for (double v : next) samples.push_back(truth(v, c));
  }
  return {static_cast<int>(samples.size()), rounds};
}

void run_case(benchmark::State& state, const Case& c) {
  Refined r;
  for (auto _ : state) {
    r = refine(c, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(r);
  }
  const int uniform = static_cast<int>(std::floor((c.v_max - c.v_min) / c.tolerance)) + 1;
  state.counters["refine_jobs"] = r.jobs;
  state.counters["rounds"] = r.rounds;
  state.counters["uniform_jobs"] = uniform;
  state.counters["ratio"] = static_cast<double>(r.jobs) / uniform;
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

BENCHMARK(BM_refine_cold_spray_1ms)->Arg(1)->Arg(2)->Arg(4);
BENCHMARK(BM_refine_cold_spray_10ms)->Arg(1)->Arg(2)->Arg(4);
BENCHMARK(BM_refine_two_mass_1mms)->Arg(1)->Arg(2)->Arg(4);

}  // namespace

BENCHMARK_MAIN();
