#!/usr/bin/env python3
"""Writes scenes/many_lights.json: a long hall lit by 64 small bulbs on
two strings, each bulb an emissive icosphere of 320 triangles (20,480
emitting triangles in all), in four colours, over a floor with a few
objects. From any point most bulbs are far away or turned away: what a
light tree is for. Deterministic; run from the repository root:
python3 benchmarks/many_lights/make_scene.py"""
import json

bulb_colours = {
    "warm": [1.0, 0.78, 0.5],
    "cool": [0.65, 0.8, 1.0],
    "rose": [1.0, 0.45, 0.5],
    "lime": [0.6, 1.0, 0.45],
}
materials = {
    "floor": {"type": "diffuse", "color": [0.6, 0.58, 0.55]},
    "wall": {"type": "diffuse", "color": [0.7, 0.7, 0.7]},
    "clay": {"type": "diffuse", "color": [0.75, 0.35, 0.2]},
    "steel": {"type": "glossy", "color": [0.9, 0.9, 0.9], "roughness": 0.15},
    "glass": {"type": "glass", "color": [0.95, 0.97, 1.0], "ior": 1.5},
}
for name, colour in bulb_colours.items():
    materials["bulb_" + name] = {"type": "emissive", "color": colour, "emittance": 60}

shapes = [
    {"type": "plane", "position": [0, 0, -14], "size": [6, 32], "material": "floor"},
    {"type": "plane", "position": [-3, 1.5, -14], "orientation": [0, 0, -1.5707963],
     "size": [3, 32], "material": "wall"},
    {"type": "plane", "position": [3, 1.5, -14], "orientation": [0, 0, 1.5707963],
     "size": [3, 32], "material": "wall"},
    {"type": "box", "position": [-1.2, 0.4, -3.5], "orientation": [0, 0.5, 0],
     "size": [0.8, 0.8, 0.8], "material": "clay"},
    {"type": "icosphere", "position": [0.6, 0.5, -2.5], "radius": 0.5, "subdivisions": 4,
     "material": "steel"},
    {"type": "icosphere", "position": [-0.5, 0.35, -7.5], "radius": 0.35, "subdivisions": 4,
     "material": "glass"},
    {"type": "box", "position": [1.1, 0.6, -11], "orientation": [0, -0.3, 0],
     "size": [0.6, 1.2, 0.6], "material": "clay"},
]
names = list(bulb_colours)
for side in (-1, 1):
    for i in range(32):
        z = -0.5 - 0.9 * i
        # Each string sags between hooks on the wall every 3.6 m.
        t = (i % 4 + 0.5) / 4.0
        y = 2.4 - 0.3 * 4.0 * t * (1.0 - t)
        x = side * 2.5
        shapes.append({"type": "icosphere", "position": [x, round(y, 3), round(z, 3)],
                       "radius": 0.04, "subdivisions": 2,
                       "material": "bulb_" + names[(i + (side > 0) * 2) % 4]})

scene = {
    "camera": {"position": [0, 1.4, 1.5], "direction": [0, -0.12, -1], "vertical_fov": 55},
    "render": {"width": 800, "height": 600, "max_depth": 6},
    "materials": materials,
    "shapes": shapes,
}
with open("scenes/many_lights.json", "w") as f:
    f.write("{\n")
    f.write('  "camera": ' + json.dumps(scene["camera"]) + ",\n")
    f.write('  "render": ' + json.dumps(scene["render"]) + ",\n")
    f.write('  "materials": {\n')
    f.write(",\n".join("    " + json.dumps(k) + ": " + json.dumps(v) for k, v in materials.items()))
    f.write("\n  },\n")
    f.write('  "shapes": [\n')
    f.write(",\n".join("    " + json.dumps(s) for s in shapes))
    f.write("\n  ]\n}\n")
