#!/usr/bin/env python3
"""materials_plot.py RESULT.npz OUT.png: the picture of materials.py's
grid, side by side: trac0r, Mitsuba with its stock plugins, and Mitsuba
with trac0r's masking-shadowing (and, for plastic, the smooth coat's
diffuse weight) swapped in (materials.py says how). Each image as trac0r's
standard view shows it: linear radiance clipped at 1, sRGB encoded (the
sky is 1, so nothing here is much brighter). The discs that were averaged
are outlined faintly.

Measurement only; needs matplotlib and numpy (Debian's python3-matplotlib
with /usr/bin/python3).
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def srgb(img):
    v = np.clip(np.nan_to_num(img, nan=0.0), 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("npz")
    p.add_argument("png")
    p.add_argument("--dpi", type=int, default=100)
    args = p.parse_args()

    r = np.load(args.npz)
    panels = [("trac0r", r["trac0r"]), ("Mitsuba 3, stock plugins", r["mitsuba"])]
    if r["mitsuba_g2"].size:
        panels.append(("Mitsuba 3, trac0r's G2 (and\nplastic: smooth-coat diffuse)",
                       r["mitsuba_g2"]))
    rows, rough = [str(x) for x in r["rows"]], r["roughness"]
    h, w, _ = panels[0][1].shape
    fig, axes = plt.subplots(1, len(panels), figsize=(len(panels) * w / args.dpi * 1.0 + 1.2,
                                                        h / args.dpi + 0.7), dpi=args.dpi)
    for k, (ax, (title, img)) in enumerate(zip(axes, panels)):
        ax.imshow(srgb(img), interpolation="nearest")
        ax.contour(r["mask"].astype(float), levels=[0.5], colors=["#ffffff"], linewidths=0.4,
                   alpha=0.35)
        ax.set_title(title, fontsize=8)
        ax.set_xticks([(c + 0.5) * w / len(rough) for c in range(len(rough))])
        ax.set_xticklabels(["r %.1f" % x for x in rough], fontsize=7)
        ax.set_yticks([(i + 0.5) * h / len(rows) for i in range(len(rows))])
        ax.set_yticklabels(rows if k == 0 else [], fontsize=7)
        ax.tick_params(length=0)
    fig.tight_layout(pad=0.3, w_pad=0.4)
    fig.savefig(args.png, facecolor="white")
    print("wrote " + args.png)


if __name__ == "__main__":
    main()
