"""The .xmf of an impact run as ParaView and meshio read it (ctest
integration.xdmf_meshio; needs python3-meshio, python3-h5py).

Runs `splat run` on the FE and the SPH Al/Al impact scenes with their
default snapshots, then:
- the .xmf is one temporal collection of at least 10 time steps whose times
  are the result file's snapshot times (read with python/splat_results.py:
  meshio's own time-series reader takes one mesh per file, and a step of ours
  holds one grid per body);
- every body's grid of the first and the last step, cut out as a one-grid
  XDMF file beside the .h5, reads with meshio.read: points and cells > 0, the
  arrays under their names with units, the stress tensor as 6 components,
  an `eroded` flag of 0/1 to threshold on, SPH bodies as points with point
  data (Polyvertex, no cell data), the interface's link states on the
  particle's nodes.

usage: xdmf_meshio_check.py SPLAT SOURCE_DIR WORK_DIR
"""

import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

import meshio

FE_CELL = ["plastic_strain", "temperature [K]", "damage", "yield_stress [Pa]", "von_mises [Pa]",
           "pressure [Pa]", "stress [Pa]", "eroded"]


def run(splat, scene, out, *sets):
    if os.path.isdir(out):
        shutil.rmtree(out)
    cmd = [splat, "run", scene, "--threads", "1", "--out", out]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode not in (0, 3):
        raise SystemExit(f"{' '.join(cmd)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    name = os.path.splitext(os.path.basename(scene))[0]
    xmf = os.path.join(out, name + ".xmf")
    assert f"(ParaView: {xmf})" in p.stdout, p.stdout
    return os.path.join(out, name + ".h5"), xmf


def one_grid_file(grid, path):
    """A grid of the time series as an XDMF file of its own (meshio.read takes one grid)."""
    root = ET.Element("Xdmf", Version="3.0")
    domain = ET.SubElement(root, "Domain")
    copy = ET.SubElement(domain, "Grid", Name=grid.get("Name"), GridType="Uniform")
    for child in grid:
        if child.tag != "Time":
            copy.append(child)
    ET.ElementTree(root).write(path, xml_declaration=True)
    return meshio.read(path, file_format="xdmf")


def check_grid(mesh, body, sph, where):
    assert len(mesh.points) > 0, where
    n_cells = sum(len(b.data) for b in mesh.cells)
    assert n_cells > 0, where
    assert "velocity [m/s]" in mesh.point_data, (where, list(mesh.point_data))
    if sph:
        assert [b.type for b in mesh.cells] == ["vertex"], where
        assert n_cells == len(mesh.points), where
        assert not mesh.cell_data, (where, list(mesh.cell_data))
        data = mesh.point_data
        n = len(mesh.points)
    else:
        assert [b.type for b in mesh.cells] in (["quad"], ["hexahedron"]), where
        data = {k: v[0] for k, v in mesh.cell_data.items()}
        n = n_cells
    for name in FE_CELL:
        assert name in data, (where, name, sorted(data))
        assert len(data[name]) == n, (where, name)
    assert data["stress [Pa]"].shape == (n, 6), where
    assert set(np.unique(data["eroded"])) <= {0, 1}, where
    if body == "particle":
        links = mesh.point_data.get("link_state")
        assert links is not None, (where, list(mesh.point_data))
        assert set(np.unique(links)) <= {0, 1, 2, 3, 4}, where
    return data


def check_scene(splat, source, work, scene, *sets, sph=False):
    sys.path.insert(0, os.path.join(source, "python"))
    import splat_results

    name = os.path.splitext(os.path.basename(scene))[0]
    h5, xmf = run(splat, os.path.join(source, "scenes", scene), os.path.join(work, name), *sets)
    root = ET.parse(xmf).getroot()
    temporal = root.find("Domain/Grid")
    assert temporal.get("CollectionType") == "Temporal", xmf
    steps = list(temporal)
    assert len(steps) >= 10, f"{xmf}: {len(steps)} time steps"
    result = splat_results.read_run(h5)
    times = [float(s.find("Time").get("Value")) for s in steps]
    assert times == [s["time"] for s in result["snapshots"]], (times, xmf)
    assert times[0] == 0.0 and times == sorted(times), times
    for k in (0, len(steps) - 1):
        for grid in steps[k].findall("Grid"):
            body = grid.get("Name")
            path = os.path.join(os.path.dirname(h5), f"check_{k}_{body}.xmf")
            mesh = one_grid_file(grid, path)
            where = f"{scene} step {k} body {body}"
            data = check_grid(mesh, body, sph, where)
            # The values are the result file's.
            np.testing.assert_array_equal(
                data["plastic_strain"], result["snapshots"][k]["bodies"][body]["plastic_strain"])
    # The impact happened between the first and the last step.
    last = result["snapshots"][-1]["bodies"]["particle"]["plastic_strain"]
    assert np.max(last) > 0.1, np.max(last)
    print(f"{scene}: {len(steps)} steps, bodies "
          f"{[g.get('Name') for g in steps[-1].findall('Grid')]} read by meshio {meshio.__version__}")


def main(argv):
    splat, source, work = (os.path.abspath(a) for a in argv[1:4])
    os.makedirs(work, exist_ok=True)
    check_scene(splat, source, work, "impact_al_al.json")
    # A coarse SPH ball (3 across) keeps the run short; the format is the same.
    check_scene(splat, source, work, "impact_al_al_sph.json",
                "/particle_impact/particle/elements_across=3", sph=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
