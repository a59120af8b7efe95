"""``same_curves``: the check a kept surface makes on every hydrostatics call, in place of
comparing the curves' network JSON — equal exactly when that JSON would be."""

from batten_native import Curve, network_to_json, same_curves

KNOTS = [0, 0, 0, 0, 1, 1, 1, 1]
POINTS = [[0, 0, 0], [1, 0.5, 0], [2, 0.5, 0], [3, 0, 0]]


def _curve(name="st1", points=POINTS, role="free", weights=None):
    return Curve(name, 3, KNOTS, points, weights, role)


def test_the_same_curves_are_the_same_and_any_change_is_seen():
    a = [_curve(), _curve("wl", role="knuckle")]
    assert same_curves(a, [_curve(), _curve("wl", role="knuckle")])
    moved = [list(p) for p in POINTS]
    moved[1][1] += 1e-12
    for other in (
        [_curve(points=moved), a[1]],
        [_curve("st2"), a[1]],
        [_curve(role="knuckle"), a[1]],
        [_curve(weights=[1, 2, 1, 1]), a[1]],
        a[:1],
        a[::-1],
    ):
        assert not same_curves(a, other)
        assert network_to_json("n", a) != network_to_json("n", other)
    assert same_curves([], [])
