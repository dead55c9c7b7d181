"""trac0r: a real-time Monte Carlo path tracer, from Python.

    import trac0r
    img = trac0r.render("scenes/cornell.json", spp=16)   # float32, height x width x 3
    trac0r.write_image("cornell.png", img)

docs/python.md has more: scenes built from NumPy arrays, progress bars,
cancelling, the EXR layers.
"""

import json as _json

from ._trac0r import (  # noqa: F401
    CancelToken,
    Progress,
    Scene,
    __version__,
    builtin_scene,
    default_spp,
    load_scene,
    parse_scene,
    render_images,
    write_image,
)

__all__ = [
    "CancelToken",
    "Progress",
    "Scene",
    "builtin_scene",
    "default_spp",
    "load_scene",
    "parse_scene",
    "render",
    "render_images",
    "scene_from_dict",
    "write_image",
]


def render(scene, spp=0, seconds=0.0, target_error=0.0, **settings):
    """Renders a scene until a stop rule and returns the image.

    scene: a Scene, or the path of a scene file (JSON) or model file.
    spp, seconds, target_error: stop at whichever comes first (none given:
    64 spp). Other settings as render_images. Returns the mean radiance as a
    float32 NumPy array of height x width x 3.
    """
    return render_images(scene, spp=spp, seconds=seconds, target_error=target_error,
                         **settings)["image"]


def scene_from_dict(description, base_dir="."):
    """A scene from a dict in the scene format (docs/scene-format.md).

    'shapes' may be left out, for meshes added with Scene.add_mesh.
    """
    return parse_scene(_json.dumps(description), base_dir=base_dir)
