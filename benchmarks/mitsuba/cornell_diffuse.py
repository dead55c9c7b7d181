#!/usr/bin/env python3
"""Render trac0r's scenes/cornell_diffuse.json with Mitsuba 3, for comparison.

Measurement only: not part of the build or the tests. Needs `pip install
mitsuba numpy`; the LLVM variant needs DRJIT_LIBLLVM_PATH (set to
/usr/lib/x86_64-linux-gnu/libLLVM-19.so when unset and that file exists):

    python3 benchmarks/mitsuba/cornell_diffuse.py --spp 256 --width 160 \
        --height 120 --seed 1 --threads 1 --output /tmp/mi.pfm

It prints the wall time of the timed mi.render() call alone (scene loading
and a warm-up render excluded), the kernel compile time left inside it
(drjit's kernel history) and the time without it. The PFM is laid out as
trac0r's write_pfm (little-endian, scale -1, bottom row first), so that
trac0r's read_pfm and benchmarks/mitsuba/rmse.py read it.

The scene is rebuilt from the JSON file with trac0r's own conventions
(trac0r/shape.cpp, trac0r/camera.cpp, trac0r/kernel/trace.h):

- geometry: the same triangles. A shape's transform is T * Rx * Ry * Rz * S
  (glm::rotate applied in x, y, z order on the right); a plane is the quad
  of local xz with normal +y, scaled (size[0], 1, size[1]); a box is the
  unit cube scaled by size; an icosphere is the unit icosahedron subdivided
  n times by edge midpoints pushed to the sphere, scaled by radius. Flat
  (face) normals, as trac0r has no shading normals.
- surfaces are two-sided in trac0r: every diffuse BSDF is wrapped in
  Mitsuba's `twosided`. Mitsuba's area emitter is one-sided, so each
  emitting triangle is put in twice, once per side: the copy facing the
  camera exactly where trac0r has it, the other LAMP_SPLIT metres behind it
  (so that a ray meets first the copy that faces it). Each copy has a small
  Python BSDF, black in front (trac0r's pure emitter ends a path there) and
  pass-through behind (a delta transmission straight on), so that a ray
  that slips past the edge of the near copy is not stopped by the back of
  the other. Radiance = color * emittance, on both sides.
- camera: pinhole, vertical_fov in degrees about the image height, image
  right = normalize(cross(direction, world_up)) and up = cross(right,
  forward), right-handed as Mitsuba's look_at. Mitsuba's image left is the
  camera's local +x, so local +x is -right, and to_world is a rotation
  (the same matrix look_at builds).
- pixels: trac0r jitters each sample uniformly in its pixel and averages:
  a 1-pixel box filter (Mitsuba `box`, radius 0.5).
- max_depth counts surface hits on a path in both (trac0r: the trace loop
  runs depth 0..max_depth-1, one hit each, and samples no light at the
  last; Mitsuba: 1 = emitters seen directly, 2 = direct light): the same
  number. Russian roulette differs (unbiased in both): trac0r's own rule,
  Mitsuba's from rr_depth (default 5).
"""

import argparse
import json
import math
import os
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SCENE = os.path.join(HERE, "..", "..", "scenes", "cornell_diffuse.json")

# How far apart (metres) the two one-sided copies of an emitter are.
LAMP_SPLIT = 1e-5


# ---- trac0r's shapes (trac0r/shape.cpp) ---------------------------------------

def rotation(angle, axis):
    c, s = math.cos(angle), math.sin(angle)
    m = np.eye(4)
    i, j = {0: (1, 2), 1: (2, 0), 2: (0, 1)}[axis]
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def model_matrix(position, orientation, scale):
    t = np.eye(4)
    t[:3, 3] = position
    s = np.diag([scale[0], scale[1], scale[2], 1.0])
    return (t @ rotation(orientation[0], 0) @ rotation(orientation[1], 1)
            @ rotation(orientation[2], 2) @ s)


