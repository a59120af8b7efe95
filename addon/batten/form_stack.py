"""The transformation stack of seed 002 §9: every change of a hull makes a copy (a new
collection beside the original, with a description), the original stays untouched until the
designer commits a copy to it or abandons the stack.

A copy is a collection with ``batten_transform_of`` (the original collection's name),
``batten_transform_index`` (its place on the stack) and ``batten_transform_description``; each
of its curve objects carries ``batten_transform_source``: the original object it stands for.
"""

from __future__ import annotations

import bpy
from batten_native import Curve, InvalidArgumentError

from .bridge import curves_out

#: Collection property: the name of the original hull collection a copy was made from.
TRANSFORM_OF = "batten_transform_of"
#: Collection property: the copy's place on its original's stack (1, 2, …).
TRANSFORM_INDEX = "batten_transform_index"
#: Collection property: what the change was.
TRANSFORM_DESCRIPTION = "batten_transform_description"
#: Object property: the original curve object a copy's object stands for.
TRANSFORM_SOURCE = "batten_transform_source"


def original_of(coll) -> bpy.types.Collection:
    """The original hull collection of ``coll`` (itself when it is no copy); InvalidArgumentError
    when the original is gone."""
    name = coll.get(TRANSFORM_OF)
    if name is None:
        return coll
    original = bpy.data.collections.get(name)
    if original is None:
        raise InvalidArgumentError(f"collection '{coll.name}': its original '{name}' no longer exists")
    return original


def stack(original) -> list:
    """The copies of ``original`` on its stack, in order."""
    copies = [c for c in bpy.data.collections if c.get(TRANSFORM_OF) == original.name]
    return sorted(copies, key=lambda c: int(c.get(TRANSFORM_INDEX, 0)))


def source_objects(coll, object_of: dict[str, str]) -> dict[str, str]:
    """For each curve name of ``coll`` (``object_of``: curve name → object name), the original
    object it stands for."""
    out = {}
    for curve_name, obj_name in object_of.items():
        obj = bpy.data.objects.get(obj_name)
        out[curve_name] = obj.get(TRANSFORM_SOURCE, obj_name) if obj is not None else obj_name
    return out


def copy_name(source: str, index: int) -> str:
    """The name of the copy of curve object ``source`` on copy ``index`` of a stack."""
    return f"{source} T{index}"


def push_copy(original, curves: list[Curve], sources: dict[str, str], description: str, *, resolution: int):
    """Draw ``curves`` as a new copy on ``original``'s stack (all objects or none). Returns the
    collection."""
    index = 1 + max((int(c.get(TRANSFORM_INDEX, 0)) for c in stack(original)), default=0)
    coll = bpy.data.collections.new(f"{original.name} transform {index}")
    created = []
    try:
        for curve in curves:
            source = sources.get(curve.name, curve.name)
            # Named for its original and the copy ("wl_z10.80 T1"): Blender would make a
            # second "wl_z10.80" into "wl_z10.001", taking ".80" for a counter, so a copy's
            # report would name curves the designer cannot find.
            obj = curves_out.new_curve_object(
                curve.renamed(copy_name(source, index)), coll, resolution=resolution
            )
            obj[TRANSFORM_SOURCE] = source
            created.append(obj)
        coll[TRANSFORM_OF] = original.name
        coll[TRANSFORM_INDEX] = index
        coll[TRANSFORM_DESCRIPTION] = description
        bpy.context.scene.collection.children.link(coll)
    except BaseException:
        _remove(coll)
        raise
    return coll


def _remove(coll) -> None:
    """Remove a copy collection with its objects and their curve data."""
    for obj in list(coll.objects):
        data = obj.data
        bpy.data.objects.remove(obj)
        if data is not None and data.users == 0:
            bpy.data.curves.remove(data)
    bpy.data.collections.remove(coll)


def drop_stack(original) -> int:
    """Remove every copy on ``original``'s stack; returns how many."""
    copies = stack(original)
    for c in copies:
        _remove(c)
    return len(copies)


def replacements(copy, curves: list[Curve], object_of: dict[str, str]) -> list[tuple[object, list[Curve]]]:
    """The original objects with the copy's curves that replace their splines, in order;
    InvalidArgumentError naming the object when an original is gone."""
    grouped: dict[str, list[Curve]] = {}
    for curve in curves:
        obj = bpy.data.objects[object_of[curve.name]]
        grouped.setdefault(obj.get(TRANSFORM_SOURCE, obj.name), []).append(curve)
    out = []
    for name, group in grouped.items():
        target = bpy.data.objects.get(name)
        if target is None or target.type != "CURVE":
            raise InvalidArgumentError(
                f"collection '{copy.name}': the original curve object '{name}' is gone"
            )
        out.append((target, group))
    return out


def release(copy) -> None:
    """Take ``copy`` off its stack: it becomes a hull of its own."""
    for key in (TRANSFORM_OF, TRANSFORM_INDEX, TRANSFORM_DESCRIPTION):
        copy.pop(key, None)
    for obj in copy.objects:
        obj.pop(TRANSFORM_SOURCE, None)
