"""Writing a file whole or not at all (no Blender needed)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def write_atomically(path, text: str | bytes) -> Path:
    """Write ``text`` (UTF-8; bytes as they are) to ``path``: into a temporary file beside
    it, then renamed over it, so a reader sees the old file or the new one, never a part.
    Missing folders are made.
    Raises OSError (and leaves no temporary file) when it cannot. Returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        binary = isinstance(text, bytes)
        with os.fdopen(fd, "wb" if binary else "w", encoding=None if binary else "utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path
