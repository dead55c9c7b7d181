#!/usr/bin/python3
"""Error against frame budget, per mode, from bench_frame_budget's CSVs.

    /usr/bin/python3 benchmarks/plot_frame_budget.py RUN.csv [RUN.csv ...] \\
        --csv OUT.csv --png OUT.png [--images OUT.png --scene NAME --budget MS]

Reads each run's CSV (one scene each; run bench_frame_budget with --images
and --csv, from the directory this script runs in, so that the images'
paths resolve), adds SSIM against the reference, and writes:

- OUT.csv: every row of the inputs with an `ssim` column, without the
  images' paths, and `detail_rmse` and `flat_rmse`: the RMSE of the
  sRGB values a screen shows (as for SSIM) on the tenth of the pixels where
  the reference changes most steeply (its sRGB luminance, smoothed by a
  Gaussian of sigma 1 against its own noise, through a Sobel filter:
  edges, shadow boundaries, highlights), and on the rest: what a filter's
  blur costs shows in the first; `white_share`: the share of the squared
  error behind the RMSE that lies in pixels a screen shows white (the
  reference above 1 in a channel: lamps and their rims);
- OUT.png: one column of panels per scene, one row per metric (RMSE,
  relative MSE, 1 - SSIM), the error against the frame budget, one line per
  mode (raw, filtered, temporal); a budget a mode does not fit is left out.
  The dotted line is the filtered image at the run's --bias-spp: the error
  the filter keeps however many samples go in (its bias, plus the
  reference's own noise);
- with --images: the scene's raw, filtered and temporal frames at the
  budget, the filtered image at --bias-spp, and the reference, tone-mapped,
  with a 3 x enlarged crop of each below.

SSIM (Wang et al. 2004, scikit-image's structural_similarity with a
Gaussian window of sigma 1.5, on the three sRGB channels, data range 1) is
computed on the images as a screen shows them: exposure 1, clamped to
[0, 1], the sRGB curve (trac0r's tonemap_channel), in float, not rounded
to 8 bits. Needs Debian's python3-numpy, python3-matplotlib and
python3-skimage (hence /usr/bin/python3).
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "mitsuba"))
from rmse import read_pfm  # noqa: E402

import matplotlib  # noqa: E402
import matplotlib.ticker  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from skimage.filters import gaussian, sobel  # noqa: E402
from skimage.metrics import structural_similarity  # noqa: E402

MODES = [("raw", "C0", "o"), ("filtered", "C1", "s"), ("temporal", "C2", "^")]
METRICS = [("rmse", "RMSE"), ("relative_mse", "relative MSE"), ("dssim", "1 - SSIM")]


def to_srgb(image):
    """Linear radiance as a screen shows it: clamp to [0, 1], the sRGB curve."""
    v = np.clip(image.astype(np.float64), 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)


def ssim(image, reference):
    return float(structural_similarity(to_srgb(image), to_srgb(reference), channel_axis=2,
                                       data_range=1.0, gaussian_weights=True, sigma=1.5,
                                       use_sample_covariance=False))


def detail_mask(reference, share=0.1):
    """The `share` of pixels where the reference as shown (its sRGB luminance,
    smoothed by a Gaussian of sigma 1 against its own noise) changes most
    steeply (Sobel): edges, shadow boundaries, texture, highlights."""
    shown = to_srgb(reference)
    lum = 0.2126 * shown[..., 0] + 0.7152 * shown[..., 1] + 0.0722 * shown[..., 2]
    gradient = sobel(gaussian(lum, sigma=1.0))
    return gradient >= np.quantile(gradient, 1.0 - share)


def shown_rmse(image, reference, mask):
    """RMSE of the sRGB values a screen shows, over the pixels of mask."""
    d = to_srgb(image)[mask] - to_srgb(reference)[mask]
    return float(np.sqrt(np.mean(d * d)))


def white_share(image, reference):
    """The share of the squared error (linear RGB, as the RMSE) that lies in
    pixels a screen shows white: where the reference exceeds 1 in a channel
    (the lamps and what borders them)."""
    d = np.sum((image.astype(np.float64) - reference.astype(np.float64)) ** 2, axis=2)
    total = float(np.sum(d))
    return float(np.sum(d[reference.max(axis=2) > 1.0])) / total if total > 0.0 else 0.0


def resolve(path, csv_path):
    """An image path as the CSV gives it: from here, or from the CSV's directory."""
    if os.path.exists(path):
        return path
    beside = os.path.join(os.path.dirname(csv_path), path)
    if os.path.exists(beside):
        return beside
    sys.exit(f"plot_frame_budget.py: {csv_path}: image {path} not found (run "
             "bench_frame_budget with --images from this directory)")


