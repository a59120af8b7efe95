"""The points a Blender spline passes through (its *joints*) and the arrays of its points, for
the curve network hierarchy (:mod:`batten.hierarchy`) and the point attributes
(:mod:`batten.point_attributes`): a Bézier spline passes through every point, between its
handles; a cubic NURBS spline with end-point and Bézier knots through every third control
point, the control points beside it acting as its handles; a POLY spline through every point,
with no handles. Also where one curve passes nearest another (a station crossing a chine).
"""

from __future__ import annotations

import numpy as np
from batten_native import CurveError

from . import point_attributes
from .bridge import curves_in


def single_spline(obj):
    """The only spline of the curve object ``obj``; CurveError naming it otherwise."""
    if obj.type != "CURVE":
        raise CurveError(f"object '{obj.name}' is a {obj.type.lower()}, not a curve object", obj.name)
    if len(obj.data.splines) != 1:
        raise CurveError(
            f"curve '{obj.name}' has {len(obj.data.splines)} splines; only a curve of one spline can attach",
            obj.name,
        )
    return obj.data.splines[0]


def end_point(obj, end: str) -> np.ndarray:
    """The world position of ``obj``'s ``end`` (``start`` or ``end``)."""
    curve = curves_in.read_object(obj)[0]
    a, b = curve.domain
    return np.asarray(curve.evaluate([a if end == "start" else b]), dtype=float).reshape(3)


def joint_layout(spline, name: str) -> tuple[np.ndarray, bool]:
    """The indices in the spline's control polygon (``co``) of the points it passes through
    (its joints), and whether they have handles (a Bézier spline's, or a cubic NURBS spline's
    neighbouring control points). A POLY spline (or a NURBS spline of order 2) passes through
    every point with no handles. CurveError naming the curve for a NURBS spline whose knots do
    not make its joints plain (anything but end-point and Bézier knots of order 4)."""
    if spline.type == "BEZIER":
        return np.arange(len(spline.bezier_points)), True
    count = len(spline.points)
    if spline.type == "POLY" or spline.order_u == 2:
        return np.arange(count), False
    if spline.order_u == 4 and spline.use_bezier_u and spline.use_endpoint_u and not spline.use_cyclic_u:
        if (count - 1) % 3 == 0:
            return np.arange(0, count, 3), True
    raise CurveError(
        f"curve '{name}': its NURBS spline does not pass through its control points; points can be "
        "attached or given attributes on a Bézier spline or a cubic NURBS spline with end-point and "
        "Bézier knots (Make Bézier in the Form panel turns it into a Bézier spline of the same shape)",
        name,
    )


def joint_arrays(world: dict[str, np.ndarray], index: np.ndarray):
    """The joints' points and handles (world) of a spline's arrays, and a writer putting new
    handles back into them."""
    co = world["co"]
    if "handle_left" in world:
        left, right = world["handle_left"].copy(), world["handle_right"].copy()

        def put(new_left, new_right) -> None:
            world["handle_left"][:], world["handle_right"][:] = new_left, new_right

        return co[index].copy(), left, right, put
    # A cubic NURBS spline with Bézier knots: the control points beside each joint.
    n = len(co)
    left = np.array([co[j - 1] if j > 0 else co[j] for j in index])
    right = np.array([co[j + 1] if j + 1 < n else co[j] for j in index])

    def put(new_left, new_right) -> None:
        for k, j in enumerate(index):
            if j > 0:
                co[j - 1] = new_left[k]
            if j + 1 < n:
                co[j + 1] = new_right[k]

    return co[index].copy(), left, right, put


def spline_points(spline) -> dict[str, np.ndarray]:
    """The spline's point arrays by attribute (``co`` 3 or 4 wide, and a Bézier spline's
    handles), in the object's space."""
    if spline.type == "BEZIER":
        pts = spline.bezier_points
        out = {}
        for attr in ("co", "handle_left", "handle_right"):
            buf = np.empty(3 * len(pts), dtype=np.float32)
            pts.foreach_get(attr, buf)
            out[attr] = buf.reshape(-1, 3).astype(float)
        return out
    buf = np.empty(4 * len(spline.points), dtype=np.float32)
    spline.points.foreach_get("co", buf)
    return {"co": buf.reshape(-1, 4).astype(float)}


def write_points(spline, arrays: dict[str, np.ndarray]) -> None:
    points = spline.bezier_points if spline.type == "BEZIER" else spline.points
    for attr, values in arrays.items():
        points.foreach_set(attr, values.astype(np.float32).ravel())
    spline.id_data.update_tag()


def world_points(obj, spline) -> dict[str, np.ndarray]:
    """``spline``'s point arrays (:func:`spline_points`) in world coordinates, (n, 3) each, by
    ``obj``'s transform."""
    matrix = np.array(obj.matrix_world, dtype=float)
    return {a: w[:, :3] @ matrix[:3, :3].T + matrix[:3, 3] for a, w in spline_points(spline).items()}


def control_points_world(obj) -> np.ndarray:
    """Every control point of ``obj``'s spline (with a Bézier spline's handles), world (n, 3)."""
    return np.concatenate(list(world_points(obj, single_spline(obj)).values()))


def joint_points(obj) -> np.ndarray:
    """The world positions of the points ``obj``'s spline passes through (its joints)."""
    spline = single_spline(obj)
    index, _ = joint_layout(spline, obj.name)
    return world_points(obj, spline)["co"][index]


def joint_direction(obj, k: int) -> np.ndarray:
    """The direction ``obj``'s curve runs through its joint ``k`` (world): from its left handle
    to its right one, or from the joint before to the one after where they coincide."""
    spline = single_spline(obj)
    index, _ = joint_layout(spline, obj.name)
    world = world_points(obj, spline)
    co, left, right, _ = joint_arrays(world, index)
    return point_attributes.through(co, left, right, k)


#: Samples per piece of a curve in the search for where it passes nearest another.
CROSSING_SAMPLES = 32


#: Alternating projections refining that search.
CROSSING_STEPS = 60


def crossing(child_curve, parent_curve) -> tuple[float, np.ndarray, float]:
    """Where ``child_curve`` passes nearest ``parent_curve``: ``(t on the child, the child's
    point there, the distance)``: the nearest pair of dense samples of both, refined by
    projecting from one curve to the other and back until it stays (a crossing converges)."""

    def samples(curve):
        a, b = curve.domain
        n = CROSSING_SAMPLES * max(1, len(np.unique(curve.knots)) - 1) + 1
        t = np.linspace(a, b, n)
        return t, np.asarray(curve.evaluate(t), dtype=float)

    tc, pc = samples(child_curve)
    _, pp = samples(parent_curve)
    best, best_d = 0, np.inf
    for lo in range(0, len(pc), 256):  # bounded memory: 256 × parent samples at a time
        d = np.linalg.norm(pc[lo : lo + 256, None, :] - pp[None, :, :], axis=2).min(axis=1)
        k = int(np.argmin(d))
        if d[k] < best_d:
            best, best_d = lo + k, float(d[k])
    t = float(tc[best])
    here = pc[best]
    for _ in range(CROSSING_STEPS):
        _, _, on_parent = parent_curve.nearest(here)
        t_new, _, back = child_curve.nearest(np.asarray(on_parent, dtype=float))
        back = np.asarray(back, dtype=float)
        if np.linalg.norm(back - here) <= 1e-12 * max(1.0, float(np.abs(here).max())):
            t, here = float(t_new), back
            break
        t, here = float(t_new), back
    return t, here, float(parent_curve.nearest(here)[1])
