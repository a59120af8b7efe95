"""Operators of the Form panel (seed 002): measure the hull's form topology, change one of its
parameters into a copy on the transformation stack, pick a copy, and commit, keep or abandon
(§7.2.5, §9). They call :mod:`batten.api` only and keep what the panel shows in the scene."""

import json

import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, StringProperty

from . import api, hierarchy, hydro_plot, spline_joints
from ._registry import register_classes, unregister_classes
from .operator_base import BattenOperator, HullOperator
from .scene_hydro import draft_of

#: Points per form edge drawn in the overlay.
EDGE_SAMPLES = 24
#: Points per curve of the original drawn beside a compared copy.
GHOST_SAMPLES = 48


def _drawing(source, form: dict) -> dict:
    """What the overlay draws of ``form`` (the form topology of ``source``): the vertices'
    positions, and each edge's kind and points along its curve."""
    curves = {c.name: c for c in api.read_curves(source)}
    edges = []
    for e in form["edges"]:
        curve = curves.get(e["curve"])
        if curve is None:
            continue
        ts = np.linspace(e["t0"], e["t1"], EDGE_SAMPLES)
        edges.append({"kind": e["kind"], "points": np.asarray(curve.evaluate(ts)).round(6).tolist()})
    return {"vertices": [v["position"] for v in form["vertices"]], "edges": edges}


def _switch_to(settings, result) -> None:
    """Work on the copy of ``result`` (an :class:`api.TransformResult`): the panel's source, its
    change before and after, and its form for the panel and the overlay."""
    report, copy = result.report, result.collection
    change = {key: report[key] for key in ("description", "before", "after")}
    settings.last_transform = json.dumps({"copy": copy.name, **change})
    settings.source = copy
    try:
        drawing = _drawing(copy, api.form_topology(copy))
    except api.BattenError:
        drawing = {}  # the copy is made and kept; only its overlay is missing
    settings.last_form = json.dumps({"source": copy.name, "parameters": report["after"], **drawing})


def move_vertex_into_copy(settings, vertex: int, move: tuple[float, float, float]):
    """Move form vertex ``vertex`` of the panels' hull by ``move`` into a new copy on its stack
    (:func:`batten.api.transform`) and work on the copy; returns the TransformResult."""
    result = api.transform(settings.source, moves=[(vertex, move)])
    _switch_to(settings, result)
    return result


def _is_copy(source) -> bool:
    """Whether ``source`` is a copy on a transformation stack (False when its original is gone)."""
    try:
        return source is not None and api.transform_stack(source)[0]["collection"] != source
    except api.BattenError:
        return False


class BATTEN_OT_measure_form(HullOperator, bpy.types.Operator):
    """Find the hull's form topology and measure its parameters (length, breadth, depth, PMB,
    bilge radius, entrance and run)"""

    bl_idname = "batten.measure_form"
    bl_label = "Measure Form"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        form = api.form_topology(settings.source)
        parameters = form["parameters"]
        settings.last_form = json.dumps(
            {"source": settings.source.name, "parameters": parameters, **_drawing(settings.source, form)}
        )
        value = parameters.get(settings.form_parameter)
        if value is not None:
            settings.form_value = value
        self.report({"INFO"}, f"Form of '{settings.source.name}' measured")
        return {"FINISHED"}


class BATTEN_OT_transform(HullOperator, bpy.types.Operator):
    """Change the chosen form parameter to the value given, in a new copy of the hull on its
    transformation stack (the original stays as it is until you commit)"""

    bl_idname = "batten.transform"
    bl_label = "Transform"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        result = api.transform(settings.source, **{settings.form_parameter: settings.form_value})
        _switch_to(settings, result)
        self.report({"INFO"}, f"'{result.collection.name}': {result.report['description']}")
        return {"FINISHED"}


#: The figures of a hydrostatic transformation the Form panel shows: key in the hydrostatics,
#: label, format.
HYDRO_ROWS = (
    ("volume", "∇ (m³)", "{:.2f}"),
    ("displacement", "Δ (t)", "{:.2f}"),
    ("cb", "Cb", "{:.4f}"),
    ("cp", "Cp", "{:.4f}"),
    ("lcb", "LCB (m)", "{:.3f}"),
)


