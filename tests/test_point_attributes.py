"""Point and curve attributes (seed 002 §5, Figs. 3 and 4): a knuckle, tangent, straight or blend
on a curve's points shapes it there and keeps shaping it as the curve and its parents change;
a knuckle or tangent curve attribute acts on the points of the curves attached to it; points a
curve passes through attach like its ends; contradictory or impossible attributes are refused
naming the curve, with nothing changed."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import attribute_marks, hierarchy, spline_joints
from batten.form_operators import (
    BATTEN_OT_attach_curves,
    BATTEN_OT_clear_point_attributes,
    BATTEN_OT_make_bezier,
    BATTEN_OT_set_curve_attribute,
    BATTEN_OT_set_point_attribute,
)
from helpers import new_bezier, new_curve
from operator_runs import execute, new_collection
from test_form_panel import _draw

CurveError, InvalidArgumentError = api.CurveError, api.InvalidArgumentError


def _curve(obj):
    return api.read_curves(obj)[0]


def _samples(obj, n: int = 4001) -> np.ndarray:
    curve = _curve(obj)
    a, b = curve.domain
    return np.asarray(curve.evaluate(np.linspace(a, b, n)))


def _bezier_arrays(obj) -> dict[str, np.ndarray]:
    return {k: v.copy() for k, v in spline_joints.spline_points(obj.data.splines[0]).items()}


def _tangent_at(obj, point: np.ndarray, side: float = 1.0) -> np.ndarray:
    """The unit tangent of ``obj``'s curve just after (``side`` 1) or before (−1) ``point``."""
    curve = _curve(obj)
    t, _, _ = curve.nearest(point)
    a, b = curve.domain
    h = 1e-6 * (b - a)
    # A secant a little way off the point (``nearest`` may land a hair beside a corner).
    p0, p1 = np.asarray(curve.evaluate([min(max(t + side * k * h, a), b) for k in (1, 2)]))
    d = (p1 - p0) * side
    return d / np.linalg.norm(d)


@pytest.fixture
def midship():
    """A midship section in the plane x = 0 through the deck at side (0, 5, 6), the lower end of
    the flat of side (0, 5, 2), the bilge's end on the flat of bottom (0, 3, 0) and the keel
    (0, 0, 0), its handles drawn roughly (free)."""
    coll = new_collection("midship")
    co = [(0, 5, 6), (0, 5, 2), (0, 3, 0), (0, 0, 0)]
    left = [(0, 5.2, 7), (0, 5.3, 2.8), (0, 3.5, 0.3), (0, 0.8, 0.1)]
    right = [(0, 4.9, 5), (0, 4.6, 1.0), (0, 2.5, -0.1), (0, -0.5, 0)]
    return new_bezier("midship", co, left, right, collection=coll)


def test_straight_blend_straight_make_a_flat_side_a_bilge_radius_and_a_flat_bottom(midship):
    api.set_point_attribute(midship, "straight", 0)
    api.set_point_attribute(midship, "blend", 1)
    api.set_point_attribute(midship, "straight", 2)
    p = _samples(midship)
    side, bottom = p[p[:, 2] >= 2.0], p[p[:, 1] <= 3.0]
    assert np.abs(side[:, 1] - 5.0).max() < 1e-6  # the flat of side is straight
    assert np.abs(bottom[:, 2]).max() < 1e-6  # and the flat of bottom
    bilge = p[(p[:, 2] < 2.0) & (p[:, 1] > 3.0)]
    radius = np.linalg.norm(bilge[:, 1:] - (3.0, 2.0), axis=1)
    # A cubic's circular arc: radius within 2.8e-4 of it (the 4/3·tan(θ/4) handle).
    assert np.abs(radius - 2.0).max() < 2.8e-4 * 2.0
    assert _curve(midship).corners() == []  # tangent into and out of the bilge
    kinds = [(a["kind"], a["point"]) for a in api.point_attributes_of(midship)]
    assert kinds == [("straight", 0), ("blend", 1), ("straight", 2)]
    types = [(b.handle_left_type, b.handle_right_type) for b in midship.data.splines[0].bezier_points]
    assert types[0][1] == "VECTOR" and types[3][0] == "VECTOR"


