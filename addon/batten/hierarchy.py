"""The curve network hierarchy (seed 002 §5, §7.1) and the curves' surface attributes: a
curve may be held in a plane (a midship section in its station plane, a flat of side curve in
the side's plane); and a curve's end may reference a point of
another curve (its parent); when the parent changes, the end follows it, and the child's free
control points follow by the elastic rule of Fig. 6; descendants update in hierarchy order
(parents before children), so a change at the top of the hierarchy runs down through it.

An attachment is stored on the child object as the custom property ``batten_attachments``: a
JSON list of ``{"end": "start" | "end", "parent": <object name>, "t": <parameter on the
parent>[, "offset": [dx, dy, dz]]}``, so it stays with the .blend. The referenced point is the
parent's point at ``t`` (world coordinates), plus the offset the child's point had from it when
attached where the two curves already met there (:func:`attach`): moving the parent's control
points carries it along; to slide an end along its parent, attach it again.

The elastic rule (Fig. 6): the control points of the child's spline between its two ends (its
anchors) move by the anchors' translations blended by their normalised chord distance along the
control polygon, ``Δ(t) = (1 − t)·Δ0 + t·Δn``; an end that is not attached is an anchor that
stays. A Bézier spline's handles move with their control point. The new control points are
computed for every child first and written all or none. A curve held in a plane has its
control points moved into it last (after its ends followed their parents), so it stays planar
whatever drags it.

A point the curve passes through (a *joint*: a Bézier point, or every third control point of a
cubic NURBS spline with end-point and Bézier knots) may be attached too (``{"point": <joint
index>, ...}`` in place of ``"end"``): a station through a chine or a flat of side. The elastic
rule then runs piecewise between consecutive anchors (the ends and the attached points).

Point attributes (:mod:`batten.point_attributes`) are stored on the object as
``batten_point_attributes`` (a JSON list of ``{"kind", "point"[, "direction"]}``) and shape the
handles at their joints after the elastic rule. Curve attributes act on the points attached to
a curve: a parent of role ``knuckle`` makes them knuckle points, and a parent held in a plane
with the *tangent* curve attribute (``batten_tangent``) makes the curves attached to it enter
the plane tangentially (their tangent there loses its component along the plane's normal).
"""

from __future__ import annotations

import json
from graphlib import CycleError, TopologicalSorter

import bpy
import numpy as np
from batten_native import CurveError, InvalidArgumentError

from . import point_attributes, spline_split
from .bridge import curves_in
from .spline_joints import (
    crossing,
    end_point,
    joint_arrays,
    joint_layout,
    joint_points,
    single_spline,
    spline_points,
    write_points,
)

#: Object property: the attachments of a curve object's ends (JSON list).
ATTACHMENTS = "batten_attachments"
#: Object property: the plane a curve object is held in (its surface attribute, JSON
#: ``{"normal": [x, y, z], "offset": d}``, the plane ``normal · p = d`` in world coordinates).
PLANE = "batten_plane"
#: Object property: the point attributes of a curve object (JSON list).
POINT_ATTRIBUTES = "batten_point_attributes"
#: Object property: the curve's *tangent* curve attribute (curves attached to it enter its plane
#: tangentially).
TANGENT = "batten_tangent"
#: The ends a curve can attach.
ENDS = ("start", "end")
#: Blender keeps curve points in single precision: an end within this many of its units in
#: the last place of its target is on it (a smaller move cannot be held, and writing it would
#: only shift the free points by the rounding, again at every update).
STILL_ULPS = 4.0
#: How far (m) an end may be from the curve it is attached to, by default.
ATTACH_DISTANCE = 0.01


def _stored(obj, key: str, valid) -> object | None:
    """The JSON value stored on ``obj`` under ``key`` (None when there is none); CurveError
    naming the curve and the property when it is no JSON or ``valid(value)`` is false (a
    property edited by hand: nothing reads it half-way)."""
    text = obj.get(key)
    if not text:
        return None
    try:
        value = json.loads(text) if isinstance(text, str) else None
        ok = value is not None and valid(value)
    except (ValueError, TypeError, KeyError):
        ok = False
    if not ok:
        raise CurveError(
            f"curve '{obj.name}': its property '{key}' is not what batten stores there; delete it "
            "(or undo the edit) and set it again from the Form panel",
            obj.name,
        )
    return value


def _finite(v) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and np.isfinite(v)


def _index(v) -> bool:
    return isinstance(v, int) and not isinstance(v, bool) and v >= 0


