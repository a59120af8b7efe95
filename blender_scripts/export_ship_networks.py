"""Write the real ships' networks as the section import makes them, for the core's benchmark
(rust/batten-core/benches/hydro.rs): ``../shared/hulls/<ship>/network.json`` through
``api.import_sections`` and ``api.export_network`` into ``build/ship_networks/<ship>.json``
(build outputs, never committed: half a megabyte each).

    PYTHONPATH=build/native/release:addon .venv/bin/python blender_scripts/export_ship_networks.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import batten.api as api

ROOT = Path(__file__).resolve().parent.parent
HULLS = ROOT.parent / "shared" / "hulls"
OUT = ROOT / "build" / "ship_networks"


def main() -> int:
    OUT.mkdir(parents=True, exist_ok=True)
    for ship in ("kcs", "kvlcc2"):
        path = HULLS / ship / "network.json"
        if not path.exists():
            print(f"{ship}: {path} not found, skipped")
            continue
        coll, _ = api.import_sections(path)
        print(api.export_network(coll, OUT / f"{ship}.json"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
