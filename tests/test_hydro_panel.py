"""The Hydrostatics panel headless: its operators through bpy.ops keep the figures (or the
error) in the scene, plot the sectional area curve and the curves of form into Blender images
updated in place, write CSV, float the hull, and Live and a changed draft recompute the figures;
the plots carry their curves. The batten.api hydrostatics are stood in for by an analytic
Wigley hull here (so the panel is tested on its own); test_hydro_real.py runs the real ones."""

import csv
import json
import math

import batten.api as api
import batten_native as bn
import bpy
import numpy as np
import pytest
from batten import hydro_operators, hydro_plot, live, overlay
from operator_runs import execute

L, B, DEPTH = 100.0, 10.0, 8.75  # examples/wigley.json: length, beam, keel to deck


def _figures(draft, trim=0.0, heel=0.0, density=1.025, lpp=None):
    """Analytic stand-in figures of a Wigley-like hull at ``draft`` (the parabolic hull's
    formulas taken at every draft, so they change with it)."""
    if not 0.0 < draft < DEPTH:
        raise bn.HydrostaticsError(f"draft {draft} m is below the keel (the lowest point is at z = 0 m)")
    lpp = lpp or L
    volume = 4 / 9 * L * B * draft
    awp = 2 / 3 * L * B
    f = {
        "volume": volume,
        "displacement": density * volume,
        "density": density,
        "draft_ap": draft + trim / 2,
        "draft_fp": draft - trim / 2,
        "draft_mid": draft,
        "draft_lcf": draft,
        "trim": trim,
        "heel": heel,
        "x_ap": L / 2 - lpp,
        "x_fp": L / 2,
        "lpp": lpp,
        "lwl": L,
        "bwl": B,
        "los": L,
        "wetted_area": 1.5 * L * draft,
        "waterplane_area": awp,
        "midship_area": 2 / 3 * B * draft,
        "max_section_area": 2 / 3 * B * draft,
        "max_section_x": 0.0,
        "cb": 4 / 9,
        "cp": 2 / 3,
        "cm": 2 / 3,
        "cwp": 2 / 3,
        "cvp": 2 / 3,
        "lcb": 0.0,
        "tcb": 0.0,
        "vcb": 5 / 8 * draft,
        "lcf": 0.0,
        "it": 3 * B**2 / 35 * volume / draft,
        "il": 3 * L**2 / 40 * volume / draft,
        "bmt": 3 * B**2 / (35 * draft),
        "bml": 3 * L**2 / (40 * draft),
        "kmt": 5 / 8 * draft + 3 * B**2 / (35 * draft),
        "kml": 5 / 8 * draft + 3 * L**2 / (40 * draft),
        "tpc": density * awp / 100,
        "mtc": density * volume * 3 * L**2 / (40 * draft) / (100 * lpp),
        "transom_area": 0.0,
        "entrance_half_angle": math.degrees(math.atan(2 * B / L)),
    }
    return f


@pytest.fixture
def stub_api(monkeypatch):
    """batten.api's hydrostatics stood in for by :func:`_figures`; the calls are recorded."""
    calls = []

    def hydrostatics(source, draft, *, trim=0.0, heel=0.0, density=1.025, lpp=None, fp=None, live=False):
        calls.append(("hydrostatics", source.name, draft, trim, heel, density, lpp, live))
        return _figures(draft, trim, heel, density, lpp)

    def sectional_areas(source, draft, stations=21, *, trim=0.0, heel=0.0, lpp=None, fp=None):
        _figures(draft)
        xs = np.linspace(-L / 2, L / 2, stations)
        return xs, 2 / 3 * B * draft * (1 - (2 * xs / L) ** 2)

    def curves_of_form(source, drafts, *, lpp=None, fp=None, density=1.025):
        return [_figures(float(d), density=density, lpp=lpp) for d in drafts]

    def float_to(source, displacement, lcg, *, density=1.025, lpp=None, fp=None):
        draft = displacement / density / (4 / 9 * L * B)
        return _figures(draft, trim=0.01 * lcg, density=density, lpp=lpp)

    for name, fn in [
        ("hydrostatics", hydrostatics),
        ("sectional_areas", sectional_areas),
        ("curves_of_form", curves_of_form),
        ("float_to", float_to),
    ]:
        monkeypatch.setattr(api, name, fn, raising=False)
    return calls


