"""Operators: convert properties, call :mod:`batten.api`, report errors. No geometry here."""

import bpy
from bpy.props import EnumProperty, FloatProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from . import api
from ._registry import register_classes, unregister_classes
from .api import example_files
from .modal_jobs import ModalJob
from .operator_base import BattenOperator, HullOperator
from .scene_build import build_into_scene
from .scene_hydro import draft_of


def _hull_source(context):
    """The scene's hull collection if set, else the selected curve objects."""
    settings = context.scene.batten
    if settings.source is not None:
        return settings.source
    return [o for o in context.selected_objects if o.type == "CURVE"]


class BATTEN_OT_build(HullOperator, bpy.types.Operator):
    """Build the smooth hull surface from the hull's curve network"""

    bl_idname = "batten.build"
    bl_label = "Build Surface"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        report = build_into_scene(context.scene)
        if report.get("hierarchy_error"):
            self.report({"WARNING"}, report["hierarchy_error"])
        for warning in report["warnings"]:
            self.report({"WARNING"}, warning["message"])
        sides = ", ".join(f"{n}-sided: {c}" for n, c in sorted(report["faces_by_sides"].items()))
        self.report({"INFO"}, f"Built {report['faces']} patches ({sides})")
        return {"FINISHED"}


class BATTEN_OT_select_curves(BattenOperator, bpy.types.Operator):
    """Select and frame the curve objects a warning names"""

    bl_idname = "batten.select_curves"
    bl_label = "Show Curves"
    bl_options = {"REGISTER", "UNDO"}

    names: StringProperty(name="Curves", description="Curve object names (exact), separated by newlines")

    def run(self, context):
        wanted = set(self.names.split("\n"))
        found = [o for o in context.view_layer.objects if o.name in wanted]
        if not found:
            self.report({"WARNING"}, "None of the named curves is in this view layer")
            return {"CANCELLED"}
        for o in context.view_layer.objects:
            o.select_set(o in found)
        context.view_layer.objects.active = found[0]
        if context.area is not None and context.area.type == "VIEW_3D":
            bpy.ops.view3d.view_selected()
        return {"FINISHED"}


class BATTEN_OT_add_example(BattenOperator, bpy.types.Operator):
    """Draw a batten example hull network as curves in a new collection"""

    bl_idname = "batten.add_example"
    bl_label = "batten Example Hull"
    bl_options = {"REGISTER", "UNDO"}

    example: StringProperty(name="Example", description="File name of the example network")

    def run(self, context):
        context.scene.batten.source = api.load_example(self.example)
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


class BATTEN_OT_export_network(BattenOperator, bpy.types.Operator, ExportHelper):
    """Write the hull's curve network (the hull collection, or the selected curves) as batten JSON"""

    bl_idname = "batten.export_network"
    bl_label = "Export batten Network"
    bl_options = {"REGISTER"}

    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def run(self, context):
        path = api.export_network(
            _hull_source(context), self.filepath, tolerance=context.scene.batten.tolerance
        )
        self.report({"INFO"}, f"Wrote {path}")
        return {"FINISHED"}


class BATTEN_OT_import_network(BattenOperator, bpy.types.Operator, ImportHelper):
    """Draw a batten JSON curve network as curve objects in a new collection"""

    bl_idname = "batten.import_network"
    bl_label = "Import batten Network"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def run(self, context):
        coll = api.load_network(self.filepath)
        if context.scene.batten.source is None:
            context.scene.batten.source = coll
        self.report({"INFO"}, f"Drew {len(coll.objects)} curves into '{coll.name}'")
        return {"FINISHED"}


class BATTEN_OT_fair_curves(ModalJob, bpy.types.Operator):
    """Refit the selected curves as fair NURBS splines within the fair tolerance (all of them,
    or none if one fails)"""

    bl_idname = "batten.fair_curves"
    bl_label = "Fair Curves"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return any(o.type == "CURVE" for o in context.selected_objects)

    def job(self, context):
        selected = [o for o in context.selected_objects if o.type == "CURVE"]
        return api.start(api.fair_curves, selected, tolerance=context.scene.batten.fair_tolerance)

    def finish(self, context, done):
        worst = max(r["max_deviation"] for r in done)
        self.report({"INFO"}, f"Faired {len(done)} curve(s); largest deviation {worst * 1e3:.2f} mm")
        return {"FINISHED"}