def add_quad(out, centre, u, v):
    """Two triangles of centre +- u/2 +- v/2, normal cross(u, v)."""
    centre, u, v = (np.asarray(x, dtype=np.float64) for x in (centre, u, v))
    a = centre - 0.5 * u - 0.5 * v
    b = centre + 0.5 * u - 0.5 * v
    c = centre + 0.5 * u + 0.5 * v
    d = centre - 0.5 * u + 0.5 * v
    out.append((a, b, c))
    out.append((a, c, d))


def unit_icosphere(subdivisions):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    v = [np.array(p, dtype=np.float64) for p in
         [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
          (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    v = [p / np.linalg.norm(p) for p in v]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9),
             (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2),
             (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
             (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        midpoints = {}

        def midpoint(i, j):
            key = (min(i, j), max(i, j))
            if key not in midpoints:
                p = v[i] + v[j]
                v.append(p / np.linalg.norm(p))
                midpoints[key] = len(v) - 1
            return midpoints[key]

        nxt = []
        for f in faces:
            ab, bc, ca = midpoint(f[0], f[1]), midpoint(f[1], f[2]), midpoint(f[2], f[0])
            nxt += [(f[0], ab, ca), (f[1], bc, ab), (f[2], ca, bc), (ab, bc, ca)]
        faces = nxt
    out = []
    for f in faces:
        a, b, c = v[f[0]], v[f[1]], v[f[2]]
        if np.dot(np.cross(b - a, c - a), (a + b + c) / 3.0) < 0.0:  # outward
            b, c = c, b
        out.append((a, b, c))
    return out


def shape_triangles(shape):
    """The shape's world-space triangles, an (n, 3, 3) float32 array."""
    kind = shape["type"]
    position = shape.get("position", [0, 0, 0])
    orientation = shape.get("orientation", [0, 0, 0])
    local = []
    if kind == "plane":
        add_quad(local, (0, 0, 0), (0, 0, 1), (1, 0, 0))
        scale = (shape["size"][0], 1.0, shape["size"][1])
    elif kind == "box":
        x, y, z = np.eye(3)
        add_quad(local, 0.5 * x, y, z)
        add_quad(local, -0.5 * x, z, y)
        add_quad(local, 0.5 * y, z, x)
        add_quad(local, -0.5 * y, x, z)
        add_quad(local, 0.5 * z, x, y)
        add_quad(local, -0.5 * z, y, x)
        scale = shape["size"]
    elif kind == "icosphere":
        local = unit_icosphere(int(shape.get("subdivisions", 2)))
        scale = (shape["radius"],) * 3
    else:
        raise SystemExit("shape type %r is not supported by this script" % kind)
    m = model_matrix(position, orientation, scale)
    tris = np.array(local, dtype=np.float64)  # (n, 3, 3)
    world = tris @ m[:3, :3].T + m[:3, 3]
    if np.linalg.det(m[:3, :3]) < 0.0:  # mirrored: keep the winding outward
        world = world[:, [0, 2, 1], :]
    return world.astype(np.float32)


def normals(tris):
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]).astype(np.float64)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def write_ply(path, tris):
    n = len(tris)
    vertices = tris.reshape(-1, 3).astype("<f4")
    faces = np.zeros(n, dtype=[("count", "u1"), ("index", "<i4", (3,))])
    faces["count"] = 3
    faces["index"] = np.arange(3 * n, dtype=np.int32).reshape(n, 3)
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\n"
                 "end_header\n" % (3 * n, n)).encode("ascii"))
        f.write(vertices.tobytes())
        f.write(faces.tobytes())


# ---- the Mitsuba scene ------------------------------------------------------------

