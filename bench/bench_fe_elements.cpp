// Cost of the finite-element internal-force loop per element-step.
//
// fe_internal_forces on a 16^3 hexahedron box and a 128 x 128 axisymmetric
// quad block of Johnson-Cook copper (no damage), in two regimes that bound a
// real run (an impact mesh is mostly elastic at any instant):
//   plastic: uniaxial compression at 1e5 /s, every element in plastic flow
//            (200 steps past first yield before timing); the nodes stay in
//            place, so each call is one more plastic step on the same
//            geometry (the return mapping runs every time);
//   elastic: the same block loaded at 1e3 /s, the velocity reversed every
//            call, so the stress oscillates far below yield (no return).
// Run with 1 and 2 OpenMP threads (the first argument).
//
// Every run times a fixed number of steps (hex_steps, quad_steps), the same
// for every build. The machine this runs on is shared, so every figure is
// measured in CPU time (google-benchmark's MeasureProcessCPUTime). Counters,
// per element and step, material update included:
//   cpu_ns_per_element_step   process CPU time / (threads x element-steps):
//                             the CPU each thread spent per element-step;
//                             for 1 thread, the single-thread cost;
//   wall_ns_per_element_step  elapsed time / element-steps (what the 1-thread
//                             and 2-thread speed-up is read from on an idle
//                             machine; inflated by any other load);
//   busiest_thread_cpu_ns_per_element_step
//                             CPU time of the busiest thread / element-steps:
//                             with OMP_WAIT_POLICY=passive (waiting threads
//                             sleep instead of spinning) the 1-thread figure
//                             over this one bounds the speed-up a second
//                             thread gives on an idle machine (work balance
//                             and the serial parts, not the scheduling delays
//                             of a loaded machine);
//   plastic_fraction          elements whose last step was plastic;
//   material_cpu_ns_per_element_step, kernel_cpu_ns_per_element_step
//                             (1 thread) the split of cpu_ns_per_element_step:
//                             update_points alone on a copy of the block's
//                             states taken before the timed steps, as many
//                             steps with the same strain increments (as
//                             *_material_only), and the rest (element work:
//                             kinematics, rotation, bulk viscosity, hourglass,
//                             forces, node gather). Only the first depends on
//                             the material model.
// The *_material_only benchmarks time the material kernel alone
// (update_points on the same states with the same strain increment, one
// thread) to give the split between the kernel and the element work.
//   build/bench/bench_fe_elements --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true     (quote the medians)
//   OMP_WAIT_POLICY=passive build/bench/bench_fe_elements ...   (thread counters)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

#include "solver/fe/fe_body.hpp"
#include "tests/support/materials.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace splat {
namespace {

using test_support::jc_copper;
using test_support::no_damage;

constexpr double plastic_rate = 1e5;  // 1/s
constexpr double elastic_rate = 1e3;  // 1/s, reversed every step
constexpr double size = 1e-3;         // block edge, m
constexpr int plastic_warmup_steps = 200;
// Fixed step counts per run (about 0.2 s each), so that every build times the
// same steps: the plastic state moves on with each step, and the return costs
// more near the onset of yield than later.
constexpr int hex_steps = 200;
constexpr int quad_steps = 50;

HexMesh box(int n) {
  HexMesh m;
  const double h = size / n;
  auto id = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.nodes.push_back(h * Vec3(i, j, k));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        m.hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                           id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                           id(i, j + 1, k + 1)});
  return m;
}

