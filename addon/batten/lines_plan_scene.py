"""The lines plan shown in Blender: a :class:`~batten.drawing.Drawing` laid flat in a scene of
its own, one curve object per layer and a text object per label, seen by an orthographic
camera from above and rendered flat (Workbench), so the designer reads the plan — the same
lines as the exported files — without leaving Blender."""

from __future__ import annotations

import bpy
import numpy as np

from .drawing import DASH, EM_PER_CAP, LAYER_STYLE, LAYERS, Drawing, baseline, dashes

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


def _remove_scene(name: str) -> None:
    """Remove the scene ``name`` and the collections, objects and data only it used."""
    scene = bpy.data.scenes.get(name)
    if scene is None:
        return
    collections = list(scene.collection.children_recursive)
    objects = set(scene.collection.all_objects)
    bpy.data.scenes.remove(scene)
    for coll in collections:
        if coll.users == 0:
            bpy.data.collections.remove(coll)
    for obj in objects:
        if obj.users_collection:
            continue
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


def sheet_scene(drawing: Drawing) -> bpy.types.Scene:
    """A new scene (replacing the one of that name) showing ``drawing``: its strokes and labels
    in a collection per layer on the plane z = 0, an orthographic camera framing it from above
    (the scene's camera) and flat Workbench shading on white, ready to render."""
    name = scene_name(drawing.title)
    _remove_scene(name)
    scene = bpy.data.scenes.new(name)
    for layer in LAYERS:
        coll = bpy.data.collections.new(f"{drawing.title} {layer}")
        scene.collection.children.link(coll)
        obj = _layer_object(drawing, layer, f"{drawing.title} {layer}")
        if obj is not None:
            coll.objects.link(obj)
        for i, label in enumerate(lab for lab in drawing.labels if lab.layer == layer):
            coll.objects.link(_label_object(label, f"{drawing.title} {layer} text {i}"))
    x0, y0, x1, y1 = drawing.bounds()
    width, height = (x1 - x0) * (1 + 2 * FRAME_MARGIN), (y1 - y0) * (1 + 2 * FRAME_MARGIN)
    cam_data = bpy.data.cameras.new(f"{drawing.title} lines plan")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = max(width, height)
    cam_data.clip_end = 2 * CAMERA_HEIGHT * width
    cam = bpy.data.objects.new(f"{drawing.title} lines plan camera", cam_data)
    cam.location = (0.5 * (x0 + x1), 0.5 * (y0 + y1), CAMERA_HEIGHT * width)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x = RENDER_WIDTH
    scene.render.resolution_y = max(int(round(RENDER_WIDTH * height / width)), 1)
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
