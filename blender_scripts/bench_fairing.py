"""Curve fairing beside FITPACK (scipy.interpolate.splprep), same data, same S, same degree.

Truth: the KCS midship-region station st10 (from ../shared/hulls), fitted noise-free. Data:
200 and 2,000 points along it with Gaussian noise sigma in the section plane. Both fitters get
S = M*sigma^2 and degree 3. Reported per size: time ratio, interior knots, max distance of
the fit from the TRUE curve, inflections of the fit (batten's counter on both).

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_fairing.py
"""

from __future__ import annotations

import json
import os
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


def main():
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


if __name__ == "__main__":
    main()
