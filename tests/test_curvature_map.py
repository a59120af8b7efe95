"""The curvature colour map (``api.surface_curvature``, ``api.show_curvature``,
``api.clear_curvature`` and their operators): figures against the analytic Wigley hull, the
attributes and colours written on the surface mesh, the map following rebuilds and live drags,
and the bad requests."""

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import curvature_map, hull_models
from batten.operators import BATTEN_OT_clear_curvature, BATTEN_OT_show_curvature
from helpers import move_point
from operator_runs import execute

L, B, T = 100.0, 10.0, 6.25


@pytest.fixture
def wigley(examples_dir):
    hull_models.forget()
    coll = api.load_network(examples_dir / "wigley_lines.json")
    yield coll
    hull_models.forget()


def wigley_mean(x, z):
    """Mean curvature (positive: convex seen from outside) of y = B/2 (1 − ξ²)(1 − w²)."""
    xi, w = 2.0 * x / L, (T - z) / T
    a, b = 1.0 - xi * xi, 1.0 - w * w
    fx, fz = 0.5 * B * (-4.0 * xi / L) * b, 0.5 * B * a * (2.0 * w / T)
    fxx, fzz = 0.5 * B * (-8.0 / L**2) * b, 0.5 * B * a * (-2.0 / T**2)
    fxz = 0.5 * B * (-4.0 * xi / L) * (2.0 * w / T)
    g = 1.0 + fx * fx + fz * fz
    return -((1 + fz * fz) * fxx - 2 * fx * fz * fxz + (1 + fx * fx) * fzz) / (2 * g**1.5)


def _attribute(mesh, name, field="value", width=1):
    data = mesh.attributes[name].data
    out = np.empty(len(data) * width, dtype=np.float32)
    data.foreach_get(field, out)
    return out.reshape(-1, width) if width > 1 else out


def test_the_wigley_hulls_mean_curvature_is_the_analytic_one_at_its_vertices(wigley):
    api.build(wigley)
    c = api.surface_curvature(wigley)
    p = c["positions"]
    inside = (p[:, 2] > 0.3) & (p[:, 2] < T - 0.3) & (np.abs(p[:, 0]) < 0.4 * L) & (p[:, 1] > 0)
    assert inside.sum() > 500
    assert c["defined"][inside].all()
    want = wigley_mean(p[inside, 0], p[inside, 2])
    err = np.abs(c["mean"][inside] - want).max()
    # The core's test measures 1.6 % of the largest H (the patches against the Wigley surface).
    assert err < 0.025 * np.abs(want).max(), err
    assert (c["mean"][inside] > 0).all(), "the Wigley hull is convex seen from outside"


def test_show_curvature_writes_both_figures_and_a_diverging_colour(wigley):
    result = api.build(wigley)
    c = api.surface_curvature(wigley)
    info = api.show_curvature(wigley, kind="gaussian")
    mesh = result.object.data
    assert mesh.color_attributes.active_color.name == curvature_map.COLOUR_ATTRIBUTE
    k = _attribute(mesh, curvature_map.GAUSSIAN_ATTRIBUTE)
    np.testing.assert_allclose(k, c["gaussian"].astype(np.float32))
    np.testing.assert_allclose(_attribute(mesh, curvature_map.MEAN_ATTRIBUTE), c["mean"].astype(np.float32))
    on = np.abs(c["gaussian"][c["defined"]])
    assert info["scale"] == pytest.approx(np.quantile(on, curvature_map.SCALE_QUANTILE))
    assert info["min"] < 0 < info["max"], "the Wigley hull has saddles at its ends and domes amidships"
    rgba = _attribute(mesh, curvature_map.COLOUR_ATTRIBUTE, "color", 4)
    red, blue = rgba[:, 0] - rgba[:, 2], rgba[:, 2] - rgba[:, 0]
    assert (red[k > 0.5 * info["scale"]] > 0.2).all(), "domes are red"
    assert (blue[k < -0.5 * info["scale"]] > 0.2).all(), "saddles are blue"
    flat = np.abs(k) < 1e-3 * info["scale"]
    assert flat.any() and (np.abs(red[flat]) < 0.01).all(), "flat is white (wall-sided topsides)"
    # A fixed scale saturates: everything beyond it is full colour.
    info = api.show_curvature(wigley, kind="mean", scale=1e-6)
    rgba = _attribute(mesh, curvature_map.COLOUR_ATTRIBUTE, "color", 4)
    full = curvature_map.colours(np.array([1.0]), np.array([True]), 1e-6)[0]
    h = _attribute(mesh, curvature_map.MEAN_ATTRIBUTE)
    np.testing.assert_allclose(rgba[h > 1e-5], np.broadcast_to(full, rgba[h > 1e-5].shape), atol=1e-6)
    assert info == {**info, "kind": "mean", "scale": 1e-6}


