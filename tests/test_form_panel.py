"""The Form panel (seed 002 §7.2.5, §9) headless: its operators measure the PMB barge's form,
change its PMB length into a copy on the stack, select the original and the copy, and commit,
keep or abandon; a change the hull cannot take is refused with nothing created; the panel draws
the parameters, the stack and the change before and after."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten.form_operators import (
    BATTEN_OT_abandon_transforms,
    BATTEN_OT_commit_transform,
    BATTEN_OT_keep_transform,
    BATTEN_OT_measure_form,
    BATTEN_OT_move_form_vertex,
    BATTEN_OT_select_transform,
    BATTEN_OT_transform,
)
from operator_runs import execute
from test_form import T, _points
from test_hydro_panel import _Layout


@pytest.fixture
def barge(barge):
    """The conftest's barge, the panels' hull."""
    bpy.context.scene.batten.source = barge
    return barge


def _same(a: dict, b: dict) -> bool:
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def _draw() -> dict:
    from batten.panels import VIEW3D_PT_batten_form

    panel = type("Panel", (), {"layout": _Layout()})()
    VIEW3D_PT_batten_form.draw(panel, bpy.context)
    return panel.layout.record


def test_measure_then_change_the_pmb_length_into_a_copy_and_commit_it(barge):
    settings = bpy.context.scene.batten
    original = _points(barge)
    settings.form_parameter = "pmb_length"
    status, reports = execute(BATTEN_OT_measure_form, bpy.context)
    assert status == {"FINISHED"}, reports
    measured = json.loads(settings.last_form)
    assert measured["source"] == barge.name
    assert measured["parameters"]["pmb_length"] == pytest.approx(20.0, abs=1e-9)
    assert settings.form_value == pytest.approx(20.0, abs=1e-6), "the value field starts at the hull's"
    drawn = _draw()
    assert "PMB length" in drawn["labels"] and "20.000 m" in drawn["labels"]
    settings.form_value = 30.0
    status, reports = execute(BATTEN_OT_transform, bpy.context)
    assert status == {"FINISHED"}, reports
    copy = settings.source
    assert copy != barge and api.transform_stack(copy)[0]["collection"] == barge
    assert _same(_points(barge), original), "the original is untouched"
    after = json.loads(settings.last_form)["parameters"]
    assert after["pmb_length"] == pytest.approx(30.0, abs=1e-6)
    drawn = _draw()
    assert "batten.commit_transform" in drawn["ops"] and "batten.select_transform" in drawn["ops"]
    assert any("20.000 m → 30.000 m" in text for text in drawn["labels"]), drawn["labels"]
    # Look at the original, then back at the copy, and commit it.
    assert execute(BATTEN_OT_select_transform, bpy.context, collection=barge.name)[0] == {"FINISHED"}
    assert settings.source == barge
    assert not BATTEN_OT_commit_transform.poll(bpy.context), "the original is no copy to commit"
    execute(BATTEN_OT_select_transform, bpy.context, collection=copy.name)
    status, reports = execute(BATTEN_OT_commit_transform, bpy.context)
    assert status == {"FINISHED"}, reports
    assert settings.source == barge
    assert not _same(_points(barge), original), "committed"
    pmb = api.form_topology(barge)["parameters"]["pmb_length"]
    assert pmb == pytest.approx(30.0, abs=1e-6)
    assert len(api.transform_stack(barge)) == 1, "the stack is gone"


def test_keep_and_abandon(barge):
    settings = bpy.context.scene.batten
    settings.form_parameter, settings.form_value = "breadth", 21.0
    execute(BATTEN_OT_transform, bpy.context)
    first = settings.source
    status, _ = execute(BATTEN_OT_keep_transform, bpy.context)
    assert status == {"FINISHED"}
    assert api.transform_stack(first)[0]["collection"] == first, "a hull of its own"
    settings.source = barge
    settings.form_parameter, settings.form_value = "bilge_radius", 2.5
    execute(BATTEN_OT_transform, bpy.context)
    execute(BATTEN_OT_transform, bpy.context)
    assert len(api.transform_stack(barge)) == 3
    status, reports = execute(BATTEN_OT_abandon_transforms, bpy.context)
    assert status == {"FINISHED"} and "2 copies" in reports[-1][1]
    assert settings.source == barge and len(api.transform_stack(barge)) == 1
    assert first.name in bpy.data.collections, "the kept hull stays"


def test_a_change_the_hull_cannot_take_is_refused_with_nothing_created(examples_dir):
    frigate = api.load_network(examples_dir / "frigate_network.json")
    settings = bpy.context.scene.batten
    settings.source = frigate
    collections = len(bpy.data.collections)
    settings.form_parameter, settings.form_value = "pmb_length", 30.0
    status, reports = execute(BATTEN_OT_transform, bpy.context)
    assert status == {"CANCELLED"}
    assert "parallel middle body" in reports[-1][1], reports
    assert len(bpy.data.collections) == collections and settings.source == frigate
    status, _ = execute(BATTEN_OT_measure_form, bpy.context)
    drawn = _draw()
    assert any(text.startswith("No PMB") for text in drawn["labels"]), "the panel says why"
    assert "batten.abandon_transforms" not in drawn["ops"], "no stack to show"


def test_the_overlay_draws_the_measured_form_by_kind_and_numbers_its_vertices(barge):
    from batten import overlay

    settings = bpy.context.scene.batten
    assert not len(overlay.form_vertices(bpy.context)), "nothing before Measure Form"
    execute(BATTEN_OT_measure_form, bpy.context)
    form = api.form_topology(barge)
    vertices = overlay.form_vertices(bpy.context)
    np.testing.assert_allclose(vertices, [v["position"] for v in form["vertices"]], atol=1e-6)
    lines = overlay.form_lines(bpy.context)
    kinds = {e["kind"] for e in form["edges"]}
    assert {k for k, v in lines.items() if len(v)} == kinds
    # Every edge drawn from its start vertex to its end vertex, along its curve.
    ends = np.concatenate([v for v in lines.values() if len(v)])
    for e in form["edges"]:
        for end in ("start", "end"):
            gap = np.linalg.norm(ends - np.asarray(form["vertices"][e[end]]["position"]), axis=1).min()
            assert gap < 1e-5, (e, end, gap)
    settings.show_form = False
    assert not len(overlay.form_vertices(bpy.context))
    assert not any(len(v) for v in overlay.form_lines(bpy.context).values()), "Show Form off"
    settings.show_form = True
    settings.source = None
    assert not len(overlay.form_vertices(bpy.context)), "another hull: nothing"


def test_moving_a_numbered_form_vertex_makes_a_copy_with_the_vertex_moved(examples_dir):
    frigate = api.load_network(examples_dir / "frigate_network.json")
    settings = bpy.context.scene.batten
    settings.source = frigate
    execute(BATTEN_OT_measure_form, bpy.context)
    form = api.form_topology(frigate)
    corner = next(i for i, v in enumerate(form["vertices"]) if {"deck", "transom"} <= set(v["curves"]))
    original = _points(frigate)
    settings.form_vertex, settings.form_move = corner, (0.0, 0.3, 0.0)
    status, reports = execute(BATTEN_OT_move_form_vertex, bpy.context)
    assert status == {"FINISHED"}, reports
    copy = settings.source
    assert copy != frigate and _same(_points(frigate), original), "the original is untouched"
    moved = api.form_topology(copy)["vertices"][corner]["position"]
    want = np.asarray(form["vertices"][corner]["position"]) + [0.0, 0.3, 0.0]
    np.testing.assert_allclose(moved, want, atol=1e-9)
    from batten import overlay

    np.testing.assert_allclose(overlay.form_vertices(bpy.context)[corner], want, atol=1e-5)
    settings.form_vertex = 999
    status, reports = execute(BATTEN_OT_move_form_vertex, bpy.context)
    assert status == {"CANCELLED"} and "999" in reports[-1][1], reports
    assert settings.source == copy, "a refused move changes nothing"


def test_hydrostatic_targets_make_a_copy_and_the_panel_shows_before_after_and_aim(barge):
    from batten.form_operators import BATTEN_OT_transform_hydrostatic

    settings = bpy.context.scene.batten
    settings.draft = 0.0  # the collection's design draft
    before = api.hydrostatics(barge, T)
    settings.hydro_volume_target = "hold"
    settings.hydro_use_lcb = False
    settings.hydro_keep_pmb = "free"
    status, reports = execute(BATTEN_OT_transform_hydrostatic, bpy.context)
    assert status == {"CANCELLED"} and any("volume target" in text for _, text in reports), reports
    assert len(api.transform_stack(barge)) == 1, "nothing made"
    settings.hydro_volume_target = "cb"
    settings.hydro_volume_value = before["cb"] + 0.01
    settings.hydro_use_lcb = True
    settings.hydro_lcb = before["lcb"] + 0.2
    status, reports = execute(BATTEN_OT_transform_hydrostatic, bpy.context)
    assert status == {"FINISHED"}, reports
    copy = settings.source
    assert copy != barge and api.transform_stack(barge)[-1]["collection"] == copy
    summary = json.loads(settings.last_hydro_transform)
    assert summary["stop"] == "converged" and summary["copy"] == copy.name
    rows = {row["label"]: row for row in summary["rows"]}
    assert rows["Cb"]["after"] == pytest.approx(before["cb"] + 0.01, abs=2e-5)
    assert rows["LCB (m)"]["aim"] == pytest.approx(before["lcb"] + 0.2, abs=1e-6)
    assert rows["Δ (t)"]["aim"] == pytest.approx(rows["∇ (m³)"]["aim"] * before["density"], rel=1e-12)
    after = api.hydrostatics(copy, T, lpp=before["lpp"], fp=before["x_fp"])
    assert after["lcb"] == pytest.approx(before["lcb"] + 0.2, abs=2e-3)
    drawn = _draw()["labels"]
    assert f"{before['cb']:.4f} → {before['cb'] + 0.01:.4f}" in drawn
    assert any("hull evaluations" in t for t in drawn) and any(t.startswith("PMB ") for t in drawn)
    # A target beyond reach: the closest copy, and the panel says what stopped it.
    settings.source = barge
    settings.hydro_use_lcb = False
    settings.hydro_volume_target = "volume"
    settings.hydro_volume_value = 0.5 * before["volume"]
    status, reports = execute(BATTEN_OT_transform_hydrostatic, bpy.context)
    assert status == {"FINISHED"}, reports
    assert any("out of range" in text for _, text in reports), reports
    assert any("parallel middle body" in t for t in _draw()["labels"])
    # Hold PMB: the ends' faces bulge instead, and the panel says by how much.
    settings.source = barge
    settings.hydro_keep_pmb = "all"
    settings.hydro_volume_target = "cb"
    settings.hydro_volume_value = before["cb"] + 0.005
    status, reports = execute(BATTEN_OT_transform_hydrostatic, bpy.context)
    assert status == {"FINISHED"}, reports
    assert json.loads(settings.last_hydro_transform)["stop"] == "converged"
    drawn = _draw()["labels"]
    assert any(t.startswith("Bulge: entrance +") for t in drawn)
    assert "PMB 20.000 → 20.000 m" in drawn, "the PMB held, and said so"
