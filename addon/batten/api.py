"""batten's scripting API: the calls the panel and operators use, for scripts and headless runs.

Every function takes Blender data (a collection, a list of curve objects, or one object) and
raises :class:`BattenError` (a ``ValueError``) with a message naming the curve and the problem.
A failed call leaves the file as it was: nothing half-written, no source curve changed.

    import batten.api as api
    curves = api.read_curves(bpy.data.collections["Hull"])
    api.export_network(bpy.data.collections["Hull"], "/tmp/hull.json")
    collection = api.load_network("/tmp/hull.json")
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import NamedTuple

import bpy
import numpy as np
from batten_native import (
    DEFAULT_TOLERANCE,
    ROLES,
    BattenError,
    Curve,
    build_surface,
    fair_points,
    fairness,
    network_from_json,
    network_to_json,
)
from batten_native import topology as _topology

from .bridge import curves_in, curves_out, mesh_out, sections_in

__all__ = [
    "BuildResult",
    "build",
    "read_network",
    "DEFAULT_TOLERANCE",
    "ROLES",
    "BattenError",
    "Curve",
    "curvature_comb",
    "curve_objects",
    "export_network",
    "fair_curve",
    "fairness",
    "import_sections",
    "load_network",
    "read_curves",
    "set_role",
    "topology",
]


#: Custom property marking a mesh object as the surface batten built, holding the source's name.
SURFACE_TAG = "batten_surface"


def _source_name(source) -> str:
    if isinstance(source, bpy.types.Collection | bpy.types.Object):
        return source.name
    return "network"


def curve_objects(source) -> list:
    """The objects of ``source``: a collection (with its child collections), an iterable of
    objects, or one object, in a stable order (by name).

    Raises BattenError when there is nothing, or when an object is not a curve (naming it).
    """
    if isinstance(source, bpy.types.Collection):
        objects = list(source.all_objects)
        where = f"collection '{source.name}'"
    elif isinstance(source, bpy.types.Object):
        objects = [source]
        where = f"object '{source.name}'"
    elif isinstance(source, Iterable) and not isinstance(source, str | bytes):
        objects = list(source)
        where = "the given objects"
    else:
        raise BattenError(
            f"expected a collection, a curve object or a list of them, got {type(source).__name__}"
        )
    # The hull surface batten built from these curves may sit beside them: it is output, not input.
    objects = [o for o in objects if not (isinstance(o, bpy.types.Object) and o.get(SURFACE_TAG))]
    if not objects:
        raise BattenError(f"{where} holds no curves")
    for obj in objects:
        if not isinstance(obj, bpy.types.Object):
            raise BattenError(f"{where}: {obj!r} is not a Blender object")
        if obj.type != "CURVE":
            raise BattenError(f"{where}: object '{obj.name}' is a {obj.type.lower()}, not a curve object")
    return sorted(objects, key=lambda o: o.name)


def read_curves(source) -> list[Curve]:
    """Every spline of the curve objects in ``source`` as :class:`Curve` (world coordinates,
    roles from the objects). See :mod:`batten.bridge.curves_in` for how each spline type is read.
    """
    curves: list[Curve] = []
    for obj in curve_objects(source):
        curves.extend(curves_in.read_object(obj))
    return curves


def _write_atomically(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def export_network(source, path, *, name: str | None = None, tolerance: float = DEFAULT_TOLERANCE) -> Path:
    """Write the curves of ``source`` to ``path`` as a batten network (versioned JSON).

    Curves shorter than ``tolerance`` are refused (zero-length curve). The file is written
    whole or not at all. Returns the path.
    """
    from batten_native import check_lengths

    curves = read_curves(source)
    check_lengths(curves, tolerance)
    text = network_to_json(name if name is not None else _source_name(source), curves)
    path = Path(path)
    _write_atomically(path, text)
    return path


def read_network(path) -> tuple[str, list[Curve]]:
    """The network file at ``path`` as ``(name, curves)``; BattenError if it cannot be read."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise BattenError(f"network file '{path}': {e.strerror or e}") from None
    try:
        return network_from_json(text)
    except BattenError as e:
        raise BattenError(f"network file '{path}': {e}") from None


def load_network(path, *, collection=None, resolution: int = 16):
    """Draw the network file at ``path`` as Blender curve objects in a new collection (named
    after the network, or ``collection`` if a name is given) linked to the scene.

    The file is read and checked whole before anything is created; if drawing fails midway,
    everything created is removed again. Returns the collection.
    """
    name, curves = read_network(path)
    coll_name = collection if isinstance(collection, str) else (name or Path(path).stem)
    return _draw_collection(coll_name, curves, resolution=resolution)


