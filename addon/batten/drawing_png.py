"""A :class:`~batten.drawing.Drawing` as a PNG picture, drawn with :class:`batten.chart.Canvas`
(numpy lines, Blender's font engine for the text: needs ``bpy`` only to save)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

from .chart import Canvas
from .drawing import DASH, EM_PER_CAP, LAYER_STYLE, LAYERS, Drawing, baseline

#: Margin around the drawing, as a share of the picture's width.
MARGIN_SHARE = 0.02
#: The thinnest pen in pixels (a grid line thinner than this fades into antialiasing).
MIN_PEN_PX = 1.0


def canvas_of(drawing: Drawing, width: int = 2400) -> Canvas:
    """``drawing`` fitted into a canvas ``width`` pixels wide (its height as the drawing's
    shape asks), lines drawn, text queued for :meth:`~batten.chart.Canvas.save_png`."""
    x0, y0, x1, y1 = drawing.bounds()
    margin = MARGIN_SHARE * width
    k = (width - 2 * margin) / max(x1 - x0, 1e-300)
    height = int(np.ceil((y1 - y0) * k + 2 * margin))
    canvas = Canvas(width, height)

    def px(points):
        return (np.asarray(points, dtype=np.float64) - (x0, y0)) * k + margin

    for layer in LAYERS:
        rgb, _ = LAYER_STYLE[layer]
        colour = (*rgb, 1.0)
        pen = max(drawing.pen(layer) * k, MIN_PEN_PX)
        for s in (s for s in drawing.strokes if s.layer == layer):
            dash = tuple(v * drawing.text_height * k for v in DASH) if s.dashed else None
            canvas.line(px(s.points), colour, pen, dash)
        for lab in (lab for lab in drawing.labels if lab.layer == layer):
            ((x, y),) = px([(lab.x, baseline(lab))])
            size = max(round(lab.height * EM_PER_CAP * k), 1)
            canvas.text(x, y, lab.text, size=size, color=colour, align=lab.align)
    return canvas


def write_png(drawing: Drawing, path, width: int = 2400) -> Path:
    """Write ``drawing`` as a PNG ``width`` pixels wide to ``path``, whole or not at all (into
    a temporary file beside it, then renamed over it); returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".png", dir=path.parent)
    os.close(fd)
    try:
        canvas_of(drawing, width).save_png(tmp)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path
