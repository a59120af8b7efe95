"""CAD files of a built hull (no Blender needed): IGES and STEP text from the core, Rhino
``.3dm`` written with rhino3dm from the core's B-spline control nets; every file written whole
or not at all, every failure an :class:`ExportError` naming the file."""

from __future__ import annotations

import datetime
import getpass
import os
from pathlib import Path

from batten_native import ExportError, cad_faces, cad_text

from .atomic_write import replace_atomically, write_atomically
from .file_text import file_path
from .progress import JobSteps, Step, in_worker

#: The file version rhino3dm writes (Rhino 7 reads it, and every later Rhino).
RHINO_FILE_VERSION = 7


def _now() -> tuple[int, int, int, int, int, int]:
    t = datetime.datetime.now(datetime.UTC)
    return (t.year, t.month, t.day, t.hour, t.minute, t.second)


def _author() -> str:
    try:
        return getpass.getuser()
    except (KeyError, OSError):
        return ""


def _written(path: Path, what: str, write) -> Path:
    try:
        return write()
    except OSError as e:
        raise ExportError(f"{what} '{path}': cannot be written: {e.strerror or e}") from e


def write_text_file(model, name: str, path, fmt: str, tolerance: float, allow_holes: bool) -> JobSteps:
    """Write ``model``'s surface (a ``batten_native.HullModel``) to ``path`` as ``fmt``
    (``"iges"`` or ``"step"``); returns the path and what the core measured (faces, patches,
    control_points, max_deviation, tolerance). A job (:class:`batten.progress.Job`): a step
    per face fitted (the core fits them in a worker thread), then one once the file is written
    (closed before that, the fitting stops and nothing is written)."""
    what = f"{fmt.upper()} file"
    path = file_path(path, what)

    def text_of(face_done):
        return cad_text(
            model, fmt, tolerance, allow_holes, name, path.name, _author(), _now(), progress=face_done
        )

    text, stats = yield from in_worker(f"{what}: faces", None, text_of)
    written = _written(path, what, lambda: write_atomically(path, text))
    yield Step(f"{what}: written", stats["faces"] + 1, stats["faces"] + 1, final=True)
    return written, stats


def write_3dm(model, name: str, path, tolerance: float, allow_holes: bool) -> JobSteps:
    """Write ``model``'s surface to ``path`` as a Rhino ``.3dm`` of NurbsSurface objects (one per
    face, named after the hull, in metres); returns the path and what was measured. A job
    (:class:`batten.progress.Job`): a step per face fitted (in a worker thread), a step per face
    added to the document, and one once the file is written (closed before that, it writes
    nothing)."""
    import rhino3dm

    what = "3dm file"
    path = file_path(path, what)

    def fit(face_done):
        return cad_faces(model, tolerance, allow_holes, progress=face_done)

    faces, stats = yield from in_worker(f"{what}: fitting", None, fit)
    doc = rhino3dm.File3dm()
    doc.Settings.ModelUnitSystem = rhino3dm.UnitSystem.Meters
    doc.Settings.ModelAbsoluteTolerance = tolerance
    for k, (knots_u, knots_v, net) in enumerate(faces):
        nu, nv = net.shape[0], net.shape[1]
        surface = rhino3dm.NurbsSurface.Create(3, False, 4, 4, nu, nv)
        # openNURBS stores count + degree - 1 knots: the clamped vector without its end knots.
        for i, t in enumerate(knots_u[1:-1]):
            surface.KnotsU[i] = float(t)
        for i, t in enumerate(knots_v[1:-1]):
            surface.KnotsV[i] = float(t)
        for i in range(nu):
            for j in range(nv):
                x, y, z = (float(c) for c in net[i, j])
                surface.Points[i, j] = rhino3dm.Point4d(x, y, z, 1.0)
        attributes = rhino3dm.ObjectAttributes()
        attributes.Name = f"{name} face {k}"
        doc.Objects.AddSurface(surface, attributes)
        yield Step(f"{what}: faces", k + 1, len(faces) + 1)

    def write(tmp: Path) -> None:
        if not doc.Write(os.fspath(tmp), RHINO_FILE_VERSION):
            raise OSError(f"rhino3dm could not write {tmp.name}")

    written = _written(path, what, lambda: replace_atomically(path, write))
    yield Step(f"{what}: written", len(faces) + 1, len(faces) + 1, final=True)
    return written, stats
