"""Write ``wigley.json``: the Wigley hull as an exact batten curve network.

The Wigley hull, port half, x forward from midship, z up from the baseline:

    y(x, z) = B/2 · (1 − (2x/L)²) · (1 − ((T − z)/T)²)      for 0 ≤ z ≤ T

and wall-sided above the design waterline up to the deck at z = T + F. Every station and every
waterline of it is a parabola, so each curve is an exact rational-free quadratic B-spline. Exact
hydrostatics (both halves, to the design waterline): volume ∇ = (4/9)·L·B·T, waterplane area
A_wp = (2/3)·L·B, block coefficient C_B = 4/9.

It writes two drawings of the same hull: ``wigley.json`` (7 stations, 3 waterlines: the light
example) and ``wigley_lines.json`` (15 stations at L/16, 6 waterlines at T/6, as a lines plan
would draw it). Built at the defaults, the light drawing's surface is within 0.02 % of the
analytic volume at T and T/2, the lines plan's within 0.001 %.

    python examples/wigley.py            # rewrites examples/wigley.json and wigley_lines.json
"""

from __future__ import annotations

import json
from pathlib import Path

L, B, T, F = 100.0, 10.0, 6.25, 2.5
STATIONS = [L * k / 8.0 for k in range(-3, 4)]  # 7 stations
WATERLINES = [T * k / 3.0 for k in (1, 2)] + [T]  # 2 waterlines + the design waterline
DECK = T + F


def half_breadth(x: float) -> float:
    return 0.5 * B * (1.0 - (2.0 * x / L) ** 2)


def depth_factor(z: float) -> float:
    s = (T - z) / T
    return 1.0 - s * s


def curve(name, role, degree, knots, points):
    return {
        "name": name,
        "role": role,
        "degree": degree,
        "knots": knots,
        "points": [[float(c) for c in p] for p in points],
        "weights": None,
    }


def station(x: float):
    """Keel (y=0, z=0) → waterline (y=c, z=T) parabola with vertical tangent at T, then the
    straight wall side to the deck: a quadratic B-spline with a double knot at the waterline."""
    c = half_breadth(x)
    pts = [(x, 0.0, 0.0), (x, c, T / 2), (x, c, T), (x, c, T + F / 2), (x, c, DECK)]
    return curve(f"station {x:+.1f}", "free", 2, [0, 0, 0, 1, 1, 2, 2, 2], pts)


def waterline(z: float, name: str, role: str = "free"):
    """y = c(z)·(1 − (2x/L)²): one quadratic Bézier from stern to stem."""
    g = depth_factor(z) if z < T else 1.0
    pts = [(-L / 2, 0.0, z), (0.0, B * g, z), (L / 2, 0.0, z)]
    return curve(name, role, 2, [0, 0, 0, 1, 1, 1], pts)


#: The lines-plan drawing: 15 stations at L/16 and 6 waterlines at T/6.
LINES_STATIONS = [L * k / 16.0 for k in range(-7, 8)]
LINES_WATERLINES = [T * k / 6.0 for k in range(1, 7)]


def network(stations=None, waterlines=None, name: str = "wigley") -> dict:
    stations = STATIONS if stations is None else stations
    waterlines = WATERLINES if waterlines is None else waterlines
    curves = [station(x) for x in stations]
    curves += [waterline(z, f"waterline {z:.3f}") for z in waterlines[:-1]]
    curves.append(waterline(T, "design waterline"))
    curves.append(waterline(DECK, "deck edge", "deck"))
    curves.append(curve("keel", "keel", 1, [0, 0, 1, 1], [(-L / 2, 0.0, 0.0), (L / 2, 0.0, 0.0)]))
    curves.append(curve("stem", "stem", 1, [0, 0, 1, 1], [(L / 2, 0.0, 0.0), (L / 2, 0.0, DECK)]))
    curves.append(curve("stern", "transom", 1, [0, 0, 1, 1], [(-L / 2, 0.0, 0.0), (-L / 2, 0.0, DECK)]))
    return {
        "format": "batten-network",
        "version": 1,
        "name": name,
        "curves": curves,
    }


def text() -> str:
    return json.dumps(network(), indent=2) + "\n"


def lines_text() -> str:
    return json.dumps(network(LINES_STATIONS, LINES_WATERLINES, "wigley_lines"), indent=2) + "\n"


if __name__ == "__main__":
    for file, body in (("wigley.json", text()), ("wigley_lines.json", lines_text())):
        out = Path(__file__).with_name(file)
        out.write_text(body)
        print(f"wrote {out}")
