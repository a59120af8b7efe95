"""Writing a file whole or not at all (no Blender needed)."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path


def replace_atomically(path, write: Callable[[Path], None]) -> Path:
    """Make the file ``path`` by ``write(temporary path)`` beside it, then rename it over
    ``path``, so a reader sees the old file or the new one, never a part. Missing folders are
    made. Raises OSError (and leaves no temporary file) when it cannot, or whatever ``write``
    raises. Returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    os.close(fd)
    try:
        write(Path(tmp))
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def write_atomically(path, text: str | bytes) -> Path:
    """Write ``text`` (UTF-8; bytes as they are) to ``path`` whole or not at all (see
    :func:`replace_atomically`)."""
    if isinstance(text, bytes):
        return replace_atomically(path, lambda tmp: tmp.write_bytes(text))
    return replace_atomically(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))
