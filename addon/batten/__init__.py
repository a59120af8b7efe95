"""batten: smooth ship hull surfaces from networks of designer curves.

The add-on is a thin front end: geometry runs in the Rust module ``batten_native``; the
scripting API is :mod:`batten.api`; operators and panels only call it. Importing the package
needs no Blender (its Blender modules load in :func:`register`), so the bpy-free modules
(:mod:`batten.fit_data`, :mod:`batten.object_names`, :mod:`batten.network_markers`,
:mod:`batten.atomic_write`, :mod:`batten.cad_export`, :mod:`batten.hydro_table`, :mod:`batten.chart`,
:mod:`batten.waterplane_outline`, the lines plan's :mod:`batten.lines_plan`, :mod:`batten.drawing`
and its writers) can be used and tested without it.
"""

import os as _os

# batten_native allocates with mimalloc, which by default gives memory it freed back to the
# system after 10 ms: the next build or live rebuild then faults all of it in again (1,300 page
# faults, a tenth of a KCS live rebuild's time). Held for a second it is there for the next
# edit. mimalloc reads this when batten_native loads, so it is set before any module here
# imports that; a value already set is kept.
_os.environ.setdefault("MIMALLOC_PURGE_DELAY", "1000")


def _modules():
    """The Blender modules, in registration order."""
    from . import (
        cad_operators,
        form_drag,
        form_operators,
        hydro_operators,
        live,
        operators,
        overlay,
        panels,
        properties,
    )

    return (
        properties,
        operators,
        cad_operators,
        hydro_operators,
        form_operators,
        form_drag,
        panels,
        overlay,
        live,
    )


def register():
    """Register properties, operators and panels (safe to call twice)."""
    for module in _modules():
        module.register()


def unregister():
    """Remove everything :func:`register` added, in reverse order (safe to call twice)."""
    for module in reversed(_modules()):
        module.unregister()
