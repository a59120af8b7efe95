"""Viewport overlay: curvature combs on the selected curves, and markers on the network's
nodes and problems (dangling ends, near misses) from the last build (drawn only, nothing
stored).

The comb geometry comes from :func:`batten.api.curvature_comb`, the markers from the scene's
last build report; this module only turns them into batches for the GPU.
"""

import json

import bpy
import numpy as np

from . import api

_handle = None


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


def markers(context) -> dict[str, np.ndarray]:
    """Marker positions from the last build: ``nodes`` and ``problems``, each (n, 3) float32."""
    text = context.scene.batten.last_report
    data = json.loads(text).get("markers", {}) if text else {}
    return {k: np.asarray(data.get(k, []), dtype=np.float32).reshape(-1, 3) for k in ("nodes", "problems")}


def _draw():
    context = bpy.context
    settings = getattr(context.scene, "batten", None)
    if settings is None:
        return
    import gpu
    from gpu_extras.batch import batch_for_shader

    shader = gpu.shader.from_builtin("UNIFORM_COLOR")
    if settings.show_combs:
        lines = comb_lines(context)
        if len(lines):
            batch = batch_for_shader(shader, "LINES", {"pos": lines})
            shader.uniform_float("color", (0.85, 0.2, 0.6, 1.0))
            batch.draw(shader)
    if settings.show_network:
        for kind, color, size in (
            ("nodes", (0.1, 0.6, 1.0, 1.0), 6.0),
            ("problems", (1.0, 0.15, 0.1, 1.0), 12.0),
        ):
            pts = markers(context)[kind]
            if len(pts):
                gpu.state.point_size_set(size)
                batch = batch_for_shader(shader, "POINTS", {"pos": pts})
                shader.uniform_float("color", color)
                batch.draw(shader)


def register():
    """Add the draw handler (once)."""
    global _handle
    if _handle is None:
        _handle = bpy.types.SpaceView3D.draw_handler_add(_draw, (), "WINDOW", "POST_VIEW")


def unregister():
    """Remove the draw handler."""
    global _handle
    if _handle is not None:
        bpy.types.SpaceView3D.draw_handler_remove(_handle, "WINDOW")
        _handle = None
