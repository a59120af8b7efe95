"""api.sections (issue 16): exact plane sections of the Wigley hull against its analytic
form, the collection of section curves and its refresh on rebuild, and bad input."""

import csv
import json
import math
from pathlib import Path

import batten.api as api
import bpy
import numpy as np
import pytest

L, B, T, DECK = 100.0, 10.0, 6.25, 8.75  # examples/wigley_lines.json


def wigley_y(x, z):
    w = np.maximum((T - z) / T, 0.0)
    return 0.5 * B * (1.0 - (2.0 * x / L) ** 2) * (1.0 - w * w)


@pytest.fixture
def wigley():
    coll = api.load_example("wigley_lines.json")
    api.build(coll)
    return coll


def test_every_family_follows_the_analytic_hull(wigley):
    result = api.sections(
        wigley, stations=9, waterlines=[1.0, 3.0, T], buttocks=4, diagonals=[(0.0, 6.0, -30.0)]
    )
    assert set(result) == {"stations", "waterlines", "buttocks", "diagonals", "knuckles"}
    st = result["stations"]
    # 9 stations evenly over the x-extent, the ends left out: every 10 m from −40 to 40.
    assert [s.offset for s in st] == pytest.approx(np.linspace(-40, 40, 9))
    assert st[0].name == "station -40.000" and st[0].family == "stations"
    for s in st + result["waterlines"] + result["diagonals"]:
        assert len(s.polylines) == 1 and len(s.curves) == 1, s.name
        pts = s.polylines[0]
        assert pts.dtype == np.float64 and pts.shape[1] == 3 and len(pts) > 10
        assert np.abs(pts[:, 1] - wigley_y(pts[:, 0], pts[:, 2])).max() < 5e-3, s.name
        assert isinstance(s.curves[0], api.Curve)
        # The fitted curve within the tolerance of the points.
        assert max(s.curves[0].nearest(p)[1] for p in pts) <= 1e-3 + 1e-9, s.name
    for s in st:
        assert np.abs(s.polylines[0][:, 0] - s.offset).max() < 1e-9
    assert [s.offset for s in result["buttocks"]] == pytest.approx([1.0, 2.0, 3.0, 4.0])
    for s in result["buttocks"]:
        pts = np.concatenate(s.polylines)
        assert np.abs(pts[:, 1] - s.offset).max() < 1e-9
        assert np.abs(pts[:, 1] - wigley_y(pts[:, 0], pts[:, 2])).max() < 5e-3
    assert result["knuckles"] == []  # the Wigley hull is smooth


def test_a_plane_missing_the_hull_has_no_polylines(wigley):
    result = api.sections(wigley, stations=[60.0], waterlines=[-1.0])
    assert result["stations"][0].polylines == [] and result["waterlines"][0].curves == []
    assert result["buttocks"] == [] and result["diagonals"] == []


@pytest.mark.parametrize(
    ("kwargs", "word"),
    [
        ({"stations": [1.0, math.nan]}, "stations"),
        ({"waterlines": [math.inf]}, "waterlines"),
        ({"buttocks": -2}, "buttocks"),
        ({"diagonals": [(0.0, math.nan, 10.0)]}, "diagonals"),
        ({"diagonals": [(0.0, 1.0, 95.0)]}, "diagonals"),
        ({"stations": 3, "tolerance": 0.0}, "tolerance"),
    ],
)
def test_bad_offsets_are_refused_naming_the_argument(wigley, kwargs, word):
    with pytest.raises(api.InvalidArgumentError, match=word):
        api.sections(wigley, **kwargs)