def test_the_attributes_hold_when_a_point_moves(midship):
    for kind, point in (("straight", 0), ("blend", 1), ("straight", 2)):
        api.set_point_attribute(midship, kind, point)
    # The bilge's lower end moved 0.5 m out along the flat of bottom (a larger bilge radius).
    bp = midship.data.splines[0].bezier_points[2]
    bp.co = (0.0, 2.5, 0.0)
    assert api.update_hierarchy([midship]) == ["midship"]
    p = _samples(midship)
    assert np.abs(p[p[:, 1] <= 2.5][:, 2]).max() < 1e-6
    assert np.abs(p[p[:, 2] >= 2.0][:, 1] - 5.0).max() < 1e-6
    assert _curve(midship).corners() == []
    # Straight into the bilge and out: the tangents at its ends are the flats' directions.
    assert _tangent_at(midship, np.array([0, 5, 2.0])) == pytest.approx([0, 0, -1], abs=2e-5)
    assert _tangent_at(midship, np.array([0, 2.5, 0.0])) == pytest.approx([0, -1, 0], abs=2e-5)
    assert api.update_hierarchy([midship]) == []  # a second update finds nothing to do


def test_a_knuckle_makes_a_corner_and_a_tangent_sets_the_direction():
    coll = new_collection("station")
    co = [(4, 0, 0), (4, 1.5, 0.8), (4, 2, 2)]
    left = [(4, -0.3, 0), (4, 1.1, 0.3), (4, 2, 1.6)]
    right = [(4, 0.5, 0), (4, 1.9, 1.3), (4, 2, 2.4)]
    st = new_bezier("st", co, left, right, collection=coll)
    assert _curve(st).corners() == []
    api.set_point_attribute(st, "knuckle", 1)
    corners = _curve(st).corners()
    assert len(corners) == 1
    before, after = _tangent_at(st, np.array(co[1]), -1.0), _tangent_at(st, np.array(co[1]))
    chord_in, chord_out = np.subtract(co[1], co[0]), np.subtract(co[2], co[1])
    assert before == pytest.approx(chord_in / np.linalg.norm(chord_in), abs=1e-5)
    assert after == pytest.approx(chord_out / np.linalg.norm(chord_out), abs=1e-5)
    # A tangent replaces the knuckle on that point.
    attribute = api.set_point_attribute(st, "tangent", 1, direction="z")
    assert attribute == {"kind": "tangent", "point": 1, "direction": [0.0, 0.0, 1.0]}
    assert [a["kind"] for a in api.point_attributes_of(st)] == ["tangent"]
    assert _curve(st).corners() == []
    assert _tangent_at(st, np.array(co[1])) == pytest.approx([0, 0, 1], abs=2e-5)
    arrays = _bezier_arrays(st)
    # Both handles on the vertical through the point.
    assert arrays["handle_left"][1] - arrays["co"][1] == pytest.approx(
        [0, 0, -np.linalg.norm(arrays["handle_left"][1] - arrays["co"][1])], abs=1e-6
    )
    # The direction it runs through a point now, when none is given.
    api.clear_point_attributes(st)
    d = api.set_point_attribute(st, "tangent", 2)["direction"]
    assert d == pytest.approx([0, 0, 1], abs=1e-6)


def test_a_cubic_nurbs_with_bezier_knots_takes_attributes_at_every_third_point():
    coll = new_collection("nurbs")
    pts = [(0, 0, 0), (1, 0.2, 0), (2, 0.8, 0), (3, 1, 0), (4, 1.3, 0), (5, 2.0, 0), (6, 2.2, 0)]
    obj = new_curve("wl", "NURBS", pts, order=4, endpoint=True, bezier=True, collection=coll)
    api.set_point_attribute(obj, "straight", 0)
    co = spline_joints.spline_points(obj.data.splines[0])["co"][:, :3]
    assert co[1] == pytest.approx((2 * co[0] + co[3]) / 3, abs=1e-6)  # on the chord, a third along
    p = _samples(obj)
    first = p[p[:, 0] <= 3.0]
    assert np.abs(np.cross(first - co[0], co[3] - co[0])).max() < 1e-5
    assert _curve(obj).corners() == []  # and leaves the straight tangentially


