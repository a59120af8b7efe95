"""batten_native: the Rust core of batten (curves, networks, hull surfaces) for Python.

Everything here is implemented in Rust (``batten_native._native``); errors are raised as
subclasses of :class:`BattenError`, a :class:`ValueError` whose message names the curve and the
problem (``batten_native._errors``: CurveError with ``.curve``, FairError, NetworkFileError,
NoSurfaceError, InvalidArgumentError, HydrostaticsError, InternalError).
"""

from ._errors import (
    BattenError,
    CurveError,
    FairError,
    HydrostaticsError,
    InternalError,
    InvalidArgumentError,
    NetworkFileError,
    NoSurfaceError,
)
from ._native import (
    DEFAULT_CORNER_ANGLE_DEG,
    DEFAULT_FAIR_DEGREE,
    DEFAULT_FAIR_TOLERANCE,
    DEFAULT_RESOLUTION,
    DEFAULT_SECTION_MODEL_TOLERANCE,
    DEFAULT_SECTION_TOLERANCE,
    DEFAULT_TOLERANCE,
    MAX_RESOLUTION,
    ROLES,
    SECTION_CAPTURE_FACTOR,
    Curve,
    __version__,
    build_surface,
    check_lengths,
    chines_from_knuckles,
    fair_points,
    fairness,
    network_from_json,
    network_to_json,
    snap_to_nodes,
    topology,
)

__all__ = [
    "DEFAULT_CORNER_ANGLE_DEG",
    "DEFAULT_FAIR_DEGREE",
    "DEFAULT_FAIR_TOLERANCE",
    "DEFAULT_RESOLUTION",
    "DEFAULT_SECTION_MODEL_TOLERANCE",
    "DEFAULT_SECTION_TOLERANCE",
    "DEFAULT_TOLERANCE",
    "MAX_RESOLUTION",
    "ROLES",
    "SECTION_CAPTURE_FACTOR",
    "BattenError",
    "CurveError",
    "FairError",
    "HydrostaticsError",
    "InternalError",
    "InvalidArgumentError",
    "NetworkFileError",
    "NoSurfaceError",
    "Curve",
    "__version__",
    "build_surface",
    "check_lengths",
    "chines_from_knuckles",
    "fair_points",
    "fairness",
    "network_from_json",
    "network_to_json",
    "snap_to_nodes",
    "topology",
]
