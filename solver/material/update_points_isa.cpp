// update_points (point_update.hpp) for one instruction set: CMake compiles
// this file once per set, with its -march and SPLAT_ISA_NAMESPACE
// (solver/CMakeLists.txt; see solver/fe/fe_block_lanes.hpp for why not
// target_clones).
//
// The lane vectors stay inside this loop (everything they pass through is
// forced inline), so GCC's note that passing them by value changes the ABI
// between instruction sets does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "solver/material/update_points_isa.hpp"

#include <cstring>
#include <variant>

#include "solver/material/point_update_fast.hpp"

#ifndef SPLAT_ISA_NAMESPACE
#error "SPLAT_ISA_NAMESPACE names the instruction set this file is compiled for"
#endif

namespace splat::SPLAT_ISA_NAMESPACE {

namespace {

constexpr int points_per_lane_group = 8;
using PointLane = Lane<points_per_lane_group>;

template <class F>
SPLAT_LANE_INLINE PointLane point_lanes(F&& f) {
  return PointLane{f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7)};
}

}  // namespace

// Groups of 8 points in lanes (point_update_fast); a group's points that the
// fast path does not cover, and the points past the last whole group, go
// through update_point one by one. The lanes accelerate Johnson-Cook only:
// the points of another law all go through update_point.
void update_points(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                   PointState* states, const int* index, std::size_t n, const Mat3* d_eps,
                   const double* J_new, double dt, const double* length, PointUpdateResult* out) {
  constexpr int W = points_per_lane_group;
  const std::size_t lanes_end = std::holds_alternative<JohnsonCookParams>(m.strength) ? n : 0;
  std::size_t k0 = 0;
  for (; k0 + W <= lanes_end; k0 += W) {
    PointState* st[W];
    for (int l = 0; l < W; ++l) st[l] = &states[index[k0 + std::size_t(l)]];
    bool symmetric = true;
    for (int l = 0; l < W; ++l)
      symmetric = symmetric && is_symmetric(st[l]->s) && is_symmetric(d_eps[k0 + std::size_t(l)]);
    LaneMask<PointLane> done{};
    PointLane evaluations{};
    if (symmetric) {
      PointFields<PointLane> f;
      PointLane de[6];
      for (int k = 0; k < 6; ++k) {
        f.s[k] =
            point_lanes([&](int l) SPLAT_LANE_LAMBDA { return st[l]->s(sym_row[k], sym_col[k]); });
        de[k] = point_lanes([&](int l) SPLAT_LANE_LAMBDA {
          return d_eps[k0 + std::size_t(l)](sym_row[k], sym_col[k]);
        });
      }
      for_each_point_field(f, [&](PointLane& v, double PointState::*field) SPLAT_LANE_LAMBDA {
        v = point_lanes([&](int l) SPLAT_LANE_LAMBDA { return st[l]->*field; });
      });
      PointLane J;
      std::memcpy(&J, J_new + k0, sizeof J);
      done = point_update_fast(m, mc, sw, f, de, J, dt, evaluations);
      for (int l = 0; l < W; ++l) {
        if (!done[l]) continue;
        PointState& p = *st[l];
        for (int k = 0; k < 6; ++k) {
          p.s(sym_row[k], sym_col[k]) = f.s[k][l];
          p.s(sym_col[k], sym_row[k]) = f.s[k][l];
        }
        for_each_point_field(
            f, [&](PointLane& v, double PointState::*field) SPLAT_LANE_LAMBDA { p.*field = v[l]; });
        out[k0 + std::size_t(l)] = {static_cast<int>(evaluations[l]), true};
      }
    }
    // The lanes have tested these points already (none, if a group's inputs
    // were not symmetric).
    for (int l = 0; l < W; ++l) {
      const std::size_t k = k0 + std::size_t(l);
      if (done[l]) continue;
      out[k] = symmetric
                   ? update_point_general(m, mc, sw, *st[l], d_eps[k], J_new[k], dt, length[k])
                   : update_point(m, mc, sw, *st[l], d_eps[k], J_new[k], dt, length[k]);
    }
  }
  for (std::size_t k = k0; k < n; ++k) {
    out[k] = update_point(m, mc, sw, states[index[k]], d_eps[k], J_new[k], dt, length[k]);
  }
}

}  // namespace splat::SPLAT_ISA_NAMESPACE
