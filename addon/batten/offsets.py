"""The offsets table of a hull as text (no Blender needed; :func:`batten.api.offsets_table` is
the call): half-breadths where the stations cross the waterlines and heights where they cross
the buttocks, read off the exact station sections.

The CSV opens with a header block (one ``key,value`` row each: the hull, units, axes, AP and
FP, design draft, tolerance and how to read the cells), then the half-breadths table (one row
per waterline: its name and height, then the half-breadth at each station) and the heights
table (one row per buttock). A cell is empty where the station does not reach that waterline
or buttock (never NaN); where a station crosses one more than once (a bulb, a skeg) the cell
holds every value in order along the station from its first point, separated by ``" / "``.
"""

from __future__ import annotations

import csv
import io

import numpy as np

#: Separates the values of a cell where a station crosses a waterline or buttock more than once.
CELL_SEPARATOR = " / "

#: Decimals of the values written (0.1 mm).
DECIMALS = 4

#: Crossings closer than this (m) are one (a polyline point on the plane ends two segments).
SAME_CROSSING = 1e-6


def crossings(polylines: list[np.ndarray], axis: int, value: float, along: int) -> list[float]:
    """Where the polylines cross the plane ``coordinate[axis] = value``: coordinate ``along``
    of each crossing (linear between the points, which lie on the surface within the
    tolerance of the chords), in order along each polyline; a point on the plane counts once."""
    out: list[float] = []
    for pts in polylines:
        d = pts[:, axis] - value
        hits = [
            pts[i, along] + d[i] / (d[i] - d[i + 1]) * (pts[i + 1, along] - pts[i, along])
            for i in range(len(pts) - 1)
            if d[i] * d[i + 1] < 0.0 or d[i] == 0.0
        ]
        if len(pts) and d[-1] == 0.0:
            hits.append(pts[-1, along])
        for h in hits:
            if not out or abs(h - out[-1]) > SAME_CROSSING:
                out.append(float(h))
    return out


def _cell(values: list[float]) -> str:
    return CELL_SEPARATOR.join(f"{v:.{DECIMALS}f}" for v in values)


def table_text(
    hull: str,
    stations: list[tuple[str, float, list[np.ndarray]]],
    waterlines: list[float],
    buttocks: list[float],
    datums: dict,
) -> str:
    """The CSV text of the offsets table: ``stations`` as ``(label, x, polylines)``, the
    waterline heights and buttock offsets (m), ``datums`` with ``x_ap``, ``x_fp``,
    ``design_draft`` (None when unknown) and ``tolerance``."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    draft = datums.get("design_draft")
    w.writerow(["batten offsets table", hull])
    w.writerow(["units", "metres"])
    w.writerow(["axes", "x forward, y to port (half-breadths of the port side), z up from the baseline"])
    w.writerow(["AP x", f"{datums['x_ap']:.{DECIMALS}f}"])
    w.writerow(["FP x", f"{datums['x_fp']:.{DECIMALS}f}"])
    w.writerow(["design draft", "" if draft is None else f"{draft:.{DECIMALS}f}"])
    w.writerow(["tolerance", f"{datums['tolerance']:g}"])
    w.writerow(
        [
            "cells",
            "empty: the station does not reach that waterline or buttock; "
            f"several values ('a{CELL_SEPARATOR}b'): crossed more than once, in order along the station",
        ]
    )
    w.writerow([])
    labels = [label for label, _, _ in stations]
    xs = [f"{x:.{DECIMALS}f}" for _, x, _ in stations]
    w.writerow(["half-breadths", "station", *labels])
    w.writerow(["waterline", "z \\ x", *xs])
    for z in waterlines:
        w.writerow(
            [f"WL {z:.3f}", f"{z:.{DECIMALS}f}", *(_cell(crossings(p, 2, z, 1)) for _, _, p in stations)]
        )
    w.writerow([])
    w.writerow(["heights", "station", *labels])
    w.writerow(["buttock", "y \\ x", *xs])
    for y in buttocks:
        w.writerow(
            [f"BL {y:.3f}", f"{y:.{DECIMALS}f}", *(_cell(crossings(p, 1, y, 2)) for _, _, p in stations)]
        )
    return buf.getvalue()
