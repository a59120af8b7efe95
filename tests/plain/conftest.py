"""Plain pytest, no Blender: the add-on's bpy-free modules, imported from ``addon/``.

This folder has its own ``pytest.ini``, so ``pytest tests/plain`` stops looking for conftest
files here and never loads ``tests/conftest.py`` (which starts Blender). ``batten_native``
comes from ``PYTHONPATH`` (the freshly built module), as for the bpy tests. Run inside the
bpy suite as well (``pytest tests``), these tests touch no Blender data.
"""

from __future__ import annotations

import sys
from pathlib import Path

ADDON = Path(__file__).resolve().parents[2] / "addon"

if str(ADDON) not in sys.path:
    sys.path.insert(0, str(ADDON))
