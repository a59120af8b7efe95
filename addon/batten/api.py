"""batten's scripting API: the calls the panel and operators use, for scripts and headless runs.

Every function takes Blender data (a collection, a list of curve objects, or one object) and
raises :class:`BattenError` (a ``ValueError``) with a message naming the curve and the problem,
as one of its kinds a script can catch: :class:`CurveError` (``.curve`` is the curve object's
name; :class:`FairError` when fairing fails), :class:`NetworkFileError` (a network or section
file that cannot be read or written), :class:`NoSurfaceError`, :class:`InvalidArgumentError`
(a bad argument value or source), :class:`Cancelled` (long work stopped by its ``progress``
callback) and :class:`InternalError` (a bug in batten's core). A failed or cancelled call
leaves the file as it was: nothing half-written, no source curve changed.

The long calls (:data:`LONG_CALLS`) take ``progress=``, a callable ``progress(label, done,
total)`` called after each step; returning ``False`` stops the work and raises
:class:`Cancelled` (see :mod:`batten.progress`). :func:`start` gives such a call as a job to
run step by step, as the modal operators do.

    import batten.api as api
    curves = api.read_curves(bpy.data.collections["Hull"])
    api.export_network(bpy.data.collections["Hull"], "/tmp/hull.json")
    collection = api.load_network("/tmp/hull.json")
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable
from pathlib import Path
from typing import NamedTuple

import bpy
import numpy as np
from batten_native import (
    DEFAULT_CORNER_ANGLE_DEG,
    DEFAULT_CUT_TOLERANCE,
    DEFAULT_EXPORT_TOLERANCE,
    DEFAULT_FAIR_DEGREE,
    DEFAULT_FAIR_TOLERANCE,
    DEFAULT_RESOLUTION,
    DEFAULT_SECTION_MODEL_TOLERANCE,
    DEFAULT_SECTION_TOLERANCE,
    DEFAULT_SURFACE_FAIR_TOLERANCE,
    DEFAULT_TOLERANCE,
    ROLES,
    SEA_WATER_DENSITY,
    SECTION_CAPTURE_FACTOR,
    BattenError,
    Cancelled,
    Curve,
    CurveError,
    ExportError,
    FairError,
    HydrostaticsError,
    InternalError,
    InvalidArgumentError,
    MeshHull,
    NetworkFileError,
    NoSurfaceError,
    build_hull_model,
    check_lengths,
    chines_from_knuckles,
    fair_points,
    fair_sections,
    fairness,
    network_from_json,
    network_to_json,
    nodes_from_data,
    snap_to_nodes,
    transform_network,
)
from batten_native import form_topology as _form_topology
from batten_native import topology as _topology
from batten_native import (
    transform_hydrostatic as _transform_hydrostatic,
)

from . import (
    bezier_form,
    cad_export,
    closed_mesh,
    curvature_map,
    flat_of_bottom,
    form_compare,
    form_stack,
    hierarchy,
    hull_models,
    point_attributes,
    sections_draw,
    spline_joints,
)
from .atomic_write import write_atomically
from .boundary_samples import (
    along_boundary,
    boundary_points,
    is_stray,
    section_anchors,
    thinned,
    without_end_stretches_along,
)
from .bridge import curves_in, curves_out, mesh_out, sections_in
from .file_text import file_path, read_text
from .fit_data import fit_data
from .object_names import blender_name, errors_named_by_object, objects_of, with_objects
from .offsets import table_text
from .progress import Job, ProgressCallback, Step, deferred, in_worker, run
from .sections import Section, all_sections, finite_offsets, planes
from .sections import cut as _cut_sections

__all__ = [
    "BuildResult",
    "DEFAULT_CUT_TOLERANCE",
    "Section",
    "export_sections",
    "offsets_table",
    "refresh_sections",
    "sections",
    "HydrostaticsError",
    "SEA_WATER_DENSITY",
    "curves_of_form",
    "float_to",
    "hydrostatics",
    "sectional_areas",
    "build",
    "settle",
    "read_network",
    "read_network_planes",
    "DEFAULT_TOLERANCE",
    "ROLES",
    "BattenError",
    "Cancelled",
    "Job",
    "start",
    "CurveError",
    "FairError",
    "InternalError",
    "InvalidArgumentError",
    "NetworkFileError",
    "NoSurfaceError",
    "Curve",
    "curvature_comb",
    "clear_curvature",
    "show_curvature",
    "surface_curvature",
    "curve_objects",
    "example_files",
    "DEFAULT_EXPORT_TOLERANCE",
    "ExportError",
    "closed_surface",
    "export_3dm",
    "export_iges",
    "export_network",
    "export_step",
    "fair_curve",
    "fair_curves",
    "fair_surface",
    "DEFAULT_SURFACE_FAIR_TOLERANCE",
    "SURFACE_FAIR_FIXED_ROLES",
    "fairness",
    "import_sections",
    "load_example",
    "load_network",
    "read_curves",
    "set_role",
    "topology",
    "TransformResult",
    "abandon",
    "commit",
    "form_topology",
    "keep",
    "transform",
    "transform_stack",
    "compare",
    "attach",
    "detach",
    "attachments",
    "update_hierarchy",
    "set_point_attribute",
    "clear_point_attributes",
    "point_attributes_of",
    "set_curve_attribute",
    "curve_attributes",
    "to_bezier",
    "set_plane",
    "clear_plane",
    "held_planes",
]


def start(function, *args, **kwargs) -> Job:
    """The long call ``function(*args, **kwargs)`` of this module (:func:`fair_curves`,
    :func:`fair_curve`, :func:`fair_surface`, :func:`import_sections`, :func:`export_iges`,
    :func:`export_step`, :func:`export_3dm`, :func:`lines_plan`, :func:`offsets_table`,
    :func:`export_sections`; ``progress=`` as they take it) as a :class:`batten.progress.Job`
    that runs step by step: ``job.step()`` until it returns True, then ``job.result`` (what the
    call returns); ``job.cancel()`` between steps stops it with nothing changed. Only argument
    checks run before the first step. Batten's modal operators run their work this way; the
    call itself runs it to its end. InvalidArgumentError for another function."""
    name = getattr(function, "__name__", "")
    if name not in LONG_CALLS or globals().get(name) is not function:
        calls = ", ".join(LONG_CALLS)
        raise InvalidArgumentError(f"start: {function!r} is no long call of batten.api ({calls})")
    job = deferred(function, *args, **kwargs)
    if job is None:
        raise InternalError(f"start: {name} ran no job")
    return job


#: The calls :func:`start` runs step by step.
LONG_CALLS = (
    "fair_curves",
    "fair_curve",
    "fair_surface",
    "import_sections",
    "export_iges",
    "export_step",
    "export_3dm",
    "lines_plan",
    "offsets_table",
    "export_sections",
)


#: Display resolution (segments per span) of the curve objects batten draws.
CURVE_RESOLUTION = 16


#: Custom property marking a mesh object as the surface batten built, holding the source's name.
SURFACE_TAG = "batten_surface"


def _source_name(source) -> str:
    if isinstance(source, bpy.types.Collection | bpy.types.Object):
        return source.name
    return "network"


def _ensure_registered() -> None:
    """Register the add-on (:func:`batten.register`) when nothing has yet: a headless script
    that imports ``batten.api`` without it would read every curve's role as "free" (a hull
    without its keel, deck, chines or flat of bottom) and could set none. Registering twice is
    harmless, so this only looks for the curves' role property."""
    if not hasattr(bpy.types.Object, "batten"):
        from . import register

        register()


def curve_objects(source) -> list:
    """The objects of ``source``: a collection (with its child collections), an iterable of
    objects, or one object, in a stable order (by name). Registers the add-on first if a
    headless script has not (:func:`_ensure_registered`), so the objects' roles are there.

    Raises InvalidArgumentError when ``source`` is none of these or holds nothing, and
    CurveError (naming the object) when an object is not a curve.
    """
    _ensure_registered()
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
        raise InvalidArgumentError(
            f"expected a collection, a curve object or a list of them, got {type(source).__name__}"
        )
    # The hull surface batten built from these curves may sit beside them: it is output, not input.
    # So are the sections batten drew (in a child collection).
    objects = [
        o
        for o in objects
        if not (isinstance(o, bpy.types.Object) and (o.get(SURFACE_TAG) or o.get(sections_draw.SECTION_TAG)))
    ]
    if not objects:
        raise InvalidArgumentError(f"{where} holds no curves")
    for obj in objects:
        if not isinstance(obj, bpy.types.Object):
            raise InvalidArgumentError(f"{where}: {obj!r} is not a Blender object")
        if obj.type != "CURVE":
            raise CurveError(
                f"{where}: object '{obj.name}' is a {obj.type.lower()}, not a curve object", obj.name
            )
    return sorted(objects, key=lambda o: o.name)


def read_curves(source) -> list[Curve]:
    """Every spline of the curve objects in ``source`` as :class:`Curve` (world coordinates,
    roles from the objects). See :mod:`batten.bridge.curves_in` for how each spline type is read.
    """
    return _read_source(source).curves


class _SourceCurves(NamedTuple):
    """The curves of a source, and the name of the object each one came from."""

    curves: list[Curve]
    object_of: dict[str, str]


def _read_source(source) -> _SourceCurves:
    curves: list[Curve] = []
    object_of: dict[str, str] = {}
    for obj in curve_objects(source):
        read = curves_in.read_object(obj)
        curves.extend(read)
        object_of.update((c.name, obj.name) for c in read)
    return _SourceCurves(curves, object_of)


def export_network(source, path, *, name: str | None = None, tolerance: float = DEFAULT_TOLERANCE) -> Path:
    """Write the curves of ``source`` to ``path`` as a batten network (versioned JSON), with
    the planes its surface is tangent to (:func:`tangent_planes`), so that
    :func:`load_network` gives back a collection that builds the same surface.

    Curves shorter than ``tolerance`` are refused (zero-length curve). The file is written
    whole or not at all (NetworkFileError naming it when it cannot be). Returns the path.
    """
    curves, object_of = _read_source(source)
    with errors_named_by_object(object_of):
        check_lengths(curves, tolerance)
    text = network_to_json(name if name is not None else _source_name(source), curves, tangent_planes(source))
    path = file_path(path, "network file")
    try:
        return write_atomically(path, text)
    except OSError as e:
        raise NetworkFileError(f"network file '{path}': {e.strerror or e}") from e


def read_network(path) -> tuple[str, list[Curve]]:
    """The network file at ``path`` as ``(name, curves)``; NetworkFileError naming the file
    (and the problem) if it cannot be read or is not a valid network. Its tangent planes:
    :func:`read_network_planes`."""
    name, curves, _planes = _read_network_file(path)
    return name, curves


def read_network_planes(path) -> list[list[float]]:
    """The tangent planes (see :data:`TANGENT_PLANES_PROPERTY`) of the network file at
    ``path``, each ``[nx, ny, nz, offset]``; ``[]`` for a file without any. NetworkFileError
    as :func:`read_network`."""
    return _read_network_file(path)[2]


def _read_network_file(path) -> tuple[str, list[Curve], list[list[float]]]:
    """The network file at ``path`` as ``(name, curves, tangent planes)`` (see
    :func:`read_network`)."""
    path = file_path(path, "network file")
    text = read_text(path, "network file")
    try:
        name, curves, planes = network_from_json(text)
    except BattenError as e:
        raise NetworkFileError(f"network file '{path}': {e}") from e
    return name, curves, planes


def load_network(path, *, collection=None, resolution: int = CURVE_RESOLUTION):
    """Draw the network file at ``path`` as Blender curve objects in a new collection (named
    after the network, or ``collection`` if a name is given) linked to the scene.

    The file is read and checked whole before anything is created; if drawing fails midway,
    everything created is removed again. The file's tangent planes, if it has any, are the
    collection's :data:`TANGENT_PLANES_PROPERTY`. Returns the collection.
    """
    name, curves, planes = _read_network_file(path)
    coll_name = collection if isinstance(collection, str) else (name or file_path(path, "network file").stem)
    coll = _draw_collection(coll_name, curves, resolution=resolution)
    if planes:
        coll[TANGENT_PLANES_PROPERTY] = planes
    return coll


def _draw_collection(name: str, curves: list[Curve], *, resolution: int = CURVE_RESOLUTION):
    """Draw ``curves`` as curve objects in a new collection ``name`` linked to the scene:
    all of them, or (if drawing fails midway) none, with everything created removed again.
    A name Blender cannot store (a file name's undecodable bytes) is drawn with U+FFFD.
    Registers the add-on first if a headless script has not, so the roles are drawn too."""
    _ensure_registered()
    coll = bpy.data.collections.new(blender_name(name))
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
    """Set the batten role (one of :data:`ROLES`) of each curve object in ``objects``
    (InvalidArgumentError for any other role)."""
    if role not in ROLES:
        raise InvalidArgumentError(f"unknown role '{role}' (one of {', '.join(ROLES)})")
    for obj in curve_objects(objects):
        obj.batten.role = role


def _curve_object(obj, what: str):
    """The curve object ``obj`` (an object or its name); InvalidArgumentError otherwise."""
    if isinstance(obj, str):
        found = bpy.data.objects.get(obj)
        if found is None:
            raise InvalidArgumentError(f"{what}: no object '{obj}'")
        obj = found
    if not isinstance(obj, bpy.types.Object):
        raise InvalidArgumentError(f"{what} needs a curve object, got {type(obj).__name__}")
    if obj.type != "CURVE":
        raise CurveError(f"object '{obj.name}' is a {obj.type.lower()}, not a curve object", obj.name)
    return obj


def _curve_objects_of(objects, what: str) -> list:
    """The curve objects ``objects`` names: one object or name, or an iterable of them."""
    if isinstance(objects, str | bpy.types.Object):
        objects = [objects]
    try:
        objects = list(objects)
    except TypeError:
        raise InvalidArgumentError(f"{what} needs curve objects, got {type(objects).__name__}") from None
    if not objects:
        raise InvalidArgumentError(f"{what}: no curve")
    return [_curve_object(o, what) for o in objects]


def attach(
    children,
    parent,
    *,
    end: str = "nearest",
    point: int | str | None = None,
    tolerance: float = hierarchy.ATTACH_DISTANCE,
) -> list[dict]:
    """Attach an end of each curve object of ``children`` (one object or name, or several) to
    the curve object ``parent`` (seed 002 §5: the curve network hierarchy): the end (``start``,
    ``end``, or ``nearest``: the one nearer the parent) references the parent's point nearest
    to it, which must be within ``tolerance`` m. From then on the end follows that point of the
    parent, and the child's free control points follow by the elastic rule
    (:func:`update_hierarchy`; Build and Live do it on every change). The children are updated
    at once, so their ends lie on the parent; but where a child's curve already meets the
    parent there (within the default model tolerance) and only its end or point lies a little
    aside, that offset is kept and nothing moves (moving it would move the child's other
    meetings off their curves).

    With ``point`` a point the child passes through is attached in place of an end: its index
    among the spline's points (a Bézier spline's points, a cubic Bézier-knot NURBS spline's
    every third control point), or ``"nearest"``: the one nearest the parent (a station where it
    crosses a chine). The elastic rule then runs between the attached points and the ends, and
    the parent's curve attributes act on the point (:func:`set_curve_attribute`).

    Returns the attachments, one ``{"child", "end" or "point", "parent", "t"[, "offset"]}`` per
    child (``t``: the parameter on the parent). All children are attached or none: CurveError naming
    the child when it is not one spline, is the parent or one of the parent's ancestors, its end
    or point is too far, or its spline does not pass through its points; InvalidArgumentError
    for an unknown end or point."""
    children = _curve_objects_of(children, "attach")
    parent = _curve_object(parent, "attach")
    if not (isinstance(tolerance, int | float) and math.isfinite(tolerance) and tolerance > 0):
        raise InvalidArgumentError(f"attach: tolerance {tolerance!r} must be a positive distance (m)")
    before = {c.name: hierarchy.attachments_of(c) for c in children}
    made = []
    try:
        for child in children:
            made.append(
                {
                    "child": child.name,
                    **hierarchy.attach(child, parent, end, float(tolerance), point, DEFAULT_TOLERANCE),
                }
            )
        hierarchy.update(_with_descendants(children))
    except BaseException:
        for child, a in zip(children, made, strict=False):
            # Its new attachment off, the one it replaced back; a point a crossing gave the
            # child stays (its shape is the same, its later points already renumbered).
            kept = [k for k in hierarchy.attachments_of(child) if hierarchy.anchor(k) != hierarchy.anchor(a)]
            former = [
                k for k in before[child.name] if "end" in k and hierarchy.anchor(k) == hierarchy.anchor(a)
            ]
            hierarchy.store(child, kept + former)
        raise
    return made


