"""Drag a form vertex with the mouse (seed 002 §7.2, interactive change): click one of the
numbered form vertices the overlay draws, move the mouse — in the view plane through the
vertex, or along X, Y or Z once that key is pressed —, and click again (or press Enter) to make
the change into a copy on the transformation stack, as *Move Vertex* does with a typed
translation. Right-click or Esc ends it with nothing changed; the viewport can be navigated
while no vertex is picked.

The translation is previewed in the overlay (a line from the vertex to where it goes); the
network is transformed once, on release, by :func:`batten.api.transform`, so a move the hull
cannot take is refused as a typed one is, with nothing created.
"""

from __future__ import annotations

import json

import bpy
import numpy as np

from . import api
from ._registry import register_classes, unregister_classes
from .form_operators import move_vertex_into_copy

#: How near (pixels) the click must be to a form vertex to pick it.
PICK_RADIUS = 24.0
#: The axis keys and their directions.
AXES = {"X": (1.0, 0.0, 0.0), "Y": (0.0, 1.0, 0.0), "Z": (0.0, 0.0, 1.0)}

#: What the overlay draws while a vertex is dragged: ``(start, end)`` (world), or None.
preview: tuple[np.ndarray, np.ndarray] | None = None


def pick_vertex(points_2d: list, mouse, radius: float = PICK_RADIUS) -> int | None:
    """The index of the point of ``points_2d`` (region pixels; None for a point behind the
    view) nearest to ``mouse``, if it is within ``radius`` pixels; else None."""
    best, best_d = None, radius
    for i, p in enumerate(points_2d):
        if p is None:
            continue
        d = float(np.hypot(p[0] - mouse[0], p[1] - mouse[1]))
        if d <= best_d:
            best, best_d = i, d
    return best


def constrained(delta, axis: str | None) -> np.ndarray:
    """``delta`` as it is (no axis), or its component along the world axis ``axis``."""
    delta = np.asarray(delta, dtype=float)
    if axis is None:
        return delta
    direction = np.asarray(AXES[axis])
    return direction * float(delta @ direction)


def main_view(context):
    """``(region, region_3d)`` of the 3D viewport the operator runs in (its main region, also
    when started from the sidebar), or None outside a 3D viewport."""
    area = getattr(context, "area", None)
    if area is None or area.type != "VIEW_3D":
        return None
    region = next((r for r in area.regions if r.type == "WINDOW"), None)
    return None if region is None else (region, area.spaces.active.region_3d)


def to_region(view, point):
    """Where the world ``point`` is in the view's region (pixels), or None behind the view."""
    from bpy_extras.view3d_utils import location_3d_to_region_2d

    region, rv3d = view
    at = location_3d_to_region_2d(region, rv3d, tuple(map(float, point)))
    return None if at is None else (at.x, at.y)


def to_world(view, mouse, depth) -> np.ndarray:
    """The world point under ``mouse`` (region pixels) in the view plane through ``depth``."""
    from bpy_extras.view3d_utils import region_2d_to_location_3d

    region, rv3d = view
    return np.array(region_2d_to_location_3d(region, rv3d, mouse, tuple(map(float, depth))))


def measured_vertices(context) -> np.ndarray:
    """The form vertices last measured for the scene's hull, (n, 3), in their numbering (none
    when its form was not measured)."""
    settings = context.scene.batten
    if settings.source is None or not settings.last_form:
        return np.zeros((0, 3))
    form = json.loads(settings.last_form)
    if form.get("source") != settings.source.name:
        return np.zeros((0, 3))
    return np.asarray(form.get("vertices", []), dtype=float).reshape(-1, 3)


