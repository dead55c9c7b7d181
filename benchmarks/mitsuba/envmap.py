#!/usr/bin/env python3
"""Render a trac0r scene lit by an environment map (benchmarks/envmap/
scene.json) with Mitsuba 3's `envmap` emitter, for comparison.

Measurement only: not part of the build or the tests. Needs `pip install
mitsuba numpy` and libLLVM for the LLVM variant (as cornell_diffuse.py,
whose camera, shapes, timing and PFM output this script reuses):

    python3 benchmarks/mitsuba/envmap.py --spp 256 --threads 1 \\
        --output /tmp/mi.pfm --output /tmp/mi.png
    python3 benchmarks/mitsuba/envmap.py --check-mapping   # no render

The environment, trac0r/kernel/environment.h: for a world direction d
turned by -rotation about +y, u = 0.5 + atan2(d.x, -d.z) / 2 pi, v =
acos(d.y) / pi (v = 0 the top row), nearest texel. Mitsuba's envmap (3.9)
looks up u = atan2(d.x, -d.z) / 2 pi, v = acos(d.y) / pi in its local frame:
the same orientation, but its u = 0 (the map's left edge) faces local -z
where trac0r's map middle faces it. So Mitsuba's to_world is a rotation
about +y by 180 + rotation degrees (Mitsuba's rotate is counter-clockwise
seen from above, as trac0r's rotation).

Filtering differs: Mitsuba interpolates bilinearly, between column centres
at (c + 0.5) / W and row centres at r / (H - 1) (its top and bottom rows
sit on the poles), where trac0r takes the texel a direction falls in. So
that both see the same piecewise-constant radiance, the map given to
Mitsuba is trac0r's function sampled at Mitsuba's texel centres of a map
--upsample times as fine (default 4): the radiance then differs only
within one fine texel of the map's texel edges.

Materials: diffuse (two-sided, as in cornell_diffuse.py) and glossy with
roughness 0, trac0r's mirror (weight `color`): Mitsuba's `conductor` with
material "none" and specular_reflectance = color. Shapes: plane, box,
icosphere (cornell_diffuse.py) and OBJ meshes with flat normals
("smooth": false in the scene; v and f records only).
"""

import argparse
import json
import math
import os
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "envmap"))

import cornell_diffuse as cd  # noqa: E402
import make_map  # noqa: E402

DEFAULT_SCENE = os.path.join(HERE, "..", "envmap", "scene.json")


# ---- the map -------------------------------------------------------------------

def read_map(mi, path):
    """The map's texels, (h, w, 3) float32, row 0 the top, as trac0r reads them."""
    if path.lower().endswith(".hdr"):
        return make_map.read_hdr(path)
    bitmap = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32,
                                     srgb_gamma=False)
    return np.array(bitmap, dtype=np.float32)[:, :, :3]


def trac0r_lookup(texels, u, v):
    """trac0r's nearest texel for map coordinates u, v (arrays)."""
    h, w, _ = texels.shape
    col = np.clip(np.floor(u * w), 0, w - 1).astype(np.int64)
    row = np.clip(np.floor(v * h), 0, h - 1).astype(np.int64)
    return texels[row, col]


def mitsuba_texels(texels, upsample):
    """A map for Mitsuba's bilinear lookup: trac0r's function at the
    centres of Mitsuba's texels of a map `upsample` times as fine, columns
    at (c + 0.5) / W and rows at r / (H - 1)."""
    h, w, _ = texels.shape
    if upsample <= 1:
        return texels
    fw, fh = w * upsample, h * upsample
    u = (np.arange(fw) + 0.5) / fw
    v = np.arange(fh) / (fh - 1.0)
    return trac0r_lookup(texels, u[None, :], v[:, None]).astype(np.float32)


def envmap_to_world(mi, rotation_degrees):
    return mi.ScalarTransform4f().rotate([0, 1, 0], 180.0 + rotation_degrees)


def environment_emitter(mi, env, base_dir, upsample):
    strength = float(env.get("strength", 1.0))
    if "color" in env:
        return {"type": "constant",
                "radiance": {"type": "rgb", "value": [strength * float(c) for c in env["color"]]}}
    texels = read_map(mi, os.path.join(base_dir, env["map"]))
    return {"type": "envmap",
            "bitmap": mi.Bitmap(np.ascontiguousarray(mitsuba_texels(texels, upsample))),
            "scale": strength,
            "to_world": envmap_to_world(mi, float(env.get("rotation", 0.0)))}


# ---- shapes ----------------------------------------------------------------------

