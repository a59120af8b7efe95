"""The Wigley hull's plane sections, computed from its formula, for the lines plan tests.

y(x, z) = B/2 · (1 − (2x/L)²) · (1 − ((T − z)/T)²) for 0 ≤ z ≤ T, wall-sided above up to the
deck at z = D (examples/wigley.py); x from −L/2 (AP) to L/2 (FP), port half.
"""

from __future__ import annotations

import numpy as np
from batten.sections import Section

L, B, T, D = 100.0, 10.0, 6.25, 8.75
#: Points per section polyline.
SAMPLES = 201


def half_breadth(x):
    return 0.5 * B * (1.0 - (2.0 * np.asarray(x) / L) ** 2)


def depth_factor(z):
    z = np.asarray(z, dtype=float)
    return np.where(z < T, 1.0 - ((T - z) / T) ** 2, 1.0)


def station(x: float) -> np.ndarray:
    z = np.linspace(0.0, D, SAMPLES)
    return np.column_stack([np.full_like(z, x), half_breadth(x) * depth_factor(z), z])


def waterline(z: float) -> np.ndarray:
    x = np.linspace(-L / 2, L / 2, SAMPLES)
    return np.column_stack([x, half_breadth(x) * depth_factor(z), np.full_like(x, z)])


def buttock(y: float) -> np.ndarray:
    """The buttock at ``y``: up the wall side at its aft end, round under the hull, up again."""
    x_end = 0.5 * L * np.sqrt(1.0 - y / (0.5 * B))
    x = np.linspace(-x_end, x_end, SAMPLES)
    ratio = np.clip(y / half_breadth(x), 0.0, 1.0)
    z = T * (1.0 - np.sqrt(1.0 - ratio))
    return np.vstack([[-x_end, y, D], np.column_stack([x, np.full_like(x, y), z]), [x_end, y, D]])


def diagonal(z0: float, angle_deg: float) -> np.ndarray:
    """The diagonal plane through (y = 0, z = z0), going down outwards at ``angle_deg``."""
    d = np.array([np.cos(np.radians(angle_deg)), -np.sin(np.radians(angle_deg))])
    x = np.linspace(-L / 2, L / 2, SAMPLES)
    lo, hi = np.zeros_like(x), np.full_like(x, z0 / -d[1])
    for _ in range(60):  # bisection of s·dy − y(x, z0 + s·dz) on [0, s at the baseline]
        s = 0.5 * (lo + hi)
        inside = s * d[0] < half_breadth(x) * depth_factor(z0 + s * d[1])
        lo, hi = np.where(inside, s, lo), np.where(inside, hi, s)
    s = 0.5 * (lo + hi)
    return np.column_stack([x, s * d[0], z0 + s * d[1]])


def sections(
    stations=21, waterlines=(1.25, 2.5, 3.75, 5.0, 6.25, 7.5), buttocks=(1.0, 2.0, 3.0, 4.0), diagonals=()
):
    """The sections dict of ``api.sections``: ``stations`` evenly from AP to FP."""
    xs = np.linspace(-L / 2, L / 2, stations)
    return {
        "stations": [Section("stations", float(x), f"st {i}", [station(x)], []) for i, x in enumerate(xs)],
        "waterlines": [Section("waterlines", z, f"WL {z:g}", [waterline(z)], []) for z in waterlines],
        "buttocks": [Section("buttocks", y, f"BL {y:g}", [buttock(y)], []) for y in buttocks],
        "diagonals": [
            Section("diagonals", z, f"D{i + 1}", [diagonal(z, a)], []) for i, (z, a) in enumerate(diagonals)
        ],
        "knuckles": [],
    }


def outline() -> list[np.ndarray]:
    """Keel, stem, stern and deck edge."""
    x = np.linspace(-L / 2, L / 2, SAMPLES)
    z = np.linspace(0.0, D, 3)
    return [
        np.column_stack([x, np.zeros_like(x), np.zeros_like(x)]),
        np.column_stack([np.full_like(z, L / 2), np.zeros_like(z), z]),
        np.column_stack([np.full_like(z, -L / 2), np.zeros_like(z), z]),
        np.column_stack([x, half_breadth(x), np.full_like(x, D)]),
    ]


def figures() -> dict:
    """The Wigley hull's exact hydrostatics at T (the keys the title block shows)."""
    volume = 4.0 / 9.0 * L * B * T
    return {
        "volume": volume,
        "displacement": 1.025 * volume,
        "waterplane_area": 2.0 / 3.0 * L * B,
        "cb": 4.0 / 9.0,
        "cp": 2.0 / 3.0,
        "cm": 2.0 / 3.0,
        "cwp": 2.0 / 3.0,
        "lcb": 0.0,
        "lcf": 0.0,
        "vcb": 0.625 * T,
        "kmt": 6.0,
    }