@pytest.fixture
def wigley():
    coll = api.load_example("wigley.json")
    bpy.context.scene.batten.source = coll
    return coll


def _figures_in_scene() -> dict:
    return json.loads(bpy.context.scene.batten.last_hydrostatics)


def test_a_new_hull_starts_at_half_its_depth_or_its_design_draft():
    settings = bpy.context.scene.batten
    coll = api.load_example("wigley.json")
    settings.source = coll
    assert settings.draft == pytest.approx(DEPTH / 2, abs=1e-4), "half of keel (0) to deck (8.75)"
    assert (settings.curves_draft_min, settings.curves_draft_max) == pytest.approx((0.875, 7.875), abs=1e-4)
    settings.source = None
    coll[api.DESIGN_DRAFT_PROPERTY] = 6.25
    settings.source = coll
    assert settings.draft == pytest.approx(6.25)


def test_compute_keeps_the_figures_and_a_draft_below_the_keel_keeps_the_error(stub_api, wigley):
    settings = bpy.context.scene.batten
    settings.draft, settings.trim, settings.heel, settings.lpp = 5.0, 0.2, math.radians(3.0), 98.0
    assert bpy.ops.batten.hydrostatics() == {"FINISHED"}
    figures = _figures_in_scene()
    assert figures["volume"] == pytest.approx(4 / 9 * L * B * 5.0)
    _, source, draft, trim, heel, density, lpp, live = stub_api[-1]
    assert not live, "Compute gives the full-accuracy figures"
    # As typed, not as Blender's float32 keeps them (0.2 is 0.200000003 there).
    assert (source, draft, trim, density, lpp) == ("wigley", 5.0, 0.2, 1.025, 98.0)
    assert heel == pytest.approx(3.0), "the panel's angle goes to the API in degrees"
    settings.lpp = 0.0
    bpy.ops.batten.hydrostatics()
    assert stub_api[-1][-2] is None, "Lpp 0 means: from the waterline (or the hull's own)"
    # A draft below the keel: CANCELLED with the API's message, and the panel shows it.
    settings.draft = -1.0
    result, reports = execute(hydro_operators.BATTEN_OT_hydrostatics, bpy.context)
    assert result == {"CANCELLED"}
    assert reports and reports[0][0] == {"ERROR"} and "below the keel" in reports[0][1]
    assert "below the keel" in _figures_in_scene()["error"]


def test_changing_the_draft_recomputes_shown_figures(stub_api, wigley):
    settings = bpy.context.scene.batten
    settings.draft = 3.0
    assert not stub_api, "nothing computed before the first Compute"
    bpy.ops.batten.hydrostatics()
    settings.draft = 4.0
    assert _figures_in_scene()["draft_mid"] == pytest.approx(4.0)
    assert stub_api[-1][-1], "figures that follow an edit are the API's live ones"
    settings.draft = -2.0
    assert "error" in _figures_in_scene()
    settings.draft = 2.0
    assert _figures_in_scene()["draft_mid"] == pytest.approx(2.0), "the fixed draft clears the error"


