"""The points a curve is faired through."""

import numpy as np
from batten.fit_data import FAIR_MIN_SAMPLES, FAIR_SAMPLES_PER_SPAN, fit_data
from batten_native import Curve


def test_a_polyline_is_its_own_data():
    pts = np.array([[0.0, 0, 0], [1, 0.2, 0], [2, 0.1, 0], [3, 0, 0]])
    points, corners = fit_data(Curve.from_poly("p", pts))
    assert np.array_equal(points, pts) and corners == []


def test_a_drawn_curve_is_sampled_with_its_ends_and_corners_exact():
    # Two Bezier pieces meeting at a corner (handles not aligned) at (1, 1, 0).
    co = np.array([[0.0, 0, 0], [1, 1, 0], [2, 0, 0]])
    left = np.array([[-0.3, 0, 0], [0.7, 0.7, 0], [1.7, 0.3, 0]])
    right = np.array([[0.3, 0.3, 0], [1.3, 0.7, 0], [2.3, 0, 0]])
    curve = Curve.from_bezier("b", co, left, right)
    points, corners = fit_data(curve)
    assert len(curve.corners()) == 1
    assert len(corners) == 1 and np.allclose(points[corners[0]], [1, 1, 0], atol=1e-12)
    assert np.allclose(points[0], co[0], atol=1e-12) and np.allclose(points[-1], co[-1], atol=1e-12)
    # Two knot spans: fewer samples than the minimum, so the minimum, split by parameter.
    assert 2 * FAIR_SAMPLES_PER_SPAN < FAIR_MIN_SAMPLES
    assert len(points) == FAIR_MIN_SAMPLES + 1
    assert corners[0] == FAIR_MIN_SAMPLES // 2, "each piece gets its share of the samples"
    # Samples are even in parameter on each piece: their parameters along the curve increase.
    t = np.array([curve.nearest(p)[0] for p in points])
    assert np.all(np.diff(t) > 0)