def _draw_collection(name: str, curves: list[Curve], *, resolution: int = 16):
    """Draw ``curves`` as curve objects in a new collection ``name`` linked to the scene:
    all of them, or (if drawing fails midway) none, with everything created removed again."""
    coll = bpy.data.collections.new(name)
    created = []
    try:
        for curve in curves:
            created.append(curves_out.new_curve_object(curve, coll, resolution=resolution))
        bpy.context.scene.collection.children.link(coll)
    except BaseException:
        for obj in created:
            data = obj.data
            bpy.data.objects.remove(obj)
            bpy.data.curves.remove(data)
        bpy.data.collections.remove(coll)
        raise
    return coll


def set_role(objects, role: str) -> None:
    """Set the batten role (one of :data:`ROLES`) of each curve object in ``objects``."""
    if role not in ROLES:
        raise BattenError(f"unknown role '{role}' (one of {', '.join(ROLES)})")
    for obj in curve_objects(objects):
        obj.batten.role = role


#: Samples per knot span when a drawn (non-polyline) curve is refitted.
FAIR_SAMPLES_PER_SPAN = 12
#: At least this many samples for a drawn curve.
FAIR_MIN_SAMPLES = 60


def _fit_data(curve: Curve) -> tuple[np.ndarray, list[int]]:
    """The points to fair a curve through, and the indices of its corners among them.

    A polyline's vertices are the data (imported or digitised points). A drawn curve is
    sampled: each smooth piece between its corners evenly in parameter, the corners exactly.
    """
    if curve.degree == 1:
        return curve.control_points, []
    a, b = curve.domain
    knots = np.unique(curve.knots)
    spans = int(np.count_nonzero((knots[:-1] >= a) & (knots[1:] <= b)))
    breaks = [a, *curve.corners(), b]
    total = max(FAIR_MIN_SAMPLES, FAIR_SAMPLES_PER_SPAN * spans)
    params, corners = [a], []
    for lo, hi in zip(breaks[:-1], breaks[1:], strict=True):
        n = max(4, int(round(total * (hi - lo) / (b - a))))
        params.extend(np.linspace(lo, hi, n + 1)[1:])
        corners.append(len(params) - 1)
    return curve.evaluate(np.asarray(params)), corners[:-1]


def fair_curve(
    obj,
    *,
    tolerance: float | None = 1e-3,
    noise: float | None = None,
    degree: int = 3,
    corner_angle_deg: float | None = 45.0,
) -> list[dict]:
    """Refit every spline of the curve object ``obj`` in place as a fair NURBS spline
    (Dierckx's smoothing spline, H-rep paper §4) and return one report per spline.

    The data are a polyline's points, or samples of a drawn curve (its corners kept). Give a
    ``tolerance`` (largest deviation, m) or a ``noise`` level σ (m). End points are kept
    exactly, corners stay sharp (given ones, and turns sharper than ``corner_angle_deg`` for
    polylines; None detects none). The object, its data-block, materials and modifiers stay;
    on any error nothing changes. Report keys: control_points, knots, interior_knots,
    max_deviation, rms_deviation, inflections, curvature_extrema, fairness_energy (∫κ² ds),
    max_curvature, corners, dropped_duplicates, pieces.
    """
    if noise is not None:
        tolerance = None
    curves = curves_in.read_object(obj)
    fitted, reports = [], []
    for curve in curves:
        points, corners = _fit_data(curve)
        new, report = fair_points(
            curve.name,
            points,
            degree=degree,
            tolerance=tolerance,
            noise=noise,
            corners=corners,
            corner_angle_deg=corner_angle_deg if curve.degree == 1 else None,
            role=curve.role,
        )
        report["curve"] = curve.name
        fitted.append(new)
        reports.append(report)
    curves_out.replace_splines(obj, fitted)
    return reports


def import_sections(
    path,
    *,
    tolerance: float = 5e-3,
    degree: int = 3,
    corner_angle_deg: float | None = 45.0,
    model_tolerance: float = 1e-3,
    collection: str | None = None,
):
    """Read a point-list file (the neutral section JSON of ``shared/hulls``, or a CSV offsets
    table ``name, x, y, z``), fair every curve within ``tolerance`` (m) keeping its end points
    and corners, and draw the curves as NURBS curve objects in a new collection, with roles
    from the curve kinds. All curves are fitted before anything is created.

    Returns ``(collection, reports)``, one report per curve (see :func:`fair_curve`).
    """
    name, sections = sections_in.read_sections(path)
    if not sections:
        raise BattenError(f"section file '{path}': no curves")
    fitted, reports = [], []
    for sec in sections:
        curve, report = fair_points(
            sec.name,
            sec.points,
            degree=degree,
            tolerance=tolerance,
            corner_angle_deg=corner_angle_deg,
            model_tolerance=model_tolerance,
            role=sec.role,
        )
        report["curve"] = sec.name
        report["points"] = len(sec.points)
        fitted.append(curve)
        reports.append(report)
    return _draw_collection(collection or name, fitted), reports


