"""The Python module: renders equal to the program's, scenes from NumPy
arrays equal to scene files, cancelling, progress, Ctrl-C, errors.

Run by ctest (test_python) with PYTHONPATH=build/python and
TRAC0R_VIEWER=build/trac0r_viewer; run from the source tree's root.
"""

import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import trac0r

VIEWER = os.environ.get("TRAC0R_VIEWER", "build/trac0r_viewer")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    # PFM rows run bottom to top.
    return data.reshape(height, width, 3)[::-1]


def viewer_pfm(tmp_path, *args):
    out = str(tmp_path / "viewer.pfm")
    subprocess.run([VIEWER, *args, "--headless", "--output", out], check=True,
                   stderr=subprocess.DEVNULL)
    return read_pfm(out)


def test_render_returns_the_image_as_float32_without_a_copy():
    img = trac0r.render(trac0r.builtin_scene(), spp=2, width=40, height=30)
    assert img.shape == (30, 40, 3)
    assert img.dtype == np.float32
    assert not img.flags["OWNDATA"]  # a view of the render's own memory
    assert img.flags["C_CONTIGUOUS"]
    assert np.isfinite(img).all() and img.max() > 0


def test_render_equals_the_program_bit_for_bit(tmp_path):
    img = trac0r.render(os.path.join(ROOT, "scenes/cornell.json"), spp=8, width=64, height=48)
    ref = viewer_pfm(tmp_path, os.path.join(ROOT, "scenes/cornell.json"), "--spp", "8",
                     "--width", "64", "--height", "48")
    assert np.array_equal(img, ref)


def test_bdpt_renders_what_the_program_does_bit_for_bit(tmp_path):
    # Its splats are integer sums: the same bits whatever the threads do.
    scene = os.path.join(ROOT, "scenes/cornell.json")
    img = trac0r.render(scene, spp=4, width=64, height=48, integrator="bdpt")
    ref = viewer_pfm(tmp_path, scene, "--spp", "4", "--width", "64", "--height", "48",
                     "--integrator", "bdpt")
    assert np.array_equal(img, ref) and img.max() > 0


def test_seconds_and_target_error_stop_a_render():
    r = trac0r.render_images(trac0r.builtin_scene(), target_error=0.5, spp=4096, width=32,
                             height=24)
    assert r["estimate"] <= 0.5 and r["spp"] < 4096
    start = time.monotonic()
    r = trac0r.render_images(trac0r.builtin_scene(), seconds=0.3, width=32, height=24)
    assert 0.3 <= time.monotonic() - start < 30 and r["spp"] > 0


OBJ = """v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 0.5 -0.5
v 0 0 0.5
f 1 2 5
f 2 3 5
f 3 4 5
f 4 1 5
f 1 4 3
f 1 3 2
"""

ROOM = {
    "render": {"width": 48, "height": 36, "max_depth": 4},
    "camera": {"position": [0, 0, -2.5], "direction": [0, 0, 1]},
    "materials": {
        "white": {"type": "diffuse", "color": [0.8, 0.8, 0.8]},
        "red": {"type": "diffuse", "color": [0.8, 0.2, 0.1]},
    },
    "environment": {"color": [1.0, 1.0, 1.0]},
}


def test_a_mesh_from_numpy_arrays_renders_as_the_same_mesh_from_a_file(tmp_path):
    (tmp_path / "pyramid.obj").write_text(OBJ)
    placement = {"position": [0.25, 0, 0.5], "orientation": [0.3, 0.5, 0], "scale": [1, 1.5, 1]}
    from_file = dict(ROOM, shapes=[dict(type="mesh", file="pyramid.obj", material="red",
                                        **placement)])
    path = tmp_path / "scene.json"
    import json
    path.write_text(json.dumps(from_file))

    positions = np.array([[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, 0.5, -0.5],
                          [-0.5, 0.5, -0.5], [0, 0, 0.5]], dtype=np.float32)
    indices = np.array([[1, 2, 5], [2, 3, 5], [3, 4, 5], [4, 1, 5], [1, 4, 3], [1, 3, 2]]) - 1
    built = trac0r.scene_from_dict(ROOM)
    assert built.shape_count == 0
    built.add_mesh(positions, indices, material="red", **placement)
    assert built.triangle_count == 6

    a = trac0r.render(built, spp=4)
    b = trac0r.render(str(path), spp=4)
    assert a.shape == (36, 48, 3)
    assert np.array_equal(a, b)
    assert a.max() > 0


