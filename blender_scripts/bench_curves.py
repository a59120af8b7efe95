"""Curve benchmarks, measured beside their peers in one run; prints ratios.

1. Evaluate a cubic B-spline with 50 control points at 1,000,000 parameters through
   ``batten_native`` and through ``scipy.interpolate.BSpline`` (same knots, same points).
2. Read 200 Blender curve objects of 100 NURBS points each into batten curves
   (``batten.api.read_curves``: foreach_get + validation in the core).

    make bench
    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_curves.py
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def best_of(fn, repeat=7):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times), float(np.median(times))


def bench_eval():
    import batten_native as bn
    from scipy.interpolate import BSpline

    n, k = 50, 3
    rng = np.random.default_rng(0)
    pts = np.column_stack([np.linspace(0, 100, n), rng.normal(0, 5, n), rng.normal(0, 2, n)])
    knots = np.concatenate([[0.0] * 4, np.linspace(0, 1, n - k + 1)[1:-1], [1.0] * 4])
    curve = bn.Curve("bench", k, knots, pts)
    spline = BSpline(knots, pts, k)
    t = rng.random(1_000_000)
    ours = curve.evaluate(t)
    theirs = spline(t)
    err = float(np.abs(ours - theirs).max())
    b_min, b_med = best_of(lambda: curve.evaluate(t))
    s_min, s_med = best_of(lambda: spline(t))
    print("evaluate cubic B-spline, 50 control points, 1,000,000 random parameters")
    print(f"  batten_native : best {b_min * 1e3:8.2f} ms  median {b_med * 1e3:8.2f} ms")
    print(f"  scipy BSpline : best {s_min * 1e3:8.2f} ms  median {s_med * 1e3:8.2f} ms")
    print(f"  speed ratio (scipy / batten, best): {s_min / b_min:.2f}x   max |difference| {err:.2e}")
    return s_min / b_min, err


def bench_read():
    user = tempfile.mkdtemp(prefix="batten_bench_")
    os.environ.setdefault("BLENDER_USER_RESOURCES", user)
    import bpy

    sys.path.insert(0, str(ROOT / "addon"))
    import batten
    import batten.api as api

    batten.register()
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    coll = bpy.data.collections.new("bench")
    bpy.context.scene.collection.children.link(coll)
    rng = np.random.default_rng(1)
    for i in range(200):
        data = bpy.data.curves.new(f"c{i}", "CURVE")
        data.dimensions = "3D"
        s = data.splines.new("NURBS")
        s.points.add(99)
        co = np.column_stack([np.linspace(0, 100, 100), rng.normal(0, 3, (100, 2)), np.ones(100)])
        s.points.foreach_set("co", co.astype(np.float32).ravel())
        s.order_u = 4
        s.use_endpoint_u = True
        coll.objects.link(bpy.data.objects.new(f"c{i}", data))
    curves = api.read_curves(coll)
    assert len(curves) == 200
    r_min, r_med = best_of(lambda: api.read_curves(coll), repeat=15)
    print("read 200 Blender NURBS curves x 100 points into batten curves (foreach_get + core validation)")
    print(f"  best {r_min * 1e3:.2f} ms  median {r_med * 1e3:.2f} ms  (target < 5 ms)")
    return r_min


if __name__ == "__main__":
    bench_eval()
    bench_read()
