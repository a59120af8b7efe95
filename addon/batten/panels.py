"""The batten tab in the 3D viewport's sidebar, and its Hydrostatics sub-panel."""

import json
import textwrap

import bpy

from . import api, form_compare, hierarchy, hydro_table
from ._registry import register_classes, unregister_classes
from .properties import FORM_PARAMETERS

#: Characters per line of a hydrostatics error in the panel (the message names where a hole
#: is, and would otherwise run off the sidebar).
ERROR_LINE_CHARS = 48


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
        row.scale_y = 1.3
        row.operator("batten.build", icon="MOD_SMOOTH")
        row.prop(settings, "live", toggle=True, icon="REC" if settings.live else "PLAY")
        layout.prop(settings, "show_network")
        _draw_report(layout, settings.last_report)
        row = layout.row(align=True)
        row.operator("batten.import_network", text="Import", icon="IMPORT")
        row.operator("batten.export_network", text="Export", icon="EXPORT")
        box = layout.box()
        box.label(text="Fairing", icon="SMOOTHCURVE")
        box.prop(settings, "fair_tolerance")
        box.operator("batten.fair_curves")
        col = box.column(align=True)
        col.prop(settings, "surface_fair_tolerance")
        col.row(align=True).prop(settings, "surface_fair_families", expand=True)
        col.operator("batten.fair_surface", icon="MOD_SMOOTH")
        row = box.row(align=True)
        row.prop(settings, "show_combs", toggle=True)
        row.prop(settings, "comb_scale", text="Scale")
        box = layout.box()
        box.label(text="Curvature", icon="COLORSET_01_VEC")
        row = box.row(align=True)
        row.prop(settings, "curvature_kind", expand=True)
        box.prop(settings, "curvature_scale")
        row = box.row(align=True)
        row.operator("batten.show_curvature", icon="SHADING_SOLID")
        row.operator("batten.clear_curvature", text="", icon="X")
        obj = context.active_object
        if obj is not None and obj.type == "CURVE":
            box = layout.box()
            box.label(text=obj.name, icon="CURVE_DATA")
            box.prop(obj.batten, "role")


def _draw_report(layout, text: str) -> None:
    """The last build's figures and warnings; each warning can select and frame its curves."""
    if not text:
        return
    report = json.loads(text)
    box = layout.box()
    if "error" in report:
        box.alert = True
        box.label(text=report["error"], icon="ERROR")
        return
    col = box.column(align=True)
    sides = ", ".join(
        f"{c}×{n}" for n, c in sorted(report["faces_by_sides"].items(), key=lambda kv: int(kv[0]))
    )
    col.label(text=f"Patches: {report['faces']} ({sides}-sided)")
    col.label(text=f"Open edges: {report['open_edges']}")
    rebuild = report.get("rebuild")
    if rebuild is not None and rebuild["kind"] == "incremental":
        col.label(text=f"Live: {rebuild['faces']} of {rebuild['of']} patches rebuilt", icon="TIME")
    if not report.get("measured", True):
        col.label(text="Figures below: last measured, again when the edits pause", icon="INFO")
    col.label(text=f"Max gap: {report['max_gap'] * 1e3:.3f} mm")
    where = report.get("max_normal_angle_curve")
    on = f" (on {where})" if where else ""
    col.label(text=f"Max normal jump: {report['max_normal_angle_deg']:.4f}°{on}")
    defects = col.row()
    holes, folds = report.get("holes", 0), report.get("folds", 0)
    defects.alert = bool(holes or folds)
    defects.label(text=f"Holes: {holes}, folds: {folds}")
    for name, lo, hi in report["crease_angles_deg"]:
        col.label(text=f"Crease {name}: {lo:.1f}°–{hi:.1f}°")
    found, corners = knuckles_found(report)
    if found:
        row = col.row()
        row.label(text=f"Knuckles found: {_names(found)}", icon="SHARPCURVE")
        row.operator("batten.select_curves", text="", icon="RESTRICT_SELECT_OFF").names = "\n".join(
            found_knuckle_objects(report)
        )
        col.label(text=f"  at corners of {_names(corners)}")
    col.label(text=f"Enclosed volume (to the top): {report['enclosed_volume']:.2f} m³")
    if report.get("hierarchy_moved"):
        col.label(text=f"Followed their parents: {_names(report['hierarchy_moved'])}", icon="LINKED")
    if report.get("hierarchy_error"):
        row = box.row()
        row.alert = True
        row.label(text=report["hierarchy_error"], icon="ERROR")
    for warning in report["warnings"]:
        row = box.row()
        row.label(text=warning["message"], icon="ERROR")
        if warning["objects"]:
            row.operator("batten.select_curves", text="", icon="RESTRICT_SELECT_OFF").names = "\n".join(
                warning["objects"]
            )


