#!/usr/bin/env python3
"""Critical velocities of the validation campaigns against measurements.

Reads the resolution ladders of one or more campaign stores (through
`splat windows --db DB --format ladders`) or of ladder JSON files, and writes
a markdown table (each pair: measurement and its source, the classic
correlations, splat's critical velocity per level and its estimate with
error) and a plot (critical velocity per resolution level, error bars, the
measured value and the correlations as bands).

usage: validation_window.py [--splat BIN] [--out-md F] [--out-png F] STORE_OR_JSON...

The measured values and correlations are those of docs/validation_sources.md
(sections 1 and 3); each row names its source key there.
"""
import argparse
import json
import subprocess
import sys

# Published reference values per particle/substrate pair, m/s. "measured":
# (value, low, high, source); "correlations": {name: value}. Sources:
# docs/validation_sources.md.
REFERENCES = {
    ("al-thesis", "al-thesis"): {
        "label": "Al on Al, thesis aluminium, eased damage (al-thesis)",
        "measured": (800.0, 752.0, 1066.0, "[PNAS25] v_cr; [NC24] rebound 752, bond 1066"),
        "correlations": {"Assadi 2003": 685.0, "Schmidt 2006": 607.0},
    },
    ("al-thesis-gf", "al-thesis-gf"): {
        "label": "Al on Al, thesis aluminium (al-thesis-gf)",
        "measured": (800.0, 752.0, 1066.0, "[PNAS25] v_cr; [NC24] rebound 752, bond 1066"),
        "correlations": {"Assadi 2003": 685.0, "Schmidt 2006": 607.0},
    },
    ("al1100-o-jc", "al1100-o-jc"): {
        "label": "Al 1100-O on Al 1100-O",
        "measured": (800.0, 752.0, 1066.0, "[PNAS25] v_cr; [NC24] rebound 752, bond 1066"),
        "correlations": {"Assadi 2003": 685.0, "Schmidt 2006": 607.0},
    },
    ("cu-ofhc-jc", "cu-ofhc-jc"): {
        "label": "Cu (Johnson-Cook) on Cu",
        "measured": None,
        "correlations": {"Assadi 2003": 642.0, "Schmidt 2006": 491.0},
    },
    ("cu-thesis", "cu-thesis"): {
        "label": "Cu (thesis Johnson-Cook) on Cu",
        "measured": None,
        "correlations": {"Assadi 2003": 642.0, "Schmidt 2006": 491.0},
    },
    ("cu-ofhc-ptw", "cu-ofhc-ptw"): {
        "label": "Cu (PTW) on Cu",
        "measured": None,
        "correlations": {"Assadi 2003": 642.0, "Schmidt 2006": 491.0},
    },
}
MATERIAL_POINTER = "/particle_impact/particle/material"
DEFAULT_MATERIAL = "al-thesis-gf"  # scenes/impact_al_al_expansion.json


