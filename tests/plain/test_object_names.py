"""Findings and curve errors named by the Blender objects the curves came from."""

import pytest
from batten.object_names import errors_named_by_object, objects_of, with_objects
from batten_native import BattenError, CurveError, FairError

# Curves as the reading names them: a one-spline object keeps its name (even "st[3]"), the
# splines of the multi-spline object "wl" are "wl[0]", "wl[1]".
OBJECT_OF = {"st[3]": "st[3]", "wl[0]": "wl", "wl[1]": "wl", "keel": "keel"}


def test_objects_of_maps_curves_to_their_objects_without_parsing_names():
    assert objects_of(["wl[1]", "st[3]", "wl[0]"], OBJECT_OF) == ["st[3]", "wl"]
    assert objects_of(["st"], OBJECT_OF) == [], "no name is taken apart at '['"
    assert objects_of([], OBJECT_OF) == []


def test_with_objects_adds_the_objects_and_keeps_the_finding():
    findings = [
        {"kind": "near_miss", "message": "m", "curves": ["keel", "wl[1]"], "location": [1, 2, 3]},
        {"kind": "unclosed_region", "message": "u", "curves": ["st[3]"], "location": None},
    ]
    named = with_objects(findings, OBJECT_OF)
    assert [f["objects"] for f in named] == [["keel", "wl"], ["st[3]"]]
    assert [{k: v for k, v in f.items() if k != "objects"} for f in named] == findings
    assert "objects" not in findings[0], "the input is not changed"


def test_curve_errors_are_raised_again_naming_the_object():
    with pytest.raises(FairError) as err, errors_named_by_object(OBJECT_OF):
        raise FairError("curve 'wl[1]': the points are not in order", "wl[1]")
    assert err.value.curve == "wl"
    assert str(err.value) == "curve 'wl[1]': the points are not in order", "the message names the spline"
    assert isinstance(err.value.__cause__, FairError) and err.value.__cause__.curve == "wl[1]"


def test_other_errors_pass_unchanged():
    with pytest.raises(CurveError) as err, errors_named_by_object(OBJECT_OF):
        raise CurveError("curve 'st[3]': zero length", "st[3]")
    assert err.value.curve == "st[3]" and err.value.__cause__ is None
    with pytest.raises(CurveError) as err, errors_named_by_object(OBJECT_OF):
        raise CurveError("curve 'other': zero length", "other")
    assert err.value.curve == "other"
    with pytest.raises(BattenError, match="tolerance") as err, errors_named_by_object(OBJECT_OF):
        raise BattenError("tolerance must be positive")
    assert type(err.value) is BattenError
