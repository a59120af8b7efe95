"""Type stubs of the compiled module batten_native._native."""

from collections.abc import Callable, Sequence
from typing import Final, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "Curve",
    "MeshHull",
    "DEFAULT_CORNER_ANGLE_DEG",
    "DEFAULT_CUT_TOLERANCE",
    "DEFAULT_EXPORT_TOLERANCE",
    "DEFAULT_FAIR_DEGREE",
    "DEFAULT_FAIR_TOLERANCE",
    "DEFAULT_RESOLUTION",
    "DEFAULT_SECTION_MODEL_TOLERANCE",
    "DEFAULT_SECTION_TOLERANCE",
    "DEFAULT_SURFACE_FAIR_TOLERANCE",
    "DEFAULT_TOLERANCE",
    "MAX_RESOLUTION",
    "ROLES",
    "SECTION_CAPTURE_FACTOR",
    "MAX_TANGENT_TURN_DEGREES",
    "__version__",
    "_panic_for_tests",
    "build_surface",
    "build_hull_model",
    "cad_faces",
    "cad_text",
    "HullModel",
    "LiveHull",
    "SEA_WATER_DENSITY",
    "check_lengths",
    "chines_from_knuckles",
    "fair_points",
    "fair_sections",
    "fairness",
    "mesh_hydrostatics",
    "mesh_sectional_areas",
    "network_from_json",
    "network_to_json",
    "nodes_from_data",
    "same_curves",
    "section_noise",
    "snap_to_nodes",
    "topology",
    "form_topology",
    "transform_hydrostatic",
    "transform_network",
]
__version__: Final[str]
DEFAULT_TOLERANCE: Final[float]
DEFAULT_RESOLUTION: Final[int]
MAX_RESOLUTION: Final[int]
DEFAULT_FAIR_TOLERANCE: Final[float]
DEFAULT_SECTION_TOLERANCE: Final[float]
DEFAULT_SECTION_MODEL_TOLERANCE: Final[float]
DEFAULT_CORNER_ANGLE_DEG: Final[float]
DEFAULT_FAIR_DEGREE: Final[int]
ROLES: Final[list[str]]
SECTION_CAPTURE_FACTOR: Final[float]
MAX_TANGENT_TURN_DEGREES: Final[float]
DEFAULT_CUT_TOLERANCE: Final[float]
DEFAULT_EXPORT_TOLERANCE: Final[float]

_F64 = npt.NDArray[np.float64]
_ArrayLike = npt.ArrayLike

@final
class Curve:
    """A designer curve: name, role and NURBS geometry (immutable; edits return new curves)."""

    def __new__(
        cls,
        name: str,
        degree: int,
        knots: _ArrayLike,
        points: _ArrayLike,
        weights: _ArrayLike | None = None,
        role: str = "free",
    ) -> Curve: ...
    @staticmethod
    def from_nurbs(
        name: str,
        points: _ArrayLike,
        order: int,
        endpoint: bool = False,
        bezier: bool = False,
        cyclic: bool = False,
        role: str = "free",
    ) -> Curve: ...
    @staticmethod
    def from_bezier(
        name: str,
        co: _ArrayLike,
        left: _ArrayLike,
        right: _ArrayLike,
        cyclic: bool = False,
        role: str = "free",
    ) -> Curve: ...
    @staticmethod
    def from_poly(name: str, points: _ArrayLike, cyclic: bool = False, role: str = "free") -> Curve: ...
    @property
    def name(self) -> str: ...
    @property
    def role(self) -> str: ...
    @property
    def degree(self) -> int: ...
    @property
    def knots(self) -> _F64: ...
    @property
    def control_points(self) -> _F64: ...
    @property
    def weights(self) -> _F64 | None: ...
    @property
    def domain(self) -> tuple[float, float]: ...
    def renamed(self, name: str | None = None, role: str | None = None) -> Curve: ...
    def evaluate(self, t: _ArrayLike) -> _F64: ...
    def derivatives(self, t: float) -> _F64: ...
    def arc_length(self, accuracy: float = 1e-9) -> float: ...
    def nearest(
        self, point: tuple[float, float, float] | list[float], accuracy: float = 1e-9
    ) -> tuple[float, float, _F64]: ...
    def bounding_box(self, accuracy: float = 1e-9) -> tuple[list[float], list[float]]: ...
    def split(self, t: float) -> tuple[Curve, Curve]: ...
    def insert_knot(self, t: float, times: int = 1) -> Curve: ...
    def reversed(self) -> Curve: ...
    def corners(self, min_angle_deg: float = 0.1) -> list[float]: ...
    def curvature(self, t: _ArrayLike) -> tuple[_F64, _F64]: ...
    def matching_layout(self) -> str | None: ...
    def bezier_control_points(self) -> _F64: ...

