"""The section file's point thinning (``boundary_samples.thinned``), without Blender."""

import numpy as np
from batten.boundary_samples import thinned


def line(xs):
    return np.array([[x, 0.0, 0.0] for x in xs])


def test_points_closer_than_the_gap_are_dropped_and_the_ends_kept():
    pts = line([0.0, 0.001, 0.002, 0.006, 0.0065, 0.013, 0.0131])
    out, _ = thinned(pts, [], 0.005)
    # 0.001 and 0.002 crowd 0; 0.0065 crowds 0.006; the end 0.0131 displaces 0.013.
    assert out[:, 0].tolist() == [0.0, 0.006, 0.0131]


def test_corners_are_kept_and_renumbered():
    pts = line([0.0, 0.004, 0.005, 0.0052, 0.02, 0.021])
    out, corners = thinned(pts, [3], 0.005)
    assert out[:, 0].tolist() == [0.0, 0.0052, 0.021]
    assert corners == [1] and out[corners[0], 0] == 0.0052


def test_spaced_points_are_untouched():
    pts = line(np.linspace(0.0, 1.0, 11))
    out, corners = thinned(pts, [5], 0.005)
    assert np.array_equal(out, pts) and corners == [5]
