#!/usr/bin/python3
"""Log-log plot of frames per second against triangle count from
bench_complexity's CSV (the thesis' figure 3.5).

    /usr/bin/python3 benchmarks/plot_complexity.py \
        benchmarks/results/complexity.csv benchmarks/results/complexity.png

Needs Debian's python3-matplotlib (hence /usr/bin/python3). One line per
backend and structure; a structure skipped at a level (its frame would have
taken too long) has no point there, and the legend says from where.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    ("cpu", "bvh"): ("C0", "o-", "CPU (OpenMP), BVH"),
    ("cpu", "flat"): ("C0", "s--", "CPU (OpenMP), flat list"),
    ("opencl", "bvh"): ("C1", "o-", "OpenCL (PoCL), BVH"),
    ("opencl", "flat"): ("C1", "s--", "OpenCL (PoCL), flat list"),
}


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_complexity.py COMPLEXITY.csv OUT.png")
    series = {}
    skipped = {}
    size = None
    try:
        with open(sys.argv[1], newline="") as f:
            for row in csv.DictReader(f):
                key = (row["backend"], row["accel"])
                triangles = int(row["triangles"])
                size = (row["width"], row["height"], row["cores"])
                if row["status"] == "measured":
                    series.setdefault(key, []).append((triangles, float(row["fps"])))
                else:
                    skipped.setdefault(key, triangles)
                    skipped[key] = min(skipped[key], triangles)
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"plot_complexity.py: {sys.argv[1]}: not a bench_complexity CSV ({e})")
    if not series:
        sys.exit(f"plot_complexity.py: {sys.argv[1]}: no measurements")

    fig, ax = plt.subplots(figsize=(7, 5), dpi=110)
    for key in sorted(series, key=lambda k: (k[1] != "bvh", k[0])):
        colour, fmt, label = STYLE.get(key, (None, "x-", f"{key[0]}, {key[1]}"))
        if key in skipped:
            label += f" (skipped from {skipped[key]:,} triangles)"
        points = sorted(series[key])
        ax.loglog([p[0] for p in points], [p[1] for p in points], fmt, color=colour, label=label)
    ax.set_xlabel("triangles")
    ax.set_ylabel(f"frames per second on {size[2]} free cores (from CPU time)")
    ax.set_title(f"Scene complexity: Cornell box + 16 icospheres, {size[0]} x {size[1]}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    try:
        fig.savefig(sys.argv[2])
    except OSError as e:
        sys.exit(f"plot_complexity.py: {sys.argv[2]}: {e}")


if __name__ == "__main__":
    main()
