"""The exceptions of batten, one class per kind of problem a script may want to catch.

All derive from :class:`BattenError`, a :class:`ValueError`; the message always names the curve
(or the file) and the problem. The Rust binding raises these same classes.
"""

from __future__ import annotations


class BattenError(ValueError):
    """A problem with the hull's curves, files or settings; the message names the curve and the problem."""


class CurveError(BattenError):
    """A problem with one designer curve; ``.curve`` is the curve object's (or spline's) name."""

    curve: str

    def __init__(self, message: str, curve: str) -> None:
        super().__init__(message, curve)
        self.curve = curve

    def __str__(self) -> str:
        return str(self.args[0])


class FairError(CurveError):
    """Fairing the points of a curve failed (too few points, bad tolerance, bad tangents …)."""


class NetworkFileError(BattenError):
    """A network, section or offsets file could not be read (missing, malformed, newer version)."""


class NoSurfaceError(BattenError):
    """The network gives no hull surface: no closed region, or no face could be patched."""


class InvalidArgumentError(BattenError):
    """An argument is out of range or of the wrong kind (resolution 0, negative tolerance, unknown role …)."""


class HydrostaticsError(BattenError):
    """Hydrostatics that cannot give a true figure: the water below the keel or over the hull's
    open top, a hole in the surface under water (the message says where), no equilibrium."""


class ExportError(BattenError):
    """A file batten cannot write faithfully: the surface has holes (unless they are allowed),
    patches cannot be approximated within the tolerance (``.faces``: their topology faces,
    else empty), or the file cannot be written."""

    faces: tuple[int, ...]

    def __init__(self, message: str, faces=()) -> None:
        super().__init__(message, tuple(faces))
        self.faces = tuple(faces)

    def __str__(self) -> str:
        return str(self.args[0])


class Cancelled(BattenError):
    """Long work stopped because its ``progress`` callback returned ``False`` (or the designer
    pressed Esc in a modal operator); nothing it would have changed or written is changed."""


class InternalError(BattenError):
    """A defect of batten (a caught panic of the core); please report it with the curves that caused it."""


__all__ = [
    "BattenError",
    "Cancelled",
    "CurveError",
    "ExportError",
    "FairError",
    "HydrostaticsError",
    "InternalError",
    "InvalidArgumentError",
    "NetworkFileError",
    "NoSurfaceError",
]