def register_emitter_surface(mi, dr):
    """A BSDF for the two copies of an emitter: black in front (trac0r's
    pure emitter ends a path there), pass-through behind (Mitsuba's `null`,
    which `twosided` does not take as one side)."""

    class EmitterSurface(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            # Delta transmission, not Null: the path integrator counts a
            # camera ray whose only hits are Null ones as missing (alpha 0).
            self.m_flags = (mi.BSDFFlags.DeltaTransmission | mi.BSDFFlags.FrontSide
                            | mi.BSDFFlags.BackSide)
            self.m_components = [self.m_flags]

        def sample(self, ctx, si, sample1, sample2, active=True):
            bs = dr.zeros(mi.BSDFSample3f)
            bs.wo = -si.wi
            bs.pdf = mi.Float(1.0)
            bs.eta = mi.Float(1.0)
            bs.sampled_type = mi.UInt32(+mi.BSDFFlags.DeltaTransmission)
            bs.sampled_component = mi.UInt32(0)
            behind = mi.Frame3f.cos_theta(si.wi) < 0.0
            return bs, dr.select(behind & active, mi.Color3f(1.0), mi.Color3f(0.0))

        def eval(self, ctx, si, wo, active=True):
            return mi.Color3f(0.0)

        def pdf(self, ctx, si, wo, active=True):
            return mi.Float(0.0)

        def eval_pdf(self, ctx, si, wo, active=True):
            return mi.Color3f(0.0), mi.Float(0.0)

        def to_string(self):
            return "EmitterSurface[]"

    mi.register_bsdf("trac0r_emitter_surface", lambda props: EmitterSurface(props))


def camera_basis(camera):
    """trac0r's camera (trac0r/camera.cpp): unit right, up and forward, and
    the position, from the scene file's camera block."""
    d = np.array(camera.get("direction", [0, 0, -1]), dtype=np.float64)
    w = np.array(camera.get("world_up", [0, 1, 0]), dtype=np.float64)
    forward = d / np.linalg.norm(d)
    right = np.cross(forward, w)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    return right, up, forward, camera.get("position", [0, 0.31, 1.2])


def camera_to_world(camera):
    """trac0r's camera as Mitsuba's to_world: columns -right, up, forward,
    position (local +x is Mitsuba's image left)."""
    right, up, forward, position = camera_basis(camera)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2] = -right, up, forward
    m[:3, 3] = position
    return m


def sensor_dict(mi, camera, width, height, sampler, spp):
    """trac0r's pinhole camera and 1-pixel box filter as Mitsuba's sensor."""
    return {
        "type": "perspective",
        "fov_axis": "y",
        "fov": float(camera.get("vertical_fov", 53.13)),
        "near_clip": 1e-4,
        "far_clip": 1e5,
        "to_world": mi.ScalarTransform4f(camera_to_world(camera).tolist()),
        "film": {"type": "hdrfilm", "width": width, "height": height,
                 "pixel_format": "rgb", "component_format": "float32",
                 "rfilter": {"type": "box"}, "sample_border": False},
        "sampler": {"type": sampler, "sample_count": spp},
    }


def build_scene_dict(mi, scene_path, mesh_dir, width, height, sampler, spp, max_depth,
                     rr_depth, samples_per_pass):
    with open(scene_path) as f:
        desc = json.load(f)
    camera = desc.get("camera", {})
    render = desc.get("render", {})
    materials = desc["materials"]
    if max_depth is None:
        max_depth = int(render.get("max_depth", 5))

    integrator = {"type": "path", "max_depth": max_depth, "rr_depth": rr_depth,
                  "hide_emitters": False}
    if samples_per_pass:
        integrator["samples_per_pass"] = samples_per_pass
    scene = {
        "type": "scene",
        "integrator": integrator,
        "sensor": sensor_dict(mi, camera, width, height, sampler, spp),
    }

    def rgb(c):
        return {"type": "rgb", "value": [float(x) for x in c]}

    for i, shape in enumerate(desc["shapes"]):
        mat = materials[shape["material"]]
        kind = mat["type"]
        if kind not in ("diffuse", "emissive"):
            raise SystemExit("material type %r is not supported by this script" % kind)
        emission = [float(c) * float(mat.get("emittance", 0.0)) for c in mat["color"]]
        emits = any(e > 0.0 for e in emission)
        tris = shape_triangles(shape)
        if kind == "emissive":
            # Black in front (trac0r ends a path on an emitter), passed
            # through behind: a ray that meets the back of one copy goes on
            # to the other copy or past the lamp's edge.
            bsdf = {"type": "trac0r_emitter_surface"}
        else:
            bsdf = {"type": "twosided", "bsdf": {"type": "diffuse",
                                                 "reflectance": rgb(mat["color"])}}
        if not emits:
            copies = [("", tris)]
        else:
            # One copy per side. The triangles of the copy that faces the
            # camera stay where trac0r has them (what the camera sees is
            # exact); the other copy is moved LAMP_SPLIT along its normal,
            # away from the first, so that a ray meets first the copy that
            # faces it.
            n = normals(tris)
            eye = np.array(camera.get("position", [0, 0.31, 1.2]), dtype=np.float64)
            to_eye = eye - tris.astype(np.float64).mean(axis=1)
            sign = np.where(np.sum(n * to_eye, axis=1) >= 0.0, 1.0, -1.0)[:, None]
            facing = sign * n  # each triangle's normal toward the camera's side
            off = (LAMP_SPLIT * facing).astype(np.float32)[:, None, :]
            flip = sign[:, 0] < 0.0
            seen = tris.copy()
            seen[flip] = seen[flip][:, [0, 2, 1], :]  # wound to face the camera
            other = (tris - off)
            other[~flip] = other[~flip][:, [0, 2, 1], :]  # wound away from it
            copies = [("_seen", seen), ("_unseen", other)]
        for suffix, t in copies:
            path = os.path.join(mesh_dir, "shape%02d%s.ply" % (i, suffix))
            write_ply(path, t)
            entry = {"type": "ply", "filename": path, "face_normals": True, "bsdf": bsdf}
            if emits:
                entry["emitter"] = {"type": "area", "radiance": rgb(emission)}
            scene["shape%02d%s" % (i, suffix)] = entry
    return scene


