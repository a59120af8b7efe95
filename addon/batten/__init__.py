"""batten: smooth ship hull surfaces from networks of designer curves.

The add-on is a thin front end: geometry runs in the Rust module ``batten_native``; the
scripting API is :mod:`batten.api`; operators and panels only call it. Importing the package
needs no Blender (its Blender modules load in :func:`register`), so the bpy-free modules
(:mod:`batten.fit_data`, :mod:`batten.object_names`, :mod:`batten.network_markers`,
:mod:`batten.atomic_write`, :mod:`batten.cad_export`, :mod:`batten.hydro_table`, :mod:`batten.chart`,
:mod:`batten.waterplane_outline`, the lines plan's :mod:`batten.lines_plan`, :mod:`batten.drawing`
and its writers) can be used and tested without it.
"""


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
