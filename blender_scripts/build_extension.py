"""Build the installable batten extension zip with Blender's own extension tool.

Stages ``addon/batten`` with the built ``batten_native`` wheel in ``wheels/``, points the
manifest's ``wheels`` list at it, then runs ``blender_ext.py build`` and ``validate`` (the
``bl_pkg`` command-line tool shipped inside the bpy package; no Blender binary needed).

    python blender_scripts/build_extension.py --wheel-dir build/wheels/release --out build/extension/release
"""

from __future__ import annotations

import argparse
import glob
import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: Packages the add-on needs from PyPI, bundled as wheels at the versions pinned in
#: requirements-dev.txt (downloaded by pip at build time, never committed): rhino3dm writes .3dm.
BUNDLED = ("rhino3dm",)

#: The platform tags of Blender 5.0's Python (CPython 3.11 on linux-x64) a bundled wheel may have.
PLATFORMS = ("manylinux_2_28_x86_64", "manylinux_2_17_x86_64", "manylinux2014_x86_64")


def pinned(name: str) -> str:
    """The ``name==version`` line of requirements-dev.txt."""
    for line in (ROOT / "requirements-dev.txt").read_text().splitlines():
        if line.split("==")[0].strip() == name:
            return line.strip()
    sys.exit(f"build_extension: {name} is not pinned in requirements-dev.txt")


def download_wheels(into: Path) -> list[Path]:
    """The bundled packages' wheels for Blender's Python, downloaded by pip into ``into``."""
    platforms = [arg for p in PLATFORMS for arg in ("--platform", p)]
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "download",
            "--quiet",
            "--only-binary=:all:",
            "--no-deps",
            "--python-version",
            "3.11",
            "--implementation",
            "cp",
            *platforms,
            "-d",
            str(into),
            *(pinned(n) for n in BUNDLED),
        ],
        check=True,
    )
    return sorted(into.glob("*.whl"))


def blender_ext_tool() -> Path:
    """Path of blender_ext.py inside the installed bpy package (found without importing bpy)."""
    spec = importlib.util.find_spec("bpy")
    if spec is None or not spec.submodule_search_locations:
        sys.exit("build_extension: the bpy package is not installed (run `make venv`)")
    hits = glob.glob(
        str(Path(spec.submodule_search_locations[0]) / "*/scripts/addons_core/bl_pkg/cli/blender_ext.py")
    )
    if not hits:
        sys.exit("build_extension: blender_ext.py not found inside the bpy package")
    return Path(hits[0])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--wheel-dir", required=True, type=Path)
    ap.add_argument("--out", required=True, type=Path)
    args = ap.parse_args()

    wheels = sorted(args.wheel_dir.glob("batten_native-*.whl"))
    if len(wheels) != 1:
        sys.exit(
            f"build_extension: expected one batten_native wheel in {args.wheel_dir}, found {len(wheels)}"
        )
    wheel = wheels[0]

    stage = args.out / "stage" / "batten"
    shutil.rmtree(args.out, ignore_errors=True)
    shutil.copytree(
        ROOT / "addon" / "batten", stage, ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "wheels")
    )
    (stage / "wheels").mkdir()
    shutil.copy2(wheel, stage / "wheels" / wheel.name)
    bundled = download_wheels(stage / "wheels")
    examples = ROOT / "examples"
    if examples.is_dir():
        shutil.copytree(examples, stage / "examples", ignore=shutil.ignore_patterns("*.py", "__pycache__"))

    manifest = stage / "blender_manifest.toml"
    text = manifest.read_text()
    listed = ", ".join(f'"./wheels/{w.name}"' for w in bundled)
    text, n = re.subn(r"(?m)^wheels\s*=\s*\[.*?\]", f"wheels = [{listed}]", text)
    if n != 1:
        sys.exit("build_extension: blender_manifest.toml needs one `wheels = [...]` line")
    manifest.write_text(text)

    tool = blender_ext_tool()
    subprocess.run([sys.executable, str(tool), "validate", str(stage)], check=True)
    subprocess.run(
        [sys.executable, str(tool), "build", "--source-dir", str(stage), "--output-dir", str(args.out)],
        check=True,
    )
    zips = sorted(args.out.glob("batten-*.zip"))
    subprocess.run([sys.executable, str(tool), "validate", str(zips[0])], check=True)
    print(f"extension: {zips[0]}")


if __name__ == "__main__":
    main()