def _vector(v) -> bool:
    return isinstance(v, list) and len(v) == 3 and all(_finite(c) for c in v)


def _valid_attachment(a) -> bool:
    return (
        isinstance(a, dict)
        and (a.get("end") in ENDS if "end" in a else _index(a.get("point")))
        and isinstance(a.get("parent"), str)
        and _finite(a.get("t"))
        and ("offset" not in a or _vector(a["offset"]))
    )


def _valid_attribute(a) -> bool:
    return (
        isinstance(a, dict)
        and a.get("kind") in point_attributes.KINDS
        and _index(a.get("point"))
        and (a["kind"] != "tangent" or _vector(a.get("direction")))
    )


def attachments_of(obj) -> list[dict]:
    """The attachments stored on ``obj`` (an empty list when it has none); CurveError naming
    the curve when the stored property is not a list of attachments."""
    value = _stored(obj, ATTACHMENTS, lambda v: isinstance(v, list) and all(map(_valid_attachment, v)))
    return value or []


def store(obj, attachments: list[dict]) -> None:
    """Store ``attachments`` on ``obj`` (the property is removed when the list is empty)."""
    if attachments:
        obj[ATTACHMENTS] = json.dumps(attachments)
    elif ATTACHMENTS in obj:
        del obj[ATTACHMENTS]


def point_attributes_of(obj) -> list[dict]:
    """The point attributes stored on ``obj`` (an empty list when it has none); CurveError
    naming the curve when the stored property is not a list of point attributes."""
    value = _stored(obj, POINT_ATTRIBUTES, lambda v: isinstance(v, list) and all(map(_valid_attribute, v)))
    return value or []


def store_point_attributes(obj, attributes: list[dict]) -> None:
    """Store ``attributes`` on ``obj`` (the property is removed when the list is empty)."""
    if attributes:
        obj[POINT_ATTRIBUTES] = json.dumps(attributes)
    elif POINT_ATTRIBUTES in obj:
        del obj[POINT_ATTRIBUTES]


def has_tangent(obj) -> bool:
    """Whether ``obj`` carries the tangent curve attribute."""
    return bool(obj.get(TANGENT))


def store_tangent(obj, on: bool) -> None:
    """Give ``obj`` the tangent curve attribute, or take it away."""
    if on:
        obj[TANGENT] = 1
    elif TANGENT in obj:
        del obj[TANGENT]


def anchor(attachment: dict) -> str:
    """What an attachment holds, for a person: ``start``, ``end`` or ``point 3``."""
    return attachment["end"] if "end" in attachment else f"point {attachment['point']}"


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


def graph(objects) -> dict[str, set[str]]:
    """Each curve object of ``objects`` with attachments, a plane or point attributes: the
    parents it references."""
    found = ((o, attachments_of(o)) for o in objects)
    return {
        o.name: {a["parent"] for a in made}
        for o, made in found
        if made or o.get(PLANE) or o.get(POINT_ATTRIBUTES)
    }


def order(objects) -> list[str]:
    """The attached curve objects of ``objects`` (and those held in a plane or with point
    attributes) in hierarchy order
    (every parent before its children); CurveError naming the curves of a cycle."""
    parents = graph(objects)
    try:
        ordered = list(TopologicalSorter(parents).static_order())
    except CycleError as e:
        cycle = list(dict.fromkeys(e.args[1]))
        raise CurveError(
            f"curves {', '.join(repr(c) for c in cycle)} reference each other in a cycle: "
            "a curve cannot be its own ancestor",
            cycle[0],
        ) from e
    return [name for name in ordered if name in parents]


def plane_of(obj) -> tuple[np.ndarray, float] | None:
    """The plane ``(unit normal, offset)`` the curve object ``obj`` is held in (its surface
    attribute), or None; CurveError naming the curve when the stored property is no plane."""
    plane = _stored(
        obj,
        PLANE,
        lambda v: (
            isinstance(v, dict) and _vector(v.get("normal")) and any(v["normal"]) and _finite(v.get("offset"))
        ),
    )
    if plane is None:
        return None
    normal = np.asarray(plane["normal"], dtype=float)
    length = float(np.linalg.norm(normal))
    return normal / length, float(plane["offset"]) / length


def store_plane(obj, plane: tuple[np.ndarray, float] | None) -> None:
    """Hold ``obj`` in ``plane`` (unit normal, offset), or release it (None)."""
    if plane is None:
        if PLANE in obj:
            del obj[PLANE]
        return
    normal, offset = plane
    obj[PLANE] = json.dumps({"normal": [float(c) for c in normal], "offset": float(offset)})


