"""Chart axes: round ticks covering the data, labelled with the decimals their step needs."""

import numpy as np
import pytest
from batten.chart import nice_ticks, tick_labels


@pytest.mark.parametrize(
    ("lo", "hi", "ticks"),
    [
        (0.0, 8.0, [0, 2, 4, 6, 8]),
        (-50.0, 50.0, [-50, -25, 0, 25, 50]),
        (0.03, 0.97, [0, 0.25, 0.5, 0.75, 1.0]),
        (3.0, 3.0, [2.6, 2.8, 3.0, 3.2, 3.4]),
        (0.0, 0.0, [-1, -0.5, 0, 0.5, 1]),
        (1.0, 312_622.0, [0, 100_000, 200_000, 300_000, 400_000]),
    ],
)
def test_ticks_are_round_and_cover_the_range(lo, hi, ticks):
    got = nice_ticks(lo, hi, 5)
    assert np.allclose(got, ticks), got
    assert got[0] <= lo and got[-1] >= hi


def test_labels_use_the_step_s_decimals_and_no_minus_zero():
    assert tick_labels(np.array([-0.5, -1e-17, 0.5, 1.0])) == ["-0.5", "0.0", "0.5", "1.0"]
    assert tick_labels(np.array([0.0, 2.5, 5.0])) == ["0.0", "2.5", "5.0"]
    assert tick_labels(np.array([0.0, 100_000.0])) == ["0", "100000"]


def test_a_range_narrower_than_the_least_span_is_widened_about_its_middle():
    """An LCB at midships that wanders by rounding (1e-10 m) is drawn on a 0.1 m axis, not
    blown up to fill the panel."""
    got = nice_ticks(-1e-10, 2e-10, 4, min_span=0.1)
    assert got[0] <= -0.05 and got[-1] >= 0.05 and got[-1] - got[0] < 0.5, got
    assert np.allclose(nice_ticks(0.0, 8.0, 5, min_span=0.1), [0, 2, 4, 6, 8]), "wide ranges keep theirs"


def test_a_legend_goes_where_the_curves_leave_room():
    from batten.chart import PALETTE, Axes, Canvas

    canvas = Canvas(400, 300)
    axes = Axes.fit(canvas, (40, 40, 380, 280), [0, 10], [0, 10])
    axes.plot([0, 5], [10, 5], PALETTE[0], width=6.0)  # through the top left corner
    axes.legend([("KB", PALETTE[1]), ("KMt", PALETTE[2])], size=14)
    swatch = np.all(np.abs(canvas.pixels[..., :3] - PALETTE[1][:3]) < 0.05, axis=-1)
    rows, cols = np.nonzero(swatch)
    assert len(cols) and cols.min() > 200 and rows.min() > 150, "top right, clear of the curve"
