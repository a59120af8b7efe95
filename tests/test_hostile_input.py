"""Hostile input found by fuzzing (issue 21), each a clear BattenError naming the curve or
the file and the parameter, or a finite result: the error-message and argument-type cases."""

import json

import batten.api as api
import batten_native as bn
import bpy
import numpy as np
import pytest


def test_array_likes_are_accepted_as_the_stub_promises():
    """Python lists, ints and float32 arrays are converted (they raised TypeError before)."""
    c = bn.Curve.from_poly("p", [[0, 0, 0], [1, 2, 2]])
    assert c.arc_length() == pytest.approx(3.0, abs=1e-12)
    assert np.allclose(c.evaluate([0.5]), [[0.5, 1.0, 1.0]])
    assert np.allclose(c.evaluate(np.array([1.0], dtype=np.float32)), [[1, 2, 2]])
    q = bn.Curve("q", 1, [0, 0, 1, 1], [[0, 0, 0], [3, 4, 0]])
    assert q.arc_length() == pytest.approx(5.0, abs=1e-12)
    pts = [[x, 0.1 * x * x, 0] for x in range(8)]
    curve, report = bn.fair_points("st", pts, tolerance=1e-3)
    assert report["max_deviation"] <= 1e-3 and np.isfinite(curve.control_points).all()


def test_model_tolerance_zero_names_the_curve_and_the_parameter():
    with pytest.raises(bn.InvalidArgumentError, match=r"curve 'st 4': model_tolerance 0 must be"):
        bn.fair_points("st 4", np.random.default_rng(1).random((20, 3)), model_tolerance=0)


def test_order_one_says_order_not_degree_zero():
    with pytest.raises(bn.CurveError, match=r"curve 'n': order 1 is outside 2\.\.=16") as e:
        bn.Curve.from_nurbs("n", [[0, 0, 0], [1, 0, 0]], 1)
    assert e.value.curve == "n"


def test_corner_angles_are_printed_in_degrees():
    with pytest.raises(bn.FairError, match="the corner angle 200° must lie strictly between 0° and 180°"):
        bn.fair_points("st", np.random.default_rng(2).random((20, 3)), corner_angle_deg=200)


@pytest.mark.parametrize(
    ("version", "says"),
    [(0, "version 0 is not a batten network version"), (99, "version 99 is newer than this batten reads")],
)
def test_a_version_below_one_is_not_called_newer(tmp_path, version, says):
    f = tmp_path / "net.json"
    f.write_text(json.dumps({"format": "batten-network", "version": version, "name": "n", "curves": []}))
    with pytest.raises(bn.NetworkFileError, match=says):
        api.read_network(f)


def test_a_network_file_that_is_not_utf8_is_a_network_file_error(tmp_path):
    f = tmp_path / "latin1.json"
    f.write_bytes('{"name": "Ægir"}'.encode("latin-1"))
    with pytest.raises(bn.NetworkFileError, match=r"network file '.*latin1.json': not UTF-8 text"):
        api.read_network(f)


def test_a_byte_order_mark_is_read_past(tmp_path, examples_dir):
    f = tmp_path / "bom.json"
    f.write_bytes(b"\xef\xbb\xbf" + (examples_dir / "wigley.json").read_bytes())
    name, curves = api.read_network(f)
    assert name == "wigley" and len(curves) == 14


def _cubic():
    return bn.Curve("c", 3, [0, 0, 0, 0, 1, 1, 1, 1], [[0, 0, 0], [1, 1, 0], [2, -1, 0], [3, 0, 0]])


