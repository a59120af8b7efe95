"""The incremental live rebuild through the API (``api.build(..., live=True)``, ``api.settle``):
moving control points rebuilds only the faces they reach and rewrites only the vertex
positions, with exactly the mesh of a full build; the report's quality figures are measured
again by ``settle``; a change of connectivity falls back to a full build and says why; a failed
rebuild keeps the previous mesh."""

import json

import batten.api as api
import bpy
import numpy as np
import pytest
from batten import hull_models, live, scene_build
from batten_native import build_surface
from helpers import move_point

RESOLUTION = 8


def _positions(obj) -> np.ndarray:
    pos = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.attributes["position"].data.foreach_get("vector", pos)
    return pos.reshape(-1, 3)


def _full(coll):
    """A full build of the collection's curves now: mesh arrays and report."""
    return build_surface(
        api.read_curves(coll), api.DEFAULT_TOLERANCE, RESOLUTION, coll.name, api.tangent_planes(coll)
    )


@pytest.fixture
def frigate(examples_dir):
    hull_models.forget()
    coll = api.load_network(examples_dir / "frigate_network.json")
    yield coll
    hull_models.forget()


def test_a_small_move_rebuilds_its_faces_and_writes_positions_only(frigate):
    first = api.build(frigate, resolution=RESOLUTION, live=True)
    assert first.report["measured"] and first.report["rebuild"]["kind"] == "full"
    mesh = first.object.data
    station = frigate.objects["st4"]
    middle = len(station.data.splines[0].points) // 2
    # Less than the model tolerance: the station stays on its waterlines (same connectivity).
    move_point(station, middle, 4e-5)
    moved = api.build(frigate, resolution=RESOLUTION, live=True)
    rebuild = moved.report["rebuild"]
    assert rebuild["kind"] == "incremental", rebuild
    assert 0 < rebuild["faces"] < rebuild["of"] == first.report["faces"]
    assert not moved.report["measured"], "the quality figures wait for settle"
    assert moved.object.data == mesh, "the same mesh, its positions rewritten"
    (positions, corners, sizes, patch), report = _full(frigate)
    assert np.array_equal(_positions(moved.object), positions.astype(np.float32))
    assert not np.array_equal(_positions(moved.object), positions.astype(np.float32) * 0)
    settled = api.settle(frigate)
    assert settled["measured"]
    for key in ("max_gap", "max_normal_angle_deg", "holes", "folds", "open_edges", "faces"):
        assert settled[key] == report[key], key
    assert [w["message"] for w in settled["warnings"]] == [w["message"] for w in report["warnings"]]
    assert settled["enclosed_volume_half"] == report["volume"]
    assert api.settle(frigate) is None, "nothing left to measure"