def curvature_comb(obj, *, samples: int = 200, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """The curvature comb (porcupine) of every spline of ``obj``: ``(bases, tips)`` arrays of
    shape (n, 3) in world coordinates. Each tooth stands on the curve, away from the centre
    of curvature, with length ``scale`` × κ (1/m)."""
    bases, tips = [], []
    for curve in curves_in.read_object(obj):
        t = np.linspace(*curve.domain, max(2, samples))
        points, kappa = curve.curvature(t)
        bases.append(points)
        tips.append(points - scale * kappa)
    return np.concatenate(bases), np.concatenate(tips)


def topology(source, *, tolerance: float = DEFAULT_TOLERANCE) -> dict:
    """The topology of the hull network in ``source`` (H-rep paper §3.1, §5.2): where the
    curves meet (nodes), the curve stretches between nodes (edges), the faces found
    automatically with their true corner counts and sides, the open boundary loops, and
    diagnostics naming the curves and locations (dangling ends, near misses, curves meeting
    nothing, regions that could not be closed, duplicates, overlaps, self-intersections).

    Returns a dict: ``nodes``, ``edges``, ``node_positions``, ``node_kinds`` (per node:
    ``crossing``, ``end_to_end``, ``end_on_curve`` — a curve ending on another where every face
    has a corner —, ``t_joint`` — a curve ending on another that runs on as one side of a face
    —, ``free_end``), ``faces`` (each ``curves``, ``corners``, ``sides``, ``edges``),
    ``faces_by_corners``, ``boundary_loops``, ``diagnostics`` (each ``kind``, ``message``,
    ``curves``, ``location``).
    """
    return _topology(read_curves(source), tolerance)


class BuildResult(NamedTuple):
    """What :func:`build` returns: the surface mesh object and the report dict."""

    object: object
    report: dict


def _surface_object(name: str):
    for obj in bpy.data.objects:
        if obj.type == "MESH" and obj.get(SURFACE_TAG) == name:
            return obj
    return None


def build(
    source, *, tolerance: float = DEFAULT_TOLERANCE, resolution: int = 8, mirror: bool = True
) -> BuildResult:
    """Build the smooth hull surface of the curve network in ``source`` (H-rep paper): nodes
    where curves meet, faces found automatically, one Gregory (4 sides) or Charrot–Gregory
    (3, 5, 6 … sides) patch per face with cross-boundary tangents from the crossing curves, G1
    across ordinary curves and G0 across knuckles, tessellated with ``resolution`` segments per
    side into one watertight mesh.

    The mesh object (``"<source> surface"``) is updated in place on every rebuild: its name,
    materials and modifiers survive. ``mirror`` adds a Mirror modifier about y = 0. Faces
    carry an integer attribute ``patch`` (the network face they belong to). A build that fails
    raises BattenError and leaves the previous mesh untouched.

    ``report`` holds: nodes, edges, faces, faces_by_sides, open_edges, max_gap,
    max_normal_angle_deg, crease_angles_deg (per knuckle curve: name, min, max), knuckle_edges
    (each ``curve``, ``source`` — ``"role"`` or ``"auto"``, found at corners of crossing
    curves —, ``corner_curves``, ``crease_deg`` (min, max) or None, ``points`` along the edge),
    volume (between the drawn half surface and the centreplane), displacement_volume (both
    halves when mirrored), mesh_vertices, mesh_faces, warnings.
    """
    curves = read_curves(source)
    name = _source_name(source)
    (positions, corners, sizes, patch), report = build_surface(curves, tolerance, resolution)
    obj = mesh_out.write_surface(
        f"{name} surface", positions, corners, sizes, patch, obj=_surface_object(name), mirror=mirror
    )
    obj[SURFACE_TAG] = name
    report["mirror"] = mirror
    report["displacement_volume"] = report["volume"] * (2.0 if mirror else 1.0)
    # Messages name curves as 'name': keep the names per warning, so the panel can show them.
    report["warning_curves"] = {
        w: sorted({c.name.split("[")[0] for c in curves if f"'{c.name}'" in w}) for w in report["warnings"]
    }
    return BuildResult(obj, report)
