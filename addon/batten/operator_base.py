"""The body every batten operator shares (its own module, so that :mod:`batten.modal_jobs`
and :mod:`batten.operators` both build on it)."""

from . import api


class BattenOperator:
    """The shared body of batten's operators: :meth:`execute` runs :meth:`run`, and a
    BattenError it raises becomes an error report on the operator and ``{'CANCELLED'}``
    (Blender's undo step is then not kept, and the API has changed nothing)."""

    def run(self, context) -> set[str]:
        """The operator's work (calls into :mod:`batten.api`); returns Blender's result set."""
        raise NotImplementedError

    def execute(self, context):
        try:
            return self.run(context)
        except api.BattenError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}


class HullOperator(BattenOperator):
    """An operator on the scene's hull collection (available only when there is one)."""

    @classmethod
    def poll(cls, context):
        return context.scene.batten.source is not None
