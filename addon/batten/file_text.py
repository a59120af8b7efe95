"""Reading a text file the way every batten reader does (no Blender needed): UTF-8, a leading
byte-order mark dropped, and any failure a NetworkFileError naming the file; and file paths as
every batten reader and writer takes them (:func:`file_path`)."""

from __future__ import annotations

import os
from pathlib import Path

from batten_native import InvalidArgumentError, NetworkFileError


def file_path(path, what: str) -> Path:
    """``path`` (a str, bytes or path-like object) as a Path the file system can name.
    ``what`` names the kind of file in the error: a path of another type, or one with a lone
    surrogate the file system cannot encode, raises InvalidArgumentError naming it."""
    try:
        p = Path(os.fsdecode(path))
    except TypeError:
        raise InvalidArgumentError(
            f"{what} path must be a str, bytes or path-like object, not {type(path).__name__}"
        ) from None
    try:
        os.fsencode(p)
    except UnicodeEncodeError:
        raise InvalidArgumentError(
            f"{what} path {str(p)!r} cannot be a file name (it holds a lone surrogate)"
        ) from None
    return p


def read_text(path, what: str) -> str:
    """The text of the file at ``path``. ``what`` names the kind of file in the error
    (``"network file"``, ``"section file"``): a missing or unreadable file, or one that is not
    UTF-8 text, raises NetworkFileError naming the file and the problem (InvalidArgumentError
    for a path that is no file name, see :func:`file_path`)."""
    path = file_path(path, what)
    try:
        return path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as e:
        raise NetworkFileError(
            f"{what} '{path}': not UTF-8 text (byte {e.object[e.start]:#04x} at offset {e.start})"
        ) from None
    except OSError as e:
        raise NetworkFileError(f"{what} '{path}': {e.strerror or e}") from None
