"""The comparison table of a copy beside its original: rows with the change and its share, a
figure missing on one side shown as such, and perpendiculars that follow the waterline's ends."""

import pytest
from batten import form_compare

QUANTITIES = (
    form_compare.Quantity("Volume", "volume", "m³", ",.2f"),
    form_compare.Quantity("PMB length", "pmb_length", "m", ".3f"),
    form_compare.Quantity("LCB", "lcb", "m", ".3f"),
    form_compare.Quantity("Cb", "cb", "", ".4f"),
    form_compare.Quantity("Bilge radius", "bilge_radius", "m", ".3f"),
)


def test_rows_give_the_change_and_its_share_of_the_original():
    rows = form_compare.rows(
        QUANTITIES,
        {"volume": 1000.0, "pmb_length": None, "lcb": 0.0, "cb": 0.5, "flag": True},
        {"volume": 1023.5, "pmb_length": 12.0, "lcb": -0.25, "cb": 0.49},
    )
    by_key = {r["key"]: r for r in rows}
    assert list(by_key) == ["volume", "pmb_length", "lcb", "cb"], "no row where neither hull has it"
    assert by_key["volume"]["change"] == pytest.approx(23.5)
    assert by_key["volume"]["change_pct"] == pytest.approx(2.35)
    assert by_key["pmb_length"]["original"] is None and by_key["pmb_length"]["change"] is None
    assert by_key["lcb"]["change"] == -0.25 and by_key["lcb"]["change_pct"] is None, "no share of zero"
    assert by_key["cb"]["change_pct"] == pytest.approx(-2.0)
    assert form_compare.value_text(by_key["volume"], "copy") == "1,023.50 m³"
    assert form_compare.value_text(by_key["pmb_length"], "original") == "—"
    assert form_compare.change_text(by_key["volume"]) == "+23.50 m³ (+2.35 %)"
    assert form_compare.change_text(by_key["cb"]) == "-0.0100 (-2.00 %)"
    assert form_compare.change_text(by_key["lcb"]) == "-0.250 m"


def test_perpendiculars_move_with_their_ends_of_the_waterline():
    # A PMB inserted forward: the bow moves 10 m, the stern stays.
    assert form_compare.moved_perpendiculars((0.0, 100.0), (-2.0, 101.0), (-2.0, 111.0)) == (0.0, 110.0)
    # Both ends move: the perpendiculars keep their distance from them.
    ap, fp = form_compare.moved_perpendiculars((5.0, 95.0), (1.0, 99.0), (-1.5, 100.25))
    assert (ap, fp) == pytest.approx((2.5, 96.25))
