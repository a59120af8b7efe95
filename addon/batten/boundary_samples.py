"""The points a section file gives a hull's boundary curves (keel/profile, stem, transom, deck,
chines) so that the file is a consistent network on its own: every station and waterline that
ends on, or crosses with a corner, a boundary curve has that point among the curve's points.

A reader joins curves that meet in its data within its tolerance plus what a chord may miss
the true curve by; a chord across a corner of the curve (the transom's lower corner on the
profile, the deck edge turning from the transom top to the side) misses it by far more, and a
section that ends there is then left dangling. So the boundary curve is sampled where the
sections meet it (the nearest curve points to their ends and corners), at its knots (where a
fitted curve's detail is, and every corner), and evenly between. A chine whose end meets no
other curve of the file (it ended on a curve the file does not hold) is cut back to its last
section: a reader joining the sections' knuckles finds the same chine. A section that runs
along a boundary curve (a station in the transom's plane) is left out: the file has the curve;
so is a stray piece ending inside faces, cut where the surface folds (:func:`is_stray`), and a
stretch from a section's end to where it meets a boundary curve that it runs beside, which a
reader would merge into that curve (:func:`without_end_stretches_along`).
"""

from __future__ import annotations

import numpy as np

#: Evenly spaced points per boundary curve, besides its knots and the sections' points on it.
EVEN_SAMPLES = 200

#: Parameters closer than this fraction of the curve's parameter span are one sample.
SAME_PARAMETER_RELATIVE = 1e-9


def section_anchors(polylines: list[np.ndarray], corners: list[list[int]]) -> np.ndarray:
    """The points of the section polylines that may lie on a boundary curve: their ends and
    corners, (n, 3)."""
    pts = [p[[0, -1, *c]] for p, c in zip(polylines, corners, strict=True) if len(p)]
    return np.concatenate(pts) if pts else np.zeros((0, 3))


def thinned(points: np.ndarray, keep, gap: float) -> tuple[np.ndarray, list[int]]:
    """``(points, keep)``: ``points`` (n, 3) without those closer than ``gap`` (m) to the last
    point kept, the ends and the indices in ``keep`` (corners) always kept, with the indices
    of ``keep`` in the result. A section cut within a fine tolerance holds runs of points
    millimetres apart (where its pieces join, where a chord is short); a reader fitting the
    file within a coarser tolerance gains nothing from them, and a least-squares fit can
    swing between parameters that close (seen: a KCS waterline fitted through 2 mm gaps
    loops 2 m off its data)."""
    n = len(points)
    pinned = {0, n - 1, *(int(k) for k in keep)}
    out: list[int] = []
    for i in range(n):
        crowded = bool(out) and np.linalg.norm(points[i] - points[out[-1]]) < gap
        if i in pinned:
            # A pinned point displaces a kept one it crowds, unless that one is pinned too.
            if crowded and out[-1] not in pinned:
                out.pop()
            out.append(i)
        elif not crowded:
            out.append(i)
    at = {j: k for k, j in enumerate(out)}
    return points[out], [at[int(k)] for k in keep]


def _on_curve(curve, anchors: np.ndarray, within: float) -> list[float]:
    """The parameters of the points of ``curve`` nearest to each anchor within ``within``."""
    lo, hi = (np.asarray(b) for b in curve.bounding_box())
    near = np.all((anchors >= lo - within) & (anchors <= hi + within), axis=1)
    out = []
    for p in anchors[near]:
        t, d, _ = curve.nearest(p.tolist())
        if d <= within:
            out.append(t)
    return out


#: Points of a section polyline checked against the boundary curves by :func:`along_boundary`.
ALONG_CHECKS = 5


def along_boundary(polyline: np.ndarray, boundary: list, within: float) -> bool:
    """Whether the section ``polyline`` runs along one of the ``boundary`` curves (a station in
    the transom's plane, a waterline along a flat keel): ``ALONG_CHECKS`` of its points, ends
    included, all within ``within`` (m) of it. The file then holds the curve already."""
    picks = polyline[np.linspace(0, len(polyline) - 1, ALONG_CHECKS).round().astype(int)]
    return any(all(c.nearest(p.tolist())[1] <= within for p in picks) for c in boundary)


