"""Fairing in Blender: fair_curve in place, section import of the real ships, combs, errors."""

import json
import math
import sys
from pathlib import Path

import batten.api as api
import bpy
import numpy as np
import pytest
from batten_native import DEFAULT_SECTION_TOLERANCE, SECTION_CAPTURE_FACTOR, build_surface
from helpers import new_curve, noisy_arc

ROOT = Path(__file__).resolve().parents[1]
HULLS = ROOT.parent / "shared" / "hulls"


def test_fair_curve_refits_a_polyline_in_place_within_tolerance():
    pts = noisy_arc()
    obj = new_curve("Station 9", "POLY", pts)
    mat = bpy.data.materials.new("hull")
    obj.data.materials.append(mat)
    data = obj.data
    (report,) = api.fair_curve(obj, tolerance=0.03)
    assert obj.data is data and obj.data.materials[0] == mat, "same object, data-block, materials"
    spline = obj.data.splines[0]
    assert spline.type == "NURBS" and len(obj.data.splines) == 1
    assert report["max_deviation"] <= 0.03
    assert report["control_points"] < 20, "a fair arc needs few control points"
    assert report["inflections"] == 0
    (curve,) = api.read_curves(obj)
    # End points kept exactly (up to Blender's float32 storage); the faired curve is near the arc.
    ends = curve.evaluate(np.array(curve.domain))
    np.testing.assert_allclose(ends, pts[[0, -1]], atol=1e-5)
    radii = np.linalg.norm(curve.evaluate(np.linspace(*curve.domain, 400))[:, :2], axis=1)
    assert np.abs(radii - 10.0).max() < 3 * 0.01 + 0.03


def test_fair_curve_keeps_a_chine_sharp():
    # A hard-chine section: bottom rising to the chine, then the topside; with a little noise.
    bottom = np.column_stack([np.zeros(30), np.linspace(0, 4, 30), np.linspace(0, 0.8, 30)])
    side = np.column_stack([np.zeros(30), np.linspace(4, 4.6, 30), np.linspace(0.8, 3.5, 30)])
    pts = np.vstack([bottom, side[1:]])
    pts[1:-1, 1:] += np.random.default_rng(2).normal(0, 0.002, (len(pts) - 2, 2))
    obj = new_curve("chine section", "POLY", pts)
    (report,) = api.fair_curve(obj, tolerance=0.01)
    assert report["corners"] == [29], "the chine point is kept as a corner"
    (curve,) = api.read_curves(obj)
    assert len(curve.corners(1.0)) == 1, "and it is sharp in the faired curve"


def test_fair_curve_failure_changes_nothing():
    pts = noisy_arc(40)
    rng = np.random.default_rng(0)
    shuffled = pts[rng.permutation(len(pts))]
    obj = new_curve("scrambled", "POLY", shuffled)
    before = np.empty(4 * len(pts), dtype=np.float32)
    obj.data.splines[0].points.foreach_get("co", before)
    with pytest.raises(api.BattenError, match="curve 'scrambled': the points are not in order"):
        api.fair_curve(obj)
    after = np.empty_like(before)
    assert obj.data.splines[0].type == "POLY"
    obj.data.splines[0].points.foreach_get("co", after)
    assert np.array_equal(before, after)
    same = new_curve("dot", "POLY", np.ones((5, 3)))
    with pytest.raises(api.BattenError, match="curve 'dot'"):
        api.fair_curve(same)
    with pytest.raises(api.BattenError, match="tolerance"):
        api.fair_curve(new_curve("ok", "POLY", noisy_arc(20)), tolerance=-1.0)


def test_fair_curve_on_a_drawn_nurbs_curve_keeps_its_shape():
    pts = np.column_stack([np.linspace(0, 20, 9), np.sin(np.linspace(0, 3, 9)), np.zeros(9)])
    obj = new_curve("sheer", "NURBS", pts, order=4, endpoint=True)
    (original,) = api.read_curves(obj)
    (report,) = api.fair_curve(obj, tolerance=1e-3)
    (faired,) = api.read_curves(obj)
    worst = max(faired.nearest(p.tolist())[1] for p in original.evaluate(np.linspace(*original.domain, 200)))
    assert worst < 1.5e-3
    assert report["max_deviation"] <= 1e-3


