"""Line charts drawn to PNG files inside Blender, with no plotting library.

Blender's Python has no matplotlib, so a chart is drawn in two passes: the lines, ticks and
markers are rasterised with numpy into an RGBA array (antialiased by each pixel's distance to
the segment), which Blender saves as a PNG; then the text is drawn onto that image with
Blender's own font engine (``blf`` into an ``imbuf`` image buffer, which needs no GPU and works
headless in the ``bpy`` module) and the result is written. Pixel coordinates run from the
bottom left, as in Blender images.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .drawing import dashes, finite_runs

#: RGBA colours (0–1).
WHITE = (1.0, 1.0, 1.0, 1.0)
BLACK = (0.0, 0.0, 0.0, 1.0)
GRID = (0.88, 0.88, 0.88, 1.0)
#: A legend's box (white, letting a little of what is under it show).
LEGEND_BOX = (1.0, 1.0, 1.0, 0.85)
#: Width of a legend character, as a share of the text size (the default font's digits and
#: letters average about half; a little more leaves room).
LEGEND_CHAR_WIDTH = 0.6
#: A pixel darker than this in some channel is ink (a curve, a mark): the background and the
#: grid lines are lighter.
INK_LEVEL = 0.8
#: Curve colours, told apart in print and by colour-blind readers (the Okabe–Ito palette).
PALETTE = (
    (0.0, 0.447, 0.698, 1.0),
    (0.835, 0.369, 0.0, 1.0),
    (0.0, 0.62, 0.451, 1.0),
    (0.8, 0.475, 0.655, 1.0),
    (0.337, 0.706, 0.914, 1.0),
    (0.902, 0.624, 0.0, 1.0),
    (0.0, 0.0, 0.0, 1.0),
)
#: The spans a tick step may take in each decade (Heckbert's "nice numbers", Graphics Gems I).
NICE_STEPS = (1.0, 2.0, 2.5, 5.0, 10.0)
#: Segments at most this many pixels across are covered in batches (:func:`_cover_segments`)
#: of this many, each over a window of pixels of its own; longer ones one by one.
BATCH_SEGMENT_PX = 12.0
BATCH_SEGMENTS = 4096
#: Squared length (pixels²) below which a segment is a dot: keeps the projection finite.
MIN_SEGMENT_LENGTH2 = 1e-12
#: A range narrower than this share of its values' size (or than this, about 0) is one value.
FLAT_RANGE_RELATIVE = 1e-12
#: Slack, in steps, for a range end that is a tick up to rounding (it stays the end tick).
TICK_SLACK = 1e-9
#: Share of a flat range's size (or 1 when it is 0) a constant curve's axis is widened by.
FLAT_RANGE_PAD = 0.1


def nice_ticks(lo: float, hi: float, count: int = 5, *, min_span: float = 0.0) -> np.ndarray:
    """About ``count`` evenly spaced round values (1, 2, 2.5 or 5 × 10^k apart) covering
    ``lo``–``hi``: the first at or below ``lo``, the last at or above ``hi``. A range narrower
    than ``min_span`` (say, the rounding noise of a figure that is in truth constant) is
    widened to it about its middle; a range of no width around its value."""
    lo, hi = float(min(lo, hi)), float(max(lo, hi))
    if hi - lo < min_span:
        mid = 0.5 * (lo + hi)
        lo, hi = mid - 0.5 * min_span, mid + 0.5 * min_span
    if hi - lo <= FLAT_RANGE_RELATIVE * max(abs(lo), abs(hi), 1.0):
        pad = FLAT_RANGE_PAD * abs(lo) if lo else 1.0
        lo, hi = lo - pad, hi + pad
    raw = (hi - lo) / max(count - 1, 1)
    decade = 10.0 ** math.floor(math.log10(raw))
    step = decade * next(s for s in NICE_STEPS if s * decade >= raw * (1 - TICK_SLACK))
    first, last = math.floor(lo / step + TICK_SLACK), math.ceil(hi / step - TICK_SLACK)
    return np.arange(first, last + 1) * step


def tick_labels(ticks: np.ndarray) -> list[str]:
    """The ticks as text, with as many decimals as their step needs (none for whole steps)."""
    step = float(ticks[1] - ticks[0]) if len(ticks) > 1 else 1.0
    decimals = 0
    while decimals < 6 and abs(step * 10**decimals - round(step * 10**decimals)) > 1e-6:
        decimals += 1
    # A tick within rounding of zero is 0, not "-0".
    return [f"{0.0 if abs(t) < 1e-9 * abs(step) else t:.{decimals}f}" for t in ticks]


@dataclass
class _Text:
    x: float
    y: float
    text: str
    size: int
    color: tuple
    align: str  # "left", "center" or "right" of x
    valign: str  # "baseline", "center" or "top" at y


@dataclass
class Canvas:
    """An RGBA image being drawn (``pixels`` (h, w, 4), row 0 at the bottom) and the text to
    put on it when saved."""

    width: int
    height: int
    pixels: np.ndarray = field(init=False)
    texts: list[_Text] = field(default_factory=list, init=False)

    def __post_init__(self):
        self.pixels = np.empty((self.height, self.width, 4), dtype=np.float32)
        self.pixels[:] = WHITE

    def _paint(self, coverage: np.ndarray, color, origin=(0, 0)) -> None:
        """Blend ``color`` over the image where ``coverage`` (0–1, a block of the image whose
        bottom left pixel is ``origin``) says."""
        x0, y0 = origin
        h, w = coverage.shape
        block = self.pixels[y0 : y0 + h, x0 : x0 + w, :3]
        a = (coverage * color[3])[..., None]
        block[:] = block * (1 - a) + np.asarray(color[:3]) * a

    def line(self, points, color, width: float = 2.0, dash: tuple[float, float] | None = None) -> None:
        """A polyline through ``points`` ((n, 2) pixels) ``width`` pixels wide, solid or
        dashed (``dash`` = (on, off) pixels); non-finite points break it."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        pieces = [p for run in finite_runs(points) for p in (dashes(run, *dash) if dash else [run])]
        self._cover(
            [(p, q) for piece in pieces for p, q in zip(piece[:-1], piece[1:], strict=True)],
            0.5 * width,
            color,
        )

    def disc(self, centre, radius: float, color) -> None:
        """A filled disc at ``centre`` (pixels)."""
        c = np.asarray(centre, dtype=float)
        self._cover([(c, c)], radius, color)

    def _cover(self, segments, half: float, color) -> None:
        """Paint the segments thickened by ``half`` each side, each pixel once (by the most
        any segment covers it: 1 inside, falling to 0 over the pixel at the edge)."""
        if not segments:
            return
        ends = np.array(segments, dtype=float).reshape(-1, 2)
        size = np.array([self.width, self.height])
        lo = np.floor(ends.min(axis=0) - half - 1).astype(int).clip(0, size)
        hi = np.ceil(ends.max(axis=0) + half + 1).astype(int).clip(0, size)
        if (hi <= lo).any():
            return
        coverage = np.zeros((hi[1] - lo[1], hi[0] - lo[0]), dtype=np.float32)
        ends = ends.reshape(-1, 2, 2)
        reach = np.abs(ends[:, 1] - ends[:, 0]).max(axis=1)
        short = reach <= BATCH_SEGMENT_PX
        for p, q in ends[~short]:
            _cover_segment(coverage, lo, p, q, half)
        for start in range(0, int(short.sum()), BATCH_SEGMENTS):
            _cover_segments(coverage, lo, ends[short][start : start + BATCH_SEGMENTS], half)
        self._paint(coverage, color, lo)

    def fill_below(self, points, base_y: float, color) -> None:
        """Fill between the curve through ``points`` ((n, 2) pixels, x increasing) and the
        row ``base_y``."""
        points = np.asarray(points, dtype=float)
        x0, x1 = max(int(math.ceil(points[0, 0])), 0), min(int(points[-1, 0]), self.width - 1)
        if x1 < x0:
            return
        cols = np.arange(x0, x1 + 1)
        top = np.interp(cols + 0.5, points[:, 0], points[:, 1])
        rows = np.arange(self.height)[:, None] + 0.5
        lo, hi = np.minimum(top, base_y), np.maximum(top, base_y)
        coverage = np.zeros((self.height, self.width), dtype=np.float32)
        coverage[:, x0 : x1 + 1] = (rows >= lo) & (rows <= hi)
        self._paint(coverage, color)

    def _block(self, x0, y0, x1, y1) -> tuple[slice, slice]:
        """The rows and columns of the pixels inside ``x0``–``x1`` × ``y0``–``y1``."""
        cols = slice(max(int(x0), 0), min(int(math.ceil(x1)), self.width))
        rows = slice(max(int(y0), 0), min(int(math.ceil(y1)), self.height))
        return rows, cols

    def drawn_pixels(self, x0, y0, x1, y1) -> int:
        """How many pixels inside the box are inked (darker than the background and grid)."""
        rows, cols = self._block(x0, y0, x1, y1)
        return int((self.pixels[rows, cols, :3] < INK_LEVEL).any(axis=-1).sum())

    def fill_rect(self, x0, y0, x1, y1, color) -> None:
        """Fill the box ``x0``–``x1`` × ``y0``–``y1`` (pixels) with ``color``."""
        rows, cols = self._block(x0, y0, x1, y1)
        coverage = np.ones((rows.stop - rows.start, cols.stop - cols.start), dtype=np.float32)
        if coverage.size:
            self._paint(coverage, color, (cols.start, rows.start))

    def text(self, x, y, text: str, *, size: int = 14, color=BLACK, align="left", valign="baseline"):
        """Put ``text`` at ``(x, y)`` (pixels) when the image is saved."""
        self.texts.append(_Text(float(x), float(y), text, size, color, align, valign))

    def save_png(self, path) -> Path:
        """Write the image with its text to ``path`` (PNG, RGBA); returns the path. The text
        is drawn by Blender's font engine into the image where it can
        (:data:`batten.compat.BLF_DRAWS_INTO_IMBUF`), else filled from the same font's glyph
        outlines into the pixels (:mod:`batten.glyph_outlines`)."""
        from . import compat

        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        if compat.BLF_DRAWS_INTO_IMBUF:
            _write_pixels(self.pixels, path)
            _draw_texts_with_blf(path, self._placed_texts())
        else:
            _write_pixels(self._pixels_with_glyphs(), path)
        return path

    def _placed_texts(self) -> list[tuple[_Text, int, int]]:
        """Each queued text with the pixel its pen starts at (baseline left), after its
        alignment, measured by Blender's font engine."""
        import blf

        placed = []
        for t in self.texts:
            blf.size(FONT, t.size)
            w, _h = blf.dimensions(FONT, t.text)
            cap = blf.dimensions(FONT, "0")[1]
            placed.append((t, *_aligned(t, w, cap)))
        return placed

    def _pixels_with_glyphs(self) -> np.ndarray:
        """A copy of the pixels with the queued texts filled in from glyph outlines, scaled
        so that a digit is as tall as Blender's font engine draws it at the text's size."""
        import blf

        from .glyph_outlines import GlyphOutlines, fill_coverage

        out = Canvas(self.width, self.height)
        out.pixels[:] = self.pixels
        with GlyphOutlines() as glyphs:
            digit = glyphs.edges("0")[..., 1]
            digit_height = digit.max() - digit.min()
            for t in self.texts:
                blf.size(FONT, t.size)
                cap = blf.dimensions(FONT, "0")[1]
                edges = glyphs.edges(t.text) * (cap / digit_height)
                if not len(edges):
                    continue
                edges += _aligned(t, edges[..., 0].max(), cap)
                lo = np.floor(edges.reshape(-1, 2).min(axis=0)).astype(int)
                hi = np.ceil(edges.reshape(-1, 2).max(axis=0)).astype(int)
                x0, y0 = max(lo[0], 0), max(lo[1], 0)
                x1, y1 = min(hi[0], self.width), min(hi[1], self.height)
                if x1 > x0 and y1 > y0:
                    out._paint(fill_coverage(edges, (y1 - y0, x1 - x0), (x0, y0)), t.color, (x0, y0))
        return out.pixels