def test_bad_point_attributes_are_refused_with_nothing_changed(midship):
    api.set_point_attribute(midship, "straight", 0)
    stored, arrays = midship[hierarchy.POINT_ATTRIBUTES], _bezier_arrays(midship)
    types = [(b.handle_left_type, b.handle_right_type) for b in midship.data.splines[0].bezier_points]

    def unchanged():
        assert midship[hierarchy.POINT_ATTRIBUTES] == stored
        for k, v in _bezier_arrays(midship).items():
            assert v == pytest.approx(arrays[k], abs=0)
        now = [(b.handle_left_type, b.handle_right_type) for b in midship.data.splines[0].bezier_points]
        assert now == types

    with pytest.raises(CurveError, match="'midship'.*point 1 has a tangent and ends a straight"):
        api.set_point_attribute(midship, "tangent", 1, direction="y")
    unchanged()
    api.set_point_attribute(midship, "blend", 1)
    stored, arrays = midship[hierarchy.POINT_ATTRIBUTES], _bezier_arrays(midship)
    types = [(b.handle_left_type, b.handle_right_type) for b in midship.data.splines[0].bezier_points]
    with pytest.raises(CurveError, match="'midship'.*knuckle and ends a blend"):
        api.set_point_attribute(midship, "knuckle", 2)
    unchanged()
    with pytest.raises(CurveError, match="point 2 ends two blends"):
        api.set_point_attribute(midship, "blend", 2)
    unchanged()
    with pytest.raises(InvalidArgumentError, match="point 3 is an end of curve 'midship'"):
        api.set_point_attribute(midship, "knuckle", 3)
    with pytest.raises(InvalidArgumentError, match="point 4 of curve 'midship' is none of 0..3"):
        api.set_point_attribute(midship, "knuckle", 4)
    with pytest.raises(InvalidArgumentError, match="from point 3 to the next.*points 0..3"):
        api.set_point_attribute(midship, "straight", 3)
    for direction in ((0, 0, 0), (float("nan"), 0, 1), "w", (1, 2)):
        with pytest.raises(InvalidArgumentError, match="direction"):
            api.set_point_attribute(midship, "tangent", 3, direction=direction)
    with pytest.raises(InvalidArgumentError, match="unknown point attribute 'fillet'"):
        api.set_point_attribute(midship, "fillet", 0)
    unchanged()
    coll = new_collection("others")
    poly = new_curve("poly", "POLY", [(0, 0, 0), (1, 0, 0), (2, 1, 0)], collection=coll)
    with pytest.raises(CurveError, match="'poly'.*POLY spline has none"):
        api.set_point_attribute(poly, "tangent", 1)
    assert hierarchy.POINT_ATTRIBUTES not in poly
    api.set_point_attribute(poly, "knuckle", 1)  # a POLY spline is a corner at every point
    uniform = new_curve("uniform", "NURBS", [(0, 0, 0), (1, 1, 0), (2, 1, 0), (3, 0, 0)], collection=coll)
    with pytest.raises(CurveError, match="'uniform'.*does not pass through its control points"):
        api.set_point_attribute(uniform, "knuckle", 1)
    assert hierarchy.POINT_ATTRIBUTES not in uniform


@pytest.fixture
def chined():
    """A chine along x at y = 2, z = 1 (x 0…10); a station at x = 4 through it at its point 1,
    smooth there, from the keel to the deck; a flat of bottom curve in z = 0."""
    coll = new_collection("chined")
    chine = new_curve("chine", "POLY", [(0, 2, 1), (10, 2, 1)], collection=coll)
    fob = new_curve("fob", "POLY", [(0, 0, 0), (10, 0, 0)], collection=coll)
    co = [(4, 0, 0), (4, 2, 1), (4, 2.6, 2.5)]
    left = [(4, -0.5, -0.2), (4, 1.6, 0.5), (4, 2.5, 2.0)]
    right = [(4, 0.5, 0.2), (4, 2.4, 1.5), (4, 2.7, 3.0)]
    st = new_bezier("st4", co, left, right, collection=coll)
    return coll, chine, fob, st