def hydro_summary(result) -> dict:
    """What the Form panel shows of a hydrostatic transformation (``result`` an
    :class:`api.TransformResult` of :func:`batten.api.transform_hydrostatic`): each figure
    before, after and aimed at (None where nothing was aimed at), and how it ended."""
    r = result.report
    rows = []
    for key, label, fmt in HYDRO_ROWS:
        aims = {
            "volume": r["target_volume"],
            "displacement": r["target_volume"] * r["before"]["density"],
            "lcb": r["target_lcb"],
            r["target_figure"]: r["target_value"],
        }
        aim = aims.get(key)
        before, after = r["before"][key], r["after"][key]
        rows.append({"label": label, "format": fmt, "before": before, "after": after, "aim": aim})
    return {
        "copy": result.collection.name,
        "description": r["description"],
        "rows": rows,
        "evaluations": r["evaluations"],
        "stop": r["stop"],
        "limit": r["limit"],
        "pmb_length": r["pmb_length"],
        "bulge": None if r["bulge"] is None else r["bulge"]["offsets"],
    }


class BATTEN_OT_transform_hydrostatic(HullOperator, bpy.types.Operator):
    """Move the ends of the parallel middle body (or, without one or with Hold PMB, bulge the
    ends' faces) until the hull has the volume (∇, Δ, Cb or Cp) and LCB asked for, in a new copy
    on its transformation stack (a target beyond reach gives the closest hull, and says what
    stopped it)"""

    bl_idname = "batten.transform_hydrostatic"
    bl_label = "Reach Targets"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        targets = {}
        if settings.hydro_volume_target != "hold":
            targets[settings.hydro_volume_target] = settings.hydro_volume_value
        if settings.hydro_use_lcb:
            targets["lcb"] = settings.hydro_lcb
        if not targets:
            self.report({"ERROR"}, "Choose a volume target or tick LCB")
            return {"CANCELLED"}
        keep = {"free": False, "all": True}.get(settings.hydro_keep_pmb, settings.hydro_keep_pmb)
        result = api.transform_hydrostatic(
            settings.source, keep_pmb=keep, draft=draft_of(settings) or None, **targets
        )
        summary = hydro_summary(result)
        settings.last_hydro_transform = json.dumps(summary)
        settings.source = result.collection
        settings.last_transform = ""
        level = "INFO" if summary["stop"] == "converged" else "WARNING"
        why = "" if summary["limit"] is None else f" ({summary['limit']})"
        self.report(
            {level},
            f"'{result.collection.name}': {summary['stop'].replace('_', ' ')} in "
            f"{summary['evaluations']} hull evaluations{why}",
        )
        return {"FINISHED"}


class BATTEN_OT_move_form_vertex(HullOperator, bpy.types.Operator):
    """Move one form vertex by the translation given, in a new copy of the hull on its stack:
    the move passes along the form edges by their kind and the curves inside the faces follow"""

    bl_idname = "batten.move_form_vertex"
    bl_label = "Move Vertex"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        result = move_vertex_into_copy(settings, settings.form_vertex, tuple(settings.form_move))
        self.report({"INFO"}, f"'{result.collection.name}': {result.report['description']}")
        return {"FINISHED"}


class BATTEN_OT_select_transform(BattenOperator, bpy.types.Operator):
    """Make this hull (the original or a copy on its stack) the one the panels work on"""

    bl_idname = "batten.select_transform"
    bl_label = "Select"
    bl_options = {"REGISTER", "UNDO"}

    collection: StringProperty(name="Collection", description="The hull collection to work on")

    def run(self, context):
        coll = bpy.data.collections.get(self.collection)
        if coll is None:
            self.report({"ERROR"}, f"No collection '{self.collection}'")
            return {"CANCELLED"}
        context.scene.batten.source = coll
        return {"FINISHED"}


class _CopyOperator(BattenOperator):
    """An operator on a copy on a transformation stack (available only when the hull is one)."""

    @classmethod
    def poll(cls, context):
        return _is_copy(context.scene.batten.source)


def _ghost(source) -> list[list[list[float]]]:
    """The curves of the hull ``source`` as polylines (mm-rounded points), for the overlay."""
    out = []
    for curve in api.read_curves(source):
        ts = np.linspace(*curve.domain, GHOST_SAMPLES)
        out.append(np.asarray(curve.evaluate(ts)).round(3).tolist())
    return out


