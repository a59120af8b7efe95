"""Write ``pmb_barge.json``: a box-like barge with a parallel middle body (seed 002's form
topology and its transformations: §7.2.5 and the hydrostatic transformations of §8).

Port half, x forward from the stern, z up from the keel: length 100 m, half breadth 10 m, depth
12 m, design draft 8 m. Two midship sections (role ``midship``) at x = 40 and 60 bound the
parallel middle body; each is flat bottom with 0.2 m rise of floor at the side, a circular
bilge of radius 2 m (an exact rational quadratic arc) and flat side. The flat-of-side and
flat-of-bottom curves run from the midship sections into the ends, the deck edge closes at the
stem and the stern, and a free station stands in each end.

    PYTHONPATH=build/native/release python examples/pmb_barge.py     # rewrites pmb_barge.json
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from batten_native import Curve, network_to_json

#: Half breadth, depth and design draft (m).
HB, D, T = 10.0, 12.0, 8.0


def _pieces(name, pts, role, weights=None):
    """A degree-2 curve of Bézier pieces (knots doubled between pieces)."""
    n = (len(pts) - 1) // 2
    knots = [0.0] * 3 + [float(k) for k in range(1, n) for _ in (0, 1)] + [float(n)] * 3
    return Curve(name, 2, knots, np.array(pts, float), None if weights is None else np.array(weights), role)


def barge_curves(r: float = 2.0, rise: float = 0.2) -> list:
    k = np.array([HB, rise])
    ub = -k / np.linalg.norm(k)
    us = np.array([0.0, 1.0])
    phi = 0.5 * math.acos(float(ub @ us))
    length = r / math.tan(phi)
    fob, fos, w = k + ub * length, k + us * length, math.sin(phi)

    def section(name, x):
        keel, deck = (x, 0.0, 0.0), (x, HB, D)
        b, c, s = (x, *fob), (x, *k), (x, *fos)
        mid = lambda p, q: tuple((np.array(p) + np.array(q)) / 2)  # noqa: E731
        return _pieces(
            name, [keel, mid(keel, b), b, c, s, mid(s, deck), deck], "midship", [1, 1, 1, w, 1, 1, 1]
        )

    deck_pts = [
        (0, 0),
        (8, HB),
        (15, HB),
        (27.5, HB),
        (40, HB),
        (50, HB),
        (60, HB),
        (72.5, HB),
        (85, HB),
        (92, HB),
        (100, 0),
    ]
    deck = _pieces("deck", [(x, y, D) for x, y in deck_pts], "deck")

    def station(name, x):
        a, b = deck.domain
        for _ in range(200):
            m = 0.5 * (a + b)
            a, b = (m, b) if deck.evaluate([m])[0][0] < x else (a, m)
        top = deck.evaluate([0.5 * (a + b)])[0]
        yd = float(top[1])
        return Curve(
            name,
            3,
            [0, 0, 0, 0, 0.5, 1, 1, 1, 1],
            np.array(
                [(x, 0, 0), (x, 0.7 * yd, 0.6), (x, 1.2 * yd, 0.45 * D), (x, 0.8 * yd, 0.75 * D), tuple(top)]
            ),
            None,
            "free",
        )

    keel = Curve(
        "keel",
        1,
        [0, 0, 1, 2, 3, 4, 5, 5],
        np.array([(x, 0, 0) for x in (5, 20, 40, 60, 80, 95)], float),
        None,
        "keel",
    )
    zs = fos[1]
    fos_c = _pieces(
        "fos",
        [(15, HB, D), (28, HB, zs), (40, HB, zs), (50, HB, zs), (60, HB, zs), (72, HB, zs), (85, HB, D)],
        "fos",
    )
    yb, zb = fob
    fob_c = _pieces(
        "fob",
        [(20, 0, 0), (30, yb, zb), (40, yb, zb), (50, yb, zb), (60, yb, zb), (70, yb, zb), (80, 0, 0)],
        "fob",
    )
    stern = _pieces("stern", [(5, 0, 0), (0, 0, 2), (0, 0, D)], "transom")
    stem = _pieces("stem", [(95, 0, 0), (100, 0, 2), (100, 0, D)], "stem")
    return [
        keel,
        stern,
        stem,
        deck,
        section("ms_aft", 40.0),
        section("ms_fwd", 60.0),
        fos_c,
        fob_c,
        station("st10", 10.0),
        station("st90", 90.0),
    ]


def text() -> str:
    return network_to_json("pmb_barge", barge_curves())


if __name__ == "__main__":
    out = Path(__file__).with_name("pmb_barge.json")
    out.write_text(text())
    print(f"wrote {out}")
