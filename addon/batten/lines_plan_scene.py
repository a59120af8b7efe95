"""The lines plan shown in Blender: a :class:`~batten.drawing.Drawing` laid flat in a scene of
its own, one curve object per layer and a text object per label, seen by an orthographic
camera from above and rendered flat (Workbench), so the designer reads the plan — the same
lines as the exported files — without leaving Blender."""

from __future__ import annotations

import bpy
import numpy as np

from .drawing import DASH, EM_PER_CAP, LAYER_STYLE, LAYERS, Drawing, baseline, dashes

#: Custom property marking the collections and objects a lines plan scene holds.
PLAN_TAG = "batten_lines_plan"
#: Blender's text alignments for the drawing's.
ALIGN_X = {"left": "LEFT", "center": "CENTER", "right": "RIGHT"}
#: The camera's picture: this many pixels wide (its height from the drawing's shape).
RENDER_WIDTH = 2400
#: Share of the drawing's size left around it in the camera's frame.
FRAME_MARGIN = 0.03
#: The camera looks down from this height over the sheet (it is orthographic: any height
#: above the sheet will do), as a share of the sheet's width.
CAMERA_HEIGHT = 0.5


def linear(rgb) -> tuple[float, float, float, float]:
    """An sRGB colour (0–1) as the linear RGBA Blender's object colours hold (IEC 61966-2-1),
    so the render shows the colours of the other formats."""
    c = np.asarray(rgb, dtype=float)
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return (*map(float, lin), 1.0)


def scene_name(hull: str) -> str:
    """The name of the lines plan scene of hull ``hull``."""
    return f"{hull} lines plan"


def _clear(scene) -> None:
    """Remove from ``scene`` the collections, objects and data a lines plan put there (marked
    :data:`PLAN_TAG`), leaving anything else the designer added."""
    ours = [c for c in scene.collection.children_recursive if c.get(PLAN_TAG)]
    objects = {o for o in scene.collection.all_objects if o.get(PLAN_TAG)}
    for coll in ours:
        bpy.data.collections.remove(coll)
    for obj in objects:
        data = obj.data
        bpy.data.objects.remove(obj)
        if data is not None and data.users == 0:
            (bpy.data.cameras if isinstance(data, bpy.types.Camera) else bpy.data.curves).remove(data)


def _layer_object(drawing: Drawing, layer: str, name: str):
    """The strokes of ``layer`` as one curve object of poly splines (dashed ones in pieces),
    as thick as the layer's pen, coloured as the layer."""
    pieces = []
    for s in (s for s in drawing.strokes if s.layer == layer):
        if s.dashed:
            pieces += dashes(s.points, *(v * drawing.text_height for v in DASH))
        else:
            pieces.append(s.points)
    if not pieces:
        return None
    curve = bpy.data.curves.new(name, "CURVE")
    curve.dimensions = "3D"
    curve.bevel_depth = 0.5 * drawing.pen(layer)
    curve.bevel_resolution = 0
    for points in pieces:
        spline = curve.splines.new("POLY")
        spline.points.add(len(points) - 1)
        co = np.zeros((len(points), 4))
        co[:, :2], co[:, 3] = points, 1.0
        spline.points.foreach_set("co", co.ravel())
    obj = bpy.data.objects.new(name, curve)
    obj.color = linear(LAYER_STYLE[layer][0])
    return obj


def _label_object(label, name: str):
    """A label as a text object, its baseline where the drawing puts it."""
    text = bpy.data.curves.new(name, "FONT")
    text.body = label.text
    text.size = label.height * EM_PER_CAP
    text.align_x = ALIGN_X[label.align]
    text.align_y = "BOTTOM_BASELINE"
    obj = bpy.data.objects.new(name, text)
    obj.location = (label.x, baseline(label), 0.0)
    obj.color = linear(LAYER_STYLE[label.layer][0])
    return obj


def _box(collection) -> tuple[np.ndarray, np.ndarray]:
    """The world box ``lo``, ``hi`` of the objects in ``collection``."""
    corners = [
        np.array(obj.matrix_world) @ np.array([*corner, 1.0])
        for obj in collection.all_objects
        for corner in obj.bound_box
    ]
    if not corners:
        return np.zeros(3), np.zeros(3)
    pts = np.array(corners)[:, :3]
    return pts.min(axis=0), pts.max(axis=0)


