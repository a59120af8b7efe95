"""batten.api calls and options no other test reaches: set_role, build without the mirror,
fair_curve's noise, degree, corner and multi-spline cases, and import_sections on bad files.
Errors are asserted as BattenError (the base class) with what the message must name."""

import json
import math

import batten.api as api
import bpy
import numpy as np
import pytest
from helpers import WIGLEY_HALF_VOLUME, evaluated_volume, new_curve, noisy_arc


def corner_points(n=21):
    """An L: 2 m along x, then 2 m along y, turning 90° at its middle point."""
    s = np.linspace(0.0, 2.0, n)
    leg1 = np.column_stack([s, np.zeros(n), np.zeros(n)])
    leg2 = np.column_stack([np.full(n - 1, 2.0), s[1:], np.zeros(n - 1)])
    return np.vstack([leg1, leg2])


# ---------------------------------------------------------------------------------------
# set_role


def test_set_role_sets_every_curve_and_rejects_an_unknown_role(examples_dir):
    coll = api.load_network(examples_dir / "wigley.json")
    stations = [o for o in coll.objects if o.name.startswith("station")]
    assert stations and all(o.batten.role == "free" for o in stations)
    api.set_role(stations, "knuckle")
    assert all(o.batten.role == "knuckle" for o in stations)
    assert coll.objects["keel"].batten.role == "keel", "other curves keep theirs"
    for role in api.ROLES:
        api.set_role(coll.objects["stem"], role)
        assert coll.objects["stem"].batten.role == role
    before = {o.name: o.batten.role for o in coll.objects}
    with pytest.raises(api.BattenError, match="chine-ish") as err:
        api.set_role(coll, "chine-ish")
    assert all(role in str(err.value) for role in api.ROLES), "the message lists the roles"
    assert {o.name: o.batten.role for o in coll.objects} == before, "nothing changed"


# ---------------------------------------------------------------------------------------
# build(mirror=False)


def test_build_without_mirror_has_one_half_and_its_volume(examples_dir):
    coll = api.load_network(examples_dir / "wigley.json")
    mirrored = api.build(coll, resolution=6)
    assert "batten mirror" in mirrored.object.modifiers
    half = api.build(coll, resolution=6, mirror=False)
    assert half.object == mirrored.object, "rebuilt in place"
    assert not any(m.type == "MIRROR" for m in half.object.modifiers), "the Mirror modifier is gone"
    r = half.report
    assert r["mirror"] is False
    # One half: measured on the mesh (field y·e_y: no flux through the centreplane y = 0 or
    # the deck plane), equal to the report's volume and to the exact half within 0.2 %.
    measured = evaluated_volume(half.object, axis=1, level=0.0)
    assert abs(measured - WIGLEY_HALF_VOLUME) / WIGLEY_HALF_VOLUME < 0.002, measured
    assert r["enclosed_volume_half"] == pytest.approx(measured, rel=1e-5)
    assert r["enclosed_volume"] == pytest.approx(measured, rel=1e-5)
    same = mirrored.report["enclosed_volume_half"]
    assert r["enclosed_volume_half"] == pytest.approx(same, rel=1e-12), "the same half surface"
    pos = np.empty(3 * len(half.object.data.vertices))
    half.object.data.vertices.foreach_get("co", pos)
    assert pos.reshape(-1, 3)[:, 1].min() > -1e-6, "port half only (y ≥ 0)"


# ---------------------------------------------------------------------------------------
# fair_curve options


def test_fair_curve_noise_mode_smooths_to_the_noise_level():
    sigma = 0.01
    pts = noisy_arc(n=150, sigma=sigma, seed=7)
    obj = new_curve("noisy", "POLY", pts)
    # noise overrides tolerance: a tolerance of 1 µm would need ~every point as a control point.
    (report,) = api.fair_curve(obj, tolerance=1e-6, noise=sigma)
    m = len(pts)
    # Dierckx's smoothing condition: sum of squares S ≤ (M + √(2M))·σ² (H-rep paper §4).
    rms_bound = sigma * math.sqrt((m + math.sqrt(2 * m)) / m)
    assert report["rms_deviation"] <= rms_bound * 1.001, report["rms_deviation"]
    assert report["rms_deviation"] > 0.5 * sigma, "smoothed, not interpolated"
    assert report["control_points"] < 15 and report["inflections"] == 0
    (curve,) = api.read_curves(obj)
    dist = [curve.nearest(p.tolist(), 1e-9)[1] for p in noisy_arc(n=50, sigma=0.0)]
    assert max(dist) < 3 * sigma, "close to the noise-free arc"


