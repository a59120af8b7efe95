"""The drawn water surface follows batten's flotation convention: draft at midships, trim by
the stern deeper aft, heel to starboard deeper on y < 0."""

import math

import numpy as np
import pytest
from batten.waterplane_outline import MARGIN_SHARE, water_height, waterplane_outline

LO, HI = np.array([-50.0, -5.0, 0.0]), np.array([50.0, 5.0, 8.75])


def test_level_water_covers_the_box_at_the_draft():
    c = waterplane_outline(LO, HI, draft=6.25)
    margin = MARGIN_SHARE * 100.0
    assert np.allclose(c[:, 2], 6.25)
    assert c[:, 0].min() == pytest.approx(-50 - margin) and c[:, 1].max() == pytest.approx(5 + margin)


def test_trim_by_the_stern_and_heel_to_starboard():
    at = dict(draft=5.0, trim=2.0, heel_deg=0.0, x_ap=-40.0, x_fp=40.0)
    assert water_height(-40.0, 0.0, **at) == pytest.approx(6.0), "T_AP = T + trim/2"
    assert water_height(40.0, 0.0, **at) == pytest.approx(4.0), "T_FP = T − trim/2"
    assert water_height(0.0, 0.0, **at) == pytest.approx(5.0), "midships between the perpendiculars"
    at.update(trim=0.0, heel_deg=10.0)
    assert water_height(0.0, -3.0, **at) == pytest.approx(5.0 + 3.0 * math.tan(math.radians(10.0)))
    c = waterplane_outline(LO, HI, draft=5.0, trim=2.0, x_ap=-40.0, x_fp=40.0)
    aft = c[:, 0] < 0
    assert (c[aft, 2] > 6.0).all() and (c[~aft, 2] < 4.0).all(), "the margin reaches past the perpendiculars"
