"""Hypothesis fuzzing of every ``batten_native`` entry point (issue 21): each call gives a
finite result or raises a ``BattenError`` subclass (never TypeError, OverflowError,
UnicodeError or a bare ValueError, never a crash or a hang), and an error about a curve names
it. Budget and time limits: ``fuzz_support``."""

from __future__ import annotations

import json

import batten_native as bn
import numpy as np
from fuzz_support import call, finite
from hypothesis import given
from hypothesis import strategies as st

# Text a caller may pass where batten wants a name, role or file text: ordinary, empty, bytes,
# or with a lone surrogate (not encodable as UTF-8).
good_names = st.text(st.characters(codec="utf-8"), min_size=1, max_size=8)
names = st.one_of(
    good_names,
    st.just(""),
    st.binary(max_size=6),
    good_names.map(lambda s: s + "\ud800"),
)
roles = st.one_of(st.sampled_from(bn.ROLES), names)

# Numbers from subnormal to overflowing, NaN and ±inf included, as Python floats or ints.
numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-1e3, 1e3),
    st.integers(-(10**20), 10**20),
    st.sampled_from([5e-324, 2.2250738585072014e-308, 1e-300, 1e200, 1e300, 1e7, 1e17]),
)
counts = st.one_of(st.integers(-3, 8), st.integers(-(2**70), 2**70))


def _as(kind: str, rows: list[list[float]]):
    """``rows`` as a Python list, a float64, float32 or int64 array (ints only when they fit)."""
    if kind == "list":
        return rows
    a = np.array(rows, dtype=np.float64).reshape(len(rows), -1) if rows else np.zeros((0, 3))
    if kind == "float32":
        with np.errstate(over="ignore"):
            return a.astype(np.float32)
    if kind == "int" and np.isfinite(a).all() and (np.abs(a) < 2**62).all():
        return a.astype(np.int64)
    return a


_THREE = st.just(3)
_FEW = st.integers(0, 9)


def arrays(width=_THREE, rows=_FEW, coords=numbers):
    """Point arrays of `rows` rows of `width` numbers in one of the kinds of :func:`_as`."""
    return st.tuples(
        st.sampled_from(["list", "float64", "float32", "int"]),
        rows,
        width,
    ).flatmap(
        lambda k: st.lists(st.lists(coords, min_size=k[2], max_size=k[2]), min_size=k[1], max_size=k[1]).map(
            lambda r, kind=k[0]: _as(kind, r)
        )
    )


# Ordinary geometry at an extreme scale and offset, so that curves mostly construct.
scales = st.sampled_from([1.0, 1e-3, 1e3, 1e-300, 1e-150, 1e150, 1e200, 5e-324])
offsets = st.sampled_from([0.0, 1e7, -1e7, 1e17])
unit = st.floats(-1, 1)


@st.composite
def curves(draw, name=good_names):
    """A curve that constructs: a polyline, a Blender NURBS layout or a Bézier spline of
    random points, scaled and moved."""
    n = draw(st.integers(2, 8))
    pts = np.array(draw(st.lists(st.lists(unit, min_size=3, max_size=3), min_size=n, max_size=n)))
    pts = pts * draw(scales) + draw(offsets)
    nm = draw(name)
    kind = draw(st.sampled_from(["poly", "nurbs", "bezier"]))
    if kind == "poly":
        made = call(bn.Curve.from_poly, nm, pts)
    elif kind == "nurbs":
        order = draw(st.integers(2, min(n, 6)))
        w = np.array(draw(st.lists(st.sampled_from([1.0, 0.5, 2.0, 1e-3, 1e3]), min_size=n, max_size=n)))
        made = call(
            bn.Curve.from_nurbs,
            nm,
            np.column_stack([pts, w]),
            order,
            endpoint=draw(st.booleans()),
            cyclic=draw(st.booleans()),
        )
    else:
        d = (np.roll(pts, -1, axis=0) - pts) / 3
        made = call(bn.Curve.from_bezier, nm, pts, pts - d, pts + d, cyclic=draw(st.booleans()))
    if isinstance(made, bn.BattenError):
        return draw(st.just(bn.Curve.from_poly(nm, [[0, 0, 0], [1, 0, 0]])))
    return made


