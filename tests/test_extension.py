"""The extension zip users download installs headless and works: the add-on enables, and
batten_native is imported from the extension's own wheel, not from this test environment; the wheels it
bundles (ezdxf for the lines plan's DXF) are installed beside it."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

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
