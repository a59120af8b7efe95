"""batten: smooth ship hull surfaces from networks of designer curves.

The add-on is a thin front end: geometry runs in the Rust module ``batten_native``; the
scripting API is :mod:`batten.api`; operators and panels only call it.
"""

from . import live, operators, overlay, panels, properties

_MODULES = (properties, operators, panels, overlay, live)


def register():
    """Register properties, operators and panels (safe to call twice)."""
    for module in _MODULES:
        module.register()


def unregister():
    """Remove everything :func:`register` added, in reverse order (safe to call twice)."""
    for module in reversed(_MODULES):
        module.unregister()
