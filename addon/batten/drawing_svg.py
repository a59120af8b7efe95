"""A :class:`~batten.drawing.Drawing` as an SVG file (plain text, no Blender needed).

The sheet is ISO A3 landscape in millimetres at a drawing scale 1:n (written at the bottom
left); each layer is a group ``<g id="layer">`` holding one ``<path>`` per stroke and one
``<text>`` per label, so a reader (or a test) finds the stations as the paths of
``g#stations``.
"""

from __future__ import annotations

from xml.sax.saxutils import escape

import numpy as np

from .atomic_write import write_atomically
from .drawing import DASH, EM_PER_CAP, LAYER_STYLE, LAYERS, MARGIN_MM, Drawing, Page, baseline, fit_page

#: Text anchors of SVG for the drawing's horizontal alignments.
ANCHOR = {"left": "start", "center": "middle", "right": "end"}
#: The font of the text (Helvetica, as in the PDF, or its look-alikes).
FONT = "Helvetica, Arial, sans-serif"
#: Digits written for a coordinate in mm (a micrometre).
DECIMALS = 3


def _colour(rgb) -> str:
    return "#" + "".join(f"{round(255 * c):02x}" for c in rgb)


def _path(points: np.ndarray) -> str:
    pts = np.round(points, DECIMALS)
    return "M" + " L".join(f"{x:g},{y:g}" for x, y in pts)


def svg_text(drawing: Drawing, page: Page | None = None) -> str:
    """The SVG document of ``drawing`` on ``page`` (default: :func:`fit_page`)."""
    page = page or fit_page(drawing)
    k = page.mm_per_unit

    def paper(points):
        p = page.to_paper(points)
        return np.column_stack([p[:, 0], page.height - p[:, 1]])

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{page.width:g}mm" height="{page.height:g}mm" '
        f'viewBox="0 0 {page.width:g} {page.height:g}">',
        f"<title>{escape(drawing.title)} lines plan</title>",
        f'<rect width="{page.width:g}" height="{page.height:g}" fill="white"/>',
    ]
    for layer in LAYERS:
        rgb, _ = LAYER_STYLE[layer]
        strokes = [s for s in drawing.strokes if s.layer == layer]
        labels = [lab for lab in drawing.labels if lab.layer == layer]
        if not strokes and not labels:
            continue
        colour = _colour(rgb)
        width = drawing.pen(layer) * k
        out.append(
            f'<g id="{layer}" stroke="{colour}" stroke-width="{width:.4g}" fill="none" '
            'stroke-linecap="round" stroke-linejoin="round">'
        )
        for s in strokes:
            dash = ""
            if s.dashed:
                on, off = (v * drawing.text_height * k for v in DASH)
                dash = f' stroke-dasharray="{on:.4g} {off:.4g}"'
            out.append(f'<path d="{_path(paper(s.points))}"{dash}/>')
        for lab in labels:
            ((x, y),) = paper([(lab.x, baseline(lab))])
            out.append(
                f'<text x="{x:.{DECIMALS}f}" y="{y:.{DECIMALS}f}" font-family="{FONT}" '
                f'font-size="{lab.height * EM_PER_CAP * k:.4g}" text-anchor="{ANCHOR[lab.align]}" '
                f'fill="{colour}" stroke="none">{escape(lab.text)}</text>'
            )
        out.append("</g>")
    out.append(
        f'<text x="{MARGIN_MM:g}" y="{page.height - 0.5 * MARGIN_MM:g}" font-family="{FONT}" '
        f'font-size="3.5">{escape(f"Scale 1:{page.scale} (A3)")}</text>'
    )
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write_svg(drawing: Drawing, path) -> None:
    """Write ``drawing`` to ``path`` as SVG, whole or not at all."""
    write_atomically(path, svg_text(drawing))
