"""A copy on the transformation stack beside its original (seed 002 §9): the main dimensions
and the hydrostatics of both as a table of rows (original, copy, change), and where the copy's
perpendiculars are. No Blender needed; :func:`batten.api.compare` measures the hulls.

Perpendiculars follow the hull: the copy's AP and FP are the original's, each moved as far as
that end of the level waterline moved (so a longer parallel middle body moves the FP forward
with the bow, and the Lpp grows by what the waterline grew). The coefficients and LCB of the two
hulls are then on comparable bases, as a naval architect expects from a lengthened ship.
"""

from __future__ import annotations

from typing import NamedTuple


class Quantity(NamedTuple):
    """One compared figure: its key (of the form parameters or the hydrostatics), label and
    unit ("" for a ratio) and the Python format spec it is shown with."""

    key: str
    label: str
    unit: str
    fmt: str


#: The main dimensions compared, from the form topology's parameters (§7.2.5).
DIMENSIONS: tuple[Quantity, ...] = (
    Quantity("length", "Length", "m", ".3f"),
    Quantity("breadth", "Breadth", "m", ".3f"),
    Quantity("depth", "Depth", "m", ".3f"),
    Quantity("waterline_breadth", "Bwl", "m", ".3f"),
    Quantity("pmb_length", "PMB length", "m", ".3f"),
    Quantity("pmb_position", "PMB position", "m", ".3f"),
    Quantity("bilge_radius", "Bilge radius", "m", ".3f"),
    Quantity("rise_of_floor", "Rise of floor", "m", ".3f"),
    Quantity("entrance_length", "Entrance length", "m", ".3f"),
    Quantity("run_length", "Run length", "m", ".3f"),
)

#: The hydrostatics compared, at the original's design draft (keys of
#: :func:`batten.api.hydrostatics`).
HYDROSTATICS: tuple[Quantity, ...] = (
    Quantity("volume", "Volume ∇", "m³", ",.2f"),
    Quantity("displacement", "Displacement Δ", "t", ",.2f"),
    Quantity("lpp", "Lpp", "m", ".3f"),
    Quantity("lwl", "Lwl", "m", ".3f"),
    Quantity("bwl", "Bwl", "m", ".3f"),
    Quantity("wetted_area", "Wetted surface S", "m²", ",.2f"),
    Quantity("waterplane_area", "Waterplane area Awp", "m²", ",.2f"),
    Quantity("midship_area", "Midship area Am", "m²", ",.3f"),
    Quantity("lcb", "LCB (x)", "m", ".3f"),
    Quantity("vcb", "VCB = KB", "m", ".3f"),
    Quantity("lcf", "LCF (x)", "m", ".3f"),
    Quantity("kmt", "KMt", "m", ".3f"),
    Quantity("kml", "KMl", "m", ".2f"),
    Quantity("tpc", "TPC", "t/cm", ".3f"),
    Quantity("mtc", "MTC", "t·m/cm", ".3f"),
    Quantity("cb", "Block Cb", "", ".4f"),
    Quantity("cp", "Prismatic Cp", "", ".4f"),
    Quantity("cm", "Midship Cm", "", ".4f"),
    Quantity("cwp", "Waterplane Cwp", "", ".4f"),
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
