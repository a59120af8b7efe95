"""The add-on's pure logic imports and runs with Blender's ``bpy`` unavailable."""

import subprocess
import sys
from pathlib import Path

ADDON = Path(__file__).resolve().parents[2] / "addon"

BPY_FREE = (
    "batten",
    "batten.atomic_write",
    "batten.chart",
    "batten.hydro_table",
    "batten.form_compare",
    "batten.point_attributes",
    "batten.waterplane_outline",
    "batten.file_text",
    "batten.fit_data",
    "batten.network_markers",
    "batten.object_names",
    "batten.bridge.sections_in",
    "batten.drawing",
    "batten.drawing_dxf",
    "batten.drawing_pdf",
    "batten.drawing_png",
    "batten.drawing_svg",
    "batten.lines_plan",
    "batten.lines_plan_files",
)


def _run_without_bpy(code: str) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh Python where ``import bpy`` fails (ImportError)."""
    prelude = f"import sys\nsys.modules['bpy'] = None\nsys.path.insert(0, {str(ADDON)!r})\n"
    return subprocess.run([sys.executable, "-c", prelude + code], capture_output=True, text=True, check=False)


def test_pure_modules_import_without_bpy():
    done = _run_without_bpy("".join(f"import {m}\n" for m in BPY_FREE) + "print('ok')")
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "ok"


def test_the_blender_modules_do_need_bpy():
    """The check above can fail: a module that imports bpy does fail in that interpreter."""
    done = _run_without_bpy("import batten.api")
    assert done.returncode != 0
    assert "import of bpy halted" in done.stderr, done.stderr
