"""Pictures of the hydrostatics: the sectional area curve and the curves of form, drawn to PNG
files (:mod:`batten.chart`) and shown as Blender images (``bpy.data.images``, updated in place
on every re-plot and packed into the .blend, so they stay with the file).

The numbers come from :mod:`batten.api` (:func:`~batten.api.sectional_areas`,
:func:`~batten.api.hydrostatics`, :func:`~batten.api.curves_of_form`); this module only draws
them.
"""

from __future__ import annotations

import os
import tempfile
import textwrap
from pathlib import Path

import numpy as np

from .chart import PALETTE, Axes, Canvas

#: Image sizes, pixels (width, height).
SAC_SIZE = (1400, 700)
CURVES_OF_FORM_SIZE = (1800, 1400)
#: Text size of the charts, pixels.
TEXT_SIZE = 16
#: Colour of a warning on a plot, and its characters per line.
NOTE = (0.8, 0.1, 0.1, 1.0)
NOTE_LINE_CHARS = 140
#: Colour of the area under the sectional area curve (the volume it integrates to).
SAC_FILL = (0.0, 0.447, 0.698, 0.12)

#: The panels of the curves of form, each against the draft (vertical axis, as naval
#: architects draw them): a title, the unit of its horizontal axis, its curves (key, legend
#: label), and the figure whose size sets the smallest change drawn (None: the curves' own).
CURVES_OF_FORM_PANELS: tuple[tuple[str, str, tuple[tuple[str, str], ...], str | None], ...] = (
    ("Volume ∇", "m³", (("volume", "∇"),), None),
    ("Displacement Δ", "t", (("displacement", "Δ"),), None),
    ("Wetted surface S", "m²", (("wetted_area", "S"),), None),
    ("Waterplane area Awp", "m²", (("waterplane_area", "Awp"),), None),
    ("KB and KMt", "m", (("vcb", "KB"), ("kmt", "KMt")), None),
    ("BMt", "m", (("bmt", "BMt"),), None),
    ("BMl", "m", (("bml", "BMl"),), None),
    ("LCB and LCF (x)", "m", (("lcb", "LCB"), ("lcf", "LCF")), "lpp"),
    ("TPC", "t/cm", (("tpc", "TPC"),), None),
    ("MTC (basis Lpp)", "t·m/cm", (("mtc", "MTC"),), None),
    ("Coefficients", "-", (("cb", "Cb"), ("cp", "Cp"), ("cm", "Cm"), ("cwp", "Cwp")), None),
    ("Midship area Am", "m²", (("midship_area", "Am"),), None),
)
#: A curve of form changing by less than this share of its scale (the panel's figure, or its
#: largest value) is drawn straight: what is left is the rounding of the integration (an LCB at
#: midships to 1e-10 m), not a change of the hull.
MIN_CHANGE_SHARE = 1e-3
#: Panels per row of the curves of form.
PANEL_COLUMNS = 4


def sac_image_name(hull: str) -> str:
    """The Blender image of a hull's sectional area curve."""
    return f"{hull} SAC"


def curves_of_form_image_name(hull: str) -> str:
    """The Blender image of a hull's curves of form."""
    return f"{hull} curves of form"


