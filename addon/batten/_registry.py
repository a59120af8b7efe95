"""Idempotent, symmetric registration of Blender classes (MolecularNodes' addon.py pattern)."""

import bpy


def register_classes(classes):
    """Register each class that is not registered yet."""
    for cls in classes:
        if not getattr(cls, "is_registered", False):
            bpy.utils.register_class(cls)


def unregister_classes(classes):
    """Unregister each registered class, in reverse order."""
    for cls in reversed(classes):
        if getattr(cls, "is_registered", False):
            bpy.utils.unregister_class(cls)