def _parent(obj, attachment: dict):
    parent = bpy.data.objects.get(attachment["parent"])
    if parent is None or parent.type != "CURVE":
        raise CurveError(
            f"curve '{obj.name}': its {anchor(attachment)} is attached to '{attachment['parent']}', "
            "which is gone",
            obj.name,
        )
    return parent


def _parent_point(parent, t: float) -> np.ndarray:
    curve = curves_in.read_object(parent)[0]
    lo, hi = curve.domain
    return np.asarray(curve.evaluate([min(max(t, lo), hi)]), dtype=float).reshape(3)


def _needs_joints(obj, attachments: list[dict]) -> bool:
    if point_attributes_of(obj) or any("point" in a for a in attachments):
        return True
    parents = (bpy.data.objects.get(a["parent"]) for a in attachments)
    return any(p is not None and has_tangent(p) for p in parents)


def _joint_of(obj, attachment: dict, count: int) -> int:
    if "end" in attachment:
        return 0 if attachment["end"] == "start" else count - 1
    k = attachment["point"]
    if not 0 <= k < count:
        raise CurveError(
            f"curve '{obj.name}': its point {k} is attached to '{attachment['parent']}', but the curve "
            f"has points 0..{count - 1} now",
            obj.name,
        )
    return k


def _inherited(obj, attachments: list[dict], count: int) -> list[dict]:
    """The point attributes ``obj``'s attached points take from their parents' curve
    attributes: a knuckle from a knuckle curve, a tangent (direction found later) from a curve
    with the tangent attribute held in a plane."""
    out = []
    for a in attachments:
        parent = _parent(obj, a)
        k = _joint_of(obj, a, count)
        if curves_in.role_of(parent) == "knuckle" and "point" in a:
            out.append({"kind": "knuckle", "point": k})
        plane = plane_of(parent)
        if has_tangent(parent) and plane is not None:
            out.append({"kind": "tangent", "point": k, "plane_normal": plane[0]})
    return out


def _attributed(obj, moved: dict[str, np.ndarray], index: np.ndarray, handles: bool, inherited) -> None:
    """Shape the handles at ``obj``'s joints by its point attributes and those its parents'
    curve attributes give (in place on the world arrays ``moved``)."""
    own = point_attributes_of(obj)
    if not own and not inherited:
        return
    co, left, right, put = joint_arrays(moved, index)
    attributes = [dict(a) for a in own]
    kinds = {(a["kind"], a["point"]) for a in attributes}
    for a in inherited:
        if a["kind"] == "tangent":
            d = point_attributes.through(co, left, right, a["point"])
            d = point_attributes.tangent_in_plane(d, a["plane_normal"])
            if d is None:
                raise CurveError(
                    f"curve '{obj.name}': at its point {a['point']} it runs square to the plane of the "
                    "curve it is attached to, so it cannot enter that plane tangentially",
                    obj.name,
                )
            a = {"kind": "tangent", "point": a["point"], "direction": d.tolist()}
        if (a["kind"], a["point"]) not in kinds:
            attributes.append(a)
            kinds.add((a["kind"], a["point"]))
    if not handles:
        shaped = sorted({a["kind"] for a in attributes} - {"knuckle", "straight"})
        if shaped:
            raise CurveError(
                f"curve '{obj.name}': a {shaped[0]} needs handles, and its POLY spline has none "
                "(it is straight between its points with a corner at each)",
                obj.name,
            )
        return
    try:
        put(*point_attributes.apply(co, left, right, attributes))
    except point_attributes.AttributeConflict as e:
        raise CurveError(f"curve '{obj.name}': {e}", obj.name) from None


