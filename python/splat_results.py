"""Reads splat results into numpy arrays and dicts.

A run's result file (``splat run ... --out DIR`` writes ``DIR/<scene>.h5``;
layout in solver/io/result_file.hpp) and a campaign store (``splat sweep
... --db FILE``; tables in campaign/README.md). Needs h5py and numpy
(Debian: python3-h5py, python3-numpy); sqlite3 is in the standard library.

    import splat_results as sr
    run = sr.read_run("out/impact_al_al.h5")
    run["histories"]["time"], run["units"]["kinetic"]   # numpy array, "J"
    snap = run["snapshots"][-1]                         # the final state
    snap["time"], snap["bodies"]["particle"]["plastic_strain"]
    store = sr.read_store("out/demo/campaign.db")
    store["windows"][0]["critical_velocity"]            # m/s or None
    sr.job_histories("out/demo/campaign.db", store["jobs"][0]["hash"])

Every array is in SI units; ``units`` maps each name to its unit. Values
are read whole into memory (an FE impact run: well under a MB).

Run as a script, ``python3 splat_results.py FILE.h5|FILE.db`` prints what
the file holds.
"""

import json
import os
import sqlite3
import sys

import numpy as np

__all__ = ["read_run", "read_store", "job_histories", "result_path", "ResultFileMissing"]


class ResultFileMissing(FileNotFoundError):
    """A store names a result file that is not there (copied without its jobs folder?)."""


def _text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def _attributes(obj):
    out = {}
    for key, value in obj.attrs.items():
        if isinstance(value, (bytes, str)):
            out[key] = _text(value)
        elif np.ndim(value) == 0:
            out[key] = value.item() if hasattr(value, "item") else value
        else:
            out[key] = np.asarray(value)
    return out


def read_run(h5_path, snapshots=True):
    """The whole result file of one run.

    Returns a dict:
      attributes: the root attributes (summary figures, scene, solver_version;
                  a number's unit is the attribute <name>_unit)
      histories:  column name -> 1D float64 array, one value per history row
      units:      column name -> unit ("s", "J", "m/s", "-")
      bodies:     body name -> {"cell_kind": "quad4"|"hex8"|"point",
                  "dimension": 2|3, "connectivity": int array (cells x nodes)}
      snapshots:  list (in time order) of {"time": s, "bodies": {body:
                  {field: array}}, "units": {body: {field: unit}},
                  "centers": {body: {field: "node"|"cell"}}}; fields include
                  "coordinates" (m), "active" and "eroded" (0/1 per cell);
                  empty when the run wrote none or snapshots=False
    """
    import h5py

    h5_path = os.fspath(h5_path)
    if not os.path.isfile(h5_path):
        raise ResultFileMissing(f"result file '{h5_path}' does not exist")
    with h5py.File(h5_path, "r") as f:
        if _text(f.attrs.get("format", "")) != "splat-result":
            raise ValueError(f"'{h5_path}' is not a splat result file (no format attribute)")
        run = {"path": h5_path, "attributes": _attributes(f), "histories": {}, "units": {},
               "bodies": {}, "snapshots": []}
        # Columns in creation order (the order the writer gave them).
        history = f["history"]
        for name in _ordered(history):
            run["histories"][name] = np.asarray(history[name][()], dtype=np.float64)
            run["units"][name] = _text(history[name].attrs.get("unit", ""))
        rows = min((len(v) for v in run["histories"].values()), default=0)
        for name in run["histories"]:  # a run cut while appending: complete rows only
            run["histories"][name] = run["histories"][name][:rows]
        for name in _ordered(f["bodies"]):
            c = f["bodies"][name]["connectivity"]
            run["bodies"][name] = {"cell_kind": _text(c.attrs["cell_kind"]),
                                   "dimension": int(c.attrs["dimension"]),
                                   "connectivity": np.asarray(c[()])}
        if snapshots:
            group = f["snapshots"]
            for k in sorted(group.keys(), key=int):
                s = group[k]
                snap = {"time": float(s.attrs["time"]), "bodies": {}, "units": {}, "centers": {}}
                for body in _ordered(s):
                    fields, units, centers = {}, {}, {}
                    for field in _ordered(s[body]):
                        d = s[body][field]
                        fields[field] = np.asarray(d[()])
                        units[field] = _text(d.attrs.get("unit", ""))
                        centers[field] = _text(d.attrs.get("center", "node"))
                    snap["bodies"][body] = fields
                    snap["units"][body] = units
                    snap["centers"][body] = centers
                run["snapshots"].append(snap)
    return run


def _ordered(group):
    """Link names of an HDF5 group in creation order (the writer tracks it;
    h5py lists a tracked group in that order)."""
    return list(group.keys())


def result_path(db_path, stored):
    """The absolute path of a result file as a store records it: relative to
    the store's folder (new stores) or absolute (older ones); None for none."""
    if not stored:
        return None
    if os.path.isabs(stored):
        return stored
    folder = os.path.dirname(os.path.abspath(os.fspath(db_path)))
    return os.path.normpath(os.path.join(folder, stored))


