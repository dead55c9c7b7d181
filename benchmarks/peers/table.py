#!/usr/bin/env python3
"""table.py RUNS.tsv REFERENCE.pfm HALF1.pfm HALF2.pfm TARGET: run.sh's table.
table.py --mean OUT.pfm A.pfm B.pfm: OUT = (A + B) / 2 (the reference).

RUNS.tsv: one line a render, tab-separated: renderer, round, spp, seed,
render seconds, image (PFM). REFERENCE.pfm is the mean of HALF1 and HALF2,
two renders of half its samples with independent seeds, so that its own
noise is measured, not guessed: its per-pixel variance is a quarter of
E|HALF1 - HALF2|^2, and so

    MSE_ref = MSE(HALF1, HALF2) / 4.

A render's MSE against the reference is its own plus the reference's (the
two are independent), so its own is MSE(render, reference) - MSE_ref.
Prints a markdown table: per renderer the spp, the RMSE against the
reference (the mean MSE of the rounds), the RMSE with the reference's noise
taken out, the RMSE from pairs of rounds (MSE(a, b) / 2: each renderer's
noise measured without the reference; it matches the previous column where
the renderer and the reference agree on the scene), the median render time
and the time to TARGET, median time x (RMSE / TARGET)^2 (the error of an
unbiased render falls as 1 / spp), then the ratios of trac0r's time to the
others'. RMSE as trac0r's image_error (benchmarks/mitsuba/rmse.py).
"""

import collections
import os
import statistics
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mitsuba"))
from rmse import read_pfm  # noqa: E402


def mse(a, b):
    if a.shape != b.shape:
        raise SystemExit("images of different sizes: %s and %s" % (a.shape, b.shape))
    d = a.astype(np.float64) - b.astype(np.float64)
    return float(np.mean(d * d))  # rmse.py's sum / (3 n)


def write_pfm(path, image):
    """As trac0r's write_pfm: little-endian (scale -1), bottom row first."""
    h, w, _ = image.shape
    with open(path, "wb") as f:
        f.write(("PF\n%d %d\n-1.0\n" % (w, h)).encode("ascii"))
        f.write(np.ascontiguousarray(image[::-1], dtype="<f4").tobytes())


def main():
    if len(sys.argv) == 5 and sys.argv[1] == "--mean":
        a, b = read_pfm(sys.argv[3]), read_pfm(sys.argv[4])
        if a.shape != b.shape:
            raise SystemExit("images of different sizes: %s and %s" % (a.shape, b.shape))
        write_pfm(sys.argv[2], ((a.astype(np.float64) + b) / 2.0).astype(np.float32))
        return
    if len(sys.argv) != 6:
        raise SystemExit(__doc__.split("\n")[0])
    runs_path, ref_path, half1_path, half2_path = sys.argv[1:5]
    target = float(sys.argv[5])
    ref = read_pfm(ref_path)
    mse_ref = mse(read_pfm(half1_path), read_pfm(half2_path)) / 4.0
    h, w = ref.shape[:2]

    runs = collections.OrderedDict()
    with open(runs_path) as f:
        for line in f:
            if not line.strip():
                continue
            name, rnd, spp, seed, seconds, image = line.rstrip("\n").split("\t")
            runs.setdefault(name, []).append(
                dict(round=int(rnd), spp=int(spp), seed=int(seed), seconds=float(seconds),
                     image=read_pfm(image)))

    print("Reference: %s, %dx%d; its own RMSE %.5f (MSE %.3g = MSE(half 1, half 2) / 4, "
          "%.1f %% of the target's MSE %.3g; taken out of each render's MSE below)"
          % (os.path.basename(ref_path), w, h, mse_ref ** 0.5, mse_ref,
             100.0 * mse_ref / target ** 2, target ** 2))
    print()
    print("| renderer | spp | rounds | RMSE vs reference | RMSE, reference noise out "
          "| RMSE from round pairs | render s, median (min-max) | s to RMSE %g |" % target)
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    to_target = {}
    for name, rs in runs.items():
        spps = sorted({r["spp"] for r in rs})
        raw = statistics.fmean(mse(r["image"], ref) for r in rs)
        own = raw - mse_ref
        pairs = [mse(a["image"], b["image"]) / 2.0
                 for i, a in enumerate(rs) for b in rs[i + 1:] if a["seed"] != b["seed"]]
        pair_rmse = "%.5f" % statistics.fmean(pairs) ** 0.5 if pairs else "-"
        times = [r["seconds"] for r in rs]
        t = statistics.median(times)
        to_target[name] = t * own / target ** 2 if own > 0.0 else float("nan")
        print("| %s | %s | %d | %.5f | %.5f | %s | %.2f (%.2f-%.2f) | %.1f |"
              % (name, "/".join(map(str, spps)), len(rs), raw ** 0.5,
                 max(own, 0.0) ** 0.5, pair_rmse, t, min(times), max(times),
                 to_target[name]))
    print()
    base = next(iter(runs))
    for name in runs:
        if name != base:
            print("%s / %s, time to RMSE %g: %.2f" % (base, name, target,
                                                     to_target[base] / to_target[name]))
    print()
    print("Per round (RMSE vs reference, render s):")
    for name, rs in runs.items():
        print("  %s: %s" % (name, ", ".join(
            "r%d %.5f %.2f" % (r["round"], mse(r["image"], ref) ** 0.5, r["seconds"])
            for r in rs)))


if __name__ == "__main__":
    main()