def test_the_collection_holds_one_curve_object_per_section_and_follows_rebuilds(wigley):
    api.sections(wigley, stations=[0.0, 20.0], waterlines=[T], collection=True)
    coll = bpy.data.collections["wigley_lines sections"]
    assert coll.name in wigley.children
    assert sorted(o.name for o in coll.objects) == ["station 0.000", "station 20.000", f"waterline {T:.3f}"]
    # Drawing again replaces them.
    api.sections(wigley, stations=[10.0], collection=True)
    assert [o.name for o in coll.objects] == ["station 10.000"]
    # The section curves are output: the hull is built from the same curves as before.
    assert not any(o.name.startswith("station 10") for o in api.curve_objects(wigley))
    # Widen the hull (every curve's y × 1.1) and rebuild: the drawn station follows.
    for obj in api.curve_objects(wigley):
        for spline in obj.data.splines:
            for p in spline.points:
                p.co[1] *= 1.1
            for p in spline.bezier_points:
                p.co[1] *= 1.1
    settings = bpy.context.scene.batten
    settings.source = wigley
    assert bpy.ops.batten.build() == {"FINISHED"}
    obj = coll.objects["station 10.000"]
    ys = [p.co[1] for s in obj.data.splines for p in s.points]
    assert max(ys) == pytest.approx(1.1 * wigley_y(10.0, DECK), rel=2e-3)


HULLS = Path(__file__).resolve().parents[2] / "shared" / "hulls"


def _read_table(path):
    rows = list(csv.reader(path.read_text().splitlines()))
    header = {r[0]: r[1] for r in rows[:8] if len(r) >= 2}
    start = next(i for i, r in enumerate(rows) if r and r[0] == "half-breadths")
    xs = [float(v) for v in rows[start + 1][2:]]
    table = {}
    for r in rows[start + 2 :]:
        if not r:
            break
        table[float(r[1])] = r[2:]
    return header, xs, table, rows


def test_offsets_table_gives_the_analytic_half_breadths(wigley, tmp_path):
    path = api.offsets_table(
        wigley, tmp_path / "wigley.csv", stations=11, waterlines=[0.0, 2.0, T, 8.0], buttocks=[2.0]
    )
    header, xs, table, rows = _read_table(path)
    assert header["batten offsets table"] == "wigley_lines" and header["units"] == "metres"
    assert "AP x" in header and "FP x" in header and header["design draft"] == ""
    assert xs == pytest.approx(np.linspace(-50, 50, 11))
    for z, cells in table.items():
        for x, cell in zip(xs, cells, strict=True):
            if abs(x) == 50.0 or z == 0.0:
                # The pointed ends and the keel: a single point (y = 0) at most.
                assert cell == "" or abs(float(cell)) < 1e-3, (x, z, cell)
                continue
            assert float(cell) == pytest.approx(wigley_y(x, z), abs=5e-3), (x, z)
    assert "nan" not in path.read_text().lower()
    # Heights at the buttock y = 2: where the station is wide enough, z from the parabola.
    i = next(i for i, r in enumerate(rows) if r and r[0] == "heights")
    bl = rows[i + 2]
    assert bl[0] == "BL 2.000"
    for x, cell in zip(xs, bl[2:], strict=True):
        if wigley_y(x, DECK) <= 2.0:
            assert cell == "", (x, cell)  # the station does not reach the buttock
        else:
            z = float(cell)
            assert wigley_y(x, z) == pytest.approx(2.0, abs=5e-3), (x, z)


def test_offsets_table_refuses_nan_and_leaves_no_file(wigley, tmp_path):
    with pytest.raises(api.InvalidArgumentError, match="waterlines"):
        api.offsets_table(wigley, tmp_path / "t.csv", waterlines=[1.0, math.nan])
    assert not (tmp_path / "t.csv").exists()
    with pytest.raises(api.NetworkFileError, match="offsets table"):
        api.offsets_table(wigley, tmp_path, stations=3)  # a folder, not a file


#: Warnings a round-tripped network must not have: the file is a consistent network.
INCONSISTENT = {"dangling_end", "unused_edges", "near_miss", "hole", "unclosed_region", "face_not_patched"}


def _round_trip(coll, tmp_path, draft, **kwargs):
    path = api.export_sections(coll, tmp_path / "sections.json", **kwargs)
    again, _ = api.import_sections(path, collection="round trip")
    report = api.build(again).report
    inconsistent = [(w["kind"], w["message"]) for w in report["warnings"] if w["kind"] in INCONSISTENT]
    assert not inconsistent, inconsistent
    assert report["holes"] == 0, report["holes"]
    return api.hydrostatics(coll, draft), api.hydrostatics(again, draft)


