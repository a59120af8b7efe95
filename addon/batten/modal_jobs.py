"""Long operators as modal operators: the work (a :func:`batten.api.start` job) runs one step
per timer event, so Blender's event loop runs between steps: the status bar shows
``"batten: <label> k/N — Esc to cancel"`` and Esc or a right click cancels, with nothing
changed (the jobs write only after their last step). Headless, or called from a script
(``bpy.ops.batten.…()`` runs ``execute`` without ``invoke``), the job runs to its end at
once, so the script sees its result."""

from __future__ import annotations

import bpy

from . import api, progress
from .operator_base import BattenOperator

#: Time between two steps of a modal job (s): the timer that drives it.
TICK_S = 0.01
#: The status bar's hint while a modal job runs.
CANCEL_HINT = " — Esc to cancel"
#: The events that cancel a modal job.
CANCEL_EVENTS = frozenset({"ESC", "RIGHTMOUSE"})


class ModalJob(BattenOperator):
    """The shared body of batten's long operators. A subclass gives :meth:`job` (the
    :func:`batten.api.start` of its call) and :meth:`finish` (its reports from the call's
    result). :meth:`execute` starts the job modally when it was invoked from the UI and Blender
    has a window, else runs it to its end; :meth:`modal` steps it on each timer event and
    cancels on Esc / right click. A BattenError becomes an error report and ``{'CANCELLED'}``,
    as for every batten operator."""

    _job = None
    _timer = None

    def job(self, context) -> api.Job:
        """The operator's work as a job (``api.start(api.<call>, …)``)."""
        raise NotImplementedError

    def finish(self, context, result) -> set[str]:
        """Report the call's ``result``; returns Blender's result set."""
        raise NotImplementedError

    def run(self, context) -> set[str]:
        """Run the job to its end at once (headless, or from a script)."""
        job = self.job(context)
        while not job.step():
            pass
        return self.finish(context, job.result)

    #: Set by :meth:`invoke` (a click in the UI, or the file browser that opens first): only then
    #: does :meth:`execute` run modally; a script's ``bpy.ops.batten.…()`` runs it at once.
    interactive: bpy.props.BoolProperty(default=False, options={"HIDDEN", "SKIP_SAVE"})

    def invoke(self, context, event):
        self.interactive = True
        parent = super()
        if hasattr(parent, "invoke"):
            return parent.invoke(context, event)  # the file browser (Import/ExportHelper)
        return self.execute(context)

    def execute(self, context):
        modal = getattr(self, "interactive", False) is True
        if not modal or bpy.app.background or context.window is None:
            return BattenOperator.execute(self, context)
        try:
            self.begin(context)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        wm = context.window_manager
        self._timer = wm.event_timer_add(TICK_S, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def begin(self, context) -> None:
        """Make the job (its argument checks run here) and show the cancel hint."""
        self._job = self.job(context)
        progress.cancel_hint = CANCEL_HINT

    def modal(self, context, event):
        if event.type in CANCEL_EVENTS and event.value == "PRESS":
            label = self._job.progress.label if self._job.progress is not None else self.bl_label
            self._job.cancel()
            self._end(context)
            self.report({"WARNING"}, f"{label}: cancelled, nothing changed")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"RUNNING_MODAL"}  # the work is under way: nothing else may change the scene
        try:
            finished = self._job.step()
        except api.BattenError as e:
            self._end(context)
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        except BaseException:
            self._end(context)
            raise
        if not finished:
            return {"RUNNING_MODAL"}
        self._end(context)
        try:
            return self.finish(context, self._job.result)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}

    def cancel(self, context):
        """Blender ends the operator (the window closes): the job stops, nothing changed."""
        if self._job is not None:
            self._job.cancel()
        self._end(context)

    def _end(self, context) -> None:
        progress.cancel_hint = ""
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        workspace = getattr(context, "workspace", None)
        if workspace is not None and not bpy.app.background:
            workspace.status_text_set(None)
