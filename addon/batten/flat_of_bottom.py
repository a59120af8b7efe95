"""The flat of bottom of a hull given as sections (seed 002 §5–6: the FOB curve of the form
topology, with its tangent attribute): the base plane the data lie flat in, and the curve
joining the points where the stations leave it.

Each station is faired with the base plane as its first flat plane (``fair_points(flat_planes=…)``):
its flat run becomes a straight piece in the plane and the bilge leaves it tangentially; the
fit reports where the flat ends. Those ends, ordered along the ship, are joined by the flat of
bottom curve (role ``fob``) in the base plane, so the faces between the keel and it are planar
and the faces above it meet the flat tangentially.

The flat of side is found the same way, at the widest breadth (:func:`side_plane`): every curve
is faired with it as a flat plane too, so a station runs straight up it to the deck, and a
waterline or the deck edge runs straight along it through the parallel middle body and leaves
it tangentially at both ends (KCS's flat of side 3.7 → 1.6 mm from its plane).

No Blender needed: the numbers come from the data and the fits.
"""

from __future__ import annotations

import numpy as np

#: The base plane is sought among the points within this height (m) of the lowest one.
BASE_SEARCH = 0.05
#: The flat of side is sought among the points within this breadth (m) of the widest: wider
#: than the base's search, as a hull's side may bulge past its flat (KVLCC2's data by 10 cm
#: at x = 115 m, where the flat is at 29.0 m).
SIDE_SEARCH = 0.2
#: The flat of side is the widest breadth at least this share of the most shared breadth near
#: the widest is shared by: a hull without a parallel middle body has one station at its
#: widest and two either side of it a little narrower, which share their breadth twice as
#: often; the flat of side is the widest one.
SIDE_SHARE = 0.5
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
    return shared_level(z, tolerance)


def side_plane(points: np.ndarray, tolerance: float) -> float | None:
    """The half breadth (|y|, m) of the flat of side the points ``points`` (n, 3) lie in, on
    either side of the centreplane: among the points within :data:`SIDE_SEARCH` of the widest,
    the widest breadth that at least :data:`SIDE_SHARE` of the most shared one's count share
    (within ``tolerance``), their median; None when fewer than :data:`MIN_FLAT_POINTS` do, or
    when that is within :data:`SIDE_SEARCH` of the centreplane (a hull given as its profile
    alone has no side)."""
    y = np.abs(np.asarray(points, dtype=float).reshape(-1, 3)[:, 1])
    level = shared_level(-y, tolerance, SIDE_SEARCH, SIDE_SHARE)
    return None if level is None or -level <= SIDE_SEARCH else -level


def shared_level(
    values: np.ndarray, tolerance: float, search: float = BASE_SEARCH, share: float | None = None
) -> float | None:
    """Among the finite ``values`` within ``search`` of the least, the value that most of them
    share (within ``tolerance``) — or with ``share``, the most shared within the tolerance of
    the least value shared by at least that share of the most — and the median of those
    sharing it; None when fewer than :data:`MIN_FLAT_POINTS` do."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if len(v) == 0:
        return None
    near = np.sort(v[v <= v.min() + search])
    # For each candidate value, how many lie within the tolerance above and below it.
    counts = np.searchsorted(near, near + tolerance, side="right") - np.searchsorted(near, near - tolerance)
    if share is None:
        best = near[int(np.argmax(counts))]
    else:
        # The least value shared enough, then the most shared value within the tolerance of it.
        least = near[int(np.argmax(counts >= max(MIN_FLAT_POINTS, share * counts.max())))]
        around = np.abs(near - least) <= tolerance
        best = near[around][int(np.argmax(counts[around]))]
    shared = near[np.abs(near - best) <= tolerance]
    return float(np.median(shared)) if len(shared) >= MIN_FLAT_POINTS else None


def is_station(points: np.ndarray, tolerance: float) -> bool:
    """Whether the points lie in one plane x = const (within ``tolerance``): a station."""
    x = np.asarray(points, dtype=float).reshape(-1, 3)[:, 0]
    return len(x) > 0 and float(np.ptp(x)) <= tolerance


def flat_ends(reports: list[dict], stations: list[bool]) -> np.ndarray:
    """The points where the stations leave the flat of bottom (from their fits' ``flats``
    reports of kind ``"bottom"``), in order along x, one per station (the outermost where a
    station's parts, or a run between a bar keel and the bilge, have several): (k, 3)."""
    ends = [
        f["point"]
        for r, s in zip(reports, stations, strict=True)
        if s
        for f in r.get("flats", [])
        if f.get("kind") == "bottom"
    ]
    ends = np.asarray(ends, dtype=float).reshape(-1, 3)
    ends = ends[np.lexsort((-np.abs(ends[:, 1]), ends[:, 0]))]
    # A station cut in parts has one flat: where two ends share a station, the outer one.
    keep = np.ones(len(ends), dtype=bool)
    keep[1:] = np.diff(ends[:, 0]) > 0.0
    return ends[keep]
