"""A curve object's exact cubic Bézier form: a NURBS or POLY spline written again as a Bézier
spline of the same shape, so the points it passes through can carry point attributes and be
attached (:mod:`batten.spline_joints`), and its handles edited as designers edit Bézier curves.

Exact for non-rational curves of degree 1 to 3: the curve's Bézier pieces (knots inserted to
full multiplicity) raised to degree 3 (Farin's degree elevation, ``Q_i = i/(p+1)·P_{i−1} +
(1 − i/(p+1))·P_i``), each piece's inner points the handles. A rational curve (a true circle
arc) or one of higher degree has no exact cubic Bézier form and is refused. Blender keeps
points in single precision, so the shape comes back to its rounding (about 1e-7 of the
coordinates).
"""

from __future__ import annotations

import numpy as np
from batten_native import CurveError

from .bridge import curves_in
from .spline_joints import single_spline

#: Weights this close to 1 (relative) are a non-rational curve's.
UNIT_WEIGHT = 1e-12


def elevate(points: np.ndarray, degree: int) -> np.ndarray:
    """The control points (4, d) of the Bézier piece ``points`` ((degree + 1, d)) raised to
    degree 3 (``degree`` ≤ 3)."""
    pts = np.asarray(points, dtype=float)
    for p in range(degree, 3):
        i = np.arange(1, p + 1)[:, None] / (p + 1)
        inner = i * pts[:-1] + (1.0 - i) * pts[1:]
        pts = np.concatenate([pts[:1], inner, pts[-1:]])
    return pts


def cubic_pieces(obj) -> np.ndarray:
    """The cubic Bézier pieces (k, 4, 3) of the curve object ``obj``'s spline, in world
    coordinates. CurveError naming it when it is not one spline, is rational, or of a degree
    above 3."""
    single_spline(obj)
    curve = curves_in.read_object(obj)[0]
    p = curve.degree
    if p > 3:
        raise CurveError(
            f"curve '{obj.name}' is of degree {p}: no cubic Bézier spline has its shape exactly "
            "(a degree 1 to 3 curve has)",
            obj.name,
        )
    weights = curve.weights
    if weights is not None and np.any(np.abs(np.asarray(weights) - 1.0) > UNIT_WEIGHT):
        raise CurveError(
            f"curve '{obj.name}' is rational (weights other than 1, a circle arc): no Bézier spline "
            "has its shape exactly",
            obj.name,
        )
    rows = np.asarray(curve.bezier_control_points(), dtype=float)[:, :3]
    count = (len(rows) - 1) // p
    return np.array([elevate(rows[k * p : k * p + p + 1], p) for k in range(count)])


def write_bezier(obj, pieces: np.ndarray) -> None:
    """Replace ``obj``'s spline by the Bézier spline of the cubic ``pieces`` (world), its
    handles free (so Blender keeps them where they are) and its end handles mirrored; the
    spline's resolution, smoothness and material kept."""
    matrix = np.array(obj.matrix_world, dtype=float)
    to_local = np.linalg.inv(matrix[:3, :3])

    def local(p: np.ndarray) -> np.ndarray:
        return (p - matrix[:3, 3]) @ to_local.T

    co = np.concatenate([pieces[:, 0], pieces[-1:, 3]])
    right = np.concatenate([pieces[:, 1], [2.0 * pieces[-1, 3] - pieces[-1, 2]]])
    left = np.concatenate([[2.0 * pieces[0, 0] - pieces[0, 1]], pieces[:, 2]])
    old = obj.data.splines[0]
    settings = {k: getattr(old, k) for k in ("resolution_u", "use_smooth", "material_index")}
    obj.data.splines.remove(old)
    spline = obj.data.splines.new("BEZIER")
    points = spline.bezier_points
    points.add(len(co) - 1)
    n = len(co)
    points.foreach_set("handle_left_type", np.zeros(n, dtype=np.int32))  # FREE
    points.foreach_set("handle_right_type", np.zeros(n, dtype=np.int32))
    for attr, values in (("co", co), ("handle_left", left), ("handle_right", right)):
        points.foreach_set(attr, local(values).astype(np.float32).ravel())
    for k, v in settings.items():
        setattr(spline, k, v)
    obj.data.update_tag()