def test_parameters_outside_the_domain_are_clamped_as_documented():
    """evaluate([2.0]) on [0, 1] is the end point, not the extrapolated cubic (6, 24, −12)."""
    c = _cubic()
    assert np.array_equal(c.evaluate([2.0, -1.0]), c.evaluate([1.0, 0.0]))
    assert np.array_equal(c.derivatives(2.0), c.derivatives(1.0))
    pts, kappa = c.curvature([5.0])
    assert np.array_equal(pts, c.evaluate([1.0])) and np.isfinite(kappa).all()


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf")])
def test_a_non_finite_parameter_is_an_error_naming_the_curve(bad):
    c = _cubic()
    for call in (lambda: c.evaluate([0.5, bad]), lambda: c.derivatives(bad), lambda: c.curvature([bad])):
        with pytest.raises(bn.CurveError, match=r"curve 'c': parameter .* is not a finite number") as e:
            call()
        assert e.value.curve == "c"


def test_a_length_check_finer_than_f64_resolves_is_refused_not_frozen(examples_dir, tmp_path):
    """check_lengths on the frigate's 120 m deck at tolerance 1e-11 (an arc-length accuracy of
    1e-14 m) froze Blender; it is now refused at once, naming the curve."""
    _, curves = api.read_network(examples_dir / "frigate_network.json")
    deck = [c for c in curves if c.name == "deck"]
    refused = r"curve 'deck': accuracy 1\.000e-14 m is finer than f64 resolves"
    with pytest.raises(bn.CurveError, match=refused):
        bn.check_lengths(deck, 1e-11)
    bn.check_lengths(deck, 1e-7)  # the smallest tolerance the panel offers is fine
    hull = api.load_network(examples_dir / "frigate_network.json")
    with pytest.raises(bn.CurveError, match="finer than f64 resolves"):
        api.export_network(hull, tmp_path / "frigate.json", tolerance=1e-11)
    assert not (tmp_path / "frigate.json").exists()


def test_lengths_that_overflow_are_errors_not_hangs():
    with pytest.raises(bn.CurveError, match="curve 'big': the curve's length is not finite"):
        bn.Curve.from_poly("big", [[0, 0, 0], [1e200, 0, 0]]).arc_length()
    with pytest.raises(bn.CurveError, match="curve 'big': accuracy .* is finer than f64 resolves"):
        bn.Curve.from_poly("big", [[0, 0, 0], [1e150, 0, 0]]).arc_length()


def test_results_that_overflow_are_errors_naming_the_curve(examples_dir):
    """Never an infinite or NaN figure as if it were a result (issue 21)."""
    cubic = _cubic()
    with pytest.raises(bn.CurveError, match="curve 'c': the distance to the query point overflows") as e:
        cubic.nearest([1e300] * 3)
    assert e.value.curve == "c"
    assert cubic.nearest([3, 1, 0])[1] == pytest.approx(1.0)  # an ordinary query is unchanged
    huge = bn.Curve("huge", 3, cubic.knots, cubic.control_points * 1e200)
    with pytest.raises(bn.CurveError, match="curve 'huge': its fairness figures overflow"):
        bn.fairness(huge)
    _, curves = api.read_network(examples_dir / "wigley.json")
    scaled = [
        bn.Curve(c.name, c.degree, c.knots, c.control_points * 1e150, c.weights, c.role) for c in curves
    ]
    with pytest.raises(bn.NoSurfaceError, match="the surface's figures overflow f64 \\(volume inf"):
        bn.build_surface(scaled, 1e146, 4)


def test_weights_that_overflow_or_underflow_are_refused():
    """w·P must be representable: evaluate returned inf, and network_to_json wrote null."""
    pts = [[0, 0, 0], [1e300, 0, 0], [2, 0, 0]]
    with pytest.raises(
        bn.CurveError, match="curve 'w': control point 1 times its weight is not representable"
    ):
        bn.Curve("w", 2, [0, 0, 0, 1, 1, 1], pts, [1.0, 1e10, 1.0])
    with pytest.raises(bn.CurveError, match="control point 0 times its weight"):
        bn.Curve("w", 2, [0, 0, 0, 1, 1, 1], [[1, 0, 0], [1, 1, 0], [2, 0, 0]], [1e-320, 1.0, 1.0])