def without_end_stretches_along(
    points: np.ndarray, corners, boundary: list, within: float, meet: float
) -> tuple[np.ndarray, list[int]]:
    """``(points, corners)`` of the section polyline ``points`` without an end stretch that
    runs within ``within`` (m) of a ``boundary`` curve from the section's end to where it meets
    that curve (within ``meet``), with the indices of ``corners`` in the result (those cut
    off dropped). A reader joining curves that come that close ends the stretch on the curve
    beside it, and the two bound a face of two sides (seen: a KCS waterline 9 mm above the
    lower corner of the shaft boss's flat end, crossing the end to its edge); the boundary
    curve is that stretch already, and the section then ends where it meets it."""
    n = len(points)
    lo, hi = 0, n - 1
    for c in boundary:
        lo = max(lo, _last_meeting(points, range(n), c, within, meet, default=0))
        hi = min(hi, _last_meeting(points, range(n - 1, -1, -1), c, within, meet, default=n - 1))
    if lo >= hi:
        return points, [int(k) for k in corners]
    return points[lo : hi + 1], [int(k) - lo for k in corners if lo <= k <= hi]


def _last_meeting(points: np.ndarray, order, curve, within: float, meet: float, default: int) -> int:
    """Walking ``points`` in ``order`` from a section's end while they stay within ``within``
    of ``curve``: the last one that meets it (within ``meet``), or ``default`` when the end
    meets it itself or none does."""
    found = default
    for k, i in enumerate(order):
        gap = curve.nearest(points[i].tolist())[1]
        if gap > within:
            break
        if gap <= meet:
            if k == 0:
                return default
            found = i
    return found


def is_stray(polyline: np.ndarray, network: list, within: float) -> bool:
    """Whether the section ``polyline`` is a stray piece: none of its points (ends first)
    within ``within`` (m) of a curve of the hull's ``network``. A section of a surface without
    holes runs from boundary to boundary, and a closed one crosses the curves of the faces it
    passes (its points at the patch edges lie on them); a piece inside one face touches none.
    It comes from a fold of the surface (a patch turning back through the plane), which the
    build reports, and would be a loose curve in the file."""
    lo, hi = polyline.min(axis=0) - within, polyline.max(axis=0) + within
    near = []
    for c in network:
        clo, chi = (np.asarray(b) for b in c.bounding_box())
        if np.all(clo <= hi) and np.all(chi >= lo):
            near.append(c)
    order = np.concatenate([[0, len(polyline) - 1], np.arange(1, len(polyline) - 1)])
    return not any(_meets(polyline[i], near, within) for i in order)


def _meets(p: np.ndarray, others: list, within: float) -> bool:
    return any(c.nearest(p.tolist())[1] <= within for c in others)


def boundary_points(curve, anchors: np.ndarray, others: list, within: float, trim_free_ends: bool):
    """The points (n, 3) a section file gives the boundary ``curve`` (module doc): its knots,
    ``EVEN_SAMPLES`` even parameters and its nearest points to ``anchors`` within ``within``
    (m). With ``trim_free_ends`` (a chine), an end farther than ``within`` from every curve of
    ``others`` and from every anchor is cut back to the anchor nearest it along the curve."""
    t0, t1 = curve.domain
    on = _on_curve(curve, anchors, within)
    lo, hi = t0, t1
    if trim_free_ends and on:
        ends = curve.evaluate([t0, t1]).reshape(2, 3)
        anchored = [np.min(np.linalg.norm(anchors - e, axis=1), initial=np.inf) <= within for e in ends]
        if not (anchored[0] or _meets(ends[0], others, within)):
            lo = min(on)
        if not (anchored[1] or _meets(ends[1], others, within)):
            hi = max(on)
    ts = np.concatenate([np.linspace(lo, hi, EVEN_SAMPLES), np.asarray(curve.knots, dtype=float), on])
    ts = np.unique(ts[(ts >= lo) & (ts <= hi)])
    keep = np.concatenate([[True], np.diff(ts) > SAME_PARAMETER_RELATIVE * (t1 - t0)])
    return np.asarray(curve.evaluate(ts[keep]), dtype=float).reshape(-1, 3)
