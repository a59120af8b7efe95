"""The hydrostatics plots: PNGs of the set size whose curves are where the data are (drawn
pixels along each curve, background away from it), with text drawn on (axes numbers,
labels), shown as a Blender image."""

import bpy
import numpy as np
from batten import chart, hydro_plot

L, B, T = 100.0, 10.0, 6.25


def _is_background(rgba) -> np.ndarray:
    return np.all(np.asarray(rgba)[..., :3] > 0.97, axis=-1)


def _near(pixels, points, radius: int = 1) -> np.ndarray:
    """Per point, whether any pixel within ``radius`` is drawn (not background)."""
    out = []
    for x, y in np.round(points).astype(int):
        block = pixels[max(y - radius, 0) : y + radius + 1, max(x - radius, 0) : x + radius + 1]
        out.append(not _is_background(block).all())
    return np.array(out)


def _figures(draft: float) -> dict:
    return {
        "x_ap": -L / 2,
        "x_fp": L / 2,
        "max_section_x": 0.0,
        "max_section_area": 2 / 3 * B * draft,
        "draft_mid": draft,
        "trim": 0.0,
        "heel": 0.0,
        "volume": 4 / 9 * L * B * draft,
    }


def test_the_sac_image_has_its_curve_marks_and_numbers(tmp_path):
    xs = np.linspace(-L / 2, L / 2, 21)
    areas = 2 / 3 * B * T * (1 - (2 * xs / L) ** 2)
    path, axes = hydro_plot.sac_png("wigley", xs, areas, _figures(T), tmp_path / "sac.png")
    pixels = hydro_plot.png_pixels(path)
    assert pixels.shape[:2] == hydro_plot.SAC_SIZE[::-1]
    # The curve: drawn at every station, in the curve's colour at a quarter length (Ax is marked at midships).
    on = axes.to_px(xs, areas)
    assert _near(pixels, on).all()
    x, y = np.round(on[5]).astype(int)
    assert np.abs(pixels[y, x, :3] - chart.PALETTE[0][:3]).max() < 0.1, pixels[y, x]
    # Above the curve, inside the frame, away from marks and grid: background.
    above = axes.to_px([-30.0, 30.0], [45.0, 45.0])
    assert not _near(pixels, above, radius=2).any()
    # Text: the tick numbers under the x axis are drawn (dark pixels in their band).
    left, bottom, right, _top = axes.box
    band = pixels[int(bottom - 30) : int(bottom - 8), int(left) : int(right)]
    assert (band[..., :3].max(axis=-1) < 0.3).sum() > 200, "tick numbers"


def test_the_curves_of_form_have_every_panel_s_curves(tmp_path):
    drafts = np.linspace(1.0, 8.0, 8)
    keys = {k for _t, _u, curves, _s in hydro_plot.CURVES_OF_FORM_PANELS for k, _ in curves} | {
        "density",
        "lpp",
    }
    rows = [
        {k: (i + 1.0) * d ** (1 + i % 3) for i, k in enumerate(sorted(keys))} | {"draft_mid": d}
        for d in drafts
    ]
    for r in rows:
        r.update(density=1.025, lpp=L, trim=0.0)
    path, all_axes = hydro_plot.curves_of_form_png("wigley", rows, tmp_path / "cof.png")
    pixels = hydro_plot.png_pixels(path)
    assert pixels.shape[:2] == hydro_plot.CURVES_OF_FORM_SIZE[::-1]
    assert len(all_axes) == len(hydro_plot.CURVES_OF_FORM_PANELS)
    for axes, (title, _unit, curves, _scale) in zip(all_axes, hydro_plot.CURVES_OF_FORM_PANELS, strict=True):
        for key, _label in curves:
            values = [r[key] for r in rows]
            assert _near(pixels, axes.to_px(values, drafts)).all(), f"{title}: {key}"


def test_a_plot_is_one_packed_image_updated_in_place(tmp_path):
    xs = np.linspace(-L / 2, L / 2, 11)
    name = hydro_plot.sac_image_name("wigley")
    for draft in (T, 3.0):
        areas = 2 / 3 * B * draft * (1 - (2 * xs / L) ** 2)
        image = hydro_plot.plot_image(
            name, lambda p, a=areas, d=draft: hydro_plot.sac_png("wigley", xs, a, _figures(d), p)
        )
    assert [i.name for i in bpy.data.images] == [name], "one image, no leftovers"
    assert image.packed_file is not None and tuple(image.size) == hydro_plot.SAC_SIZE