def _aligned(t: _Text, width: float, cap: float) -> tuple[int, int]:
    """The pixel where the pen starts (baseline left) for ``t`` ``width`` pixels wide whose
    digits are ``cap`` pixels tall, after its alignment."""
    x = t.x - {"left": 0.0, "center": 0.5 * width, "right": width}[t.align]
    y = t.y - {"baseline": 0.0, "center": 0.5 * cap, "top": cap}[t.valign]
    return round(x), round(y)


#: Blender's default font, in ``blf`` and for text objects: it has the ship symbols
#: (∇, Δ, ², ³, °).
FONT = 0


def _write_pixels(pixels: np.ndarray, path: Path) -> None:
    """Save an RGBA pixel array (row 0 at the bottom) as the PNG ``path``, through a
    throwaway Blender image."""
    import bpy

    height, width = pixels.shape[:2]
    image = bpy.data.images.new(".batten chart", width, height, alpha=True)
    try:
        image.pixels.foreach_set(pixels.ravel())
        image.filepath_raw, image.file_format = str(path), "PNG"
        image.save()
    finally:
        bpy.data.images.remove(image)


def _draw_texts_with_blf(path: Path, placed) -> None:
    """Draw ``placed`` texts with Blender's font engine into the PNG ``path`` (read into an
    image buffer, drawn, written back)."""
    import blf
    import imbuf

    buffer = imbuf.load(str(path))
    try:
        with blf.bind_imbuf(FONT, buffer):
            for t, x, y in placed:
                blf.size(FONT, t.size)
                blf.color(FONT, *t.color)
                blf.position(FONT, x, y, 0)
                blf.draw_buffer(FONT, t.text)
        imbuf.write(buffer, filepath=str(path))
    finally:
        buffer.free()


