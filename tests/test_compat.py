"""What differs between Blender versions (batten.compat): each way works on the Blender it
is for, and the fallback used on older Blenders draws what the newer way draws."""

import bpy
import numpy as np
import pytest
from batten import chart, compat, glyph_outlines
from batten.hydro_plot import png_pixels

#: A pixel darker than this in some channel is ink.
INK = chart.INK_LEVEL


def test_the_capability_matches_the_running_blender():
    # blf.bind_imbuf came with Blender 4.3: 4.2 LTS charts go through the glyph outlines.
    assert compat.BLF_DRAWS_INTO_IMBUF == (bpy.app.version >= (4, 3, 0)), bpy.app.version


def test_a_zero_is_a_ring_with_its_hole_open():
    size = 60
    with glyph_outlines.GlyphOutlines() as glyphs:
        edges = glyphs.edges("0") * size
    lo, hi = edges.reshape(-1, 2).min(axis=0), edges.reshape(-1, 2).max(axis=0)
    # A digit of a 60 px font stands on the baseline, about 0.73 em tall and 0.5 em wide.
    assert lo[1] == pytest.approx(0.0, abs=1.5) and hi[1] == pytest.approx(0.73 * size, rel=0.1), (lo, hi)
    assert 0.35 * size < hi[0] - lo[0] < 0.65 * size, (lo, hi)
    w, h = int(np.ceil(hi[0])) + 1, int(np.ceil(hi[1])) + 1
    cover = glyph_outlines.fill_coverage(edges, (h, w))
    mid_x, mid_y = int(0.5 * (lo[0] + hi[0])), int(0.5 * (lo[1] + hi[1]))
    assert cover[mid_y, mid_x] == 0.0, "the hole of the 0 is filled"
    assert cover[mid_y, int(lo[0]) + 2] == 1.0, "the left stroke of the 0 is empty"
    assert cover[int(lo[1]) + 1, mid_x] == 1.0, "the bottom stroke of the 0 is empty"
    # Antialiased: the edge pixels are partly covered.
    assert ((cover > 0.05) & (cover < 0.95)).sum() > 20
    assert bpy.data.objects.get(".batten glyphs") is None, "the text object is left behind"


def _chart(tmp_path, name, monkeypatch, use_blf: bool):
    monkeypatch.setattr(compat, "BLF_DRAWS_INTO_IMBUF", use_blf)
    canvas = chart.Canvas(240, 60)
    canvas.text(120, 30, "∇ = 1,234.5 m³", size=18, align="center", valign="center")
    return png_pixels(canvas.save_png(tmp_path / name))


def test_the_glyph_text_is_where_the_font_engine_puts_it(tmp_path, monkeypatch):
    pixels = _chart(tmp_path, "glyphs.png", monkeypatch, use_blf=False)
    ink = (pixels[..., :3] < INK).any(axis=-1)
    rows, cols = np.nonzero(ink)
    assert ink.sum() > 150, ink.sum()
    # Centred on (120, 30): the ink's box has its middle there, within a few pixels.
    assert abs(0.5 * (cols.min() + cols.max()) - 120) < 4, (cols.min(), cols.max())
    assert abs(0.5 * (rows.min() + rows.max()) - 30) < 6, (rows.min(), rows.max())
    if not compat.BLF_DRAWS_INTO_IMBUF:
        return
    drawn = _chart(tmp_path, "blf.png", monkeypatch, use_blf=True)
    blf_ink = (drawn[..., :3] < INK).any(axis=-1)
    b_rows, b_cols = np.nonzero(blf_ink)
    # The same size (Blender's text objects use a narrower built-in font than blf): as
    # tall within 2 px, centred on the same point within 3 px, 75-100 % as wide.
    assert abs((rows.max() - rows.min()) - (b_rows.max() - b_rows.min())) <= 2
    assert abs((cols.min() + cols.max()) - (b_cols.min() + b_cols.max())) <= 6
    assert abs((rows.min() + rows.max()) - (b_rows.min() + b_rows.max())) <= 6
    assert 0.75 < (cols.max() - cols.min()) / (b_cols.max() - b_cols.min()) <= 1.0