class BATTEN_OT_compare_transform(_CopyOperator, bpy.types.Operator):
    """Set this copy beside its original: main dimensions and hydrostatics at the original's design
    draft (else the Hydrostatics panel's draft) side by side, both sectional area curves in the image
    '<copy> vs original SAC', and the original's curves drawn in the viewport"""

    bl_idname = "batten.compare_transform"
    bl_label = "Compare with Original"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        copy = settings.source
        original = api.transform_stack(copy)[0]["collection"]
        draft = api.design_draft(original)
        comparison = api.compare(copy, draft=draft if draft is not None else draft_of(settings))
        image = hydro_plot.plot_image(
            hydro_plot.comparison_image_name(copy.name),
            lambda path: hydro_plot.sac_comparison_png(comparison, path),
        )
        hydro_plot.show_in_image_editors(context, image)
        shown = {
            k: comparison[k]
            for k in ("original", "copy", "description", "draft", "dimensions", "hydrostatics")
        }
        settings.last_comparison = json.dumps({**shown, "ghost": _ghost(original)})
        volume = next(r for r in comparison["hydrostatics"] if r["key"] == "volume")
        self.report(
            {"INFO"},
            f"'{copy.name}' beside '{original.name}': ∇ {volume['change_pct']:+.2f} %; "
            f"sectional areas in image '{image.name}'",
        )
        return {"FINISHED"}


class BATTEN_OT_commit_transform(_CopyOperator, bpy.types.Operator):
    """Apply this copy to the original hull's curves and drop the stack"""

    bl_idname = "batten.commit_transform"
    bl_label = "Commit"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        settings = context.scene.batten
        original = api.commit(settings.source)
        settings.source = original
        self.report({"INFO"}, f"Committed to '{original.name}'")
        return {"FINISHED"}


class BATTEN_OT_keep_transform(_CopyOperator, bpy.types.Operator):
    """Keep this copy as a hull of its own, off the stack"""

    bl_idname = "batten.keep_transform"
    bl_label = "Keep as New Hull"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        kept = api.keep(context.scene.batten.source)
        self.report({"INFO"}, f"'{kept.name}' kept as a hull of its own")
        return {"FINISHED"}


class BATTEN_OT_abandon_transforms(BattenOperator, bpy.types.Operator):
    """Drop every copy on the stack; the original stays as it is"""

    bl_idname = "batten.abandon_transforms"
    bl_label = "Abandon All"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        source = context.scene.batten.source
        try:
            return source is not None and len(api.transform_stack(source)) > 1
        except api.BattenError:
            return False

    def run(self, context):
        settings = context.scene.batten
        original = api.transform_stack(settings.source)[0]["collection"]
        removed = api.abandon(settings.source)
        settings.source = original
        self.report({"INFO"}, f"{removed} cop{'y' if removed == 1 else 'ies'} dropped")
        return {"FINISHED"}


def _selected_curves(context, *, but_active: bool = False) -> list:
    """The selected curve objects (other than the active object with ``but_active``)."""
    active = context.view_layer.objects.active if but_active else None
    return [o for o in context.selected_objects if o.type == "CURVE" and o != active]


class BATTEN_OT_attach_curves(BattenOperator, bpy.types.Operator):
    """Attach the nearer end of each selected curve to the active curve (the curve network
    hierarchy): the ends then follow it when it changes, and the curves' free points follow them"""

    bl_idname = "batten.attach_curves"
    bl_label = "Attach to Active"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        active = context.view_layer.objects.active
        return (
            active is not None and active.type == "CURVE" and bool(_selected_curves(context, but_active=True))
        )

    what: EnumProperty(
        name="Attach",
        items=[
            ("end", "Nearer End", "The end of each curve nearer the active curve"),
            (
                "point",
                "Crossing Point",
                "The point of each curve nearest the active curve (it passes through it)",
            ),
        ],
        default="end",
    )

    def run(self, context):
        parent = context.view_layer.objects.active
        children = _selected_curves(context, but_active=True)
        made = api.attach(children, parent, point="nearest" if self.what == "point" else None)
        ends = ", ".join(f"{a['child']} ({hierarchy.anchor(a)})" for a in made)
        self.report({"INFO"}, f"Attached to '{parent.name}': {ends}")
        return {"FINISHED"}


