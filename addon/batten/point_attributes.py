"""Point attributes of a curve (seed 002 §5, Fig. 3): rules on a curve's control points that
shape it where it passes through them, without the designer placing handles by hand.

- ``knuckle`` on a point: the curve has a corner there. Where it runs smoothly through the
  point, its handles are turned to point at the neighbouring points, a third of the way
  (Blender's *vector* handles); where it already turns there (a fitted chine), its handles stay;
- ``tangent`` on a point: the curve passes through it along a fixed direction (both handles on
  that line, their lengths kept);
- ``straight`` on a point pair (``point`` and the next): the curve is a straight line between
  them, and enters and leaves that line tangentially (unless an end is a knuckle);
- ``blend`` on a point pair: the curve between them is shaped by the tangents it arrives and
  leaves with (the handles towards the two tangent lines' meeting point, in the ratio a
  circular arc has: ``4/3·tan(θ/4) / tan(θ/2)`` of the way for a turn θ), as a bilge radius
  between a flat of side and a flat of bottom.

The rules act on *joints*: the points a curve passes through, each with a left and right
handle (a Bézier spline's points and handles; a cubic NURBS spline with Bézier knots' every
third control point and its neighbours). Like every attribute in the paper they add nothing
but control point positions, so a transformation moves the points and the rules hold again.
Pure numpy; :mod:`batten.hierarchy` reads and writes the Blender splines.
"""

from __future__ import annotations

import math

import numpy as np

#: The point attributes: two on one point, two on a point and the next.
KINDS = ("knuckle", "tangent", "straight", "blend")
#: The attributes on a pair of points (``point`` and ``point + 1``).
PAIR_KINDS = ("straight", "blend")
#: A point where the curve turns by more than this (radians) is a corner already.
CORNER = math.radians(0.1)
#: A handle shorter than this fraction of its segment's chord has no direction to keep.
SHORT_HANDLE = 1e-9


class AttributeConflict(ValueError):
    """Two attributes ask for different shapes at one point, or an attribute names a point the
    curve does not have. The message names the point."""


def validate(attributes: list[dict], count: int) -> None:
    """Check ``attributes`` on a curve of ``count`` joints: every point exists (a pair's second
    too), a tangent has a finite non-zero direction, a point is not both a knuckle and tangent,
    a tangent is not on a straight's end, a knuckle is not on a blend's end, and no point ends
    two blends. AttributeConflict naming the point otherwise."""
    knuckles, tangents, straight_ends, blend_ends = set(), set(), set(), {}
    for a in attributes:
        kind, i = a.get("kind"), a.get("point")
        if kind not in KINDS:
            raise AttributeConflict(f"unknown point attribute {kind!r} (one of {', '.join(KINDS)})")
        if not isinstance(i, int) or isinstance(i, bool) or not 0 <= i < count:
            raise AttributeConflict(f"{kind} on point {i!r}: the curve has points 0..{count - 1}")
        if kind in PAIR_KINDS and i + 1 >= count:
            raise AttributeConflict(f"{kind} on points {i}, {i + 1}: the curve's last point is {count - 1}")
        if kind == "knuckle":
            knuckles.add(i)
        elif kind == "tangent":
            d = np.asarray(a.get("direction", ()), dtype=float).reshape(-1)
            if d.shape != (3,) or not np.all(np.isfinite(d)) or np.linalg.norm(d) == 0.0:
                raise AttributeConflict(
                    f"tangent on point {i}: direction {a.get('direction')!r} is no direction"
                )
            tangents.add(i)
        elif kind == "straight":
            straight_ends.update((i, i + 1))
        else:
            for j in (i, i + 1):
                if j in blend_ends:
                    raise AttributeConflict(
                        f"point {j} ends two blends; a blend takes its tangent from the other side"
                    )
                blend_ends[j] = i
    for i in sorted(knuckles & tangents):
        raise AttributeConflict(f"point {i} is a knuckle and has a tangent; it can only be one")
    for i in sorted(tangents & straight_ends):
        raise AttributeConflict(f"point {i} has a tangent and ends a straight, which sets its own tangent")
    for i in sorted(knuckles & set(blend_ends)):
        raise AttributeConflict(f"point {i} is a knuckle and ends a blend, which is tangent at its ends")


def _unit(v: np.ndarray) -> np.ndarray | None:
    n = float(np.linalg.norm(v))
    return v / n if n > 0.0 and math.isfinite(n) else None


def _oriented(d: np.ndarray, along: np.ndarray) -> np.ndarray:
    """``d`` (unit) turned to point the way ``along`` does."""
    return -d if float(d @ along) < 0.0 else d


