"""Live-rebuild timing: move one control point of the frigate example and rebuild at
resolution 12, end to end (curves in, surface, mesh written), with the core's share.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_rebuild.py
    blender -b -P blender_scripts/bench_rebuild.py
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
os.environ.setdefault("BLENDER_USER_RESOURCES", tempfile.mkdtemp(prefix="batten_bench_"))

import bpy  # noqa: E402

sys.path.insert(0, str(ROOT / "addon"))
import batten  # noqa: E402
import batten.api as api  # noqa: E402
import batten_native as bn  # noqa: E402

RESOLUTION = 12
RUNS = 30


def main() -> None:
    batten.register()
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    coll = api.load_network(ROOT / "examples" / "frigate_network.json")
    api.build(coll, resolution=RESOLUTION)
    obj = next(
        o for o in coll.objects if o.data.splines[0].type == "NURBS" and len(o.data.splines[0].points) > 3
    )
    point = obj.data.splines[0].points[1]
    total, read, core = [], [], []
    for i in range(RUNS):
        co = point.co.copy()
        co.y += 0.01 * (1 if i % 2 else -1)
        point.co = co
        t0 = time.perf_counter()
        api.build(coll, resolution=RESOLUTION)
        total.append(time.perf_counter() - t0)
        t1 = time.perf_counter()
        curves = api.read_curves(coll)
        t2 = time.perf_counter()
        bn.build_surface(curves, 1e-4, RESOLUTION)
        t3 = time.perf_counter()
        read.append(t2 - t1)
        core.append(t3 - t2)
    med = lambda xs: float(np.median(xs)) * 1e3  # noqa: E731
    r = api.build(coll, resolution=RESOLUTION).report
    print(f"frigate example, resolution {RESOLUTION}: {r['faces']} patches, {r['mesh_faces']} mesh faces")
    print(
        f"  rebuild end to end (move a point, curves in, surface, mesh written): median {med(total):.1f} ms, "
        f"best {min(total) * 1e3:.1f} ms   (target < 33 ms)"
    )
    print(f"  of which reading curves {med(read):.1f} ms, core surface {med(core):.1f} ms")


if __name__ == "__main__":
    main()
