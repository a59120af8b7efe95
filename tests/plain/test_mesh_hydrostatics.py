"""batten_native.mesh_hydrostatics and mesh_sectional_areas: a box barge exact, bad arrays and
holes as errors, and a convex hull's wet part against trimesh (qhull) on identical input."""

from __future__ import annotations

import math

import batten_native as bn
import numpy as np
import pytest
import trimesh

L, B, D, T = 20.0, 6.0, 4.0, 1.3

# Every figure of the core's Hydrostatics, by its serde name.
FIELDS = [
    "volume", "displacement", "density", "draft_ap", "draft_fp", "draft_mid", "draft_lcf",
    "trim", "heel", "x_ap", "x_fp", "lpp", "lwl", "bwl", "los", "wetted_area",
    "waterplane_area", "midship_area", "max_section_area", "max_section_x", "cb", "cp", "cm",
    "cwp", "cvp", "lcb", "tcb", "vcb", "lcf", "it", "il", "bmt", "bml", "kmt", "kml", "tpc",
    "mtc", "transom_area", "entrance_half_angle",
]  # fmt: skip


def box(length=L, breadth=B, depth=D, *, open_top=False, half=False):
    """The box 0 <= x <= length, |y| <= breadth/2, 0 <= z <= depth, outward triangles; without
    its deck when ``open_top``; only its port half (y >= 0, open along y = 0) when ``half``."""
    width = breadth / 2 if half else breadth
    b = trimesh.creation.box(extents=(length, width, depth))
    v = np.asarray(b.vertices) + (length / 2, width / 2 if half else 0.0, depth / 2)
    f = np.asarray(b.faces)
    corners = v[f]
    drop = np.zeros(len(f), dtype=bool)
    if open_top:
        drop |= np.all(np.isclose(corners[:, :, 2], depth), axis=1)
    if half:
        drop |= np.all(np.isclose(corners[:, :, 1], 0.0), axis=1)
    return v, f[~drop]


def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(abs(b), 1.0)


def test_a_box_barge_is_exact():
    v, f = box()
    h = bn.mesh_hydrostatics(v, f, T, lpp=L, fp=L)
    assert list(h) == FIELDS
    assert all(isinstance(x, float) for x in h.values())
    assert close(h["volume"], L * B * T)
    assert close(h["displacement"], 1.025 * L * B * T)
    assert close(h["vcb"], T / 2)
    assert close(h["bmt"], B * B / (12 * T))
    assert close(h["bml"], L * L / (12 * T))
    assert close(h["waterplane_area"], L * B)
    assert close(h["lcf"], L / 2)
    assert close(h["wetted_area"], L * B + 2 * L * T + 2 * B * T)
    assert close(h["cb"], 1.0)
    # The perpendiculars by default: the waterline's ends.
    d = bn.mesh_hydrostatics(v, f, T, density=1.0)
    assert close(d["x_fp"], L) and close(d["x_ap"], 0.0, 1e-12)
    assert close(d["displacement"], L * B * T)
    xs, areas = bn.mesh_sectional_areas(v, f, T, 5, trim=0.4, lpp=L, fp=L)
    assert np.allclose(xs, [0, 5, 10, 15, 20], rtol=0, atol=1e-12)
    assert np.allclose(areas, B * (T + 0.4 * (0.5 - xs / L)), rtol=1e-12, atol=0)


def test_a_half_box_heeled_is_the_whole_box():
    v, f = box()
    port_v, port_f = box(open_top=True, half=True)
    for heel in (0.0, 5.0):
        whole = bn.mesh_hydrostatics(v, f, T, heel=heel, lpp=L, fp=L)
        half = bn.mesh_hydrostatics(port_v, port_f, T, heel=heel, lpp=L, fp=L)
        for key in ("volume", "lcb", "vcb", "bmt", "waterplane_area", "wetted_area"):
            assert close(half[key], whole[key], 1e-11), (key, heel, half[key], whole[key])
        assert abs(half["tcb"] - whole["tcb"]) < 1e-11 * B
    t = math.tan(math.radians(5.0))
    assert close(whole["tcb"], -t * B * B / (12 * T), 1e-11)


@pytest.mark.parametrize(
    ("positions", "triangles", "needle"),
    [
        (np.zeros((4, 2)), [[0, 1, 2]], "3 columns"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1]], "3 columns"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.array([[0.0, 1.0, 2.0]]), "integers"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, -1]], "triangle 0"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 7]], "vertex 7"),
        ([[0, 0, 0], [1, 0, math.nan], [0, 1, 0]], [[0, 1, 2]], "vertex 1"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.zeros((0, 3), dtype=int), "no triangles"),
        ("not an array", [[0, 1, 2]], "positions"),
    ],
)
def test_bad_arrays_are_invalid_arguments(positions, triangles, needle):
    with pytest.raises(bn.InvalidArgumentError, match=needle):
        bn.mesh_hydrostatics(positions, triangles, 0.5)