def new_points(obj) -> dict[str, np.ndarray] | None:
    """The new point arrays of the child ``obj``'s spline (object space) that put its attached
    ends and points on their parents' points and its free points where the elastic rule takes
    them, shape its handles by its point attributes and its parents' curve attributes, and
    hold it in its plane; None when nothing moves. CurveError naming the curve when a parent is
    gone or the attributes cannot be met."""
    spline = single_spline(obj)
    attachments = attachments_of(obj)
    plane = plane_of(obj)
    matrix = np.array(obj.matrix_world, dtype=float)
    to_local = np.linalg.inv(matrix[:3, :3])
    arrays = spline_points(spline)
    world = {attr: a[:, :3] @ matrix[:3, :3].T + matrix[:3, 3] for attr, a in arrays.items()}
    moved = {attr: w.copy() for attr, w in world.items()}
    index, handles = joint_layout(spline, obj.name) if _needs_joints(obj, attachments) else (None, False)
    last = len(world["co"]) - 1
    deltas = {}  # control polygon index -> translation
    for a in attachments:
        target = _parent_point(_parent(obj, a), a["t"]) + np.asarray(a.get("offset", (0.0, 0.0, 0.0)))
        if "end" in a:
            deltas[0 if a["end"] == "start" else last] = target - end_point(obj, a["end"])
        else:
            at = int(index[_joint_of(obj, a, len(index))])
            deltas[at] = target - world["co"][at]
    if deltas:
        # The elastic rule over the control polygon, piecewise between the anchors (an end
        # not attached stays); a Bézier point's handles move with it.
        anchors = sorted({0, last, *deltas})
        moves = np.zeros_like(world["co"])
        for lo, hi in zip(anchors, anchors[1:], strict=False):
            moves[lo : hi + 1] = elastic(
                world["co"][lo : hi + 1], deltas.get(lo, np.zeros(3)), deltas.get(hi, np.zeros(3))
            )
        for w in moved.values():
            w += moves
    if index is not None:
        _attributed(obj, moved, index, handles, _inherited(obj, attachments, len(index)))
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
            written.append((spline, spline_points(spline)))
            write_points(spline, arrays)
            moved.append(name)
    except BaseException:
        for spline, before in reversed(written):
            write_points(spline, before)
        raise
    return moved


def attach(
    child, parent, end: str, tolerance: float, point: int | str | None = None, meet: float = 0.0
) -> dict:
    """Attach ``child``'s ``end`` (``start``, ``end``, or ``nearest``: the end nearer to
    ``parent``) to the point of ``parent`` nearest to it, which must be within ``tolerance``
    (m); or, with ``point`` (a joint index, or ``nearest``), that point of the child in place of
    an end. ``nearest`` is the point where the child's curve passes nearest the parent (a
    station where it crosses a chine); where the child has no point within ``tolerance`` of
    there, its spline gets one, its shape unchanged (:mod:`batten.spline_split`). Replaces that
    end's or point's former attachment. Returns the attachment. InvalidArgumentError for an
    unknown end or point; CurveError naming the curve for a child that is its parent, a parent
    that descends from the child, or an end, point or curve too far from the parent.

    Where the child's curve already passes within ``meet`` (m) of the parent's point (the two
    meet there, to the model tolerance, though the child's point itself may lie a little
    aside: a station's joint a fraction of a millimetre from where it crosses a fitted flat
    of bottom curve), the attachment keeps the point's ``offset`` from the parent's point and
    nothing moves: moving the child onto it would move its other meetings off their curves.
    Farther off, the point is moved onto the parent."""
    if end not in (*ENDS, "nearest"):
        raise InvalidArgumentError(f"end '{end}' is none of start, end, nearest")
    single_spline(child)
    if child == parent:
        raise CurveError(f"curve '{child.name}' cannot attach to itself", child.name)
    parent_curve = curves_in.read_object(parent)[0]
    if point is None:
        found = {e: parent_curve.nearest(end_point(child, e)) for e in ENDS}
        if end == "nearest":
            end = min(ENDS, key=lambda e: found[e][1])
        t, distance, _ = found[end]
        key, what, here = {"end": end}, f"its {end}", end_point(child, end)
    else:
        joints = joint_points(child)
        if point == "nearest":
            point, split_at = _crossing_joint(child, parent_curve, joints, tolerance)
            if split_at is not None:
                return _attach_split(child, parent, parent_curve, point, split_at)
        elif isinstance(point, bool) or not isinstance(point, int) or not 0 <= point < len(joints):
            raise InvalidArgumentError(
                f"point {point!r} of curve '{child.name}' is none of 0..{len(joints) - 1}, 'nearest'"
            )
        t, distance, _ = parent_curve.nearest(joints[point])
        key, what, here = {"point": int(point)}, f"its point {point}", joints[point]
    if distance > tolerance:
        raise CurveError(
            f"curve '{child.name}': {what} is {distance:.4g} m from '{parent.name}' (more than "
            f"{tolerance:g} m); move it onto the curve first",
            child.name,
        )
    attachment = {**key, "parent": parent.name, "t": float(t)}
    on_parent = np.asarray(parent_curve.evaluate([t]), dtype=float).reshape(3)
    if distance > still(here) and curves_in.read_object(child)[0].nearest(on_parent)[1] <= meet:
        attachment["offset"] = (here - on_parent).tolist()
    others = [a for a in attachments_of(child) if anchor(a) != anchor(attachment)]
    store(child, [*others, attachment])
    try:
        order([o for o in bpy.data.objects if o.type == "CURVE"])
    except CurveError:
        store(child, others)
        raise
    return attachment


