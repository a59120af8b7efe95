"""Build warnings and topology diagnostics reach Python as data: one dict per finding with
its kind, message, curves, the objects they came from, location and (for a face that could
not be patched) the patch error; the panel's Show Curves selects exactly those objects, for
any object name."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import panels
from batten.scene_build import build_into_scene
from helpers import new_curve
from operator_runs import new_collection

KEYS = {"kind", "message", "curves", "objects", "location", "error"}


def _line(name, a, b, coll):
    return new_curve(name, "POLY", np.array([a, b], dtype=float), collection=coll)


def _add_spline(obj, a, b):
    """A second POLY spline from ``a`` to ``b`` in the object ``obj`` (world = local here)."""
    spline = obj.data.splines.new("POLY")
    spline.points.add(1)
    spline.points.foreach_set("co", np.array([*a, 1.0, *b, 1.0], dtype=np.float32))


def _of_kind(findings, kind) -> list[dict]:
    found = [f for f in findings if f["kind"] == kind]
    for f in found:
        assert set(f) == KEYS, f
        assert isinstance(f["message"], str) and f["message"]
    return found


@pytest.fixture
def spur_panel():
    """A side panel (plane y = 1) split by a station, a waterline to the station (a T-joint)
    and a spur from the station ending in the open. The keel and deck are the two splines of
    one object "rails" (curves "rails[0]", "rails[1]"); the spur's object is named "spur[1]"."""
    coll = new_collection("panel")
    rails = _line("rails", (0, 1, 0), (10, 1, 0), coll)
    _add_spline(rails, (0, 1, 3), (10, 1, 3))
    for name, a, b in (
        ("aft", (0, 0), (0, 3)),
        ("stem", (10, 0), (10, 3)),
        ("st5", (5, 0), (5, 3)),
        ("wl", (0, 1.5), (5, 1.5)),
        ("spur[1]", (5, 2.5), (7, 2.5)),
    ):
        _line(name, (a[0], 1.0, a[1]), (b[0], 1.0, b[1]), coll)
    bpy.context.scene.batten.source = coll
    return coll


def test_a_dangling_end_and_a_near_miss_name_their_curves_and_objects(spur_panel):
    report = api.build(spur_panel).report
    (dangling,) = _of_kind(report["warnings"], "dangling_end")
    assert dangling["curves"] == ["spur[1]"] and dangling["objects"] == ["spur[1]"]
    assert dangling["location"] == pytest.approx([7.0, 1.0, 2.5]) and dangling["error"] is None
    # The same findings, in the same shape, from the topology.
    topo = api.topology(spur_panel)
    assert _of_kind(topo["diagnostics"], "dangling_end") == [dangling]
    assert report["node_kinds"] == topo["node_kinds"]
    assert np.allclose(report["node_positions"], topo["node_positions"], atol=0.0)
    # Lift the spur's root 0.5 mm off st5 (tolerance 0.1 mm): a near miss between the two.
    spur_panel.objects["spur[1]"].data.splines[0].points[0].co = (5.0005, 1.0, 2.5, 1.0)
    report = api.build(spur_panel).report
    (near,) = _of_kind(report["warnings"], "near_miss")
    assert near["curves"] == ["spur[1]", "st5"] and near["objects"] == ["spur[1]", "st5"]
    assert np.allclose(near["location"], [5.00025, 1.0, 2.5], atol=1e-4)


def test_findings_on_a_multi_spline_object_name_the_object(spur_panel):
    """A spur from the deck spline ("rails[1]") ends in the open: the finding names the curve
    "rails[1]" and the object "rails"."""
    _add_spline(spur_panel.objects["rails"], (2, 1, 3), (2, 1, 4))
    report = api.build(spur_panel).report
    ends = {tuple(f["curves"]): f["objects"] for f in _of_kind(report["warnings"], "dangling_end")}
    assert ends == {("spur[1]",): ["spur[1]"], ("rails[2]",): ["rails"]}


