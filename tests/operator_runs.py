"""Helpers for the tests of batten's operators and error kinds (new collections, operators
run without bpy.ops)."""

from __future__ import annotations

import bpy


def new_collection(name: str):
    """A new collection linked to the scene."""
    coll = bpy.data.collections.new(name)
    bpy.context.scene.collection.children.link(coll)
    return coll


def execute(cls, context, **props) -> tuple[set[str], list]:
    """Run the operator class ``cls``'s ``execute`` on a stand-in with ``props`` and return its
    result set and its reports ``(kind, message)``: bpy.ops turns an ERROR report into a
    RuntimeError, which hides the CANCELLED the operator returned."""
    reports = []
    stub = type("Stub", (), {"report": lambda _self, kind, message: reports.append((kind, message))})()
    for key, value in props.items():
        setattr(stub, key, value)
    stub.run = lambda ctx: cls.run(stub, ctx)
    return cls.execute(stub, context), reports
