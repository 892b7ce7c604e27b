# Type stubs of the extension (python/module.cpp); its docstrings give units and shapes.
from os import PathLike
from typing import Any

import numpy as np
import numpy.typing as npt

__version__: str

_Path = str | PathLike[str]
_Depth = npt.NDArray[np.uint16] | npt.NDArray[np.float32]
_Mask = npt.NDArray[np.bool_] | npt.NDArray[np.uint8]

class ProcessingError(RuntimeError): ...

class Mesh:
    def __init__(
        self,
        vertices: npt.ArrayLike,
        faces: npt.ArrayLike,
        colors: npt.ArrayLike | None = None,
        normals: npt.ArrayLike | None = None,
    ) -> None: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...  # N×3
    @property
    def faces(self) -> npt.NDArray[np.int32]: ...  # M×3
    @property
    def colors(self) -> npt.NDArray[np.float32]: ...  # N×3 RGB in [0, 1], or 0×3
    @property
    def normals(self) -> npt.NDArray[np.float64]: ...  # N×3, or 0×3
    @property
    def vertex_hole(self) -> npt.NDArray[np.int32]: ...  # N, -1 for the input's
    @property
    def face_hole(self) -> npt.NDArray[np.int32]: ...  # M, -1 for the input's

def fill_depth(
    depth: _Depth,
    mask: _Mask | None = None,
    *,
    color: npt.NDArray[np.uint8] | None = None,  # H×W×3 (RGB or BGR) or H×W grey
    inpainter: str = "harmonic",
    fast: bool = False,
    threads: int = ...,  # every hardware thread
    backend_max_pixels: int = 2000,
    max_hole_pixels: int = 0,
    keep_border: bool = False,
    reach: int = 32,
    discontinuity: float = 0.05,
    trend: str = "none",
    trend_ring: float = 3,
    margin: int = 5,
    radius: float = 5,
    foe_start: str = "telea",
    foe_tolerance: float = 3e-3,
    foe_iterations: int = 10,
) -> tuple[_Depth, dict[str, Any]]: ...
def inpaint(
    image: npt.NDArray[np.float32],
    mask: _Mask,
    backend: str,
    *,
    radius: float = 5,
    model: str = "depth",
    mls_alpha: float = 1 / 64,
    mls_ring: float = 3,
    foe_start: str = "harmonic",
    foe_tolerance: float = 1e-6,
    foe_iterations: int = 100,
) -> npt.NDArray[np.float32]: ...
def backends() -> list[str]: ...
def read_depth(path: _Path) -> _Depth: ...
def read_color(path: _Path) -> npt.NDArray[np.uint8]: ...
def write_depth(depth: _Depth, path: _Path) -> None: ...
def read_mesh(path: _Path) -> Mesh: ...
def write_mesh(mesh: Mesh, path: _Path, *, ascii: bool = False, provenance: bool = True) -> None: ...
def filler_names() -> list[str]: ...
def repair(
    mesh: Mesh,
    *,
    filler: str = "fairing",
    fallback: str = "plane,front,least-area",
    select: str = "fairing,fairing:c1,plane:telea",
    inpainter: str = "foe",
    trend: str = "auto",
    holes: list[int] | None = None,
    fill_all: bool = False,
    border_share: float = 0.2,
    max_hole_size: int = 0,
    max_hole_area: float = 0,
    passes: int = 8,
    threads: int = ...,  # every hardware thread
    beta: float = 0.87,
    gamma: float = 75,
    rings: int = 0,
    radius: float = 5,
    alpha: float = 1 / 64,
    mesher: str = "greedy",
) -> tuple[Mesh, dict[str, Any]]: ...
def holes(mesh: Mesh, *, vertices: bool = False) -> dict[str, Any]: ...
