"""batten curves → Blender curve objects that Blender draws as exactly the same shape.

A curve whose knots are an end-point or uniform layout keeps its control points (so it stays
as editable as it was drawn); any other knot vector is written as an end-point + Bézier NURBS
spline of its Bézier pieces, which Blender evaluates as exactly the same curve. Degree-1 curves
become POLY splines.
"""

from __future__ import annotations

import bpy
import numpy as np
from batten_native import Curve, CurveError

#: Blender's legacy curves have orders 2..6.
MAX_BLENDER_DEGREE = 5


#: Blender stores curve points as float32: larger coordinates would be drawn as inf.
FLOAT32_MAX = float(np.finfo(np.float32).max)


def _spline_data(curve: Curve) -> tuple[str, np.ndarray, dict]:
    kind, points, flags = _spline_layout(curve)
    largest = float(np.abs(points).max(initial=0.0))
    if largest > FLOAT32_MAX:
        raise CurveError(
            f"curve '{curve.name}': a control point coordinate or weight ({largest:.3e}) is beyond "
            f"what Blender stores (float32, {FLOAT32_MAX:.3e})",
            curve.name,
        )
    return kind, points, flags


def _spline_layout(curve: Curve) -> tuple[str, np.ndarray, dict]:
    degree = curve.degree
    if degree > MAX_BLENDER_DEGREE:
        raise CurveError(
            f"curve '{curve.name}': degree {degree} is above the largest Blender draws "
            f"({MAX_BLENDER_DEGREE})",
            curve.name,
        )
    layout = curve.matching_layout()
    weights = curve.weights
    if layout is not None:
        pts = curve.control_points
        w = np.ones(len(pts)) if weights is None else weights
        points = np.column_stack([pts, w])
        if degree == 1 and layout == "endpoint" and weights is None:
            return "POLY", points, {}
        return "NURBS", points, {"order_u": degree + 1, "use_endpoint_u": layout == "endpoint"}
    points = curve.bezier_control_points()
    return "NURBS", points, {"order_u": degree + 1, "use_endpoint_u": True, "use_bezier_u": True}


def write_spline(data, spec: tuple[str, np.ndarray, dict], to_local: np.ndarray | None = None):
    """Add one spline to the curve data-block ``data`` from ``spec`` (what ``_spline_data``
    returns for a curve); ``to_local`` (4×4) maps batten's world coordinates into the
    object's space (identity when None)."""
    kind, points, flags = spec
    if to_local is not None:
        points = points.copy()
        points[:, :3] = points[:, :3] @ to_local[:3, :3].T + to_local[:3, 3]
    spline = data.splines.new(kind)
    spline.points.add(len(points) - 1)
    spline.points.foreach_set("co", points.astype(np.float32).ravel())
    for key, value in flags.items():
        setattr(spline, key, value)
    return spline


def new_curve_object(curve: Curve, collection, *, resolution: int = 16):
    """A new curve object drawing ``curve`` (world coordinates, identity transform), linked to
    ``collection``, with the curve's role set. Returns the object."""
    obj = new_curves_object(curve.name, [curve], collection, resolution=resolution)
    if hasattr(obj, "batten"):
        obj.batten.role = curve.role
    return obj


def new_curves_object(name: str, curves: list[Curve], collection, *, resolution: int = 16):
    """A new curve object ``name`` with one spline per curve of ``curves`` (world coordinates,
    identity transform), linked to ``collection``. Returns the object."""
    specs = [_spline_data(c) for c in curves]  # refuses what Blender cannot draw before anything is created
    data = bpy.data.curves.new(name, "CURVE")
    try:
        data.dimensions = "3D"
        data.resolution_u = resolution
        for spec in specs:
            write_spline(data, spec)
        obj = bpy.data.objects.new(name, data)
    except Exception:
        bpy.data.curves.remove(data)
        raise
    collection.objects.link(obj)
    return obj


def _write_splines(obj, specs: list) -> None:
    """Replace every spline of the curve object ``obj`` by ``specs`` (world coordinates)."""
    to_local = np.array(obj.matrix_world.inverted(), dtype=np.float64)
    data = obj.data
    data.splines.clear()
    for spec in specs:
        write_spline(data, spec, to_local)


def _restore(data, backup) -> None:
    """Put the copy ``backup`` of the curve data-block ``data`` back in its place, for every
    user, under its name."""
    name = data.name
    data.user_remap(backup)
    bpy.data.curves.remove(data)
    backup.name = name


def replace_splines_of(replacements: list[tuple[object, list[Curve]]]) -> None:
    """Replace every spline of each curve object by its curves (world coordinates), keeping the
    objects, their data-blocks, materials and modifiers: all of them or none. Everything
    Blender cannot draw is refused before anything is changed; if writing fails midway, every
    object written so far gets its curve data back as it was."""
    specs = [(obj, [_spline_data(curve) for curve in curves]) for obj, curves in replacements]
    backups = {}  # data-block pointer → (data-block, untouched copy)
    try:
        for obj, obj_specs in specs:
            key = obj.data.as_pointer()
            if key not in backups:
                backups[key] = (obj.data, obj.data.copy())
            _write_splines(obj, obj_specs)
    except BaseException:
        for data, backup in backups.values():
            _restore(data, backup)
        raise
    for _, backup in backups.values():
        bpy.data.curves.remove(backup)
