"""Blender curve objects → :class:`batten_native.Curve`, exactly as Blender draws them.

Every spline of a curve object is read with ``foreach_get`` (no per-point Python loops), with
the object's world transform applied:

- POLY splines become degree-1 curves through their points;
- BEZIER splines become piecewise cubic curves through points and handles (corners stay);
- NURBS splines keep their order, weights and knot layout (end-point, Bézier, cyclic), using
  Blender's own knot rules. A NURBS spline that Blender itself cannot evaluate (too few points
  for its Bézier knots) is drawn by Blender as its control polygon, and read the same way.

A curve with one spline is named after its object; the splines of a multi-spline object are
named ``"Object[i]"``.
"""

from __future__ import annotations

import numpy as np
from batten_native import Curve, CurveError

from ..object_names import errors_named_by_object


def _array(collection, attr: str, count: int, width: int) -> np.ndarray:
    buf = np.empty(count * width, dtype=np.float32)
    collection.foreach_get(attr, buf)
    return buf.reshape(count, width).astype(np.float64)


def _world(obj) -> np.ndarray | None:
    """The object's world matrix, or None where it is the identity (most hull curves): their
    coordinates are then read as they are, without a product per spline."""
    matrix = np.array(obj.matrix_world, dtype=np.float64)
    return None if np.array_equal(matrix, _IDENTITY) else matrix


_IDENTITY = np.eye(4)


def _transform(matrix: np.ndarray | None, xyz: np.ndarray) -> np.ndarray:
    # NaN/inf coordinates pass through; the core rejects them with the curve's name.
    if matrix is None:
        return np.ascontiguousarray(xyz)
    with np.errstate(invalid="ignore", over="ignore"):
        return xyz @ matrix[:3, :3].T + matrix[:3, 3]


def _blender_nurbs_valid(n: int, order: int, endpoint: bool, bezier: bool, cyclic: bool) -> bool:
    """Blender's own validity rule for a NURBS spline (curve_nurbs.cc, check_valid_num_and_order)."""
    if n < 2 or n < order:
        return False
    if bezier:
        if not (endpoint or n > order):
            return False
        if cyclic and n % (order - 1) != 0:
            return False
    return True


def role_of(obj) -> str:
    """The batten role of an object ("free" when the add-on's property is absent)."""
    settings = getattr(obj, "batten", None)
    return getattr(settings, "role", "free") or "free"


def read_object(obj) -> list[Curve]:
    """Every spline of the curve object ``obj`` as a Curve in world coordinates.

    Raises CurveError (``curve`` is the object's name; the message names the spline) when it
    is not a curve, has no splines, or a spline is invalid (NaN or infinite coordinates, too
    few points, zero or negative weights).
    """
    if obj.type != "CURVE":
        raise CurveError(f"object '{obj.name}' is a {obj.type.lower()}, not a curve object", obj.name)
    splines = obj.data.splines
    if len(splines) == 0:
        raise CurveError(f"curve '{obj.name}' has no splines", obj.name)
    matrix = _world(obj)
    role = role_of(obj)
    names = [obj.name] if len(splines) == 1 else [f"{obj.name}[{i}]" for i in range(len(splines))]
    with errors_named_by_object(dict.fromkeys(names, obj.name)):
        return [_read_spline(spline, name, role, matrix) for spline, name in zip(splines, names, strict=True)]


def control_points(obj) -> np.ndarray:
    """Every control point (with a Bézier spline's handles) of the curve object ``obj``, in
    world coordinates, (n, 3): the curves lie in their box (NaN and inf pass through)."""
    matrix = _world(obj)
    points = []
    for spline in obj.data.splines:
        if spline.type == "BEZIER":
            pts, n = spline.bezier_points, len(spline.bezier_points)
            points += [_array(pts, attr, n, 3) for attr in ("co", "handle_left", "handle_right")]
        else:
            points.append(_array(spline.points, "co", len(spline.points), 4)[:, :3])
    return _transform(matrix, np.concatenate(points)) if points else np.zeros((0, 3))


def _read_spline(spline, name: str, role: str, matrix: np.ndarray | None) -> Curve:
    cyclic = bool(spline.use_cyclic_u)
    if spline.type == "BEZIER":
        pts = spline.bezier_points
        n = len(pts)
        co = _transform(matrix, _array(pts, "co", n, 3))
        left = _transform(matrix, _array(pts, "handle_left", n, 3))
        right = _transform(matrix, _array(pts, "handle_right", n, 3))
        return Curve.from_bezier(name, co, left, right, cyclic=cyclic, role=role)
    pts = spline.points
    n = len(pts)
    co = _array(pts, "co", n, 4)
    xyz = _transform(matrix, co[:, :3])
    if spline.type == "POLY":
        return Curve.from_poly(name, xyz, cyclic=cyclic, role=role)
    if spline.type != "NURBS":
        raise CurveError(f"curve '{name}': spline type {spline.type} is not supported", name)
    order = int(spline.order_u)
    endpoint, bezier = bool(spline.use_endpoint_u), bool(spline.use_bezier_u)
    if not _blender_nurbs_valid(n, order, endpoint, bezier, cyclic):
        # Blender shows such a spline as its control polygon; so does batten.
        return Curve.from_poly(name, xyz, cyclic=cyclic, role=role)
    points = np.column_stack([xyz, co[:, 3]])
    return Curve.from_nurbs(name, points, order, endpoint=endpoint, bezier=bezier, cyclic=cyclic, role=role)
