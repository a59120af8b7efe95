"""Operators: convert properties, call :mod:`batten.api`, report errors. No geometry here."""

import json
from pathlib import Path

import bpy
from bpy.props import FloatProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from . import api
from ._registry import register_classes, unregister_classes


def _hull_source(context):
    """The scene's hull collection if set, else the selected curve objects."""
    settings = context.scene.batten
    if settings.source is not None:
        return settings.source
    return [o for o in context.selected_objects if o.type == "CURVE"]


def build_into_scene(scene) -> dict:
    """Build the scene's hull with its settings, keep the report in the scene (JSON), and
    return it; a failure is kept as the report's error and raised again."""
    settings = scene.batten
    try:
        result = api.build(
            settings.source,
            tolerance=settings.tolerance,
            resolution=settings.resolution,
            mirror=settings.mirror,
        )
    except api.BattenError as e:
        settings.last_report = json.dumps({"error": str(e)})
        raise
    topo = api.topology(settings.source, tolerance=settings.tolerance)
    result.report["markers"] = network_markers(topo)
    settings.last_report = json.dumps(result.report)
    return result.report


# Marker kinds of the viewport overlay: node kinds and diagnostic kinds of api.topology.
_NODE_MARKERS = {"crossing": "nodes", "end_to_end": "nodes", "end_on_curve": "nodes", "t_joint": "t_joints"}
_DIAGNOSTIC_MARKERS = {"dangling_end": "dangling_ends", "near_miss": "near_misses"}


def network_markers(topo: dict) -> dict[str, list]:
    """Marker positions by kind from an :func:`api.topology` dict: ``nodes`` (crossings, ends
    on ends, ends on a curve where the faces have corners), ``t_joints``, ``dangling_ends``,
    ``near_misses`` and ``problems`` (every other diagnostic with a location). A free end is
    marked by its dangling-end diagnostic, not as a node."""
    marks = {k: [] for k in ("nodes", "t_joints", "dangling_ends", "near_misses", "problems")}
    for position, kind in zip(topo["node_positions"], topo["node_kinds"], strict=True):
        if kind in _NODE_MARKERS:
            marks[_NODE_MARKERS[kind]].append(position)
    for d in topo["diagnostics"]:
        if d["location"] is not None:
            marks[_DIAGNOSTIC_MARKERS.get(d["kind"], "problems")].append(list(d["location"]))
    return marks


class BATTEN_OT_build(bpy.types.Operator):
    """Build the smooth hull surface from the hull's curve network"""

    bl_idname = "batten.build"
    bl_label = "Build Surface"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.scene.batten.source is not None

    def execute(self, context):
        try:
            report = build_into_scene(context.scene)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        for warning in report["warnings"]:
            self.report({"WARNING"}, warning)
        sides = ", ".join(f"{n}-sided: {c}" for n, c in sorted(report["faces_by_sides"].items()))
        self.report({"INFO"}, f"Built {report['faces']} patches ({sides})")
        return {"FINISHED"}


class BATTEN_OT_select_curves(bpy.types.Operator):
    """Select and frame the curves a warning names"""

    bl_idname = "batten.select_curves"
    bl_label = "Show Curves"
    bl_options = {"REGISTER", "UNDO"}

    names: StringProperty(name="Curves", description="Curve object names, separated by newlines")

    def execute(self, context):
        wanted = {n for n in self.names.split("\n") if n}
        found = [o for o in context.view_layer.objects if o.name in wanted or o.name.split("[")[0] in wanted]
        if not found:
            self.report({"WARNING"}, "None of the named curves is in this view layer")
            return {"CANCELLED"}
        for o in context.view_layer.objects:
            o.select_set(o in found)
        context.view_layer.objects.active = found[0]
        if context.area is not None and context.area.type == "VIEW_3D":
            bpy.ops.view3d.view_selected()
        return {"FINISHED"}


def example_files() -> list[Path]:
    """The example networks: shipped inside the extension, or in this checkout's examples/."""
    here = Path(__file__).resolve().parent
    for folder in (here / "examples", here.parent.parent / "examples"):
        files = sorted(folder.glob("*.json"))
        if files:
            return files
    return []


class BATTEN_OT_add_example(bpy.types.Operator):
    """Draw a batten example hull network as curves in a new collection"""

    bl_idname = "batten.add_example"
    bl_label = "batten Example Hull"
    bl_options = {"REGISTER", "UNDO"}

    example: StringProperty(name="Example", description="File name of the example network")

    def execute(self, context):
        path = next((p for p in example_files() if p.name == self.example), None)
        if path is None:
            self.report({"ERROR"}, f"No example '{self.example}'")
            return {"CANCELLED"}
        try:
            coll = api.load_network(path)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        context.scene.batten.source = coll
        return {"FINISHED"}


