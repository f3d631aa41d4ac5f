// Cost of one material-point stress update (Johnson-Cook with adiabatic
// heating, damage, linear EOS), in ns per update; the median over 10
// repetitions is the figure to quote.
//   build/bench/bench_material_update --benchmark_repetitions=10
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <vector>

#include "solver/input/material_io.hpp"
#include "solver/material/damage.hpp"
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

// The shear-failure criterion's largest shear stress (max_shear_stress,
// from the deviator's invariants) against Eigen's closed-form eigenvalues,
// which it replaced: ns per call over 4,096 random stresses.
std::vector<Mat3> random_stresses() {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e8, 1e8);
  std::vector<Mat3> v(4096);
  for (Mat3& s : v) {
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) s(i, j) = s(j, i) = u(rng);
  }
  return v;
}
void BM_max_shear_stress_invariants(benchmark::State& state) {
  const std::vector<Mat3> v = random_stresses();
  for (auto _ : state) {
    for (const Mat3& s : v) benchmark::DoNotOptimize(max_shear_stress(s));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long long>(v.size()));
}
void BM_max_shear_stress_eigen_direct(benchmark::State& state) {
  const std::vector<Mat3> v = random_stresses();
  for (auto _ : state) {
    for (const Mat3& s : v) {
      Eigen::SelfAdjointEigenSolver<Mat3> es;
      es.computeDirect(s, Eigen::EigenvaluesOnly);
      benchmark::DoNotOptimize(0.5 * (es.eigenvalues()(2) - es.eigenvalues()(0)));
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long long>(v.size()));
}

BENCHMARK(BM_update_plastic_cu);
BENCHMARK(BM_update_plastic_cu_damage);
BENCHMARK(BM_update_plastic_al_shear_damage);
BENCHMARK(BM_update_elastic_cu);
BENCHMARK(BM_max_shear_stress_invariants);
BENCHMARK(BM_max_shear_stress_eigen_direct);

}  // namespace

BENCHMARK_MAIN();
