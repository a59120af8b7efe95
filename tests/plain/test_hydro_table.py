"""The hydrostatics table: every figure has a row with its unit, and the CSV files give back
the very numbers written, under a header of names and units."""

import csv
import math

import pytest
from batten import hydro_table

#: The keys of batten.api.hydrostatics (issue 14's contract).
KEYS = (
    "volume displacement density draft_ap draft_fp draft_mid draft_lcf trim heel x_ap x_fp lpp lwl bwl los "
    "wetted_area waterplane_area midship_area max_section_area max_section_x cb cp cm cwp cvp lcb tcb vcb "
    "lcf it il bmt bml kmt kml tpc mtc transom_area entrance_half_angle"
).split()


def _figures(draft: float) -> dict:
    """Figures with awkward floats (not short decimals), different per key and draft."""
    return {key: math.pi * (i + 1) * draft / 7.0 for i, key in enumerate(KEYS)}


def test_every_figure_has_one_row_with_a_unit():
    assert sorted(r.key for r in hydro_table.ROWS) == sorted(KEYS)
    units = {r.key: r.unit for r in hydro_table.ROWS}
    assert units["volume"] == "m³" and units["displacement"] == "t" and units["tpc"] == "t/cm"
    assert units["mtc"] == "t·m/cm" and units["it"] == "m⁴" and units["cb"] == "" and units["heel"] == "°"


def test_the_panel_text_has_the_unit_and_a_dash_for_a_missing_figure():
    row = next(r for r in hydro_table.ROWS if r.key == "volume")
    assert hydro_table.value_text(row, {"volume": 52030.4567}) == "52,030.46 m³"
    assert hydro_table.value_text(row, {}) == "—"


def test_curves_of_form_csv_round_trips(tmp_path):
    rows = [_figures(d) for d in (1.0, 2.5, 4.0)]
    rows[1]["extra"] = 1.5  # a key not in every row is left out
    path = hydro_table.curves_of_form_csv(rows, tmp_path / "cof.csv")
    with path.open(encoding="utf-8", newline="") as f:
        table = list(csv.reader(f))
    header, body = table[0], table[1:]
    assert header[0] == "draft_mid [m]" and "volume [m³]" in header and "cb [-]" in header
    assert len(header) == len(KEYS) and len(body) == 3
    keys = [h.split(" [")[0] for h in header]
    for written, line in zip(rows, body, strict=True):
        assert {k: float(v) for k, v in zip(keys, line, strict=True)} == {k: written[k] for k in KEYS}


def test_hydrostatics_csv_round_trips(tmp_path):
    figures = _figures(6.25)
    path = hydro_table.hydrostatics_csv(figures, tmp_path / "h.csv")
    with path.open(encoding="utf-8", newline="") as f:
        lines = list(csv.DictReader(f))
    assert [ln["key"] for ln in lines] == [r.key for r in hydro_table.ROWS]
    assert {ln["key"]: float(ln["value"]) for ln in lines} == figures
    volume = next(ln for ln in lines if ln["key"] == "volume")
    assert volume["quantity"] == "Volume ∇" and volume["unit"] == "m³"


def test_no_drafts_is_an_error(tmp_path):
    with pytest.raises(ValueError, match="no drafts"):
        hydro_table.curves_of_form_csv([], tmp_path / "x.csv")
    assert not (tmp_path / "x.csv").exists()
