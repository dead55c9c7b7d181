#!/usr/bin/env python3
"""Writes scenes/maps/sky.hdr: a 512 x 256 equirectangular sky (Radiance
RGBE, run-length encoded) in trac0r's convention (docs/lights.md): a blue
sky brighter towards the horizon, a small bright sun 35 degrees up towards
+x and -z (u = 0.625 side), and a grey-brown ground below the horizon.
Deterministic, plain Python; run from the repository root:

    python3 scenes/maps/make_sky.py
"""
import math

WIDTH, HEIGHT = 512, 256
SUN_ELEVATION = math.radians(35.0)
SUN_AZIMUTH = math.radians(40.0)  # from -z towards +x: atan2(x, -z)
SUN_RADIUS = math.radians(2.5)    # larger than the real sun: a few texels, softer caustics
SUN_RADIANCE = (600.0, 550.0, 480.0)


def direction(u, v):
    """The unit direction of map coordinates (u, v), as trac0r reads them."""
    theta = math.pi * v
    psi = 2.0 * math.pi * (u - 0.5)  # atan2(x, -z)
    return (math.sin(theta) * math.sin(psi), math.cos(theta), -math.sin(theta) * math.cos(psi))


sun = (math.cos(SUN_ELEVATION) * math.sin(SUN_AZIMUTH), math.sin(SUN_ELEVATION),
       -math.cos(SUN_ELEVATION) * math.cos(SUN_AZIMUTH))


def radiance(d):
    x, y, z = d
    cos_sun = x * sun[0] + y * sun[1] + z * sun[2]
    angle = math.acos(max(-1.0, min(1.0, cos_sun)))
    if angle < SUN_RADIUS:
        return SUN_RADIANCE
    if y < 0.0:  # the ground: darker far below, lit a little by the sky
        g = 0.18 + 0.1 * math.exp(8.0 * y)
        return (g * 1.0, g * 0.9, g * 0.75)
    zenith = (0.12, 0.25, 0.65)
    horizon = (0.75, 0.85, 1.0)
    t = math.exp(-5.0 * y)
    glow = 0.6 * math.exp(-angle * angle / 0.08)  # the sky bright around the sun
    return tuple(zenith[c] * (1.0 - t) + horizon[c] * t + glow * (1.0, 0.9, 0.7)[c]
                 for c in range(3))


def rgbe(colour):
    peak = max(colour)
    if peak < 1e-32:
        return (0, 0, 0, 0)
    mantissa, exponent = math.frexp(peak)
    scale = mantissa * 256.0 / peak
    return tuple(int(c * scale) for c in colour) + (exponent + 128,)


def run_length(channel):
    """One channel of a scanline in the format's new-style RLE."""
    out = bytearray()
    i = 0
    n = len(channel)
    while i < n:
        run = 1
        while i + run < n and run < 127 and channel[i + run] == channel[i]:
            run += 1
        if run >= 4:
            out += bytes((128 + run, channel[i]))
            i += run
            continue
        start = i
        while i < n and i - start < 128:
            if i + 3 < n and channel[i] == channel[i + 1] == channel[i + 2] == channel[i + 3]:
                break
            i += 1
        out += bytes((i - start,)) + bytes(channel[start:i])
    return out


def main():
    with open("scenes/maps/sky.hdr", "wb") as f:
        f.write(b"#?RADIANCE\n# made by scenes/maps/make_sky.py\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(b"-Y %d +X %d\n" % (HEIGHT, WIDTH))
        for row in range(HEIGHT):
            pixels = []
            for column in range(WIDTH):
                # The texel's mean over a 3 x 3 grid, so the sun's disc is
                # antialiased.
                total = [0.0, 0.0, 0.0]
                for k in range(9):
                    d = direction((column + (k % 3 + 0.5) / 3.0) / WIDTH,
                                  (row + (k // 3 + 0.5) / 3.0) / HEIGHT)
                    total = [t + r / 9.0 for t, r in zip(total, radiance(d))]
                pixels.append(rgbe(total))
            f.write(bytes((2, 2, WIDTH >> 8, WIDTH & 255)))
            for c in range(4):
                f.write(run_length([p[c] for p in pixels]))


main()
