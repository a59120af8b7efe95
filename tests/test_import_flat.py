"""The flat of bottom of a hull given as sections: every station runs straight in the base
plane and leaves it tangentially, a flat of bottom curve (role ``fob``) joins where they leave
it, and the surface between the keel and that curve is flat: on a synthetic hull to rounding,
on KCS and KVLCC2 (when ``shared/hulls`` is beside the checkout) within the real-ships issue's
1 mm."""

import json
import math
import sys
from pathlib import Path

import batten.api as api
import numpy as np
import pytest
from batten import flat_of_bottom
from batten_native import build_surface

HULLS = Path(__file__).resolve().parents[2] / "shared" / "hulls"
SCRIPTS = Path(__file__).resolve().parents[1] / "blender_scripts"
#: The synthetic hull: length, bilge radius, depth, spacing of the points (m).
L, R, D, STEP = 60.0, 2.0, 6.0, 0.05


def half_flat(x: float) -> float:
    """Half-width of the synthetic hull's flat of bottom at ``x``."""
    return 3.0 + 2.0 * math.sin(math.pi * x / L)


def station(x: float) -> list[list[float]]:
    w = half_flat(x)
    pts = [[x, w * i / round(w / STEP), 0.0] for i in range(round(w / STEP))]
    arc = round(R * math.pi / 2 / STEP)
    pts += [
        [x, w + R * math.sin(a), R * (1 - math.cos(a))]
        for a in np.linspace(0, math.pi / 2, arc, endpoint=False)
    ]
    side = round((D - R) / STEP)
    pts += [[x, w + R, R + (D - R) * i / side] for i in range(side + 1)]
    return pts


@pytest.fixture
def flat_hull(tmp_path):
    xs = np.linspace(0.0, L, 11)
    # The end stations are the hull's ends (its transoms).
    kinds = ["transom"] + ["station"] * (len(xs) - 2) + ["transom"]
    curves = [
        {"name": f"st{i:02d}", "kind": k, "points": station(x)}
        for i, (x, k) in enumerate(zip(xs, kinds, strict=True))
    ]
    for z in (0.5, 1.5, 3.0, 4.5):
        wl = [[x, half_flat(x) + math.sqrt(R * R - max(R - z, 0.0) ** 2), z] for x in np.linspace(0, L, 121)]
        curves.append({"name": f"wl{z}", "kind": "waterline", "points": wl})
    curves.append(
        {"name": "keel", "kind": "profile", "points": [[x, 0.0, 0.0] for x in np.linspace(0, L, 61)]}
    )
    deck = [[x, half_flat(x) + R, D] for x in np.linspace(0, L, 61)]
    curves.append({"name": "deck", "kind": "deck", "points": deck})
    path = tmp_path / "flat.json"
    path.write_text(json.dumps({"name": "flat", "curves": curves}))
    return path


def test_base_plane_needs_a_flat():
    pts = np.array([[0, 0, 0.0002 * i] for i in range(10)] + [[0, 1, 5.0]])
    assert flat_of_bottom.base_plane(pts, 1e-3) == pytest.approx(0.0009, abs=1e-3)
    assert flat_of_bottom.base_plane(pts[:5], 1e-3) is None, "five points are no flat"


def test_side_plane_is_the_widest_breadth_shared_enough():
    y = np.concatenate([np.full(80, 7.0), np.full(160, 6.902), 7.05 + 0.004 * np.arange(5)])
    pts = np.column_stack([np.zeros_like(y), y, np.zeros_like(y)])
    # The widest breadth half the most shared one's points share: not the two narrower
    # stations' (160 points), nor a bulge's scatter (5 points).
    assert flat_of_bottom.side_plane(pts, 1e-3) == pytest.approx(7.0)
    assert flat_of_bottom.side_plane(pts[80:], 1e-3) == pytest.approx(6.902)
    assert flat_of_bottom.side_plane(pts[:5], 1e-3) is None, "five points are no flat"
    # A port half (y < 0) has its flat of side at the same breadth.
    assert flat_of_bottom.side_plane(pts * [1, -1, 1], 1e-3) == pytest.approx(7.0)
    # A profile (every point in the centreplane) has none.
    assert flat_of_bottom.side_plane(pts * [1, 0, 1], 1e-3) is None