def test_an_unclosed_region_names_the_curves_round_it():
    """A square inside a square, joined by one bridge: the ring between them runs along the
    bridge on both sides, so it bounds no disk and no face is made of it."""
    coll = new_collection("ring")
    y = 1.0
    for name, pts in (
        ("outer", [(0, 0), (4, 0), (4, 4), (0, 4)]),
        ("inner", [(1.5, 1.5), (2.5, 1.5), (2.5, 2.5), (1.5, 2.5)]),
    ):
        for i in range(4):
            a, b = pts[i], pts[(i + 1) % 4]
            _line(f"{name} {i}", (a[0], y, a[1]), (b[0], y, b[1]), coll)
    _line("bridge", (0, y, 2), (1.5, y, 2), coll)
    report = api.build(coll).report
    (region,) = _of_kind(report["warnings"], "unclosed_region")
    assert "bridge" in region["curves"] and {"outer 0", "inner 0"} <= set(region["curves"])
    assert region["objects"] == sorted(region["curves"]), "one-spline objects: the same names"
    assert region["location"] is not None and region["location"][1] == pytest.approx(y)


def test_a_non_manifold_node_names_the_curves_through_it():
    """A spine with three fins round it at 120 degrees (like a bulkhead meeting the hull)."""
    coll = new_collection("fins")
    p0, p1 = np.zeros(3), np.array([2.0, 0, 0])
    _line("spine", p0, p1, coll)
    for k in range(3):
        phi = 2 * np.pi * k / 3
        d = np.array([0.0, np.cos(phi), np.sin(phi)])
        _line(f"rib{k}a", p0, p0 + d, coll)
        _line(f"rib{k}b", p1, p1 + d, coll)
        _line(f"fin{k}", p0 + d, p1 + d, coll)
    findings = api.topology(coll)["diagnostics"]
    nodes = _of_kind(findings, "non_manifold_node")
    assert len(nodes) == 2, findings
    for n in nodes:
        assert "spine" in n["curves"] and len(n["curves"]) == 4 and n["objects"] == sorted(n["curves"])
    built = api.build(coll).report["warnings"]
    assert _of_kind(built, "non_manifold_node") == nodes, "the same findings in the build report"


def test_a_face_that_cannot_be_patched_carries_the_patch_error():
    """A 17-gon (more sides than the N-sided patch takes) beside a square: the square is
    built, the 17-gon is named with the patch error."""
    coll = new_collection("polygon")
    n = 17

    def p(k):
        a = 2 * np.pi * (k % n) / n
        return np.array([np.cos(a), np.sin(a), 0.0])

    for k in range(n):
        _line(f"side {k}", p(k), p(k + 1), coll)
    out = (p(0) + p(1)) / np.linalg.norm(p(0) + p(1)) * np.linalg.norm(p(1) - p(0))
    q0, q1 = p(0) + out, p(1) + out
    _line("square a", p(1), q1, coll)
    _line("square b", q1, q0, coll)
    _line("square c", q0, p(0), coll)
    report = api.build(coll).report
    assert report["faces"] == 1
    (face,) = _of_kind(report["warnings"], "face_not_patched")
    assert "side 16" in face["curves"] and face["objects"] == sorted(face["curves"])
    assert set(face["error"]) == {"kind", "message"} and "17" in face["error"]["message"]
    assert face["location"] is None or len(face["location"]) == 3


class _Layout:
    """Records the labels and the Show Curves buttons a panel draws (headless stand-in)."""

    def __init__(self, record=None):
        self.record = {"labels": [], "buttons": []} if record is None else record
        self.alert = False

    def label(self, text="", icon="NONE"):
        self.record["labels"].append(text)

    def operator(self, idname, **_kwargs):
        button = type("Op", (), {"idname": idname})()
        self.record["buttons"].append(button)
        return button

    def box(self, **_kwargs):
        return _Layout(self.record)

    column = row = box


def test_show_curves_selects_the_objects_of_every_warning(spur_panel):
    report = build_into_scene(bpy.context.scene)
    warnings = json.loads(bpy.context.scene.batten.last_report)["warnings"]
    assert warnings == report["warnings"] and warnings, "the scene keeps the warnings as data"
    layout = _Layout()
    panels._draw_report(layout, bpy.context.scene.batten.last_report)
    buttons = [b for b in layout.record["buttons"] if b.idname == "batten.select_curves"]
    assert [b.names for b in buttons] == ["\n".join(w["objects"]) for w in warnings if w["objects"]]
    assert all(w["message"] in layout.record["labels"] for w in warnings)
    for button, warning in zip(buttons, (w for w in warnings if w["objects"]), strict=True):
        assert bpy.ops.batten.select_curves(names=button.names) == {"FINISHED"}
        assert sorted(o.name for o in bpy.context.selected_objects) == warning["objects"]
    assert any(b.names == "spur[1]" for b in buttons), "an object named with '['"
    # Names are matched exactly: "spur" is not "spur[1]", "rails[1]" is not "rails".
    assert bpy.ops.batten.select_curves(names="spur\nrails[1]") == {"CANCELLED"}


