"""Hydrostatic transformations through Blender (seed 002 §8): the PMB barge taken to a target
Cb, LCB or both as a new copy on the transformation stack, the original untouched; targets out
of range, hulls without a parallel middle body and bad arguments."""

import batten.api as api
import numpy as np
import pytest
from test_form import T, _points


def test_cb_plus_one_hundredth_lcb_held_as_a_copy_on_the_stack(barge):
    before = api.hydrostatics(barge, T)
    original_points = _points(barge)
    result = api.transform_hydrostatic(barge, cb=before["cb"] + 0.01)
    r = result.report
    assert r["stop"] == "converged" and r["limit"] is None
    assert 2 <= r["evaluations"] <= 12
    # Measured again on the copy, independently of the solver's figures.
    after = api.hydrostatics(result.collection, T, lpp=r["x_fp"] - r["x_ap"], fp=r["x_fp"])
    assert after["cb"] == pytest.approx(before["cb"] + 0.01, abs=2e-5)
    assert abs(after["lcb"] - before["lcb"]) <= 1e-5 * before["lpp"]
    # The copy's curves are Blender's float32 coordinates: the same hull to about 1e-8.
    assert after["volume"] == pytest.approx(r["after"]["volume"], rel=1e-7)
    assert r["pmb_length"][1] > r["pmb_length"][0]
    assert "Cb" in r["description"]
    # The original is untouched until commit; the copy is on its stack.
    assert _points(barge).keys() == original_points.keys()
    for key, a in original_points.items():
        assert np.array_equal(_points(barge)[key], a), key
    assert [s["collection"] for s in api.transform_stack(barge)][-1] == result.collection
    # The sectional-area curve: the midship area kept over a longer PMB (the ends squeezed,
    # so near the ends a station now cuts a finer part), more area in all.
    sac = r["sac"]
    xs, a0, a1 = (np.asarray(sac[k]) for k in ("x", "before", "after"))
    assert len(xs) == api.SAC_STATIONS
    mid = api.SAC_STATIONS // 2
    assert a1[mid] == pytest.approx(a0[mid], rel=1e-6)
    full = lambda a: int(np.sum(a >= a0[mid] * (1 - 1e-3)))  # noqa: E731
    assert full(a1) >= full(a0) + 4
    assert a1.sum() > a0.sum()
    assert xs[0] == pytest.approx(r["x_ap"]) and xs[-1] == pytest.approx(r["x_fp"])
    assert api.abandon(barge) == 1
    assert api.transform_stack(barge)[-1]["collection"] == barge


def test_lcb_forward_with_volume_held_then_both(barge):
    before = api.hydrostatics(barge, T)
    target = before["lcb"] + 0.0025 * before["lpp"]
    r = api.transform_hydrostatic(barge, lcb=target).report
    assert r["stop"] == "converged"
    assert abs(r["after"]["lcb"] - target) <= 1e-5 * before["lpp"]
    assert r["after"]["volume"] == pytest.approx(before["volume"], rel=1e-5)
    assert r["entrance_length"][1] < r["entrance_length"][0] < r["run_length"][1]
    volume, lcb = before["volume"] * 1.005, before["lcb"] - 0.001 * before["lpp"]
    r = api.transform_hydrostatic(barge, volume=volume, lcb=lcb).report
    assert r["stop"] == "converged" and r["evaluations"] <= 12
    assert r["after"]["volume"] == pytest.approx(before["volume"] * 1.005, rel=1e-5)


def test_target_out_of_range_gives_the_closest_hull_and_says_why(barge):
    before = api.hydrostatics(barge, T)
    result = api.transform_hydrostatic(barge, volume=0.9 * before["volume"])
    r = result.report
    assert r["stop"] == "out_of_range"
    assert "parallel middle body" in r["limit"]
    assert r["after"]["volume"] < before["volume"]
    assert r["explored"]["volume"][0] == pytest.approx(r["after"]["volume"], rel=1e-12)
    assert api.transform_stack(barge)[-1]["collection"] == result.collection