class BATTEN_OT_detach_curves(BattenOperator, bpy.types.Operator):
    """Detach the ends and points of each selected curve from the curves they are attached to
    (the curves stay where they are)"""

    bl_idname = "batten.detach_curves"
    bl_label = "Detach"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return any(hierarchy.ATTACHMENTS in o for o in _selected_curves(context))

    def run(self, context):
        count = sum(api.detach(o) for o in _selected_curves(context))
        self.report({"INFO"}, f"{count} end(s) or point(s) detached")
        return {"FINISHED"}


class BATTEN_OT_hold_in_plane(BattenOperator, bpy.types.Operator):
    """Hold each selected curve in a plane (its surface attribute): Build and Live keep it there
    whatever drags it"""

    bl_idname = "batten.hold_in_plane"
    bl_label = "Hold in Plane"
    bl_options = {"REGISTER", "UNDO"}

    plane: EnumProperty(
        name="Plane",
        items=[
            ("fit", "Its Own", "The plane the curve's control points lie closest to"),
            ("x", "Station (x)", "The plane square to x through the curve"),
            ("y", "Buttock (y)", "The plane square to y through the curve (centreplane, flat of side)"),
            ("z", "Waterplane (z)", "The plane square to z through the curve (flat of bottom)"),
        ],
        default="fit",
    )

    @classmethod
    def poll(cls, context):
        return bool(_selected_curves(context))

    def run(self, context):
        held = api.set_plane(_selected_curves(context), self.plane)
        self.report({"INFO"}, f"Held in their planes: {', '.join(h['curve'] for h in held)}")
        return {"FINISHED"}


class BATTEN_OT_release_plane(BattenOperator, bpy.types.Operator):
    """Release each selected curve from its plane (it stays where it is)"""

    bl_idname = "batten.release_plane"
    bl_label = "Release Plane"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return any(hierarchy.PLANE in o for o in _selected_curves(context))

    def run(self, context):
        count = api.clear_plane(_selected_curves(context))
        self.report({"INFO"}, f"{count} curve(s) released")
        return {"FINISHED"}


def _selected_joints(obj) -> list[int]:
    """The points of the curve object ``obj``'s spline that are selected in Edit Mode, counted
    among the points it passes through (:func:`batten.spline_joints.joint_layout`)."""
    spline = spline_joints.single_spline(obj)
    index, _ = spline_joints.joint_layout(spline, obj.name)
    if spline.type == "BEZIER":
        selected = [p.select_control_point for p in spline.bezier_points]
    else:
        selected = [p.select for p in spline.points]
    return [k for k, j in enumerate(index) if selected[j]]


_POINT_KINDS = [
    ("knuckle", "Knuckle", "A corner at each selected point"),
    ("tangent", "Tangent", "The curve passes through each selected point along a fixed direction"),
    ("straight", "Straight", "A straight line between each two neighbouring selected points"),
    ("blend", "Blend", "A blend (a radius) between each two neighbouring selected points"),
]


class BATTEN_OT_set_point_attribute(BattenOperator, bpy.types.Operator):
    """Give the selected points of the curve being edited a point attribute (a knuckle, a
    tangent, or a straight or blend between neighbouring points); Build and Live keep it as the
    curve changes"""

    bl_idname = "batten.set_point_attribute"
    bl_label = "Point Attribute"
    bl_options = {"REGISTER", "UNDO"}

    kind: EnumProperty(name="Attribute", items=_POINT_KINDS, default="knuckle")
    direction: EnumProperty(
        name="Direction",
        items=[
            ("current", "As It Runs", "The direction the curve runs through the point now"),
            ("x", "X", "Along the ship"),
            ("y", "Y", "Across the ship"),
            ("z", "Z", "Vertical"),
        ],
        default="current",
    )

    @classmethod
    def poll(cls, context):
        obj = context.edit_object
        return obj is not None and obj.type == "CURVE"

    def run(self, context):
        obj = context.edit_object
        joints = _selected_joints(obj)
        if self.kind in ("straight", "blend"):
            joints = [k for k in joints if k + 1 in joints]
        if not joints:
            need = (
                "two neighbouring points"
                if self.kind in ("straight", "blend")
                else "a point it passes through"
            )
            self.report({"ERROR"}, f"'{obj.name}': select {need} of the curve")
            return {"CANCELLED"}
        direction = None if self.direction == "current" else self.direction
        for k in joints:
            api.set_point_attribute(
                obj, self.kind, k, direction=direction if self.kind == "tangent" else None
            )
        self.report({"INFO"}, f"'{obj.name}': {self.kind} on point(s) {', '.join(map(str, joints))}")
        return {"FINISHED"}


