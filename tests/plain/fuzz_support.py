"""What the hypothesis fuzz tests share (issue 21): the budget profiles, the per-call time limit
and the check that a call gave a finite result or a ``BattenError``.

``BATTEN_FUZZ_PROFILE`` picks the budget: ``short`` (default, ``make test``) or ``long``
(``make fuzz``). On CI (``CI`` set) the short run is derandomised, so a failure replays
exactly. Every call runs under :func:`call`: hypothesis's ``deadline`` fails a call slower than
:data:`CALL_SECONDS` with its input, and a call that never returns (the GIL held, so nothing in
Python can interrupt it) ends the process after :data:`HANG_SECONDS` with its input and the
Python traceback in :data:`HANG_REPORT`.
"""

from __future__ import annotations

import atexit
import faulthandler
import math
import os
import tempfile
from datetime import timedelta
from pathlib import Path

import batten_native as bn
import numpy as np
from hypothesis import HealthCheck, settings

#: A call slower than this fails the example (hypothesis ``deadline``), naming its input.
CALL_SECONDS = 2.0
#: A call still running after this long is a hang: the process ends, see :data:`HANG_REPORT`.
HANG_SECONDS = 20.0
#: Where a hang is reported: the pending call's input, then every thread's traceback (empty
#: unless the process ended inside a call): one file per process, as sessions may test side by
#: side, removed at exit when no call hung.
HANG_REPORT = Path(
    os.environ.get(
        "BATTEN_FUZZ_HANG_REPORT", Path(tempfile.gettempdir()) / f"batten_fuzz_hang_{os.getpid()}.txt"
    )
)

#: Report entries documented to be infinite at times: a fairing piece's smoothing parameter
#: ``p`` is ∞ for the least-squares spline (Dierckx).
DOCUMENTED_INFINITE = frozenset({"p"})

_COMMON = {
    "deadline": timedelta(seconds=CALL_SECONDS),
    "suppress_health_check": [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
    "print_blob": True,
}
settings.register_profile("short", max_examples=40, derandomize=bool(os.environ.get("CI")), **_COMMON)
settings.register_profile("long", max_examples=3000, **_COMMON)
settings.load_profile(os.environ.get("BATTEN_FUZZ_PROFILE", "short"))

_report = HANG_REPORT.open("w", encoding="utf-8", errors="backslashreplace")


@atexit.register
def _remove_an_empty_report() -> None:
    _report.close()
    if "BATTEN_FUZZ_HANG_REPORT" not in os.environ and HANG_REPORT.stat().st_size == 0:
        HANG_REPORT.unlink()


def call(fn, *args, **kwargs):
    """``fn(*args, **kwargs)`` under the hang watchdog: its result, or the ``BattenError`` it
    raised (any other exception propagates and fails the example)."""
    _report.seek(0)
    _report.truncate()
    with np.printoptions(threshold=200, precision=17):
        on = getattr(fn, "__self__", None)
        where = f" on {describe(on)}" if isinstance(on, bn.Curve) else ""
        _report.write(
            f"hang in {getattr(fn, '__qualname__', fn)}(*{describe(args)}, **{describe(kwargs)}){where}\n"
        )
    _report.flush()
    faulthandler.dump_traceback_later(HANG_SECONDS, exit=True, file=_report)
    try:
        return fn(*args, **kwargs)
    except bn.BattenError as e:
        return e
    finally:
        faulthandler.cancel_dump_traceback_later()
        _report.seek(0)
        _report.truncate()


def describe(value) -> str:
    """``repr`` of a call's argument, with the geometry of every curve in it (so that the
    report of a hang rebuilds the input)."""
    if isinstance(value, bn.Curve):
        weights = None if value.weights is None else value.weights.tolist()
        return (
            f"Curve({value.name!r}, {value.degree}, {value.knots.tolist()!r}, "
            f"{value.control_points.tolist()!r}, {weights!r}, {value.role!r})"
        )
    if isinstance(value, list | tuple):
        inner = ", ".join(describe(v) for v in value)
        return f"[{inner}]" if isinstance(value, list) else f"({inner},)"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k!r}: {describe(v)}" for k, v in value.items()) + "}"
    return repr(value)


def finite(value) -> bool:
    """True when every number in ``value`` (nested tuples, lists, dicts, arrays) is finite."""
    if isinstance(value, bool | str | bytes | None.__class__):
        return True
    if isinstance(value, int | float):
        return math.isfinite(value)
    if isinstance(value, np.ndarray):
        return value.dtype.kind not in "fc" or bool(np.isfinite(value).all())
    if isinstance(value, dict):
        return all(finite(v) for k, v in value.items() if k not in DOCUMENTED_INFINITE)
    if isinstance(value, list | tuple):
        return all(finite(v) for v in value)
    if isinstance(value, bn.Curve):
        return finite((value.knots, value.control_points, value.weights))
    return True