def test_plots_become_images_updated_in_place(stub_api, wigley):
    settings = bpy.context.scene.batten
    settings.draft = 6.25
    assert bpy.ops.batten.sectional_areas() == {"FINISHED"}
    sac = bpy.data.images[hydro_plot.sac_image_name("wigley")]
    assert tuple(sac.size) == hydro_plot.SAC_SIZE and sac.packed_file is not None
    before = np.empty(len(sac.pixels), dtype=np.float32)
    sac.pixels.foreach_get(before)
    images = len(bpy.data.images)
    settings.draft = 3.0
    assert bpy.ops.batten.sectional_areas() == {"FINISHED"}
    assert len(bpy.data.images) == images, "re-plotted into the same image"
    after = np.empty(len(sac.pixels), dtype=np.float32)
    bpy.data.images[hydro_plot.sac_image_name("wigley")].pixels.foreach_get(after)
    assert not np.array_equal(before, after), "the new draft's curve"
    settings.curves_draft_min, settings.curves_draft_max, settings.curves_drafts = 1.0, 8.0, 8
    assert bpy.ops.batten.curves_of_form() == {"FINISHED"}
    cof = bpy.data.images[hydro_plot.curves_of_form_image_name("wigley")]
    assert tuple(cof.size) == hydro_plot.CURVES_OF_FORM_SIZE


def test_a_failed_plot_keeps_the_error_and_makes_no_image(stub_api, wigley):
    bpy.context.scene.batten.draft = -1.0
    result, reports = execute(hydro_operators.BATTEN_OT_sectional_areas, bpy.context)
    assert result == {"CANCELLED"} and "below the keel" in reports[0][1]
    assert "error" in _figures_in_scene()
    assert hydro_plot.sac_image_name("wigley") not in bpy.data.images


def test_export_csv_writes_the_figures_and_the_curves_of_form(stub_api, wigley, tmp_path):
    settings = bpy.context.scene.batten
    settings.draft = 5.0
    one = tmp_path / "hydrostatics.csv"
    assert bpy.ops.batten.export_hydrostatics(filepath=str(one), table="HYDROSTATICS") == {"FINISHED"}
    rows = {r["key"]: r for r in csv.DictReader(one.open(encoding="utf-8"))}
    assert float(rows["volume"]["value"]) == _figures(5.0)["volume"] and rows["volume"]["unit"] == "m³"
    many = tmp_path / "cof.csv"
    settings.curves_draft_min, settings.curves_draft_max, settings.curves_drafts = 2.0, 6.0, 5
    assert bpy.ops.batten.export_hydrostatics(filepath=str(many), table="CURVES_OF_FORM") == {"FINISHED"}
    table = list(csv.DictReader(many.open(encoding="utf-8")))
    assert [float(r["draft_mid [m]"]) for r in table] == [2.0, 3.0, 4.0, 5.0, 6.0]
    assert float(table[2]["bmt [m]"]) == pytest.approx(_figures(4.0)["bmt"], rel=1e-15)


def test_an_unwritable_csv_is_an_error_report(stub_api, wigley, tmp_path):
    (tmp_path / "file").write_text("")
    result, reports = execute(
        hydro_operators.BATTEN_OT_export_hydrostatics,
        bpy.context,
        filepath=str(tmp_path / "file" / "x.csv"),
        table="HYDROSTATICS",
    )
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"} and "x.csv" in reports[0][1]


def test_float_at_displacement_sets_draft_and_trim(stub_api, wigley):
    settings = bpy.context.scene.batten
    settings.float_displacement, settings.float_lcg = 1.025 * 4 / 9 * L * B * 4.0, 20.0
    assert bpy.ops.batten.float_to() == {"FINISHED"}
    assert settings.draft == pytest.approx(4.0, abs=1e-5)
    assert settings.trim == pytest.approx(0.2, abs=1e-6)
    assert _figures_in_scene()["draft_mid"] == pytest.approx(4.0)


def test_live_rebuild_recomputes_the_figures_once_computed(stub_api, wigley, monkeypatch):
    settings = bpy.context.scene.batten
    settings.resolution, settings.live = 4, True
    live.rebuild_scene(bpy.context.scene.name)
    assert not stub_api, "no figures shown: Live only rebuilds"
    bpy.ops.batten.hydrostatics()
    n = len(stub_api)
    settings.last_hydrostatics = json.dumps({"volume": 0.0})  # a stale figure
    live.rebuild_scene(bpy.context.scene.name)
    assert len(stub_api) == n + 1 and stub_api[-1][-1], "live figures"
    assert _figures_in_scene()["volume"] == pytest.approx(_figures(settings.draft)["volume"])


