"""A copy on the transformation stack beside its original (seed 002 §9): ``api.compare`` gives
the dimensions and hydrostatics of both on perpendiculars that follow the hull, and both
sectional area curves; the Form panel's Compare operator shows them, plots the two SACs and
draws the original's curves beside the copy; bad requests are refused with nothing changed."""

import json
import math

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import hydro_plot, overlay
from batten.form_operators import GHOST_SAMPLES, BATTEN_OT_compare_transform, BATTEN_OT_select_transform
from operator_runs import execute
from test_form import T, _points
from test_form_panel import _draw


def _row(rows: list[dict], key: str) -> dict:
    return next(r for r in rows if r["key"] == key)


def test_a_longer_pmb_beside_its_original(barge):  # noqa: F811
    before = _points(barge)
    result = api.transform(barge, pmb_length=30.0)
    collections, images = len(bpy.data.collections), len(bpy.data.images)
    c = api.compare(result)
    assert (c["original"], c["copy"], c["draft"]) == (barge.name, result.collection.name, T)
    assert "pmb_length 30" in c["description"]
    dims = c["dimensions"]
    assert _row(dims, "pmb_length")["change"] == pytest.approx(10.0, abs=1e-6)
    assert _row(dims, "pmb_length")["change_pct"] == pytest.approx(50.0, abs=1e-5)
    assert _row(dims, "entrance_length")["change"] == pytest.approx(-5.0, abs=1e-6)
    assert _row(dims, "breadth")["change"] == pytest.approx(0.0, abs=1e-9)
    # The barge keeps its length, so the copy keeps the original's perpendiculars.
    (ap, fp), (ap2, fp2) = c["perpendiculars"]["original"], c["perpendiculars"]["copy"]
    assert (ap2, fp2) == pytest.approx((ap, fp), abs=1e-9)
    # Every figure is the hull's own hydrostatics on those perpendiculars.
    for key, coll in (("original", barge), ("copy", result.collection)):
        x_ap, x_fp = c["perpendiculars"][key]
        h = api.hydrostatics(coll, T, lpp=x_fp - x_ap, fp=x_fp)
        for row in c["hydrostatics"]:
            assert row[key] == h[row["key"]], (key, row["key"])
        xs, areas = c["sac"][key]
        assert xs[0] == pytest.approx(x_ap) and xs[-1] == pytest.approx(x_fp) and len(xs) == 21
        assert np.trapz(areas, xs) == pytest.approx(h["volume"], rel=0.01), "the SAC holds the volume"
    hydro = c["hydrostatics"]
    # The midship section is the PMB's: unchanged; the longer PMB makes the hull fuller.
    assert _row(hydro, "midship_area")["change_pct"] == pytest.approx(0.0, abs=1e-6)
    volume = _row(hydro, "volume")
    assert volume["change"] > 50.0 and volume["change_pct"] == pytest.approx(
        100 * volume["change"] / volume["original"]
    )
    assert _row(hydro, "cb")["change_pct"] == pytest.approx(volume["change_pct"], abs=1e-6), "same L, B, T"
    # Nothing was made or changed.
    assert (len(bpy.data.collections), len(bpy.data.images)) == (collections, images)
    now = _points(barge)
    assert now.keys() == before.keys() and all(np.array_equal(now[k], before[k]) for k in now)


def test_the_copys_perpendiculars_follow_its_waterline_ends(barge):  # noqa: F811
    # Without datums a hull's perpendiculars are its level waterline's ends.
    waterline = api.hydrostatics(barge, T)
    barge[api.LPP_PROPERTY], barge[api.FP_PROPERTY] = 95.0, 97.0
    form = api.form_topology(barge)
    bow = max(range(len(form["vertices"])), key=lambda i: form["vertices"][i]["position"][0])
    result = api.transform(barge, moves=[(bow, (3.0, 0.0, 0.0))])
    c = api.compare(result)
    assert c["perpendiculars"]["original"] == pytest.approx((2.0, 97.0), abs=1e-12)
    # Each perpendicular moved as far as its end of the waterline (the copy has no datums).
    moved = api.hydrostatics(result.collection, T)
    aft, fore = moved["x_ap"] - waterline["x_ap"], moved["x_fp"] - waterline["x_fp"]
    assert fore > 0.5, "the bow moved forward"
    assert c["perpendiculars"]["copy"] == pytest.approx((2.0 + aft, 97.0 + fore), abs=1e-9)
    assert _row(c["hydrostatics"], "lpp")["change"] == pytest.approx(fore - aft, abs=1e-9)


