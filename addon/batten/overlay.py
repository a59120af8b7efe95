"""Viewport overlay: curvature combs on the selected curves; the form topology last measured
(its edges by kind and its numbered vertices); the curves' point attributes (knuckles,
tangents, straights, blends) and attached points; and from the last build markers
on the network's nodes, T-joints, dangling ends, near misses and other problems, and the
knuckle edges as thick lines, the automatically found ones in their own colour, and the water
surface at the Hydrostatics panel's draft, trim and heel (drawn only, nothing stored).

The comb geometry comes from :func:`batten.api.curvature_comb`, the markers and knuckle lines
from the scene's last build report (through :mod:`batten.network_markers`); this module only
turns them into batches for the GPU. The water surface is the plane of the flotation
(:mod:`batten.waterplane_outline`) drawn as a semi-transparent rectangle over the hull's box,
with the perpendiculars of the last figures (the box's ends before any).
"""

import json

import bpy
import numpy as np

from . import api, attribute_marks, hierarchy
from .network_markers import knuckle_segments, marker_arrays
from .scene_hydro import hull_box, last_figures
from .waterplane_outline import waterplane_outline

_handle = None
_label_handle = None


def comb_lines(context) -> np.ndarray:
    """Line segment end points (2k, 3), float32: every tooth (base → tip) and the comb's
    outline (tip → next tip) of each selected curve, or an empty array."""
    settings = context.scene.batten
    segments = []
    for obj in context.selected_objects:
        if obj.type != "CURVE":
            continue
        try:
            bases, tips = api.curvature_comb(obj, scale=settings.comb_scale)
        except api.BattenError:
            continue  # a broken curve draws no comb; the build reports it
        teeth = np.stack([bases, tips], axis=1).reshape(-1, 3)
        outline = np.stack([tips[:-1], tips[1:]], axis=1).reshape(-1, 3)
        segments += [teeth, outline]
    if not segments:
        return np.zeros((0, 3), dtype=np.float32)
    return np.concatenate(segments).astype(np.float32)


# Marker kinds of the build report (network_markers.MARKER_KINDS): colour, point size (px).
MARKER_STYLES = {
    "nodes": ((0.1, 0.6, 1.0, 1.0), 6.0),
    "t_joints": ((0.2, 0.85, 0.3, 1.0), 10.0),
    "dangling_ends": ((1.0, 0.85, 0.1, 1.0), 12.0),
    "near_misses": ((1.0, 0.2, 0.85, 1.0), 14.0),
    "holes": ((0.6, 0.2, 1.0, 1.0), 16.0),
    "folds": ((1.0, 0.5, 0.0, 1.0), 16.0),
    "problems": ((1.0, 0.15, 0.1, 1.0), 12.0),
}
# Knuckle edges by source (network_markers.KNUCKLE_SOURCES; "role": the curve's role, "auto":
# found at corners of crossing curves): colour, line width (px).
KNUCKLE_STYLES = {
    "role": ((1.0, 0.5, 0.0, 1.0), 4.0),
    "auto": ((0.0, 0.9, 0.9, 1.0), 4.0),
}


# Point attributes (attribute_marks.attribute_marks): colour, point size or line width (px).
ATTRIBUTE_POINT_STYLES = {
    "knuckle": ((1.0, 0.5, 0.0, 1.0), 12.0),
    "attached": ((0.75, 0.75, 0.75, 1.0), 9.0),
}
ATTRIBUTE_LINE_STYLES = {
    "tangent": ((1.0, 0.95, 0.3, 1.0), 3.0),
    "straight": ((0.3, 0.9, 0.4, 1.0), 4.0),
    "blend": ((0.45, 0.6, 1.0, 1.0), 4.0),
}


def attribute_mark_arrays(context) -> dict[str, np.ndarray]:
    """The point attributes and attached points of the scene's hull curves (all the scene's
    curves when no hull is chosen): :func:`batten.attribute_marks.attribute_marks`."""
    source = context.scene.batten.source
    objects = source.all_objects if source is not None else context.scene.objects
    return attribute_marks.attribute_marks(
        o
        for o in objects
        if o.type == "CURVE" and (hierarchy.ATTACHMENTS in o or hierarchy.POINT_ATTRIBUTES in o)
    )