def test_an_attached_point_follows_its_parent_between_fixed_ends(chined):
    coll, chine, fob, st = chined
    made = api.attach(st, chine, point="nearest")
    assert made == [{"child": "st4", "point": 1, "parent": "chine", "t": pytest.approx(0.4)}]
    assert api.attachments(coll) == [{"child": "st4", "point": 1, "parent": "chine", "t": pytest.approx(0.4)}]
    # The chine raised 0.5 m: the station's point 1 follows, its ends stay.
    spline = chine.data.splines[0]
    spline.points.foreach_set("co", np.array([[0, 2, 1.5, 1], [10, 2, 1.5, 1]], dtype=np.float32).ravel())
    assert api.update_hierarchy(coll) == ["st4"]
    arrays = _bezier_arrays(st)
    assert arrays["co"] == pytest.approx(np.array([(4, 0, 0), (4, 2, 1.5), (4, 2.6, 2.5)]), abs=1e-6)
    assert arrays["handle_right"][1] - arrays["co"][1] == pytest.approx([0, 0.4, 0.5], abs=1e-6)
    assert api.detach(st, point=1) == 1 and api.attachments(coll) == []


def test_a_knuckle_curve_makes_its_attached_points_knuckles(chined):
    coll, chine, fob, st = chined
    api.attach(st, chine, point=1)
    assert _curve(st).corners() == []
    api.set_curve_attribute(chine, "knuckle")
    assert chine.batten.role == "knuckle"
    assert api.curve_attributes(chine) == {"knuckle": True, "tangent": False}
    assert len(_curve(st).corners()) == 1
    assert _tangent_at(st, np.array([4, 2, 1.0])) == pytest.approx(
        np.array([0, 0.6, 1.5]) / np.linalg.norm([0, 0.6, 1.5]), abs=2e-5
    )
    api.set_curve_attribute(chine, "knuckle", on=False)
    assert chine.batten.role == "free"


def test_a_tangent_curve_makes_attached_curves_enter_its_plane_tangentially(chined):
    coll, chine, fob, st = chined
    api.attach(st, fob, end="start")
    with pytest.raises(CurveError, match="'fob' is held in no plane"):
        api.set_curve_attribute(fob, "tangent")
    assert not api.curve_attributes(fob)["tangent"]
    api.set_plane(fob, "z")
    api.set_curve_attribute(fob, "tangent")
    assert api.curve_attributes(fob) == {"knuckle": False, "tangent": True}
    # The station leaves the flat of bottom horizontally (it rose 0.2 in 0.5 before).
    assert _tangent_at(st, np.array([4, 0, 0.0])) == pytest.approx([0, 1, 0], abs=2e-5)
    assert json.loads(st.get(hierarchy.ATTACHMENTS))[0]["end"] == "start"
    assert hierarchy.POINT_ATTRIBUTES not in st  # a curve attribute, not stored on the child


