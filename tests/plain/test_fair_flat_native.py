"""``fair_points(flat_plane=…)`` through the binding: a section's flat of bottom comes back as a
straight piece in the plane, reported as ``flat`` and not as a corner; ``flat_noise`` lets the
run go on over points that stray further; a bad plane is an InvalidArgumentError naming the
curve, and no curve is made."""

import math

import batten_native as bn
import numpy as np
import pytest


def _section(w=4.0, r=2.0, step=0.05):
    flat = [[10.0, y, 0.0] for y in np.arange(0.0, w, step)]
    arc = [
        [10.0, w + r * math.sin(a), r * (1 - math.cos(a))]
        for a in np.linspace(0, math.pi / 2, 63, endpoint=False)
    ]
    side = [[10.0, w + r, z] for z in np.linspace(r, 8.0, 121)]
    return np.array(flat + arc + side)


def test_the_flat_comes_back_straight_and_is_no_corner():
    curve, report = bn.fair_points("st", _section(), tolerance=5e-3, flat_plane=((0, 0, 2.0), 0.0, 1e-3))
    assert report["corners"] == [] and report["corner_parameters"] == []
    flat = report["flat"]
    assert flat["point"][2] == 0.0 and 4.0 <= flat["point"][1] < 4.1
    ts = np.linspace(curve.domain[0], flat["parameter"], 200)
    assert np.abs(np.asarray(curve.evaluate(ts))[:, 2]).max() < 1e-12
    _, plain = bn.fair_points("st", _section(), tolerance=5e-3)
    assert plain["flat"] is None


def test_noise_lets_the_flat_go_over_points_that_straddle_the_plane():
    pts = _section()
    pts[1:80:2, 2] = -0.002  # every other point of the flat 2 mm below the plane
    plane = ((0, 0, 1), 0.0, 1e-3)
    _, strict = bn.fair_points("st", pts, tolerance=5e-3, flat_plane=plane)
    assert strict["flat"] is None
    curve, report = bn.fair_points("st", pts, tolerance=5e-3, flat_plane=plane, flat_noise=5e-3)
    flat = report["flat"]
    assert flat["point"][2] == 0.0 and 4.0 <= flat["point"][1] < 4.1
    ts = np.linspace(curve.domain[0], flat["parameter"], 200)
    assert np.abs(np.asarray(curve.evaluate(ts))[:, 2]).max() < 1e-12


@pytest.mark.parametrize("noise", [math.nan, -1e-3, math.inf])
def test_a_bad_noise_is_refused_naming_the_curve(noise):
    with pytest.raises(bn.InvalidArgumentError, match="curve 'st': flat_noise"):
        bn.fair_points("st", _section(), flat_plane=((0, 0, 1), 0.0, 1e-3), flat_noise=noise)


@pytest.mark.parametrize(
    "plane",
    [
        ((0, 0, 0), 0.0, 1e-3),
        ((0, 0, 1), math.nan, 1e-3),
        ((0, 0, 1), 0.0, -1.0),
        ((0, math.inf, 1), 0.0, 1e-3),
    ],
)
def test_a_bad_plane_is_refused_naming_the_curve(plane):
    with pytest.raises(bn.InvalidArgumentError, match="curve 'st': flat_plane"):
        bn.fair_points("st", _section(), flat_plane=plane)
