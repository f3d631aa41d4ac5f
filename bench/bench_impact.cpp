// Time to a verdict of the shipped impact example (scenes/impact_al_al.json:
// Al on Al, R 12.5 um, 500 m/s, thesis 3.5.3 adhesion, axisymmetric FE, adaptive
// end time), on one thread, without output: at the scene's 8 elements across
// and at the schema's default 12. Target (issue 5): a verdict in under 20 s
// on one core at the default resolution. Prints seconds per run, steps and
// ns per element-step.
//   build/bench/bench_impact --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"

namespace {

using namespace splat;

void impact_verdict(benchmark::State& state) {
  const int across = static_cast<int>(state.range(0));
  const LoadedScene loaded =
      load_scene(std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes" / "impact_al_al.json",
                 {"/particle_impact/particle/elements_across=" + std::to_string(across)});
  long long steps = 0, element_steps = 0;
  std::string outcome;
  for (auto _ : state) {
    SimulationOptions options;
    options.threads = 1;
    Simulation sim(loaded.scene, loaded.resolved, options);
    const RunSummary s = sim.run();
    long long elements = 0;
    for (const BodySummary& b : s.bodies) elements += b.elements;
    steps += s.steps;
    element_steps += s.steps * elements;
    outcome = to_string(s.outcome);
  }
  state.SetLabel(outcome);
  state.counters["steps"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kAvgIterations);
  state.counters["ns_per_element_step"] =
      benchmark::Counter(static_cast<double>(element_steps) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(impact_verdict)->Arg(8)->Arg(12)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK_MAIN();
