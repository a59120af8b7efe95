"""The point attribute rules (seed 002 §5, Fig. 3) on joints and handles, without Blender: a
blend is a circular arc where its tangents allow, a straight is straight and entered
tangentially, a knuckle has vector handles, a tangent keeps its handles' lengths; the rules are
idempotent; contradictions are named."""

import math

import numpy as np
import pytest
from batten import point_attributes as pa


def _cubic(p0, p1, p2, p3, n=2001):
    u = np.linspace(0.0, 1.0, n)[:, None]
    return (1 - u) ** 3 * p0 + 3 * (1 - u) ** 2 * u * p1 + 3 * (1 - u) * u**2 * p2 + u**3 * p3


@pytest.mark.parametrize("turn_deg", [30.0, 60.0, 90.0, 120.0])
def test_a_symmetric_blend_is_a_circular_arc(turn_deg):
    # An arc of radius 3 about the origin turning by θ, from angle 0.
    theta, r = math.radians(turn_deg), 3.0
    p0, p1 = np.array([r, 0.0, 0.0]), r * np.array([math.cos(theta), math.sin(theta), 0.0])
    t0, t1 = np.array([0.0, 1.0, 0.0]), np.array([-math.sin(theta), math.cos(theta), 0.0])
    h0, h1 = pa.blend_handles(p0, t0, p1, t1)
    handle = 4.0 / 3.0 * math.tan(theta / 4.0) * r
    assert np.linalg.norm(h0 - p0) == pytest.approx(handle, rel=1e-12)
    assert np.linalg.norm(p1 - h1) == pytest.approx(handle, rel=1e-12)
    radius = np.linalg.norm(_cubic(p0, h0, h1, p1), axis=1)
    # The cubic's classic error: 2.7e-4 of the radius at 90°, less for smaller turns.
    assert np.abs(radius - r).max() < 2.8e-4 * r * max(1.0, (turn_deg / 90.0) ** 6)


def test_a_blend_whose_tangents_never_meet_takes_a_third_of_the_chord():
    p0, p1 = np.zeros(3), np.array([2.0, 0.0, 0.0])
    t = np.array([0.0, 1.0, 0.0])  # parallel tangents: an S, no meeting point
    h0, h1 = pa.blend_handles(p0, t, p1, t)
    assert h0 == pytest.approx([0, 2 / 3, 0]) and h1 == pytest.approx([2, -2 / 3, 0])


def _joints():
    co = np.array([[0, 5, 6], [0, 5, 2], [0, 3, 0], [0, 0, 0]], dtype=float)
    left = co + [[0, 0.2, 1], [0, 0.3, 0.8], [0, 0.5, 0.3], [0, 0.8, 0.1]]
    right = co + [[0, -0.1, -1], [0, -0.4, -1], [0, -0.5, -0.1], [0, -0.5, 0]]
    return co, left, right


def test_straight_blend_straight_and_idempotent():
    co, left, right = _joints()
    attributes = [
        {"kind": "straight", "point": 0},
        {"kind": "blend", "point": 1},
        {"kind": "straight", "point": 2},
    ]
    left, right = pa.apply(co, left, right, attributes)
    assert right[0] == pytest.approx(co[0] + (co[1] - co[0]) / 3)  # the straight's inside: a third
    assert left[1] == pytest.approx(co[1] - (co[1] - co[0]) / 3)
    k = 4.0 / 3.0 * math.tan(math.pi / 8.0) * 2.0
    assert right[1] == pytest.approx(co[1] + [0, 0, -k])  # the bilge: a quarter circle, r 2
    assert left[2] == pytest.approx(co[2] + [0, k, 0])
    again = pa.apply(co, left, right, attributes)
    assert np.array_equal(again[0], left) and np.array_equal(again[1], right)


def test_a_knuckle_has_vector_handles_where_the_curve_was_smooth_and_a_tangent_keeps_its_lengths():
    co, left, right = _joints()
    left[1], right[1] = co[1] + [0, 0.4, 1.0], co[1] + [0, -0.2, -0.5]  # smooth through point 1
    new_left, new_right = pa.apply(co, left, right, [{"kind": "knuckle", "point": 1}])
    assert new_left[1] == pytest.approx(co[1] + (co[0] - co[1]) / 3)
    assert new_right[1] == pytest.approx(co[1] + (co[2] - co[1]) / 3)
    assert np.array_equal(new_left[[0, 2, 3]], left[[0, 2, 3]]), "the others keep their handles"
    # A corner already (by 0.6°, a fitted chine): its handles stay.
    co, left, right = _joints()
    kept = pa.apply(co, left, right, [{"kind": "knuckle", "point": 1}])
    assert np.array_equal(kept[0], left) and np.array_equal(kept[1], right)
    new_left, new_right = pa.apply(co, left, right, [{"kind": "tangent", "point": 2, "direction": [0, 2, 0]}])
    # Oriented the way the curve runs (towards −y here), lengths kept.
    assert new_right[2] == pytest.approx(co[2] + [0, -np.linalg.norm(right[2] - co[2]), 0])
    assert new_left[2] == pytest.approx(co[2] + [0, np.linalg.norm(left[2] - co[2]), 0])


@pytest.mark.parametrize(
    "attributes, message",
    [
        (
            [{"kind": "knuckle", "point": 1}, {"kind": "tangent", "point": 1, "direction": [0, 0, 1]}],
            "knuckle and has a tangent",
        ),
        (
            [{"kind": "straight", "point": 0}, {"kind": "tangent", "point": 1, "direction": [0, 0, 1]}],
            "tangent and ends a straight",
        ),
        ([{"kind": "blend", "point": 1}, {"kind": "knuckle", "point": 2}], "knuckle and ends a blend"),
        ([{"kind": "blend", "point": 0}, {"kind": "blend", "point": 1}], "point 1 ends two blends"),
        ([{"kind": "straight", "point": 3}], "last point is 3"),
        ([{"kind": "knuckle", "point": -1}], "points 0..3"),
        ([{"kind": "tangent", "point": 1, "direction": [0, 0, 0]}], "no direction"),
        ([{"kind": "fillet", "point": 1}], "unknown point attribute"),
    ],
)
def test_contradictions_are_named(attributes, message):
    co, left, right = _joints()
    with pytest.raises(pa.AttributeConflict, match=message):
        pa.apply(co, left, right, attributes)


def test_the_tangent_into_a_plane_loses_its_normal_part():
    normal = np.array([0.0, 0.0, 1.0])
    assert pa.tangent_in_plane(np.array([0.0, 0.5, 0.2]), normal) == pytest.approx([0, 1, 0])
    assert pa.tangent_in_plane(np.array([0.0, 0.0, -3.0]), normal) is None
