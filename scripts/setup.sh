#!/usr/bin/env bash
# Installs the Debian 12 packages splat needs (only when one is missing) and
# configures + builds the project. Idempotent; run as root on a fresh machine.
#   scripts/setup.sh [BUILD_DIR] [extra cmake args...]
# SPLAT_BUILD_TARGETS="a b" builds only those targets (default: all).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-$here/build}"
shift || true

packages=(build-essential cmake git pkg-config ca-certificates
  libeigen3-dev libsqlite3-dev libcpp-httplib-dev nlohmann-json3-dev
  libhdf5-dev hdf5-tools libgtest-dev libgmock-dev libbenchmark-dev
  libvalijson-dev libcli11-dev
  python3-h5py python3-numpy python3-meshio python3-matplotlib)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
targets=()
for t in ${SPLAT_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
