// Cost of one material-point stress update (Johnson-Cook with adiabatic
// heating, damage, linear EOS), in ns per update; the median over 10
// repetitions is the figure to quote.
//   build/bench/bench_material_update --benchmark_repetitions=10
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "solver/input/material_io.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update.hpp"

namespace {

using namespace splat;

// A point in plastic flow at 1e6 /s: every update takes the radial return
// (or, with `alternate`, an elastic point loaded and unloaded in turn).
void run_updates(benchmark::State& state, const char* material, double strain_step, bool damage,
                 bool alternate = false) {
  const Material m = load_material(material);
  ModelSwitches sw;
  sw.damage = damage;
  const MaterialConstants mc = derive_constants(m);
  const double dt = 1e-9;
  Mat3 d = Mat3::Zero();
  d(0, 0) = -strain_step;
  d(1, 1) = d(2, 2) = 0.5 * strain_step;
  PointState st = initial_point_state(m, sw, 300.0, 0.0);
  const PointState start = st;
  long long iterations = 0;
  for (auto _ : state) {
    const PointUpdateResult r = update_point(m, mc, sw, st, d, st.J, dt, 1e-6);
    iterations += r.iterations;
    if (st.eps_p > 1.0) st = start;  // stay in the hardening range, far from melt
    if (alternate) d = -d;           // load and unload: stays elastic
    benchmark::DoNotOptimize(st);
  }
  state.counters["return_iterations"] =
      benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
}

void BM_update_plastic_cu(benchmark::State& s) {
  run_updates(s, "cu-thesis", 1e-3, false);
}
void BM_update_plastic_cu_damage(benchmark::State& s) {
  run_updates(s, "cu-thesis", 1e-3, true);
}
void BM_update_plastic_al_shear_damage(benchmark::State& s) {
  run_updates(s, "al-thesis", 1e-3, true);
}
void BM_update_elastic_cu(benchmark::State& s) {
  run_updates(s, "cu-thesis", 1e-5, false, true);
}

BENCHMARK(BM_update_plastic_cu);
BENCHMARK(BM_update_plastic_cu_damage);
BENCHMARK(BM_update_plastic_al_shear_damage);
BENCHMARK(BM_update_elastic_cu);

}  // namespace

BENCHMARK_MAIN();
