"""The batten tab in the 3D viewport's sidebar."""

import bpy

from ._registry import register_classes, unregister_classes


class VIEW3D_PT_batten(bpy.types.Panel):
    """Hull settings, network import/export, and the active curve's role."""

    bl_label = "batten"
    bl_idname = "VIEW3D_PT_batten"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "batten"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.batten
        col = layout.column()
        col.prop(settings, "source")
        col.prop(settings, "tolerance")
        col.prop(settings, "resolution")
        col.prop(settings, "mirror")
        row = layout.row(align=True)
        row.operator("batten.import_network", text="Import", icon="IMPORT")
        row.operator("batten.export_network", text="Export", icon="EXPORT")
        box = layout.box()
        box.label(text="Fairing", icon="SMOOTHCURVE")
        box.prop(settings, "fair_tolerance")
        box.operator("batten.fair_curves")
        row = box.row(align=True)
        row.prop(settings, "show_combs", toggle=True)
        row.prop(settings, "comb_scale", text="Scale")
        obj = context.active_object
        if obj is not None and obj.type == "CURVE":
            box = layout.box()
            box.label(text=obj.name, icon="CURVE_DATA")
            box.prop(obj.batten, "role")


_CLASSES = (VIEW3D_PT_batten,)


def register():
    """Register the panel."""
    register_classes(_CLASSES)


def unregister():
    """Unregister the panel."""
    unregister_classes(_CLASSES)