def sac_png(hull: str, xs, areas, figures: dict, path, *, note: str = "") -> tuple[Path, Axes]:
    """Draw the sectional area curve A(x) of ``hull`` (stations ``xs``, immersed areas
    ``areas``, as from :func:`batten.api.sectional_areas`) with the aft and forward
    perpendiculars, midships and the largest section Ax marked, to the PNG ``path``.
    ``figures``: the hydrostatics at the same flotation (``x_ap``, ``x_fp`` and ``draft_mid``
    at least; without ``max_section_x`` / ``max_section_area`` Ax is the largest station, and
    ∇ is given when ``volume`` is). ``note``: a warning written in red under the title.
    Returns the path and the axes (their ``to_px`` places data on the image)."""
    xs, areas = np.asarray(xs, float), np.asarray(areas, float)
    x_ap, x_fp = figures["x_ap"], figures["x_fp"]
    largest = int(np.argmax(areas))
    x_ax = figures.get("max_section_x", xs[largest])
    a_ax = figures.get("max_section_area", areas[largest])
    canvas = Canvas(*SAC_SIZE)
    s = TEXT_SIZE
    w, h = SAC_SIZE
    notes = _lines(note)
    axes = Axes.fit(
        canvas,
        (6 * s, 5 * s, w - 2 * s, h - 5 * s - 1.4 * s * len(notes)),
        np.concatenate([xs, [x_ap, x_fp]]),
        np.concatenate([areas, [0.0, a_ax]]),
        xcount=10,
        ycount=6,
    )
    volume = f"; ∇ = {figures['volume']:,.1f} m³" if "volume" in figures else ""
    axes.frame(xlabel="x (m, forward)", ylabel="A (m²)", size=s)
    title = f"{hull}: sectional areas at {_flotation_text(figures)}{volume}"
    canvas.text(w / 2, h - 2 * s, title, size=round(1.2 * s), align="center")
    for i, line in enumerate(notes):
        canvas.text(w / 2, h - 3.6 * s - 1.4 * s * i, line, size=s, color=NOTE, align="center")
    curve = axes.to_px(xs, areas)
    canvas.fill_below(curve, axes.to_px([xs[0]], [0.0])[0, 1], SAC_FILL)
    axes.plot(xs, areas, PALETTE[0], width=3.0)
    axes.vline(x_ap, "AP", size=s)
    axes.vline(x_fp, "FP", size=s)
    axes.vline(0.5 * (x_ap + x_fp), "midships", size=s)
    (px, py) = axes.to_px([x_ax], [a_ax])[0]
    canvas.disc((px, py), 6.0, PALETTE[1])
    canvas.text(px + 10, py + 10, f"Ax = {a_ax:,.2f} m² at x = {x_ax:.2f} m", size=s, color=PALETTE[1])
    return canvas.save_png(path), axes


def comparison_image_name(copy: str) -> str:
    """The Blender image of a copy's sectional areas beside its original's."""
    return f"{copy} vs original SAC"


def sac_comparison_png(comparison: dict, path) -> tuple[Path, Axes]:
    """Draw the sectional area curves of a copy and its original on one chart (``comparison``
    from :func:`batten.api.compare`), each hull's AP and FP marked (the copy's dashed in its
    colour where they moved), the change of ∇ in the title, to the PNG ``path``. Returns the
    path and the axes."""
    sac = comparison["sac"]
    (xo, ao), (xc, ac) = (
        (np.asarray(v, float) for v in sac["original"]),
        (np.asarray(v, float) for v in sac["copy"]),
    )
    canvas = Canvas(*SAC_SIZE)
    s = TEXT_SIZE
    w, h = SAC_SIZE
    axes = Axes.fit(
        canvas,
        (6 * s, 5 * s, w - 2 * s, h - 6.5 * s),
        np.concatenate([xo, xc]),
        np.concatenate([ao, ac, [0.0]]),
        xcount=10,
        ycount=6,
    )
    axes.frame(xlabel="x (m, forward)", ylabel="A (m²)", size=s)
    volume = next((r for r in comparison["hydrostatics"] if r["key"] == "volume"), None)
    change = ""
    if volume is not None and volume["change"] is not None:
        change = f"; ∇ {volume['original']:,.1f} → {volume['copy']:,.1f} m³ ({volume['change_pct']:+.2f} %)"
    title = f"{comparison['copy']} ({comparison['description']}) beside {comparison['original']}"
    canvas.text(w / 2, h - 2 * s, title, size=round(1.2 * s), align="center")
    canvas.text(
        w / 2,
        h - 3.8 * s,
        f"sectional areas at T = {comparison['draft']:.3f} m{change}",
        size=s,
        align="center",
    )
    canvas.fill_below(axes.to_px(xo, ao), axes.to_px([xo[0]], [0.0])[0, 1], SAC_FILL)
    axes.plot(xo, ao, PALETTE[0], width=3.0)
    axes.plot(xc, ac, PALETTE[1], width=3.0, dash=(14.0, 6.0))
    (ap_o, fp_o), (ap_c, fp_c) = (
        comparison["perpendiculars"]["original"],
        comparison["perpendiculars"]["copy"],
    )
    axes.vline(ap_o, "AP", size=s)
    axes.vline(fp_o, "FP", size=s)
    moved = max(abs(fp_o - ap_o), 1.0) * 1e-9
    if abs(ap_c - ap_o) > moved:
        axes.vline(ap_c, "AP'", PALETTE[1], size=s)
    if abs(fp_c - fp_o) > moved:
        axes.vline(fp_c, "FP'", PALETTE[1], size=s)
    axes.legend([(comparison["original"], PALETTE[0]), (comparison["copy"], PALETTE[1])], size=s)
    return canvas.save_png(path), axes


def _lines(note: str) -> list[str]:
    """A note's lines as drawn (wrapped at :data:`NOTE_LINE_CHARS`)."""
    return textwrap.wrap(note, NOTE_LINE_CHARS)


