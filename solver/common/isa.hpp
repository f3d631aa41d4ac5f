// The instruction sets the hot loops are compiled for, and the one they run.
//
// The lane loops (the FE element blocks, update_points) are compiled once per
// instruction set, each in its own translation unit with that set's -march
// (solver/CMakeLists.txt), and the best one this CPU supports is chosen at run
// time. The build has -ffp-contract=off, so every set gives the same bits.
#pragma once

namespace splat {

enum class Isa {
  baseline,   // x86-64 (SSE2)
  x86_64_v3,  // AVX2
  x86_64_v4,  // AVX-512 (F, BW, CD, DQ, VL)
};

// The best set this CPU supports.
Isa machine_isa();

// The set the lane loops run: machine_isa() unless set_active_isa chose
// another.
Isa active_isa();

// Runs the lane loops compiled for `isa` from now on (tests and benchmarks
// compare the sets). Throws std::invalid_argument if the CPU lacks it.
void set_active_isa(Isa isa);

// "x86-64", "x86-64-v3", "x86-64-v4".
const char* isa_name(Isa isa);

}  // namespace splat
