"""Renders scene.json's quad, cube and lamp with Blender's Cycles.

    blender -b -P benchmarks/handedness/blender_render.py -- OUT.png [SPP]

Checks trac0r's camera convention against Blender's (docs/scene-format.md,
"The camera convention"): the same OBJ files (uv_quad.obj, red_cube.obj)
through Blender's own OBJ importer with its default axes (forward -Z, up Y:
OBJ (x, y, z) becomes Blender (x, -z, y)), the same camera, lamp and image
size as scene.json. Written for Debian 12's Blender 3.4; run.sh puts its
picture beside trac0r's.
"""
import math
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not argv:
    sys.exit("usage: blender -b -P blender_render.py -- OUT.png [SPP]")
out = os.path.abspath(argv[0])
spp = int(argv[1]) if len(argv) > 1 else 64

# scene.json's values, in OBJ/trac0r coordinates (y up).
WIDTH, HEIGHT = 320, 240
VERTICAL_FOV = 55.0                    # degrees
CAMERA = (0.0, 0.0, 3.0)               # looking along -z, y up
LAMP = (0.0, 1.0, 5.0)                 # a 6 x 6 square facing -z
LAMP_SIZE = 6.0
LAMP_RADIANCE = 2.0                    # trac0r's emittance, colour 1
MAX_DEPTH = 5


def blender_from_obj(p):
    """OBJ/trac0r (x, y, z) to Blender (x, -z, y), as the importer maps it."""
    x, y, z = p
    return (x, -z, y)


# An empty scene: no default cube, camera or light.
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene

for name in ("uv_quad.obj", "red_cube.obj"):
    path = os.path.join(HERE, name)
    if hasattr(bpy.ops.wm, "obj_import"):      # Blender 3.2+: the C++ importer
        bpy.ops.wm.obj_import(filepath=path, forward_axis="NEGATIVE_Z",
                              up_axis="Y")
    else:                                      # older: the Python add-on
        bpy.ops.import_scene.obj(filepath=path, axis_forward="-Z",
                                 axis_up="Y")

# The camera: Blender's looks along its local -Z with local +Y up; turned
# 90 degrees about X it looks along Blender +Y (OBJ -z) with Blender +Z
# (OBJ +y) up.
cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(VERTICAL_FOV)
cam = bpy.data.objects.new("camera", cam_data)
cam.location = blender_from_obj(CAMERA)
cam.rotation_euler = (math.radians(90.0), 0.0, 0.0)
scene.collection.objects.link(cam)
scene.camera = cam

# The lamp: an emitting square as in scene.json (a mesh, not a Blender
# light, so its radiance is trac0r's: an Emission shader of strength L
# emits radiance L). Its plane is OBJ z = 5, Blender y = -5.
h = LAMP_SIZE / 2
cx, cy, cz = blender_from_obj(LAMP)
lamp_mesh = bpy.data.meshes.new("lamp")
lamp_mesh.from_pydata([(cx - h, cy, cz - h), (cx + h, cy, cz - h),
                       (cx + h, cy, cz + h), (cx - h, cy, cz + h)],
                      [], [(0, 1, 2, 3)])
lamp = bpy.data.objects.new("lamp", lamp_mesh)
scene.collection.objects.link(lamp)
mat = bpy.data.materials.new("lamp")
mat.use_nodes = True
nodes = mat.node_tree.nodes
nodes.clear()
emission = nodes.new("ShaderNodeEmission")
emission.inputs["Strength"].default_value = LAMP_RADIANCE
output = nodes.new("ShaderNodeOutputMaterial")
mat.node_tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
lamp_mesh.materials.append(mat)
# Cycles' Emission shader emits from both sides of a face, as trac0r's
# emitters do; the lamp is behind the camera, out of its view.

# A black world, as trac0r's background.
world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.max_bounces = MAX_DEPTH
scene.render.resolution_x = WIDTH
scene.render.resolution_y = HEIGHT
scene.render.resolution_percentage = 100
# trac0r's PNG is radiance clamped to [0, 1] and sRGB-encoded: Blender's
# "Standard" view, not its default Filmic.
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.dither_intensity = 0.0    # trac0r does not dither its PNG
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.color_depth = "8"
scene.render.filepath = out

bpy.ops.render.render(write_still=True)
print("wrote", out)