class BATTEN_MT_add_example(bpy.types.Menu):
    """Add ▸ Curve ▸ batten example hulls"""

    bl_idname = "BATTEN_MT_add_example"
    bl_label = "batten Example Hulls"

    def draw(self, _context):
        for path in example_files():
            op = self.layout.operator(
                BATTEN_OT_add_example.bl_idname, text=path.stem.replace("_", " ").title()
            )
            op.example = path.name


def _menu_add_curve(self, _context):
    self.layout.menu(BATTEN_MT_add_example.bl_idname, icon="MOD_CURVE")


class BATTEN_OT_export_network(bpy.types.Operator, ExportHelper):
    """Write the hull's curve network (the hull collection, or the selected curves) as batten JSON"""

    bl_idname = "batten.export_network"
    bl_label = "Export batten Network"
    bl_options = {"REGISTER"}

    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def execute(self, context):
        try:
            path = api.export_network(
                _hull_source(context), self.filepath, tolerance=context.scene.batten.tolerance
            )
        except (api.BattenError, OSError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Wrote {path}")
        return {"FINISHED"}


class BATTEN_OT_import_network(bpy.types.Operator, ImportHelper):
    """Draw a batten JSON curve network as curve objects in a new collection"""

    bl_idname = "batten.import_network"
    bl_label = "Import batten Network"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def execute(self, context):
        try:
            coll = api.load_network(self.filepath)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        if context.scene.batten.source is None:
            context.scene.batten.source = coll
        self.report({"INFO"}, f"Drew {len(coll.objects)} curves into '{coll.name}'")
        return {"FINISHED"}


class BATTEN_OT_fair_curves(bpy.types.Operator):
    """Refit the selected curves as fair NURBS splines within the fair tolerance"""

    bl_idname = "batten.fair_curves"
    bl_label = "Fair Curves"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return any(o.type == "CURVE" for o in context.selected_objects)

    def execute(self, context):
        tolerance = context.scene.batten.fair_tolerance
        done = []
        for obj in [o for o in context.selected_objects if o.type == "CURVE"]:
            try:
                reports = api.fair_curve(obj, tolerance=tolerance)
            except api.BattenError as e:
                self.report({"ERROR"}, str(e))
                return {"CANCELLED"} if not done else {"FINISHED"}
            done.extend(reports)
        worst = max(r["max_deviation"] for r in done)
        self.report({"INFO"}, f"Faired {len(done)} curve(s); largest deviation {worst * 1e3:.2f} mm")
        return {"FINISHED"}


class BATTEN_OT_import_sections(bpy.types.Operator, ImportHelper):
    """Import sections or offsets (neutral JSON point lists, or CSV rows name,x,y,z) as fair curves"""

    bl_idname = "batten.import_sections"
    bl_label = "Import Sections / Offsets"
    bl_options = {"REGISTER", "UNDO"}

    filter_glob: StringProperty(default="*.json;*.csv", options={"HIDDEN"})
    tolerance: FloatProperty(name="Tolerance", default=5e-3, min=1e-6, max=1.0, precision=4, unit="LENGTH")

    def execute(self, context):
        try:
            coll, reports = api.import_sections(self.filepath, tolerance=self.tolerance)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        worst = max(r["max_deviation"] for r in reports)
        self.report(
            {"INFO"}, f"Imported {len(reports)} curves into '{coll.name}'; worst {worst * 1e3:.2f} mm"
        )
        return {"FINISHED"}


def _menu_import(self, _context):
    self.layout.operator(BATTEN_OT_import_network.bl_idname, text="batten Network (.json)")
    self.layout.operator(BATTEN_OT_import_sections.bl_idname, text="batten Sections / Offsets (.json, .csv)")


def _menu_export(self, _context):
    self.layout.operator(BATTEN_OT_export_network.bl_idname, text="batten Network (.json)")


_CLASSES = (
    BATTEN_OT_build,
    BATTEN_OT_select_curves,
    BATTEN_OT_add_example,
    BATTEN_MT_add_example,
    BATTEN_OT_export_network,
    BATTEN_OT_import_network,
    BATTEN_OT_fair_curves,
    BATTEN_OT_import_sections,
)


def register():
    """Register the operators and their File menu entries."""
    register_classes(_CLASSES)
    bpy.types.TOPBAR_MT_file_import.remove(_menu_import)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    bpy.types.TOPBAR_MT_file_import.append(_menu_import)
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)
    bpy.types.VIEW3D_MT_curve_add.remove(_menu_add_curve)
    bpy.types.VIEW3D_MT_curve_add.append(_menu_add_curve)


def unregister():
    """Remove the menu entries and operators."""
    bpy.types.TOPBAR_MT_file_import.remove(_menu_import)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    bpy.types.VIEW3D_MT_curve_add.remove(_menu_add_curve)
    unregister_classes(_CLASSES)