class BATTEN_OT_drag_form_vertex(bpy.types.Operator):
    """Click a numbered form vertex in the viewport and move it with the mouse (X, Y or Z to
    move along that axis); click again or press Enter to make the change into a copy on the
    stack; right-click or Esc to leave it"""

    bl_idname = "batten.drag_form_vertex"
    bl_label = "Drag Vertex"
    bl_options = {"REGISTER", "UNDO", "BLOCKING"}

    @classmethod
    def poll(cls, context):
        return len(measured_vertices(context)) > 0

    def begin(self, context, view) -> None:
        """Start: nothing picked yet."""
        self._view = view
        self._vertices = measured_vertices(context)
        self._index = None
        self._grab = None  # the world point under the mouse when the vertex was picked
        self._delta = np.zeros(3)
        self._axis = None

    def invoke(self, context, event):
        view = main_view(context)
        if view is None:
            self.report({"ERROR"}, "Drag Vertex works in a 3D viewport")
            return {"CANCELLED"}
        self.begin(context, view)
        context.window_manager.modal_handler_add(self)
        self._status(context)
        return {"RUNNING_MODAL"}

    def _mouse(self, event):
        region = self._view[0]
        return (event.mouse_x - region.x, event.mouse_y - region.y)

    def _status(self, context) -> None:
        area = getattr(context, "area", None)
        if area is None:
            return
        if self._index is None:
            text = "Click a form vertex to drag it (Esc or right-click: leave)"
        else:
            axis = f" along {self._axis}" if self._axis else ""
            d = self._delta
            text = (
                f"Form vertex {self._index}{axis}: Δ ({d[0]:+.3f}, {d[1]:+.3f}, {d[2]:+.3f}) m — "
                "X/Y/Z: axis, click or Enter: apply, Esc or right-click: leave"
            )
        area.header_text_set(text)
        area.tag_redraw()

    def _end(self, context, result: set[str]) -> set[str]:
        global preview
        preview = None
        area = getattr(context, "area", None)
        if area is not None:
            area.header_text_set(None)
            area.tag_redraw()
        return result

    def modal(self, context, event):
        global preview
        if event.type in {"RIGHTMOUSE", "ESC"} and event.value == "PRESS":
            return self._end(context, {"CANCELLED"})
        mouse = self._mouse(event)
        if self._index is None:
            if event.type == "LEFTMOUSE" and event.value == "PRESS":
                index = pick_vertex([to_region(self._view, p) for p in self._vertices], mouse)
                if index is None:
                    return {"RUNNING_MODAL"}  # a click beside every vertex picks nothing
                self._index = index
                self._grab = to_world(self._view, mouse, self._vertices[index])
                preview = (self._vertices[index], self._vertices[index])
                self._status(context)
                return {"RUNNING_MODAL"}
            return {"PASS_THROUGH"}  # navigate the view until a vertex is picked
        start = self._vertices[self._index]
        if event.type in AXES and event.value == "PRESS":
            self._axis = None if self._axis == event.type else event.type
        if event.type in {"MOUSEMOVE", *AXES}:
            self._delta = constrained(to_world(self._view, mouse, start) - self._grab, self._axis)
            preview = (start, start + self._delta)
            self._status(context)
            return {"RUNNING_MODAL"}
        if (event.type == "LEFTMOUSE" and event.value == "PRESS") or (
            event.type in {"RET", "NUMPAD_ENTER"} and event.value == "PRESS"
        ):
            return self._end(context, self._apply(context))
        return {"RUNNING_MODAL"}

    def _apply(self, context) -> set[str]:
        settings = context.scene.batten
        if not np.any(self._delta):
            self.report({"INFO"}, "The vertex did not move: nothing changed")
            return {"CANCELLED"}
        move = tuple(float(c) for c in self._delta)
        try:
            result = move_vertex_into_copy(settings, self._index, move)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"'{result.collection.name}': form vertex {self._index} moved {move}")
        return {"FINISHED"}


_CLASSES = (BATTEN_OT_drag_form_vertex,)


def register():
    """Register the drag operator."""
    register_classes(_CLASSES)


def unregister():
    """Remove it."""
    unregister_classes(_CLASSES)
