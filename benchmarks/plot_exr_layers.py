#!/usr/bin/env python3
"""docs/exr_layers.png: an EXR written with --exr-layers all, side by side:
the image (sRGB, clipped at 1), albedo, normal (xyz as rgb, (n + 1) / 2),
depth (near is light; nothing hit is black) and the square root of the
variance (scaled to its 99th percentile).

    build/trac0r_viewer scenes/cornell.json --headless --spp 64 \\
        --width 320 --height 240 --output cornell.exr --exr-layers all
    python3 -m venv /tmp/exr && /tmp/exr/bin/pip install numpy OpenEXR pillow
    /tmp/exr/bin/python benchmarks/plot_exr_layers.py cornell.exr docs/exr_layers.png

Needs PyPI's OpenEXR, numpy and pillow (measurement and docs only; never
the build or the tests).
"""
import sys

import numpy as np
import OpenEXR
from PIL import Image


def srgb(linear):
    v = np.clip(linear, 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)
    return (s * 255.0 + 0.5).astype(np.uint8)


def main():
    source, target = sys.argv[1], sys.argv[2]
    channels = OpenEXR.File(source).channels()
    image = channels["RGB"].pixels.astype(np.float64)
    albedo = channels["albedo"].pixels.astype(np.float64)
    normal = np.stack([channels["normal." + a].pixels for a in "XYZ"], axis=-1)
    depth = channels["Z"].pixels.astype(np.float64)
    variance = channels["variance.Y"].pixels.astype(np.float64)

    hit = np.isfinite(depth)
    near, far = depth[hit].min(), depth[hit].max()
    grey = np.where(hit, 1.0 - (np.where(hit, depth, far) - near) / (far - near), 0.0)
    spread = np.sqrt(np.where(np.isfinite(variance), variance, 0.0))
    spread /= max(np.percentile(spread, 99), 1e-12)

    def rgb8(a):
        return (np.clip(a, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)

    panels = [srgb(image), srgb(albedo), rgb8((normal + 1.0) / 2.0),
              rgb8(np.repeat(grey[..., None], 3, axis=2)),
              rgb8(np.repeat(spread[..., None], 3, axis=2))]
    gap = np.full((image.shape[0], 4, 3), 255, dtype=np.uint8)
    row = [panels[0]]
    for p in panels[1:]:
        row += [gap, p]
    Image.fromarray(np.concatenate(row, axis=1)).save(target, optimize=True)


if __name__ == "__main__":
    main()
