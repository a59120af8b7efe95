"""Parametric form-topology change + rebuild timing (seed 002 §7.2.5): the frigate example
(breadth +5 %, a transverse scale, and depth +1 m through the form topology), the PMB barge of
``tests/test_form.py`` (breadth +5 %, PMB length +10 m, bilge radius 2.0 -> 2.5 m) and KCS
imported from ``../shared/hulls`` at the defaults (breadth +5 %), each the core transformation
(``transform_network``: form topology found, moves distributed, curves moved, connections
checked) and the core rebuild (``build_surface`` at resolution 12, its report measured). Median
of RUNS.

For KCS also the rebuild a designer waits for: the live path (``LiveHull.rebuild`` from the
hull before the change, the topology kept, the report's quality sampling left to ``settle``,
timed apart), as Live rebuilds after every edit.

    PYTHONPATH=build/native/release:addon:tests .venv/bin/python blender_scripts/bench_form_transform.py
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

# The add-on first, as in Blender: it sets batten_native's allocator options before loading it.
import batten  # noqa: E402
import batten_native as bn  # noqa: E402

RESOLUTION = 12
RUNS = 15


def _median_ms(f) -> float:
    times = []
    for _ in range(RUNS):
        t0 = time.perf_counter()
        f()
        times.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(times)


def _case(label, curves, target, draft):
    moved, _ = bn.transform_network(curves, [target], [], draft=draft)
    t_transform = _median_ms(lambda: bn.transform_network(curves, [target], [], draft=draft))
    t_build = _median_ms(lambda: bn.build_surface(moved, 1e-4, RESOLUTION))
    total = t_transform + t_build
    print(f"{label:34s} transform {t_transform:8.2f} ms  rebuild {t_build:8.2f} ms  total {total:8.2f} ms")


def main() -> None:
    _, frigate, _ = bn.network_from_json((ROOT / "examples" / "frigate_network.json").read_text())
    form = bn.form_topology(frigate, draft=4.8)["parameters"]
    _case("frigate breadth +5 %", frigate, ("breadth", 1.05 * form["breadth"]), 4.8)
    _case("frigate depth +1 m", frigate, ("depth", form["depth"] + 1.0), 4.8)
    from test_form import _barge_curves  # noqa: PLC0415

    barge = _barge_curves()
    _case("barge breadth +5 %", barge, ("breadth", 21.0), 8.0)
    _case("barge PMB length +10 m", barge, ("pmb_length", 30.0), 8.0)
    _case("barge bilge radius 2.0 -> 2.5 m", barge, ("bilge_radius", 2.5), 8.0)
    _kcs()


def _kcs() -> None:
    path = ROOT.parent / "shared" / "hulls" / "kcs" / "network.json"
    if not path.exists():
        print(f"KCS: {path} not found, skipped")
        return
    import batten.api as api  # noqa: PLC0415

    batten.register()
    coll, _ = api.import_sections(path)
    kcs = api.read_curves(coll)
    draft = float(coll[api.DESIGN_DRAFT_PROPERTY])
    target = ("breadth", 1.05 * bn.form_topology(kcs, draft=draft)["parameters"]["breadth"])
    _case("KCS breadth +5 %", kcs, target, draft)
    moved, _ = bn.transform_network(kcs, [target], [], draft=draft)
    t_transform = _median_ms(lambda: bn.transform_network(kcs, [target], [], draft=draft))
    live, settle = [], []
    for _ in range(RUNS):
        hull = bn.LiveHull(kcs, 1e-4, RESOLUTION)
        t0 = time.perf_counter()
        hull.rebuild(moved)
        live.append(1e3 * (time.perf_counter() - t0))
        t0 = time.perf_counter()
        hull.settle()
        settle.append(1e3 * (time.perf_counter() - t0))
    t_live = statistics.median(live)
    print(
        f"{'KCS breadth +5 %, live rebuild':34s} transform {t_transform:8.2f} ms  rebuild {t_live:8.2f} ms  "
        f"total {t_transform + t_live:8.2f} ms  (report after it settles: {statistics.median(settle):.2f} ms)"
    )


if __name__ == "__main__":
    main()