def _cover_segments(coverage: np.ndarray, origin, ends: np.ndarray, half: float) -> None:
    """:func:`_cover_segment` for many short segments at once (``ends`` (n, 2, 2), each no
    longer than :data:`BATCH_SEGMENT_PX` across): the same coverage, over one window of pixels
    per segment, for polylines of many points (a lines plan's sections)."""
    h, w = coverage.shape
    size = int(np.ceil(BATCH_SEGMENT_PX + 2 * half + 3))
    p, q = ends[:, 0], ends[:, 1]
    corner = np.floor(np.minimum(p, q) - half - 1).astype(int) - origin  # (n, 2) window origins
    grid = np.arange(size)
    px = (corner[:, 0, None, None] + grid[None, None, :]) + origin[0] + 0.5  # (n, 1, size)
    py = (corner[:, 1, None, None] + grid[None, :, None]) + origin[1] + 0.5  # (n, size, 1)
    d = q - p
    dd = np.maximum((d * d).sum(axis=1), MIN_SEGMENT_LENGTH2)[:, None, None]
    t = (
        (px - p[:, 0, None, None]) * d[:, 0, None, None] + (py - p[:, 1, None, None]) * d[:, 1, None, None]
    ) / dd
    t = t.clip(0.0, 1.0)
    dist = np.hypot(
        px - p[:, 0, None, None] - t * d[:, 0, None, None], py - p[:, 1, None, None] - t * d[:, 1, None, None]
    )
    value = (half + 0.5 - dist).clip(0.0, 1.0)
    cols = np.broadcast_to(corner[:, 0, None, None] + grid[None, None, :], value.shape)
    rows = np.broadcast_to(corner[:, 1, None, None] + grid[None, :, None], value.shape)
    inside = (value > 0.0) & (cols >= 0) & (cols < w) & (rows >= 0) & (rows < h)
    np.maximum.at(coverage, (rows[inside], cols[inside]), value[inside].astype(coverage.dtype))