def apply(co: np.ndarray, left: np.ndarray, right: np.ndarray, attributes: list[dict]):
    """The joints' handles ``(left, right)`` (each (n, 3), world) that the ``attributes`` ask
    for, given the joints ``co`` and their handles as they are; a handle no attribute touches
    keeps its place. Rules run tangents, knuckles, straights, then blends (a blend takes its
    tangents from what the others made). :func:`validate` first."""
    n = len(co)
    validate(attributes, n)
    left, right = left.copy(), right.copy()

    def chord(i: int, j: int) -> np.ndarray:
        return co[j] - co[i]

    def set_along(i: int, d: np.ndarray, sides=("left", "right")) -> None:
        # Both handles of joint i on the line through it along d, their lengths kept (a third
        # of the neighbouring chord where a handle has no length).
        for side in sides:
            handle, sign, other = (left, -1.0, i - 1) if side == "left" else (right, 1.0, i + 1)
            if not 0 <= other < n:
                continue
            length = float(np.linalg.norm(handle[i] - co[i]))
            if length <= SHORT_HANDLE * float(np.linalg.norm(chord(i, other))):
                length = float(np.linalg.norm(chord(i, other))) / 3.0
            handle[i] = co[i] + sign * length * d

    for a in attributes:
        if a["kind"] == "tangent":
            i = a["point"]
            d = _unit(np.asarray(a["direction"], dtype=float))
            set_along(i, _oriented(d, through(co, left, right, i)))
    for a in attributes:
        if a["kind"] == "knuckle" and 0 < a["point"] < n - 1:  # an end is no corner
            i = a["point"]
            into, out = _unit(co[i] - left[i]), _unit(right[i] - co[i])
            if into is not None and out is not None and float(into @ out) < math.cos(CORNER):
                continue  # a corner already: the designer's (or the fit's) handles stay
            left[i] = co[i] + chord(i, i - 1) / 3.0
            right[i] = co[i] + chord(i, i + 1) / 3.0
    knuckles = {a["point"] for a in attributes if a["kind"] == "knuckle"}
    straights = [a["point"] for a in attributes if a["kind"] == "straight"]
    for i in straights:
        right[i] = co[i] + chord(i, i + 1) / 3.0
        left[i + 1] = co[i + 1] - chord(i, i + 1) / 3.0
    for i in straights:
        d = _unit(chord(i, i + 1))
        if d is None:
            continue
        # Into and out of the straight tangentially: the outer handles on its line.
        if i not in knuckles and i - 1 not in straights:
            set_along(i, d, ("left",))
        if i + 1 not in knuckles and i + 1 not in straights:
            set_along(i + 1, d, ("right",))
    for a in attributes:
        if a["kind"] == "blend":
            i = a["point"]
            t0 = _unit(co[i] - left[i]) if i > 0 else None
            t0 = t0 if t0 is not None else _unit(chord(i, i + 1))
            t1 = _unit(right[i + 1] - co[i + 1]) if i + 2 < n else None
            t1 = t1 if t1 is not None else _unit(chord(i, i + 1))
            if t0 is None or t1 is None:
                continue
            right[i], left[i + 1] = blend_handles(co[i], t0, co[i + 1], t1)
    return left, right


def through(co: np.ndarray, left: np.ndarray, right: np.ndarray, i: int) -> np.ndarray:
    """The unit direction the curve runs through joint ``i``: from its left handle to its right
    one, or from the joint before to the one after where the handles coincide (zero where the
    curve has no length there)."""
    n = len(co)
    d = _unit(right[i] - left[i])
    if d is None:
        d = _unit(co[min(i + 1, n - 1)] - co[max(i - 1, 0)])
    return d if d is not None else np.zeros(3)


def blend_handles(p0: np.ndarray, t0: np.ndarray, p1: np.ndarray, t1: np.ndarray):
    """The inner handles of the cubic from ``p0`` leaving along ``t0`` to ``p1`` arriving
    along ``t1`` (unit) that makes a circular arc where the two tangent lines meet at equal
    distances (the arc's 4/3·tan(θ/4)·r handle), and the same ratio of each distance where they
    do not. Where the lines do not meet ahead of both points (parallel, skew by more than a
    tenth of the chord, or behind), each handle is a third of the chord along its tangent."""
    chord = p1 - p0
    length = float(np.linalg.norm(chord))
    # The closest points of the lines p0 + s·t0 and p1 − u·t1.
    b = float(t0 @ t1)
    denom = 1.0 - b * b
    if denom > 1e-12:
        s = (float(chord @ t0) - b * float(chord @ t1)) / denom
        u = (float(chord @ t1) - b * float(chord @ t0)) / denom
        gap = np.linalg.norm((p0 + s * t0) - (p1 - u * t1))
        if s > 0.0 and u > 0.0 and gap <= 0.1 * length:
            theta = math.acos(max(-1.0, min(1.0, b)))
            k = 4.0 / 3.0 * math.tan(theta / 4.0) / math.tan(theta / 2.0)
            return p0 + k * s * t0, p1 - k * u * t1
    return p0 + length / 3.0 * t0, p1 - length / 3.0 * t1


def tangent_in_plane(direction: np.ndarray, normal: np.ndarray) -> np.ndarray | None:
    """``direction`` with its component along the plane's unit ``normal`` taken away, made
    unit: the tangent a curve attached to a curve held in that plane enters it with (a curve
    attribute, seed 002 §5). None when ``direction`` is square to the plane."""
    d = np.asarray(direction, dtype=float)
    flat = d - float(d @ normal) * normal
    if float(np.linalg.norm(flat)) <= 1e-9 * max(float(np.linalg.norm(d)), 1e-300):
        return None
    return _unit(flat)
