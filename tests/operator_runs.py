"""Helpers for the tests of batten's operators and error kinds (new collections, operators
run without bpy.ops)."""

from __future__ import annotations

import bpy


def new_collection(name: str):
    """A new collection linked to the scene."""
    coll = bpy.data.collections.new(name)
    bpy.context.scene.collection.children.link(coll)
    return coll


class _StandIn:
    """An operator of class ``cls`` without Blender's operator machinery: the class's methods
    bound to it, its properties plain attributes, its reports collected."""

    def __init__(self, cls, reports: list, props: dict) -> None:
        self._cls, self._reports = cls, reports
        for key, value in props.items():
            setattr(self, key, value)

    def report(self, kind, message) -> None:
        self._reports.append((kind, message))

    def __getattr__(self, name):
        attr = getattr(self._cls, name)
        return attr.__get__(self) if callable(attr) and hasattr(attr, "__get__") else attr


def stand_in(cls, **props) -> tuple[_StandIn, list]:
    """A stand-in operator of class ``cls`` with ``props``, and the list its reports
    ``(kind, message)`` go to."""
    reports: list = []
    return _StandIn(cls, reports, props), reports


def execute(cls, context, **props) -> tuple[set[str], list]:
    """Run the operator class ``cls``'s ``execute`` on a stand-in with ``props`` and return its
    result set and its reports ``(kind, message)``: bpy.ops turns an ERROR report into a
    RuntimeError, which hides the CANCELLED the operator returned."""
    op, reports = stand_in(cls, **props)
    return cls.execute(op, context), reports


class FakeEvent:
    """An event as a modal operator sees it: ``type`` and ``value``."""

    def __init__(self, type: str, value: str = "NOTHING") -> None:
        self.type, self.value = type, value


def run_modal(cls, context, events, **props) -> tuple[list[set[str]], list, object]:
    """Start the modal operator class ``cls`` (a :class:`batten.modal_jobs.ModalJob`) on a
    stand-in with ``props`` as its ``execute`` does with a window (without the timer and the
    handler, which need one), and feed it ``events`` (event type names; ``"TIMER"`` runs one
    step) until it ends. Returns the result sets of each :meth:`modal` call, the reports and
    the stand-in."""
    op, reports = stand_in(cls, **props)
    op.begin(context)
    results = []
    for kind in events:
        result = op.modal(context, FakeEvent(kind, "PRESS"))
        results.append(result)
        if result != {"RUNNING_MODAL"}:
            break
    return results, reports, op
