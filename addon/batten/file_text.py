"""Reading a text file the way every batten reader does (no Blender needed): UTF-8, a leading
byte-order mark dropped, and any failure a NetworkFileError naming the file."""

from __future__ import annotations

from pathlib import Path

from batten_native import NetworkFileError


def read_text(path, what: str) -> str:
    """The text of the file at ``path``. ``what`` names the kind of file in the error
    (``"network file"``, ``"section file"``): a missing or unreadable file, or one that is not
    UTF-8 text, raises NetworkFileError naming the file and the problem."""
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as e:
        raise NetworkFileError(
            f"{what} '{path}': not UTF-8 text (byte {e.object[e.start]:#04x} at offset {e.start})"
        ) from None
    except OSError as e:
        raise NetworkFileError(f"{what} '{path}': {e.strerror or e}") from None
