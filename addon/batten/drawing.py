"""A flat line drawing: polylines and text on named layers, in model units (no Blender needed).

A lines plan is laid out once as a :class:`Drawing` (metres on the sheet's plane, y up) and
written by each format's writer (:mod:`batten.drawing_svg`, :mod:`batten.drawing_pdf`,
:mod:`batten.drawing_dxf`, :mod:`batten.drawing_png`), so every file shows the same lines.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: The layers of a lines plan, bottom to top, with the colour (RGB 0–1) and pen width (a share
#: of the text height) each is drawn with: the section families, the hull's outline, the grid
#: of the planes and the title block.
LAYER_STYLE: dict[str, tuple[tuple[float, float, float], float]] = {
    "grid": ((0.62, 0.62, 0.62), 0.035),
    "waterlines": ((0.0, 0.45, 0.25), 0.07),
    "buttocks": ((0.7, 0.25, 0.0), 0.07),
    "diagonals": ((0.5, 0.2, 0.6), 0.07),
    "stations": ((0.0, 0.25, 0.65), 0.07),
    "knuckles": ((0.0, 0.0, 0.0), 0.1),
    "outline": ((0.0, 0.0, 0.0), 0.1),
    "dwl": ((0.0, 0.3, 0.8), 0.06),
    "title": ((0.0, 0.0, 0.0), 0.05),
}
LAYERS = tuple(LAYER_STYLE)
#: Horizontal anchors of a text at its point, and vertical ones.
ALIGNS = ("left", "center", "right")
VALIGNS = ("baseline", "center", "top")
#: Dash and gap of a dashed line, as shares of the text height.
DASH = (1.2, 0.6)


@dataclass(frozen=True)
class Stroke:
    """A polyline ``points`` ((n, 2), n ≥ 2) on ``layer``, solid or dashed."""

    layer: str
    points: np.ndarray
    dashed: bool = False


@dataclass(frozen=True)
class Label:
    """Text at ``(x, y)``, ``height`` tall (capital height), anchored by ``align`` and
    ``valign`` at that point, on ``layer``."""

    layer: str
    x: float
    y: float
    text: str
    height: float
    align: str = "left"
    valign: str = "baseline"


@dataclass
class Drawing:
    """The strokes and labels of a drawing, its title, the text height its pens scale with,
    ``marks``: named places of the layout (a view's centreline, say) for whoever reads it,
    and ``tables`` ((title, header, rows of text cells)) a document format prints after it."""

    title: str
    text_height: float
    strokes: list[Stroke] = field(default_factory=list)
    labels: list[Label] = field(default_factory=list)
    marks: dict[str, float] = field(default_factory=dict)
    tables: list[tuple[str, list[str], list[list[str]]]] = field(default_factory=list)

    def line(self, layer: str, points, *, dashed: bool = False) -> None:
        """Add a polyline, broken where a point is not finite (pieces of fewer than 2 points
        are left out)."""
        if layer not in LAYER_STYLE:
            raise ValueError(f"unknown layer {layer!r}")
        for run in finite_runs(np.asarray(points, dtype=np.float64).reshape(-1, 2)):
            self.strokes.append(Stroke(layer, run, dashed))

    def text(
        self, layer: str, x: float, y: float, text: str, *, height=None, align="left", valign="baseline"
    ):
        """Add a label (``height`` defaults to the drawing's text height)."""
        if align not in ALIGNS or valign not in VALIGNS:
            raise ValueError(f"bad anchor {align!r}, {valign!r}")
        self.labels.append(
            Label(layer, float(x), float(y), text, float(height or self.text_height), align, valign)
        )

    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of the strokes and of the labels' estimated boxes."""
        boxes = [np.vstack([s.points.min(axis=0), s.points.max(axis=0)]) for s in self.strokes]
        boxes += [np.array(label_box(lab)).reshape(2, 2) for lab in self.labels]
        if not boxes:
            return (0.0, 0.0, 1.0, 1.0)
        allp = np.vstack(boxes)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))

    def pen(self, layer: str) -> float:
        """The pen width of ``layer`` in drawing units."""
        return LAYER_STYLE[layer][1] * self.text_height


#: Width of a character as a share of the capital height, for the layout's estimates
#: (Helvetica's digits are 0.556 em and its capitals 0.718 em tall: 0.77 cap heights).
CHAR_WIDTH = 0.8
#: The em (font size) of a text whose capital height is 1 (Helvetica's cap height 0.718 em).
EM_PER_CAP = 1.0 / 0.718


