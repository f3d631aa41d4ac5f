// Cost of the contact stage's parts, to choose the Lagrange-multiplier solver
// by measurement and to size the search:
//   solve   one step's impulses for n pairs of a flat press (every slave node
//           of a finer block penetrating a coarser one by 1e-3 of an element;
//           the pairs couple through the shared master nodes), by projected
//           Gauss-Seidel (tolerance 1e-10 of the largest penetration speed)
//           and by the active-set method with sparse LDL^T; ns per pair and
//           the sweeps / passes taken (counter "iterations").
//   search  bucket search against all pairs on the same surfaces, ns per
//           slave node (time_per_slave_node).
//   build/bench/bench_contact --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <vector>

#include "solver/contact/contact_search.hpp"
#include "solver/contact/contact_solver.hpp"
#include "solver/mesh/generators.hpp"

namespace {

using namespace splat;

struct Press {
  std::vector<Vec3> x;
  ContactSurface master, slave;
  ContactProblem problem;
};

// n_master x n_master master faces (3D) or n_master segments (2D); the slave
// block is 1.37 times finer so nodes never line up.
Press make_press(bool three_d, int n_master) {
  Press p;
  const double h = 1e-6;  // master element size, m
  const int n_slave = static_cast<int>(1.37 * n_master);
  const double L = n_master * h;
  const double dip = 1e-3 * h;
  std::vector<std::array<int, 4>> mf, sf;
  if (three_d) {
    const HexMesh a = hex_box(Vec3(0, 0, -2 * h), Vec3(L, L, 0), n_master, n_master, 2, {});
    const HexMesh b = hex_box(Vec3(0, 0, -dip), Vec3(L, L, 2 * h - dip), n_slave, n_slave, 2, {});
    p.x = a.nodes;
    const int off = static_cast<int>(p.x.size());
    p.x.insert(p.x.end(), b.nodes.begin(), b.nodes.end());
    for (std::size_t k = 0; k < a.boundary_faces.size(); ++k) {
      if (a.face_boundary[k] & boundary_z_max) mf.push_back(a.boundary_faces[k]);
    }
    for (std::size_t k = 0; k < b.boundary_faces.size(); ++k) {
      if (!(b.face_boundary[k] & boundary_z_min)) continue;
      std::array<int, 4> f = b.boundary_faces[k];
      for (int& id : f) id += off;
      sf.push_back(f);
    }
    p.master = make_contact_surface(DetectionKind::node_on_quad, mf);
    p.slave = make_contact_surface(DetectionKind::node_on_quad, sf);
  } else {
    const AxisymMesh a = axisym_rectangle(L, -2 * h, 0.0, n_master, 2, {});
    const AxisymMesh b = axisym_rectangle(L, -dip, 2 * h - dip, n_slave, 2, {});
    for (const Vec2& q : a.nodes) p.x.emplace_back(q.x(), q.y(), 0.0);
    const int off = static_cast<int>(p.x.size());
    for (const Vec2& q : b.nodes) p.x.emplace_back(q.x(), q.y(), 0.0);
    for (std::size_t k = 0; k < a.boundary_segments.size(); ++k) {
      if (a.segment_boundary[k] & boundary_y_max) {
        mf.push_back({a.boundary_segments[k][0], a.boundary_segments[k][1], 0, 0});
      }
    }
    for (std::size_t k = 0; k < b.boundary_segments.size(); ++k) {
      if (b.segment_boundary[k] & boundary_y_min) {
        sf.push_back({b.boundary_segments[k][0] + off, b.boundary_segments[k][1] + off, 0, 0});
      }
    }
    p.master = make_contact_surface(DetectionKind::node_on_segment, mf);
    p.slave = make_contact_surface(DetectionKind::node_on_segment, sf);
  }
  // Lumped masses of aluminium surface nodes (rho h^3 / 8 in 3D, per node).
  const double m_master = 2700.0 * h * h * h / 8.0;
  const double m_slave = m_master / (1.37 * 1.37 * 1.37);
  const auto pairs = find_pairs_buckets(p.master, p.slave, p.x, SearchSettings{});
  std::vector<int> local(p.x.size(), -1);
  const double dt = 1e-10;
  auto loc = [&](int g, double m) {
    if (local[g] < 0) {
      local[g] = static_cast<int>(p.problem.inv_mass.size());
      p.problem.inv_mass.push_back(Vec3::Constant(1.0 / m));
      p.problem.velocity.push_back(Vec3::Zero());
    }
    return local[g];
  };
  const int npf = p.master.nodes_per_face();
  for (const DetectedPair& d : pairs) {
    std::array<int, 5> ids{-1, -1, -1, -1, -1};
    std::array<double, 5> c{};
    ids[0] = loc(p.slave.nodes[d.slave], m_slave);
    c[0] = 1.0;
    for (int k = 0; k < npf; ++k) {
      ids[k + 1] = loc(p.master.faces[d.face][k], m_master);
      c[k + 1] = -d.geometry.weights[k];
    }
    p.problem.node.push_back(ids);
    p.problem.coef.push_back(c);
    p.problem.normal.push_back(d.geometry.normal);
    p.problem.tangent1.push_back(d.geometry.tangent1);
    p.problem.tangent2.push_back(d.geometry.tangent2);
    p.problem.b.push_back(-d.geometry.gap / dt);
    p.problem.lo.push_back(0.0);
    p.problem.b_hold.push_back(p.problem.b.back());
    p.problem.mu.push_back(0.0);
  }
  return p;
}

void solve(benchmark::State& state, bool three_d, ContactSolverKind kind) {
  const Press p = make_press(three_d, static_cast<int>(state.range(0)));
  ContactSolverSettings st;
  st.kind = kind;
  int iterations = 0;
  double residual = 0.0;
  for (auto _ : state) {
    const ContactSolution s = solve_contact(p.problem, st);
    iterations = s.iterations;
    residual = s.residual;
    benchmark::DoNotOptimize(s);
  }
  const double n = static_cast<double>(p.problem.pairs());
  state.counters["pairs"] = n;
  state.counters["iterations"] = iterations;
  state.counters["residual_rel"] = residual / (1e-3 * 1e-6 / 1e-10);
  // Seconds per pair (printed with an SI prefix: "u" = us, "n" = ns).
  state.counters["time_per_pair"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void search(benchmark::State& state, bool three_d, bool buckets) {
  const Press p = make_press(three_d, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto r = buckets ? find_pairs_buckets(p.master, p.slave, p.x, SearchSettings{})
                     : find_pairs_all_pairs(p.master, p.slave, p.x, SearchSettings{});
    benchmark::DoNotOptimize(r);
  }
  const double n = static_cast<double>(p.slave.nodes.size());
  state.counters["slave_nodes"] = n;
  state.counters["time_per_slave_node"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_solve_pgs_2d(benchmark::State& s) {
  solve(s, false, ContactSolverKind::pgs);
}
void BM_solve_active_set_2d(benchmark::State& s) {
  solve(s, false, ContactSolverKind::active_set);
}
void BM_solve_pgs_3d(benchmark::State& s) {
  solve(s, true, ContactSolverKind::pgs);
}
void BM_solve_active_set_3d(benchmark::State& s) {
  solve(s, true, ContactSolverKind::active_set);
}
void BM_search_buckets_3d(benchmark::State& s) {
  search(s, true, true);
}
void BM_search_all_pairs_3d(benchmark::State& s) {
  search(s, true, false);
}

BENCHMARK(BM_solve_pgs_2d)->Arg(20)->Arg(100)->Arg(400);
BENCHMARK(BM_solve_active_set_2d)->Arg(20)->Arg(100)->Arg(400);
BENCHMARK(BM_solve_pgs_3d)->Arg(8)->Arg(20)->Arg(40);
BENCHMARK(BM_solve_active_set_3d)->Arg(8)->Arg(20)->Arg(40);
BENCHMARK(BM_search_buckets_3d)->Arg(8)->Arg(20)->Arg(40);
BENCHMARK(BM_search_all_pairs_3d)->Arg(8)->Arg(20);

}  // namespace

BENCHMARK_MAIN();
