"""File ▸ Export ▸ batten Hull Surface (.igs, .stp, .3dm): operators that only call
:mod:`batten.api` (the exports and their errors are there)."""

import bpy
from bpy.props import BoolProperty, FloatProperty, StringProperty
from bpy_extras.io_utils import ExportHelper

from . import api
from ._registry import register_classes, unregister_classes
from .modal_jobs import ModalJob
from .operators import _hull_source


class _CadExport(ModalJob, ExportHelper):
    """The shared body: the hull's surface written by ``api.<export>`` within ``tolerance``."""

    export = ""
    bl_options = {"REGISTER"}
    tolerance: FloatProperty(
        name="Tolerance",
        description="Largest deviation of the exported faces from batten's surface",
        default=api.DEFAULT_EXPORT_TOLERANCE,
        min=1e-7,
        max=0.01,
        precision=5,
        unit="LENGTH",
    )
    allow_holes: BoolProperty(
        name="Allow Holes", description="Write what exists even if the surface has holes", default=False
    )

    def job(self, context):
        export = getattr(api, self.export)
        source = _hull_source(context)
        options = {"tolerance": self.tolerance, "allow_holes": self.allow_holes}
        return api.start(export, source, self.filepath, **options)

    def finish(self, context, path):
        self.report({"INFO"}, f"Wrote {path}")
        return {"FINISHED"}


class BATTEN_OT_export_iges(_CadExport, bpy.types.Operator):
    """Write the hull surface as IGES 5.3 B-spline surfaces (entity 128), in metres"""

    bl_idname = "batten.export_iges"
    bl_label = "Export Hull Surface (IGES)"
    export = "export_iges"
    filename_ext = ".igs"
    filter_glob: StringProperty(default="*.igs;*.iges", options={"HIDDEN"})


class BATTEN_OT_export_step(_CadExport, bpy.types.Operator):
    """Write the hull surface as a STEP AP214 shell of B-spline faces, in metres"""

    bl_idname = "batten.export_step"
    bl_label = "Export Hull Surface (STEP)"
    export = "export_step"
    filename_ext = ".stp"
    filter_glob: StringProperty(default="*.stp;*.step", options={"HIDDEN"})


class BATTEN_OT_export_3dm(_CadExport, bpy.types.Operator):
    """Write the hull surface as Rhino NURBS surfaces (.3dm), in metres"""

    bl_idname = "batten.export_3dm"
    bl_label = "Export Hull Surface (Rhino)"
    export = "export_3dm"
    filename_ext = ".3dm"
    filter_glob: StringProperty(default="*.3dm", options={"HIDDEN"})


_CLASSES = (BATTEN_OT_export_iges, BATTEN_OT_export_step, BATTEN_OT_export_3dm)


def _menu_export(self, _context):
    self.layout.operator(BATTEN_OT_export_iges.bl_idname, text="batten Hull Surface (.igs)")
    self.layout.operator(BATTEN_OT_export_step.bl_idname, text="batten Hull Surface (.stp)")
    self.layout.operator(BATTEN_OT_export_3dm.bl_idname, text="batten Hull Surface (.3dm)")


def register():
    """Register the operators and their File ▸ Export entries (safe to call twice)."""
    register_classes(_CLASSES)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)


def unregister():
    """Remove the menu entries and operators."""
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    unregister_classes(_CLASSES)
