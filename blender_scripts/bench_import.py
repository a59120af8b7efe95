"""Time the new user's two steps on the real ships: ``api.import_sections`` then ``api.build``
with every setting at its default (real-ships issue: import + build of KCS under 1 s).

    make native PROFILE=release
    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/bench_import.py

Prints, per ship, the best of ``--repeat`` runs of each step and of both (a fresh scene each
time), and the machine's load average, since the machine may be shared.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main() -> None:
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
    ap = argparse.ArgumentParser(prog="bench_import.py")
    ap.add_argument("--ships", type=Path, default=ROOT.parent / "shared" / "hulls")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT / "addon"))
    import batten
    import bpy

    batten.register()
    from batten import api

    for path in sorted(args.ships.glob("*/network.json")):
        imports, builds = [], []
        for _ in range(args.repeat):
            bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
            t0 = time.perf_counter()
            coll, _ = api.import_sections(path, collection=path.parent.name)
            t1 = time.perf_counter()
            api.build(coll)
            t2 = time.perf_counter()
            imports.append(t1 - t0)
            builds.append(t2 - t1)
        both = min(a + b for a, b in zip(imports, builds, strict=True))
        print(
            f"{path.parent.name}: import {min(imports) * 1e3:.0f} ms, build {min(builds) * 1e3:.0f} ms, "
            f"import + build {both * 1e3:.0f} ms (best of {args.repeat}; load {os.getloadavg()[0]:.1f})"
        )


if __name__ == "__main__":
    main()
