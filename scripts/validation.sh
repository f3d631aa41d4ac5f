#!/usr/bin/env bash
# Runs the validation campaigns (campaigns/validation/: Al on Al with two
# aluminium sets, Cu on Cu; scenes/impact_al_al_expansion.json's bonding
# model, axisymmetric FE, 8 / 16 / 32 elements across, coarse to fine;
# about 9 minutes on 2 cores after the build) and writes their critical
# velocities against the measurements and correlations of
# docs/validation_sources.md:
# docs/validation_window.md (table) and docs/validation_window.png (plot).
# Stores stay in out/validation/ (run again: every job is reused).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/setup.sh" "$here/build"
splat="$here/build/app/splat"
out="$here/out/validation"
mkdir -p "$out"
for campaign in al_al cu_cu; do
  "$splat" sweep "$here/campaigns/validation/$campaign.json" --db "$out/$campaign.db" --workers 2
done
/usr/bin/python3 "$here/scripts/validation_window.py" --splat "$splat" \
  --out-md "$here/docs/validation_window.md" --out-png "$here/docs/validation_window.png" \
  "$out/al_al.db" "$out/cu_cu.db"
