#!/usr/bin/env bash
# Sets everything up and runs the main job. Until the campaign manager lands,
# the main job is the material-point demo: Johnson-Cook copper and aluminium
# driven in uniaxial compression at cold-spray strain rates, with adiabatic
# heating and damage, printing a short table per run (full CSV in out/).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" "$here/build"
splat="$here/build/app/splat"
out="$here/out/demo"
mkdir -p "$out"
"$splat" --version
"$splat" materials
for material in cu-thesis al-thesis; do
  for rate in 1e3 1e7; do
    csv="$out/mat-point-$material-$rate.csv"
    "$splat" mat-point --material "$material" --mode uniaxial-stress --strain-rate "$rate" \
      --max-strain -2.0 --steps 4000 --out "$csv"
    echo
    echo "$material, uniaxial compression at $rate /s (every 0.25 of strain; $csv):"
    awk -F, 'NR == 1 { printf "%10s %12s %12s %10s %8s %12s\n", "strain", "stress_MPa", "plastic", "T_K", "damage", "yield_MPa"; next }
             (NR - 2) % 500 == 0 { printf "%10.3f %12.1f %12.4f %10.1f %8.4f %12.1f\n", $2, $3 / 1e6, $4, $5, $6, $7 / 1e6 }' "$csv"
  done
done