def _with_descendants(objects) -> list:
    """The curve objects ``objects`` and every curve object that references one of them,
    directly or not."""
    curves = [o for o in bpy.data.objects if o.type == "CURVE"]
    parents = hierarchy.graph(curves)
    found = {o.name for o in objects}
    frontier = set(found)
    while frontier:
        frontier = {child for child, ps in parents.items() if ps & frontier} - found
        found |= frontier
    return [bpy.data.objects[name] for name in sorted(found)]


def detach(child, *, end: str | None = None, point: int | None = None) -> int:
    """Detach the ends and attached points of the curve object ``child`` (only ``end``,
    ``start`` or ``end``, or only the point ``point``, when given) from their parents; the
    curve stays where it is. Returns how many were detached."""
    child = _curve_object(child, "detach")
    if end is not None and end not in hierarchy.ENDS:
        raise InvalidArgumentError(f"end '{end}' is none of start, end")
    if end is not None and point is not None:
        raise InvalidArgumentError("detach: give an end or a point, not both")
    if end is None and point is None:
        return _take_all(child, hierarchy.attachments_of, hierarchy.store)
    before = hierarchy.attachments_of(child)
    target = end if end is not None else f"point {point}"
    kept = [a for a in before if hierarchy.anchor(a) != target]
    hierarchy.store(child, kept)
    return len(before) - len(kept)


def _take_all(obj, read, store) -> int:
    """Take every item ``read(obj)`` gives off ``obj`` with ``store(obj, [])``, a property edited
    by hand that no longer reads included (counted as none). Returns how many there were."""
    try:
        count = len(read(obj))
    except CurveError:
        count = 0
    store(obj, [])
    return count


def attachments(source) -> list[dict]:
    """The attachments of the curve objects of ``source`` (as :func:`curve_objects` takes it),
    in hierarchy order (every parent's before its children's): each ``{"child", "end" (or
    "point"), "parent", "t"}``. CurveError naming the curves when they reference each other in a cycle."""
    objects = curve_objects(source)
    by_name = {o.name: o for o in objects}
    return [
        {"child": name, **a}
        for name in hierarchy.order(objects)
        for a in hierarchy.attachments_of(by_name[name])
    ]


#: The planes :func:`set_plane` names: the axis each is square to.
PLANE_AXES = {"x": 0, "y": 1, "z": 2}


def set_plane(objects, plane="fit", *, tolerance: float = hierarchy.ATTACH_DISTANCE) -> list[dict]:
    """Hold each curve object of ``objects`` (one object or name, or several) in a plane: its
    surface attribute (seed 002 §5). ``plane``: ``"x"``, ``"y"`` or ``"z"`` (the plane square to
    that axis through the curve's control points: a station or midship section, the
    centreplane or a flat of side, a waterplane or the flat of bottom), ``"fit"`` (the plane the
    control points lie closest to, by least squares) or ``(normal, offset)`` (the plane
    ``normal · p = offset``). From then on the curve is kept in it: Build and Live move its
    control points into the plane after its ends followed their parents
    (:func:`update_hierarchy`). Each curve is moved into its plane at once.

    Returns one ``{"curve", "normal", "offset"}`` per curve. All curves or none: CurveError
    naming the curve when it is not one spline or lies farther than ``tolerance`` m from the
    plane; InvalidArgumentError for an unknown plane."""
    curves = _curve_objects_of(objects, "set_plane")
    if not (isinstance(tolerance, int | float) and math.isfinite(tolerance) and tolerance > 0):
        raise InvalidArgumentError(f"set_plane: tolerance {tolerance!r} must be a positive distance (m)")
    planes = []
    for obj in curves:
        points = spline_joints.control_points_world(obj)
        if isinstance(plane, str) and plane in PLANE_AXES:
            normal = np.eye(3)[PLANE_AXES[plane]]
            offset = float(points[:, PLANE_AXES[plane]].mean())
        elif plane == "fit":
            centre = points.mean(axis=0)
            normal = np.linalg.svd(points - centre)[2][-1]
            offset = float(normal @ centre)
        elif isinstance(plane, tuple | list) and len(plane) == 2:
            normal = np.asarray(plane[0], dtype=float).reshape(-1)
            length = float(np.linalg.norm(normal)) if normal.shape == (3,) else 0.0
            if not (math.isfinite(length) and length > 0 and math.isfinite(float(plane[1]))):
                raise InvalidArgumentError(
                    f"set_plane: plane {plane!r} needs a finite non-zero normal and offset"
                )
            normal, offset = normal / length, float(plane[1]) / length
        else:
            raise InvalidArgumentError(
                f"set_plane: plane {plane!r} is none of 'x', 'y', 'z', 'fit', (normal, offset)"
            )
        off = float(np.abs(points @ normal - offset).max())
        if off > tolerance:
            raise CurveError(
                f"curve '{obj.name}' is {off:.4g} m off the plane (more than {tolerance:g} m); "
                "move it nearer first",
                obj.name,
            )
        planes.append((obj, (normal, offset)))
    before = {obj.name: hierarchy.plane_of(obj) for obj in curves}
    try:
        for obj, p in planes:
            hierarchy.store_plane(obj, p)
        hierarchy.update(_with_descendants(curves))
    except BaseException:
        for obj in curves:
            hierarchy.store_plane(obj, before[obj.name])
        raise
    return [{"curve": obj.name, "normal": p[0].tolist(), "offset": p[1]} for obj, p in planes]


def clear_plane(objects) -> int:
    """Release each curve object of ``objects`` from its plane (it stays where it is). Returns
    how many were held."""
    count = 0
    for obj in _curve_objects_of(objects, "clear_plane"):
        count += hierarchy.PLANE in obj  # a property edited by hand goes too
        hierarchy.store_plane(obj, None)
    return count


def held_planes(source) -> list[dict]:
    """The curves of ``source`` (as :func:`curve_objects` takes it) held in a plane: each
    ``{"curve", "normal", "offset"}``."""
    out = []
    for obj in curve_objects(source):
        p = hierarchy.plane_of(obj)
        if p is not None:
            out.append({"curve": obj.name, "normal": p[0].tolist(), "offset": p[1]})
    return out


def update_hierarchy(source) -> list[str]:
    """Bring every attached curve of ``source`` (as :func:`curve_objects` takes it) to its
    parents, in hierarchy order (seed 002 §7.1): each attached end onto its parent's point, the
    free control points by the elastic rule; and every curve held in a plane into it
    (:func:`set_plane`). All curves or none are changed. Returns the names
    of the curves that moved. CurveError naming the curve when a parent is gone or curves
    reference each other in a cycle."""
    return hierarchy.update(curve_objects(source))


#: The directions :func:`set_point_attribute` names for a tangent.
AXIS_DIRECTIONS = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}
#: The curve attributes (seed 002 §5): see :func:`set_curve_attribute`.
CURVE_ATTRIBUTES = ("knuckle", "tangent")
#: The Bézier handle types each point attribute gives its points (left, right), so Blender's
#: own handle rules keep the shape while the designer edits: vector handles for a corner or a
#: straight's inside, aligned ones where the curve runs smoothly through.
_HANDLE_TYPES = {
    "knuckle": (("VECTOR", "VECTOR"),),
    "tangent": (("ALIGNED", "ALIGNED"),),
    "straight": (("ALIGNED", "VECTOR"), ("VECTOR", "ALIGNED")),
    "blend": (("ALIGNED", "ALIGNED"), ("ALIGNED", "ALIGNED")),
}


def set_point_attribute(curve, kind: str, point: int, *, direction=None) -> dict:
    """Give the point ``point`` of the curve object ``curve`` a point attribute (seed 002 §5,
    Fig. 3) and shape the curve by it at once: ``knuckle`` (a corner there), ``tangent`` (the
    curve passes through it along ``direction``: ``"x"``, ``"y"``, ``"z"``, three numbers, or
    None for its direction there now), or, on the point and the next, ``straight`` (a straight
    line between them, entered and left tangentially) or ``blend`` (a smooth blend between the
    tangents the curve arrives and leaves with, circular where they allow). ``point`` counts
    the points the curve passes through (a Bézier spline's points; a cubic Bézier-knot NURBS
    spline's every third control point). Build and Live keep the attribute as the curve and its
    parents change (:func:`update_hierarchy`); it is stored on the object, so it stays with the
    .blend. A knuckle or tangent replaces the point's former knuckle or tangent.

    Returns the attribute ``{"kind", "point"[, "direction"]}``. Nothing changes on an error:
    CurveError naming the curve when it is not one spline, does not pass through its points, is
    a POLY spline asked for a tangent or blend, or the attribute contradicts another one on the
    point (a knuckle with a tangent or a blend, a tangent on a straight's end, two blends);
    InvalidArgumentError for an unknown kind, point or direction."""
    obj = _curve_object(curve, "set_point_attribute")
    if kind not in point_attributes.KINDS:
        raise InvalidArgumentError(
            f"unknown point attribute '{kind}' (one of {', '.join(point_attributes.KINDS)})"
        )
    spline = spline_joints.single_spline(obj)
    index, handles = spline_joints.joint_layout(spline, obj.name)
    if isinstance(point, bool) or not isinstance(point, int) or not 0 <= point < len(index):
        raise InvalidArgumentError(
            f"set_point_attribute: point {point!r} of curve '{obj.name}' is none of 0..{len(index) - 1}"
        )
    if kind == "knuckle" and point in (0, len(index) - 1):
        raise InvalidArgumentError(
            f"set_point_attribute: point {point} is an end of curve '{obj.name}'; a knuckle is a corner "
            "inside a curve"
        )
    if kind in point_attributes.PAIR_KINDS and point + 1 >= len(index):
        raise InvalidArgumentError(
            f"set_point_attribute: a {kind} runs from point {point} to the next, and curve "
            f"'{obj.name}' has points 0..{len(index) - 1}"
        )
    if not handles and kind in ("tangent", "blend"):
        raise CurveError(
            f"curve '{obj.name}': a {kind} needs handles, and its POLY spline has none", obj.name
        )
    attribute = {"kind": kind, "point": point}
    if kind == "tangent":
        attribute["direction"] = _tangent_direction(obj, point, direction)
    elif direction is not None:
        raise InvalidArgumentError(f"set_point_attribute: a {kind} takes no direction")
    slot = {"knuckle", "tangent"} if kind in ("knuckle", "tangent") else {kind}
    before = hierarchy.point_attributes_of(obj)
    after = [a for a in before if not (a["point"] == point and a["kind"] in slot)] + [attribute]
    try:
        point_attributes.validate(after, len(index))
    except point_attributes.AttributeConflict as e:
        raise CurveError(f"curve '{obj.name}': {e}", obj.name) from None
    types = _handle_types(spline) if spline.type == "BEZIER" else None
    try:
        hierarchy.store_point_attributes(obj, after)
        if types is not None:
            for offset, (left, right) in enumerate(_HANDLE_TYPES[kind]):
                p = spline.bezier_points[point + offset]
                p.handle_left_type, p.handle_right_type = left, right
        hierarchy.update(_with_descendants([obj]))
    except BaseException:
        hierarchy.store_point_attributes(obj, before)
        if types is not None:
            for p, (left, right) in zip(spline.bezier_points, types, strict=True):
                p.handle_left_type, p.handle_right_type = left, right
        raise
    return attribute


def _handle_types(spline) -> list[tuple[str, str]]:
    return [(p.handle_left_type, p.handle_right_type) for p in spline.bezier_points]