def load_ladders(source, splat):
    """Ladders of a store (via splat) or of a JSON file written by
    `splat windows --format ladders`."""
    if source.endswith(".json"):
        with open(source, encoding="utf-8") as f:
            return json.load(f)
    out = subprocess.run([splat, "windows", "--db", source, "--format", "ladders"],
                         check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def pair_of(ladder):
    particle = ladder.get("params", {}).get(MATERIAL_POINTER, DEFAULT_MATERIAL)
    return (particle, particle)


def fmt(value, digits=0):
    return "-" if value is None else f"{value:.{digits}f}"


def level_text(levels):
    cells = []
    for lv in levels:
        est, half = lv.get("estimate"), lv.get("half_width")
        cells.append("open" if est is None else f"{est:.0f} +- {half:.0f}")
    return " / ".join(cells)


def edge_text(edge):
    value, error = edge.get("value"), edge.get("error")
    return "open" if value is None else f"{value:.0f} +- {error:.0f} ({edge['status']})"


def table_rows(ladders):
    rows = []
    for ladder in ladders:
        pair = pair_of(ladder)
        ref = REFERENCES.get(pair, {"label": f"{pair[0]} on {pair[1]}", "measured": None,
                                    "correlations": {}})
        crit, maxi = ladder["critical"], ladder["maximum"]
        measured = ref["measured"]
        value, error = crit.get("value"), crit.get("error")
        gap = None if measured is None or value is None else value / measured[0]
        rows.append({
            "label": ref["label"],
            "levels": "/".join(f"{lv:g}" for lv in ladder["levels"]),
            "per_level": level_text(crit["levels"]),
            "splat": edge_text(crit),
            "maximum": edge_text(maxi),
            "measured": "not found" if measured is None
            else f"{measured[0]:.0f} [{measured[1]:.0f}, {measured[2]:.0f}] {measured[3]}",
            "correlations": ", ".join(f"{k} {v:.0f}" for k, v in ref["correlations"].items()),
            "ratio": fmt(gap, 2),
            "jobs": sum(c["jobs"] for c in ladder.get("cost", [])),
        })
    return rows


def write_markdown(rows, path):
    lines = [
        "| pair | elements across | splat critical velocity per level, m/s | splat estimate, m/s "
        "| measured, m/s | correlations, m/s | splat / measured | splat maximum velocity, m/s "
        "| jobs |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        lines.append(f"| {r['label']} | {r['levels']} | {r['per_level']} | {r['splat']} | "
                     f"{r['measured']} | {r['correlations']} | {r['ratio']} | {r['maximum']} | "
                     f"{r['jobs']} |")
    text = "\n".join(lines) + "\n"
    if path:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    return text


def write_plot(ladders, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    drawn = set()  # correlations already drawn (the Cu rows share theirs)
    for i, ladder in enumerate(ladders):
        pair = pair_of(ladder)
        ref = REFERENCES.get(pair, {"label": f"{pair[0]} on {pair[1]}", "measured": None,
                                    "correlations": {}})
        xs, ys, es = [], [], []
        for level, lv in zip(ladder["levels"], ladder["critical"]["levels"]):
            if lv.get("estimate") is not None:
                xs.append(level)
                ys.append(lv["estimate"])
                es.append(lv["half_width"])
        colour = f"C{i}"
        ax.errorbar(xs, ys, yerr=es, marker="o", capsize=3, color=colour,
                    label=f"{ref['label']}: splat")
        if ref["measured"] is not None:
            value, low, high, _ = ref["measured"]
            ax.axhspan(low, high, color=colour, alpha=0.12)
            ax.axhline(value, color=colour, linestyle="--", label=f"{ref['label']}: measured")
        for name, v in ref["correlations"].items():
            if (name, v) in drawn:
                continue
            drawn.add((name, v))
            ax.axhline(v, color="grey", linestyle=":", linewidth=0.8)
            metal = ref["label"].split()[0]
            ax.text(0.01, v, f"{name}, {metal}: {v:.0f}", transform=ax.get_yaxis_transform(),
                    fontsize=7, color="grey", va="bottom")
    ax.set_xscale("log", base=2)
    ax.set_xlabel("elements across the particle radius")
    ax.set_ylabel("critical velocity [m/s]")
    ax.set_title("Critical velocity by resolution against measurements")
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sources", nargs="+", help="campaign stores (.db) or ladder JSON files")
    parser.add_argument("--splat", default="splat", help="the splat binary")
    parser.add_argument("--out-md", help="write the markdown table here")
    parser.add_argument("--out-png", help="write the plot here")
    args = parser.parse_args(argv)
    ladders = []
    for source in args.sources:
        ladders.extend(load_ladders(source, args.splat))
    if not ladders:
        print("no resolution ladder in " + ", ".join(args.sources), file=sys.stderr)
        return 1
    sys.stdout.write(write_markdown(table_rows(ladders), args.out_md))
    if args.out_png:
        write_plot(ladders, args.out_png)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
