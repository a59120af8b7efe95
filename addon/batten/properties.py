"""Data batten keeps in the .blend: a curve's role, and the hull settings of a scene.

Everything lives in Blender data (saved with the file, seen by undo); nothing in Python globals.
"""

import math

import bpy
from batten_native import (
    DEFAULT_FAIR_TOLERANCE,
    DEFAULT_RESOLUTION,
    DEFAULT_SURFACE_FAIR_TOLERANCE,
    DEFAULT_TOLERANCE,
    MAX_RESOLUTION,
)
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    PointerProperty,
    StringProperty,
)

from ._registry import register_classes, unregister_classes

#: The form parameters the Form panel can set (seed 002 §7.2.5): key, label, description.
FORM_PARAMETERS = (
    ("breadth", "Breadth", "Largest breadth of the hull"),
    ("depth", "Depth", "Keel to deck"),
    ("pmb_length", "PMB length", "Length of the parallel middle body"),
    ("pmb_position", "PMB position", "x of the centre of the parallel middle body"),
    ("bilge_radius", "Bilge radius", "Radius of the bilge arc of the midship sections"),
    ("entrance_length", "Entrance length", "From the forward end of the PMB to the stem"),
    ("run_length", "Run length", "From the transom to the aft end of the PMB"),
)

#: Sea water, t/m³: the default density of :func:`batten.api.hydrostatics` (ITTC, 15 °C).
SEA_WATER_DENSITY = 1.025
#: Stations of the sectional area curve, and drafts of the curves of form, by default.
DEFAULT_STATIONS = 21
DEFAULT_CURVES_OF_FORM_DRAFTS = 10
#: The largest heel the panel takes, radians (the hydrostatics refuse 90° and more).
MAX_HEEL = math.radians(89.0)

#: (identifier, label, description); identifiers are the core's role names.
ROLE_ITEMS = [
    ("free", "Free", "An ordinary curve: the surface is smooth (G1) across it"),
    ("knuckle", "Knuckle (chine)", "The surface keeps a sharp crease (G0) across this curve"),
    ("keel", "Keel", "The keel line"),
    ("stem", "Stem", "The stem profile"),
    ("transom", "Transom", "The transom outline"),
    ("deck", "Deck edge", "The deck edge (sheer line)"),
    ("midship", "Midship", "The midship section"),
    ("fos", "Flat of side", "Boundary of the flat of side"),
    ("fob", "Flat of bottom", "Boundary of the flat of bottom"),
]


class BattenCurveSettings(bpy.types.PropertyGroup):
    """batten's data on a curve object."""

    role: EnumProperty(
        name="Role",
        description="What this curve is to the hull",
        items=ROLE_ITEMS,
        default="free",
    )


def _is_collection(_self, _coll):
    return True


def _hull_changed(settings, _context):
    """A new hull: its drafts (design draft, range of the curves of form) and no figures yet."""
    from .scene_hydro import set_default_drafts

    set_default_drafts(settings)


def _live_changed(settings, context):
    """Live switched on or off: the live machinery follows (:func:`batten.live.live_changed`)."""
    from .live import live_changed

    live_changed(settings, context)


def _flotation_changed(settings, _context):
    """Draft, trim, heel, density or Lpp changed: recompute the figures if the panel shows some
    (an error too: the change may be its fix)."""
    if not settings.last_hydrostatics or settings.source is None:
        return
    from . import api
    from .scene_hydro import hydrostatics_into_scene

    try:
        hydrostatics_into_scene(settings.id_data, live=True)  # the scene owning these settings
    except api.BattenError:
        pass  # kept as the figures' error, shown in the panel


