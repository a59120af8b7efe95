"""Write ``sections/multi_chine.json``: a double-chine hull given only as sections, the way
offsets arrive, in the neutral section format of ``shared/hulls`` (point lists with their kind
and plane). batten finds the two knuckles in every station, joins them into chines, and builds.

Port half, x forward from the transom (x = 0) to the bow transom (x = L), z up from the keel.
Every station is a polygon keel → lower chine → upper chine → sheer, sampled densely along each
straight panel (so the knuckles are corners of the data, found by the fit), and every vertex
moves linearly in x. The chines, keel and sheer are therefore straight lines, each panel
between two stations is a bilinear (ruled) surface, the section area A(x) between the hull and
the centreplane is a quadratic in x, and the volume of the half hull up to the sheer is
∫A(x)dx, which Simpson's rule gives exactly: ``exact_volume()``.

    python examples/multi_chine.py            # rewrites examples/sections/multi_chine.json
"""

from __future__ import annotations

import json
from pathlib import Path

L = 16.0  # length between the two transoms (m)
STATIONS = 9  # stations at x = 0, L/8, …, L (the end ones are the transoms)
SAMPLES = 12  # points per panel of a station (ends included once)

# Section vertices (y, z) at the stern (x = 0) and the bow (x = L): keel, lower chine, upper
# chine, sheer. Panels turn by more than 45° at each chine (the fit's default corner angle):
# the bottom rises at 12° deadrise, the side at 70° and the topside leans in at 125°.
STERN = [(0.0, 0.0), (2.2, 0.4676), (2.5, 1.2919), (2.1, 1.8631)]
BOW = [(0.0, 0.6), (1.1, 0.8338), (1.25, 1.2460), (1.05, 1.5316)]


def vertices(x: float) -> list[tuple[float, float]]:
    """The section's four vertices at ``x``: linear between the stern and the bow."""
    s = x / L
    return [(a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])) for a, b in zip(STERN, BOW, strict=True)]


def station_points(x: float) -> list[list[float]]:
    """The station at ``x``, keel to sheer, ``SAMPLES`` points per panel."""
    v = vertices(x)
    pts = []
    for (y0, z0), (y1, z1) in zip(v, v[1:], strict=False):
        for i in range(SAMPLES - 1):
            t = i / (SAMPLES - 1)
            pts.append([x, y0 + t * (y1 - y0), z0 + t * (z1 - z0)])
    pts.append([x, *v[-1]])
    return [[round(c, 12) for c in p] for p in pts]


def section_area(x: float) -> float:
    """Area between the section polygon, the centreplane y = 0 and the sheer's height: the
    polygon keel → chines → sheer → (0, z_sheer) closed along the centreplane (shoelace)."""
    v = vertices(x)
    poly = [*v, (0.0, v[-1][1])]
    return 0.5 * abs(sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(poly, poly[1:] + poly[:1], strict=True)))


def exact_volume() -> float:
    """∫₀ᴸ A(x) dx for the quadratic A: Simpson's rule on one interval is exact."""
    return L / 6.0 * (section_area(0.0) + 4.0 * section_area(L / 2) + section_area(L))


def network() -> dict:
    xs = [L * i / (STATIONS - 1) for i in range(STATIONS)]
    curves = []
    for i, x in enumerate(xs):
        kind = "transom" if i in (0, STATIONS - 1) else "station"
        curves.append(
            {"name": f"st{i}", "kind": kind, "plane": {"axis": "x", "value": x}, "points": station_points(x)}
        )
    line = [[x, *vertices(x)[0]] for x in xs]
    sheer = [[x, *vertices(x)[-1]] for x in xs]
    curves.append({"name": "keel", "kind": "profile", "plane": {"axis": "y", "value": 0.0}, "points": line})
    curves.append({"name": "sheer", "kind": "deck", "points": sheer})
    return {
        "name": "multi_chine",
        "units": "m",
        "axes": "x fwd from the stern transom, y port, z up from the keel",
        "exact_volume": exact_volume(),
        "notes": "Double-chine hull from sections only; chines are generated from the knuckles.",
        "curves": curves,
    }


def text() -> str:
    """The section file's text."""
    return json.dumps(network(), indent=1) + "\n"


def main() -> None:
    out = Path(__file__).with_name("sections") / "multi_chine.json"
    out.parent.mkdir(exist_ok=True)
    out.write_text(text())
    print(f"wrote {out}: exact half-hull volume {exact_volume():.9f} m³")


if __name__ == "__main__":
    main()
