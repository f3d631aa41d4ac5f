// Cost of the finite-element internal-force loop per element-step.
//
// fe_internal_forces on a 16^3 hexahedron box and a 128 x 128 axisymmetric
// quad block of Johnson-Cook copper (no damage) under uniaxial compression at
// 1e5 /s, so every element is in plastic flow; the nodes stay in place, so
// each call is one more plastic step on the same geometry. Run with 1 and 2
// OpenMP threads (the argument). Counter ns_per_element_step is the wall time
// per element and step, material update included. The *_material_only
// benchmarks time the material kernel alone (update_point on the same states
// at the same strain rate) to give the split between the kernel and the
// element work.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "solver/fe/fe_body.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace splat {
namespace {

constexpr double strain_rate = 1e5;  // 1/s
constexpr double size = 1e-3;        // block edge, m

Material copper() {
  Material m;
  m.name = "copper";
  m.density = 8960.0;
  m.elastic = {124e9, 0.34};
  m.strength.A = 90e6, m.strength.B = 292e6, m.strength.n = 0.31, m.strength.C = 0.025;
  m.strength.m = 1.09, m.strength.T_ref = 300.0, m.strength.T_melt = 1356.0;
  m.thermal.c_p = 385.0;
  return m;
}

ModelSwitches no_damage() {
  ModelSwitches sw;
  sw.damage = false;
  return sw;
}

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

void set_threads(const benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
#else
  (void)state;
#endif
}

// A block under uniaxial compression along z (axisymmetric: component 1),
// loaded until its elements yield; dt is half the stable step.
struct Block {
  NodeSet nodes;
  FeBody body;
  double dt = 0.0;
  Mat3 L = Mat3::Zero();  // the uniform velocity gradient
};

Block make_block(bool axisymmetric) {
  Block b;
  const int axial = axisymmetric ? 1 : 2;
  if (axisymmetric) {
    b.body = make_fe_body("block", rectangle(128), copper(), no_damage(), FeSettings{},
                          Vec3::Zero(), 300.0, 1, b.nodes);
  } else {
    b.body = make_fe_body("block", box(16), copper(), no_damage(), FeSettings{}, Vec3::Zero(),
                          300.0, 1, b.nodes);
  }
  for (std::size_t n = 0; n < b.nodes.size(); ++n) {
    b.nodes.v[n].setZero();
    b.nodes.v[n][axial] = -strain_rate * (b.nodes.x[n][axial] - 0.5 * size);
  }
  b.L(axial, axial) = -strain_rate;
  b.dt = 0.5 * fe_internal_forces(b.body, b.nodes, 0.0).dt_stable;
  for (int warm = 0; warm < 1000 && b.body.state[0].eps_p <= 0.0; ++warm) {
    fe_internal_forces(b.body, b.nodes, b.dt);
  }
  return b;
}

void per_unit_counter(benchmark::State& state, const char* name, std::size_t units) {
  const double unit_steps = static_cast<double>(state.iterations()) * static_cast<double>(units);
  state.counters[name] = benchmark::Counter(
      unit_steps * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void run_internal_forces(benchmark::State& state, bool axisymmetric) {
  set_threads(state);
  Block b = make_block(axisymmetric);
  int iterations = 0;
  for (auto _ : state) {
    for (auto& f : b.nodes.f) f.setZero();
    FeStepResult r = fe_internal_forces(b.body, b.nodes, b.dt);
    iterations = std::max(iterations, r.max_return_iterations);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  if (b.body.state[0].eps_p <= 0.0) state.SkipWithError("elements did not yield");
  per_unit_counter(state, "ns_per_element_step", b.body.num_elements());
  state.counters["eps_p"] = b.body.state[0].eps_p;
  state.counters["return_iterations"] = iterations;
}

// The material kernel alone (update_point, not part of the element code) on
// the same block's states with its uniform strain rate, one thread: the part
// of ns_per_element_step that is not element work.
void run_material(benchmark::State& state, bool axisymmetric) {
  Block b = make_block(axisymmetric);
  FeBody& body = b.body;
  const Mat3 D = 0.5 * (b.L + b.L.transpose());  // no spin in uniaxial compression
  for (auto _ : state) {
    for (std::size_t e = 0; e < body.num_elements(); ++e) {
      PointState& st = body.state[e];
      PointUpdateResult r =
          update_point(body.material, body.constants, body.switches, st, b.dt * D,
                       body.volume[e] / body.volume0[e], b.dt, body.char_length[e]);
      benchmark::DoNotOptimize(r);
    }
  }
  per_unit_counter(state, "ns_per_point_update", body.num_elements());
  state.counters["eps_p"] = body.state[0].eps_p;
}

void BM_hex8_internal_forces(benchmark::State& state) {
  run_internal_forces(state, false);
}
void BM_quad4_axisym_internal_forces(benchmark::State& state) {
  run_internal_forces(state, true);
}
void BM_hex8_material_only(benchmark::State& state) {
  run_material(state, false);
}
void BM_quad4_axisym_material_only(benchmark::State& state) {
  run_material(state, true);
}

BENCHMARK(BM_hex8_internal_forces)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_quad4_axisym_internal_forces)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_hex8_material_only)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_quad4_axisym_material_only)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace splat

BENCHMARK_MAIN();
