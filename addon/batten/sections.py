"""Plane sections of a hull's exact surface as data: which planes a request names, and the
:class:`Section` each one gives (no Blender needed; :func:`batten.api.sections` is the call).

Families and how each argument names its planes (``None``: none of that family):

- ``stations`` (planes x = c), ``waterlines`` (z = c), ``buttocks`` (y = c): an int ``n`` for
  ``n`` planes evenly spaced over the hull's extent in that direction, the extremes left out
  (stations over [AP, FP] when the hull's perpendiculars are known, else its x-extent;
  waterlines over its z-extent; buttocks over its y-extent, the centreplane left out), or a
  sequence of offsets (m).
- ``diagonals``: a sequence of ``(y0, z0, angle_deg)``, the plane through the line parallel to
  x at (y0, z0) in the body plan whose trace there rises outboard at ``angle_deg`` above the
  horizontal (negative: falling outboard, as diagonals drawn from the centreline down across
  the bilge); or an int ``n`` for ``n`` diagonals from the centreline at heights evenly spaced
  over the z-extent (extremes left out), falling outboard at :data:`DEFAULT_DIAGONAL_ANGLE_DEG`.
  A diagonal's ``offset`` is the height where it crosses the centreplane.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from batten_native import BattenError, Curve, InvalidArgumentError, fair_points

#: The plane families in the order they are cut, and each one's singular (for names).
FAMILIES = {"stations": "station", "waterlines": "waterline", "buttocks": "buttock", "diagonals": "diagonal"}

#: The key of the knuckle (chine) lines in a :func:`batten.api.sections` result.
KNUCKLES = "knuckles"

#: The angle (degrees, falling outboard) of the diagonals asked for by count.
DEFAULT_DIAGONAL_ANGLE_DEG = -45.0

#: Unit normals of the axis families.
_AXIS = {"stations": (1.0, 0.0, 0.0), "waterlines": (0.0, 0.0, 1.0), "buttocks": (0.0, 1.0, 0.0)}


@dataclass(frozen=True)
class Section:
    """One plane section (or one knuckle line) of a hull.

    ``family``: ``"stations"``, ``"waterlines"``, ``"buttocks"``, ``"diagonals"`` or
    ``"knuckles"``; ``offset``: the plane's x, z or y (m; a diagonal's height at the
    centreplane; a knuckle line's index); ``name``: e.g. ``"station 12.500"``;
    ``polylines``: one (n, 3) float64 array per piece the plane cuts (hull coordinates, the drawn
    half), in order along the section, within the tolerance of the surface between points;
    ``curves``: the fitted NURBS of each polyline (:class:`batten_native.Curve`, knuckles kept
    as corners); ``closed`` and ``corners``: per polyline, whether it closes on itself and the
    indices of its corners (where it crosses a knuckle)."""

    family: str
    offset: float
    name: str
    polylines: list[np.ndarray]
    curves: list
    closed: list[bool] = field(default_factory=list)
    corners: list[list[int]] = field(default_factory=list)


def finite_offsets(values, what: str) -> list[float]:
    """``values`` as floats; InvalidArgumentError naming ``what`` for a value that is no number,
    NaN or infinite."""
    try:
        out = [float(v) for v in values]
    except (TypeError, ValueError):
        raise InvalidArgumentError(
            f"{what} must be a count or a sequence of numbers, got {values!r}"
        ) from None
    bad = [v for v in out if not math.isfinite(v)]
    if bad:
        raise InvalidArgumentError(f"{what}: offset {bad[0]} is not a finite number of metres")
    return out


def _count(n, what: str) -> int | None:
    if isinstance(n, bool):
        raise InvalidArgumentError(f"{what} must be a count or a sequence of offsets, not {n!r}")
    if isinstance(n, int | np.integer):
        if n < 0:
            raise InvalidArgumentError(f"{what} count {n} must not be negative")
        return int(n)
    return None


def _spread(n: int, lo: float, hi: float) -> list[float]:
    """``n`` values evenly spaced over (lo, hi), the ends left out."""
    return [float(v) for v in np.linspace(lo, hi, n + 2)[1:-1]]


def planes(
    family: str, spec, extent: tuple[float, float]
) -> list[tuple[tuple[float, float, float], float, float, str]]:
    """The planes ``spec`` names in ``family`` over ``extent`` (the hull's range in that
    direction): ``(normal, offset along it, section offset, name)`` each."""
    if spec is None:
        return []
    if family == "diagonals":
        return _diagonals(spec, extent)
    n = _count(spec, family)
    offsets = _spread(n, *extent) if n is not None else finite_offsets(spec, family)
    word = FAMILIES[family]
    return [(_AXIS[family], c, c, f"{word} {c:.3f}") for c in offsets]


def _diagonals(spec, extent) -> list:
    n = _count(spec, "diagonals")
    if n is not None:
        lines = [(0.0, z, DEFAULT_DIAGONAL_ANGLE_DEG) for z in _spread(n, *extent)]
    else:
        try:
            lines = [tuple(finite_offsets(d, "diagonals")) for d in spec]
        except TypeError:
            raise InvalidArgumentError(
                f"diagonals must be a count or a sequence of (y0, z0, angle_deg), got {spec!r}"
            ) from None
    out = []
    for line in lines:
        if len(line) != 3:
            raise InvalidArgumentError(f"diagonals: {line!r} is not (y0, z0, angle_deg)")
        y0, z0, angle = line
        if abs(angle) >= 90.0:
            raise InvalidArgumentError(
                f"diagonals: angle {angle}° must be within ±90° (a vertical plane is a buttock)"
            )
        a = math.radians(angle)
        normal = (0.0, -math.sin(a), math.cos(a))
        centre = z0 - y0 * math.tan(a)
        out.append((normal, normal[1] * y0 + normal[2] * z0, centre, f"diagonal {centre:.3f} {angle:+.1f}°"))
    return out


def cut(model, requests: dict, extents: dict, tolerance: float) -> dict[str, list[Section]]:
    """The sections of ``model`` (a :class:`batten_native.HullModel`) that ``requests`` (family
    → spec) ask for, over ``extents`` (family → (lo, hi)), and its knuckle lines, within
    ``tolerance`` (m)."""
    if not (isinstance(tolerance, int | float) and math.isfinite(tolerance) and tolerance > 0):
        raise InvalidArgumentError(f"tolerance {tolerance!r} must be a positive finite number of metres")
    result: dict[str, list[Section]] = {}
    for family in FAMILIES:
        ps = planes(family, requests.get(family), extents[family])
        cuts = (
            model.sections([p[0] for p in ps], [p[1] for p in ps], [p[3] for p in ps], tolerance)
            if ps
            else []
        )
        result[family] = [
            Section(
                family=family,
                offset=offset,
                name=name,
                polylines=[pts for pts, _, _, _ in pieces],
                curves=[c for _, _, _, c in pieces],
                closed=[closed for _, closed, _, _ in pieces],
                corners=[list(cs) for _, _, cs, _ in pieces],
            )
            for (_, _, offset, name), pieces in zip(ps, cuts, strict=True)
        ]
    result[KNUCKLES] = [
        _knuckle(k, name, pts, tolerance) for k, (name, pts) in enumerate(model.knuckle_lines())
    ]
    return result


def _knuckle(index: int, curve_name: str, points: np.ndarray, tolerance: float) -> Section:
    name = f"knuckle {curve_name}"
    curves: list[Curve] = []
    try:
        curve, _ = fair_points(name, points, tolerance=tolerance, corner_angle_deg=None)
        curves.append(curve)
    except BattenError:
        pass  # too few points to fit: the polyline is the line
    return Section(KNUCKLES, float(index), name, [points], curves, [False], [[]])


def all_sections(result: dict[str, list[Section]]) -> Sequence[Section]:
    """Every section of a :func:`cut` result, family by family."""
    return [s for family in (*FAMILIES, KNUCKLES) for s in result.get(family, [])]
