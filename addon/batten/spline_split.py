"""A new point in a Blender spline where its curve already passes, its shape unchanged: the
Bézier piece (or POLY segment) is split by de Casteljau's construction (in homogeneous
coordinates, so a rational NURBS piece splits exactly too), so a station gets a point of its
own where it crosses a chine and can be attached there (:func:`batten.hierarchy.attach`).

The splines it splits are those whose points the curve passes through
(:func:`batten.spline_joints.joint_layout`): Bézier splines, cubic NURBS splines with end-point and
Bézier knots, and POLY splines. Their core curves (:mod:`batten.bridge.curves_in`) have a unit
of parameter per piece, so parameter ``t`` lies in piece ``floor(t)``.
"""

from __future__ import annotations

import numpy as np


def de_casteljau(points: np.ndarray, u: float) -> tuple[np.ndarray, np.ndarray]:
    """The control points (each (p + 1, d)) of the two halves of the Bézier piece ``points``
    ((p + 1, d), homogeneous where rational) split at ``u`` in (0, 1)."""
    rows = [np.asarray(points, dtype=float)]
    while len(rows[-1]) > 1:
        r = rows[-1]
        rows.append((1.0 - u) * r[:-1] + u * r[1:])
    return np.array([r[0] for r in rows]), np.array([r[-1] for r in reversed(rows)])


def _point_arrays(points, attrs: dict[str, int]) -> dict[str, np.ndarray]:
    out = {}
    for attr, width in attrs.items():
        dtype = np.int32 if attr.endswith("_type") else np.float32
        buf = np.empty(len(points) * width, dtype=dtype)
        points.foreach_get(attr, buf)
        out[attr] = buf.reshape(len(points), width) if width > 1 else buf
    return out


def _write(points, arrays: dict[str, np.ndarray], added: int) -> None:
    points.add(added)
    for attr, values in arrays.items():
        points.foreach_set(attr, np.ascontiguousarray(values).ravel())


#: Per-point arrays of a Bézier spline (width), kept through a split.
BEZIER_ATTRS = {
    "co": 3,
    "handle_left": 3,
    "handle_right": 3,
    "handle_left_type": 1,
    "handle_right_type": 1,
    "tilt": 1,
    "radius": 1,
}
#: Per-point arrays of a NURBS or POLY spline (width), kept through a split.
NURBS_ATTRS = {"co": 4, "tilt": 1, "radius": 1}
#: Blender's handle types: the handles a split changes become these (their positions are
#: what keeps the shape, so Blender must not recompute them).
FREE, ALIGNED, AUTO, VECTOR, AUTO_CLAMPED = 0, 1, 2, 3, 4


def split(spline, piece: int, u: float) -> None:
    """Insert a point into ``spline`` in its piece ``piece`` at ``u`` (0 < u < 1), keeping its
    shape: a Bézier spline gets one point (its neighbours' inner handles shortened, automatic
    handles made aligned so Blender keeps them), a cubic Bézier-knot NURBS spline three control
    points, a POLY spline one. The new point is the spline's point ``piece + 1`` (among the
    points it passes through)."""
    if spline.type == "BEZIER":
        bp = spline.bezier_points
        a = _point_arrays(bp, BEZIER_ATTRS)
        k = piece
        piece_pts = np.array([a["co"][k], a["handle_right"][k], a["handle_left"][k + 1], a["co"][k + 1]])
        first, second = de_casteljau(piece_pts.astype(float), u)
        new = {
            "co": first[3],
            "handle_left": first[2],
            "handle_right": second[1],
            "handle_left_type": ALIGNED,
            "handle_right_type": ALIGNED,
            "tilt": (1 - u) * a["tilt"][k] + u * a["tilt"][k + 1],
            "radius": (1 - u) * a["radius"][k] + u * a["radius"][k + 1],
        }
        out = {attr: np.insert(v, k + 1, new[attr], axis=0) for attr, v in a.items()}
        out["handle_right"][k], out["handle_left"][k + 2] = first[1], second[2]
        for side, i in (("handle_right_type", k), ("handle_left_type", k + 2)):
            if out[side][i] in (AUTO, AUTO_CLAMPED):
                out[side][i] = ALIGNED
            elif out[side][i] == VECTOR:
                out[side][i] = FREE
        # Automatic handles elsewhere on the two points would be recomputed from the new
        # neighbour: aligned keeps them where they are.
        for side in ("handle_left_type", "handle_right_type"):
            for i in (k, k + 2):
                if out[side][i] in (AUTO, AUTO_CLAMPED):
                    out[side][i] = ALIGNED
        _write(bp, {attr: v.astype(a[attr].dtype) for attr, v in out.items()}, 1)
        return
    pts = spline.points
    a = _point_arrays(pts, NURBS_ATTRS)
    co = a["co"].astype(float)
    homogeneous = np.column_stack([co[:, :3] * co[:, 3:4], co[:, 3]])
    if spline.type == "POLY" or spline.order_u == 2:
        lo, degree = piece, 1
    else:
        lo, degree = 3 * piece, 3
    first, second = de_casteljau(homogeneous[lo : lo + degree + 1], u)
    inner = np.concatenate([first[1:], second[1:-1]])  # replaces the piece's inner points
    inner = np.column_stack([inner[:, :3] / inner[:, 3:4], inner[:, 3]])
    added = len(inner) - (degree - 1)
    s = np.linspace(0.0, 1.0, len(inner) + 2)[1:-1]

    def along(values):
        v0, v1 = values[lo], values[lo + degree]
        return (1 - s) * v0 + s * v1

    out = {
        "co": np.concatenate([co[: lo + 1], inner, co[lo + degree :]]),
        "tilt": np.concatenate([a["tilt"][: lo + 1], along(a["tilt"]), a["tilt"][lo + degree :]]),
        "radius": np.concatenate([a["radius"][: lo + 1], along(a["radius"]), a["radius"][lo + degree :]]),
    }
    _write(pts, {attr: v.astype(np.float32) for attr, v in out.items()}, added)
