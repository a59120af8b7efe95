"""The section file's point thinning (``boundary_samples.thinned``) and end trimming
(``without_end_stretches_along``), without Blender."""

import numpy as np
import pytest
from batten.boundary_samples import thinned, without_end_stretches_along


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


class Segment:
    """A straight boundary curve with the ``nearest`` of the binding's curves."""

    def __init__(self, a, b):
        self.a, self.b = np.asarray(a, float), np.asarray(b, float)

    def nearest(self, p):
        d = self.b - self.a
        t = float(np.clip(np.dot(np.asarray(p) - self.a, d) / np.dot(d, d), 0.0, 1.0))
        q = self.a + t * d
        return q.tolist(), float(np.linalg.norm(np.asarray(p) - q))


#: A flat end's edge rising 15 mm over 0.1 m from its lower corner at the origin.
EDGE = Segment([0.0, 0.0, 0.0], [0.1, 0.0, 0.015])
WITHIN, MEET = 0.01, 1e-4


def grazing(z=0.009, far=1.0):
    """A waterline at height ``z`` from the profile (x = 0) across the end to the edge (at
    x = z / 0.15) and on, 5 mm apart."""
    xs = sorted({*np.arange(0.0, far, 0.005).round(6), round(z / 0.15, 9)})
    return np.array([[x, 0.0, z] for x in xs])


def test_an_end_stretch_beside_a_boundary_curve_is_cut_back_to_where_it_meets_it():
    pts = grazing()
    out, corners = without_end_stretches_along(pts, [3, 40], [EDGE], WITHIN, MEET)
    # The waterline now starts on the edge, at x 0.06; the corner at index 3 was cut off.
    assert out[0].tolist() == pytest.approx([0.06, 0.0, 0.009])
    assert len(out) == len(pts) - 12 and np.array_equal(out[-1], pts[-1])
    assert corners == [28] and np.array_equal(out[28], pts[40])


def test_the_far_end_is_cut_back_the_same_way():
    pts = grazing()[::-1]
    out, _ = without_end_stretches_along(pts, [], [EDGE], WITHIN, MEET)
    assert out[-1].tolist() == pytest.approx([0.06, 0.0, 0.009]) and np.array_equal(out[0], pts[0])


@pytest.mark.parametrize(
    "pts",
    [
        grazing(z=0.012),  # 12 mm above the corner: farther than `within` at its end
        grazing()[12:],  # starts on the edge
        np.array([[x, 0.0, 0.005] for x in np.arange(-0.5, 0.0, 0.005)]),  # 5 mm off, never meets it
    ],
)
def test_sections_not_beside_the_curve_up_to_a_meeting_are_untouched(pts):
    out, corners = without_end_stretches_along(pts, [2], [EDGE], WITHIN, MEET)
    assert np.array_equal(out, pts) and corners == [2]