class BATTEN_OT_clear_point_attributes(BattenOperator, bpy.types.Operator):
    """Take the point attributes off the selected points of the curve being edited (in Object
    Mode: off every point of the selected curves); the curves keep their shape"""

    bl_idname = "batten.clear_point_attributes"
    bl_label = "Clear Point Attributes"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = context.edit_object
        if obj is not None:
            return hierarchy.POINT_ATTRIBUTES in obj
        return any(hierarchy.POINT_ATTRIBUTES in o for o in _selected_curves(context))

    def run(self, context):
        obj = context.edit_object
        if obj is not None:
            count = sum(api.clear_point_attributes(obj, k) for k in _selected_joints(obj))
        else:
            count = sum(api.clear_point_attributes(o) for o in _selected_curves(context))
        self.report({"INFO"}, f"{count} point attribute(s) cleared")
        return {"FINISHED"}


class BATTEN_OT_set_curve_attribute(BattenOperator, bpy.types.Operator):
    """Give each selected curve a curve attribute, acting on the points of the curves attached
    to it: Knuckle (they become knuckle points) or Tangent (they enter the curve's plane
    tangentially)"""

    bl_idname = "batten.set_curve_attribute"
    bl_label = "Curve Attribute"
    bl_options = {"REGISTER", "UNDO"}

    kind: EnumProperty(
        name="Attribute",
        items=[
            ("knuckle", "Knuckle", "A knuckle line: the points attached to it are knuckles"),
            ("tangent", "Tangent", "The curves attached to it enter its plane tangentially"),
        ],
        default="knuckle",
    )
    on: BoolProperty(name="On", description="Give the attribute (off: take it away)", default=True)

    @classmethod
    def poll(cls, context):
        return bool(_selected_curves(context))

    def run(self, context):
        curves = _selected_curves(context)
        api.set_curve_attribute(curves, self.kind, self.on)
        verb = "given" if self.on else "taken from"
        self.report({"INFO"}, f"Curve attribute {self.kind} {verb} {', '.join(o.name for o in curves)}")
        return {"FINISHED"}


class BATTEN_OT_make_bezier(BattenOperator, bpy.types.Operator):
    """Write each selected curve again as a Bézier spline of exactly the same shape (its points
    can then carry point attributes and be attached; a rational curve or one of degree above 3
    has no such form and is left as it is)"""

    bl_idname = "batten.make_bezier"
    bl_label = "Make Bézier"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.edit_object is None and any(
            o.data.splines and o.data.splines[0].type != "BEZIER" for o in _selected_curves(context)
        )

    def run(self, context):
        converted = api.to_bezier(_selected_curves(context))
        self.report({"INFO"}, f"Bézier splines now: {', '.join(converted) or 'none (they were)'}")
        return {"FINISHED"}


_CLASSES = (
    BATTEN_OT_make_bezier,
    BATTEN_OT_set_point_attribute,
    BATTEN_OT_clear_point_attributes,
    BATTEN_OT_set_curve_attribute,
    BATTEN_OT_measure_form,
    BATTEN_OT_transform,
    BATTEN_OT_transform_hydrostatic,
    BATTEN_OT_move_form_vertex,
    BATTEN_OT_select_transform,
    BATTEN_OT_compare_transform,
    BATTEN_OT_commit_transform,
    BATTEN_OT_keep_transform,
    BATTEN_OT_abandon_transforms,
    BATTEN_OT_attach_curves,
    BATTEN_OT_detach_curves,
    BATTEN_OT_hold_in_plane,
    BATTEN_OT_release_plane,
)


def register():
    """Register the Form panel's operators."""
    register_classes(_CLASSES)


def unregister():
    """Remove them."""
    unregister_classes(_CLASSES)