def test_the_map_follows_rebuilds_and_settled_drags_until_cleared(wigley):
    first = api.build(wigley, live=True)
    api.show_curvature(wigley, kind="mean")
    before = _attribute(first.object.data, curvature_map.MEAN_ATTRIBUTE).copy()
    rebuilt = api.build(wigley, resolution=12)
    mapped = _attribute(rebuilt.object.data, curvature_map.MEAN_ATTRIBUTE)
    assert len(mapped) == len(rebuilt.object.data.vertices), "a rebuild at another resolution is mapped"
    api.build(wigley, live=True)
    station = next(o for o in wigley.objects if o.name.startswith("station"))
    move_point(station, len(station.data.splines[0].points) // 2, 4e-5)
    moved = api.build(wigley, live=True)
    assert not moved.report["measured"]
    api.settle(wigley)
    after = _attribute(moved.object.data, curvature_map.MEAN_ATTRIBUTE)
    assert len(after) == len(before) and not np.array_equal(after, before), "mapped again once settled"
    fresh = api.surface_curvature(wigley)["mean"].astype(np.float32)
    np.testing.assert_array_equal(after, fresh)
    assert api.clear_curvature(wigley)
    assert curvature_map.MEAN_ATTRIBUTE not in moved.object.data.attributes
    again = api.build(wigley)
    assert curvature_map.COLOUR_ATTRIBUTE not in again.object.data.attributes, "cleared for good"
    assert not api.clear_curvature(wigley)


def test_bad_requests_are_refused_and_change_nothing(wigley):
    with pytest.raises(api.NoSurfaceError, match="build it first"):
        api.surface_curvature(wigley)
    result = api.build(wigley)
    with pytest.raises(api.InvalidArgumentError, match="kind"):
        api.show_curvature(wigley, kind="principal")
    for scale in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(api.InvalidArgumentError, match="scale"):
            api.show_curvature(wigley, scale=scale)
    assert curvature_map.COLOUR_ATTRIBUTE not in result.object.data.attributes
    assert api.CURVATURE_MAP_PROPERTY not in result.object


def test_the_operators_show_and_clear_the_map(wigley):
    settings = bpy.context.scene.batten
    settings.source = wigley
    result = api.build(wigley)
    settings.curvature_kind = "mean"
    status, reports = execute(BATTEN_OT_show_curvature, bpy.context)
    assert status == {"FINISHED"}, reports
    assert "Mean curvature" in reports[-1][1] and "1/m" in reports[-1][1]
    assert result.object[api.CURVATURE_MAP_PROPERTY] == "mean"
    settings.curvature_scale = 0.05
    execute(BATTEN_OT_show_curvature, bpy.context)
    assert result.object[api.CURVATURE_SCALE_PROPERTY] == pytest.approx(0.05)
    status, _ = execute(BATTEN_OT_clear_curvature, bpy.context)
    assert status == {"FINISHED"}
    assert curvature_map.COLOUR_ATTRIBUTE not in result.object.data.attributes
    api.clear_curvature(wigley)
    bpy.data.objects.remove(result.object)
    status, reports = execute(BATTEN_OT_show_curvature, bpy.context)
    assert status == {"CANCELLED"} and "build it first" in reports[-1][1]
