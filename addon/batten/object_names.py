"""Which Blender object each curve came from: findings (build warnings, topology diagnostics)
and curve errors named by the objects a designer can select (no Blender needed).

The core names curves, and a curve object with several splines gives several curves. The
reading side knows which object each curve came from (``{curve name: object name}``); these
functions use that mapping and never take names apart, so any object name works.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from contextlib import contextmanager

from batten_native import CurveError


def blender_name(text: str) -> str:
    """``text`` as a name Blender can store (UTF-8 only): each lone surrogate, as Python keeps
    the undecodable bytes of a file name (``x\\udcff.csv``), becomes U+FFFD."""
    return "".join("\ufffd" if "\ud800" <= ch <= "\udfff" else ch for ch in text)


def objects_of(curves: Iterable[str], object_of: Mapping[str, str]) -> list[str]:
    """The names of the objects the named ``curves`` came from, sorted, without repeats
    (curves not in ``object_of`` are left out)."""
    return sorted({object_of[c] for c in curves if c in object_of})


def with_objects(findings: list[dict], object_of: Mapping[str, str]) -> list[dict]:
    """Each finding (a dict with ``curves``) with an ``objects`` key added: the objects its
    curves came from (see :func:`objects_of`)."""
    return [{**f, "objects": objects_of(f["curves"], object_of)} for f in findings]


@contextmanager
def errors_named_by_object(object_of: Mapping[str, str]):
    """Inside the block, a :class:`CurveError` whose ``curve`` is a curve of ``object_of`` is
    raised again as the same kind of error with ``curve`` set to its object's name (the message,
    which names the curve, stays)."""
    try:
        yield
    except CurveError as e:
        obj = object_of.get(e.curve)
        if obj is None or obj == e.curve:
            raise
        raise type(e)(str(e), obj) from e
