"""Write ``hard_chine.json``: a hard-chine motor-boat hull drawn from sections with a corner at
the chine, the chine line connecting those corners (the H-rep paper's Neuwerk-style example).

Port half, x forward from the transom, z up from the keel. Keel, chine and sheer are exact
quadratic curves in x (quadratic Béziers whose x runs linearly), so every section's chine and
sheer points lie exactly on them. Each section is a polyline keel → chine → sheer: straight
bottom (deadrise) and straight topside, the corner at the chine. The chine has role knuckle.

    python examples/hard_chine.py            # rewrites examples/hard_chine.json
"""

from __future__ import annotations

import json
from pathlib import Path

L = 12.0  # length, transom at x = 0, stem at x = L
STATIONS = [2.0, 4.0, 6.0, 8.0, 10.0]

# Quadratic Béziers (x, y, z) with x = L·s: keel rises at the bow, chine and sheer close in.
KEEL = [(0.0, 0.0, 0.0), (L / 2, 0.0, 0.0), (L, 0.0, 0.35)]
CHINE = [(0.0, 1.9, 0.30), (L / 2, 2.2, 0.30), (L, 0.0, 0.75)]
SHEER = [(0.0, 2.0, 1.40), (L / 2, 2.45, 1.45), (L, 0.0, 1.90)]


def bezier(ctrl, x: float) -> tuple[float, float, float]:
    s = x / L
    b = ((1 - s) ** 2, 2 * s * (1 - s), s * s)
    return tuple(sum(w * p[i] for w, p in zip(b, ctrl, strict=True)) for i in range(3))


def curve(name, role, degree, knots, points):
    return {
        "name": name,
        "role": role,
        "degree": degree,
        "knots": knots,
        "points": [[round(c, 12) for c in p] for p in points],
        "weights": None,
    }


def polyline(name, role, points):
    n = len(points)
    return curve(name, role, 1, [0, *range(n), n - 1], points)


def network() -> dict:
    curves = [
        curve("keel", "keel", 2, [0, 0, 0, 1, 1, 1], KEEL),
        curve("chine", "knuckle", 2, [0, 0, 0, 1, 1, 1], CHINE),
        curve("sheer", "deck", 2, [0, 0, 0, 1, 1, 1], SHEER),
        polyline("transom", "transom", [bezier(KEEL, 0.0), bezier(CHINE, 0.0), bezier(SHEER, 0.0)]),
        polyline("stem", "stem", [bezier(KEEL, L), bezier(CHINE, L), bezier(SHEER, L)]),
    ]
    for x in STATIONS:
        curves.append(
            polyline(f"station {x:g}", "free", [bezier(KEEL, x), bezier(CHINE, x), bezier(SHEER, x)])
        )
    return {"format": "batten-network", "version": 1, "name": "hard_chine", "curves": curves}


def text() -> str:
    return json.dumps(network(), indent=2) + "\n"


if __name__ == "__main__":
    out = Path(__file__).with_name("hard_chine.json")
    out.write_text(text())
    print(f"wrote {out}")
