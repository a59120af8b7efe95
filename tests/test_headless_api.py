"""A headless script that imports ``batten.api`` and never calls ``batten.register()`` (the
README's scripting example) gets the roles of its curves: the API registers the add-on on
first use. Run in a fresh interpreter, since the tests' own session registers it up front."""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SCRIPT = textwrap.dedent(
    """
    import json, os, sys
    import bpy
    import batten.api as api
    print("REGISTERED BEFORE", hasattr(bpy.types.Object, "batten"))
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    hull = api.load_network(sys.argv[1])
    roles = {o.name: o.batten.role for o in api.curve_objects(hull)}
    free = next(name for name, role in sorted(roles.items()) if role == "free")
    api.set_role([bpy.data.objects[free]], "knuckle")
    read = {c.name: c.role for c in api.read_curves(hull)}
    print("ROLES", json.dumps({"drawn": roles, "read": read, "set": free}))
    sys.stdout.flush()
    sys.stderr.flush()
    # The bpy 4.2 module crashes at exit once any property with a Python callback has been
    # registered (add-on or not: a five-line script without batten does it); what this test
    # checks is printed above.
    os._exit(0)
    """
)


def test_a_script_that_never_registers_gets_the_roles(tmp_path):
    example = ROOT / "examples" / "hard_chine.json"
    expected = {c["name"]: c.get("role", "free") for c in json.loads(example.read_text())["curves"]}
    assert {"keel", "knuckle", "deck", "transom", "stem"} <= set(expected.values())
    script = tmp_path / "script.py"
    script.write_text(SCRIPT)
    env = {k: v for k, v in os.environ.items() if k != "BLENDER_USER_RESOURCES"}
    env["BLENDER_USER_RESOURCES"] = str(tmp_path / "user")
    out = subprocess.run(
        [sys.executable, str(script), str(example)], env=env, capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert "REGISTERED BEFORE False" in out.stdout, out.stdout
    line = next(ln for ln in out.stdout.splitlines() if ln.startswith("ROLES "))
    got = json.loads(line.removeprefix("ROLES "))
    assert got["drawn"] == expected
    assert got["read"] == {**expected, got["set"]: "knuckle"}
