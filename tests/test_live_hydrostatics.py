"""Hydrostatics that follow a live drag: after an incremental rebuild (faces k of N patched
again) the hull's cells for hydrostatics are made again only for those faces, the rest kept
from the model before, and the figures are those of a fresh full build, bit for bit."""

import json

import batten.api as api
import pytest
from batten import hull_models
from batten_native import DEFAULT_RESOLUTION, build_hull_model
from helpers import move_point


@pytest.fixture
def kcs(hulls_dir):
    path = hulls_dir / "kcs" / "network.json"
    if not path.exists():
        pytest.skip(f"{path} not found")
    ref = json.loads(path.read_text())
    hull_models.forget()
    coll, _ = api.import_sections(path)
    yield coll, ref["T"], ref["Lpp"]
    hull_models.forget()


def _kept_model(coll):
    return hull_models._kept[coll.name].model


def _fresh(coll):
    """The model of a full build of the collection's curves now."""
    curves = api.read_curves(coll)
    return build_hull_model(
        curves, api.DEFAULT_TOLERANCE, DEFAULT_RESOLUTION, coll.name, api.tangent_planes(coll)
    )[2]


def test_drags_keep_the_other_faces_cells_and_give_a_full_build_s_figures(kcs):
    coll, draft, lpp = kcs
    api.build(coll, live=True)
    before = api.hydrostatics(coll, draft, lpp=lpp, fp=lpp)
    api.hydrostatics(coll, draft, lpp=lpp, fp=lpp, live=True)
    total = _kept_model(coll).cells
    assert _kept_model(coll).cells_kept == 0, "the first build makes every cell"
    station = coll.objects["st10"]
    middle = len(station.data.splines[0].points) // 2
    # Sub-tolerance drags (the station stays on its crossings): the first two without figures
    # in between (the cells kept are then those of the last model that made them).
    for dys, check in (((4e-5, -3e-5), True), ((2e-5,), True), ((-5e-5,), False)):
        for dy in dys:
            move_point(station, middle, dy)
            rebuild = api.build(coll, live=True).report["rebuild"]
            assert rebuild["kind"] == "incremental" and 0 < rebuild["faces"] < rebuild["of"], rebuild
        after = api.hydrostatics(coll, draft, lpp=lpp, fp=lpp)
        live = api.hydrostatics(coll, draft, lpp=lpp, fp=lpp, live=True)
        model = _kept_model(coll)
        assert model.cells == total
        # Only the cells of the faces the drags reached were made again.
        assert 0.5 * total < model.cells_kept < total, (model.cells_kept, total)
        if check:
            fresh = _fresh(coll)
            assert fresh.cells_kept == 0
            assert fresh.hydrostatics(draft, lpp=lpp, fp=lpp) == after
            assert fresh.hydrostatics(draft, lpp=lpp, fp=lpp, live=True) == live
    # The drags moved the surface: the figures moved with it (by a sliver).
    assert after["volume"] != before["volume"]
    assert after["volume"] == pytest.approx(before["volume"], rel=1e-6)


def test_a_full_rebuild_makes_every_cell_again(kcs):
    coll, draft, lpp = kcs
    api.build(coll, live=True)
    api.hydrostatics(coll, draft, lpp=lpp, fp=lpp)
    station = coll.objects["st10"]
    # The control point nearest the station's crossing with the design waterline: moving it
    # takes the station off the crossing, which changes the connectivity, and so does the move
    # back: both are full rebuilds, and nothing is kept.
    curve = api.read_curves(coll.objects["wl_z10.80"])[0]
    spline = station.data.splines[0]
    points = [tuple(p.co)[:3] for p in spline.points]
    crossing = min((curve.nearest(p)[1], i) for i, p in enumerate(points))[1]
    for dy in (0.05, -0.05):
        move_point(station, crossing, dy)
        rebuild = api.build(coll, live=True).report["rebuild"]
        assert rebuild["kind"] == "full", rebuild
    after = api.hydrostatics(coll, draft, lpp=lpp, fp=lpp)
    assert _kept_model(coll).cells_kept == 0
    assert _fresh(coll).hydrostatics(draft, lpp=lpp, fp=lpp) == after
