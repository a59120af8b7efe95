"""A chart's lines: short segments covered in batches give the very pixels the one-by-one
cover gives (the lines plan's polylines have thousands of them)."""

import numpy as np
import pytest
from batten import chart


@pytest.mark.parametrize("half", [0.5, 1.2, 2.5])
def test_batched_cover_is_the_one_by_one_cover(half):
    rng = np.random.default_rng(7)
    points = np.cumsum(rng.normal(0.0, 4.0, (800, 2)), axis=0) + 300.0
    ends = np.stack([points[:-1], points[1:]], axis=1)
    lo = np.floor(points.min(axis=0) - half - 1).astype(int)
    hi = np.ceil(points.max(axis=0) + half + 1).astype(int)
    one = np.zeros((hi[1] - lo[1], hi[0] - lo[0]), np.float32)
    for p, q in ends:
        chart._cover_segment(one, lo, p, q, half)
    short = np.abs(ends[:, 1] - ends[:, 0]).max(axis=1) <= chart.BATCH_SEGMENT_PX
    assert 0 < (~short).sum() < short.sum()  # both paths taken below
    batched = np.zeros_like(one)
    for p, q in ends[~short]:
        chart._cover_segment(batched, lo, p, q, half)
    chart._cover_segments(batched, lo, ends[short], half)
    assert one.max() > 0.99  # ink (a line of width 1 covers some pixel centre nearly whole)
    np.testing.assert_array_equal(batched, one)