def _tangent_direction(obj, point: int, direction) -> list[float]:
    if direction is None:
        d = spline_joints.joint_direction(obj, point)
    elif isinstance(direction, str) and direction in AXIS_DIRECTIONS:
        d = np.asarray(AXIS_DIRECTIONS[direction])
    else:
        try:
            d = np.asarray(direction, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            d = np.zeros(0)
    length = float(np.linalg.norm(d)) if d.shape == (3,) else 0.0
    if not (math.isfinite(length) and length > 0.0):
        raise InvalidArgumentError(
            f"set_point_attribute: direction {direction!r} is none of 'x', 'y', 'z', three finite "
            "numbers not all zero, None"
        )
    return (d / length).tolist()


def clear_point_attributes(curve, point: int | None = None) -> int:
    """Take the point attributes off the curve object ``curve`` (only those on ``point``, the
    pairs it begins included, when given); the curve keeps its shape. Returns how many were
    taken off."""
    obj = _curve_object(curve, "clear_point_attributes")
    if point is None:
        return _take_all(obj, hierarchy.point_attributes_of, hierarchy.store_point_attributes)
    before = hierarchy.point_attributes_of(obj)
    kept = [a for a in before if a["point"] != point]
    hierarchy.store_point_attributes(obj, kept)
    return len(before) - len(kept)


def point_attributes_of(source) -> list[dict]:
    """The point attributes of the curve objects of ``source`` (as :func:`curve_objects` takes
    it): each ``{"curve", "kind", "point"[, "direction"]}``."""
    return [
        {"curve": obj.name, **a} for obj in curve_objects(source) for a in hierarchy.point_attributes_of(obj)
    ]


def set_curve_attribute(curves, kind: str, on: bool = True) -> None:
    """Give each curve object of ``curves`` a curve attribute (seed 002 §5, Fig. 4), or take it
    away (``on=False``); it acts on the points of the curves attached to it
    (:func:`attach` with ``point``). ``knuckle``: the curve is a knuckle line (its role becomes
    ``knuckle``: the surface keeps a crease across it) and every point attached to it is a
    knuckle point of its curve. ``tangent``: the curves attached to it enter the plane it is
    held in tangentially (a flat of side or bottom curve, so stations run into the flat); the
    curve must be held in a plane (:func:`set_plane`). The attached curves are reshaped at once.
    All curves or none: CurveError naming a curve not held in a plane for ``tangent``;
    InvalidArgumentError for an unknown kind."""
    if kind not in CURVE_ATTRIBUTES:
        raise InvalidArgumentError(f"unknown curve attribute '{kind}' (one of {', '.join(CURVE_ATTRIBUTES)})")
    objs = _curve_objects_of(curves, "set_curve_attribute")
    if kind == "tangent" and on:
        for obj in objs:
            if hierarchy.plane_of(obj) is None:
                raise CurveError(
                    f"curve '{obj.name}' is held in no plane; hold it in one (Hold in Plane) before "
                    "giving it the tangent attribute",
                    obj.name,
                )
    before = [(obj, obj.batten.role, hierarchy.has_tangent(obj)) for obj in objs]
    try:
        for obj in objs:
            if kind == "knuckle":
                if on:
                    obj.batten.role = "knuckle"
                elif obj.batten.role == "knuckle":
                    obj.batten.role = "free"
            else:
                hierarchy.store_tangent(obj, on)
        hierarchy.update(_with_descendants(objs))
    except BaseException:
        for obj, role, tangent in before:
            obj.batten.role = role
            hierarchy.store_tangent(obj, tangent)
        raise


def to_bezier(curves) -> list[str]:
    """Write each curve object of ``curves`` (one object or name, or several) again as a Bézier
    spline of exactly the same shape (:mod:`batten.bezier_form`: its Bézier pieces raised to
    cubic), so the points it passes through can carry point attributes and be attached, and its
    handles be edited. Curves already Bézier splines are left as they are; the curves attached
    to a converted one take their parameters on it again. Returns the names of the curves
    converted. All or none: CurveError naming the curve when it is not one spline, is rational
    (a true circle arc) or of degree above 3."""
    objs = _curve_objects_of(curves, "to_bezier")
    editing = [o.name for o in objs if o.mode == "EDIT"]
    if editing:
        raise CurveError(
            f"curve '{editing[0]}' is in Edit Mode; leave it to make it a Bézier spline", editing[0]
        )
    todo = [(o, bezier_form.cubic_pieces(o)) for o in objs if spline_joints.single_spline(o).type != "BEZIER"]
    converted = {o.name for o, _ in todo}
    children = [o for o in bpy.data.objects if o.type == "CURVE" and _references(o, converted)]
    for obj, pieces in todo:
        bezier_form.write_bezier(obj, pieces)
    hierarchy.refresh(children)
    return [o.name for o, _ in todo]


def _references(obj, parents: set[str]) -> bool:
    """Whether the curve object ``obj`` is attached to one of ``parents`` (False where its
    attachments do not read: Build names those)."""
    try:
        return any(a["parent"] in parents for a in hierarchy.attachments_of(obj))
    except CurveError:
        return False


def curve_attributes(curve) -> dict[str, bool]:
    """The curve attributes of the curve object ``curve``: ``{"knuckle", "tangent"}``."""
    obj = _curve_object(curve, "curve_attributes")
    return {"knuckle": curves_in.role_of(obj) == "knuckle", "tangent": hierarchy.has_tangent(obj)}


def example_files() -> list[Path]:
    """The example networks: shipped inside the extension, or in this checkout's examples/."""
    here = Path(__file__).resolve().parent
    for folder in (here / "examples", here.parent.parent / "examples"):
        files = sorted(folder.glob("*.json"))
        if files:
            return files
    return []


def load_example(file_name: str):
    """Draw the example network ``file_name`` (one of :func:`example_files`, by file name) as
    in :func:`load_network`; InvalidArgumentError when there is no such example."""
    path = next((p for p in example_files() if p.name == file_name), None)
    if path is None:
        raise InvalidArgumentError(f"No example '{file_name}'")
    return load_network(path)


def _fair_object(obj, *, tolerance, noise, degree, corner_angle_deg) -> list[tuple[Curve, dict]]:
    """Every spline of ``obj`` faired (see :func:`fair_curves`), with its report; nothing is
    written."""
    fits = []
    for curve in curves_in.read_object(obj):
        points, corners = fit_data(curve)
        with errors_named_by_object({curve.name: obj.name}):
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
        report["object"] = obj.name
        fits.append((new, report))
    return fits


def fair_curves(
    objects,
    *,
    tolerance: float | None = DEFAULT_FAIR_TOLERANCE,
    noise: float | None = None,
    degree: int = DEFAULT_FAIR_DEGREE,
    corner_angle_deg: float | None = DEFAULT_CORNER_ANGLE_DEG,
    progress: ProgressCallback | None = None,
) -> list[dict]:
    """Refit every spline of the curve objects in ``objects`` (as for :func:`curve_objects`) in
    place as a fair NURBS spline (Dierckx's smoothing spline, H-rep paper §4) and return one
    report per spline, all or nothing: every spline is fitted before any object is written,
    and if one fails (or a write fails midway) every object stays as it was.

    The data are a polyline's points, or samples of a drawn curve (its corners kept; see
    :func:`batten.fit_data.fit_data`). Give a ``tolerance`` (largest deviation, m) or a
    ``noise`` level σ (m). End points are kept exactly, corners stay sharp (given ones, and
    turns sharper than ``corner_angle_deg`` for polylines; None detects none). The objects,
    their data-blocks, materials and modifiers stay. Report keys: curve, object,
    control_points, knots, interior_knots, max_deviation, rms_deviation, inflections,
    curvature_extrema, fairness_energy (∫κ² ds), max_curvature, corners, dropped_duplicates,
    pieces.

    ``progress``: ``progress(label, done, total)`` after each object is fitted (see
    :mod:`batten.progress`); returning ``False`` raises :class:`Cancelled` before any object
    is written.
    """
    return run(_fair_curves_steps(objects, tolerance, noise, degree, corner_angle_deg), progress)


def _fair_curves_steps(objects, tolerance, noise, degree, corner_angle_deg):
    """:func:`fair_curves` as a job (:class:`batten.progress.Job`): a step per object fitted,
    the objects written after the last."""
    if noise is not None:
        tolerance = None
    chosen = curve_objects(objects)
    fitted = []
    for k, obj in enumerate(chosen):
        fits = _fair_object(
            obj, tolerance=tolerance, noise=noise, degree=degree, corner_angle_deg=corner_angle_deg
        )
        fitted.append((obj, fits))
        yield Step("fairing curves", k + 1, len(chosen))
    curves_out.replace_splines_of([(obj, [curve for curve, _ in fits]) for obj, fits in fitted])
    return [report for _, fits in fitted for _, report in fits]


def fair_curve(
    obj,
    *,
    tolerance: float | None = DEFAULT_FAIR_TOLERANCE,
    noise: float | None = None,
    degree: int = DEFAULT_FAIR_DEGREE,
    corner_angle_deg: float | None = DEFAULT_CORNER_ANGLE_DEG,
    progress: ProgressCallback | None = None,
) -> list[dict]:
    """:func:`fair_curves` of the one curve object ``obj``: every spline refitted, one report
    per spline; on any error (or a cancel) nothing changes."""
    return fair_curves(
        obj,
        tolerance=tolerance,
        noise=noise,
        degree=degree,
        corner_angle_deg=corner_angle_deg,
        progress=progress,
    )


#: The roles whose curves :func:`fair_surface` keeps as they are by default: the outline (keel,
#: stem, transom, deck), the midship section, the flat of side and bottom, and the knuckle lines.
SURFACE_FAIR_FIXED_ROLES = ("keel", "stem", "transom", "deck", "midship", "fos", "fob", "knuckle")


def fair_surface(
    source,
    *,
    tolerance: float = DEFAULT_SURFACE_FAIR_TOLERANCE,
    families=("stations", "waterlines"),
    fixed=SURFACE_FAIR_FIXED_ROLES,
    fixed_points=(),
    curve_tolerances: dict | None = None,
    max_rounds: int = 12,
    filter: str = "cubic",
    bias_target: float | None = None,
    smoothing_length: float | None = None,
    model_tolerance: float = DEFAULT_TOLERANCE,
    progress: ProgressCallback | None = None,
) -> dict:
    """Fair the hull in ``source`` through its families of plane sections, as loftsmen did
    (seed 003, Pla et al. 1998 §4). First every section is smoothed along itself, all together
    so that the nodes stay where both their curves pass: its waves shorter than
    ``smoothing_length`` (m; default 200 × the tolerance, 2 m at 10 mm; 0 for none) are taken
    out, its form and its turns tighter than that kept, within the tolerance. Then in each
    family (``"stations"``, ``"waterlines"``, ``"buttocks"``: the network's curves in planes
    x, z, y = const) the section of largest bias against its filtered section (``filter``:
    ``"cubic"`` through two neighbours on each side, or the paper's ``"equidistant"``) is moved
    toward it as far as every constraint allows when that makes it fairer, and again, family
    after family, for at most ``max_rounds`` rounds or until no section's RMS bias
    exceeds ``bias_target`` (m; default 1 % of the tolerance). A node moved on a station moves on
    its waterline too, so the network stays exact and the surface rebuilds from it.

    Constraints: every point stays within ``tolerance`` (m) of where it was (or the curve
    object's own value in ``curve_tolerances``, ``{object name: m}``); the curves named in
    ``fixed`` — roles (default :data:`SURFACE_FAIR_FIXED_ROLES`) or curve object names (user
    locks) — are not touched; every curve's ends stay (so the perpendiculars, the DWL's ends and
    the outline), and nodes within ``model_tolerance`` of ``fixed_points``; sections stay in
    their planes; knuckle points stay knuckles.

    The curve objects that moved are rewritten in place (all or none, as :func:`fair_curves`;
    a failure changes nothing; the operator's undo restores them). Returns the report: ``rounds``,
    ``moves``, ``converged``, ``smoothing_length`` (m), ``smoothed`` (sections the smoothing
    moved), ``max_deviation`` (m), ``sections`` (per family, its movable
    sections), ``before`` / ``after`` (the hull's ``curvature_variation`` Σ∫κ′² ds, 1/m³,
    ``inflections``, ``max_bias`` m) and ``curves``: per curve ``curve``, ``object``,
    ``family``, ``offset``, ``moves``, ``tolerance``, ``max_deviation``, ``before``, ``after``.
    InvalidArgumentError for a bad family, filter, role, tolerance or an unknown name.

    ``progress``: ``progress(label, round, max_rounds)`` after each round (the core calls back
    between rounds; see :mod:`batten.progress`); returning ``False`` stops the fairing and
    raises :class:`Cancelled`, and no curve is changed.
    """
    options = {
        "tolerance": tolerance,
        "families": families,
        "fixed": fixed,
        "fixed_points": fixed_points,
        "curve_tolerances": curve_tolerances,
        "max_rounds": max_rounds,
        "filter": filter,
        "bias_target": bias_target,
        "smoothing_length": smoothing_length,
        "model_tolerance": model_tolerance,
    }
    return run(_fair_surface_steps(source, **options), progress)


def _fair_surface_steps(
    source,
    *,
    tolerance,
    families,
    fixed,
    fixed_points,
    curve_tolerances,
    max_rounds,
    filter,
    bias_target,
    smoothing_length,
    model_tolerance,
):
    """:func:`fair_surface` as a job: the core's rounds run in a worker thread (it touches no
    Blender data), a step per round; the curve objects are written after the last."""
    curves, object_of = _read_source(source)
    by_object: dict[str, list[str]] = {}
    for c in curves:
        by_object.setdefault(object_of[c.name], []).append(c.name)
    fixed_roles, fixed_curves = [], []
    for item in [fixed] if isinstance(fixed, str) else list(fixed):
        if item in ROLES:
            fixed_roles.append(item)
        elif item in by_object:
            fixed_curves.extend(by_object[item])
        elif item in object_of:
            fixed_curves.append(item)
        else:
            raise InvalidArgumentError(f"fixed: '{item}' is no role and no curve of '{_source_name(source)}'")
    per_curve = []
    for obj_name, tol in (curve_tolerances or {}).items():
        if obj_name not in by_object:
            raise InvalidArgumentError(f"curve_tolerances: no curve object '{obj_name}'")
        per_curve.extend((name, float(tol)) for name in by_object[obj_name])

    def fair(round_done):
        return fair_sections(
            curves,
            tolerance=tolerance,
            families=[families] if isinstance(families, str) else list(families),
            fixed_roles=fixed_roles,
            fixed_curves=fixed_curves,
            fixed_points=[tuple(map(float, p)) for p in fixed_points],
            curve_tolerances=per_curve,
            filter=filter,
            max_rounds=max_rounds,
            bias_target=bias_target,
            smoothing_length=smoothing_length,
            model_tolerance=model_tolerance,
            progress=round_done,
        )

    with errors_named_by_object(object_of):
        faired, report = yield from in_worker("fairing the surface", max_rounds, fair)
    moved = {c["curve"] for c in report["curves"] if c["moves"] > 0}
    new_of = {c.name: c for c in faired}
    objects = {o.name: o for o in curve_objects(source)}
    curves_out.replace_splines_of(
        [
            (objects[obj_name], [new_of[n] for n in names])
            for obj_name, names in by_object.items()
            if moved.intersection(names)
        ]
    )
    for c in report["curves"]:
        c["object"] = object_of[c["curve"]]
    return report


#: Rounds of fitting and snapping :func:`import_sections` makes at most, and how much closer
#: (factor of the tolerance) each round fits a curve that the move through its nodes took past
#: the tolerance.
SNAP_ROUNDS = 4
SNAP_TIGHTEN = 0.7
#: The moved curves keep their points within this share of the tolerance, so that Blender's
#: single-precision control points (rounding by up to 8 µm at 250 m) stay within it.
SNAP_KEEP_WITHIN = 0.99


def import_sections(
    path,
    *,
    tolerance: float = DEFAULT_SECTION_TOLERANCE,
    degree: int = DEFAULT_FAIR_DEGREE,
    corner_angle_deg: float | None = DEFAULT_CORNER_ANGLE_DEG,
    model_tolerance: float = DEFAULT_SECTION_MODEL_TOLERANCE,
    collection: str | None = None,
    progress: ProgressCallback | None = None,
):
    """Read a point-list file (the neutral section JSON of ``shared/hulls``, or a CSV offsets table
    ``name, x, y, z``), find where the point curves cross or end on each other
    (``nodes_from_data``: within twice ``tolerance`` plus what their chords may miss the true
    curve by) and give each such node one point that every curve through it takes among its
    points, fair every curve within ``tolerance`` (m) keeping its end points and corners (a
    station's run along the flat of bottom, and any curve's run along the flat of side, made
    straight in its plane and left tangentially; see :mod:`batten.flat_of_bottom`), join
    the corners (knuckles) of consecutive sections into chines (role ``knuckle``; a chine in one
    plane, a transom's edge, is carried on in that plane to the profile's and the deck edge's
    corners there, shaped like the nearest station; a flat end that the profile outlines
    between two of its knuckles, a shaft boss's, gets its edge shaped the same way and straight
    lines across it and on to that station, role ``free``), then move the
    curves, as little as possible, through the nodes where they meet (where two curves come
    within ``SECTION_CAPTURE_FACTOR`` × ``tolerance`` of each other they are one node, and both
    pass exactly through it; where three or more curves meet at a smooth node, their tangents
    are turned into the one plane they are closest to, by at most
    ``MAX_TANGENT_TURN_DEGREES``, so the surface is G1 there), and draw them as NURBS curve
    objects in a new collection, with roles from the curve kinds. So curves that cross in the
    data meet exactly, and the network builds at the default model tolerance. All curves are
    fitted before anything is created. A file that cannot be read, or holds no curves, raises
    NetworkFileError naming it.

    Returns ``(collection, reports)``, one report per curve (see :func:`fair_curves`; a
    chine's report has ``kind`` ``"chine"`` and ``points``, the knuckles it joins; a flat end's
    line ``"line"``; the flat of bottom ``"flat_of_bottom"``), with
    ``points`` (how many the data had), ``data_nodes`` (nodes of the data it was fitted
    through), ``nodes`` (nodes the curve was moved through),
    ``skipped_nodes`` (nodes it leaves out because meeting them would take one of its points
    past ``tolerance``; the build names them as near misses), ``snap_move`` (m, the largest
    distance to a node before the move), ``tangent_nodes`` and ``tangent_turn_deg`` (smooth
    nodes where its tangent was turned into the node's plane, and the largest turn in degrees),
    ``flats`` (where a section leaves a flat: ``kind`` ``"bottom"`` or ``"side"``, ``plane``,
    ``index``, ``parameter``, ``point``), ``max_deviation`` and ``max_deviation_index``
    measured after the move (``rms_deviation`` is the fit's), and ``fit_tolerance``: a curve
    that leaves nodes out is fitted again closer (× ``SNAP_TIGHTEN``, up to ``SNAP_ROUNDS``
    times) and the nodes found again. ``dropped_points`` lists the indices of the file's points
    a section no longer runs through: an end that meets another curve at a few degrees and runs
    beside it in a needle (a waterline beside a falling sheer) ends at its last node before it,
    and the surface, not the curve, passes those points.

    ``progress``: ``progress(label, done, total)`` after each section is fitted (see
    :mod:`batten.progress`); returning ``False`` raises :class:`Cancelled` and nothing is
    created.
    """
    options = {
        "tolerance": tolerance,
        "degree": degree,
        "corner_angle_deg": corner_angle_deg,
        "model_tolerance": model_tolerance,
        "collection": collection,
    }
    return run(_import_sections_steps(path, **options), progress)


def _import_sections_steps(path, *, tolerance, degree, corner_angle_deg, model_tolerance, collection):
    """:func:`import_sections` as a job: a step per section fitted; the collection drawn after
    the last."""
    name, sections = sections_in.read_sections(path)
    if not sections:
        raise NetworkFileError(f"section file '{path}': no curves")
    # Nodes from the data: where the point curves meet, one point each curve is fitted through.
    noded, sources, nodes = nodes_from_data(
        [sec.name for sec in sections],
        [sec.points for sec in sections],
        tolerance,
        corner_angle_deg,
        model_tolerance,
    )
    data = [sections_in.PointCurve(sec.name, sec.role, pts) for sec, pts in zip(sections, noded, strict=True)]
    # The flats: stations run straight in the base plane and leave it tangentially; any curve
    # runs straight along the flat of side (a station up to the deck, a waterline or the deck
    # edge through the parallel middle body) and leaves it tangentially.
    everything = np.concatenate([sec.points for sec in data])
    base = flat_of_bottom.base_plane(everything, model_tolerance)
    side = flat_of_bottom.side_plane(everything, model_tolerance)
    stations = [flat_of_bottom.is_station(sec.points, model_tolerance) for sec in data]

    def fit(i: int, within: float):
        sec = data[i]
        planes = []
        if base is not None and stations[i]:
            planes.append(("bottom", ((0.0, 0.0, 1.0), base, model_tolerance)))
        if side is not None:
            # Either side of the centreplane: a curve runs in the one its points are on.
            planes.append(("side", ((0.0, 1.0, 0.0), side, model_tolerance)))
            planes.append(("side", ((0.0, 1.0, 0.0), -side, model_tolerance)))
        curve, report = fair_points(
            sec.name,
            sec.points,
            degree=degree,
            tolerance=within,
            corner_angle_deg=corner_angle_deg,
            model_tolerance=model_tolerance,
            role=sec.role,
            flat_planes=[plane for _, plane in planes],
            flat_noise=within,
        )
        for flat in report["flats"]:
            flat["kind"] = planes[flat["plane"]][0]
        report["curve"] = sec.name
        return curve, report

    fits = []
    for k in range(len(data)):
        fits.append(fit(k, tolerance))
        yield Step("fitting sections", k + 1, len(data))
    within = [tolerance] * len(sections)
    for round_ in range(SNAP_ROUNDS + 1):
        curves = [c for c, _ in fits]
        knuckles = _off_given_chines([_corner_points(c, r) for c, r in fits], curves, tolerance)
        chines = chines_from_knuckles(curves, knuckles, tolerance)
        # A chine's own data are the knuckles it joins; the flat of bottom's, the flats' ends.
        points = [sec.points for sec in data] + [
            _chain_points(ch, knuckles, model_tolerance) for ch in chines
        ]
        fob = _flat_of_bottom_curve([r for _, r in fits], stations, curves, model_tolerance)
        if fob is not None:
            chines.append(fob[0])
            points.append(fob[1])
        snapped, snaps = snap_to_nodes(
            curves + chines, SECTION_CAPTURE_FACTOR * tolerance, points, SNAP_KEEP_WITHIN * tolerance
        )
        short = [i for i, s in enumerate(snaps[: len(sections)]) if s["skipped"]]
        if not short or round_ == SNAP_ROUNDS:
            break
        # These curves would leave their data to meet some nodes: fit them closer and try again.
        for i in short:
            within[i] *= SNAP_TIGHTEN
            fits[i] = fit(i, within[i])
    reports = [report for _, report in fits]
    reports += [
        {
            "curve": ch.name,
            "kind": CHINE_KIND_OF_ROLE[ch.role],
            "points": len(p),
            "corners": [],
            "fit_tolerance": None,
        }
        for ch, p in zip(chines, points[len(sections) :], strict=True)
    ]
    for report, snap, w in zip(reports, snaps, within + [None] * len(chines), strict=True):
        report["nodes"] = snap["nodes"]
        report["skipped_nodes"] = snap["skipped"]
        report["snap_move"] = snap["max_move"]
        report["tangent_nodes"] = snap["tangent_nodes"]
        report["tangent_turn_deg"] = snap["max_tangent_turn"]
        report["fit_tolerance"] = w
        report["max_deviation"] = snap["max_deviation"]
        report["max_deviation_index"] = snap["max_deviation_index"]
    # Point indices in the reports are the file's: a node between two points is the nearer.
    for i, (report, sec, source) in enumerate(zip(reports[: len(sections)], sections, sources, strict=True)):
        report["points"] = len(sec.points)
        report["data_nodes"] = sum(1 for n in nodes if i in n["curves"])
        kept = {k for k in source if k is not None}
        report["dropped_points"] = [k for k in range(len(sec.points)) if k not in kept]
        report["max_deviation_index"] = _file_index(report["max_deviation_index"], source)
        report["corners"] = [_file_index(k, source) for k in report["corners"]]
    coll = _draw_collection(collection or name, snapped)
    datums = sections_in.read_datums(path)
    if "lpp" in datums:
        coll[LPP_PROPERTY] = datums["lpp"]
        coll[FP_PROPERTY] = datums["lpp"]
    if "draft" in datums:
        coll[DESIGN_DRAFT_PROPERTY] = datums["draft"]
    # The surface is tangent to the flats the curves were fitted to run straight in.
    planes = [[0.0, 1.0, 0.0, side], [0.0, 1.0, 0.0, -side]] if side is not None else []
    planes += [[0.0, 0.0, 1.0, base]] if base is not None else []
    if planes:
        coll[TANGENT_PLANES_PROPERTY] = planes
    return coll, reports


def _flat_of_bottom_curve(
    reports: list[dict], stations: list[bool], curves: list[Curve], model_tolerance: float
):
    """``(curve, points)``: the flat of bottom curve (role ``fob``) through the points where the
    stations leave the base plane, and those points; None with fewer than
    :data:`flat_of_bottom.MIN_STATIONS` such stations, or when a curve of that name is given.
    It passes within 1 % of the model tolerance of each point, so it crosses each station where
    the station's flat run ends (its knot): at 0.5 mm a crossing fell up to 0.55 mm inside the
    flat run, and the bilge patch's side then ended in that short flat stretch, which tilted the
    bilge off the flat (KCS 0.53°, a synthetic flat-bottomed hull 1.17°)."""
    ends = flat_of_bottom.flat_ends(reports, stations)
    if len(ends) < flat_of_bottom.MIN_STATIONS or any(c.name == flat_of_bottom.NAME for c in curves):
        return None
    curve, _ = fair_points(
        flat_of_bottom.NAME,
        ends,
        degree=min(3, len(ends) - 1),
        tolerance=0.01 * model_tolerance,
        corner_angle_deg=None,
        model_tolerance=0.001 * model_tolerance,
        role="fob",
    )
    return curve, ends


def _file_index(k: int, source: list[int | None]) -> int:
    """The index in the file of point ``k`` of a curve's points with its data nodes
    (``source`` from ``nodes_from_data``): its own, or for an inserted node the point before."""
    return max((i for i in source[: k + 1] if i is not None), default=0)


def _corner_points(curve: Curve, report: dict) -> np.ndarray:
    """The knuckle points of a faired curve, (k, 3): where its fit kept corners."""
    t = report["corner_parameters"]
    return np.asarray(curve.evaluate(t), dtype=float).reshape(-1, 3) if t else np.zeros((0, 3))


def _off_given_chines(knuckles: list[np.ndarray], curves: list[Curve], within: float) -> list[np.ndarray]:
    """The knuckle points not on a chine the file gives (within ``within`` m of it): a chine of
    the file joins those itself, and joining them again would draw it twice."""
    given = [c for c in curves if c.role == "knuckle"]
    off = [[k for k in ks if all(g.nearest(k)[1] > within for g in given)] for ks in knuckles]
    return [np.asarray(ks, dtype=float).reshape(-1, 3) for ks in off]


#: The ``kind`` of the report of a curve the import adds, by its role: a chine joining knuckles,
#: the flat of bottom, or a straight line parting a flat end (a shaft boss's) and the band
#: beside it.
CHINE_KIND_OF_ROLE = {"knuckle": "chine", "fob": "flat_of_bottom", "free": "line"}


def _chain_points(chine: Curve, knuckles: list[np.ndarray], within: float) -> np.ndarray:
    """The knuckle points a chine joins: those it passes through (within ``within`` m)."""
    found = [k for ks in knuckles for k in ks if chine.nearest(k)[1] <= within]
    return np.asarray(found, dtype=float).reshape(-1, 3)


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
    ``curves`` — curve names —, ``objects`` — the names of the objects they came from —,
    ``location`` and ``error``, as the build report's warnings).
    """
    curves, object_of = _read_source(source)
    with errors_named_by_object(object_of):
        topo = _topology(curves, tolerance)
    topo["diagnostics"] = with_objects(topo["diagnostics"], object_of)
    return topo


class BuildResult(NamedTuple):
    """What :func:`build` returns: the surface mesh object and the report dict."""

    object: object
    report: dict


def _surface_object(name: str):
    for obj in bpy.data.objects:
        if obj.type == "MESH" and obj.get(SURFACE_TAG) == name:
            return obj
    return None


#: Custom property of a hull collection: the planes its surface is tangent to wherever its
#: curves run in them, each ``[nx, ny, nz, offset]`` for the plane ``n · p = offset`` — the flat
#: of side (either side of the centreplane) and the flat of bottom that
#: :func:`import_sections` finds in the data, or set by hand.
TANGENT_PLANES_PROPERTY = "batten_tangent_planes"


def tangent_planes(source) -> list[list[float]]:
    """The planes the surface of ``source`` is tangent to where its curves run in them (see
    :data:`TANGENT_PLANES_PROPERTY`): a collection's own, or for an object or a list of
    objects the first collection holding one that has them; ``[]`` when none has."""
    if isinstance(source, bpy.types.Collection):
        holders = [source]
    elif isinstance(source, bpy.types.Object):
        holders = list(source.users_collection)
    elif isinstance(source, Iterable) and not isinstance(source, str | bytes):
        holders = [c for o in source if isinstance(o, bpy.types.Object) for c in o.users_collection]
    else:
        holders = []
    for holder in holders:
        planes = holder.get(TANGENT_PLANES_PROPERTY)
        if planes is not None:
            return _checked_planes(planes, holder.name)
    return []


def _checked_planes(planes, holder: str) -> list[list[float]]:
    """``planes`` as lists of four floats; InvalidArgumentError naming ``holder`` (a collection)
    when one is not four finite numbers with a non-zero normal."""
    where = f"collection '{holder}': {TANGENT_PLANES_PROPERTY}"
    try:
        out = [[float(v) for v in plane] for plane in planes]
    except (TypeError, ValueError) as e:
        raise InvalidArgumentError(f"{where} must be a list of [nx, ny, nz, offset]: {e}") from e
    for plane in out:
        if len(plane) != 4 or not all(math.isfinite(v) for v in plane) or not any(plane[:3]):
            raise InvalidArgumentError(
                f"{where} holds {plane}: a plane is [nx, ny, nz, offset], four finite numbers "
                "with a non-zero normal"
            )
    return out


def _planes_moved_with(
    planes: list[list[float]], before: list[Curve], after: list[Curve]
) -> list[list[float]]:
    """The tangent planes ``planes`` of the hull with curves ``before``, moved to where the
    same curves run in them ``after`` a change (a transformation's copy): the curves with two
    control points or more in a plane before (a flat run's control points all lie in its
    plane) say where it went, at the offset most of their control points share after (the
    median of those within the import's model tolerance of it; nearest the old offset among
    equals). A plane no curve ran in that is the mirror image across the centreplane of one
    they ran in (the port side's flat of a starboard half) goes to the mirror image of where
    that one went; any other stays as it is. One they no longer share is left out."""
    tol = DEFAULT_SECTION_MODEL_TOLERANCE
    moved = _planes_moved_by_curves(planes, before, after, tol)
    out = []
    for plane, went in zip(planes, moved, strict=True):
        if went is not None:
            if went:
                out.append(went)
            continue
        mirror = [plane[0], -plane[1], plane[2], plane[3]]
        twin = next(
            (w for p, w in zip(planes, moved, strict=True) if w and _same_plane(mirror, p, tol)),
            None,
        )
        if twin is None:
            out.append([float(v) for v in plane])
            continue
        image = [twin[0], -twin[1], twin[2], twin[3]]
        sign = 1.0 if np.dot(image[:3], plane[:3]) > 0.0 else -1.0
        out.append([float(sign * v) for v in image])
    return out


def _same_plane(a: list[float], b: list[float], tol: float) -> bool:
    """Whether planes ``a`` and ``b`` (each ``[nx, ny, nz, offset]``, normals of any length
    and either sense) are one plane: normals parallel, offsets within ``tol``."""
    na, nb = np.asarray(a[:3], dtype=float), np.asarray(b[:3], dtype=float)
    la, lb = float(np.linalg.norm(na)), float(np.linalg.norm(nb))
    sign = 1.0 if np.dot(na, nb) > 0.0 else -1.0
    return bool(np.allclose(na / la, sign * nb / lb, atol=1e-9) and abs(a[3] / la - sign * b[3] / lb) <= tol)


def _planes_moved_by_curves(
    planes: list[list[float]], before: list[Curve], after: list[Curve], tol: float
) -> list[list[float] | None]:
    """Per plane of ``planes``, where the curves running in it ``before`` run in it ``after``
    (see :func:`_planes_moved_with`): the moved plane, ``[]`` where they no longer share one,
    ``None`` where no curve ran in it."""
    points = {c.name: np.asarray(c.control_points, dtype=float).reshape(-1, 3) for c in after}
    moved: list[list[float] | None] = []
    for plane in planes:
        normal, offset = np.asarray(plane[:3], dtype=float), float(plane[3])
        within = tol * float(np.linalg.norm(normal))
        on = [
            c.name
            for c in before
            if int(
                np.sum(
                    np.abs(np.asarray(c.control_points, dtype=float).reshape(-1, 3) @ normal - offset)
                    <= within
                )
            )
            >= 2
        ]
        if not on:
            moved.append(None)
            continue
        values = np.sort(np.concatenate([points[n] @ normal for n in on if n in points] or [np.zeros(0)]))
        if len(values) < 2:
            moved.append([])
            continue
        counts = np.searchsorted(values, values + within, side="right") - np.searchsorted(
            values, values - within
        )
        if counts.max() < 2:
            moved.append([])
            continue
        best = values[counts == counts.max()]
        level = best[int(np.argmin(np.abs(best - offset)))]
        moved.append([*map(float, plane[:3]), float(np.median(values[np.abs(values - level) <= within]))])
    return moved


def _move_planes(coll, planes: list[list[float]], before: list[Curve], after: list[Curve]) -> None:
    """Give ``coll`` (whose curves are ``after``) the tangent planes ``planes`` of the hull of
    ``before``, moved with them (:func:`_planes_moved_with`); nothing when there are none."""
    if planes:
        coll[TANGENT_PLANES_PROPERTY] = _planes_moved_with(planes, before, after)


def build(
    source,
    *,
    tolerance: float = DEFAULT_TOLERANCE,
    resolution: int = DEFAULT_RESOLUTION,
    mirror: bool = True,
    live: bool = False,
) -> BuildResult:
    """Build the smooth hull surface of the curve network in ``source`` (H-rep paper): nodes
    where curves meet, faces found automatically, one Gregory (4 sides) or Charrot–Gregory
    (3, 5, 6 … sides) patch per face with cross-boundary tangents from the crossing curves, G1
    across ordinary curves and G0 across knuckles, tessellated with ``resolution`` segments per
    side into one watertight mesh.

    The mesh object (``"<source> surface"``) is updated in place on every rebuild: its name,
    materials and modifiers survive. ``mirror`` adds a Mirror modifier about y = 0. Faces
    carry an integer attribute ``patch`` (the network face they belong to). A build that fails
    raises BattenError (NoSurfaceError when no face could be made) and leaves the previous
    mesh untouched.

    ``report`` holds: nodes, edges, node_positions, node_kinds (as in :func:`topology`),
    faces, faces_by_sides, open_edges, max_gap, max_normal_angle_deg with where it is
    (max_normal_angle_at, max_normal_angle_curve), max_neighbour_angle_deg and
    max_neighbour_angle_at (the largest angle between neighbouring mesh faces off the knuckles),
    holes and folds (counts of the ``hole`` and ``fold`` warnings), crease_angles_deg (per
    knuckle curve: name, min, max), knuckle_edges (each ``curve``, ``objects`` — the object
    it came from —, ``source`` — ``"role"`` or ``"auto"``, found at corners of crossing curves
    —, ``corner_curves``, ``crease_deg`` (min, max) or None, ``points`` along the edge),
    enclosed_volume_half (m³, between the drawn half surface and the centreplane, up to the
    top of the surface: a volume of the shape, not a displacement, which
    :func:`hydrostatics` gives at a draft), enclosed_volume (both halves when mirrored, else
    the half), mesh_vertices, mesh_faces, and warnings: each a dict with ``kind``
    (``dangling_end``, ``near_miss``, ``unclosed_region``, ``face_not_patched``, ``hole`` — free
    edges off the profile, deck and transom —, ``fold`` — neighbouring mesh faces more than 30°
    apart off the knuckles, or a patch out of its boundary's box —, ``side_blended`` — a face
    whose Gregory or Charrot–Gregory patch folded, given the side-blended patch of the same
    curves and ribbon planes, which folds clearly less —, ``knuckle_in_face`` — a corner of a
    bounding curve inside a face's side where the hull has a knuckle no curve follows, whose
    ribbon step the patch spreads inside the face —, …),
    ``message``, ``curves`` (curve names),
    ``objects`` (the names of the curve objects they came from, for selecting them),
    ``location`` ([x, y, z] or None) and ``error`` (for a face that could not be patched the
    patch error as ``{"kind", "message"}``, else None).

    Where a curve runs in one of the source's tangent planes (:func:`tangent_planes`: the flat
    of side and bottom an import found), the faces along it take that plane as their tangent
    plane, so a flat of side stays flat between the curves that outline it.

    ``live=True`` (Live mode, scripts that move curves in a loop) keeps the hull between calls
    and rebuilds it incrementally: when the curves' connectivity is unchanged only the faces
    the moved curves reach are built again and only the mesh's vertex positions are
    rewritten — the mesh is exactly that of a full build. The report then says
    ``measured: False``: its quality figures (gaps, normal jumps, creases, holes, folds,
    warnings) are those of the last measured build until :func:`settle` measures them; its
    ``rebuild`` says what was done (``kind`` ``"full"`` or ``"incremental"``, ``faces``
    rebuilt ``of`` all, and the ``reason`` a rebuild was full).
    """
    curves, object_of = _read_source(source)
    name = _source_name(source)
    with errors_named_by_object(object_of):
        planes = tangent_planes(source)
        if live:
            arrays, report, model = hull_models.live_build(name, curves, tolerance, resolution, planes)
        else:
            arrays, report, model = build_hull_model(curves, tolerance, resolution, name, planes)
            hull_models.keep(name, curves, tolerance, resolution, model, tangent_planes=planes)
    positions, corners, sizes, patch = arrays
    obj = _surface_object(name)
    moved_only = (
        live
        and report["rebuild"]["kind"] == "incremental"
        and mesh_out.update_positions(obj, positions, corners, sizes)
    )
    if moved_only:
        mesh_out.set_mirror(obj, mirror)
    else:
        obj = mesh_out.write_surface(
            f"{name} surface", positions, corners, sizes, patch, obj=obj, mirror=mirror
        )
    obj[SURFACE_TAG] = name
    if report.get("measured", True):
        # A live drag's surface is mapped once it settles (:func:`settle`), not every frame.
        _remap_curvature(source, obj)
    return BuildResult(obj, _build_report(report, object_of, mirror))


def _build_report(report: dict, object_of, mirror: bool) -> dict:
    """The core's build report as :func:`build` gives it: the volume keys named for what they
    are, the objects of the curves named in warnings and knuckle edges."""
    report["mirror"] = mirror
    half = report.pop("volume")  # the core's: the drawn half surface to the centreplane
    report["enclosed_volume_half"] = half
    report["enclosed_volume"] = half * (2.0 if mirror else 1.0)
    report["warnings"] = with_objects(report["warnings"], object_of)
    report["knuckle_edges"] = [
        {**k, "objects": objects_of([k["curve"]], object_of)} for k in report["knuckle_edges"]
    ]
    return report


def settle(source, *, mirror: bool = True) -> dict | None:
    """Measure the report of ``source``'s live hull (:func:`build` with ``live=True``) when a
    rebuild left its quality figures unmeasured, and return it as :func:`build` does (with
    ``measured: True``); None when there is nothing to measure. The mesh is not touched: it
    is already exact."""
    settled = hull_models.settle(_source_name(source))
    if settled is None:
        return None
    _arrays, report, _model = settled
    _curves, object_of = _read_source(source)
    obj = _surface_object(_source_name(source))
    if obj is not None:
        _remap_curvature(source, obj)
    return _build_report(report, object_of, mirror)


# --- Curvature ---------------------------------------------------------------------------------

#: Custom property of a surface object showing a curvature map: its kind (``"gaussian"`` or
#: ``"mean"``), kept so that a rebuild (and a live drag, once it settles) maps the new surface.
CURVATURE_MAP_PROPERTY = "batten_curvature_map"
#: Custom property holding the map's fixed scale (1/m² or 1/m), when one was asked for.
CURVATURE_SCALE_PROPERTY = "batten_curvature_scale"


def _built_surface(source):
    """``(surface object, model)`` of the hull in ``source`` as last built, or NoSurfaceError
    when it has no surface object or the object's mesh is not the kept surface's (the curves
    moved since, or the mesh was edited)."""
    name = _source_name(source)
    obj = _surface_object(name)
    if obj is None:
        raise NoSurfaceError(f"'{name}' has no surface yet: build it first (batten.api.build)")
    model = _hull_model(source, measured=False)
    return obj, model


def surface_curvature(source) -> dict:
    """The Gaussian and mean curvature of the hull surface of ``source`` at every vertex of its
    surface mesh, from the exact patches (do Carmo §3-3; not from the mesh): ``gaussian``
    (1/m², positive on a dome such as the bilge turning into the bottom, negative on a saddle
    such as the run into the skeg, zero where flat or developable), ``mean`` (1/m, positive
    where the hull bulges outwards, negative where it is hollow), ``defined`` (bool; False at a
    singular point of a patch, where both hold 0), each an array in the mesh's vertex order,
    and ``positions`` (n, 3) of the vertices. A vertex on an edge between patches takes their
    mean, so a curvature step across a G1 edge shows.

    Raises NoSurfaceError when ``source`` has not been built (or its curves moved since and
    it cannot be built)."""
    obj, model = _built_surface(source)
    name = _source_name(source)
    resolution = hull_models.kept_resolution(name)
    gaussian, mean, defined = model.vertex_curvature(resolution)
    n = len(obj.data.vertices)
    if len(gaussian) != n:
        raise NoSurfaceError(
            f"the mesh of '{obj.name}' ({n} vertices) is not the surface of '{name}' "
            f"({len(gaussian)} vertices): build it again"
        )
    positions = np.empty(n * 3, dtype=np.float32)
    obj.data.vertices.foreach_get("co", positions)
    return {
        "gaussian": gaussian,
        "mean": mean,
        "defined": defined,
        "positions": positions.reshape(n, 3).astype(np.float64),
    }


def show_curvature(source, *, kind: str = "gaussian", scale: float | None = None) -> dict:
    """Colour the surface mesh of ``source`` by its curvature (:func:`surface_curvature`):
    ``kind`` ``"gaussian"`` or ``"mean"``, blue negative, white zero, red positive, full colour
    at ± ``scale`` (1/m² or 1/m; default: the 95th percentile of the magnitudes on this hull).
    Both curvatures are written as point attributes (``batten_gaussian_curvature``,
    ``batten_mean_curvature``) and the colour as ``batten_curvature``, the mesh's active and
    render colour (Solid mode: Attribute colour; a material: the Color Attribute node). The map
    follows rebuilds: every build of the hull, and a live drag once it settles, maps the new
    surface until :func:`clear_curvature`.

    Returns ``{"kind", "scale", "min", "max", "defined"}`` (the range over defined vertices and
    their count). Raises InvalidArgumentError for an unknown kind or a scale that is not a
    positive number, NoSurfaceError as :func:`surface_curvature`."""
    if kind not in curvature_map.KINDS:
        raise InvalidArgumentError(f"kind must be one of {sorted(curvature_map.KINDS)}, not {kind!r}")
    if scale is not None and not (np.isfinite(scale) and scale > 0.0):
        raise InvalidArgumentError(f"scale must be a positive number, not {scale!r}")
    c = surface_curvature(source)
    values, defined = c[kind], c["defined"]
    used = scale if scale is not None else curvature_map.default_scale(values, defined)
    obj = _surface_object(_source_name(source))
    curvature_map.write(obj.data, c["gaussian"], c["mean"], defined, kind, used)
    obj[CURVATURE_MAP_PROPERTY] = kind
    if scale is None:
        obj.pop(CURVATURE_SCALE_PROPERTY, None)
    else:
        obj[CURVATURE_SCALE_PROPERTY] = float(scale)
    on = values[defined]
    return {
        "kind": kind,
        "scale": float(used),
        "min": float(on.min()) if len(on) else 0.0,
        "max": float(on.max()) if len(on) else 0.0,
        "defined": int(defined.sum()),
    }


def clear_curvature(source) -> bool:
    """Remove the curvature map of ``source``'s surface (its attributes, and the setting that
    maps rebuilds); True when there was one."""
    obj = _surface_object(_source_name(source))
    if obj is None:
        return False
    had = obj.pop(CURVATURE_MAP_PROPERTY, None) is not None
    obj.pop(CURVATURE_SCALE_PROPERTY, None)
    return curvature_map.clear(obj.data) or had


def _remap_curvature(source, obj) -> None:
    """Map the new surface in ``obj`` as the last :func:`show_curvature` asked, if it did."""
    kind = obj.get(CURVATURE_MAP_PROPERTY)
    if kind in curvature_map.KINDS:
        show_curvature(source, kind=kind, scale=obj.get(CURVATURE_SCALE_PROPERTY))


# --- Hydrostatics -------------------------------------------------------------------------------

#: Custom properties of a hull collection that give its perpendiculars and design draft (set by
#: :func:`import_sections` from a file's ``Lpp`` and ``T``, or by hand): ``batten_lpp`` (m),
#: ``batten_fp`` (x of the forward perpendicular, m) and ``batten_design_draft`` (m).
LPP_PROPERTY = "batten_lpp"
FP_PROPERTY = "batten_fp"
DESIGN_DRAFT_PROPERTY = "batten_design_draft"


#: Vertices of a mesh object closer than this (relative to its size) are one vertex.
MESH_WELD_RELATIVE = 1e-9


def _is_mesh(source) -> bool:
    return isinstance(source, bpy.types.Object) and source.type == "MESH"


def _mesh_hull(obj) -> MeshHull:
    """A Blender mesh object (as evaluated: modifiers such as Mirror applied, in world
    coordinates) as a triangle hull."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        mesh.calc_loop_triangles()
        n = len(mesh.vertices)
        positions = np.empty(n * 3, dtype=np.float64)
        mesh.vertices.foreach_get("co", positions)
        positions = positions.reshape(n, 3)
        tris = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
        mesh.loop_triangles.foreach_get("vertices", tris)
    finally:
        evaluated.to_mesh_clear()
    m = np.array(obj.matrix_world, dtype=np.float64)
    positions = positions @ m[:3, :3].T + m[:3, 3]
    # Weld coincident vertices (a Mirror modifier's seam, split edges): within 1e-9 of the size.
    size = float(np.ptp(positions, axis=0).max()) if n else 1.0
    key = np.round(positions / (MESH_WELD_RELATIVE * max(size, 1e-300))).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return MeshHull(positions[first], inverse.reshape(-1)[tris].reshape(-1, 3))


def _hull_model(source, *, measured: bool = True):
    """The exact surface of the hull in ``source`` (a collection or its name), built if its
    curves changed since the last build, with errors naming the curve objects. ``measured``
    False: the patches and mesh suffice (hydrostatics), and a live rebuild's surface whose
    report is not yet measured will do."""
    curves, object_of = _read_source(source)
    with errors_named_by_object(object_of):
        return hull_models.model_for(
            _source_name(source), curves, measured=measured, tangent_planes=tangent_planes(source)
        )


def _datums(source, lpp, fp):
    """``(lpp, fp)``: as given, else the collection's ``batten_lpp`` / ``batten_fp``."""
    coll = source if isinstance(source, bpy.types.Collection) else bpy.data.collections.get(str(source))
    if coll is not None:
        if lpp is None and coll.get(LPP_PROPERTY) is not None:
            lpp = float(coll[LPP_PROPERTY])
        if fp is None and lpp is not None and coll.get(FP_PROPERTY) is not None:
            fp = float(coll[FP_PROPERTY])
    return lpp, fp


def design_draft(source) -> float | None:
    """The design draft the hull collection carries (``batten_design_draft``), or None."""
    coll = source if isinstance(source, bpy.types.Collection) else bpy.data.collections.get(str(source))
    if coll is None or coll.get(DESIGN_DRAFT_PROPERTY) is None:
        return None
    return float(coll[DESIGN_DRAFT_PROPERTY])


def hydrostatics(
    source,
    draft: float,
    *,
    trim: float = 0.0,
    heel: float = 0.0,
    density: float = SEA_WATER_DENSITY,
    lpp: float | None = None,
    fp: float | None = None,
    live: bool = False,
) -> dict:
    """The hydrostatics of the hull in ``source`` (a collection or its name), integrated on its
    patches themselves (both sides of a half hull), floating at ``draft`` (m above the baseline,
    at midships), ``trim`` (m, T_AP − T_FP, by the stern positive), ``heel`` (degrees, to
    starboard positive) in water of ``density`` (t/m³).

    Returns a dict of floats, SI units, x forward, z up from the baseline: ``volume`` (m³),
    ``displacement`` (t), ``density``, ``draft_ap``, ``draft_fp``, ``draft_mid``, ``draft_lcf``,
    ``trim``, ``heel``, ``x_ap``, ``x_fp``, ``lpp``, ``lwl``, ``bwl``, ``los`` (length of the
    submerged hull), ``wetted_area`` (the hull's patches under water; an open transom's plane is
    not plating), ``waterplane_area``, ``midship_area`` (at midships), ``max_section_area`` and
    ``max_section_x``, ``cb``, ``cp``, ``cm``, ``cwp``, ``cvp`` (on Lpp, Bwl and the midship
    draft), ``lcb``, ``tcb``, ``vcb`` (= KB), ``lcf``, ``it``, ``il`` (m⁴, about the waterplane's
    centroid), ``bmt``, ``bml``, ``kmt``, ``kml``, ``tpc`` (t/cm), ``mtc`` (t·m/cm, Δ·BMl/(100·Lpp)),
    ``transom_area`` (the immersed transom) and ``entrance_half_angle`` (degrees).

    Perpendiculars: ``fp`` (x of FP) with ``lpp``; else the collection's ``batten_lpp`` /
    ``batten_fp``; else FP at the fore end of the level waterline at ``draft`` and AP ``lpp`` aft
    of it, or at its aft end (Lpp = Lwl). ``live`` uses coarser cells (about 1e-8 relative) for
    figures updated while dragging.

    Raises HydrostaticsError when the draft is below the keel or floods the open top, or the
    surface has a hole under water (the message says where); an open transom in a steep plane is
    closed by that plane. InvalidArgumentError for NaN, a density ≤ 0, a heel of 90° or more.

    ``source`` may also be a Blender mesh object: its triangles (as evaluated, in world
    coordinates) are integrated exactly, so its figures can be set beside another tool's on the
    same mesh.
    """
    if _is_mesh(source):
        return _mesh_hull(source).hydrostatics(draft, trim=trim, heel=heel, density=density, lpp=lpp, fp=fp)
    model = _hull_model(source, measured=False)
    lpp, fp = _datums(source, lpp, fp)
    return model.hydrostatics(draft, trim, heel, density, lpp, fp, live)


def _stations(model, draft, stations, lpp, fp) -> np.ndarray:
    if isinstance(stations, int | np.integer):
        if stations < 2:
            raise InvalidArgumentError(f"stations {stations} must be at least 2 (AP and FP)")
        x_ap, x_fp = model.datums(draft, lpp, fp)
        return np.linspace(x_ap, x_fp, int(stations))
    xs = np.asarray(stations, dtype=np.float64).ravel()
    if xs.size == 0 or not np.all(np.isfinite(xs)):
        raise InvalidArgumentError("stations must be a count or a non-empty list of finite x values")
    return xs


def sectional_areas(
    source,
    draft: float,
    stations=21,
    *,
    trim: float = 0.0,
    heel: float = 0.0,
    lpp: float | None = None,
    fp: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The sectional area curve of the hull in ``source`` at ``draft`` (and ``trim``, ``heel``):
    ``(xs, areas)``, the immersed area (m², both sides) of each station plane ``x = xs[k]``.
    ``stations``: a count of stations equally spaced from AP to FP inclusive (21: stations 0 to
    20), or the x values themselves. Perpendiculars as in :func:`hydrostatics`. A mesh object
    takes a count only."""
    if _is_mesh(source):
        if not isinstance(stations, int | np.integer):
            raise InvalidArgumentError("a mesh's sectional areas take a count of stations")
        return _mesh_hull(source).sectional_areas(draft, int(stations), trim=trim, heel=heel, lpp=lpp, fp=fp)
    model = _hull_model(source, measured=False)
    lpp, fp = _datums(source, lpp, fp)
    xs = _stations(model, draft, stations, lpp, fp)
    return xs, model.sectional_areas(draft, xs.tolist(), trim, heel, lpp, fp)


def curves_of_form(
    source,
    drafts,
    *,
    density: float = SEA_WATER_DENSITY,
    lpp: float | None = None,
    fp: float | None = None,
    design: float | None = None,
) -> list[dict]:
    """The curves of form of the hull in ``source``: one :func:`hydrostatics` dict per draft of
    ``drafts`` (upright, level), all about the same perpendiculars — those given, the
    collection's, or those of the level waterline at ``design`` (default: the collection's
    design draft, else the deepest of ``drafts``)."""
    drafts = [float(d) for d in drafts]
    if not drafts:
        raise InvalidArgumentError("drafts must hold at least one draft")
    model = _hull_model(source, measured=False)
    lpp, fp = _datums(source, lpp, fp)
    if fp is None:
        at = design if design is not None else design_draft(source)
        x_ap, x_fp = model.datums(at if at is not None else max(drafts), lpp, None)
        lpp, fp = x_fp - x_ap, x_fp
    return [model.hydrostatics(d, 0.0, 0.0, density, lpp, fp, False) for d in drafts]


def float_to(
    source,
    displacement: float,
    lcg: float,
    *,
    vcg: float | None = None,
    density: float = SEA_WATER_DENSITY,
    lpp: float | None = None,
    fp: float | None = None,
) -> dict:
    """Float the hull in ``source`` at ``displacement`` (t) with its centre of gravity at
    x = ``lcg`` (m): the draft and trim (upright) at which it displaces that much with the centre
    of buoyancy under G — on the true vertical through G when ``vcg`` (m above the baseline) is
    given, else LCB = LCG as hydrostatic tables take it. Returns the :func:`hydrostatics` dict
    there (``draft_mid`` and ``trim`` are the answer). Perpendiculars as in :func:`hydrostatics`,
    found at the level draft of the displacement when not given.

    Raises InvalidArgumentError for a displacement that is not positive or more than the hull
    holds below its open top; HydrostaticsError when no equilibrium is found or the water reaches
    a hole."""
    model = _hull_model(source, measured=False)
    lpp, fp = _datums(source, lpp, fp)
    level = model.level_draft(displacement, density)
    return model.float_to(displacement, lcg, level, vcg, density, lpp, fp)


# --- Sections -----------------------------------------------------------------------------------


def _station_extent(source, model) -> tuple[float, float]:
    """[AP, FP]: the collection's perpendiculars, else those at its design draft, else the
    surface's x-extent."""
    lpp, fp = _datums(source, None, None)
    if lpp is not None and fp is not None:
        return fp - lpp, fp
    draft = design_draft(source)
    if draft is not None:
        try:
            return model.datums(draft, lpp, fp)
        except HydrostaticsError:
            pass  # the draft does not float this surface: its extent will do
    lo, hi = model.bounds
    return lo[0], hi[0]


def sections(
    source,
    *,
    stations=None,
    waterlines=None,
    buttocks=None,
    diagonals=None,
    tolerance: float | None = None,
    collection: bool = False,
) -> dict[str, list[Section]]:
    """Plane sections of the hull in ``source`` (what :func:`build` takes), cut from its patches
    themselves: a dict with keys ``"stations"``, ``"waterlines"``, ``"buttocks"``,
    ``"diagonals"`` and ``"knuckles"`` (the hull's chine lines), each a list of
    :class:`~batten.sections.Section` (family, offset, name, polylines (n, 3) in hull
    coordinates — the drawn half —, fitted curves).

    Each family's argument is None (none), an int ``n`` (``n`` planes evenly spaced over the
    hull's extent, the extremes left out: stations over [AP, FP] — the collection's
    perpendiculars, else those at its design draft, else the x-extent — waterlines over the
    z-extent, buttocks over the y-extent), or a sequence of offsets (m); diagonals a sequence of
    ``(y0, z0, angle_deg)`` (see :mod:`batten.sections`). ``tolerance`` (m, default
    ``DEFAULT_CUT_TOLERANCE``, 1 mm) bounds the chords' distance from the surface and the
    fitted curves' from the points. A plane missing the hull gives a section without
    polylines.

    With ``collection=True`` the sections are also drawn as curve objects (one per section,
    named e.g. ``"station 12.500"``) in the collection ``"<hull> sections"``, a child of the
    hull's collection, replacing what it held; Build and Live rebuilds cut them again.

    Raises InvalidArgumentError for NaN or infinite offsets (naming the argument), a negative
    count, a tolerance that is not a positive number; what :func:`build` raises for the
    surface.
    """
    tol = DEFAULT_CUT_TOLERANCE if tolerance is None else tolerance
    requests = {"stations": stations, "waterlines": waterlines, "buttocks": buttocks, "diagonals": diagonals}
    model = _hull_model(source)
    lo, hi = model.bounds
    extents = {
        "stations": _station_extent(source, model),
        "waterlines": (lo[2], hi[2]),
        "buttocks": (lo[1], hi[1]),
        "diagonals": (lo[2], hi[2]),
    }
    result = _cut_sections(model, requests, extents, tol)
    if collection:
        _draw_sections(source, result, {**requests, "tolerance": tol})
    return result


def _json_request(request: dict) -> dict:
    """A request as JSON values (numpy numbers and tuples made plain)."""

    def plain(v):
        if isinstance(v, int | float | str | bool) or v is None:
            return v
        if isinstance(v, np.generic):
            return v.item()
        return [plain(x) for x in v]

    return {k: plain(v) for k, v in request.items()}


def _draw_sections(source, result: dict[str, list[Section]], request: dict):
    parent = source if isinstance(source, bpy.types.Collection) else None
    return sections_draw.draw(_source_name(source), parent, all_sections(result), _json_request(request))


def refresh_sections(source) -> bool:
    """Cut again the sections drawn for the hull in ``source`` (its ``"<hull> sections"``
    collection, with the request that made them), as a rebuild does; False when none are drawn."""
    coll = sections_draw.existing(_source_name(source))
    request = coll and sections_draw.request_of(coll)
    if not request:
        return False
    tol = request.pop("tolerance", None)
    families = {k: request.get(k) for k in ("stations", "waterlines", "buttocks", "diagonals")}
    sections(source, **families, tolerance=tol, collection=True)
    return True


# --- Offsets table and section export -------------------------------------------------------------

#: The chordal tolerance (m) of the station sections an offsets table is read off: 0.1 mm, the
#: table's last decimal.
OFFSETS_TOLERANCE = 1e-4

#: The kind (in the neutral section format) of a curve of each batten role, for the curves
#: :func:`export_sections` writes beside the sections.
KIND_OF_ROLE = {"keel": "profile", "stem": "stem", "transom": "transom", "deck": "deck", "knuckle": "chine"}

#: A section's end or corner within this distance (m) of a boundary curve lies on it, for
#: :func:`export_sections` (the sections' points are polished onto the patches, whose edges are
#: the curves: measured within 1e-6 m on KCS).
EXPORT_MEET_DISTANCE = 1e-4


def _station_xs(source, model, stations) -> tuple[list[float], list[str]]:
    """Station x values and labels: a count from AP to FP inclusive (21: stations 0 to 20, as
    :func:`sectional_areas` counts them), or the x values themselves."""
    if isinstance(stations, int | np.integer) and not isinstance(stations, bool):
        if stations < 2:
            raise InvalidArgumentError(f"stations {stations} must be at least 2 (AP and FP)")
        x_ap, x_fp = _station_extent(source, model)
        xs = [float(x) for x in np.linspace(x_ap, x_fp, int(stations))]
        return xs, [str(k) for k in range(len(xs))]
    xs = finite_offsets(stations, "stations")
    if not xs:
        raise InvalidArgumentError("stations must be a count or a non-empty list of x values")
    return xs, [f"{x:.3f}" for x in xs]


def _offsets(source, family, spec, model) -> list[float]:
    lo, hi = model.bounds
    extent = {"waterlines": (lo[2], hi[2]), "buttocks": (lo[1], hi[1])}[family]
    return [p[2] for p in planes(family, spec, extent)]


def offsets_table(
    source,
    path,
    *,
    stations=21,
    waterlines=10,
    buttocks=5,
    tolerance: float = OFFSETS_TOLERANCE,
    progress: ProgressCallback | None = None,
) -> Path:
    """Write the offsets table of the hull in ``source`` to ``path`` (CSV, whole or not at all):
    the half-breadths (m) where the stations cross the waterlines and the heights (m) where
    they cross the buttocks, read off the exact station sections (within ``tolerance``, m).

    ``stations``: a count of stations equally spaced from AP to FP inclusive (21: stations 0 to
    20; AP and FP as in :func:`sections`), or their x values; ``waterlines`` and ``buttocks``:
    a count (evenly spaced over the hull's height and half-breadth, the extremes left out) or
    the heights / offsets (m). The header names the units, the axes, AP, FP and the design
    draft. An empty cell: the station does not reach that waterline or buttock (no NaN is
    written); a cell ``"a / b"``: the station crosses it more than once (see
    :mod:`batten.offsets`). Returns the path; NetworkFileError when it cannot be written,
    InvalidArgumentError for bad counts or offsets (naming the argument). ``progress``: as
    :func:`export_iges`'s (steps: the surface measured, the stations cut, the file written).
    """
    return run(_offsets_table_steps(source, path, stations, waterlines, buttocks, tolerance), progress)


def _offsets_table_steps(source, path, stations, waterlines, buttocks, tolerance):
    """:func:`offsets_table` as a job of three steps; the file written at the last."""
    model = _hull_model(source)
    yield Step("offsets table", 1, 3)
    xs, labels = _station_xs(source, model, stations)
    wls = _offsets(source, "waterlines", waterlines, model)
    bls = _offsets(source, "buttocks", buttocks, model)
    cut = sections(source, stations=xs, tolerance=tolerance)["stations"]
    yield Step("offsets table", 2, 3)
    written = _write_offsets(source, path, model, labels, cut, wls, bls, tolerance)
    yield Step("offsets table", 3, 3, final=True)
    return written


def _write_offsets(source, path, model, labels, cut, wls, bls, tolerance) -> Path:
    """The offsets table of :func:`offsets_table` from its stations ``cut``."""
    x_ap, x_fp = _station_extent(source, model)
    datums = {"x_ap": x_ap, "x_fp": x_fp, "design_draft": design_draft(source), "tolerance": tolerance}
    rows = [(label, s.offset, s.polylines) for label, s in zip(labels, cut, strict=True)]
    text = table_text(_source_name(source), rows, wls, bls, datums)
    path = file_path(path, "offsets table")
    try:
        return write_atomically(path, text)
    except OSError as e:
        raise NetworkFileError(f"offsets table '{path}': {e.strerror or e}") from e


def export_sections(
    source,
    path,
    *,
    stations=41,
    waterlines=12,
    tolerance: float = OFFSETS_TOLERANCE,
    progress: ProgressCallback | None = None,
) -> Path:
    """Write the hull in ``source`` as a section file in the neutral format that
    :func:`import_sections` reads (``shared/hulls``' JSON): its stations (``stations`` as in
    :func:`offsets_table`) and waterlines (as in :func:`sections`) cut from the exact surface
    within ``tolerance`` (m), every piece a curve of dense points (none closer than
    :func:`import_sections`' default tolerance to the last, ends and corners kept), and the hull's boundary
    curves (keel/profile, stem, transom, deck, chines: the curves with those roles), with
    ``Lpp`` and ``T`` when the collection carries them (AP at x = 0 is then assumed, as the
    format has it). The file is a consistent network (:mod:`batten.boundary_samples`): a
    boundary curve has among its points every section end and corner on it, a chine ends on
    a section or a boundary curve, and a section piece along a boundary curve, or one ending
    inside faces (cut where the surface folds, which the build reports), is left out, as is
    the stretch from a section's end to where it meets a boundary curve that it runs beside
    (a reader would join the two).
    Returns the path; NetworkFileError when it cannot be written. ``progress``: as
    :func:`export_iges`'s (steps: the surface measured, the sections cut, the file written)."""
    return run(_export_sections_steps(source, path, stations, waterlines, tolerance), progress)


def _export_sections_steps(source, path, stations, waterlines, tolerance):
    """:func:`export_sections` as a job of three steps; the file written at the last."""
    model = _hull_model(source)
    yield Step("section file", 1, 3)
    xs, _ = _station_xs(source, model, stations)
    cut = sections(source, stations=xs, waterlines=waterlines, tolerance=tolerance)
    yield Step("section file", 2, 3)
    written = _write_section_file(source, path, cut)
    yield Step("section file", 3, 3, final=True)
    return written


def _write_section_file(source, path, cut) -> Path:
    """The section file of :func:`export_sections` from its sections ``cut``."""
    network = read_curves(source)
    boundary = [c for c in network if c.role in KIND_OF_ROLE]
    curves = []
    kept: list[tuple[np.ndarray, list[int]]] = []
    for family, kind in (("stations", "station"), ("waterlines", "waterline")):
        for s in cut[family]:
            for k, pts in enumerate(s.polylines):
                if along_boundary(pts, boundary, EXPORT_MEET_DISTANCE) or is_stray(
                    pts, network, EXPORT_MEET_DISTANCE
                ):
                    continue
                name = s.name if k == 0 else f"{s.name} ({k + 1})"
                pts, corners = without_end_stretches_along(
                    pts,
                    s.corners[k],
                    boundary,
                    SECTION_CAPTURE_FACTOR * DEFAULT_SECTION_TOLERANCE,
                    EXPORT_MEET_DISTANCE,
                )
                kept.append((pts, corners))
                pts, _ = thinned(pts, corners, DEFAULT_SECTION_TOLERANCE)
                curves.append({"name": name, "kind": kind, "points": np.round(pts, 6).tolist()})
    anchors = section_anchors([p for p, _ in kept], [c for _, c in kept])
    for c in boundary:
        others = [o for o in boundary if o is not c]
        trim = c.role == "knuckle"
        pts = boundary_points(c, anchors, others, EXPORT_MEET_DISTANCE, trim_free_ends=trim)
        curves.append({"name": c.name, "kind": KIND_OF_ROLE[c.role], "points": np.round(pts, 6).tolist()})
    data = {"name": _source_name(source), "curves": curves}
    lpp, _fp = _datums(source, None, None)
    if lpp is not None:
        data["Lpp"] = lpp
    if design_draft(source) is not None:
        data["T"] = design_draft(source)
    path = file_path(path, "section file")
    try:
        return write_atomically(path, json.dumps(data))
    except OSError as e:
        raise NetworkFileError(f"section file '{path}': {e.strerror or e}") from e


#: Points each outline curve (keel, stem, transom, deck edge) is drawn through in a lines plan.
OUTLINE_SAMPLES = 200
#: The curve roles drawn as the outline of a lines plan.
OUTLINE_ROLES = ("keel", "stem", "transom", "deck")


def lines_plan_drawing(
    source,
    *,
    stations=21,
    waterlines=None,
    buttocks=None,
    diagonals=None,
    draft: float | None = None,
    lpp: float | None = None,
    fp: float | None = None,
    tolerance: float | None = None,
    collection: bool = False,
):
    """The lines plan of the hull in ``source`` (a collection) as a
    :class:`batten.drawing.Drawing` (model metres on the sheet, with its offsets tables), which
    :func:`lines_plan` writes; the arguments are :func:`lines_plan`'s (``collection`` as
    :func:`sections` takes it)."""
    from . import lines_plan as plan

    draft = design_draft(source) if draft is None else draft
    if draft is None:
        raise InvalidArgumentError(
            f"lines plan of '{_source_name(source)}': give draft= (the collection has no design draft)"
        )
    if isinstance(draft, bool) or not (isinstance(draft, int | float) and np.isfinite(draft) and draft > 0):
        raise InvalidArgumentError(f"lines plan: draft {draft!r} must be a finite height above the baseline")
    curves = read_curves(source)
    model = _hull_model(source)
    lpp, fp = _datums(source, lpp, fp)
    xs = _stations(model, draft, stations, lpp, fp)
    x_ap, x_fp = model.datums(draft, lpp, fp)
    _lo, hi = model.bounds
    secs = sections(
        source,
        stations=xs.tolist(),
        waterlines=plan.default_waterlines(draft, float(hi[2])) if waterlines is None else waterlines,
        buttocks=plan.default_buttocks(float(hi[1])) if buttocks is None else buttocks,
        diagonals=diagonals,
        tolerance=tolerance,
        collection=collection,
    )
    try:
        figures, note = hydrostatics(source, draft, lpp=lpp, fp=fp), ""
    except BattenError as e:
        figures, note = None, str(e)
    outline = [c.evaluate(np.linspace(*c.domain, OUTLINE_SAMPLES)) for c in curves if c.role in OUTLINE_ROLES]
    hull = plan.Hull(_source_name(source), float(x_ap), float(x_fp), float(draft), figures, note)
    try:
        drawing = plan.layout(secs, outline, hull)
    except ValueError as e:
        raise InvalidArgumentError(f"lines plan of '{hull.name}': {e}") from None
    drawing.tables = plan.offsets_tables(secs, hull)
    return drawing


def lines_plan(source, path, **options) -> Path:
    """Draw the lines plan of the hull in ``source`` (a collection) to ``path``: SVG, DXF (one
    layer per family: stations, waterlines, buttocks, diagonals, knuckles, outline, dwl, grid,
    title; metres at full size), PDF (A3 to a standard scale) or a PNG picture, by the suffix
    (``.svg``, ``.dxf``, ``.pdf``, ``.png``). Returns the path.

    The body plan (aft stations left of the centreline, fore ones right), the profile with the
    buttocks and the half-breadth plan with the waterlines (and the diagonals expanded, when
    asked), the knuckle lines and the outline (the keel, stem, transom and deck curves), the
    grids labelled (stations numbered 0–20 from the AP, waterline heights, buttock offsets), the
    DWL at ``draft`` (default: the collection's design draft) and a title block with the main
    dimensions and the :func:`hydrostatics` there (or why they could not be had).

    Options: the sections are :func:`sections` of the surface itself, ``stations`` a count from
    AP to FP inclusive (default 21: stations 0–20) or x values; ``waterlines`` (default: five
    up to the DWL, on at that spacing to the top) and ``buttocks`` (default: at 0.2, 0.4, 0.6,
    0.8 of the half-beam) a count or offsets, ``()`` for none; ``diagonals`` and ``tolerance``
    as :func:`sections` takes them; ``draft``; ``lpp`` and ``fp`` as in :func:`hydrostatics`.

    The file is written whole or not at all: InvalidArgumentError for another suffix, no draft,
    a bad count or offset; NetworkFileError naming the file when it cannot be written.
    ``progress=``: as :func:`export_iges`'s (steps: the drawing made, the file written).
    """
    from . import lines_plan_files

    progress = options.pop("progress", None)
    path = file_path(path, "lines plan")
    try:
        lines_plan_files.format_of(path)
    except ValueError as e:
        raise InvalidArgumentError(f"lines plan '{path}': {e}") from None
    return run(_lines_plan_steps(source, path, options), progress)


def _lines_plan_steps(source, path, options):
    """:func:`lines_plan` as a job of two steps: the drawing made, the file written."""
    drawing = lines_plan_drawing(source, **options)
    yield Step("lines plan", 1, 2)
    written = write_lines_plan(drawing, path)
    yield Step("lines plan", 2, 2, final=True)
    return written


def write_lines_plan(drawing, path) -> Path:
    """Write a :func:`lines_plan_drawing` to ``path`` in the format of its suffix (as
    :func:`lines_plan`), so one set of sections gives several files."""
    from . import lines_plan_files

    path = file_path(path, "lines plan")
    try:
        return lines_plan_files.write(drawing, path)
    except ImportError as e:
        raise InvalidArgumentError(f"lines plan '{path}': {e.name or 'ezdxf'} is not installed") from e
    except OSError as e:
        raise NetworkFileError(f"lines plan '{path}': {e.strerror or e}") from e
    except ValueError as e:
        raise InvalidArgumentError(f"lines plan '{path}': {e}") from None


def lines_plan_scene(source, **options):
    """Show the lines plan of the hull in ``source`` in Blender: a scene ``"<hull> lines
    plan"`` (made anew each time) with the drawing of :func:`lines_plan` laid flat, a
    collection per layer, and an orthographic camera over it (its render is the plan as a
    picture), and the hull's sections collection (drawn by :func:`sections`, cut again on every
    rebuild) linked in with an orthographic camera each for the profile, the half-breadth plan
    and the body plan. Options as :func:`lines_plan`'s. Returns the scene."""
    from .lines_plan_scene import sheet_scene
    from .sections_draw import existing

    drawing = lines_plan_drawing(source, collection=True, **options)
    return sheet_scene(drawing, existing(_source_name(source)))


# --- CAD exports --------------------------------------------------------------------------------


def _export(source, path, fmt: str, tolerance: float, allow_holes: bool, progress) -> Path:
    return run(_export_steps(source, path, fmt, tolerance, allow_holes), progress)


def _export_steps(source, path, fmt: str, tolerance: float, allow_holes: bool):
    """An export as a job (see :mod:`batten.cad_export` for its steps)."""
    model = _hull_model(source)
    name = _source_name(source)
    try:
        if fmt == "3dm":
            return (yield from cad_export.write_3dm(model, name, path, tolerance, allow_holes))[0]
        return (yield from cad_export.write_text_file(model, name, path, fmt, tolerance, allow_holes))[0]
    except ExportError as e:
        if not e.faces:
            raise
        faces = topology(source, tolerance=hull_models.kept_tolerance(name))["faces"]
        around = "; ".join(f"face {f}: " + ", ".join(f"'{c}'" for c in faces[f]["curves"]) for f in e.faces)
        raise ExportError(f"{e} — the curves around them: {around}", e.faces) from None


def export_iges(
    source,
    path,
    *,
    tolerance: float = DEFAULT_EXPORT_TOLERANCE,
    allow_holes: bool = False,
    progress: ProgressCallback | None = None,
) -> Path:
    """Write the hull surface of ``source`` (as :func:`build` makes it, with the last build's
    settings) to ``path`` as IGES 5.3: every patch approximated by bicubic B-spline surfaces
    (entity 128, with their parameter ranges; an N-sided patch as N quads) within
    ``tolerance`` m of batten's surface, neighbours meeting on the same curves, in metres.

    A surface whose build found holes (``hole``, ``face_not_patched`` or ``near_miss``
    warnings) raises ExportError saying so, unless ``allow_holes`` (then what exists is
    written). The file is written whole or not at all (ExportError naming it when it cannot
    be). Returns the path.

    ``progress``: ``progress(label, done, total)`` after each step (each face fitted — the
    core fits them in a worker thread —, for 3dm each face added to the document, then the file
    written); returning ``False`` before the file is written stops the fitting, raises
    :class:`Cancelled`, and no file is written (see :mod:`batten.progress`).
    """
    return _export(source, path, "iges", tolerance, allow_holes, progress)


def export_step(
    source,
    path,
    *,
    tolerance: float = DEFAULT_EXPORT_TOLERANCE,
    allow_holes: bool = False,
    progress: ProgressCallback | None = None,
) -> Path:
    """Write the hull surface of ``source`` to ``path`` as STEP AP214: one open shell of
    B-spline faces (``ADVANCED_FACE`` on ``B_SPLINE_SURFACE_WITH_KNOTS``, bounded by their
    B-spline edge curves), in metres; the faces, holes and errors as :func:`export_iges`."""
    return _export(source, path, "step", tolerance, allow_holes, progress)


def export_3dm(
    source,
    path,
    *,
    tolerance: float = DEFAULT_EXPORT_TOLERANCE,
    allow_holes: bool = False,
    progress: ProgressCallback | None = None,
) -> Path:
    """Write the hull surface of ``source`` to ``path`` as a Rhino ``.3dm`` (rhino3dm): one
    NurbsSurface object per face, in metres; the faces, holes and errors as
    :func:`export_iges`."""
    return _export(source, path, "3dm", tolerance, allow_holes, progress)


def closed_surface(source, *, tolerance: float = DEFAULT_TOLERANCE):
    """A closed mesh of the hull in ``source`` (a collection or its name, built first if it has
    no surface object yet, or the surface mesh object itself) for Blender's own exporters
    (File ▸ Export ▸ STL / Wavefront OBJ, "Selection Only"): a new object ``"<surface> closed"``
    (replacing an older one) with the surface as evaluated (the Mirror modifier applied, both
    halves) and planar lids on its open rim: the deck, and the transom (the rim's run in the
    plane of its aft end, within ``tolerance``) where the hull has one. Every edge then has
    two faces and the faces point out, so the mesh's volume is twice ``build``'s
    enclosed_volume_half (up to the split of its quads into triangles).

    An open loop below the top of the hull (a hole in the surface) raises ExportError saying
    where, and makes nothing. Returns the object."""
    if _is_mesh(source):
        surface = source
    else:
        surface = _surface_object(_source_name(source)) or build(source).object
    return closed_mesh.closed_copy(surface, tolerance)


# --- Form topology and transformations (seed 002) ------------------------------------------------


def form_topology(source, *, tolerance: float = DEFAULT_TOLERANCE, draft: float | None = None) -> dict:
    """The form topology of the hull in ``source`` (Bole, seed 002 §6): the form curves (every
    curve with a role, and the curves those end on), its ``vertices`` (``position``, ``curves``,
    ``planes``), ``edges`` (``curve``, ``t0``, ``t1``, ``start``, ``end``, ``kind``:
    ``free_form``, ``straight`` or ``blend``), ``faces`` and ``planes``, and the ``parameters``
    measured from it (§7.2.5): ``length``, ``breadth``, ``depth``, ``draft``,
    ``waterline_breadth`` (at ``draft``, default the collection's design draft),
    ``pmb_length``, ``pmb_position``, ``bilge_radius``, ``rise_of_floor``,
    ``entrance_length``, ``run_length`` — None where the hull has no such feature, with
    ``no_pmb_reason`` saying why there is no parallel middle body. Curve names are those of
    :func:`read_curves`.
    """
    curves, object_of = _read_source(source)
    draft = design_draft(source) if draft is None else draft
    with errors_named_by_object(object_of):
        return _form_topology(curves, tolerance, draft)


class TransformResult(NamedTuple):
    """What :func:`transform` returns: the copy (a new collection on the stack) and the report."""

    collection: object
    report: dict


def transform(
    source,
    *,
    breadth: float | None = None,
    depth: float | None = None,
    pmb_length: float | None = None,
    pmb_position: float | None = None,
    bilge_radius: float | None = None,
    entrance_length: float | None = None,
    run_length: float | None = None,
    moves: Iterable[tuple[int, Iterable[float]]] | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
    draft: float | None = None,
    resolution: int = CURVE_RESOLUTION,
) -> TransformResult:
    """Transform the hull collection ``source`` (an original or a copy on its stack) through its
    form topology (seed 002 §7.2) into a new copy on the stack (§9): the ``moves`` first —
    ``(vertex, (dx, dy, dz))`` with vertex indices of :func:`form_topology` —, then each given
    target value (metres) in the order of the signature. The original is not touched (until
    :func:`commit`).

    ``report``: ``steps`` (each ``what``, ``value``, ``reattached`` — curves re-attached at
    their nodes —, ``max_move``), ``before`` and ``after`` (the measured parameters),
    ``description``. Raises InvalidArgumentError for a target the hull cannot take (naming the
    parameter: no parallel middle body, no arc in the midship section, a PMB that would not
    fit …) and CurveError naming the curves when the change would break a connection; nothing
    is created then.
    """
    if not isinstance(source, bpy.types.Collection):
        raise InvalidArgumentError(f"transform needs a hull collection, got {type(source).__name__}")
    targets = [
        (name, float(value))
        for name, value in (
            ("breadth", breadth),
            ("depth", depth),
            ("pmb_length", pmb_length),
            ("pmb_position", pmb_position),
            ("bilge_radius", bilge_radius),
            ("entrance_length", entrance_length),
            ("run_length", run_length),
        )
        if value is not None
    ]
    move_list = [(int(v), tuple(float(c) for c in t)) for v, t in (moves or [])]
    if not targets and not move_list:
        raise InvalidArgumentError("transform: give a target value or moves")
    original = form_stack.original_of(source)
    curves, object_of = _read_source(source)
    draft = design_draft(original) if draft is None else draft
    with errors_named_by_object(object_of):
        new_curves, report = transform_network(curves, targets, move_list, tolerance, draft)
    description = ", ".join(
        [f"{name} {value:g} m" for name, value in targets]
        + ([f"{len(move_list)} vertex move(s)"] if move_list else [])
    )
    report["description"] = description
    sources = form_stack.source_objects(source, object_of)
    coll = form_stack.push_copy(original, new_curves, sources, description, resolution=resolution)
    _move_planes(coll, tangent_planes(source), curves, new_curves)
    return TransformResult(coll, report)


#: Stations (AP to FP inclusive) of the sectional-area curves in a hydrostatic transformation's
#: report.
SAC_STATIONS = 41


def transform_hydrostatic(
    source,
    *,
    volume: float | None = None,
    displacement: float | None = None,
    cb: float | None = None,
    cp: float | None = None,
    lcb: float | None = None,
    keep_pmb: bool | str = False,
    draft: float | None = None,
    lpp: float | None = None,
    fp: float | None = None,
    density: float = SEA_WATER_DENSITY,
    tolerance: float = DEFAULT_TOLERANCE,
    resolution: int = CURVE_RESOLUTION,
) -> TransformResult:
    """Take the hull collection ``source`` (an original or a copy on its stack) to a target
    displaced volume and LCB through its form topology (seed 002 §8). Give one of ``volume``
    (m³), ``displacement`` (t), ``cb`` or ``cp`` (linked through Cm), and/or ``lcb`` (x of the
    centre of buoyancy, m, as :func:`hydrostatics` gives it); a target not given is held at the
    hull's present value. The result is a new copy on the stack, as :func:`transform` makes
    (undo with :func:`abandon`, keep with :func:`commit`).

    Two deformations (§8.3's schedule: the first unless the PMB is held):

    - a hull with a parallel middle body has its PMB's ends moved (§8.1): the ends, the deck
      and the midship section keep their shape;
    - a hull without one, or with ``keep_pmb`` True, has the form faces of its entrance and
      run below the waterline bulged or flattened (§8.2): an offset along their normals,
      largest in the middle of each face and zero on its edges; the form curves stay;
    - ``keep_pmb="length"`` holds the PMB's length: it shifts for the LCB and both ends bulge
      alike for the volume; ``keep_pmb="position"`` holds its position: it lengthens for the
      volume and the ends bulge opposite ways for the LCB;
    - a change too large for the PMB's ends alone is combined: from the closest hull they
      reach, the ends' faces are bulged as well (``mode`` ``"pmb+bulge"``).

    Lackenby's model (general case, with a PMB), or two trial bulges, start a quasi-Newton
    iteration on batten's hydrostatics of each deformed and rebuilt hull, until ∇ is within
    1e-5 of its target and the LCB within 1e-5·Lpp. A target beyond the deformation's limits
    (the PMB, entrance and run each at least 2 % of the length, or a bulge at most a quarter of
    the half breadth; every hull building with the original's faces and no new warning, and no
    station gaining an inflection) gives the closest hull, no exception.

    ``draft``: the collection's design draft when not given. Perpendiculars as in
    :func:`hydrostatics`, held for every hull; every hull is built with the collection's
    tangent planes (:func:`tangent_planes`), as :func:`build` builds it. ``report``:
    ``before`` and ``after`` (the hydrostatics dicts), ``target_volume``, ``target_lcb``, ``entrance_length``,
    ``run_length``, ``pmb_length`` (each ``[before, after]``; None without a PMB), ``evaluations`` (hulls
    transformed, rebuilt and floated, the original's included), ``stop`` (``"converged"``,
    ``"out_of_range"`` or ``"evaluations_spent"``), ``limit`` (what stopped it), ``explored``
    (``volume`` and ``lcb`` ``[min, max]`` over the hulls evaluated), ``mode`` (``"pmb"``,
    ``"bulge"``, ``"pmb+bulge"``, ``"pmb_shift+bulge"`` or ``"pmb_length+bulge"``),
    ``bulge`` (None, or the ``offsets`` of the entrance and the run, m, and their form faces
    ``entrance_faces``, ``run_faces``), ``sac`` (``x``,
    ``before``, ``after``: the sectional areas at :data:`SAC_STATIONS` stations from AP to
    FP), ``x_ap``, ``x_fp`` and ``description``.

    Raises InvalidArgumentError for a hull with neither a PMB nor a form face of its entrance
    and run below the waterline, for no target, several volume targets, or a target that is not
    a finite positive number; HydrostaticsError when the hull does not float at the draft.
    Nothing is created then.
    """
    if not isinstance(source, bpy.types.Collection):
        kind = type(source).__name__
        raise InvalidArgumentError(f"transform_hydrostatic needs a hull collection, got {kind}")
    original = form_stack.original_of(source)
    draft = design_draft(original) if draft is None else draft
    if draft is None:
        raise InvalidArgumentError(
            f"transform_hydrostatic: collection '{original.name}' has no design draft; give draft="
        )
    lpp, fp = _datums(original, lpp, fp)
    curves, object_of = _read_source(source)
    with errors_named_by_object(object_of):
        new_curves, report = _transform_hydrostatic(
            curves,
            float(draft),
            volume=volume,
            displacement=displacement,
            cb=cb,
            cp=cp,
            lcb=lcb,
            keep_pmb=keep_pmb,
            lpp=lpp,
            fp=fp,
            density=density,
            tolerance=tolerance,
            tangent_planes=tangent_planes(source),
        )
    asked = [
        f"{name} {value:g}"
        for name, value in (("∇", volume), ("Δ", displacement), ("Cb", cb), ("Cp", cp), ("LCB", lcb))
        if value is not None
    ]
    how = {
        "pmb": "PMB ends",
        "bulge": "bulged ends",
        "pmb+bulge": "PMB ends and bulged ends",
        "pmb_shift+bulge": "PMB shifted, ends bulged",
        "pmb_length+bulge": "PMB lengthened, ends bulged",
    }[report["mode"]]
    report["description"] = f"hydrostatic ({how}): " + ", ".join(asked)
    sources = form_stack.source_objects(source, object_of)
    coll = form_stack.push_copy(original, new_curves, sources, report["description"], resolution=resolution)
    _move_planes(coll, tangent_planes(source), curves, new_curves)
    datums = {"lpp": report["x_fp"] - report["x_ap"], "fp": report["x_fp"]}
    xs = np.linspace(report["x_ap"], report["x_fp"], SAC_STATIONS)
    report["sac"] = {
        "x": xs,
        "before": sectional_areas(source, draft, xs, **datums)[1],
        "after": sectional_areas(coll, draft, xs, **datums)[1],
    }
    return TransformResult(coll, report)


def transform_stack(source) -> list[dict]:
    """The transformation stack of ``source`` (an original or one of its copies, seed 002 §9):
    the original first, then its copies in order, each ``{"collection", "index"`` (0 for the
    original), ``"description"}`` (what the change was; the original's is ``"original"``)."""
    original = form_stack.original_of(source)
    return [{"collection": original, "index": 0, "description": "original"}] + [
        {
            "collection": c,
            "index": int(c.get(form_stack.TRANSFORM_INDEX, 0)),
            "description": str(c.get(form_stack.TRANSFORM_DESCRIPTION, "")),
        }
        for c in form_stack.stack(original)
    ]


def _copy_collection(result, what: str) -> bpy.types.Collection:
    """The copy collection of ``result`` (a :class:`TransformResult` or a collection);
    InvalidArgumentError when it is no copy on a transformation stack."""
    copy = result.collection if isinstance(result, TransformResult) else result
    if isinstance(copy, str):
        if copy not in bpy.data.collections:
            raise InvalidArgumentError(f"{what}: no collection '{copy}'")
        copy = bpy.data.collections[copy]
    if not isinstance(copy, bpy.types.Collection):
        raise InvalidArgumentError(f"{what} needs a transformation copy, got {type(copy).__name__}")
    if form_stack.original_of(copy) is copy:
        raise InvalidArgumentError(f"collection '{copy.name}' is not a transformation copy")
    return copy


def compare(
    result,
    *,
    draft: float | None = None,
    stations: int = 21,
    density: float = SEA_WATER_DENSITY,
    tolerance: float = DEFAULT_TOLERANCE,
) -> dict:
    """A copy on the transformation stack beside its original (seed 002 §9): ``result`` is a
    :class:`TransformResult`, a copy collection or its name. Both hulls are measured afresh at ``draft``
    (default: the original's design draft), upright and level, in water of ``density``.

    Perpendiculars: the original's (its ``batten_lpp`` / ``batten_fp``, else its level
    waterline's ends); the copy's are those moved as far as each end of its waterline moved
    (:mod:`batten.form_compare`), so both hulls' coefficients and centres are on comparable bases.

    Returns a dict: ``original`` and ``copy`` (collection names), ``description`` (the change),
    ``draft``, ``density``, ``perpendiculars`` (``{"original": (x_ap, x_fp), "copy": …}``),
    ``dimensions`` and ``hydrostatics`` (rows of ``key``, ``label``, ``unit``, ``fmt``,
    ``original``, ``copy``, ``change``, ``change_pct``; a dimension the hull does not have is
    None), ``form_errors`` (per hull, why its form could not be measured, if so) and ``sac``
    (``{"original": (xs, areas), "copy": (xs, areas)}``: ``stations`` equally spaced stations
    from each hull's AP to its FP). Nothing is changed in the scene.

    Raises InvalidArgumentError when ``result`` is no copy, no draft is given and the original
    has none, or ``stations`` < 2; HydrostaticsError (naming where) when a hull cannot float at
    the draft.
    """
    copy = _copy_collection(result, "compare")
    original = form_stack.original_of(copy)
    if draft is None:
        draft = design_draft(original)
        if draft is None:
            raise InvalidArgumentError(
                f"compare: the original '{original.name}' has no design draft; "
                "give draft= (m above the baseline)"
            )
    draft = float(draft)
    if not math.isfinite(draft):
        raise InvalidArgumentError(f"compare: draft {draft} is not a number")
    if int(stations) < 2:
        raise InvalidArgumentError(f"stations {stations} must be at least 2 (AP and FP)")
    hulls = {"original": original, "copy": copy}
    models = {key: _hull_model(coll, measured=False) for key, coll in hulls.items()}
    lpp, fp = _datums(original, None, None)
    ends = {key: tuple(model.datums(draft, None, None)) for key, model in models.items()}
    if fp is None:
        ours = tuple(models["original"].datums(draft, lpp, None))
    else:
        ours = (fp - lpp, fp)
    moved = form_compare.moved_perpendiculars(ours, ends["original"], ends["copy"])
    perpendiculars = {"original": ours, "copy": moved}
    figures, sac, forms, form_errors = {}, {}, {}, {}
    for key, model in models.items():
        x_ap, x_fp = perpendiculars[key]
        figures[key] = model.hydrostatics(draft, 0.0, 0.0, density, x_fp - x_ap, x_fp, False)
        xs = np.linspace(x_ap, x_fp, int(stations))
        sac[key] = (xs, np.asarray(model.sectional_areas(draft, xs.tolist(), 0.0, 0.0, x_fp - x_ap, x_fp)))
        try:
            forms[key] = form_topology(hulls[key], tolerance=tolerance, draft=draft)["parameters"]
        except BattenError as e:
            forms[key], form_errors[key] = {}, str(e)
    return {
        "original": original.name,
        "copy": copy.name,
        "description": str(copy.get(form_stack.TRANSFORM_DESCRIPTION, "")),
        "draft": draft,
        "density": float(density),
        "perpendiculars": perpendiculars,
        "dimensions": form_compare.rows(form_compare.DIMENSIONS, forms["original"], forms["copy"]),
        "hydrostatics": form_compare.rows(form_compare.HYDROSTATICS, figures["original"], figures["copy"]),
        "form_errors": form_errors,
        "sac": sac,
    }


def commit(result) -> bpy.types.Collection:
    """Apply the copy of ``result`` (a :class:`TransformResult` or a copy collection) to its
    original: every original curve object gets the copy's splines (objects, names, roles,
    materials kept; all or none), then the stack is dropped. Returns the original."""
    copy = result.collection if isinstance(result, TransformResult) else result
    original = form_stack.original_of(copy)
    if original is copy:
        raise InvalidArgumentError(f"collection '{copy.name}' is not a transformation copy")
    curves, object_of = _read_source(copy)
    curves_out.replace_splines_of(form_stack.replacements(copy, curves, object_of))
    if TANGENT_PLANES_PROPERTY in copy:
        original[TANGENT_PLANES_PROPERTY] = tangent_planes(copy)
    # The refitted curves have new parameters: attached ends reference their points again.
    hierarchy.refresh([o for o in bpy.data.objects if o.type == "CURVE"])
    form_stack.drop_stack(original)
    return original


def abandon(source) -> int:
    """Drop every copy on the transformation stack of ``source`` (an original or one of its
    copies); the original stays as it is. Returns the number of copies removed."""
    return form_stack.drop_stack(form_stack.original_of(source))


def keep(result) -> bpy.types.Collection:
    """Keep the copy of ``result`` (a :class:`TransformResult` or a copy collection) as a new
    hull of its own, off the stack (seed 002 §9); the original and the other copies stay.
    Returns the collection."""
    copy = result.collection if isinstance(result, TransformResult) else result
    if form_stack.original_of(copy) is copy:
        raise InvalidArgumentError(f"collection '{copy.name}' is not a transformation copy")
    form_stack.release(copy)
    return copy