def test_show_curves_of_found_knuckles_selects_their_object(examples_dir):
    """The hard-chine example with its chine drawn free, as the first spline of an object
    that holds a second, far-off spline: the knuckle edges found on "chine[0]" select the
    object "chine"."""
    coll = api.load_network(examples_dir / "hard_chine.json")
    chine = coll.objects["chine"]
    chine.batten.role = "free"
    _add_spline(chine, (0, -5, 10), (1, -5, 10))
    bpy.context.scene.batten.source = coll
    report = build_into_scene(bpy.context.scene)
    assert {k["curve"] for k in report["knuckle_edges"]} == {"chine[0]"}
    assert panels.knuckles_found(report)[0] == ["chine[0]"]
    assert panels.found_knuckle_objects(report) == ["chine"]
    layout = _Layout()
    panels._draw_report(layout, bpy.context.scene.batten.last_report)
    assert layout.record["buttons"][0].names == "chine", "the first button: the found knuckles"
    assert bpy.ops.batten.select_curves(names="chine") == {"FINISHED"}
    assert [o.name for o in bpy.context.selected_objects] == ["chine"]


def test_a_degenerate_corner_names_its_face_curves_and_place():
    """A triangle with a 0.5° corner is built, and the patch's repair of that corner reaches
    Python as a ``degenerate_corner`` dict naming the face's three curves, at the face."""
    coll = new_collection("sliver")
    a = np.radians(0.5)
    tip = (10 * np.cos(a), 10 * np.sin(a), 0.0)
    _line("base", (0, 0, 0), (10, 0, 0), coll)
    _line("slant", (0, 0, 0), tip, coll)
    _line("end", (10, 0, 0), tip, coll)
    report = api.build(coll, mirror=False).report
    found = _of_kind(report["warnings"], "degenerate_corner")
    assert found, report["warnings"]
    w = found[0]
    assert sorted(w["curves"]) == ["base", "end", "slant"], w
    assert sorted(w["objects"]) == ["base", "end", "slant"], w
    centre = (np.array([0, 0, 0]) + np.array([10, 0, 0]) + np.array(tip)) / 3
    assert np.allclose(w["location"], centre, atol=1e-5), w  # float32 curve data
    assert w["error"] is None, w


def test_a_side_blended_face_names_its_curves_and_both_fold_figures():
    """A narrow triangle, gently twisted, whose long side waves like an S across its chord:
    its Charrot–Gregory patch folds, the side-blended patch that replaces it does not, and the
    report says so as a ``side_blended`` dict naming the face's curves, with no fold left."""
    coll = new_collection("wave")

    def at(x, y):
        return (5.0 * x, 5.0 * y, 0.25 * x * y)

    thirds = np.linspace(0.0, 1.0, 4)
    wave = [at(0, 0), at(0.3, 0.2), at(0.6, -0.2), at(1, 0)]
    new_curve("waterline", "NURBS", np.array(wave, dtype=float), endpoint=True, collection=coll)
    station = [at(1 - 0.95 * t, 0.2 * t) for t in thirds]
    new_curve("station", "NURBS", np.array(station, dtype=float), endpoint=True, collection=coll)
    keel = [at(0.05 * (1 - t), 0.2 * (1 - t)) for t in thirds]
    new_curve("keel", "NURBS", np.array(keel, dtype=float), endpoint=True, collection=coll)
    report = api.build(coll, mirror=False).report
    assert report["faces"] == 1, report["warnings"]
    found = _of_kind(report["warnings"], "side_blended")
    assert len(found) == 1, report["warnings"]
    w = found[0]
    assert sorted(w["curves"]) == ["keel", "station", "waterline"], w
    assert sorted(w["objects"]) == ["keel", "station", "waterline"], w
    assert "Charrot–Gregory patch folds" in w["message"] and "(0 pair(s)" in w["message"], w
    assert w["location"] is not None and w["error"] is None, w
    assert report["folds"] == 0, report["warnings"]