def test_a_scene_built_with_add_methods_renders_as_its_scene_file(tmp_path):
    (tmp_path / "pyramid.obj").write_text(OBJ)
    shapes = [
        {"type": "plane", "material": "floor", "position": [0, -0.6, 0], "size": [3, 3]},
        {"type": "box", "material": "coat", "position": [0.5, -0.3, 0.3], "size": [0.4, 0.6, 0.4],
         "orientation": [0, 0.4, 0]},
        {"type": "icosphere", "material": "gold", "position": [-0.5, -0.3, 0.2], "radius": 0.3},
        {"type": "mesh", "file": "pyramid.obj", "scale": [0.3, 0.3, 0.3],
         "position": [0, 0.2, 0.6], "smooth_angle": 40},
    ]
    materials = {
        "floor": {"type": "diffuse", "color": [0.7, 0.7, 0.6]},
        "coat": {"type": "plastic", "color": [0.1, 0.2, 0.7], "roughness": 0.3},
        "gold": {"type": "conductor", "metal": "gold", "roughness": 0.2},
    }
    lights = [{"type": "spot", "position": [0, 2, -1], "direction": [0, -1, 0.5], "intensity": 8,
               "angle": 50},
              {"type": "sun", "direction": [0.4, 1, -0.3], "irradiance": 1.5}]
    environment = {"color": [0.2, 0.3, 0.5], "strength": 0.5}
    described = {"render": ROOM["render"], "camera": ROOM["camera"], "materials": materials,
                 "shapes": shapes, "lights": lights, "environment": environment}
    path = tmp_path / "scene.json"
    import json
    path.write_text(json.dumps(described))

    built = trac0r.scene_from_dict({"render": ROOM["render"], "camera": ROOM["camera"],
                                    "materials": {"floor": materials["floor"]}})
    built.add_material("coat", **materials["coat"])
    built.add_material("gold", "conductor", metal="gold", roughness=np.float32(0.2))
    for shape in shapes:
        built.add_shape(base_dir=str(tmp_path), **shape)
    built.add_light("spot", position=np.array([0, 2, -1]), direction=(0, -1, 0.5), intensity=8,
                    angle=50)
    built.add_light(**lights[1])
    built.set_environment(**environment)
    assert built.materials == ["floor", "coat", "gold", "default"]
    a = trac0r.render(built, spp=4)
    b = trac0r.render(str(path), spp=4)
    assert a.max() > 0
    assert np.array_equal(a, b)


def test_bad_scene_objects_raise_value_errors_and_leave_the_scene_as_it_was():
    scene = trac0r.scene_from_dict(ROOM)
    before = (scene.materials, scene.shape_count, repr(scene))
    with pytest.raises(ValueError, match=r"^Scene.add_material: /red2/roughness: expected a number "
                                         r"in \[0, 1\], got 1.5$"):
        scene.add_material("red2", "glossy", color=(1, 0, 0), roughness=1.5)
    with pytest.raises(ValueError, match=r"/emittance: the colour times the emittance is 1e\+31"):
        scene.add_material("sun", "emissive", color=(1, 1, 1), emittance=1e31)
    with pytest.raises(ValueError, match=r'/material: unknown material "blue" \(known materials: '
                                         r'"red", "white"\)'):
        scene.add_shape("box", material="blue", size=(1, 1, 1))
    with pytest.raises(ValueError, match=r"/size: expected an array of 3 finite positive numbers"):
        scene.add_shape("box", material="red", size=(1, -1, 1))
    with pytest.raises(ValueError, match=r"Scene.add_shape: /file: .*no_such.obj"):
        scene.add_shape("mesh", file="no_such.obj")
    with pytest.raises(ValueError, match=r"/intensity: the colour times the intensity is 1e\+31"):
        scene.add_light("point", position=(0, 1, 0), intensity=1e31)
    with pytest.raises(ValueError, match=r"unknown key in a point light"):
        scene.add_light("point", position=(0, 1, 0), intensity=1, radius=2)
    with pytest.raises(ValueError, match=r"Scene.set_environment: /strength: expected a finite number >= 0, got -1"):
        scene.set_environment(color=(1, 1, 1), strength=-1)
    with pytest.raises(TypeError, match=r"expected numbers, lists, strings and booleans"):
        scene.add_light("point", position=object(), intensity=1)
    assert (scene.materials, scene.shape_count, repr(scene)) == before


