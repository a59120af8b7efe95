"""The lines plan of a hull laid out as a :class:`~batten.drawing.Drawing` (no Blender needed).

The three views of the classic lines plan, in model metres on one sheet:

- the **profile** (x forward to the right, z up), with the buttocks as curves, the stations
  and waterlines as the straight grid, the DWL, baseline, AP and FP;
- the **half-breadth plan** below it on the same x (the centreline at its top, y downwards),
  with the waterlines as curves, the stations and buttocks as the grid, and the diagonals
  expanded above its centreline (distance along each diagonal plane from the centreplane);
- the **body plan** to the right of the profile on the same z, the aft half of the stations
  to the left of its centreline and the fore half to the right, the waterlines and buttocks
  as its grid and each diagonal as a straight line;

the knuckle lines and the outline (keel, stem, transom, deck edge) in all three, stations
numbered from the AP on the 0–20 scale (station 10 amidships), waterlines by their height
above the baseline, buttocks by their offset from the centreplane, and a title block with
the main dimensions and the hydrostatics at the DWL. Sections are any objects with
``family``, ``offset``, ``name`` and ``polylines`` ((n, 3) arrays of the port half), as
:class:`batten.sections.Section`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import hydro_table
from .drawing import CHAR_WIDTH, Drawing

#: Families of sections drawn as curves, and the layer of each.
FAMILIES = ("stations", "waterlines", "buttocks", "diagonals", "knuckles")
#: Station numbers run 0 (AP) to this (FP), the classic 20 intervals.
STATION_INTERVALS = 20
#: Text height as a share of the sheet's width (so about 3 mm on an A3 sheet).
TEXT_SHARE = 1.0 / 140.0
#: Gap between the views, in text heights.
GAP_TEXTS = 4.0
#: How far grid lines run past the hull, in text heights.
OVERRUN_TEXTS = 0.8
#: Two stations closer than this share of Lpp are the same one (the midship station is drawn
#: on both halves of the body plan).
SAME_STATION = 1e-6
#: The figures of the title block, by key of :func:`batten.api.hydrostatics`.
TITLE_FIGURES = ("volume", "displacement", "wetted_area", "waterplane_area", "cb", "cp", "cm", "cwp")
TITLE_CENTRES = ("lcb", "lcf", "vcb", "kmt")


@dataclass(frozen=True)
class Hull:
    """What the title block and the datums need: the hull's name, the perpendiculars (x of
    AP and FP), the draft of the DWL (m above the baseline) and the hydrostatics there (a dict
    as from :func:`batten.api.hydrostatics`, or None when they could not be had; ``note``
    then says why)."""

    name: str
    x_ap: float
    x_fp: float
    draft: float
    hydrostatics: dict | None = None
    note: str = ""


def station_number(x: float, hull: Hull) -> str:
    """The station's number on the 0 (AP) – 20 (FP) scale, as short as it reads."""
    n = STATION_INTERVALS * (x - hull.x_ap) / (hull.x_fp - hull.x_ap)
    return f"{n:.2f}".rstrip("0").rstrip(".").replace("-0", "0") if abs(n) >= 0.005 else "0"


def _metres(v: float) -> str:
    return f"{v:.2f}"


def spaced(positions, room: float) -> list[int]:
    """The indices of ``positions`` to label so that labelled ones lie ``room`` apart or more:
    from the first in order, each next one far enough from the last kept."""
    order = np.argsort(positions)
    kept: list[int] = []
    for i in order:
        if not kept or positions[i] - positions[kept[-1]] >= room:
            kept.append(int(i))
    return kept