def test_the_operators_and_the_panel(chined):
    coll, chine, fob, st = chined
    for o in bpy.context.view_layer.objects:
        o.select_set(o == st)
    bpy.context.view_layer.objects.active = st
    bpy.ops.object.mode_set(mode="EDIT")
    try:
        assert BATTEN_OT_set_point_attribute.poll(bpy.context)
        points = st.data.splines[0].bezier_points
        for k, b in enumerate(points):
            b.select_control_point = k == 1
        status, reports = execute(
            BATTEN_OT_set_point_attribute, bpy.context, kind="straight", direction="current"
        )
        assert status == {"CANCELLED"} and "select two neighbouring points" in reports[-1][1]
        status, reports = execute(
            BATTEN_OT_set_point_attribute, bpy.context, kind="knuckle", direction="current"
        )
        assert status == {"FINISHED"}, reports
    finally:
        bpy.ops.object.mode_set(mode="OBJECT")
    assert [(a["kind"], a["point"]) for a in api.point_attributes_of(st)] == [("knuckle", 1)]
    assert len(_curve(st).corners()) == 1
    drawn = _draw()
    assert "Knuckle on point 1" in drawn["labels"]
    assert {"batten.set_point_attribute", "batten.set_curve_attribute"} <= set(drawn["ops"])
    st.select_set(True)
    assert BATTEN_OT_clear_point_attributes.poll(bpy.context)
    assert execute(BATTEN_OT_clear_point_attributes, bpy.context)[0] == {"FINISHED"}
    assert api.point_attributes_of(st) == []
    # The station's crossing point attached to the chine, which becomes a knuckle line.
    chine.select_set(True)
    bpy.context.view_layer.objects.active = chine
    status, reports = execute(BATTEN_OT_attach_curves, bpy.context, what="point")
    assert status == {"FINISHED"} and "st4 (point 1)" in reports[-1][1]
    st.select_set(False)
    assert execute(BATTEN_OT_set_curve_attribute, bpy.context, kind="knuckle", on=True)[0] == {"FINISHED"}
    assert chine.batten.role == "knuckle" and len(_curve(st).corners()) == 1
    assert "chine: curve attribute knuckle" in _draw()["labels"]
    status, reports = execute(BATTEN_OT_set_curve_attribute, bpy.context, kind="tangent", on=True)
    assert status == {"CANCELLED"} and "held in no plane" in reports[-1][1]
    # Make Bézier on the (POLY) chine.
    assert BATTEN_OT_make_bezier.poll(bpy.context)
    status, reports = execute(BATTEN_OT_make_bezier, bpy.context)
    assert status == {"FINISHED"} and "chine" in reports[-1][1]
    assert chine.data.splines[0].type == "BEZIER" and not BATTEN_OT_make_bezier.poll(bpy.context)
    assert "batten.make_bezier" in _draw()["ops"]


def test_the_overlay_marks_the_attributes(midship, chined):
    for kind, point in (("straight", 0), ("blend", 1), ("straight", 2)):
        api.set_point_attribute(midship, kind, point)
    marks = attribute_marks.attribute_marks([midship])
    assert marks["straight"].shape == (4 * attribute_marks.MARK_SAMPLES, 3)
    radius = np.linalg.norm(marks["blend"][:, 1:] - (3.0, 2.0), axis=1)
    assert np.abs(radius - 2.0).max() < 2.8e-4 * 2.0
    assert len(marks["knuckle"]) == len(marks["tangent"]) == len(marks["attached"]) == 0
    coll, chine, fob, st = chined
    api.set_point_attribute(st, "tangent", 0, direction="y")
    api.set_point_attribute(st, "knuckle", 1)
    api.attach(st, chine, point=1)
    marks = attribute_marks.attribute_marks([st])
    # The tangent at the keel: along y through it, a third of its chord (√5) either side.
    third = np.sqrt(5.0) / 3.0
    assert marks["tangent"] == pytest.approx(np.array([[4, -third, 0], [4, third, 0]]), abs=1e-6)
    assert marks["knuckle"] == pytest.approx(np.array([[4, 2, 1]]), abs=1e-6)
    assert marks["attached"] == pytest.approx(np.array([[4, 2, 1]]), abs=1e-6)


def _flat_station(coll, lift: float = 0.0):
    """A flat of bottom line at y = 2 in z = 0, and a station at x = 4 whose flat piece runs
    along y in z = ``lift`` past the line to its point 1 at y = 2.0003 (0.3 mm aside)."""
    fob = new_curve("fob", "POLY", [(0, 2, 0), (10, 2, 0)], collection=coll)
    co = [(4, 0, lift), (4, 2.0003, lift), (4, 3, 1)]
    left = [(4, -0.6, lift), (4, 1.4, lift), (4, 3, 0.5)]
    right = [(4, 0.6, lift), (4, 2.5, lift), (4, 3, 1.5)]
    return fob, new_bezier("st4", co, left, right, collection=coll)