def test_curvature_comb_of_a_circle_has_teeth_of_scale_over_radius(tmp_path):
    import batten_native as bn

    s = math.sqrt(0.5)
    unit = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
    pts = np.array([[3.0 * x, 3.0 * y, 1.0] for x, y in unit])
    knots = np.array([0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4], dtype=float)
    circle = bn.Curve("ring", 2, knots, pts, np.array([1, s, 1, s, 1, s, 1, s, 1]))
    path = tmp_path / "ring.json"
    path.write_text(bn.network_to_json("ring", [circle]))
    obj = api.load_network(path).objects[0]  # exact rational circle of radius 3 in Blender
    bases, tips = api.curvature_comb(obj, samples=50, scale=2.0)
    np.testing.assert_allclose(np.linalg.norm(bases[:, :2], axis=1), 3.0, rtol=1e-6)
    np.testing.assert_allclose(np.linalg.norm(tips - bases, axis=1), 2.0 / 3.0, rtol=1e-5)
    np.testing.assert_allclose(np.linalg.norm(tips[:, :2], axis=1), 3.0 + 2.0 / 3.0, rtol=1e-5)


def test_comb_overlay_lines_follow_the_selection():
    from batten import overlay

    obj = new_curve("arc", "POLY", noisy_arc(30, sigma=0.0))
    api.fair_curve(obj, tolerance=1e-3)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    lines = overlay.comb_lines(bpy.context)
    assert lines.shape == (2 * 200 + 2 * 199, 3) and lines.dtype == np.float32
    obj.select_set(False)
    assert len(overlay.comb_lines(bpy.context)) == 0


@pytest.mark.parametrize("ship", ["kcs", "kvlcc2"])
def test_real_ship_sections_import_within_5_mm(ship):
    path = HULLS / ship / "network.json"
    assert path.is_file(), f"{path} missing: CI keeps shared/ beside the repository"
    coll, reports = api.import_sections(path)
    assert len(coll.objects) == len(reports) > 40
    worst = max(r["max_deviation"] for r in reports)
    assert worst <= 0.005, f"{ship}: worst deviation {worst * 1e3:.2f} mm"
    curves = {c.name: c for c in api.read_curves(coll)}
    # Measured, not reported: every point of the file (read here, not by the add-on) lies
    # within 5 mm of the curve drawn in Blender (float32 control points), by closest point.
    data = json.loads(path.read_text())["curves"]
    chines = [r["curve"] for r in reports if r.get("kind") == "chine"]
    flats = [r["curve"] for r in reports if r.get("kind") == "flat_of_bottom"]
    lines = [r["curve"] for r in reports if r.get("kind") == "line"]
    assert len(data) + len(chines) + len(flats) + len(lines) == len(curves)
    assert all(curves[name].role == "knuckle" for name in chines)
    # KCS's shaft boss ends flat: its edge is a chine, and two lines part it (KVLCC2's lowest
    # waterline ends at its boss's lower corner, so that end is left as the sections give it).
    assert len(lines) == {"kcs": 2, "kvlcc2": 0}[ship], lines
    assert all(curves[name].role == "free" for name in lines)
    assert flats == ["flat of bottom"] and curves["flat of bottom"].role == "fob", "a flat-bottomed ship"
    # A section end running into a needle beside another curve is cut back to its last node
    # (KVLCC2's highest waterline beside its falling deck edge): the surface passes those
    # points, within 5 mm, instead of the curve.
    dropped = {r["curve"]: r["dropped_points"] for r in reports if r.get("dropped_points")}
    assert sorted(dropped) == {"kcs": [], "kvlcc2": ["wl_z25.50_part1of2", "wl_z25.50_part2of2"]}[ship]
    for c in data:
        drawn = curves[c["name"]]
        gone = set(dropped.get(c["name"], []))
        far = max(drawn.nearest(p, 1e-9)[1] for k, p in enumerate(c["points"]) if k not in gone)
        assert far <= 0.005, f"{ship} {c['name']}: a point is {far * 1e3:.2f} mm from the drawn curve"
    if dropped:
        sys.path.insert(0, str(ROOT / "blender_scripts"))
        from measure_ships import clipped_triangles, surface_distance

        (positions, corners, sizes, _), _ = build_surface(
            api.read_curves(coll), resolution=32, tangent_planes=api.tangent_planes(coll)
        )
        by_name = {c["name"]: c["points"] for c in data}
        points = np.array([by_name[name][k] for name, ks in dropped.items() for k in ks])
        far = surface_distance(points, clipped_triangles(positions, corners, sizes, np.inf)).max()
        assert far <= 0.005, f"{ship}: a dropped point is {far * 1e3:.2f} mm from the surface"
    for r in reports:
        c = curves[r["curve"]]
        assert len(c.corners(1.0)) == len(r["corners"]), f"{r['curve']}: corners kept sharp in Blender"
    roles = {o.batten.role for o in coll.objects}
    assert {"keel", "deck", "free"} <= roles