@pytest.mark.parametrize("edit", ["split", "insert_knot"])
def test_an_edit_at_the_first_subnormal_is_refused(edit):
    """split(5e-324) and insert_knot(5e-324, 3) made curves that evaluate to NaN."""
    c = _cubic()
    t = float(np.nextafter(0, 1))
    with pytest.raises(bn.CurveError, match="curve 'c': an edit at parameter 5e-324 leaves a knot span"):
        c.split(t) if edit == "split" else c.insert_knot(t, 3)


def test_a_reversal_that_rounds_knots_together_is_refused():
    """Knots ending at 1e17: a + b − u rounds 0.3 onto 1e17, the curve fell apart (NaN)."""
    pts = [[0, 0, 0], [1, 1, 0], [2, -1, 0], [3, 0, 0], [4, 0, 0]]
    c = bn.Curve("r", 3, [0, 0, 0, 0, 0.3, 1e17, 1e17, 1e17, 1e17], pts)
    with pytest.raises(bn.CurveError, match="curve 'r': knot 100000000000000000 is repeated 5 times") as e:
        c.reversed()
    assert e.value.curve == "r"
    ok = bn.Curve("ok", 3, [0, 0, 0, 0, 0.3, 1, 1, 1, 1], pts).reversed()
    assert np.allclose(ok.knots, [0, 0, 0, 0, 0.7, 1, 1, 1, 1])


def test_network_text_errors_name_the_curve_or_say_what_is_wrong(examples_dir):
    text = (examples_dir / "wigley.json").read_text()
    assert bn.network_from_json("\ufeff" + text)[0] == "wigley"  # a byte-order mark is read past
    with pytest.raises(bn.NetworkFileError, match=r"not valid JSON \(trailing characters"):
        bn.network_from_json(text + "x")
    data = json.loads(text)
    del data["curves"][2]["points"]
    with pytest.raises(bn.NetworkFileError, match=r"curve 2 \('station -12\.5'\): missing field `points`"):
        bn.network_from_json(json.dumps(data))


@pytest.mark.parametrize(
    ("call", "says"),
    [
        (
            lambda: bn.fair_points("st", np.zeros((9, 3)), degree=-1),
            "curve 'st': degree -1 must not be negative",
        ),
        (
            lambda: bn.fair_points("st", np.zeros((9, 3)), corners=[-2]),
            "curve 'st': corner index -2 must not be",
        ),
        (lambda: bn.Curve("c", -3, [0, 1], [[0, 0, 0]]), "curve 'c': degree -3 must not be negative"),
        (lambda: bn.Curve.from_nurbs("n", [[0, 0, 0], [1, 0, 0]], -4), "curve 'n': order -4 must not be"),
        (lambda: _cubic().insert_knot(0.5, -1), "curve 'c': times -1 must not be negative"),
        (lambda: bn.build_surface([_cubic()], 1e-4, -8), "resolution -8 must not be negative"),
    ],
)
def test_negative_counts_are_invalid_arguments_not_overflow_errors(call, says):
    """A negative int for a count raised OverflowError from Python's conversion."""
    with pytest.raises(bn.InvalidArgumentError, match=says):
        call()


def test_dense_noise_is_neither_corners_nor_disorder():
    """30,000 points along a 2 m arc with 1 mm noise (0.07 mm apart): no corner at the default
    45 degrees and 5 mm tolerance (there were thousands), not refused as out of order (it
    was); the same points shuffled are refused, naming the curve."""
    rng = np.random.default_rng(30)
    m = 30_000
    a = np.linspace(0.0, np.pi / 2, m)
    r = 4.0 / np.pi + np.concatenate([[0.0], rng.normal(0.0, 1e-3, m - 2), [0.0]])
    pts = np.column_stack([r * np.cos(a), r * np.sin(a), np.zeros(m)])
    curve, report = bn.fair_points("scan", pts, tolerance=5e-3)
    assert report["corners"] == []
    assert len(curve.control_points) < 20, "far fewer control points than points"
    assert report["max_deviation"] <= 5e-3 and np.isfinite(curve.control_points).all()
    with pytest.raises(bn.FairError, match="curve 'scan': the points are not in order"):
        bn.fair_points("scan", pts[rng.permutation(2000)], tolerance=5e-3)


