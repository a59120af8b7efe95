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

import bpy
from batten_native import DEFAULT_TOLERANCE, ROLES, BattenError, Curve, network_from_json, network_to_json

from .bridge import curves_in, curves_out

__all__ = [
    "DEFAULT_TOLERANCE",
    "ROLES",
    "BattenError",
    "Curve",
    "curve_objects",
    "export_network",
    "load_network",
    "read_network",
    "read_curves",
    "set_role",
]


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
    coll = bpy.data.collections.new(coll_name)
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
