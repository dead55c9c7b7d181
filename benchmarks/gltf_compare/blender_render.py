"""Renders scene.json's glTF model with Blender's own glTF importer and
Cycles, for comparison with trac0r's render of the same file.

    blender -b -P benchmarks/gltf_compare/blender_render.py -- OUT.png [SPP]

The same camera, image size and light as scene.json: a white world of
radiance 1 (trac0r's "environment": {"color": [1, 1, 1]}), Cycles with the
"Standard" view (trac0r's PNG: radiance clamped to [0, 1], sRGB). The
importer maps glTF (x, y, z) to Blender (x, -z, y). Written for Debian 12's
Blender 3.4; run.sh puts its picture beside trac0r's.
"""
import json
import math
import os
import sys

import bpy
import numpy

# Debian 12's Blender 3.4 glTF importer still names numpy.bool, which
# Debian's numpy 1.24 no longer has; the builtin is what it meant.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

HERE = os.path.dirname(os.path.abspath(__file__))

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not argv:
    sys.exit("usage: blender -b -P blender_render.py -- OUT.png [SPP]")
out = os.path.abspath(argv[0])
spp = int(argv[1]) if len(argv) > 1 else 64

with open(os.path.join(HERE, "scene.json")) as f:
    scene_json = json.load(f)
camera = scene_json["camera"]
render = scene_json["render"]
model = scene_json["shapes"][0]["file"]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
bpy.ops.import_scene.gltf(filepath=model)


def blender_from_gltf(p):
    x, y, z = p
    return (x, -z, y)


# scene.json's camera looks along -z with y up: Blender's camera turned 90
# degrees about X looks along Blender +Y (glTF -z) with Blender +Z up.
cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(camera["vertical_fov"])
cam = bpy.data.objects.new("camera", cam_data)
cam.location = blender_from_gltf(camera["position"])
cam.rotation_euler = (math.radians(90.0), 0.0, 0.0)
scene.collection.objects.link(cam)
scene.camera = cam

world = bpy.data.worlds.new("white")
world.use_nodes = True
background = world.node_tree.nodes["Background"]
background.inputs["Color"].default_value = (1, 1, 1, 1)
background.inputs["Strength"].default_value = 1.0
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.max_bounces = render["max_depth"]
scene.render.resolution_x = render["width"]
scene.render.resolution_y = render["height"]
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.dither_intensity = 0.0
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.color_depth = "8"
scene.render.filepath = out
bpy.ops.render.render(write_still=True)
print("wrote", out)