# Found by the fuzz suite (tests/plain/test_fuzz_native.py, rust/batten-core/tests/fuzz).


@pytest.mark.parametrize(
    ("call", "says"),
    [
        (
            lambda: bn.Curve.from_poly(b"st", [[0, 0, 0], [1, 0, 0]]),
            "the curve name must be text \\(str\\), not bytes",
        ),
        (
            lambda: bn.Curve.from_poly("st\ud800", [[0, 0, 0], [1, 0, 0]]),
            "the curve name 'st\\\\ud800' is not valid Unicode text",
        ),
        (
            lambda: bn.Curve.from_poly("st", [[0, 0, 0], [1, 0, 0]], role=b"keel"),
            "curve 'st': role must be text",
        ),
        (lambda: _cubic().renamed(name="\udcff"), "curve 'c': new name '\\\\udcff' is not valid Unicode"),
        (lambda: bn.fair_points(b"st", np.zeros((9, 3))), "the curve name must be text"),
        (
            lambda: bn.fair_points("st", np.zeros((9, 3)), role="\ud800"),
            "curve 'st': role '\\\\ud800' is not",
        ),
        (lambda: bn.network_to_json(b"net", [_cubic()]), "the network name must be text"),
        (lambda: bn.network_from_json(b"{}"), "the network text must be text \\(str\\), not bytes"),
    ],
)
def test_text_that_is_bytes_or_holds_a_lone_surrogate_is_an_invalid_argument(call, says):
    """They raised TypeError and UnicodeEncodeError."""
    with pytest.raises(bn.InvalidArgumentError, match=says):
        call()


@pytest.mark.parametrize(
    ("call", "says"),
    [
        (lambda: bn.Curve("c", 1, [0, 0, 1, 1], []), "curve 'c': points must be a 2-D array of numbers"),
        (lambda: bn.Curve.from_poly("p", [[0, 0, 0], [1, 0]]), "curve 'p': points must be a 2-D array"),
        (
            lambda: bn.Curve("c", 1, [[0, 0], [1, 1]], [[0, 0, 0], [1, 0, 0]]),
            "curve 'c': knots must be a 1-D array",
        ),
        (lambda: _cubic().evaluate([[0.5]]), "curve 'c': t must be a 1-D array"),
        (
            lambda: bn.Curve("c", 2**70, [0, 1], [[0, 0, 0]]),
            "curve 'c': degree 1180591620717411303424 must be a whole",
        ),
        (lambda: _cubic().insert_knot(0.5, 2**64), "curve 'c': times 18446744073709551616 must be a whole"),
        (lambda: bn.fair_points("st", np.zeros((9, 3)), corners=[2**65]), "curve 'st': corner index"),
        (lambda: bn.build_surface([_cubic()], 1e-4, 2**63), "resolution 9223372036854775808 must be a whole"),
    ],
)
def test_points_of_the_wrong_shape_and_counts_beyond_64_bits_are_invalid_arguments(call, says):
    """An empty or ragged list raised TypeError ("dimensionality mismatch"); 2**70 OverflowError."""
    with pytest.raises(bn.InvalidArgumentError, match=says):
        call()


def test_a_knot_span_of_subnormals_is_refused_at_construction():
    """Knots [0, 0, 4e-323, 4e-323] made a curve that evaluates to NaN (and bounding_box panicked)."""
    with pytest.raises(
        bn.CurveError, match="curve 'tiny': knot span 1 is 4e-323 wide, too short for f64"
    ) as e:
        bn.Curve("tiny", 1, [0, 0, 4e-323, 4e-323], [[0, 0, 0], [1, 0, 0]])
    assert e.value.curve == "tiny"


