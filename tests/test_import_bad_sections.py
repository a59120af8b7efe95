"""Bad input on the way from sections to a hull (real-ships issue): points out of order, a
section crossing itself, duplicate sections, sections that never meet, NaN — each a clear
error or diagnostic naming the curve, and a failed import draws nothing."""

import json
import math

import batten.api as api
import bpy
import numpy as np
import pytest
from batten_native import BattenError, FairError, NoSurfaceError


def _section(name, points, kind="station"):
    return {"name": name, "kind": kind, "points": [[float(c) for c in p] for p in points]}


def _arc(x, n=30):
    return [(x, math.sin(t), 1.0 - math.cos(t)) for t in np.linspace(0.0, math.pi / 2, n)]


def _waterline(z=0.5):
    return _section(
        "wl", [(x, math.sqrt(1 - (1 - z) ** 2), z) for x in np.linspace(-1.0, 6.0, 20)], "waterline"
    )


def _write(tmp_path, name, curves):
    path = tmp_path / f"{name}.json"
    # json writes NaN as the bare token NaN, which the section reader must refuse by name.
    path.write_text(json.dumps({"name": name, "curves": curves}))
    return path


def _objects():
    return {o.name for o in bpy.data.objects}, {c.name for c in bpy.data.collections}


@pytest.mark.parametrize(
    ("case", "curves", "error", "named"),
    [
        (
            "out_of_order",
            [_section("st1", [_arc(0.0)[i] for i in np.random.default_rng(1).permutation(30)])],
            FairError,
            "st1",
        ),
        (
            "nan",
            [_section("st1", _arc(0.0)[:10] + [(0.0, math.nan, 0.0)] + _arc(0.0)[11:])],
            BattenError,
            "st1",
        ),
    ],
)
def test_a_bad_section_is_an_error_naming_it_and_nothing_is_drawn(tmp_path, case, curves, error, named):
    before = _objects()
    with pytest.raises(error, match=f"'{named}'"):
        api.import_sections(_write(tmp_path, case, curves))
    assert _objects() == before, "a failed import draws nothing"


def test_a_section_crossing_itself_is_named_by_the_build(tmp_path):
    figure_eight = [
        (0.0, 0.5 + math.cos(t), 1.0 + math.sin(2 * t)) for t in np.linspace(0.1, 2 * math.pi - 0.1, 80)
    ]
    coll, _ = api.import_sections(_write(tmp_path, "eight", [_section("st1", figure_eight), _waterline(1.0)]))
    topo = api.topology(coll)
    crossing = [d for d in topo["diagnostics"] if d["kind"] == "self_intersection"]
    assert crossing and crossing[0]["curves"] == ["st1"], topo["diagnostics"]


def test_duplicate_sections_are_named_and_one_is_left_out(tmp_path):
    curves = [_section("st1", _arc(0.0)), _section("st1_again", _arc(0.0)), _waterline()]
    coll, _ = api.import_sections(_write(tmp_path, "dup", curves))
    topo = api.topology(coll)
    dup = [d for d in topo["diagnostics"] if d["kind"] == "duplicate_curve"]
    assert dup and set(dup[0]["curves"]) == {"st1", "st1_again"}, topo["diagnostics"]


def test_sections_that_never_meet_build_nothing_and_say_which(tmp_path):
    coll, _ = api.import_sections(
        _write(tmp_path, "apart", [_section("st1", _arc(0.0)), _section("st2", _arc(5.0))])
    )
    with pytest.raises(NoSurfaceError, match="network 'apart'.*'st1'.*meets no other curve"):
        api.build(coll)
