"""Measure the CAD export of the real ships as a new user gets them: import
``shared/hulls/<ship>/network.json`` and build with every setting at its default, export STEP
(or IGES) at the default 0.1 mm, and read the file back with OpenCASCADE (OCP, dev venv only;
``tests/cad_readback.py``): the faces read against the faces expected (one per 4-sided patch, N
per N-sided one), the largest distance of batten's default build's mesh vertices from the read
faces, the faces sewn at 0.1 mm with their free edges (and those off the centreplane and the
top edge, which would be gaps), and OCCT's volume of the sewn half hull below a draft (closed
with planar lids) against ``api.hydrostatics`` there.

The draft is the design draft, except KVLCC2's 18.5 m: at its design draft (20.8 m) the transom
is wet and its free edges lie in two planes (x = -5.5 m and -4.0 m), which the planar lids of
the read-back cannot close.

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/measure_cad_export.py \
        [--ship kcs|kvlcc2] [--format step|iges]
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
HULLS = ROOT.parent / "shared" / "hulls"
sys.path.insert(0, str(ROOT / "tests"))

#: The draft at which each ship's volume is compared (None: its design draft); see above.
VOLUME_DRAFT = {"kcs": None, "kvlcc2": 18.5}
#: The export tolerance (the default) and the tolerance the lids are sewn at (KCS's imported
#: profile curve lies up to 0.11 mm off the centreplane, at nodes with curves whose offsets
#: end up to 0.2 mm off it).
TOL, LID_TOL = 1e-4, 1e-3


def measure(ship: str, fmt: str, folder: Path) -> dict:
    import batten.api as api  # noqa: PLC0415
    import cad_readback as rb  # noqa: PLC0415

    coll, _ = api.import_sections(HULLS / ship / "network.json")
    build = api.build(coll)
    expected = sum((1 if int(n) == 4 else int(n)) * k for n, k in build.report["faces_by_sides"].items())
    path = folder / f"{ship}.{'stp' if fmt == 'step' else 'igs'}"
    start = time.perf_counter()
    getattr(api, f"export_{fmt}")(coll, path)
    took = time.perf_counter() - start
    faces = rb.faces(rb.read_shape(path))
    obj = build.object
    co = np.empty(3 * len(obj.data.vertices))
    obj.data.vertices.foreach_get("co", co)
    points = co.reshape(-1, 3)
    deviation = rb.Surfaces.of_faces(faces).distances(points)
    sewn, free = rb.sew(faces, TOL)
    top = points[:, 2].max()
    gaps = 0
    for e in rb.free_edges(sewn, TOL):
        q = rb.edge_points(e, 5)
        on_centreplane = np.abs(q[:, 1]).max() <= LID_TOL
        # The top edge (KVLCC2's deck edge falls by about 1 m towards the ends).
        on_top = q[:, 2].min() >= top - 1.5
        gaps += not (on_centreplane or on_top)
    draft = VOLUME_DRAFT[ship] or api.design_draft(coll)
    batten = api.hydrostatics(coll, draft)["volume"]
    occt = rb.volume_below(sewn, draft, 1e3, LID_TOL)
    return {
        "ship": ship,
        "format": fmt,
        "patches": build.report["faces"],
        "faces_expected": expected,
        "faces_read": len(faces),
        "bytes": path.stat().st_size,
        "export_s": round(took, 1),
        "points": len(points),
        "max_deviation_mm": round(1e3 * float(deviation.max()), 4),
        "free_edges": free,
        "free_edges_off_the_rim": gaps,
        "draft": draft,
        "volume_occt": round(occt, 3),
        "volume_batten": round(batten, 3),
        "volume_relative": float(f"{occt / batten - 1:.2e}"),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ship", choices=sorted(VOLUME_DRAFT), action="append")
    parser.add_argument("--format", choices=["step", "iges"], default="step")
    args = parser.parse_args()
    import batten  # noqa: PLC0415

    batten.register()
    with tempfile.TemporaryDirectory() as folder:
        for ship in args.ship or sorted(VOLUME_DRAFT):
            print(json.dumps(measure(ship, args.format, Path(folder))))


if __name__ == "__main__":
    main()