def _names(names: list[str], most: int = 6) -> str:
    """``a, b, c``; past ``most`` names the first ones and how many more."""
    if len(names) <= most:
        return ", ".join(names)
    return f"{', '.join(names[: most - 1])} … (+{len(names) - most + 1})"


def knuckles_found(report: dict) -> tuple[list[str], list[str]]:
    """The curves with automatically found knuckle edges, and the crossing curves whose corners
    made them knuckles (both sorted, without repeats), from a build report."""
    auto = [k for k in report.get("knuckle_edges", []) if k["source"] == "auto"]
    return sorted({k["curve"] for k in auto}), sorted({c for k in auto for c in k["corner_curves"]})


def found_knuckle_objects(report: dict) -> list[str]:
    """The curve objects with automatically found knuckle edges (sorted, without repeats),
    from a build report."""
    return sorted({o for k in report.get("knuckle_edges", []) if k["source"] == "auto" for o in k["objects"]})


class _SubPanel:
    """Where batten's sub-panels sit: in the batten tab, under the main panel, closed at first."""

    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "batten"
    bl_parent_id = VIEW3D_PT_batten.bl_idname
    bl_options = {"DEFAULT_CLOSED"}


class VIEW3D_PT_batten_hydrostatics(_SubPanel, bpy.types.Panel):
    """The hull's hydrostatics: flotation, the table of figures, plots, CSV and floating."""

    bl_label = "Hydrostatics"
    bl_idname = "VIEW3D_PT_batten_hydrostatics"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.batten
        col = layout.column(align=True)
        for name in ("draft", "trim", "heel", "density", "lpp"):
            col.prop(settings, name)
        row = layout.row(align=True)
        row.scale_y = 1.3
        row.operator("batten.hydrostatics", text="Compute", icon="MOD_FLUID")
        row.prop(settings, "show_waterline", toggle=True, icon="MOD_OCEAN")
        _draw_figures(layout, settings.last_hydrostatics)
        box = layout.box()
        box.label(text="Plots", icon="IMAGE_DATA")
        row = box.row(align=True)
        row.prop(settings, "stations")
        row.operator("batten.sectional_areas")
        row = box.row(align=True)
        row.prop(settings, "curves_draft_min")
        row.prop(settings, "curves_draft_max")
        row = box.row(align=True)
        row.prop(settings, "curves_drafts")
        row.operator("batten.curves_of_form")
        row = box.row(align=True)
        row.operator("batten.lines_plan", icon="MESH_GRID").stations = settings.stations
        row.operator("batten.export_lines_plan", text="", icon="EXPORT").stations = settings.stations
        row = layout.row(align=True)
        row.operator("batten.export_hydrostatics", text="Export CSV", icon="EXPORT").table = "HYDROSTATICS"
        row.operator(
            "batten.export_hydrostatics", text="Curves of Form CSV", icon="EXPORT"
        ).table = "CURVES_OF_FORM"
        box = layout.box()
        box.label(text="Float", icon="FORCE_BOID")
        col = box.column(align=True)
        col.prop(settings, "float_displacement", text="Δ (t)")
        col.prop(settings, "float_lcg")
        box.operator("batten.float_to")


