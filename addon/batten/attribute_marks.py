"""Where the curves' point attributes act and which of their points are attached, as line
segments and points for the viewport overlay (:mod:`batten.overlay` turns them into batches)."""

from __future__ import annotations

import numpy as np
from batten_native import CurveError

from . import point_attributes
from .hierarchy import POINT_ATTRIBUTES, attachments_of, point_attributes_of
from .spline_joints import end_point, joint_arrays, joint_layout, joint_points, single_spline, world_points

#: Samples per segment of a straight or blend drawn in the overlay.
MARK_SAMPLES = 16


def attribute_marks(objects) -> dict[str, np.ndarray]:
    """Where the point attributes of the curve objects ``objects`` act, for the overlay, each
    float32 in world coordinates: ``knuckle`` points (n, 3); ``tangent`` segments (2k, 3)
    through each tangent point along its direction, a third of its shorter neighbouring chord
    either side; ``straight`` and ``blend`` segments (2k, 3) along the curve between each
    pair's points; ``attached`` points (n, 3), the ends and points attached to a parent. A curve
    whose attributes cannot be read (its spline changed type, its property edited by hand)
    marks nothing: Build names it."""
    out = {k: [] for k in (*point_attributes.KINDS, "attached")}
    for obj in objects:
        try:
            own = point_attributes_of(obj) if obj.get(POINT_ATTRIBUTES) else []
            attached = attachments_of(obj)
            if not own and not attached:
                continue
            spline = single_spline(obj)
            world = world_points(obj, spline)
            if attached:
                ends = [end_point(obj, a["end"]) for a in attached if "end" in a]
                points = [a["point"] for a in attached if "point" in a]
                if points:
                    ends += list(joint_points(obj)[points])
                out["attached"].append(np.asarray(ends).reshape(-1, 3))
            if not own:
                continue
            index, handles = joint_layout(spline, obj.name)
            if not handles:
                world = {
                    "co": world["co"],
                    "handle_left": world["co"].copy(),
                    "handle_right": world["co"].copy(),
                }
            co, left, right, _ = joint_arrays(world, index)
        except (CurveError, IndexError):
            continue
        for a in own:
            i = a["point"]
            if i >= len(co) or (a["kind"] in point_attributes.PAIR_KINDS and i + 1 >= len(co)):
                continue
            if a["kind"] == "knuckle":
                out["knuckle"].append(co[i][None, :])
            elif a["kind"] == "tangent":
                chords = [np.linalg.norm(co[j] - co[i]) for j in (i - 1, i + 1) if 0 <= j < len(co)]
                d = np.asarray(a["direction"], dtype=float) * min(chords, default=0.0) / 3.0
                out["tangent"].append(np.array([co[i] - d, co[i] + d]))
            else:
                u = np.linspace(0.0, 1.0, MARK_SAMPLES + 1)[:, None]
                b = (1 - u) ** 3 * co[i] + 3 * (1 - u) ** 2 * u * right[i]
                b = b + 3 * (1 - u) * u**2 * left[i + 1] + u**3 * co[i + 1]
                out[a["kind"]].append(np.stack([b[:-1], b[1:]], axis=1).reshape(-1, 3))
    return {
        k: np.concatenate(v).astype(np.float32) if v else np.zeros((0, 3), dtype=np.float32)
        for k, v in out.items()
    }
