"""Progress of long work, where the user sees it, and the way to cancel it: one small module
for every long job of :mod:`batten.api` (importing sections, fairing curves, surface fairing,
exports, lines plans, offsets tables).

- With a window: Blender's window-manager progress (the counter that replaces the mouse
  cursor) and the status bar's text ``"<label> k/N"`` (``" — Esc to cancel"`` added when a
  modal operator runs the job, see :mod:`batten.modal_jobs`).
- Headless (a script, ``blender -b``, the bpy module): a ``batten: <label> k/N`` line on
  stderr, at most every :data:`LINE_INTERVAL_S` and at the last step.
- A script cancels: every long call of :mod:`batten.api` takes ``progress=``, a callable
  ``progress(label, done, total)`` called after each step; returning ``False`` (not merely
  something falsy: a callback that only prints returns None and the work goes on) stops the
  work there and raises :class:`Cancelled`, a ``BattenError``. The jobs check between steps
  and write only at the end (all or nothing), so a cancelled job changes no curve and writes
  no file.
"""

from __future__ import annotations

import queue
import sys
import threading
import time
from collections.abc import Callable, Generator
from typing import Any, NamedTuple

from batten_native import Cancelled

__all__ = ["Cancelled", "Job", "Progress", "ProgressCallback", "Step", "LINE_INTERVAL_S", "run"]

#: Least time between two headless progress lines (s): often enough to show that work goes
#: on, seldom enough to keep a log short.
LINE_INTERVAL_S = 1.0

#: ``progress(label, done, total)``: return ``False`` to cancel.
ProgressCallback = Callable[[str, int, int], object]

#: Longest wait (s) of a job for a round of core work running in its worker thread before it
#: hands control back (so a modal operator's timer step returns to Blender's event loop).
POLL_S = 0.05

#: The status bar's hint while a modal operator runs a job (set by :mod:`batten.modal_jobs`).
cancel_hint = ""


def _status_target():
    """The workspace whose status bar shows progress, or None (headless, or no workspace)."""
    import bpy

    if bpy.app.background:
        return None
    return getattr(bpy.context, "workspace", None)


class Progress:
    """``total`` steps of work named ``label``: :meth:`step` after each (or :meth:`at` to set
    the count); used as a ``with`` block, which ends the window-manager progress and clears
    the status bar however the work ends. ``callback``: as the module says; returning
    ``False`` raises :class:`Cancelled` from :meth:`step`."""

    def __init__(self, label: str, total: int, callback: ProgressCallback | None = None) -> None:
        import bpy  # here, so that the jobs (Step, Job, run) need no Blender

        self.label, self.total, self.done = label, max(int(total), 1), 0
        self.callback = callback
        self._wm = None if bpy.app.background else bpy.context.window_manager
        self._workspace = _status_target()
        self._last_line = -LINE_INTERVAL_S

    def __enter__(self) -> Progress:
        if self._wm is not None:
            self._wm.progress_begin(0, self.total)
        self._show_status()
        return self

    def __exit__(self, *exc) -> None:
        if self._wm is not None:
            self._wm.progress_end()
        if self._workspace is not None:
            self._workspace.status_text_set(None)

    def status_text(self) -> str:
        """The status bar's text: ``"<label> k/N"`` and the cancel hint of a modal run."""
        return f"batten: {self.label} {self.done}/{self.total}{cancel_hint}"

    def _show_status(self) -> None:
        if self._workspace is not None:
            self._workspace.status_text_set(self.status_text())

    def step(self, *, final: bool = False) -> None:
        """One more step done: see :meth:`at`."""
        self.at(self.done + 1, final=final)

    def at(self, done: int, *, final: bool = False) -> None:
        """``done`` steps done: the cursor's counter and the status bar, or (headless) a line
        at most every :data:`LINE_INTERVAL_S` and at the last step; then the callback, and
        :class:`Cancelled` if it returned ``False`` — unless ``final``: a step reported once
        the work is committed (a file written) can no longer be undone, so it never cancels."""
        self.done = min(int(done), self.total)
        if self._wm is not None:
            self._wm.progress_update(self.done)
            self._show_status()
        else:
            now = time.monotonic()
            if now - self._last_line >= LINE_INTERVAL_S or self.done >= self.total:
                self._last_line = now
                print(f"batten: {self.label} {self.done}/{self.total}", file=sys.stderr, flush=True)
        answer = None if self.callback is None else self.callback(self.label, self.done, self.total)
        if answer is False and not final:
            raise Cancelled(f"{self.label} cancelled after {self.done}/{self.total} steps: nothing changed")