class VIEW3D_PT_batten_form(_SubPanel, bpy.types.Panel):
    """The hull's form topology (seed 002): its measured parameters, a parametric change into a
    copy on the transformation stack, the stack, and commit / keep / abandon."""

    bl_label = "Form"
    bl_idname = "VIEW3D_PT_batten_form"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.batten
        source = settings.source
        row = layout.row(align=True)
        row.operator("batten.measure_form", icon="DRIVER_DISTANCE")
        row.prop(settings, "show_form", text="", icon="HIDE_OFF" if settings.show_form else "HIDE_ON")
        _draw_form(layout, settings.last_form, source)
        box = layout.box()
        box.label(text="Change", icon="MOD_SIMPLEDEFORM")
        row = box.row(align=True)
        row.prop(settings, "form_parameter", text="")
        row.prop(settings, "form_value", text="")
        box.operator("batten.transform", icon="DUPLICATE")
        col = box.column(align=True)
        col.prop(settings, "form_vertex")
        col.prop(settings, "form_move", text="")
        row = col.row(align=True)
        row.operator("batten.move_form_vertex", icon="EMPTY_ARROWS")
        row.operator("batten.drag_form_vertex", icon="RESTRICT_SELECT_OFF")
        box = layout.box()
        box.label(text="Hydrostatic targets", icon="MOD_FLUIDSIM")
        row = box.row(align=True)
        row.prop(settings, "hydro_volume_target", text="")
        sub = row.row(align=True)
        sub.enabled = settings.hydro_volume_target != "hold"
        sub.prop(settings, "hydro_volume_value", text="")
        row = box.row(align=True)
        row.prop(settings, "hydro_use_lcb")
        sub = row.row(align=True)
        sub.enabled = settings.hydro_use_lcb
        sub.prop(settings, "hydro_lcb", text="")
        row = box.row(align=True)
        row.prop(settings, "hydro_keep_pmb", text="")
        row.operator("batten.transform_hydrostatic", icon="DUPLICATE")
        _draw_hydro_change(layout, settings.last_hydro_transform, source)
        try:
            stack = api.transform_stack(source) if source is not None else []
        except api.BattenError:
            stack = []
        if len(stack) > 1:
            box = layout.box()
            box.label(text="Stack", icon="LINENUMBERS_ON")
            col = box.column(align=True)
            for entry in stack:
                coll = entry["collection"]
                text = f"{entry['index']}: {entry['description']}" if entry["index"] else coll.name
                icon = "RADIOBUT_ON" if coll == source else "RADIOBUT_OFF"
                col.operator("batten.select_transform", text=text, icon=icon).collection = coll.name
            row = box.row(align=True)
            row.operator("batten.commit_transform", icon="CHECKMARK")
            row.operator("batten.keep_transform", text="Keep", icon="DUPLICATE")
            row.operator("batten.abandon_transforms", text="", icon="X")
            row = box.row(align=True)
            row.operator("batten.compare_transform", icon="ARROW_LEFTRIGHT")
            row.prop(
                settings,
                "show_comparison",
                text="",
                icon="HIDE_OFF" if settings.show_comparison else "HIDE_ON",
            )
        _draw_change(layout, settings.last_transform)
        _draw_comparison(layout, settings.last_comparison, source)
        _draw_hierarchy(layout, context)


#: The other measured parameters the Form panel lists, with their labels (metres).
FORM_ROWS = (
    ("length", "Length"),
    ("draft", "Draft"),
    ("waterline_breadth", "Bwl"),
    ("rise_of_floor", "Rise of floor"),
)


def _form_rows():
    return [(key, label) for key, label, _ in FORM_PARAMETERS] + list(FORM_ROWS)


def _metres(value) -> str:
    return "—" if value is None else f"{value:.3f} m"