def network_to_json(
    name: str, curves: list[Curve], tangent_planes: Sequence[Sequence[float]] | None = None
) -> str: ...
def same_curves(a: list[Curve], b: list[Curve]) -> bool: ...
def network_from_json(text: str) -> tuple[str, list[Curve], list[list[float]]]: ...
def check_lengths(curves: list[Curve], tolerance: float) -> None: ...
def chines_from_knuckles(
    curves: list[Curve], knuckles: list[_ArrayLike], tolerance: float
) -> list[Curve]: ...
def nodes_from_data(
    names: list[str],
    points: list[_ArrayLike],
    tolerance: float,
    corner_angle_deg: float | None,
    model_tolerance: float,
) -> tuple[list[_F64], list[list[int | None]], list[dict]]: ...
def snap_to_nodes(
    curves: list[Curve],
    capture: float,
    points: list[_ArrayLike] | None = None,
    tolerance: float | None = None,
) -> tuple[list[Curve], list[dict]]: ...
def _panic_for_tests(message: str) -> None: ...  # dev builds only (cargo feature test-hooks)
def fair_points(
    name: str,
    points: _ArrayLike,
    *,
    degree: int | None = None,  # None: DEFAULT_FAIR_DEGREE
    tolerance: float | None = None,
    noise: float | None = None,
    smoothing_factor: float | None = None,
    corners: list[int] | None = None,
    corner_angle_deg: float | None = ...,  # DEFAULT_CORNER_ANGLE_DEG
    start_tangent: tuple[float, float, float] | None = None,
    end_tangent: tuple[float, float, float] | None = None,
    model_tolerance: float = ...,  # DEFAULT_TOLERANCE
    max_parameter_iterations: int | None = None,  # None: 20 rounds of parameter correction
    role: str = "free",
    flat_planes: list[tuple[tuple[float, float, float], float, float]] | None = None,  # (normal, offset, tol)
    flat_noise: float | None = None,  # None: each flat plane's tolerance
) -> tuple[Curve, dict]: ...
def fairness(curve: Curve) -> dict: ...
def fair_sections(
    curves: list[Curve],
    *,
    tolerance: float = ...,  # DEFAULT_SURFACE_FAIR_TOLERANCE
    families: list[str] = ...,  # ["stations", "waterlines"]
    fixed_roles: list[str] | None = None,  # None: keel, stem, transom, deck, midship, fos, fob, knuckle
    fixed_curves: list[str] = ...,
    fixed_points: list[tuple[float, float, float]] = ...,
    curve_tolerances: list[tuple[str, float]] = ...,
    filter: str = "cubic",
    max_rounds: int = ...,
    bias_target: float | None = None,
    smoothing_length: float | None = None,  # None: 200 x tolerance; 0: no smoothing along the sections
    model_tolerance: float = ...,  # DEFAULT_TOLERANCE
    progress: Callable[[int, int], object] | None = None,  # False stops: Cancelled
) -> tuple[list[Curve], dict]: ...
def section_noise(
    curves: list[Curve],
    amplitude: float,
    seed: int,
    *,
    families: list[str] = ...,
    fixed_roles: list[str] | None = None,
    fixed_curves: list[str] = ...,
    model_tolerance: float = ...,
) -> list[Curve]: ...

DEFAULT_SURFACE_FAIR_TOLERANCE: Final[float]

def topology(curves: list[Curve], tolerance: float = ...) -> dict: ...  # DEFAULT_TOLERANCE
def form_topology(
    curves: list[Curve],
    tolerance: float = ...,  # DEFAULT_TOLERANCE
    draft: float | None = None,
) -> dict: ...
def transform_network(
    curves: list[Curve],
    targets: list[tuple[str, float]],
    moves: list[tuple[int, tuple[float, float, float]]],
    tolerance: float = ...,  # DEFAULT_TOLERANCE
    draft: float | None = None,
) -> tuple[list[Curve], dict]: ...
def transform_hydrostatic(
    curves: list[Curve],
    draft: float,
    *,
    volume: float | None = None,
    displacement: float | None = None,
    cb: float | None = None,
    cp: float | None = None,
    lcb: float | None = None,
    keep_pmb: bool | str | None = None,
    lpp: float | None = None,
    fp: float | None = None,
    density: float = ...,  # SEA_WATER_DENSITY
    tolerance: float = ...,  # DEFAULT_TOLERANCE
    resolution: int = ...,  # DEFAULT_RESOLUTION
    tangent_planes: Sequence[Sequence[float]] | None = None,  # each [nx, ny, nz, offset]
) -> tuple[list[Curve], dict]: ...

SEA_WATER_DENSITY: float