class Step(NamedTuple):
    """What a job yields after each step: ``done`` of ``total`` steps of ``label``; ``final``
    when the work is committed (a file written) and can no longer be cancelled."""

    label: str
    done: int
    total: int
    final: bool = False


#: A job: a generator of :class:`Step` that returns its result; it changes nothing (no
#: curve, no file) before its last step, so closing it between steps cancels it cleanly.
JobSteps = Generator[Step, None, Any]


class Job:
    """A long call of :mod:`batten.api` run step by step: :meth:`step` until it returns True,
    then :attr:`result`; :meth:`cancel` between steps stops it with nothing changed. The
    synchronous API runs a job to its end (:func:`run`); a modal operator steps it on a
    timer so that Blender's event loop (the status bar, Esc) runs between steps."""

    def __init__(self, steps: JobSteps, callback: ProgressCallback | None = None) -> None:
        self._steps, self.callback = steps, callback
        self._progress: Progress | None = None
        self.result: Any = None
        self.finished = False

    @property
    def progress(self) -> Progress | None:
        """The job's :class:`Progress` (None before its first step and once it ended)."""
        return self._progress

    def step(self) -> bool:
        """Run the job to its next step and report it (:meth:`Progress.at`); True once it has
        finished. Raises what the job raises, and :class:`Cancelled` when the callback
        returned ``False`` (the job is then closed: nothing changed)."""
        try:
            s = next(self._steps)
        except StopIteration as stop:
            self.result, self.finished = stop.value, True
            self._end()
            return True
        except BaseException:
            self._end()
            raise
        p = self._progress
        if p is None:
            p = self._progress = Progress(s.label, s.total, self.callback).__enter__()
        if s.done == p.done and s.label == p.label:
            return False  # a wait for core work that has not finished a (first) round yet
        p.label, p.total = s.label, max(int(s.total), 1)
        try:
            p.at(s.done, final=s.final)
        except BaseException:
            self.cancel()
            raise
        return False

    def cancel(self) -> None:
        """Stop the job between steps: nothing it would change is changed."""
        self._steps.close()
        self._end()

    def _end(self) -> None:
        if self._progress is not None:
            self._progress.__exit__(None, None, None)
            self._progress = None


#: Set by :func:`deferred` for the next :func:`run` of this thread: hand the job back instead.
_deferring = threading.local()


def run(steps: JobSteps, callback: ProgressCallback | None = None):
    """Run the job ``steps`` to its end, reporting its progress (see :class:`Job`); returns
    its result (or, the first run inside :func:`deferred`, the :class:`Job` itself)."""
    job = Job(steps, callback)
    if getattr(_deferring, "on", False):
        _deferring.on = False
        return job
    while not job.step():
        pass
    return job.result


def deferred(function, *args, **kwargs) -> Job | None:
    """The job of ``function(*args, **kwargs)``, a call that checks its arguments and then
    returns ``run(<its steps>, progress)``: that run hands back the :class:`Job` unstarted.
    None when ``function`` returned without running a job."""
    _deferring.on = True
    try:
        job = function(*args, **kwargs)
    finally:
        _deferring.on = False
    return job if isinstance(job, Job) else None


def in_worker(label: str, total: int | None, call: Callable[[Callable[[int, int], bool]], Any]) -> JobSteps:
    """Run ``call(round_done)`` (core work that touches no Blender data, its GIL released,
    calling ``round_done(done, total)`` after each round and stopping when it returns False) in
    a worker thread, yielding a :class:`Step` for every round (and at least every
    :data:`POLL_S`, so that a modal operator's step returns to the event loop) out of ``total``
    rounds, or (``total`` None) out of the total the core reports; returns what ``call``
    returned, raises what it raised. The core may report from several threads: the steps count
    the most rounds reported. Closed between steps (a cancel), it tells the core to stop at its
    next round and waits for it."""
    rounds: queue.SimpleQueue[tuple[int, int]] = queue.SimpleQueue()
    out: dict[str, Any] = {}
    stop = threading.Event()

    def round_done(done: int, of: int) -> bool:
        rounds.put((done, of))
        return not stop.is_set()

    def work() -> None:
        try:
            out["value"] = call(round_done)
        except BaseException as e:  # handed to the job's thread below
            out["error"] = e

    worker = threading.Thread(target=work, name=f"batten: {label}", daemon=True)
    worker.start()
    done, of = 0, total if total is not None else 1
    try:
        while worker.is_alive() or not rounds.empty():
            try:
                reported, reported_of = rounds.get(timeout=POLL_S)
                done = max(done, reported)
                of = total if total is not None else reported_of
            except queue.Empty:
                pass
            yield Step(label, done, of)
    finally:
        stop.set()
        worker.join()
    if "error" in out:
        raise out["error"]
    return out["value"]