def test_csv_offsets_import(tmp_path):
    rows = ["name,x,y,z"]
    for name, x in (("st1", 10.0), ("st2", 20.0)):
        for z in np.linspace(0, 5, 25):
            rows.append(f"{name},{x},{3 * math.sin(z / 5 * math.pi / 2):.6f},{z:.6f}")
    path = tmp_path / "offsets.csv"
    path.write_text("\n".join(rows) + "\n")
    coll, reports = api.import_sections(path, tolerance=1e-3)
    assert sorted(o.name for o in coll.objects) == ["st1", "st2"]
    assert all(r["max_deviation"] <= 1e-3 for r in reports)
    bad = tmp_path / "bad.csv"
    bad.write_text("st1,1,2\n")
    n = len(bpy.data.objects)
    with pytest.raises(api.BattenError, match="line 1: expected name, x, y, z"):
        api.import_sections(bad)
    assert len(bpy.data.objects) == n


def test_fair_operator_reports_through_bpy_ops():
    obj = new_curve("wl", "POLY", noisy_arc(50))
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.context.scene.batten.fair_tolerance = 0.03
    assert bpy.ops.batten.fair_curves() == {"FINISHED"}
    assert obj.data.splines[0].type == "NURBS"


# At the defaults, before curves were moved through their nodes, KCS built 4 faces with 144
# near misses: each section faired on its own no longer met its neighbours.
# The transom's side edge is a knuckle in the upper waterlines and the deck: joined, it is a chine
# (one per ship); KCS's shaft boss ends flat, and the edge of that end, between two knuckles of
# the profile, is a second. KCS kept one near miss (wl_z12.50 could not meet the profile at the
# stem within 5 mm of its points) until the nodes were found in the data and the curves fitted
# through them.
@pytest.mark.parametrize(
    ("ship", "faces", "near_misses", "chines"), [("kcs", 280, 0, 2), ("kvlcc2", 300, 0, 1)]
)
def test_real_ship_curves_meet_at_their_nodes_and_build_at_the_defaults(ship, faces, near_misses, chines):
    coll, reports = api.import_sections(HULLS / ship / "network.json")
    joined = [r for r in reports if r.get("kind") == "chine"]
    assert len(joined) == chines, [r["curve"] for r in joined]
    assert all(r["points"] >= 2 and r["max_deviation"] < 1e-6 for r in joined), joined
    moved = [r for r in reports if r["nodes"] > 0]
    assert len(moved) >= 0.9 * len(reports), f"{len(moved)} of {len(reports)} curves meet their nodes"
    assert max(r["snap_move"] for r in reports) <= SECTION_CAPTURE_FACTOR * DEFAULT_SECTION_TOLERANCE
    assert max(r["max_deviation"] for r in reports) <= DEFAULT_SECTION_TOLERANCE
    report = api.build(coll).report
    misses = [w for w in report["warnings"] if w["kind"] == "near_miss"]
    assert report["faces"] >= faces, report["faces"]
    assert len(misses) <= near_misses, [w["message"] for w in misses]


def test_kcs_stem_node_gets_one_tangent_plane_and_the_hull_is_g1_within_0_05_degrees():
    """Where st20 and the design waterline meet KCS's stem profile, their tangents missed one
    plane by 0.23° (the data's slopes off the centreplane, a few thousandths, disagree), and the
    patches on either side of each met at up to 0.44°: the largest normal jump of the hull. The
    import turns the three tangents into their common plane (real-ships issue: compatible at
    every node, the change reported), and every smooth edge is then within the issue's 0.05°."""
    coll, reports = api.import_sections(HULLS / "kcs" / "network.json")
    turned = {r["curve"]: r["tangent_turn_deg"] for r in reports if r["tangent_nodes"]}
    assert {"st20_part2of2", "wl_z10.80", "profile_centreline"} <= set(turned), turned
    assert all(0.01 < t < 0.5 for t in turned.values()), turned
    report = api.build(coll).report
    jump = report["max_normal_angle_deg"]
    assert jump <= 0.05, f"{jump:.4f}° at {report['max_normal_angle_at']}"