def _clean(result, name=None) -> None:
    """A call's result is finite, or its BattenError names the curve `name`."""
    if isinstance(result, bn.BattenError):
        if isinstance(result, bn.CurveError) and name is not None and isinstance(name, str):
            assert result.curve == name, (result, name)
        if (
            name is not None
            and isinstance(name, str)
            and name
            and isinstance(result, bn.CurveError | bn.InvalidArgumentError)
        ):
            assert repr(name)[1:-1] in str(result) or name in str(result), (result, name)
        return
    assert finite(result), result


@given(
    name=names,
    degree=counts,
    knots=arrays(width=st.just(1), rows=st.integers(0, 14)),
    points=arrays(),
    weights=st.one_of(st.none(), arrays(width=st.just(1))),
    role=roles,
)
def test_curve_constructor(name, degree, knots, points, weights, role):
    k = np.asarray(knots, dtype=float).ravel() if len(knots) else knots
    w = None if weights is None else np.asarray(weights, dtype=float).ravel()
    _clean(call(bn.Curve, name, degree, k, points, w, role), name)


@given(
    name=names,
    points=arrays(width=st.sampled_from([2, 3, 4])),
    order=counts,
    endpoint=st.booleans(),
    bezier=st.booleans(),
    cyclic=st.booleans(),
    role=roles,
)
def test_from_nurbs_and_poly(name, points, order, endpoint, bezier, cyclic, role):
    _clean(call(bn.Curve.from_nurbs, name, points, order, endpoint, bezier, cyclic, role), name)
    _clean(call(bn.Curve.from_poly, name, points, cyclic, role), name)


@given(name=names, co=arrays(), left=arrays(), right=arrays(), cyclic=st.booleans(), role=roles)
def test_from_bezier(name, co, left, right, cyclic, role):
    _clean(call(bn.Curve.from_bezier, name, co, left, right, cyclic, role), name)


@given(
    c=curves(),
    ts=arrays(width=st.just(1), rows=st.integers(0, 5)),
    t=numbers,
    accuracy=numbers,
    point=st.lists(numbers, min_size=3, max_size=3),
    times=counts,
    angle=numbers,
)
def test_curve_methods(c, ts, t, accuracy, point, times, angle):
    ts = np.asarray(ts, dtype=float).ravel() if len(ts) else ts
    for fn, args in [
        (c.evaluate, (ts,)),
        (c.curvature, (ts,)),
        (c.derivatives, (t,)),
        (c.arc_length, (accuracy,)),
        (c.nearest, (point, accuracy)),
        (c.bounding_box, (accuracy,)),
        (c.split, (t,)),
        (c.insert_knot, (t, times)),
        (c.reversed, ()),
        (c.corners, (angle,)),
        (c.matching_layout, ()),
        (c.bezier_control_points, ()),
        (bn.fairness, (c,)),
    ]:
        _clean(call(fn, *args), c.name)


@given(c=curves(), name=st.one_of(st.none(), names), role=st.one_of(st.none(), roles))
def test_renamed(c, name, role):
    _clean(call(c.renamed, name, role), name if name is not None else c.name)


@st.composite
def fit_points(draw):
    """Points to fair: noisy arcs and lines, random points, duplicates, extreme sizes."""
    n = draw(st.integers(0, 120))
    kind = draw(st.sampled_from(["arc", "line", "random"]))
    s = np.linspace(0, 1, n)
    if kind == "arc":
        a = s * draw(st.floats(0.01, 6))
        pts = np.column_stack([np.cos(a), np.sin(a), 0 * a])
    elif kind == "line":
        pts = np.column_stack([s, 0.5 * s, -0.2 * s])
    else:
        pts = np.array(
            draw(st.lists(st.lists(unit, min_size=3, max_size=3), min_size=n, max_size=n))
        ).reshape(n, 3)
    noise = draw(st.sampled_from([0.0, 1e-6, 1e-3, 1e-2]))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    pts = pts + noise * rng.standard_normal(pts.shape)
    for i in draw(st.lists(st.integers(0, max(n - 1, 0)), max_size=3)):
        if n:
            pts = np.insert(pts, i, pts[i], axis=0)
    return pts * draw(scales) + draw(offsets)


optional_numbers = st.one_of(st.none(), numbers)