class BATTEN_OT_fair_surface(ModalJob, bpy.types.Operator):
    """Fair the hull through its families of plane sections (stations, waterlines), each point
    kept within the surface tolerance; the outline, midship, flats and knuckles stay fixed"""

    bl_idname = "batten.fair_surface"
    bl_label = "Fair Surface"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        settings = context.scene.batten
        return settings.source is not None and bool(settings.surface_fair_families)

    def job(self, context):
        settings = context.scene.batten
        families = [f for f in ("stations", "waterlines", "buttocks") if f in settings.surface_fair_families]
        return api.start(
            api.fair_surface, settings.source, tolerance=settings.surface_fair_tolerance, families=families
        )

    def finish(self, context, report):
        before, after = report["before"], report["after"]
        moved = sum(1 for c in report["curves"] if c["moves"] > 0)
        self.report(
            {"INFO"},
            f"Faired {moved} section(s): {report['smoothed']} smoothed along themselves "
            f"({report['smoothing_length']:.2f} m), {report['moves']} move(s) in "
            f"{report['rounds']} round(s); curvature variation "
            f"{before['curvature_variation']:.4g} → {after['curvature_variation']:.4g} /m³, "
            f"inflections {before['inflections']} → {after['inflections']}; largest move "
            f"{report['max_deviation'] * 1e3:.2f} mm",
        )
        return {"FINISHED"}


class BATTEN_OT_import_sections(ModalJob, bpy.types.Operator, ImportHelper):
    """Import sections or offsets (neutral JSON point lists, or CSV rows name,x,y,z) as fair curves"""

    bl_idname = "batten.import_sections"
    bl_label = "Import Sections / Offsets"
    bl_options = {"REGISTER", "UNDO"}

    filter_glob: StringProperty(default="*.json;*.csv", options={"HIDDEN"})
    tolerance: FloatProperty(
        name="Tolerance", default=api.DEFAULT_SECTION_TOLERANCE, min=1e-6, max=1.0, precision=4, unit="LENGTH"
    )

    def job(self, context):
        return api.start(api.import_sections, self.filepath, tolerance=self.tolerance)

    def finish(self, context, result):
        coll, reports = result
        worst = max(r["max_deviation"] for r in reports)
        self.report(
            {"INFO"}, f"Imported {len(reports)} curves into '{coll.name}'; worst {worst * 1e3:.2f} mm"
        )
        return {"FINISHED"}


class _LinesPlanOptions:
    """The choices of a lines plan of the scene's hull (it needs one): how many stations, and
    the draft of its DWL (the Hydrostatics panel's draft)."""

    stations: IntProperty(
        name="Stations",
        description="Stations from AP to FP inclusive (21: stations 0 to 20)",
        default=21,
        min=2,
        max=201,
    )

    @classmethod
    def poll(cls, context):
        return context.scene.batten.source is not None

    def plan_options(self, context) -> dict:
        """The keyword arguments of :func:`batten.api.lines_plan`."""
        return {"stations": self.stations, "draft": draft_of(context.scene.batten)}


class BATTEN_OT_lines_plan(BattenOperator, _LinesPlanOptions, bpy.types.Operator):
    """Draw the hull's lines plan (body plan, profile, half-breadth plan, title block) in a scene
    of its own, seen by an orthographic camera"""

    bl_idname = "batten.lines_plan"
    bl_label = "Lines Plan"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        source = context.scene.batten.source
        options = self.plan_options(context)
        scene = api.lines_plan_scene(source, **options)
        if scene != context.scene:
            # The plan's scene names the hull and its draft, so it can be drawn again from there.
            scene.batten.source = source
            scene.batten.draft = options["draft"]
        if context.window is not None:
            context.window.scene = scene
        self.report({"INFO"}, f"Drew the lines plan of '{source.name}' in scene '{scene.name}'")
        return {"FINISHED"}


