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
    were 30° apart. The patch choice now also weighs each polygon along a smooth edge against
    that tangent plane, and takes the side-blended patch there."""
    coll, _ = api.import_sections(HULLS / "kcs" / "network.json")
    report = api.build(coll, resolution=12).report
    folds = [w for w in report["warnings"] if w["kind"] == "fold"]
    assert report["folds"] == 0, folds
    blended = [w for w in report["warnings"] if w["kind"] == "side_blended"]
    assert any({"st01", "st1.50", "wl_z0.30", "wl_z1.50"} <= set(w["curves"]) for w in blended), blended
    assert report["max_normal_angle_deg"] < 0.01
