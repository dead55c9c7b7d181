#!/usr/bin/env python3
"""trac0r's microfacet materials against Mitsuba 3: a grid of spheres under
a constant white sky, rendered by both, and the mean radiance of each
sphere compared.

Measurement only: not part of the build or the tests. Needs `pip install
mitsuba numpy`, libLLVM for the LLVM variant (cornell_diffuse.py's
load_mitsuba), and a built trac0r_viewer:

    python3 benchmarks/mitsuba/materials.py --viewer build/trac0r_viewer \\
        --spp 256 --seeds 4 --px 20 --npz /tmp/materials.npz
    /usr/bin/python3 benchmarks/mitsuba/materials_plot.py /tmp/materials.npz \\
        docs/materials_grid.png      # the picture (matplotlib)
    python3 benchmarks/mitsuba/materials.py --viewer build/trac0r_viewer \\
        --furnace --spp 64 --seeds 4  # trac0r alone against computed albedos

It prints a markdown table: per sphere, the mean radiance (the average of R,
G and B) over a disc inside its silhouette in trac0r, in Mitsuba with its
stock plugins, and in Mitsuba with the stock plugins' masking-shadowing
(and plastic's diffuse weight) swapped for trac0r's (below), with relative
differences and standard errors. With --furnace it instead renders single
spheres in trac0r alone and compares them with albedos this script
computes by quadrature (furnace()).

The scene (written to --workdir, trac0r's JSON and the OBJ it uses):

- one row per material, one column per roughness (--roughness, default
  0.1 0.3 0.6 1.0); unit spheres --spacing apart (default 3 radii, so a
  neighbour covers 0.27 sr of a sphere's sky) in the plane z = 0, no floor.
- the sphere: a UV sphere of --segments x --segments/2 quads (pole fans of
  triangles), poles on +-y, with its exact normals as OBJ `vn`, smooth in
  both renderers (trac0r `"smooth": true`, Mitsuba `obj` with face_normals
  false); the same file in both, placed by a translation alone.
- the sky: radiance 1 from every direction (trac0r `"environment":
  {"color": [1, 1, 1]}`, Mitsuba `constant`). With no floor and convex
  spheres, what a sphere shows is its directional albedo under a white sky,
  less what the neighbours hide.
- the camera: trac0r's pinhole on +z looking along -z from --distance
  (default 60, so a sphere's outline is nearly a circle), the vertical field
  of view fitted to the grid; Mitsuba's sensor from cornell_diffuse.py
  (trac0r's conventions, box pixel filter). --px pixels per unit length.
- max_depth 32 in both (surface hits, cornell_diffuse.py); Russian roulette
  each its own (unbiased).
- the disc: the pixels whose centre ray passes within --disc (default
  0.85) radii of a sphere's centre (the analytic sphere; the tessellated one
  is within 0.03 % of it at 128 segments), so no pixel straddles the edge.

The materials, trac0r's -> Mitsuba's (alpha = roughness^2 in both):

- gold: `conductor` with "metal": "gold" -> `roughconductor`, ggx,
  material "Au" (trac0r's eta and k of gold are Mitsuba's RGB values).
- steel F0: `conductor` with "color" [0.56, 0.57, 0.58] (Schlick's Fresnel
  with the colour as F0). Mitsuba's roughconductor has no Schlick mode; its
  `principled` with metallic 1 is exactly that (front side: Schlick with
  base_color as F0, GGX, no other lobe), so that is the reference.
- glass: `glass`, colour white, ior 1.5 -> `roughdielectric`, ggx,
  int_ior 1.5, ext_ior 1. Mitsuba scales radiance by 1/eta^2 on
  refraction, trac0r does not; on a closed sphere the factors cancel for
  every path that leaves it, so only paths cut off inside (max_depth)
  differ.
- plastic: `plastic`, [0.7, 0.1, 0.05], ior 1.5 -> `roughplastic`, ggx,
  int_ior 1.5, ext_ior 1, nonlinear false. The specular lobes are the same;
  the diffuse one differs by design: trac0r weights the base by the smooth
  coat's transmittance (1 - F(cos_o)) (1 - F(cos_i)), Mitsuba by the rough
  coat's, from a precomputed table (the two agree as roughness goes to 0).
- principled m0 / m1: `principled` (glTF 2.0 Appendix B: Lambert diffuse
  times 1 - F_schlick(v.h), F0 0.04 from ior 1.5, metal Schlick with base
  as F0) -> Mitsuba's `principled` (Disney 2015) with the same base_color,
  metallic and roughness, specular 0.5 (F0 0.04 as well). With metallic 1
  both are GGX with Schlick's F0 = base: the same model. With metallic 0
  they differ: Disney's diffuse has the retro-reflective (1 + (F_D90 - 1)
  (1 - cos)^5) factors instead of glTF's 1 - F(v.h), and its specular
  uses the exact dielectric Fresnel, not Schlick's.

Masking-shadowing: trac0r uses Smith's height-correlated G2 = 1 / (1 +
Lambda(wi) + Lambda(wo)); Mitsuba 3's rough plugins and principled use the
separable G1(wi) G1(wo) (mitsuba/render/microfacet.h, MicrofacetDistribution
::G), which is never larger: rough spheres come out darker in stock
Mitsuba, by design. So that what is left can be told from this, the
"Mitsuba G2" column wraps each stock BSDF in a small Python BSDF that
multiplies its GGX lobe by G2 / (G1(wi) G1(wo)) = 1 / (G1(wi) + G1(wo) -
G1(wi) G1(wo)) (both from Lambda of the same direction; the density is left
as it is): the whole BSDF for conductor, glass and principled m1 (one GGX
lobe, reflection or refraction); for plastic roughplastic's specular
component 0 alone, plus, in place of its diffuse component, the diffuse
lobe of Mitsuba's smooth `plastic` (same ior, nonlinear false), whose
weight (1 - F(cos_o)) (1 - F(cos_i)) / (eta^2 (1 - F_dr)) is trac0r's;
none for principled m0 (Disney's model differs; --furnace checks trac0r's
glTF model against its own quadrature instead). Directions are still
sampled by the stock plugin, the weight is the swapped value over its
density. So this column is Mitsuba's code with trac0r's documented
modelling choices, and what is left between the two is what neither
choice explains.

Statistics: --seeds renders of --spp each in both (trac0r's Sobol sampler,
Mitsuba's independent one), the mean of a sphere's disc taken per seed; the
table gives the mean over seeds and its standard error (the spread of the
seeds' means / sqrt(seeds)); the relative difference's standard error
combines both.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import cornell_diffuse as cd  # noqa: E402
import rmse  # noqa: E402

STEEL = [0.56, 0.57, 0.58]
PLASTIC = [0.7, 0.1, 0.05]
PAINT = [0.1, 0.25, 0.7]
COPPER = [0.95, 0.64, 0.54]

# name, trac0r material (roughness added), the G2 swap's mode
ROWS = [
    ("gold", {"type": "conductor", "metal": "gold"}, "whole"),
    ("steel F0", {"type": "conductor", "color": STEEL}, "whole"),
    ("glass", {"type": "glass", "color": [1, 1, 1], "ior": 1.5}, "whole"),
    ("plastic", {"type": "plastic", "color": PLASTIC, "ior": 1.5}, "plastic"),
    ("principled m0", {"type": "principled", "color": PAINT, "metallic": 0.0, "ior": 1.5},
     "none"),
    ("principled m1", {"type": "principled", "color": COPPER, "metallic": 1.0, "ior": 1.5},
     "whole"),
]


def mitsuba_bsdf(trac0r_mat, roughness):
    alpha = roughness * roughness
    kind = trac0r_mat["type"]

    def rgb(c):
        return {"type": "rgb", "value": [float(x) for x in c]}

    if kind == "conductor" and "metal" in trac0r_mat:
        return {"type": "roughconductor", "distribution": "ggx", "alpha": alpha,
                "material": "Au"}
    if kind == "conductor":
        return {"type": "principled", "base_color": rgb(trac0r_mat["color"]), "metallic": 1.0,
                "roughness": roughness, "specular": 0.5}
    if kind == "glass":
        return {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha,
                "int_ior": 1.5, "ext_ior": 1.0}
    if kind == "plastic":
        return {"type": "roughplastic", "distribution": "ggx", "alpha": alpha,
                "int_ior": 1.5, "ext_ior": 1.0, "nonlinear": False,
                "diffuse_reflectance": rgb(trac0r_mat["color"])}
    if kind == "principled":
        return {"type": "principled", "base_color": rgb(trac0r_mat["color"]),
                "metallic": float(trac0r_mat["metallic"]), "roughness": roughness,
                "specular": 0.5}
    raise SystemExit("no Mitsuba counterpart for %r" % trac0r_mat)


# ---- the scene ------------------------------------------------------------------

def write_uv_sphere(path, segments):
    """A unit UV sphere, poles on +-y, exact normals, counter-clockwise seen
    from outside."""
    rings = segments // 2
    lines = []
    verts = [(0.0, 1.0, 0.0)]
    for i in range(1, rings):
        th = math.pi * i / rings
        for j in range(segments):
            ph = 2.0 * math.pi * j / segments
            verts.append((math.sin(th) * math.sin(ph), math.cos(th), math.sin(th) * math.cos(ph)))
    verts.append((0.0, -1.0, 0.0))
    for v in verts:
        lines.append("v %.9f %.9f %.9f" % v)
    for v in verts:
        lines.append("vn %.9f %.9f %.9f" % v)

    def ring(i, j):  # 1-based OBJ index of ring i (1..rings-1), segment j
        return 2 + (i - 1) * segments + (j % segments)

    faces = []
    bottom = len(verts)
    for j in range(segments):
        faces.append((1, ring(1, j), ring(1, j + 1)))
        faces.append((bottom, ring(rings - 1, j + 1), ring(rings - 1, j)))
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b = ring(i, j), ring(i, j + 1)
            c, d = ring(i + 1, j + 1), ring(i + 1, j)
            faces.append((a, d, c))
            faces.append((a, c, b))
    # Check the winding on one face: its normal must point outward.
    p = [np.array(verts[k - 1]) for k in faces[2 * segments + 1]]
    if np.dot(np.cross(p[1] - p[0], p[2] - p[0]), p[0] + p[1] + p[2]) <= 0.0:
        raise SystemExit("UV sphere wound inward")
    for f in faces:
        lines.append("f %d//%d %d//%d %d//%d" % (f[0], f[0], f[1], f[1], f[2], f[2]))
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")


def layout(args):
    """Sphere centres (row, column -> x, y), camera and image size."""
    rows, cols = len(ROWS), len(args.roughness)
    centres = {}
    for r in range(rows):
        for c in range(cols):
            centres[r, c] = ((c - (cols - 1) / 2.0) * args.spacing,
                             ((rows - 1) / 2.0 - r) * args.spacing)
    half_w, half_h = cols * args.spacing / 2.0, rows * args.spacing / 2.0
    width, height = int(round(2 * half_w * args.px)), int(round(2 * half_h * args.px))
    # Fit the view to the grid's half height at the spheres' nearest depth
    # (z = 1), so no sphere is cut.
    fov = 2.0 * math.degrees(math.atan(half_h / (args.distance - 1.0)))
    camera = {"position": [0.0, 0.0, args.distance], "direction": [0.0, 0.0, -1.0],
              "world_up": [0.0, 1.0, 0.0], "vertical_fov": fov}
    return centres, camera, width, height


def trac0r_scene(args, centres, camera, width, height, obj_name):
    materials, shapes = {}, []
    for (r, c), (x, y) in sorted(centres.items()):
        name = "m%d_%d" % (r, c)
        mat = dict(ROWS[r][1])
        mat["roughness"] = args.roughness[c]
        materials[name] = mat
        shapes.append({"type": "mesh", "file": obj_name, "smooth": True,
                       "file_materials": False, "position": [x, y, 0.0],
                       "scale": [1, 1, 1], "material": name})
    return {"camera": camera,
            "render": {"width": width, "height": height, "max_depth": args.max_depth},
            "materials": materials, "environment": {"color": [1, 1, 1]}, "shapes": shapes}


def disc_masks(centres, camera, width, height, disc):
    """Per sphere, the pixels whose centre ray passes within `disc` radii of
    its centre (trac0r's camera: vertical fov, +x right, +y up in the image)."""
    t = math.tan(math.radians(camera["vertical_fov"]) / 2.0)
    aspect = width / height
    xs = (2.0 * (np.arange(width) + 0.5) / width - 1.0) * t * aspect
    ys = (1.0 - 2.0 * (np.arange(height) + 0.5) / height) * t
    dx, dy = np.meshgrid(xs, ys)
    d = np.stack([dx, dy, -np.ones_like(dx)], axis=-1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    eye = np.array(camera["position"])
    masks = {}
    for key, (x, y) in centres.items():
        to_c = np.array([x, y, 0.0]) - eye
        along = d @ to_c
        dist2 = to_c @ to_c - along * along
        masks[key] = dist2 < disc * disc
    return masks


# ---- trac0r -------------------------------------------------------------------------

def run_viewer(cmd):
    """Runs trac0r_viewer quietly (its progress bar), its messages shown on failure."""
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise SystemExit("%s failed (%d):\n%s%s" % (" ".join(cmd), done.returncode,
                                                     done.stdout, done.stderr))


def render_trac0r(args, scene_path, seed):
    out = os.path.join(args.workdir, "trac0r_seed%d.pfm" % seed)
    cmd = [args.viewer, scene_path, "--headless", "--spp", str(args.spp), "--seed", str(seed),
           "--integrator", "nee", "--sampler", "sobol", "--max-depth", str(args.max_depth),
           "-o", out]
    if args.threads:
        cmd += ["--threads", str(args.threads)]
    t0 = time.perf_counter()
    run_viewer(cmd)
    print("trac0r seed %d: %.1f s" % (seed, time.perf_counter() - t0), flush=True)
    return rmse.read_pfm(out)


# ---- Mitsuba --------------------------------------------------------------------------

def register_g2_swap(mi, dr, name, inner, alpha, mode, diffuse=None):
    """`inner` (a loaded Mitsuba BSDF) with its GGX lobe's separable
    G1(wi) G1(wo) replaced by the height-correlated G2 (the module's text):
    mode "whole" scales the whole BSDF, "lobe0" component 0 alone, and
    "plastic" component 0 alone with `diffuse` (a smooth `plastic`, whose
    diffuse lobe has the smooth coat's transmittance) in place of
    component 1. Directions and densities stay inner's."""

    def g1(v):
        z2 = dr.square(mi.Frame3f.cos_theta(v))
        tan2 = dr.maximum(1.0 - z2, 0.0) / dr.maximum(z2, 1e-20)
        return 2.0 / (1.0 + dr.sqrt(1.0 + alpha * alpha * tan2))

    def ratio(wi, wo):
        a, b = g1(wi), g1(wo)
        den = a + b - a * b
        return dr.select(den > 0.0, 1.0 / den, 1.0)

    class G2Swap(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.m_flags = inner.flags()
            self.m_components = [inner.flags(i) for i in range(inner.component_count())]

        def eval_swapped(self, ctx, si, wo, active):
            if mode == "whole":
                return inner.eval(ctx, si, wo, active) * ratio(si.wi, wo)
            spec_ctx = mi.BSDFContext(ctx.mode, ctx.type_mask, 0)
            if mode == "plastic":  # smooth plastic: its diffuse lobe alone
                rest = diffuse.eval(ctx, si, wo, active)
            else:
                rest = inner.eval(mi.BSDFContext(ctx.mode, ctx.type_mask, 1), si, wo, active)
            return inner.eval(spec_ctx, si, wo, active) * ratio(si.wi, wo) + rest

        def sample(self, ctx, si, sample1, sample2, active=True):
            bs, weight = inner.sample(ctx, si, sample1, sample2, active)
            if mode == "whole":
                return bs, weight * ratio(si.wi, bs.wo)
            value = self.eval_swapped(ctx, si, bs.wo, active)
            ok = active & (bs.pdf > 0.0)
            return bs, dr.select(ok, value / dr.select(ok, bs.pdf, 1.0), 0.0)

        def eval(self, ctx, si, wo, active=True):
            return self.eval_swapped(ctx, si, wo, active)

        def pdf(self, ctx, si, wo, active=True):
            return inner.pdf(ctx, si, wo, active)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self.eval_swapped(ctx, si, wo, active), inner.pdf(ctx, si, wo, active)

        def to_string(self):
            return "G2Swap[%s]" % name

    mi.register_bsdf(name, lambda props: G2Swap(props))


def mitsuba_scene(mi, dr, args, centres, camera, width, height, obj_path, swap):
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": args.max_depth, "rr_depth": 5,
                       "hide_emitters": False},
        "sensor": cd.sensor_dict(mi, camera, width, height, "independent", args.spp),
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": [1.0, 1.0, 1.0]}},
    }
    for (r, c), (x, y) in sorted(centres.items()):
        rough = args.roughness[c]
        bsdf = mitsuba_bsdf(ROWS[r][1], rough)
        if swap and ROWS[r][2] != "none":
            plugin = "trac0r_g2swap_%d_%d" % (r, c)
            diffuse = None
            if ROWS[r][2] == "plastic":
                diffuse = mi.load_dict({"type": "plastic", "int_ior": 1.5, "ext_ior": 1.0,
                                        "nonlinear": False,
                                        "diffuse_reflectance": bsdf["diffuse_reflectance"]})
            register_g2_swap(mi, dr, plugin, mi.load_dict(bsdf), max(rough * rough, 1e-3),
                             ROWS[r][2], diffuse)
            bsdf = {"type": plugin}
        scene["s%d_%d" % (r, c)] = {
            "type": "obj", "filename": obj_path, "face_normals": False,
            "to_world": mi.ScalarTransform4f().translate([x, y, 0.0]), "bsdf": bsdf}
    return mi.load_dict(scene)


def render_mitsuba(mi, dr, scene, args, seed, label):
    t0 = time.perf_counter()
    img = mi.render(scene, spp=args.spp, seed=seed)
    image = np.array(img, dtype=np.float32)[:, :, :3]
    print("Mitsuba %s seed %d: %.1f s" % (label, seed, time.perf_counter() - t0), flush=True)
    return image


# ---- the measurement ----------------------------------------------------------------

def disc_means(images, masks):
    """means[key] = per-seed means of the disc's (R + G + B) / 3, and of each channel."""
    out = {}
    for key, m in masks.items():
        out[key] = np.array([img[m].mean(axis=0) for img in images], dtype=np.float64)
    return out


def stat(per_seed):
    grey = per_seed.mean(axis=1)
    n = len(grey)
    se = grey.std(ddof=1) / math.sqrt(n) if n > 1 else float("nan")
    return grey.mean(), se, per_seed.mean(axis=0)


# ---- the furnace check (trac0r alone) --------------------------------------------------

def ggx_albedo(mu, alpha, height_correlated, base=None, n=400):
    """Directional albedo at cos theta_i = mu, by midpoint quadrature over
    the outgoing hemisphere, of a white GGX mirror (F = 1; base None) or of
    glTF 2.0's dielectric BRDF (Appendix B, ior 1.5: F0 0.04) with base
    colour `base`: (1 - F) base / pi + F D G2 / (4 mu_i mu_o), F Schlick's
    at v.h. An RGB triple."""
    th = (np.arange(n) + 0.5) / n * (math.pi / 2.0)
    ph = (np.arange(2 * n) + 0.5) / (2 * n) * (2.0 * math.pi)
    t, p = np.meshgrid(th, ph, indexing="ij")
    wo = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)
    wi = np.array([math.sqrt(max(0.0, 1.0 - mu * mu)), 0.0, mu])
    h = wo + wi
    h /= np.linalg.norm(h, axis=-1, keepdims=True)

    def lam(z):
        tan2 = np.maximum(1.0 - z * z, 0.0) / np.maximum(z * z, 1e-30)
        return (np.sqrt(1.0 + alpha * alpha * tan2) - 1.0) / 2.0

    li, lo = lam(mu), lam(wo[..., 2])
    g = 1.0 / (1.0 + li + lo) if height_correlated else 1.0 / ((1.0 + li) * (1.0 + lo))
    c2 = h[..., 2] ** 2
    d = alpha * alpha / (math.pi * (c2 * (alpha * alpha - 1.0) + 1.0) ** 2)
    spec = d * g / (4.0 * mu)
    dw = np.sin(t) * (math.pi / 2.0 / n) * (2.0 * math.pi / (2 * n))
    if base is None:
        return np.full(3, float(np.sum(spec * dw)))
    f = 0.04 + 0.96 * (1.0 - np.clip(h @ wi, 0.0, 1.0)) ** 5
    out = []
    for b in base:
        f_cos = (1.0 - f) * b / math.pi * wo[..., 2] + f * spec
        out.append(float(np.sum(f_cos * dw)))
    return np.array(out)


