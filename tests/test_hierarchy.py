"""The curve network hierarchy (seed 002 §5, §7.1): a curve's end attached to another curve
follows the point it references when that curve changes, its free control points follow by the
elastic rule (Fig. 6), descendants update in hierarchy order through Build and Live; bad
attachments (too far, cycles, multi-spline, a gone parent) are refused naming the curves, with
nothing changed."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import hierarchy
from batten.form_operators import (
    BATTEN_OT_attach_curves,
    BATTEN_OT_detach_curves,
    BATTEN_OT_hold_in_plane,
    BATTEN_OT_release_plane,
)
from batten.scene_build import build_into_scene
from helpers import new_curve
from operator_runs import execute, new_collection


def _co(obj) -> np.ndarray:
    spline = obj.data.splines[0]
    buf = np.empty(4 * len(spline.points), dtype=np.float32)
    spline.points.foreach_get("co", buf)
    return buf.reshape(-1, 4)[:, :3].astype(float)


def _set_co(obj, points) -> None:
    spline = obj.data.splines[0]
    co = np.column_stack([np.asarray(points, dtype=float), np.ones(len(points))])
    spline.points.foreach_set("co", co.astype(np.float32).ravel())
    obj.data.update_tag()


@pytest.fixture
def frame():
    """A deck line at z = 2 (x 0…10), a keel at z = 0, a station at x = 4 from the keel to the
    deck, and a waterline from a point of the station to x = 9."""
    coll = new_collection("frame")
    deck = new_curve(
        "deck", "NURBS", [(0, 1, 2), (5, 1.5, 2), (10, 1, 2)], order=3, endpoint=True, collection=coll
    )
    keel = new_curve("keel", "POLY", [(0, 0, 0), (10, 0, 0)], collection=coll)
    # The deck's quadratic at x = 4 (t = 0.4): y = 0.36 + 0.72 + 0.16.
    st = new_curve(
        "st4",
        "NURBS",
        [(4, 0, 0), (4, 0.8, 0.3), (4, 1.1, 1.0), (4, 1.24, 1.6), (4, 1.24, 2.0)],
        order=4,
        endpoint=True,
        collection=coll,
    )
    station = api.read_curves(st)[0]
    on_station = np.asarray(station.evaluate([0.5 * sum(station.domain)]))[0]
    wl = new_curve(
        "wl1",
        "NURBS",
        [on_station, on_station + (2.0, 0.1, 0.0), on_station + (5.0, -0.2, 0.0)],
        order=3,
        endpoint=True,
        collection=coll,
    )
    return coll, deck, keel, st, wl


def test_elastic_rule_blends_by_chord_distance():
    polygon = np.array([[0, 0, 0], [1, 0, 0], [3, 0, 0], [4, 0, 0]], dtype=float)
    moves = hierarchy.elastic(polygon, np.array([0, 0, 1.0]), np.array([0, 0, -1.0]))
    assert moves[:, 2].tolist() == pytest.approx([1.0, 0.5, -0.5, -1.0])
    assert np.abs(moves[:, :2]).max() == 0.0


def test_an_attached_end_follows_its_parent_and_the_free_points_follow_elastically(frame):
    coll, deck, keel, st, wl = frame
    made = api.attach(st, deck)
    assert made == [{"child": "st4", "end": "end", "parent": "deck", "t": pytest.approx(made[0]["t"])}]
    api.attach("st4", keel, end="start")
    api.attach(wl, st)  # the waterline's start sits on the station
    order = [a["child"] for a in api.attachments(coll)]
    assert order.index("st4") < order.index("wl1"), "parents before children"
    before = _co(st)
    wl_before = _co(wl)
    # Raise the deck by 0.5 m: the station's top follows, its keel end stays, its middle
    # points move by their chord share; the waterline's start follows the station.
    _set_co(deck, _co(deck) + [0.0, 0.0, 0.5])
    assert api.update_hierarchy(coll) == ["st4", "wl1"]
    after = _co(st)
    chords = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(before, axis=0), axis=1))])
    share = chords / chords[-1]
    assert after[:, 2] - before[:, 2] == pytest.approx(0.5 * share, abs=1e-6)
    assert np.abs(after[:, :2] - before[:, :2]).max() < 1e-6
    top = api.read_curves(st)[0].evaluate([api.read_curves(st)[0].domain[1]])[0]
    deck_curve = api.read_curves(deck)[0]
    assert deck_curve.nearest(top)[1] < 1e-6, "the station's top is on the deck"
    station = api.read_curves(st)[0]
    start = api.read_curves(wl)[0].evaluate([0.0])[0]
    assert station.nearest(start)[1] < 1e-5, "the waterline's start is on the moved station"
    assert _co(wl)[-1] == pytest.approx(wl_before[-1], abs=1e-6), "its free end stays"
    assert api.update_hierarchy(coll) == [], "nothing moves twice"
    # Detached, the station stays where it is and no longer follows.
    assert api.detach(st, end="end") == 1
    _set_co(deck, _co(deck) - [0.0, 0.0, 0.5])
    api.update_hierarchy(coll)
    assert _co(st) == pytest.approx(after, abs=1e-6)


def test_build_brings_attached_curves_to_their_parents_first(barge):  # noqa: F811
    st, deck = barge.objects["st10"], barge.objects["deck"]
    api.attach(st, deck, end="end")
    top = _co(st)[-1].copy()
    pts = _co(st)
    pts[-1] += (0.0, -0.005, 0.0)  # the designer nudged it off the deck
    _set_co(st, pts)
    settings = bpy.context.scene.batten
    settings.source = barge
    report = build_into_scene(bpy.context.scene)
    assert report["hierarchy_moved"] == ["st10"]
    assert _co(st)[-1] == pytest.approx(top, abs=1e-6), "back on the deck"
    assert not [w for w in report["warnings"] if w["kind"] == "near_miss"]
    assert json.loads(settings.last_report)["hierarchy_moved"] == ["st10"]
    # A gone parent is said in the report, and the build goes on.
    st["batten_attachments"] = json.dumps([{"end": "start", "parent": "no such curve", "t": 0.0}])
    report = build_into_scene(bpy.context.scene)
    assert "'no such curve', which is gone" in report["hierarchy_error"]
    assert report["faces"] > 0


def test_bad_attachments_are_refused_with_nothing_changed(frame):
    coll, deck, keel, st, wl = frame
    far = new_curve("far", "POLY", [(20, 0, 5), (21, 0, 5)], collection=coll)
    before = _co(far)
    with pytest.raises(api.CurveError, match="'far': its (start|end) is .* m from 'deck'") as err:
        api.attach([st, far], deck)
    assert err.value.curve == "far"
    assert not st.get(hierarchy.ATTACHMENTS), "all or none: the station is not attached either"
    assert _co(far) == pytest.approx(before)
    with pytest.raises(api.CurveError, match="itself"):
        api.attach(st, st)
    api.attach(wl, st)
    with pytest.raises(api.CurveError, match="cycle"):
        api.attach(st, wl, end="start", tolerance=2.0)
    assert not st.get(hierarchy.ATTACHMENTS)
    two = new_curve("two", "POLY", [(4, 1.4, 2.0), (5, 1, 2)], collection=coll)
    two.data.splines.new("POLY").points.add(1)
    with pytest.raises(api.CurveError, match="'two' has 2 splines"):
        api.attach(two, deck)
    with pytest.raises(api.InvalidArgumentError, match="end 'middle'"):
        api.attach(st, deck, end="middle")
    with pytest.raises(api.InvalidArgumentError, match="tolerance"):
        api.attach(st, deck, tolerance=float("nan"))
    with pytest.raises(api.InvalidArgumentError, match="no object 'nothing'"):
        api.attach("nothing", deck)
    with pytest.raises(api.InvalidArgumentError, match="needs curve objects, got int"):
        api.attach(3, deck)
    with pytest.raises(api.InvalidArgumentError, match="no curve"):
        api.set_plane([], "x")
    # A parent that is gone is named, and the hierarchy changes nothing.
    api.attach(st, deck)
    bpy.data.objects.remove(deck)
    moved = _co(wl)
    with pytest.raises(api.CurveError, match="attached to 'deck', which is gone"):
        api.update_hierarchy(coll)
    assert _co(wl) == pytest.approx(moved)


def test_attach_and_detach_operators(frame):
    coll, deck, keel, st, wl = frame
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    st.select_set(True)
    deck.select_set(True)
    bpy.context.view_layer.objects.active = deck
    assert BATTEN_OT_attach_curves.poll(bpy.context)
    status, reports = execute(BATTEN_OT_attach_curves, bpy.context, what="end")
    assert status == {"FINISHED"}, reports
    assert "st4 (end)" in reports[-1][1]
    assert hierarchy.attachments_of(st)[0]["parent"] == "deck"
    bpy.context.view_layer.objects.active = st
    assert BATTEN_OT_detach_curves.poll(bpy.context)
    status, reports = execute(BATTEN_OT_detach_curves, bpy.context)
    assert status == {"FINISHED"} and "1 end(s)" in reports[-1][1]
    assert not hierarchy.attachments_of(st)
    # Held in its station plane, and released.
    deck.select_set(False)
    status, reports = execute(BATTEN_OT_hold_in_plane, bpy.context, plane="x")
    assert status == {"FINISHED"}, reports
    assert hierarchy.plane_of(st)[0].tolist() == [1.0, 0.0, 0.0]
    assert BATTEN_OT_release_plane.poll(bpy.context)
    assert execute(BATTEN_OT_release_plane, bpy.context)[0] == {"FINISHED"}
    assert hierarchy.plane_of(st) is None


def test_live_rebuilds_carry_the_hierarchy(frame):
    from batten import live

    coll, deck, keel, st, wl = frame
    api.attach(st, deck)
    settings = bpy.context.scene.batten
    settings.source = coll
    settings.live = True
    try:
        _set_co(deck, _co(deck) + [0.0, 0.0, 0.4])
        live.rebuild_scene(bpy.context.scene.name)
        assert _co(st)[-1][2] == pytest.approx(2.4, abs=1e-6)
    finally:
        settings.live = False


def test_a_committed_transformation_keeps_the_attachments_on_their_points(barge):  # noqa: F811
    st, deck = barge.objects["st10"], barge.objects["deck"]
    api.attach(st, deck, end="end")
    result = api.transform(barge, breadth=21.0)
    api.commit(result)
    top = _co(st)[-1].copy()
    api.update_hierarchy(barge)
    assert _co(st)[-1] == pytest.approx(top, abs=1e-6), "the end stays where the transformation put it"
    assert api.update_hierarchy(barge) == [], "and stays"
    t = hierarchy.attachments_of(st)[0]["t"]
    assert api.read_curves(deck)[0].nearest(top)[0] == pytest.approx(t, abs=1e-9)


def test_a_curve_held_in_its_plane_stays_there(frame):
    coll, deck, keel, st, wl = frame
    held = api.set_plane(st, "x")
    assert held == [{"curve": "st4", "normal": [1.0, 0.0, 0.0], "offset": pytest.approx(4.0, abs=1e-6)}]
    assert api.held_planes(coll) == held
    # A drag out of the plane is taken back into it; the other coordinates stay.
    pts = _co(st)
    pts[2] += (0.3, 0.05, 0.0)
    _set_co(st, pts)
    assert api.update_hierarchy(coll) == ["st4"]
    after = _co(st)
    assert after[:, 0] == pytest.approx(4.0, abs=1e-6)
    assert after[2, 1:] == pytest.approx(pts[2, 1:], abs=1e-6)
    assert api.update_hierarchy(coll) == [], "nothing moves twice"
    # Attached and held: the end follows the deck, then the curve is taken into its plane.
    api.attach(st, deck, end="end")
    _set_co(deck, _co(deck) + [0.2, 0.0, 0.3])
    api.update_hierarchy(coll)
    assert _co(st)[:, 0] == pytest.approx(4.0, abs=1e-6), "still in its station plane"
    assert _co(st)[-1][2] == pytest.approx(2.3, abs=1e-6), "and its top went up with the deck"
    # Its own plane, of a curve in one: the waterline's, z = const.
    fitted = api.set_plane(wl, "fit")[0]
    assert np.abs(np.abs(fitted["normal"]) - [0, 0, 1]).max() < 1e-9
    assert api.clear_plane([st, wl]) == 2 and api.held_planes(coll) == []


def test_bad_planes_are_refused_with_nothing_changed(frame):
    coll, deck, keel, st, wl = frame
    before = _co(st)
    with pytest.raises(api.CurveError, match=r"'st4' is 0\.876 m off the plane \(more than 0\.01 m\)"):
        api.set_plane(st, "y")
    with pytest.raises(api.CurveError, match="'st4' is .* m off the plane") as err:
        api.set_plane([wl, st], ((0, 0, 1), float(_co(wl)[0][2])))  # the waterline's own plane
    assert err.value.curve == "st4" and not wl.get(hierarchy.PLANE), "all or none"
    for plane in ("w", ((0, 0, 0), 1.0), ((0, 0, 1), float("nan")), 3):
        with pytest.raises(api.InvalidArgumentError):
            api.set_plane(st, plane)
    assert _co(st) == pytest.approx(before) and not st.get(hierarchy.PLANE)
