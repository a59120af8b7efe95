"""The Hydrostatics panel on batten's real hydrostatics (examples/wigley.json): each operator
gives what its batten.api call gives, a draft below the keel is the API's error in the panel,
and floating at the displacement of a draft finds that draft again."""

import csv
import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import hydro_operators, hydro_plot
from operator_runs import execute

L, B, T = 100.0, 10.0, 6.25  # examples/wigley.py


@pytest.fixture
def wigley():
    coll = api.load_example("wigley.json")
    settings = bpy.context.scene.batten
    settings.source = coll
    settings.draft = T
    return coll


def _shown() -> dict:
    return json.loads(bpy.context.scene.batten.last_hydrostatics)


def test_compute_shows_what_the_api_gives(wigley):
    assert bpy.ops.batten.hydrostatics() == {"FINISHED"}
    # The same figures (to rounding: the core's parallel sums may add in another order).
    direct = api.hydrostatics(wigley, T)
    assert _shown().keys() == direct.keys()
    assert _shown() == {k: pytest.approx(v, rel=1e-12, abs=1e-12) for k, v in direct.items()}
    # The Wigley hull's exact volume 4/9·L·B·T, well within the panel's 2 decimals.
    assert _shown()["volume"] == pytest.approx(4 / 9 * L * B * T, rel=1e-3)


def test_a_draft_below_the_keel_is_the_api_s_error_in_the_panel(wigley):
    bpy.context.scene.batten.draft = -1.0
    result, reports = execute(hydro_operators.BATTEN_OT_hydrostatics, bpy.context)
    with pytest.raises(api.BattenError) as direct:
        api.hydrostatics(wigley, -1.0)
    assert result == {"CANCELLED"} and reports == [({"ERROR"}, str(direct.value))]
    assert _shown() == {"error": str(direct.value)}


def test_the_sac_image_follows_the_api_s_areas(wigley, tmp_path):
    settings = bpy.context.scene.batten
    assert bpy.ops.batten.sectional_areas() == {"FINISHED"}
    image = bpy.data.images[hydro_plot.sac_image_name("wigley")]
    xs, areas = api.sectional_areas(wigley, T, settings.stations)
    assert len(xs) == settings.stations
    # Midships area of the Wigley hull: 2/3·B·T.
    assert np.interp(0.0, xs, areas) == pytest.approx(2 / 3 * B * T, rel=2e-3)
    path, axes = hydro_plot.sac_png("wigley", xs, areas, api.hydrostatics(wigley, T), tmp_path / "sac.png")
    drawn = hydro_plot.png_pixels(path)
    w, h = image.size
    shown = np.empty(w * h * 4, dtype=np.float32)
    image.pixels.foreach_get(shown)
    assert np.abs(shown.reshape(h, w, 4) - drawn).max() < 1 / 255 + 1e-6, "the image is that plot"
    for x, y in np.round(axes.to_px(xs, areas)).astype(int):
        assert (drawn[y - 1 : y + 2, x - 1 : x + 2, :3] < 0.97).any(), (x, y)


def test_curves_of_form_csv_is_the_api_s(wigley, tmp_path):
    settings = bpy.context.scene.batten
    settings.curves_draft_min, settings.curves_draft_max, settings.curves_drafts = 2.0, 7.0, 6
    assert bpy.ops.batten.curves_of_form() == {"FINISHED"}
    assert hydro_plot.curves_of_form_image_name("wigley") in bpy.data.images
    path = tmp_path / "cof.csv"
    assert bpy.ops.batten.export_hydrostatics(filepath=str(path), table="CURVES_OF_FORM") == {"FINISHED"}
    table = list(csv.DictReader(path.open(encoding="utf-8")))
    rows = api.curves_of_form(wigley, np.linspace(2.0, 7.0, 6))
    assert [float(r["volume [m³]"]) for r in table] == pytest.approx([r["volume"] for r in rows], rel=1e-12)


def test_floating_at_a_draft_s_displacement_finds_that_draft(wigley):
    at5 = api.hydrostatics(wigley, 5.0)
    settings = bpy.context.scene.batten
    settings.float_displacement, settings.float_lcg = at5["displacement"], at5["lcb"]
    assert bpy.ops.batten.float_to() == {"FINISHED"}
    assert settings.draft == pytest.approx(5.0, abs=1e-4)
    assert settings.trim == pytest.approx(0.0, abs=1e-4)
    assert _shown()["displacement"] == pytest.approx(at5["displacement"], rel=1e-5)
