"""The Hydrostatics panel's operators: compute the figures, plot the sectional area curve and
the curves of form, export them as CSV, float the hull at a displacement. Each converts the
scene's settings, calls :mod:`batten.api` and keeps the figures (or the error) in the scene.
"""

import bpy
import numpy as np
from bpy.props import EnumProperty, StringProperty
from bpy_extras.io_utils import ExportHelper

from . import api, hydro_plot, hydro_table
from ._registry import register_classes, unregister_classes
from .operator_base import HullOperator
from .scene_hydro import draft_of, figures_kept_in, flotation, hydrostatics_into_scene, keep_figures, typed


class BATTEN_OT_hydrostatics(HullOperator, bpy.types.Operator):
    """Compute the hull's hydrostatics at the draft, trim, heel and density"""

    bl_idname = "batten.hydrostatics"
    bl_label = "Compute Hydrostatics"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        f = hydrostatics_into_scene(context.scene)
        self.report(
            {"INFO"},
            f"∇ = {f['volume']:,.2f} m³, Δ = {f['displacement']:,.2f} t at T = {f['draft_mid']:.3f} m",
        )
        return {"FINISHED"}


class BATTEN_OT_sectional_areas(HullOperator, bpy.types.Operator):
    """Plot the sectional area curve at the draft, trim and heel into the image '<hull> SAC'"""

    bl_idname = "batten.sectional_areas"
    bl_label = "Sectional Areas"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        figures = hydrostatics_into_scene(context.scene)
        at = flotation(settings)
        with figures_kept_in(settings):
            xs, areas = api.sectional_areas(
                settings.source,
                draft_of(settings),
                settings.stations,
                trim=at["trim"],
                heel=at["heel"],
                lpp=at["lpp"],
            )
        hull = settings.source.name
        image = hydro_plot.plot_image(
            hydro_plot.sac_image_name(hull), lambda path: hydro_plot.sac_png(hull, xs, areas, figures, path)
        )
        hydro_plot.show_in_image_editors(context, image)
        self.report({"INFO"}, f"Sectional area curve in image '{image.name}'")
        return {"FINISHED"}


def _curves_of_form(settings) -> list[dict]:
    """The curves of form over the panel's draft range (even keel)."""
    drafts = np.linspace(
        typed(settings.curves_draft_min), typed(settings.curves_draft_max), settings.curves_drafts
    )
    at = flotation(settings)
    return api.curves_of_form(settings.source, drafts, lpp=at["lpp"], density=at["density"])


class BATTEN_OT_curves_of_form(HullOperator, bpy.types.Operator):
    """Plot the curves of form over the draft range into the image '<hull> curves of form'"""

    bl_idname = "batten.curves_of_form"
    bl_label = "Curves of Form"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        with figures_kept_in(settings):
            rows = _curves_of_form(settings)
        hull = settings.source.name
        image = hydro_plot.plot_image(
            hydro_plot.curves_of_form_image_name(hull),
            lambda path: hydro_plot.curves_of_form_png(hull, rows, path),
        )
        hydro_plot.show_in_image_editors(context, image)
        self.report({"INFO"}, f"Curves of form ({len(rows)} drafts) in image '{image.name}'")
        return {"FINISHED"}


class BATTEN_OT_export_hydrostatics(HullOperator, bpy.types.Operator, ExportHelper):
    """Write the hydrostatics at the draft, or the curves of form over the draft range, as CSV
    (computed afresh; the file is the only thing written)"""

    bl_idname = "batten.export_hydrostatics"
    bl_label = "Export Hydrostatics CSV"
    bl_options = {"REGISTER"}

    filename_ext = ".csv"
    filter_glob: StringProperty(default="*.csv", options={"HIDDEN"})
    table: EnumProperty(
        name="Table",
        items=[
            ("HYDROSTATICS", "Hydrostatics", "The figures at the draft, trim and heel, one per line"),
            (
                "CURVES_OF_FORM",
                "Curves of form",
                "The figures at each draft of the range, one draft per line",
            ),
        ],
        default="HYDROSTATICS",
    )

    def run(self, context):
        settings = context.scene.batten
        try:
            if self.table == "CURVES_OF_FORM":
                path = hydro_table.curves_of_form_csv(_curves_of_form(settings), self.filepath)
            else:
                figures = api.hydrostatics(settings.source, draft_of(settings), **flotation(settings))
                path = hydro_table.hydrostatics_csv(figures, self.filepath)
        except OSError as e:
            self.report({"ERROR"}, f"CSV file '{self.filepath}': {e.strerror or e}")
            return {"CANCELLED"}
        self.report({"INFO"}, f"Wrote {path}")
        return {"FINISHED"}


class BATTEN_OT_float_to(HullOperator, bpy.types.Operator):
    """Find the draft and trim at which the hull floats at the displacement with its centre of
    buoyancy under the LCG, and set them"""

    bl_idname = "batten.float_to"
    bl_label = "Float at Displacement"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        with figures_kept_in(settings):
            f = api.float_to(
                settings.source,
                typed(settings.float_displacement),
                typed(settings.float_lcg),
                density=flotation(settings)["density"],
                lpp=flotation(settings)["lpp"],
            )
        settings.draft, settings.trim, settings.heel = f["draft_mid"], f["trim"], np.radians(f["heel"])
        keep_figures(settings, f)
        self.report(
            {"INFO"}, f"Floats at T = {f['draft_mid']:.3f} m, trim {f['trim']:.3f} m (LCB {f['lcb']:.3f} m)"
        )
        return {"FINISHED"}


_CLASSES = (
    BATTEN_OT_hydrostatics,
    BATTEN_OT_sectional_areas,
    BATTEN_OT_curves_of_form,
    BATTEN_OT_export_hydrostatics,
    BATTEN_OT_float_to,
)


def register():
    """Register the operators."""
    register_classes(_CLASSES)


def unregister():
    """Unregister the operators."""
    unregister_classes(_CLASSES)
