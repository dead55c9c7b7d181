#!/usr/bin/env python3
"""Writes the small equirectangular test maps of benchmarks/envmap/ as
Radiance .hdr (RGBE, flat scanlines), and reads them back as stb_image
(trac0r's reader) does.

    python3 benchmarks/envmap/make_map.py sky /tmp/sky.hdr      # 512 x 256
    python3 benchmarks/envmap/make_map.py halves /tmp/halves.hdr

- sky: a blue gradient above the horizon, a warm brown ground below (both
  times 1 + 0.3 cos 2 pi u), and a bright "sun" patch of 16 x 16 texels
  (radiance 60, about 0.031 sr, irradiance about 1.9 face on) at 35 degrees
  above the horizon, a quarter turn right of the map's middle.
- halves: the convention check: red where u > 1/2 (the right half), green
  where v < 1/2 (the top half), so black, green, red and yellow quarters.

Measurement only; needs numpy.
"""

import math
import sys

import numpy as np


def sky_map(width=512, height=256):
    v = (np.arange(height) + 0.5) / height  # 0 at the top row
    u = (np.arange(width) + 0.5) / width
    img = np.zeros((height, width, 3), dtype=np.float64)
    elevation = (0.5 - v) * math.pi  # +pi/2 at the zenith
    for r in range(height):
        if elevation[r] >= 0.0:
            t = math.sin(elevation[r])  # 0 at the horizon, 1 at the zenith
            horizon = np.array([0.9, 0.95, 1.0])
            zenith = np.array([0.15, 0.3, 0.9])
            img[r, :] = (1.0 - t) * horizon + t * zenith
        else:
            img[r, :] = [0.25, 0.18, 0.12]
    # A faint variation across so that the map's turn shows in the images.
    img *= (1.0 + 0.3 * np.cos(2.0 * math.pi * u))[None, :, None]
    # The sun: 16 x 16 texels, 35 degrees up, u = 0.75.
    row = int(round((0.5 - 35.0 / 180.0) * height))
    col = int(round(0.75 * width))
    img[row - 8:row + 8, col - 8:col + 8] = [60.0, 57.0, 52.0]
    return img.astype(np.float32)


def halves_map(width=512, height=256):
    img = np.zeros((height, width, 3), dtype=np.float32)
    img[:, width // 2:, 0] = 1.0
    img[:height // 2, :, 1] = 1.0
    return img


def write_hdr(path, img):
    """RGBE, flat (not run-length) scanlines, top row first ('-Y H +X W')."""
    h, w, _ = img.shape
    m = img.max(axis=2).astype(np.float64)
    mantissa, exponent = np.frexp(m)
    scale = np.where(m > 1e-32, mantissa * 256.0 / np.where(m > 0.0, m, 1.0), 0.0)
    rgbe = np.zeros((h, w, 4), dtype=np.uint8)
    rgbe[..., :3] = np.clip(np.floor(img * scale[..., None]), 0, 255).astype(np.uint8)
    rgbe[..., 3] = np.where(m > 1e-32, exponent + 128, 0).astype(np.uint8)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(("-Y %d +X %d\n" % (h, w)).encode("ascii"))
        f.write(rgbe.tobytes())


def read_hdr(path):
    """An (h, w, 3) float32 array, row 0 at the top, decoded as stb_image's
    stbi__hdr_convert: c * 2^(e - 136), no half-step offset. Reads only
    what write_hdr writes (flat scanlines, '-Y H +X W')."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"\n\n") + 2
    line_end = data.index(b"\n", end)
    fields = data[end:line_end].split()
    if fields[0] != b"-Y" or fields[2] != b"+X":
        raise SystemExit(path + ": expected '-Y H +X W'")
    h, w = int(fields[1]), int(fields[3])
    rgbe = np.frombuffer(data, dtype=np.uint8, count=h * w * 4,
                         offset=line_end + 1).reshape(h, w, 4)
    f = np.where(rgbe[..., 3] > 0,
                 np.ldexp(1.0, rgbe[..., 3].astype(np.int32) - 136), 0.0)
    return (rgbe[..., :3].astype(np.float64) * f[..., None]).astype(np.float32)


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("sky", "halves"):
        raise SystemExit("usage: make_map.py sky|halves OUT.hdr")
    img = sky_map() if sys.argv[1] == "sky" else halves_map()
    write_hdr(sys.argv[2], img)
    back = read_hdr(sys.argv[2])
    print("%s: %d x %d, max %.4g, mean RGB %s" % (sys.argv[2], img.shape[1], img.shape[0],
                                                 back.max(), back.reshape(-1, 3).mean(0)))


if __name__ == "__main__":
    main()
