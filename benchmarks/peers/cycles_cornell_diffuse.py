"""Render trac0r's scenes/cornell_diffuse.json with Blender's Cycles, for comparison.

Measurement only: not part of the build or the tests. Written for Debian
12's Blender 3.4 (/usr/bin/blender, CPU):

    blender -b --python-exit-code 1 -P benchmarks/peers/cycles_cornell_diffuse.py -- \
        --spp 256 --width 160 --height 120 --seed 1 --threads 2 \
        --output /tmp/cycles.pfm

It prints the wall time of the timed bpy.ops.render.render() call alone
(Blender's start-up, building the scene, a 1-spp warm-up render with
another seed and writing the image excluded; the call still holds Cycles'
scene sync and BVH build, a few milliseconds here). The PFM is laid out as
trac0r's write_pfm (little-endian, scale -1, bottom row first), so that
trac0r's read_pfm and benchmarks/mitsuba/rmse.py read it.

The scene is rebuilt from the JSON file as benchmarks/mitsuba/cornell_diffuse.py
does (its shape_triangles, the same triangles in trac0r's own coordinates:
Blender's z-up convention does not matter to a render), with:

- camera: pinhole, vertical_fov about the image height (sensor fit
  vertical), right = normalize(cross(direction, world_up)), up =
  cross(right, forward); Blender's camera looks along its local -Z with
  +Y up and +X right, so its matrix has the columns right, up, -forward.
- pixels: a 1-pixel box filter (Cycles' "Box", filter_width 1), trac0r's
  uniform jitter in the pixel.
- surfaces: Diffuse BSDF (roughness 0: Lambert), two-sided in Cycles as in
  trac0r. The lamp: an Emission shader of the lamp's colour and strength
  emittance (Cycles' mesh emission of strength L is radiance L), which
  Cycles emits on both sides of a face, as trac0r; a path ends on it (no
  BSDF), as in trac0r. Lamp triangles are sampled as lights (Multiple
  Importance, Blender's default). A black world.
- bounces: trac0r's max_depth counts surface hits, the light sample at the
  last but one; Cycles' max_bounces 0 is direct light (two hits), so
  max_bounces = diffuse_bounces = max_depth - 2.
- no denoising, no adaptive sampling, no clamping (Cycles 3.4 clamps
  indirect light at 10 by default), light threshold 0 (default 0.01), no
  path guiding; Blender 3.4 has no light tree. Sampling pattern: Cycles'
  default, progressive multi-jitter. View transform "Standard" (the PFM is
  the linear render either way).
"""

import argparse
import json
import math
import os
import sys
import tempfile
import time

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "mitsuba"))
import cornell_diffuse as mts  # noqa: E402  (shape_triangles, write_pfm; no Mitsuba import)

DEFAULT_SCENE = os.path.join(HERE, "..", "..", "scenes", "cornell_diffuse.json")


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(
        prog="blender -b -P cycles_cornell_diffuse.py --",
        description=__doc__.split("\n")[0])
    p.add_argument("--scene", default=DEFAULT_SCENE)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--width", type=int, default=None, help="default: the scene's")
    p.add_argument("--height", type=int, default=None, help="default: the scene's")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--threads", type=int, default=0, help="CPU threads (0: all)")
    p.add_argument("--max-depth", type=int, default=None, help="default: the scene's")
    p.add_argument("--warmup", choices=["1spp", "none"], default="1spp",
                   help="a 1-spp render (seed + 1000) before the timed one")
    p.add_argument("--output", action="append", default=[],
                   help=".pfm (linear) or .png (sRGB, Standard); may be repeated")
    return p.parse_args(argv)


