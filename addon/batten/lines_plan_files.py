"""A lines plan written in the format its file name asks for (no Blender needed)."""

from __future__ import annotations

from pathlib import Path

from .atomic_write import write_atomically
from .drawing import Drawing

#: The formats a lines plan is written in, by file suffix (a PNG needs Blender's font engine).
FORMATS = (".svg", ".dxf", ".pdf", ".png")


def format_of(path) -> str:
    """The format of ``path`` by its suffix (lower case); ValueError for any other."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(
            f"a lines plan is written as {', '.join(FORMATS)}, not {suffix or 'a file without suffix'!r}"
        )
    return suffix


def file_bytes(drawing: Drawing, suffix: str) -> str | bytes:
    """The file of ``drawing`` in the format of ``suffix`` (the PDF with the drawing's
    tables on pages of their own)."""
    if suffix == ".svg":
        from .drawing_svg import svg_text

        return svg_text(drawing)
    if suffix == ".dxf":
        from .drawing_dxf import dxf_text

        return dxf_text(drawing)
    from .drawing_pdf import drawing_pdf

    return drawing_pdf(drawing, drawing.tables)


def write(drawing: Drawing, path) -> Path:
    """Write ``drawing`` to ``path`` in the format its suffix names, whole or not at all;
    returns the path. ValueError for an unknown suffix, OSError when it cannot be written."""
    suffix = format_of(path)
    if suffix == ".png":
        from .drawing_png import write_png

        return write_png(drawing, path)
    return write_atomically(path, file_bytes(drawing, suffix))
