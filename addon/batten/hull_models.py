"""The exact surfaces of the hulls built in this session, kept for hydrostatics.

:func:`batten.api.build` keeps each source's :class:`batten_native.HullModel` here under the
source's name, with the curves it was built from and the build's tolerance, resolution and
tangent planes (:func:`batten.api.tangent_planes`). Hydrostatics reuse it while the curves and
planes are unchanged (the curves compared as curves: :func:`batten_native.same_curves`) and
rebuild it (with the same settings) when they have changed, so figures never describe a
surface other than the one the curves give now.
"""

from __future__ import annotations

from typing import NamedTuple

from batten_native import (
    DEFAULT_RESOLUTION,
    DEFAULT_TOLERANCE,
    LiveHull,
    build_hull_model,
    same_curves,
)


class _Kept(NamedTuple):
    curves: list
    tolerance: float
    resolution: int
    model: object
    #: False for a live rebuild's surface whose report (warnings, knuckle edges) is not yet
    #: measured: its patches and mesh are exact, its report is the last measured one.
    measured: bool = True
    #: The planes the surface is tangent to where curves run in them, each
    #: ``(nx, ny, nz, offset)`` (``build_hull_model``'s ``tangent_planes``).
    tangent_planes: tuple = ()


_kept: dict[str, _Kept] = {}

#: The live hulls (:class:`batten_native.LiveHull`) of the sources built with ``live=True``,
#: by source name: rebuilt incrementally while their curves move.
_live: dict[str, LiveHull] = {}


def keep(
    name: str,
    curves: list,
    tolerance: float,
    resolution: int,
    model,
    measured: bool = True,
    tangent_planes=(),
) -> None:
    """Keep ``model``, built from ``curves`` with these settings, as ``name``'s surface;
    ``measured`` False when its report waits for :func:`settle`."""
    _kept[name] = _Kept(curves, tolerance, resolution, model, measured, _planes(tangent_planes))


def _planes(tangent_planes) -> tuple:
    """The tangent planes as a tuple of 4-tuples of floats (comparable, hashable)."""
    return tuple(tuple(float(v) for v in p) for p in tangent_planes)


def model_for(name: str, curves: list, *, measured: bool = True, tangent_planes=None):
    """The surface of ``curves`` under ``name``: the kept one when the curves are those it was
    built from (and, when ``tangent_planes`` is given, with those planes), else built now with
    the last build's settings (or the defaults; ``tangent_planes`` when given) and kept.
    ``measured`` asks for a surface whose report is measured (sections and exports read its
    knuckle edges and warnings): a live rebuild's is measured first (:func:`settle`)."""
    kept = _kept.get(name)
    planes = _planes(tangent_planes) if tangent_planes is not None else None
    # The curves compared as they are (their names, roles and geometry), not by writing their
    # JSON: a live drag's figures pay microseconds for this, not milliseconds.
    if (
        kept is not None
        and same_curves(kept.curves, curves)
        and (planes is None or planes == kept.tangent_planes)
    ):
        if measured and not kept.measured:
            settle(name)
            return _kept[name].model
        return kept.model
    tolerance = kept_tolerance(name)
    resolution = kept.resolution if kept else DEFAULT_RESOLUTION
    if planes is None:
        planes = kept.tangent_planes if kept else ()
    _arrays, _report, model = build_hull_model(curves, tolerance, resolution, name, planes)
    _kept[name] = _Kept(curves, tolerance, resolution, model, True, planes)
    return model


def live_build(name: str, curves: list, tolerance: float, resolution: int, tangent_planes=()):
    """``(arrays, report, model)`` of ``curves`` from ``name``'s live hull: rebuilt when it
    was built with these settings (incrementally unless the curves' names, roles or
    connectivity changed, which its report says), else built anew and kept. The model is
    kept for hydrostatics as by :func:`keep`."""
    live = _live.get(name)
    planes = _planes(tangent_planes)
    kept = _kept.get(name)
    same_planes = kept is not None and kept.tangent_planes == planes
    if live is not None and live.tolerance == tolerance and live.resolution == resolution and same_planes:
        arrays, report, model = live.rebuild(curves)
    else:
        live = LiveHull(curves, tolerance, resolution, name, planes)
        arrays, report, model = live.result()
        _live[name] = live
    keep(name, curves, tolerance, resolution, model, measured=report["measured"], tangent_planes=planes)
    return arrays, report, model


def settle(name: str):
    """``(arrays, report, model)`` of ``name``'s live hull with its report measured (and that
    surface kept in place of the unmeasured one), or None when it has no live hull or its
    report is already measured."""
    live = _live.get(name)
    if live is None or live.measured:
        return None
    settled = live.settle()
    kept = _kept.get(name)
    if kept is not None and not kept.measured:
        _kept[name] = kept._replace(model=settled[2], measured=True)
    return settled


def kept_tolerance(name: str) -> float:
    """The model tolerance ``name``'s kept surface was built with (the default if none)."""
    kept = _kept.get(name)
    return kept.tolerance if kept else DEFAULT_TOLERANCE


def kept_resolution(name: str) -> int:
    """The resolution ``name``'s kept surface was meshed at (the default if none)."""
    kept = _kept.get(name)
    return kept.resolution if kept else DEFAULT_RESOLUTION


def forget_live(name: str) -> None:
    """Drop ``name``'s live hull (Live switched off), its surface measured first when the last
    live rebuild left it unmeasured, so the kept surface stays whole for hydrostatics, sections
    and exports."""
    settle(name)
    _live.pop(name, None)


def forget(name: str | None = None) -> None:
    """Drop the kept surface and live hull of ``name`` (all of them with ``None``)."""
    if name is None:
        _kept.clear()
        _live.clear()
    else:
        _kept.pop(name, None)
        _live.pop(name, None)
