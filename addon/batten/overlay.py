"""Viewport overlay: curvature combs on the selected curves (drawn only, nothing stored).

The comb geometry comes from :func:`batten.api.curvature_comb`; this module only turns it
into line batches for the GPU.
"""

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


def _draw():
    context = bpy.context
    if not getattr(context.scene, "batten", None) or not context.scene.batten.show_combs:
        return
    import gpu
    from gpu_extras.batch import batch_for_shader

    lines = comb_lines(context)
    if len(lines) == 0:
        return
    shader = gpu.shader.from_builtin("UNIFORM_COLOR")
    batch = batch_for_shader(shader, "LINES", {"pos": lines})
    shader.uniform_float("color", (0.85, 0.2, 0.6, 1.0))
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
