"""The extension zip users download installs headless into a fresh user profile and works: the
add-on enables, batten_native is imported from the extension's own wheel, not from this test
environment; the wheels it bundles (ezdxf for the lines plan's DXF) are installed beside it; the
Wigley example builds; and the add-on disables cleanly. It runs on the bpy running the tests:
5.0 in `make test`, 4.2 and 4.5 in `make test-compat`."""

import os
import subprocess
import sys
import textwrap
import zipfile
from pathlib import Path

import bpy
import pytest

SCRIPT = textwrap.dedent(
    """
    import os, sys, tempfile, shutil, atexit
    user = tempfile.mkdtemp(prefix="batten_ext_")
    atexit.register(shutil.rmtree, user, True)
    os.environ["BLENDER_USER_RESOURCES"] = user
    import bpy
    result = bpy.ops.extensions.package_install_files(
        filepath=sys.argv[1], repo="user_default", enable_on_install=True)
    assert result == {"FINISHED"}, result
    assert "bl_ext.user_default.batten" in bpy.context.preferences.addons
    import batten_native
    assert batten_native.__file__.startswith(user), batten_native.__file__
    import numpy as np
    c = batten_native.Curve.from_poly("probe", np.array([[0.0, 0, 0], [3, 4, 0]]))
    print("LENGTH", c.arc_length())
    here = os.path.dirname(batten_native.__file__)
    # ezdxf (the lines plan's DXF) installed from the extension's own wheels beside it.
    site = os.path.dirname(here)
    bundled = ("ezdxf", "fontTools", "pyparsing")
    print("BUNDLED", sorted(n for n in bundled if os.path.isdir(os.path.join(site, n))))
    ex = os.path.join(user, "extensions", "user_default", "batten", "examples", "wigley.json")
    bpy.ops.batten.import_network(filepath=ex)
    print("CURVES", sum(o.type == "CURVE" for o in bpy.data.objects))
    assert bpy.ops.batten.build() == {"FINISHED"}
    import json
    print("PATCHES", json.loads(bpy.context.scene.batten.last_report)["faces"])
    hull = next(o for o in bpy.data.objects if o.type == "MESH" and o.name != "Cube")
    print("QUADS", len(hull.data.polygons))
    bpy.ops.preferences.addon_disable(module="bl_ext.user_default.batten")
    left = [
        *(n for n in dir(bpy.types) if n.startswith("BATTEN_") or n.endswith("_batten")),
        *(n for n in ("Object", "Scene") if hasattr(getattr(bpy.types, n), "batten")),
        *(f.__module__ for n in dir(bpy.app.handlers) if isinstance(h := getattr(bpy.app.handlers, n), list)
          for f in h if "batten" in getattr(f, "__module__", "")),
    ]
    print("DISABLED", "bl_ext.user_default.batten" not in bpy.context.preferences.addons, left)
    print("BLENDER", bpy.app.version_string)
    """
)


def test_extension_zip_installs_and_runs(tmp_path):
    zip_path = os.environ.get("BATTEN_EXTENSION_ZIP")
    if not zip_path:
        pytest.fail("BATTEN_EXTENSION_ZIP is not set: run the tests through `make test`")
    assert Path(zip_path).is_file(), zip_path
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "BLENDER_USER_RESOURCES")}
    script = tmp_path / "install.py"
    script.write_text(SCRIPT)
    out = subprocess.run(
        [sys.executable, str(script), zip_path], env=env, capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert "LENGTH 5.0" in out.stdout
    assert "CURVES 14" in out.stdout
    assert "BUNDLED ['ezdxf', 'fontTools', 'pyparsing']" in out.stdout
    assert "PATCHES 32" in out.stdout, out.stdout
    assert "QUADS 2048" in out.stdout, out.stdout
    # Nothing of the add-on left registered: operators, panels, properties, handlers.
    assert "DISABLED True []" in out.stdout, out.stdout
    assert "Traceback" not in out.stderr, out.stderr


def test_the_running_blender_validates_the_zip():
    """The zip passes the `extension validate` of the Blender running the tests (its bl_pkg
    tool inside the bpy package: the bpy module has no command line), so each tested
    Blender accepts its manifest (version range, tags, permissions, wheels) and layout."""
    zip_path = os.environ.get("BATTEN_EXTENSION_ZIP")
    if not zip_path:
        pytest.fail("BATTEN_EXTENSION_ZIP is not set: run the tests through `make test`")
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "blender_scripts"))
    from build_extension import blender_ext_tool

    tool = blender_ext_tool()
    assert f"{bpy.app.version[0]}.{bpy.app.version[1]}" in tool.parts, (tool, bpy.app.version)
    out = subprocess.run(
        [sys.executable, str(tool), "validate", zip_path], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert "Success" in out.stdout, out.stdout
    # The licence and the documentation ship in the zip, beside the add-on's code.
    with zipfile.ZipFile(zip_path) as z:
        names = set(z.namelist())
        assert {"LICENSE", "README.md", "blender_manifest.toml"} <= names, sorted(names)[:20]
        assert "GNU GENERAL PUBLIC LICENSE" in z.read("LICENSE").decode()