#: The orthographic views of the 3D sections: the name, the direction the camera looks in,
#: its up, and the two box axes (across, up) the view shows.
SECTION_VIEWS = (
    ("profile", (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0, 2)),  # from starboard: bow to the right
    ("half-breadth", (0.0, 0.0, -1.0), (0.0, 1.0, 0.0), (0, 1)),  # from above
    ("body plan", (-1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1, 2)),  # from ahead: port to the right
)


def _section_cameras(scene, hull: str, lo, hi) -> None:
    """An orthographic camera for each of :data:`SECTION_VIEWS`, framing the box ``lo``–``hi``
    (the 3D sections) in the scene's picture shape."""
    from mathutils import Vector

    centre, size = 0.5 * (lo + hi), hi - lo
    aspect = scene.render.resolution_x / scene.render.resolution_y
    reach = float(size.max())
    for view, look, up, (across, upward) in SECTION_VIEWS:
        data = bpy.data.cameras.new(f"{hull} {view}")
        data.type = "ORTHO"
        data.ortho_scale = max(size[across], size[upward] * aspect, reach * 1e-3) * (1 + 2 * FRAME_MARGIN)
        data.clip_end = 4 * reach
        cam = bpy.data.objects.new(f"{hull} {view} camera", data)
        cam[PLAN_TAG] = True
        cam.location = Vector(centre.tolist()) - Vector(look) * 2 * reach
        cam.rotation_euler = Vector(look).to_track_quat("-Z", "Z" if up[2] else "Y").to_euler()
        scene.collection.objects.link(cam)


def sheet_scene(drawing: Drawing, sections=None) -> bpy.types.Scene:
    """The scene ``"<hull> lines plan"`` (new, or the one of that name with the plan it showed
    replaced) showing ``drawing``: its strokes and labels in a collection per layer on the
    plane z = 0, an orthographic camera framing it from above (the scene's camera) and flat
    Workbench shading on white, ready to render. With ``sections`` (the hull's sections
    collection, see :func:`batten.api.sections`) linked in too, the live 3D sections with an
    orthographic camera each for the profile, the half-breadth plan and the body plan, and the
    sheet laid beside them (to starboard) so its camera sees the sheet alone."""
    name = scene_name(drawing.title)
    scene = bpy.data.scenes.get(name) or bpy.data.scenes.new(name)
    _clear(scene)
    x0, y0, x1, y1 = drawing.bounds()
    scene.render.resolution_x = RENDER_WIDTH
    scene.render.resolution_y = max(int(round(RENDER_WIDTH * (y1 - y0) / (x1 - x0))), 1)
    shift = 0.0
    if sections is not None:
        if sections.name not in scene.collection.children:
            scene.collection.children.link(sections)
        lo, hi = _box(sections)
        _section_cameras(scene, drawing.title, lo, hi)
        # The sheet's top below the sections' mirror image, a text height clear.
        shift = -hi[1] - drawing.text_height - y1
    for layer in LAYERS:
        coll = bpy.data.collections.new(f"{drawing.title} {layer}")
        coll[PLAN_TAG] = True
        scene.collection.children.link(coll)
        objects = [
            _label_object(lab, f"{drawing.title} {layer} text {i}")
            for i, lab in enumerate(lab for lab in drawing.labels if lab.layer == layer)
        ]
        lines = _layer_object(drawing, layer, f"{drawing.title} {layer}")
        for obj in ([lines] if lines is not None else []) + objects:
            obj[PLAN_TAG] = True
            obj.location.y += shift
            coll.objects.link(obj)
    y0, y1 = y0 + shift, y1 + shift
    width, height = (x1 - x0) * (1 + 2 * FRAME_MARGIN), (y1 - y0) * (1 + 2 * FRAME_MARGIN)
    cam_data = bpy.data.cameras.new(f"{drawing.title} lines plan")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = max(width, height)
    cam_data.clip_end = 2 * CAMERA_HEIGHT * width
    cam = bpy.data.objects.new(f"{drawing.title} lines plan camera", cam_data)
    cam[PLAN_TAG] = True
    cam.location = (0.5 * (x0 + x1), 0.5 * (y0 + y1), CAMERA_HEIGHT * width)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_percentage = 100
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.image_settings.file_format = "PNG"
    scene.view_settings.view_transform = "Standard"
    shading = scene.display.shading
    shading.light = "FLAT"
    shading.color_type = "OBJECT"
    shading.background_type = "VIEWPORT"
    shading.background_color = (1.0, 1.0, 1.0)
    scene.display.render_aa = "8"
    return scene
