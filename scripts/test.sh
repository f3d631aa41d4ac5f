#!/usr/bin/env bash
# Sets everything up (Debian packages, configure, build, the dashboard's npm
# packages from web/package-lock.json and Debian's chromium for the `browser`
# label) and runs the default test set: every ctest label except `long`, `extremes` and
# `slurm` (so `api` and `browser` too), then the unit and API tests
# once more under AddressSanitizer + UndefinedBehaviorSanitizer, then the
# `slurm` label (installs slurm-wlm and munge, starts and stops its own
# one-node cluster; fails clearly if they cannot be installed). Idempotent.
#   scripts/test.sh            # what CI runs
#   scripts/test.sh --long     # the long verification runs only (label `long`)
#   scripts/test.sh --extremes # the extremes matrix only (label `extremes`: every
#                              # fidelity rung x 1-3000 m/s x two resolutions x
#                              # adhesion x Al/Al, Cu/Cu; hours on 2 cores; tables
#                              # in build/test-artifacts/extremes_*.md)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="$(nproc)"

if [ "${1:-}" = "--long" ] || [ "${1:-}" = "--extremes" ]; then
  label="${1#--}"
  "$here/scripts/setup.sh" "$here/build"
  ctest --test-dir "$here/build" -L "$label" --output-on-failure -j "$jobs"
  exit 0
fi

"$here/scripts/setup.sh" "$here/build"

# The dashboard's packages (Chart.js, playwright-core) exactly as locked, and
# a browser for the `browser` label: Debian's chromium (and node/npm when the
# machine has none).
browser_packages=(chromium)
command -v npm >/dev/null 2>&1 || browser_packages+=(nodejs npm)
missing=()
for p in "${browser_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "test: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get update -q
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
(cd "$here/web" && npm ci --no-audit --no-fund)
# cmake looks for node when it configures the `browser` test.
cmake -S "$here" -B "$here/build" >/dev/null

ctest --test-dir "$here/build" -LE 'long|slurm|extremes' --output-on-failure -j "$jobs"
echo "test: dashboard screenshot in $here/build/test-artifacts/dashboard.png"

# Sanitizer pass over the unit and API tests (no benchmarks; only the
# executables these labels run are built). -O1 (AddressSanitizer's
# documentation: -O1 or higher for reasonable speed) and -g1 (line tables,
# all a report's stack trace needs): half the build time of -O2 -g.
SPLAT_BUILD_TARGETS="splat_unit_tests splat_api_tests" "$here/scripts/setup.sh" "$here/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DSPLAT_SANITIZE=ON -DSPLAT_BUILD_BENCHMARKS=OFF
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$here/build-asan" -L 'unit|api' --output-on-failure -j "$jobs"

# Slurm executor against a real one-node cluster (label `slurm`).
"$here/tests/slurm/cluster.sh" install
ctest --test-dir "$here/build" -L slurm --output-on-failure