class BattenSceneSettings(bpy.types.PropertyGroup):
    """The hull settings of a scene."""

    source: PointerProperty(
        name="Hull curves",
        description="Collection holding the hull's curve network",
        type=bpy.types.Collection,
        update=_hull_changed,
    )
    tolerance: FloatProperty(
        name="Tolerance",
        description="Model tolerance: curves closer than this meet",
        default=DEFAULT_TOLERANCE,
        min=1e-7,
        max=1.0,
        precision=6,
        unit="LENGTH",
    )
    resolution: IntProperty(
        name="Resolution",
        description="Surface segments per patch side",
        default=DEFAULT_RESOLUTION,
        min=1,
        max=MAX_RESOLUTION,
        soft_max=64,
    )
    mirror: BoolProperty(
        name="Mirror",
        description="Mirror the drawn half hull about the centreplane (y = 0)",
        default=True,
    )
    live: BoolProperty(
        name="Live",
        description="Rebuild the surface whenever a curve of the hull changes",
        default=False,
        update=_live_changed,
    )
    last_report: StringProperty(
        name="Last report",
        description="The report of the last build (JSON), shown in the panel",
        default="",
        options={"HIDDEN"},
    )
    fair_tolerance: FloatProperty(
        name="Fair tolerance",
        description="Largest distance a faired curve may stray from its points",
        default=DEFAULT_FAIR_TOLERANCE,
        min=1e-6,
        max=1.0,
        precision=4,
        unit="LENGTH",
    )
    form_parameter: EnumProperty(
        name="Parameter",
        description="The form parameter to change (seed 002 §7.2.5)",
        items=list(FORM_PARAMETERS),
        default="breadth",
    )
    form_value: FloatProperty(
        name="Value",
        description="The value the parameter is to take",
        default=10.0,
        min=-1e5,
        max=1e5,
        precision=3,
        unit="LENGTH",
    )
    form_vertex: IntProperty(
        name="Vertex",
        description="The form vertex to move: its number in the overlay (Measure Form)",
        default=0,
        min=0,
    )
    form_move: FloatVectorProperty(
        name="Move",
        description="The translation of the form vertex (m); the network follows by the form "
        "topology's rules (seed 002 §7.2)",
        size=3,
        default=(0.0, 0.0, 0.0),
        subtype="TRANSLATION",
        unit="LENGTH",
    )
    hydro_volume_target: EnumProperty(
        name="Volume target",
        description="What the hydrostatic transformation aims at for the volume (seed 002 §8); "
        "Hold keeps the present volume",
        items=[
            ("hold", "Hold ∇", "Keep the present displaced volume"),
            ("volume", "∇ (m³)", "Displaced volume, both sides"),
            ("displacement", "Δ (t)", "Displacement at the scene's density"),
            ("cb", "Cb", "Block coefficient on Lpp, Bwl and the draft"),
            ("cp", "Cp", "Prismatic coefficient on the midship section and Lpp"),
        ],
        default="cb",
    )
    hydro_volume_value: FloatProperty(
        name="Value",
        description="The target of the chosen volume figure",
        default=0.7,
        min=0.0,
        max=1e9,
        precision=4,
    )
    hydro_use_lcb: BoolProperty(
        name="LCB",
        description="Aim at an LCB too (else the present LCB is held)",
        default=False,
    )
    hydro_lcb: FloatProperty(
        name="LCB",
        description="The target x of the centre of buoyancy (m, as the Hydrostatics panel gives it)",
        default=0.0,
        min=-1e5,
        max=1e5,
        precision=3,
        unit="LENGTH",
    )
    hydro_keep_pmb: EnumProperty(
        name="Hold PMB",
        description="What of the parallel middle body to keep; the entrance's and run's faces are "
        "bulged or flattened for the rest (seed 002 §8.2–8.3; hulls without a PMB always are)",
        items=[
            ("free", "PMB free", "Move the PMB's ends (and bulge the ends when that is not enough)"),
            ("length", "Hold length", "Shift the PMB for the LCB; bulge both ends alike for the volume"),
            ("position", "Hold position", "Lengthen the PMB for the volume; bulge the ends opposite ways"),
            ("all", "Hold PMB", "Bulge the ends' faces only"),
        ],
        default="free",
    )
    last_hydro_transform: StringProperty(
        name="Last hydrostatic transform",
        description="The last hydrostatic transformation's figures before, after and aimed at (JSON), "
        "shown in the Form panel",
        default="",
        options={"HIDDEN"},
    )
    last_form: StringProperty(
        name="Last form",
        description="The form parameters last measured (JSON), shown in the Form panel",
        default="",
        options={"HIDDEN"},
    )
    show_form: BoolProperty(
        name="Show Form",
        description="Draw the form topology last measured in the viewport: its vertices, numbered as "
        "batten.api.transform's moves take them, and its edges by kind (free-form, straight, blend)",
        default=True,
    )
    last_transform: StringProperty(
        name="Last transform",
        description="The last transformation's parameters before and after (JSON), shown in the Form panel",
        default="",
        options={"HIDDEN"},
    )
    last_comparison: StringProperty(
        name="Last comparison",
        description="The last comparison of a copy with its original (JSON): dimensions and hydrostatics "
        "side by side, shown in the Form panel, and the original's curves the viewport draws beside the copy",
        default="",
        options={"HIDDEN"},
    )
    show_comparison: BoolProperty(
        name="Show Original",
        description="Draw the original hull's curves in the viewport while its compared copy is the hull "
        "the panels work on",
        default=True,
    )
    curvature_kind: EnumProperty(
        name="Curvature",
        description="Which curvature the map shows",
        items=[
            (
                "gaussian",
                "Gaussian",
                "K = κ1·κ2 (1/m²): red where the surface is curved the same way "
                "in every direction, blue on a saddle, white where flat or developable",
            ),
            (
                "mean",
                "Mean",
                "H = (κ1 + κ2)/2 (1/m): red where the hull bulges outwards, blue where it is hollow",
            ),
        ],
        default="gaussian",
    )
    curvature_scale: FloatProperty(
        name="Scale",
        description="Curvature shown in full colour (1/m² or 1/m); 0: the 95th percentile of the "
        "hull's own values",
        default=0.0,
        min=0.0,
        precision=4,
    )
    surface_fair_tolerance: FloatProperty(
        name="Surface tolerance",
        description="Largest distance a point of a section may move when the hull is faired through its "
        "sections",
        default=DEFAULT_SURFACE_FAIR_TOLERANCE,
        min=1e-6,
        max=1.0,
        precision=4,
        unit="LENGTH",
    )
    surface_fair_families: EnumProperty(
        name="Families",
        description="The families of plane sections the hull is faired through, one after the other",
        items=(
            ("stations", "Stations", "The network's curves in planes x = const"),
            ("waterlines", "Waterlines", "The network's curves in planes z = const"),
            ("buttocks", "Buttocks", "The network's curves in planes y = const"),
        ),
        options={"ENUM_FLAG"},
        default={"stations", "waterlines"},
    )
    show_network: BoolProperty(
        name="Network markers",
        description=(
            "Mark the network's nodes, T-joints, dangling ends and near misses, and draw the knuckle "
            "edges (automatically found ones in cyan), in the viewport"
        ),
        default=True,
    )
    show_combs: BoolProperty(
        name="Curvature combs",
        description="Draw curvature combs (porcupines) on the selected curves",
        default=False,
    )
    comb_scale: FloatProperty(
        name="Comb scale",
        description="Length of a comb tooth per unit curvature (m per 1/m)",
        default=10.0,
        min=0.0,
        soft_max=10000.0,
    )

    # Hydrostatics (the Hydrostatics panel; figures from batten.api.hydrostatics).
    draft: FloatProperty(
        name="Draft",
        description=(
            "Draft at midships (halfway between the perpendiculars), above the baseline z = 0. Set "
            "when the hull is chosen: its design draft (the collection's 'batten_design_draft' "
            "property) if it has one, else half its depth"
        ),
        default=1.0,
        precision=3,
        unit="LENGTH",
        update=_flotation_changed,
    )
    trim: FloatProperty(
        name="Trim",
        description="Trim T_AP − T_FP (by the stern positive)",
        default=0.0,
        precision=3,
        unit="LENGTH",
        update=_flotation_changed,
    )
    heel: FloatProperty(
        name="Heel",
        description="Heel (to starboard positive)",
        default=0.0,
        min=-MAX_HEEL,
        max=MAX_HEEL,
        subtype="ANGLE",
        unit="ROTATION",
        update=_flotation_changed,
    )
    density: FloatProperty(
        name="Density",
        description="Water density, t/m³ (sea water 1.025, fresh water 1.000)",
        default=SEA_WATER_DENSITY,
        min=0.001,
        soft_min=0.9,
        soft_max=1.1,
        precision=4,
        update=_flotation_changed,
    )
    lpp: FloatProperty(
        name="Lpp",
        description=(
            "Length between perpendiculars, FP at the stem's waterline, AP this far aft; 0: AP at the "
            "waterline's aft end (Lpp = Lwl)"
        ),
        default=0.0,
        min=0.0,
        precision=3,
        unit="LENGTH",
        update=_flotation_changed,
    )
    show_waterline: BoolProperty(
        name="Waterline",
        description="Draw the water surface at the draft, trim and heel in the viewport",
        default=True,
    )
    stations: IntProperty(
        name="Stations",
        description="Stations of the sectional area curve, evenly spaced along the hull",
        default=DEFAULT_STATIONS,
        min=3,
        max=1001,
        soft_max=101,
    )
    curves_draft_min: FloatProperty(
        name="From",
        description="Lowest draft of the curves of form",
        default=0.5,
        precision=3,
        unit="LENGTH",
    )
    curves_draft_max: FloatProperty(
        name="To",
        description="Highest draft of the curves of form",
        default=1.0,
        precision=3,
        unit="LENGTH",
    )
    curves_drafts: IntProperty(
        name="Drafts",
        description="Drafts of the curves of form, evenly spaced",
        default=DEFAULT_CURVES_OF_FORM_DRAFTS,
        min=2,
        max=200,
        soft_max=50,
    )
    float_displacement: FloatProperty(
        name="Displacement",
        description="Displacement Δ to float the hull at, t",
        default=1000.0,
        min=0.0,
        precision=1,
    )
    float_lcg: FloatProperty(
        name="LCG",
        description="Longitudinal centre of gravity, x (the hull trims until LCB is under it)",
        default=0.0,
        precision=3,
        unit="LENGTH",
    )
    last_hydrostatics: StringProperty(
        name="Last hydrostatics",
        description="The figures of the last hydrostatics (JSON, or its error), shown in the panel",
        default="",
        options={"HIDDEN"},
    )


_CLASSES = (BattenCurveSettings, BattenSceneSettings)


def register():
    """Register the property groups and attach them to objects and scenes."""
    register_classes(_CLASSES)
    bpy.types.Object.batten = PointerProperty(type=BattenCurveSettings)
    bpy.types.Scene.batten = PointerProperty(type=BattenSceneSettings)


def unregister():
    """Detach and unregister the property groups."""
    for owner in (bpy.types.Object, bpy.types.Scene):
        if hasattr(owner, "batten"):
            del owner.batten
    unregister_classes(_CLASSES)
