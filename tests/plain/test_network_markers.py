"""The overlay's markers and knuckle lines from a build report's data."""

import numpy as np
from batten.network_markers import MARKER_KINDS, knuckle_segments, marker_arrays, network_markers


def _finding(kind, location):
    return {"kind": kind, "message": kind, "curves": ["a"], "location": location, "error": None}


def test_markers_by_kind():
    positions = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0], [4, 0, 0]]
    kinds = ["crossing", "t_joint", "end_to_end", "free_end", "end_on_curve"]
    findings = [
        _finding("dangling_end", [3, 0, 0]),
        _finding("near_miss", (5, 0, 0)),
        _finding("unused_edges", [6, 0, 0]),
        _finding("face_not_patched", [7, 0, 0]),
        _finding("hole", [8, 0, 0]),
        _finding("fold", [9, 0, 0]),
        _finding("fold", [10, 0, 0]),
        _finding("unclosed_region", None),
    ]
    marks = network_markers(positions, kinds, findings)
    assert marks == {
        "nodes": [[0, 0, 0], [2, 0, 0], [4, 0, 0]],
        "t_joints": [[1, 0, 0]],
        "dangling_ends": [[3, 0, 0]],
        "near_misses": [[5, 0, 0]],
        "holes": [[8, 0, 0]],
        "folds": [[9, 0, 0], [10, 0, 0]],
        "problems": [[6, 0, 0], [7, 0, 0]],
    }, "a free end is marked by its dangling-end finding only; a finding without a place is not drawn"


def test_marker_arrays_are_float32_triples_for_every_kind():
    arrays = marker_arrays({"t_joints": [[1, 2, 3]]})
    assert set(arrays) == set(MARKER_KINDS)
    assert arrays["t_joints"].dtype == np.float32 and arrays["t_joints"].tolist() == [[1, 2, 3]]
    assert arrays["nodes"].shape == (0, 3)


def test_knuckle_segments_join_consecutive_points_by_source():
    edges = [
        {"curve": "chine", "source": "role", "points": [[0, 0, 0], [1, 0, 0], [2, 0, 0]]},
        {"curve": "k", "source": "auto", "points": [[0, 1, 0], [0, 2, 0]]},
        {"curve": "dot", "source": "auto", "points": [[9, 9, 9]]},
    ]
    lines = knuckle_segments(edges)
    assert lines["role"].tolist() == [[0, 0, 0], [1, 0, 0], [1, 0, 0], [2, 0, 0]]
    assert lines["auto"].tolist() == [[0, 1, 0], [0, 2, 0]], "a one-point edge draws nothing"
    assert knuckle_segments([])["role"].shape == (0, 3)
