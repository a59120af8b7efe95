"""batten_native through Python: values, errors as BattenError naming the curve, no panics."""

import math

import batten_native as bn
import numpy as np
import pytest


def cubic(name="c", pts=None, knots=None, weights=None):
    pts = np.array([[0, 0, 0], [1, 2, 0], [2, -1, 1], [3, 0, 0]], dtype=float) if pts is None else pts
    knots = np.array([0, 0, 0, 0, 1, 1, 1, 1], dtype=float) if knots is None else knots
    return bn.Curve(name, 3, knots, pts, weights)


def test_error_is_a_value_error():
    assert issubclass(bn.BattenError, ValueError)


def test_bezier_cubic_values_match_bernstein_form():
    c = cubic()
    t = np.linspace(0.0, 1.0, 11)
    p = np.array([[0, 0, 0], [1, 2, 0], [2, -1, 1], [3, 0, 0]], dtype=float)
    b = np.stack([(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t**2 * (1 - t), t**3], axis=1)
    np.testing.assert_allclose(c.evaluate(t), b @ p, atol=1e-14)
    d = c.derivatives(0.0)
    np.testing.assert_allclose(d[1], 3 * (p[1] - p[0]), atol=1e-12)


def test_large_evaluation_is_identical_to_small_batches():
    c = cubic()
    t = np.random.default_rng(1).random(100_000)
    whole = c.evaluate(t)
    parts = np.concatenate([c.evaluate(t[i : i + 1000]) for i in range(0, len(t), 1000)])
    assert np.array_equal(whole, parts)


def test_rational_circle_arc_length_and_nearest():
    s = math.sqrt(0.5)
    pts = np.array([[1, 0, 0], [1, 1, 0], [0, 1, 0], [-1, 1, 0], [-1, 0, 0]], dtype=float)
    c = bn.Curve("half circle", 2, np.array([0, 0, 0, 1, 1, 2, 2, 2.0]), pts, np.array([1, s, 1, s, 1]))
    assert c.arc_length(1e-12) == pytest.approx(math.pi, abs=1e-11)
    t, dist, p = c.nearest([0.3, 3.0, 0.0])
    assert dist == pytest.approx(math.hypot(0.3, 3.0) - 1.0, abs=1e-9)
    np.testing.assert_allclose(p, np.array([0.3, 3.0, 0]) / math.hypot(0.3, 3.0), atol=1e-7)
    lo, hi = c.bounding_box(1e-9)
    np.testing.assert_allclose(lo, [-1, 0, 0], atol=1e-8)
    np.testing.assert_allclose(hi, [1, 1, 0], atol=1e-8)


def test_split_and_insert_keep_shape():
    c = cubic()
    a, b = c.split(0.4)
    np.testing.assert_allclose(a.evaluate(np.array([0.4])), c.evaluate(np.array([0.4])), atol=1e-14)
    np.testing.assert_allclose(b.evaluate(np.array([0.7])), c.evaluate(np.array([0.7])), atol=1e-14)
    k = c.insert_knot(0.25, 2)
    assert len(k.control_points) == 6
    t = np.linspace(0, 1, 33)
    np.testing.assert_allclose(k.evaluate(t), c.evaluate(t), atol=1e-14)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"pts": np.array([[0, 0, 0], [1, np.nan, 0], [2, 0, 0], [3, 0, 0]])}, "non-finite"),
        ({"pts": np.array([[0, 0, 0], [1, np.inf, 0], [2, 0, 0], [3, 0, 0]])}, "non-finite"),
        ({"pts": np.zeros((3, 3)), "knots": np.array([0, 0, 0, 0, 1, 1, 1.0])}, "fewer than order 4"),
        ({"knots": np.array([0, 0, 0, 1, 0.5, 1, 1, 1.0])}, "knots decrease"),
        ({"weights": np.array([1, 0, 1, 1.0])}, "weight 1 is 0"),
        ({"weights": np.array([1, 1, -2, 1.0])}, "weight 2 is -2"),
        ({"knots": np.zeros(5)}, "knots given"),
    ],
)
def test_bad_curves_raise_named_errors(kwargs, fragment):
    with pytest.raises(bn.BattenError) as err:
        cubic(name="Station 7", **kwargs)
    assert "curve 'Station 7'" in str(err.value)
    assert fragment in str(err.value)


def test_bad_arguments_raise_clean_errors():
    c = cubic(name="sheer")
    with pytest.raises(bn.BattenError, match="curve 'sheer'.*outside the domain"):
        c.split(1.0)
    with pytest.raises(bn.BattenError, match="accuracy"):
        c.arc_length(0.0)
    with pytest.raises(bn.BattenError, match="non-finite"):
        c.nearest([np.nan, 0, 0])
    with pytest.raises(bn.BattenError, match="unknown role 'bulb'"):
        bn.Curve.from_poly("x", np.zeros((2, 3)) + [[0, 0, 0], [1, 0, 0]], role="bulb")
    with pytest.raises(
        bn.BattenError, match=r"curve .x.: points must have shape \(n, 3 or 4\), got \(4, 2\)"
    ):
        bn.Curve.from_poly("x", np.zeros((4, 2)))


def test_zero_length_and_duplicate_names():
    dot = bn.Curve.from_poly("dot", np.array([[1.0, 2, 3], [1, 2, 3]]))
    with pytest.raises(bn.BattenError, match="curve 'dot'.*zero length"):
        bn.check_lengths([dot], 1e-4)
    ok = bn.Curve.from_poly("ok", np.array([[0.0, 0, 0], [1, 0, 0]]))
    with pytest.raises(bn.BattenError, match="two curves are named 'ok'"):
        bn.network_to_json("n", [ok, ok])
    with pytest.raises(bn.BattenError, match="tolerance"):
        bn.check_lengths([ok], -1.0)


def test_json_round_trip_is_exact():
    c = cubic(name="a", weights=np.array([1, 0.3, 2.5, 1]))
    text = bn.network_to_json("net", [c, c.renamed(name="b", role="knuckle")])
    name, back, planes = bn.network_from_json(text)
    assert name == "net" and planes == []
    assert [x.name for x in back] == ["a", "b"]
    assert back[1].role == "knuckle"
    assert np.array_equal(back[0].control_points, c.control_points)
    assert np.array_equal(back[0].weights, c.weights)
    assert bn.network_to_json("net", back) == text
    flats = [[0.0, 1.0, 0.0, 16.1003], [0.0, 0.0, 1.0, 0.0]]
    with_planes = bn.network_to_json("net", back, flats)
    assert bn.network_from_json(with_planes)[2] == flats
    with pytest.raises(bn.BattenError, match="non-zero finite normal"):
        bn.network_to_json("net", back, [[0.0, 0.0, 0.0, 1.0]])


def test_a_panic_in_the_core_is_a_batten_error_not_a_crash():
    from batten_native import _native

    with pytest.raises(bn.BattenError, match="internal error in batten's core \\(boom at node 7\\)"):
        _native._panic_for_tests("boom at node 7")
    # and the module still works afterwards
    assert bn.Curve.from_poly("after", np.array([[0.0, 0, 0], [1, 0, 0]])).arc_length() == 1.0