_parsed = ("", {})  # the last report text and its parse (the overlay redraws every frame)


def _last_report(context) -> dict:
    global _parsed
    text = context.scene.batten.last_report
    if text != _parsed[0]:
        _parsed = (text, json.loads(text) if text else {})
    return _parsed[1]


def markers(context) -> dict[str, np.ndarray]:
    """Marker positions from the last build, each (n, 3) float32, by kind: ``nodes``,
    ``t_joints``, ``dangling_ends``, ``near_misses``, ``holes``, ``folds``, ``problems``."""
    return marker_arrays(_last_report(context).get("markers", {}))


def knuckle_lines(context) -> dict[str, np.ndarray]:
    """Line segment end points (2k, 3), float32, along the knuckle edges of the last build,
    by source: ``role`` and ``auto``."""
    return knuckle_segments(_last_report(context).get("knuckle_edges", []))


#: The water surface: fill and outline colours, outline width (px).
WATER_FILL = (0.1, 0.45, 0.85, 0.25)
WATER_EDGE = (0.05, 0.35, 0.8, 0.9)
WATER_EDGE_WIDTH = 2.0


def water_surface(context) -> np.ndarray:
    """The corners (4, 3), float32, of the water surface at the scene's draft, trim and heel
    over the hull's box (both sides when mirrored), or an empty array (no hull, or Waterline
    off)."""
    settings = context.scene.batten
    if not settings.show_waterline or settings.source is None:
        return np.zeros((0, 3), dtype=np.float32)
    try:
        lo, hi = hull_box(settings.source)
    except api.BattenError:
        return np.zeros((0, 3), dtype=np.float32)
    if settings.mirror:
        lo[1] = -max(abs(lo[1]), abs(hi[1]))
        hi[1] = -lo[1]
    figures = last_figures(settings)
    corners = waterplane_outline(
        lo,
        hi,
        draft=settings.draft,
        trim=settings.trim,
        heel_deg=np.degrees(settings.heel),
        x_ap=figures.get("x_ap"),
        x_fp=figures.get("x_fp"),
    )
    return corners.astype(np.float32)


def _draw_water(context) -> None:
    import gpu
    from gpu_extras.batch import batch_for_shader

    corners = water_surface(context)
    if not len(corners):
        return
    gpu.state.blend_set("ALPHA")
    fill = gpu.shader.from_builtin("UNIFORM_COLOR")
    fill.uniform_float("color", WATER_FILL)
    batch_for_shader(fill, "TRIS", {"pos": corners}, indices=((0, 1, 2), (0, 2, 3))).draw(fill)
    edge = gpu.shader.from_builtin("POLYLINE_UNIFORM_COLOR")
    edge.uniform_float("viewportSize", gpu.state.viewport_get()[2:])
    edge.uniform_float("lineWidth", WATER_EDGE_WIDTH)
    edge.uniform_float("color", WATER_EDGE)
    batch_for_shader(edge, "LINE_LOOP", {"pos": corners}).draw(edge)
    gpu.state.blend_set("NONE")


#: Form edges by kind (seed 002 §7.2: free-form edges stop a translation, straight edges pass
#: its part across the line, blends pass it whole): colour, line width (px).
FORM_EDGE_STYLES = {
    "free_form": ((0.55, 0.55, 0.65, 1.0), 3.0),
    "straight": ((0.15, 0.75, 0.35, 1.0), 3.0),
    "blend": ((0.95, 0.55, 0.1, 1.0), 3.0),
}
#: Form vertices: colour, point size (px); their numbers' colour and size (px).
FORM_VERTEX_STYLE = ((0.9, 0.1, 0.45, 1.0), 11.0)
FORM_LABEL_STYLE = ((1.0, 1.0, 1.0, 1.0), 13)
#: The original's curves beside a compared copy: colour (RGBA) and line width (pixels).
COMPARISON_STYLE = ((0.2, 0.8, 0.95, 1.0), 1.5)
#: The drag of a form vertex: colour and line width (pixels).
DRAG_STYLE = ((1.0, 0.85, 0.1, 1.0), 2.5)

