#!/usr/bin/python3
"""Log-log plot of error against render time from bench_convergence's CSV.

    /usr/bin/python3 benchmarks/plot_convergence.py convergence.csv convergence.png

Needs Debian's python3-matplotlib (hence /usr/bin/python3). One colour per
configuration: solid, the relative MSE against the reference; dashed, the
renderer's own estimate; dotted grey, the time^-1 that Monte Carlo promises.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_convergence.py CONVERGENCE.csv OUT.png")
    rows = {}
    reference_noise = 0.0
    try:
        with open(sys.argv[1], newline="") as f:
            for row in csv.DictReader(f):
                rows.setdefault(row["config"], []).append(row)
                reference_noise = float(row["reference_rel_mse"])
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"plot_convergence.py: {sys.argv[1]}: not a bench_convergence CSV ({e})")
    if not rows:
        sys.exit(f"plot_convergence.py: {sys.argv[1]}: no checkpoints")

    fig, ax = plt.subplots(figsize=(7, 5), dpi=110)
    for i, (config, points) in enumerate(rows.items()):
        colour = f"C{i}"
        t = [float(p["seconds"]) for p in points]
        rel = [float(p["rel_mse"]) for p in points]
        est = [(float(p["seconds"]), float(p["estimated_rel_mse"])) for p in points
               if not math.isnan(float(p["estimated_rel_mse"]))]
        ax.loglog(t, rel, "o-", color=colour, label=f"{config}: rel. MSE vs reference")
        if est:
            ax.loglog([e[0] for e in est], [e[1] for e in est], "x--", color=colour,
                      alpha=0.7, label=f"{config}: estimate (no reference)")
    # time^-1 through the first configuration's 8 spp point.
    first = next(iter(rows.values()))
    anchor = next((p for p in first if int(p["spp"]) >= 8), first[-1])
    t0, e0 = float(anchor["seconds"]), float(anchor["rel_mse"])
    t_all = [float(p["seconds"]) for pts in rows.values() for p in pts]
    xs = [min(t_all), max(t_all)]
    ax.loglog(xs, [e0 * t0 / x for x in xs], ":", color="grey", label="time$^{-1}$")
    if reference_noise > 0:
        ax.axhline(reference_noise, color="black", lw=0.8, alpha=0.5,
                   label="reference's own noise")
    ax.set_xlabel("render time on free cores (s): CPU time / cores")
    ax.set_ylabel("relative MSE")
    ax.set_title("Error against render time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(sys.argv[2])
    print(f"wrote {sys.argv[2]}")


if __name__ == "__main__":
    main()