def test_kvlcc2_builds_closed_at_the_defaults_with_its_volume():
    """KVLCC2 imported and built with every setting at its default (real-ships issue): the
    curves that meet in the data meet (nodes from the data), so no region is left open but the
    two named below, and the volume below T is the reference's within 0.1 % (LCB within 0.05 %
    Lpp). Before the nodes from the data: 8 holes, 6 dangling ends, ∇ 3.96 % short."""
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "blender_scripts"))
    from measure_ships import clipped_triangles, mesh_figures

    ship = HULLS / "kvlcc2"
    ref = json.loads((ship / "reference.json").read_text())
    coll, _ = api.import_sections(ship / "network.json")
    report = api.build(coll).report
    kinds = [w["kind"] for w in report["warnings"]]
    assert kinds.count("dangling_end") == 0 and kinds.count("unclosed_region") == 0, kinds
    # No hole: the skeg side over the boss (st0.50_part1of2, wl_z5.00, st01, wl_z8.00 and the
    # profile) and the strip under wl_z0.30 from st18.50 to st19.75 were traced into the boundary
    # loop while node normals were oriented by the sign of their dot product (2 holes).
    holes = [w for w in report["warnings"] if w["kind"] == "hole"]
    assert not holes, [w["message"] for w in holes]
    (positions, corners, sizes, _), _ = build_surface(
        api.read_curves(coll), tangent_planes=api.tangent_planes(coll)
    )
    fig = mesh_figures(clipped_triangles(positions, corners, sizes, ref["T"]))
    c = ref["computed"]
    volume = 100 * (fig["volume"] / c["displaced_volume"] - 1)
    lcb = 100 * (fig["lcb"] - c["LCB_from_AP"]) / ref["Lpp"]
    assert abs(volume) <= 0.1, f"volume below T {volume:+.3f} % of the reference"
    assert abs(lcb) <= 0.05, f"LCB {lcb:+.4f} % Lpp from the reference"


# Before node normals were carried along the edges to orient them, both ships had a hole under
# water over the shaft boss (and KCS one at the boss's end face, whose profile knuckles were no
# nodes), and api.hydrostatics refused them.
@pytest.mark.parametrize("ship", ["kcs", "kvlcc2"])
def test_real_ship_has_no_hole_under_water_and_gives_its_hydrostatics(ship):
    ref = json.loads((HULLS / ship / "reference.json").read_text())
    lpp, draft = ref["Lpp"], ref["T"]
    coll, _ = api.import_sections(HULLS / ship / "network.json")
    report = api.build(coll).report
    holes = [w for w in report["warnings"] if w["kind"] == "hole" and w["location"][2] < draft]
    assert not holes, [w["message"] for w in holes]
    h = api.hydrostatics(coll, draft, lpp=lpp, fp=lpp)
    c = ref["computed"]
    lcb = 100 * (h["lcb"] - c["LCB_from_AP"]) / lpp
    assert abs(lcb) <= 0.05, f"LCB {lcb:+.4f} % Lpp from the reference"
    assert abs(h["lwl"] / c["Lwl_at_T"] - 1) <= 1e-3, h["lwl"]


def test_imported_sections_carry_the_ships_perpendiculars_and_draft():
    coll, _ = api.import_sections(HULLS / "kcs" / "network.json")
    assert coll["batten_lpp"] == 230.0 and coll["batten_fp"] == 230.0
    assert api.design_draft(coll) == 10.8
    api.build(coll)
    h = api.hydrostatics(coll, 10.8)  # the collection's perpendiculars: AP at x = 0
    assert h["x_ap"] == 0.0 and h["x_fp"] == 230.0


@pytest.mark.parametrize("ship", ["kcs", "kvlcc2"])
def test_real_ship_hydrostatics_give_the_reference_figures(ship):
    """The hydrostatics issue's real-ship figures at the design draft, on the patches: ∇ within
    0.1 %, LCB and LCF within 0.05 % Lpp, Awp within 0.1 %, Cb and Cm within 0.002 (they divide
    by the measured Bwl, 32.23 m for KCS where the reference takes the nominal 32.2 m), and the
    wetted surface within 1 % (measured +0.11 % and +0.47 %: the fits' flat of bottom and the
    forefoot folds add area). Both forefoot patches fold 14-19 cm across the centreplane; the
    surface still counts as a port half (api.hydrostatics allows 5 % of the half-breadth)."""
    ref = json.loads((HULLS / ship / "reference.json").read_text())
    lpp, c = ref["Lpp"], ref["computed"]
    coll, _ = api.import_sections(HULLS / ship / "network.json")
    api.build(coll)
    h = api.hydrostatics(coll, ref["T"], lpp=lpp, fp=lpp)
    assert abs(h["volume"] / c["displaced_volume"] - 1) <= 1e-3, (h["volume"], c["displaced_volume"])
    assert abs(h["lcb"] - c["LCB_from_AP"]) <= 5e-4 * lpp, (h["lcb"], c["LCB_from_AP"])
    assert abs(h["lcf"] - c["LCF_from_AP"]) <= 5e-4 * lpp, (h["lcf"], c["LCF_from_AP"])
    assert abs(h["waterplane_area"] / c["waterplane_area"] - 1) <= 1e-3, h["waterplane_area"]
    assert abs(h["cb"] - c["Cb"]) <= 2e-3 and abs(h["cm"] - c["Cm"]) <= 2e-3, (h["cb"], h["cm"])
    assert abs(h["wetted_area"] / c["wetted_surface_below_T"] - 1) <= 1e-2, h["wetted_area"]
