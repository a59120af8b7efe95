"""KVLCC2's station 20 is at the FP, x = 320 m, where its stem also stands between z = 20.3 and
21.7 m: the station runs up the stem and meets it at 9°, 2.35 cm below where the waterline at
20.8 m ends on it (when ``shared/hulls`` is beside the checkout). Where along the stem so
shallow a meeting lies is uncertain by the capture over sin 9°, so the two ends are one node;
the face between station and stem then has a cusp there, and takes the side-blended patch. The
surface is G1 within the real-ships issue's 0.05° at the default resolution and at the demo's
(it was 9.39° and 11.7°)."""

from pathlib import Path

import batten.api as api
import numpy as np
import pytest

HULLS = Path(__file__).resolve().parents[2] / "shared" / "hulls"


@pytest.mark.skipif(not HULLS.is_dir(), reason="shared/hulls is not beside the checkout")
def test_kvlcc2_fp_station_meets_the_stem_at_one_node_and_the_surface_is_g1():
    coll, _ = api.import_sections(HULLS / "kvlcc2" / "network.json")
    for resolution in (8, 12):
        report = api.build(coll, resolution=resolution).report
        # Measured 0.047° at both (at the station's crossing with wl_z5.00).
        assert report["max_normal_angle_deg"] < 0.05, (resolution, report["max_normal_angle_at"])
        cusps = [w for w in report["warnings"] if w["kind"] == "side_blended" and "cusp" in w["message"]]
        assert len(cusps) == 1 and "st20_part1of2" in cusps[0]["curves"], cusps
    nodes = np.asarray(report["node_positions"])
    top = np.linalg.norm(nodes - [320.0, 0.0, 20.8], axis=1)
    end = np.linalg.norm(nodes - [320.0, 0.0, 20.7766], axis=1)
    assert top.min() < 1e-3, "the node is where the waterline ends on the stem"
    assert end.min() > 0.02, "and no second node where the station ended, 2.35 cm below"
