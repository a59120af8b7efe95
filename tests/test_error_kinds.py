"""Errors a script can catch by kind: each BattenError subclass raised by batten.api where it
applies, with ``.curve`` naming the curve object, and operators turning them into reports."""

import batten.api as api
import bpy
import numpy as np
import pytest
from helpers import new_curve
from operator_runs import execute, new_collection
from test_fairing import noisy_arc

SQUARE = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])


def test_the_kinds_are_battenerrors_and_valueerrors():
    for kind in (
        api.CurveError,
        api.FairError,
        api.NetworkFileError,
        api.NoSurfaceError,
        api.InvalidArgumentError,
        api.InternalError,
    ):
        assert issubclass(kind, api.BattenError) and issubclass(kind, ValueError), kind
    assert issubclass(api.FairError, api.CurveError)


def test_a_non_curve_object_is_a_curve_error_naming_it():
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.active_object
    cube.name = "Deck[house]"
    with pytest.raises(api.CurveError, match="object 'Deck\\[house\\]' is a mesh, not a curve object") as err:
        api.read_curves([new_curve("keel", "POLY", SQUARE[:2]), cube])
    assert err.value.curve == "Deck[house]"
    with pytest.raises(api.CurveError) as err:
        api.fair_curve(cube)
    assert err.value.curve == "Deck[house]"


def test_a_bad_spline_of_a_multi_spline_object_names_the_object():
    obj = new_curve("rails", "POLY", SQUARE[:2])
    spline = obj.data.splines.new("POLY")
    spline.points.add(1)
    spline.points.foreach_set("co", np.array([0, 0, 1, 1, np.nan, 0, 1, 1], dtype=np.float32))
    with pytest.raises(api.CurveError, match="curve 'rails\\[1\\]'") as err:
        api.read_curves(obj)
    assert err.value.curve == "rails", "the object a script can look up"
    assert bpy.data.objects[err.value.curve] == obj


def test_a_zero_length_curve_is_a_curve_error_naming_its_object(tmp_path):
    coll = new_collection("hull")
    new_curve("keel", "POLY", SQUARE[:2], collection=coll)
    new_curve("dot", "POLY", np.ones((3, 3)), collection=coll)
    with pytest.raises(api.CurveError, match="curve 'dot'") as err:
        api.export_network(coll, tmp_path / "never.json")
    assert err.value.curve == "dot"
    assert not (tmp_path / "never.json").exists()


def test_a_failed_fit_is_a_fair_error_naming_the_object():
    pts = noisy_arc(40)
    obj = new_curve("scrambled", "POLY", pts[np.random.default_rng(0).permutation(len(pts))])
    with pytest.raises(api.FairError, match="curve 'scrambled': the points are not in order") as err:
        api.fair_curve(obj)
    assert err.value.curve == "scrambled"
    # A spline of a multi-spline object: the message names the spline, .curve the object.
    spline = obj.data.splines.new("POLY")
    spline.points.add(len(pts) - 1)
    spline.points.foreach_set("co", np.column_stack([pts, np.ones(len(pts))]).astype(np.float32).ravel())
    with pytest.raises(api.FairError, match="curve 'scrambled\\[0\\]'") as err:
        api.fair_curve(obj)
    assert err.value.curve == "scrambled"


def test_bad_arguments_are_invalid_argument_errors():
    coll = new_collection("Empty hull")
    with pytest.raises(api.InvalidArgumentError, match="collection 'Empty hull' holds no curves"):
        api.build(coll)
    with pytest.raises(api.InvalidArgumentError, match="expected a collection"):
        api.topology(42)
    with pytest.raises(api.InvalidArgumentError, match="is not a Blender object"):
        api.read_curves(["keel"])
    obj = new_curve("keel", "POLY", SQUARE[:2])
    with pytest.raises(api.InvalidArgumentError, match="unknown role 'bulb'"):
        api.set_role([obj], "bulb")
    assert obj.batten.role == "free"
    with pytest.raises(api.InvalidArgumentError, match="No example 'nope.json'"):
        api.load_example("nope.json")