def obj_triangles(path, shape):
    """An OBJ's faces (fan-triangulated) in world space, trac0r's transform."""
    vertices, tris = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                idx = [int(p.split("/")[0]) for p in parts[1:]]
                idx = [i - 1 if i > 0 else len(vertices) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    tris.append([vertices[idx[0]], vertices[idx[k]], vertices[idx[k + 1]]])
    m = cd.model_matrix(shape.get("position", [0, 0, 0]), shape.get("orientation", [0, 0, 0]),
                        shape.get("scale", [1, 1, 1]))
    world = np.array(tris, dtype=np.float64) @ m[:3, :3].T + m[:3, 3]
    return world.astype(np.float32)


def triangles(shape, base_dir):
    if shape["type"] == "mesh":
        if shape.get("smooth", True):
            raise SystemExit("a mesh here needs \"smooth\": false (flat normals in both)")
        return obj_triangles(os.path.join(base_dir, shape["file"]), shape)
    return cd.shape_triangles(shape)


def bsdf(mat):
    c = {"type": "rgb", "value": [float(x) for x in mat["color"]]}
    if mat["type"] == "diffuse" and float(mat.get("emittance", 0.0)) == 0.0:
        return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": c}}
    if mat["type"] == "glossy" and float(mat.get("roughness", 0.0)) == 0.0:
        return {"type": "conductor", "material": "none", "specular_reflectance": c}
    raise SystemExit("material %r is not supported by this script" % mat)


def build_scene_dict(mi, scene_path, mesh_dir, width, height, sampler, spp, max_depth,
                     rr_depth, upsample):
    with open(scene_path) as f:
        desc = json.load(f)
    base_dir = os.path.dirname(os.path.abspath(scene_path))
    if max_depth is None:
        max_depth = int(desc.get("render", {}).get("max_depth", 5))
    scene = {
        "type": "scene",
        # max_depth: surface hits in both (cornell_diffuse.py).
        "integrator": {"type": "path", "max_depth": max_depth, "rr_depth": rr_depth,
                       "hide_emitters": False},
        "sensor": cd.sensor_dict(mi, desc.get("camera", {}), width, height, sampler, spp),
    }
    if "environment" in desc:
        scene["environment"] = environment_emitter(mi, desc["environment"], base_dir, upsample)
    for i, shape in enumerate(desc["shapes"]):
        path = os.path.join(mesh_dir, "shape%02d.ply" % i)
        cd.write_ply(path, triangles(shape, base_dir))
        scene["shape%02d" % i] = {"type": "ply", "filename": path, "face_normals": True,
                                  "bsdf": bsdf(desc["materials"][shape["material"]])}
    return scene


# ---- the convention check ----------------------------------------------------------

def check_mapping(mi, dr, scene_path, upsample, count=200000):
    """Mitsuba's envmap (as built here) against trac0r's lookup at random
    directions: the share of directions whose radiance agrees (to 1e-3
    relative), and the same with Mitsuba's to_world left at the identity
    and at 180 - rotation (wrong conventions), for comparison."""
    with open(scene_path) as f:
        env = json.load(f)["environment"]
    base_dir = os.path.dirname(os.path.abspath(scene_path))
    texels = read_map(mi, os.path.join(base_dir, env["map"]))
    rotation = float(env.get("rotation", 0.0))
    strength = float(env.get("strength", 1.0))
    rng = np.random.default_rng(1)
    d = rng.normal(size=(count, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    # trac0r: environment_from_world turns by -rotation about +y.
    c, s = math.cos(math.radians(rotation)), math.sin(math.radians(rotation))
    m = np.stack([c * d[:, 0] - s * d[:, 2], d[:, 1], s * d[:, 0] + c * d[:, 2]], axis=1)
    u = 0.5 + np.arctan2(m[:, 0], -m[:, 2]) / (2.0 * math.pi)
    v = np.arccos(np.clip(m[:, 1], -1.0, 1.0)) / math.pi
    expected = strength * trac0r_lookup(texels, u, v)
    si = dr.zeros(mi.SurfaceInteraction3f, count)
    si.wi = -mi.Vector3f(d[:, 0], d[:, 1], d[:, 2])
    fine = mi.Bitmap(np.ascontiguousarray(mitsuba_texels(texels, upsample)))
    for label, turn in (("180 + rotation (this script)", 180.0 + rotation),
                        ("identity", 0.0), ("rotation alone", rotation),
                        ("180 - rotation", 180.0 - rotation)):
        emitter = mi.load_dict({"type": "envmap", "bitmap": fine, "scale": strength,
                                "to_world": mi.ScalarTransform4f().rotate([0, 1, 0], turn)})
        got = np.stack([np.array(x) for x in emitter.eval(si)], axis=1)
        close = np.all(np.abs(got - expected) <= 1e-3 * (np.abs(expected) + 1e-3), axis=1)
        deviation = np.abs(got - expected).mean() / np.abs(expected).mean()
        print("Mitsuba to_world = rotate(+y, %s): %.2f %% of %d directions agree with trac0r's "
              "lookup; mean |difference| / mean radiance %.4f"
              % (label, 100.0 * close.mean(), count, deviation))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    cd.add_common_arguments(p, DEFAULT_SCENE)
    p.add_argument("--upsample", type=int, default=4,
                   help="the map given to Mitsuba is this many times as fine, sampled "
                        "from trac0r's nearest-texel lookup (1: the map as it is)")
    p.add_argument("--warmup", choices=["1spp", "full", "none"], default="1spp")
    p.add_argument("--check-mapping", action="store_true",
                   help="compare Mitsuba's envmap with trac0r's lookup at random "
                        "directions, then exit")
    args = p.parse_args()

    mi, dr = cd.load_mitsuba(args.variant, args.threads)
    if args.check_mapping:
        check_mapping(mi, dr, args.scene, args.upsample)
        return
    with open(args.scene) as f:
        render = json.load(f).get("render", {})
    width = args.width or int(render.get("width", 800))
    height = args.height or int(render.get("height", 600))
    with tempfile.TemporaryDirectory(prefix="trac0r_mitsuba_") as mesh_dir:
        scene = mi.load_dict(build_scene_dict(
            mi, args.scene, mesh_dir, width, height, args.sampler, args.spp,
            args.max_depth, args.rr_depth, args.upsample))
    print("mitsuba %s %s, %dx%d, sampler %s, seed %d, threads %s, map upsampled %dx"
          % (mi.__version__, args.variant, width, height, args.sampler, args.seed,
             dr.thread_count(), args.upsample))
    image = cd.timed_render(mi, dr, scene, args.spp, args.seed, args.warmup)
    cd.write_outputs(mi, args.output, image)


if __name__ == "__main__":
    main()
