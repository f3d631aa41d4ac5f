"""Renders the final shape of a splat impact run with ParaView (pvpython).

    pvpython scripts/paraview/render_impact.py /tmp/splat/impact_al_al.xmf \
        --out /tmp/splat/impact_al_al.png

Debian's ParaView renders through X: without a display, run it under
xvfb-run -a (package xvfb); an X error printed at exit does not affect the
image.

Reads the run's .xmf (written by `splat run`), takes the last time step,
keeps the live material (threshold on `eroded` < 0.5), and colours it by a
field (default plastic_strain). An axisymmetric result, the (r, z) section,
is revolved about its axis into the 3D particle and crater (Transform: axis
onto z; Rotational Extrusion over `--angle` degrees, 180 by default so that
the section shows); a 3D result is drawn as it is (SPH bodies as points).
The camera frames the first body (the particle); --whole frames everything.
Writes a PNG and prints the number of points and cells drawn.

Debian 12: apt-get install paraview python3-paraview.
"""

import argparse
import os
import sys

from paraview import servermanager
from paraview.simple import (CellDatatoPointData, ColorBy, ExtractSurface, GetActiveViewOrCreate,
                             GetColorTransferFunction, MergeBlocks, OpenDataFile,
                             RotationalExtrusion, SaveScreenshot, Show, Threshold, Transform)


def parse(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("xmf", help="the run's .xmf file")
    p.add_argument("--out", default="impact.png", help="PNG to write")
    p.add_argument("--field", default="plastic_strain",
                   help="array to colour by (as ParaView names it, e.g. 'temperature [K]')")
    p.add_argument("--angle", type=float, default=180.0,
                   help="degrees of revolution of an axisymmetric result")
    p.add_argument("--size", type=int, nargs=2, default=[1200, 800], help="image size, pixels")
    p.add_argument("--whole", action="store_true",
                   help="frame every body (default: zoom on the first body, the particle)")
    return p.parse_args(argv)


def main(argv):
    args = parse(argv)
    reader = OpenDataFile(args.xmf)
    if reader is None:
        raise SystemExit(f"ParaView cannot open '{args.xmf}'")
    times = list(reader.TimestepValues) or [0.0]
    t_last = times[-1]
    reader.UpdatePipeline(t_last)
    # The first body of the file (the particle of an impact scene): what the camera frames.
    data = servermanager.Fetch(reader)
    blocks = data.NewIterator()
    blocks.InitTraversal()
    first = blocks.GetCurrentDataObject().GetBounds() if not blocks.IsDoneWithTraversal() else None
    merged = MergeBlocks(Input=reader)
    merged.UpdatePipeline(t_last)
    source = merged
    arrays = set(merged.CellData.keys()) | set(merged.PointData.keys())
    if "eroded" in arrays:
        live = Threshold(Input=merged)
        live.Scalars = ["CELLS" if "eroded" in merged.CellData.keys() else "POINTS", "eroded"]
        live.LowerThreshold, live.UpperThreshold = 0.0, 0.5
        source = live
    source.UpdatePipeline(t_last)
    bounds = source.GetDataInformation().GetBounds()
    axisymmetric = bounds[4] == bounds[5] == 0.0  # (r, z) section in the x-y plane
    if axisymmetric:
        # Point data for a smooth sweep; the section's outline swept about the axis.
        points = CellDatatoPointData(Input=source)
        upright = Transform(Input=points)
        upright.Transform.Rotate = [90.0, 0.0, 0.0]  # model z (view y) onto the view z axis
        surface = ExtractSurface(Input=upright)
        source = RotationalExtrusion(Input=surface)
        source.Resolution = max(12, int(args.angle / 5))
        source.Angle = args.angle
        source.Capping = 1
    source.UpdatePipeline(t_last)

    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = args.size
    view.ViewTime = t_last
    view.OrientationAxesVisibility = 1
    display = Show(source, view)
    if not axisymmetric and "eroded" not in merged.CellData.keys():
        display.SetRepresentationType("Points")
        display.PointSize = 3
    field_arrays = set(source.PointData.keys()) | set(source.CellData.keys())
    if args.field in field_arrays:
        where = "POINTS" if args.field in source.PointData.keys() else "CELLS"
        ColorBy(display, (where, args.field))
        display.RescaleTransferFunctionToDataRange(True, False)
        display.SetScalarBarVisibility(view, True)
        GetColorTransferFunction(args.field).ApplyPreset("Viridis (matplotlib)", True)
    else:
        print(f"render_impact: no array '{args.field}'; arrays: {sorted(field_arrays)}",
              file=sys.stderr)
    # Onto the cut face (the plane y = 0, the half y < 0 removed), from above.
    view.CameraPosition = [0.5, -2.0, 1.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()
    if first is not None and not args.whole:
        if axisymmetric:  # the revolved particle: radius r_max, height its z range
            r = first[1]
            frame = [-r, r, -r, r, first[2], first[3]]
        else:
            frame = list(first)
        view.ResetCamera(*[1.6 * v for v in frame])
    SaveScreenshot(args.out, view, ImageResolution=args.size)
    info = source.GetDataInformation()
    print(f"{args.out}: t = {t_last:.4e} s, {info.GetNumberOfPoints()} points, "
          f"{info.GetNumberOfCells()} cells{' (revolved)' if axisymmetric else ''}")
    return 0


if __name__ == "__main__":
    code = main(sys.argv[1:])
    sys.stdout.flush()
    # Skip ParaView's teardown: under xvfb-run its OpenGL context release
    # aborts after the image is written.
    os._exit(code)
