"""The flat of bottom of a hull given as sections (seed 002 §5–6: the FOB curve of the form
topology, with its tangent attribute): the base plane the data lie flat in, and the curve
joining the points where the stations leave it.

Each station is faired with the base plane as a flat plane (``fair_points(flat_planes=[…])``):
its flat run becomes a straight piece in the plane and the bilge leaves it tangentially; the
fit reports where the flat ends. Those ends, ordered along the ship, are joined by the flat of
bottom curve (role ``fob``) in the base plane, so the faces between the keel and it are planar
and the faces above it meet the flat tangentially.

No Blender needed: the numbers come from the data and the fits.
"""

from __future__ import annotations

import numpy as np

#: The base plane is sought among the points within this height (m) of the lowest one.
BASE_SEARCH = 0.05
#: Fewest points that make a flat: fewer points at one height are a keel line, not a flat.
MIN_FLAT_POINTS = 8
#: Fewest stations whose flats make a flat of bottom curve.
MIN_STATIONS = 3
#: The flat of bottom curve's name.
NAME = "flat of bottom"


def base_plane(points: np.ndarray, tolerance: float) -> float | None:
    """The height (z, m) of the base plane the points ``points`` (n, 3) lie flat in: among the
    points within :data:`BASE_SEARCH` of the lowest, the height that most of them share
    (within ``tolerance``), their median; None when fewer than :data:`MIN_FLAT_POINTS` do."""
    z = np.asarray(points, dtype=float).reshape(-1, 3)[:, 2]
    z = z[np.isfinite(z)]
    if len(z) == 0:
        return None
    near = np.sort(z[z <= z.min() + BASE_SEARCH])
    # For each candidate height, how many points lie within the tolerance above and below it.
    counts = np.searchsorted(near, near + tolerance, side="right") - np.searchsorted(near, near - tolerance)
    best = near[int(np.argmax(counts))]
    shared = near[np.abs(near - best) <= tolerance]
    return float(np.median(shared)) if len(shared) >= MIN_FLAT_POINTS else None


def is_station(points: np.ndarray, tolerance: float) -> bool:
    """Whether the points lie in one plane x = const (within ``tolerance``): a station."""
    x = np.asarray(points, dtype=float).reshape(-1, 3)[:, 0]
    return len(x) > 0 and float(np.ptp(x)) <= tolerance


def flat_ends(reports: list[dict], stations: list[bool], kind: str = "bottom") -> np.ndarray:
    """The points where the stations leave the flat (from their fits' ``flats`` reports, the
    runs of that ``kind``), in order along x, one per station (the outermost where a station's
    parts have several): (k, 3)."""
    ends = [
        f["point"]
        for r, s in zip(reports, stations, strict=True)
        if s
        for f in r.get("flats", [])
        if f.get("kind") == kind
    ]
    ends = np.asarray(ends, dtype=float).reshape(-1, 3)
    ends = ends[np.lexsort((-np.abs(ends[:, 1]), ends[:, 0]))]
    # A station cut in parts has one flat: where two ends share a station, the outer one.
    keep = np.ones(len(ends), dtype=bool)
    keep[1:] = np.diff(ends[:, 0]) > 0.0
    return ends[keep]