def label_box(label: Label) -> tuple[float, float, float, float]:
    """An estimate of the box ``(xmin, ymin, xmax, ymax)`` a label covers."""
    w = CHAR_WIDTH * label.height * len(label.text)
    x0 = label.x - {"left": 0.0, "center": 0.5 * w, "right": w}[label.align]
    y0 = baseline(label)
    return (x0, y0 - 0.25 * label.height, x0 + w, y0 + label.height)


#: The scales drawings are made at: 1:n for n one of these × 10^k (a whole number; 1:25,
#: 1:250 and 1:40, 1:400 are the shipyard's steps between ISO 5455's 1, 2, 5).
SCALE_STEPS = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0)
#: ISO A3 landscape (mm), the sheet a lines plan is printed on, and its margin.
A3_LANDSCAPE = (420.0, 297.0)
MARGIN_MM = 12.0
#: Millimetres per metre.
MM_PER_M = 1000.0


def nice_scale(ratio: float) -> int:
    """The largest drawing scale 1:n (n one of :data:`SCALE_STEPS` × 10^k, a whole number,
    1 at least) with n ≥ ``ratio`` (model length per paper length)."""
    if not ratio > 1.0:
        return 1
    decade = 10 ** math.floor(math.log10(ratio))
    return int(
        next(
            step * decade
            for step in SCALE_STEPS
            if step * decade >= ratio and float(step * decade).is_integer()
        )
    )


@dataclass(frozen=True)
class Page:
    """A drawing placed on a sheet ``width`` × ``height`` mm at the scale 1:``scale``:
    model point ``(x, y)`` m is at ``offset + (x, y) · 1000/scale`` mm from the sheet's
    bottom left."""

    width: float
    height: float
    scale: int
    offset: tuple[float, float]

    @property
    def mm_per_unit(self) -> float:
        """Millimetres on the sheet per model metre."""
        return MM_PER_M / self.scale

    def to_paper(self, points) -> np.ndarray:
        """Model points ((n, 2) m) as sheet points ((n, 2) mm from the bottom left)."""
        return np.asarray(points, dtype=np.float64) * self.mm_per_unit + np.asarray(self.offset)


def fit_page(drawing: Drawing, size: tuple[float, float] = A3_LANDSCAPE, margin: float = MARGIN_MM) -> Page:
    """The drawing at the largest :func:`nice_scale` that fits inside ``size`` (mm) less
    ``margin`` each side, centred."""
    x0, y0, x1, y1 = drawing.bounds()
    room_w, room_h = size[0] - 2 * margin, size[1] - 2 * margin
    scale = nice_scale(MM_PER_M * max((x1 - x0) / room_w, (y1 - y0) / room_h))
    k = MM_PER_M / scale
    offset = (0.5 * size[0] - 0.5 * (x0 + x1) * k, 0.5 * size[1] - 0.5 * (y0 + y1) * k)
    return Page(size[0], size[1], scale, offset)


def baseline(label: Label) -> float:
    """The y of the baseline of ``label``'s text (from its anchor and capital height)."""
    return label.y - {"baseline": 0.0, "center": 0.5 * label.height, "top": label.height}[label.valign]


def dashes(points: np.ndarray, on: float, off: float) -> list[np.ndarray]:
    """The drawn pieces of the polyline ``points`` dashed ``on``, ``off`` (drawing units)."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    pieces = []
    for start in np.arange(0.0, s[-1], on + off):
        end = min(start + on, s[-1])
        at = np.concatenate([[start], s[(s > start) & (s < end)], [end]])
        piece = np.column_stack([np.interp(at, s, points[:, 0]), np.interp(at, s, points[:, 1])])
        if len(piece) >= 2:
            pieces.append(piece)
    return pieces


def finite_runs(points: np.ndarray) -> list[np.ndarray]:
    """The stretches of ``points`` with no non-finite coordinate, each of two points or more."""
    ok = np.isfinite(points).all(axis=1)
    runs, start = [], None
    for i, good in enumerate([*ok, False]):
        if good and start is None:
            start = i
        elif not good and start is not None:
            if i - start >= 2:
                runs.append(points[start:i])
            start = None
    return runs
