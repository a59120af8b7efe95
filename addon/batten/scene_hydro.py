"""The hydrostatics of a scene's hull with the scene's settings (the Hydrostatics panel's
operators and Live both use this): the arguments for :mod:`batten.api`, the figures kept in
the scene (JSON, or the error), and the drafts a new hull starts with.
"""

from __future__ import annotations

import json
import math
from contextlib import contextmanager

import numpy as np

from . import api
from .bridge import curves_in

#: Without a design draft the Draft starts at this share of the hull's depth above its keel:
#: a waterline always inside the hull, so the first Compute gives figures, not an error.
DEFAULT_DRAFT_SHARE = 0.5
#: The curves of form start over this share of the depth above the keel (clear of the keel,
#: where BM grows without bound, and of the top, where the hull floods).
CURVES_OF_FORM_SHARE = (0.1, 0.9)


def typed(value: float) -> float:
    """A float property's value as the user typed it: Blender keeps single precision (1.025
    becomes 1.02499998), and the shortest decimal that rounds to the same float32 is the
    number typed (``1.025``)."""
    return float(str(np.float32(value)))


def draft_of(settings) -> float:
    """The scene's draft, as typed."""
    return typed(settings.draft)


def flotation(settings) -> dict:
    """The keyword arguments of :func:`batten.api.hydrostatics` (and
    :func:`~batten.api.sectional_areas`) from the scene's settings, besides the draft."""
    return {
        "trim": typed(settings.trim),
        "heel": math.degrees(settings.heel),
        "density": typed(settings.density),
        "lpp": typed(settings.lpp) or None,
    }


@contextmanager
def figures_kept_in(settings):
    """Run the body; a BattenError it raises is kept as the scene's figures' error (shown in
    the panel) and raised again."""
    try:
        yield
    except api.BattenError as e:
        settings.last_hydrostatics = json.dumps({"error": str(e)})
        raise


def hydrostatics_into_scene(scene, *, live: bool = False) -> dict:
    """The hydrostatics of the scene's hull at its draft, trim, heel and density, kept in the
    scene (JSON) for the panel, and returned; a failure is kept as the error and raised.
    ``live``: the API's quicker figures for updates while editing."""
    settings = scene.batten
    with figures_kept_in(settings):
        figures = api.hydrostatics(settings.source, draft_of(settings), **flotation(settings), live=live)
    keep_figures(settings, figures)
    return figures


def keep_figures(settings, figures: dict) -> None:
    """Keep ``figures`` (a hydrostatics dict) as the scene's last hydrostatics."""
    settings.last_hydrostatics = json.dumps(figures)


def last_figures(settings) -> dict:
    """The scene's last hydrostatics (``{}`` before the first, ``{"error": …}`` after a
    failure)."""
    return json.loads(settings.last_hydrostatics) if settings.last_hydrostatics else {}


def hull_box(source) -> tuple[np.ndarray, np.ndarray]:
    """The world box ``(lo, hi)`` of the control points of the curves of ``source`` (a
    collection or objects): it holds the curves, so the hull. Read from the curves' data, as
    the overlay does on every redraw (not from Blender's bound boxes, which lag behind an edit
    until the depsgraph is evaluated). InvalidArgumentError when it has no finite points."""
    points = np.concatenate([curves_in.control_points(obj) for obj in api.curve_objects(source)])
    points = points[np.isfinite(points).all(axis=1)]
    if not len(points):
        raise api.InvalidArgumentError("the hull's curves have no finite control points")
    return points.min(axis=0), points.max(axis=0)


def set_default_drafts(settings) -> None:
    """Start a newly chosen hull's Draft at its design draft (:func:`batten.api.design_draft`,
    the collection's ``batten_design_draft``) or at
    :data:`DEFAULT_DRAFT_SHARE` of its depth, and the curves of form over
    :data:`CURVES_OF_FORM_SHARE` of its depth; forget the last figures (another hull's)."""
    source = settings.source
    settings.last_hydrostatics = ""
    if source is None:
        return
    try:
        lo, hi = hull_box(source)
    except api.BattenError:
        return  # an empty or broken hull: the drafts stay; building it will say what is wrong
    keel, depth = float(lo[2]), float(hi[2] - lo[2])
    design = api.design_draft(source)
    settings.draft = design if design is not None else keel + DEFAULT_DRAFT_SHARE * depth
    settings.curves_draft_min, settings.curves_draft_max = (keel + s * depth for s in CURVES_OF_FORM_SHARE)
