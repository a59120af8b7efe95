"""Hypothesis fuzzing of ``batten.api`` inside Blender (issue 21): curve objects drawn from
jittered grids at extreme sizes, offsets and object transforms, and files of hostile content
and names, through read_curves, topology, build, export_network, read_network,
import_sections, curvature_comb and fair_curves. Each call gives a finite result or raises a
``BattenError`` (never another exception, never a crash or a hang); the budget and limits
are those of ``plain/fuzz_support.py``."""

from __future__ import annotations

import json

import batten.api as api
import bpy
import numpy as np
from helpers import new_curve
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from mathutils import Matrix
from plain.fuzz_support import call, finite

# One Blender file for all examples of a test: each example clears what the last one drew.
_per_example = settings(suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])

scales = st.sampled_from([1.0, 1e-3, 1e3, 1e-30, 1e30])
offsets = st.sampled_from([0.0, 1e4, 1e7])


def _clear() -> None:
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for coll in list(bpy.data.collections):
        bpy.data.collections.remove(coll)


@st.composite
def grid_objects(draw):
    """Stations and waterlines of a jittered Wigley-like grid as POLY or NURBS curve objects
    (Blender stores float32), scaled and moved by the object transform or in the points."""
    _clear()
    m, k = draw(st.integers(2, 4)), draw(st.integers(2, 4))
    x, z = np.meshgrid(np.linspace(0, 1, m), np.linspace(0, 1, k), indexing="ij")
    grid = np.stack([x, 0.3 * (1 - (2 * x - 1) ** 2) * (1 - z**2), z], axis=-1)
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    grid = grid + draw(st.sampled_from([0.0, 1e-6, 1e-3])) * rng.standard_normal(grid.shape)
    size, at = draw(scales), draw(offsets)
    in_matrix = draw(st.booleans())
    matrix = Matrix.Translation((at, at, 0)) @ Matrix.Scale(size, 4) if in_matrix else None
    pts = grid if in_matrix else grid * size + at
    kind = draw(st.sampled_from(["POLY", "NURBS"]))
    rows = [pts[i] for i in range(m)] + [pts[:, j] for j in range(k)]
    return [
        new_curve(f"c{i}", kind, r, order=min(4, len(r)), endpoint=True, matrix=matrix)
        for i, r in enumerate(rows)
    ]


def _clean(result) -> None:
    if not isinstance(result, api.BattenError):
        assert finite(result), result


@_per_example
@given(
    objects=grid_objects(), tolerance=st.sampled_from([1e-4, 1e-9, 1e-2, 1.0]), resolution=st.integers(1, 6)
)
def test_api_on_curve_objects(objects, tolerance, resolution, tmp_path):
    _clean(call(api.read_curves, objects))
    _clean(call(api.topology, objects, tolerance=tolerance))
    built = call(api.build, objects, tolerance=tolerance, resolution=resolution)
    if not isinstance(built, api.BattenError):
        assert finite(built.report), built.report
    written = call(api.export_network, objects, tmp_path / "net.json", tolerance=tolerance)
    if not isinstance(written, api.BattenError):
        name, curves = api.read_network(written)
        assert [c.name for c in curves] == [o.name for o in objects]
    _clean(call(api.curvature_comb, objects[0]))
    _clean(call(api.fair_curves, objects, tolerance=tolerance))  # last: it redraws the objects


paths = st.one_of(
    st.text(st.characters(codec="utf-8", exclude_characters="/\x00"), min_size=1, max_size=8),
    st.binary(min_size=1, max_size=6).filter(lambda b: b"/" not in b and b"\x00" not in b),
    st.just("\ud800.json"),
    st.just("x\udcff.csv"),
)
contents = st.one_of(
    st.binary(max_size=40),
    st.text(max_size=40).map(lambda s: s.encode("utf-8", "surrogatepass")),
    st.builds(
        lambda pts, kind: json.dumps(
            {"name": "s", "curves": [{"name": "st", "kind": kind, "points": pts}]}
        ).encode(),
        st.lists(st.lists(st.floats(allow_nan=True), min_size=3, max_size=3), max_size=12),
        st.sampled_from(["station", "waterline", "keel", "bogus", 3]),
    ),
    st.builds(
        lambda rows: "".join(f"st,{a},{b},{c}\n" for a, b, c in rows).encode(),
        st.lists(st.tuples(st.floats(), st.floats(), st.floats()), max_size=12),
    ),
)


@_per_example
@given(name=paths, content=contents, suffix=st.sampled_from(["", ".json", ".csv"]))
def test_api_on_hostile_files(name, content, suffix, tmp_path):
    _clear()
    path = tmp_path / "missing.json"
    try:
        full = tmp_path / (name if isinstance(name, str) else name.decode("utf-8", "surrogateescape"))
        full = full.with_name(full.name + suffix)
        full.write_bytes(content)
        path = full
    except (OSError, UnicodeEncodeError, ValueError):
        pass
    for target in (path, str(path), bytes(str(path), "utf-8", "surrogateescape")):
        _clean(call(api.read_network, target))
        _clean(call(api.import_sections, target))