def test_derivatives_and_curvature_that_overflow_are_errors_naming_the_curve():
    """Weights 1e-200 beside 0.1 gave C'' = -inf and a NaN curvature."""
    c = bn.Curve("w", 1, [0, 0.01, 0.02, 0.03], [[0, 0, 0], [0, 0, 0.75]], [1e-200, 0.1])
    with pytest.raises(
        bn.CurveError, match="curve 'w': its derivatives or curvature at parameter 1e-2 overflow"
    ):
        c.derivatives(0.01)
    with pytest.raises(
        bn.CurveError, match="curve 'w': its derivatives or curvature at parameter 1e-2 overflow"
    ):
        c.curvature([0.015, 0.01])
    assert np.isfinite(_cubic().derivatives(0.5)).all()


def test_a_length_whose_speed_is_rougher_than_the_accuracy_is_an_error_not_a_hang():
    """Weights 1e-200 beside 1e200 at 1e17 m: the quadrature halved to depth 40 everywhere."""
    pts = [[1e17, 1e17, z] for z in (0.1, 0.0033, 0.1, 0.015, 0.0)]
    c = bn.Curve("rough", 2, [0, 0, 0, 0.01, 0.02, 0.03, 0.03, 0.03], pts, [7.7, 1e-200, 4.85, 1e200, 1e200])
    try:
        assert np.isfinite(c.arc_length(1.0))
    except bn.CurveError as e:
        assert "curve 'rough': its length does not settle to the accuracy 1e0 m" in str(e)


@pytest.mark.parametrize("path", [b"/nonexistent/net.json", "/nonexistent/\udcffnet.json"])
def test_a_path_as_bytes_is_a_path(path):
    """bytes paths raised TypeError from pathlib; they name a file like a str does."""
    with pytest.raises(bn.NetworkFileError, match="network file '/nonexistent/.*net.json': No such file"):
        api.read_network(path)


def test_a_path_with_a_lone_surrogate_is_an_invalid_argument(tmp_path):
    """It raised UnicodeEncodeError from open()."""
    with pytest.raises(
        bn.InvalidArgumentError, match="network file path '.*\\\\ud800.json' cannot be a file name"
    ):
        api.read_network(tmp_path / "\ud800.json")
    with pytest.raises(bn.InvalidArgumentError, match="section file path .* cannot be a file name"):
        api.import_sections(str(tmp_path / "\ud800.csv"))


def test_a_weight_at_the_normal_limit_is_refused_before_an_edit_loses_it():
    """A weight of 2.2e-308 was accepted; knot insertion blended it below the limit and the
    Bézier decomposition panicked inside bounding_box."""
    pts = [[0, 0, 0], [1, 1, 0], [2, 0, 0]]
    with pytest.raises(
        bn.CurveError, match=r"curve 'w': weight 1 is 2\.2250738585072014e-308, below the smallest"
    ):
        bn.Curve("w", 2, [0, 0, 0, 1, 1, 1], pts, [1.0, 2.2250738585072014e-308, 1.0])
    assert bn.Curve("w", 2, [0, 0, 0, 1, 1, 1], pts, [1.0, 1e-200, 1.0]).bounding_box()[1][0] == 2.0


def test_a_section_file_whose_name_is_not_utf8_draws_a_collection(tmp_path):
    """A file named with the byte 0xff (Python: 'x\\udcff.csv') raised TypeError from
    bpy.data.collections.new (its stem names the collection)."""
    f = tmp_path / "x\udcff.csv"
    f.write_text("st,0,0,0\nst,0,0.5,1\nst,0,1.5,2\nst,0,3,3\n")
    coll, reports = api.import_sections(f)
    assert coll.name == "x\ufffd" and [r["curve"] for r in reports] == ["st"]


def test_a_curve_beyond_float32_is_refused_before_blender_draws_it_as_inf(tmp_path):
    """Found by the api fuzz test: sections beyond 3.4e38 m were drawn with float32 overflow (inf)."""
    f = tmp_path / "huge.csv"
    f.write_text("".join(f"st,{x * 1e39},{x * x * 1e38},0\n" for x in range(6)))
    with pytest.raises(
        bn.CurveError, match=r"curve 'st': a control point coordinate or weight \(.*\) is beyond"
    ) as e:
        api.import_sections(f, tolerance=1e36)
    assert e.value.curve == "st" and "huge" not in bpy.data.collections