def test_bad_meshes_raise_value_errors_naming_the_argument():
    scene = trac0r.scene_from_dict(ROOM)
    with pytest.raises(ValueError, match=r"indices: triangle 0 has vertex 7, past the 3"):
        scene.add_mesh(np.zeros((3, 3)), [[0, 1, 7]], material="white")
    with pytest.raises(ValueError, match=r"positions: expected 3 numbers a vertex"):
        scene.add_mesh(np.zeros(10), [[0, 1, 2]])
    with pytest.raises(ValueError, match=r'unknown material "blue" \(known materials: "red", "white"\)'):
        scene.add_mesh(np.eye(3), [[0, 1, 2]], material="blue")
    with pytest.raises(ValueError, match=r"positions: vertex 1 has a number that is not finite"):
        scene.add_mesh([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"no triangle of the shape can be rendered"):
        scene.add_mesh(np.zeros((3, 3)), [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"indices: expected an array of integers"):
        scene.add_mesh(np.eye(3), np.array([[0.0, 1.0, 2.0]]))
    with pytest.raises(ValueError, match=r"indices: triangle 0 has vertex -1"):
        scene.add_mesh(np.eye(3), [[0, 1, -1]])
    with pytest.raises(ValueError, match=r"position: expected three finite numbers"):
        scene.add_mesh(np.eye(3), [[0, 1, 2]], position=(0, float("inf"), 0))
    # None of the refused meshes changed the scene (not even its materials).
    assert scene.shape_count == 0 and scene.materials == ["red", "white"]
    scene.add_mesh(np.eye(3), [[0, 1, 2]])  # no material: the default grey, added now
    assert scene.shape_count == 1 and scene.materials == ["red", "white", "default"]


def test_bad_input_raises_with_the_loaders_messages(tmp_path):
    with pytest.raises(RuntimeError, match=r"no/such\.json"):
        trac0r.load_scene("no/such.json")
    with pytest.raises(RuntimeError, match=r"/materials/white/type"):
        trac0r.scene_from_dict(dict(ROOM, materials={"white": {"type": "paint"}}))
    with pytest.raises(ValueError, match=r"backend: expected 'cpu' or 'opencl', got 'gpu'"):
        trac0r.render(trac0r.builtin_scene(), spp=1, backend="gpu")
    with pytest.raises(ValueError, match=r"naive"):
        trac0r.render(trac0r.builtin_scene(), spp=1, integrator="mlt")
    with pytest.raises(ValueError, match=r"layers"):
        trac0r.render_images(trac0r.builtin_scene(), spp=1, layers=["colour"])
    scene = trac0r.builtin_scene()
    with pytest.raises(ValueError, match=r"seconds: expected 0 \(not set\) or a finite positive"):
        trac0r.render(scene, seconds=float("nan"))
    with pytest.raises(ValueError, match=r"target_error"):
        trac0r.render(scene, target_error=float("inf"))
    with pytest.raises(ValueError, match=r"width: expected an integer in \[1, 16384\], got 100000"):
        trac0r.render(scene, spp=1, width=100000)
    with pytest.raises(ValueError, match=r"max_depth"):
        scene.max_depth = 0
    with pytest.raises(ValueError, match=r"device: expected an OpenCL device index from 0"):
        trac0r.render(scene, spp=1, device=-1)
    with pytest.raises(ValueError, match=r"path: expected a str or path-like"):
        trac0r.load_scene(42)


def test_the_progress_callback_reports_and_cancels():
    seen = []

    def progress(p):
        seen.append((p.spp, p.fraction))
        return None if p.spp < 3 else False  # None (or True) goes on

    # Frames of 48 x 36 take well under the 0.1 s between reports: a slow
    # machine may report at a later spp; the render stops at the first
    # report from spp 3 on.
    r = trac0r.render_images(trac0r.builtin_scene(), spp=100000, width=48, height=36,
                             progress=progress)
    assert r["cancelled"]
    assert r["spp"] >= 3 and r["spp"] == seen[-1][0]
    assert all(0 <= f <= 1 for _, f in seen)
    again = trac0r.render(trac0r.builtin_scene(), spp=r["spp"], width=48, height=36)
    assert np.array_equal(r["image"], again)  # the partial image: whole frames


def test_an_exception_in_the_progress_callback_stops_the_render_and_is_raised():
    def progress(p):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        trac0r.render(trac0r.builtin_scene(), spp=100000, width=32, height=24, progress=progress)


def test_a_render_is_cancelled_from_another_thread_and_the_gil_is_free():
    token = trac0r.CancelToken()
    ticks = []

    def cancel_later():
        for _ in range(30):  # runs only while the render has released the GIL
            ticks.append(time.monotonic())
            time.sleep(0.01)
        token.cancel()

    thread = threading.Thread(target=cancel_later)
    start = time.monotonic()
    thread.start()
    # Held, the GIL would keep the thread from cancelling before the 20 s.
    r = trac0r.render_images(trac0r.builtin_scene(), seconds=20, width=48, height=36,
                             cancel=token)
    elapsed = time.monotonic() - start
    thread.join()
    assert token.cancelled and r["cancelled"]
    assert elapsed < 15 and r["spp"] > 0
    again = trac0r.render(trac0r.builtin_scene(), spp=r["spp"], width=48, height=36)
    assert np.array_equal(r["image"], again)
    # Cancelled, the token stops the next render after one frame, until reset.
    assert trac0r.render_images(trac0r.builtin_scene(), spp=50, width=8, height=6,
                                cancel=token)["spp"] == 1
    token.reset()
    assert trac0r.render_images(trac0r.builtin_scene(), spp=50, width=8, height=6,
                                cancel=token)["spp"] == 50


def test_ctrl_c_cancels_a_render_and_raises_keyboard_interrupt():
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        trac0r.render(trac0r.builtin_scene(), seconds=600, width=48, height=36)
    timer.join()
    assert time.monotonic() - start < 60


def test_layers_and_the_filtered_image_come_as_arrays():
    r = trac0r.render_images(trac0r.builtin_scene(), spp=4, width=32, height=24, filtered=True,
                             layers=["albedo", "normal", "depth", "variance"])
    assert r["filtered"].shape == (24, 32, 3)
    assert not np.array_equal(r["filtered"], r["image"])
    assert sorted(r["layers"]) == sorted(["albedo.R", "albedo.G", "albedo.B", "normal.X",
                                          "normal.Y", "normal.Z", "Z", "variance.Y"])
    assert all(v.shape == (24, 32) and v.dtype == np.float32 for v in r["layers"].values())
    assert np.array_equal(r["variance"], r["layers"]["variance.Y"])


def test_write_image_writes_what_it_is_given(tmp_path):
    img = trac0r.render(trac0r.builtin_scene(), spp=2, width=20, height=10)
    trac0r.write_image(str(tmp_path / "a.pfm"), img)
    assert np.array_equal(read_pfm(str(tmp_path / "a.pfm")), img)
    trac0r.write_image(str(tmp_path / "a.png"), img, exposure=2.0, view="filmic")
    assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match="height x width x 3"):
        trac0r.write_image(str(tmp_path / "b.png"), np.zeros((4, 4)))
    with pytest.raises(ValueError, match="filmic"):
        trac0r.write_image(str(tmp_path / "b.png"), img, view="log")
    assert not (tmp_path / "b.png").exists()


def test_a_model_file_opens_on_its_own_as_in_the_program(tmp_path):
    import pathlib
    model = os.path.join(ROOT, "scenes/meshes/tetrahedron.obj")
    scene = trac0r.load_scene(pathlib.Path(model))
    assert scene.triangle_count == 4
    img = trac0r.render(model, spp=2, width=32, height=24)
    ref = viewer_pfm(tmp_path, model, "--spp", "2", "--width", "32", "--height", "24")
    assert np.array_equal(img, ref)


@pytest.mark.parametrize("lens", [{"vertical_fov": 50},
                                  {"projection": "orthographic", "view_height": 0.8}])
def test_a_camera_block_moves_the_camera_as_the_programs_camera_flag(tmp_path, lens):
    import json
    camera = {"position": [0.2, 0.1, -0.3], "direction": [-0.3, -0.1, 1], **lens}
    (tmp_path / "camera.json").write_text(json.dumps({"camera": camera}))
    scene = trac0r.builtin_scene()
    scene.set_camera(camera)
    img = trac0r.render(scene, spp=2, width=32, height=24)
    ref = viewer_pfm(tmp_path, "--camera", str(tmp_path / "camera.json"), "--spp", "2",
                     "--width", "32", "--height", "24")
    assert np.array_equal(img, ref)
    assert not np.array_equal(img, trac0r.render(trac0r.builtin_scene(), spp=2, width=32,
                                                 height=24))
    with pytest.raises(RuntimeError, match=r"<camera>: /vertical_fov"):
        scene.set_camera({"vertical_fov": 500})
