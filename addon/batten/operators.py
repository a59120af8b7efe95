"""Operators: convert properties, call :mod:`batten.api`, report errors. No geometry here."""

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


def unregister():
    """Remove the menu entries and operators."""
    bpy.types.TOPBAR_MT_file_import.remove(_menu_import)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    unregister_classes(_CLASSES)
