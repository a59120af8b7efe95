"""Build the installable batten extension zip with Blender's own extension tool.

Stages ``addon/batten`` with the built ``batten_native`` wheel and the wheels of the Python
packages it bundles (:data:`BUNDLED`, at their pins in requirements-dev.txt, downloaded with
pip once into ``<wheel-dir>/../bundled`` and reused) in ``wheels/``, points the manifest's
``wheels`` list at them, then runs ``blender_ext.py build`` and ``validate`` (the ``bl_pkg``
command-line tool shipped inside the bpy package; no Blender binary needed).

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
#: The packages the add-on needs beside batten_native, bundled as wheels: ezdxf (writes the
#: lines plan's DXF) and its dependencies (numpy is Blender's own), rhino3dm (writes .3dm).
BUNDLED = ("ezdxf", "fonttools", "pyparsing", "typing_extensions", "rhino3dm")
#: The oldest glibc the extension runs on: Blender's own Linux builds need 2.28. The
#: batten_native wheel is linked against it (the Makefile's ``maturin build --zig
#: --compatibility manylinux_2_28``) and every wheel staged must load there.
GLIBC = (2, 28)
#: Blender's Python (3.11 in 4.2 to 5.0) and the extension's platform (blender_manifest.toml
#: ``platforms``): CPython 3.11 on linux-x64, as the manylinux tags that glibc 2.28 takes.
PLATFORMS = ("manylinux_2_28_x86_64", "manylinux_2_17_x86_64", "manylinux2014_x86_64")
#: The files beside the add-on in the zip: its licence and its documentation.
DOCS = ("LICENSE", "README.md")
WHEEL_TAGS = (
    "--python-version", "3.11", "--implementation", "cp",
    *(arg for p in PLATFORMS for arg in ("--platform", p)),
)  # fmt: skip


def pins(names) -> list[str]:
    """``name==version`` of each of ``names`` as requirements-dev.txt pins it."""
    found = dict(
        line.split("==", 1)
        for line in (ROOT / "requirements-dev.txt").read_text().splitlines()
        if "==" in line and not line.lstrip().startswith("#")
    )
    missing = [n for n in names if n not in found]
    if missing:
        sys.exit(f"build_extension: requirements-dev.txt pins no version of {', '.join(missing)}")
    return [f"{n}=={found[n].strip()}" for n in names]


def bundled_wheels(cache: Path) -> list[Path]:
    """The wheels of :data:`BUNDLED` for Blender's Python, from ``cache`` or downloaded into it."""
    cache.mkdir(parents=True, exist_ok=True)

    def wheel_of(spec: str) -> list[Path]:
        name, version = spec.split("==")
        return sorted(cache.glob(f"{name.replace('-', '_')}-{version}-*.whl"))

    wanted = pins(BUNDLED)
    missing = [spec for spec in wanted if not wheel_of(spec)]
    if missing:
        subprocess.run(
            [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps", "--only-binary=:all:",
             *WHEEL_TAGS, "--dest", str(cache), *missing],
            check=True,
        )  # fmt: skip
    wheels = [w for spec in wanted for w in wheel_of(spec)[:1]]
    if len(wheels) != len(wanted):
        sys.exit(f"build_extension: no wheel of {', '.join(s for s in wanted if not wheel_of(s))} in {cache}")
    return wheels


def oldest_glibc(wheel: Path) -> tuple[int, int] | None:
    """The oldest glibc ``wheel`` installs on by its platform tags (its file name's last
    field; the least that any of its tags needs: ``manylinux_2_17_x86_64.manylinux2014_x86_64``
    needs 2.17); None for a pure-Python wheel (``any``)."""
    legacy = {"manylinux1": (2, 5), "manylinux2010": (2, 12), "manylinux2014": (2, 17)}
    needs = []
    for tag in wheel.stem.split("-")[-1].split("."):
        if tag == "any":
            return None
        if m := re.fullmatch(r"manylinux_(\d+)_(\d+)_x86_64", tag):
            needs.append((int(m[1]), int(m[2])))
        elif (m := re.fullmatch(r"(manylinux\w+?)_x86_64", tag)) and m[1] in legacy:
            needs.append(legacy[m[1]])
        else:
            sys.exit(f"build_extension: {wheel.name} is not for manylinux x86_64 ({tag})")
    return min(needs)


def check_glibc(wheels: list[Path]) -> None:
    """Exit unless every wheel loads on :data:`GLIBC`: its tags say so, and for
    batten_native ``auditwheel show`` (the symbols it links) agrees."""
    for w in wheels:
        need = oldest_glibc(w)
        if need is not None and need > GLIBC:
            sys.exit(f"build_extension: {w.name} needs glibc {need[0]}.{need[1]} (> {GLIBC[0]}.{GLIBC[1]})")
    native = next(w for w in wheels if w.name.startswith("batten_native-"))
    shown = subprocess.run(
        [sys.executable, "-m", "auditwheel", "show", str(native)], check=True, capture_output=True, text=True
    ).stdout
    print(shown.strip())
    tag = re.search(
        r'consistent\s+with\s+the\s+following\s+platform\s+tag:\s*"manylinux_(\d+)_(\d+)_x86_64"', shown
    )
    if tag is None or (int(tag[1]), int(tag[2])) > GLIBC:
        sys.exit(f"build_extension: auditwheel finds {native.name} needs a glibc newer than 2.28")


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
    staged = [wheel, *bundled_wheels(args.wheel_dir.parent / "bundled")]
    check_glibc(staged)
    for w in staged:
        shutil.copy2(w, stage / "wheels" / w.name)
    for doc in DOCS:
        shutil.copy2(ROOT / doc, stage / doc)
    examples = ROOT / "examples"
    if examples.is_dir():
        shutil.copytree(examples, stage / "examples", ignore=shutil.ignore_patterns("*.py", "__pycache__"))

    manifest = stage / "blender_manifest.toml"
    text = manifest.read_text()
    listed = ", ".join(f'"./wheels/{w.name}"' for w in staged)
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
