// The phased block loops (fe_block_lanes.hpp) for one instruction set: CMake
// compiles this file once per set, with its -march and SPLAT_ISA_NAMESPACE
// (solver/CMakeLists.txt).
#include "solver/fe/fe_block_lanes.hpp"

#ifndef SPLAT_ISA_NAMESPACE
#error "SPLAT_ISA_NAMESPACE names the instruction set this file is compiled for"
#endif

namespace splat::fe_block::SPLAT_ISA_NAMESPACE {

namespace {

void hex_block(FeBody& body, const NodeSet& nodes, std::size_t begin, std::size_t end, double dt,
               BlockSums& sums, std::vector<int>& erode) {
  hex_block_lanes<lane_width>(body, nodes, begin, end, dt, sums, erode);
}

void quad_block(FeBody& body, const NodeSet& nodes, std::size_t begin, std::size_t end, double dt,
                BlockSums& sums, std::vector<int>& erode) {
  quad_block_lanes<lane_width>(body, nodes, begin, end, dt, sums, erode);
}

}  // namespace

BlockLoops block_loops() {
  return {hex_block, quad_block};
}

}  // namespace splat::fe_block::SPLAT_ISA_NAMESPACE
