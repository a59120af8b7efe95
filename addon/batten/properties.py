"""Data batten keeps in the .blend: a curve's role, and the hull settings of a scene.

Everything lives in Blender data (saved with the file, seen by undo); nothing in Python globals.
"""

import bpy
from batten_native import DEFAULT_FAIR_TOLERANCE, DEFAULT_RESOLUTION, DEFAULT_TOLERANCE, MAX_RESOLUTION
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from ._registry import register_classes, unregister_classes

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


class BattenSceneSettings(bpy.types.PropertyGroup):
    """The hull settings of a scene."""

    source: PointerProperty(
        name="Hull curves",
        description="Collection holding the hull's curve network",
        type=bpy.types.Collection,
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
