#!/usr/bin/env python3
"""Directional albedos, by numerical integration: how much of the light
arriving from angle theta a white surface reflects, for two of trac0r's
microfacet models (docs/materials.md cites the tables).

A white GGX conductor (F = 1), single scattering only (no energy
compensation): what it keeps, the rest lost between the microfacets. The
integral over microfacet normals h with GGX's inverse CDF substituted
(theta_h = atan(alpha sqrt(u / (1 - u))), so D(h) cos(theta_h) dh = du
dv), of G2(wo, wi) (wo.h) / (wo.n) where the mirrored wi is above: the
same integral as tests/test_rough_materials.cpp's.

glTF 2.0's metallic-roughness BRDF (Appendix B) for a white,
non-metallic surface:

Appendix B weights the Lambertian lobe by 1 - F(v.h) of each pair of
directions, where F is Schlick's Fresnel at the half vector, not by the
energy the specular lobe took from the incoming light: towards grazing
incidence the specular lobe reflects much (v.h small near the mirror
direction, F near 1), while for most diffuse directions v.h is large, F
small and the diffuse weight near one, so the sum exceeds one. (Roughness
0.1 is left out: its peak is narrower than the grid.) trac0r's `principled` follows Appendix B as written (as
glTF viewers do); this script gives the figures docs/materials.md cites.

Measurement only. Needs numpy:

    python3 benchmarks/materials/albedo.py
"""

import numpy as np


def ggx_d(alpha, hz):
    a2 = alpha * alpha
    t = (1.0 - hz * hz) / a2 + hz * hz
    return 1.0 / (np.pi * a2 * t * t)


def lam(alpha, z):
    z = np.maximum(z, 1e-12)
    return 0.5 * (np.sqrt(1.0 + alpha * alpha * (1.0 - z * z) / (z * z)) - 1.0)


def albedo(roughness, theta, cells=1200):
    """Integral of f cos over directions l (z = cos in (0, 1], phi), midpoint."""
    alpha = max(roughness * roughness, 1e-3)
    v = np.array([np.sin(theta), 0.0, np.cos(theta)])
    z = (np.arange(cells) + 0.5) / cells
    phi = 2.0 * np.pi * (np.arange(2 * cells) + 0.5) / (2 * cells)
    Z, P = np.meshgrid(z, phi, indexing="ij")
    S = np.sqrt(1.0 - Z * Z)
    lx, ly, lz = S * np.cos(P), S * np.sin(P), Z
    hx, hy, hz = lx + v[0], ly + v[1], lz + v[2]
    n = np.sqrt(hx * hx + hy * hy + hz * hz)
    hx, hy, hz = hx / n, hy / n, hz / n
    vh = np.clip(v[0] * hx + v[2] * hz, 0.0, 1.0)
    w = (1.0 - vh) ** 5
    f0 = 0.04
    fr = f0 + (1.0 - f0) * w
    g2 = 1.0 / (1.0 + lam(alpha, v[2]) + lam(alpha, lz))
    vd = ggx_d(alpha, hz) * g2 / (4.0 * v[2] * lz)
    f = (1.0 - fr) / np.pi + fr * vd
    d_omega = (1.0 / cells) * (np.pi / cells)  # dz dphi
    return float(np.sum(f * lz) * d_omega)


def conductor_albedo(roughness, theta, cells=1000):
    alpha = max(roughness * roughness, 1e-3)
    u = (np.arange(cells) + 0.5) / cells
    th = np.arctan(alpha * np.sqrt(u / (1.0 - u)))
    ph = 2.0 * np.pi * (np.arange(cells) + 0.5) / cells
    T, P = np.meshgrid(th, ph, indexing="ij")
    hx, hy, hz = np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)
    ox, oz = np.sin(theta), np.cos(theta)
    oh = ox * hx + oz * hz
    ix, iy, iz = 2 * oh * hx - ox, 2 * oh * hy, 2 * oh * hz - oz
    ok = (oh > 0) & (iz > 0)
    iz_safe = np.where(ok, iz, 1.0)
    g2 = 1.0 / (1.0 + lam(alpha, oz) + lam_xyz(alpha, ix, iy, iz_safe))
    return float(np.sum(np.where(ok, g2 * oh / (oz * hz), 0.0)) / cells**2)


def lam_xyz(alpha, x, y, z):
    return 0.5 * (np.sqrt(1.0 + alpha * alpha * (x * x + y * y) / (z * z)) - 1.0)


def main():
    print("White GGX conductor, single scattering:")
    print("| roughness | 0 deg | 45 deg | 75 deg |")
    print("| ---: | ---: | ---: | ---: |")
    for r in (0.3, 0.6, 1.0):
        row = [conductor_albedo(r, np.radians(t)) for t in (0.0, 45.0, 75.0)]
        print(f"| {r} | " + " | ".join(f"{a:.3f}" for a in row) + " |")
    print()
    print("White principled (glTF Appendix B), metallic 0, ior 1.5:")
    print("| roughness | 0 deg | 45 deg | 70 deg | 85 deg |")
    print("| ---: | ---: | ---: | ---: | ---: |")
    for r in (0.3, 0.6, 1.0):
        row = [albedo(r, np.radians(t)) for t in (0.0, 45.0, 70.0, 85.0)]
        print(f"| {r} | " + " | ".join(f"{a:.3f}" for a in row) + " |")


if __name__ == "__main__":
    main()
