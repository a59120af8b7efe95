"""Benchmark: hydrostatics on the patch surface (batten.api.hydrostatics), for the example hulls
and the real ships at their design drafts: the build, the cells made on first use, and one full
set of figures (exact cells and the Live ones), best of N.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_hydro_surface.py

A ship whose surface has a hole under water at its design draft is timed at the deepest draft
below the hole (the figures' work is the same), and says so.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import batten.api as api
from batten_native import HydrostaticsError, build_hull_model

ROOT = Path(__file__).resolve().parent.parent
HULLS = ROOT.parent / "shared" / "hulls"
REPEAT = 7


def best(f) -> float:
    times = []
    for _ in range(REPEAT):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def bench(name: str, coll, draft: float, lpp=None, fp=None) -> None:
    curves = api.read_curves(coll)
    t = time.perf_counter()
    planes = api.tangent_planes(coll)
    _arrays, _report, model = build_hull_model(curves, api.DEFAULT_TOLERANCE, None, name, planes)
    built = time.perf_counter() - t
    t = time.perf_counter()
    cells = model.cells
    made = time.perf_counter() - t
    note = ""
    at = draft
    while True:
        try:
            model.hydrostatics(at, lpp=lpp, fp=fp)
            break
        except HydrostaticsError as e:
            if "hole" not in str(e) or at < 0.2 * draft:
                print(f"{name:>14}: no figures at any draft down to {at:.2f} m: {e}")
                return
            note = f" (a hole under water at {draft} m: timed at {at:.2f} m; {e})"
            at -= 0.05 * draft
    exact = best(lambda: model.hydrostatics(at, lpp=lpp, fp=fp))
    model.hydrostatics(at, lpp=lpp, fp=fp, live=True)
    live = best(lambda: model.hydrostatics(at, lpp=lpp, fp=fp, live=True))
    print(
        f"{name:>14}: build {built * 1e3:6.1f} ms, {cells:5d} cells made in {made * 1e3:6.1f} ms, "
        f"hydrostatics {exact * 1e3:5.2f} ms (Live cells {live * 1e3:5.2f} ms){note}"
    )


def main() -> int:
    for file, draft in (("frigate_network.json", 4.0), ("wigley.json", 6.25), ("wigley_lines.json", 6.25)):
        bench(file.removesuffix(".json"), api.load_example(file), draft)
    for ship in ("kcs", "kvlcc2"):
        path = HULLS / ship / "network.json"
        if not path.exists():
            print(f"{ship}: {path} not found, skipped")
            continue
        ref = json.loads(path.read_text())
        coll, _ = api.import_sections(path)
        bench(ship, coll, ref["T"], lpp=ref["Lpp"], fp=ref["Lpp"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