def test_what_it_refuses(barge, examples_dir):
    wigley = api.load_network(examples_dir / "wigley.json")
    with pytest.raises(api.InvalidArgumentError, match="role 'midship'"):
        api.transform_hydrostatic(wigley, cb=0.5, draft=3.0)
    assert len(api.transform_stack(wigley)) == 1
    with pytest.raises(api.InvalidArgumentError, match="one of volume"):
        api.transform_hydrostatic(barge, cb=0.8, volume=1000.0)
    with pytest.raises(api.InvalidArgumentError, match="give a volume"):
        api.transform_hydrostatic(barge)
    with pytest.raises(api.InvalidArgumentError, match="cb"):
        api.transform_hydrostatic(barge, cb=float("nan"))
    with pytest.raises(api.InvalidArgumentError, match="lcb"):
        api.transform_hydrostatic(barge, lcb=float("inf"))
    del barge[api.DESIGN_DRAFT_PROPERTY]
    with pytest.raises(api.InvalidArgumentError, match="design draft"):
        api.transform_hydrostatic(barge, cb=0.8)
    # Nothing was pushed by any refusal.
    assert len(api.transform_stack(barge)) == 1


def test_frigate_without_a_pmb_bulges_its_ends(examples_dir):
    frigate = api.load_network(examples_dir / "frigate_network.json")
    before = api.hydrostatics(frigate, 4.8)
    result = api.transform_hydrostatic(frigate, cb=before["cb"] - 0.005, draft=4.8)
    r = result.report
    assert (r["mode"], r["stop"]) == ("bulge", "converged")
    assert r["pmb_length"] is None and "bulged ends" in r["description"]
    entrance, run = r["bulge"]["offsets"]
    assert entrance < 0 and run < 0, "finer: both ends flattened"
    # Cb on the original's Lpp, Bwl and draft: a volume target (flattening the ends narrows
    # the waterline a little, so the copy's own Cb is not the one asked for).
    assert (r["target_figure"], r["target_value"]) == ("cb", pytest.approx(before["cb"] - 0.005))
    assert r["target_volume"] == pytest.approx(before["volume"] * (1 - 0.005 / before["cb"]), rel=1e-9)
    after = api.hydrostatics(result.collection, 4.8, lpp=r["x_fp"] - r["x_ap"], fp=r["x_fp"])
    assert after["volume"] == pytest.approx(r["target_volume"], rel=2e-5)
    assert abs(after["lcb"] - before["lcb"]) <= 2e-5 * before["lpp"]


def test_barge_with_its_pmb_held_is_bulged_not_lengthened(barge):
    before = api.hydrostatics(barge, T)
    r = api.transform_hydrostatic(barge, cb=before["cb"] + 0.005, keep_pmb=True).report
    assert (r["mode"], r["stop"]) == ("bulge", "converged")
    assert r["pmb_length"][1] == pytest.approx(r["pmb_length"][0], abs=1e-9)
    # Alike to what the solve stops at (|δLCB| ≤ 1e-5·Lpp), not bit for bit.
    assert r["bulge"]["offsets"][0] == pytest.approx(r["bulge"]["offsets"][1], rel=1e-3)
    assert r["bulge"]["offsets"][0] > 0


def test_a_change_too_large_for_the_pmb_alone_bulges_the_ends_as_well(barge):
    before = api.hydrostatics(barge, T)
    r = api.transform_hydrostatic(barge, cb=before["cb"] + 0.2).report
    assert r["mode"] == "pmb+bulge" and r["stop"] == "out_of_range"
    assert "then, bulging the ends" in r["limit"] and "PMB ends and bulged ends" in r["description"]
    assert r["pmb_length"][1] > r["pmb_length"][0] and min(r["bulge"]["offsets"]) > 0
    assert r["after"]["volume"] > 1.03 * before["volume"]


def test_pmb_held_in_part_and_a_bad_hold(barge):
    before = api.hydrostatics(barge, T)
    r = api.transform_hydrostatic(
        barge, cb=before["cb"] + 0.005, lcb=before["lcb"] + 0.002 * before["lpp"], keep_pmb="length"
    ).report
    assert (r["mode"], r["stop"]) == ("pmb_shift+bulge", "converged")
    assert r["pmb_length"][1] == pytest.approx(r["pmb_length"][0], abs=1e-9)
    assert "PMB shifted" in r["description"]
    with pytest.raises(api.InvalidArgumentError, match="keep_pmb"):
        api.transform_hydrostatic(barge, cb=0.8, keep_pmb="sideways")