def test_the_exported_sections_end_on_points_of_the_boundary_curves(wigley, tmp_path):
    # Every station and waterline end is a point of the keel's, stem's or deck's polyline in
    # the file (a chord across the curve would miss it): measured within 1e-6 m.
    data = json.loads(api.export_sections(wigley, tmp_path / "s.json", stations=11, waterlines=6).read_text())
    cut = [c for c in data["curves"] if c["kind"] in ("station", "waterline")]
    boundary = np.array([p for c in data["curves"] if c not in cut for p in c["points"]])
    ends = np.array([c["points"][k] for c in cut for k in (0, -1)])
    gaps = np.linalg.norm(ends[:, None, :] - boundary[None, :, :], axis=2).min(axis=1)
    assert len(ends) == 2 * 15 and gaps.max() <= 2e-6, gaps.max()


def test_wigley_sections_round_trip_within_0_1_percent(wigley, tmp_path):
    before, after = _round_trip(wigley, tmp_path, T, stations=11, waterlines=6)
    assert after["volume"] == pytest.approx(before["volume"], rel=1e-3)


def test_frigate_sections_round_trip_with_its_transom_and_a_straight_keel(examples_dir, tmp_path):
    # 40 stations end on the frigate's straight keel (one cubic span: its move through their
    # ends once failed), the station at the AP lies in the transom's plane (left out of the
    # file: the transom keeps its role). Measured: volume -0.0029 % at 4 m.
    coll = api.load_network(examples_dir / "frigate_network.json")
    api.build(coll)
    before, after = _round_trip(coll, tmp_path, 4.0, stations=40, waterlines=12)
    assert after["volume"] == pytest.approx(before["volume"], rel=1e-3)


def test_kcs_sections_round_trip_within_0_1_percent(tmp_path):
    # The file's stations end on the profile's and deck's points (the profile's corner at the
    # transom and the deck's at its top were cut by chords by up to 0.23 m), the chine ends on
    # the sections, and the station piece cut where KCS's surface folds at the counter
    # (x 5.9 m) is left out: no dangling end, near miss or hole (before: 6 dangling ends, 2
    # holes). The sections never double back, and their points are no closer than the import's
    # tolerance: the re-import's fits no longer loop off their data (one looped 2 m off at the
    # counter and its patch folded across the centreplane, halving the volume). Waterline
    # 3.459 crosses the shaft boss's flat end 9 mm above its lower corner: it starts at the
    # end's edge, else the re-import joins it to the corner and it bounds a two-sided face
    # with the edge (a near miss of 0.84 mm). Measured: volume +0.004 % (before: -0.040 %).
    coll, _ = api.import_sections(HULLS / "kcs" / "network.json")
    api.build(coll)
    before, after = _round_trip(coll, tmp_path, api.design_draft(coll), stations=40, waterlines=12)
    assert after["volume"] == pytest.approx(before["volume"], rel=1e-3), (after["volume"], before["volume"])


def test_a_slow_cut_waits_while_dragging_and_comes_once_the_rebuilds_pause(wigley):
    from batten import scene_build

    api.sections(wigley, stations=[10.0], collection=True)
    coll = bpy.data.collections["wigley_lines sections"]
    coll.objects["station 10.000"]["mark"] = 1  # a new object will not carry it
    scene_build._cut_seconds[wigley.name] = 1.0  # as if the last cut took a second
    scene_build.refresh_sections(wigley, live=True)
    assert coll.objects["station 10.000"].get("mark") == 1, "not cut again while dragging"
    pending = scene_build._deferred[wigley.name]
    assert bpy.app.timers.is_registered(pending)
    bpy.app.timers.unregister(pending)
    pending()  # what the timer does once the rebuilds have paused
    assert coll.objects["station 10.000"].get("mark") is None, "cut again"
    scene_build._cut_seconds[wigley.name] = 0.0
    scene_build.refresh_sections(wigley, live=True)  # a fast cut happens at once
    assert wigley.name not in scene_build._deferred
