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
    ],
)
def test_a_bad_request_changes_nothing(bad, message):
    coll = _noisy(api.load_example("wigley_lines.json"))
    before = _points(coll)
    with pytest.raises(api.InvalidArgumentError, match=message):
        api.fair_surface(coll, **bad)
    after = _points(coll)
    assert all(np.array_equal(after[n], before[n]) for n in before)
