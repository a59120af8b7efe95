"""Text filled from glyph outlines into a pixel array, for Blenders whose ``blf`` can't draw
into an image buffer (4.2; see :data:`batten.compat.BLF_DRAWS_INTO_IMBUF`).

A throwaway text object in Blender's built-in font (which has the ship symbols ∇, Δ, ², ³, °,
as ``blf``'s default font has) is turned into a mesh with its fill off: the glyph contours as
closed loops of edges, one unit per em, the baseline at y = 0. The loops are filled by the
even-odd rule (the built-in font's contours don't overlap, so holes such as the middle of an
"o" stay open) on a grid of :data:`SUPERSAMPLE` × :data:`SUPERSAMPLE` samples per pixel,
whose mean is the pixel's coverage: antialiased text without a GPU.
"""

from __future__ import annotations

import bpy
import numpy as np

#: Samples per pixel along each axis: 4 × 4 give 17 levels of grey, smooth enough for the
#: 10–16 px text of a chart.
SUPERSAMPLE = 4
#: Segments per Bézier span of a glyph outline: at chart sizes a span is a few pixels long,
#: so 4 chords keep the outline within a small fraction of a pixel.
OUTLINE_RESOLUTION = 4


class GlyphOutlines:
    """Outlines of text in Blender's built-in font, from one throwaway text object (removed
    by :meth:`close`, or on leaving a ``with`` block)."""

    def __init__(self) -> None:
        self._curve = bpy.data.curves.new(".batten glyphs", type="FONT")
        self._curve.fill_mode = "NONE"
        self._curve.resolution_u = OUTLINE_RESOLUTION
        self._object = bpy.data.objects.new(".batten glyphs", self._curve)

    def __enter__(self) -> GlyphOutlines:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Remove the text object and its curve from the file."""
        bpy.data.objects.remove(self._object)
        bpy.data.curves.remove(self._curve)

    def edges(self, text: str) -> np.ndarray:
        """The glyph contours of ``text`` as segments ((n, 2, 2), em units, pen at the origin)."""
        self._curve.body = text
        mesh = self._object.to_mesh()
        try:
            co = np.empty(len(mesh.vertices) * 3, dtype=np.float64)
            mesh.vertices.foreach_get("co", co)
            ends = np.empty(len(mesh.edges) * 2, dtype=np.int64)
            mesh.edges.foreach_get("vertices", ends)
        finally:
            self._object.to_mesh_clear()
        return co.reshape(-1, 3)[:, :2][ends.reshape(-1, 2)]


def fill_coverage(edges: np.ndarray, shape: tuple[int, int], origin=(0.0, 0.0)) -> np.ndarray:
    """Coverage (0–1, ``shape`` (h, w) pixels, row 0 at the bottom) of the region inside the
    closed loops ``edges`` ((n, 2, 2), pixels; the block's bottom left corner at ``origin``)
    by the even-odd rule, :data:`SUPERSAMPLE` × :data:`SUPERSAMPLE` samples a pixel."""
    h, w = shape
    ys = origin[1] + (np.arange(h * SUPERSAMPLE) + 0.5) / SUPERSAMPLE
    xs = origin[0] + (np.arange(w * SUPERSAMPLE) + 0.5) / SUPERSAMPLE
    inside = np.zeros((len(ys), len(xs)), dtype=bool)
    if len(edges):
        p, q = edges[:, 0], edges[:, 1]
        lo, hi = np.minimum(p[:, 1], q[:, 1]), np.maximum(p[:, 1], q[:, 1])
        # Half-open in y: a row through a vertex meets exactly one of its two edges.
        crosses = (ys[:, None] >= lo) & (ys[:, None] < hi)
        dy = np.where(q[:, 1] == p[:, 1], 1.0, q[:, 1] - p[:, 1])
        x_at = p[:, 0] + (ys[:, None] - p[:, 1]) / dy * (q[:, 0] - p[:, 0])
        x_at = np.sort(np.where(crosses, x_at, np.inf), axis=1)
        for row, hits in enumerate(x_at):
            inside[row] = np.searchsorted(hits, xs) % 2 == 1
    return inside.reshape(h, SUPERSAMPLE, w, SUPERSAMPLE).mean(axis=(1, 3))
