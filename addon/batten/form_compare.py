"""A copy on the transformation stack beside its original (seed 002 §9): the main dimensions
and the hydrostatics of both as a table of rows (original, copy, change), and where the copy's
perpendiculars are. No Blender needed; :func:`batten.api.compare` measures the hulls.

Perpendiculars follow the hull: the copy's AP and FP are the original's, each moved as far as
that end of the level waterline moved (so a longer parallel middle body moves the FP forward
with the bow, and the Lpp grows by what the waterline grew). The coefficients and LCB of the two
hulls are then on comparable bases, as a naval architect expects from a lengthened ship.
"""

from __future__ import annotations

from .hydro_table import ROWS, Row

#: One compared figure: its label, key (of the form parameters or the hydrostatics), unit
#: ("" for a ratio) and the Python format spec it is shown with (the hydrostatics table's row).
Quantity = Row

#: The main dimensions compared, from the form topology's parameters (§7.2.5).
DIMENSIONS: tuple[Quantity, ...] = tuple(
    Quantity(label, key, "m", ".3f")
    for key, label in (
        ("length", "Length"),
        ("breadth", "Breadth"),
        ("depth", "Depth"),
        ("waterline_breadth", "Bwl"),
        ("pmb_length", "PMB length"),
        ("pmb_position", "PMB position"),
        ("bilge_radius", "Bilge radius"),
        ("rise_of_floor", "Rise of floor"),
        ("entrance_length", "Entrance length"),
        ("run_length", "Run length"),
    )
)

#: The hydrostatics compared, at the original's design draft: these rows of the
#: hydrostatics table (:data:`batten.hydro_table.ROWS`), labels, units and formats as there.
HYDROSTATICS: tuple[Quantity, ...] = tuple(
    next(row for row in ROWS if row.key == key)
    for key in (
        "volume displacement lpp lwl bwl wetted_area waterplane_area midship_area lcb vcb lcf "
        "kmt kml tpc mtc cb cp cm cwp"
    ).split()
)


def moved_perpendiculars(
    original: tuple[float, float],
    waterline_original: tuple[float, float],
    waterline_copy: tuple[float, float],
) -> tuple[float, float]:
    """The copy's ``(x_ap, x_fp)``: the original's perpendiculars ``original``, each moved as
    far as its end of the level waterline moved (``waterline_*``: ``(aft end, fore end)``)."""
    (ap, fp), (wa, wf), (ca, cf) = original, waterline_original, waterline_copy
    return ap + (ca - wa), fp + (cf - wf)


def _number(value) -> float | None:
    return float(value) if isinstance(value, int | float) and not isinstance(value, bool) else None


def rows(quantities: tuple[Quantity, ...], original: dict, copy: dict) -> list[dict]:
    """One row per quantity either hull has: ``key``, ``label``, ``unit``, ``fmt``,
    ``original``, ``copy`` (None where that hull has no such figure, e.g. no PMB), ``change``
    (copy − original) and ``change_pct`` (relative to the original; None where either is
    missing or the original is zero)."""
    out = []
    for q in quantities:
        a, b = _number(original.get(q.key)), _number(copy.get(q.key))
        if a is None and b is None:
            continue
        change = None if a is None or b is None else b - a
        pct = None if change is None or a == 0.0 else 100.0 * change / abs(a)
        out.append({**q._asdict(), "original": a, "copy": b, "change": change, "change_pct": pct})
    return out


def value_text(row: dict, which: str) -> str:
    """The row's ``which`` figure (``original``, ``copy`` or ``change``) with its unit, as the
    panel shows it (``"—"`` when missing; a change with its sign)."""
    value = row[which]
    if value is None:
        return "—"
    fmt = ("+" if which == "change" else "") + row["fmt"]
    text = format(value, fmt)
    return f"{text} {row['unit']}" if row["unit"] else text


def change_text(row: dict) -> str:
    """The row's change with its percentage, e.g. ``+1,234.50 m³ (+2.37 %)``."""
    text = value_text(row, "change")
    return text if row["change_pct"] is None else f"{text} ({row['change_pct']:+.2f} %)"
