"""Blender curves in: batten sees exactly the curve Blender draws.

For every spline type and flag combination (orders 2–6, end-point / Bézier / cyclic, rational
weights ≠ 1), every vertex of Blender's own evaluated polyline lies on batten's curve within
1e-6 of the curve's size, and the end points coincide.
"""

import itertools

import batten.api as api
import bpy
import numpy as np
import pytest
from batten.bridge import curves_in
from helpers import evaluated_polyline, new_bezier, new_curve
from mathutils import Matrix

REL = 1e-6
WORLD = Matrix.Translation((3.0, -2.0, 1.5)) @ Matrix.Rotation(0.7, 4, (1.0, 2.0, 0.5)) @ Matrix.Scale(2.5, 4)


def control_points(n, seed=0):
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.0, n)
    return np.column_stack([10 * t, 3 * np.sin(5 * t) + rng.normal(0, 0.3, n), rng.normal(0, 1.0, n)])


def check_on_curve(obj, closed):
    (curve,) = curves_in.read_object(obj)
    poly = evaluated_polyline(obj)
    size = np.linalg.norm(np.ptp(curve.control_points, axis=0))
    worst = max(curve.nearest(p.tolist(), 1e-12)[1] for p in poly)
    assert worst <= REL * size, f"{obj.name}: vertex {worst:.3e} off the curve (size {size:.1f})"
    a, b = curve.domain
    ends = curve.evaluate(np.array([a, b]))
    assert np.linalg.norm(poly[0] - ends[0]) <= REL * size, f"{obj.name}: start point differs"
    if closed:
        assert np.linalg.norm(ends[0] - ends[1]) <= REL * size, f"{obj.name}: closed curve does not close"
    else:
        assert np.linalg.norm(poly[-1] - ends[1]) <= REL * size, f"{obj.name}: end point differs"
    return curve


NURBS_CASES = list(itertools.product(range(2, 7), [False, True], [False, True], [False, True], [False, True]))


@pytest.mark.parametrize("order, endpoint, bezier, cyclic, rational", NURBS_CASES)
def test_nurbs_splines_match_blender(order, endpoint, bezier, cyclic, rational):
    n = 13 if order in (2, 4, 5) else 11  # both valid and invalid Bézier-mode counts occur
    weights = np.array([1, 0.5, 3, 1, 2, 0.25, 1.5, 1, 0.7, 2.2, 1, 0.9, 1.3])[:n] if rational else None
    obj = new_curve(
        "nurbs",
        "NURBS",
        control_points(n, order),
        order=order,
        endpoint=endpoint,
        bezier=bezier,
        cyclic=cyclic,
        weights=weights,
        matrix=WORLD,
    )
    curve = check_on_curve(obj, cyclic)
    if curves_in._blender_nurbs_valid(n, order, endpoint, bezier, cyclic):
        assert curve.degree == order - 1
        assert (curve.weights is not None) == rational


@pytest.mark.parametrize("cyclic", [False, True])
def test_bezier_splines_match_blender_and_keep_corners(cyclic):
    co = np.array([[0, 0, 0], [4, 1, 0.5], [8, 0, 0], [11, -2, 1]], dtype=float)
    left = co - [[1, 0.5, 0], [1, 0, 0.2], [1, 1, 0], [0.5, -1, 0]]
    right = co + [[1, 0.5, 0], [1, 0, 0.2], [0.3, -1.2, 0], [0.5, -1, 0]]  # point 2: a corner
    obj = new_bezier("bez", co, left, right, cyclic=cyclic, matrix=WORLD)
    curve = check_on_curve(obj, cyclic)
    assert curve.degree == 3
    assert 2.0 in curve.corners(), "the non-aligned handles at point 2 are a corner"
    assert 1.0 not in curve.corners(), "aligned handles at point 1 are smooth"


@pytest.mark.parametrize("cyclic", [False, True])
def test_poly_splines_match_blender(cyclic):
    obj = new_curve("poly", "POLY", control_points(7), cyclic=cyclic, matrix=WORLD)
    curve = check_on_curve(obj, cyclic)
    assert curve.degree == 1


def test_world_transform_is_applied():
    pts = control_points(6)
    obj = new_curve("moved", "NURBS", pts, order=4, endpoint=True, matrix=WORLD)
    (curve,) = curves_in.read_object(obj)
    m = np.array(WORLD)
    expected = pts.astype(np.float32).astype(float) @ m[:3, :3].T + m[:3, 3]
    np.testing.assert_allclose(curve.control_points, expected, atol=1e-9)


def test_multi_spline_objects_name_each_spline():
    obj = new_curve("frame", "POLY", control_points(4))
    s = obj.data.splines.new("POLY")
    s.points.add(2)
    s.points.foreach_set("co", np.array([0, 0, 0, 1, 1, 0, 0, 1, 2, 1, 0, 1], dtype=np.float32))
    curves = api.read_curves(obj)
    assert [c.name for c in curves] == ["frame[0]", "frame[1]"]


def test_roles_come_from_the_object():
    obj = new_curve("chine", "POLY", control_points(3))
    obj.batten.role = "knuckle"
    (curve,) = api.read_curves([obj])
    assert curve.role == "knuckle"


def test_nan_coordinates_name_the_curve():
    pts = control_points(5)
    pts[2, 1] = np.nan
    obj = new_curve("Station 3", "NURBS", pts, order=4, endpoint=True)
    with pytest.raises(api.BattenError, match=r"curve 'Station 3': control point 2 has a non-finite"):
        api.read_curves(obj)


def test_infinite_coordinates_name_the_curve():
    pts = control_points(5)
    pts[4, 0] = np.inf
    obj = new_curve("WL 2", "POLY", pts)
    with pytest.raises(api.BattenError, match=r"curve 'WL 2': control point 4 has a non-finite"):
        api.read_curves(obj)


def test_too_few_points():
    obj = new_curve("stub", "NURBS", control_points(2)[:1], order=4)
    with pytest.raises(api.BattenError, match=r"curve 'stub': 1 control points are fewer than order 2"):
        api.read_curves(obj)


def test_zero_length_curve_is_refused_on_export(tmp_path):
    obj = new_curve("dot", "POLY", np.ones((3, 3)))
    with pytest.raises(api.BattenError, match=r"curve 'dot': the curve has zero length"):
        api.export_network([obj], tmp_path / "n.json")
    assert not (tmp_path / "n.json").exists(), "nothing half-written"


def test_empty_collection_and_non_curve_objects():
    coll = bpy.data.collections.new("Hull")
    bpy.context.scene.collection.children.link(coll)
    with pytest.raises(api.BattenError, match=r"collection 'Hull' holds no curves"):
        api.read_curves(coll)
    new_curve("keel", "POLY", control_points(3), collection=coll)
    mesh = bpy.data.objects.new("Cube", bpy.data.meshes.new("Cube"))
    coll.objects.link(mesh)
    with pytest.raises(api.BattenError, match=r"object 'Cube' is a mesh, not a curve object"):
        api.read_curves(coll)
    with pytest.raises(api.BattenError, match="expected a collection"):
        api.read_curves(42)


def test_reading_does_not_change_the_source():
    obj = new_curve("src", "NURBS", control_points(6), order=4, endpoint=True, matrix=WORLD)
    before = np.empty(24, dtype=np.float32)
    obj.data.splines[0].points.foreach_get("co", before)
    api.read_curves(obj)
    after = np.empty(24, dtype=np.float32)
    obj.data.splines[0].points.foreach_get("co", after)
    assert np.array_equal(before, after)
    assert obj.matrix_world == WORLD