def test_bad_settings_are_invalid_argument_errors():
    coll = new_collection("square")
    for i in range(4):
        new_curve(f"side{i}", "POLY", np.array([SQUARE[i], SQUARE[(i + 1) % 4]]), collection=coll)
    with pytest.raises(api.InvalidArgumentError, match="resolution"):
        api.build(coll, resolution=0)
    with pytest.raises(api.InvalidArgumentError, match="tolerance"):
        api.build(coll, tolerance=-1e-4)
    with pytest.raises(api.InvalidArgumentError, match="tolerance"):
        api.topology(coll, tolerance=0.0)
    # A fairing tolerance is checked per curve: a FairError naming it.
    with pytest.raises(api.FairError, match="curve .arc.: the fairing tolerance -1 must be") as err:
        api.fair_curve(new_curve("arc", "POLY", noisy_arc(20)), tolerance=-1.0)
    assert err.value.curve == "arc"


def test_curves_that_enclose_nothing_are_no_surface():
    coll = new_collection("two lines")
    new_curve("a", "POLY", SQUARE[:2], collection=coll)
    new_curve("b", "POLY", SQUARE[2:], collection=coll)
    with pytest.raises(api.NoSurfaceError, match="no faces"):
        api.build(coll)
    assert not any(o.type == "MESH" for o in bpy.data.objects), "nothing is written"


def test_network_files_that_cannot_be_read_or_written_are_network_file_errors(tmp_path):
    with pytest.raises(api.NetworkFileError, match="missing.json"):
        api.read_network(tmp_path / "missing.json")
    (tmp_path / "bad.json").write_text("{not json")
    with pytest.raises(api.NetworkFileError, match="bad.json"):
        api.load_network(tmp_path / "bad.json")
    (tmp_path / "bad.csv").write_text("st1,1,2\n")
    with pytest.raises(api.NetworkFileError, match="bad.csv', line 1: expected name, x, y, z"):
        api.import_sections(tmp_path / "bad.csv")
    (tmp_path / "empty.json").write_text('{"name": "e", "curves": []}')
    with pytest.raises(api.NetworkFileError, match="empty.json': no curves"):
        api.import_sections(tmp_path / "empty.json")
    with pytest.raises(api.NetworkFileError, match="nowhere.json"):
        api.import_sections(tmp_path / "nowhere.json")
    (tmp_path / "a file").write_text("")
    obj = new_curve("keel", "POLY", SQUARE[:2])
    with pytest.raises(api.NetworkFileError, match="network file '.*a file/hull.json'"):
        api.export_network(obj, tmp_path / "a file" / "hull.json")
    assert len(bpy.data.collections) == 0, "nothing was drawn"


def test_a_panic_in_the_core_is_an_internal_error():
    """(Through the test hook of dev builds, which the tests run on.)"""
    from batten_native import _native

    with pytest.raises(api.InternalError, match="internal error in batten's core \\(boom\\)"):
        _native._panic_for_tests("boom")


def test_operators_report_the_error_and_cancel(tmp_path):
    """Every operator shares one body: a BattenError becomes an ERROR report (RuntimeError
    through bpy.ops) and CANCELLED, with the file unchanged."""
    from batten import operators

    result, reports = execute(operators.BATTEN_OT_add_example, bpy.context, example="nope.json")
    assert result == {"CANCELLED"}
    assert reports == [({"ERROR"}, "No example 'nope.json'")]
    for cls in (getattr(operators, n) for n in dir(operators) if n.startswith("BATTEN_OT_")):
        assert issubclass(cls, operators.BattenOperator), cls
        assert "execute" not in cls.__dict__, f"{cls.__name__} uses the shared execute"
    with pytest.raises(RuntimeError, match="bad.json"):
        (tmp_path / "bad.json").write_text("{not json")
        bpy.ops.batten.import_network(filepath=str(tmp_path / "bad.json"))
    assert len(bpy.data.objects) == 0
