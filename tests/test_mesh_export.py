"""STL through Blender's own exporter: the hull surface as evaluated (both halves, the Mirror
modifier applied) is open at the deck and the transom; ``api.closed_surface`` closes it, and
the STL Blender writes of that is watertight (every edge of two triangles, read back with
trimesh) with twice the half hull's volume."""

from __future__ import annotations

from pathlib import Path

import batten.api as api
import bpy
import numpy as np
import pytest
from helpers import wigley_without_keel

trimesh = pytest.importorskip("trimesh")

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
RESOLUTION = 8  # build()'s default


def _stl(obj, path: Path):
    """``obj`` written by Blender's STL exporter (modifiers applied) and read back."""
    bpy.ops.object.select_all(action="DESELECT")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.wm.stl_export(filepath=str(path), export_selected_objects=True, apply_modifiers=True) == {
        "FINISHED"
    }
    return trimesh.load(path, file_type="stl")


def _edge_uses(mesh) -> np.ndarray:
    """How many triangles each distinct edge of ``mesh`` has."""
    return np.unique(np.sort(mesh.edges, axis=1), axis=0, return_counts=True)[1]


@pytest.mark.parametrize("example", ["wigley_lines.json", "frigate_network.json"])
def test_a_closed_mirrored_stl_is_watertight_with_the_hulls_volume(example, tmp_path):
    coll = api.load_network(EXAMPLES / example)
    fine = 2 * api.build(coll, resolution=2 * RESOLUTION).report["enclosed_volume_half"]
    result = api.build(coll, resolution=RESOLUTION)
    volume = 2 * result.report["enclosed_volume_half"]
    # Blender's exporter alone writes the open surface: the deck (and transom) have one face.
    assert (_edge_uses(_stl(result.object, tmp_path / "open.stl")) == 1).any(), "the rim is open"
    closed = api.closed_surface(coll)
    assert closed.name == f"{result.object.name} closed"
    stl = _stl(closed, tmp_path / "closed.stl")
    uses = _edge_uses(stl)
    assert (uses == 2).all(), f"edges with {sorted(set(uses.tolist()) - {2})} triangles"
    assert stl.is_winding_consistent and stl.volume > 0, "faces point out"
    # The core's half volume counts each quad as the mean of its two splits, Blender splits it
    # one way: far below the tessellation error, measured as the change at twice the resolution.
    tessellation = abs(fine - volume)
    assert abs(stl.volume - volume) < 0.2 * tessellation, (
        f"STL {stl.volume:.4f} m³, 2 × half {volume:.4f} m³, tessellation error {tessellation:.4f} m³"
    )
    print(
        f"{example}: {len(stl.faces)} triangles, STL {stl.volume:.4f} m³, 2 × half {volume:.4f} m³ "
        f"({stl.volume / volume - 1:+.1e}), tessellation error {tessellation / volume:.1e}"
    )


def test_closing_again_replaces_the_closed_copy(tmp_path):
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    first = api.closed_surface(coll).name
    api.closed_surface(coll)
    assert [o.name for o in bpy.data.objects if o.name.startswith(first)] == [first], "one closed copy"


def test_an_unmirrored_surface_is_not_closed_silently():
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    api.build(coll, mirror=False)
    with pytest.raises(api.ExportError, match="not symmetric about the centreplane"):
        api.closed_surface(coll)
    assert not any(o.name.endswith(" closed") for o in bpy.data.objects), "nothing made"


def test_a_surface_with_a_hole_is_not_closed_over_it():
    coll = wigley_without_keel()
    api.build(coll)
    with pytest.raises(api.ExportError, match=r"a hole near \(.*, 1\.042\) m, below its top"):
        api.closed_surface(coll)
    assert not any(o.name.endswith(" closed") for o in bpy.data.objects), "nothing made"
