"""batten_native: the Rust core of batten (curves, networks, hull surfaces) for Python.

Everything here is implemented in Rust (``batten_native._native``); errors are raised as
:class:`BattenError`, a :class:`ValueError` whose message names the curve and the problem.
"""

from ._native import (
    DEFAULT_TOLERANCE,
    ROLES,
    BattenError,
    Curve,
    __version__,
    build_surface,
    check_lengths,
    fair_points,
    fairness,
    network_from_json,
    network_to_json,
    topology,
)

__all__ = [
    "DEFAULT_TOLERANCE",
    "ROLES",
    "BattenError",
    "Curve",
    "__version__",
    "build_surface",
    "check_lengths",
    "fair_points",
    "fairness",
    "network_from_json",
    "network_to_json",
    "topology",
]