def test_a_point_near_a_curve_its_curve_already_meets_keeps_its_offset_and_nothing_moves():
    coll = new_collection("flat")
    fob, st = _flat_station(coll)
    before = _bezier_arrays(st)
    made = api.attach(st, fob, point="nearest")
    assert made[0]["point"] == 1
    assert made[0]["offset"] == pytest.approx([0.0, 3e-4, 0.0], abs=1e-6)
    for k, v in _bezier_arrays(st).items():
        assert np.array_equal(v, before[k]), "attaching moved nothing"
    # The flat of bottom widened by 0.5 m: the point follows it, keeping its 0.3 mm.
    fob.data.splines[0].points.foreach_set(
        "co", np.array([[0, 2.5, 0, 1], [10, 2.5, 0, 1]], dtype=np.float32).ravel()
    )
    assert api.update_hierarchy(coll) == ["st4"]
    co = _bezier_arrays(st)["co"]
    assert co == pytest.approx(np.array([(4, 0, 0), (4, 2.5003, 0), (4, 3, 1)]), abs=1e-6)
    # Drawn 5 mm apart, the curves do not meet: the point is moved onto the line.
    coll = new_collection("lifted")
    fob, st = _flat_station(coll, lift=0.005)
    made = api.attach(st, fob, point="nearest")
    assert "offset" not in made[0]
    assert _bezier_arrays(st)["co"][1] == pytest.approx([4, 2.0, 0.0], abs=1e-6)


def _shape(obj, n: int = 801) -> tuple[object, np.ndarray]:
    curve = _curve(obj)
    a, b = curve.domain
    return curve, np.asarray(curve.evaluate(np.linspace(a, b, n)))


def _same_shape(before, obj) -> float:
    """The largest distance (m) between the curve ``before`` was and ``obj``'s curve now."""
    (c0, p0), (c1, p1) = before, _shape(obj)
    return max(max(c1.nearest(p)[1] for p in p0), max(c0.nearest(p)[1] for p in p1))


@pytest.mark.parametrize("kind", ["BEZIER", "NURBS"])
def test_a_crossing_without_a_point_gets_one_with_the_shape_unchanged(kind):
    coll = new_collection(f"split {kind}")
    if kind == "BEZIER":
        st = new_bezier(
            "st",
            [(4, 0, 0), (4, 2.6, 2.5)],
            [(4, -0.5, -0.2), (4, 2.5, 2.0)],
            [(4, 1.5, 0.1), (4, 2.7, 3.0)],
            collection=coll,
        )
    else:
        pts = [(4, 0, 0), (4, 1.5, 0.1), (4, 2.5, 2.0), (4, 2.6, 2.5)]
        st = new_curve("st", "NURBS", pts, order=4, endpoint=True, bezier=True, collection=coll)
    api.set_point_attribute(st, "tangent", 1)  # the end: point 1 before, 2 after
    # A chine along x through the station's point at t = 0.37 (no point of it there).
    at = _curve(st).evaluate([0.37])[0]
    chine = new_curve("chine", "POLY", [(0, at[1], at[2]), (10, at[1], at[2])], collection=coll)
    wl = new_curve("wl", "POLY", [(0, 2.6, 2.5), (4, 2.6, 2.5)], collection=coll)
    api.attach(wl, st, end="end")  # a curve attached to the station, to the station's end
    before = _shape(st)
    made = api.attach(st, chine, point="nearest")
    assert made[0]["point"] == 1 and "offset" not in made[0]
    assert len(spline_joints.joint_points(st)) == 3
    assert spline_joints.joint_points(st)[1] == pytest.approx(at, abs=1e-6)
    assert _same_shape(before, st) < 1e-6, "the split kept the curve's shape"
    assert [(a["kind"], a["point"]) for a in api.point_attributes_of(st)] == [("tangent", 2)]
    # The waterline's attachment to the station's end: its parameter taken again (t 1 → 2).
    assert hierarchy.attachments_of(wl)[0]["t"] == pytest.approx(2.0, abs=1e-9)
    assert api.update_hierarchy(coll) == []
    # The chine raised: the station's new point follows it, its ends stay.
    chine.data.splines[0].points.foreach_set(
        "co", np.array([[0, at[1], at[2] + 0.2, 1], [10, at[1], at[2] + 0.2, 1]], dtype=np.float32).ravel()
    )
    assert "st" in api.update_hierarchy(coll)
    assert spline_joints.joint_points(st)[1] == pytest.approx(at + (0, 0, 0.2), abs=1e-6)
    assert spline_joints.joint_points(st)[[0, 2]] == pytest.approx(
        np.array([(4, 0, 0), (4, 2.6, 2.5)]), abs=1e-6
    )


