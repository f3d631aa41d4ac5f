// Cost of one two-mass run (thesis 3.5.1.1: M = 1, m = 2, V0 = 1, G_c A = 0.2,
// default time step, no output), the unit the campaign manager pays per job
// on top of process start-up; and the steps per CPU second.
//   build/bench/bench_two_mass --benchmark_repetitions=10
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <limits>

#include "solver/two_mass/two_mass_model.hpp"

namespace {

using namespace splat;

void two_mass_run(benchmark::State& state, double k, double sigma_c) {
  TwoMassSpec s;
  s.M = 1.0;
  s.m = 2.0;
  s.k = k;
  s.V0 = 1.0;
  s.area = 1.0;
  s.adhesion.G_c = 0.2;
  s.adhesion.sigma_c = sigma_c;
  TimeSpec t;
  t.end_time = 100.0;
  long long steps = 0;
  for (auto _ : state) {
    const TwoMassRun r = integrate_two_mass(s, t);
    steps += r.steps;
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps_per_run"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kAvgIterations);
  state.counters["steps_per_second"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK_CAPTURE(two_mass_run, k0_cap0_5, 0.0, 0.5)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(two_mass_run, k0_5_cap0_05, 0.5, 0.05)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(two_mass_run, k0_5_cap5, 0.5, 5.0)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
