"""The hydrostatic figures as a table: which rows the panel shows (label, key, unit, format, in
groups) and the CSV files of one flotation and of the curves of form (no Blender needed).

The keys are those of :func:`batten.api.hydrostatics`; ITTC symbols, SI units (m, m², m³, t,
t/cm, t·m/cm, degrees). CSV files hold every figure at full precision (shortest round-trip
text of each float) with a header naming each column and its unit, ``key [unit]``.
"""

from __future__ import annotations

import csv
import io
from typing import NamedTuple

from .atomic_write import write_atomically


class Row(NamedTuple):
    """One figure: its label (with the ITTC symbol), key, unit ("" for a ratio) and the
    Python format spec it is shown with."""

    label: str
    key: str
    unit: str
    fmt: str


#: The figures in the order the panel shows them, by group.
GROUPS: tuple[tuple[str, tuple[Row, ...]], ...] = (
    (
        "Flotation",
        (
            Row("Draft T (midships)", "draft_mid", "m", ".3f"),
            Row("Draft at AP", "draft_ap", "m", ".3f"),
            Row("Draft at FP", "draft_fp", "m", ".3f"),
            Row("Draft at LCF", "draft_lcf", "m", ".3f"),
            Row("Trim (by the stern +)", "trim", "m", ".3f"),
            Row("Heel (to starboard +)", "heel", "°", ".2f"),
            Row("Density ρ", "density", "t/m³", ".4f"),
        ),
    ),
    (
        "Volume",
        (
            Row("Volume ∇", "volume", "m³", ",.2f"),
            Row("Displacement Δ", "displacement", "t", ",.2f"),
            Row("Wetted surface S", "wetted_area", "m²", ",.2f"),
        ),
    ),
    (
        "Dimensions",
        (
            Row("AP at x", "x_ap", "m", ".3f"),
            Row("FP at x", "x_fp", "m", ".3f"),
            Row("Lpp", "lpp", "m", ".3f"),
            Row("Lwl", "lwl", "m", ".3f"),
            Row("Bwl", "bwl", "m", ".3f"),
            Row("LOS (submerged)", "los", "m", ".3f"),
        ),
    ),
    (
        "Sections",
        (
            Row("Midship area Am", "midship_area", "m²", ",.3f"),
            Row("Largest section Ax", "max_section_area", "m²", ",.3f"),
            Row("Ax at x", "max_section_x", "m", ".3f"),
            Row("Immersed transom", "transom_area", "m²", ",.3f"),
            Row("Half angle of entrance", "entrance_half_angle", "°", ".2f"),
        ),
    ),
    (
        "Centres",
        (
            Row("LCB (x)", "lcb", "m", ".3f"),
            Row("TCB (y)", "tcb", "m", ".3f"),
            Row("VCB = KB (z)", "vcb", "m", ".3f"),
            Row("LCF (x)", "lcf", "m", ".3f"),
        ),
    ),
    (
        "Waterplane and stability",
        (
            Row("Waterplane area Awp", "waterplane_area", "m²", ",.2f"),
            Row("It", "it", "m⁴", ",.0f"),
            Row("Il", "il", "m⁴", ",.0f"),
            Row("BMt", "bmt", "m", ".3f"),
            Row("BMl", "bml", "m", ".2f"),
            Row("KMt", "kmt", "m", ".3f"),
            Row("KMl", "kml", "m", ".2f"),
            Row("TPC", "tpc", "t/cm", ".3f"),
            Row("MTC (basis Lpp)", "mtc", "t·m/cm", ".3f"),
        ),
    ),
    (
        "Coefficients",
        (
            Row("Block Cb", "cb", "", ".4f"),
            Row("Prismatic Cp", "cp", "", ".4f"),
            Row("Midship Cm", "cm", "", ".4f"),
            Row("Waterplane Cwp", "cwp", "", ".4f"),
            Row("Vertical prismatic Cvp", "cvp", "", ".4f"),
        ),
    ),
)

#: Every row, in order.
ROWS: tuple[Row, ...] = tuple(row for _group, rows in GROUPS for row in rows)
_BY_KEY = {row.key: row for row in ROWS}


def value_text(row: Row, figures: dict) -> str:
    """The figure of ``row`` with its unit, as the panel shows it (``"—"`` when missing)."""
    value = figures.get(row.key)
    if not isinstance(value, int | float):
        return "—"
    text = format(value, row.fmt)
    return f"{text} {row.unit}" if row.unit else text


def column_name(key: str) -> str:
    """A CSV column's header: ``key [unit]`` (``[-]`` for a ratio; just ``key`` for a figure
    this table does not know)."""
    row = _BY_KEY.get(key)
    if row is None:
        return key
    return f"{key} [{row.unit or '-'}]"


def _columns(figures: list[dict]) -> list[str]:
    """The numeric keys every dict of ``figures`` has: the table's in its order, then the
    others (sorted)."""
    common = set.intersection(
        *(
            {k for k, v in f.items() if isinstance(v, int | float) and not isinstance(v, bool)}
            for f in figures
        )
    )
    known = [row.key for row in ROWS if row.key in common]
    return known + sorted(common - set(known))


def curves_of_form_csv(rows: list[dict], path):
    """Write the curves of form (one hydrostatics dict per draft, as from
    :func:`batten.api.curves_of_form`) to ``path``: a header ``key [unit]`` and one line per
    draft, drafts ascending as given. Whole or not at all; returns the path."""
    if not rows:
        raise ValueError("no drafts to write")
    keys = _columns(rows)
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([column_name(k) for k in keys])
    for figures in rows:
        writer.writerow([repr(float(figures[k])) for k in keys])
    return write_atomically(path, out.getvalue())


def hydrostatics_csv(figures: dict, path):
    """Write one flotation's figures (as from :func:`batten.api.hydrostatics`) to ``path``:
    the header ``quantity,key,value,unit`` and one line per figure. Whole or not at all;
    returns the path."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["quantity", "key", "value", "unit"])
    for key in _columns([figures]):
        row = _BY_KEY.get(key, Row(key, key, "", ""))
        writer.writerow([row.label, key, repr(float(figures[key])), row.unit])
    return write_atomically(path, out.getvalue())
