"""The exact surfaces of the hulls built in this session, kept for hydrostatics.

:func:`batten.api.build` keeps each source's :class:`batten_native.HullModel` here under the
source's name, with a fingerprint of the curves it was built from (their network JSON) and the
build's tolerance and resolution. Hydrostatics reuse it while the curves are unchanged and
rebuild it (with the same settings) when they have changed, so figures never describe a surface
other than the one the curves give now.
"""

from __future__ import annotations

from typing import NamedTuple

from batten_native import DEFAULT_RESOLUTION, DEFAULT_TOLERANCE, build_hull_model, network_to_json


class _Kept(NamedTuple):
    fingerprint: str
    tolerance: float
    resolution: int
    model: object


_kept: dict[str, _Kept] = {}


def fingerprint(name: str, curves: list) -> str:
    """What identifies the curves of a build: their network JSON."""
    return network_to_json(name, curves)


def keep(name: str, curves: list, tolerance: float, resolution: int, model) -> None:
    """Keep ``model``, built from ``curves`` with these settings, as ``name``'s surface."""
    _kept[name] = _Kept(fingerprint(name, curves), tolerance, resolution, model)


def model_for(name: str, curves: list):
    """The surface of ``curves`` under ``name``: the kept one when the curves are those it was
    built from, else built now with the last build's settings (or the defaults) and kept."""
    kept = _kept.get(name)
    key = fingerprint(name, curves)
    if kept is not None and kept.fingerprint == key:
        return kept.model
    tolerance = kept_tolerance(name)
    resolution = kept.resolution if kept else DEFAULT_RESOLUTION
    _arrays, _report, model = build_hull_model(curves, tolerance, resolution, name)
    _kept[name] = _Kept(key, tolerance, resolution, model)
    return model


def kept_tolerance(name: str) -> float:
    """The model tolerance ``name``'s kept surface was built with (the default if none)."""
    kept = _kept.get(name)
    return kept.tolerance if kept else DEFAULT_TOLERANCE


def forget(name: str | None = None) -> None:
    """Drop the kept surface of ``name`` (all of them with ``None``)."""
    if name is None:
        _kept.clear()
    else:
        _kept.pop(name, None)
