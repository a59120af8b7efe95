"""Measure the sections round trip (``api.export_sections`` → ``api.import_sections`` →
``api.build``) on the Wigley lines example, the frigate example and the KCS: the warnings of the
round-tripped network (dangling ends, unused edges, near misses, holes, folds), its faces, and
the change of the volume at the design draft.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/measure_round_trip.py \
        [--stations 40 --waterlines 12] [--hull kcs|frigate|wigley]
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: The hulls measured: how each is made, and its draft (None: the collection's design draft).
HULLS = {
    "wigley": ("example", "wigley_lines.json", 6.25),
    "frigate": ("example", "frigate_network.json", 4.0),
    "kcs": ("sections", ROOT.parent / "shared" / "hulls" / "kcs" / "network.json", None),
}


def counts(report: dict) -> dict:
    """The warnings of a build report counted by kind, with its faces, holes and folds."""
    kinds: dict[str, int] = {}
    for w in report["warnings"]:
        kinds[w["kind"]] = kinds.get(w["kind"], 0) + 1
    return {
        "faces": report["faces"],
        "holes": report["holes"],
        "folds": report["folds"],
        "max_normal_angle_deg": round(report["max_normal_angle_deg"], 3),
        "warnings": kinds,
    }


def measure(api, hull: str, stations: int, waterlines: int) -> dict:
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    how, what, draft = HULLS[hull]
    coll = api.load_example(what) if how == "example" else api.import_sections(what)[0]
    before = api.build(coll).report
    draft = draft if draft is not None else api.design_draft(coll)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "sections.json"
        api.export_sections(coll, path, stations=stations, waterlines=waterlines)
        again, _ = api.import_sections(path, collection=f"{hull} round trip")
    after = api.build(again).report
    v0 = api.hydrostatics(coll, draft)["volume"]
    try:
        v1 = api.hydrostatics(again, draft)["volume"]
        change = 100 * (v1 / v0 - 1)
    except api.BattenError as e:
        change = str(e)
    located = [
        (w["kind"], [round(c, 2) for c in w["location"]] if w["location"] else None, w["curves"])
        for w in after["warnings"]
        if w["kind"] in ("hole", "dangling_end", "near_miss", "fold")
    ]
    return {
        "hull": hull,
        "stations": stations,
        "waterlines": waterlines,
        "before": counts(before),
        "after": counts(after),
        "volume_change_pct": change,
        "first_findings": located[:12],
    }


def main() -> None:
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser(prog="measure_round_trip.py")
    ap.add_argument("--hull", choices=sorted(HULLS), action="append")
    ap.add_argument("--stations", type=int, action="append")
    ap.add_argument("--waterlines", type=int, default=12)
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT / "addon"))
    import batten

    batten.register()
    from batten import api

    for hull in args.hull or sorted(HULLS):
        for stations in args.stations or [40]:
            print(json.dumps(measure(api, hull, stations, args.waterlines)), flush=True)


if __name__ == "__main__":
    main()