# ---- images ---------------------------------------------------------------------

def write_pfm(path, image):
    """As trac0r's write_pfm: colour, little-endian (scale -1), bottom row first."""
    h, w, _ = image.shape
    with open(path, "wb") as f:
        f.write(("PF\n%d %d\n-1.0\n" % (w, h)).encode("ascii"))
        f.write(np.ascontiguousarray(image[::-1], dtype="<f4").tobytes())


def write_png(mi, path, image):
    """sRGB, clamped to [0, 1], as trac0r's tonemap at exposure 1."""
    v = np.clip(np.nan_to_num(image, nan=0.0), 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)
    bytes_ = np.rint(s * 255.0).astype(np.uint8)
    mi.Bitmap(bytes_, pixel_format=mi.Bitmap.PixelFormat.RGB).write(path)


def add_common_arguments(p, default_scene):
    """The options every script here takes: scene, size, samples, output,
    Mitsuba's variant, threads, depths."""
    p.add_argument("--scene", default=default_scene)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--width", type=int, default=None)
    p.add_argument("--height", type=int, default=None)
    p.add_argument("--sampler", choices=["independent", "multijitter", "stratified"],
                   default="independent",
                   help="Mitsuba's; stratified rounds --spp up to a power of 4")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--output", action="append", default=[],
                   help=".pfm (linear) or .png (sRGB); may be repeated")
    p.add_argument("--threads", type=int, default=None, help="drjit thread count")
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--max-depth", type=int, default=None, help="default: the scene's")
    p.add_argument("--rr-depth", type=int, default=5, help="Mitsuba's default, 5")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    add_common_arguments(p, DEFAULT_SCENE)
    p.add_argument("--samples-per-pass", type=int, default=0,
                   help="spp per Mitsuba pass (default 0: Mitsuba chooses, as it "
                        "recommends; it splits a render whose wavefront is too large)")
    p.add_argument("--warmup", choices=["1spp", "full", "none"], default="1spp",
                   help="render before the timed one, another seed: 1 spp (default), "
                        "the full spp (the timed render then compiles nothing), or none")
    args = p.parse_args()

    mi, dr = load_mitsuba(args.variant, args.threads)
    register_emitter_surface(mi, dr)

    with open(args.scene) as f:
        render = json.load(f).get("render", {})
    width = args.width or int(render.get("width", 800))
    height = args.height or int(render.get("height", 600))

    spp_pass = args.samples_per_pass
    if spp_pass > 0 and args.spp % spp_pass:
        raise SystemExit("--spp must be a multiple of --samples-per-pass")

    with tempfile.TemporaryDirectory(prefix="trac0r_mitsuba_") as mesh_dir:
        t0 = time.perf_counter()
        scene = mi.load_dict(build_scene_dict(
            mi, args.scene, mesh_dir, width, height, args.sampler, args.spp,
            args.max_depth, args.rr_depth, spp_pass))
        load_s = time.perf_counter() - t0

    print("mitsuba %s %s, %dx%d, spp per pass: %s, sampler %s, seed %d, threads %s"
          % (mi.__version__, args.variant, width, height,
             spp_pass if spp_pass > 0 else "Mitsuba's choice", args.sampler,
             args.seed, dr.thread_count()))
    print("scene load: %.3f s" % load_s)
    image = timed_render(mi, dr, scene, args.spp, args.seed, args.warmup)
    write_outputs(mi, args.output, image)