def _extent(sections: dict, outline: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """The box ``lo``, ``hi`` (x, y, z) of every polyline and outline curve."""
    pts = [p for fam in FAMILIES for s in sections.get(fam, ()) for p in s.polylines if len(p)]
    pts += [c for c in outline if len(c)]
    if not pts:
        raise ValueError("no sections to draw: the surface has no lines in these planes")
    allp = np.vstack(pts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    lo[1] = 0.0
    return lo, hi


def diagonal_frame(polylines: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray] | None:
    """A diagonal plane (parallel to x) from its section's points: the point where its trace
    in the body plan meets the centreplane (y = 0, z) and the unit direction (y, z) along it
    outwards; None when the points do not fix a line."""
    yz = np.vstack([p[:, 1:] for p in polylines if len(p)]) if polylines else np.empty((0, 2))
    if len(yz) < 2:
        return None
    centre = yz.mean(axis=0)
    _, s, vt = np.linalg.svd(yz - centre, full_matrices=False)
    if s[0] <= 0.0:
        return None
    d = vt[0] if vt[0][0] >= 0 else -vt[0]
    if d[0] <= 0.0:
        return None
    origin = centre - d * (centre[0] / d[0])
    return origin, d


class _Sheet:
    """The views' places on the sheet for one hull."""

    def __init__(self, lo, hi, hull: Hull, diagonal_reach: float):
        self.lo, self.hi, self.hull, self.diagonal_reach = lo, hi, hull, diagonal_reach
        self.half_beam = float(hi[1])
        width = (hi[0] - lo[0]) + 2 * self.half_beam
        self.h = TEXT_SHARE * width * 1.25
        self.gap = GAP_TEXTS * self.h
        self.over = OVERRUN_TEXTS * self.h
        # The plan's centreline: below the profile, with room for the expanded diagonals.
        self.plan_cl = lo[2] - self.gap - diagonal_reach
        # The body plan's centreline: right of the profile (and of its labels).
        self.body_cl = hi[0] + self.gap + 3 * self.h + self.half_beam
        self.mid = 0.5 * (hull.x_ap + hull.x_fp)

    def profile(self, p):
        return p[:, [0, 2]]

    def plan(self, p):
        return np.column_stack([p[:, 0], self.plan_cl - p[:, 1]])

    def body(self, p, side: float):
        return np.column_stack([self.body_cl + side * p[:, 1], p[:, 2]])

    def side_of(self, x: float) -> list[float]:
        """The body plan halves a station at ``x`` is drawn in: aft −1 (left), fore +1."""
        lpp = abs(self.hull.x_fp - self.hull.x_ap)
        if abs(x - self.mid) <= SAME_STATION * lpp:
            return [-1.0, 1.0]
        return [-1.0] if x < self.mid else [1.0]


def layout(sections: dict, outline: list[np.ndarray], hull: Hull) -> Drawing:
    """The lines plan of a hull from its ``sections`` (a dict family → list of sections, as
    from :func:`batten.api.sections`), its ``outline`` curves ((n, 3) points: keel, stem,
    transom, deck edge) and the datums and figures of ``hull``."""
    if not hull.x_fp > hull.x_ap:
        raise ValueError(f"FP (x = {hull.x_fp}) must lie forward of AP (x = {hull.x_ap})")
    lo, hi = _extent(sections, outline)
    frames = [(s, diagonal_frame(s.polylines)) for s in sections.get("diagonals", ())]
    reach = max(
        (float(np.hypot(*(p[:, 1:] - f[0]).T).max()) for s, f in frames if f for p in s.polylines if len(p)),
        default=0.0,
    )
    sheet = _Sheet(lo, hi, hull, reach)
    d = Drawing(title=hull.name, text_height=sheet.h)
    # The body plan's centreline (x on the sheet) and the half-breadth plan's (y on the sheet):
    # a section point (x, y, z) is at (body_cl ± y, z) and (x, plan_cl − y).
    d.marks.update(body_plan_cl=sheet.body_cl, half_breadth_cl=sheet.plan_cl)
    _grid(d, sheet, sections)
    _curves(d, sheet, sections, outline, frames)
    _title_block(d, sheet)
    return d


def _grid(d: Drawing, sh: _Sheet, sections: dict) -> None:
    """The planes of the sections as straight lines in the views they are seen edge-on in,
    with their labels; the baseline, the DWL and the perpendiculars."""
    lo, hi, h, o = sh.lo, sh.hi, sh.h, sh.over
    b, hull = sh.half_beam, sh.hull
    z_top = hi[2] + o
    xs = np.array([float(s.offset) for s in sections.get("stations", ())])
    numbers = [station_number(x, hull) for x in xs]
    for x in xs:
        d.line("grid", [(x, lo[2] - o), (x, z_top)])
        d.line("grid", [(x, sh.plan_cl + sh.diagonal_reach + o), (x, sh.plan_cl - b - o)])
    for i in spaced(xs, CHAR_WIDTH * h * (max(map(len, numbers), default=1) + 1)):
        d.text("grid", xs[i], lo[2] - o - 0.5 * h, numbers[i], align="center", valign="top")
        d.text("grid", xs[i], sh.plan_cl - b - o - 0.5 * h, numbers[i], align="center", valign="top")
    zs = np.array([float(s.offset) for s in sections.get("waterlines", ())])
    for z in zs:
        d.line("grid", [(lo[0] - o, z), (hi[0] + o, z)])
        d.line("grid", [(sh.body_cl - b - o, z), (sh.body_cl + b + o, z)])
    for i in spaced(zs, 1.3 * h):
        d.text("grid", lo[0] - o - 0.4 * h, zs[i], f"WL {_metres(zs[i])}", align="right", valign="center")
        d.text("grid", sh.body_cl + b + o + 0.4 * h, zs[i], _metres(zs[i]), valign="center")
    ys = np.array([float(s.offset) for s in sections.get("buttocks", ())])
    for y in ys:
        d.line("grid", [(lo[0] - o, sh.plan_cl - y), (hi[0] + o, sh.plan_cl - y)])
        for side in (-1.0, 1.0):
            d.line("grid", [(sh.body_cl + side * y, lo[2] - o), (sh.body_cl + side * y, z_top)])
    for i in spaced(np.concatenate([[0.0], ys]), 1.3 * h):
        if i > 0:
            y = ys[i - 1]
            d.text(
                "grid",
                lo[0] - o - 0.4 * h,
                sh.plan_cl - y,
                f"BT {_metres(y)}",
                align="right",
                valign="center",
            )
    for i in spaced(np.concatenate([[0.0], ys]), CHAR_WIDTH * h * 5):
        if i > 0:
            y = ys[i - 1]
            d.text("grid", sh.body_cl + y, lo[2] - o - 0.5 * h, _metres(y), align="center", valign="top")
    # Centrelines, baseline, DWL, perpendiculars.
    d.line("grid", [(lo[0] - o, sh.plan_cl), (hi[0] + o, sh.plan_cl)])
    d.text("grid", lo[0] - o - 0.4 * h, sh.plan_cl, "CL", align="right", valign="center")
    d.line("grid", [(sh.body_cl, lo[2] - o), (sh.body_cl, z_top)])
    d.text("grid", sh.body_cl, z_top + 0.5 * h, "CL", align="center")
    d.line("outline", [(lo[0] - o, 0.0), (hi[0] + o, 0.0)])
    d.text("grid", hi[0] + o + 0.4 * h, 0.0, "BL", valign="center")
    t = hull.draft
    d.line("dwl", [(lo[0] - 2 * o, t), (hi[0] + 2 * o, t)], dashed=True)
    d.line("dwl", [(sh.body_cl - b - 2 * o, t), (sh.body_cl + b + 2 * o, t)], dashed=True)
    d.text("dwl", hi[0] + o + 0.4 * h, t, "DWL", valign="center")
    for x, name in ((hull.x_ap, "AP"), (hull.x_fp, "FP")):
        d.line("grid", [(x, lo[2] - 2 * o), (x, z_top + o)])
        d.text("grid", x, z_top + o + 0.4 * h, name, align="center")
    d.text("title", lo[0], z_top + o + 2.4 * h, "PROFILE", height=1.3 * h)
    d.text("title", lo[0], sh.plan_cl - b - o - 3.2 * h, "HALF-BREADTH PLAN", height=1.3 * h, valign="top")
    d.text("title", sh.body_cl, z_top + o + 2.4 * h, "BODY PLAN", height=1.3 * h, align="center")
    d.text("grid", sh.body_cl - 0.5 * b, lo[2] - o - 2.2 * h, "AFT", align="center", valign="top")
    d.text("grid", sh.body_cl + 0.5 * b, lo[2] - o - 2.2 * h, "FORE", align="center", valign="top")


def _curves(d: Drawing, sh: _Sheet, sections: dict, outline, frames) -> None:
    """The sections as curves in the views that show them true, the knuckle lines and the
    outline in all three."""
    for s in sections.get("stations", ()):
        for side in sh.side_of(float(s.offset)):
            for p in s.polylines:
                d.line("stations", sh.body(p, side))
    for s in sections.get("waterlines", ()):
        for p in s.polylines:
            d.line("waterlines", sh.plan(p))
    for s in sections.get("buttocks", ()):
        for p in s.polylines:
            d.line("buttocks", sh.profile(p))
    for k, (s, frame) in enumerate(frames, start=1):
        if frame is None:
            continue
        origin, direction = frame
        reach = 0.0
        for p in s.polylines:
            along = (p[:, 1:] - origin) @ direction
            reach = max(reach, float(along.max()))
            d.line("diagonals", np.column_stack([p[:, 0], sh.plan_cl + along]))
        end = origin + direction * (reach + sh.over)
        for side in (-1.0, 1.0):
            d.line("diagonals", [(sh.body_cl, origin[1]), (sh.body_cl + side * end[0], end[1])])
        # Named D1, D2… in order (a section's own name, "diagonal 5.000 -35.0°", is long).
        name = f"D{k}"
        d.text("diagonals", sh.body_cl - end[0] - 0.3 * sh.h, end[1], name, align="right", valign="center")
        d.text("diagonals", sh.lo[0] - sh.over - 0.4 * sh.h, sh.plan_cl + reach, name, align="right")
    for layer, curves in (
        ("knuckles", [p for s in sections.get("knuckles", ()) for p in s.polylines]),
        ("outline", outline),
    ):
        for p in curves:
            if len(p) < 2:
                continue
            d.line(layer, sh.profile(p))
            d.line(layer, sh.plan(p))
            aft = p[:, 0] <= sh.mid
            for side, keep in ((-1.0, aft), (1.0, ~aft)):
                # Each half with its neighbour across midships, so the pieces meet there.
                grown = keep | np.roll(keep, 1) | np.roll(keep, -1)
                d.line(layer, np.where(grown[:, None], sh.body(p, side), np.nan))


def _title_block(d: Drawing, sh: _Sheet) -> None:
    """The hull's name, main dimensions and hydrostatics at the DWL, in a ruled box of two
    columns at the bottom right of the sheet, below the plan and the body plan."""
    hull, h = sh.hull, sh.h
    lpp = hull.x_fp - hull.x_ap
    left = [
        ("Length over all", f"{sh.hi[0] - sh.lo[0]:.3f} m"),
        ("Length b.p. Lpp", f"{lpp:.3f} m"),
        ("Breadth B", f"{2 * sh.half_beam:.3f} m"),
        ("Depth D", f"{sh.hi[2] - min(sh.lo[2], 0.0):.3f} m"),
        ("Draft T (DWL)", f"{hull.draft:.3f} m"),
    ]
    right: list[tuple[str, str]] = []
    fig = hull.hydrostatics
    if fig:
        by_key = {row.key: row for row in hydro_table.ROWS}
        left += [(by_key[k].label, hydro_table.value_text(by_key[k], fig)) for k in TITLE_FIGURES[:4]]
        right = [
            (by_key[k].label, hydro_table.value_text(by_key[k], fig))
            for k in TITLE_FIGURES[4:] + TITLE_CENTRES
        ]
    else:
        left.append(("Hydrostatics", hull.note or "not available"))
    line = 1.6 * h
    columns = [c for c in (left, right) if c]
    widths = [(max(len(r[0]) for r in c) * 0.72 + max(len(r[1]) for r in c) * 0.8 + 3) * h for c in columns]
    x1 = sh.body_cl + sh.half_beam + sh.over + 4 * h
    x0 = x1 - sum(widths)
    top = sh.plan_cl - sh.half_beam - sh.over - 4.5 * h - sh.gap
    title_h = 1.5 * h
    rule = top - 2 * title_h - 1.2 * h
    bottom = rule - line * (max(len(c) for c in columns) + 0.6)
    d.line("title", [(x0, top), (x1, top), (x1, bottom), (x0, bottom), (x0, top)])
    d.text("title", x0 + h, top - 0.6 * h, f"{hull.name}: lines plan", height=title_h, valign="top")
    d.text(
        "title",
        x0 + h,
        top - 1.1 * title_h - 0.9 * h,
        "Main dimensions and hydrostatics at the DWL",
        valign="top",
    )
    d.line("title", [(x0, rule), (x1, rule)])
    cx = x0
    for column, width in zip(columns, widths, strict=True):
        if cx > x0:
            d.line("title", [(cx, rule), (cx, bottom)])
        for i, (label, value) in enumerate(column):
            y = rule - line * (i + 1)
            d.text("title", cx + h, y, label)
            d.text("title", cx + width - h, y, value, align="right")
        cx += width


#: Default waterlines: this many between the baseline and the DWL (the DWL the last), and on
#: at the same spacing up to the top of the hull.
WATERLINES_TO_DWL = 5
#: Default buttocks: at these shares of the largest half-breadth.
BUTTOCK_SHARES = (0.2, 0.4, 0.6, 0.8)
#: A waterline closer than this share of the spacing under the top of the hull is left out
#: (it would cut only the deck edge).
TOP_CLEARANCE = 0.25


def default_waterlines(draft: float, top: float) -> list[float]:
    """The heights of the default waterlines: :data:`WATERLINES_TO_DWL` evenly up to the DWL
    at ``draft``, then at the same spacing while below ``top`` (the hull's highest point)."""
    step = draft / WATERLINES_TO_DWL
    count = int(np.floor((top - step * TOP_CLEARANCE) / step))
    return [step * k for k in range(1, max(count, WATERLINES_TO_DWL) + 1)]


def default_buttocks(half_beam: float) -> list[float]:
    """The offsets of the default buttocks, :data:`BUTTOCK_SHARES` of ``half_beam``."""
    return [share * half_beam for share in BUTTOCK_SHARES]


#: Decimals of the offsets printed with a lines plan (millimetres).
OFFSET_DECIMALS = 3


def offsets_tables(sections: dict, hull: Hull) -> list[tuple[str, list[str], list[list[str]]]]:
    """The offsets table of the drawn sections, as the PDF prints it after the plan: the
    half-breadths where the stations cross the waterlines, and the heights where they cross the
    buttocks (m, read off the station sections by :func:`batten.offsets.crossings`; several
    crossings of one station joined as in the offsets CSV, none left empty). Each table is
    (title, header, rows): a row per waterline or buttock, a column per station (by number)."""
    from .offsets import CELL_SEPARATOR, crossings

    stations = sorted(sections.get("stations", ()), key=lambda s: s.offset)
    header = [station_number(float(s.offset), hull) for s in stations]

    def cell(station, axis: int, value: float, along: int) -> str:
        values = crossings(station.polylines, axis, value, along)
        return CELL_SEPARATOR.join(f"{v:.{OFFSET_DECIMALS}f}" for v in values)

    def rows(family: str, axis: int, along: int) -> list[list[str]]:
        planes = sorted(sections.get(family, ()), key=lambda p: p.offset)
        return [
            [_metres(float(p.offset))] + [cell(s, axis, p.offset, along) for s in stations] for p in planes
        ]

    tables = []
    if stations and sections.get("waterlines"):
        tables.append(
            (
                f"{hull.name}: half-breadths (m) at the stations",
                ["WL z \\ station", *header],
                rows("waterlines", 2, 1),
            )
        )
    if stations and sections.get("buttocks"):
        tables.append(
            (
                f"{hull.name}: heights (m) at the stations",
                ["BT y \\ station", *header],
                rows("buttocks", 1, 2),
            )
        )
    return tables