def read_rows(paths):
    rows = []
    images = {}
    sizes = {}
    for path in paths:
        try:
            with open(path, newline="") as f:
                for row in csv.DictReader(f):
                    size = (row["width"], row["height"])
                    if sizes.setdefault(row["scene"], size) != size:
                        sys.exit(f"plot_frame_budget.py: {row['scene']} at two resolutions; "
                                 "plot each resolution apart")
                    row["fits"] = row["fits"] == "1"
                    row["budget_ms"] = float(row["budget_ms"]) if row["budget_ms"] else None
                    if row["fits"]:
                        if not row["image"] or not row["reference"]:
                            sys.exit(f"plot_frame_budget.py: {path}: no image paths (run "
                                     "bench_frame_budget with --images)")
                        image = read_pfm(resolve(row["image"], path))
                        reference = read_pfm(resolve(row["reference"], path))
                        row["ssim"] = ssim(image, reference)
                        row["dssim"] = 1.0 - row["ssim"]
                        mask = detail_mask(reference)
                        row["detail_rmse"] = shown_rmse(image, reference, mask)
                        row["flat_rmse"] = shown_rmse(image, reference, ~mask)
                        row["white_share"] = white_share(image, reference)
                        images[(row["scene"], row["budget_ms"], row["mode"], row["spp"])] = image
                        images[(row["scene"], "reference")] = reference
                    rows.append(row)
        except (OSError, KeyError, ValueError) as e:
            sys.exit(f"plot_frame_budget.py: {path}: not a bench_frame_budget CSV ({e})")
    if not rows:
        sys.exit("plot_frame_budget.py: no rows")
    return rows, images


def write_csv(rows, path):
    fields = ["scene", "width", "height", "budget_ms", "mode", "spp", "frames", "used_ms",
              "fits", "rmse", "relative_mse", "psnr", "ssim", "detail_rmse", "flat_rmse",
              "white_share", "reused", "spp_ms", "filter_ms", "temporal_ms", "reference_spp",
              "reference_rel_mse"]
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(fields)
        for row in rows:
            values = []
            for k in fields:
                v = row.get(k, "")
                if k == "fits":
                    v = 1 if v else 0
                elif k == "budget_ms":
                    v = "" if v is None else "%g" % v
                elif k in ("ssim", "detail_rmse", "flat_rmse", "white_share"):
                    v = "%.4f" % v if v != "" else ""
                values.append(v)
            out.writerow(values)


