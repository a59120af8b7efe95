"""Conversions between Blender data and batten_native arrays (no geometry is computed here)."""
