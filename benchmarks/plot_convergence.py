#!/usr/bin/python3
"""Log-log plot of error against render time from bench_convergence's CSV.

    /usr/bin/python3 benchmarks/plot_convergence.py [--rmse] convergence.csv convergence.png

Needs Debian's python3-matplotlib (hence /usr/bin/python3). One colour per
configuration: solid, the relative MSE against the reference; dashed, the
renderer's own estimate; dotted grey, the time^-1 that Monte Carlo promises.
With --rmse: the RMSE against the reference instead, and time^-1/2 (the
renderer estimates only the relative MSE).
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description="Log-log plot of bench_convergence's CSV.")
    parser.add_argument("--rmse", action="store_true",
                        help="plot the RMSE against the reference, not the relative MSE")
    parser.add_argument("csv", metavar="CONVERGENCE.csv")
    parser.add_argument("png", metavar="OUT.png")
    args = parser.parse_args()
    metric = "rmse" if args.rmse else "rel_mse"
    rows = {}
    reference_noise = 0.0
    try:
        with open(args.csv, newline="") as f:
            for row in csv.DictReader(f):
                rows.setdefault(row["config"], []).append(row)
                reference_noise = float(row["reference_rel_mse"])
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"plot_convergence.py: {args.csv}: not a bench_convergence CSV ({e})")
    if not rows:
        sys.exit(f"plot_convergence.py: {args.csv}: no checkpoints")

    fig, ax = plt.subplots(figsize=(7, 5), dpi=110)
    for i, (config, points) in enumerate(rows.items()):
        colour = f"C{i}"
        t = [float(p["seconds"]) for p in points]
        try:
            error = [float(p[metric]) for p in points]
        except (KeyError, ValueError) as e:
            sys.exit(f"plot_convergence.py: {args.csv}: no {metric} column ({e})")
        est = [(float(p["seconds"]), float(p["estimated_rel_mse"])) for p in points
               if not args.rmse and not math.isnan(float(p["estimated_rel_mse"]))]
        ax.loglog(t, error, "o-", color=colour,
                  label=f"{config}: {'RMSE' if args.rmse else 'rel. MSE'} vs reference")
        if est:
            ax.loglog([e[0] for e in est], [e[1] for e in est], "x--", color=colour,
                      alpha=0.7, label=f"{config}: estimate (no reference)")
    # time^-1 (time^-1/2 for the RMSE) through the first configuration's
    # 8 spp point.
    first = next(iter(rows.values()))
    anchor = next((p for p in first if int(p["spp"]) >= 8), first[-1])
    t0, e0 = float(anchor["seconds"]), float(anchor[metric])
    t_all = [float(p["seconds"]) for pts in rows.values() for p in pts]
    xs = [min(t_all), max(t_all)]
    power = 0.5 if args.rmse else 1.0
    ax.loglog(xs, [e0 * (t0 / x) ** power for x in xs], ":", color="grey",
              label="time$^{-1/2}$" if args.rmse else "time$^{-1}$")
    if reference_noise > 0 and not args.rmse:
        ax.axhline(reference_noise, color="black", lw=0.8, alpha=0.5,
                   label="reference's own noise")
    ax.set_xlabel("render time on free cores (s): CPU time / cores")
    ax.set_ylabel("RMSE" if args.rmse else "relative MSE")
    ax.set_title("Error against render time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.png)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
