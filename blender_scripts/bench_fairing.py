"""Curve fairing beside FITPACK (scipy.interpolate.splprep), same data, same S, same degree.

Truth: the KCS midship-region station st10 (from ../shared/hulls), fitted noise-free. Data:
200 and 2,000 points along it with Gaussian noise sigma in the section plane. Both fitters get
S = M*sigma^2 and degree 3. Reported per size: time ratio, interior knots, max distance of
the fit from the TRUE curve, inflections of the fit (batten's counter on both).

Then dense noisy data (a laser scan of a section: 10^4-10^5 points): a 2 m quarter arc
(radius 4/pi) at 10,000, 30,000 and 100,000 points with 1 mm Gaussian noise in the radius
(0.2, 0.07 and 0.02 mm apart: the noise is larger than the spacing). batten fits at the
default corner angle (45 degrees) within 5 mm, and with the noise given (S = M*sigma^2);
splprep gets the same S. Reported: best-of-3 time, corners, control points, max deviation
from the points, max distance of the fit from the TRUE arc, inflections (the arc has none).
`--dense` runs only this part.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_fairing.py
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

# FITPACK and batten's fitting are single-threaded; idle OpenBLAS worker threads spin after
# numpy calls and steal a core from both (2-core machines gave +-30 % run to run).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import batten_native as bn
import numpy as np
from scipy.interpolate import splprep

ROOT = Path(__file__).resolve().parent.parent
HULL = ROOT.parent / "shared" / "hulls" / "kcs" / "network.json"
SIGMA = 0.005
DENSE_SIGMA = 1e-3
DENSE_TOLERANCE = 5e-3


def best(fn, repeat=20):
    out, times = None, []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, min(times)


def truth_curve():
    data = json.loads(HULL.read_text())
    sec = next(c for c in data["curves"] if c["name"] == "st10")
    pts = np.asarray(sec["points"], dtype=float)
    curve, _ = bn.fair_points("truth", pts, tolerance=1e-4, model_tolerance=1e-3)
    return curve


def distance_from_truth(truth, pts):
    return max(truth.nearest(p.tolist(), 1e-9)[1] for p in pts)


def row(name, seconds, knots, dev, infl):
    print(f"  {name:<28} {seconds * 1e3:9.2f} ms {knots:6d} knots {dev * 1e3:8.2f} mm {infl:4d} infl")


DENSE_RADIUS = 2.0 / (np.pi / 2)


def noisy_arc(m, rng):
    a = np.linspace(0.0, np.pi / 2, m)
    r = DENSE_RADIUS + np.concatenate([[0.0], rng.normal(0.0, DENSE_SIGMA, m - 2), [0.0]])
    return np.column_stack([r * np.cos(a), r * np.sin(a), np.zeros(m)])


def dense_scans():
    rng = np.random.default_rng(21)
    for m in (10_000, 30_000, 100_000):
        pts = noisy_arc(m, rng)
        print(f"\n{m} points, 1 mm noise, spacing {2.0 / (m - 1) * 1e3:.3f} mm")
        for label, kwargs in (
            (f"batten tolerance {DENSE_TOLERANCE * 1e3:g} mm", {"tolerance": DENSE_TOLERANCE}),
            ("batten noise 1 mm", {"noise": DENSE_SIGMA}),
        ):
            (curve, rep), sec = best(
                lambda kwargs=kwargs, pts=pts: bn.fair_points("scan", pts, **kwargs), repeat=3
            )
            dense_fit = curve.evaluate(np.linspace(*curve.domain, 20_000))
            off = np.abs(np.linalg.norm(dense_fit[:, :2], axis=1) - DENSE_RADIUS).max()
            print(
                f"  {label:<24} {sec * 1e3:8.1f} ms  corners {len(rep['corners']):3d}  "
                f"control points {len(curve.control_points):4d}  "
                f"max dev {rep['max_deviation'] * 1e3:.2f} mm  from truth {off * 1e3:.2f} mm  "
                f"inflections {rep['inflections']}"
            )
        (tck, _u), sec = best(
            lambda pts=pts, m=m: splprep(pts.T, s=m * DENSE_SIGMA**2, k=3, quiet=2), repeat=3
        )
        print(f"  {'scipy splprep (same S)':<24} {sec * 1e3:8.1f} ms  control points {len(tck[0]) - 4:4d}")


def main():
    if "--dense" in sys.argv:
        dense_scans()
        return
    truth = truth_curve()
    t_inf = bn.fairness(truth)["inflections"]
    rng = np.random.default_rng(7)
    n_cp = len(truth.control_points)
    print(f"truth: KCS st10, {n_cp} control points, {t_inf} inflections; noise sigma {SIGMA} m")
    for m in (200, 2000):
        u = np.linspace(*truth.domain, m)
        clean = truth.evaluate(u)
        pts = clean.copy()
        pts[1:-1, 1:] += rng.normal(0.0, SIGMA, (m - 2, 2))  # station plane x = const
        s_factor = m * SIGMA**2
        print(f"\n{m} points, S = {s_factor:.4g} m^2, degree 3")

        def ours(iterations, pts=pts, s_factor=s_factor):
            return bn.fair_points(
                "b",
                pts,
                smoothing_factor=s_factor,
                corner_angle_deg=None,
                max_parameter_iterations=iterations,
            )

        def fitpack(pts=pts, s_factor=s_factor):
            return splprep(pts.T, s=s_factor, k=3, quiet=2)

        results = {}
        for label, fn in (
            ("batten (foot-point param)", lambda: ours(20)),
            ("batten (chord param only)", lambda: ours(0)),
        ):
            (curve, rep), sec = best(fn)
            dense = curve.evaluate(np.linspace(*curve.domain, 3000))
            results[label] = sec
            row(label, sec, rep["interior_knots"], distance_from_truth(truth, dense), rep["inflections"])
        (tck, _u), sec = best(fitpack)
        t, c, k = tck
        n = len(t) - k - 1
        fp = bn.Curve("fitpack", k, np.asarray(t), np.column_stack([ci[:n] for ci in c]))
        dense = fp.evaluate(np.linspace(*fp.domain, 3000))
        row(
            "scipy splprep (FITPACK)",
            sec,
            len(t) - 2 * (k + 1),
            distance_from_truth(truth, dense),
            bn.fairness(fp)["inflections"],
        )
        for label, s in results.items():
            print(f"  time ratio {label} / FITPACK: {s / sec:.1f}x")
    dense_scans()


if __name__ == "__main__":
    main()
