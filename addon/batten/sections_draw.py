"""A hull's sections drawn as curve objects in the collection ``"<hull> sections"`` (a child of
the hull's collection), replaced whole on every redraw; the request that made them kept on the
collection so a rebuild can cut them again."""

from __future__ import annotations

import json

import bpy

from .bridge import curves_out
from .object_names import blender_name

#: Custom property marking a curve object as a drawn section (output, never a hull curve).
SECTION_TAG = "batten_section"

#: Custom property of a sections collection: the JSON of the request that cut its sections.
REQUEST_PROPERTY = "batten_sections_request"


def collection_name(hull: str) -> str:
    """The name of the sections collection of the hull ``hull``."""
    return f"{hull} sections"


def existing(hull: str):
    """The sections collection of ``hull``, or None."""
    return bpy.data.collections.get(blender_name(collection_name(hull)))


def request_of(coll) -> dict | None:
    """The request kept on a sections collection (None when it has none)."""
    text = coll.get(REQUEST_PROPERTY)
    if not isinstance(text, str):
        return None
    try:
        request = json.loads(text)
    except json.JSONDecodeError:
        return None
    return request if isinstance(request, dict) else None


def draw(hull: str, parent, sections, request: dict):
    """Draw ``sections`` (each with curves) as curve objects, one per section named after it,
    in the sections collection of ``hull`` (made as a child of ``parent``, or of the scene's
    collection when None), replacing what it held; keep ``request`` on it. Returns it."""
    coll = existing(hull)
    if coll is None:
        coll = bpy.data.collections.new(blender_name(collection_name(hull)))
        (parent if parent is not None else bpy.context.scene.collection).children.link(coll)
    for obj in list(coll.objects):
        data = obj.data
        bpy.data.objects.remove(obj)
        if data is not None and data.users == 0:
            bpy.data.curves.remove(data)
    for section in sections:
        if not section.curves:
            continue
        obj = curves_out.new_curves_object(blender_name(section.name), section.curves, coll)
        obj[SECTION_TAG] = section.family
    coll[REQUEST_PROPERTY] = json.dumps(request)
    return coll
