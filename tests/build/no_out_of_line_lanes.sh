#!/bin/sh
# Fails if a binary holds an out-of-line function that takes or returns lane
# vectors (GCC vector extensions, solver/common/simd_lanes.hpp). The lane
# kernels must be inlined into the loops that call them: a function left out
# of line passes its vectors through memory, and under the target_clones the
# element loop once used it was compiled for the baseline instruction set
# (SSE2) and called from the AVX-512 code, which cost the loop 10-15 % (a
# state-gathering lambda; SPLAT_LANE_INLINE, SPLAT_LANE_LAMBDA).
set -eu
bin=$1
found=$(nm -C "$bin" | grep -E ' [tTwW] ' | grep -F '__vector(' || true)
if [ -n "$found" ]; then
  echo "out-of-line functions on lane vectors in $bin:"
  echo "$found" | cut -c1-300
  exit 1
fi
echo "no out-of-line function on lane vectors in $bin"