def test_stations_run_flat_into_a_flat_of_bottom_curve_and_the_bottom_is_flat(flat_hull):
    coll, fits = api.import_sections(flat_hull)
    fob = coll.objects[flat_of_bottom.NAME]
    assert fob.batten.role == "fob"
    report = next(r for r in fits if r["curve"] == flat_of_bottom.NAME)
    assert report["kind"] == "flat_of_bottom" and report["points"] == 11
    stations = [r for r in fits if r["curve"].startswith("st")]
    assert all([f["kind"] for f in r["flats"]][:1] == ["bottom"] and not r["corners"] for r in stations), (
        "a flat of bottom each, no knuckle"
    )
    # The widest station (midships, y = 7 m) is the only one whose side is at the widest
    # breadth: it alone runs straight up a flat of side too.
    sides = [r["curve"] for r in fits if any(f["kind"] == "side" for f in r.get("flats", []))]
    assert [c for c in sides if c.startswith("st")] == ["st05"], sides
    # The flat ends where the bilge arc leaves the base plane by the model tolerance.
    leave = math.sqrt(2 * R * 1e-3) + STEP
    curve = api.read_curves(fob)[0]
    for x in np.linspace(0.0, L, 11):
        t = curve.nearest([x, half_flat(x), 0.0])[0]
        y = np.asarray(curve.evaluate([t]))[0]
        assert abs(y[2]) < 1e-9, "in the base plane"
        assert half_flat(x) - 1e-9 <= y[1] <= half_flat(x) + leave
    result = api.build(coll)
    assert not result.report["folds"] and not result.report["holes"]
    assert not [w for w in result.report["warnings"] if w["kind"] == "near_miss"]
    # G1 everywhere, the bilge onto the flat too (measured 8.4e-5°; 1.17° at the flat of bottom
    # while it was fitted within 0.5 mm of the stations' flat ends, so crossed them off their
    # knots).
    assert result.report["max_normal_angle_deg"] < 0.01, result.report["max_normal_angle_at"]
    (positions, _, _, _), _ = build_surface(
        api.read_curves(coll), resolution=12, tangent_planes=api.tangent_planes(coll)
    )
    positions = np.asarray(positions)
    flat = positions[:, 1] < np.array([half_flat(x) for x in positions[:, 0]]) - 0.01
    assert flat.sum() > 500
    assert np.abs(positions[flat, 2]).max() < 1e-6, "the faces between keel and flat of bottom are flat"
    # Up the bilge the surface stays within the import tolerance of the arc.
    bilge = (positions[:, 2] > 0.05) & (positions[:, 2] < R - 0.05)
    y, z = positions[bilge, 1], positions[bilge, 2]
    centre_y = np.array([half_flat(x) for x in positions[bilge, 0]])
    radius = np.hypot(y - centre_y, z - R)
    assert np.abs(radius - R).max() < 0.01


@pytest.mark.skipif(not HULLS.is_dir(), reason="shared/hulls is not beside the checkout")
@pytest.mark.parametrize("ship", ["kcs", "kvlcc2"])
def test_the_real_ships_flat_of_bottom_is_flat_within_1_mm(ship):
    sys.path.insert(0, str(SCRIPTS))
    import measure_ships

    coll, fits = api.import_sections(HULLS / ship / "network.json")
    assert any(r["curve"] == flat_of_bottom.NAME for r in fits)
    (positions, _, _, _), _ = build_surface(
        api.read_curves(coll), resolution=16, tangent_planes=api.tangent_planes(coll)
    )
    data = json.loads((HULLS / ship / "network.json").read_text())
    points = np.array([p for c in data["curves"] for p in c["points"]])
    assert measure_ships.flatness(points, np.asarray(positions), 2, 0.0) < 1e-3


