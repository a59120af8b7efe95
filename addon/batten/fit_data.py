"""The data a curve is faired through: a polyline's own points, or samples of a drawn curve
with its corners kept (no Blender needed)."""

from __future__ import annotations

import numpy as np

#: Samples per knot span when a drawn (non-polyline) curve is refitted.
FAIR_SAMPLES_PER_SPAN = 12
#: At least this many samples for a drawn curve.
FAIR_MIN_SAMPLES = 60
#: At least this many sample intervals on each smooth piece between corners.
FAIR_MIN_PIECE_SAMPLES = 4


def fit_data(curve) -> tuple[np.ndarray, list[int]]:
    """The points to fair ``curve`` (a :class:`batten_native.Curve`) through, and the indices of
    its corners among them.

    A polyline's vertices are the data (imported or digitised points). A drawn curve is
    sampled: each smooth piece between its corners evenly in parameter, the corners exactly.
    """
    if curve.degree == 1:
        return curve.control_points, []
    a, b = curve.domain
    knots = np.unique(curve.knots)
    spans = int(np.count_nonzero((knots[:-1] >= a) & (knots[1:] <= b)))
    breaks = [a, *curve.corners(), b]
    total = max(FAIR_MIN_SAMPLES, FAIR_SAMPLES_PER_SPAN * spans)
    params, corners = [a], []
    for lo, hi in zip(breaks[:-1], breaks[1:], strict=True):
        n = max(FAIR_MIN_PIECE_SAMPLES, int(round(total * (hi - lo) / (b - a))))
        params.extend(np.linspace(lo, hi, n + 1)[1:])
        corners.append(len(params) - 1)
    return curve.evaluate(np.asarray(params)), corners[:-1]
