"""The curve network hierarchy (seed 002 §5, §7.1) and the curves' surface attributes: a
curve may be held in a plane (a midship section in its station plane, a flat of side curve in
the side's plane); and a curve's end may reference a point of
another curve (its parent); when the parent changes, the end follows it, and the child's free
control points follow by the elastic rule of Fig. 6; descendants update in hierarchy order
(parents before children), so a change at the top of the hierarchy runs down through it.

An attachment is stored on the child object as the custom property ``batten_attachments``: a
JSON list of ``{"end": "start" | "end", "parent": <object name>, "t": <parameter on the
parent>}``, so it stays with the .blend. The referenced point is the parent's point at ``t``
(world coordinates): moving the parent's control points carries it along; to slide an end
along its parent, attach it again.

The elastic rule (Fig. 6): the control points of the child's spline between its two ends (its
anchors) move by the anchors' translations blended by their normalised chord distance along the
control polygon, ``Δ(t) = (1 − t)·Δ0 + t·Δn``; an end that is not attached is an anchor that
stays. A Bézier spline's handles move with their control point. The new control points are
computed for every child first and written all or none. A curve held in a plane has its
control points moved into it last (after its ends followed their parents), so it stays planar
whatever drags it.
"""

from __future__ import annotations

import json
from graphlib import CycleError, TopologicalSorter

import bpy
import numpy as np
from batten_native import CurveError, InvalidArgumentError

from .bridge import curves_in

#: Object property: the attachments of a curve object's ends (JSON list).
ATTACHMENTS = "batten_attachments"
#: Object property: the plane a curve object is held in (its surface attribute, JSON
#: ``{"normal": [x, y, z], "offset": d}``, the plane ``normal · p = d`` in world coordinates).
PLANE = "batten_plane"
#: The ends a curve can attach.
ENDS = ("start", "end")
#: Blender keeps curve points in single precision: an end within this many of its units in
#: the last place of its target is on it (a smaller move cannot be held, and writing it would
#: only shift the free points by the rounding, again at every update).
STILL_ULPS = 4.0
#: How far (m) an end may be from the curve it is attached to, by default.
ATTACH_DISTANCE = 0.01


def attachments_of(obj) -> list[dict]:
    """The attachments stored on ``obj`` (an empty list when it has none)."""
    text = obj.get(ATTACHMENTS)
    return json.loads(text) if text else []


def store(obj, attachments: list[dict]) -> None:
    """Store ``attachments`` on ``obj`` (the property is removed when the list is empty)."""
    if attachments:
        obj[ATTACHMENTS] = json.dumps(attachments)
    elif ATTACHMENTS in obj:
        del obj[ATTACHMENTS]


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


def still(point) -> float:
    """The largest move (m) of ``point`` that is no move: the rounding of Blender's single
    precision there (:data:`STILL_ULPS` units in the last place of its largest coordinate)."""
    return STILL_ULPS * float(np.finfo(np.float32).eps) * max(float(np.abs(point).max()), 1.0)


def elastic(anchors: np.ndarray, delta0: np.ndarray, delta1: np.ndarray) -> np.ndarray:
    """The translations of the control polygon ``anchors`` (n, 3) by the elastic rule (Fig. 6):
    ``delta0`` at the first point and ``delta1`` at the last, blended by the normalised chord
    distance along the polygon (by index where the polygon has no length)."""
    n = len(anchors)
    chords = np.linalg.norm(np.diff(anchors, axis=0), axis=1)
    total = float(chords.sum())
    if total > 0.0:
        t = np.concatenate([[0.0], np.cumsum(chords)]) / total
    else:
        t = np.linspace(0.0, 1.0, n) if n > 1 else np.zeros(1)
    return (1.0 - t)[:, None] * np.asarray(delta0)[None, :] + t[:, None] * np.asarray(delta1)[None, :]


def _spline_points(spline) -> dict[str, np.ndarray]:
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


def _write(spline, arrays: dict[str, np.ndarray]) -> None:
    points = spline.bezier_points if spline.type == "BEZIER" else spline.points
    for attr, values in arrays.items():
        points.foreach_set(attr, values.astype(np.float32).ravel())
    spline.id_data.update_tag()


def graph(objects) -> dict[str, set[str]]:
    """Each curve object of ``objects`` with attachments or a plane: the parents it references."""
    found = ((o, attachments_of(o)) for o in objects)
    return {o.name: {a["parent"] for a in made} for o, made in found if made or o.get(PLANE)}


def order(objects) -> list[str]:
    """The attached curve objects of ``objects`` (and those held in a plane) in hierarchy order
    (every parent before its children); CurveError naming the curves of a cycle."""
    try:
        ordered = list(TopologicalSorter(graph(objects)).static_order())
    except CycleError as e:
        cycle = list(dict.fromkeys(e.args[1]))
        raise CurveError(
            f"curves {', '.join(repr(c) for c in cycle)} reference each other in a cycle: "
            "a curve cannot be its own ancestor",
            cycle[0],
        ) from e
    children = set(graph(objects))
    return [name for name in ordered if name in children]


def plane_of(obj) -> tuple[np.ndarray, float] | None:
    """The plane ``(unit normal, offset)`` the curve object ``obj`` is held in (its surface
    attribute), or None."""
    text = obj.get(PLANE)
    if not text:
        return None
    plane = json.loads(text)
    return np.asarray(plane["normal"], dtype=float), float(plane["offset"])


def store_plane(obj, plane: tuple[np.ndarray, float] | None) -> None:
    """Hold ``obj`` in ``plane`` (unit normal, offset), or release it (None)."""
    if plane is None:
        if PLANE in obj:
            del obj[PLANE]
        return
    normal, offset = plane
    obj[PLANE] = json.dumps({"normal": [float(c) for c in normal], "offset": float(offset)})


