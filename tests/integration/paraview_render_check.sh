#!/bin/sh
# scripts/paraview/render_impact.py under ParaView (ctest integration.paraview_render,
# registered only where pvpython and xvfb-run are installed): renders the final
# shape of a fresh scenes/impact_al_al.json run, revolved, into a PNG.
# usage: paraview_render_check.sh SPLAT SOURCE_DIR WORK_DIR
set -eu
splat="$1"; source="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
"$splat" run "$source/scenes/impact_al_al.json" --threads 1 --out "$work" > "$work/run.txt"
# Two attempts: on a loaded machine the X server of xvfb-run -a is not
# always up in time for pvpython (a fault of the harness, not of the script).
render() {
  xvfb-run -a -s "-screen 0 1280x1024x24" pvpython \
    "$source/scripts/paraview/render_impact.py" "$work/impact_al_al.xmf" --out "$work/impact.png" \
    2> "$work/pvpython.txt"
}
out=$(render) || { cat "$work/pvpython.txt" >&2; sleep 2; out=$(render); }
echo "$out"
# The ParaView pipeline drew the revolved particle and substrate: points and cells.
echo "$out" | grep -Eq "impact.png: t = [0-9.e+-]+ s, [1-9][0-9]* points, [1-9][0-9]* cells \(revolved\)"
# A PNG of the asked size (1200 x 800 by default).
python3 - "$work/impact.png" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
width, height = struct.unpack(">II", data[16:24])
assert (width, height) == (1200, 800), (width, height)
assert len(data) > 20000, len(data)  # an image, not a blank frame
PY