def _draw_form(layout, text: str, source) -> None:
    """The form parameters last measured for ``source`` (nothing when they were measured for
    another hull)."""
    if not text or source is None:
        return
    form = json.loads(text)
    if form.get("source") != source.name:
        return
    p = form["parameters"]
    col = layout.box().column(align=True)
    for key, label in _form_rows():
        split = col.split(factor=0.55, align=True)
        split.label(text=label)
        split.label(text=_metres(p.get(key)))
    if p.get("no_pmb_reason"):
        for i, line in enumerate(textwrap.wrap(f"No PMB: {p['no_pmb_reason']}", ERROR_LINE_CHARS)):
            col.label(text=line, icon="INFO" if i == 0 else "BLANK1")


def _draw_change(layout, text: str) -> None:
    """The last transformation: each parameter before and after."""
    if not text:
        return
    change = json.loads(text)
    box = layout.box()
    box.label(text=f"{change['copy']}: {change['description']}", icon="SORTSIZE")
    col = box.column(align=True)
    for key, label in _form_rows():
        before, after = change["before"].get(key), change["after"].get(key)
        if before is None and after is None:
            continue
        split = col.split(factor=0.4, align=True)
        split.label(text=label)
        split.label(text=f"{_metres(before)} → {_metres(after)}")


def _draw_hierarchy(layout, context) -> None:
    """The curve network hierarchy and the curves' attributes (seed 002 §5, §7.1): attach the
    selected curves' ends or crossing points to the active curve or detach them, hold them in a
    plane or release them, give points of the curve being edited a point attribute and the
    selected curves a curve attribute; and the active curve's attributes, what it is attached
    to, carries and is held in."""
    box = layout.box()
    box.label(text="Hierarchy", icon="LINKED")
    row = box.row(align=True)
    row.operator_menu_enum("batten.attach_curves", "what", text="Attach to Active", icon="LINKED")
    row.operator("batten.detach_curves", icon="UNLINKED")
    row = box.row(align=True)
    row.operator_menu_enum("batten.hold_in_plane", "plane", icon="MESH_PLANE")
    row.operator("batten.release_plane", text="", icon="X")
    row = box.row(align=True)
    row.operator_menu_enum("batten.set_point_attribute", "kind", icon="HANDLE_VECTOR")
    row.operator("batten.clear_point_attributes", text="", icon="X")
    row.operator("batten.make_bezier", text="", icon="IPO_BEZIER")
    row = box.row(align=True)
    row.operator_menu_enum("batten.set_curve_attribute", "kind", icon="IPO_CONSTANT")
    active = context.view_layer.objects.active
    if active is None or active.type != "CURVE":
        return
    col = box.column(align=True)
    try:
        _draw_attachments(col, active)
    except api.BattenError as e:
        row = col.row()
        row.alert = True
        row.label(text=str(e), icon="ERROR")


def _draw_attachments(col, active) -> None:
    """What the curve object ``active`` carries: its curve and point attributes, its plane,
    what it is attached to and what is attached to it (BattenError where a stored property is
    broken)."""
    attributes = api.curve_attributes(active)
    if any(attributes.values()):
        on = [k for k, v in attributes.items() if v]
        col.label(text=f"{active.name}: curve attribute {', '.join(on)}")
    for a in hierarchy.point_attributes_of(active):
        pair = (
            f"points {a['point']}–{a['point'] + 1}"
            if a["kind"] in ("straight", "blend")
            else f"point {a['point']}"
        )
        col.label(text=f"{a['kind'].capitalize()} on {pair}")
    plane = hierarchy.plane_of(active)
    if plane is not None:
        n, d = plane
        col.label(text=f"{active.name} in the plane ({n[0]:.3f}, {n[1]:.3f}, {n[2]:.3f})·p = {d:.4g}")
    for a in hierarchy.attachments_of(active):
        col.label(text=f"{active.name} {hierarchy.anchor(a)} → {a['parent']} (t {a['t']:.4g})")
    children = sorted(
        o.name
        for o in bpy.data.objects
        if any(a["parent"] == active.name for a in hierarchy.attachments_of(o))
    )
    if children:
        col.label(text=f"Carries: {_names(children)}")


