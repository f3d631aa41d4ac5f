// Cost of one material-point stress update (Johnson-Cook with adiabatic
// heating, damage, linear EOS), in ns per update; the median over 10
// repetitions is the figure to quote.
//   build/bench/bench_material_update --benchmark_repetitions=10
//     --benchmark_report_aggregates_only=true
// The BM_points_* pairs compare update_point called point by point with
// update_points (SIMD lanes, point_update_batch.hpp) on the same 1024 points,
// in CPU ns per point; the ratio scalar / batch is printed at the end.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "solver/input/material_io.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update.hpp"
#include "solver/material/point_update_batch.hpp"

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

// 1024 copper points at 300-400 K with slightly different strain increments
// (so the lanes take different return iterations), loaded at 1e6 /s
// (plastic; reset to the start when eps_p passes 1) or loaded and unloaded in
// turn (elastic). One benchmark iteration updates all points once; the
// figure is CPU ns per point.
void run_points(benchmark::State& state, bool batch, bool plastic, bool damage) {
  const Material m = load_material("cu-thesis");
  ModelSwitches sw;
  sw.damage = damage;
  const MaterialConstants mc = derive_constants(m);
  const double dt = 1e-9;
  const std::size_t n = 1024;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PointState> states(n), start(n);
  std::vector<int> index(n);
  std::vector<Mat3> d(n);
  std::vector<double> J_new(n), length(n, 1e-6);
  const double step = plastic ? 1e-3 : 1e-5;
  for (std::size_t k = 0; k < n; ++k) {
    states[k] = start[k] = initial_point_state(m, sw, 300.0 + 100.0 * u(rng), 0.0);
    index[k] = static_cast<int>(k);
    const double e = step * (0.8 + 0.4 * u(rng));
    d[k] = Mat3::Zero();
    d[k](0, 0) = -e;
    d[k](1, 1) = d[k](2, 2) = 0.5 * e;
    d[k](0, 1) = d[k](1, 0) = 0.1 * e * u(rng);
    J_new[k] = 1.0;
  }
  std::vector<PointUpdateResult> out(n);
  long long iterations = 0;
  for (auto _ : state) {
    if (batch) {
      update_points(m, mc, sw, states.data(), index.data(), n, d.data(), J_new.data(), dt,
                    length.data(), out.data());
    } else {
      for (std::size_t k = 0; k < n; ++k)
        out[k] = update_point(m, mc, sw, states[k], d[k], J_new[k], dt, length[k]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      iterations += out[k].iterations;
      if (states[k].eps_p > 1.0) states[k] = start[k];
      if (!plastic) d[k] = -d[k];
    }
    benchmark::DoNotOptimize(states.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["ns_per_point"] = benchmark::Counter(
      static_cast<double>(state.iterations() * n),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
  state.counters["return_iterations"] = benchmark::Counter(
      static_cast<double>(iterations) / static_cast<double>(n), benchmark::Counter::kAvgIterations);
}

void BM_points_plastic_scalar(benchmark::State& s) {
  run_points(s, false, true, false);
}
void BM_points_plastic_batch(benchmark::State& s) {
  run_points(s, true, true, false);
}
void BM_points_plastic_damage_scalar(benchmark::State& s) {
  run_points(s, false, true, true);
}
void BM_points_plastic_damage_batch(benchmark::State& s) {
  run_points(s, true, true, true);
}
void BM_points_elastic_scalar(benchmark::State& s) {
  run_points(s, false, false, false);
}
void BM_points_elastic_batch(benchmark::State& s) {
  run_points(s, true, false, false);
}

BENCHMARK(BM_points_plastic_scalar);
BENCHMARK(BM_points_plastic_batch);
BENCHMARK(BM_points_plastic_damage_scalar);
BENCHMARK(BM_points_plastic_damage_batch);
BENCHMARK(BM_points_elastic_scalar);
BENCHMARK(BM_points_elastic_batch);

// Console output as usual, then scalar / batch CPU-time ratios of the
// BM_points_* pairs (medians when repetitions are run).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      const std::string name = r.benchmark_name();
      const bool median = r.run_type == Run::RT_Aggregate && r.aggregate_name == "median";
      if (r.run_type == Run::RT_Iteration || median) {
        std::string key = name;
        if (median) key = name.substr(0, name.rfind("_median"));
        cpu_[key] = r.GetAdjustedCPUTime();
      }
    }
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    for (const char* pair : {"plastic", "plastic_damage", "elastic"}) {
      const std::string s = std::string("BM_points_") + pair + "_scalar";
      const std::string b = std::string("BM_points_") + pair + "_batch";
      if (cpu_.count(s) && cpu_.count(b) && cpu_[b] > 0.0) {
        std::printf("%-16s scalar %8.2f ns/point  batch %8.2f ns/point  ratio %.2f\n", pair,
                    cpu_[s] / 1024.0, cpu_[b] / 1024.0, cpu_[s] / cpu_[b]);
      }
    }
  }

 private:
  std::map<std::string, double> cpu_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
