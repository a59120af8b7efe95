"""CAD exports read back: IGES and STEP with OpenCASCADE (OCP), .3dm with rhino3dm. Every face
is there, batten's surface lies within 0.1 mm of the read faces at its mesh vertices, the
faces sew into one shell (mirroring closes the centreplane), and the sewn half hull (cut at the
design draft, closed with lids on the centreplane, the waterplane and the transom) has batten's
displacement volume within 0.01 %."""

from __future__ import annotations

import time
from pathlib import Path

import batten.api as api
import numpy as np
import pytest
from helpers import wigley_without_keel

rb = pytest.importorskip("cad_readback")

HULLS = Path(__file__).resolve().parents[2] / "shared" / "hulls"
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
TOL = 1e-4  # the export tolerance, 0.1 mm


def _quads(coll) -> int:
    """Faces an export has: one per 4-sided patch, N per N-sided one."""
    sides = api.build(coll, resolution=1).report["faces_by_sides"]
    return sum((1 if int(n) == 4 else int(n)) * count for n, count in sides.items())


def _samples(coll, resolution: int) -> np.ndarray:
    """batten's own surface points: the vertices of a build (each on its patch)."""
    obj = api.build(coll, resolution=resolution).object
    n = len(obj.data.vertices)
    co = np.empty(3 * n)
    obj.data.vertices.foreach_get("co", co)
    return co.reshape(n, 3)


def _draft(coll, points: np.ndarray) -> float:
    return api.design_draft(coll) or float(0.5 * (points[:, 2].min() + points[:, 2].max()))


@pytest.mark.parametrize("example", ["wigley_lines.json", "frigate_network.json"])
@pytest.mark.parametrize("fmt", ["iges", "step"])
def test_iges_and_step_read_back_within_the_tolerance(example, fmt, tmp_path):
    coll = api.load_network(EXAMPLES / example)
    path = tmp_path / f"hull.{'igs' if fmt == 'iges' else 'stp'}"
    start = time.perf_counter()
    assert getattr(api, f"export_{fmt}")(coll, path) == path
    took = time.perf_counter() - start
    shape = rb.read_shape(path)
    faces = rb.faces(shape)
    assert len(faces) == _quads(coll), "every face read back"
    # Samples are float32 mesh vertices (rounding about 4e-6 m at 50 m): well inside.
    points = _samples(coll, 12)
    deviation = rb.Surfaces.of_faces(faces).distances(points)
    assert deviation.max() <= TOL, f"batten's surface {deviation.max():.2e} m off the faces"
    sewn, free = rb.sew(faces, TOL)
    whole, free_whole = rb.sew([sewn, rb.mirrored(sewn)], TOL)
    # Mirrored, only the rim (deck, transom) stays free: fewer free edges than the half.
    assert free_whole < free, f"mirroring closed nothing: {free} → {free_whole} free edges"
    draft = _draft(coll, points)
    batten = api.hydrostatics(coll, draft)["volume"]
    occt = rb.volume_below(sewn, draft, 1e3, TOL)
    assert occt == pytest.approx(batten, rel=1e-4), "OCCT's volume of the read-back hull"
    print(
        f"{example} {fmt}: {len(faces)} faces, {path.stat().st_size} bytes, {took:.2f} s, "
        f"max deviation {deviation.max():.2e} m, free edges {free} half / {free_whole} mirrored, "
        f"volume at T={draft:.3f}: OCCT {occt:.4f} batten {batten:.4f} ({occt / batten - 1:+.1e})"
    )


