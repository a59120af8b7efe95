"""The Live rebuild path headless: the depsgraph handler schedules one coalesced rebuild for a
real edit of a hull curve (and none otherwise), and the timer callback rebuilds the surface,
keeping a failure in the scene's report with the previous mesh. Blender's timers do not run
without an event loop, so the registered callback is captured and called as Blender would."""

import json
from types import SimpleNamespace

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import live, scene_build


@pytest.fixture
def timers(monkeypatch):
    """The callbacks the handler registers with bpy.app.timers, with their first intervals."""
    calls = []

    def register(fn, first_interval=0.0):
        calls.append((fn, first_interval))

    monkeypatch.setattr(bpy.app.timers, "register", register)
    yield calls
    live._scheduled.clear()


@pytest.fixture
def hull(examples_dir):
    coll = api.load_network(examples_dir / "wigley.json")
    settings = bpy.context.scene.batten
    settings.source = coll
    settings.resolution = 4
    settings.live = True
    return coll


def _surface():
    return next((o for o in bpy.context.scene.objects if o.type == "MESH"), None)


def _positions(obj):
    pos = np.empty(3 * len(obj.data.vertices))
    obj.data.vertices.foreach_get("co", pos)
    return pos.reshape(-1, 3)


def _update(id_, *, geometry=False, transform=False):
    return SimpleNamespace(id=id_, is_updated_geometry=geometry, is_updated_transform=transform)


def _fire(*updates):
    live._on_depsgraph_update(bpy.context.scene, SimpleNamespace(updates=list(updates)))


def test_an_edit_schedules_one_rebuild_and_the_timer_builds(hull, timers):
    assert _surface() is None
    station = hull.objects["station +0.0"]
    station.data.splines[0].points[3].co.y += 0.5
    bpy.context.view_layer.update()  # the real depsgraph update reaches the registered handler
    assert live._on_depsgraph_update in bpy.app.handlers.depsgraph_update_post
    assert len(timers) == 1, "one coalesced rebuild for the edit"
    callback, interval = timers[0]
    assert interval == live.COALESCE_SECONDS
    assert bpy.context.scene.name in live._scheduled
    _fire(_update(station, geometry=True))
    _fire(_update(station.data, geometry=True))
    assert len(timers) == 1, "already scheduled: no second timer"
    assert callback() is None, "a one-shot timer"
    assert not live._scheduled and not live._rebuilding
    obj = _surface()
    assert obj is not None and len(obj.data.polygons) == 32 * 4 * 4
    report = json.loads(bpy.context.scene.batten.last_report)
    assert report["faces"] == 32
    assert report["measured"] and report["rebuild"]["kind"] == "full", "the first live build is full"
    assert len(timers) == 2, "the rebuild's own depsgraph updates schedule nothing"
    settle, interval = timers[1]
    assert interval == scene_build.SECTIONS_SETTLE_SECONDS, "and the report is measured once edits pause"
    assert settle() is None, "a one-shot timer"
    assert not scene_build._settling


def test_only_real_edits_of_hull_curves_schedule(hull, timers):
    station = hull.objects["station +0.0"]
    stray = bpy.data.objects.new("stray", bpy.data.curves.new("stray", "CURVE"))
    bpy.context.scene.collection.objects.link(stray)
    _fire(_update(station))  # a relations update: neither flag
    _fire(_update(stray, geometry=True))  # not a hull curve
    _fire(_update(bpy.context.scene, transform=True))  # not a curve
    assert timers == [] and not live._scheduled
    bpy.context.scene.batten.live = False
    _fire(_update(station, geometry=True))
    assert timers == [], "Live off"
    bpy.context.scene.batten.live = True
    _fire(_update(station, transform=True))  # a moved curve counts
    assert len(timers) == 1


def test_the_timer_keeps_a_failure_and_the_previous_mesh(hull, timers):
    scene = bpy.context.scene
    live.rebuild_scene(scene.name)
    obj = _surface()
    before = _positions(obj).copy()
    hull.objects["keel"].data.splines[0].points[0].co = (float("nan"), 0, 0, 1)
    live._scheduled[scene.name] = lambda: None  # as the handler leaves it
    assert live.rebuild_scene(scene.name) is None, "no exception out of a timer"
    assert not live._scheduled and not live._rebuilding
    assert "keel" in json.loads(scene.batten.last_report)["error"]
    assert _surface() == obj and np.array_equal(_positions(obj), before), "the previous mesh stays"
    scene.batten.live = False
    hull.objects["keel"].data.splines[0].points[0].co = (-50.0, 0, 0, 1)
    live.rebuild_scene(scene.name)
    assert "error" in json.loads(scene.batten.last_report), "Live off: no rebuild"
    live.rebuild_scene("no such scene")  # the scene was deleted before the timer fired
