"""Live-rebuild timing: move one control point of a station and rebuild, end to end (curves in,
surface, mesh written), as a full build and as the incremental live rebuild
(``api.build(..., live=True)``) in the same run, with their ratio; on the frigate example, on
KCS imported from ``../shared/hulls`` at the defaults, and on a synthetic 308-patch network
(the exact Wigley hull drawn with 27 stations and 10 waterlines, ``examples/wigley.py``), at
resolutions 12 and 24.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_rebuild.py
    blender -b -P blender_scripts/bench_rebuild.py

The move is smaller than the model tolerance, so the station stays on the curves it crosses
and the network's connectivity is unchanged, as in a drag of a network whose crossings move
together; a move that takes a curve off its crossings is a full rebuild (reported as such).
The live figure includes ``api.settle``'s cost separately: the report's quality sampling, run
once the drag pauses.

Then the round trip of a live drag with its figures: move the control point, rebuild live, and
``api.hydrostatics`` at the design draft (exact cells, then Live cells): the figures' time is
the cells of the faces the drag reached, made again, and the integration (the other faces'
cells are kept from the model before).
"""

from __future__ import annotations

import json
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
from batten import hull_models  # noqa: E402

RUNS = 30
#: The move of the control point (m): below the default model tolerance (0.1 mm).
STEP = 4e-5


def _hull(name: str):
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    hull_models.forget()
    if name == "frigate":
        coll = api.load_network(ROOT / "examples" / "frigate_network.json")
        station = coll.objects["st4"]
    elif name == "synthetic":
        coll = api.load_network(_synthetic_network())
        station = coll.objects[SYNTHETIC_STATION]
    else:
        coll, _ = api.import_sections(ROOT.parent / "shared" / "hulls" / name / "network.json")
        station = coll.objects["st10"]
    return coll, station


#: The synthetic network: Wigley stations and waterlines at these counts give 308 patches.
SYNTHETIC_STATIONS, SYNTHETIC_WATERLINES = 27, 10
#: The station the synthetic drag moves (off midship, so its faces are like the others).
SYNTHETIC_STATION = "station +14.3"


def _synthetic_network() -> Path:
    """The synthetic network's JSON file (written once per run into a temporary folder)."""
    sys.path.insert(0, str(ROOT / "examples"))
    import wigley

    n = SYNTHETIC_STATIONS
    stations = [wigley.L * k / (n + 1) for k in range(-(n // 2), n // 2 + 1)]
    waterlines = [wigley.T * k / SYNTHETIC_WATERLINES for k in range(1, SYNTHETIC_WATERLINES + 1)]
    path = Path(tempfile.mkdtemp(prefix="batten_bench_")) / "synthetic.json"
    path.write_text(json.dumps(wigley.network(stations, waterlines, name="synthetic")))
    return path


def _drag(point, i: int) -> None:
    """Move ``point`` by ``STEP`` along y, to one side on even ``i`` and back on odd."""
    co = point.co.copy()
    co.y += STEP * (1 if i % 2 else -1)
    point.co = co


def _median_ms(xs) -> float:
    return float(np.median(xs)) * 1e3


def bench(name: str, resolution: int) -> None:
    coll, station = _hull(name)
    point = station.data.splines[0].points[len(station.data.splines[0].points) // 2]

    full, inc, settle, kinds = [], [], [], set()
    api.build(coll, resolution=resolution)
    for i in range(RUNS):
        _drag(point, i)
        t0 = time.perf_counter()
        api.build(coll, resolution=resolution)
        full.append(time.perf_counter() - t0)
    api.build(coll, resolution=resolution, live=True)
    for i in range(RUNS):
        _drag(point, i)
        t0 = time.perf_counter()
        r = api.build(coll, resolution=resolution, live=True).report
        inc.append(time.perf_counter() - t0)
        kinds.add((r["rebuild"]["kind"], r["rebuild"]["faces"], r["rebuild"]["of"]))
        t0 = time.perf_counter()
        api.settle(coll)
        settle.append(time.perf_counter() - t0)
    f, li = _median_ms(full), _median_ms(inc)
    print(
        f"{name}, resolution {resolution}: full rebuild {f:.1f} ms, live rebuild {li:.1f} ms "
        f"(best {min(inc) * 1e3:.1f} ms; {sorted(kinds)}), ratio {f / li:.1f}×; "
        f"settle {_median_ms(settle):.1f} ms"
    )


def bench_figures(name: str) -> None:
    """Drag → live rebuild → api.hydrostatics at the design draft, timed part by part."""
    coll, station = _hull(name)
    point = station.data.splines[0].points[len(station.data.splines[0].points) // 2]
    if name == "frigate":
        draft, lpp, fp = 4.0, None, None
    else:
        ref = json.loads((ROOT.parent / "shared" / "hulls" / name / "network.json").read_text())
        draft, lpp, fp = ref["T"], ref["Lpp"], ref["Lpp"]
    api.build(coll, live=True)
    api.hydrostatics(coll, draft, lpp=lpp, fp=fp)
    api.hydrostatics(coll, draft, lpp=lpp, fp=fp, live=True)
    rebuild, exact, live_cells, kept = [], [], [], set()
    for i in range(RUNS):
        _drag(point, i)
        t0 = time.perf_counter()
        api.build(coll, live=True)
        t1 = time.perf_counter()
        api.hydrostatics(coll, draft, lpp=lpp, fp=fp)
        t2 = time.perf_counter()
        rebuild.append(t1 - t0)
        exact.append(t2 - t1)
        model = hull_models._kept[coll.name].model
        kept.add((model.cells_kept, model.cells))
    for i in range(RUNS):
        _drag(point, i)
        api.build(coll, live=True)
        t1 = time.perf_counter()
        api.hydrostatics(coll, draft, lpp=lpp, fp=fp, live=True)
        live_cells.append(time.perf_counter() - t1)
    print(
        f"{name}, drag then hydrostatics at {draft} m: live rebuild {_median_ms(rebuild):.1f} ms; "
        f"then hydrostatics {_median_ms(exact):.2f} ms (best {min(exact) * 1e3:.2f} ms; cells kept "
        f"of all {sorted(kept)}), with Live cells {_median_ms(live_cells):.2f} ms "
        f"(best {min(live_cells) * 1e3:.2f} ms)"
    )


def main() -> None:
    batten.register()
    for name in ("frigate", "kcs", "synthetic"):
        for resolution in (12, 24):
            bench(name, resolution)
    for name in ("frigate", "kcs"):
        bench_figures(name)


if __name__ == "__main__":
    main()