@pytest.mark.parametrize("example", ["wigley_lines.json", "frigate_network.json"])
def test_3dm_reads_back_with_rhino3dm_within_the_tolerance(example, tmp_path):
    import rhino3dm

    coll = api.load_network(EXAMPLES / example)
    path = api.export_3dm(coll, tmp_path / "hull.3dm")
    surfaces = rb.rhino_surfaces(path)
    assert len(surfaces) == _quads(coll), "every face read back"
    assert rhino3dm.File3dm.Read(str(path)).Settings.ModelUnitSystem == rhino3dm.UnitSystem.Meters
    # The read-back control nets evaluated against the same faces written as IGES.
    igs = api.export_iges(coll, tmp_path / "hull.igs")
    faces = rb.Surfaces.of_faces(rb.faces(rb.read_shape(igs)))
    pts = []
    for s in surfaces:
        assert s.IsValid, "a valid NurbsSurface"
        (u0, u1), (v0, v1) = (s.Domain(0).T0, s.Domain(0).T1), (s.Domain(1).T0, s.Domain(1).T1)
        for u in np.linspace(u0, u1, 7):
            for v in np.linspace(v0, v1, 7):
                p = s.PointAt(u, v)
                pts.append((p.X, p.Y, p.Z))
    gap = faces.distances(np.array(pts))
    assert gap.max() <= 1e-9, f"the .3dm faces are the IGES faces (off by {gap.max():.1e} m)"
    deviation = rb.Surfaces.of_faces(rb.faces(rb.read_shape(igs))).distances(_samples(coll, 8))
    assert deviation.max() <= TOL, f"{deviation.max():.2e} m"


def test_kcs_exports_whole_and_reads_back_within_the_tolerance(tmp_path):
    """KCS imported and built at the default settings, exported as STEP at the default 0.1 mm
    and read back with OCCT: every face there, batten's surface within 0.1 mm of the faces at
    every vertex of its default build, the faces sewn into one shell, and the sewn half hull's
    volume below T batten's within 0.01 %. (Until the knuckles inside faces were spread inside
    the patch, face 90 cracked 3 mm along the line from wl_z0.30's corner by the stem and no
    B-spline could follow it; faces 75 and 76, beside wl_z9.00's 27 mm step in the offsets,
    need up to 204 x 152 cells.)"""
    coll, _ = api.import_sections(HULLS / "kcs" / "network.json")
    report = api.build(coll).report
    # The build names the knuckle by the stem, where the patch spreads its ribbon's step.
    knuckles = [w for w in report["warnings"] if w["kind"] == "knuckle_in_face"]
    said = [w for w in knuckles if w["message"].startswith("face 90 ")]
    assert len(said) == 1 and "wl_z0.30" in said[0]["curves"], [w["message"] for w in knuckles]
    assert "(228.242, 0.035, 0.300)" in said[0]["message"], said[0]["message"]
    path = tmp_path / "kcs.stp"
    start = time.perf_counter()
    assert api.export_step(coll, path) == path
    took = time.perf_counter() - start
    faces = rb.faces(rb.read_shape(path))
    assert len(faces) == _quads(coll), "every face read back"
    # The default build's vertices: the patches the export fitted (at another resolution
    # the fold check may choose another patch for a face, KCS's face 76 at 12).
    points = _samples(coll, api.DEFAULT_RESOLUTION)
    deviation = rb.Surfaces.of_faces(faces).distances(points)
    assert deviation.max() <= TOL, f"batten's surface {deviation.max():.2e} m off the faces"
    sewn, free = rb.sew(faces, TOL)
    draft = api.design_draft(coll)
    batten = api.hydrostatics(coll, draft)["volume"]
    # Lids sewn at 1 mm: KCS's imported profile curve lies up to 0.11 mm off the centreplane,
    # at nodes with curves whose offsets end up to 0.2 mm off it (st0.50 at x = 5.75 m).
    occt = rb.volume_below(sewn, draft, 1e3, 1e-3)
    assert occt == pytest.approx(batten, rel=1e-4), "OCCT's volume of the read-back hull"
    print(
        f"KCS step: {len(faces)} faces, {path.stat().st_size} bytes, {took:.1f} s, max deviation "
        f"{deviation.max():.2e} m at {len(points)} points, {free} free edges, volume at T={draft}: "
        f"OCCT {occt:.3f} batten {batten:.3f} ({occt / batten - 1:+.1e})"
    )


