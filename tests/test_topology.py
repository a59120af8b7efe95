"""Topology through Blender: the same answers as the core, from curves drawn in Blender."""

import batten.api as api
import numpy as np
import pytest
from helpers import new_curve


def test_frigate_faces_from_blender_curves(examples_dir):
    coll = api.load_network(examples_dir / "frigate_network.json")
    topo = api.topology(coll)
    assert (topo["nodes"], topo["edges"]) == (29, 45)
    assert topo["faces_by_corners"] == {3: 1, 4: 15, 5: 1}
    five = [f for f in topo["faces"] if f["corners"] == 5]
    assert len(five) == 1 and sorted(five[0]["curves"]) == sorted(
        ["cwl", "knuckle", "rounding", "st8", "stem"]
    )
    by_curves = {tuple(sorted(f["curves"])): f for f in topo["faces"]}
    for names in [("cwl", "keel", "st2", "st4"), ("cwl", "deck", "st4", "st6")]:
        face = by_curves[names]
        assert (face["edges"], face["corners"]) == (5, 4), (
            f"T-joint beside {names}: a composite side, not a corner"
        )
    assert len(topo["boundary_loops"]) == 1
    assert topo["diagnostics"] == []
    # T-joints: the knuckle ends on st6, wl_aft on st2, the rounding on the cwl; stations end
    # on the keel and the deck (every face has a corner there).
    kinds = {k: topo["node_kinds"].count(k) for k in set(topo["node_kinds"])}
    assert kinds == {"crossing": 7, "end_to_end": 4, "end_on_curve": 15, "t_joint": 3}


def test_wigley_grid_counts(examples_dir):
    coll = api.load_network(examples_dir / "wigley.json")
    topo = api.topology(coll)
    m, n = 7, 3  # stations x waterlines between keel and deck
    assert topo["nodes"] == m * n + 2 * m + 2 * n + 4
    assert topo["edges"] == 2 * m * n + 3 * m + 3 * n + 4
    assert topo["faces_by_corners"] == {4: (m + 1) * (n + 1)}
    assert len(topo["node_positions"]) == topo["nodes"]


def test_near_miss_and_dangling_end_are_named():
    new_curve("keel", "POLY", np.array([[0.0, 0, 0], [10, 0, 0]]))
    new_curve("deck", "POLY", np.array([[0.0, 0, 3], [10, 0, 3]]))
    new_curve("aft", "POLY", np.array([[0.0, 0, 0], [0, 0, 3]]))
    new_curve("stem", "POLY", np.array([[10.0, 0, 0], [10, 0, 3]]))
    # A station stopping 0.5 mm short of the deck (tolerance 0.1 mm): a near miss, not a join.
    new_curve("st5", "POLY", np.array([[5.0, 0, 0], [5, 0, 2.9995]]))
    topo = api.topology(list(__import__("bpy").data.objects), tolerance=1e-4)
    kinds = {d["kind"]: d for d in topo["diagnostics"]}
    assert "near_miss" in kinds
    assert sorted(kinds["near_miss"]["curves"]) == ["deck", "st5"]
    assert kinds["near_miss"]["location"] == pytest.approx([5, 0, 3], abs=1e-3)
    assert "st5" in kinds["dangling_end"]["curves"]


def test_bad_tolerance_and_empty_input():
    obj = new_curve("a", "POLY", np.array([[0.0, 0, 0], [1, 0, 0]]))
    with pytest.raises(api.BattenError, match="tolerance"):
        api.topology([obj], tolerance=0.0)
    with pytest.raises(api.BattenError, match="holds no curves"):
        api.topology([])
