"""Form topology and transformations through Blender (seed 002 §6–§7, §9): the frigate (no
parallel middle body) and a barge with a parallel middle body, flat of side and bottom, rise of
floor and a circular bilge; the transformation stack leaves the original untouched until
commit."""

import importlib.util
from pathlib import Path

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import form_stack

HB, D, T = 10.0, 12.0, 8.0  # as examples/pmb_barge.py


def _barge_curves():
    """The PMB barge of ``examples/pmb_barge.py`` (its generator, not the JSON, so both are
    tested: ``test_examples`` checks that the JSON is what it writes)."""
    path = Path(__file__).resolve().parent.parent / "examples" / "pmb_barge.py"
    spec = importlib.util.spec_from_file_location("pmb_barge", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.barge_curves()


def _points(coll):
    """Every spline point of the collection's objects, by object name (bitwise)."""
    out = {}
    for obj in sorted(coll.all_objects, key=lambda o: o.name):
        for i, s in enumerate(obj.data.splines):
            pts = s.points if len(s.points) else s.bezier_points
            a = np.zeros(len(pts) * (4 if len(s.points) else 3))
            pts.foreach_get("co", a)
            out[(obj.name, i)] = a
    return out


def _warning_kinds(coll):
    kinds = {}
    for w in api.build(coll).report["warnings"]:
        kinds[w["kind"]] = kinds.get(w["kind"], 0) + 1
    return kinds


def test_frigate_form_has_no_pmb_and_breadth_plus_five_percent(examples_dir):
    coll = api.load_network(examples_dir / "frigate_network.json")
    form = api.form_topology(coll, draft=4.8)
    p = form["parameters"]
    assert p["pmb_length"] is None and "midship" in p["no_pmb_reason"]
    assert "st6" in form["curves"] and "cwl" not in form["curves"]
    assert {e["kind"] for e in form["edges"]} <= {"free_form", "straight", "blend"}
    before = _points(coll)
    warnings_before = _warning_kinds(coll)
    result = api.transform(coll, breadth=1.05 * p["breadth"], draft=4.8)
    after = result.report["after"]
    assert after["waterline_breadth"] == pytest.approx(1.05 * p["waterline_breadth"], abs=1e-3)
    assert result.report["before"]["waterline_breadth"] == pytest.approx(p["waterline_breadth"], abs=1e-12)
    assert result.collection.name != coll.name and result.collection.name in bpy.data.collections
    # The original is bitwise unchanged until commit.
    now = _points(coll)
    assert now.keys() == before.keys() and all(np.array_equal(now[k], before[k]) for k in now)
    for kind, n in _warning_kinds(result.collection).items():
        assert warnings_before.get(kind, 0) >= n, f"new warning {kind}"
    with pytest.raises(api.InvalidArgumentError, match="parallel middle body"):
        api.transform(coll, pmb_length=30.0)
    copy_name = result.collection.name
    kept = api.transform(coll, depth=p["depth"] + 1.0, draft=4.8)
    assert kept.report["after"]["depth"] == pytest.approx(p["depth"] + 1.0, abs=1e-6)
    assert api.keep(kept).get("batten_transform_of") is None
    assert api.abandon(coll) == 1, "the kept copy is off the stack"
    assert copy_name not in bpy.data.collections
    assert kept.collection.name in bpy.data.collections


HULLS = Path(__file__).resolve().parents[2] / "shared" / "hulls"


def _station_inflections(curve, threshold=0.01, samples=3000):
    """Sign changes of a station's curvature in its plane x = constant, among samples where
    |κ| reaches ``threshold`` of its largest (the fairness metric's threshold, sampled densely
    along the whole curve rather than 24 times a knot span)."""
    t0, t1 = curve.domain
    kappa = []
    for t in np.linspace(t0, t1, samples + 2)[1:-1]:
        d = np.asarray(curve.derivatives(t))
        kappa.append(np.cross(d[1], d[2])[0] / np.linalg.norm(d[1]) ** 3)
    kappa = np.asarray(kappa)
    signs = np.sign(kappa[np.abs(kappa) > threshold * np.abs(kappa).max()])
    return int(np.count_nonzero(signs[1:] != signs[:-1]))


@pytest.mark.skipif(not HULLS.is_dir(), reason="shared/hulls is not beside the checkout")
def test_kcs_breadth_plus_five_percent_keeps_its_stations_and_warns_of_nothing_new():
    """The form-topology issue's acceptance on KCS, imported and built at the defaults. Widened,
    it gained three fold warnings (the counter's 2.5 cm ridge beside wl_z9.00's seam at 30.2°
    between polygons, wl_z0.30's hook at the stem at 92° and 77°) where the surface turns by 23°,
    7° and 20°, and a knuckle_in_face warning for st19.75's 0.09° corner (a ribbon step of
    1.38e-3 growing to 1.55e-3, which the mends now take up to the 0.05° G1 budget, 1.745e-3)."""
    coll, _ = api.import_sections(HULLS / "kcs" / "network.json")
    before = api.build(coll).report
    p = api.form_topology(coll)["parameters"]
    assert p["pmb_length"] is None and "midship" in p["no_pmb_reason"]
    result = api.transform(coll, breadth=1.05 * p["breadth"])
    b, a = result.report["before"], result.report["after"]
    assert a["waterline_breadth"] == pytest.approx(1.05 * b["waterline_breadth"], abs=1e-3)
    assert a["breadth"] == pytest.approx(1.05 * b["breadth"], abs=1e-3)
    after = api.build(result.collection).report
    kinds = {}
    for w in before["warnings"]:
        kinds[w["kind"]] = kinds.get(w["kind"], 0) + 1
    for w in after["warnings"]:
        kinds[w["kind"]] = kinds.get(w["kind"], 0) - 1
    assert all(n >= 0 for n in kinds.values()), f"new warnings: {kinds}\n{after['warnings']}"
    assert after["folds"] == after["holes"] == 0 and after["faces"] == before["faces"]
    assert after["max_normal_angle_deg"] < 0.01
    # A transverse scale keeps the sign of every station's curvature (the copy's points are
    # the originals scaled, to Blender's float32), so their inflections stay.
    old = {c.name: c for c in api.read_curves(coll) if c.name.startswith("st")}
    new = {c.name.rsplit(" ", 1)[0]: c for c in api.read_curves(result.collection) if c.name.startswith("st")}
    assert new.keys() == old.keys() and len(old) == 36
    for name, c in old.items():
        scaled = np.asarray(c.control_points) * [1.0, 1.05, 1.0]
        assert np.abs(np.asarray(new[name].control_points) - scaled).max() < 2e-6, name
        assert _station_inflections(new[name]) == _station_inflections(c), name


def test_barge_pmb_length_commit_and_abandon(barge):
    form = api.form_topology(barge)
    p = form["parameters"]
    assert p["pmb_length"] == pytest.approx(20.0, abs=1e-12)
    # Blender keeps float32 coordinates: these are checked to 1e-9 in the core's tests.
    assert p["bilge_radius"] == pytest.approx(2.0, abs=1e-6)
    assert p["rise_of_floor"] == pytest.approx(0.2, abs=1e-6)
    assert (p["entrance_length"], p["run_length"]) == pytest.approx((40.0, 40.0), abs=1e-9)
    result = api.transform(barge, pmb_length=30.0)
    assert result.report["after"]["pmb_length"] == pytest.approx(30.0, abs=1e-9)
    assert "pmb_length 30 m" in result.report["description"]
    # A second change stacks on the first copy.
    second = api.transform(result.collection, bilge_radius=2.5)
    assert second.report["after"]["bilge_radius"] == pytest.approx(2.5, abs=1e-3)
    assert api.form_topology(barge)["parameters"]["pmb_length"] == pytest.approx(20.0, abs=1e-12)
    original = api.commit(second)
    assert original == barge
    p2 = api.form_topology(barge)["parameters"]
    assert p2["pmb_length"] == pytest.approx(30.0, abs=1e-9)
    assert p2["bilge_radius"] == pytest.approx(2.5, abs=1e-3)
    assert all(c.get("batten_transform_of") is None for c in bpy.data.collections), "the stack is dropped"
    assert all(o.batten.role != "free" or o.name.startswith("st") for o in barge.all_objects), "roles kept"


def test_barge_breadth_and_back_returns_the_network(barge):
    original = {c.name: c for c in api.read_curves(barge)}
    b = api.form_topology(barge)["parameters"]["breadth"]
    wider = api.transform(barge, breadth=1.05 * b)
    assert wider.report["after"]["waterline_breadth"] == pytest.approx(1.05 * b, abs=1e-3)
    assert wider.report["after"]["bilge_radius"] == pytest.approx(2.0, abs=1e-6)
    back = api.transform(wider.collection, breadth=b)
    worst = 0.0
    for c in api.read_curves(back.collection):
        name = bpy.data.objects[c.name][form_stack.TRANSFORM_SOURCE]
        assert c.name == f"{name} T2", "a copy's curves are named for their originals and the copy"
        worst = max(worst, float(np.abs(c.control_points - original[name].control_points).max()))
    assert worst <= 1e-6, worst  # Blender stores float32: 1e-9 is checked in the core tests


def test_a_connection_breaking_move_is_refused_naming_the_curve(barge):
    form = api.form_topology(barge)
    v = next(i for i, x in enumerate(form["vertices"]) if set(x["curves"]) >= {"keel", "ms_fwd"})
    n_collections = len(bpy.data.collections)
    with pytest.raises(api.CurveError) as err:
        api.transform(barge, moves=[(v, (-30.0, 0.0, 0.0))])
    assert err.value.curve in {o.name for o in barge.all_objects}
    assert "connection" in str(err.value)
    assert len(bpy.data.collections) == n_collections, "nothing created"
    with pytest.raises(api.InvalidArgumentError, match="breadth"):
        api.transform(barge, breadth=-1.0)
    with pytest.raises(api.InvalidArgumentError):
        api.transform(barge)


def test_a_transformed_copy_keeps_its_tangent_planes_where_its_flats_went(barge):
    """The flat of side an import would give the barge (and the same plane with its normal
    reversed) moves with the breadth onto the copy, and on to the original when the copy is
    committed; the port side's, which no curve runs in, goes to its mirror image; a plane no
    curve runs in that mirrors none (one across the hull) stays as it is."""
    planes = [[0.0, 1.0, 0.0, HB], [0.0, 1.0, 0.0, -HB], [0.0, -1.0, 0.0, -HB], [1.0, 0.0, 0.0, 50.0]]
    barge[api.TANGENT_PLANES_PROPERTY] = planes
    result = api.transform(barge, breadth=2.0 * (HB + 1.0))
    moved = api.tangent_planes(result.collection)
    np.testing.assert_allclose(
        moved,
        [
            [0.0, 1.0, 0.0, HB + 1.0],
            [0.0, 1.0, 0.0, -HB - 1.0],
            [0.0, -1.0, 0.0, -HB - 1.0],
            [1.0, 0.0, 0.0, 50.0],
        ],
        atol=1e-6,
    )
    assert api.tangent_planes(barge) == planes, "the original's stay until commit"
    # The copy builds with the moved planes, without a fold (as the original).
    assert not api.build(result.collection).report["folds"]
    # A hydrostatic transformation keeps the breadth: the planes stay where they were.
    fuller = api.transform_hydrostatic(barge, draft=T, cb=api.hydrostatics(barge, T)["cb"] + 0.01)
    np.testing.assert_allclose(api.tangent_planes(fuller.collection), planes, atol=1e-6)
    api.commit(result)
    np.testing.assert_allclose(api.tangent_planes(barge), moved, atol=1e-12)