@pytest.mark.skipif(not HULLS.is_dir(), reason="shared/hulls is not beside the checkout")
@pytest.mark.parametrize("ship", ["kcs", "kvlcc2"])
def test_the_real_ships_flat_of_side_is_flat_within_1_mm(ship):
    """The import gives the collection the flats it found as the surface's tangent planes, and
    the surface keeps to the flat of side within 1 mm wherever the data are on it (measured
    0.97 mm on KCS, 0.92 mm on KVLCC2 at resolution 16). Without the planes KCS's surface stood
    1.12 mm off beside station 6, whose run up the side starts 10 cm above the node with a
    waterline that crosses the side at 0.8°; KVLCC2's deck edge, which curves along the flat of
    side from x = 79 m to 131 m, bowed 2.3 mm off it before it was fitted on the plane."""
    sys.path.insert(0, str(SCRIPTS))
    import measure_ships

    coll, _fits = api.import_sections(HULLS / ship / "network.json")
    data = json.loads((HULLS / ship / "network.json").read_text())
    points = np.array([p for c in data["curves"] for p in c["points"]])
    side = flat_of_bottom.side_plane(points, 1e-3)
    base = flat_of_bottom.base_plane(points, 1e-3)
    assert api.tangent_planes(coll) == [[0.0, 1.0, 0.0, side], [0.0, 1.0, 0.0, -side], [0.0, 0.0, 1.0, base]]
    curves = api.read_curves(coll)
    (positions, _, _, _), _ = build_surface(curves, resolution=16, tangent_planes=api.tangent_planes(coll))
    assert measure_ships.flatness(points, np.asarray(positions), 1, side) < 1e-3
    if ship == "kcs":
        (bare, _, _, _), _ = build_surface(curves, resolution=16)
        assert measure_ships.flatness(points, np.asarray(bare), 1, side) > 1e-3


@pytest.mark.skipif(not HULLS.is_dir(), reason="shared/hulls is not beside the checkout")
def test_an_imported_ship_saved_as_a_network_file_builds_the_same_surface(tmp_path):
    """export_network then load_network keeps KCS's flats: the loaded collection's surface
    keeps to the flat of side within 1 mm as the imported one does (without its planes it
    stood 1.1 mm off), and its volume is the imported one's."""
    sys.path.insert(0, str(SCRIPTS))
    import measure_ships

    coll, _fits = api.import_sections(HULLS / "kcs" / "network.json")
    path = api.export_network(coll, tmp_path / "kcs.json")
    loaded = api.load_network(path, collection="kcs loaded")
    assert api.tangent_planes(loaded) == api.tangent_planes(coll) != []
    side = api.tangent_planes(loaded)[0][3]
    points = np.array(
        [p for c in json.loads((HULLS / "kcs" / "network.json").read_text())["curves"] for p in c["points"]]
    )
    curves = api.read_curves(loaded)
    (after, _, _, _), report = build_surface(curves, resolution=16, tangent_planes=api.tangent_planes(loaded))
    assert measure_ships.flatness(points, np.asarray(after), 1, side) < 1e-3
    _, before = build_surface(api.read_curves(coll), resolution=16, tangent_planes=api.tangent_planes(coll))
    assert report["volume"] == pytest.approx(before["volume"], rel=1e-9)
    (bare, _, _, _), _ = build_surface(curves, resolution=16)
    assert measure_ships.flatness(points, np.asarray(bare), 1, side) > 1e-3


def test_a_port_half_gets_the_same_flats(flat_hull, tmp_path):
    data = json.loads(flat_hull.read_text())
    for c in data["curves"]:
        c["points"] = [[x, -y, z] for x, y, z in c["points"]]
    port = tmp_path / "port.json"
    port.write_text(json.dumps(data))
    _, starboard = api.import_sections(flat_hull, collection="starboard")
    _, fits = api.import_sections(port, collection="port")

    def flats(reports):
        return {
            r["curve"]: [(f["kind"], f["index"]) for f in r.get("flats", [])]
            for r in reports
            if r.get("flats")
        }

    assert flats(fits) == flats(starboard)
    assert [kind for kind, _ in flats(fits)["st05"]] == ["bottom", "side"], "the widest station's"