def _cover_segment(coverage: np.ndarray, origin, p, q, half: float) -> None:
    """Raise ``coverage`` (a block of pixels whose bottom left is ``origin``) to each pixel's
    share of the segment ``p``–``q`` thickened by ``half`` each side."""
    h, w = coverage.shape
    lo = (np.floor(np.minimum(p, q) - half - 1).astype(int) - origin).clip(0, [w, h])
    hi = (np.ceil(np.maximum(p, q) + half + 1).astype(int) - origin).clip(0, [w, h])
    if (hi <= lo).any():
        return
    px, py = np.meshgrid(np.arange(lo[0], hi[0]) + origin[0] + 0.5, np.arange(lo[1], hi[1]) + origin[1] + 0.5)
    d = q - p
    t = (((px - p[0]) * d[0] + (py - p[1]) * d[1]) / max(float(d @ d), MIN_SEGMENT_LENGTH2)).clip(0.0, 1.0)
    dist = np.hypot(px - p[0] - t * d[0], py - p[1] - t * d[1])
    block = coverage[lo[1] : hi[1], lo[0] : hi[0]]
    np.maximum(block, (half + 0.5 - dist).clip(0.0, 1.0), out=block)


@dataclass
class Axes:
    """A plotting frame in a canvas: the pixel box ``left``, ``bottom``, ``right``, ``top``
    and the data ranges it shows (widened to round ticks)."""

    canvas: Canvas
    box: tuple[float, float, float, float]
    xticks: np.ndarray
    yticks: np.ndarray

    @classmethod
    def fit(
        cls, canvas: Canvas, box, xs, ys, *, xcount: int = 7, ycount: int = 5, xmin_span: float = 0.0
    ) -> Axes:
        """Axes in ``box`` whose ranges cover the finite values of ``xs`` and ``ys``, the
        horizontal one at least ``xmin_span`` wide (see :func:`nice_ticks`)."""
        xs, ys = _finite(xs), _finite(ys)
        xticks = nice_ticks(xs.min(), xs.max(), xcount, min_span=xmin_span)
        return cls(canvas, box, xticks, nice_ticks(ys.min(), ys.max(), ycount))

    def to_px(self, x, y) -> np.ndarray:
        """Data points ``(x, y)`` (arrays) as pixels, (n, 2)."""
        left, bottom, right, top = self.box
        x0, x1, y0, y1 = self.xticks[0], self.xticks[-1], self.yticks[0], self.yticks[-1]
        px = left + (np.asarray(x, float) - x0) / (x1 - x0) * (right - left)
        py = bottom + (np.asarray(y, float) - y0) / (y1 - y0) * (top - bottom)
        return np.column_stack([np.atleast_1d(px), np.atleast_1d(py)])

    def frame(self, *, xlabel: str, ylabel: str, title: str = "", size: int = 14) -> None:
        """The grid, the box, ticks with their numbers, the axis labels (``ylabel`` above the
        vertical axis, as the unit of a column is written) and the title."""
        c, (left, bottom, right, top) = self.canvas, self.box
        for x in self.to_px(self.xticks, np.full(len(self.xticks), self.yticks[0]))[:, 0]:
            c.line([(x, bottom), (x, top)], GRID, 1.0)
        for y in self.to_px(np.full(len(self.yticks), self.xticks[0]), self.yticks)[:, 1]:
            c.line([(left, y), (right, y)], GRID, 1.0)
        c.line([(left, bottom), (right, bottom), (right, top), (left, top), (left, bottom)], BLACK, 1.5)
        tick = 0.4 * size
        xpx = self.to_px(self.xticks, np.full(len(self.xticks), self.yticks[0]))[:, 0]
        for x, label in zip(xpx, tick_labels(self.xticks), strict=True):
            c.line([(x, bottom), (x, bottom - tick)], BLACK, 1.5)
            c.text(x, bottom - tick - 0.3 * size, label, size=size, align="center", valign="top")
        ypx = self.to_px(np.full(len(self.yticks), self.xticks[0]), self.yticks)[:, 1]
        for y, label in zip(ypx, tick_labels(self.yticks), strict=True):
            c.line([(left - tick, y), (left, y)], BLACK, 1.5)
            c.text(left - tick - 0.3 * size, y, label, size=size, align="right", valign="center")
        c.text(0.5 * (left + right), bottom - 2.6 * size, xlabel, size=size, align="center", valign="top")
        c.text(left, top + 0.6 * size, ylabel, size=size, align="left")
        if title:
            c.text(0.5 * (left + right), top + 2.0 * size, title, size=round(1.2 * size), align="center")

    def plot(self, x, y, color, *, width: float = 2.5, dash=None) -> None:
        """The curve through the data points ``(x, y)``."""
        self.canvas.line(self.to_px(x, y), color, width, dash)

    def vline(self, x: float, label: str, color=BLACK, *, size: int = 14) -> None:
        """A dashed vertical line at data ``x`` labelled at its top, inside the box."""
        (px, _), (_, top) = self.to_px([x], [self.yticks[0]])[0], self.to_px([x], [self.yticks[-1]])[0]
        _, bottom, _, _ = self.box
        self.canvas.line([(px, bottom), (px, top)], color, 1.5, dash=(8.0, 5.0))
        self.canvas.text(px + 4, top - 0.5 * size, label, size=size, color=color, valign="top")

    def legend(self, entries: list[tuple[str, tuple]], *, size: int = 14) -> None:
        """A key of (label, colour) pairs, a short line each, on a white box in the corner of
        the frame where the curves drawn so far leave the most room."""
        left, bottom, right, top = self.box
        row, pad = 1.4 * size, 0.5 * size
        width = 3.0 * size + LEGEND_CHAR_WIDTH * size * max(len(label) for label, _ in entries)
        height = row * len(entries) + pad
        corners = [
            (x, y) for y in (top - pad - height, bottom + pad) for x in (left + pad, right - pad - width)
        ]
        x0, y0 = min(corners, key=lambda c: self.canvas.drawn_pixels(c[0], c[1], c[0] + width, c[1] + height))
        self.canvas.fill_rect(x0, y0, x0 + width, y0 + height, LEGEND_BOX)
        y = y0 + height - 0.5 * pad - 0.5 * row
        for label, color in entries:
            self.canvas.line([(x0 + pad, y), (x0 + pad + 2 * size, y)], color, 3.0)
            self.canvas.text(x0 + pad + 2.5 * size, y, label, size=size, valign="center")
            y -= row


def _finite(values) -> np.ndarray:
    values = np.asarray(values, dtype=float).ravel()
    values = values[np.isfinite(values)]
    return values if len(values) else np.zeros(1)