_parsed_form = ("", {})


def _last_form(context) -> dict:
    """The form last measured for the scene's hull (empty for another hull, or Show Form off)."""
    global _parsed_form
    settings = context.scene.batten
    if not settings.show_form or settings.source is None:
        return {}
    text = settings.last_form
    if text != _parsed_form[0]:
        _parsed_form = (text, json.loads(text) if text else {})
    form = _parsed_form[1]
    return form if form.get("source") == settings.source.name else {}


def form_lines(context) -> dict[str, np.ndarray]:
    """Line segment end points (2k, 3), float32, along the form edges last measured, by kind:
    ``free_form``, ``straight``, ``blend``."""
    out = {kind: [] for kind in FORM_EDGE_STYLES}
    for edge in _last_form(context).get("edges", []):
        pts = np.asarray(edge["points"], dtype=np.float32)
        if edge["kind"] in out and len(pts) > 1:
            out[edge["kind"]].append(np.stack([pts[:-1], pts[1:]], axis=1).reshape(-1, 3))
    return {k: np.concatenate(v) if v else np.zeros((0, 3), dtype=np.float32) for k, v in out.items()}


def form_vertices(context) -> np.ndarray:
    """The form vertices last measured (n, 3), float32, in their numbering."""
    vertices = _last_form(context).get("vertices", [])
    return np.asarray(vertices, dtype=np.float32).reshape(-1, 3)


_parsed_comparison = ("", {})


def comparison_lines(context) -> np.ndarray:
    """Line segment end points (2k, 3), float32, along the original's curves of the last
    comparison, while its copy is the scene's hull and Show Original is on (else none)."""
    global _parsed_comparison
    settings = context.scene.batten
    if not settings.show_comparison or settings.source is None:
        return np.zeros((0, 3), dtype=np.float32)
    text = settings.last_comparison
    if text != _parsed_comparison[0]:
        _parsed_comparison = (text, json.loads(text) if text else {})
    comparison = _parsed_comparison[1]
    if comparison.get("copy") != settings.source.name:
        return np.zeros((0, 3), dtype=np.float32)
    segments = [
        np.stack([pts[:-1], pts[1:]], axis=1).reshape(-1, 3)
        for pts in (np.asarray(line, dtype=np.float32) for line in comparison.get("ghost", []))
        if len(pts) > 1
    ]
    return np.concatenate(segments) if segments else np.zeros((0, 3), dtype=np.float32)


def drag_lines() -> np.ndarray:
    """The form vertex being dragged (:mod:`batten.form_drag`): a segment from where it was to
    where it goes, (2, 3) float32; none while nothing is dragged."""
    from . import form_drag

    if form_drag.preview is None:
        return np.zeros((0, 3), dtype=np.float32)
    return np.asarray(form_drag.preview, dtype=np.float32).reshape(2, 3)


def _draw_form_labels():
    """Each form vertex's number beside it (pixel space)."""
    context = bpy.context
    if getattr(context.scene, "batten", None) is None or context.region_data is None:
        return
    vertices = form_vertices(context)
    if not len(vertices):
        return
    import blf
    from bpy_extras.view3d_utils import location_3d_to_region_2d

    color, size = FORM_LABEL_STYLE
    blf.size(0, size)
    blf.color(0, *color)
    for i, v in enumerate(vertices):
        at = location_3d_to_region_2d(context.region, context.region_data, tuple(map(float, v)))
        if at is not None:
            blf.position(0, at.x + 8, at.y + 6, 0)
            blf.draw(0, str(i))


