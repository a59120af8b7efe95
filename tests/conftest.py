"""pytest inside bpy: one Blender per process, the add-on registered from ``addon/``, and a
fresh empty file for every test.

``BLENDER_USER_RESOURCES`` points Blender's user folders (preferences, extensions, caches) at a
temporary directory before bpy is imported, so tests never touch the user's Blender setup.
``batten_native`` comes from ``PYTHONPATH`` (the Makefile puts the freshly built module there).
"""

from __future__ import annotations

import atexit
import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
_USER_DIR = tempfile.mkdtemp(prefix="batten_bl_user_")
os.environ["BLENDER_USER_RESOURCES"] = _USER_DIR
# Registered before `import bpy`, so it runs after bpy's own exit handlers.
atexit.register(shutil.rmtree, _USER_DIR, True)

if str(ROOT / "addon") not in sys.path:
    sys.path.insert(0, str(ROOT / "addon"))

import bpy  # noqa: E402

# isort: split
import addon_utils  # noqa: E402  (importable only once bpy is)


@pytest.fixture(scope="session")
def addon():
    """The batten add-on, enabled once per session from the source folder."""
    module = addon_utils.enable("batten", default_set=True, handle_error=None)
    assert module is not None, "batten add-on failed to enable"
    yield module
    addon_utils.disable("batten", default_set=True)


@pytest.fixture(autouse=True)
def empty_file(addon):
    """A fresh, empty file (no objects) with the add-on registered, for every test."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    yield bpy.context


@pytest.fixture
def examples_dir() -> Path:
    return ROOT / "examples"


@pytest.fixture
def hulls_dir() -> Path:
    """The real ships' sections (``../shared/hulls``, beside the project)."""
    return ROOT.parent / "shared" / "hulls"


@pytest.fixture
def barge(tmp_path):
    """The barge with a parallel middle body of ``examples/pmb_barge.py`` (from its generator),
    as the hull collection 'barge' with its design draft."""
    import importlib.util

    import batten.api as api
    from batten_native import network_to_json

    spec = importlib.util.spec_from_file_location("pmb_barge", ROOT / "examples" / "pmb_barge.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    path = tmp_path / "barge.json"
    path.write_text(network_to_json("barge", module.barge_curves()))
    coll = api.load_network(path)
    coll[api.DESIGN_DRAFT_PROPERTY] = module.T
    return coll
