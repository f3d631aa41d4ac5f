"""python/splat_results.py on a real run and a real store (ctest
integration.python_reader; needs python3-h5py, python3-numpy).

- read_run on `splat run scenes/impact_al_al_temperature.json`: the histories and their
  units, the figures of the summary as root attributes, the snapshots in
  time order with the bodies' coordinates and fields, and the histories
  agree with the summary the run printed (end time, particle velocity);
- read_store on a two-velocity sweep of the same scene: campaigns, jobs with
  outcomes and result paths (files with histories and no snapshots),
  windows; job_histories of a job;
- the store folder copied elsewhere (and the original removed) still gives
  every job's histories; without its jobs folder it raises
  ResultFileMissing naming the file.

usage: python_reader_check.py SPLAT SOURCE_DIR WORK_DIR
"""

import json
import os
import shutil
import subprocess
import sys

import numpy as np


def check_run(splat, source, work, sr):
    out = os.path.join(work, "run")
    shutil.rmtree(out, ignore_errors=True)
    scene = os.path.join(source, "scenes", "impact_al_al_temperature.json")
    # 600 m/s: above the scene's critical velocity, a stick to read.
    p = subprocess.run([splat, "run", scene, "--threads", "1", "--out", out, "--json",
                        "--set", "/particle_impact/velocity=600"],
                       capture_output=True, text=True, check=True)
    summary = json.loads(p.stdout)
    run = sr.read_run(os.path.join(out, "impact_al_al_temperature.h5"))

    h = run["histories"]
    assert run["units"]["time"] == "s" and run["units"]["kinetic"] == "J", run["units"]
    assert run["units"]["particle_vz"] == "m/s"
    n = len(h["time"])
    assert n > 100 and all(len(v) == n for v in h.values()), n
    assert isinstance(h["kinetic"], np.ndarray) and h["kinetic"].dtype == np.float64
    assert np.all(np.diff(h["time"]) > 0)
    assert h["time"][-1] == summary["end_time"], (h["time"][-1], summary["end_time"])
    # The particle's final velocity in the histories is the summary's.
    particle = next(b for b in summary["bodies"] if b["name"] == "particle")
    assert abs(h["particle_vz"][-1] - particle["centroid_velocity"][2]) <= 1e-9 * 600
    # The energy at the start: all kinetic.
    assert abs(h["kinetic"][0] / summary["energy"]["initial_total"] - 1) < 1e-12

    a = run["attributes"]
    assert a["outcome"] == summary["outcome"] == "stick", (a.get("outcome"), summary["outcome"])
    assert a["scene_name"] == "impact_al_al_temperature"

    snaps = run["snapshots"]
    assert len(snaps) >= 10, len(snaps)
    times = [s["time"] for s in snaps]
    assert times[0] == 0.0 and times == sorted(times) and times[-1] == summary["end_time"]
    bodies = run["bodies"]
    assert set(bodies) == {"particle", "substrate"}, bodies
    conn = bodies["particle"]["connectivity"]
    assert bodies["particle"]["cell_kind"] == "quad4" and conn.shape[1] == 4
    last = snaps[-1]["bodies"]["particle"]
    assert last["coordinates"].shape == (conn.max() + 1, 2), last["coordinates"].shape
    assert last["plastic_strain"].shape == (conn.shape[0],)
    assert last["stress"].shape == (conn.shape[0], 6)
    assert snaps[-1]["units"]["particle"]["temperature"] == "K"
    assert snaps[-1]["centers"]["particle"]["temperature"] == "cell"
    # The summary's largest plastic strain is that of the live elements of the final state.
    live = last["active"] == 1
    assert last["plastic_strain"][live].max() == summary["max_plastic_strain"]
    assert np.array_equal(last["eroded"], 1 - last["active"])
    # The particle flattened: its height shrank from the first snapshot to the last.
    z0 = snaps[0]["bodies"]["particle"]["coordinates"][:, 1]
    z1 = last["coordinates"][:, 1]
    assert np.ptp(z1) < 0.9 * np.ptp(z0), (np.ptp(z0), np.ptp(z1))
    print(f"run: {n} history rows, {len(snaps)} snapshots")


def check_store(splat, source, work, sr):
    folder = os.path.join(work, "store")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    spec = os.path.join(folder, "campaign.json")
    with open(spec, "w") as f:
        json.dump({"name": "reader", "base_scene": os.path.join(source, "scenes",
                                                               "impact_al_al_temperature.json"),
                   "velocity": {"values": [100, 600]}, "job": {"time_limit": 120}}, f)
    db = os.path.join(folder, "c.db")
    subprocess.run([splat, "sweep", spec, "--db", db], capture_output=True, text=True, check=True)

    store = sr.read_store(db)
    assert [c["name"] for c in store["campaigns"]] == ["reader"], store["campaigns"]
    jobs = store["jobs"]
    assert [j["velocity"] for j in jobs] == [100.0, 600.0], jobs
    assert all(j["state"] == "succeeded" for j in jobs), [j["state"] for j in jobs]
    assert jobs[1]["outcome"] == "stick", jobs[1]["outcome"]
    assert all(os.path.isabs(j["hdf5_path"]) and os.path.isfile(j["hdf5_path"]) for j in jobs)
    # Campaign jobs keep to histories: no field snapshots unless the base scene asks.
    assert all(not sr.read_run(j["hdf5_path"])["snapshots"] for j in jobs)
    assert list(store["velocities"][1]) == [100.0, 600.0]
    assert len(store["windows"]) == 1 and store["windows"][0]["params"] == {}
    w = store["windows"][0]
    assert w["critical_velocity"] is not None and 100 < w["critical_velocity"] < 600, w
    histories = sr.job_histories(db, jobs[1]["hash"])["histories"]
    assert histories["time"][-1] == jobs[1]["summary"]["end_time"]

    # The folder copied elsewhere, the original gone: the paths follow the store.
    moved = os.path.join(work, "moved")
    shutil.rmtree(moved, ignore_errors=True)
    shutil.copytree(folder, moved)
    shutil.rmtree(folder)
    moved_db = os.path.join(moved, "c.db")
    for j in sr.read_store(moved_db)["jobs"]:
        assert j["hdf5_path"].startswith(moved + os.sep), j["hdf5_path"]
        again = sr.job_histories(moved_db, j["hash"])["histories"]
        assert len(again["time"]) > 0
    # Without its jobs folder: a clear error naming the file, not an empty result.
    shutil.rmtree(moved_db + ".jobs")
    try:
        sr.job_histories(moved_db, jobs[1]["hash"])
    except sr.ResultFileMissing as e:
        assert "is missing" in str(e) and moved_db + ".jobs" in str(e), str(e)
    else:
        raise AssertionError("a missing result file read as histories")
    print(f"store: {len(jobs)} jobs, critical velocity {w['critical_velocity']} m/s")


def main(argv):
    splat, source, work = (os.path.abspath(a) for a in argv[1:4])
    os.makedirs(work, exist_ok=True)
    sys.path.insert(0, os.path.join(source, "python"))
    import splat_results

    check_run(splat, source, work, splat_results)
    check_store(splat, source, work, splat_results)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