def test_a_move_off_the_crossings_falls_back_to_a_full_build(frigate):
    api.build(frigate, resolution=RESOLUTION, live=True)
    station = frigate.objects["st4"]
    move_point(station, len(station.data.splines[0].points) // 2, 0.02)
    result = api.build(frigate, resolution=RESOLUTION, live=True)
    rebuild = result.report["rebuild"]
    assert rebuild["kind"] == "full" and "connectivity" in rebuild["reason"], rebuild
    (positions, _, sizes, _), _ = _full(frigate)
    assert len(result.object.data.polygons) == len(sizes)
    assert np.array_equal(_positions(result.object), positions.astype(np.float32))


def test_a_failed_live_rebuild_keeps_the_mesh(frigate):
    result = api.build(frigate, resolution=RESOLUTION, live=True)
    before = _positions(result.object).copy()
    keep = {"st4", "cwl"}
    removed = [o for o in frigate.objects if o.name not in keep]
    for obj in removed:
        frigate.objects.unlink(obj)
    with pytest.raises(api.BattenError):
        api.build(frigate, resolution=RESOLUTION, live=True)
    assert np.array_equal(_positions(result.object), before), "the previous mesh stays"
    for obj in removed:
        frigate.objects.link(obj)
    again = api.build(frigate, resolution=RESOLUTION, live=True)
    assert np.array_equal(_positions(again.object), before), "and rebuilds from where it was"


def test_fifty_drags_on_kcs_end_in_the_full_build(hulls_dir):
    hull_models.forget()
    coll, _ = api.import_sections(hulls_dir / "kcs" / "network.json")
    api.build(coll, resolution=RESOLUTION, live=True)
    rng = np.random.default_rng(50)
    stations = [o for o in coll.objects if o.name.startswith("st")]
    kinds = []
    for _ in range(50):
        obj = stations[rng.integers(len(stations))]
        n = len(obj.data.splines[0].points)
        move_point(obj, int(rng.integers(1, n - 1)), float(rng.uniform(-3e-5, 3e-5)))
        kinds.append(api.build(coll, resolution=RESOLUTION, live=True).report["rebuild"]["kind"])
    assert kinds.count("incremental") >= 45, kinds
    surface = bpy.data.objects[f"{coll.name} surface"]
    (positions, _, sizes, _), report = _full(coll)
    assert len(surface.data.polygons) == len(sizes)
    assert np.array_equal(_positions(surface), positions.astype(np.float32))
    assert api.settle(coll)["max_normal_angle_deg"] == report["max_normal_angle_deg"]
    hull_models.forget()


def _pending() -> list:
    """The timers waiting: the measurement of the report and the coalesced rebuild."""
    return list(scene_build._settling.values()) + list(live._scheduled.values())


def _drag_pending(frigate):
    """Live on for ``frigate``, built, and a point moved: a rebuild and a measurement wait."""
    settings = bpy.context.scene.batten
    settings.source = frigate
    settings.live = True
    scene_build.build_into_scene(bpy.context.scene, live=True)
    frigate.objects["st4"].data.splines[0].points[2].co.y += 4e-5
    bpy.context.view_layer.update()  # the edit reaches the handler: a rebuild is scheduled
    pending = _pending()
    assert len(pending) == 2, "a rebuild and a measurement wait"
    return pending


def test_unregistering_the_add_on_leaves_no_handler_or_timer_behind(frigate):
    pending = _drag_pending(frigate)
    assert all(bpy.app.timers.is_registered(f) for f in pending)
    live.unregister()
    assert not scene_build._settling and not live._scheduled
    assert not any(bpy.app.timers.is_registered(f) for f in pending), "no timer left behind"
    assert live._on_depsgraph_update not in bpy.app.handlers.depsgraph_update_post
    live.register()
    bpy.context.scene.batten.live = False


def test_switching_live_off_measures_now_and_leaves_no_handler_or_timer(frigate):
    handlers = bpy.app.handlers.depsgraph_update_post
    assert live._on_depsgraph_update not in handlers, "no handler before Live is on"
    _drag_pending(frigate)
    assert live._on_depsgraph_update in handlers, "Live on: the handler is there"
    scene = bpy.context.scene
    live._scheduled[scene.name]()  # the rebuild runs, as its timer would
    report = json.loads(scene.batten.last_report)
    assert report["rebuild"]["kind"] == "incremental"
    assert report["measured"] is False, "the live rebuild's report waits for a pause"
    assert frigate.name in hull_models._live
    frigate.objects["st4"].data.splines[0].points[2].co.y -= 4e-5
    bpy.context.view_layer.update()
    pending = _pending()
    assert len(pending) == 2, "a rebuild and a measurement wait again"
    scene.batten.live = False
    assert not any(bpy.app.timers.is_registered(f) for f in pending), "no timer left behind"
    assert not live._scheduled and not scene_build._settling
    assert live._on_depsgraph_update not in handlers, "no handler left behind"
    assert frigate.name not in hull_models._live, "the live hull is dropped"
    report = json.loads(bpy.context.scene.batten.last_report)
    assert report["measured"] is True, "what waited for the pause ran: the report is measured"
    # An edit now rebuilds nothing.
    frigate.objects["st4"].data.splines[0].points[2].co.y += 4e-5
    bpy.context.view_layer.update()
    assert not live._scheduled, "Live off: an edit schedules nothing"


def test_opening_a_file_leaves_nothing_of_live_behind_and_resumes_its_live(frigate, tmp_path):
    handlers = bpy.app.handlers.depsgraph_update_post
    pending = _drag_pending(frigate)
    path = str(tmp_path / "live.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    assert not any(bpy.app.timers.is_registered(f) for f in pending), "no timer left behind"
    assert not live._scheduled and not scene_build._settling
    assert live._on_depsgraph_update not in handlers, "the new file has no Live: no handler"
    assert not hull_models._live and not hull_models._kept, "the session's hulls forgotten"
    bpy.ops.wm.open_mainfile(filepath=path)
    assert bpy.context.scene.batten.live, "the saved file has Live on"
    assert live._on_depsgraph_update in handlers, "and Live resumes with it"
    coll = bpy.context.scene.batten.source
    coll.objects["st4"].data.splines[0].points[2].co.y += 4e-5
    bpy.context.view_layer.update()
    assert bpy.context.scene.name in live._scheduled, "an edit schedules a rebuild again"
    bpy.context.scene.batten.live = False
    assert live._on_depsgraph_update not in handlers


def test_sections_and_exports_read_a_measured_report_after_a_live_rebuild(frigate):
    api.build(frigate, resolution=RESOLUTION, live=True)
    station = frigate.objects["st4"]
    move_point(station, len(station.data.splines[0].points) // 2, 4e-5)
    assert not api.build(frigate, resolution=RESOLUTION, live=True).report["measured"]
    kept = hull_models._kept[frigate.name]
    api.hydrostatics(frigate, 4.0)
    assert hull_models._kept[frigate.name] is kept, "hydrostatics need only the exact patches"
    api.sections(frigate, stations=3)
    assert hull_models._kept[frigate.name].measured, "sections read the knuckle edges: measured"
    assert api.settle(frigate) is None, "the live hull is measured too"


def test_a_live_rebuild_follows_the_mirror_setting(frigate):
    api.build(frigate, resolution=RESOLUTION, live=True)
    station = frigate.objects["st4"]
    move_point(station, len(station.data.splines[0].points) // 2, 4e-5)
    result = api.build(frigate, resolution=RESOLUTION, live=True, mirror=False)
    assert result.report["rebuild"]["kind"] == "incremental"
    assert not result.object.modifiers, "mirror off: no Mirror modifier"
    assert result.report["enclosed_volume"] == result.report["enclosed_volume_half"]