def test_a_curve_that_passes_far_from_the_parent_is_refused_unsplit(chined):
    coll, chine, fob, st = chined
    far = new_curve("far", "POLY", [(0, 5, 5), (10, 5, 5)], collection=coll)
    before = _bezier_arrays(st)
    with pytest.raises(CurveError, match="'st4' passes .* m from 'far' at the nearest"):
        api.attach(st, far, point="nearest")
    assert len(st.data.splines[0].bezier_points) == 3 and hierarchy.ATTACHMENTS not in st
    for k, v in _bezier_arrays(st).items():
        assert np.array_equal(v, before[k])


@pytest.mark.parametrize(
    "key, text",
    [
        (hierarchy.POINT_ATTRIBUTES, "not json"),
        (hierarchy.POINT_ATTRIBUTES, '[{"kind": "fillet", "point": 1}]'),
        (hierarchy.POINT_ATTRIBUTES, '[{"kind": "tangent", "point": 1, "direction": [0, 0]}]'),
        (hierarchy.ATTACHMENTS, "[1, 2]"),
        (hierarchy.ATTACHMENTS, '[{"end": "middle", "parent": "keel", "t": 0}]'),
        (hierarchy.ATTACHMENTS, '[{"point": 1, "parent": "chine", "t": NaN}]'),
        (hierarchy.PLANE, '{"normal": [0, 0, 0], "offset": 1}'),
        (hierarchy.PLANE, '{"normal": [1, 0, 0]}'),
    ],
)
def test_a_property_edited_by_hand_is_named_and_nothing_breaks(barge, key, text):  # noqa: F811
    from batten.scene_build import build_into_scene

    st = barge.objects["st10"]
    bpy.context.scene.batten.source = barge
    st[key] = text
    before = _bezier_arrays(st) if st.data.splines[0].type == "BEZIER" else None
    report = build_into_scene(bpy.context.scene)
    assert f"curve 'st10': its property '{key}' is not what batten stores there" in report["hierarchy_error"]
    assert report["faces"] > 0, "the build goes on with the curves as they are"
    assert before is None or all(np.array_equal(v, before[k]) for k, v in _bezier_arrays(st).items())
    assert len(attribute_marks.attribute_marks([st])["attached"]) == 0
    bpy.context.view_layer.objects.active = st
    drawn = _draw()
    assert any("its property" in text for text in drawn["alerts"]), "the panel says so"
    with pytest.raises(CurveError, match="its property"):
        api.attach(st, barge.objects["deck"], end="end")
    # Clearing, detaching or releasing takes the broken property away.
    {
        hierarchy.POINT_ATTRIBUTES: lambda: api.clear_point_attributes(st),
        hierarchy.ATTACHMENTS: lambda: api.detach(st),
        hierarchy.PLANE: lambda: api.clear_plane(st),
    }[key]()
    assert key not in st
    assert "hierarchy_error" not in build_into_scene(bpy.context.scene)


