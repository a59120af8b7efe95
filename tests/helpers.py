"""Helpers for building Blender curves in tests (foreach_set, no per-point loops)."""

from __future__ import annotations

import math

import bpy
import numpy as np

L, B, T, F = 100.0, 10.0, 6.25, 2.5  # examples/wigley.py: length, beam, draught, freeboard
WIGLEY_HALF_VOLUME = (2 / 9) * L * B * T + (1 / 3) * L * B * F  # to the deck, one half


def _curve_data(name: str, resolution: int):
    """An empty 3D curve data-block."""
    data = bpy.data.curves.new(name, "CURVE")
    data.dimensions = "3D"
    data.resolution_u = resolution
    return data


def _link(name: str, data, matrix, collection):
    """A new object for ``data`` with ``matrix`` (if any), linked to ``collection`` (or the scene)."""
    obj = bpy.data.objects.new(name, data)
    if matrix is not None:
        obj.matrix_world = matrix
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def new_curve(
    name: str,
    kind: str,
    points,
    *,
    order: int = 4,
    endpoint: bool = False,
    bezier: bool = False,
    cyclic: bool = False,
    weights=None,
    resolution: int = 12,
    collection=None,
    matrix=None,
):
    """A curve object with one POLY or NURBS spline through ``points`` (n, 3)."""
    points = np.asarray(points, dtype=np.float64)
    data = _curve_data(name, resolution)
    spline = data.splines.new(kind)
    spline.points.add(len(points) - 1)
    w = np.ones(len(points)) if weights is None else np.asarray(weights, dtype=np.float64)
    spline.points.foreach_set("co", np.column_stack([points, w]).astype(np.float32).ravel())
    spline.order_u = order
    spline.use_endpoint_u = endpoint
    spline.use_bezier_u = bezier
    spline.use_cyclic_u = cyclic
    return _link(name, data, matrix, collection)


def new_bezier(
    name: str, co, left, right, *, cyclic: bool = False, resolution: int = 12, collection=None, matrix=None
):
    """A curve object with one BEZIER spline (points and FREE handles as given)."""
    co = np.asarray(co, dtype=np.float32)
    data = _curve_data(name, resolution)
    spline = data.splines.new("BEZIER")
    bp = spline.bezier_points
    bp.add(len(co) - 1)
    n = len(co)
    bp.foreach_set("handle_left_type", np.full(n, 0, dtype=np.int32))  # HD_FREE
    bp.foreach_set("handle_right_type", np.full(n, 0, dtype=np.int32))
    bp.foreach_set("co", co.ravel())
    bp.foreach_set("handle_left", np.asarray(left, dtype=np.float32).ravel())
    bp.foreach_set("handle_right", np.asarray(right, dtype=np.float32).ravel())
    spline.use_cyclic_u = cyclic
    return _link(name, data, matrix, collection)


def evaluated_polyline(obj) -> np.ndarray:
    """Blender's own evaluated polyline of a curve object, in world coordinates."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(depsgraph)
    mesh = ev.to_mesh()
    try:
        n = len(mesh.vertices)
        buf = np.empty(3 * n, dtype=np.float32)
        mesh.vertices.foreach_get("co", buf)
        local = buf.reshape(n, 3).astype(np.float64)
    finally:
        ev.to_mesh_clear()
    m = np.array(obj.matrix_world, dtype=np.float64)
    return local @ m[:3, :3].T + m[:3, 3]


def evaluated_volume(obj, *, axis: int, level: float) -> float:
    """The volume enclosed by the evaluated mesh of ``obj`` (its modifiers applied) and the
    plane ``x[axis] = level`` together with any planes normal to the other axes that close its
    openings: the divergence theorem with the field ``e_axis · (x[axis] − level)``, whose flux
    through those planes is zero, summed exactly over a fan of triangles per face."""
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    me = evaluated.to_mesh()
    try:
        pos = np.empty(3 * len(me.vertices))
        me.vertices.foreach_get("co", pos)
        pos = pos.reshape(-1, 3)
        total = 0.0
        for poly in me.polygons:
            v = pos[list(poly.vertices)]
            a, b, c = v[0], v[1:-1], v[2:]
            area = 0.5 * np.cross(b - a, c - a)[:, axis]
            centroid = (a[axis] + b[:, axis] + c[:, axis]) / 3.0
            total += float(np.sum((centroid - level) * area))
    finally:
        evaluated.to_mesh_clear()
    return total


def move_point(obj, index: int, dy: float) -> None:
    """Move control point ``index`` of ``obj``'s first spline by ``dy`` along y (a drag)."""
    point = obj.data.splines[0].points[index]
    co = point.co.copy()
    co.y += dy
    point.co = co


def noisy_arc(n=120, r=10.0, sigma=0.01, seed=4):
    """A quarter circle of radius ``r`` as ``n`` points, the interior ones moved by Gaussian
    noise σ in x and y (seeded)."""
    rng = np.random.default_rng(seed)
    a = np.linspace(0.0, math.pi / 2, n)
    pts = np.column_stack([r * np.cos(a), r * np.sin(a), np.zeros(n)])
    pts[1:-1, :2] += rng.normal(0.0, sigma, (n - 2, 2))
    return pts


def wigley_without_keel():
    """The Wigley example with its keel deleted: the stations end on nothing, so the row of
    faces between the keel and the first waterline is missing, a hole along 'waterline 1.042'."""
    import batten.api as api

    coll = api.load_example("wigley_lines.json")
    bpy.data.objects.remove(coll.objects["keel"])
    return coll
