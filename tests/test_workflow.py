"""The designer's workflow: Build and Live through bpy.ops and the depsgraph, the examples
menu, select-and-frame from warnings, and failures that change nothing."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import live, operators, scene_build
from test_build import mesh_arrays


@pytest.fixture
def frigate(examples_dir):
    assert bpy.ops.batten.add_example(example="frigate_network.json") == {"FINISHED"}
    coll = bpy.context.scene.batten.source
    assert coll is not None and len(coll.objects) == 13
    return coll


def test_examples_menu_lists_every_example():
    names = [p.name for p in operators.example_files()]
    assert {"frigate_network.json", "wigley.json"} <= set(names)
    with pytest.raises(RuntimeError, match="No example 'nope.json'"):
        bpy.ops.batten.add_example(example="nope.json")


def test_build_operator_matches_api_and_keeps_the_report(frigate):
    bpy.context.scene.batten.resolution = 6
    assert bpy.ops.batten.build() == {"FINISHED"}
    report = json.loads(bpy.context.scene.batten.last_report)
    assert report["faces_by_sides"] == {"3": 1, "4": 15, "5": 1}
    obj = api._surface_object(frigate.name)
    via_ops = mesh_arrays(obj).copy()
    api.build(frigate, resolution=6)
    assert np.array_equal(mesh_arrays(obj), via_ops), "operator and API give the same mesh"
    assert {"REGISTER", "UNDO"} <= operators.BATTEN_OT_build.bl_options
    from batten import overlay

    marks = overlay.markers(bpy.context)
    # 29 nodes: three T-joints (the knuckle ends on st6, wl_aft on st2, the rounding on the cwl:
    # each runs on straight through the node as a face's side), 26 plain nodes, no problems.
    assert {k: len(v) for k, v in marks.items()} == {
        "nodes": 26,
        "t_joints": 3,
        "dangling_ends": 0,
        "near_misses": 0,
        "holes": 0,
        "folds": 0,
        "problems": 0,
    }
    curves = {c.name: c for c in api.read_curves(frigate)}
    expected = []
    for end, on in (("knuckle", "st6"), ("wl_aft", "st2"), ("rounding", "cwl")):
        ends = curves[end].evaluate(np.array(curves[end].domain))
        expected += [p for p in ends if curves[on].nearest(p)[1] < 1e-3]
    assert len(expected) == 3, "each of the three curves has one end on the other curve"
    found = sorted(marks["t_joints"].tolist())
    assert np.allclose(found, sorted(np.array(expected).tolist()), atol=1e-3), (found, expected)
    # The frigate's only knuckle is the knuckle curve (by role), cut by st8 into two edges.
    lines = overlay.knuckle_lines(bpy.context)
    assert lines["role"].shape == (2 * 16 * 2, 3) and lines["auto"].shape == (0, 3)


def test_build_operator_errors_change_nothing(frigate):
    bpy.context.scene.batten.resolution = 4
    bpy.ops.batten.build()
    obj = api._surface_object(frigate.name)
    before = mesh_arrays(obj).copy()
    frigate.objects["keel"].data.splines[0].points[0].co.x = float("nan")  # Blender clamps inf
    with pytest.raises(RuntimeError, match="curve 'keel'"):
        bpy.ops.batten.build()
    assert np.array_equal(mesh_arrays(obj), before)
    assert "curve 'keel'" in json.loads(bpy.context.scene.batten.last_report)["error"]
    empty = bpy.data.collections.new("empty")
    bpy.context.scene.collection.children.link(empty)
    bpy.context.scene.batten.source = empty
    with pytest.raises(RuntimeError, match="holds no curves"):
        bpy.ops.batten.build()


def test_live_rebuild_follows_a_moved_control_point(frigate):
    scene = bpy.context.scene
    scene.batten.resolution = 4
    bpy.ops.batten.build()
    obj = api._surface_object(frigate.name)
    before = mesh_arrays(obj).copy()
    scene.batten.live = True
    station = next(o for o in frigate.objects if o.name.startswith("st"))
    p = station.data.splines[0].points[1]
    p.co = (p.co.x, p.co.y + 0.3, p.co.z, p.co.w)
    bpy.context.view_layer.update()  # the depsgraph update a drag makes
    assert scene.name in live._scheduled, "a rebuild was scheduled (coalesced by a timer)"
    live.rebuild_scene(scene.name)  # what the timer runs (no event loop headless)
    assert scene.name not in live._scheduled
    assert not np.array_equal(mesh_arrays(obj), before), "the mesh followed the curve"
    bpy.context.view_layer.update()
    assert scene.name not in live._scheduled, "the rebuild's own update schedules no other"
    # An update that touches no hull curve schedules nothing.
    other = bpy.data.objects.new("lamp", bpy.data.lights.new("lamp", "POINT"))
    scene.collection.objects.link(other)
    other.location.x += 1.0
    bpy.context.view_layer.update()
    assert scene.name not in live._scheduled


def test_select_curves_selects_the_named_ones(frigate):
    assert bpy.ops.batten.select_curves(names="keel\nstem") == {"FINISHED"}
    selected = sorted(o.name for o in bpy.context.selected_objects)
    assert selected == ["keel", "stem"]
    assert bpy.ops.batten.select_curves(names="nothing") == {"CANCELLED"}


def test_knuckle_role_makes_a_crease_and_free_makes_it_smooth():
    """Sections bend 3 degrees at the chine (below the 5 degree automatic knuckle rule):
    with the chine free the hull is smoothed across it (G1), as a knuckle it keeps the crease."""
    from helpers import new_curve

    coll = bpy.data.collections.new("barge")
    bpy.context.scene.collection.children.link(coll)
    bend = np.radians(3.0)
    chine = np.array([0.0, 2.0, 0.5])
    d = chine[1:] / np.linalg.norm(chine[1:])  # bottom direction in (y, z)
    turned = np.array([d[0] * np.cos(bend) - d[1] * np.sin(bend), d[0] * np.sin(bend) + d[1] * np.cos(bend)])
    top = np.array([0.0, *(chine[1:] + 1.5 * turned)])
    xs = [0.0, 3.0, 6.0, 9.0]
    for x in xs:
        pts = np.array([[x, 0.0, 0.0], [x, *chine[1:]], [x, *top[1:]]])
        new_curve(f"st{x:g}", "POLY", pts, collection=coll)
    for name, p in (("keel", [0.0, 0.0, 0.0]), ("chine", list(chine)), ("sheer", list(top))):
        new_curve(name, "POLY", np.array([[0.0, *p[1:]], [9.0, *p[1:]]]), collection=coll)
    smooth = api.build(coll, resolution=6).report
    assert smooth["crease_angles_deg"] == []
    # Free: the chine is G1 between nodes; only the 3 degree corners drawn into the sections
    # themselves remain, at the nodes, since the surface passes through every curve.
    assert smooth["max_normal_angle_deg"] <= 3.0 + 1e-3
    coll.objects["chine"].batten.role = "knuckle"
    creased = api.build(coll, resolution=6).report
    ((name, lo, hi),) = creased["crease_angles_deg"]
    assert name == "chine" and lo == pytest.approx(3.0, abs=0.01) and hi == pytest.approx(3.0, abs=0.01)
    coll.objects["chine"].batten.role = "free"
    assert api.build(coll, resolution=6).report["crease_angles_deg"] == []


class _Layout:
    """Records the labels a panel draws (a stand-in for ``bpy.types.UILayout`` headless)."""

    def __init__(self, labels=None):
        self.labels = [] if labels is None else labels
        self.alert = False

    def label(self, text="", icon="NONE"):
        self.labels.append(text)

    def operator(self, *_args, **_kwargs):
        return type("Op", (), {})()

    def box(self, **_kwargs):
        return _Layout(self.labels)

    column = row = box


def _panel_labels(report_json: str) -> list[str]:
    from batten import panels

    layout = _Layout()
    panels._draw_report(layout, report_json)
    return layout.labels


def _kinds(report) -> list[tuple[str, str]]:
    return [(k["curve"], k["source"]) for k in report["knuckle_edges"]]


def test_hard_chine_knuckle_edges_by_role_and_found(examples_dir):
    """The hard-chine example: the chine's six edges (transom, stations 2 … 10, stem) are the
    knuckle edges, by role; drawn free they are found at the corners of the crossing curves,
    and the panel names them."""
    from batten import overlay, panels

    coll = api.load_network(examples_dir / "hard_chine.json")
    scene = bpy.context.scene
    scene.batten.source = coll
    scene.batten.resolution = 8
    role = scene_build.build_into_scene(scene)
    assert _kinds(role) == [("chine", "role")] * 6
    ((name, lo, hi),) = role["crease_angles_deg"]
    creases = [k["crease_deg"] for k in role["knuckle_edges"]]
    assert name == "chine" and (lo, hi) == (min(c[0] for c in creases), max(c[1] for c in creases))
    assert hi - lo > 10.0, "the crease varies along the chine"
    lines = overlay.knuckle_lines(bpy.context)
    assert lines["role"].shape == (6 * 16 * 2, 3) and lines["auto"].shape == (0, 3)
    chine = next(c for c in api.read_curves(coll) if c.name == "chine")
    for p in lines["role"]:
        assert chine.nearest(p.astype(np.float64))[1] < 1e-4, "drawn on the chine"
    assert panels.knuckles_found(role) == ([], [])
    assert not any(t.startswith("Knuckles found") for t in _panel_labels(scene.batten.last_report))

    coll.objects["chine"].batten.role = "free"
    free = scene_build.build_into_scene(scene)
    assert _kinds(free) == [("chine", "auto")] * 6
    assert np.allclose([k["crease_deg"] for k in free["knuckle_edges"]], creases, atol=1e-9)
    assert free["crease_angles_deg"][0][1:] == pytest.approx((lo, hi), abs=1e-9)
    stations = [f"station {x}" for x in (10, 2, 4, 6, 8)]
    assert panels.knuckles_found(free) == (["chine"], sorted([*stations, "transom"]))
    stored = json.loads(scene.batten.last_report)["knuckle_edges"]
    assert stored[0]["corner_curves"] == ["station 2", "transom"], "kept in the scene's report"
    labels = _panel_labels(scene.batten.last_report)
    assert "Knuckles found: chine" in labels, labels
    assert "  at corners of station 10, station 2, station 4, station 6, station 8, transom" in labels
    lines = overlay.knuckle_lines(bpy.context)
    assert lines["role"].shape == (0, 3) and lines["auto"].shape == (6 * 16 * 2, 3)


def test_markers_tell_t_joints_and_dangling_ends_apart():
    """A side panel (plane y = 1) split by a station, a waterline from the aft end to the station
    (a T-joint there) and a spur from the station ending in the open (a dangling end)."""
    from batten import overlay
    from helpers import new_curve

    coll = bpy.data.collections.new("panel")
    bpy.context.scene.collection.children.link(coll)
    for name, a, b in (
        ("keel", (0, 0), (10, 0)),
        ("deck", (0, 3), (10, 3)),
        ("aft", (0, 0), (0, 3)),
        ("stem", (10, 0), (10, 3)),
        ("st5", (5, 0), (5, 3)),
        ("wl", (0, 1.5), (5, 1.5)),
        ("spur", (5, 2.5), (7, 2.5)),
    ):
        new_curve(name, "POLY", np.array([[a[0], 1.0, a[1]], [b[0], 1.0, b[1]]]), collection=coll)
    # The panel's rim is the hull's boundary (else every free edge of it would be a hole).
    for name, role in (("keel", "keel"), ("deck", "deck"), ("aft", "transom"), ("stem", "stem")):
        api.set_role([coll.objects[name]], role)
    scene = bpy.context.scene
    scene.batten.source = coll
    report = scene_build.build_into_scene(scene)
    assert report["faces_by_sides"] == {4: 3}
    marks = overlay.markers(bpy.context)
    # Nodes: the 4 panel corners, st5 on keel and deck, wl on aft, the spur's root on st5 (its
    # branch bounds no face, so no T-joint); the spur's free end is a dangling end, not a node.
    assert len(marks["nodes"]) == 8
    assert marks["t_joints"].tolist() == [[5.0, 1.0, 1.5]]
    assert marks["dangling_ends"].tolist() == [[7.0, 1.0, 2.5]]
    assert len(marks["near_misses"]) == 0
    assert marks["problems"].tolist() == [[5.0, 1.0, 2.5]], "the spur's unused edge"
    assert report["knuckle_edges"] == []
    # Lift the spur's root 0.5 mm off st5 (tolerance 0.1 mm): a near miss, and the spur is now
    # free at both ends.
    spur = coll.objects["spur"].data.splines[0].points[0]
    spur.co = (5.0005, 1.0, 2.5, 1.0)
    scene_build.build_into_scene(scene)
    marks = overlay.markers(bpy.context)
    assert len(marks["near_misses"]) == 1
    assert np.allclose(marks["near_misses"][0], [5.00025, 1.0, 2.5], atol=1e-4)
    assert len(marks["dangling_ends"]) == 0, "an isolated curve is a problem, not a dangling end"
    assert np.allclose(marks["problems"], [[5.0005, 1.0, 2.5]], atol=1e-4), "the isolated spur"
    assert len(marks["nodes"]) == 7 and len(marks["t_joints"]) == 1
