#!/usr/bin/python3
"""Draws docs/environment_map.png: scenes/maps/sky.hdr as trac0r reads an
equirectangular map, with the directions its columns and rows face.
Needs Debian's python3-matplotlib; run from the repository root:

    /usr/bin/python3 benchmarks/plot_environment_map.py
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_hdr(path):
    """A Radiance RGBE file (flat or new-style run-length scanlines)."""
    data = open(path, "rb").read()
    header_end = data.index(b"\n\n") + 2
    size_end = data.index(b"\n", header_end)
    _, height, _, width = data[header_end:size_end].split()
    width, height = int(width), int(height)
    at = size_end + 1
    rgbe = np.zeros((height, width, 4), np.uint8)
    for row in range(height):
        if data[at] == 2 and data[at + 1] == 2:
            at += 4
            for c in range(4):
                x = 0
                while x < width:
                    count = data[at]
                    at += 1
                    if count > 128:
                        rgbe[row, x:x + count - 128, c] = data[at]
                        at += 1
                        x += count - 128
                    else:
                        rgbe[row, x:x + count, c] = np.frombuffer(data[at:at + count], np.uint8)
                        at += count
                        x += count
        else:
            rgbe[row] = np.frombuffer(data[at:at + 4 * width], np.uint8).reshape(width, 4)
            at += 4 * width
    scale = np.where(rgbe[..., 3] > 0, np.ldexp(1.0, rgbe[..., 3].astype(int) - 136), 0.0)
    return rgbe[..., :3] * scale[..., None]


radiance = read_hdr("scenes/maps/sky.hdr")
# Displayed as the standard view would show it at exposure 1: clamped,
# sRGB-encoded.
linear = np.clip(radiance, 0.0, 1.0)
display = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)

fig, ax = plt.subplots(figsize=(9, 5.2), dpi=100)
ax.imshow(display, extent=(0, 1, 1, 0), aspect="auto")
ax.set_xlabel("u = 0.5 + atan2(d.x, -d.z) / 2\u03c0")
ax.set_ylabel("v = acos(d.y) / \u03c0  (row 0 at the top)")
ax.set_xticks([0, 0.25, 0.5, 0.75, 1])
ax.set_yticks([0, 0.5, 1])
for u, label in [(0.0, "+z\n(behind)"), (0.25, "\u2212x\n(left)"), (0.5, "\u2212z\n(ahead)"),
                 (0.75, "+x\n(right)"), (1.0, "+z\n(behind)")]:
    ax.axvline(u, color="white", lw=0.8, ls="--")
    ax.text(u, 0.96, label, color="white", ha="center", va="bottom", fontsize=10,
            bbox=dict(facecolor="black", alpha=0.45, lw=0))
ax.axhline(0.5, color="white", lw=0.8, ls=":")
ax.text(0.005, 0.03, "+y (up)", color="white", va="top", fontsize=10)
ax.text(0.005, 0.49, "horizon", color="white", va="bottom", fontsize=10)
ax.set_title("scenes/maps/sky.hdr as trac0r reads it: the middle is what a camera looking "
             "along \u2212z sees")
fig.tight_layout()
fig.savefig("docs/environment_map.png")