def test_bad_options_are_invalid_arguments():
    v, f = box()
    with pytest.raises(bn.InvalidArgumentError, match="lpp"):
        bn.mesh_hydrostatics(v, f, T, fp=L)
    with pytest.raises(bn.InvalidArgumentError, match="density"):
        bn.mesh_hydrostatics(v, f, T, density=0.0)
    with pytest.raises(bn.InvalidArgumentError, match="stations"):
        bn.mesh_sectional_areas(v, f, T, 1)


def test_holes_and_drafts_out_of_range_are_hydrostatics_errors():
    v, f = box()
    bottom = np.all(np.isclose(v[f][:, :, 2], 0.0), axis=1)
    holed = np.delete(f, np.flatnonzero(bottom)[0], axis=0)
    with pytest.raises(bn.HydrostaticsError, match="hole below the waterline"):
        bn.mesh_hydrostatics(v, holed, T, lpp=L, fp=L)
    with pytest.raises(bn.HydrostaticsError, match="below the keel"):
        bn.mesh_hydrostatics(v, f, -1.0, lpp=L, fp=L)
    ov, of = box(open_top=True)
    with pytest.raises(bn.HydrostaticsError, match="draft 5"):
        bn.mesh_hydrostatics(ov, of, 5.0, lpp=L, fp=L)


def wet_hull(mesh: trimesh.Trimesh, zeta: np.ndarray) -> trimesh.Trimesh:
    """The part of a convex mesh where ``zeta <= 0`` (zeta linear, per vertex), as the convex
    hull (qhull) of its wet vertices and the crossings of its edges with ``zeta = 0``."""
    v = np.asarray(mesh.vertices)
    e = np.asarray(mesh.edges_unique)
    za, zb = zeta[e[:, 0]], zeta[e[:, 1]]
    cut = (za <= 0) != (zb <= 0)
    t = (za[cut] / (za[cut] - zb[cut]))[:, None]
    crossings = v[e[cut, 0]] + t * (v[e[cut, 1]] - v[e[cut, 0]])
    return trimesh.convex.convex_hull(np.vstack([v[zeta <= 0], crossings]))


@pytest.mark.parametrize(("draft", "heel"), [(1.1, 0.0), (0.8, 12.0)])
def test_a_convex_hull_agrees_with_trimesh(draft, heel):
    # An ellipsoid of semi-axes 5, 2, 1.5 about (5, 0, 1.5), 5,120 triangles.
    m = trimesh.creation.icosphere(subdivisions=4)
    m.apply_scale((5.0, 2.0, 1.5))
    m.apply_translation((5.0, 0.0, 1.5))
    v, f = np.asarray(m.vertices), np.asarray(m.faces)
    h = bn.mesh_hydrostatics(v, f, draft, heel=heel, lpp=10.0, fp=10.0)
    # The water surface z = T - y tan(heel) (upright in trim, about x_mid = 5).
    zeta = v[:, 2] - draft + v[:, 1] * math.tan(math.radians(heel))
    wet = wet_hull(m, zeta)
    assert close(h["volume"], wet.volume, 1e-9), (h["volume"], wet.volume)
    cx, cy, cz = wet.center_mass
    assert close(h["lcb"], cx, 1e-9)
    assert abs(h["tcb"] - cy) < 1e-9 * 5.0, (h["tcb"], cy)
    assert close(h["vcb"], cz, 1e-9)


def test_a_mesh_hull_built_once_answers_like_the_one_call():
    v, f = box(open_top=True, half=True)
    hull = bn.MeshHull(v, f)
    assert hull.is_half and hull.triangle_count == len(f)
    for draft in (0.7, T):
        assert hull.hydrostatics(draft, lpp=L, fp=L) == bn.mesh_hydrostatics(v, f, draft, lpp=L, fp=L)
        assert close(hull.hydrostatics(draft, lpp=L, fp=L)["volume"], L * B * draft)
    xs, areas = hull.sectional_areas(T, 3, lpp=L, fp=L)
    assert np.allclose(areas, B * T, rtol=1e-12, atol=0)
    with pytest.raises(bn.InvalidArgumentError, match="no triangles"):
        bn.MeshHull(v, np.zeros((0, 3), dtype=np.int64))
