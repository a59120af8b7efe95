"""Progress of long work, where the user sees it: Blender's window-manager progress (the
counter that replaces the mouse cursor) when Blender has a window, a ``batten:`` line on
stderr when it runs headless (a script, ``blender -b``, the bpy module).

Implementation note: an operator's ``execute`` keeps Blender's event loop waiting, so the
status bar isn't redrawn and no key can cancel while it runs; those need the work split
into a modal operator's steps, which nothing here does yet.
"""

from __future__ import annotations

import sys
import time

import bpy

#: Least time between two headless progress lines (s): often enough to show that work goes
#: on, seldom enough to keep a log short.
LINE_INTERVAL_S = 1.0


class Progress:
    """``total`` steps of work named ``label``: :meth:`step` after each; used as a ``with``
    block, which ends the window-manager progress however the work ends."""

    def __init__(self, label: str, total: int) -> None:
        self.label, self.total, self.done = label, max(total, 1), 0
        self._wm = None if bpy.app.background else bpy.context.window_manager
        self._last_line = -LINE_INTERVAL_S

    def __enter__(self) -> Progress:
        if self._wm is not None:
            self._wm.progress_begin(0, self.total)
        return self

    def __exit__(self, *exc) -> None:
        if self._wm is not None:
            self._wm.progress_end()

    def step(self) -> None:
        """One more step done: the cursor's counter, or (headless) a line at most every
        :data:`LINE_INTERVAL_S` and at the last step."""
        self.done += 1
        if self._wm is not None:
            self._wm.progress_update(self.done)
            return
        now = time.monotonic()
        if now - self._last_line >= LINE_INTERVAL_S or self.done >= self.total:
            self._last_line = now
            print(f"batten: {self.label} {self.done}/{self.total}", file=sys.stderr, flush=True)