def test_breadth_plus_five_percent_on_the_frigate(examples_dir):
    frigate = api.load_network(examples_dir / "frigate_network.json")
    breadth = api.form_topology(frigate, draft=4.8)["parameters"]["breadth"]
    result = api.transform(frigate, breadth=1.05 * breadth, draft=4.8)
    c = api.compare(result, draft=4.8)
    assert _row(c["dimensions"], "breadth")["change_pct"] == pytest.approx(5.0, abs=1e-6)
    bwl = _row(c["hydrostatics"], "bwl")
    assert bwl["copy"] == pytest.approx(1.05 * bwl["original"], abs=1e-3)
    # The frigate has no PMB: no such row.
    assert all(r["key"] != "pmb_length" for r in c["dimensions"])
    # A breadth change scales the sections: ∇ +5 %, the block coefficient kept.
    assert _row(c["hydrostatics"], "volume")["change_pct"] == pytest.approx(5.0, abs=0.05)
    assert _row(c["hydrostatics"], "cb")["change_pct"] == pytest.approx(0.0, abs=0.05)
    assert _row(c["hydrostatics"], "lpp")["change"] == pytest.approx(0.0, abs=1e-6), "no longer"


def test_bad_requests_are_refused_naming_what(barge):  # noqa: F811
    with pytest.raises(api.InvalidArgumentError, match="not a transformation copy"):
        api.compare(barge)
    with pytest.raises(api.InvalidArgumentError, match="not a transformation copy"):
        api.compare("barge")
    with pytest.raises(api.InvalidArgumentError, match="no collection 'nothing'"):
        api.compare("nothing")
    with pytest.raises(api.InvalidArgumentError, match="needs a transformation copy, got int"):
        api.compare(3)
    result = api.transform(barge, pmb_length=30.0)
    assert api.compare(result.collection.name)["copy"] == result.collection.name
    with pytest.raises(api.InvalidArgumentError, match="stations"):
        api.compare(result, stations=1)
    with pytest.raises(api.InvalidArgumentError, match="not a number"):
        api.compare(result, draft=math.nan)
    del barge[api.DESIGN_DRAFT_PROPERTY]
    with pytest.raises(api.InvalidArgumentError, match=f"'{barge.name}' has no design draft"):
        api.compare(result)
    with pytest.raises(api.HydrostaticsError):
        api.compare(result, draft=-1.0)
    assert api.compare(result, draft=T)["draft"] == T


def test_the_compare_operator_panel_plot_and_overlay(barge):  # noqa: F811
    settings = bpy.context.scene.batten
    settings.source = barge
    assert not BATTEN_OT_compare_transform.poll(bpy.context), "the original is no copy"
    result = api.transform(barge, pmb_length=30.0)
    copy = result.collection
    settings.source = copy
    assert BATTEN_OT_compare_transform.poll(bpy.context)
    status, reports = execute(BATTEN_OT_compare_transform, bpy.context)
    assert status == {"FINISHED"}, reports
    assert "∇ +0." in reports[-1][1]
    shown = json.loads(settings.last_comparison)
    assert shown["copy"] == copy.name and shown["original"] == barge.name
    assert _row(shown["dimensions"], "pmb_length")["copy"] == pytest.approx(30.0, abs=1e-6)
    image = bpy.data.images[hydro_plot.comparison_image_name(copy.name)]
    assert tuple(image.size) == hydro_plot.SAC_SIZE
    pixels = np.empty(len(image.pixels), dtype=np.float32)
    image.pixels.foreach_get(pixels)
    rgb = pixels.reshape(-1, 4)[:, :3]
    for colour in (hydro_plot.PALETTE[0], hydro_plot.PALETTE[1]):
        assert (np.abs(rgb - colour[:3]).max(axis=1) < 0.02).sum() > 500, f"a curve drawn in {colour}"
    drawn = _draw()
    assert f"Beside '{barge.name}' at T = {T:.3f} m" in drawn["labels"]
    assert any(text.startswith("20.000 m → 30.000 m") for text in drawn["labels"]), drawn["labels"]
    assert any("(+50.00 %)" in text for text in drawn["labels"])
    # The overlay draws the original's curves, every one, on the original.
    lines = overlay.comparison_lines(bpy.context)
    curves = api.read_curves(barge)
    assert lines.shape == (2 * len(curves) * (GHOST_SAMPLES - 1), 3)
    for curve in curves:
        start = np.asarray(curve.evaluate([curve.domain[0]]))[0]
        assert np.abs(lines - start).max(axis=1).min() < 1e-3, f"{curve.name} drawn"
    settings.show_comparison = False
    assert len(overlay.comparison_lines(bpy.context)) == 0
    settings.show_comparison = True
    execute(BATTEN_OT_select_transform, bpy.context, collection=barge.name)
    assert len(overlay.comparison_lines(bpy.context)) == 0, "only beside the compared copy"
    assert not any(text.startswith("Beside") for text in _draw()["labels"])