AxisymMesh rectangle(int n) {
  AxisymMesh m;
  const double h = size / n;
  auto id = [n](int i, int j) { return i + (n + 1) * j; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.nodes.push_back(h * Vec2(i, j));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

int set_threads(const benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
  return static_cast<int>(state.range(0));
#else
  (void)state;
  return 1;
#endif
}

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// CPU time of each OpenMP thread of a team of `threads` (libgomp keeps the
// same threads for every parallel region of a team size, so a difference of
// two calls is the CPU each thread spent in between), s.
std::vector<double> thread_cpu_seconds(int threads) {
  std::vector<double> t(static_cast<std::size_t>(threads), 0.0);
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
  {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    t[static_cast<std::size_t>(omp_get_thread_num())] =
        static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
#else
  t[0] = process_cpu_seconds();
#endif
  return t;
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A block under uniaxial compression along z (axisymmetric: component 1);
// dt is half the stable step. Plastic: loaded until its elements yield.
struct Block {
  NodeSet nodes;
  FeBody body;
  double dt = 0.0;
  Mat3 L = Mat3::Zero();  // the uniform velocity gradient
};

Block make_block(bool axisymmetric, bool plastic) {
  Block b;
  const int axial = axisymmetric ? 1 : 2;
  const double rate = plastic ? plastic_rate : elastic_rate;
  if (axisymmetric) {
    b.body = make_fe_body("block", rectangle(128), jc_copper(), no_damage(), FeSettings{},
                          Vec3::Zero(), 300.0, 1, b.nodes);
  } else {
    b.body = make_fe_body("block", box(16), jc_copper(), no_damage(), FeSettings{}, Vec3::Zero(),
                          300.0, 1, b.nodes);
  }
  for (std::size_t n = 0; n < b.nodes.size(); ++n) {
    b.nodes.v[n].setZero();
    b.nodes.v[n][axial] = -rate * (b.nodes.x[n][axial] - 0.5 * size);
  }
  b.L(axial, axial) = -rate;
  b.dt = 0.5 * fe_internal_forces(b.body, b.nodes, 0.0).dt_stable;
  for (int warm = 0; plastic && warm < 1000 && b.body.state[0].eps_p <= 0.0; ++warm) {
    fe_internal_forces(b.body, b.nodes, b.dt);
  }
  // Past the onset of yield, where n < 1 makes the hardening slope unbounded
  // and the first returns take many bisection steps: the benchmark times
  // established plastic flow.
  for (int warm = 0; plastic && warm < plastic_warmup_steps; ++warm) {
    fe_internal_forces(b.body, b.nodes, b.dt);
  }
  return b;
}

void reverse_velocity(Block& b) {
  for (auto& v : b.nodes.v) v = -v;
  b.L = -b.L;
}

double plastic_fraction(const FeBody& body) {
  const auto n = std::count_if(body.state.begin(), body.state.end(),
                               [](const PointState& st) { return st.eps_dot_p > 0.0; });
  return static_cast<double>(n) / static_cast<double>(body.num_elements());
}

void per_unit_counters(benchmark::State& state, const char* unit, double cpu, double wall,
                       int threads, std::size_t units) {
  const double n = static_cast<double>(state.iterations()) * static_cast<double>(units);
  state.counters[std::string("cpu_ns_per_") + unit] = 1e9 * cpu / (n * threads);
  state.counters[std::string("wall_ns_per_") + unit] = 1e9 * wall / n;
}

// Material inputs of every element for the block's uniform strain increment,
// in update_points' form.
struct MaterialInputs {
  std::vector<int> index;
  std::vector<Mat3> d_eps;
  std::vector<double> J_new, length;
  std::vector<PointUpdateResult> out;
};

MaterialInputs material_inputs(const Block& b) {
  const FeBody& body = b.body;
  MaterialInputs in;
  const Mat3 D = 0.5 * (b.L + b.L.transpose());  // no spin in uniaxial compression
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    in.index.push_back(static_cast<int>(e));
    in.d_eps.push_back(b.dt * D);
    in.J_new.push_back(body.volume[e] / body.volume0[e]);
    in.length.push_back(body.char_length[e]);
  }
  in.out.resize(in.index.size());
  return in;
}

// One material update of every element: update_points (8 points per SIMD
// lane group, as the element loop's lanes) in calls of 64 points.
void update_all(FeBody& body, double dt, MaterialInputs& in) {
  constexpr std::size_t chunk = 64;
  for (std::size_t k = 0; k < in.index.size(); k += chunk) {
    const std::size_t n = std::min(chunk, in.index.size() - k);
    update_points(body.material, body.constants, body.switches, body.state.data(), &in.index[k], n,
                  &in.d_eps[k], &in.J_new[k], dt, &in.length[k], &in.out[k]);
  }
}

// CPU time of `steps` material updates of every element of a copy of `b`
// (update_all), s.
double material_cpu_seconds(Block b, bool plastic, benchmark::IterationCount steps) {
  MaterialInputs in = material_inputs(b);
  MaterialInputs reversed = in;
  for (Mat3& d : reversed.d_eps) d = -d;
  const double cpu0 = process_cpu_seconds();
  for (benchmark::IterationCount k = 0; k < steps; ++k) {
    MaterialInputs& now = plastic || k % 2 == 0 ? in : reversed;
    update_all(b.body, b.dt, now);
    benchmark::DoNotOptimize(now.out.data());
  }
  return process_cpu_seconds() - cpu0;
}

void run_internal_forces(benchmark::State& state, bool axisymmetric, bool plastic) {
  const int threads = set_threads(state);
  Block b = make_block(axisymmetric, plastic);
  const Block copy = b;
  int iterations = 0;
  const std::vector<double> team0 = thread_cpu_seconds(threads);
  const double cpu0 = process_cpu_seconds(), wall0 = wall_seconds();
  for (auto _ : state) {
    for (auto& f : b.nodes.f) f.setZero();
    FeStepResult r = fe_internal_forces(b.body, b.nodes, b.dt);
    if (!plastic) reverse_velocity(b);
    iterations = std::max(iterations, r.max_return_iterations);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  const double cpu = process_cpu_seconds() - cpu0, wall = wall_seconds() - wall0;
  const std::vector<double> team1 = thread_cpu_seconds(threads);
  double busiest = 0.0;
  for (std::size_t t = 0; t < team1.size(); ++t) busiest = std::max(busiest, team1[t] - team0[t]);
  state.counters["busiest_thread_cpu_ns_per_element_step"] =
      1e9 * busiest /
      (static_cast<double>(state.iterations()) * static_cast<double>(b.body.num_elements()));
  const double fraction = plastic_fraction(b.body);
  if (plastic ? fraction < 1.0 : fraction > 0.0) {
    state.SkipWithError(plastic ? "not every element yielded" : "an element yielded");
  }
  per_unit_counters(state, "element_step", cpu, wall, threads, b.body.num_elements());
  if (threads == 1) {
    const double material = material_cpu_seconds(copy, plastic, state.iterations());
    const double n =
        static_cast<double>(state.iterations()) * static_cast<double>(b.body.num_elements());
    state.counters["material_cpu_ns_per_element_step"] = 1e9 * material / n;
    state.counters["kernel_cpu_ns_per_element_step"] = 1e9 * (cpu - material) / n;
  }
  state.counters["plastic_fraction"] = fraction;
  state.counters["return_iterations"] = iterations;
}

// The material kernel alone (update_points, not part of the element code) on
// the same block's states with its uniform strain rate, one thread: the part
// of the element-step cost that is not element work.
void run_material(benchmark::State& state, bool axisymmetric, bool plastic) {
  Block b = make_block(axisymmetric, plastic);
  FeBody& body = b.body;
  long long iterations = 0;
  const double cpu0 = process_cpu_seconds(), wall0 = wall_seconds();
  MaterialInputs in = material_inputs(b);
  MaterialInputs reversed = in;
  for (Mat3& d : reversed.d_eps) d = -d;
  bool flip = false;
  for (auto _ : state) {
    MaterialInputs& now = flip ? reversed : in;
    update_all(body, b.dt, now);
    for (const PointUpdateResult& r : now.out) iterations += r.iterations;
    benchmark::DoNotOptimize(now.out.data());
    if (!plastic) flip = !flip;
  }
  const double cpu = process_cpu_seconds() - cpu0, wall = wall_seconds() - wall0;
  per_unit_counters(state, "point_update", cpu, wall, 1, body.num_elements());
  state.counters["plastic_fraction"] = plastic_fraction(body);
  state.counters["mean_return_iterations"] =
      static_cast<double>(iterations) /
      (static_cast<double>(state.iterations()) * static_cast<double>(body.num_elements()));
}

void BM_hex8_plastic(benchmark::State& state) {
  run_internal_forces(state, false, true);
}
void BM_hex8_elastic(benchmark::State& state) {
  run_internal_forces(state, false, false);
}
void BM_quad4_axisym_plastic(benchmark::State& state) {
  run_internal_forces(state, true, true);
}
void BM_quad4_axisym_elastic(benchmark::State& state) {
  run_internal_forces(state, true, false);
}
void BM_hex8_material_only_plastic(benchmark::State& state) {
  run_material(state, false, true);
}
void BM_hex8_material_only_elastic(benchmark::State& state) {
  run_material(state, false, false);
}
void BM_quad4_axisym_material_only_plastic(benchmark::State& state) {
  run_material(state, true, true);
}
void BM_quad4_axisym_material_only_elastic(benchmark::State& state) {
  run_material(state, true, false);
}

BENCHMARK(BM_hex8_plastic)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(hex_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_hex8_elastic)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(hex_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_quad4_axisym_plastic)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(quad_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_quad4_axisym_elastic)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(quad_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_hex8_material_only_plastic)
    ->Iterations(hex_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_hex8_material_only_elastic)
    ->Iterations(hex_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_quad4_axisym_material_only_plastic)
    ->Iterations(quad_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_quad4_axisym_material_only_elastic)
    ->Iterations(quad_steps)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace splat

BENCHMARK_MAIN();
