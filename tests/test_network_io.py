"""Network files: export from Blender, draw back as Blender curves, same shapes; bad files
change nothing."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from helpers import evaluated_polyline, new_bezier, new_curve


def shapes_match(a, b, rel=1e-6):
    """Sample curve ``a`` densely; every sample lies on ``b`` (and vice versa for the ends)."""
    size = np.linalg.norm(np.ptp(a.control_points, axis=0))
    t = np.linspace(*a.domain, 101)
    worst = max(b.nearest(p.tolist(), 1e-12)[1] for p in a.evaluate(t))
    return worst <= rel * size


def test_export_then_load_gives_the_same_curves(tmp_path):
    src = bpy.data.collections.new("Hull")
    bpy.context.scene.collection.children.link(src)
    rng = np.random.default_rng(3)
    pts = np.column_stack([np.linspace(0, 20, 8), rng.normal(0, 2, 8), rng.normal(0, 1, 8)])
    new_curve("station", "NURBS", pts, order=4, endpoint=True, weights=np.linspace(0.5, 2, 8), collection=src)
    new_curve("chine", "NURBS", pts[:6], order=3, collection=src).batten.role = "knuckle"
    new_curve("keel", "POLY", pts[:4], collection=src)
    co = pts[:3]
    new_bezier("stem", co, co - 0.5, co + [[0.5, 0.5, 0.5], [1, 0, 0], [0.2, 0.9, 0]], collection=src)
    path = api.export_network(src, tmp_path / "hull.json")
    data = json.loads(path.read_text())
    assert data["format"] == "batten-network" and data["version"] == 1 and data["name"] == "Hull"
    assert sorted(c["name"] for c in data["curves"]) == ["chine", "keel", "station", "stem"]

    before = {c.name: c for c in api.read_curves(src)}
    coll = api.load_network(path, collection="Loaded")
    assert coll.name == "Loaded" and len(coll.objects) == 4
    after = {c.name.split(".")[0]: c for c in api.read_curves(coll)}
    assert after["chine"].role == "knuckle"
    for name, curve in before.items():
        assert shapes_match(curve, after[name]), name
        assert shapes_match(after[name], curve), name
    # The drawn curves are what Blender shows, too.
    obj = coll.objects["stem.001"]
    poly = evaluated_polyline(obj)
    assert max(before["stem"].nearest(p.tolist())[1] for p in poly) < 1e-5


def test_non_layout_knots_are_drawn_exactly(tmp_path):
    import batten_native as bn

    pts = np.array([[0, 0, 0], [1, 2, 0], [3, 2, 1], [4, 0, 0], [6, -1, 0.5]], dtype=float)
    odd = bn.Curve(
        "odd knots", 3, np.array([0, 0, 0, 0, 0.2, 1, 1, 1, 1.0]), pts, np.array([1, 2, 0.5, 1, 1.0])
    )
    path = tmp_path / "odd.json"
    path.write_text(bn.network_to_json("odd", [odd]))
    coll = api.load_network(path)
    obj = coll.objects[0]
    spline = obj.data.splines[0]
    assert spline.use_bezier_u and spline.use_endpoint_u and spline.order_u == 4
    poly = evaluated_polyline(obj)
    assert max(odd.nearest(p.tolist())[1] for p in poly) < 1e-6 * 8


def test_bad_file_creates_nothing(tmp_path):
    path = tmp_path / "bad.json"
    text = open(api.__file__.replace("addon/batten/api.py", "examples/wigley.json")).read()
    good = json.loads(text)
    good["curves"][3]["points"][1][2] = "NaN"
    path.write_text(json.dumps(good))
    n_objects, n_coll = len(bpy.data.objects), len(bpy.data.collections)
    with pytest.raises(api.BattenError, match="bad.json"):
        api.load_network(path)
    assert (len(bpy.data.objects), len(bpy.data.collections)) == (n_objects, n_coll)
    with pytest.raises(api.BattenError, match="No such file"):
        api.load_network(tmp_path / "missing.json")
    good = json.loads(text)
    good["curves"][2]["knots"] = [0, 1, 0.5, 1, 1, 2, 2, 2]
    path.write_text(json.dumps(good))
    with pytest.raises(api.BattenError, match=r"curve 'station -12.5': knots decrease"):
        api.load_network(path)
    assert (len(bpy.data.objects), len(bpy.data.collections)) == (n_objects, n_coll)


def test_a_network_file_keeps_the_collections_tangent_planes(tmp_path):
    """The flat of side and bottom a collection's surface is tangent to go into the file
    (version 2) and come back on the loaded collection; a file without them stays version 1."""
    src = api.load_example("wigley.json")
    plain = json.loads(api.export_network(src, tmp_path / "plain.json").read_text())
    assert plain["version"] == 1 and "tangent_planes" not in plain
    planes = [[0.0, 1.0, 0.0, 1.25], [0.0, 0.0, 1.0, -0.625]]
    src[api.TANGENT_PLANES_PROPERTY] = planes
    path = api.export_network(src, tmp_path / "flats.json")
    data = json.loads(path.read_text())
    assert data["version"] == 2 and data["tangent_planes"] == planes
    assert api.read_network_planes(path) == planes and api.read_network_planes(tmp_path / "plain.json") == []
    coll = api.load_network(path, collection="Loaded")
    assert api.tangent_planes(coll) == planes
    assert api.TANGENT_PLANES_PROPERTY not in api.load_network(tmp_path / "plain.json", collection="Plain")

    # A bad plane is named, and nothing is drawn.
    data["tangent_planes"][1] = [0.0, 0.0, 0.0, 1.0]
    path.write_text(json.dumps(data))
    n_objects, n_coll = len(bpy.data.objects), len(bpy.data.collections)
    with pytest.raises(api.NetworkFileError, match=r"flats.json.*tangent plane 1.*non-zero"):
        api.load_network(path)
    data["tangent_planes"] = planes
    data["version"] = 1
    path.write_text(json.dumps(data))
    with pytest.raises(api.NetworkFileError, match=r"tangent_planes.*needs version 2"):
        api.load_network(path)
    assert (len(bpy.data.objects), len(bpy.data.collections)) == (n_objects, n_coll)


def test_degree_above_blender_is_refused_cleanly(tmp_path):
    import batten_native as bn

    pts = np.column_stack([np.arange(8.0), np.sin(np.arange(8.0)), np.zeros(8)])
    c = bn.Curve("high", 6, np.array([0] * 7 + [0.5] + [1] * 7, dtype=float), pts)
    ok = bn.Curve.from_poly("ok", pts[:2])
    path = tmp_path / "high.json"
    path.write_text(bn.network_to_json("n", [ok, c]))
    n_objects = len(bpy.data.objects)
    with pytest.raises(api.BattenError, match="curve 'high': degree 6 is above"):
        api.load_network(path)
    assert len(bpy.data.objects) == n_objects, "the curve drawn before the failure was removed"
    assert "n" not in bpy.data.collections
