"""The add-on in Blender: registration, operators through bpy.ops, data saved in the .blend."""

import json

import batten
import bpy
import numpy as np
import pytest
from helpers import new_curve


def test_register_is_idempotent_and_symmetric():
    batten.register()  # already registered by the fixture: a second call must be harmless
    try:
        assert hasattr(bpy.types.Object, "batten") and hasattr(bpy.types.Scene, "batten")
        batten.unregister()
        assert not hasattr(bpy.types.Object, "batten") and not hasattr(bpy.types.Scene, "batten")
        assert not hasattr(bpy.types, "BATTEN_OT_export_network")
        assert not hasattr(bpy.types, "VIEW3D_PT_batten")
        batten.unregister()  # twice: harmless
    finally:
        batten.register()
    assert hasattr(bpy.types, "BATTEN_OT_import_network") and hasattr(bpy.types.Object, "batten")


def _surface_faces(scene) -> int:
    return len(next(o for o in scene.objects if o.type == "MESH").data.polygons)


def test_operators_keep_no_state_and_support_undo(tmp_path, examples_dir):
    # Undo: every batten operator that changes the file is an undo step (export writes a
    # file only). Found from bpy.ops, so a new operator is checked too.
    ops = {name: getattr(bpy.types, f"BATTEN_OT_{name}") for name in dir(bpy.ops.batten)}
    assert len(ops) >= 6
    assert all("REGISTER" in cls.bl_options for cls in ops.values())
    assert {n for n, cls in ops.items() if "UNDO" not in cls.bl_options} == {
        "export_network",
        "export_hydrostatics",
        "export_lines_plan",
        "export_iges",
        "export_step",
        "export_3dm",
    }
    # No hidden state: two scenes with their own hulls and settings, built alternately; each
    # build follows its own scene's data alone (a setting or source kept in Python from the
    # previous call would build the other hull or resolution).
    a = bpy.context.scene
    assert bpy.ops.batten.import_network(filepath=str(examples_dir / "wigley.json")) == {"FINISHED"}
    a.batten.resolution = 4
    b = bpy.data.scenes.new("B")
    with bpy.context.temp_override(scene=b):
        assert bpy.ops.batten.import_network(filepath=str(examples_dir / "hard_chine.json")) == {"FINISHED"}
    b.batten.resolution = 6
    assert b.batten.source.name == "hard_chine" and a.batten.source.name == "wigley"
    for scene in (a, b, a, b):
        with bpy.context.temp_override(scene=scene):
            assert bpy.ops.batten.build() == {"FINISHED"}
    assert _surface_faces(a) == 32 * 4 * 4, "wigley at resolution 4"
    faces_b = _surface_faces(b)
    assert json.loads(b.batten.last_report)["mesh_faces"] == faces_b != _surface_faces(a)
    # Everything an operator needs is in the file: saved, a fresh file opened and the saved
    # one reopened, the build gives the same mesh.
    path = tmp_path / "two.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    bpy.ops.wm.open_mainfile(filepath=str(path))
    b = bpy.data.scenes["B"]
    assert b.batten.source.name == "hard_chine" and b.batten.resolution == 6
    with bpy.context.temp_override(scene=b):
        assert bpy.ops.batten.build() == {"FINISHED"}
    assert _surface_faces(b) == faces_b


def test_import_operator_draws_and_sets_the_hull(examples_dir):
    result = bpy.ops.batten.import_network(filepath=str(examples_dir / "wigley.json"))
    assert result == {"FINISHED"}
    coll = bpy.context.scene.batten.source
    assert coll is not None and coll.name == "wigley"
    assert len(coll.objects) == 14
    assert coll.objects["keel"].batten.role == "keel"


def test_export_operator_matches_api(tmp_path, examples_dir):
    import batten.api as api

    coll = api.load_network(examples_dir / "wigley.json")
    bpy.context.scene.batten.source = coll
    assert bpy.ops.batten.export_network(filepath=str(tmp_path / "op.json")) == {"FINISHED"}
    api.export_network(coll, tmp_path / "api.json")
    assert (tmp_path / "op.json").read_text() == (tmp_path / "api.json").read_text()


def test_operator_errors_are_runtime_errors_and_change_nothing(tmp_path):
    coll = bpy.data.collections.new("Empty hull")
    bpy.context.scene.collection.children.link(coll)
    bpy.context.scene.batten.source = coll
    with pytest.raises(RuntimeError, match="collection 'Empty hull' holds no curves"):
        bpy.ops.batten.export_network(filepath=str(tmp_path / "x.json"))
    assert not (tmp_path / "x.json").exists()
    (tmp_path / "bad.json").write_text("{not json")
    n = len(bpy.data.objects)
    with pytest.raises(RuntimeError, match="bad.json"):
        bpy.ops.batten.import_network(filepath=str(tmp_path / "bad.json"))
    assert len(bpy.data.objects) == n


def test_roles_and_settings_survive_save_and_reload(tmp_path):
    obj = new_curve("chine", "POLY", np.array([[0, 0, 0], [1, 1, 0], [2, 1, 1.0]]))
    obj.batten.role = "knuckle"
    scene = bpy.context.scene
    scene.batten.tolerance = 2.5e-4
    scene.batten.resolution = 12
    path = tmp_path / "hull.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    assert "chine" not in bpy.data.objects
    bpy.ops.wm.open_mainfile(filepath=str(path))
    assert bpy.data.objects["chine"].batten.role == "knuckle"
    assert bpy.context.scene.batten.tolerance == pytest.approx(2.5e-4)
    assert bpy.context.scene.batten.resolution == 12