def _crossing_joint(child, parent_curve, joints: np.ndarray, tolerance: float):
    """``(joint, None)``: the child's point at (within ``tolerance`` of) where its curve passes
    nearest the parent; or ``(piece, u)`` where no point of it is there and the piece must be
    split at ``u`` to give one."""
    child_curve = curves_in.read_object(child)[0]
    t, here, distance = crossing(child_curve, parent_curve)
    if distance > tolerance:
        raise CurveError(
            f"curve '{child.name}' passes {distance:.4g} m from '{parent_curve.name}' at the nearest (more "
            f"than {tolerance:g} m); move it onto the curve first",
            child.name,
        )
    gaps = np.linalg.norm(joints - here, axis=1)
    k = int(np.argmin(gaps))
    if gaps[k] <= tolerance:
        return k, None
    a, _ = child_curve.domain
    piece = min(int(np.floor(t - a)), len(joints) - 2)
    return piece, (t - a) - piece


def _attach_split(child, parent, parent_curve, piece: int, u: float) -> dict:
    """Give ``child`` a point where its curve crosses ``parent`` (piece ``piece`` at ``u``, its
    shape unchanged) and attach that point; the child's attributes and attachments of later
    points move up one, and the curves attached to the child take their parameters again."""
    new = piece + 1
    attributes = point_attributes_of(child)
    if any(a["kind"] == "blend" and a["point"] == piece for a in attributes):
        raise CurveError(
            f"curve '{child.name}' crosses '{parent.name}' inside its blend from point {piece}; "
            "a blend has no point inside it",
            child.name,
        )
    shifted = []
    for a in attributes:
        a = dict(a)
        if a["point"] >= new:
            a["point"] += 1
        shifted.append(a)
        if a["kind"] == "straight" and a["point"] == piece:
            shifted.append({"kind": "straight", "point": new})  # both halves straight
    own = [
        {**a, "point": a["point"] + 1} if "point" in a and a["point"] >= new else a
        for a in attachments_of(child)
    ]
    before = attachments_of(child)
    attachment = {"point": new, "parent": parent.name, "t": 0.0}
    store(child, [*own, attachment])
    try:
        order([o for o in bpy.data.objects if o.type == "CURVE"])
    except CurveError:
        store(child, before)
        raise
    spline_split.split(single_spline(child), piece, u)
    store_point_attributes(child, shifted)
    t, distance, _ = parent_curve.nearest(joint_points(child)[new])
    attachment["t"] = float(t)
    store(child, [*own, attachment])
    # The curves attached to the child: its parameters moved on by one piece after the split.
    refresh(
        o
        for o in bpy.data.objects
        if o.type == "CURVE" and any(a["parent"] == child.name for a in attachments_of(o))
    )
    return attachment


def _joint_point(obj, k: int) -> np.ndarray | None:
    try:
        joints = joint_points(obj)
    except CurveError:
        return None
    return joints[k] if 0 <= k < len(joints) else None


def refresh(objects) -> int:
    """Take again, for each attachment of ``objects`` whose end or point lies on its parent
    (within :data:`ATTACH_DISTANCE`), the parent's parameter nearest to it: after the parent's
    curve was replaced (a committed transformation refits curves, and its parameters change),
    the attachment references the same point again. Returns how many were refreshed."""
    count = 0
    for obj in objects:
        try:
            kept = attachments_of(obj)
        except CurveError:
            continue  # a property edited by hand: Build names it
        for a in kept:
            parent = bpy.data.objects.get(a["parent"])
            if parent is None or parent.type != "CURVE":
                continue
            here = end_point(obj, a["end"]) if "end" in a else _joint_point(obj, a["point"])
            if here is None:
                continue
            curve = curves_in.read_object(parent)[0]
            t, distance, _ = curve.nearest(here)
            if distance <= ATTACH_DISTANCE:
                a["t"] = float(t)
                if "offset" in a:
                    a["offset"] = (here - np.asarray(curve.evaluate([t]), dtype=float).reshape(3)).tolist()
                count += 1
        store(obj, kept)
    return count
