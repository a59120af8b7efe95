"""Dragging a form vertex with the mouse (seed 002 §7.2, interactive): a click picks the
numbered vertex under it, the mouse moves it in the view plane or along an axis, a click makes
the change into a copy exactly as the typed move would; Esc, a still vertex and a move the hull
cannot take change nothing. The view is a stand-in orthographic side view (headless Blender has
no 3D viewport); the operator's own modal code runs on it."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import form_drag, overlay
from batten.form_drag import BATTEN_OT_drag_form_vertex, constrained, pick_vertex
from batten.form_operators import BATTEN_OT_measure_form
from operator_runs import execute, stand_in
from test_form import _points

#: The stand-in view: looking at the port side (along −y), 10 pixels a metre, (0, 0) at (100, 100).
SCALE, ORIGIN = 10.0, 100.0


class _Region:
    x = y = 0


class _Event:
    def __init__(self, type: str, at=(0.0, 0.0), value: str = "PRESS") -> None:
        self.type, self.value = type, value
        self.mouse_x, self.mouse_y = at


def _at(p) -> tuple[float, float]:
    return (ORIGIN + SCALE * p[0], ORIGIN + SCALE * p[2])


@pytest.fixture
def side_view(monkeypatch):
    monkeypatch.setattr(form_drag, "to_region", lambda view, p: _at(p))
    monkeypatch.setattr(
        form_drag,
        "to_world",
        lambda view, mouse, depth: np.array(
            [(mouse[0] - ORIGIN) / SCALE, float(depth[1]), (mouse[1] - ORIGIN) / SCALE]
        ),
    )
    return (_Region(), None)


def _drag(context, view, events):
    op, reports = stand_in(BATTEN_OT_drag_form_vertex)
    op.begin(context, view)
    results = [op.modal(context, e) for e in events]
    return results, reports


def _by_source(copy) -> dict:
    """A copy's spline points by the original object each curve object stands for."""
    return {
        obj["batten_transform_source"]: np.asarray(api.read_curves(obj)[0].control_points).round(12).tolist()
        for obj in copy.objects
    }


def _measured(coll):
    bpy.context.scene.batten.source = coll
    assert execute(BATTEN_OT_measure_form, bpy.context)[0] == {"FINISHED"}
    return json.loads(bpy.context.scene.batten.last_form)["vertices"]


def test_pick_and_constrain():
    points = [(0.0, 0.0), None, (30.0, 40.0), (5.0, 3.0)]
    assert pick_vertex(points, (4.0, 4.0)) == 3, "the nearest"
    assert pick_vertex(points, (29.0, 41.0)) == 2
    assert pick_vertex(points, (100.0, 100.0)) is None, "none within the radius"
    assert pick_vertex([None], (0.0, 0.0)) is None, "a point behind the view is not picked"
    assert constrained((1.0, 2.0, 3.0), None).tolist() == [1.0, 2.0, 3.0]
    assert constrained((1.0, 2.0, 3.0), "Y").tolist() == [0.0, 2.0, 0.0]


