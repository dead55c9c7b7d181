#!/usr/bin/env python3
"""Equal-time error of trac0r and Mitsuba 3 on benchmarks/envmap/scene.json.

    python3 benchmarks/envmap/efficiency.py --reference REF.pfm \\
        --seconds 5 10 20 --repeats 3 --out /tmp/envmap_runs

Each repeat runs, for each time T, trac0r (`--headless --seconds T
--threads 1`, its defaults: NEE, Sobol) and then Mitsuba (llvm_ad_rgb, one
thread, `path`, max_depth the scene's) at the spp that takes T seconds at
the rate measured first (a 256-spp calibration render), one process at a
time, alternating. Times: trac0r's own "rendered ... in X s"; Mitsuba's
"render without compiling" (the timed mi.render() call less the kernel
compile time drjit reports). Prints each run and a table of medians of
the RMSE against REF (benchmarks/mitsuba/rmse.py). With --rescore it
renders nothing and scores the images a run left in --out against REF
again (another reference), with the spp and times of the run's log
(--log, this script's output). Measurement only.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(HERE, "..", "mitsuba"))

import rmse  # noqa: E402

SCENE = os.path.join(HERE, "scene.json")
MITSUBA = os.path.join(HERE, "..", "mitsuba", "envmap.py")


def run(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    return out.stdout + out.stderr


def trac0r(viewer, seconds, seed, path):
    text = run([viewer, SCENE, "--headless", "--seconds", str(seconds), "--threads", "1",
                "--seed", str(seed), "--output", path])
    m = re.search(r"rendered (\d+) spp of \S+ in ([\d.]+) s", text)
    return int(m.group(1)), float(m.group(2))


def mitsuba(python, spp, seed, path):
    text = run([python, MITSUBA, "--spp", str(spp), "--threads", "1", "--seed", str(seed),
                "--output", path])
    m = re.search(r"render without compiling: ([\d.]+) s", text)
    return spp, float(m.group(1))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--reference", required=True)
    p.add_argument("--seconds", type=float, nargs="+", default=[5, 10, 20])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--first-seed", type=int, default=100,
                   help="repeat r renders with seed FIRST_SEED + r (another run: other seeds)")
    p.add_argument("--out", default="/tmp/envmap_runs")
    p.add_argument("--viewer", default=os.path.join(ROOT, "build", "trac0r_viewer"))
    p.add_argument("--python", default=sys.executable, help="the Python with Mitsuba")
    p.add_argument("--rescore", action="store_true",
                   help="render nothing: score the images in --out against --reference")
    p.add_argument("--log", help="with --rescore: the output of the run that made them")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    ref = rmse.read_pfm(args.reference)
    if args.rescore:
        rescore(args, ref)
        return

    spp, t = mitsuba(args.python, 256, 999, os.path.join(args.out, "calibrate.pfm"))
    rate = spp / t
    print("Mitsuba calibration: %d spp in %.3f s, %.1f spp/s" % (spp, t, rate), flush=True)

    results = {}  # (renderer, T) -> list of (spp, seconds, rmse)
    for rep in range(args.repeats):
        for seconds in args.seconds:
            seed = args.first_seed + rep
            for name in ("trac0r", "mitsuba"):
                path = os.path.join(args.out, "%s_%gs_%d.pfm" % (name, seconds, rep))
                if name == "trac0r":
                    spp, t = trac0r(args.viewer, seconds, seed, path)
                else:
                    spp, t = mitsuba(args.python, max(1, int(round(seconds * rate))), seed,
                                     path)
                e = rmse.image_error(rmse.read_pfm(path), ref)[0]
                results.setdefault((name, seconds), []).append((spp, t, e))
                print("repeat %d, %s, %g s: %d spp in %.2f s, rmse %.5f"
                      % (rep, name, seconds, spp, t, e), flush=True)

    print_table(args.seconds, results)


def rescore(args, ref):
    results = {}
    with open(args.log) as f:
        for line in f:
            m = re.match(r"repeat (\d+), (\w+), ([\d.]+) s: (\d+) spp in ([\d.]+) s", line)
            if not m:
                continue
            rep, name, seconds = int(m.group(1)), m.group(2), float(m.group(3))
            path = os.path.join(args.out, "%s_%gs_%d.pfm" % (name, seconds, rep))
            e = rmse.image_error(rmse.read_pfm(path), ref)[0]
            results.setdefault((name, seconds), []).append(
                (int(m.group(4)), float(m.group(5)), e))
    print_table(sorted({k[1] for k in results}), results)


def print_table(all_seconds, results):
    print("\n| renderer | target s | median s | median spp | median RMSE | RMSEs |")
    print("| --- | --- | --- | --- | --- | --- |")
    for seconds in all_seconds:
        for name in ("trac0r", "mitsuba"):
            rs = results[(name, seconds)]
            print("| %s | %g | %.2f | %d | %.5f | %s |"
                  % (name, seconds, statistics.median(r[1] for r in rs),
                     statistics.median(r[0] for r in rs),
                     statistics.median(r[2] for r in rs),
                     ", ".join("%.5f" % r[2] for r in rs)))


if __name__ == "__main__":
    main()
