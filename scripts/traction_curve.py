#!/usr/bin/env python3
"""Force-displacement curves of the traction test (thesis 3.2) from result files.

Plots <set>_reaction_z against <set>_displacement_z of each result file
(`splat run scenes/thesis/traction_cylinder_axisym.json --out DIR`), with the
uniform-bar closed form of its material (the resolved scene in the file):
F = E eps A0 exp(-2 nu eps) while elastic, sigma_y(eps_p, v / L, T) A0
exp(-eps_p - 2 nu sigma / E) once plastic, T adiabatic
(tests/exact/uniform_bar_tension.hpp, written again here for the plot).

    python3 scripts/traction_curve.py OUT.png RUN.h5 [RUN.h5 ...] [--set pulled_end]
"""
import argparse
import json
import math

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def closed_form(scene, u_values, speed):
    """The uniform bar's force (N) at each elongation u (m), Johnson-Cook bodies only."""
    body = scene["bodies"][0]
    mat, geo, sw = body["material"], body["geometry"], body["switches"]
    st = mat["strength"]
    E, nu = mat["elastic"]["E"], mat["elastic"]["nu"]
    L0 = geo["z_max"] - geo["z_min"]
    A0 = math.pi * geo["radius"] ** 2
    heating = mat["thermal"]["heat_fraction"] / (mat["density"] * mat["thermal"]["c_p"])
    T0 = body["initial"]["temperature"]

    def sigma(eps_p, rate, T):
        h = st["A"] + st["B"] * max(eps_p, 0.0) ** st["n"]
        r = 1.0 + st["C"] * math.log(max(rate / st["eps_dot_0"], 1.0)) if sw["rate_hardening"] else 1.0
        t = (T - st["T_ref"]) / (st["T_melt"] - st["T_ref"]) if sw["thermal_softening"] else 0.0
        return h * r * (1.0 - min(max(t, 0.0), 1.0) ** st["m"])

    out = []
    for u in u_values:
        eps, rate = math.log1p(u / L0), speed / (L0 + u)
        if E * eps <= sigma(0.0, rate, T0):
            out.append(E * eps * A0 * math.exp(-2 * nu * eps))
            continue
        steps, eps_p, T = 2000, 0.0, T0
        d = eps / steps
        s = sigma(0.0, rate, T)
        while eps_p + s / E < eps:
            s_pred = sigma(eps_p + d, rate, T + heating * s * d)
            T += heating * 0.5 * (s + s_pred) * d
            eps_p += d
            s = sigma(eps_p, rate, T)
        out.append(s * A0 * math.exp(-eps_p - 2 * nu * s / E))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("png")
    parser.add_argument("results", nargs="+")
    parser.add_argument("--set", default="pulled_end", help="named boundary condition")
    parser.add_argument("--speed", type=float, default=2.4, help="pull speed after the ramp, m/s")
    args = parser.parse_args()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for path in args.results:
        with h5py.File(path, "r") as f:
            h = f["history"]
            u = h[args.set + "_displacement_z"][:]
            force = h[args.set + "_reaction_z"][:]
            assert h[args.set + "_reaction_z"].attrs["unit"] == "N"
            scene = json.loads(f.attrs["scene"])
        body = scene["bodies"][0]
        label = "%d across, softening %s" % (
            body["discretization"]["elements_across"],
            "on" if body["switches"]["thermal_softening"] else "off",
        )
        ax.plot(u * 1e3, force * 1e-3, label="splat " + label)
        ax.plot(u[::20] * 1e3, [x * 1e-3 for x in closed_form(scene, u[::20], args.speed)], "k:",
                label="uniform bar (before necking), softening %s"
                % ("on" if body["switches"]["thermal_softening"] else "off"))
    ax.set_xlabel("elongation [mm]")
    ax.set_ylabel("force [kN]")
    ax.set_title("Traction test (thesis 3.2): al-thesis cylinder 40 x 120 mm, 2.4 m/s")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)


if __name__ == "__main__":
    main()