def plot(rows, path):
    scenes = []
    for row in rows:
        if row["scene"] not in scenes:
            scenes.append(row["scene"])
    fig, axes = plt.subplots(len(METRICS), len(scenes), figsize=(4.2 * len(scenes), 9.5),
                             dpi=100, squeeze=False)
    for c, scene in enumerate(scenes):
        mine = [r for r in rows if r["scene"] == scene]
        first = mine[0]
        budgets = sorted({r["budget_ms"] for r in mine if r["budget_ms"] is not None})
        for m, (key, label) in enumerate(METRICS):
            ax = axes[m][c]
            for mode, colour, marker in MODES:
                points = [(r["budget_ms"], float(r[key])) for r in mine
                          if r["mode"] == mode and r["budget_ms"] is not None and r["fits"]]
                if points:
                    ax.loglog([p[0] for p in points], [p[1] for p in points], marker + "-",
                              color=colour, label=mode)
            for r in mine:
                if r["mode"] == "filtered" and r["budget_ms"] is None and r["fits"]:
                    ax.axhline(float(r[key]), color="C1", linestyle=":", linewidth=1,
                               label=f"filtered, {r['spp']} spp")
            ax.set_xticks(budgets)
            ax.set_xticklabels(["%g" % b for b in budgets])
            ax.minorticks_off()
            ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(base=10.0,
                                                                    subs=(1.0, 2.0, 5.0)))
            ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
            ax.set_xlim(budgets[0] / 1.5, budgets[-1] * 1.5)
            ax.grid(True, which="major", alpha=0.3)
            if m == 0:
                ax.set_title(f"{scene}, {first['width']} x {first['height']}")
            if m == len(METRICS) - 1:
                ax.set_xlabel("frame budget, ms")
            if c == 0:
                ax.set_ylabel(label)
            if m == 0 and c == 0:
                ax.legend(fontsize=8)
    fig.suptitle("Error against a converged reference in a frame budget (CPU, NEE, Sobol); "
                 "no point: does not fit", fontsize=10)
    fig.tight_layout()
    fig.savefig(path)


def plot_images(rows, images, scene, budget, path):
    mine = [r for r in rows if r["scene"] == scene]
    if not mine:
        sys.exit(f"plot_frame_budget.py: --scene {scene}: not in the CSVs")
    panels = []
    for mode, _, _ in MODES:
        for r in mine:
            if r["mode"] == mode and r["budget_ms"] == budget and r["fits"]:
                panels.append((f"{mode}, {budget:g} ms ({r['spp']} spp"
                               + (f" x {r['frames']} frames)" if mode == "temporal" else ")"),
                               images[(scene, budget, mode, r["spp"])]))
    for r in mine:
        if r["mode"] == "filtered" and r["budget_ms"] is None and r["fits"]:
            panels.append((f"filtered, {r['spp']} spp", images[(scene, None, "filtered",
                                                                 r["spp"])]))
    panels.append((f"reference, {mine[0]['reference_spp']} spp", images[(scene, "reference")]))
    h, w = panels[-1][1].shape[:2]
    # The crop: a quarter of each side, centred a little below the middle
    # (the objects of the Cornell scenes).
    cw, ch = w // 4, h // 4
    x0, y0 = (w - cw) // 2, (h - ch) // 2 + h // 8
    fig, axes = plt.subplots(2, len(panels), figsize=(3.2 * len(panels), 5.2), dpi=80,
                             squeeze=False)
    for i, (title, image) in enumerate(panels):
        shown = to_srgb(image)
        axes[0][i].imshow(shown, interpolation="nearest")
        axes[0][i].add_patch(matplotlib.patches.Rectangle((x0, y0), cw, ch, fill=False,
                                                          edgecolor="yellow", linewidth=1))
        axes[0][i].set_title(title, fontsize=9)
        axes[1][i].imshow(shown[y0:y0 + ch, x0:x0 + cw], interpolation="nearest")
        for ax in (axes[0][i], axes[1][i]):
            ax.set_xticks([])
            ax.set_yticks([])
    fig.tight_layout()
    fig.savefig(path)


def main():
    parser = argparse.ArgumentParser(
        description="SSIM and plots from bench_frame_budget's CSVs.")
    parser.add_argument("runs", metavar="RUN.csv", nargs="+")
    parser.add_argument("--csv", required=True, metavar="OUT.csv")
    parser.add_argument("--png", required=True, metavar="OUT.png")
    parser.add_argument("--images", metavar="OUT.png",
                        help="the scene's frames at the budget beside the reference")
    parser.add_argument("--scene", help="with --images: the scene (its file's stem)")
    parser.add_argument("--budget", type=float, help="with --images: the budget, ms")
    args = parser.parse_args()
    if args.images and (args.scene is None or args.budget is None):
        parser.error("--images needs --scene and --budget")
    rows, images = read_rows(args.runs)
    write_csv(rows, args.csv)
    plot(rows, args.png)
    if args.images:
        plot_images(rows, images, args.scene, args.budget, args.images)


if __name__ == "__main__":
    main()