def _connect(db_path):
    db_path = os.fspath(db_path)
    if not os.path.isfile(db_path):
        raise FileNotFoundError(f"store '{db_path}' does not exist")
    # Read-only: a reader never changes a store a running sweep writes.
    con = sqlite3.connect(f"file:{os.path.abspath(db_path)}?mode=ro", uri=True)
    con.row_factory = sqlite3.Row
    return con


def read_store(db_path):
    """A campaign store's campaigns, windows and jobs.

    Returns a dict of lists of dicts:
      campaigns: id, name, state, executor, tags (list), spec (dict)
      windows:   campaign_id, params (dict), critical_velocity and
                 maximum_velocity (m/s, None when open), window (the full
                 window document: brackets, intervals, unclassified jobs)
      jobs:      one row per campaign point: campaign_id, params (dict),
                 velocity (m/s), origin, hash, state, outcome (None before a
                 result), reason, wall_seconds (s), threads, hdf5_path
                 (absolute, None without a file), summary (dict or None)
    and "velocities": campaign id -> float64 array of the points' velocities
    in the order of "jobs" (for plotting).
    """
    with _connect(db_path) as con:
        campaigns = []
        for r in con.execute("SELECT id, name, state, executor, tags, spec FROM campaigns "
                             "ORDER BY id"):
            campaigns.append({"id": r["id"], "name": r["name"], "state": r["state"],
                              "executor": r["executor"], "tags": json.loads(r["tags"] or "[]"),
                              "spec": json.loads(r["spec"] or "{}")})
        windows = []
        for r in con.execute("SELECT campaign_id, params, critical_velocity, maximum_velocity, "
                             "window FROM windows ORDER BY campaign_id, params_key"):
            windows.append({"campaign_id": r["campaign_id"], "params": json.loads(r["params"]),
                            "critical_velocity": r["critical_velocity"],
                            "maximum_velocity": r["maximum_velocity"],
                            "window": json.loads(r["window"])})
        jobs = []
        for r in con.execute(
                "SELECT p.campaign_id, p.params, p.velocity, p.origin, p.job_hash, j.state, "
                "j.wall_seconds, j.threads, r.outcome, r.reason, r.summary, r.hdf5_path "
                "FROM campaign_points p JOIN jobs j ON j.hash = p.job_hash "
                "LEFT JOIN results r ON r.job_hash = p.job_hash "
                "ORDER BY p.campaign_id, p.params_key, p.velocity"):
            jobs.append({"campaign_id": r["campaign_id"], "params": json.loads(r["params"]),
                         "velocity": r["velocity"], "origin": r["origin"], "hash": r["job_hash"],
                         "state": r["state"], "outcome": r["outcome"], "reason": r["reason"],
                         "wall_seconds": r["wall_seconds"], "threads": r["threads"],
                         "hdf5_path": result_path(db_path, r["hdf5_path"]),
                         "summary": json.loads(r["summary"]) if r["summary"] else None})
    velocities = {}
    for c in campaigns:
        velocities[c["id"]] = np.array([j["velocity"] for j in jobs
                                        if j["campaign_id"] == c["id"]], dtype=np.float64)
    return {"path": os.fspath(db_path), "campaigns": campaigns, "windows": windows,
            "jobs": jobs, "velocities": velocities}


def job_histories(db_path, job_hash):
    """The histories (and their units) of one job of a store: read_run's
    "histories" and "units". Raises ResultFileMissing naming the file when
    the store records one that is not there, LookupError without a result."""
    with _connect(db_path) as con:
        r = con.execute("SELECT hdf5_path FROM results WHERE job_hash = ?", (job_hash,)).fetchone()
    if r is None:
        raise LookupError(f"job {job_hash} has no result in '{db_path}'")
    path = result_path(db_path, r["hdf5_path"])
    if path is None:
        raise LookupError(f"job {job_hash} wrote no result file")
    if not os.path.isfile(path):
        raise ResultFileMissing(
            f"job {job_hash}: result file '{path}' is missing (was the store copied "
            f"without its jobs folder '{os.fspath(db_path)}.jobs'?)")
    run = read_run(path, snapshots=False)
    return {"histories": run["histories"], "units": run["units"]}


def _main(argv):
    if len(argv) != 2:
        print("usage: splat_results.py FILE.h5|STORE.db", file=sys.stderr)
        return 2
    path = argv[1]
    if path.endswith(".h5"):
        run = read_run(path)
        rows = len(run["histories"].get("time", []))
        print(f"{path}: {len(run['histories'])} history columns x {rows} rows, "
              f"{len(run['snapshots'])} snapshots, bodies {', '.join(run['bodies'])}")
        for s in run["snapshots"]:
            sizes = ", ".join(f"{b} {len(f['coordinates'])} nodes" for b, f in s["bodies"].items())
            print(f"  t = {s['time']:.4e} s: {sizes}")
    else:
        store = read_store(path)
        print(f"{path}: {len(store['campaigns'])} campaigns, {len(store['jobs'])} jobs, "
              f"{len(store['windows'])} windows")
        for w in store["windows"]:
            print(f"  campaign {w['campaign_id']} {json.dumps(w['params'])}: critical "
                  f"{w['critical_velocity']} m/s, maximum {w['maximum_velocity']} m/s")
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv))
