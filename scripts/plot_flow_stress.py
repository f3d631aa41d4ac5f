#!/usr/bin/env python3
"""Draws the flow-stress curves that `splat materials --plot NAME` writes.

The CSV (strain_rate, temperature, plastic_strain, flow_stress in SI units)
holds the isothermal flow stress of one library material against plastic
strain at three plastic strain rates and two temperatures, computed by the
solver's own strength law; this script only draws it: one line per rate,
solid at the first temperature and dashed at the second, stress in MPa.

    splat materials --plot cu-ofhc-jc --out cu.csv
    python3 scripts/plot_flow_stress.py cu.csv            # writes cu.png
    python3 scripts/plot_flow_stress.py cu.csv --out f.png
"""
import argparse
import csv
import os
from collections import defaultdict


def read_curves(path):
    """{(rate, T): ([eps_p], [sigma in Pa])} in the order of the file."""
    curves = defaultdict(lambda: ([], []))
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            key = (float(row["strain_rate"]), float(row["temperature"]))
            curves[key][0].append(float(row["plastic_strain"]))
            curves[key][1].append(float(row["flow_stress"]))
    return curves


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="CSV written by splat materials --plot")
    parser.add_argument("--out", help="PNG to write (default: the CSV's name with .png)")
    parser.add_argument("--title", help="plot title (default: the CSV's file name)")
    args = parser.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    curves = read_curves(args.csv)
    temperatures = sorted({T for _, T in curves})
    rates = sorted({rate for rate, _ in curves})
    styles = ["-", "--", ":", "-."]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, rate in enumerate(rates):
        for j, T in enumerate(temperatures):
            eps, sigma = curves[(rate, T)]
            ax.plot(eps, [s * 1e-6 for s in sigma], styles[j % len(styles)], color=f"C{i}",
                    label=f"{rate:g} /s, {T:.0f} K")
    ax.set_xlabel("plastic strain")
    ax.set_ylabel("flow stress, MPa")
    ax.set_title(args.title or os.path.basename(args.csv))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    out = args.out or os.path.splitext(args.csv)[0] + ".png"
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(out)


if __name__ == "__main__":
    main()