def test_drag_the_bow_forward_into_a_copy(barge, side_view):  # noqa: F811
    settings = bpy.context.scene.batten
    settings.last_form = ""
    assert not BATTEN_OT_drag_form_vertex.poll(bpy.context), "the form must be measured first"
    vertices = _measured(barge)
    assert BATTEN_OT_drag_form_vertex.poll(bpy.context)
    bow = max(range(len(vertices)), key=lambda i: vertices[i][0])
    start = _at(vertices[bow])
    before = _points(barge)
    collections = len(bpy.data.collections)
    miss = (start[0] - 60.0, start[1] + 60.0)
    results, reports = _drag(
        bpy.context,
        side_view,
        [
            _Event("MOUSEMOVE", miss, "NOTHING"),  # navigating: passed through
            _Event("LEFTMOUSE", miss),  # beside every vertex: nothing picked
            _Event("LEFTMOUSE", (start[0] + 3.0, start[1] - 2.0)),  # picks the bow
            _Event("MOUSEMOVE", (start[0] + 33.0, start[1] + 8.0), "NOTHING"),
        ],
    )
    assert results == [{"PASS_THROUGH"}, {"RUNNING_MODAL"}, {"RUNNING_MODAL"}, {"RUNNING_MODAL"}]
    drawn = overlay.drag_lines()
    assert drawn[0] == pytest.approx(np.float32(vertices[bow]))
    assert drawn[1] - drawn[0] == pytest.approx(np.float32([3.0, 0.0, 1.0]), abs=1e-5), "the mouse's move"
    assert len(bpy.data.collections) == collections, "nothing made while dragging"

    # Along x only, then applied.
    op, reports = stand_in(BATTEN_OT_drag_form_vertex)
    op.begin(bpy.context, side_view)
    op.modal(bpy.context, _Event("LEFTMOUSE", start))
    op.modal(bpy.context, _Event("MOUSEMOVE", (start[0] + 20.0, start[1] + 10.0), "NOTHING"))
    op.modal(bpy.context, _Event("X", (start[0] + 20.0, start[1] + 10.0)))
    assert overlay.drag_lines()[1] - overlay.drag_lines()[0] == pytest.approx(np.float32([2.0, 0.0, 0.0]))
    assert op.modal(bpy.context, _Event("LEFTMOUSE", (start[0] + 20.0, start[1] + 10.0))) == {"FINISHED"}
    assert len(overlay.drag_lines()) == 0, "the preview is gone"
    copy = settings.source
    assert copy != barge and api.transform_stack(copy)[0]["collection"] == barge
    now = _points(barge)
    assert now.keys() == before.keys() and all(np.array_equal(now[k], before[k]) for k in now), (
        "original kept"
    )
    # The same change as the typed move.
    typed = api.transform(barge, moves=[(bow, (2.0, 0.0, 0.0))]).collection
    assert _by_source(copy) == _by_source(typed)
    moved = api.form_topology(copy)["vertices"][bow]["position"]
    assert moved == pytest.approx(np.add(vertices[bow], (2.0, 0.0, 0.0)), abs=1e-9)


def test_esc_a_still_vertex_and_a_refused_move_change_nothing(barge, side_view):  # noqa: F811
    vertices = _measured(barge)
    collections = len(bpy.data.collections)
    at = _at(vertices[0])
    results, _ = _drag(bpy.context, side_view, [_Event("LEFTMOUSE", at), _Event("ESC")])
    assert results[-1] == {"CANCELLED"} and len(overlay.drag_lines()) == 0
    results, reports = _drag(bpy.context, side_view, [_Event("LEFTMOUSE", at), _Event("RET")])
    assert results[-1] == {"CANCELLED"} and "did not move" in reports[-1][1]
    # The keel's vertex at the forward midship section dragged 30 m aft breaks a connection.
    form = api.form_topology(barge)
    v = next(i for i, x in enumerate(form["vertices"]) if set(x["curves"]) >= {"keel", "ms_fwd"})
    at = _at(vertices[v])
    results, reports = _drag(
        bpy.context,
        side_view,
        [
            _Event("LEFTMOUSE", at),
            _Event("MOUSEMOVE", (at[0] - 300.0, at[1]), "NOTHING"),
            _Event("LEFTMOUSE"),
        ],
    )
    assert results[-1] == {"CANCELLED"}
    assert reports[-1][0] == {"ERROR"} and "connection" in reports[-1][1]
    assert len(bpy.data.collections) == collections and bpy.context.scene.batten.source == barge


def test_outside_a_3d_viewport_it_says_so(barge):  # noqa: F811
    _measured(barge)
    op, reports = stand_in(BATTEN_OT_drag_form_vertex)
    assert BATTEN_OT_drag_form_vertex.invoke(op, bpy.context, _Event("LEFTMOUSE")) == {"CANCELLED"}
    assert reports == [({"ERROR"}, "Drag Vertex works in a 3D viewport")]