@given(
    name=names,
    points=st.one_of(fit_points(), arrays(rows=st.integers(0, 12))),
    degree=st.one_of(st.none(), counts),
    tolerance=optional_numbers,
    noise=optional_numbers,
    smoothing=optional_numbers,
    corners=st.one_of(st.none(), st.lists(counts, max_size=3)),
    corner_angle=optional_numbers,
    start=st.one_of(st.none(), st.tuples(numbers, numbers, numbers)),
    end=st.one_of(st.none(), st.tuples(numbers, numbers, numbers)),
    model_tolerance=numbers,
    iterations=st.one_of(st.none(), counts),
    role=roles,
)
def test_fair_points(
    name,
    points,
    degree,
    tolerance,
    noise,
    smoothing,
    corners,
    corner_angle,
    start,
    end,
    model_tolerance,
    iterations,
    role,
):
    result = call(
        bn.fair_points,
        name,
        points,
        degree=degree,
        tolerance=tolerance,
        noise=noise,
        smoothing_factor=smoothing,
        corners=corners,
        corner_angle_deg=corner_angle,
        start_tangent=start,
        end_tangent=end,
        model_tolerance=model_tolerance,
        max_parameter_iterations=iterations,
        role=role,
    )
    _clean(result, name)


@st.composite
def networks(draw):
    """A few curves with distinct names: a jittered grid of polylines or random curves."""
    if draw(st.booleans()):
        m, k = draw(st.integers(2, 4)), draw(st.integers(2, 4))
        x, z = np.meshgrid(np.linspace(0, 1, m), np.linspace(0, 1, k), indexing="ij")
        y = 0.3 * (1 - (2 * x - 1) ** 2) * (1 - z**2)
        grid = np.stack([x, y, z], axis=-1)
        grid = grid + draw(st.sampled_from([0.0, 1e-9, 1e-5, 1e-2])) * np.random.default_rng(
            draw(st.integers(0, 99))
        ).standard_normal(grid.shape)
        grid = grid * draw(scales) + draw(offsets)
        rows = [grid[i] for i in range(m)] + [grid[:, j] for j in range(k)]
        cs = [call(bn.Curve.from_poly, f"c{i}", r) for i, r in enumerate(rows)]
        return [c for c in cs if isinstance(c, bn.Curve)]
    return [c.renamed(f"c{i}") for i, c in enumerate(draw(st.lists(curves(), max_size=5)))]


@given(curves=networks(), tolerance=numbers, resolution=st.one_of(st.none(), counts), name=names)
def test_network_calls(curves, tolerance, resolution, name):
    _clean(call(bn.topology, curves, tolerance))
    _clean(call(bn.check_lengths, curves, tolerance))
    _clean(call(bn.build_surface, curves, tolerance, resolution))
    text = call(bn.network_to_json, name, curves)
    _clean(text)
    if isinstance(text, str):
        back = call(bn.network_from_json, text)
        assert not isinstance(back, bn.BattenError), back
        assert back[0] == name and [c.name for c in back[1]] == [c.name for c in curves]


@given(
    curves=networks(),
    capture=numbers,
    with_data=st.booleans(),
    data=arrays(),
    tolerance=numbers,
    knuckles=arrays(),
    name=names,
)
def test_wireframe_calls(curves, capture, with_data, data, tolerance, knuckles, name):
    """Snapping to nodes (with or without data per curve), chines from knuckles, and a named
    build: finite results or a BattenError."""
    points = [data] * len(curves) if with_data else None
    _clean(call(bn.snap_to_nodes, curves, capture, points, tolerance if with_data else None))
    _clean(call(bn.chines_from_knuckles, curves, [knuckles] * len(curves), tolerance))
    _clean(call(bn.build_surface, curves, tolerance, None, name))


@given(
    base=networks(),
    cut=st.integers(0, 10**6),
    insert=st.one_of(
        st.text(max_size=3), st.sampled_from(['"', "{", "]", "null", "1e999", "-0", "\ufeff", "\ud800"])
    ),
    junk=st.one_of(st.text(max_size=20), st.binary(max_size=8)),
)
def test_network_from_json_text(base, cut, insert, junk):
    text = bn.network_to_json("n", base)
    i = cut % (len(text) + 1)
    _clean(call(bn.network_from_json, text[:i] + insert + text[i:]))
    _clean(call(bn.network_from_json, junk))
    data = json.loads(text)
    if data["curves"]:
        data["curves"][0]["degree"] = cut - 5
        _clean(call(bn.network_from_json, json.dumps(data)))