@pytest.mark.parametrize(
    "kind, points, order, bezier",
    [
        ("POLY", [(0, 0, 0), (1, 0.5, 0), (2, 0.2, 0.4), (3, 1.0, 0.3)], 4, False),
        ("NURBS", [(0, 0, 0), (1, 0.5, 0), (2, 0.2, 0.4), (3, 1.0, 0.3), (4, 0.8, 0)], 3, False),
        ("NURBS", [(0, 0, 0), (1, 0.5, 0), (2, 0.2, 0.4), (3, 1.0, 0.3), (4, 0.8, 0)], 3, True),
        ("NURBS", [(0, 0, 0), (1, 0.5, 0), (2, 0.2, 0.4), (3, 1.0, 0.3), (4, 0.8, 0), (5, 0, 1)], 4, False),
    ],
)
def test_make_bezier_keeps_the_shape_exactly(kind, points, order, bezier):
    coll = new_collection("to bezier")
    obj = new_curve("c", kind, points, order=order, endpoint=True, bezier=bezier, collection=coll)
    obj.location = (10.0, -2.0, 1.0)  # the object's transform is kept
    bpy.context.view_layer.update()
    before = _shape(obj)
    child = new_curve("child", "POLY", [before[1][400], before[1][400] + (0, 0, 1)], collection=coll)
    api.attach(child, obj, end="start")
    assert api.to_bezier([obj]) == ["c"]
    spline = obj.data.splines[0]
    assert spline.type == "BEZIER"
    assert _same_shape(before, obj) < 2e-6, "the same shape, to Blender's single precision"
    # The curve attached to it references the same point, on the new parameters.
    assert api.update_hierarchy(coll) == [], "nothing moves"
    assert _co_of(child)[0] == pytest.approx(before[1][400], abs=1e-5)
    # Its points now carry attributes.
    api.set_point_attribute(obj, "knuckle", 1)
    assert _curve(obj).corners()[0] == pytest.approx(1.0), "a corner at point 1"
    assert api.to_bezier([obj]) == [], "a Bézier spline is left as it is"


def _co_of(obj) -> np.ndarray:
    spline = obj.data.splines[0]
    buf = np.empty(4 * len(spline.points), dtype=np.float32)
    spline.points.foreach_get("co", buf)
    return buf.reshape(-1, 4)[:, :3].astype(float)


def test_make_bezier_refuses_what_has_no_exact_bezier_form():
    coll = new_collection("no bezier")
    quintic = new_curve(
        "quintic", "NURBS", [(i, (i % 2) * 0.3, 0) for i in range(7)], order=6, endpoint=True, collection=coll
    )
    arc = new_curve(
        "arc",
        "NURBS",
        [(1, 0, 0), (1, 1, 0), (0, 1, 0)],
        order=3,
        endpoint=True,
        weights=[1.0, 0.7071, 1.0],
        collection=coll,
    )
    plain = new_curve("plain", "POLY", [(0, 0, 0), (1, 0, 0)], collection=coll)
    with pytest.raises(CurveError, match="'quintic' is of degree 5"):
        api.to_bezier([plain, quintic])
    assert plain.data.splines[0].type == "POLY", "all or none"
    with pytest.raises(CurveError, match="'arc' is rational"):
        api.to_bezier(arc)
    assert arc.data.splines[0].type == "NURBS"
    bpy.context.view_layer.objects.active = plain
    bpy.ops.object.mode_set(mode="EDIT")
    try:
        with pytest.raises(CurveError, match="'plain' is in Edit Mode"):
            api.to_bezier(plain)
    finally:
        bpy.ops.object.mode_set(mode="OBJECT")
    assert plain.data.splines[0].type == "POLY"


def test_attributes_hold_through_a_transformation_committed_to_the_original(barge):  # noqa: F811
    st = barge.objects["st10"]
    assert api.to_bezier([st]) == ["st10"]
    api.set_point_attribute(st, "knuckle", 1)
    result = api.transform(barge, breadth=21.0, draft=8.0)
    api.commit(result)
    # The committed curve is written again (its joints the same), and keeps its attribute.
    assert [(a["kind"], a["point"]) for a in api.point_attributes_of(st)] == [("knuckle", 1)]
    assert _curve(st).corners() == pytest.approx([1.0])
    assert api.update_hierarchy(barge) == [], "the attribute holds already"
