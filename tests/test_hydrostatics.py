"""batten.api hydrostatics on the patch surface: the Wigley hull drawn as a lines plan against
its analytic figures, the sectional area curve, curves of form, floating at a displacement, the
kept surface following edits, and bad input."""

from __future__ import annotations

import math

import batten.api as api
import numpy as np
import pytest
from batten_native import HydrostaticsError, InvalidArgumentError

L, B, T = 100.0, 10.0, 6.25

KEYS = {
    "volume", "displacement", "density", "draft_ap", "draft_fp", "draft_mid", "draft_lcf", "trim", "heel",
    "x_ap", "x_fp", "lpp", "lwl", "bwl", "los", "wetted_area", "waterplane_area", "midship_area",
    "max_section_area", "max_section_x", "cb", "cp", "cm", "cwp", "cvp", "lcb", "tcb", "vcb", "lcf", "it",
    "il", "bmt", "bml", "kmt", "kml", "tpc", "mtc", "transom_area", "entrance_half_angle",
}  # fmt: skip


@pytest.fixture
def wigley(addon):
    return api.load_example("wigley_lines.json")


def test_wigley_at_the_design_draft_is_the_analytic_hull(wigley):
    h = api.hydrostatics(wigley, T)
    assert set(h) == KEYS
    volume = 4 / 9 * L * B * T
    exact = {
        "volume": volume,
        "displacement": 1.025 * volume,
        "waterplane_area": 2 / 3 * L * B,
        "vcb": 5 * T / 8,
        "bmt": 3 * B**2 / (35 * T),
        "bml": 3 * L**2 / (40 * T),
        "cm": 2 / 3,
        "cp": 2 / 3,
        "cwp": 2 / 3,
        "cb": 4 / 9,
        "lwl": L,
        "bwl": B,
        "lpp": L,
        "midship_area": 2 / 3 * B * T,
    }
    for key, want in exact.items():
        assert h[key] == pytest.approx(want, rel=5e-4), key
    assert abs(h["lcb"]) < 5e-4 * L and abs(h["lcf"]) < 5e-4 * L
    assert h["x_ap"] == pytest.approx(-L / 2) and h["x_fp"] == pytest.approx(L / 2)
    assert h["entrance_half_angle"] == pytest.approx(math.degrees(math.atan(2 * B / L)), rel=1e-3)
    assert all(math.isfinite(v) for v in h.values())


def test_sectional_areas_follow_the_parabola(wigley):
    xs, areas = api.sectional_areas(wigley, T, 21)
    np.testing.assert_allclose(xs, np.linspace(-L / 2, L / 2, 21))
    exact = 2 / 3 * B * T * (1 - (2 * xs / L) ** 2)
    np.testing.assert_allclose(areas, exact, rtol=5e-4, atol=1e-3)
    xs2, areas2 = api.sectional_areas(wigley, T, [0.0, 10.0])
    assert areas2[0] == pytest.approx(2 / 3 * B * T, rel=5e-4)


def test_curves_of_form_grow_with_draft(wigley):
    rows = api.curves_of_form(wigley, [2.0, 4.0, 6.0])
    assert [r["draft_mid"] for r in rows] == [2.0, 4.0, 6.0]
    volumes = [r["volume"] for r in rows]
    assert volumes == sorted(volumes) and volumes[0] > 0
    # One pair of perpendiculars for the whole table.
    assert len({(r["x_ap"], r["x_fp"]) for r in rows}) == 1


def test_float_to_finds_the_draft_of_a_displacement(wigley):
    want = api.hydrostatics(wigley, 0.5 * T)
    h = api.float_to(wigley, want["displacement"], 0.0)
    assert h["draft_mid"] == pytest.approx(0.5 * T, rel=1e-7)
    assert abs(h["trim"]) < 1e-6
    aft = api.float_to(wigley, want["displacement"], -1.0)
    assert aft["trim"] > 0 and aft["lcb"] == pytest.approx(-1.0, abs=1e-6)


def test_the_kept_surface_follows_an_edit(wigley):
    before = api.hydrostatics(wigley, T)["volume"]
    # Widen the hull by 10 %: every curve's points (and handles) scaled in y.
    for obj in wigley.objects:
        for spline in obj.data.splines:
            for p in spline.points:
                p.co.y *= 1.1
            for p in spline.bezier_points:
                for v in (p.co, p.handle_left, p.handle_right):
                    v.y *= 1.1
    after = api.hydrostatics(wigley, T)["volume"]
    # (not exactly 1.1: the ribbons scale with side lengths, which a stretch in y changes unevenly)
    assert after == pytest.approx(1.1 * before, rel=1e-5)


def test_bad_drafts_and_numbers_are_refused(wigley):
    with pytest.raises(HydrostaticsError, match="below the keel"):
        api.hydrostatics(wigley, -1.0)
    with pytest.raises(HydrostaticsError, match="open top"):
        api.hydrostatics(wigley, 20.0)
    with pytest.raises(InvalidArgumentError, match="density"):
        api.hydrostatics(wigley, T, density=0.0)
    with pytest.raises(InvalidArgumentError, match="finite"):
        api.hydrostatics(wigley, float("nan"))
    with pytest.raises(InvalidArgumentError, match="heel"):
        api.hydrostatics(wigley, T, heel=95.0)
    with pytest.raises(InvalidArgumentError, match="more than the hull holds"):
        api.float_to(wigley, 1e9, 0.0)
    with pytest.raises(InvalidArgumentError, match="stations"):
        api.sectional_areas(wigley, T, 1)


def test_the_surface_mesh_gives_the_patches_figures(wigley):
    """The mesh batten writes, as a Blender mesh object (the port half): the same figures as
    the patches to within its chords' error."""
    result = api.build(wigley, resolution=32, mirror=False)
    exact = api.hydrostatics(wigley, T)
    mesh = api.hydrostatics(result.object, T, lpp=L, fp=L / 2)
    for key in ("volume", "waterplane_area", "vcb", "bmt", "wetted_area"):
        assert mesh[key] == pytest.approx(exact[key], rel=2e-3), key
    xs, areas = api.sectional_areas(result.object, T, 5, lpp=L, fp=L / 2)
    np.testing.assert_allclose(areas, 2 / 3 * B * T * (1 - (2 * xs / L) ** 2), rtol=3e-3, atol=1e-2)