def _draw():
    context = bpy.context
    settings = getattr(context.scene, "batten", None)
    if settings is None:
        return
    import gpu
    from gpu_extras.batch import batch_for_shader

    _draw_water(context)
    ghost = comparison_lines(context)
    if len(ghost):
        wide = gpu.shader.from_builtin("POLYLINE_UNIFORM_COLOR")
        wide.uniform_float("viewportSize", gpu.state.viewport_get()[2:])
        _draw_styled(wide, "LINES", "lineWidth", {"original": ghost}, {"original": COMPARISON_STYLE})
    drag = drag_lines()
    if len(drag):
        wide = gpu.shader.from_builtin("POLYLINE_UNIFORM_COLOR")
        wide.uniform_float("viewportSize", gpu.state.viewport_get()[2:])
        _draw_styled(wide, "LINES", "lineWidth", {"drag": drag}, {"drag": DRAG_STYLE})
        dots = gpu.shader.from_builtin("POINT_UNIFORM_COLOR")
        _draw_styled(dots, "POINTS", "size", {"v": drag[1:]}, {"v": FORM_VERTEX_STYLE})
    form_edges = form_lines(context)
    if any(len(v) for v in form_edges.values()):
        wide = gpu.shader.from_builtin("POLYLINE_UNIFORM_COLOR")
        wide.uniform_float("viewportSize", gpu.state.viewport_get()[2:])
        _draw_styled(wide, "LINES", "lineWidth", form_edges, FORM_EDGE_STYLES)
        dots = gpu.shader.from_builtin("POINT_UNIFORM_COLOR")
        _draw_styled(dots, "POINTS", "size", {"v": form_vertices(context)}, {"v": FORM_VERTEX_STYLE})
    shader = gpu.shader.from_builtin("UNIFORM_COLOR")
    if settings.show_combs:
        lines = comb_lines(context)
        if len(lines):
            batch = batch_for_shader(shader, "LINES", {"pos": lines})
            shader.uniform_float("color", (0.85, 0.2, 0.6, 1.0))
            batch.draw(shader)
    if not settings.show_network:
        return
    # Thick lines need the polyline shader (core-profile GPU backends ignore line_width_set).
    wide = gpu.shader.from_builtin("POLYLINE_UNIFORM_COLOR")
    wide.uniform_float("viewportSize", gpu.state.viewport_get()[2:])
    _draw_styled(wide, "LINES", "lineWidth", knuckle_lines(context), KNUCKLE_STYLES)
    marks = attribute_mark_arrays(context)
    _draw_styled(
        wide, "LINES", "lineWidth", {k: marks[k] for k in ATTRIBUTE_LINE_STYLES}, ATTRIBUTE_LINE_STYLES
    )
    dots = gpu.shader.from_builtin("POINT_UNIFORM_COLOR")
    _draw_styled(dots, "POINTS", "size", markers(context), MARKER_STYLES)
    _draw_styled(
        dots, "POINTS", "size", {k: marks[k] for k in ATTRIBUTE_POINT_STYLES}, ATTRIBUTE_POINT_STYLES
    )


def _draw_styled(shader, primitive: str, size_uniform: str, groups: dict, styles: dict):
    """Draw each non-empty group of positions with its style's colour and size (line width
    or point size, set through ``size_uniform``)."""
    from gpu_extras.batch import batch_for_shader

    for kind, pos in groups.items():
        if len(pos):
            color, size = styles[kind]
            shader.uniform_float(size_uniform, size)
            shader.uniform_float("color", color)
            batch_for_shader(shader, primitive, {"pos": pos}).draw(shader)


def register():
    """Add the draw handlers (once): the 3D one, and the form vertices' numbers in pixels."""
    global _handle, _label_handle
    if _handle is None:
        _handle = bpy.types.SpaceView3D.draw_handler_add(_draw, (), "WINDOW", "POST_VIEW")
    if _label_handle is None:
        _label_handle = bpy.types.SpaceView3D.draw_handler_add(_draw_form_labels, (), "WINDOW", "POST_PIXEL")


def unregister():
    """Remove the draw handlers."""
    global _handle, _label_handle
    if _handle is not None:
        bpy.types.SpaceView3D.draw_handler_remove(_handle, "WINDOW")
        _handle = None
    if _label_handle is not None:
        bpy.types.SpaceView3D.draw_handler_remove(_label_handle, "WINDOW")
        _label_handle = None