def control_points_world(obj) -> np.ndarray:
    """Every control point of ``obj``'s spline (with a Bézier spline's handles), world (n, 3)."""
    matrix = np.array(obj.matrix_world, dtype=float)
    arrays = _spline_points(single_spline(obj))
    pts = np.concatenate([a[:, :3] for a in arrays.values()])
    return pts @ matrix[:3, :3].T + matrix[:3, 3]


def new_points(obj) -> dict[str, np.ndarray] | None:
    """The new point arrays of the child ``obj``'s spline (object space) that put its attached
    ends on their parents' points and its free points where the elastic rule takes them; None
    when nothing moves. CurveError naming the curve when a parent is gone."""
    spline = single_spline(obj)
    deltas = {}
    for a in attachments_of(obj):
        parent = bpy.data.objects.get(a["parent"])
        if parent is None or parent.type != "CURVE":
            raise CurveError(
                f"curve '{obj.name}': its {a['end']} is attached to '{a['parent']}', which is gone", obj.name
            )
        curve = curves_in.read_object(parent)[0]
        lo, hi = curve.domain
        target = np.asarray(curve.evaluate([min(max(a["t"], lo), hi)]), dtype=float).reshape(3)
        deltas[a["end"]] = target - end_point(obj, a["end"])
    plane = plane_of(obj)
    matrix = np.array(obj.matrix_world, dtype=float)
    to_local = np.linalg.inv(matrix[:3, :3])
    arrays = _spline_points(spline)
    world = {attr: a[:, :3] @ matrix[:3, :3].T + matrix[:3, 3] for attr, a in arrays.items()}
    moved = {attr: w.copy() for attr, w in world.items()}
    if deltas:
        # The elastic rule over the control polygon; a Bézier point's handles move with it.
        moves = elastic(world["co"], deltas.get("start", np.zeros(3)), deltas.get("end", np.zeros(3)))
        for w in moved.values():
            w += moves
    if plane is not None:
        # The surface attribute: every control point into the plane (the curve, an affine
        # combination of them, lies in it then).
        normal, offset = plane
        for w in moved.values():
            w -= np.outer(w @ normal - offset, normal)
    if all(
        np.abs(moved[k] - world[k]).max(initial=0.0) <= still(np.abs(world[k]).max(initial=0.0))
        for k in world
    ):
        return None
    out = {attr: values.copy() for attr, values in arrays.items()}
    for attr, values in out.items():
        values[:, :3] = (moved[attr] - matrix[:3, 3]) @ to_local.T
    return out


def update(objects) -> list[str]:
    """Update every attached curve of ``objects`` in hierarchy order (each from its parents as
    they are after their own update), all or none. Returns the names of the curves that moved."""
    names = order(objects)
    written: list[tuple[object, dict]] = []  # (spline, its arrays before) to restore
    moved = []
    try:
        for name in names:
            obj = bpy.data.objects[name]
            arrays = new_points(obj)
            if arrays is None:
                continue
            spline = single_spline(obj)
            written.append((spline, _spline_points(spline)))
            _write(spline, arrays)
            moved.append(name)
    except BaseException:
        for spline, before in reversed(written):
            _write(spline, before)
        raise
    return moved


def attach(child, parent, end: str, tolerance: float) -> dict:
    """Attach ``child``'s ``end`` (``start``, ``end``, or ``nearest``: the end nearer to
    ``parent``) to the point of ``parent`` nearest to it, which must be within ``tolerance``
    (m). Replaces that end's former attachment. Returns the attachment. InvalidArgumentError
    for an unknown end; CurveError naming the curve for a child that is its parent, a parent
    that descends from the child, or an end too far from the parent."""
    if end not in (*ENDS, "nearest"):
        raise InvalidArgumentError(f"end '{end}' is none of start, end, nearest")
    single_spline(child)
    if child == parent:
        raise CurveError(f"curve '{child.name}' cannot attach to itself", child.name)
    parent_curve = curves_in.read_object(parent)[0]
    found = {e: parent_curve.nearest(end_point(child, e)) for e in ENDS}
    if end == "nearest":
        end = min(ENDS, key=lambda e: found[e][1])
    t, distance, _ = found[end]
    if distance > tolerance:
        raise CurveError(
            f"curve '{child.name}': its {end} is {distance:.4g} m from '{parent.name}' (more than "
            f"{tolerance:g} m); move it onto the curve first",
            child.name,
        )
    attachment = {"end": end, "parent": parent.name, "t": float(t)}
    others = [a for a in attachments_of(child) if a["end"] != end]
    store(child, [*others, attachment])
    try:
        order([o for o in bpy.data.objects if o.type == "CURVE"])
    except CurveError:
        store(child, others)
        raise
    return attachment


def refresh(objects) -> int:
    """Take again, for each attachment of ``objects`` whose end lies on its parent (within
    :data:`ATTACH_DISTANCE`), the parent's parameter nearest to that end: after the parent's
    curve was replaced (a committed transformation refits curves, and its parameters change),
    the attachment references the same point again. Returns how many were refreshed."""
    count = 0
    for obj in objects:
        kept = attachments_of(obj)
        for a in kept:
            parent = bpy.data.objects.get(a["parent"])
            if parent is None or parent.type != "CURVE":
                continue
            t, distance, _ = curves_in.read_object(parent)[0].nearest(end_point(obj, a["end"]))
            if distance <= ATTACH_DISTANCE:
                a["t"] = float(t)
                count += 1
        store(obj, kept)
    return count
