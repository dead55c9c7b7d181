# Type stubs of the extension trac0r._trac0r (python/module.cpp).
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str
default_spp: int

class Scene:
    width: int
    height: int
    max_depth: int
    @property
    def triangle_count(self) -> int: ...
    @property
    def shape_count(self) -> int: ...
    @property
    def materials(self) -> list[str]: ...
    @property
    def warnings(self) -> list[str]: ...
    def set_camera(self, camera: Union[dict, str]) -> None: ...
    def add_material(self, name: str, type: str, **params: Any) -> None: ...
    def add_shape(self, type: str, base_dir: str = ".", **params: Any) -> None: ...
    def add_light(self, type: str, **params: Any) -> None: ...
    def set_environment(self, base_dir: str = ".", **params: Any) -> None: ...
    def add_mesh(
        self,
        positions: npt.ArrayLike,
        indices: npt.ArrayLike,
        normals: Optional[npt.ArrayLike] = None,
        uvs: Optional[npt.ArrayLike] = None,
        material: str = "",
        position: Sequence[float] = (0.0, 0.0, 0.0),
        orientation: Sequence[float] = (0.0, 0.0, 0.0),
        scale: Sequence[float] = (1.0, 1.0, 1.0),
    ) -> None: ...

class Progress:
    @property
    def spp(self) -> int: ...
    @property
    def seconds(self) -> float: ...
    @property
    def paths_per_second(self) -> float: ...
    @property
    def estimate(self) -> float: ...
    @property
    def fraction(self) -> float: ...

class CancelToken:
    def __init__(self) -> None: ...
    def cancel(self) -> None: ...
    @property
    def cancelled(self) -> bool: ...

def load_scene(path: str, strict: bool = False) -> Scene: ...
def parse_scene(text: str, base_dir: str = ".", strict: bool = False) -> Scene: ...
def builtin_scene() -> Scene: ...
def render_images(
    scene: Union[Scene, str],
    spp: int = 0,
    seconds: float = 0.0,
    target_error: float = 0.0,
    width: int = 0,
    height: int = 0,
    max_depth: int = 0,
    seed: int = 1,
    backend: str = "cpu",
    device: int = 0,
    threads: int = 0,
    integrator: str = "",
    sampler: str = "",
    progress: Optional[Callable[[Progress], Optional[bool]]] = None,
    cancel: Optional[CancelToken] = None,
    filtered: bool = False,
    layers: Sequence[str] = (),
) -> dict: ...
def write_image(
    path: str, image: npt.NDArray[np.float32], exposure: float = 1.0, view: str = "standard"
) -> None: ...