def test_the_waterline_overlay_follows_draft_trim_and_heel(stub_api, wigley):
    settings = bpy.context.scene.batten
    settings.draft = 5.0
    corners = overlay.water_surface(bpy.context)
    assert corners.shape == (4, 3)
    assert np.allclose(corners[:, 2], 5.0), "level"
    assert corners[:, 1].min() == pytest.approx(-corners[:, 1].max(), rel=1e-6), "both sides when mirrored"
    assert corners[:, 0].min() < -L / 2 and corners[:, 0].max() > L / 2, "over the whole hull"
    settings.trim = 1.0
    aft, fwd = corners[:, 0].argmin(), corners[:, 0].argmax()
    corners = overlay.water_surface(bpy.context)
    assert corners[aft, 2] > 5.0 > corners[fwd, 2], "by the stern: deeper aft"
    settings.show_waterline = False
    assert len(overlay.water_surface(bpy.context)) == 0


class _Layout:
    """Records what a panel draws: labels, properties, operators, and alert boxes (headless)."""

    def __init__(self, record=None):
        self.record = {"labels": [], "props": [], "ops": [], "alerts": []} if record is None else record
        self.alert = False

    def label(self, text="", icon="NONE"):
        self.record["labels"].append(text)
        if self.alert:
            self.record["alerts"].append(text)

    def prop(self, _data, name, **_kwargs):
        self.record["props"].append(name)

    def operator(self, idname, **_kwargs):
        self.record["ops"].append(idname)
        return type("Op", (), {})()

    def operator_menu_enum(self, idname, _property, **_kwargs):
        self.record["ops"].append(idname)

    def _child(self, **_kwargs):
        child = _Layout(self.record)
        child.alert = self.alert
        return child

    box = column = row = split = _child


def _draw_panel() -> dict:
    from batten.panels import VIEW3D_PT_batten_hydrostatics

    panel = type("Panel", (), {"layout": _Layout()})()
    VIEW3D_PT_batten_hydrostatics.draw(panel, bpy.context)
    return panel.layout.record


def test_the_panel_shows_the_settings_the_table_with_units_and_the_error(stub_api, wigley):
    settings = bpy.context.scene.batten
    settings.draft = 5.0
    drawn = _draw_panel()
    assert {"draft", "trim", "heel", "density", "lpp", "show_waterline"} <= set(drawn["props"])
    assert {"batten.hydrostatics", "batten.sectional_areas", "batten.curves_of_form"} <= set(drawn["ops"])
    assert {"batten.export_hydrostatics", "batten.float_to"} <= set(drawn["ops"])
    assert "Volume ∇" not in drawn["labels"], "no table before Compute"
    bpy.ops.batten.hydrostatics()
    labels = _draw_panel()["labels"]
    assert "Volume ∇" in labels and "2,222.22 m³" in labels and "0.4444" in labels
    assert labels[labels.index("BMt") + 1] == f"{3 * B**2 / 35 / 5.0:.3f} m"
    settings.draft = -1.0
    drawn = _draw_panel()
    assert drawn["alerts"] and "below the keel" in " ".join(drawn["alerts"])
    assert "Volume ∇" not in drawn["labels"]


def test_the_hull_box_holds_bezier_handles_and_the_object_transform():
    from batten.scene_hydro import hull_box
    from helpers import new_bezier
    from mathutils import Matrix

    obj = new_bezier(
        "stem",
        [(0, 0, 0), (0, 0, 4)],
        [(0, -1, -1), (0, 2, 3)],
        [(0, 1, 1), (3, 0, 5)],
        matrix=Matrix.Translation((10, 0, 1)),
    )
    lo, hi = hull_box([obj])
    assert lo.tolist() == [10, -1, 0] and hi.tolist() == [13, 2, 6]
