"""The real ships as a new user builds them show no fold where the patches' own checks can see
one coming (when ``shared/hulls`` is beside the checkout)."""

from pathlib import Path

import batten.api as api
import pytest

HULLS = Path(__file__).resolve().parents[2] / "shared" / "hulls"


@pytest.mark.skipif(not HULLS.is_dir(), reason="shared/hulls is not beside the checkout")
def test_kcs_at_the_demo_resolution_has_no_fold_along_its_stern_waterline():
    """KCS's five-sided face aft of station 1.5 (profile, st01, wl_z0.30, st1.50, wl_z1.50): its
    Charrot–Gregory patch turned away from the tangent plane along wl_z1.50 within its first row
    of polygons, and folded at 35.7° against the face above, though no two of its own polygons
    were 30° apart. The patch choice weighs each polygon along a smooth edge against that
    tangent plane (and took the side-blended patch there, before the edges' normal fields
    stopped turning where their curves' parameters crowd; the Charrot–Gregory patch no longer
    folds)."""
    coll, _ = api.import_sections(HULLS / "kcs" / "network.json")
    report = api.build(coll, resolution=12).report
    folds = [w for w in report["warnings"] if w["kind"] == "fold"]
    assert report["folds"] == 0, folds
    assert report["max_normal_angle_deg"] < 0.01


@pytest.mark.skipif(not HULLS.is_dir(), reason="shared/hulls is not beside the checkout")
@pytest.mark.parametrize("ship", ["kcs", "kvlcc2"])
def test_the_real_ships_at_the_defaults_have_no_fold(ship):
    """The real-ships issue's acceptance: import and build with every setting at its default,
    no fold anywhere. KCS's counter (the five-sided face between wl_z9.00 and wl_z10.80 aft of
    station 1) creased at 39.8° along a line from x = 10.05 m on wl_z9.00, where the offsets
    cross a seam of the surface they were cut from and are sampled densely: the waterline's
    parameter crowded 30 times there, and its normal field turned with it."""
    coll, _ = api.import_sections(HULLS / ship / "network.json")
    report = api.build(coll).report
    folds = [w for w in report["warnings"] if w["kind"] == "fold"]
    assert report["folds"] == 0, folds