def test_fairness_of_a_slow_parametrisation_is_finite_and_the_same():
    """∫κ²ds and κ do not depend on the parametrisation: a cubic over [0, 1e60] (speed 1e-60,
    whose cube and sixth power underflow) gives the figures of the same cubic over [0, 1]."""
    pts = [[0, 0, 0], [1, 1, 0], [2, 1, 0], [3, 0, 0]]
    unit = bn.fairness(bn.Curve("c", 3, [0, 0, 0, 0, 1, 1, 1, 1], pts))
    slow = bn.fairness(bn.Curve("c", 3, [0, 0, 0, 0, 1e60, 1e60, 1e60, 1e60], pts))
    for key in ("fairness_energy", "max_curvature"):
        assert np.isfinite(slow[key]) and slow[key] == pytest.approx(unit[key], rel=1e-9), key


@pytest.mark.parametrize(
    ("points", "kwargs"),
    [
        # Found by the fuzz suite: 5 mm asked of points 4.5e14 m out (f64 resolves 1.6 m there)
        # was reported as a fit 0.5 m off.
        ([[0.0, 0.0, 451248538562651.0], [0, 0, 0], [0, 0, 1], [0, 0, 0]], {"tolerance": 5e-3}),
        # Noise of 1e-82 m on an arc at x = -976 m (f64 resolves 3.5e-12 m): a NaN energy.
        (
            np.column_stack(
                [np.cos(np.linspace(0, 4.8, 174)), np.sin(np.linspace(0, 4.8, 174)), np.zeros(174)]
            )
            * 1e-79
            + [-976.43, 0, 0],
            {"noise": 1e-82, "degree": 2, "corner_angle_deg": None, "model_tolerance": 1e-300},
        ),
    ],
)
def test_a_closeness_finer_than_f64_resolves_is_refused(points, kwargs):
    with pytest.raises(bn.FairError, match="curve 'st': the asked closeness .* is finer than f64 resolves"):
        bn.fair_points("st", points, **kwargs)


def test_points_too_far_for_squared_distances_are_refused():
    """Found by the fuzz suite: points 4.5e154 m out gave a report with an infinite residual."""
    far = [[0, 0, 0], [0, -4.5e154, 0], [0, 0, 0], [0, -4.5e154, 0], [0, 0, 0]]
    with pytest.raises(bn.FairError, match="curve 'st': point 1 is more than 1e150 m from the origin"):
        bn.fair_points("st", far, tolerance=1e148, degree=2, model_tolerance=1e-3)


@pytest.mark.parametrize(
    ("planes", "says"),
    [
        ([[0.0, 0.0, 0.0, 1.0]], "non-zero normal"),
        ([[0.0, 1.0, 0.0]], "four finite numbers"),
        ([[0.0, 1.0, 0.0, float("nan")]], "four finite numbers"),
        (3.0, "must be a list of"),
    ],
)
def test_a_bad_tangent_plane_on_the_collection_is_an_invalid_argument_and_builds_nothing(
    examples_dir, planes, says
):
    coll = api.load_network(examples_dir / "wigley.json", collection="bad planes")
    coll[api.TANGENT_PLANES_PROPERTY] = planes
    with pytest.raises(
        api.InvalidArgumentError, match=f"collection 'bad planes': batten_tangent_planes.*{says}"
    ):
        api.build(coll)
    assert f"{coll.name} surface" not in bpy.data.objects, "nothing drawn"
    # The binding refuses it too, as an invalid argument, not a crash.
    with pytest.raises(bn.BattenError):
        bn.build_surface(api.read_curves(coll), tangent_planes=[[0.0, 0.0, 0.0, 1.0]])
