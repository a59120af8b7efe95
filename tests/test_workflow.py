"""The designer's workflow: Build and Live through bpy.ops and the depsgraph, the examples
menu, select-and-frame from warnings, and failures that change nothing."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import live, operators
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
    assert marks["nodes"].shape == (29, 3) and len(marks["problems"]) == 0


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