def test_fair_curve_degree_sets_the_spline_order():
    pts = noisy_arc(n=60, sigma=0.002, seed=7)
    for degree in (2, 5):
        obj = new_curve(f"deg{degree}", "POLY", pts)
        (report,) = api.fair_curve(obj, tolerance=5e-3, degree=degree)
        spline = obj.data.splines[0]
        assert spline.type == "NURBS" and spline.order_u == degree + 1
        (curve,) = api.read_curves(obj)
        assert curve.degree == degree
        assert report["max_deviation"] <= 5e-3
    with pytest.raises(api.BattenError, match="degree"):
        api.fair_curve(new_curve("deg0", "POLY", pts), degree=0)


def test_fair_curve_corner_angle_none_keeps_no_corner():
    sharp = new_curve("sharp", "POLY", corner_points())
    (report,) = api.fair_curve(sharp, tolerance=1e-3)
    assert report["corners"] == [20], "the 90° turn is kept at 45° (the default)"
    (curve,) = api.read_curves(sharp)
    assert len(curve.corners(1.0)) == 1
    smooth = new_curve("smooth", "POLY", corner_points())
    (report,) = api.fair_curve(smooth, tolerance=1e-3, corner_angle_deg=None)
    assert report["corners"] == []
    (curve,) = api.read_curves(smooth)
    assert curve.corners(1.0) == [], "fitted through the turn as one smooth curve"


def test_fair_curve_refits_every_spline_of_an_object():
    obj = new_curve("pair", "POLY", noisy_arc(n=60, sigma=0.003, seed=7))
    second = obj.data.splines.new("POLY")
    pts = noisy_arc(n=40, r=6.0, sigma=0.003, seed=3) + [0.0, 0.0, 2.0]
    second.points.add(len(pts) - 1)
    second.points.foreach_set("co", np.column_stack([pts, np.ones(len(pts))]).astype(np.float32).ravel())
    reports = api.fair_curve(obj, tolerance=0.01)
    assert [r["curve"] for r in reports] == ["pair[0]", "pair[1]"]
    assert len(obj.data.splines) == 2 and all(s.type == "NURBS" for s in obj.data.splines)
    assert all(r["max_deviation"] <= 0.01 for r in reports)
    lower, upper = api.read_curves(obj)
    ends = upper.evaluate(np.array(upper.domain))
    np.testing.assert_allclose(ends, pts[[0, -1]], atol=1e-5, err_msg="the second spline is the second curve")
    assert np.allclose(lower.evaluate(np.array([lower.domain[0]]))[0], [10.0, 0.0, 0.0], atol=1e-5)


# ---------------------------------------------------------------------------------------
# import_sections on bad files


def _bad_files(tmp_path):
    (tmp_path / "broken.json").write_text('{"name": "x", "curves": [')
    one_point = {"name": "one", "curves": [{"name": "dot", "points": [[0, 0, 0]]}]}
    (tmp_path / "single.json").write_text(json.dumps(one_point))
    (tmp_path / "words.csv").write_text("name,x,y,z\nst1,0,0,0\nst1,1,zero,0\n")
    return [
        (tmp_path / "missing.json", "missing.json"),
        (tmp_path / "broken.json", "broken.json"),
        (tmp_path / "single.json", "dot"),
        (tmp_path / "words.csv", "line 3"),
    ]


def test_import_sections_rejects_bad_files_and_creates_nothing(tmp_path):
    for path, named in _bad_files(tmp_path):
        counts = (len(bpy.data.collections), len(bpy.data.objects), len(bpy.data.curves))
        with pytest.raises(api.BattenError, match=named):
            api.import_sections(path)
        assert (len(bpy.data.collections), len(bpy.data.objects), len(bpy.data.curves)) == counts, path.name
