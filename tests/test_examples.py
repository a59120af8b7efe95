"""Example networks: the committed JSON is what its generator writes, and it loads."""

import importlib.util

import batten.api as api
import pytest


@pytest.mark.parametrize("name", ["wigley", "hard_chine", "pmb_barge"])
def test_example_json_matches_its_generator(examples_dir, name):
    spec = importlib.util.spec_from_file_location(name, examples_dir / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert (examples_dir / f"{name}.json").read_text() == module.text()


def test_wigley_lines_plan_matches_its_generator(examples_dir):
    spec = importlib.util.spec_from_file_location("wigley", examples_dir / "wigley.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert (examples_dir / "wigley_lines.json").read_text() == module.lines_text()


def test_wigley_sections_are_exact(examples_dir):
    import numpy as np

    name, curves = api.read_network(examples_dir / "wigley.json")
    L, B, T = 100.0, 10.0, 6.25
    for c in curves:
        if not c.name.startswith("station"):
            continue
        p = c.evaluate(np.linspace(0, 1, 50))  # the underwater parabola
        x, y, z = p[:, 0], p[:, 1], p[:, 2]
        exact = B / 2 * (1 - (2 * x / L) ** 2) * (1 - ((T - z) / T) ** 2)
        np.testing.assert_allclose(y, exact, atol=1e-12)


def _multi_chine(examples_dir):
    spec = importlib.util.spec_from_file_location("multi_chine", examples_dir / "multi_chine.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_multi_chine_sections_match_their_generator_and_exact_volume(examples_dir):
    import math

    import numpy as np

    mc = _multi_chine(examples_dir)
    assert (examples_dir / "sections" / "multi_chine.json").read_text() == mc.text()
    # The panels turn by more than the fit's 45° corner angle at both chines, at both ends.
    for ends in (mc.STERN, mc.BOW):
        angles = [
            math.degrees(math.atan2(b[1] - a[1], b[0] - a[0]))
            for a, b in zip(ends[:-1], ends[1:], strict=True)
        ]
        np.testing.assert_allclose(angles, [12.0, 70.0, 125.0], atol=0.01)
    # Simpson on the quadratic A(x) is the integral: a fine trapezoid sum agrees.
    x = np.linspace(0.0, mc.L, 20001)
    a = np.array([mc.section_area(v) for v in x])
    trapezoid = float(np.sum(0.5 * (a[1:] + a[:-1]) * np.diff(x)))
    assert abs(trapezoid / mc.exact_volume() - 1) < 1e-8


def test_multi_chine_from_sections_only_builds_its_exact_hull(examples_dir):
    """Sections with two knuckles each and nothing else: the import finds the knuckles, joins
    them into two chines, and the hull built at the defaults has every panel, creases at the
    chines and the exact volume."""
    import json

    path = examples_dir / "sections" / "multi_chine.json"
    coll, reports = api.import_sections(path)
    chines = [r for r in reports if r.get("kind") == "chine"]
    assert len(chines) == 2 and all(r["points"] == 9 for r in chines), chines
    assert all(len(r["corners"]) == 2 for r in reports if r["curve"].startswith("st"))
    report = api.build(coll).report
    assert report["faces_by_sides"] == {4: 24}, report["faces_by_sides"]
    assert report["warnings"] == [], [w["message"] for w in report["warnings"]]
    assert report["max_normal_angle_deg"] < 1e-3
    creases = {name: (lo, hi) for name, lo, hi in report["crease_angles_deg"]}
    assert len(creases) == 2
    for lo, hi in creases.values():
        assert 50.0 < lo <= hi < 60.0 and hi - lo < 0.1, creases
    exact = json.loads(path.read_text())["exact_volume"]
    assert abs(report["enclosed_volume_half"] / exact - 1) < 1e-6, (report["enclosed_volume_half"], exact)


def test_pmb_barge_has_its_parallel_middle_body_and_floats_at_its_draft(examples_dir):
    coll = api.load_network(examples_dir / "pmb_barge.json")
    p = api.form_topology(coll, draft=8.0)["parameters"]
    assert (p["pmb_aft"], p["pmb_fwd"]) == pytest.approx((40.0, 60.0), abs=1e-9)
    assert p["bilge_radius"] == pytest.approx(2.0, abs=1e-6)  # Blender's float32 points
    assert (p["entrance_length"], p["run_length"]) == pytest.approx((40.0, 40.0), abs=1e-9)
    h = api.hydrostatics(coll, 8.0)
    # The midship section, exactly: 20 m × 8 m less the rise of floor's triangles (0.2 m over
    # 10 m) and the two bilge fillets, r²(cot(θ/2) − (π − θ)/2) each at the corner angle θ
    # between the bottom line and the side.
    import math

    theta = math.pi / 2 + math.atan(0.02)
    fillet = 2.0**2 * (1 / math.tan(theta / 2) - (math.pi - theta) / 2)
    assert h["midship_area"] == pytest.approx(2 * (10 * 8 - 10 * 0.2 / 2 - fillet), rel=1e-6)
    assert h["bwl"] == pytest.approx(20.0, abs=1e-6)
