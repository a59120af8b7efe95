"""What the viewport overlay draws from a build report: marker positions by kind (nodes,
T-joints, dangling ends, near misses, holes and folds of the surface, other problems) and the
knuckle edges as line segments (no Blender needed)."""

from __future__ import annotations

import numpy as np

#: Marker kinds, in drawing order.
MARKER_KINDS = ("nodes", "t_joints", "dangling_ends", "near_misses", "holes", "folds", "problems")
#: Knuckle edge sources: the curve's role, or found at corners of the crossing curves.
KNUCKLE_SOURCES = ("role", "auto")

# Marker kind of each node kind and finding kind; a free end is marked by its dangling-end
# finding, not as a node, and a finding of any other kind is a problem.
_NODE_MARKERS = {"crossing": "nodes", "end_to_end": "nodes", "end_on_curve": "nodes", "t_joint": "t_joints"}
_FINDING_MARKERS = {
    "dangling_end": "dangling_ends",
    "near_miss": "near_misses",
    "hole": "holes",
    "fold": "folds",
}


def network_markers(node_positions: list, node_kinds: list[str], findings: list[dict]) -> dict[str, list]:
    """Marker positions ([x, y, z] lists) by kind (:data:`MARKER_KINDS`) from a build report's
    ``node_positions``, ``node_kinds`` and ``warnings`` (or a topology's ``diagnostics``):
    ``nodes`` (crossings, ends on ends, ends on a curve where the faces have corners),
    ``t_joints``, ``dangling_ends``, ``near_misses``, ``holes`` and ``folds`` of the surface,
    and ``problems`` (every other finding with a location)."""
    marks = {k: [] for k in MARKER_KINDS}
    for position, kind in zip(node_positions, node_kinds, strict=True):
        if kind in _NODE_MARKERS:
            marks[_NODE_MARKERS[kind]].append(list(position))
    for f in findings:
        if f["location"] is not None:
            marks[_FINDING_MARKERS.get(f["kind"], "problems")].append(list(f["location"]))
    return marks


def marker_arrays(markers: dict) -> dict[str, np.ndarray]:
    """Each marker kind of :func:`network_markers` as an (n, 3) float32 array (empty when
    ``markers`` has none of that kind)."""
    return {k: np.asarray(markers.get(k, []), dtype=np.float32).reshape(-1, 3) for k in MARKER_KINDS}


def knuckle_segments(knuckle_edges: list[dict]) -> dict[str, np.ndarray]:
    """Line segment end points (2k, 3), float32, along a build report's ``knuckle_edges``, by
    source (:data:`KNUCKLE_SOURCES`)."""
    segments = {k: [] for k in KNUCKLE_SOURCES}
    for edge in knuckle_edges:
        pts = np.asarray(edge["points"], dtype=np.float32).reshape(-1, 3)
        if edge["source"] in segments and len(pts) > 1:
            segments[edge["source"]].append(np.stack([pts[:-1], pts[1:]], axis=1).reshape(-1, 3))
    return {k: np.concatenate(v) if v else np.zeros((0, 3), dtype=np.float32) for k, v in segments.items()}
