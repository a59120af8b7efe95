"""Building a scene's hull with the scene's settings (the Build operator and Live both do), and
cutting its drawn sections again after each build."""

import json
import time

import bpy

from . import api
from .network_markers import network_markers

#: A live rebuild (while a control point is dragged) cuts the drawn sections again only when
#: their last cut took at most this (s); a slower cut waits until the rebuilds pause.
SECTIONS_LIVE_BUDGET = 0.005

#: Seconds without a rebuild after which sections skipped while dragging are cut again.
SECTIONS_SETTLE_SECONDS = 0.5

#: How long the last cut of each hull's drawn sections took (s), by hull collection name.
_cut_seconds: dict[str, float] = {}
#: The pending deferred cut of each hull (its timer function), by hull collection name.
_deferred: dict[str, object] = {}
#: The pending measurement of each live hull's report (its timer function), by scene name.
_settling: dict[str, object] = {}


#: What a live rebuild's report says beyond the surface, kept when the settled report replaces it.
KEPT_ON_SETTLE = ("sections_error", "hierarchy_moved", "hierarchy_error")


def build_into_scene(scene, *, live: bool = False) -> dict:
    """Build the scene's hull with its settings, keep the report in the scene (JSON) with the
    overlay's markers (from the report's nodes and warnings), cut its drawn sections again (see
    :func:`refresh_sections`), and return the report; a failure is kept as the report's error
    and raised again. Attached curves are first brought to their parents
    (:func:`batten.api.update_hierarchy`; the report's ``hierarchy_moved`` names them, and
    ``hierarchy_error`` says why they could not be, the build going on with the curves as
    they are)."""
    settings = scene.batten
    try:
        # The curve hierarchy first (seed 002 §7.1): attached curves follow their parents.
        moved, hierarchy_error = api.update_hierarchy(settings.source), None
    except api.BattenError as e:
        moved, hierarchy_error = [], str(e)
    try:
        result = api.build(
            settings.source,
            tolerance=settings.tolerance,
            resolution=settings.resolution,
            mirror=settings.mirror,
            live=live,
        )
    except api.BattenError as e:
        settings.last_report = json.dumps({"error": str(e)})
        raise
    report = result.report
    report["hierarchy_moved"] = moved
    if hierarchy_error is not None:
        report["hierarchy_error"] = hierarchy_error
    try:
        refresh_sections(settings.source, live=live)
    except api.BattenError as e:
        report["sections_error"] = str(e)
    _keep_report(settings, report)
    if live:
        _settle_later(scene.name)
    return report


def _keep_report(settings, report: dict) -> None:
    """Keep ``report`` in the scene's settings (JSON) with the overlay's markers."""
    report["markers"] = network_markers(report["node_positions"], report["node_kinds"], report["warnings"])
    settings.last_report = json.dumps(report)


def _settle_later(scene_name: str) -> None:
    """Measure the live hull's report once the rebuilds of ``scene_name`` have paused for
    :data:`SECTIONS_SETTLE_SECONDS` (a live rebuild leaves its quality figures unmeasured),
    and keep it in the scene's report."""
    pending = _settling.pop(scene_name, None)
    if pending is not None and bpy.app.timers.is_registered(pending):
        bpy.app.timers.unregister(pending)

    def later():
        _settling.pop(scene_name, None)
        scene = bpy.data.scenes.get(scene_name)
        if scene is None or scene.batten.source is None:
            return None
        settings = scene.batten
        try:
            report = api.settle(settings.source, mirror=settings.mirror)
        except api.BattenError as e:
            settings.last_report = json.dumps({"error": str(e)})
            return None
        if report is not None:
            # What the live rebuild said of the sections and the hierarchy stays.
            before = json.loads(settings.last_report or "{}")
            report.update({k: before[k] for k in KEPT_ON_SETTLE if k in before})
            _keep_report(settings, report)
        return None

    _settling[scene_name] = later
    bpy.app.timers.register(later, first_interval=SECTIONS_SETTLE_SECONDS)


def cancel_pending() -> None:
    """Unregister every pending deferred cut and report measurement (another file opened, the
    add-on unregistered)."""
    for pending in list(_deferred.values()) + list(_settling.values()):
        if bpy.app.timers.is_registered(pending):
            bpy.app.timers.unregister(pending)
    _deferred.clear()
    _settling.clear()


def flush_pending(scene_name: str, source_name: str | None) -> None:
    """Run now what waits for a pause of ``scene_name``'s live rebuilds — the measurement of
    its report and the cut of its hull's (``source_name``) drawn sections — and unregister
    their timers (Live switched off: the report and sections then describe the surface)."""
    waiting = [_settling.pop(scene_name, None)]
    if source_name is not None:
        waiting.append(_deferred.pop(source_name, None))
    for pending in waiting:
        if pending is None:
            continue
        if bpy.app.timers.is_registered(pending):
            bpy.app.timers.unregister(pending)
        pending()


def refresh_sections(source, *, live: bool = False) -> None:
    """Cut the hull's drawn sections (``"<hull> sections"``) again, if it has any: now, or
    during a live rebuild when their last cut took more than :data:`SECTIONS_LIVE_BUDGET`,
    once the rebuilds have paused for :data:`SECTIONS_SETTLE_SECONDS`."""
    name = source.name
    pending = _deferred.pop(name, None)
    if pending is not None and bpy.app.timers.is_registered(pending):
        bpy.app.timers.unregister(pending)
    if live and _cut_seconds.get(name, 0.0) > SECTIONS_LIVE_BUDGET:

        def later():
            _deferred.pop(name, None)
            coll = bpy.data.collections.get(name)
            if coll is not None:
                try:
                    refresh_sections(coll)
                except api.BattenError:
                    pass  # the sections stay as they were; the next build reports it
            return None

        _deferred[name] = later
        bpy.app.timers.register(later, first_interval=SECTIONS_SETTLE_SECONDS)
        return
    start = time.perf_counter()
    if api.refresh_sections(source):
        _cut_seconds[name] = time.perf_counter() - start