@final
class HullModel:
    @property
    def cells(self) -> int: ...
    @property
    def cells_kept(self) -> int: ...
    @property
    def is_half(self) -> bool: ...
    def datums(
        self, draft: float, lpp: float | None = None, fp: float | None = None
    ) -> tuple[float, float]: ...
    def hydrostatics(
        self,
        draft: float,
        trim: float = 0.0,
        heel: float = 0.0,
        density: float = ...,
        lpp: float | None = None,
        fp: float | None = None,
        live: bool = False,
    ) -> dict[str, float]: ...
    def sectional_areas(
        self,
        draft: float,
        xs: list[float],
        trim: float = 0.0,
        heel: float = 0.0,
        lpp: float | None = None,
        fp: float | None = None,
    ) -> _F64: ...
    def level_draft(self, displacement: float, density: float = ...) -> float: ...
    def float_to(
        self,
        displacement: float,
        lcg: float,
        design_draft: float,
        vcg: float | None = None,
        density: float = ...,
        lpp: float | None = None,
        fp: float | None = None,
    ) -> dict[str, float]: ...
    def sections(
        self,
        normals: list[tuple[float, float, float]],
        offsets: list[float],
        names: list[str],
        tolerance: float = ...,
    ) -> list[list[tuple[_F64, bool, list[int], Curve]]]: ...
    def knuckle_lines(self) -> list[tuple[str, _F64]]: ...
    def vertex_curvature(
        self, resolution: int
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.bool_]]: ...
    @property
    def bounds(self) -> tuple[list[float], list[float]]: ...

def build_hull_model(
    curves: list[Curve],
    tolerance: float = ...,  # DEFAULT_TOLERANCE
    resolution: int | None = None,  # None: DEFAULT_RESOLUTION
    name: str | None = None,
    tangent_planes: Sequence[Sequence[float]] | None = None,  # each [nx, ny, nz, offset]
) -> tuple[
    tuple[_F64, npt.NDArray[np.int32], npt.NDArray[np.int32], npt.NDArray[np.int32]], dict, HullModel
]: ...
def cad_text(
    model: HullModel,
    format: str,
    tolerance: float,
    allow_holes: bool,
    name: str,
    file_name: str,
    author: str,
    timestamp: tuple[int, int, int, int, int, int],
    *,
    progress: Callable[[int, int], object] | None = None,
) -> tuple[str, dict]: ...
def cad_faces(
    model: HullModel,
    tolerance: float,
    allow_holes: bool,
    *,
    progress: Callable[[int, int], object] | None = None,
) -> tuple[list[tuple[_F64, _F64, _F64]], dict]: ...
def build_surface(
    curves: list[Curve],
    tolerance: float = ...,  # DEFAULT_TOLERANCE
    resolution: int | None = None,  # None: DEFAULT_RESOLUTION
    name: str | None = None,
    tangent_planes: Sequence[Sequence[float]] | None = None,  # each [nx, ny, nz, offset]
) -> tuple[tuple[_F64, npt.NDArray[np.int32], npt.NDArray[np.int32], npt.NDArray[np.int32]], dict]: ...

_MeshArrays = tuple[_F64, npt.NDArray[np.int32], npt.NDArray[np.int32], npt.NDArray[np.int32]]

@final
class LiveHull:
    """A hull kept between edits and rebuilt incrementally (the mesh exactly a full build's)."""

    def __new__(
        cls,
        curves: list[Curve],
        tolerance: float = ...,  # DEFAULT_TOLERANCE
        resolution: int | None = None,  # None: DEFAULT_RESOLUTION
        name: str | None = None,
        tangent_planes: Sequence[Sequence[float]] | None = None,  # each [nx, ny, nz, offset]
    ) -> LiveHull: ...
    def result(self) -> tuple[_MeshArrays, dict, HullModel]: ...
    def rebuild(self, curves: list[Curve]) -> tuple[_MeshArrays, dict, HullModel]: ...
    def settle(self) -> tuple[_MeshArrays, dict, HullModel]: ...
    @property
    def measured(self) -> bool: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def resolution(self) -> int: ...

def mesh_hydrostatics(
    positions: _ArrayLike,
    triangles: _ArrayLike,
    draft: float,
    *,
    trim: float = 0.0,
    heel: float = 0.0,
    density: float = ...,  # 1.025 t/m³, sea water
    lpp: float | None = None,
    fp: float | None = None,
) -> dict[str, float]: ...
def mesh_sectional_areas(
    positions: _ArrayLike,
    triangles: _ArrayLike,
    draft: float,
    stations: int,
    *,
    trim: float = 0.0,
    heel: float = 0.0,
    lpp: float | None = None,
    fp: float | None = None,
) -> tuple[_F64, _F64]: ...

@final
class MeshHull:
    """A triangle mesh built once as a hull, for its hydrostatics at many flotations."""

    def __new__(cls, positions: _ArrayLike, triangles: _ArrayLike) -> MeshHull: ...
    @property
    def is_half(self) -> bool: ...
    @property
    def triangle_count(self) -> int: ...
    def hydrostatics(
        self,
        draft: float,
        *,
        trim: float = 0.0,
        heel: float = 0.0,
        density: float = ...,  # 1.025 t/m³, sea water
        lpp: float | None = None,
        fp: float | None = None,
    ) -> dict[str, float]: ...
    def sectional_areas(
        self,
        draft: float,
        stations: int,
        *,
        trim: float = 0.0,
        heel: float = 0.0,
        lpp: float | None = None,
        fp: float | None = None,
    ) -> tuple[_F64, _F64]: ...
