#!/usr/bin/env python3
"""scripts/validation_window.py on ladders of known values: the table puts
each ladder next to its pair's measurement and correlations with the ratio
splat / measured, and the plot is written.

usage: validation_window_check.py SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def ladder(material, values, status, value, error, maximum=None):
    levels = [{"estimate": v, "half_width": 5.0} for v in values]
    params = {} if material is None else {"/particle_impact/particle/material": material}
    return {
        "campaign_id": 1, "pointer": "/particle_impact/particle/elements_across",
        "levels": [8.0, 16.0, 32.0], "params": params,
        "cost": [{"jobs": 10, "job_seconds": 1.0}, {"jobs": 6, "job_seconds": 2.0},
                 {"jobs": 4, "job_seconds": 8.0}],
        "critical": {"levels": levels, "status": status, "value": value, "error": error,
                     "order": None},
        "maximum": {"levels": [{"estimate": None, "half_width": None}] * 3,
                    "status": "open" if maximum is None else "extrapolated",
                    "value": None if maximum is None else maximum[0],
                    "error": None if maximum is None else maximum[1], "order": None},
    }


def main(source, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    path = os.path.join(work, "ladders.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump([ladder(None, [280.0, 290.0, 270.0], "not-converged", 270.0, 30.0),
                   ladder("cu-ofhc-jc", [600.0, 620.0, 630.0], "extrapolated", 640.0, 12.0,
                          (900.0, 20.0))], f)
    md, png = os.path.join(work, "table.md"), os.path.join(work, "window.png")
    out = subprocess.run([sys.executable, os.path.join(source, "scripts", "validation_window.py"),
                          "--out-md", md, "--out-png", png, path],
                         check=True, capture_output=True, text=True).stdout
    rows = [line for line in out.splitlines() if line.startswith("| ") and "---" not in line]
    assert len(rows) == 3, out
    al = next(r for r in rows if r.startswith("| Al on Al, thesis aluminium (al-thesis-gf) |"))
    # The scene's own material (no material field) is al-thesis-gf: Al on
    # Al, measured 800 m/s [PNAS25]; 270 / 800 = 0.34.
    assert "280 +- 5 / 290 +- 5 / 270 +- 5" in al, al
    assert "270 +- 30 (not-converged)" in al, al
    assert "800 [752, 1066]" in al and "[PNAS25]" in al, al
    assert "| 0.34 | open | 20 |" in al, al
    cu = next(r for r in rows if r.startswith("| Cu (Johnson-Cook) on Cu |"))
    assert "640 +- 12 (extrapolated)" in cu and "not found" in cu, cu
    assert "| 900 +- 20 (extrapolated) |" in cu, cu
    assert "Schmidt 2006 491" in cu and "| - |" in cu, cu
    with open(md, encoding="utf-8") as f:
        assert f.read() == out
    with open(png, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000, len(data)
    print("validation_window: table and plot as expected")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