def curves_of_form_png(hull: str, rows: list[dict], path) -> tuple[Path, list[Axes]]:
    """Draw the curves of form of ``hull`` (``rows``: one hydrostatics dict per draft, as from
    :func:`batten.api.curves_of_form`) to the PNG ``path``: one panel per quantity of
    :data:`CURVES_OF_FORM_PANELS`, each against the draft at midships with its own axis and
    unit. Returns the path and the panels' axes (in that order)."""
    drafts = np.array([r["draft_mid"] for r in rows], dtype=float)
    w, h = CURVES_OF_FORM_SIZE
    s = TEXT_SIZE
    canvas = Canvas(w, h)
    n_rows = -(-len(CURVES_OF_FORM_PANELS) // PANEL_COLUMNS)
    cell_w, cell_h = w / PANEL_COLUMNS, (h - 4 * s) / n_rows
    canvas.text(
        w / 2,
        h - 2 * s,
        f"{hull}: curves of form ({_condition_text(rows[0])})",
        size=round(1.3 * s),
        align="center",
    )
    all_axes = []
    for i, (title, unit, curves, scale_key) in enumerate(CURVES_OF_FORM_PANELS):
        col, row = i % PANEL_COLUMNS, i // PANEL_COLUMNS
        left, top = col * cell_w, h - 4 * s - row * cell_h
        box = (left + 5.5 * s, top - cell_h + 4 * s, left + cell_w - 1.5 * s, top - 3.5 * s)
        values = np.array([[r[key] for r in rows] for key, _ in curves], dtype=float)
        scale = rows[0][scale_key] if scale_key else np.abs(values).max()
        axes = Axes.fit(canvas, box, values, drafts, xcount=4, ycount=5, xmin_span=MIN_CHANGE_SHARE * scale)
        axes.frame(xlabel=f"{title} ({unit})", ylabel="T (m)", size=s)
        for j, values_j in enumerate(values):
            axes.plot(values_j, drafts, PALETTE[j], width=2.5)
        if len(curves) > 1:
            axes.legend([(label, PALETTE[j]) for j, (_k, label) in enumerate(curves)], size=s)
        all_axes.append(axes)
    return canvas.save_png(path), all_axes


def _flotation_text(figures: dict) -> str:
    text = f"T = {figures['draft_mid']:.3f} m"
    if figures.get("trim"):
        text += f", trim {figures['trim']:.3f} m"
    if figures.get("heel"):
        text += f", heel {figures['heel']:.1f}°"
    return text


def _condition_text(figures: dict) -> str:
    text = f"ρ = {figures['density']:.4f} t/m³, Lpp = {figures['lpp']:.2f} m"
    return text + (f", trim {figures['trim']:.3f} m" if figures.get("trim") else ", even keel")


def png_pixels(path) -> np.ndarray:
    """The image file at ``path`` as RGBA floats (h, w, 4), row 0 at the bottom (read by
    Blender; no image is left behind)."""
    import bpy

    loaded = bpy.data.images.load(str(path), check_existing=False)
    try:
        w, h = loaded.size
        pixels = np.empty(w * h * 4, dtype=np.float32)
        loaded.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(loaded)
    return pixels.reshape(h, w, 4)


def show_image(name: str, path):
    """The Blender image ``name`` holding the picture in the PNG ``path``: made, or updated in
    place (resized if need be) when it exists, and packed into the .blend. Returns it."""
    import bpy

    pixels = png_pixels(path)
    h, w = pixels.shape[:2]
    image = bpy.data.images.get(name)
    if image is None:
        image = bpy.data.images.new(name, w, h, alpha=True)
    elif tuple(image.size) != (w, h):
        image.scale(w, h)
    image.pixels.foreach_set(pixels.ravel())
    image.update()
    image.pack()
    return image


def show_in_image_editors(context, image) -> None:
    """Show ``image`` in every Image Editor of the window's screen (none headless)."""
    screen = getattr(context, "screen", None)
    for area in screen.areas if screen is not None else ():
        if area.type == "IMAGE_EDITOR":
            area.spaces.active.image = image


def plot_image(name: str, draw) -> object:
    """Run ``draw(path)`` (one of the ``*_png`` functions with its data bound) into a temporary
    PNG and show it as the Blender image ``name`` (:func:`show_image`); returns the image."""
    fd, tmp = tempfile.mkstemp(suffix=".png", prefix=".batten_plot_")
    os.close(fd)
    try:
        draw(tmp)
        return show_image(name, tmp)
    finally:
        os.unlink(tmp)
