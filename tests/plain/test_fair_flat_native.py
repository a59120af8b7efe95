"""``fair_points(flat_planes=…)`` through the binding: a section's flat of bottom comes back as a
straight piece in the plane, reported in ``flats`` and not as a corner; a waterline's run
along a flat of side comes back straight with both its ends reported; ``flat_noise`` lets the
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
    curve, report = bn.fair_points("st", _section(), tolerance=5e-3, flat_planes=[((0, 0, 2.0), 0.0, 1e-3)])
    assert report["corners"] == [] and report["corner_parameters"] == []
    [flat] = report["flats"]
    assert flat["point"][2] == 0.0 and 4.0 <= flat["point"][1] < 4.1
    ts = np.linspace(curve.domain[0], flat["parameter"], 200)
    assert np.abs(np.asarray(curve.evaluate(ts))[:, 2]).max() < 1e-12
    _, plain = bn.fair_points("st", _section(), tolerance=5e-3)
    assert plain["flats"] == []


def test_noise_lets_the_flat_go_over_points_that_straddle_the_plane():
    pts = _section()
    pts[1:80:2, 2] = -0.002  # every other point of the flat 2 mm below the plane
    plane = ((0, 0, 1), 0.0, 1e-3)
    _, strict = bn.fair_points("st", pts, tolerance=5e-3, flat_planes=[plane])
    assert strict["flats"] == []
    curve, report = bn.fair_points("st", pts, tolerance=5e-3, flat_planes=[plane], flat_noise=5e-3)
    [flat] = report["flats"]
    assert flat["point"][2] == 0.0 and 4.0 <= flat["point"][1] < 4.1
    ts = np.linspace(curve.domain[0], flat["parameter"], 200)
    assert np.abs(np.asarray(curve.evaluate(ts))[:, 2]).max() < 1e-12


@pytest.mark.parametrize("noise", [math.nan, -1e-3, math.inf])
def test_a_bad_noise_is_refused_naming_the_curve(noise):
    with pytest.raises(bn.InvalidArgumentError, match="curve 'st': flat_noise"):
        bn.fair_points("st", _section(), flat_planes=[((0, 0, 1), 0.0, 1e-3)], flat_noise=noise)


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
    with pytest.raises(bn.InvalidArgumentError, match="curve 'st': a flat plane"):
        bn.fair_points("st", _section(), flat_planes=[plane])


def test_a_waterline_runs_straight_along_the_flat_of_side_and_leaves_it_at_both_ends():
    # Half-breadth 6 m through the parallel middle body (x 20..40), falling off as a parabola
    # to 1 m at the ends; points every 0.5 m.
    x = np.arange(0.0, 60.25, 0.5)
    y = 6.0 - 0.0125 * np.maximum(np.abs(x - 30.0) - 10.0, 0.0) ** 2
    pts = np.column_stack([x, y, np.full_like(x, 5.0)])
    curve, report = bn.fair_points(
        "wl", pts, tolerance=5e-3, flat_planes=[((0, 1, 0), 6.0, 1e-3)], flat_noise=5e-3
    )
    ends = report["flats"]
    assert [f["plane"] for f in ends] == [0, 0] and report["corners"] == []
    # The run is the points within 1 mm of the side: x 20..40 (19.5 and 40.5 are 3.1 mm off).
    assert [f["index"] for f in ends] == [40, 80]
    assert [f["point"] for f in ends] == [[20.0, 6.0, 5.0], [40.0, 6.0, 5.0]]
    ts = np.linspace(ends[0]["parameter"], ends[1]["parameter"], 400)
    assert np.abs(np.asarray(curve.evaluate(ts))[:, 1] - 6.0).max() < 1e-12, "straight in the plane"
    # One spline fitted as a whole rounds the flat's ends off the side (2.5 mm).
    plain, _ = bn.fair_points("wl", pts, tolerance=5e-3)
    ts = np.linspace(*plain.domain, 2000)
    side = np.asarray(plain.evaluate(ts))
    inside = (side[:, 0] > 20.5) & (side[:, 0] < 39.5)
    assert np.abs(side[inside, 1] - 6.0).max() > 1e-3