def node_material(name, shader, output, inputs):
    """A Cycles material of one shader node (its `output` socket into the
    surface), its inputs set from `inputs`."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    node = nodes.new(shader)
    for socket, value in inputs.items():
        node.inputs[socket].default_value = value
    out = nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    mat.node_tree.links.new(node.outputs[output], out.inputs["Surface"])
    return mat


def diffuse_material(name, color):
    return node_material(name, "ShaderNodeBsdfDiffuse", "BSDF",
                         {"Color": (*[float(c) for c in color], 1.0), "Roughness": 0.0})


def emission_material(name, color, strength):
    mat = node_material(name, "ShaderNodeEmission", "Emission",
                        {"Color": (*[float(c) for c in color], 1.0), "Strength": float(strength)})
    mat.cycles.sample_as_light = True
    return mat


def camera_matrix(camera):
    """trac0r's camera as Blender's matrix_world: columns right, up,
    -forward, position."""
    right, up, forward, position = mts.camera_basis(camera)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2] = right, up, -forward
    m[:3, 3] = position
    return m


def build_scene(args):
    with open(args.scene) as f:
        desc = json.load(f)
    camera = desc.get("camera", {})
    render = desc.get("render", {})
    materials = desc["materials"]
    width = args.width or int(render.get("width", 800))
    height = args.height or int(render.get("height", 600))
    max_depth = args.max_depth or int(render.get("max_depth", 5))
    if max_depth < 2:
        raise SystemExit("--max-depth must be at least 2 (direct light)")

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    made = {}
    for i, shape in enumerate(desc["shapes"]):
        name = shape["material"]
        mat = materials[name]
        if mat["type"] not in ("diffuse", "emissive"):
            raise SystemExit("material type %r is not supported by this script" % mat["type"])
        if name not in made:
            if mat["type"] == "emissive":
                made[name] = emission_material(name, mat["color"],
                                               float(mat.get("emittance", 0.0)))
            else:
                made[name] = diffuse_material(name, mat["color"])
        tris = mts.shape_triangles(shape).astype(np.float64)  # (n, 3, 3)
        n = len(tris)
        mesh = bpy.data.meshes.new("shape%02d" % i)
        mesh.from_pydata(tris.reshape(-1, 3).tolist(), [],
                         np.arange(3 * n).reshape(n, 3).tolist())
        for poly in mesh.polygons:
            poly.use_smooth = False  # flat normals, as trac0r
        mesh.materials.append(made[name])
        mesh.validate()
        obj = bpy.data.objects.new("shape%02d" % i, mesh)
        scene.collection.objects.link(obj)

    import mathutils
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(float(camera.get("vertical_fov", 53.13)))
    cam_data.clip_start = 1e-4
    cam_data.clip_end = 1e5
    cam = bpy.data.objects.new("camera", cam_data)
    cam.matrix_world = mathutils.Matrix(camera_matrix(camera).tolist())
    scene.collection.objects.link(cam)
    scene.camera = cam

    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bg.inputs["Strength"].default_value = 0.0
    scene.world = world

    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    scene.view_layers[0].cycles.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.use_guiding = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.max_bounces = max_depth - 2
    c.diffuse_bounces = max_depth - 2
    c.glossy_bounces = max_depth - 2
    c.transmission_bounces = max_depth - 2
    c.transparent_max_bounces = max_depth - 2
    c.volume_bounces = 0
    c.blur_glossy = 0.0
    c.film_exposure = 1.0
    c.use_animated_seed = False
    c.seed = args.seed
    scene.render.film_transparent = False
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.use_border = False
    if args.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = args.threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.dither_intensity = 0.0
    return scene, width, height, max_depth


def render_pixels(scene, width, height, tmp_dir):
    """The Render Result as an (height, width, 3) float32 array, bottom row
    first (Blender's order, and the PFM's): saved as a float EXR (linear,
    no view transform) and read back."""
    path = os.path.join(tmp_dir, "render.exr")
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGB"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    bpy.data.images["Render Result"].save_render(filepath=path, scene=scene)
    img = bpy.data.images.load(path)
    img.colorspace_settings.name = "Linear"
    if tuple(img.size) != (width, height):
        raise SystemExit("render is %dx%d, expected %dx%d" % (*img.size, width, height))
    px = np.empty(width * height * img.channels, dtype=np.float32)
    img.pixels.foreach_get(px)
    return px.reshape(height, width, img.channels)[:, :, :3].copy()


def write_pfm_bottom_first(path, bottom_first):
    # mts.write_pfm takes row 0 at the top.
    mts.write_pfm(path, bottom_first[::-1])


def write_png(path, bottom_first):
    """sRGB, clamped to [0, 1], as trac0r's tonemap at exposure 1."""
    v = np.clip(np.nan_to_num(bottom_first, nan=0.0), 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)
    h, w, _ = s.shape
    img = bpy.data.images.new("png_out", w, h, alpha=False, float_buffer=True)
    img.colorspace_settings.name = "Non-Color"  # already encoded
    rgba = np.ones((h, w, 4), dtype=np.float32)
    rgba[:, :, :3] = s
    img.pixels.foreach_set(rgba.ravel())
    img.filepath_raw = path
    img.file_format = "PNG"
    img.save()


def main():
    args = parse_args()
    scene, width, height, max_depth = build_scene(args)
    print("blender %s, Cycles CPU, %dx%d, %d spp, sampling %s, seed %d, threads %d, "
          "max_bounces %d (scene max_depth %d)"
          % (bpy.app.version_string, width, height, args.spp,
             scene.cycles.sampling_pattern, args.seed, scene.render.threads,
             scene.cycles.max_bounces, max_depth))
    if args.warmup == "1spp":
        scene.cycles.samples = 1
        scene.cycles.seed = args.seed + 1000
        t0 = time.perf_counter()
        bpy.ops.render.render()
        print("warm-up render (1 spp): %.3f s" % (time.perf_counter() - t0))
        scene.cycles.samples = args.spp
        scene.cycles.seed = args.seed
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    bpy.ops.render.render()
    render_s = time.perf_counter() - t0
    cpu_s = time.process_time() - cpu0
    print("%d spp" % args.spp)
    print("render: %.3f s wall, %.3f s CPU of this process, %.2f Msamples/s"
          % (render_s, cpu_s, width * height * args.spp / render_s / 1e6))
    with tempfile.TemporaryDirectory(prefix="trac0r_cycles_") as tmp_dir:
        image = render_pixels(scene, width, height, tmp_dir)
    print("mean RGB: %.6f %.6f %.6f" % tuple(image.reshape(-1, 3).mean(axis=0)))
    for out in args.output:
        if out.lower().endswith(".pfm"):
            write_pfm_bottom_first(out, image)
        elif out.lower().endswith(".png"):
            write_png(os.path.abspath(out), image)
        else:
            raise SystemExit(out + ": expected .pfm or .png")
        print("wrote", out)


try:
    main()
except SystemExit as e:
    # Blender ignores a script's exit status; make a failure one.
    if e.code not in (None, 0):
        print("cycles_cornell_diffuse.py:", e.code, file=sys.stderr)
        sys.stdout.flush()
        os._exit(1)
    raise
