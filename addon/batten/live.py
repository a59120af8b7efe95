"""Live rebuild: when a curve of a hull with Live on changes, rebuild its surface (and its
hydrostatics, once the panel has computed them).

Depsgraph updates are coalesced with a short timer, so dragging a control point triggers one
rebuild per pause rather than one per mouse event, and updates that touch no hull curve are
skipped. The design state (Live on/off, the hull collection) lives in scene properties; only
the transient "a rebuild is scheduled" flag lives here.

The depsgraph handler is there only while some scene has Live on: switching Live off in the
last one removes it, runs what waited for the drag to pause (the report's measurement, the
drawn sections' cut) and drops the scene's live hull; opening another file cancels every
pending timer and forgets the session's hulls, and the handler comes back when the opened
file has a scene with Live on.
"""

import bpy

from . import api, hull_models, sections_draw
from .scene_build import build_into_scene, cancel_pending, flush_pending
from .scene_hydro import hydrostatics_into_scene

#: Seconds to wait after the last change before rebuilding.
COALESCE_SECONDS = 0.05

#: The pending rebuild of each scene (its timer function), by scene name.
_scheduled: dict[str, object] = {}
#: True while a live rebuild runs: the depsgraph updates it causes itself (a new mesh changes
#: the relations, which re-reports every hull curve) must not schedule another rebuild.
_rebuilding = False


def _hull_curve_names(settings) -> set[str]:
    if settings.source is None:
        return set()
    # Drawn sections are output: redrawing them is no edit of the hull.
    return {
        o.name
        for o in settings.source.all_objects
        if o.type == "CURVE" and not o.get(sections_draw.SECTION_TAG)
    }


def rebuild_scene(scene_name: str):
    """Rebuild the surface of a scene's hull now (the timer callback), and its hydrostatics
    when they have been computed once (the panel then shows the figures of the new shape).
    Errors are kept in the scene's last report (and last hydrostatics); the previous mesh
    stays."""
    _scheduled.pop(scene_name, None)
    scene = bpy.data.scenes.get(scene_name)
    if scene is None or not scene.batten.live or scene.batten.source is None:
        return None
    global _rebuilding
    _rebuilding = True
    try:
        build_into_scene(scene, live=True)
        if scene.batten.last_hydrostatics:
            hydrostatics_into_scene(scene, live=True)
    except api.BattenError:
        pass  # kept in the scene's report or figures; the previous mesh stays
    finally:
        try:
            bpy.context.view_layer.update()  # consume the updates this rebuild caused
        finally:
            _rebuilding = False
    return None


@bpy.app.handlers.persistent  # the load handlers decide whether it stays for the next file
def _on_depsgraph_update(scene, depsgraph):
    settings = getattr(scene, "batten", None)
    if _rebuilding or settings is None or not settings.live or scene.name in _scheduled:
        return
    names = _hull_curve_names(settings)
    if not names:
        return
    # Only real edits count: a relations rebuild (an object linked anywhere, a new mesh)
    # re-reports every object with neither flag set.
    touched = any(
        (u.is_updated_geometry or u.is_updated_transform)
        and isinstance(u.id, bpy.types.Object | bpy.types.Curve)
        and (u.id.name in names or _curve_of(u.id, names))
        for u in depsgraph.updates
    )
    if touched:
        name = scene.name

        def rebuild():
            return rebuild_scene(name)

        _scheduled[name] = rebuild
        bpy.app.timers.register(rebuild, first_interval=COALESCE_SECONDS)


def _curve_of(data, names) -> bool:
    if not isinstance(data, bpy.types.Curve):
        return False
    return any(o.data == data and o.name in names for o in bpy.data.objects if o.type == "CURVE")


def _any_live() -> bool:
    """True when a scene of the open file has Live on (False while add-on registration keeps
    ``bpy.data`` out of reach; the file's load or the next Live switch then decides)."""
    try:
        scenes = bpy.data.scenes
    except AttributeError:
        return False
    return any(getattr(s, "batten", None) is not None and s.batten.live for s in scenes)


def _sync_handler() -> None:
    """The depsgraph handler present exactly while some scene has Live on."""
    handlers = bpy.app.handlers.depsgraph_update_post
    if _any_live():
        if _on_depsgraph_update not in handlers:
            handlers.append(_on_depsgraph_update)
    elif _on_depsgraph_update in handlers:
        handlers.remove(_on_depsgraph_update)


def _cancel_scheduled(scene_name: str | None = None) -> None:
    """Unregister the pending rebuild of ``scene_name`` (of every scene with None)."""
    names = list(_scheduled) if scene_name is None else [scene_name]
    for name in names:
        pending = _scheduled.pop(name, None)
        if pending is not None and bpy.app.timers.is_registered(pending):
            bpy.app.timers.unregister(pending)


def live_changed(settings, _context) -> None:
    """A scene's Live setting changed (the property's update): switched off, the scene's
    pending rebuild is dropped, what waited for a pause runs now, its live hull is dropped;
    either way the handler follows (:func:`_sync_handler`)."""
    if not settings.live:
        scene = settings.id_data
        source = settings.source.name if settings.source is not None else None
        _cancel_scheduled(scene.name)
        flush_pending(scene.name, source)
        if source is not None:
            hull_models.forget_live(source)
    _sync_handler()


@bpy.app.handlers.persistent
def _on_load_pre(*_args) -> None:
    """Another file is being opened: nothing of this one's Live may run on into it."""
    _cancel_scheduled()
    cancel_pending()
    hull_models.forget()
    if _on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(_on_depsgraph_update)


@bpy.app.handlers.persistent
def _on_load_post(*_args) -> None:
    """A file was opened: Live resumes for its scenes that have it on."""
    _sync_handler()


def register():
    """Add the file handlers, and the depsgraph handler if a scene has Live on."""
    if _on_load_pre not in bpy.app.handlers.load_pre:
        bpy.app.handlers.load_pre.append(_on_load_pre)
    if _on_load_post not in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.append(_on_load_post)
    _sync_handler()


def unregister():
    """Remove the handlers and every pending timer."""
    for handlers, handler in (
        (bpy.app.handlers.depsgraph_update_post, _on_depsgraph_update),
        (bpy.app.handlers.load_pre, _on_load_pre),
        (bpy.app.handlers.load_post, _on_load_post),
    ):
        if handler in handlers:
            handlers.remove(handler)
    _cancel_scheduled()
    cancel_pending()
