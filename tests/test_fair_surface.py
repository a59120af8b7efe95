"""api.fair_surface: the paper's test (seed 003 §5) on the Wigley lines — noise below the
tolerance added to every station and waterline, then faired through both families — in
Blender: the curve objects are rewritten in place, fixed ones untouched, the network stays
exact and builds, and a bad request changes nothing."""

import batten.api as api
import batten_native
import numpy as np
import pytest
from batten.bridge import curves_out

TOL = 0.01  # 10 mm


def _points(source) -> dict[str, np.ndarray]:
    out = {}
    for c in api.read_curves(source):
        out[c.name] = np.asarray(c.evaluate(np.linspace(*c.domain, 101)))
    return out


def _curves(source) -> dict:
    return {c.name: c for c in api.read_curves(source)}


def _from(points: dict[str, np.ndarray], curves: dict) -> float:
    """The largest distance of the sampled ``points`` from the ``curves`` of the same names
    (written back to Blender a curve may change its parametrisation, not its shape)."""
    return max(curves[n].nearest(p.tolist())[1] for n, pts in points.items() for p in pts)


def _noisy(coll):
    """The collection's station and waterline curves moved by noise of 30 % of the tolerance."""
    curves = api.read_curves(coll)
    noisy = batten_native.section_noise(curves, 0.3 * TOL, 3)
    objects = {o.name: o for o in api.curve_objects(coll)}
    curves_out.replace_splines_of([(objects[c.name], [c]) for c in noisy])
    return coll


def test_noise_is_faired_within_the_tolerance_and_the_network_stays_exact():
    coll = api.load_example("wigley_lines.json")
    clean = _curves(coll)
    clean_volume = api.build(coll).report["enclosed_volume"]
    _noisy(coll)
    noisy, noisy_curves = _points(coll), _curves(coll)
    noise = _from(noisy, clean)
    assert 0.2 * TOL < noise < TOL, noise
    nodes = api.topology(coll)["nodes"]
    report = api.fair_surface(coll, tolerance=TOL)
    assert report["moves"] > 20, report["moves"]
    assert report["max_deviation"] <= TOL
    faired = _points(coll)
    # Blender keeps single precision: within the tolerance of the noisy curves to its rounding.
    assert _from(faired, noisy_curves) <= TOL + 1e-5
    # Nearer the clean hull than the noise was.
    left = _from(faired, clean)
    assert left < noise, (left, noise)
    # The keel, stem, stern and deck edge are fixed: untouched.
    for name in ("keel", "stem", "stern", "deck edge"):
        assert np.array_equal(faired[name], noisy[name]), name
    # Still one exact network: the same nodes, and it builds with the volume kept.
    topo = api.topology(coll)
    assert topo["nodes"] == nodes
    assert not [d for d in topo["diagnostics"] if d["kind"] == "near_miss"]
    volume = api.build(coll).report["enclosed_volume"]
    assert volume == pytest.approx(clean_volume, rel=5e-4)
    per_curve = {c["curve"]: c for c in report["curves"]}
    assert per_curve["keel"]["family"] is None and per_curve["keel"]["moves"] == 0
    assert per_curve["station +0.0"]["object"] == "station +0.0"
    assert report["sections"] == {"stations": 15, "waterlines": 6}


def test_a_curve_object_named_in_fixed_stays():
    coll = _noisy(api.load_example("wigley_lines.json"))
    before = _points(coll)
    report = api.fair_surface(coll, tolerance=TOL, fixed=(*api.SURFACE_FAIR_FIXED_ROLES, "station +0.0"))
    after = _points(coll)
    assert np.array_equal(after["station +0.0"], before["station +0.0"])
    assert {c["curve"]: c["moves"] for c in report["curves"]}["station +0.0"] == 0
    assert report["moves"] > 0


@pytest.mark.parametrize(
    "bad, message",
    [
        ({"families": ("stations", "diagonals")}, "diagonals"),
        ({"filter": "gaussian"}, "gaussian"),
        ({"fixed": ("no such curve",)}, "no such curve"),
        ({"tolerance": -1.0}, "tolerance"),
        ({"curve_tolerances": {"nope": 0.01}}, "nope"),
        ({"smoothing_length": -2.0}, "smoothing length"),
    ],
)
def test_a_bad_request_changes_nothing(bad, message):
    coll = _noisy(api.load_example("wigley_lines.json"))
    before = _points(coll)
    with pytest.raises(api.InvalidArgumentError, match=message):
        api.fair_surface(coll, **bad)
    after = _points(coll)
    assert all(np.array_equal(after[n], before[n]) for n in before)


def test_kcs_with_noise_is_faired_back_within_the_tolerance_of_the_clean_hull(hulls_dir):
    """Issue 17's test on KCS as ``import_sections`` draws it: noise of 30 % of the 10 mm
    tolerance at every station and waterline control point (seed 3, as
    blender_scripts/bench_fairing_surface.py), faired at the defaults: every point within the
    tolerance of the clean hull, the curvature variation 10× below the noisy hull's and within
    2× of the clean hull's, the volume within 0.05 %, the outline bitwise the same, most of the
    noise's inflections gone. (The inflection count itself is not back to the clean count
    ±10 % here: 42 against 55; through Blender's single precision the noisy input differs
    from the bench's by rounding and the count by ten: see the issue's note.)"""
    path = hulls_dir / "kcs" / "network.json"
    if not path.exists():
        pytest.skip("../shared/hulls is not beside the project")
    coll, _ = api.import_sections(path)
    clean_curves = api.read_curves(coll)
    clean = {c.name: c for c in clean_curves}
    # The outline (profile, upper edge, chines): fixed by name, as the import draws it free.
    outline = [n for n in clean if n.startswith(("profile", "deck", "chine"))]
    clean_figures = batten_native.fair_sections(
        clean_curves, tolerance=TOL, max_rounds=0, smoothing_length=0.0
    )[1]["before"]
    clean_volume = api.build(coll).report["enclosed_volume"]
    noisy = batten_native.section_noise(clean_curves, 0.3 * TOL, 3, fixed_curves=outline)
    objects = {o.name: o for o in api.curve_objects(coll)}
    curves_out.replace_splines_of([(objects[c.name], [c]) for c in noisy])
    noisy_points = _points(coll)
    report = api.fair_surface(coll, tolerance=TOL, fixed=(*api.SURFACE_FAIR_FIXED_ROLES, *outline))
    assert report["smoothing_length"] == pytest.approx(200 * TOL)
    assert report["smoothed"] >= 40
    faired = _points(coll)
    # Every point of every curve within the tolerance of the clean hull (and of the noisy input).
    assert _from(faired, clean) <= TOL
    assert report["max_deviation"] <= TOL
    before, after = report["before"], report["after"]
    assert after["curvature_variation"] <= 0.1 * before["curvature_variation"]
    assert after["curvature_variation"] <= 2.0 * clean_figures["curvature_variation"]
    assert after["inflections"] < 0.5 * before["inflections"], (before, after)
    assert after["inflections"] > 0.5 * clean_figures["inflections"], (clean_figures, after)
    for name in outline:
        assert np.array_equal(faired[name], noisy_points[name]), name
    volume = api.build(coll).report["enclosed_volume"]
    assert volume == pytest.approx(clean_volume, rel=5e-4)
