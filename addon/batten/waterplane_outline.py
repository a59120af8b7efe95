"""The water surface at a draft, trim and heel, as the rectangle the viewport draws over a
hull's box (no Blender needed).

batten's flotation convention (``rust/batten-core/src/hydro/waterplane.rs``): ``draft`` is the
draft at midships (halfway between the perpendiculars), ``trim = T_AP − T_FP`` (by the stern
positive), heel positive to starboard (``y < 0`` goes down); the water surface in the ship's
axes is ``z = T − (x − x_mid)·trim/Lpp − y·tan(heel)``.
"""

from __future__ import annotations

import math

import numpy as np

#: How far the drawn water surface reaches past the hull's box, as a share of its length.
MARGIN_SHARE = 0.05


def water_height(x, y, *, draft: float, trim: float, heel_deg: float, x_ap: float, x_fp: float):
    """Height ``z`` of the water surface above the ship point ``(x, y)`` (arrays or floats)."""
    x_mid, lpp = 0.5 * (x_ap + x_fp), x_fp - x_ap
    return draft - (np.asarray(x) - x_mid) * trim / lpp - np.asarray(y) * math.tan(math.radians(heel_deg))


def waterplane_outline(
    lo, hi, *, draft: float, trim: float = 0.0, heel_deg: float = 0.0, x_ap=None, x_fp=None
) -> np.ndarray:
    """The corners (4, 3) of the water surface over the box ``lo``–``hi`` (x, y ranges of the
    hull, widened by :data:`MARGIN_SHARE` of its length), in order around it. The
    perpendiculars default to the box's ends."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    x_ap = lo[0] if x_ap is None else x_ap
    x_fp = hi[0] if x_fp is None else x_fp
    margin = MARGIN_SHARE * (hi[0] - lo[0])
    (x0, y0), (x1, y1) = lo[:2] - margin, hi[:2] + margin
    xy = np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    z = water_height(xy[:, 0], xy[:, 1], draft=draft, trim=trim, heel_deg=heel_deg, x_ap=x_ap, x_fp=x_fp)
    return np.column_stack([xy, z])