def furnace(args):
    """One sphere alone under the white sky, per roughness, in trac0r: a
    white Schlick conductor (color [1, 1, 1]: F = 1) and the principled
    metallic 0 of the grid; its disc mean of (R + G + B) / 3 against the
    albedo E(mu) (ggx_albedo; for the conductor also with the separable G
    Mitsuba uses) averaged over the same pixels, mu = -d.n of each pixel's
    centre ray on the analytic sphere. A convex sphere alone sees only the
    sky, so its radiance is E(mu) exactly (no other surface)."""
    obj = os.path.join(args.workdir, "uv_sphere.obj")
    write_uv_sphere(obj, args.segments)
    size = 96
    camera = {"position": [0.0, 0.0, args.distance], "direction": [0.0, 0.0, -1.0],
              "world_up": [0.0, 1.0, 0.0],
              "vertical_fov": 2.0 * math.degrees(math.atan(1.15 / (args.distance - 1.0)))}
    t = math.tan(math.radians(camera["vertical_fov"]) / 2.0)
    xs = (2.0 * (np.arange(size) + 0.5) / size - 1.0) * t
    dx, dy = np.meshgrid(xs, -xs)
    d = np.stack([dx, dy, -np.ones_like(dx)], axis=-1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    eye = np.array(camera["position"])
    along = d @ -eye
    dist2 = eye @ eye - along * along
    mask = dist2 < args.disc ** 2
    hit = eye + d * (along - np.sqrt(np.maximum(1.0 - dist2, 0.0)))[..., None]
    mu = np.clip(-np.sum(d * hit, axis=-1)[mask], 0.0, 1.0)
    grid = np.linspace(mu.min(), 1.0, 24)

    def expected(alpha, hc, base):
        table = np.array([ggx_albedo(m, alpha, hc, base) for m in grid])
        return float(np.mean([np.interp(mu, grid, table[:, k]).mean() for k in range(3)]))

    cases = [("white conductor", {"type": "conductor", "color": [1, 1, 1]}, None),
             ("principled m0", {"type": "principled", "color": PAINT, "metallic": 0.0,
                                "ior": 1.5}, PAINT)]
    print("| material | roughness | trac0r | E, height-correlated G2 | diff "
          "| E, separable G (Mitsuba's) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for label, mat, base in cases:
        for rough in args.roughness:
            alpha = max(rough * rough, 1e-3)
            m = dict(mat)
            m["roughness"] = rough
            scene = {"camera": camera,
                     "render": {"width": size, "height": size, "max_depth": args.max_depth},
                     "materials": {"m": m}, "environment": {"color": [1, 1, 1]},
                     "shapes": [{"type": "mesh", "file": "uv_sphere.obj", "smooth": True,
                                 "file_materials": False, "material": "m"}]}
            path = os.path.join(args.workdir, "furnace.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            out = os.path.join(args.workdir, "furnace.pfm")
            run_viewer([args.viewer, path, "--headless", "--spp", str(args.spp * args.seeds),
                        "--integrator", "nee", "--sampler", "sobol", "-o", out])
            got = float(rmse.read_pfm(out)[mask].mean())
            e_hc = expected(alpha, True, base)
            e_sep = "%.4f" % expected(alpha, False, base) if base is None else ""
            print("| %s | %.1f | %.4f | %.4f | %+.2f%% | %s |" % (
                label, rough, got, e_hc, 100.0 * (got / e_hc - 1.0), e_sep))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--viewer", default="build/trac0r_viewer")
    p.add_argument("--workdir", default="/tmp/trac0r_materials")
    p.add_argument("--spp", type=int, default=64, help="per seed, in both")
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--roughness", type=float, nargs="+", default=[0.1, 0.3, 0.6, 1.0])
    p.add_argument("--spacing", type=float, default=3.0)
    p.add_argument("--distance", type=float, default=60.0)
    p.add_argument("--px", type=float, default=16.0, help="pixels per unit length")
    p.add_argument("--segments", type=int, default=128)
    p.add_argument("--disc", type=float, default=0.85)
    p.add_argument("--max-depth", type=int, default=32)
    p.add_argument("--threads", type=int, default=None, help="both renderers' threads")
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--no-swap", action="store_true", help="skip the Mitsuba G2 renders")
    p.add_argument("--limit", type=float, default=0.02, help="the agreement asked for")
    p.add_argument("--npz", default=None, help="save images, masks and table for the plot")
    p.add_argument("--furnace", action="store_true",
                   help="trac0r alone: a white conductor sphere per roughness against the "
                        "GGX albedo computed here, then exit")
    args = p.parse_args()

    os.makedirs(args.workdir, exist_ok=True)
    if args.furnace:
        furnace(args)
        return
    t_start = time.perf_counter()
    obj_path = os.path.join(args.workdir, "uv_sphere.obj")
    write_uv_sphere(obj_path, args.segments)
    centres, camera, width, height = layout(args)
    scene_path = os.path.join(args.workdir, "materials.json")
    with open(scene_path, "w") as f:
        json.dump(trac0r_scene(args, centres, camera, width, height, "uv_sphere.obj"), f, indent=1)
    masks = disc_masks(centres, camera, width, height, args.disc)
    print("%dx%d, %d spp x %d seeds, %d pixels per disc"
          % (width, height, args.spp, args.seeds, min(m.sum() for m in masks.values())))

    seeds = list(range(1, args.seeds + 1))
    trac0r_imgs = [render_trac0r(args, scene_path, s) for s in seeds]

    mi, dr = cd.load_mitsuba(args.variant, args.threads)
    print("mitsuba %s %s, threads %d" % (mi.__version__, args.variant, dr.thread_count()))
    stock = mitsuba_scene(mi, dr, args, centres, camera, width, height, obj_path, False)
    mi_imgs = [render_mitsuba(mi, dr, stock, args, s, "stock") for s in seeds]
    sw_imgs = []
    if not args.no_swap:
        swapped = mitsuba_scene(mi, dr, args, centres, camera, width, height, obj_path, True)
        sw_imgs = [render_mitsuba(mi, dr, swapped, args, s, "G2") for s in seeds]

    t_means = disc_means(trac0r_imgs, masks)
    m_means = disc_means(mi_imgs, masks)
    s_means = disc_means(sw_imgs, masks) if sw_imgs else None

    def rel(a, b):
        (ma, sa, _), (mb, sb, _) = a, b
        d = ma / mb - 1.0
        se = (ma / mb) * math.sqrt((sa / ma) ** 2 + (sb / mb) ** 2)
        return d, se

    print()
    print("Disc mean of (R+G+B)/3 (+- standard error over %d seeds of %d spp); "
          "difference = trac0r / Mitsuba - 1" % (args.seeds, args.spp))
    print()
    head = "| material | roughness | trac0r | Mitsuba (stock) | diff | within %g%% |" % (
        100 * args.limit)
    sep = "| --- | ---: | ---: | ---: | ---: | :---: |"
    if s_means:
        head += " Mitsuba G2 | diff vs G2 | within %g%% |" % (100 * args.limit)
        sep += " ---: | ---: | :---: |"
    print(head)
    print(sep)
    table = []
    for (r, c) in sorted(centres):
        name = ROWS[r][0]
        t = stat(t_means[r, c])
        m = stat(m_means[r, c])
        d, dse = rel(t, m)
        row = "| %s | %.1f | %.4f ± %.4f | %.4f ± %.4f | %+.2f%% ± %.2f | %s |" % (
            name, args.roughness[c], t[0], t[1], m[0], m[1], 100 * d, 100 * dse,
            "yes" if abs(d) <= args.limit else "**no**")
        entry = [r, c, t[0], t[1], m[0], m[1], d]
        if s_means:
            if ROWS[r][2] == "none":
                row += " (no swap) | | |"
                entry += [m[0], m[1], d]
            else:
                s = stat(s_means[r, c])
                ds, dsse = rel(t, s)
                row += " %.4f ± %.4f | %+.2f%% ± %.2f | %s |" % (
                    s[0], s[1], 100 * ds, 100 * dsse,
                    "yes" if abs(ds) <= args.limit else "**no**")
                entry += [s[0], s[1], ds]
        print(row)
        table.append(entry)
    print()
    print("per channel (R, G, B) trac0r / Mitsuba stock - 1, in %:")
    for (r, c) in sorted(centres):
        t, m = stat(t_means[r, c])[2], stat(m_means[r, c])[2]
        print("  %-14s %.1f  %+6.2f %+6.2f %+6.2f" % ((ROWS[r][0], args.roughness[c])
                                                     + tuple(100 * (t / m - 1.0))))
    print("wall time: %.1f s" % (time.perf_counter() - t_start))

    if args.npz:
        np.savez_compressed(
            args.npz, trac0r=np.mean(trac0r_imgs, axis=0), mitsuba=np.mean(mi_imgs, axis=0),
            mitsuba_g2=np.mean(sw_imgs, axis=0) if sw_imgs else np.zeros(0),
            table=np.array(table), rows=np.array([r[0] for r in ROWS]),
            roughness=np.array(args.roughness),
            centres=np.array([[r, c, x, y] for (r, c), (x, y) in sorted(centres.items())]),
            mask=np.any(np.stack(list(masks.values())), axis=0))


if __name__ == "__main__":
    main()