class BATTEN_OT_export_lines_plan(ModalJob, _LinesPlanOptions, bpy.types.Operator, ExportHelper):
    """Write the hull's lines plan as PDF (A3, to scale), SVG, DXF (a layer per family) or PNG"""

    bl_idname = "batten.export_lines_plan"
    bl_label = "Export Lines Plan"
    bl_options = {"REGISTER"}

    filename_ext = ".pdf"
    filter_glob: StringProperty(default="*.pdf;*.svg;*.dxf;*.png", options={"HIDDEN"})
    file_format: EnumProperty(
        name="Format",
        items=(
            (".pdf", "PDF", "A3 sheet to a standard scale, vector"),
            (".svg", "SVG", "A3 sheet to a standard scale, vector"),
            (".dxf", "DXF", "Full size in metres, a layer per family, for CAD"),
            (".png", "PNG", "A picture 2400 pixels wide"),
        ),
        default=".pdf",
    )

    def check(self, _context):
        """Keep the file name's suffix that of the chosen format."""
        wanted = bpy.path.ensure_ext(bpy.path.abspath(self.filepath).rsplit(".", 1)[0], self.file_format)
        changed = wanted != self.filepath
        self.filepath = wanted
        return changed

    def job(self, context):
        source = context.scene.batten.source
        return api.start(api.lines_plan, source, self.filepath, **self.plan_options(context))

    def finish(self, context, path):
        self.report({"INFO"}, f"Wrote {path}")
        return {"FINISHED"}


class BATTEN_OT_show_curvature(HullOperator, bpy.types.Operator):
    """Colour the hull surface by its Gaussian or mean curvature (blue negative, white zero, red
    positive), shown in Solid mode with Attribute colour; the map follows rebuilds"""

    bl_idname = "batten.show_curvature"
    bl_label = "Curvature Map"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        scale = settings.curvature_scale if settings.curvature_scale > 0.0 else None
        info = api.show_curvature(settings.source, kind=settings.curvature_kind, scale=scale)
        # Show the colours where the user looks: Solid shading coloured by the attribute.
        for area in context.screen.areas if context.screen else ():
            if area.type == "VIEW_3D":
                shading = area.spaces.active.shading
                if shading.type == "WIREFRAME":
                    shading.type = "SOLID"
                if shading.type == "SOLID":
                    shading.color_type = "VERTEX"
        unit = "1/m²" if info["kind"] == "gaussian" else "1/m"
        self.report(
            {"INFO"},
            f"{info['kind'].capitalize()} curvature: full colour at ±{info['scale']:.3g} {unit}; "
            f"range {info['min']:.3g} to {info['max']:.3g} {unit}",
        )
        return {"FINISHED"}


class BATTEN_OT_clear_curvature(HullOperator, bpy.types.Operator):
    """Remove the curvature map from the hull surface"""

    bl_idname = "batten.clear_curvature"
    bl_label = "Clear Curvature Map"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        if not api.clear_curvature(context.scene.batten.source):
            self.report({"INFO"}, "The surface has no curvature map")
        for area in context.screen.areas if context.screen else ():
            if area.type == "VIEW_3D" and area.spaces.active.shading.color_type == "VERTEX":
                area.spaces.active.shading.color_type = "MATERIAL"
        return {"FINISHED"}


def _menu_import(self, _context):
    self.layout.operator(BATTEN_OT_import_network.bl_idname, text="batten Network (.json)")
    self.layout.operator(BATTEN_OT_import_sections.bl_idname, text="batten Sections / Offsets (.json, .csv)")


def _menu_export(self, _context):
    self.layout.operator(BATTEN_OT_export_network.bl_idname, text="batten Network (.json)")
    self.layout.operator(BATTEN_OT_export_lines_plan.bl_idname, text="batten Lines Plan (.pdf, .svg, .dxf)")


_CLASSES = (
    BATTEN_OT_build,
    BATTEN_OT_select_curves,
    BATTEN_OT_add_example,
    BATTEN_MT_add_example,
    BATTEN_OT_export_network,
    BATTEN_OT_import_network,
    BATTEN_OT_fair_curves,
    BATTEN_OT_fair_surface,
    BATTEN_OT_show_curvature,
    BATTEN_OT_clear_curvature,
    BATTEN_OT_import_sections,
    BATTEN_OT_lines_plan,
    BATTEN_OT_export_lines_plan,
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
