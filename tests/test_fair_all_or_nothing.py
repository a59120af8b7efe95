"""Fair Curves on a selection is all or nothing: when one curve fails, none is changed."""

import batten.api as api
import bpy
import numpy as np
import pytest
from batten.bridge import curves_out
from helpers import new_bezier, new_curve
from operator_runs import execute
from test_fairing import noisy_arc

#: Fair tolerance (m) that the arcs' 1 cm noise allows.
TOLERANCE = 0.05


def _state(obj) -> list:
    """Everything of a curve object's splines that fairing would change, exactly."""
    out = []
    for s in obj.data.splines:
        if s.type == "BEZIER":
            n = len(s.bezier_points)
            arrays = {k: np.empty(3 * n, dtype=np.float32) for k in ("co", "handle_left", "handle_right")}
            for k, a in arrays.items():
                s.bezier_points.foreach_get(k, a)
        else:
            arrays = {"co": np.empty(4 * len(s.points), dtype=np.float32)}
            s.points.foreach_get("co", arrays["co"])
        flags = (s.type, s.order_u, s.use_endpoint_u, s.use_bezier_u)
        out.append((flags, {k: a.tolist() for k, a in arrays.items()}))
    return out


@pytest.fixture
def three_curves():
    """Two curves that fair well (a polyline and a drawn Bezier curve) and, third by name, a
    polyline whose points are out of order (the fit fails), all selected."""
    a = new_curve("a wl", "POLY", noisy_arc(40, seed=1))
    co = np.array([[0.0, 0, 0], [5, 2, 0], [10, 0, 0]])
    b = new_bezier("b sheer", co, co - [1.5, 0, 0], co + [1.5, 0, 0])
    pts = noisy_arc(40, r=8.0, seed=2)
    c = new_curve("c scrambled", "POLY", pts[np.random.default_rng(0).permutation(len(pts))])
    for obj in (a, b, c):
        obj.select_set(True)
    bpy.context.view_layer.objects.active = a
    bpy.context.scene.batten.fair_tolerance = TOLERANCE
    return a, b, c


def test_api_fair_curves_fits_all_or_changes_nothing(three_curves):
    before = [_state(o) for o in three_curves]
    with pytest.raises(api.FairError, match="curve 'c scrambled'"):
        api.fair_curves(three_curves, tolerance=TOLERANCE)
    assert [_state(o) for o in three_curves] == before, "the first two are left as they were"
    reports = api.fair_curves(three_curves[:2], tolerance=TOLERANCE)
    assert [r["object"] for r in reports] == ["a wl", "b sheer"]
    assert all(o.data.splines[0].type == "NURBS" for o in three_curves[:2]), "both faired"


def test_fair_operator_is_all_or_nothing(three_curves):
    from batten import operators

    before = [_state(o) for o in three_curves]
    with pytest.raises(RuntimeError, match="curve 'c scrambled': the points are not in order"):
        bpy.ops.batten.fair_curves()
    assert [_state(o) for o in three_curves] == before, "the first two are left as they were"
    # The operator's own result (bpy.ops turns the error report into RuntimeError).
    result, reports = execute(operators.BATTEN_OT_fair_curves, bpy.context)
    assert result == {"CANCELLED"}
    assert [kind for kind, _ in reports] == [{"ERROR"}]
    assert [_state(o) for o in three_curves] == before
    three_curves[2].select_set(False)
    assert bpy.ops.batten.fair_curves() == {"FINISHED"}
    assert [o.data.splines[0].type for o in three_curves] == ["NURBS", "NURBS", "POLY"]


def test_a_write_failing_midway_restores_what_was_written(three_curves, monkeypatch):
    """The fits all succeed, but writing the third object fails after the first two were
    written (and the third half cleared): every object gets its curve data back."""
    a, b, _ = three_curves
    c = new_curve("c ok", "POLY", noisy_arc(30, r=6.0, seed=3))
    objs = [a, b, c]
    a.data.materials.append(bpy.data.materials.new("paint"))
    before = [_state(o) for o in objs]
    names = [o.data.name for o in objs]
    n_curves = len(bpy.data.curves)
    real = curves_out.write_spline
    calls = []

    def failing(data, spec, to_local=None):
        calls.append(data.name)
        if len(calls) == 3:
            raise RuntimeError("disk on fire")
        return real(data, spec, to_local)

    monkeypatch.setattr(curves_out, "write_spline", failing)
    with pytest.raises(RuntimeError, match="disk on fire"):
        api.fair_curves(objs, tolerance=TOLERANCE)
    assert calls == names, "one spline each; the third object was being written"
    assert [_state(o) for o in objs] == before
    assert [o.data.name for o in objs] == names, "under their own names"
    assert a.data.materials[0].name == "paint"
    assert len(bpy.data.curves) == n_curves, "no copy is left behind"
    monkeypatch.undo()
    api.fair_curves(objs, tolerance=TOLERANCE)
    assert len(bpy.data.curves) == n_curves and [o.data.name for o in objs] == names
