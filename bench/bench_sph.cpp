// Cost of the SPH internal-force loop per particle-step.
//
// sph_internal_forces on an HCP ball of Johnson-Cook aluminium (al-deck
// parameters, no damage) at the thesis's Al/Al resolution (spacing 2.5 um,
// i.e. SPH radius 1.25 um, h = spacing: about 54 neighbours inside), with
// about 12,000 particles as in the LAMMPS MACHDYN comparison of issue 8. The
// particles keep a uniform compressive velocity field of 1e5 /s on fixed
// positions, so after a few steps every particle is in plastic flow and each
// call is one more plastic step: material update, pair forces, viscosity and
// hourglass control included. Run with 1 and 2 OpenMP threads (the argument).
// Counters: ns_per_particle_step (wall time per particle and step),
// neighbours (mean pairs per particle), bytes_per_particle (the body's arrays,
// the shared NodeSet included).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "solver/sph/sph_body.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace splat {
namespace {

constexpr double strain_rate = 1e5;  // 1/s
constexpr double spacing = 2.5e-6;   // m

Material aluminium() {
  Material m;
  m.name = "al-deck";
  m.density = 2700.0;
  m.elastic = {70.2e9, 0.3};
  m.strength = JohnsonCookParams{
      .A = 60e6, .B = 140e6, .n = 0.42, .C = 0.01, .m = 1.0, .T_ref = 300.0, .T_melt = 916.0};
  m.thermal.c_p = 900.0;
  return m;
}

template <class T>
std::size_t bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t body_bytes(const SphBody& b, const NodeSet& n) {
  return bytes(b.volume0) + bytes(b.outward_normal) + bytes(b.X) + bytes(b.volume_ref) +
         bytes(b.J_ref) + bytes(b.F_ref) + bytes(b.h) + bytes(b.pairs.offsets) + bytes(b.pairs.j) +
         bytes(b.pairs.op) + bytes(b.pair_t) + bytes(b.pair_hg) + bytes(b.pair_visc) +
         bytes(b.null_projector) + bytes(b.B) + bytes(b.state) + bytes(b.F) + bytes(b.Fdot) +
         bytes(b.record) + bytes(b.dt_bound) + bytes(b.active) + bytes(n.x0) + bytes(n.x) +
         bytes(n.v) + bytes(n.f) + bytes(n.mass) + bytes(n.boundary);
}

void BM_sph_internal_forces(benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
#endif
  ParticleSpec s;
  s.shape = ParticleShape::sphere;
  s.radius = 12.65 * spacing;
  s.spacing = spacing;
  const ParticleCloud cloud = generate_particles(s);
  NodeSet nodes;
  ModelSwitches sw;
  sw.damage = false;
  SphSettings settings;
  settings.update_threshold = 0.0;  // positions are fixed: F stays I
  SphBody body =
      make_sph_body("ball", cloud, aluminium(), sw, settings, {}, Vec3::Zero(), 300.0, 1, nodes);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    nodes.v[i] = Vec3(0.0, 0.0, -strain_rate * (cloud.x[i].z() - s.centre.z()));
  }
  const double dt = 0.5 * sph_internal_forces(body, nodes, 0.0).dt_stable;
  for (int warm = 0; warm < 200 && body.state[0].eps_p <= 0.0; ++warm) {
    sph_internal_forces(body, nodes, dt);
  }
  for (auto _ : state) {
    for (auto& f : nodes.f) f.setZero();
    SphStepResult r = sph_internal_forces(body, nodes, dt);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
  }
  if (body.state[0].eps_p <= 0.0) state.SkipWithError("particles did not yield");
  const double n = static_cast<double>(cloud.size());
  state.counters["ns_per_particle_step"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * n * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["particles"] = n;
  state.counters["neighbours"] = static_cast<double>(body.pairs.num_pairs()) / n;
  state.counters["bytes_per_particle"] = static_cast<double>(body_bytes(body, nodes)) / n;
}

// The reference neighbour search and kernel correction (done once, and at
// each reference update), one thread.
void BM_sph_build_reference(benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
#endif
  ParticleSpec s;
  s.shape = ParticleShape::sphere;
  s.radius = 12.65 * spacing;
  s.spacing = spacing;
  const ParticleCloud cloud = generate_particles(s);
  NodeSet nodes;
  SphBody body = make_sph_body("ball", cloud, aluminium(), ModelSwitches{}, SphSettings{}, {},
                               Vec3::Zero(), 300.0, 1, nodes);
  for (auto _ : state) {
    sph_build_reference(body);
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_particle"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(cloud.size()) * 1e-9,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_sph_internal_forces)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_sph_build_reference)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace splat

BENCHMARK_MAIN();
