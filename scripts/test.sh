#!/usr/bin/env bash
# Sets everything up (Debian packages, configure, build) and runs the default
# test set: every ctest label except `long` and `slurm`, then the unit tests
# once more under AddressSanitizer + UndefinedBehaviorSanitizer, then the
# `slurm` label (installs slurm-wlm and munge, starts and stops its own
# one-node cluster; fails clearly if they cannot be installed). Idempotent.
#   scripts/test.sh            # what CI runs
#   scripts/test.sh --long     # the long verification runs only (label `long`)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"

if [ "${1:-}" = "--long" ]; then
  "$here/scripts/setup.sh" "$here/build"
  ctest --test-dir "$here/build" -L long --output-on-failure -j "$jobs"
  exit 0
fi

"$here/scripts/setup.sh" "$here/build"
ctest --test-dir "$here/build" -LE 'long|slurm' --output-on-failure -j "$jobs"

# Sanitizer pass over the unit tests (debug info, no benchmarks).
"$here/scripts/setup.sh" "$here/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSPLAT_SANITIZE=ON -DSPLAT_BUILD_BENCHMARKS=OFF
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$here/build-asan" -L unit --output-on-failure -j "$jobs"

# Slurm executor against a real one-node cluster (label `slurm`).
"$here/tests/slurm/cluster.sh" install
ctest --test-dir "$here/build" -L slurm --output-on-failure
