// What fe_body.cpp shares with the phased block loops on lanes
// (fe_block_lanes.hpp), which fe_blocks_isa.cpp compiles once per instruction
// set (solver/common/isa.hpp). Internal to solver/fe.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "solver/common/simd_lanes.hpp"
#include "solver/fe/fe_body.hpp"

namespace splat::fe_block {

// Elements per reduction block: partial sums are taken over fixed blocks and
// combined in block order, so they do not depend on the thread count.
inline constexpr std::size_t block_size = 64;

// Reductions of one block of elements.
struct BlockSums {
  double dt_min = std::numeric_limits<double>::infinity();
  double hourglass_power = 0.0;
  double viscosity_power = 0.0;
  int max_iterations = 0;
  bool failed = false;
  long long inverted = 0;
};

// Zeroes element e's forces (fe_body.cpp; out of line, off the common path).
void zero_forces(FeBody& body, std::size_t e);

// Zeroes element e's forces and lists it for erosion (fe_body.cpp).
void flag_for_erosion(FeBody& body, std::size_t e, std::vector<int>& erode);

// True if the element meets an erosion criterion (settings.erosion): damage at
// its cap (if erosion_on_damage), non-positive volume, or a CFL bound below
// erosion_min_time_step.
// Without erosion a non-positive volume is counted as inverted.
SPLAT_LANE_INLINE bool to_be_eroded(const FeBody& body, std::size_t e, double V, double dt_e,
                                    BlockSums& sums) {
  const FeSettings& s = body.settings;
  if (!s.erosion) {
    if (!(V > 0.0)) ++sums.inverted;
    return false;
  }
  if (!(V > 0.0)) return true;
  const DamageParams& dm = body.material.damage;
  if (s.erosion_on_damage && body.switches.damage && dm.initiation != DamageInitiation::none &&
      body.state[e].D >= dm.D_max - 1e-12) {
    return true;
  }
  return s.erosion_min_time_step > 0.0 && dt_e < s.erosion_min_time_step;
}

// Books an element's step whose forces the caller has written to
// elem_force[e]: an element flagged for erosion exerts no force (they are
// zeroed) and sets no time-step bound (it is removed before the next step).
SPLAT_LANE_INLINE void finish_element(FeBody& body, std::size_t e, double V, double dt_e,
                                      double q_power, double hourglass_power, BlockSums& sums,
                                      std::vector<int>& erode) {
  if (to_be_eroded(body, e, V, dt_e, sums)) {
    flag_for_erosion(body, e, erode);
    return;
  }
  sums.dt_min = std::min(sums.dt_min, dt_e);
  sums.hourglass_power += hourglass_power;
  sums.viscosity_power += q_power;
}

// An element with non-positive volume: no force, no material update.
SPLAT_LANE_INLINE void inverted_element(FeBody& body, std::size_t e, BlockSums& sums,
                                        std::vector<int>& erode) {
  if (to_be_eroded(body, e, 0.0, std::numeric_limits<double>::infinity(), sums)) {
    flag_for_erosion(body, e, erode);
  } else {
    zero_forces(body, e);
  }
}

// The block loop of elements [begin, end) of one element kind.
using BlockLoop = void (*)(FeBody& body, const NodeSet& nodes, std::size_t begin, std::size_t end,
                           double dt, BlockSums& sums, std::vector<int>& erode);
struct BlockLoops {
  BlockLoop hex;
  BlockLoop quad;
};

// The loops compiled for each instruction set (fe_blocks_isa.cpp).
namespace isa_baseline {
BlockLoops block_loops();
}
namespace isa_v3 {
BlockLoops block_loops();
}
namespace isa_v4 {
BlockLoops block_loops();
}

}  // namespace splat::fe_block
