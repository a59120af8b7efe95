"""Live rebuild: when a curve of a hull with Live on changes, rebuild its surface (and its
hydrostatics, once the panel has computed them).

Depsgraph updates are coalesced with a short timer, so dragging a control point triggers one
rebuild per pause rather than one per mouse event, and updates that touch no hull curve are
skipped. The design state (Live on/off, the hull collection) lives in scene properties; only
the transient "a rebuild is scheduled" flag lives here.
"""

import bpy

from . import api, sections_draw
from .scene_build import build_into_scene, cancel_pending
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


@bpy.app.handlers.persistent  # survives opening a file, like the Live setting it serves
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


def register():
    """Add the depsgraph handler (once)."""
    if _on_depsgraph_update not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(_on_depsgraph_update)


def unregister():
    """Remove the depsgraph handler."""
    if _on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(_on_depsgraph_update)
    for pending in _scheduled.values():
        if bpy.app.timers.is_registered(pending):
            bpy.app.timers.unregister(pending)
    _scheduled.clear()
    cancel_pending()
