"""Point lists in: the neutral section format of ``shared/hulls/*/network.json`` and plain CSV
offsets tables, as named point sequences with roles (no geometry is computed here).

Neutral format: ``{"name": ..., "curves": [{"name", "kind", "points": [[x, y, z], ...]}, ...]}``
with kinds station, waterline, buttock, profile, deck, chine.
CSV: one point per row, ``name, x, y, z`` (a header row is allowed); rows of one curve are
consecutive and in order along the curve.
"""

from __future__ import annotations

import csv
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from batten_native import NetworkFileError

from ..file_text import file_path, read_text

#: The batten role a curve of each kind gets.
ROLE_OF_KIND = {
    "station": "free",
    "waterline": "free",
    "buttock": "free",
    "profile": "keel",
    "deck": "deck",
    "chine": "knuckle",
    "knuckle": "knuckle",
    "stem": "stem",
    "transom": "transom",
}


@dataclass
class PointCurve:
    """A named, ordered point list with the role its kind implies."""

    name: str
    role: str
    points: np.ndarray


def read_sections(path) -> tuple[str, list[PointCurve]]:
    """``(name, curves)`` from a neutral JSON or CSV point file; NetworkFileError naming the file
    (and the curve or row) when it cannot be read."""
    path = file_path(path, "section file")
    text = read_text(path, "section file")
    if path.suffix.lower() == ".csv":
        return path.stem, _read_csv(path, text)
    return _read_json(path, text)


def read_datums(path) -> dict[str, float]:
    """The ship's datums a neutral JSON section file carries (as ``shared/hulls`` do): ``lpp``
    from ``Lpp`` and ``draft`` from ``T`` (m), where they are positive numbers; nothing for CSV
    or a file without them. The files' axes run from the aft perpendicular, so the forward one
    is at x = Lpp."""
    path = file_path(path, "section file")
    if path.suffix.lower() == ".csv":
        return {}
    try:
        data = json.loads(read_text(path, "section file"))
    except json.JSONDecodeError:
        return {}
    out = {}
    for key, name in (("Lpp", "lpp"), ("T", "draft")):
        v = data.get(key) if isinstance(data, dict) else None
        if isinstance(v, int | float) and not isinstance(v, bool) and 0 < v < float("inf"):
            out[name] = float(v)
    return out


def _read_json(path: Path, text: str) -> tuple[str, list[PointCurve]]:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise NetworkFileError(f"section file '{path}': not JSON ({e})") from None
    if not isinstance(data, dict) or not isinstance(data.get("curves"), list):
        raise NetworkFileError(f"section file '{path}': expected an object with a 'curves' list")
    curves = []
    for i, c in enumerate(data["curves"]):
        name = str(c.get("name") or f"curve {i}")
        try:
            pts = np.asarray(c["points"], dtype=np.float64)
        except (KeyError, TypeError, ValueError):
            raise NetworkFileError(
                f"section file '{path}': curve '{name}' has no numeric 'points' list"
            ) from None
        if pts.ndim != 2 or pts.shape[1] != 3:
            raise NetworkFileError(f"section file '{path}': curve '{name}' points must be [x, y, z] triples")
        kind = str(c.get("kind", "")).lower()
        curves.append(PointCurve(name, ROLE_OF_KIND.get(kind, "free"), pts))
    return str(data.get("name") or path.stem), curves


def _read_csv(path: Path, text: str) -> list[PointCurve]:
    rows: dict[str, list[list[float]]] = {}
    for lineno, row in enumerate(csv.reader(text.splitlines()), start=1):
        if not row or all(not c.strip() for c in row):
            continue
        if len(row) != 4:
            raise NetworkFileError(f"section file '{path}', line {lineno}: expected name, x, y, z")
        try:
            xyz = [float(v) for v in row[1:]]
        except ValueError:
            if lineno == 1:
                continue  # header
            raise NetworkFileError(f"section file '{path}', line {lineno}: x, y, z must be numbers") from None
        rows.setdefault(row[0].strip(), []).append(xyz)
    if not rows:
        raise NetworkFileError(f"section file '{path}': no points")
    return [PointCurve(name, "free", np.asarray(pts)) for name, pts in rows.items()]