def test_faces_that_cannot_be_fitted_are_refused_by_name(tmp_path):
    """A tolerance no cubic reaches on the frigate within the most spans (1e-13 m): the export
    names the faces it could not fit, each with its curves and what its fit reached (or that
    its boundary curves could not be fitted), and what to do, and writes nothing."""
    coll = api.load_network(EXAMPLES / "frigate_network.json")
    report = api.build(coll).report
    path = tmp_path / "frigate.stp"
    with pytest.raises(
        api.ExportError, match=rf"of {report['faces']} patches could not be approximated"
    ) as err:
        api.export_step(coll, path, tolerance=1e-13)
    message = str(err.value)
    assert "fair or move the curves around it" in message, "what the user can do"
    assert err.value.faces, "the faces it could not fit"
    faces = api.topology(coll)["faces"]
    around = dict(part.split(": ", 1) for part in message.split("the curves around them: ")[1].split("; "))
    assert sorted(around) == sorted(f"face {f}" for f in err.value.faces), "every face's curves"
    for f in err.value.faces:
        said = (f"face {f} (reached ", f"face {f} (its boundary curves could not be fitted)")
        assert any(s in message for s in said), f"face {f} with what its fit reached, or why none"
        assert around[f"face {f}"] == ", ".join(f"'{c}'" for c in faces[f]["curves"]), f"face {f}'s curves"
    assert not any(tmp_path.iterdir()), "nothing written"


def test_an_unwritable_path_is_a_clear_error_and_leaves_no_file(tmp_path):
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder")
    for export in (api.export_iges, api.export_step, api.export_3dm):
        with pytest.raises(api.ExportError, match="cannot be written"):
            export(coll, blocker / "hull.out")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file"], "no partial or temporary file"


@pytest.mark.parametrize("fmt", ["iges", "step", "3dm"])
def test_a_folder_in_the_way_is_a_clear_error_and_leaves_no_file(fmt, tmp_path):
    """The file's own name taken by a folder: the whole file was made (in a temporary file
    beside it) and cannot replace it; the temporary file is removed again."""
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    taken = tmp_path / f"taken.{fmt}"
    taken.mkdir()
    with pytest.raises(api.ExportError, match=f"'{taken}': cannot be written"):
        getattr(api, f"export_{fmt}")(coll, taken)
    assert [p.name for p in tmp_path.iterdir()] == [taken.name], "no partial or temporary file"
    assert taken.is_dir() and not any(taken.iterdir()), "the folder untouched"


@pytest.mark.parametrize("fmt", ["iges", "step", "3dm"])
def test_a_surface_with_a_hole_is_refused_by_its_curves_unless_allowed(fmt, tmp_path):
    coll = wigley_without_keel()
    report = api.build(coll, resolution=1).report
    assert report["holes"] == 1, "the build reports the hole"
    export = getattr(api, f"export_{fmt}")
    path = tmp_path / f"hull.{fmt}"
    path.write_text("an older export")
    with pytest.raises(api.ExportError, match="has holes.*allow_holes.*'waterline 1.042' near"):
        export(coll, path)
    assert path.read_text() == "an older export", "nothing written over the old file"
    assert [p.name for p in tmp_path.iterdir()] == [path.name], "no partial or temporary file"
    assert export(coll, path, allow_holes=True) == path
    # What exists: the 96 patches left of Wigley's 112 faces, each one face.
    read = rb.rhino_surfaces(path) if fmt == "3dm" else rb.faces(rb.read_shape(path))
    assert len(read) == _quads(coll) == 96, "every existing face written"


def test_a_bad_tolerance_is_an_invalid_argument(tmp_path):
    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    with pytest.raises(api.InvalidArgumentError, match="tolerance"):
        api.export_iges(coll, tmp_path / "x.igs", tolerance=0.0)
    assert not (tmp_path / "x.igs").exists()


def test_the_export_operator_writes_what_the_api_writes(tmp_path):
    import bpy

    coll = api.load_network(EXAMPLES / "wigley_lines.json")
    bpy.context.scene.batten.source = coll
    path = tmp_path / "op.stp"
    assert bpy.ops.batten.export_step(filepath=str(path)) == {"FINISHED"}
    faces = rb.faces(rb.read_shape(path))
    assert len(faces) == _quads(coll), "the operator's file has every face"