def _draw_hydro_change(layout, text: str, source) -> None:
    """The last hydrostatic transformation, while its copy is the panel's hull: each figure
    before → after (and the target), the evaluations, and why it stopped."""
    if not text or source is None:
        return
    change = json.loads(text)
    if change.get("copy") != source.name:
        return
    box = layout.box()
    box.label(text=f"{change['copy']}: {change['description']}", icon="SORTSIZE")
    col = box.column(align=True)
    for row in change["rows"]:
        fmt = row["format"]
        split = col.split(factor=0.3, align=True)
        split.label(text=row["label"])
        split = split.split(factor=0.6, align=True)
        split.label(text=f"{fmt.format(row['before'])} → {fmt.format(row['after'])}")
        split.label(text="—" if row["aim"] is None else fmt.format(row["aim"]))
    pmb, bulge = change["pmb_length"], change.get("bulge")
    if pmb is not None:
        col.label(text=f"PMB {pmb[0]:.3f} → {pmb[1]:.3f} m")
    if bulge is not None:
        col.label(text=f"Bulge: entrance {bulge[0]:+.3f} m, run {bulge[1]:+.3f} m")
    col.label(text=f"{change['evaluations']} hull evaluations")
    if change["stop"] != "converged":
        text = f"{change['stop'].replace('_', ' ')}: {change['limit'] or 'targets not met'}"
        for i, line in enumerate(textwrap.wrap(text, ERROR_LINE_CHARS)):
            col.label(text=line, icon="ERROR" if i == 0 else "BLANK1")


def _draw_comparison(layout, text: str, source) -> None:
    """The last comparison of ``source`` (a copy) with its original: each dimension and
    hydrostatic figure of both, and the change (nothing when it was made for another hull)."""
    if not text or source is None:
        return
    comparison = json.loads(text)
    if comparison.get("copy") != source.name:
        return
    box = layout.box()
    box.label(
        text=f"Beside '{comparison['original']}' at T = {comparison['draft']:.3f} m", icon="ARROW_LEFTRIGHT"
    )
    col = box.column(align=True)
    for group, rows in (
        ("Dimensions", comparison["dimensions"]),
        ("Hydrostatics", comparison["hydrostatics"]),
    ):
        col.label(text=group)
        for row in rows:
            split = col.split(factor=0.3, align=True)
            split.label(text=row["label"])
            split = split.split(factor=0.55, align=True)
            split.label(
                text=f"{form_compare.value_text(row, 'original')} → {form_compare.value_text(row, 'copy')}"
            )
            split.label(text=form_compare.change_text(row) if row["change"] is not None else "—")


def _draw_figures(layout, text: str) -> None:
    """The last hydrostatics as a table of figures with units, by group; or its error."""
    if not text:
        return
    figures = json.loads(text)
    box = layout.box()
    if "error" in figures:
        box.alert = True
        col = box.column(align=True)
        for i, line in enumerate(textwrap.wrap(figures["error"], ERROR_LINE_CHARS)):
            col.label(text=line, icon="ERROR" if i == 0 else "BLANK1")
        return
    col = box.column(align=True)
    for group, rows in hydro_table.GROUPS:
        col.label(text=group)
        for row in rows:
            split = col.split(factor=0.55, align=True)
            split.label(text=row.label)
            split.label(text=hydro_table.value_text(row, figures))


_CLASSES = (VIEW3D_PT_batten, VIEW3D_PT_batten_hydrostatics, VIEW3D_PT_batten_form)


def register():
    """Register the panel."""
    register_classes(_CLASSES)


def unregister():
    """Unregister the panel."""
    unregister_classes(_CLASSES)