def load_mitsuba(variant, threads=None):
    """Imports Mitsuba and drjit with `variant` set; an LLVM variant needs
    libLLVM (DRJIT_LIBLLVM_PATH, set here when unset and a known file
    exists)."""
    if variant.startswith("llvm") and not os.environ.get("DRJIT_LIBLLVM_PATH"):
        for lib in ("/usr/lib/x86_64-linux-gnu/libLLVM-19.so",
                    "/usr/lib/x86_64-linux-gnu/libLLVM.so"):
            if os.path.exists(lib):
                os.environ["DRJIT_LIBLLVM_PATH"] = lib
                break
    import mitsuba as mi
    mi.set_variant(variant)
    import drjit as dr
    if threads is not None:
        dr.set_thread_count(threads)
    return mi, dr


def timed_render(mi, dr, scene, spp, seed, warmup="1spp"):
    """Renders `scene` at `spp` and prints the timings (see the module's
    text); returns the image, an (height, width, 3) float32 array."""
    dr.set_flag(dr.JitFlag.KernelHistory, True)
    warm_s = None
    warm_spp = {"1spp": 1, "full": spp, "none": 0}[warmup]
    if warm_spp:
        # Compiles the kernels, with another seed. The render kernel's code
        # depends on the film size and the spp (its hash changes with them;
        # with stratified and multijitter for every spp), so only "full"
        # makes the timed render a certain cache hit; with "1spp" the
        # compile time left in it is reported (kernel history) and taken out.
        t0 = time.perf_counter()
        dr.eval(mi.render(scene, spp=warm_spp, seed=seed + 0x7FFFFFFF))
        dr.sync_thread()
        warm_s = time.perf_counter() - t0
    dr.kernel_history_clear()
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()
    render_s = time.perf_counter() - t0
    cpu_s = time.process_time() - cpu0
    history = dr.kernel_history()
    compile_s = sum(k.get("codegen_time", 0.0) + k.get("backend_time", 0.0)
                    for k in history) / 1000.0
    misses = sum(1 for k in history if not k.get("cache_hit", True))

    image = np.array(img, dtype=np.float32)[:, :, :3]
    # The stratified sampler rounds the count up to a square power of two.
    spp = scene.sensors()[0].sampler().sample_count()
    height, width = image.shape[:2]
    samples = width * height * spp
    print("%d spp" % spp)
    if warm_s is not None:
        print("warm-up render (%d spp): %.3f s" % (warm_spp, warm_s))
    print("render: %.3f s wall, %.3f s CPU of this process, %.2f Msamples/s"
          % (render_s, cpu_s, samples / render_s / 1e6))
    print("kernels in the timed render: %d launched, %d compiled (not cached), "
          "%.3f s codegen+backend" % (len(history), misses, compile_s))
    print("render without compiling: %.3f s wall, %.2f Msamples/s"
          % (render_s - compile_s, samples / (render_s - compile_s) / 1e6))
    print("mean RGB: %.6f %.6f %.6f" % tuple(image.reshape(-1, 3).mean(axis=0)))
    return image


def write_outputs(mi, outputs, image):
    for out in outputs:
        if out.lower().endswith(".pfm"):
            write_pfm(out, image)
        elif out.lower().endswith(".png"):
            write_png(mi, out, image)
        else:
            raise SystemExit(out + ": expected .pfm or .png")


if __name__ == "__main__":
    main()
